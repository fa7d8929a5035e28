"""Load-side chains (issue 16, item 1): the driven machine behind load shafts, wheel J2 --(kL1, dL1)-- JL1 -- ...

The drive of the issue: centre distance 40 mm, ratio 40, lead angle 3.5 deg, mu = 0.08, worm-side inertia 2e-4 kg*m^2,
the driven machine (0.5 kg*m^2) behind a 2e4 N*m/rad load shaft, written as examples/drives/load-shaft.toml."""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from exudyn_worm.config import ResolveParameters
from exudyn_worm.linearization import AnalyzeLinearStability, DriveStability

ROOT = Path(__file__).resolve().parents[1]
LOAD_SHAFT = ROOT / 'examples' / 'drives' / 'load-shaft.toml'

# the drive, derived by hand: a = r1 + r2 and u = r2 / (r1 tan(gamma)) give r1 = a / (1 + u tan(gamma))
A, U, GAMMA, MU = 0.040, 40., math.radians(3.5), 0.08
R1 = A / (1 + U * math.tan(GAMMA))
R2 = A - R1
J1, JL1, KL1 = 2e-4, 0.5, 2e4
# chosen values (no source; stated in the drive file): wheel-side inertia, mesh and drive-shaft stiffness and damping
J2, KV, DV, KT, DT = 0.02, 3e7, 300., 300., 0.05


@pytest.fixture(scope='module')
def fileParameters():
    return ResolveParameters(config=LOAD_SHAFT)


def _HandBuiltEigenvalues(J2Wheel, load):
    """The drive built by hand in Exudyn: ground --kT-- worm, mesh, wheel --kL1-- load (``load`` None: no load
    shaft, the load lumped into ``J2Wheel``); linearized with the contact state held."""
    import exudyn as exu
    from exudyn.itemInterface import (CoordinateSpringDamper, MarkerNodeCoordinate, Node1D, NodePointGround,
                                      ObjectRotationalMass1D)
    from exudyn_worm import ContactOptions, CreateWormGear, WormGear
    gear = WormGear(alphaN=math.radians(20), gamma=GAMMA, r1=R1, r2=R2, kV=KV, dV=DV, backlash=0., mu=MU)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()

    def Rotor(J, name, angle=0.):
        n = mbs.AddNode(Node1D(referenceCoordinates=[0.], initialCoordinates=[angle], initialVelocities=[0.],
                               name=name))
        mbs.AddObject(ObjectRotationalMass1D(nodeNumber=n, inertia=J))
        return n, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n, coordinate=0))

    ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    worm, mWorm = Rotor(J1, 'worm', 1e-6 / gear.normalLever)            # pre-deflected into contact
    wheel, mWheel = Rotor(J2Wheel, 'wheel')
    mbs.AddObject(CoordinateSpringDamper(markerNumbers=[ground, mWorm], stiffness=KT, damping=DT))
    if load is not None:
        _, mLoad = Rotor(load[0], 'load')
        mbs.AddObject(CoordinateSpringDamper(markerNumbers=[mWheel, mLoad], stiffness=load[1], damping=0.))
    CreateWormGear(mbs, [worm, wheel], gear=gear, contactOptions=ContactOptions(), name='mesh')
    mbs.Assemble()
    return AnalyzeLinearStability(mbs)


def test_radii_derived_by_hand():
    assert R1 + R2 == pytest.approx(A, rel=1e-15)
    assert R2 / (R1 * math.tan(GAMMA)) == pytest.approx(U, rel=1e-12)


def test_drive_file_gives_the_three_mass_drive(fileParameters):
    p = fileParameters
    assert (p['JL1'], p['kL1'], p['dL1']) == (JL1, KL1, 0.)
    assert p['r1'] == pytest.approx(R1, rel=1e-9) and p['r2'] == pytest.approx(R2, rel=1e-9)
    for key, value in (('J1', J1), ('J2', J2), ('kV', KV), ('dV', DV), ('kT', KT), ('dT', DT), ('mu', MU)):
        assert p[key] == pytest.approx(value, rel=1e-12), key


def test_drive_file_equals_the_drive_built_by_hand_in_exudyn(fileParameters):
    """The done-when of issue 16: same verdict and same eigenvalues (to 1e-6) as the hand-built Exudyn model."""
    fromFile = DriveStability(fileParameters)
    byHand = _HandBuiltEigenvalues(J2, (JL1, KL1))
    assert fromFile.stable == byHand.stable
    for S in (1, -1):
        a, b = fromFile.State(S), byHand.State(S)
        assert a.stable == b.stable
        np.testing.assert_allclose(a.eigenvalues, b.eigenvalues, rtol=1e-6)


def test_lumping_the_load_into_j2_turns_the_verdict(fileParameters):
    """The issue's report: lumped into J2 the drive looks stable (with margin), with the load shaft it chatters at
    about 200 Hz in the wheel's mode. Both verdicts from hand-built Exudyn models and from the package."""
    from exudyn_worm.design import DesignCheck
    from exudyn_worm.presets import LumpedLoadSide
    lumped = LumpedLoadSide(fileParameters)
    assert lumped['J2'] == pytest.approx(J2 + JL1) and 'JL1' not in lumped and 'kL1' not in lumped
    assert _HandBuiltEigenvalues(J2 + JL1, None).stable and DriveStability(lumped).stable
    assert DesignCheck(lumped).stableWithMargin
    chained = _HandBuiltEigenvalues(J2, (JL1, KL1))
    assert not chained.stable and chained.State(1).stable
    growing = max(chained.State(-1).modes, key=lambda m: m.eigenvalue.real)
    assert growing.eigenvalue.real > 0 and 150. < growing.frequencyHz < 300.
    assert growing.Participants(0.5) == ['wheel']
