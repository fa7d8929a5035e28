"""Drivetrain builders and motion/load laws: ordinary Exudyn items around the connector."""
import math

import exudyn as exu
import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.model.friction import MATH_OPS, NUMPY_OPS
from exudyn_worm.items.drivetrain import FLYWHEEL_INERTIA, _ConstantSpeedFromStart
from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.model.profiles import (ConstantSpeed, CoulombViscousFriction, GravityLeverTorque,
                                  LinearMotorCharacteristic, StartStopProfile)


def test_start_stop_profile_is_smooth_and_consistent():
    p = StartStopProfile(speed=10., rampTime=1., brakeTime=5.)
    t = np.linspace(0, 7, 70001)
    angle, speed = p.AngleAndSpeed(t, NUMPY_OPS)
    np.testing.assert_allclose(np.gradient(angle, t), speed, atol=1e-3)     # speed is the angle's rate
    assert speed[0] == 0 and speed[-1] == pytest.approx(0, abs=1e-12)
    assert angle[-1] == pytest.approx(10. * 5.)                            # 0.5 s lost in each ramp
    assert np.all(np.diff(angle) >= -1e-12)
    with pytest.raises(ValueError, match="'brakeTime' must be >= rampTime = 1 s, got 0.5 s"):
        StartStopProfile(speed=1., rampTime=1., brakeTime=0.5)


def test_torque_laws():
    assert GravityLeverTorque(175., 1.2).maximum == pytest.approx(2060., abs=1.)   # paper: M2 = 2060 N*m
    assert GravityLeverTorque(175., 1.2).Torque(0., 0., 0., MATH_OPS) == pytest.approx(-2060., abs=1.)
    motor = LinearMotorCharacteristic(stallTorque=10., noLoadSpeed=100.)
    assert motor.Torque(0., 50., 0., MATH_OPS) == pytest.approx(5.)
    assert motor.Torque(0., 150., 0., MATH_OPS) == 0.
    friction = CoulombViscousFriction(coulombTorque=2., viscous=0.1, regularizationSpeed=0.1)
    assert friction.Torque(0., 10., 0., MATH_OPS) == pytest.approx(-3.)
    assert friction.Torque(0., -0.05, 0., MATH_OPS) == pytest.approx(1. + 0.005)
    with pytest.raises(ValueError, match="'mass' must be >= 0 kg, got -1 kg"):
        GravityLeverTorque(-1., 1.)


def _Solve(mbs, endTime, h=1e-3):
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.timeIntegration.endTime = endTime
    ss.timeIntegration.numberOfSteps = int(endTime / h)
    ss.timeIntegration.verboseMode = 0
    mbs.SolveDynamic(ss)


@pytest.mark.physics
@pytest.mark.parametrize('useSymbolic', [True, False])
def test_prescribed_start_up_drives_the_worm(useSymbolic, tmp_path, monkeypatch):
    """Start from rest with a smooth start-up; the worm follows the motor through the shaft."""
    monkeypatch.chdir(tmp_path)
    drive = ew.ElasticDriveFromParameters(ew.GetPreset('reel-P2'))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    motor = ew.CreateRotor(mbs, 1e-3)
    worm = ew.CreateRotor(mbs, drive.J1)
    wheel = ew.CreateRotor(mbs, drive.J2)
    ew.CreatePrescribedRotation(mbs, motor, StartStopProfile(speed=20., rampTime=0.5), useSymbolic=useSymbolic)
    ew.CreateShaft(mbs, [motor, worm], stiffness=drive.kT, damping=drive.dT)
    ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear, useSymbolic=useSymbolic)
    ew.CreateRotorTorque(mbs, wheel, CoulombViscousFriction(coulombTorque=50., regularizationSpeed=0.01),
                         useSymbolic=useSymbolic)
    _Solve(mbs, 1.)
    omega1 = mbs.GetNodeOutput(worm['nodeNumber'], exu.OutputVariableType.Coordinates_t)
    omega2 = mbs.GetNodeOutput(wheel['nodeNumber'], exu.OutputVariableType.Coordinates_t)
    assert omega1 == pytest.approx(20., rel=1e-2)
    assert omega2 == pytest.approx(20. / drive.gear.ratio, rel=1e-2)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.physics
def test_motor_characteristic_reaches_its_operating_point():
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    rotor = ew.CreateRotor(mbs, 0.01)
    ew.CreateRotorTorque(mbs, rotor, LinearMotorCharacteristic(stallTorque=2., noLoadSpeed=100.))
    ew.CreateRotorTorque(mbs, rotor, CoulombViscousFriction(coulombTorque=1.))
    _Solve(mbs, 6.)                                        # time constant 0.01/0.02 = 0.5 s
    omega = mbs.GetNodeOutput(rotor['nodeNumber'], exu.OutputVariableType.Coordinates_t)
    assert omega == pytest.approx(50., rel=1e-3)          # 2 (1 - w/100) = 1


@pytest.mark.physics
def test_neighbouring_inertia_adds_a_mode():
    """Figure 19: an extra inertia on the drive side is just another rotor and shaft; the linearized
    system then has three modes."""
    drive = ew.ElasticDriveFromParameters(ew.GetPreset('reel-P1'))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    motor, inertia4 = ew.CreateRotor(mbs, 1e-3), ew.CreateRotor(mbs, 0.05)
    worm, wheel = ew.CreateRotor(mbs, drive.J1, initialAngle=1e-3), ew.CreateRotor(mbs, drive.J2)
    ew.CreatePrescribedRotation(mbs, motor, ConstantSpeed(0.))
    ew.CreateShaft(mbs, [motor, inertia4], stiffness=2e4, damping=1.)
    ew.CreateShaft(mbs, [inertia4, worm], stiffness=drive.kT, damping=drive.dT)
    ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear,
                      contactOptions=ew.ContactOptions(fixedS=1, dampingCanPull=True))
    mbs.Assemble()
    values, _ = mbs.ComputeODE2Eigenvalues(computeComplexEigenvalues=True, useAbsoluteValues=False)
    assert np.count_nonzero(np.asarray(values).imag > 1.) == 3


@pytest.mark.messages
def test_builders_validate_arguments():
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    rotor = ew.CreateRotor(mbs, 1.)
    with pytest.raises(ValueError, match="CreateShaft: 'stiffness' must be > 0 N\\*m/rad, got 0 N\\*m/rad"):
        ew.CreateShaft(mbs, [rotor, ew.CreateRotor(mbs, 1.)], stiffness=0.)
    with pytest.raises(TypeError, match="CreatePrescribedRotation: 'profile' must have AngleAndSpeed"):
        ew.CreatePrescribedRotation(mbs, rotor, 3.)
    with pytest.raises(TypeError, match="CreateRotorTorque: 'law' must have Torque"):
        ew.CreateRotorTorque(mbs, rotor, 3.)
    with pytest.raises(TypeError, match="CreateRotor: 'initialSpeed' must be a real number"):
        ew.CreateRotor(mbs, 1., initialSpeed='fast')


def test_main_system_methods_are_explicit():
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ew.AddMainSystemMethods()
    assert mbs.CreateRotor(inertia=0.1)['nodeNumber'] is not None
    assert exu.MainSystem.CreateTorque is not ew.CreateRotorTorque        # Exudyn's own builder untouched


def test_connector_with_explicit_solver_and_sensors(tmp_path, monkeypatch):
    """Explicit solvers work when the drive has no constraint (here a motor characteristic), and the
    connector's sensors give the mesh quantities over time."""
    monkeypatch.chdir(tmp_path)
    drive = ew.ElasticDriveFromParameters(ew.GetPreset('reel-P2'))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    motor = ew.CreateRotor(mbs, 0.05, initialSpeed=40.)
    worm = ew.CreateRotor(mbs, drive.J1, initialSpeed=40.)
    wheel = ew.CreateRotor(mbs, drive.J2, initialSpeed=40. / drive.gear.ratio)
    ew.CreateRotorTorque(mbs, motor, LinearMotorCharacteristic(stallTorque=400., noLoadSpeed=50.))
    ew.CreateShaft(mbs, [motor, worm], stiffness=drive.kT, damping=drive.dT)
    mesh = ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear)
    ew.CreateRotorTorque(mbs, wheel, GravityLeverTorque(100., 1.))
    mesh.AddSensors(mbs)
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.timeIntegration.endTime = 0.5
    ss.timeIntegration.numberOfSteps = 5000
    ss.timeIntegration.verboseMode = 0
    mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.RK44)
    state = mesh.StoredMeshState(mbs)
    assert np.all(state.S[10:] == 1.)                  # worm drives, lifting: S = +1 throughout
    # quasi-static end state: the wheel torque balances the load 100*9.81*cos(phi2)
    phi2 = mesh.StoredStates(mbs)['phi2'][-1]
    assert state.wheelTorque[-1] == pytest.approx(981. * math.cos(phi2), rel=0.05)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize('useSymbolic', [True, False])
def test_custom_torque_law_as_callable(useSymbolic):
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    rotor = ew.CreateRotor(mbs, 2.)
    ew.CreateRotorTorque(mbs, rotor, lambda phi, omega, t, ops: ops.min(10. * t, 5.), useSymbolic=useSymbolic)
    _Solve(mbs, 1.)
    omega = mbs.GetNodeOutput(rotor['nodeNumber'], exu.OutputVariableType.Coordinates_t)
    assert omega == pytest.approx((0.5 * 10. * 0.5**2 + 5. * 0.5) / 2., rel=1e-3)   # ramp to 5 N*m at 0.5 s


class _SameLaw:
    """A profile object with the law of ``profile`` that is not a ConstantSpeed."""

    def __init__(self, profile):
        self.AngleAndSpeed = profile.AngleAndSpeed


@pytest.mark.physics
@pytest.mark.parametrize('initialAngle, velocityLevel', [(0.3, True), (0., False)])
def test_constant_speed_on_velocity_level_is_the_same_motion(initialAngle, velocityLevel):
    """A ConstantSpeed whose initial state the rotor has is prescribed on velocity level, without a user
    function; the worm then moves as with the angle prescribed by a user function. A rotor that does not
    start on the profile keeps the angle constraint (which moves it onto the profile)."""
    drive = ew.ElasticDriveFromParameters(ew.GetPreset('reel-P1'))
    speeds = []
    for forceUserFunction in (False, True):
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        motor = ew.CreateRotor(mbs, 1e-3, initialAngle=initialAngle, initialSpeed=20.)
        worm = ew.CreateRotor(mbs, drive.J1, initialAngle=initialAngle, initialSpeed=20.)
        profile = ConstantSpeed(20., initialAngle=0.3)
        if forceUserFunction:              # the same law, not a ConstantSpeed: prescribed by a user function
            profile = _SameLaw(profile)
        c = ew.CreatePrescribedRotation(mbs, motor, profile)
        assert mbs.GetObject(c['objectNumber'])['velocityLevel'] is (velocityLevel and not forceUserFunction)
        ew.CreateShaft(mbs, [motor, worm], stiffness=drive.kT, damping=drive.dT)
        sensor = mbs.AddSensor(exu.itemInterface.SensorNode(nodeNumber=worm['nodeNumber'], storeInternal=True,
                                                            outputVariableType=exu.OutputVariableType.Coordinates))
        _Solve(mbs, 0.2)
        speeds.append(mbs.GetSensorStoredData(sensor)[:, 1])
    assert (_ConstantSpeedFromStart(mbs, motor, ConstantSpeed(20., initialAngle=0.3)) is not None) is velocityLevel
    np.testing.assert_allclose(speeds[0], speeds[1], rtol=0, atol=1e-9 * np.max(np.abs(speeds[1])))


@pytest.mark.parametrize('preset', ['reel-P1', 'reel-P7'])
def test_constant_speed_flywheel_is_the_constraint_bit_for_bit(preset):
    """A motor at constant speed kept by its inertia (FLYWHEEL_INERTIA, constraint=False, what SimulateReelChanger
    builds) turns exactly as the velocity-level constraint prescribes it: every stored state is the same to the
    last bit over the first second (P7: through its first chatter), with the same solver work; the constraint holds
    the motor's speed at the prescribed one exactly, which is why the flywheel needs no speed sensor."""
    drive = ew.ResolveDrive(preset)
    runs = []
    for motorConstraint in (True, False):
        model = BuildReelChanger(exu.SystemContainer().AddSystem(), drive, motorConstraint=motorConstraint)
        mbs = model.mbs
        mbs.Assemble()
        assert (mbs.systemData.NumberOfObjects() > 0 and
                any(len(mbs.systemData.GetObjectLTGAE(i)) for i in range(mbs.systemData.NumberOfObjects()))) \
            is motorConstraint
        ss, solverType = SolverSettings(1., RecommendedStepSize(drive))
        printing, exu.config.printToConsole = exu.config.printToConsole, False
        try:
            mbs.SolveDynamic(ss, solverType=solverType)
        finally:
            exu.config.printToConsole = printing
        assert model.motorFlywheel is not motorConstraint and ('omega0' in model.sensors) is motorConstraint
        states = model.connector.StoredStates(mbs)
        states.update({k: mbs.GetSensorStoredData(model.sensors[k])[:, 1] for k in ('phi0', 'omega0')
                       if k in model.sensors})
        it = mbs.sys['dynamicSolver'].it
        runs.append((states, (int(it.newtonStepsCount), int(it.newtonJacobiCount))))
    (withConstraint, work), (flywheel, flywheelWork) = runs
    assert flywheelWork == work
    # the flywheel has no speed sensor: its speed is the prescribed one, which the constraint holds exactly
    assert np.all(withConstraint.pop('omega0') == drive.parameters['motorSpeed'])
    assert sorted(flywheel) == sorted(withConstraint)
    for key in withConstraint:
        np.testing.assert_array_equal(flywheel[key], withConstraint[key], err_msg=key)


@pytest.mark.messages
def test_flywheel_refuses_a_rotor_without_its_mass_object():
    """constraint=False sets the rotor's inertia: a rotor dict without 'objectNumber' is refused by name, and a
    'constraint' that is not a bool as well."""
    mbs = exu.SystemContainer().AddSystem()
    rotor = ew.CreateRotor(mbs, 1e-3, initialSpeed=20.)
    bare = {'markerNumber': rotor['markerNumber'], 'nodeNumber': rotor['nodeNumber']}
    with pytest.raises(TypeError, match=r"CreatePrescribedRotation: with constraint=False 'rotor' must be a rotor "
                                        r"returned by CreateRotor"):
        ew.CreatePrescribedRotation(mbs, bare, ConstantSpeed(20.), constraint=False)
    with pytest.raises(TypeError, match=r"CreatePrescribedRotation: 'constraint'"):
        ew.CreatePrescribedRotation(mbs, rotor, ConstantSpeed(20.), constraint='no')
    assert ew.CreatePrescribedRotation(mbs, rotor, ConstantSpeed(20.), constraint=False) == \
        {'objectNumber': None, 'groundNodeNumber': None}
    assert mbs.GetObject(rotor['objectNumber'])['inertia'] == FLYWHEEL_INERTIA
