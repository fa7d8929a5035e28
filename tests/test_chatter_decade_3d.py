"""``chatter --vary`` over a decade of bearing stiffness on the 3D model (the small-displacement model of
``examples/drives/reel-3d-chatter.toml``): where the pseudo-arclength continuation fails, natural-parameter points, each
from its own settled time simulation, cover the rest of the range; every point carries its accuracy (shooting
residual and the trivial Floquet multiplier's error, or the settled run's last move on its Poincare section) and
a decided or undecided stability label."""
import json
import math

import numpy as np
import pytest

from exudyn_worm.analysis.orbits.chatterbranch import (BEARING_LOAD_KEYS, REST_FORCE_FACTOR, AnalyzeChatterBranch,
                                                       ChatterBranch)
from exudyn_worm.analysis.orbits.lowering import BuildRigidBodyLoweringModel, LoweringPhaseDrive
from exudyn_worm.analysis.orbits.periodic import TRIVIAL_MULTIPLIER_TOLERANCE, PeriodicOrbit
from exudyn_worm.analysis.orbits.settledbranch import SETTLED_ORBIT_TOLERANCE, SETTLED_STEP_RATIO, SettledValues
from exudyn_worm.analysis.orbits.settling import SettleOnSection
from exudyn_worm.analysis.orbits.continuation import BranchPoint
from exudyn_worm.cli.formatchatter import FormatBranch
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.wholedrive import ResolveDrive
from conftest import Shared

pytest.importorskip('exudyn')
DRIVE_3D = 'examples/drives/reel-3d-chatter.toml'
LOW, HIGH = 3e8, 3e9


def _Parameters():
    return LoweringPhaseDrive(ResolveDrive(config=DRIVE_3D))


def test_settled_values_step_by_at_most_the_ratio_and_end_at_the_range_end():
    # 1e9 down to 3e8: log10(1e9/3e8) = 0.523 decades, ten points a decade -> 6 points at the ratio (1e9/3e8)^(1/6)
    values = SettledValues(1e9, 3e8)
    assert len(values) == 6 and values[-1] == 3e8
    ratios = np.array([1e9] + values[:-1]) / np.array(values)
    np.testing.assert_allclose(ratios, (1e9 / 3e8) ** (1 / 6), rtol=1e-12)
    assert SETTLED_STEP_RATIO == pytest.approx(10 ** 0.1) and np.all(ratios <= SETTLED_STEP_RATIO)
    assert SettledValues(2., 2.) == []
    # a range through zero: even steps of 1/25 of the distance
    np.testing.assert_allclose(SettledValues(-1., 1.), np.linspace(-1., 1., 26)[1:], rtol=0, atol=1e-15)


@pytest.mark.messages
def test_settling_from_a_state_of_the_wrong_size_names_the_argument():
    model = BuildRigidBodyLoweringModel(_Parameters())
    with pytest.raises(ValueError, match=r"SettleOnSection: 'initialState' must hold 24 finite flow coordinates, "
                                         r"got \[0.0, 0.0\]"):
        SettleOnSection(model, initialState=[0., 0.])


def test_points_without_an_orbit_are_rows_of_the_table_and_json_with_their_label():
    orbit = PeriodicOrbit(state=np.zeros(3), period=0.03, monodromy=np.diag([1.002, 0.5, 0.2]),
                          velocity=np.array([1., 0., 0.]), residual=4e-4, iterations=30, converged=False)
    point = BranchPoint(1.2e9, orbit, {'forceFactor': 2.7, 'maxWheelAcceleration': 100., 'method': 'shooting',
                                       **{k: 1e3 for k in BEARING_LOAD_KEYS}})
    amplitude = {'forceFactor': 1.01, 'maxWheelAcceleration': 3., **{k: 2e3 for k in BEARING_LOAD_KEYS}}
    rest = {'value': 3e9, 'method': 'rest', 'frequencyHz': 53.7, 'amplitude': amplitude, 'residual': None,
            'stabilityDecided': True, 'reason': 'r'}
    longRun = dict(rest, value=8e8, method='long simulation', residual=0.0047, stabilityDecided=False)
    branch = ChatterBranch('wheelRadialStiffness', (LOW, HIGH), points=[point], model='3D',
                           simulated=[longRun, rest])
    text = FormatBranch(branch, 'title')
    # the rows by value: the long simulation, the orbit (closing to its residual), the rest
    assert text[3].split()[0] == '8e+08' and text[3].endswith('long simulation, undecided (no orbit: shooting '
                                                               'residual 0.0047)')
    assert text[4].split()[0] == '1.2e+09' and text[4].endswith('stable, residual 0.0004')
    assert text[5].split()[0] == '3e+09' and text[5].endswith('rest (linearly stable; the settled run stays in '
                                                               'contact)')
    data = json.loads(json.dumps(branch.ToDict()))
    assert data['points'][0]['residual'] == 4e-4 and data['points'][0]['method'] == 'shooting'
    assert [s['method'] for s in data['simulated']] == ['long simulation', 'rest']
    # the one-angle branch's JSON keeps its form
    assert 'simulated' not in ChatterBranch('J1', (0.05, 0.3)).ToDict()


@pytest.fixture(scope='module')
def decade():
    # the command's branch (maxPoints as the command's default), computed once for this module's tests
    # (conftest.Shared): about 50 s of CPU
    return Shared(AnalyzeChatterBranch, _Parameters(), 'wheelRadialStiffness', LOW, HIGH, maxPoints=60)


def _Labelled(branch):
    """(value, kind) of every point of the branch, by value."""
    rows = [(p.value, 'orbit') for p in branch.points] + [(s['value'], s['method']) for s in branch.simulated]
    return sorted(rows)


@pytest.mark.slow
def test_the_decade_of_bearing_stiffness_is_covered(decade):
    rows = _Labelled(decade)
    values = np.array([v for v, _ in rows])
    # from one end of the range to the other, no gap wider than the natural-parameter step
    assert values[0] == LOW and values[-1] == HIGH
    assert np.all(values[1:] / values[:-1] <= SETTLED_STEP_RATIO * (1 + 1e-12))
    assert {kind for _, kind in rows} <= {'orbit', 'rest', 'long simulation'}
    # the continuation's own orbits remain, around the drive's value
    assert any(p.value == 1e9 and p.orbit.converged for p in decade.points)
    assert any('natural-parameter points' in m for m in decade.messages)


@pytest.mark.slow
def test_every_orbit_of_the_decade_carries_its_accuracy_and_a_label(decade):
    for p in decade.points:
        residual, error = p.orbit.residual, p.orbit.trivialMultiplierError
        # accepted: converged to the shooting tolerance, or closing to the accepted residual of the settled points
        assert residual <= (1e-8 if p.orbit.converged else SETTLED_ORBIT_TOLERANCE)
        # the label from its definition: decided where the largest multiplier is farther from 1 than the error
        largest = max(abs(complex(m)) for m in p.orbit.nontrivialMultipliers)
        assert p.orbit.stabilityDecided == (error <= TRIVIAL_MULTIPLIER_TOLERANCE and abs(largest - 1.) > error)
        # an orbit loses contact: its largest normal force is at least the rest limit
        assert p.info['forceFactor'] >= REST_FORCE_FACTOR
    data = json.loads(json.dumps(decade.ToDict()))
    for p in data['points']:
        assert {'residual', 'trivialMultiplierError', 'stabilityDecided', 'method'} <= set(p)


@pytest.mark.slow
def test_every_point_without_an_orbit_says_why_and_is_labelled(decade):
    for s in decade.simulated:
        vibration = s['amplitude']
        if s['method'] == 'rest':
            # rest only where the linearized drive is stable and the settled run stays in contact, sliding forward
            assert s['linearGrowth'] < 0 and vibration['forceFactor'] < REST_FORCE_FACTOR
            assert vibration['minWormSpeed'] > 0
            assert s['stabilityDecided'] is True and s['residual'] is None
        else:
            assert s['method'] == 'long simulation' and s['stabilityDecided'] is False
            # no orbit: shooting stopped above the accepted residual, or the run never lost contact
            assert (s['residual'] is None and vibration['forceFactor'] < REST_FORCE_FACTOR
                    or s['residual'] > SETTLED_ORBIT_TOLERANCE)
        assert s['reason'] and s['settledS'] > 0 and math.isfinite(s['sectionChange'])


@pytest.mark.slow
@pytest.mark.usefixtures('sharedChatterAnalyses')      # the branch of the fixture decade, computed once
def test_chatter_vary_over_the_decade_prints_every_point(capsys, decade):
    status = Main(['chatter', '--config', DRIVE_3D, '--vary', 'wheelRadialStiffness=3e8:3e9'])
    out, err = capsys.readouterr()
    assert status == 0, err
    rows = [line for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert len(rows) == len(decade.points) + len(decade.simulated)
    # each row with its label: stable or unstable (decided), undecided, rest, or a long simulation
    assert all(any(word in line for word in ('stable', 'undecided', 'INACCURATE', 'rest (', 'long simulation'))
               for line in rows)
