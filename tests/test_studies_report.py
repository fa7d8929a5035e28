"""validation/studies.py: the study definitions and the generated analysis of the stability map."""
import math

import numpy as np
import pytest

from exudyn_worm.drive.presets import PRESETS
from exudyn_worm.analysis.studies.study import RunStudy
from exudyn_worm.analysis.studies.studygrid import Study, Variation
from validation import studies


def test_map_grid_spans_the_paper_points():
    for DV in studies.MAP_DV:
        study = studies.MapStudy(DV)
        assert len(study.points) == 144 and study.keys == ['J1', 'kT']
        J1, kT = (np.array(v.values) for v in study.variations)
        assert np.allclose(np.diff(np.log(J1)), np.log(J1[1] / J1[0]))          # log spacing
        for name in ('reel-P2', 'reel-P3', 'reel-P4', 'reel-P5', 'reel-P6', 'reel-P7'):
            assert J1[0] < PRESETS[name]['J1'] < J1[-1] and kT[0] < PRESETS[name]['kT'] < kT[-1]
        assert study.base['DV'] == DV and study.base['DTV'] == 1. and 'DT' not in study.base


def test_backlash_study_holds_the_paper_values():
    study = studies.BacklashStudy('reel-P7')
    values = study.variations[0].values
    assert len(values) >= 9 and values[0] == 0 and values[-1] == pytest.approx(1e-3)
    assert all(any(math.isclose(v, b) for v in values) for b in (0.25e-3, 0.5e-3, 0.75e-3))
    assert study.endTime == 10. and study.windows[-1] == (6., 10.)


def test_map_analysis_finds_and_explains_a_disagreement():
    # P1 chatters and is unstable; at kT = 700 (P7's shaft, P1's worm) it is stable and quiet: both agree
    base = studies.MapStudy(0.014).base
    result = RunStudy(Study(base, [Variation('J1', (0.1,)), Variation('kT', (700., 7000.))]), workers=2, quiet=True)
    analysis = studies.MapAnalysis(result)
    assert analysis['agreement'] == 1. and analysis['disagreements'] == []
    assert analysis['counts']['unstable, chatter'] == 1 and analysis['counts']['stable, no chatter'] == 1
    # flip the simulated verdict of the stable point: it becomes a disagreement with a generated explanation
    result.rows[0]['loweringChatter'] = True
    analysis = studies.MapAnalysis(result)
    (d,) = analysis['disagreements']
    assert analysis['agreement'] == 0.5 and d['kT'] == 700. and d['analyticStable'] and d['sigma'] < 0
    assert d['gridSteps'] == 1 and d['kTFactor'] is not None and d['kTFactor'] > 1
    assert d['explanation'].startswith('Analytically stable, simulated with chatter: next to the boundary')
