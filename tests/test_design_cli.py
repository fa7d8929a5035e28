"""``exudyn-worm check`` and the hint of ``exudyn-worm stability --json`` (run in-process with Main)."""
import json
import re

import numpy as np
import pytest

from exudyn_worm import AnalyzeStability, ApplyOverrides, ElasticDriveFromParameters, GetPreset
from exudyn_worm.analysis.design import designcheck
from exudyn_worm.cli.main import Main
from exudyn_worm.analysis.design.designcheck import DesignCheck, LocalCharts
from exudyn_worm.plotting.plot_design import PlotDesignCheck, _Dense
from exudyn_worm.drive.wholedrive import ResolveDrive
from paper_model import BoundaryDecades, HurwitzStable


def Run(capsys, *argv):
    rc = Main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def Json(capsys, *argv):
    rc, out, err = Run(capsys, *argv, '--json')
    assert rc == 0, err
    return json.loads(out)


# every test runs in an empty directory and checks that nothing was written to it (conftest)
pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')


def test_check_p1_json(capsys):
    data = Json(capsys, 'check', '--preset', 'reel-P1')
    assert data['stable'] is False and data['maxRealPart'] > 0
    assert data['S']['+1']['stable'] is True and data['S']['-1']['stable'] is False
    assert {'x', 'y', 'DV', 'DTV', 'distanceToBoundary'} <= set(data['chartPoint'])
    moves = {(r['parameter'], r['factor'] > 1) for r in data['recommendations']}
    assert {('J1', True), ('J1', False), ('kT', True), ('kT', False), ('J2', True), ('J2', False),
            ('DT', True), ('DV', True)} == moves
    p1 = GetPreset('reel-P1')
    for r in data['recommendations']:
        assert set(r) >= {'parameter', 'factor', 'newValue', 'maxRealPartAfter'}
        assert r['maxRealPartAfter'] < 0
        assert AnalyzeStability(ElasticDriveFromParameters(ApplyOverrides(p1, {r['parameter']: r['newValue']}))).stable
    assert data['margin']['decades'] == 0.1


def test_check_stable_preset_and_set(capsys):
    assert Json(capsys, 'check', '--preset', 'reel-P2')['recommendations'] == []
    data = Json(capsys, 'check', '--preset', 'reel-P1', '--set', 'J1=0.3')      # = P2 via --set
    assert data['stable'] is True and data['recommendations'] == []


# Stability boundaries of set (28) when J1, J2 or kT alone changes (DT, DV held), from the Hurwitz conditions
# (17), (19) of eqs. (16), (22), (23) written out in tests/paper_model.py: (parameter, stable t, unstable t)
# brackets in decades, the up and down boundary of each
BRACKETS = {('J1', True): (0.5, 0.), ('J1', False): (-0.5, 0.), ('J2', True): (0.5, 0.), ('J2', False): (-0.5, 0.),
            ('kT', True): (0.3, 0.), ('kT', False): (-0.5, 0.)}


def _Recommended(key, up, margin=0.1):
    """Factor of the smallest stable-with-margin change: the boundary moved on by the margin (decades)."""
    t = BoundaryDecades(GetPreset('reel-P1'), key, *BRACKETS[key, up])
    return 10. ** (t + margin if up else t - margin)


@pytest.mark.physics
def test_check_recommendations_are_the_boundaries_of_eq19_plus_the_margin(capsys):
    data = Json(capsys, 'check', '--preset', 'reel-P1')
    factors = {(r['parameter'], r['factor'] > 1): r['factor'] for r in data['recommendations']}
    for key, up in BRACKETS:
        # both bisect to 1e-10 decades or finer: 1e-9 relative covers both
        assert factors[key, up] == pytest.approx(_Recommended(key, up), rel=1e-9), (key, up)


def test_check_table(capsys):
    rc, out, err = Run(capsys, 'check', '--preset', 'reel-P1')
    assert rc == 0 and err == ''
    p1 = GetPreset('reel-P1')
    x, y = p1['kT'] / (p1['kV'] * p1['r1']**2), p1['J1'] / p1['J2']      # chart axes of Figure 4
    for text in ('Verdict: UNSTABLE', 'S = -1: UNSTABLE', f'Chart point: x = kT/(kV r1^2) = {x:.4g}',
                 f'J1/J2 = {y:.3g}', 'decades to the stability boundary', 'Margin: 0.1 decades'):
        assert text in out, text
    rows = {line.split()[0] + line.split()[1][0]: line.split()[1] for line in out.splitlines()
            if line.startswith('  ') and len(line.split()) > 2 and line.split()[1][0] in 'x/'}
    for key, up in BRACKETS:
        factor = _Recommended(key, up)
        assert rows[key + ('x' if up else '/')] == (f'x{factor:.3g}' if up else f'/{1 / factor:.3g}'), (key, up)
    rc, out, _ = Run(capsys, 'check', '--preset', 'reel-P2')
    assert 'STABLE with margin' in out and 'No change needed.' in out
    rc, out, _ = Run(capsys, 'check', '--preset', 'reel-P1', '--span', '1.5')
    assert 'No single parameter within a factor 1.5' in out and 'Best pair: J1 /' in out


@pytest.mark.physics
def test_check_best_pair_is_stable_with_margin_by_eq19(capsys):
    """Within a factor 1.5 no single change suffices (every boundary of eq. (19) plus the margin lies beyond it);
    the pair that is given is stable by (17), (19) on the whole margin square (tests/paper_model.py, 11 x 11
    points). Which pair is smallest is the design module's grid search and is not re-derived here."""
    assert all(max(f, 1 / f) > 1.5 for f in (_Recommended(key, up) for key, up in BRACKETS))
    data = Json(capsys, 'check', '--preset', 'reel-P1', '--span', '1.5')
    assert data['recommendations'] == []
    pair = data['bestPair']
    p1 = GetPreset('reel-P1')
    offsets = [10. ** (0.1 * k / 5) for k in range(-5, 6)]          # 10^-0.1 .. 10^0.1
    for fa in offsets:
        for fb in offsets:
            changed = dict(p1)
            for key, factor, off in zip(pair['parameters'], pair['factors'], (fa, fb)):
                assert 1 / 1.5 <= factor <= 1.5
                changed[key] = p1[key] * factor * off
            assert HurwitzStable(changed), (fa, fb)
    assert not HurwitzStable(p1)


def test_check_plot(capsys, tmp_path):
    path = tmp_path / 'check.png'
    rc, out, err = Run(capsys, 'check', '--preset', 'reel-P1', '--plot', str(path), '--json')
    assert rc == 0 and json.loads(out)['stable'] is False
    assert path.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
    assert f'wrote {path}' in err


@pytest.mark.parametrize('argv, message', [
    (('--margin', '-1'), "DesignCheck: 'margin' must be in [0, 1] decades, got -1"),
    (('--span', '1'), "DesignCheck: 'span' must be in (1, 10000], got 1"),
    (('--margin', 'abc'), "argument --margin: invalid float value: 'abc'"),
    (('--plot', 'chart.txt'), "--plot: expected a file ending in .png, .pdf, .svg, got 'chart.txt'"),
    (('--set', 'J1=-1'), "'J1' must be > 0 kg*m^2, got -1"),
    (('--preset', 'chart', '--set', 'J1=0.01', '--set', 'kT=10', '--set', 'DT=0.01', '--simulate'),
     "check --simulate: the reel-changer simulation needs loadMass, leverArm, motorSpeed; missing loadMass, leverArm, motorSpeed"),
    (('--simulate', '--step-size', '0'), "argument --step-size: must be > 0 s, got 0 s"),
    (('--step-size', '0.01'), "--step-size 0.01 only applies with --simulate"),
    (('--plot', 'missing-folder/check.png'), "--plot missing-folder/check.png: the folder missing-folder does not exist"),
    (('--set', 'J4=0.1'), "DriveSideChain: 'J4' needs the stiffness 'k4' (N*m/rad) of the spring-damper on its motor side"),
    (('--set', 'kA=1e8'), "'kA' = 1e+08 N/m > 0 needs the worm's axially moving mass 'mA' (kg)"),
])
@pytest.mark.messages
def test_check_bad_input(capsys, argv, message):
    rc, out, err = Run(capsys, 'check', *argv)
    assert rc == 2 and out == ''
    assert err.count('\n') == 1 and err.startswith('exudyn-worm: error: ') and message in err, err
    assert 'Traceback' not in err


@pytest.mark.messages
def test_check_plot_path_is_checked_before_computing(capsys, tmp_path, monkeypatch):
    monkeypatch.setattr(designcheck, 'DesignCheck', lambda *a, **k: pytest.fail('computed before the path check'))
    (tmp_path / 'folder.png').mkdir()
    rc, _, err = Run(capsys, 'check', '--plot', str(tmp_path / 'folder.png'))
    assert rc == 2 and 'is a folder' in err


def test_stability_json_has_the_tables_hint(capsys):
    data = Json(capsys, 'stability', '--preset', 'reel-P1')
    hint = data['hint']
    assert [h['parameter'] for h in hint['nearestStable']] == ['J1', 'kT']
    j1 = hint['nearestStable'][0]
    assert 0.033 < j1['below'] < 0.1 < j1['above'] < 0.3 and j1['ratioName'] == 'J1/J2'
    assert j1['ratioAbove'] == pytest.approx(j1['above'] / 33.)
    rc, out, _ = Run(capsys, 'stability', '--preset', 'reel-P1')
    assert hint['text'] in out.splitlines()                       # the table prints the same hint
    assert Json(capsys, 'stability', '--preset', 'reel-P2')['hint'] is None


def test_check_simulate(capsys):
    data = Json(capsys, 'check', '--preset', 'reel-P1', '--span', '1.5', '--simulate')
    # no single change within 1.5: the best pair is simulated (and the given drive)
    assert data['simulatedChatterWhileLowering'] is True
    assert data['bestPair']['simulatedChatterWhileLowering'] is False


def test_heavy_damping_recommendations_get_a_remark(capsys):
    """P1's table recommends DT x65 (0.91) and DV x79 (1.1): damping ratios an engineer cannot take at face value."""
    rc, out, err = Run(capsys, 'check', '--preset', 'reel-P1')
    note = [line for line in out.splitlines() if line.startswith('Note: DT = 0.912 and DV = 1.1 are damping ratios')]
    assert rc == 0 and len(note) == 1 and 'critical damping' in note[0]


def test_check_plot_reads_well():
    """Readable: D_V / D_TV in mathtext, no label box over the boundary, the shading in the legend, and
    the legend off the chart."""
    result = DesignCheck(ResolveDrive(parameters=GetPreset('reel-P1')))
    fig = PlotDesignCheck(result, LocalCharts(result.drive), title='reel-P1')
    ax = fig.axes[0]
    legend = ax.get_legend()
    texts = [t.get_text() for t in legend.get_texts()]
    for text in [ax.get_title()] + texts:
        plain = re.sub(r'\$[^$]*\$', '', text)                  # what is left outside mathtext
        assert not re.search(r'D_V|D_TV|D_T\b', plain), text
    assert '$D_V$ = 0.014' in ax.get_title() and '$D_{TV}$ = 1' in ax.get_title()
    assert texts[0].startswith('$S = -1$: unstable region (shaded)')
    fig.draw_without_rendering()
    renderer = fig._get_renderer()
    assert legend.get_window_extent(renderer).y1 <= ax.get_window_extent(renderer).y0 + 0.5   # below the axes
    boundary = np.concatenate([_Dense(ax.transData.transform(line.get_xydata())) for line in ax.lines
                               if (line.get_gid() or '').startswith('boundary')])
    labels = [t for t in ax.texts if t.get_gid() == 'move label']
    assert len(labels) == 4                                     # J1 x = J2 /, J1 / = J2 x, kT x, kT /
    for text in labels:
        assert text.get_bbox_patch() is None                    # no box that could hide the line
        box = text.get_window_extent(renderer)
        inside = ((boundary[:, 0] >= box.x0) & (boundary[:, 0] <= box.x1) &
                  (boundary[:, 1] >= box.y0) & (boundary[:, 1] <= box.y1))
        assert not inside.any(), text.get_text()


@pytest.mark.slow
def test_check_states_chatter_after_a_disturbance(capsys):
    # J1 = 0.25 kg m^2 with 0.5 mm backlash: the linear check calls the drive stable with margin, yet rest and
    # chatter coexist (docs/chatter-amplitude.md); by default the check of a drive with backlash says so
    backlash = ('check', '--preset', 'reel-P1', '--set', 'J1=0.25', '--set', 'backlash=0.5 mm')
    data = Json(capsys, *backlash)
    assert data['stable'] is True
    d = data['disturbance']
    assert d['linearlyStable'] is True and d['chatterFound'] is True
    # the threshold lies between kicks of 1 % (ends at rest) and 30 % (ends in chatter) of the motor speed
    speed = GetPreset('reel-P1')['motorSpeed']
    assert 0.01 * speed < d['smallestDisturbance'] < 0.3 * speed
    assert d['forceFactor'] > 4.
    assert d['text'].startswith('linearly stable, but chatters after a worm-speed disturbance of')
    rc, out, _ = Run(capsys, *backlash)
    assert rc == 0 and 'After a disturbance (lowering, nonlinear mesh): linearly stable, but chatters' in out
    assert 'disturbance' not in Json(capsys, *backlash, '--no-disturbance')


def test_check_disturbance_only_when_asked_or_backlash(capsys):
    assert 'disturbance' not in Json(capsys, 'check', '--preset', 'reel-P1')     # no backlash: not by default
    d = Json(capsys, 'check', '--preset', 'reel-P2', '--disturbance')['disturbance']
    assert d['linearlyStable'] is True and d['chatterFound'] is False and d['smallestDisturbance'] is None
    d = Json(capsys, 'check', '--preset', 'reel-P1', '--disturbance')['disturbance']
    assert d['linearlyStable'] is False and d['chatterFound'] is True and d['smallestDisturbance'] == 0.
    rc, _, err = Run(capsys, 'check', '--preset', 'reel-P1', '--disturbance', '--no-disturbance')
    assert rc == 2 and err.count('\n') == 1
