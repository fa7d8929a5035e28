"""Design check (exudyn_worm.analysis.design.designcheck): recommendations for the paper's P1, the margin rule, the chart point.

Every recommendation is re-checked here with the scalar analytical model (AnalyzeStability of the changed
parameter set), independently of the vectorized scan that found it.
"""
import json
import math
import numpy as np
import pytest

from exudyn_worm import AnalyzeStability, ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.analysis.design.designcheck import DesignCheck
from exudyn_worm.analysis.design.designconfirm import ConfirmBySimulation
from exudyn_worm.analysis.design.designrules import DEFAULT_MARGIN
from exudyn_worm.analysis.design.stabilityhint import NearestStableValue, StabilizingChanges
from exudyn_worm.analysis.design.designscan import DesignParameters
from exudyn_worm.drive.wholedrive import ResolveDrive


def _Stable(p):
    return AnalyzeStability(ElasticDriveFromParameters(p)).stable


def _StableWithMargin(parameters, changes, margin, samples=41):
    """Stable for every factor 10**s, |s| <= margin, on each changed parameter (all combinations)."""
    offsets = np.linspace(-margin, margin, samples if len(changes) == 1 else 9)
    keys = list(changes)
    grids = np.meshgrid(*[offsets] * len(keys), indexing='ij')
    for combo in zip(*(g.ravel() for g in grids)):
        p = ApplyOverrides(parameters, {k: changes[k] * 10. ** s for k, s in zip(keys, combo)})
        if not _Stable(p):
            return False
    return True


@pytest.fixture(scope='module')
def p1Check():
    return DesignCheck(ResolveDrive(parameters=GetPreset('reel-P1')))


@pytest.mark.physics
def test_p1_is_unstable_and_gets_increases_and_decreases(p1Check):
    r = p1Check
    assert not r.stable and not r.stableWithMargin and r.maxRealPart > 0
    assert r.analysis.State(-1).stable is False and r.analysis.State(1).stable is True
    moves = {(x.parameter, x.factor > 1) for x in r.recommendations}
    for key in ('J1', 'J2', 'kT'):
        assert (key, True) in moves and (key, False) in moves, key
    assert ('DT', True) in moves and ('DV', True) in moves             # more damping helps ...
    assert ('DT', False) not in moves and ('DV', False) not in moves   # ... less does not, within 100
    assert set(r.Missing()) == {('DT', -1), ('DV', -1)}
    for x in r.recommendations:
        assert 1 / 100 <= x.factor <= 100
        assert x.newValue == pytest.approx(GetPreset('reel-P1')[x.parameter] * x.factor, rel=1e-12)


@pytest.mark.physics
def test_each_recommendation_is_stable_with_the_margin_and_the_smallest(p1Check):
    p1 = GetPreset('reel-P1')
    for x in p1Check.recommendations:
        assert x.maxRealPartAfter < 0
        assert _StableWithMargin(p1, x.changes, DEFAULT_MARGIN), x
        # a slightly smaller change is not stable with margin: the boundary lies just inside the margin
        t = math.log10(x.factor)
        inside = t - math.copysign(DEFAULT_MARGIN + 1e-3, t)
        assert not _Stable(ApplyOverrides(p1, {x.parameter: p1[x.parameter] * 10. ** inside})), x


@pytest.mark.physics
def test_paper_points_p2_to_p5_lie_beyond_the_boundaries(p1Check):
    # section 3.2.4: P2 (J1 x3), P3 (J1 /3), P4 (kT x2), P5 (kT /5) are stable; each lies at or beyond our
    # margin-0 boundary in its direction (this is a consistency check, not a tuning target)
    nearest = {(s.key, d): v for s in StabilizingChanges(ResolveDrive(parameters=GetPreset('reel-P1')))
               for d, v in ((-1, s.below), (1, s.above))}
    assert 0.033 < nearest['J1', -1] < 0.1 < nearest['J1', 1] < 0.3
    assert 1400. < nearest['kT', -1] < 7000. < nearest['kT', 1] < 14000.


@pytest.mark.physics
def test_stable_preset_needs_no_change():
    r = DesignCheck(ResolveDrive(parameters=GetPreset('reel-P2')))
    assert r.stable and r.stableWithMargin and r.recommendations == [] and r.marginShortBy == []
    assert r.bestPair is None and r.maxRealPart < 0
    assert r.ToDict()['recommendations'] == []


def test_margin_rule_is_the_same_everywhere(p1Check):
    p1 = GetPreset('reel-P1')
    wide = DesignCheck(ResolveDrive(parameters=p1), margin=0.2)
    zero = DesignCheck(ResolveDrive(parameters=p1), margin=0.)
    for a, b, c in zip(p1Check.recommendations, wide.recommendations, zero.recommendations):
        assert a.parameter == b.parameter == c.parameter
        sign = math.copysign(1., math.log10(a.factor))
        # boundary + margin: 0.1 decades further for margin 0.2, 0.1 decades closer for margin 0
        assert math.log10(b.factor) - math.log10(a.factor) == pytest.approx(0.1 * sign, abs=1e-8)
        assert math.log10(a.factor) - math.log10(c.factor) == pytest.approx(0.1 * sign, abs=1e-8)
    # margin 0 = the nearest stable values of the stability hint (one scan behind both)
    for s in StabilizingChanges(ResolveDrive(parameters=p1)):
        byDirection = {x.factor > 1: x.newValue for x in zero.recommendations if x.parameter == s.key}
        assert byDirection[False] == pytest.approx(s.below, rel=1e-9)
        assert byDirection[True] == pytest.approx(s.above, rel=1e-9)


def test_stable_drive_within_the_margin_is_moved_away_from_the_boundary(p1Check):
    p1 = GetPreset('reel-P1')
    up = next(x for x in p1Check.recommendations if x.parameter == 'J1' and x.factor > 1)
    boundary = up.newValue / 10 ** DEFAULT_MARGIN
    near = ApplyOverrides(p1, {'J1': boundary * 1.05})          # stable, 0.02 decades beyond the boundary
    r = DesignCheck(ResolveDrive(parameters=near))
    assert r.stable and not r.stableWithMargin and 'J1' in r.marginShortBy
    again = next(x for x in r.recommendations if x.parameter == 'J1' and x.factor > 1)
    assert again.newValue == pytest.approx(up.newValue, rel=1e-8)    # the same target as from P1
    assert _StableWithMargin(near, again.changes, DEFAULT_MARGIN)


def test_no_single_parameter_gives_the_best_pair():
    p1 = GetPreset('reel-P1')
    r = DesignCheck(ResolveDrive(parameters=p1), span=1.5)
    assert r.recommendations == [] and not r.singleParameterSuffices
    pair = r.bestPair
    assert pair is not None and pair.maxRealPartAfter < 0
    assert all(1 / 1.5 <= f <= 1.5 for f in pair.factors)
    assert _StableWithMargin(p1, pair.changes, DEFAULT_MARGIN)
    # neither of its two changes alone is stable with margin (else it would be a single recommendation)
    for key, value in pair.changes.items():
        assert not _StableWithMargin(p1, {key: value}, DEFAULT_MARGIN)
    data = r.ToDict()
    assert data['singleParameterSuffices'] is False and data['bestPair']['parameters'] == list(pair.parameters)


@pytest.mark.physics
def test_chart_point_and_distance_to_the_boundary(p1Check):
    point = p1Check.chartPoint
    # section 3.1: P1 at kT/(kV r1^2) = 0.107 and J1/J2 = 0.003 (printed digits)
    assert point['x'] == pytest.approx(0.107, abs=5e-4) and point['y'] == pytest.approx(0.003, abs=5e-4)
    assert point['DV'] == pytest.approx(0.014) and point['DTV'] == pytest.approx(1.)
    d, b = p1Check.distanceToBoundary, p1Check.nearestBoundaryPoint
    assert 0 < d < 0.5
    u = np.log10([b['x'] / point['x'], b['y'] / point['y']])
    assert np.hypot(*u) == pytest.approx(d, rel=1e-9)
    p1 = GetPreset('reel-P1')
    for scale, stable in ((0.95, False), (1.05, True)):           # unstable before, stable beyond
        p = ApplyOverrides(p1, {'kT': p1['kT'] * 10 ** (scale * u[0]), 'J1': p1['J1'] * 10 ** (scale * u[1])})
        assert _Stable(p) is stable
    # no stable point is closer than d: sample a circle of radius 0.95 d
    for angle in np.linspace(0, 2 * np.pi, 72, endpoint=False):
        p = ApplyOverrides(p1, {'kT': p1['kT'] * 10 ** (0.95 * d * np.cos(angle)),
                                'J1': p1['J1'] * 10 ** (0.95 * d * np.sin(angle))})
        assert not _Stable(p)


def test_damping_held_as_given():
    p1 = GetPreset('reel-P1')
    assert DesignParameters(ResolveDrive(parameters=p1)) == ['J1', 'J2', 'kT', 'DT', 'DV']
    drive = ElasticDriveFromParameters(p1)
    constants = ApplyOverrides(p1, {'dT': drive.dT, 'dV': drive.gear.dV})
    assert DesignParameters(ResolveDrive(parameters=constants)) == ['J1', 'J2', 'kT', 'dT', 'dV']
    assert DesignParameters(ResolveDrive(parameters=GetPreset('reel-P6'))) == ['J1', 'J2', 'kT', 'DTV', 'DV']
    measures = DesignCheck(ResolveDrive(parameters=p1))
    held = DesignCheck(ResolveDrive(parameters=constants))
    for r, heldKey, heldValue in ((measures, 'DT', 0.014), (held, 'dT', drive.dT)):
        up = next(x for x in r.recommendations if x.parameter == 'J1' and x.factor > 1)
        after = ElasticDriveFromParameters(ApplyOverrides(r.parameters, up.changes))
        assert (after.DT if heldKey == 'DT' else after.dT) == pytest.approx(heldValue, rel=1e-12)
    # holding dT (instead of D_T) while J1 grows lowers D_T as 1/sqrt(factor) (eq. (22))
    up = next(x for x in held.recommendations if x.parameter == 'J1' and x.factor > 1)
    assert ElasticDriveFromParameters(ApplyOverrides(constants, up.changes)).DT == pytest.approx(0.014 / up.factor ** 0.5)


def test_to_dict_is_json_ready(p1Check):
    data = json.loads(json.dumps(p1Check.ToDict(), allow_nan=False))
    assert {'stable', 'maxRealPart', 'chartPoint', 'recommendations', 'S', 'margin'} <= set(data)
    assert set(data['S']) == {'+1', '-1'} and data['S']['-1']['stable'] is False
    assert {'x', 'y', 'DV', 'DTV', 'distanceToBoundary'} <= set(data['chartPoint'])
    for x in data['recommendations']:
        assert {'parameter', 'factor', 'newValue', 'maxRealPartAfter'} <= set(x)
    assert data['margin']['decades'] == DEFAULT_MARGIN and 'stable with margin' in data['margin']['rule']


@pytest.mark.messages
def test_bad_arguments():
    p1 = GetPreset('reel-P1')
    with pytest.raises(ValueError, match="DesignCheck: 'margin' must be in \\[0, 1\\] decades, got -0.1"):
        DesignCheck(ResolveDrive(parameters=p1), margin=-0.1)
    with pytest.raises(ValueError, match="DesignCheck: 'span' must be in \\(1, 10000\\]"):
        DesignCheck(ResolveDrive(parameters=p1), span=1.)
    with pytest.raises(TypeError, match="DesignCheck: 'margin' must be a real number"):
        DesignCheck(ResolveDrive(parameters=p1), margin='0.1')
    with pytest.raises(ValueError, match="ChatterWhileLowering: the reel-changer simulation needs loadMass, leverArm, motorSpeed; missing"):
        ConfirmBySimulation(DesignCheck(ResolveDrive(parameters=GetPreset('chart') | {'J1': 0.01, 'kT': 10., 'DT': 0.01})))


def test_nearest_stable_value():
    p1 = GetPreset('reel-P1')
    assert NearestStableValue(ResolveDrive(parameters=p1), 'J1', +1, span=1.5) is None
    assert NearestStableValue(ResolveDrive(parameters=GetPreset('reel-P2')), 'J1', +1) == 0.3        # already stable
    with pytest.raises(ValueError, match="'direction' must be -1 or \\+1"):
        NearestStableValue(ResolveDrive(parameters=p1), 'J1', 0)
    with pytest.raises(ValueError, match="'span' must be > 1"):
        NearestStableValue(ResolveDrive(parameters=p1), 'J1', 1, span=0.5)


@pytest.mark.physics
def test_simulation_confirms_recommendations(p1Check):
    # P1 chatters while lowering; none of its recommended drives does (one rotation each)
    calls = []
    r = ConfirmBySimulation(p1Check, progress=lambda: calls.append(1))
    assert r.simulatedChatter is True
    assert [x.simulatedChatter for x in r.recommendations] == [False] * len(p1Check.recommendations)
    assert len(calls) == 1 + len(p1Check.recommendations)
    assert r.ToDict()['simulatedChatterWhileLowering'] is True
