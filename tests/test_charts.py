"""Tests of the stability charts (exudyn_worm.analysis.charts.stabilitychart): the vectorized chart agrees with the single-drive
analysis, the largest real part agrees with the verdict and with numpy's eigenvalues, the chart is
dimensionless, S = +1 is stable everywhere, boundaries, ranges, JSON and bad input."""
import json
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings, strategies as st
from numpy.testing import assert_allclose

from exudyn_worm.analysis.charts.stabilitychart import (ChartCoefficients, ChartCoordinates, ComputeStabilityChart, MaxRealPartGrid, UnstableGrid)
from exudyn_worm.analysis.charts.contours import ContourLines
from exudyn_worm.analysis.charts.quartic import MaxRealPart
from exudyn_worm.model.drive import ElasticDrive, MeshDampingFromMeasure, TorsionalDampingFromMeasure
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GearFromParameters, GetPreset
from exudyn_worm.model.stability import AnalyzeStability, CharacteristicCoefficients, HurwitzStable

GEAR25 = GearFromParameters(GetPreset('chart'), meshDamping=False)     # set (25)
J2_25 = GetPreset('chart')['J2']
GEAR28 = GearFromParameters(GetPreset('reel-P1'), meshDamping=False)   # set (28)
J2_28 = GetPreset('reel-P1')['J2']

#: |largest real part| / omega below which eigenvalue- and Hurwitz-based verdicts may differ by rounding
#: (omega = b4^(1/4), the scale of the eigenvalues)
ROUNDING = 1e-9

logX = st.floats(-4., 2.)
logY = st.floats(-6., 0.)
DVs = st.floats(0.001, 0.2)
DTVs = st.floats(0., 30.)


def Drive(gear, J2, x, y, DV, DTV):
    """The ElasticDrive at chart point (x, y, DV, DTV), built through the single-drive path."""
    J1, kT = y * J2, x * gear.kV * gear.r1**2
    g = gear.Replace(dV=MeshDampingFromMeasure(DV, gear.kV, gear.r2, J2))
    return ElasticDrive(g, J1=J1, J2=J2, kT=kT, dT=TorsionalDampingFromMeasure(DTV * DV, kT, J1))


def Omega(b):
    return np.sqrt(np.sqrt(np.asarray(b)[3]))


# --- agreement with the single-drive analysis -------------------------------------------------------------------
@pytest.mark.physics
@pytest.mark.parametrize('DV, DTV', [(0.014, 1.), (0.014, 25.), (0.056, 5.)])
def test_mask_agrees_with_scalar_analysis_at_random_points(DV, DTV):
    chart = ComputeStabilityChart(GEAR25, J2_25, DV, DTV, resolution=(150, 130))
    assert chart.unstable.shape == (130, 150) and chart.unstable.any() and not chart.unstable.all()
    rng = np.random.default_rng(6)
    i, j = rng.integers(0, 130, 300), rng.integers(0, 150, 300)
    # half the samples next to the boundary, where a wrong formula would show first
    edge = np.argwhere(chart.unstable[1:, :] != chart.unstable[:-1, :])
    k = rng.integers(0, len(edge), 150)
    i, j = np.r_[i, edge[k, 0]], np.r_[j, edge[k, 1]]
    checked = 0
    for a, c in zip(i, j):
        drive = Drive(GEAR25, J2_25, chart.x[c], chart.y[a], DV, DTV)
        b = CharacteristicCoefficients(drive, -1)
        assert (not HurwitzStable(b)) == chart.unstable[a, c]
        lam = AnalyzeStability(drive).contact[-1].eigenvalues
        if abs(lam.real.max()) > ROUNDING * Omega(b):
            assert (not AnalyzeStability(drive).contact[-1].stable) == chart.unstable[a, c]
            checked += 1
    assert checked > 400


@pytest.mark.physics
@settings(max_examples=200, deadline=None)
@given(logX, logY, DVs, DTVs, st.sampled_from([-1, 1]))
def test_grid_functions_agree_with_analysis(lx, ly, DV, DTV, S):
    x, y = 10.**lx, 10.**ly
    drive = Drive(GEAR25, J2_25, x, y, DV, DTV)
    b = CharacteristicCoefficients(drive, S)
    assert_allclose(ChartCoefficients(GEAR25, J2_25, x, y, DV, DTV, S), b, rtol=1e-12)
    lam = AnalyzeStability(drive).contact[S].eigenvalues
    assert_allclose(MaxRealPartGrid(GEAR25, J2_25, x, y, DV, DTV, S), lam.real.max(), rtol=0,
                    atol=1e-10 * Omega(b))
    assert bool(UnstableGrid(GEAR25, J2_25, x, y, DV, DTV, S)) == (not HurwitzStable(b))


@pytest.mark.physics
def test_chart_coordinates_of_p1_and_its_verdict():
    drive = ElasticDriveFromParameters(GetPreset('reel-P1'))
    c = ChartCoordinates(drive)
    assert set(c) == {'x', 'y', 'DV', 'DTV'}
    # section 3.1: P1 at kT/(kV r1^2) = 0.107, J1/J2 = 0.003 (printed digits)
    assert abs(c['x'] - 0.107) <= 5e-4 and abs(c['y'] - 0.003) <= 5e-4
    assert_allclose([c['DV'], c['DTV']], [0.014, 1.], rtol=1e-12)
    # the drive's own analysis and the chart evaluation at its coordinates are the same thing
    unstable = bool(UnstableGrid(drive.gear, drive.J2, c['x'], c['y'], c['DV'], c['DTV'], -1))
    assert unstable == (not AnalyzeStability(drive).contact[-1].stable) == True  # noqa: E712
    assert_allclose(MaxRealPartGrid(drive.gear, drive.J2, c['x'], c['y'], c['DV'], c['DTV']),
                    AnalyzeStability(drive).contact[-1].eigenvalues.real.max(), rtol=1e-9)


@pytest.mark.physics
def test_many_drives_at_once_broadcast():
    x = np.array([0.107, 0.107, 0.214, 0.0214])
    y = np.array([0.00303, 0.0091, 0.00303, 0.00303])
    DV = np.array([0.014, 0.014, 0.014, 0.056])
    out = MaxRealPartGrid(GEAR28, J2_28, x, y, DV, 1.)
    assert out.shape == (4,)
    for k in range(4):
        assert out[k] == pytest.approx(float(MaxRealPartGrid(GEAR28, J2_28, x[k], y[k], DV[k], 1.)), rel=1e-12)
    assert (UnstableGrid(GEAR28, J2_28, x, y, DV, 1.) == (out > 0)).all()
    assert ChartCoefficients(GEAR28, J2_28, x[:, None], y[None, :], 0.014, 1.).shape == (4, 4, 4)


# --- largest real part ----------------------------------------------------------------------------------------
@pytest.mark.physics
@pytest.mark.parametrize('DV, DTV, S', [(0.014, 1., -1), (0.056, 25., -1), (0.014, 5., 1), (0.014, 0.2, -1)])
def test_max_real_part_sign_matches_mask_and_eigvals(DV, DTV, S):
    chart = ComputeStabilityChart(GEAR25, J2_25, DV, DTV, resolution=200, S=S)
    b = chart.Coefficients()
    mrp = chart.maxRealPart
    assert mrp.shape == chart.unstable.shape
    clear = np.abs(mrp) > ROUNDING * Omega(b)
    assert clear.mean() > 0.99
    assert ((mrp > 0) == chart.unstable)[clear].all()
    rng = np.random.default_rng(1)
    i, j = rng.integers(0, 200, 500), rng.integers(0, 200, 500)
    ref = np.array([np.roots(np.r_[1., b[:, a, c]]).real.max() for a, c in zip(i, j)])
    assert_allclose(mrp[i, j], ref, rtol=0, atol=1e-10 * Omega(b[:, i, j]).max())


@pytest.mark.physics
def test_max_real_part_of_hard_polynomials():
    cases = [np.poly([-1., -1., -1., -1.]),                  # fourfold root: Newton cannot polish it
             np.poly([1., -2., -3., -4.]),                   # real roots, b4 < 0
             np.poly([-0.5 + 3j, -0.5 - 3j, 2e-3 + 1e4j, 2e-3 - 1e4j]),   # widely separated modes
             np.poly([0., -1., -1 + 1j, -1 - 1j])]           # b4 = 0
    b = np.array([c[1:].real for c in cases]).T
    value, fallback = MaxRealPart(b, returnFallback=True)
    assert_allclose(value, [-1., 1., 2e-3, 0.], rtol=1e-6, atol=2e-4)
    assert fallback.shape == (4,) and fallback.dtype == bool


# --- dimensionless chart ---------------------------------------------------------------------------------------
@pytest.mark.physics
@settings(max_examples=150, deadline=None)
@given(logX, logY, DVs, DTVs, st.floats(0.1, 10.), st.floats(0.01, 100.), st.floats(0.01, 1000.))
def test_chart_depends_only_on_dimensionless_gear(lx, ly, DV, DTV, size, stiffness, J2):
    """Same angles and r2/r1, any size, mesh stiffness and J2: the same scaled eigenvalues, same verdict."""
    other = GEAR25.Replace(r1=GEAR25.r1 * size, r2=GEAR25.r2 * size, kV=GEAR25.kV * stiffness)
    x, y = 10.**lx, 10.**ly
    b0 = ChartCoefficients(GEAR25, J2_25, x, y, DV, DTV)
    b1 = ChartCoefficients(other, J2, x, y, DV, DTV)
    s0 = MaxRealPart(b0) / Omega(b0)
    s1 = MaxRealPart(b1) / Omega(b1)
    assert s1 == pytest.approx(s0, rel=1e-9, abs=1e-12)
    assume(abs(s0) > ROUNDING)
    assert bool(UnstableGrid(GEAR25, J2_25, x, y, DV, DTV)) == bool(UnstableGrid(other, J2, x, y, DV, DTV))


#: neighbourhood (decades) within which set (25)'s verdict must be constant for the set-(28) comparison: sets
#: (25) and (28) have the same angles and friction but r2/r1 = 5.8671 and 5.8698 (0.05 % apart), which moves
#: the boundary a little; 0.01 decades is 0.17 % of the 6-decade axis, below a printed line width
NEIGHBOURHOOD = 0.01


@pytest.mark.physics
@settings(max_examples=300, deadline=None)
@given(logX, logY, st.floats(0.005, 0.2), st.floats(0., 30.))
def test_sets_25_and_28_give_the_same_verdict(lx, ly, DV, DTV):
    x, y = 10.**lx, 10.**ly
    d = 10.**np.array([-NEIGHBOURHOOD, 0., NEIGHBOURHOOD])
    around = UnstableGrid(GEAR25, J2_25, x * d[:, None], y * d[None, :], DV, DTV)
    assume(around.all() or not around.any())
    assert bool(UnstableGrid(GEAR28, J2_28, x, y, DV, DTV)) == bool(around[1, 1])


@pytest.mark.physics
def test_sets_25_and_28_charts_nearly_identical():
    c25 = ComputeStabilityChart(GEAR25, J2_25, 0.014, 1., resolution=300)
    c28 = ComputeStabilityChart(GEAR28, J2_28, 0.014, 1., resolution=300)
    differ = c25.unstable != c28.unstable
    assert differ.sum() < 0.001 * differ.size          # only grid points next to the boundary
    assert not (differ[1:-1, 1:-1] & (c25.unstable[:-2, 1:-1] == c25.unstable[2:, 1:-1])
                & (c25.unstable[1:-1, :-2] == c25.unstable[1:-1, 2:])
                & (c25.unstable[:-2, 1:-1] == c25.unstable[1:-1, 2:])).any()


# --- S = +1 and the paper's charts -----------------------------------------------------------------------------
@pytest.mark.physics
@pytest.mark.parametrize('DV', [0.014, 0.056])
@pytest.mark.parametrize('DTV', [1., 5., 25.])
def test_no_unstable_points_for_S_plus_1(DV, DTV):
    chart = ComputeStabilityChart(GEAR25, J2_25, DV, DTV, resolution=300, S=+1)
    assert not chart.unstable.any()
    assert chart.unstableXRange is None and chart.unstableYRange is None and chart.unstableFraction == 0.
    assert chart.boundaries == [] and (chart.maxRealPart < 0).all()


@pytest.mark.physics
def test_damping_shrinks_the_unstable_x_range():
    """Sanity of the chart object (not a paper statement): at D_TV = 5 more mesh damping ends the unstable
    stiffness ratios earlier."""
    ends = [ComputeStabilityChart(GEAR25, J2_25, DV, 5., resolution=200).unstableXRange[1] for DV in (0.014, 0.056)]
    assert ends[1] < ends[0]


# --- boundaries and ranges ---------------------------------------------------------------------------------
@pytest.mark.physics
def test_boundary_points_separate_stable_from_unstable():
    chart = ComputeStabilityChart(GEAR25, J2_25, 0.014, 5., resolution=200)
    lines = chart.boundaries
    assert lines and all(line.ndim == 2 and line.shape[1] == 2 for line in lines)
    pts = np.concatenate(lines)
    assert (pts[:, 0] >= chart.x[0]).all() and (pts[:, 0] <= chart.x[-1]).all()
    assert (pts[:, 1] >= chart.y[0]).all() and (pts[:, 1] <= chart.y[-1]).all()
    step = 10.**(np.log10(chart.x[1] / chart.x[0]))
    sample = pts[np.random.default_rng(2).integers(0, len(pts), 300)]
    around = np.array([1. / step, 1., step])
    for x, y in sample:
        # the exact verdict changes within one grid step (3 x 3 points around it, itself included: at the tip
        # of an oval thinner than a grid step only the point itself is unstable)
        verdicts = chart.IsUnstable(x * around[:, None], y * around[None, :])
        assert verdicts.any() and not verdicts.all()


@pytest.mark.physics
def test_ranges_cover_the_unstable_points_and_the_boundary():
    chart = ComputeStabilityChart(GEAR25, J2_25, 0.014, 25., resolution=200)
    (x0, x1), (y0, y1) = chart.unstableXRange, chart.unstableYRange
    i, j = np.nonzero(chart.unstable)
    assert x0 <= chart.x[j].min() and x1 >= chart.x[j].max()
    assert y0 <= chart.y[i].min() and y1 >= chart.y[i].max()
    # beyond the range the exact verdict is stable along the whole y axis (dense scan), just inside it is not
    dense = np.geomspace(chart.y[0], chart.y[-1], 200001)
    assert not chart.IsUnstable(x1 * 1.001, dense).any() and chart.IsUnstable(x1 / 1.001, dense).any()
    assert chart.clippedSides == ['left', 'bottom'] and x0 == chart.x[0] and y0 == chart.y[0]
    assert chart.unstableFraction == pytest.approx(chart.unstable.mean())
    assert chart.unstableArea == pytest.approx(chart.unstableFraction * 36.)
    ext = chart.UnstableYExtent()
    assert ext.shape == chart.x.shape and (ext[~chart.unstable.any(axis=0)] == 0).all()


@pytest.mark.physics
@pytest.mark.parametrize('DV, DTV', [(0.014, 1.), (0.056, 5.)])
def test_range_ends_do_not_depend_on_the_resolution(DV, DTV):
    """At D_V = 0.014, D_TV = 1 the region ends in a needle thinner than a grid step of a 100 x 100 grid;
    the ends follow it."""
    ends = [ComputeStabilityChart(GEAR25, J2_25, DV, DTV, resolution=n) for n in (100, 400)]
    assert_allclose(ends[0].unstableXRange, ends[1].unstableXRange, rtol=1e-6)
    assert_allclose(ends[0].unstableYRange, ends[1].unstableYRange, rtol=1e-6)
    dense = np.geomspace(1e-6, 1., 400001)
    x1 = ends[0].unstableXRange[1]
    assert not ends[0].IsUnstable(x1 * 1.001, dense).any() and ends[0].IsUnstable(x1 / 1.001, dense).any()


@pytest.mark.physics
def test_contour_lines_of_a_circle():
    u = np.linspace(-1., 1., 81)
    field = u[None, :]**2 + u[:, None]**2 - 0.25
    lines = ContourLines(u, u, field)
    assert len(lines) == 1
    line = lines[0]
    assert_allclose(line[0], line[-1])                        # closed
    assert_allclose(np.hypot(line[:, 0], line[:, 1]), 0.5, atol=2e-3)
    # a curve that leaves the grid stays open
    open_ = ContourLines(u, u, u[None, :] + 0. * u[:, None])
    assert len(open_) == 1 and not np.allclose(open_[0][0], open_[0][-1])
    assert_allclose(open_[0][:, 0], 0., atol=1e-12)


# --- data object -------------------------------------------------------------------------------------------
def test_to_dict_is_json_ready():
    chart = ComputeStabilityChart(GEAR25, J2_25, 0.014, 1., resolution=60)
    d = json.loads(json.dumps(chart.ToDict(boundaries=True), allow_nan=False))
    assert {'DV', 'DTV', 'unstableXRange', 'unstableYRange', 'unstableFraction'} <= set(d)
    assert d['DV'] == 0.014 and d['DTV'] == 1. and d['S'] == -1 and d['resolution'] == [60, 60]
    assert len(d['unstableXRange']) == 2 and d['unstableXRange'][0] < d['unstableXRange'][1]
    assert all(len(p) == 2 for line in d['boundaries'] for p in line)
    stable = ComputeStabilityChart(GEAR25, J2_25, 0.014, 1., resolution=30, S=1).ToDict()
    assert stable['unstableXRange'] is None and stable['unstableYRange'] is None


def test_grid_is_logarithmic_and_maxrealpart_is_lazy():
    chart = ComputeStabilityChart(GEAR25, J2_25, 0.014, 1., xRange=(1e-2, 10.), yRange=(1e-5, 1e-1),
                                  resolution=(31, 41))
    assert_allclose(chart.x, np.geomspace(1e-2, 10., 31)) and len(chart.y) == 41
    assert 'maxRealPart' not in chart._cache
    assert chart.maxRealPart.shape == (41, 31)


# --- bad input -----------------------------------------------------------------------------------------------
@pytest.mark.messages
@pytest.mark.parametrize('kwargs, error, message', [
    (dict(DV=-0.1), ValueError, r"ComputeStabilityChart: 'DV' must be >= 0, got -0.1"),
    (dict(DTV=math.nan), ValueError, r"ComputeStabilityChart: 'DTV' must be finite"),
    (dict(J2=0.), ValueError, r"ComputeStabilityChart: 'J2' must be > 0 kg\*m\^2, got 0"),
    (dict(xRange=(1., 0.1)), ValueError, r"'xRange' must have min < max, got \(1, 0.1\)"),
    (dict(yRange=(0., 1.)), ValueError, r"'yRange\[0\]' must be > 0, got 0"),
    (dict(xRange=3.), TypeError, r"'xRange' must be a pair \(min, max\), got 3.0"),
    (dict(resolution=1), ValueError, r"'resolution' must be in \[2, 20000\] grid points per axis, got 1"),
    (dict(resolution=10.5), TypeError, r"'resolution' must be an integer"),
    (dict(resolution=(10, 20, 30)), ValueError, r"'resolution' must be an int or a pair"),
    (dict(S=0), ValueError, r"contact parameter 'S' must be \+1 or -1, got 0"),
    (dict(gear='chart'), TypeError, r"'gear' must be a WormGear, got str"),
])
def test_bad_input(kwargs, error, message):
    args = dict(gear=GEAR25, J2=J2_25, DV=0.014, DTV=1.)
    args.update(kwargs)
    with pytest.raises(error, match=message):
        ComputeStabilityChart(**args)


@pytest.mark.messages
def test_bad_input_of_grid_functions():
    with pytest.raises(ValueError, match=r"ChartCoefficients: 'x' must be finite and > 0 everywhere, got -1"):
        UnstableGrid(GEAR25, J2_25, np.array([0.1, -1.]), 0.01, 0.014, 1.)
    with pytest.raises(ValueError, match=r"MaxRealPart: 'b' must have shape \(4, ...\), got \(3,\)"):
        MaxRealPart([1., 2., 3.])
    with pytest.raises(TypeError, match=r"ChartCoordinates: 'drive' must be an ElasticDrive, got dict"):
        ChartCoordinates({})
