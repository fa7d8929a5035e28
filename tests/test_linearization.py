"""Linearized stability of any Exudyn system with worm-gear connectors (the paper's Figure 19)."""
import json

import numpy as np
import pytest

import exudyn as exu
import exudyn_worm as ew
from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability, LinearizationModel, LinearStabilityOfDrive
from exudyn_worm.drive.presets import PRESETS, ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.drive.wholedrive import Drive, ResolveDrive

REEL_PRESETS = [name for name in PRESETS if name.startswith('reel-')]


@pytest.mark.physics
@pytest.mark.parametrize('name', REEL_PRESETS)
def test_two_mass_drive_agrees_with_the_analytical_model(name):
    """Required: on the two-mass drive the generic analysis equals eqs. (15)-(16) to 1e-6."""
    drive = ElasticDriveFromParameters(GetPreset(name))
    mbs = LinearizationModel(Drive.OfTwoMass(drive)).mbs
    linear = AnalyzeLinearStability(mbs)
    analytical = ew.AnalyzeStability(drive)
    assert sorted(linear.states) == [(-1,), (1,)] and linear.coordinates == ['motor', 'worm', 'wheel']
    for S in (1, -1):
        state, reference = linear.State(S), analytical.contact[S]
        np.testing.assert_allclose(state.eigenvalues, reference.eigenvalues, rtol=1e-6, atol=0)
        np.testing.assert_allclose(state.frequenciesHz, reference.frequenciesHz, rtol=1e-6)
        np.testing.assert_allclose([m.lehrDamping for m in state.modes], reference.lehrDamping, rtol=1e-6)
        np.testing.assert_allclose(state.characteristicCoefficients, reference.b, rtol=1e-6)
        assert state.stable == reference.stable
        for mode in state.modes:                         # the prescribed motor does not move
            assert mode.shape['motor'] == 0 and mode.energyShare['motor'] == 0
            assert sum(mode.energyShare.values()) == pytest.approx(1.)
    assert linear.stable == analytical.stable


@pytest.mark.physics
def test_reel_changer_model_with_load_and_its_options_restored(tmp_path, monkeypatch):
    """The full reel changer (load, equilibrium start) linearizes as the two-mass drive; the load's angle
    dependence adds a stiffness of about 1e-6 relative, hence the looser tolerance here."""
    monkeypatch.chdir(tmp_path)
    p = GetPreset('reel-P1')
    model = ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p))
    options = model.connector.options
    linear = AnalyzeLinearStability(model.mbs)
    analytical = ew.AnalyzeStability(model.drive)
    for S in (1, -1):
        np.testing.assert_allclose(linear.State(S).eigenvalues, analytical.contact[S].eigenvalues, rtol=1e-5)
    assert linear.State(1).stable and not linear.State(-1).stable and not linear.stable
    assert model.connector.options is options
    json.dumps(linear.ToDict())
    # the analysis leaves the system as it was: simulating it gives what a fresh model gives
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps, ss.timeIntegration.verboseMode = 2.6, 5200, 0
    results = []
    for m in (model, ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p))):
        m.mbs.Assemble()
        m.mbs.SolveDynamic(ss)
        results.append(m.connector.StoredStates(m.mbs)['alpha2'])
    assert np.max(np.abs(results[1])) > 10
    np.testing.assert_array_equal(results[0], results[1])


def _TwoDrives():
    """Two independent Figure 2 drives (P1 and P2) in one system: two meshes."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    drives = [ElasticDriveFromParameters(GetPreset(n)) for n in ('reel-P1', 'reel-P2')]
    for k, drive in enumerate(drives):
        g = drive.gear
        motor = ew.CreateRotor(mbs, 1e-3, name=f'motor{k}')
        worm = ew.CreateRotor(mbs, drive.J1, initialAngle=1e-6 / g.normalLever, name=f'worm{k}')
        wheel = ew.CreateRotor(mbs, drive.J2, name=f'wheel{k}')
        ew.CreatePrescribedRotation(mbs, motor, ew.ConstantSpeed(0.))
        ew.CreateShaft(mbs, [motor, worm], stiffness=drive.kT, damping=drive.dT)
        ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=g, name=f'mesh{k}')
    return SC, mbs, drives


@pytest.mark.physics
def test_every_combination_of_contact_states_for_two_meshes():
    SC, mbs, drives = _TwoDrives()
    linear = AnalyzeLinearStability(mbs)
    assert linear.meshes == ['mesh0', 'mesh1']
    assert list(linear.states) == [(1, 1), (1, -1), (-1, 1), (-1, -1)]
    single = [ew.AnalyzeStability(d) for d in drives]
    for (S0, S1), state in linear.states.items():
        expected = np.concatenate([single[0].contact[S0].eigenvalues, single[1].contact[S1].eigenvalues])
        np.testing.assert_allclose(np.sort_complex(state.eigenvalues), np.sort_complex(expected), rtol=1e-6)
        assert state.stable == (single[0].contact[S0].stable and single[1].contact[S1].stable)
        for mode in state.modes:                      # decoupled drives: each mode lives in one of them
            shares = [sum(v for c, v in mode.energyShare.items() if c.endswith(str(k))) for k in (0, 1)]
            assert max(shares) == pytest.approx(1., abs=1e-9)
    # P2 alone is stable for both states, P1 unstable for S = -1 only
    assert linear.State(1, -1).stable and not linear.State(-1, 1).stable
    only = AnalyzeLinearStability(mbs, contactStates=[(-1, -1)])
    assert list(only.states) == [(-1, -1)]


@pytest.mark.physics
def test_drive_side_inertia_adds_a_mode_with_its_participants():
    p = ApplyOverrides(GetPreset('reel-P1'), {'J4': 0.05, 'k4': 2e4, 'd4': 1.})
    linear = AnalyzeLinearStability(ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p)).mbs)
    assert linear.coordinates == ['motor', 'worm', 'wheel', 'inertia4']
    for state in linear.states.values():
        assert len(state.frequenciesHz) == 3 and state.rigidBodyModes == 0
        assert state.massMatrix.shape == (3, 3)
        top = state.modes[-1]                          # inertia4 swings between k4 and kT, the worm a little
        assert top.Participants(0.01) == ['inertia4', 'worm'] and top.energyShare['inertia4'] > 0.9
        assert all(m.energyShare['inertia4'] < 0.1 for m in state.modes[:2])


@pytest.mark.messages
def test_linear_analysis_rejects_bad_input():
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ew.CreateRotor(mbs, 1.)
    with pytest.raises(ValueError, match='AnalyzeLinearStability: the system has no worm-gear connector'):
        AnalyzeLinearStability(mbs)
    drive = ElasticDriveFromParameters(GetPreset('reel-P1'))
    worm, wheel = ew.CreateRotor(mbs, drive.J1), ew.CreateRotor(mbs, drive.J2)
    ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear, name='open')
    with pytest.raises(ValueError, match="mesh 'open' is not in contact at the initial state"):
        AnalyzeLinearStability(mbs)
    mbs = LinearizationModel(Drive.OfTwoMass(drive)).mbs
    with pytest.raises(ValueError, match='each contact state must be 1 value'):
        AnalyzeLinearStability(mbs, contactStates=[(1, 1)])
    with pytest.raises(TypeError, match="'connectors' must hold WormGearConnector objects"):
        AnalyzeLinearStability(mbs, connectors=[3])


@pytest.mark.physics
def test_linear_stability_from_parameters_with_chain_and_axial_bearing():
    p = GetPreset('reel-P1')
    plain = LinearStabilityOfDrive(ResolveDrive(parameters=p))
    analytical = ew.AnalyzeStability(ElasticDriveFromParameters(p))
    np.testing.assert_allclose(plain.State(-1).eigenvalues, analytical.contact[-1].eigenvalues, rtol=1e-6)
    full = LinearStabilityOfDrive(ResolveDrive(parameters=ApplyOverrides(p, {'J4': 0.05, 'k4': 2e4, 'd4': 1., 'J5': 0.02, 'k5': 1e5,
                                                            'kA': 5e8, 'mA': 5.})))
    assert full.coordinates == ['motor', 'worm', 'wheel', 'inertia4', 'inertia5', 'wormAxial']
    assert all(len(s.frequenciesHz) == 5 for s in full.states.values())
