"""Plots only draw: the plotting modules take results and draw; every analysis lives on the
analysis side with its result object; numerical modules never import matplotlib; one spelling, ``.plot()``."""
import ast
import importlib
import inspect
import pkgutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import exudyn_worm
from exudyn_worm.items.results import SimulationResult
from exudyn_worm.analysis.studies.studygrid import ParseVariation
from exudyn_worm.analysis.studies.study import Study, StudyResult
from exudyn_worm.analysis.charts.stabilitychart import (ChartCoordinates, ChartPoints, ComputeStabilityChart, FirstCriterionCurves,
                                                        PresetChartPoints, StabilityChart)
from exudyn_worm.analysis.design.designcheck import DesignCheckResult
from exudyn_worm.analysis.charts.speedchart import SpeedChart
from exudyn_worm.plotting.plot_charts import PlotStabilityChart
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.analysis.studies.studymap import ComputeChatterMap

PACKAGE = Path(exudyn_worm.__file__).parent
PLOT_DIR = PACKAGE / 'plotting'
PLOT_MODULES = sorted(p.stem for p in PLOT_DIR.glob('plot*.py'))
NON_PLOT_MODULES = sorted(m.name for m in pkgutil.walk_packages(exudyn_worm.__path__, 'exudyn_worm.')
                          if not m.name.rsplit('.', 1)[-1].startswith('plot'))
#: modules a plotting module may take anything from: the other plotting modules and pure helpers (labels, spacing,
#: the atomic write that saves a figure whole or not at all)
DRAWING_HELPERS = {'params.parameters', '_spacing', '_files'}


def _InternalImports(stem: str):
    """``(module, name)`` of every relative import in a plotting module, at its top or inside a function."""
    tree = ast.parse((PLOT_DIR / f'{stem}.py').read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level in (1, 2):      # .plot (plotting), ..analysis.charts.stabilitychart
            base = 'plotting' if node.level == 1 else ''
            for alias in node.names:
                module = '.'.join(part for part in (base, node.module) if part)
                yield module or alias.name, alias.name
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and (node.module or '').startswith('exudyn_worm'):
            for alias in node.names:
                yield node.module.removeprefix('exudyn_worm').lstrip('.') or alias.name, alias.name
        elif isinstance(node, ast.Import):
            assert not any(a.name.startswith('exudyn_worm') for a in node.names), f'{stem}: import {node.names}'


def test_the_plot_modules_are_found():
    assert {'plot', 'plot_charts', 'plot_design', 'plot_study'} <= set(PLOT_MODULES)


@pytest.mark.parametrize('stem', PLOT_MODULES)
def test_plot_module_imports_no_computation(stem):
    """From an analysis module a plotting module takes only result types (for its isinstance checks) and
    constants (units, labels), never a function: no linearization, chart, preset or design check is run
    while drawing (plot_study ran linearizations, plot_design recomputed LocalCharts, plot_charts resolved preset
    names)."""
    imports = list(_InternalImports(stem))
    assert imports, stem
    for module, name in imports:
        if module.startswith('plotting') or module in DRAWING_HELPERS:
            continue
        obj = getattr(importlib.import_module(f'exudyn_worm.{module}'), name)
        assert not (inspect.isfunction(obj) or inspect.ismodule(obj)), \
            f'{stem} imports the {"module" if inspect.ismodule(obj) else "function"} {module}.{name}'


def test_the_rule_catches_a_computation(tmp_path, monkeypatch):
    """The check above is not vacuous: the import plot_study had before fails it."""
    monkeypatch.setattr(sys.modules[__name__], 'PLOT_DIR', tmp_path)
    (tmp_path / 'plot_old.py').write_text(textwrap.dedent('''
        def AnalyticalMap():
            from ..analysis.stability.drivestability import AnalyzeDrive
            from ..drive.presets import ApplyOverrides
    '''))
    with pytest.raises(AssertionError, match='function analysis.stability.drivestability.AnalyzeDrive'):
        test_plot_module_imports_no_computation('plot_old')


def test_no_numerical_module_imports_matplotlib():
    """Import every module of the package except the plotting ones, one after the other in a fresh
    interpreter: none pulls in matplotlib."""
    code = textwrap.dedent(f'''
        import importlib, sys
        for name in {NON_PLOT_MODULES!r}:
            importlib.import_module(name)
            if 'matplotlib' in sys.modules:
                print(name)
                break
        else:
            print('none', len({NON_PLOT_MODULES!r}))
    ''')
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ['none', str(len(NON_PLOT_MODULES))], f'{out[0]} imports matplotlib'
    assert {'exudyn_worm.analysis.charts.stabilitychart', 'exudyn_worm.analysis.studies.studymap', 'exudyn_worm.analysis.design.designcheck', 'exudyn_worm.analysis.studies.study',
            'exudyn_worm.items.results', 'exudyn_worm.cli.formatchart'} <= set(NON_PLOT_MODULES)


def test_every_result_object_spells_plot_in_lower_case():
    """The result objects of the analyses draw with ``.plot()``, and only with it."""
    for cls in (SimulationResult, StudyResult, StabilityChart, FirstCriterionCurves, SpeedChart, DesignCheckResult):
        assert callable(getattr(cls, 'plot', None)), cls.__name__
        assert not hasattr(cls, 'Plot'), cls.__name__


def test_chart_points_are_resolved_before_drawing():
    """charts.ChartPoints turns preset names and drives into chart coordinates; the plotting function only
    takes coordinates and names the resolver for anything else."""
    pytest.importorskip('matplotlib')
    drive = ElasticDriveFromParameters(GetPreset('reel-P7'))
    c = ChartCoordinates(drive)
    p1 = PresetChartPoints(['reel-P1'])['P1']
    assert ChartPoints({'d': drive, 'q': {'x': 2., 'y': 3.}, 't': (4, 5)}) == \
        {'d': (c['x'], c['y']), 'q': (2., 3.), 't': (4., 5.)}
    assert ChartPoints(['P1']) == {'P1': (p1['x'], p1['y'])}
    assert ChartPoints(None) == {}
    chart = ComputeStabilityChart(drive.gear, drive.J2, c['DV'], c['DTV'], resolution=20)
    for points in (['P1'], {'d': drive}):
        with pytest.raises(TypeError, match='resolved by exudyn_worm.analysis.charts.stabilitychart.ChartPoints'):
            PlotStabilityChart(chart, points=points)
    ax = chart.plot(points={'d': drive})
    assert [line.get_xydata()[0].tolist() for line in ax.lines if line.get_gid() == 'point d'] == \
        [[c['x'], c['y']]]
    vertex = chart.boundaries[0][len(chart.boundaries[0]) // 2]
    assert chart.NearestBoundary(tuple(vertex)) == 0.
    assert 0. < chart.NearestBoundary((vertex[0] * 10 ** 0.5, vertex[1])) <= 0.5


@pytest.mark.messages
def test_chatter_map_names_itself_for_a_key_not_varied():
    study = Study(ResolveParameters('reel-P1'), [ParseVariation('J1=0.1,0.2'), ParseVariation('kT=7000,8000')])
    with pytest.raises(ValueError, match=r"ComputeChatterMap: 'y' must be a varied key \(J1, kT\), got 'kV'"):
        ComputeChatterMap(StudyResult(study, []), 'J1', 'kV')
