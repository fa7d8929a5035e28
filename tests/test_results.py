"""SimulationResult: units of every series in the CSV header, windows checked against the simulated time."""
import csv

import numpy as np
import pytest
from scipy.fft import next_fast_len

from exudyn_worm import ApplyOverrides, GetPreset, SimulateReelChanger
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.items.results import SeriesUnit, SimulationResult, _FastFftLength
from exudyn_worm.analysis.studies.studygrid import ParseVariation, Study
from exudyn_worm.drive.wholedrive import ResolveDrive


@pytest.fixture(scope='module')
def wholeDrive():
    """P1 with a drive-side inertia and an axial bearing: series phi4.. and xA.., axialForce."""
    p = ApplyOverrides(GetPreset('reel-P1'), {'J4': 0.05, 'k4': 2e4, 'kA': 5e8, 'mA': 5.})
    return SimulateReelChanger(ResolveDrive(parameters=p), endTime=0.05, progress=False)


def test_csv_header_has_a_unit_for_every_series(wholeDrive, tmp_path):
    """phi4, omega4, alpha4 and the bearing's xA, vA, aA, axialForce were written as '[-]'."""
    path = wholeDrive.ToCsv(tmp_path / 'r.csv')
    header = next(csv.reader(path.open()))
    units = dict(h[:-1].split(' [') for h in header)
    assert {k: units[k] for k in ('phi4', 'omega4', 'alpha4', 'xA', 'vA', 'aA', 'axialForce')} == {
        'phi4': 'rad', 'omega4': 'rad/s', 'alpha4': 'rad/s^2', 'xA': 'm', 'vA': 'm/s', 'aA': 'm/s^2',
        'axialForce': 'N'}
    assert [k for k, u in units.items() if u == '-'] == ['S', 'sf']
    with pytest.raises(KeyError, match="no unit known for the series 'foo'"):
        SeriesUnit('foo')


@pytest.mark.messages
def test_to_csv_refuses_a_folder(wholeDrive, tmp_path):
    with pytest.raises(ValueError, match=r"ToCsv: 'path' must be a file in an existing folder, got .* \(a folder\)"):
        wholeDrive.ToCsv(tmp_path)


@pytest.mark.messages
@pytest.mark.parametrize('windows, error, message', [
    ([(0., 0.1)], ValueError, r"the window 0:0.1 s ends after the simulated end 0.05 s"),
    ([(-0.01, 0.02)], ValueError, r"a window must have 0 <= t0 < t1 \(s\), got -0.01:0.02"),
    ((0., 0.02), TypeError, r"'windows' must be a sequence of \(t0, t1\) pairs"),
])
def test_windows_beyond_the_end_are_refused(wholeDrive, windows, error, message):
    """A window past the end was judged on the part that exists: a P1 run to 6 s said no chatter in 2-10 s."""
    with pytest.raises(error, match=message):
        wholeDrive.WindowMetrics(windows)


@pytest.mark.messages
def test_study_refuses_windows_beyond_its_end_time():
    with pytest.raises(ValueError, match=r"Study: the window 2:6 s ends after the simulated end 3 s"):
        Study(ResolveParameters('reel-P1'), [ParseVariation('J1=0.1')], endTime=3., windows=[(0., 2.), (2., 6.)])
    assert np.isclose(Study(ResolveParameters('reel-P1'), [ParseVariation('J1=0.1')], endTime=3.,
                            windows=[(0., 2.), (2., 3.)]).windows[1][1], 3.)


def test_fft_length_is_scipys_fast_length():
    """The padded length of DominantFrequency: SciPy's fast length of a real FFT (prime factors 2, 3, 5)."""
    lengths = [*range(1, 2000), 4 * 1289, 4 * 2 * 1289, 4 * 3 * 1289, 2 ** 20 + 1, 3 ** 9 * 5 - 1]
    assert [_FastFftLength(n) for n in lengths] == [next_fast_len(n, real=True) for n in lengths]


@pytest.mark.physics
@pytest.mark.parametrize('samples', [1289, 2 * 1289, 4001])
def test_dominant_frequency_of_a_sine_within_its_resolution(samples):
    """A window whose padded length 4 N had the prime factor 1289 (a slow FFT) is padded to a fast length: its
    dominant frequency is still the sine's (closed form) and the unpadded FFT's, each within the frequency step
    of the unpadded spectrum, 1 / (4 N dt)."""
    dt, f = 1e-3, 43.7
    t = np.arange(samples) * dt
    x = 3. + np.sin(2 * np.pi * f * t) + 0.2 * np.sin(2 * np.pi * 3.1 * f * t)
    result = SimulationResult(time=t, series={'alpha2': x}, J2=1., r2=1.)
    found = result.DominantFrequency(0., t[-1])
    step = 1. / (4 * samples * dt)
    window = (x - x.mean()) * np.hanning(samples)
    unpadded = np.fft.rfftfreq(4 * samples, dt)[1:][np.argmax(np.abs(np.fft.rfft(window, n=4 * samples))[1:])]
    assert abs(found - f) <= step and abs(found - unpadded) <= step
