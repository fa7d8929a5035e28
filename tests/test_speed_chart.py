"""Stability over motor speed with a speed-dependent friction law: the chart over speed, the
command line, the design check's speed recommendation and the study's verdict at the operating point."""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from exudyn_worm.analysis.design.designcheck import DesignCheck
from exudyn_worm.analysis.design.designscan import SPEED_KEY
from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.drive.presets import ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.model.profiles import STANDARD_GRAVITY
from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.analysis.charts.speedchart import RPM, SpeedChart, SpeedCurve, SpeedStabilityChart
from exudyn_worm.model.stability import AnalyzeStability, OperatingPointAt
from exudyn_worm.drive.wholedrive import ResolveDrive

#: reel-P3 with the steep Stribeck law of docs/friction.md (mu(v0) = 0.132 at 472.5 rpm)
P3 = {**GetPreset('reel-P3'), 'frictionLaw': 'stribeck', 'mu': 0.092, 'muStatic': 0.2, 'stribeckVelocity': 0.9}
SPEEDS = np.geomspace(20, 2000, 25) * RPM


def test_constant_mu_does_not_depend_on_speed():
    chart = SpeedStabilityChart(ResolveDrive(parameters=GetPreset('reel-P3')), SPEEDS)
    atRest = AnalyzeStability(ElasticDriveFromParameters(GetPreset('reel-P3')))
    # the reel changer's duty lifts and lowers at m g l: one curve per direction, each its contact state at rest
    assert [(c.phase, c.S) for c in chart.curves] == [('lifting', 1), ('lowering', -1)]
    for c in chart.curves:
        np.testing.assert_allclose(c.maxRealPart, np.max(atRest.contact[c.S].eigenvalues.real), rtol=1e-12)
    np.testing.assert_allclose(chart.maxRealPart, max(np.max(atRest.contact[S].eigenvalues.real) for S in (1, -1)),
                               rtol=1e-12)
    assert chart.unstableRanges == [] and chart.Boundaries() == [] and chart.frictionLaw == 'constant'


def test_each_speed_is_the_extended_eq16_at_its_operating_point():
    chart = SpeedStabilityChart(ResolveDrive(parameters=P3), SPEEDS)
    drive = ElasticDriveFromParameters(P3)
    torque = P3['loadMass'] * STANDARD_GRAVITY * P3['leverArm']
    for i in (0, 12, 24):
        op = OperatingPointAt(drive.gear, SPEEDS[i], torque)
        expected = np.max(AnalyzeStability(drive, op).contact[-1].eigenvalues.real)
        assert chart.Curve(-1).maxRealPart[i] == pytest.approx(expected, rel=1e-12)
        lifting = np.max(AnalyzeStability(drive, OperatingPointAt(drive.gear, SPEEDS[i], torque, 1)).contact[1]
                         .eigenvalues.real)
        assert chart.Curve(1).maxRealPart[i] == pytest.approx(lifting, rel=1e-12)
        assert chart.maxRealPart[i] == pytest.approx(max(expected, lifting), rel=1e-12)
        assert chart.mu[i] == pytest.approx(op.mu) and chart.dmuDv[i] == pytest.approx(op.dmuDv)


def test_the_chattering_speed_range_of_reel_p3():
    chart = SpeedStabilityChart(ResolveDrive(parameters=P3), SPEEDS)
    # docs/friction.md: stable at 50 rpm and at >= 700 rpm, unstable at 100 to 472.5 rpm
    assert not chart.unstable[0] and not chart.unstable[-1]
    (low, high), = chart.unstableRanges
    assert low / RPM <= 110 and high / RPM >= 472.5
    b = chart.Boundaries()
    assert len(b) == 2 and 50 < b[0] / RPM < 100 and 472.5 < b[1] / RPM < 700
    for boundary in b:            # the interpolated boundary: the sign changes across it
        near = SpeedStabilityChart(ResolveDrive(parameters=P3), [boundary * 0.97, boundary * 1.03]).maxRealPart
        assert near[0] * near[1] < 0
    d = chart.ToDict()
    assert d['unstableRangesRpm'][0][0] == pytest.approx(low / RPM) and len(d['maxRealPart']) == 25


def test_unstable_ranges_of_separate_runs():
    s = np.arange(1., 8.)
    curve = SpeedCurve('lowering', -1, 1., s, np.array([1., -1., 1., 1., -1., -1., 2.]), s, s)
    assert curve.unstableRanges == [(1., 1.), (3., 4.), (7., 7.)]
    assert len(curve.Boundaries()) == 4
    # the chart's ranges are those of the largest real part over its curves
    other = SpeedCurve('lifting', 1, 1., s, np.array([-1., 1., -1., -1., -1., -1., -1.]), s, s)
    chart = SpeedChart(s, s, s, s, (other, curve), 'stribeck')
    assert chart.unstableRanges == [(1., 4.), (7., 7.)] and chart.Curve(-1) is curve
    with pytest.raises(ValueError, match='no lowering operating point'):
        SpeedChart(s, s, s, s, (other,), 'stribeck').Curve(-1)


@pytest.mark.parametrize('speeds, match', [([], 'non-empty'), ([10., -1.], r"'motorSpeeds\[1\]' must be > 0 rad/s")])
def test_bad_speeds(speeds, match):
    with pytest.raises(ValueError, match=match):
        SpeedStabilityChart(ResolveDrive(parameters=P3), speeds)


def test_needs_the_load():
    p = {k: v for k, v in P3.items() if k != 'loadMass'}
    with pytest.raises(ValueError, match="the load .* needs loadMass, leverArm; missing loadMass"):
        SpeedStabilityChart(ResolveDrive(parameters=p), SPEEDS)
    p = {k: v for k, v in P3.items() if k not in ('loadMass', 'leverArm')}
    with pytest.raises(ValueError, match=r"the drive has no load torque.*give \[load\]"):
        SpeedStabilityChart(ResolveDrive(parameters=p), SPEEDS)


def test_at_the_drives_own_speed_a_curve_is_its_verdict():
    """Evaluated at the duty's own speed, each curve is the analysis of `stability` at that operating point."""
    analysis = AnalyzeDrive(ResolveDrive(parameters=P3))
    chart = SpeedStabilityChart(ResolveDrive(parameters=P3), [P3['motorSpeed']])
    assert [p.phase for p in chart.ownPoints] == ['lifting', 'lowering']
    for p in analysis.operatingPoints:
        assert chart.Curve(p.S).maxRealPart[0] == pytest.approx(p.maxRealPart, rel=1e-12)
    assert chart.stable is analysis.stable is False


def test_a_drive_without_motor_takes_its_load_at_every_speed():
    p = {k: v for k, v in P3.items() if k != 'motorSpeed'}
    chart = SpeedStabilityChart(ResolveDrive(parameters=p), SPEEDS[:3])
    with_motor = SpeedStabilityChart(ResolveDrive(parameters=P3), SPEEDS[:3])
    assert chart.ownPoints == () and chart.stable is None
    for a, b in zip(chart.curves, with_motor.curves):
        np.testing.assert_allclose(a.maxRealPart, b.maxRealPart, rtol=1e-12)


def test_the_study_verdict_is_taken_at_the_operating_point():
    assert AnalyzeDrive(ResolveDrive(parameters=GetPreset('reel-P3'))).stable
    assert not AnalyzeDrive(ResolveDrive(parameters=P3)).State(-1).stable                   # 472.5 rpm lies in the chattering range
    assert AnalyzeDrive(ResolveDrive(parameters=ApplyOverrides(P3, {'motorSpeed': 2000 * RPM}))).stable


def test_design_check_recommends_a_speed_change_that_is_stable_with_margin():
    result = DesignCheck(ResolveDrive(parameters=P3))
    assert not result.stable
    speeds = [r for r in result.recommendations if r.parameter == SPEED_KEY]
    assert {r.factor > 1 for r in speeds} == {True, False}            # faster and slower both help
    for r in speeds:
        chart = SpeedStabilityChart(ResolveDrive(parameters=P3), r.newValue * 10. ** np.linspace(-result.margin, result.margin, 21))
        assert not chart.unstable.any()
        assert r.maxRealPartAfter < 0
    # and the drive scans use mu at the operating point: with the nominal constant mu P3 is stable
    assert DesignCheck(ResolveDrive(parameters=GetPreset('reel-P3'))).stable
    assert SPEED_KEY not in DesignCheck(ResolveDrive(parameters=GetPreset('reel-P3'))).scans


def _Cli(*args):
    return subprocess.run([sys.executable, '-m', 'exudyn_worm', 'chart', '--preset', 'reel-P3', '--set',
                           'frictionLaw=stribeck', '--set', 'mu=0.092', '--set', 'muStatic=0.2', '--set',
                           'stribeckVelocity=0.9 m/s', *args], capture_output=True, text=True)


def test_cli_chart_over_speed(tmp_path):
    run = _Cli('--speed', '20rpm:2000rpm:9:log')
    assert run.returncode == 0, run.stderr
    assert 'CHATTER' in run.stdout and 'Chatter while lowering (S = -1, load torque 2060 N*m) at' in run.stdout
    assert "At the drive's own operating points" in run.stdout and 'the drive is UNSTABLE' in run.stdout
    run = _Cli('--speed', '50rpm,472.5rpm,2000rpm', '--json')
    data = json.loads(run.stdout)
    assert data['unstable'] == [False, True, False]
    assert data['motorSpeedRpm'][1] == pytest.approx(472.5)
    figure = tmp_path / 'speed.png'
    run = _Cli('--speed', '20rpm:2000rpm:9:log', '--output', str(figure))
    assert run.returncode == 0 and figure.stat().st_size > 0


def test_cli_chart_over_speed_bad_input():
    run = _Cli('--speed', '0:100rpm:3')
    # refused as the --vary grid of a sweep is: at parsing, naming the specification and the key
    assert run.returncode == 2 and "'motorSpeed=0:100rpm:3': 'motorSpeed' must be > 0 rad/s, got 0" in run.stderr
    assert 'Traceback' not in run.stderr
