"""examples/drive_side_inertia.py (Figures 19-20, section 3.2.5): its linear frequencies, stability verdicts and
simulated frequencies, and the agreement of its hand-built model with BuildReelChanger."""
import exudyn as exu
import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability
from exudyn_worm.drive.wholedrive import ResolveDrive

from conftest import LoadScript


@pytest.fixture(scope='module')
def example():
    return LoadScript('examples/drive_side_inertia.py', 'drive_side_inertia')


@pytest.fixture(scope='module')
def run(example):
    return example.RunExample(scanStiffnesses=(None,))


@pytest.mark.physics
def test_third_natural_frequency_is_116_hz(run, example):
    p = run['parameters']
    assert p['J4'] == example.J4 == 0.05
    assert p['d4'] == pytest.approx(2 * 0.014 * np.sqrt(p['k4'] * p['J4']), rel=1e-12)
    plus = run['linear'].State(1)
    assert len(plus.frequenciesHz) == 3 and plus.stable
    assert plus.frequenciesHz[2] == pytest.approx(116., abs=0.01)
    assert plus.modes[2].Participants(0.5) == ['inertia4']           # the new mode is inertia4's
    assert 25 < plus.frequenciesHz[0] < plus.frequenciesHz[1] < 50


@pytest.mark.physics
def test_hand_built_model_equals_build_reel_changer(run, example):
    p = run['parameters']
    built = AnalyzeLinearStability(ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p)).mbs)
    for S in (1, -1):
        np.testing.assert_allclose(run['linear'].State(S).eigenvalues, built.State(S).eigenvalues, rtol=1e-9)
    assert run['linear'].coordinates == ['motor', 'inertia4', 'worm', 'wheel']


@pytest.mark.physics
def test_extra_inertia_moves_p1_towards_stability_and_into_it(run, example):
    minus = run['linear'].State(-1)
    assert not minus.stable                                            # Figure 20: chatter continues
    assert 0 < minus.maxRealPart < run['P1maxRealPart']                # but less unstable than P1
    scan, = run['scans']
    assert scan['k4'] == run['parameters']['k4']
    (low, high), = scan['stableRanges']
    assert 0.1 < low < 0.3 < 0.5 < high < 1.                           # the region of P2 (J1 = 0.3)
    k4 = scan['k4']
    for J, sign in ((0.97 * low, 1), (1.03 * low, -1), (0.97 * high, -1), (1.03 * high, 1)):
        assert np.sign(example.MaxRealPart(example.DriveSideParameters(J, k4))) == sign


@pytest.mark.physics
def test_simulation_chatters_and_excites_the_new_mode(run):
    s = run['summary']
    growing = max(run['linear'].State(-1).modes, key=lambda m: m.eigenvalue.real)
    assert s['chatterWhileLowering']
    assert s['chatterHz'] == pytest.approx(growing.frequencyHz, abs=0.5)    # linear and simulation agree
    assert s['alpha4DominantHz'] == pytest.approx(s['thirdHarmonicHz'], abs=0.25)
    assert s['alpha4ThirdToFundamental'] > 1 > 5 * s['alpha1ThirdToFundamental']
    assert s['alpha4ModePeakHz'] == pytest.approx(116., abs=1.)


def test_worked_example_reads_time_normal_force_and_state(run):
    r = run['result']
    assert np.allclose(np.diff(r.time), run['result'].info['stepSize'], rtol=1e-6)   # a sample every step
    lifting, lowering = r.time < 1.9, (r.time > 2.5) & (r.time < 5.5)
    assert np.all(r.series['normalForce'][lifting] > 0)                # driving flank while lifting
    assert np.mean(r.series['normalForce'][lowering] < 0) > 0.6        # mostly the second flank while lowering
    second = r.series['normalForce'] < 0
    assert np.all(r.series['S'][second & (r.series['omega1'] > 1.)] == -1)


@pytest.mark.physics
def test_stable_inertia_does_not_chatter(example, run):
    """The simulation confirms the linear verdict inside the stable range."""
    scan, = run['scans']
    (low, high), = scan['stableRanges']
    p = example.DriveSideParameters(np.sqrt(low * high), scan['k4'])
    r = example.SimulateDriveSideInertia(p, stepSize=5e-4)
    assert not r.Chatter(2., 6.)


@pytest.mark.messages
def test_figures_and_bad_output_folder(example, run, tmp_path, capsys):
    paths = example._WriteFigures(run, tmp_path)
    assert sorted(p.name for p in paths) == ['fig19_linear_scan.png', 'fig20_accelerations.png', 'fig20_spectrum.png']
    assert all(p.stat().st_size > 1000 for p in paths)
    blocker = tmp_path / 'file'
    blocker.write_text('x')
    assert example.main(['--out', str(blocker / 'sub')]) == 2
    err = capsys.readouterr().err
    assert err.startswith('drive_side_inertia.py: error: cannot write to --out') and err.count('\n') == 1
