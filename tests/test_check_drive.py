"""``exudyn-worm check`` gives the verdict of ``exudyn-worm stability`` for every drive (one drive, one verdict):
the hoist files, the reel presets, a drive-side chain (Figure 19) and a load-side chain, with recommendations for
the whole drive, the self-locking verdicts at every operating point and a plot that says which boundary decides.

Independent references: the closed-form two-mass model and the drive-side chain's matrices written out from the
paper's equations (tests/paper_model.py), the self-locking limit gamma < rho of eq. (13), and ``stability``.
"""
import json
import math
import re
from contextlib import redirect_stdout
from io import StringIO
from pathlib import Path

import numpy as np
import pytest

from exudyn_worm import ApplyOverrides, GetPreset
from exudyn_worm.cli.main import Main
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.drive.presets import DriveSideChain
from exudyn_worm.analysis.design.designcheck import DesignCheck, LocalCharts
from exudyn_worm.drive import operatingpoints
from exudyn_worm.drive.wholedrive import ResolveDrive
from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from paper_model import ChainEigenvalues, HurwitzStable

DRIVES = Path(__file__).resolve().parents[1] / 'examples' / 'drives'
HOIST, AGMA, FIGURE19, LOAD_SHAFT = (str(DRIVES / f'{n}.toml') for n in ('hoist', 'hoist-agma', 'figure19', 'load-shaft'))


def _Run(*argv):
    out = StringIO()
    with redirect_stdout(out):
        rc = Main(list(argv))
    assert rc == 0, argv
    return out.getvalue()


def _Json(*argv):
    return json.loads(_Run(*argv, '--json'))


_CHECKS = {}


def _Check(*argv):
    """``check --json`` once per drive (a whole drive's check scans a few hundred linearized drives)."""
    if argv not in _CHECKS:
        _CHECKS[argv] = _Json('check', '--quiet', *argv)
    return _CHECKS[argv]


def _SameVerdict(check, stability):
    assert check['stable'] is stability['stable']
    assert check['operatingPoints'] == stability['operatingPoints']
    assert check['deciding'] == stability['deciding'] and check['dangerous'] is stability['dangerous']


def _LumpedAgma(tmp_path) -> str:
    """hoist-agma.toml without its [[loadSide]] stage: drum and load rigidly on the wheel (J2 = 0.02 + 6.2)."""
    text = Path(AGMA).read_text()
    text = re.sub(r'\[\[loadSide\]\].*?\n\n', '', text, flags=re.S)
    text = text.replace('inertia = "0.02 kg*m^2"', 'inertia = "6.22 kg*m^2"')
    assert '[[loadSide]]' not in text and '6.22 kg*m^2' in text
    path = tmp_path / 'hoist-agma-lumped.toml'
    path.write_text(text)
    return str(path)


@pytest.mark.parametrize('path', [HOIST, FIGURE19, LOAD_SHAFT])
def test_whole_drives_get_the_stability_verdict_and_recommendations(path):
    check = _Check('--config', path)
    stability = _Json('stability', '--config', path)
    _SameVerdict(check, stability)
    assert check['stable'] is False and check['model'] == 'linearized' and check['method'] == 'exudyn'
    assert check['chartPoint']['applies'] is False and check['chartPoint']['distanceToBoundary'] is None
    assert check['recommendations']
    for r in check['recommendations']:
        # the recommended drive, analysed afresh by stability, is stable; a change 0.105 decades smaller (inside the
        # margin, the boundary bisected to 1e-3 decades) is not: each move is the boundary plus the margin
        changed = _Json('stability', '--config', path, '--set', f"{r['parameter']}={r['newValue']!r}")
        assert changed['stable'] is True and r['maxRealPartAfter'] == pytest.approx(changed['maxRealPart'], rel=1e-9)
        t = math.log10(r['factor'])
        inside = r['newValue'] / r['factor'] * 10. ** (t - math.copysign(0.105, t))
        assert _Json('stability', '--config', path, '--set', f"{r['parameter']}={inside!r}")['stable'] is False, r


def test_hoist_is_unstable_while_lifting_and_lowering():
    check = _Check('--config', HOIST)
    points = {p['phase']: p for p in check['operatingPoints']}
    assert set(points) == {'lifting', 'lowering'} and not any(p['stable'] for p in points.values())
    # the file's 100 rpm and the worm radius q mx / 2 = 24 mm, tan(gamma) = z1 / q = 1/16: v0 = r1 omega / cos(gamma)
    v0 = 0.024 * 100 * 2 * math.pi / 60 / math.cos(math.atan(1 / 16))
    assert points['lifting']['slidingSpeed'] == pytest.approx(v0, rel=1e-12)
    assert 150. < check['frequencyHz'] < 250.
    text = _Run('check', '--quiet', '--config', HOIST)
    assert 'Verdict: UNSTABLE' in text and 'Deciding: lifting at 100 rpm' in text
    assert 'Chart point: none' in text and 'Smallest single changes' in text


@pytest.mark.parametrize('lumped', [pytest.param(False, marks=pytest.mark.slow), True])   # with the chain: 2.4 s
def test_agma_hoist_gets_the_danger_verdict_with_and_without_its_load_side_chain(lumped, tmp_path):
    path = _LumpedAgma(tmp_path) if lumped else AGMA
    check = _Json('check', '--quiet', '--config', path)
    _SameVerdict(check, _Json('stability', '--config', path))
    assert check['model'] == ('analytical' if lumped else 'linearized')
    # eq. (13): self-locking iff gamma < rho = atan(mu / cos(alphaN)), i.e. mu > cos(alphaN) tan(gamma) = 0.0587
    limit = math.cos(math.radians(20)) / 16
    verdicts = check['selfLockingAtOperatingPoints']
    assert len(verdicts) == 2 and check['dangerous'] is True
    for v in verdicts.values():
        assert v['static']['mu'] == 0.15 > limit and v['static']['selfLocking'] is True
        assert v['dynamic']['mu'] < limit and v['dynamic']['selfLocking'] is False and v['dangerous'] is True
    text = _Run('check', '--quiet', '--config', path)
    dangers = [line for line in text.splitlines() if line.startswith('DANGER at ')]
    assert len(dangers) == 2 and {'lifting', 'lowering'} == {d.split()[2] for d in dangers}
    assert 'grey zone 0.45 to 0.55' in text and 'moving no (mu 0.02433' in text


@pytest.mark.parametrize('preset', [f'reel-P{i}' for i in range(1, 8)])
def test_reel_presets_keep_the_two_mass_verdict(preset):
    check = _Json('check', '--preset', preset)
    _SameVerdict(check, _Json('stability', '--preset', preset))
    # constant mu: both contact states of eqs. (16)-(19) (the closed forms of tests/paper_model.py); D_T = D_TV D_V (24)
    p = dict(GetPreset(preset))
    if 'DTV' in p:
        p['DT'] = p.pop('DTV') * p['DV']
    assert check['stable'] is HurwitzStable(p) and check['model'] == 'analytical'
    assert check['chartPoint']['applies'] is True and set(check['S']) == {'+1', '-1'}
    assert (check['recommendations'] == []) is check['stableWithMargin']


def test_figure19_recommendations_are_stable_by_the_chain_matrices():
    """Figure 19 with constant mu: the linearized drive is the chain's mass, damping and stiffness matrices
    written out from eq. (14) (tests/paper_model.py); every recommended drive is stable in both contact states."""
    p = ResolveParameters(config=FIGURE19)
    for S in (+1, -1):
        assert bool(np.max(ChainEigenvalues(p, DriveSideChain(p), S).real) < 0) is (S == +1)    # chatters lowering
    check = _Check('--config', FIGURE19)
    keys = {r['parameter'] for r in check['recommendations']}
    assert {'J1', 'kT', 'J4', 'k4'} <= keys
    for r in check['recommendations']:
        q = ApplyOverrides(p, {r['parameter']: r['newValue']})
        for S in (+1, -1):
            assert np.max(ChainEigenvalues(q, DriveSideChain(q), S).real) < 0, (r, S)


def test_load_side_chain_gets_its_own_parameters_and_notes():
    check = _Check('--config', LOAD_SHAFT)
    assert {'JL1', 'kL1'} <= set(check['designParameters'])
    assert any(n.startswith('dL1 = 0 cannot be changed') for n in check['notes'])
    assert {r['parameter'] for r in check['recommendations']} >= {'kL1'}


def test_operating_points_are_computed_once_per_check(monkeypatch):
    """Inertias, stiffnesses and dampings do not move the operating points: the scans reuse the drive's."""
    calls = []
    original = operatingpoints._DutyOperatingPoints
    monkeypatch.setattr(operatingpoints, '_DutyOperatingPoints', lambda d: calls.append(1) or original(d))
    result = DesignCheck(ResolveDrive(config=FIGURE19))
    assert len(calls) == 1 and result.evaluations > 100


def test_whole_drive_plot_says_there_is_no_chart(tmp_path):
    result = DesignCheck(ResolveDrive(config=FIGURE19), span=3.)
    fig = result.plot(title='figure19')
    ax = fig.axes[0]
    title = ' '.join(ax.get_title().split())
    assert 'No stability chart' in title and 'this drive has a drive-side chain (J4, ...)' in title
    assert [t.get_text() for t in ax.get_yticklabels()][:3] == ['$J_1$', '$J_2$', '$k_T$']
    path = tmp_path / 'check.png'
    assert Main(['check', '--quiet', '--config', FIGURE19, '--span', '3', '--plot', str(path), '--json']) == 0
    assert path.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


def test_two_mass_plot_draws_the_chart_at_the_deciding_operating_point(tmp_path):
    """A Stribeck hoist without its load shaft: the chart is taken at mu(v0) and the slope of its one operating
    point (lifting only: a constant load torque at a constant speed); the drive's own point has the verdict of
    AnalyzeDrive, and a point the chart calls stable is stable for AnalyzeDrive too."""
    drive = ResolveDrive(config=_LumpedAgma(tmp_path)).Replace(
        frictionLaw='stribeck', mu=0.07, muStatic=0.12, stribeckVelocity=0.3, motorType='constantSpeed',
        motorSpeed=100 * 2 * math.pi / 60)
    assert drive.isTwoMass
    result = DesignCheck(drive)
    charts = LocalCharts(result.drive)
    analysis = AnalyzeDrive(result.drive)
    assert list(charts) == [p.S for p in analysis.operatingPoints] == [+1]
    chart, op = charts[+1], analysis.operatingPoints[0].point.operatingPoint
    assert chart.operatingPoint == op and op.dmuDv < 0
    x, y = result.chartPoint['x'], result.chartPoint['y']
    assert bool(chart.IsUnstable(x, y)) is (not analysis.stable) is True
    kT = next(r for r in result.recommendations if r.parameter == 'kT')
    assert not chart.IsUnstable(kT.chartPointAfter['x'], y)
    ax = result.plot().axes[0]
    assert 'charts at the deciding operating points' in ax.get_title() and '-0.138' in ax.get_title()
