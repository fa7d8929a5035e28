"""The rigid-body mesh with its law in C++ (CreateRigidBodyWormGear(useSymbolic=True)): the same runs as the
plain-Python law and the one-angle connector; node layouts it cannot take are refused in one line."""
import exudyn as exu
import numpy as np
import pytest
from exudyn.rigidBodyUtilities import RigidBodyInertia

from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability
from exudyn_worm.analysis.simulation.reelchanger import BuildReelChanger, SolverSettings
from exudyn_worm.items.rigidmesh import CreateRigidBodyWormGear
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

from conftest import LoadScript

pytest.importorskip('exudyn')
P1 = GetPreset('reel-P1')
#: full Newton to a tight tolerance: the models agree to round-off, not to the default tolerance (1e-6)
TIGHT = {'timeIntegration.newton.relativeTolerance': 1e-10, 'timeIntegration.newton.useModifiedNewton': False}


@pytest.fixture(scope='module')
def bench():
    return LoadScript('benchmarks/rigid_mesh_compiled.py', 'rigid_mesh_compiled')


def _NormalForce(mbs, connector, endTime=0.3):
    ss, solverType = SolverSettings(endTime, 7.76e-4, TIGHT)
    mbs.SolveDynamic(ss, solverType=solverType)
    return np.asarray(connector.StoredMeshState(mbs).normalForce, dtype=float)


@pytest.mark.physics
@pytest.mark.parametrize('coordinateJoints', [True, False])
def test_compiled_law_gives_the_python_law_and_the_one_angle_connector(bench, coordinateJoints):
    """P1, 0.3 s, worm and wheel on ideal joints (coordinate constraints or ObjectJointGeneric): the normal force of
    the C++ law equals the plain-Python law's and the one-angle connector's within 1e-8 of its peak."""
    compiled = _NormalForce(*bench.BuildCompiledRigidBodyReelChanger(P1, coordinateJoints)[1:])
    python = _NormalForce(*bench.BuildCompiledRigidBodyReelChanger(P1, coordinateJoints, useSymbolic=False)[1:])
    reference = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=P1))
    reference.mbs.Assemble()
    oneAngle = _NormalForce(reference.mbs, reference.connector)
    peak = np.max(np.abs(oneAngle))
    assert peak > 1e4
    assert np.max(np.abs(compiled - python)) < 1e-8 * peak
    assert np.max(np.abs(compiled - oneAngle)) < 1e-8 * peak


def test_compiled_law_refuses_nodes_it_cannot_take():
    """Euler-parameter nodes, and Rxyz nodes turning about their first angle: one line naming the way out."""
    gear = ElasticDriveFromParameters(P1).gear
    for nodeType, message in ((exu.NodeType.RotationEulerParameters, 'needs Tait-Bryan \\(RotationRxyz\\) nodes'),
                              (exu.NodeType.RotationRxyz, 'the law\'s inputs change with the turns')):
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        inertia = RigidBodyInertia(mass=5., inertiaTensor=np.eye(3) * 0.1)
        worm = mbs.CreateRigidBody(nodeType=nodeType, inertia=inertia, returnDict=True)
        wheel = mbs.CreateRigidBody(nodeType=nodeType, inertia=inertia, referencePosition=[0., gear.r1 + gear.r2, 0.],
                                    returnDict=True)
        with pytest.raises(ValueError, match=f"CreateRigidBodyWormGear: 'useSymbolic' .*{message}.*useSymbolic=False"):
            CreateRigidBodyWormGear(mbs, [worm, wheel], gear=gear, useSymbolic=True)


@pytest.mark.physics
def test_compiled_law_gives_the_two_mass_eigenvalues(bench):
    """AnalyzeLinearStability holds S in the C++ law too: on ideal joints the eigenvalues of P1 are the two-mass
    drive's (1e-6; Exudyn differentiates the law numerically)."""
    reference = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=P1))
    reference.mbs.Assemble()
    expected = AnalyzeLinearStability(reference.mbs)
    got = AnalyzeLinearStability(bench.BuildCompiledRigidBodyReelChanger(P1)[1])
    for S in (1, -1):
        a = np.array(sorted((m.eigenvalue for m in got.State(S).modes), key=lambda z: z.imag))
        b = np.array(sorted((m.eigenvalue for m in expected.State(S).modes), key=lambda z: z.imag))
        np.testing.assert_allclose(a, b, rtol=1e-6)
