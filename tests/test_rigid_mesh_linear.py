"""Linear stability of the reel changer with worm and wheel as rigid bodies: AnalyzeLinearStability finds the
meshes between rigid bodies; ideal joints give the two-mass eigenvalues, elastic bearings add modes."""
import exudyn as exu
import numpy as np
import pytest

from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

pytest.importorskip('exudyn')
P1 = GetPreset('reel-P1')


def _Eigenvalues(analysis, S):
    return np.array(sorted((m.eigenvalue for m in analysis.State(S).modes), key=lambda z: z.imag))


@pytest.mark.physics
@pytest.mark.parametrize('extra', [{}, {'kA': 5e8, 'dA': 0., 'mA': 5.}])
def test_ideal_joints_give_the_eigenvalues_of_the_one_angle_model(extra):
    """P1 (and P1 with the worm's axial bearing) on ideal revolute joints: the eigenvalues of the 2-DOF (3-DOF)
    model for S = +1 and -1 within 1e-6 relative (Exudyn differentiates the user functions numerically)."""
    parameters = {**P1, **extra}
    reference = AnalyzeLinearStability(BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=parameters)).mbs)
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=parameters))
    model.mbs.Assemble()
    analysis = AnalyzeLinearStability(model.mbs)
    for S in (1, -1):
        expected, got = _Eigenvalues(reference, S), _Eigenvalues(analysis, S)
        assert len(got) == len(expected)
        np.testing.assert_allclose(got, expected, rtol=1e-6)
        assert analysis.State(S).stable == reference.State(S).stable


@pytest.mark.physics
def test_elastic_bearings_add_modes_with_their_bearing_named():
    """Elastic bearings (worm 5e8 N/m radial, 3e8 N/m axial): more modes; the worm's axial motion (its node's y)
    takes the largest energy share of one of them, and the torsional chatter pair stays near 40 Hz."""
    bearings = dict(wormMass=5., wormRadialStiffness=5e8, wormAxialStiffness=3e8, wormBearingSpan=0.12,
                    wormTiltInertia=0.1, wheelMass=30., wheelRadialStiffness=1e9, wheelAxialStiffness=1e9,
                    wheelBearingSpan=0.05, wheelTiltInertia=33.)
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters={**P1, **bearings}),
                                      model='exact')
    model.mbs.Assemble()
    state = AnalyzeLinearStability(model.mbs).State(-1)
    assert len(state.modes) > 2
    axial = [m for m in state.modes if max(m.energyShare, key=m.energyShare.get) == 'Node:worm[1]']
    assert axial, [dict(m.energyShare) for m in state.modes]
    torsional = [m for m in state.modes if m.energyShare.get('Node:worm[5]', 0.) > 0.5]
    assert torsional and all(30. < m.frequencyHz < 50. for m in torsional)
