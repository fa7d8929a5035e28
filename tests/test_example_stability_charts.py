"""examples/stability_charts.py (Figures 3-5): its numbers, its output folder check, and that it writes PNGs."""
import math

import numpy as np
import pytest

from conftest import LoadScript
from exudyn_worm.charts import ChartCoordinates
from exudyn_worm.presets import DriveFromParameters, GetPreset
from exudyn_worm.stability import AnalyzeStability

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
        drive = DriveFromParameters(GetPreset(f'reel-{label}'))
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
