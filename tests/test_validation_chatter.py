"""validation/chatter.py: the report's verdicts come from the numbers (synthetic studies, no simulation)."""
import pytest

from validation.chatter import TOLERANCE, Main, WriteCsv, WriteReport


def _Row(value, orbit, long, stable=True):
    return {'study': 's', 'parameter': 'J1', 'value': value, 'stable': stable,
            'orbitForceFactor': orbit, 'longForceFactor': long, 'orbitWheelAcceleration': 100.,
            'longWheelAcceleration': 100., 'orbitFrequencyHz': 40., 'longFrequencyHz': 40.}


def _Branch(rows, kicks=()):
    return {'study': 'J1', 'parameter': 'J1', 'range': (0.05, 0.3), 'points': 10, 'seconds': 1.,
            'linearBoundaries': [0.0763820], 'unstableOrbits': 0, 'folds': [], 'coexistence': [], 'disturbances': [],
            'hopf': [{'value': 0.0763821, 'type': 'supercritical', 'linearBoundary': 0.0763820,
                      'relativeDifference': 1.3e-6}], 'kicks': list(kicks), 'rows': rows}


def test_report_passes_within_and_fails_beyond_the_tolerance(tmp_path):
    inside = 2.5 * (1 + 0.9 * TOLERANCE)
    outside = 2.5 * (1 + 1.1 * TOLERANCE)
    text = WriteReport([_Branch([_Row(0.1, inside, 2.5)]), _Branch([_Row(0.1, outside, 2.5)])],
                       tmp_path / 'C.md').read_text()
    assert '**1 of 2 studies PASS.**' in text
    assert 'within 0.5 %' in text and text.count('FAIL (tolerance') == 1


def test_kick_on_the_wrong_side_of_the_threshold_fails(tmp_path):
    kicks = [{'value': 0.25, 'kick': 0.95 * 0.17, 'threshold': 0.17, 'forceFactor': 4.85},   # below, yet chatter
             {'value': 0.25, 'kick': 1.05 * 0.17, 'threshold': 0.17, 'forceFactor': 4.85}]
    text = WriteReport([_Branch([_Row(0.25, 4.85, 4.86)], kicks)], tmp_path / 'C.md').read_text()
    assert '**0 of 1 studies PASS.**' in text
    assert 'expected rest: FAIL' in text and 'expected chatter: PASS' in text
    csv = WriteCsv([_Branch([_Row(0.25, 4.85, 4.86)])], tmp_path / 'c.csv').read_text().splitlines()
    assert len(csv) == 2 and csv[0].startswith('study,parameter,value')


def _Friction(rows, hopfDifference=4.8e-6, minimumRows=8):
    rows = [{**r, 'settled': True, 'longSeconds': 60., 'peakSpread': 0.001} for r in rows]
    long = {'forceFactor': 1.91, 'peakSpread': 0.14, 'settled': True, 'duration': 14.}
    return {'study': 'reel-P3, Stribeck friction', 'parameter': 'motorSpeed', 'unit': 'rpm', 'seconds': 1.,
            'points': 16, 'branchRange': (85.2, 88.6), 'linearBoundaries': [85.08],
            'hopf': [{'value': 85.08, 'linearBoundary': 85.08, 'relativeDifference': hopfDifference,
                      'type': 'supercritical'}], 'failed': [(88.8, 'no convergence')], 'messages': [],
            'unsettled': [], 'sticking': [{'rpm': 140., 'long': long, 'orbit': {'error': 'no convergence'}}],
            'rows': rows, 'minimumRows': minimumRows}


def test_friction_branch_needs_enough_settled_points_and_its_hopf_point(tmp_path):
    rows = [_Row(86. + 0.3 * k, 1.3, 1.3 * (1 + 0.5 * TOLERANCE)) for k in range(8)]
    text = WriteReport([_Friction(rows), _Friction(rows[:7]), _Friction(rows, hopfDifference=0.006)],
                       tmp_path / 'C.md').read_text()
    assert '**1 of 3 studies PASS.**' in text
    assert 'NOT within 0.5 %' in text and 'at least 8 settled points' in text
    assert '| 140 | 1.9100 | 14.0% |' in text
    csv = WriteCsv([_Friction(rows)], tmp_path / 'c.csv').read_text().splitlines()
    assert len(csv) == 9 and csv[0].endswith('settled,longSeconds,peakSpread')


def test_only_matching_no_study_is_refused(capsys):
    with pytest.raises(SystemExit) as exit:
        Main(['--only', 'no such study'])
    assert exit.value.code == 2 and "--only 'no such study' matches no study" in capsys.readouterr().err
