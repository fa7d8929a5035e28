"""SimulationResult: units of every series in the CSV header, windows checked against the simulated time."""
import csv

import numpy as np
import pytest

from exudyn_worm import ApplyOverrides, GetPreset, SimulateReelChanger
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.items.results import SeriesUnit
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
