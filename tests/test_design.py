"""Design check: the nearest stable J1 and kT of an unstable drive agree with the paper's chart points."""
import pytest

from exudyn_worm import AnalyzeStability, ApplyOverrides, DriveFromParameters, GetPreset
from exudyn_worm.design import NearestStableValue, StabilizingChanges


def _Stable(p):
    return AnalyzeStability(DriveFromParameters(p)).stable


def test_p1_is_stabilized_both_ways_as_figure_4_shows():
    p1 = GetPreset('reel-P1')
    ranges = {r.key: r for r in StabilizingChanges(p1)}
    j1, kT = ranges['J1'], ranges['kT']
    # Figure 4 / section 3.2.4: P2 (J1 = 0.3), P3 (J1 = 0.033), P4 (2 kT), P5 (kT / 5) are stable
    assert 0.033 < j1.below < 0.1 < j1.above < 0.3
    assert 1400. < kT.below < 7000. < kT.above < 14000.
    for r in (j1, kT):                          # the boundary: stable just beyond, unstable just inside
        for value, inside in ((r.below, r.below * 1.001), (r.above, r.above / 1.001)):
            assert _Stable(ApplyOverrides(p1, {r.key: value}))
            assert not _Stable(ApplyOverrides(p1, {r.key: inside}))
    assert j1.ratioScale == pytest.approx(1 / 33.)


def test_no_stable_value_within_a_small_span():
    assert NearestStableValue(GetPreset('reel-P1'), 'J1', +1, span=1.5) is None
    with pytest.raises(ValueError, match="'direction' must be -1 or \\+1"):
        NearestStableValue(GetPreset('reel-P1'), 'J1', 0)
    with pytest.raises(ValueError, match="'span' must be > 1"):
        NearestStableValue(GetPreset('reel-P1'), 'J1', 1, span=0.5)
