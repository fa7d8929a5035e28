"""examples/stability_charts.py (Figures 3-5): its numbers, its output folder check, and that it writes PNGs."""
import math

import numpy as np
import pytest

from conftest import LoadScript
from exudyn_worm.analysis.charts.stabilitychart import ChartCoordinates, MaxRealPartGrid
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GearFromParameters, GetPreset
from exudyn_worm.model.stability import AnalyzeStability
from exudyn_worm.plotting.plot_charts import HATCHES, POINT_SIZE, NearestBoundary, PlotStabilityCharts

example = LoadScript('examples/stability_charts.py', 'example_stability_charts')


@pytest.fixture(scope='module')
def figures():
    return example.ComputeFigures(resolution=120)


@pytest.mark.physics
def test_figure3_is_fuesgen_limit(figures):
    curves = figures[3]
    u = curves.ratio
    assert abs(u - 63.) < 0.05                                  # set (25): u = 63 as printed
    i = list(np.degrees(curves.rho)).index(8.)
    for j in (10, 200, 300):
        g = curves.gamma[j]
        expected = math.tan(math.radians(8.) - g) / (u**2 * math.tan(g)) if g < math.radians(8.) else math.nan
        assert curves.limit[i, j] == pytest.approx(expected, rel=1e-12, nan_ok=True)
    # "the risk of chatter grows for increasing friction angles and decreasing pitch angles" (section 2.2)
    finite = np.where(np.isfinite(curves.limit), curves.limit, 0.)
    assert (np.diff(finite, axis=0) >= 0).all()
    assert all((np.diff(row[np.isfinite(row)]) < 0).all() for row in curves.limit)


@pytest.mark.physics
def test_figures_4_and_5_charts_and_points(figures):
    rows = example.Summary(figures)
    assert [(r['figure'], r['DV'], r['DTV']) for r in rows] == [(4, 0.014, 1.), (4, 0.014, 5.), (4, 0.014, 25.),
                                                                (5, 0.056, 1.), (5, 0.056, 5.), (5, 0.056, 25.)]
    assert all(r['S'] == -1 and r['unstableXRange'] is not None for r in rows)
    # each point's verdict on the chart of its own D_V and D_TV is the single-drive analysis of its preset
    for label, c in figures['points'].items():
        drive = ElasticDriveFromParameters(GetPreset(f'reel-{label}'))
        assert c == ChartCoordinates(drive)
        own = [chart for chart in figures[4] + [figures['P6'][4]] if math.isclose(chart.DTV, c['DTV'])]
        assert own, label
        chart = own[0]
        assert bool(chart.IsUnstable(c['x'], c['y'])) == (not AnalyzeStability(drive).contact[-1].stable)
    text = example.FormatSummary(figures)
    assert len(text.splitlines()) == 7 and 'P7' in text.splitlines()[0]


def test_output_folder_is_checked_before_computing(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(example, 'ComputeFigures', lambda *a, **k: pytest.fail('computed before the check'))
    afile = tmp_path / 'file.png'
    afile.write_text('x')
    assert example.main(['--out', str(afile)]) == 2
    assert "cannot write to --out" in capsys.readouterr().err
    assert example.main(['--out', str(tmp_path / 'new'), '--resolution', '1']) == 2
    assert '--resolution must be in [2, 20000]' in capsys.readouterr().err


def test_main_writes_the_three_figures(tmp_path, capsys):
    out = tmp_path / 'figs'
    assert example.main(['--out', str(out), '--resolution', '40']) == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == ['fig03_first_criterion.png', 'fig04_chart_DV0.014.png', 'fig05_chart_DV0.056.png']
    assert all((out / n).read_bytes()[:8] == b'\x89PNG\r\n\x1a\n' for n in names)
    assert 'fig04_chart_DV0.014.png' in capsys.readouterr().out


# --- readable charts: regions that do not blend into an unexplained grey, P3 drawn truthfully, the points of
# set (28) explained in the figure ---------------------------------------------------------------------------

@pytest.fixture(scope='module')
def drawn(figures):
    return example.DrawFigures(figures)


def _Chart(drawn, figure):
    name = next(n for n in drawn if n.startswith(f'fig{figure:02d}'))
    return drawn[name].axes[0]


@pytest.mark.parametrize('figure', [4, 5])
def test_regions_are_hatched_not_blended_and_all_explained(drawn, figure):
    ax = _Chart(drawn, figure)
    regions = [c for c in ax.collections if (c.get_gid() or '').startswith('region DTV=')]
    assert [c.get_gid() for c in regions] == [f'region DTV={v:g}' for v in example.DTV_VALUES]
    for k, region in enumerate(regions):
        # no fill (a translucent fill of three regions mixes into grey): transparent face, a hatch of its own
        assert np.all(region.get_facecolor()[:, 3] == 0.)
        assert region.hatches == [HATCHES[k]]
    assert len({tuple(r.hatches) for r in regions}) == len(regions)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    for v in example.DTV_VALUES:
        assert any(t.startswith(f'$D_{{TV}}$ = {v:g}: unstable (hatched)') for t in texts)
    assert any('crossed hatches' in t for t in texts) and any('no hatch: stable' in t for t in texts)
    assert any('P6' in t and 'boundary only' in t for t in texts)
    # the points of set (28) on the chart of set (25): said in the legend, not in a footnote
    points = next(t for t in texts if t.startswith('P1-P7'))
    assert 'set (28)' in points and 'set (25)' in points and 'P6: 2' in points
    assert not [t for t in ax.texts if 'set (28)' in t.get_text()]


def test_p3_is_outside_the_DTV25_region_and_drawn_so(figures, drawn):
    """P3 (set (28), J1 / 3) is stable on all three charts of Figure 4, analytically; the D_TV = 25 boundary
    passes 0.05 decades from it, which the main axes cannot show: the inset does, with a verdict computed
    from the chart."""
    p3 = figures['points']['P3']
    chart25 = next(c for c in figures[4] if c.DTV == 25.)
    assert not any(c.IsUnstable(p3['x'], p3['y']) for c in figures[4])
    # analytically, at P3's exact (x, y): the largest real part of the S = -1 eigenvalues of the D_TV = 25 chart
    # is negative (the grid's boundary line is not consulted)
    parameters = GetPreset('chart')
    growth = MaxRealPartGrid(GearFromParameters(parameters, meshDamping=False), parameters['J2'],
                             np.array([p3['x']]), np.array([p3['y']]), chart25.DV, 25.)
    assert growth[0] < 0.
    distance = NearestBoundary(chart25, (p3['x'], p3['y']))
    assert 0.02 < distance < example.ZOOM_DECADES
    assert 'P3' in example.PointsToZoom(figures[4], figures['points'])
    ax = _Chart(drawn, 4)
    inset = next(a for a in ax.child_axes if a.get_gid() == 'zoom P3')
    assert 'P3: stable on every chart' in inset.get_title() and 'D_{TV}$ = 25' in inset.get_title()
    fig = ax.figure
    fig.draw_without_rendering()
    radius = POINT_SIZE / 2 * fig.dpi / 72
    for axes, least in ((inset, 6 * radius), (ax, radius)):
        marker = next(l for l in axes.lines if l.get_gid() == 'point P3')
        centre = axes.transData.transform(np.column_stack([marker.get_xdata(), marker.get_ydata()]))[0]
        line = np.concatenate([l.get_xydata() for l in axes.lines if l.get_gid() == 'boundary DTV=25'])
        gap = np.min(np.hypot(*(axes.transData.transform(line) - centre).T))
        assert gap > least, (axes.get_gid(), gap, least)      # the marker does not touch the line
        # on the side of the boundary the chart calls stable: the boundary's nearest vertex is left of P3
        nearest = line[np.argmin(np.hypot(*(axes.transData.transform(line) - centre).T))]
        assert nearest[0] < p3['x']
    assert not [a for a in _Chart(drawn, 5).child_axes]            # Figure 5: no point that close


def test_inset_is_the_default_for_a_point_next_to_a_boundary(figures):
    """`exudyn-worm chart --points P3` draws through PlotStabilityCharts' default: the same inset; zoom=None: none;
    the note goes into the legend, where it meets no inset."""
    points = {k: (c['x'], c['y']) for k, c in figures['points'].items() if k in ('P1', 'P3', 'P7')}
    ax = PlotStabilityCharts(figures[4], points=points, note='gear: preset reel-P1')
    assert [a.get_gid() for a in ax.child_axes] == ['zoom P3']
    assert 'gear: preset reel-P1' in [t.get_text() for t in ax.get_legend().get_texts()]
    assert not [t for t in ax.texts if 'gear' in t.get_text()]
    assert not PlotStabilityCharts(figures[4], points=points, zoom=None).child_axes
