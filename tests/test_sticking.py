"""True sticking of the worm at zero sliding speed: ContactOptions(frictionModel='sticking').

The hold test: the reel-P1 gear (gamma 5.32 deg < rho 8 deg, self-locking) with the hanging
175 kg load at 1.2 m and no motor. The drift is measured after 5 s, when the mesh's own oscillation (39 Hz,
1.3 % damping, excited by the load applied at t = 0 or by the stop) has decayed; the creep of the regularized
law (0.0095 rad in 18 s, measured with the regularized law) is a steady sinking, which the same measure shows.
"""
import math

import exudyn as exu
import numpy as np
import pytest

exu = pytest.importorskip('exudyn')

from exudyn_worm import GetPreset
from exudyn_worm.items.connector import CreateWormGear
from exudyn_worm.model.contact import ContactOptions, FrictionState, MeshContact, SlidingCoordinate, StickSlipUpdate
from exudyn_worm.model.friction import MATH_OPS
from exudyn_worm.items.drivetrain import CreateRotor, CreateRotorTorque
from exudyn_worm.model.friction import StribeckFriction
from exudyn_worm.drive.presets import ElasticDriveFromParameters
from exudyn_worm.model.profiles import GravityLeverTorque
from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger, SolverSettings
from exudyn_worm.drive.wholedrive import ResolveDrive

P1 = GetPreset('reel-P1')
SETTLE, HOLD = 5., 18.         # s: settling of the mesh oscillation, then the hold time
STEP = 1e-3


def _Hold(options=ContactOptions(), omega1=0., mu=None, endTime=SETTLE + HOLD, wormTorque=None, useSymbolic=True,
          gear=None):
    drive = ElasticDriveFromParameters(P1)
    if gear is None:
        gear = drive.gear if mu is None else drive.gear.Replace(mu=mu)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    worm = CreateRotor(mbs, drive.J1, initialSpeed=omega1, name='worm')
    wheel = CreateRotor(mbs, drive.J2, initialSpeed=omega1 / gear.ratio, name='wheel')
    mesh = CreateWormGear(mbs, [worm, wheel], gear=gear, contactOptions=options, useSymbolic=useSymbolic)
    CreateRotorTorque(mbs, wheel, GravityLeverTorque(mass=P1['loadMass'], leverArm=P1['leverArm']),
                      useSymbolic=useSymbolic)
    if wormTorque is not None:
        CreateRotorTorque(mbs, worm, wormTorque, useSymbolic=useSymbolic)
    mesh.AddSensors(mbs)
    mbs.Assemble()
    ss, solverType = SolverSettings(endTime, STEP)
    printing, exu.config.printToConsole = exu.config.printToConsole, False
    try:
        mbs.SolveDynamic(ss, solverType=solverType)
    finally:
        exu.config.printToConsole = printing
    return mbs, mesh, mesh.StoredStates(mbs)


def _Drift(states, settle=SETTLE):
    k = int(np.searchsorted(states['time'], settle))
    return float(np.max(np.abs(states['phi2'][k:] - states['phi2'][k])))


def test_self_locking_gear_holds_from_rest():
    mbs, mesh, s = _Hold()
    assert ElasticDriveFromParameters(P1).gear.selfLocking
    assert _Drift(s) < 1e-6                      # required: below 1e-6 rad over 18 s
    m = mesh.StoredMeshState(mbs)
    assert np.all(m.stuck[s['time'] > 0.1] == 1.)
    fn = np.abs(m.normalForce[-1])
    assert abs(m.frictionForce[-1]) <= mesh.gear.muStatic * fn      # held within the static limit


def test_self_locking_gear_stops_after_lowering_and_holds():
    mbs, mesh, s = _Hold(omega1=-49.5)           # the reel changer's lowering speed, motor gone
    assert s['omega1'][0] == pytest.approx(-49.5)
    assert _Drift(s) < 1e-6
    assert abs(s['omega1'][-1]) < 1e-6
    assert mesh.stickSlip.state.stuck == 1.


def test_regularized_law_creeps_and_stays_available():
    _, mesh, s = _Hold(ContactOptions(frictionModel='regularized'))
    assert mesh.stickSlip is None
    assert _Drift(s) > 1e-3                      # the regularized law's 0.0095 rad in 18 s


def test_gear_that_is_not_self_locking_runs_away():
    _, mesh, s = _Hold(mu=0.03, endTime=3.)
    assert not mesh.gear.selfLocking
    assert s['phi2'][-1] < -0.5                  # the load runs down


def _StribeckGear():
    """The required runaway case: mu 0.05 (kinetic, below tan(gamma) cos(alphaN): not self-locking once moving),
    muStatic 0.15 (self-locking at rest), stribeckVelocity 0.1 m/s."""
    return ElasticDriveFromParameters(P1).gear.Replace(mu=0.05).Replace(
        friction=StribeckFriction(mu=0.05, muStatic=0.15, stribeckVelocity=0.1))


def test_stribeck_gear_holds_from_rest():
    gear = _StribeckGear()
    assert gear.muStatic == 0.15 and gear.gamma > math.atan(0.05 / math.cos(gear.alphaN))
    _, mesh, s = _Hold(gear=gear)
    assert _Drift(s) < 1e-6                      # statically self-locking: holds without creep


def test_stribeck_gear_keeps_running_from_lowering_speed():
    _, mesh, s = _Hold(gear=_StribeckGear(), omega1=-49.5, endTime=1.)
    assert s['omega1'][-1] < -49.5               # dynamically not self-locking: the load accelerates the drive
    assert s['phi2'][-1] < -0.5                  # and runs down


def _BreakawayTorque(gear, loadTorque):
    """Worm torque at which the stuck flanks reach muStatic Fn driving the worm positively (lifting), from the
    static balance of the stuck mesh: worm Tw = A1 Fn + B1 Phi, wheel -TL = A2 Fn - B2 Phi, Phi = muStatic Fn."""
    a1 = gear.r1 * math.cos(gear.alphaN) * math.sin(gear.gamma)
    a2 = gear.r2 * math.cos(gear.alphaN) * math.cos(gear.gamma)
    b1, b2 = SlidingCoordinate(gear, 1., 0.), SlidingCoordinate(gear, 0., 1.)
    fn = -loadTorque / (a2 - b2 * gear.muStatic)
    return fn * (a1 + b1 * gear.muStatic)


@pytest.mark.parametrize('factor, breaks', [(0.9, False), (1.1, True)])
def test_breakaway_above_the_static_limit(factor, breaks):
    gear = ElasticDriveFromParameters(P1).gear
    limit = _BreakawayTorque(gear, -GravityLeverTorque(mass=P1['loadMass'], leverArm=P1['leverArm']).maximum)
    assert limit > 0

    def WormTorque(phi, omega, t, ops):            # ramped in over 3..5 s, after the load has settled
        return factor * limit * ops.max(0., ops.min(1., (t - 3.) * 0.5)) + 0. * phi

    mbs, mesh, s = _Hold(wormTorque=WormTorque, endTime=8.)
    moved = s['phi2'][-1] - s['phi2'][int(np.searchsorted(s['time'], 3.))]
    if breaks:
        assert moved > 1e-3 and mesh.stickSlip.switches >= 1
    else:
        assert abs(moved) < 1e-4 and mesh.stickSlip.switches == 0


def test_plain_python_connector_holds_too():
    _, mesh, s = _Hold(omega1=-49.5, endTime=SETTLE + 2., useSymbolic=False)
    assert _Drift(s) < 1e-6


@pytest.mark.parametrize('name', ['reel-P1'])
def test_reel_changer_unchanged_where_the_worm_never_stops(name):
    p = GetPreset(name)
    a = SimulateReelChanger(ResolveDrive(parameters=p), contactOptions=ContactOptions(frictionModel='regularized'))
    b = SimulateReelChanger(ResolveDrive(parameters=p))
    window = (2., 6.)
    ma, mb = a.WindowMetrics([window])[0], b.WindowMetrics([window])[0]
    assert np.min(np.abs(b.series['omega1'])) > 1.           # the worm never stops
    for key in ('maxAbsWheelAcceleration', 'maxNormalForce'):
        assert mb[key] == pytest.approx(ma[key], rel=3e-3)   # required: at most 0.3 %


def test_stick_slip_update_rules():
    gear = ElasticDriveFromParameters(P1).gear
    options = ContactOptions()
    phi1 = 0.01
    sliding = FrictionState(0., 1., 0.)
    assert StickSlipUpdate(gear, options, sliding, phi1, 0., 5., 5. / gear.ratio) == (None, 0.)
    new, jump = StickSlipUpdate(gear, options, sliding, phi1, 0., -0.01, 0.)
    assert new.stuck == 1. and new.direction == 1.
    mesh = MeshContact(gear, phi1, 0., -0.01, 0., options, MATH_OPS, frictionState=new)
    assert mesh.frictionForce == pytest.approx(gear.mu * abs(mesh.normalForce), rel=1e-9)   # no jump
    assert jump == pytest.approx(0., abs=1e-6 * abs(mesh.normalForce))
    over = FrictionState(1., 1., SlidingCoordinate(gear, phi1, 0.) - 2 * gear.muStatic * abs(mesh.normalForce) / gear.kV)
    new, jump = StickSlipUpdate(gear, options, over, phi1, 0., 0., 0.)
    assert new.stuck == 0. and new.direction == 1. and jump > 0


def test_contact_options_friction_model_errors():
    with pytest.raises(ValueError, match="ContactOptions: 'frictionModel' must be one of 'sticking', 'regularized', "
                                         "got 'stiking'.*did you mean 'sticking'"):
        ContactOptions(frictionModel='stiking')
    with pytest.raises(ValueError, match="stickingStiffness"):
        ContactOptions(stickingStiffness=-1.)
    assert ContactOptions().frictionModel == 'sticking' and ContactOptions().hasStickState
    assert not ContactOptions(fixedS=1).hasStickState


def _Lowering():
    """(mbs, worm, mesh): the reel-P1 worm and wheel on the sticking mesh, started at the lowering speed, the
    hanging load on the wheel, no motor."""
    drive = ElasticDriveFromParameters(P1)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    worm = CreateRotor(mbs, drive.J1, initialSpeed=-49.5)
    wheel = CreateRotor(mbs, drive.J2, initialSpeed=-49.5 / drive.gear.ratio)
    mesh = CreateWormGear(mbs, [worm, wheel], gear=drive.gear)
    CreateRotorTorque(mbs, wheel, GravityLeverTorque(mass=P1['loadMass'], leverArm=P1['leverArm']))
    return mbs, worm, mesh


def test_linearization_options_and_back_keep_the_switching():
    """Holding S for a linearization (fixed S, no stick state) and restoring the options: the mesh is checked
    again after the next step, so a worm started at lowering speed still stops and holds."""
    mbs, worm, mesh = _Lowering()
    mesh.AddSensors(mbs)
    mesh.SetContactOptions(mbs, ContactOptions(fixedS=-1))
    mbs.Assemble()
    ss, solverType = SolverSettings(0.01, STEP)
    mbs.SolveDynamic(ss, solverType=solverType)             # sets the clock far ahead: no stick state
    mesh.SetContactOptions(mbs, ContactOptions())
    mbs.Assemble()
    ss, solverType = SolverSettings(2., STEP)
    printing, exu.config.printToConsole = exu.config.printToConsole, False
    try:
        mbs.SolveDynamic(ss, solverType=solverType)
    finally:
        exu.config.printToConsole = printing
    assert mesh.stickSlip.state.stuck == 1.
    assert abs(mesh.StoredStates(mbs)['omega1'][-1]) < 1e-3        # stopped (the mesh still rings a little)


def test_a_system_grown_between_solves_is_read_anew():
    """The stick/slip state reads Exudyn's coordinates in place (views, no copies); a solve that continues in time
    after the system was assembled again with many more coordinates reads the new vectors, not the freed ones."""
    mbs, worm, mesh = _Lowering()
    mbs.Assemble()
    ss, solverType = SolverSettings(0.05, STEP)
    mbs.SolveDynamic(ss, solverType=solverType)
    for k in range(500):                                     # Exudyn reallocates its state vectors
        CreateRotor(mbs, 1., name=f'extra{k}')
    mbs.Assemble()
    ss, solverType = SolverSettings(0.1, STEP)
    ss.timeIntegration.startTime = 0.05                      # continued in time: no earlier step to notice
    mbs.SolveDynamic(ss, solverType=solverType)
    i = mbs.GetNodeODE2Index(worm['nodeNumber'])
    assert mbs.systemData.ODE2Size() == 502
    assert mesh.stickSlip.WormSpeed() == mbs.systemData.GetODE2Coordinates_t()[i]
