"""The Exudyn worm-gear connector: linearization = analytical theory, symbolic = Python, clean errors."""
import os

import numpy as np
import pytest

import exudyn as exu
from exudyn.itemInterface import NodePoint
from exudyn_worm import AnalyzeStability
from exudyn_worm.items.connector import CreateWormGear
from exudyn_worm.items.drivetrain import CreateRotor, CreateShaft
from exudyn_worm.analysis.stability.linearization import ExudynStabilityAnalysis
from exudyn_worm.drive.presets import PRESETS, ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.drive.wholedrive import ResolveDrive

REEL_PRESETS = [name for name in PRESETS if name.startswith('reel-')]


@pytest.mark.physics
@pytest.mark.parametrize('name', REEL_PRESETS + ['chart'])
def test_linearized_exudyn_model_reproduces_analytical_eigenvalues(name):
    """Required: 1e-6 relative. The connector implements eqs. (1)-(2)."""
    p = GetPreset(name)
    if name == 'chart':                                   # the chart preset sweeps J1, kT: pick a point
        p = ApplyOverrides(p, {'J1': 1e-4, 'kT': 0.5, 'DT': 0.028})
    drive = ElasticDriveFromParameters(p)
    analytical = AnalyzeStability(drive)
    exudyn = ExudynStabilityAnalysis(drive)
    for S in (1, -1):
        a, e = analytical.contact[S].eigenvalues, exudyn.contact[S].eigenvalues
        np.testing.assert_allclose(e, a, rtol=1e-6, atol=0)
        assert exudyn.contact[S].stable == analytical.contact[S].stable
    assert exudyn.stable == analytical.stable


@pytest.mark.physics
def test_linearization_with_backlash_and_python_user_function():
    drive = ElasticDriveFromParameters(ApplyOverrides(GetPreset('reel-P1'), {'backlash': 0.5e-3}))
    exudyn = ExudynStabilityAnalysis(drive, useSymbolic=False)
    for S in (1, -1):
        np.testing.assert_allclose(exudyn.contact[S].eigenvalues, AnalyzeStability(drive).contact[S].eigenvalues,
                                   rtol=1e-6)


@pytest.mark.physics
def test_symbolic_and_python_user_functions_give_identical_results(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    p = ApplyOverrides(GetPreset('reel-P1'), {'backlash': 0.25e-3})
    fast = SimulateReelChanger(ResolveDrive(parameters=p), endTime=2.6)
    slow = SimulateReelChanger(ResolveDrive(parameters=p), endTime=2.6, useSymbolic=False)
    scale = np.max(np.abs(fast.series['alpha2']))
    assert scale > 10                                     # chatter has started: a meaningful comparison
    np.testing.assert_allclose(slow.series['alpha2'], fast.series['alpha2'], rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(slow.series['normalForce'], fast.series['normalForce'], rtol=0,
                               atol=1e-6 * np.max(np.abs(fast.series['normalForce'])))
    assert os.listdir(tmp_path) == []                     # nothing written to the current directory


def _System():
    SC = exu.SystemContainer()
    return SC, SC.AddSystem()


@pytest.mark.messages
def test_connector_rejects_bad_input():
    SC, mbs = _System()
    gear = ElasticDriveFromParameters(GetPreset('reel-P1')).gear
    worm, wheel = CreateRotor(mbs, 0.1), CreateRotor(mbs, 33.)
    nodes = [worm['nodeNumber'], wheel['nodeNumber']]
    with pytest.raises(TypeError, match="CreateWormGear: 'gear' must be a WormGear"):
        CreateWormGear(mbs, nodes, gear={'kV': 1})
    with pytest.raises(ValueError, match=r"'nodeNumbers' must be \[nWorm, nWheel\]"):
        CreateWormGear(mbs, nodes[:1], gear=gear)
    nPoint = mbs.AddNode(NodePoint())
    with pytest.raises(ValueError, match="one rotation coordinate"):
        CreateWormGear(mbs, [nodes[0], nPoint], gear=gear)
    with pytest.raises(TypeError, match=r"CreateShaft: 'rotors\[1\]' must be a rotor"):
        CreateShaft(mbs, [worm, 3], stiffness=1.)
    with pytest.raises(ValueError, match="CreateRotor: 'inertia' must be > 0 kg\\*m\\^2, got -1"):
        CreateRotor(mbs, -1.)


@pytest.mark.physics
def test_full_model_linearizes_with_exudyn():
    """mbs.ComputeLinearizedSystem works on a system containing the connector and the load."""
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    model.mbs.Assemble()
    M, K, D = model.mbs.ComputeLinearizedSystem()
    assert np.all(np.isfinite(K)) and np.any(K != 0)


@pytest.mark.physics
def test_starts_in_static_equilibrium():
    r = SimulateReelChanger(ResolveDrive(parameters=GetPreset('reel-P1')), endTime=0.5)
    assert np.max(np.abs(r.series['alpha2'])) < 0.01          # rad/s^2: no start-up transient
    assert np.max(np.abs(r.series['alpha1'])) < 1.
