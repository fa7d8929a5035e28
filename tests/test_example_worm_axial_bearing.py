"""The worm's axial bearing, linear part: the 3-DOF characteristic problem from the Exudyn model,
checked against an independent matrix model, and examples/worm_axial_bearing.py's statements with numbers."""
import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.model.stability import SortEigenvalues

from conftest import LoadScript


@pytest.fixture(scope='module')
def example():
    return LoadScript('examples/worm_axial_bearing.py', 'worm_axial_bearing')


def _ThreeDofEigenvalues(parameters, S):
    """Independent of the contact law's code: M q'' + D q' + K q = 0 in q = [phi1, phi2, xA] written out
    from Delta s = L (phi1 - u phi2) + a xA, F = kV Delta s + dV Delta s', torques -c2 F, +c4 F, axial -c4 F / r2."""
    drive = ew.ElasticDriveFromParameters(parameters)
    g = drive.gear
    _, c2, _, c4 = g.Coefficients(S)
    L, a, u = g.normalLever, g.axialLever, g.ratio
    kA, dA, mA = parameters['kA'], parameters['dA'], parameters['mA']
    lever = np.array([c2, -c4, c4 / g.r2])              # generalized force per unit F is -lever
    gradient = np.array([L, -L * u, a])                  # d(Delta s)/dq
    K = np.diag([drive.kT, 0., kA]) + g.kV * np.outer(lever, gradient)
    D = np.diag([drive.dT, 0., dA]) + g.dV * np.outer(lever, gradient)
    Minv = np.diag(1. / np.array([drive.J1, drive.J2, mA]))
    A = np.block([[np.zeros((3, 3)), np.eye(3)], [-Minv @ K, -Minv @ D]])
    return SortEigenvalues(np.linalg.eigvals(A))


@pytest.mark.physics
@pytest.mark.parametrize('kA, dA', [(5e8, 0.), (2e8, 1e4), (3e9, 5e3)])
def test_three_dof_problem_from_exudyn_equals_the_matrix_model(example, kA, dA):
    p = example.AxialParameters('reel-P1', kA, dA=dA)
    linear = example.AxialLinearStability(p)
    assert linear.coordinates == ['motor', 'worm', 'wheel', 'wormAxial']
    for S in (1, -1):
        state = linear.State(S)
        assert state.eigenvalues.size == 6 and state.characteristicCoefficients.size == 6
        np.testing.assert_allclose(state.eigenvalues, _ThreeDofEigenvalues(p, S), rtol=1e-6)
        axial = state.modes[-1]                          # the fast axial mode lives in xA
        assert axial.Participants(0.5) == ['wormAxial'] and axial.frequencyHz > 1000


@pytest.mark.physics
def test_stiff_bearing_gives_back_the_two_mass_drive(example):
    """kA = 1e13 N/m: the rotational eigenvalues differ from eqs. (15)-(16) by about kV a^2/kA = 2e-5."""
    linear = example.AxialLinearStability(example.AxialParameters('reel-P1', 1e13))
    analytical = ew.AnalyzeStability(ew.ElasticDriveFromParameters(ew.GetPreset('reel-P1')))
    for S in (1, -1):
        slow = linear.State(S).eigenvalues[:4]
        np.testing.assert_allclose(slow, analytical.contact[S].eigenvalues, rtol=1e-4)


@pytest.fixture(scope='module')
def run(example):
    return example.RunExample()


@pytest.mark.physics
def test_soft_bearing_moves_p1_off_the_unstable_region(example, run):
    boundary = run['boundaryP1']
    assert 5e8 < boundary < 1e9                        # rolling bearings: about 1e8..1e9 N/m
    assert example.MaxRealPart('reel-P1', 0.97 * boundary) < 0 < example.MaxRealPart('reel-P1', 1.03 * boundary)
    rigid, *soft = run['table']['reel-P1']
    assert rigid == pytest.approx(ew.AnalyzeStability(ew.ElasticDriveFromParameters(ew.GetPreset('reel-P1')))
                                  .contact[-1].eigenvalues.real.max(), rel=1e-6)
    assert all(a > b for a, b in zip([rigid] + soft[:2], soft[:3]))   # less unstable as kA falls to 5e8
    # the bearing acts as a spring in series with the mesh: the two-mass reading gives the same boundary
    assert run['twoMassBoundaryP1'] == pytest.approx(boundary, rel=0.03)
    assert run['chartXRigid'] < run['chartXAtBoundary']
    # neither the mass nor a bearing damping of 1e4 N*s/m moves the boundary by more than 1 %
    for key in ('boundaryP1Mass1kg', 'boundaryP1Mass20kg', 'boundaryP1Damped'):
        assert run[key] == pytest.approx(boundary, rel=0.01)


@pytest.mark.physics
def test_soft_bearing_moves_p2_and_p5_onto_it(example, run):
    for name in ('reel-P2', 'reel-P5'):
        row = run['table'][name]
        assert row[0] < 0 and row[-1] > 0              # stable with a rigid bearing, unstable at 1e8 N/m
    assert 1e8 < run['boundaryP5'] < run['boundaryP2'] < 3e8
    assert 5e7 < run['boundaryP2Low'] < 1e8                # P2: a window of soft bearings
    assert example.MaxRealPart('reel-P2', 0.9 * run['boundaryP2Low']) < 0
    assert 5e7 < run['boundaryP7'] < 1.5e8                 # P7 needs a very soft bearing


@pytest.mark.physics
def test_simulation_agrees_with_the_linear_verdict(run):
    cases = {(s['preset'], s['kA']): s for s in run['simulations']}
    assert not cases[('reel-P1', 5e8)]['chatter'] and cases[('reel-P1', 5e8)]['linearStable']
    assert cases[('reel-P1', 1e9)]['chatter'] and not cases[('reel-P1', 1e9)]['linearStable']
    # P2 on a soft bearing vibrates while lowering: the mesh swings across both flanks (amplitude >= 1); the
    # time-domain verdict can read that window as decaying, its swing measured uncorrected for the lever's load that
    # falls within it (validation/CHATTER_RULE.md, "What it cannot do")
    soft = cases[('reel-P2', 1e8)]
    assert not soft['linearStable'] and soft['chatterAmplitude'] >= 1.
    assert soft['maxAbsWheelAcceleration'] > 100. * cases[('reel-P1', 5e8)]['maxAbsWheelAcceleration']


@pytest.mark.messages
def test_bad_output_folder(example, tmp_path, capsys):
    blocker = tmp_path / 'file'
    blocker.write_text('x')
    assert example.main(['--out', str(blocker / 'sub')]) == 2
    assert capsys.readouterr().err.startswith('worm_axial_bearing.py: error: cannot write to --out')
