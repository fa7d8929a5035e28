"""One drive, one verdict: `stability`, `check`, `chart --speed` (at the drive's own speeds) and `sweep` (its linear
columns) give the same verdict for whole drives with a load-side chain, a drive-side chain, an axial bearing, a speed table, a
constant speed, a motor on its characteristic, a constant load torque, a lever load and constant, Stribeck or AGMA
friction."""
import json
import math
from pathlib import Path

import pytest

from exudyn_worm.cli.main import Main

DRIVES = Path(__file__).resolve().parents[1] / 'examples' / 'drives'
RPM = 2 * math.pi / 60

#: the drive's options, its J2 in kg*m^2 as given (sweep varies J2 at that value: one run of the drive itself), and
#: the verdict its file states (None: not stated; the commands must still agree)
CASES = {
    # load-side chain, speed table, constant load torque, Stribeck friction: chatters at +-100 rpm (its file)
    'hoist': (['--config', str(DRIVES / 'hoist.toml')], 0.02, False),
    # the same hoist at 1450 rpm with the AGMA law (mu 0.024 at 3.65 m/s): its modes decay
    'hoist-agma': (['--config', str(DRIVES / 'hoist-agma.toml')], 0.02, None),
    # drive-side chain (Figure 19), lever load, constant speed, constant mu: P1 chatters while lowering (section 3.2)
    'figure19': (['--config', str(DRIVES / 'figure19.toml')], 33., False),
    # load-side chain, lever load: the whole drive chatters at about 230 Hz (its file)
    'load-shaft': (['--config', str(DRIVES / 'load-shaft.toml')], 0.02, False),
    # axial bearing and a motor on its characteristic (a free rotor: its rigid-body mode is not a growth)
    'reel-P2 bearing, characteristic': (['--preset', 'reel-P2', '--set', 'kA=7e8', '--set', 'mA=5', '--set',
                                         'motorType=characteristic', '--set', 'motorInertia=0.05', '--set',
                                         'stallTorque=200', '--set', 'noLoadSpeed=52 rad/s'], 33., None),
}

pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')   # nothing written to the cwd


def _Json(capsys, *argv, status=0):
    assert Main(list(argv)) == status, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize('name', [pytest.param(n, marks=pytest.mark.slow) if n == 'load-shaft' else n   # 2.1 s
                                  for n in sorted(CASES)])
def test_stability_chart_and_sweep_give_one_verdict(capsys, name):
    drive, J2, expected = CASES[name]
    simulates = True           # the step rule takes the operating points (at rest AGMA's slope asked for 6e-12 s)
    stability = _Json(capsys, 'stability', *drive, '--json')
    points = stability['operatingPoints']
    assert points and stability['stable'] is all(p['stable'] for p in points)
    assert all(p['stable'] is (p['maxRealPart'] < 0) for p in points)
    if expected is not None:
        assert stability['stable'] is expected

    speeds = sorted({abs(p['motorSpeed']) for p in points})
    chart = _Json(capsys, 'chart', *drive, '--speed', ','.join(f'{s / RPM!r}rpm' for s in speeds),
                  '--json', '--quiet')
    assert chart['stable'] is stability['stable']
    assert [(p['phase'], p['stable']) for p in chart['operatingPoints']] == [(p['phase'], p['stable']) for p in points]
    curves = {c['S']: c for c in chart['curves']}
    for p in points:         # the chart's own linearization at this speed and load: the same point
        i = min(range(len(speeds)), key=lambda k: abs(chart['motorSpeed'][k] - abs(p['motorSpeed'])))
        assert chart['motorSpeed'][i] == pytest.approx(abs(p['motorSpeed']), rel=1e-9)
        curve = curves[p['S']]
        assert curve['loadTorque'] == pytest.approx(abs(p['loadTorque']), rel=1e-12)
        assert curve['unstable'][i] is (not p['stable'])
        assert curve['maxRealPart'][i] == pytest.approx(p['maxRealPart'], rel=1e-9, abs=1e-9)

    check = _Json(capsys, 'check', *drive, '--json', '--quiet', '--no-disturbance')
    assert check['stable'] is stability['stable']
    assert [(p['phase'], p['stable']) for p in check['operatingPoints']] == [(p['phase'], p['stable']) for p in points]

    # a short run at a fixed step: the linear columns do not depend on the simulation
    sweep = _Json(capsys, 'sweep', *drive, '--vary', f'J2={J2!r}', '--end-time', '0.02', '--step-size', '1e-5',
                  '--no-check-step', '--workers', '1', '--quiet', '--json', status=0 if simulates else 1)
    run, = sweep['runs']
    assert run['status'] == ('ok' if simulates else 'failed'), run['error']
    assert run['analyticStable'] is stability['stable']
    lowering = [p['stable'] for p in points if p['S'] == -1]
    assert run['analyticStableLowering'] is all(lowering)
