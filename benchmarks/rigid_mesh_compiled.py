"""Investigation: can the mesh between rigid bodies run in C++ within 3x of the one-angle connector?

Exudyn 1.13.6 cannot record a symbolic user function whose vector argument has 8 or more entries
(docs/exudyn-notes.md), and the mesh's ``ObjectGenericODE2`` on the two rigid-body nodes has 12.
``CreateRigidBodyWormGear(..., useSymbolic=True)`` keeps below the limit and keeps the one contact law
(``MeshContact``): for Tait-Bryan nodes whose turn is their *last* angle the four law inputs (worm angle, wheel
angle, axial displacement, radial approach) are linear in the node coordinates to first order in the tilts, so 7
auxiliary coordinates tied to the nodes by linear constraints carry them and the law is one symbolic
``ObjectGenericODE2`` on those (docs/mesh-3d.md, "Speed").

The layout turns the worm onto global y (reference rotation Rx(-pi/2), its turn about its local z = the last angle),
the wheel about z, the centre line along x. Variants (P1, 8 s, recommended step, ``SOLVER_SETTINGS``, one run each)::

    python benchmarks/rigid_mesh_compiled.py [--end-time 8]

1. the one-angle connector (``BuildReelChanger``), the reference;
2. the C++ law, the bodies on ``ObjectJointGeneric`` revolute joints;
3. the same with each ideal joint as one linear coordinate constraint (the node's translations and tilt angles held);
4. variant 3 with the law returning zero forces (what the bodies, joints and auxiliary coordinates cost alone).

It prints the solve's CPU seconds, Newton iterations and Jacobians, and the normal force's largest difference from the
one-angle connector (relative to its peak) before the first loss of contact (2.4 s) and over the run. Nothing is
written. Results in benchmarks/README.md.
"""
from __future__ import annotations

import argparse
import math
import sys
import time

import exudyn as exu
import numpy as np

from exudyn_worm.analysis.simulation.reelchanger import BuildReelChanger, SolverSettings, _SolverCounters
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.items._userfunctions import SetGenericForceLaw
from exudyn_worm.items.drivetrain import CreatePrescribedRotation, CreateRotor
from exudyn_worm.items.equilibrium import SteadyInitialState
from exudyn_worm.items.rigidmesh import CreateRigidBodyWormGear
from exudyn_worm.model.contact import ContactOptions
from exudyn_worm.model.profiles import ConstantSpeed
from exudyn_worm.drive.duty import LoadFromParameters
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['BuildCompiledRigidBodyReelChanger', 'Main']

#: variants of the rigid-body model: (label, joints as coordinate constraints, law returns zero)
VARIANTS = (('C++ law on 7 aux. coordinates, ObjectJointGeneric joints', False, False),
            ('  + joints as linear coordinate constraints', True, False),
            ('  + the law returning zero (bodies and constraints only)', True, True))


def BuildCompiledRigidBodyReelChanger(parameters, coordinateJoints: bool = True, zeroLaw: bool = False,
                                      useSymbolic: bool = True):
    """The reel changer P1 with worm and wheel as Rxyz rigid bodies on ideal joints and the mesh law in C++
    (``useSymbolic=True``, module docstring; False: the same model with the plain-Python law). Returns
    ``(SC, mbs, connector)``, assembled, with the connector's sensors."""
    import exudyn as exu
    from exudyn.itemInterface import (CoordinateSpringDamper, MarkerBodyRigid, MarkerNodeCoordinate,
                                      MarkerNodeCoordinates, NodePointGround,
                                      ObjectConnectorCoordinateVector, ObjectGenericODE2, ObjectGround,
                                      ObjectJointGeneric)
    from exudyn.rigidBodyUtilities import RigidBodyInertia, RotationMatrixX, RotationMatrixZ
    options = ContactOptions()
    drive = ElasticDriveFromParameters(parameters)
    gear, load, speed = drive.gear, LoadFromParameters(parameters), float(parameters['motorSpeed'])
    init = SteadyInitialState(drive, load, speed, options)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    R0 = RotationMatrixX(-math.pi / 2)            # the worm's local z (its spin, the last Rxyz angle) onto global y
    worm = mbs.CreateRigidBody(name='worm', nodeType=exu.NodeType.RotationRxyz, referenceRotationMatrix=R0,
                               inertia=RigidBodyInertia(mass=5., inertiaTensor=np.eye(3) * drive.J1),
                               initialRotationMatrix=RotationMatrixZ(init['phi1']),
                               initialAngularVelocity=list(R0 @ [0., 0., init['omega1']]), returnDict=True)
    wheel = mbs.CreateRigidBody(name='wheel', nodeType=exu.NodeType.RotationRxyz,
                                referencePosition=[gear.r1 + gear.r2, 0., 0.],
                                inertia=RigidBodyInertia(mass=30., inertiaTensor=np.eye(3) * drive.J2),
                                initialRotationMatrix=RotationMatrixZ(init['phi2']),
                                initialAngularVelocity=[0., 0., init['omega2']], returnDict=True)
    if coordinateJoints:        # each node's translations and tilt angles held: one linear constraint per body
        mFix = mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=mbs.AddNode(NodePointGround())))
        for body in (worm, wheel):
            reference = np.asarray(mbs.GetNode(body['nodeNumber'])['referenceCoordinates'])[:5]
            mbs.AddObject(ObjectConnectorCoordinateVector(
                markerNumbers=[mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=body['nodeNumber'])), mFix],
                scalingMarker0=np.eye(6)[:5], scalingMarker1=np.zeros((5, 0)), offset=list(-reference)))
    else:
        for body, R in ((worm, R0), (wheel, np.eye(3))):
            position = mbs.GetNode(body['nodeNumber'])['referenceCoordinates'][:3]
            ground = mbs.AddObject(ObjectGround(referencePosition=list(position)))
            m0 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localHT=exu.HT(rotation=R)))
            m1 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body['bodyNumber']))
            mbs.AddObject(ObjectJointGeneric(markerNumbers=[m0, m1], constrainedAxes=[1, 1, 1, 1, 1, 0]))
    motor = CreateRotor(mbs, 1e-3, initialSpeed=speed, name='motor')
    CreatePrescribedRotation(mbs, motor, ConstantSpeed(speed), name='motorDrive')
    wormAngle = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=worm['nodeNumber'], coordinate=5))
    mbs.AddObject(CoordinateSpringDamper(markerNumbers=[motor['markerNumber'], wormAngle], stiffness=drive.kT,
                                         damping=drive.dT))
    connector = CreateRigidBodyWormGear(mbs, [worm, wheel], gear=gear, wormAxis=[0., 0., 1.], wheelAxis=[0., 0., 1.],
                                        contactOptions=options, useSymbolic=useSymbolic)
    if zeroLaw:
        SetGenericForceLaw(mbs, connector.compiled['objectNumber'], 7, lambda t, q, q_t, ops: [0. * q[0]] * 7, True,
                           check=False)
    # the reel's load on the wheel's turn, its last angle
    zeros = np.zeros((6, 6))
    oLoad = mbs.AddObject(ObjectGenericODE2(nodeNumbers=[wheel['nodeNumber']], massMatrix=zeros, stiffnessMatrix=zeros,
                                            dampingMatrix=zeros))
    mbs.variables['rigidMeshLoad'] = SetGenericForceLaw(
        mbs, oLoad, 6, lambda t, q, q_t, ops: [0.] * 5 + [load.Torque(q[5], q_t[5], t, ops)], True)
    connector.AddSensors(mbs)
    mbs.Assemble()
    return SC, mbs, connector


def _Solve(mbs, parameters, endTime):
    """CPU seconds of the solve and the solver's counters."""
    ss, solverType = SolverSettings(endTime, RecommendedStepSize(ResolveDrive(parameters=parameters)))
    cpu = time.process_time()
    mbs.SolveDynamic(ss, solverType=solverType)
    return time.process_time() - cpu, _SolverCounters(mbs)


def Main(argv=None) -> int:
    """Run the variants and print the table."""
    import exudyn as exu
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--end-time', type=float, default=8.)
    args = parser.parse_args(argv)
    exu.config.printToConsole = False
    p1 = GetPreset('reel-P1')
    reference = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=p1))
    reference.mbs.Assemble()
    wall, counters = _Solve(reference.mbs, p1, args.end_time)
    mesh = reference.connector.StoredMeshState(reference.mbs)
    peak = np.max(np.abs(mesh.normalForce))
    print(f"{'model (P1, ' + format(args.end_time, 'g') + ' s)':58s} {'CPU s':>7s} {'ratio':>6s} {'Newton it.':>10s} "
          f"{'Jac.':>5s} {'dFn <2.4 s':>10s} {'dFn all':>8s}")
    print(f"{'one-angle connector (BuildReelChanger)':58s} {wall:7.3f} {1.:6.2f} {counters['newtonIterations']:10d} "
          f"{counters['jacobians']:5d}")
    for label, coordinateJoints, zeroLaw in VARIANTS:
        SC, mbs, connector = BuildCompiledRigidBodyReelChanger(p1, coordinateJoints, zeroLaw)
        seconds, c = _Solve(mbs, p1, args.end_time)
        state = connector.StoredMeshState(mbs)
        n = min(len(state.normalForce), len(mesh.normalForce))
        d = np.abs(np.asarray(state.normalForce)[:n] - np.asarray(mesh.normalForce)[:n]) / peak
        early = d[np.asarray(mesh.time)[:n] < 2.4]
        print(f"{label:58s} {seconds:7.3f} {seconds / wall:6.2f} {c['newtonIterations']:10d} {c['jacobians']:5d} "
              + (f"{'-':>10s} {'-':>8s}" if zeroLaw else f"{early.max():10.1e} {d.max():8.1e}"))
    return 0


if __name__ == '__main__':
    sys.exit(Main())
