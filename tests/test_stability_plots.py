"""The stability results draw their eigenvalues (growth rate against frequency): every point where the analysis put
it, the deciding one circled and named, the growing half-plane shaded."""
import math

import numpy as np
import pytest

from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.drive.wholedrive import ResolveDrive
from exudyn_worm.model.stability import AnalyzeStability

pytest.importorskip('matplotlib')


def _Points(ax, label):
    line = next(l for l in ax.get_lines() if l.get_label() == label)
    return np.column_stack(line.get_data())


def _Expected(eigenvalues):
    lam = np.asarray(eigenvalues, dtype=complex)
    lam = lam[lam.imag >= 0.]
    return np.column_stack([lam.real, lam.imag / (2 * math.pi)])


def test_drive_analysis_draws_each_operating_point_and_circles_the_deciding_eigenvalue():
    analysis = AnalyzeDrive(ResolveDrive('reel-P1'))
    ax = analysis.plot()
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for p in analysis.operatingPoints:
        assert p.point.Label() in labels
        np.testing.assert_allclose(_Points(ax, p.point.Label()), _Expected(p.eigenvalues), rtol=1e-12)
    deciding = next(l for l in labels if l.startswith('deciding: '))
    assert analysis.deciding.point.Label() in deciding
    circle = _Points(ax, deciding)
    np.testing.assert_allclose(circle, [[analysis.maxRealPart, analysis.frequencyHz]], rtol=1e-9)
    assert circle[0, 0] > 0                              # P1 chatters while lowering: the circled mode grows
    assert ax.get_title().replace('\n', ' ') == analysis.decidingText and 'growing (Re > 0)' in labels


def test_the_closed_form_draws_both_contact_states():
    analysis = AnalyzeStability(ResolveDrive('reel-P1').elastic)
    ax = analysis.plot(title='P1')
    for S in (1, -1):
        np.testing.assert_allclose(_Points(ax, f'S = {S:+d}'), _Expected(analysis.State(S).eigenvalues), rtol=1e-12)
    assert ax.get_title() == 'P1'


def test_a_whole_drive_without_a_steady_phase_draws_its_linearization_at_rest():
    drive = ResolveDrive('chart', sets=['J1=0.1', 'kT=7000', 'DTV=1', 'J2=33', 'J4=0.05', 'k4=2e4'])
    analysis = AnalyzeDrive(drive)
    assert not analysis.operatingPoints
    ax = analysis.plot()
    for key, state in analysis.atRest.states.items():
        label = 'S = ' + ', '.join(f'{s:+d}' for s in key)
        np.testing.assert_allclose(_Points(ax, label), _Expected(state.eigenvalues), rtol=1e-12)
