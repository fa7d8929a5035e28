"""The static equilibrium under load: exudyn_worm.items.equilibrium.SteadyInitialState."""
import math
import re
from pathlib import Path

import exudyn as exu
import pytest

import exudyn_worm as ew
from exudyn_worm.model.drive import AxialBearing
from exudyn_worm.model.contact import ContactOptions, MeshContact
from exudyn_worm.model.friction import MATH_OPS
from exudyn_worm.items.equilibrium import SteadyInitialState
from exudyn_worm.drive.presets import ElasticDriveFromParameters, DriveSideChain, GetPreset
from exudyn_worm.model.profiles import GravityLeverTorque

DOCS = Path(__file__).resolve().parents[1] / 'docs'
P1 = GetPreset('reel-P1')
DRIVE = ElasticDriveFromParameters(P1)
SPEED = P1['motorSpeed']


def _NetTorques(drive, state, load, chain, loadSide):
    """Torque on every rotor at the state (springs only: all rotors of a side turn at the same speed)."""
    g = drive.gear
    mesh = MeshContact(g, state['phi1'], state['phi2'], state['omega1'], state['omega2'], ContactOptions(), MATH_OPS)
    # worm side: angles worm, J4, J5, ..., motor (phi0 = 0); spring i joins rotor i and rotor i + 1
    sideAngles = [state['phi1']] + [state[f'phi{i}'] for i in range(4, 4 + len(chain))] + [0.]
    springs = [drive.kT] + [k for _, k, _ in chain]
    passed = [k * (sideAngles[i + 1] - sideAngles[i]) for i, k in enumerate(springs)]   # torque on rotor i
    torques = {'worm': mesh.wormTorque + passed[0]}
    for i in range(len(chain)):
        torques[f'J{i + 4}'] = passed[i + 1] - passed[i]
    angles = [state['phi2']] + [state[f'phiL{i}'] for i in range(1, len(loadSide) + 1)]
    end = angles[-1]
    loadTorque = load if isinstance(load, float) else load.Torque(end, state['omega2'], 0., MATH_OPS)
    springs = [k for _, k, *_ in loadSide]
    inner = [springs[i] * (angles[i] - angles[i + 1]) for i in range(len(springs))]   # torque passed outwards
    torques['wheel'] = mesh.wheelTorque - (inner[0] if inner else -loadTorque)
    for i in range(len(springs)):
        outer = inner[i + 1] if i + 1 < len(springs) else -loadTorque
        torques[f'JL{i + 1}'] = inner[i] - outer
    return torques, abs(loadTorque)


@pytest.mark.parametrize('load', [-2000., 1500., GravityLeverTorque(175., 1.2)])
@pytest.mark.parametrize('loadSide', [[], [(0.5, 2e4)], [(0.5, 2e4, 3.), (2., 5e3), (10., 8e4, 0.)]])
@pytest.mark.parametrize('chain', [[], [(0.05, 2000., 0.1), (0.02, 5000., 0.)]])
def test_every_rotor_is_in_balance(load, loadSide, chain):
    state = SteadyInitialState(DRIVE, load, SPEED, chain=chain, loadSide=loadSide)
    torques, scale = _NetTorques(DRIVE, state, load, chain, loadSide)
    for name, torque in torques.items():
        assert abs(torque) < 1e-9 * scale, (name, torque, scale)
    assert all(state[f'omegaL{i}'] == state['omega2'] for i in range(1, len(loadSide) + 1))


@pytest.mark.parametrize('M', [-2000., 800.])
def test_load_shafts_are_pretwisted_by_the_transmitted_torque(M):
    stages = [(0.5, 2e4), (1., 5e3), (3., 1e5)]
    state = SteadyInitialState(DRIVE, M, SPEED, loadSide=stages)
    angles = [state['phi2']] + [state[f'phiL{i}'] for i in (1, 2, 3)]
    for (_, k), a, b in zip(stages, angles, angles[1:]):
        assert (b - a) * k == pytest.approx(M, rel=1e-12)
    # the mesh side does not see the load side: the same load on the wheel directly gives the same worm and wheel
    direct = SteadyInitialState(DRIVE, M, SPEED)
    assert (state['phi1'], state['phi2']) == (direct['phi1'], direct['phi2'])


def test_reel_changer_keeps_its_equilibrium():
    """The steady state of the reel changer with a drive-side chain and an axial bearing has their coordinates."""
    load = GravityLeverTorque(P1['loadMass'], P1['leverArm'])
    p = {**P1, 'J4': 0.05, 'k4': 2000., 'kA': 1e8, 'mA': 3.}
    state = SteadyInitialState(ElasticDriveFromParameters(p), load, SPEED, ContactOptions(), AxialBearing(1e8, 0., 3.),
                               DriveSideChain(p))
    assert set(state) == {'phi1', 'phi2', 'omega1', 'omega2', 'phi4', 'omega4', 'xA', 'vA'}


@pytest.mark.parametrize('kwargs, error, pattern', [
    ({'drive': 'P1'}, TypeError, r"SteadyInitialState: 'drive' must be an ElasticDrive"),
    ({'load': 'heavy'}, TypeError, r"'load' must be None, a torque in N\*m or have Torque"),
    ({'motorSpeed': math.nan}, ValueError, r"'motorSpeed' must be finite"),
    ({'loadSide': [(0.5,)]}, TypeError, r"'loadSide' stage 1 must be \(inertia kg\*m\^2, stiffness"),
    ({'loadSide': [(0.5, -1.)]}, ValueError, r"'loadSide\[0\] stiffness' must be > 0 N\*m/rad, got -1"),
    ({'loadSide': [(0.5, 1., 2.), (0., 1.)]}, ValueError, r"'loadSide\[1\] inertia' must be > 0 kg\*m\^2"),
    ({'loadSide': 3}, TypeError, r"'loadSide' must be a sequence"),
])
def test_bad_arguments(kwargs, error, pattern):
    with pytest.raises(error, match=pattern):
        SteadyInitialState(**{'drive': DRIVE, 'load': -100., 'motorSpeed': SPEED, **kwargs})


def _DocsExample():
    text = (DOCS / 'equilibrium.md').read_text()
    return re.search(r"```python\n(.*?)```", text, re.S).group(1)


@pytest.mark.parametrize('equilibrium', [True, False])
def test_docs_example_linearizes_and_stays_at_rest(tmp_path, monkeypatch, equilibrium):
    """Runs the code of docs/equilibrium.md; then a simulation from that state keeps every speed and the load
    shaft's torque (to 1e-9); without the load shaft's pre-twist it does not (the check can fail)."""
    monkeypatch.chdir(tmp_path)
    code = _DocsExample()
    if not equilibrium:          # a user's mistake: the load shaft started untwisted
        code = code.replace("initialAngle=state['phiL1']", "initialAngle=state['phi2']")
    namespace = {}
    exec(compile(code, 'docs/equilibrium.md', 'exec'), namespace)
    analysis, mbs = namespace['analysis'], namespace['mbs']
    assert set(analysis.states) == {(1,), (-1,)}
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 0.02
    ss.timeIntegration.numberOfSteps = 200
    ss.solution.file.write = False
    ss.timeIntegration.verboseMode = 0
    mbs.SolveDynamic(ss)
    out = lambda rotor, kind: mbs.GetNodeOutput(namespace[rotor]['nodeNumber'], kind)
    speeds = [out(r, exu.OutputVariableType.Coordinates_t) for r in ('worm', 'wheel', 'load')]
    state = namespace['state']
    twist = out('load', exu.OutputVariableType.Coordinates) - out('wheel', exu.OutputVariableType.Coordinates)
    still = (speeds == pytest.approx([state['omega1'], state['omega2'], state['omega2']], rel=1e-9)
             and twist * 2e4 == pytest.approx(namespace['loadTorque'], rel=1e-9))
    assert still == equilibrium
    assert list(tmp_path.iterdir()) == []          # nothing written to the current directory
