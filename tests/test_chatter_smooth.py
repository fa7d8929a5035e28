"""The branch of friction-limited chatter from a smooth Hopf point (exudyn_worm.analysis.orbits.smoothbranch.SmoothHopfBranch,
used by AnalyzeChatterBranch and ``exudyn-worm chatter``): reel-P3 with a Stribeck law over the motor speed.

Independent checks: the Hopf point (from the orbits' amplitudes alone) against the linear boundary (roots of the
analytical model's largest real part, S = -1); near a smooth Hopf point the squared amplitude grows linearly with
the distance from it (normal form of the Hopf bifurcation), which a third orbit must follow.
"""
import json
import math

import pytest

import exudyn_worm as ew
from exudyn_worm.analysis.orbits.smoothbranch import SmoothHopfBranch
from exudyn_worm.analysis.charts.speedchart import RPM
from exudyn_worm.cli.chatter import ParseVary
from exudyn_worm.cli.main import Main, UsageError
from exudyn_worm.drive.wholedrive import ResolveDrive

pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')

STRIBECK = ['--set', 'frictionLaw=stribeck', '--set', 'mu=0.092', '--set', 'muStatic=0.2',
            '--set', 'stribeckVelocity=0.9']


def test_vary_takes_units_as_set_does():
    name, low, high = ParseVary('motorSpeed=80rpm:89rpm')
    assert name == 'motorSpeed'
    assert (low, high) == pytest.approx((80 * 2 * math.pi / 60, 89 * 2 * math.pi / 60), rel=1e-12)
    assert ParseVary('backlash=0.2 mm:0.5mm')[1:] == pytest.approx((2e-4, 5e-4), rel=1e-12)
    assert ParseVary('J1=0.05:0.3') == ('J1', 0.05, 0.3)
    with pytest.raises(UsageError, match=r"'motorSpeed' must be an angular speed"):
        ParseVary('motorSpeed=80kg:89rpm')


@pytest.mark.slow
@pytest.mark.physics
def test_cli_follows_the_friction_branch_from_its_hopf_point(capsys):
    # before SmoothHopfBranch the command stopped at its first orbit (force factor below 1.9) or found none
    argv = ['chatter', '--preset', 'reel-P3'] + STRIBECK + ['--vary', 'motorSpeed=80rpm:89rpm', '--json']
    assert Main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    hopf, points = data['hopfPoints'][0], data['points']
    assert data['hopf']['type'] == 'supercritical'
    assert len(data['linearBoundaries']) == 1 and 84. < data['linearBoundaries'][0] / RPM < 86.
    assert hopf['linearBoundary'] == data['linearBoundaries'][0]
    assert data['hopf']['value'] == pytest.approx(hopf['linearBoundary'], rel=0.005)    # required: 0.5 %
    assert len(points) >= 10
    values = [p['value'] for p in points]
    assert values == sorted(values) and values[0] > hopf['linearBoundary']
    factors = [p['amplitude']['forceFactor'] for p in points]
    assert all(1. < f < 2. for f in factors)                  # the mesh stays in contact: friction-limited
    assert factors == sorted(factors) and all(p['stable'] for p in points)
    # smooth Hopf point: the squared amplitude is linear in the distance near it; the third orbit lies on the line
    # through the first two (from which the Hopf point was extrapolated) within 2 %
    (v1, v2, v3), (a1, a2, a3) = values[:3], [p['amplitude']['maxWheelAcceleration'] ** 2 for p in points[:3]]
    assert a3 == pytest.approx(a1 + (a2 - a1) * (v3 - v1) / (v2 - v1), rel=0.02)
    ends = [m for m in data['messages'] if m.startswith('the branch ends at motorSpeed')]
    assert len(ends) == 1 and 'the worm turns back' in ends[0]


def test_smooth_branch_refuses_bad_side_and_limit():
    p = ew.GetPreset('reel-P3')
    with pytest.raises(ValueError, match=r"SmoothHopfBranch: 'side' must be \+1 or -1"):
        SmoothHopfBranch(ResolveDrive(parameters=p), 'motorSpeed', 8.9, 0)
    with pytest.raises(ValueError, match=r"SmoothHopfBranch: 'limit' must lie on the unstable side \(above\)"):
        SmoothHopfBranch(ResolveDrive(parameters=p), 'motorSpeed', 8.9, 1, limit=8.0)


@pytest.mark.messages
def test_cli_vary_with_a_wrong_unit_is_one_line_exit_2(capsys):
    assert Main(['chatter', '--preset', 'reel-P1', '--vary', 'motorSpeed=80kg:89rpm']) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and 'Traceback' not in err
    assert "'motorSpeed' must be an angular speed in rad/s" in err
