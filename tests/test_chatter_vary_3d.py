"""``chatter --vary`` on a drive with elastic shaft bearings (the 3D model): the first orbit is the one without
``--vary`` (shooting from a run settled on the Poincare section), the branch is continued from it on the 3D model,
the bearing keys can be continued, and every point carries the largest bearing loads in the table, the JSON and the
plot; the one-angle branch's output keeps its form."""
import json

import numpy as np
import pytest

from exudyn_worm.analysis.orbits.chatter import SteadyChatterSummary
from exudyn_worm.analysis.orbits.chatterbranch import BEARING_LOAD_KEYS, AnalyzeChatterBranch, ChatterBranch
from exudyn_worm.analysis.orbits.continuation import BranchPoint
from exudyn_worm.analysis.orbits.lowering import (BuildRigidBodyLoweringModel, LoweringPhaseDrive,
                                                  UpdateLoweringModel)
from exudyn_worm.analysis.orbits.periodic import PeriodicOrbit
from exudyn_worm.cli.formatchatter import FormatBranch
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.wholedrive import ResolveDrive
from conftest import Shared

pytest.importorskip('exudyn')
DRIVE_3D = 'examples/drives/reel-3d-chatter.toml'
#: the static normal force of reel-P1's lowering point in N (tests/test_chatter_3d.py)
STATIC_NORMAL_FORCE = 20513.1
BEARING_KEYS = ('wormRadialStiffness', 'wormAxialStiffness', 'wormRadialDamping', 'wormAxialDamping',
                'wormBearingSpan', 'wheelRadialStiffness', 'wheelAxialStiffness', 'wheelRadialDamping',
                'wheelAxialDamping', 'wheelBearingSpan', 'wormMass', 'wheelMass', 'wormTiltInertia',
                'wheelTiltInertia')


def _Parameters():
    return LoweringPhaseDrive(ResolveDrive(config=DRIVE_3D))


def _Run(capsys, *argv):
    status = Main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def _FakePoint(value, loads=True):
    orbit = PeriodicOrbit(state=np.zeros(4), period=0.032, monodromy=np.diag([1., 0.5, 0.4, 0.3]),
                          velocity=np.array([1., 0., 0., 0.]), residual=1e-9, iterations=3, converged=True)
    info = {'forceFactor': 2.74, 'maxWheelAcceleration': 112.7, 'minWormSpeed': 48.2}
    if loads:
        info.update({k: 1e3 * (i + 1) for i, k in enumerate(BEARING_LOAD_KEYS)})
    return BranchPoint(value, orbit, info)


def test_bearing_keys_can_be_continued_on_the_3d_model_only():
    parameters = _Parameters()
    # a chain key is not part of the 3D model: refused at once, naming the bearing keys that can be continued
    with pytest.raises(ValueError, match='kL1') as err:
        AnalyzeChatterBranch(parameters, 'kL1', 1e6, 1e7)
    assert all(k in str(err.value) for k in BEARING_KEYS) and "shaft bearings" in str(err.value)
    # the one-angle model has no bearings to vary
    with pytest.raises(ValueError, match='wheelRadialStiffness'):
        AnalyzeChatterBranch(ResolveDrive(preset='reel-P1'), 'wheelRadialStiffness', 0.9e9, 1.1e9)


def test_the_3d_lowering_model_is_rebuilt_as_the_3d_model_for_a_new_parameter_value():
    parameters = _Parameters()
    model = BuildRigidBodyLoweringModel(parameters)
    assert UpdateLoweringModel(model, parameters) is model
    new = UpdateLoweringModel(model, parameters.Replace(wheelRadialStiffness=1.2e9))
    assert new is not model and new.rigidBody is not None and len(new.coordinates) == len(model.coordinates)
    assert new.whole.parameters['wheelRadialStiffness'] == 1.2e9 and model.whole.parameters['wheelRadialStiffness'] == 1e9


def test_branch_points_of_the_3d_model_carry_the_bearing_loads_in_text_and_json():
    branch = ChatterBranch('wheelRadialStiffness', (0.9e9, 1.1e9), points=[_FakePoint(1e9), _FakePoint(1.05e9)],
                           model='3D', settling={'value': 1e9, 'duration': 14., 'change': 0.2, 'settled': True})
    data = json.loads(json.dumps(branch.ToDict()))
    assert data['model'] == '3D' and data['settling']['duration'] == 14.
    assert all(p['amplitude'][k] == 1e3 * (i + 1) for p in data['points'] for i, k in enumerate(BEARING_LOAD_KEYS))
    text = FormatBranch(branch, 'title')
    assert 'worm axial kN' in text[2] and 'wheel radial kN' in text[2]
    assert text[3].split()[-5:] == ['1.000', '2.000', '3.000', '4.000', 'stable']
    # the one-angle branch keeps its JSON and its table
    one = ChatterBranch('J1', (0.05, 0.3), points=[_FakePoint(0.1, loads=False)])
    assert 'model' not in one.ToDict() and set(one.ToDict()['points'][0]['amplitude']) == {
        'forceFactor', 'maxWheelAcceleration'}
    assert FormatBranch(one, 'title')[2] == f"  {'J1':>12} {'Fn/Fstatic':>11} {'|phi2dd| rad/s2':>16} {'f Hz':>8}  orbit"


def test_a_branch_point_whose_multiplier_is_closer_to_1_than_its_error_is_undecided_with_both_numbers():
    # the trivial multiplier 0.995 (error 0.005), a pair of modulus 0.999 (0.001 from the unit circle): the monodromy
    # cannot tell stable from unstable, so the table says so with both numbers instead of 'stable'
    pair = 0.999 * np.exp(0.5j)
    monodromy = np.zeros((4, 4))
    monodromy[:2, :2] = [[pair.real, -pair.imag], [pair.imag, pair.real]]
    monodromy[2, 2], monodromy[3, 3] = 0.995, 0.3
    orbit = PeriodicOrbit(state=np.zeros(4), period=0.032, monodromy=monodromy, velocity=np.array([0., 0., 1., 0.]),
                          residual=1e-9, iterations=3, converged=True)
    point = BranchPoint(1e9, orbit, {'forceFactor': 2.74, 'maxWheelAcceleration': 112.7})
    branch = ChatterBranch('wheelRadialStiffness', (0.9e9, 1.1e9), points=[point, _FakePoint(1.05e9)], model='3D')
    text = FormatBranch(branch, 'title')
    assert text[3].endswith('undecided (|mu| 0.9990: 0.001 from 1, error 0.005)')
    assert text[4].endswith('stable')
    assert [p['stabilityDecided'] for p in branch.ToDict()['points']] == [False, True]


def test_chatter_vary_on_a_bearing_drive_with_a_chain_key_prints_one_line(capsys):
    status, out, err = _Run(capsys, 'chatter', '--config', DRIVE_3D, '--vary', 'kL1=1e6:1e7')
    assert status == 2 and len(err.strip().splitlines()) == 1 and not out and 'Traceback' not in err
    assert 'kL1' in err and 'wheelRadialStiffness' in err


@pytest.fixture(scope='module')
def stiffnessBranch():
    # reel-3d-chatter.toml's wheel bearings (1e9 N/m) +-5 %: linearly unstable on the whole range, so the first orbit is at
    # the drive's own value, as without --vary; two orbits in each direction (about 30 s on the 2-core machine);
    # the same branch as the command line's in test_chatter_vary_on_a_bearing_drive_gives_the_3d_branch_as_json,
    # computed once for both (conftest.Shared)
    return Shared(AnalyzeChatterBranch, _Parameters(), 'wheelRadialStiffness', 0.95e9, 1.05e9, maxPoints=2)


@pytest.mark.slow
@pytest.mark.usefixtures('sharedChatterAnalyses')      # the steady chatter of test_chatter_3d.py, computed once
def test_3d_branch_starts_at_the_orbit_without_vary(stiffnessBranch):
    summary = SteadyChatterSummary(_Parameters())
    assert summary['method'] == 'shooting'
    first = [p for p in stiffnessBranch.points if p.value == 1e9]
    assert len(first) == 1
    # the same settled start and the same shooting: equal to the shooting tolerance (1e-8 of the state scale)
    assert first[0].orbit.period == pytest.approx(summary['periodS'], rel=1e-7)
    for key, value in summary['amplitude'].items():
        assert first[0].info[key] == pytest.approx(value, rel=1e-6), key
    assert stiffnessBranch.settling['value'] == 1e9 and stiffnessBranch.settling['settled']
    assert stiffnessBranch.settling['duration'] == summary['settledS']


@pytest.mark.slow
def test_3d_branch_moves_monotonically_and_carries_positive_bearing_loads(stiffnessBranch, tmp_path):
    branch = stiffnessBranch
    assert branch.model == '3D' and len(branch.points) == 5            # two orbits each way from the first
    values = np.array([p.value for p in branch.points])
    assert np.all(np.diff(values) > 0) and values[0] < 1e9 < values[-1]
    assert all(0.95e9 <= v <= 1.05e9 for v in values)
    for p in branch.points:
        assert p.orbit.converged is not False and p.orbit.residual < 1e-7
        assert all(p.info[k] > 0. for k in BEARING_LOAD_KEYS)
        # the worm's axial and the wheel's radial bearings carry the mesh force's large components
        normal = p.info['forceFactor'] * STATIC_NORMAL_FORCE
        assert p.info['maxWormAxialLoad'] > 0.8 * normal and p.info['maxWheelRadialLoad'] > 0.8 * normal
    # the chatter is locked to the wheel's tilt mode (31 Hz): a stiffer wheel bearing raises its frequency
    # (measured: 30.98 Hz at 0.9968e9 to 31.08 Hz at 1.0032e9 N/m)
    frequencies = np.array([p.orbit.frequencyHz for p in branch.points])
    assert np.all(np.diff(frequencies) > 0)
    assert any('settled on the Poincare section' in m for m in branch.messages)
    data = json.loads(json.dumps(branch.ToDict()))
    assert [p['value'] for p in data['points']] == list(values)
    axes = branch.plot(str(tmp_path / 'branch.png'))
    assert len(axes) == 3 and (tmp_path / 'branch.png').stat().st_size > 0
    assert len(axes[2].get_lines()) >= 4


@pytest.mark.slow
@pytest.mark.usefixtures('sharedChatterAnalyses')      # the branch of stiffnessBranch, computed once
def test_chatter_vary_on_a_bearing_drive_gives_the_3d_branch_as_json(capsys):
    status, out, err = _Run(capsys, 'chatter', '--config', DRIVE_3D, '--vary',
                            'wheelRadialStiffness=0.95e9N/m:1.05e9N/m', '--max-points', '2', '--json')
    assert status == 0, err
    data = json.loads(out)
    assert data['model'] == '3D' and data['parameter'] == 'wheelRadialStiffness' and len(data['points']) == 5
    assert data['points'][2]['value'] == 1e9
    assert all(p['amplitude'][k] > 0. for p in data['points'] for k in BEARING_LOAD_KEYS)
