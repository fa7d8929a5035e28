"""Tests of the chart measures of the validation (validation/charts.py, validation/charts_paper.py): the paper's
stated domain as a closed form of set (25), the linear-axis measures on charts whose answer is written out by hand,
the tail beyond a bound, and the bound on the stated J1 range against the paper's equations written out
independently (tests/paper_model.py)."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from paper_model import BoundaryDecades
from validation.charts import DisplayedDomain, Tail, TailText
from validation.charts_paper import (BOUND_X_END, BoundChart, LinearArea, LinearCellWidths, LinearXExtent,
                                     PaperChart, SmallXLinearYExtent)

#: set (25) as printed: kV = 1.7728e6 N/m, r1 = 3.235 mm, J2 = 0.1 kg*m^2; section 2.3: kT from 5e-3 to 5 N*m,
#: J1 from 1e-6 to 1e-3 kg*m^2
KV, R1, J2 = 1.7728e6, 3.235e-3, 0.1
KT_RANGE, J1_RANGE = (5e-3, 5.), (1e-6, 1e-3)


def _Chart(x, y, unstable, xRange=None):
    """A stand-in chart: only the fields the measures read."""
    return SimpleNamespace(x=np.asarray(x, float), y=np.asarray(y, float), unstable=np.asarray(unstable, bool),
                           unstableXRange=xRange)


@pytest.mark.physics
def test_the_stated_ranges_give_the_chart_domain_in_closed_form():
    (x0, x1), (y0, y1) = DisplayedDomain()
    # x = kT / (kV r1^2), y = J1 / J2 with the printed numbers of set (25)
    assert (x0, x1) == pytest.approx((KT_RANGE[0] / (KV * R1**2), KT_RANGE[1] / (KV * R1**2)), rel=1e-12)
    assert (y0, y1) == pytest.approx((J1_RANGE[0] / J2, J1_RANGE[1] / J2), rel=1e-12)
    assert (x0, x1, y0, y1) == pytest.approx((2.6950e-4, 0.26950, 1e-5, 1e-2), rel=5e-5)   # as validation/README.md prints


@pytest.mark.physics
def test_the_paper_domain_charts_span_the_stated_ranges():
    (x0, x1), (y0, y1) = DisplayedDomain()
    chart = PaperChart(0.014, 25.)
    assert (chart.x[0], chart.x[-1], chart.y[0], chart.y[-1]) == pytest.approx((x0, x1, y0, y1), rel=1e-12)
    bound = BoundChart(0.014, 25.)
    assert (bound.x[0], bound.x[-1], bound.y[0], bound.y[-1]) == pytest.approx((x0, BOUND_X_END, y0, y1), rel=1e-12)


def test_linear_cells_tile_the_domain():
    # edges halfway between the points, the outer ones at the ends: [1, 1.5, 3, 4]
    assert LinearCellWidths([1., 2., 4.]) == pytest.approx([0.5, 1.5, 1.])
    grid = np.geomspace(2.695e-4, 0.2695, 600)
    assert LinearCellWidths(grid).sum() == pytest.approx(0.2695 - 2.695e-4, rel=1e-12)
    with pytest.raises(ValueError, match="'grid' must be an increasing 1-d array of at least 2 values"):
        LinearCellWidths([1., 1., 2.])


def test_linear_area_of_an_all_unstable_chart_is_the_domain_area():
    x, y = np.geomspace(2.695e-4, 0.2695, 50), np.geomspace(1e-5, 1e-2, 40)
    chart = _Chart(x, y, np.ones((40, 50)))
    assert LinearArea(chart) == pytest.approx((0.2695 - 2.695e-4) * (1e-2 - 1e-5), rel=1e-12)
    assert LinearArea(_Chart(x, y, np.zeros((40, 50)))) == 0.


def test_linear_area_of_a_half_plane():
    # x = 0 .. 10 (11 points), y = 0 .. 2 (3 points), unstable for x >= 5: its cells span x from 4.5 to 10
    x, y = np.linspace(0., 10., 11), np.linspace(0., 2., 3)
    unstable = np.broadcast_to(x >= 5., (3, 11))
    assert LinearArea(_Chart(x, y, unstable)) == pytest.approx(5.5 * 2.)


def test_linear_x_extent():
    assert LinearXExtent(_Chart([1.], [1.], [[True]], (0.02, 0.3))) == pytest.approx(0.28)
    assert LinearXExtent(_Chart([1.], [1.], [[False]], None)) == 0.


def test_small_x_linear_y_extent_is_the_width_weighted_mean():
    x, y = [0.01, 0.03, 0.05, 0.2], [1., 2., 3., 4.]
    unstable = np.array([[1, 0, 0, 1],
                         [1, 0, 1, 1],
                         [1, 0, 1, 1],
                         [0, 0, 1, 1]])
    # columns x < 0.10: extents 2 (y 1..3), 0 (none), 2 (y 2..4); cell widths 0.01, 0.02, 0.085 (edges 0.01, 0.02,
    # 0.04, 0.125); the column at x = 0.2 is left out
    expected = (2. * 0.01 + 0. * 0.02 + 2. * 0.085) / (0.01 + 0.02 + 0.085)
    assert SmallXLinearYExtent(_Chart(x, y, unstable)) == pytest.approx(expected, rel=1e-12)
    assert SmallXLinearYExtent(_Chart(x, y, unstable), xMax=0.005) == 0.


def test_tail_beyond_and_before_a_bound():
    x, y = [0.1, 1., 10.], [1e-3, 1e-2, 1e-1]
    unstable = np.array([[1, 0, 0],
                         [1, 1, 0],
                         [1, 1, 0]])
    tail = Tail(_Chart(x, y, unstable, (0.1, 5.)), 3.)
    assert tail['decades'] == pytest.approx(math.log10(5. / 3.))
    assert tail['end'] == 5. and tail['band'] == (1e-2, 1e-1) and tail['edges'] == ['top']
    assert 'decades beyond 3' in TailText(_Chart(x, y, unstable, (0.1, 5.)), 3.)
    assert Tail(_Chart(x, y, unstable, (0.1, 0.3)), 3.)['decades'] == pytest.approx(-1.)
    assert Tail(_Chart(x, y, np.zeros((3, 3)), None), 3.) is None
    with pytest.raises(ValueError, match="'bound' must be a stiffness ratio > 0"):
        Tail(_Chart(x, y, unstable, (0.1, 5.)), 0.)


@pytest.mark.physics
def test_bound_on_the_stated_J1_range_against_the_paper_equations():
    """D_TV = 1, D_V = 0.014: on the stated J1 range the unstable band ends against its top edge J1 = 1e-3 kg*m^2,
    so its end is the boundary in kT at that J1 of eqs. (16), (17), (19), (22), (23) written out independently.
    Compared to the digits the report and the known-differences list print for it (x = 0.375): the chart's end is
    bisected on the ridge of the unstable set, whose refinement may look up to about 1e-4 decades past the top edge
    (0.37540 against 0.37530 here)."""
    chart = BoundChart(0.014, 1.)
    tail = Tail(chart, 3.)
    assert tail['edges'] == ['top']
    kVr1 = KV * R1**2
    p = dict(alphaN=math.radians(20.), gamma=math.radians(5.3228), mu=0.132, r1=R1, r2=18.98e-3, kV=KV, DV=0.014,
             DT=0.014, J1=J1_RANGE[1], J2=J2, kT=0.3 * kVr1)
    t = BoundaryDecades(p, 'kT', stable=math.log10(1. / 0.3), unstable=0.)      # x = 0.3 unstable, x = 1 stable
    reference = 0.3 * 10.**t
    assert abs(reference - 0.375) <= 0.0005 and abs(tail['end'] - 0.375) <= 0.0005      # both print as 0.375
    assert math.log10(3. / reference) == pytest.approx(0.90, abs=0.005)                  # "0.90 decades before 3"
