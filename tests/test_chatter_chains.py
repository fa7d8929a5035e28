"""Steady chatter of drives beyond the two-mass drive of Figure 2 (exudyn_worm.analysis.orbits.chatter): the lowering model with
drive-side and load-side chains and the worm's axial bearing, and the orbit of a user's own Exudyn system.

Independent checks: a load shaft so stiff that the load follows the wheel gives the two-mass drive's orbit (load
lumped into J2); the Hopf point of a chain's branch against the roots of the largest real part of the whole drive's
linearization (DriveStability, the Exudyn linearization for a chain); the orbit against a long time simulation
with the time simulations' own solver settings; a hand-built three-mass Exudyn system against the same drive
given as a parameter set.
"""
import json

import exudyn as exu
import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.analysis.orbits.chatter import (BuildLoweringModel, FindSteadyChatter, LoweringModelOfSystem, SettleLowering, SteadyChatterOfSystem, _LinearlyStable)
from exudyn_worm.analysis.orbits.lowering import EquilibriumState
from exudyn_worm.analysis.orbits.longsimulation import LongSimulationAmplitude
from exudyn_worm.cli.main import Main
from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm.analysis.orbits.chatterbranch import AnalyzeChatterBranch, LinearBoundaries, SmallestDisturbance
from exudyn_worm.items.drivetrain import CreatePrescribedRotation, CreateRotor, CreateRotorTorque, CreateShaft
from exudyn_worm.model.profiles import ConstantSpeed, ConstantTorque
from exudyn_worm.drive.wholedrive import ResolveDrive

pytestmark = pytest.mark.usefixtures('emptyWorkingDirectory')

P1 = ew.GetPreset('reel-P1')
#: P1 with 10 of its 33 kg m^2 wheel-side inertia behind a load shaft; lumped, it is P1 again
SPLIT = {**P1, 'J2': 23., 'JL1': 10.}
#: a load shaft that matters: it moves the lower J1 boundary of P1 (0.07638) by 2.4 % (0.07825)
CHAIN = {**SPLIT, 'kL1': 1e7}


@pytest.fixture(scope='module')
def orbitP1():
    return FindSteadyChatter(ResolveDrive(parameters=P1))


@pytest.fixture(scope='module')
def orbitChain():
    return FindSteadyChatter(ResolveDrive(parameters=CHAIN))


def test_chain_model_holds_every_free_coordinate_and_starts_at_rest():
    p = {**CHAIN, 'J4': 0.05, 'k4': 2e5, 'd4': 1., 'kA': 5e8, 'mA': 2., 'dA': 1e3}
    model = BuildLoweringModel(ResolveDrive(parameters=p))
    mbs = model.mbs
    # every ODE2 coordinate but the prescribed motor: worm, wheel, inertia4, loadInertia1, the worm's axial one
    assert len(model.coordinates) == mbs.systemData.ODE2Size() - 1
    assert model.stateKeys == ('phi1', 'phi2', 'phi4', 'phiL1', 'xA')
    u = model.drive.gear.ratio
    speeds = model.steadySpeeds[list(model.coordinates)]
    np.testing.assert_allclose(speeds, [p['motorSpeed'], p['motorSpeed'] / u, p['motorSpeed'], p['motorSpeed'] / u,
                                        0.], rtol=1e-12)
    x0 = EquilibriumState(model)
    # the load shaft carries the load torque m g l: its twist is m g l / kL1
    assert (model.steady['phiL1'] - model.steady['phi2']) * p['kL1'] == pytest.approx(model.loadTorque, rel=1e-9)
    # the static deflection is an equilibrium of the built system: without a kick nothing moves
    x, _ = SettleLowering(model, 0.05, kick=0.)
    scale = np.concatenate([np.full(4, 1e-9), [1e-12], np.full(5, 1e-7)])
    assert np.all(np.abs(x - x0) < scale)


def test_stiff_load_shaft_gives_the_two_mass_orbit(orbitP1):
    # a 1e9 N m/rad load shaft (its stage at 1.6 kHz): the load follows the wheel, as lumped into J2 = 33
    stiff = FindSteadyChatter(ResolveDrive(parameters={**SPLIT, 'kL1': 1e9}))
    assert stiff.converged and len(stiff.state) == 6
    # required: amplitudes within 2 % of the long simulation's
    assert stiff.info['forceFactor'] == pytest.approx(orbitP1.info['forceFactor'], rel=0.02)
    assert stiff.info['maxWheelAcceleration'] == pytest.approx(orbitP1.info['maxWheelAcceleration'], rel=0.02)
    assert stiff.frequencyHz == pytest.approx(orbitP1.frequencyHz, rel=0.02)


def test_stiff_axial_bearing_gives_the_two_mass_orbit(orbitP1):
    # the worm's axial bearing at 5e10 N/m (the mesh's kV is 2e8 N/m): nearly the axially rigid worm of Figure 2;
    # the flow state holds the axial coordinate, the mesh is evaluated with it
    p = {**P1, 'kA': 5e10, 'mA': 2., 'dA': 100.}
    orbit = FindSteadyChatter(ResolveDrive(parameters=p))
    assert orbit.info['model'].stateKeys[-1] == 'xA' and len(orbit.state) == 6
    assert orbit.info['forceFactor'] == pytest.approx(orbitP1.info['forceFactor'], rel=0.02)
    assert orbit.info['maxWheelAcceleration'] == pytest.approx(orbitP1.info['maxWheelAcceleration'], rel=0.02)
    # and the disturbance search reads the mesh with the axial coordinate too: P1 is linearly unstable
    assert SmallestDisturbance(ResolveDrive(parameters=p), duration=0.5, steps=1) <= 0.25


def test_chain_orbit_matches_long_simulation(orbitChain):
    long = LongSimulationAmplitude(ResolveDrive(parameters=CHAIN), duration=4.0, stepSize=2e-4)
    assert orbitChain.converged and orbitChain.stable
    assert orbitChain.info['forceFactor'] == pytest.approx(long['forceFactor'], rel=0.02)
    assert orbitChain.info['maxWheelAcceleration'] == pytest.approx(long['maxWheelAcceleration'], rel=0.02)
    assert orbitChain.frequencyHz == pytest.approx(long['frequencyHz'], rel=0.005)


def test_chain_branch_hopf_point_on_the_linear_boundary():
    branch = AnalyzeChatterBranch(ResolveDrive(parameters=CHAIN), 'J1', 0.06, 0.1, maxPoints=40)
    chainRoots, _ = LinearBoundaries(ResolveDrive(parameters=CHAIN), 'J1', 0.06, 0.1)           # DriveStability: the whole drive
    lumpedRoots, _ = LinearBoundaries(ResolveDrive(parameters=P1), 'J1', 0.06, 0.1)             # the load lumped into J2
    assert len(chainRoots) == 1 and len(branch.hopf) == 1
    # the chain moves the boundary by more than the tolerance, so the check tells chain from lumped drive
    assert abs(chainRoots[0] - lumpedRoots[0]) > 0.01 * chainRoots[0]
    # required: the Hopf point coincides with the linear boundary within 0.5 %
    assert branch.hopf[0]['value'] == pytest.approx(chainRoots[0], rel=0.005)
    assert branch.hopf[0]['type'] == 'supercritical'


def _HandBuiltThreeMass(parameters):
    """motor (prescribed) --kT-- worm == mesh == wheel --kL1-- load inertia <- constant load torque, built with the
    public builders at the steady state, as a user would."""
    drive = ew.ElasticDriveFromParameters(parameters)
    w = parameters['motorSpeed']
    M = parameters['loadMass'] * 9.80665 * parameters['leverArm']             # lowering: the load drives the wheel
    s = ew.SteadyInitialState(drive, load=M, motorSpeed=w, loadSide=[(parameters['JL1'], parameters['kL1'])])
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    motor = CreateRotor(mbs, 1e-3, initialSpeed=w)
    worm = CreateRotor(mbs, drive.J1, initialAngle=s['phi1'], initialSpeed=s['omega1'])
    wheel = CreateRotor(mbs, drive.J2, initialAngle=s['phi2'], initialSpeed=s['omega2'])
    load = CreateRotor(mbs, parameters['JL1'], initialAngle=s['phiL1'], initialSpeed=s['omegaL1'])
    CreatePrescribedRotation(mbs, motor, ConstantSpeed(w))
    CreateShaft(mbs, [motor, worm], stiffness=drive.kT, damping=drive.dT)
    connector = ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=drive.gear)
    CreateShaft(mbs, [wheel, load], stiffness=parameters['kL1'])
    CreateRotorTorque(mbs, load, ConstantTorque(M))
    mbs.Assemble()
    return SC, mbs, connector


def test_own_three_mass_system_gives_the_parameter_sets_orbit(orbitChain):
    SC, mbs, connector = _HandBuiltThreeMass(CHAIN)
    orbit = SteadyChatterOfSystem(mbs, connector)
    model = orbit.info['model']
    assert len(model.coordinates) == 3                     # worm, wheel, load; the prescribed motor left out
    assert orbit.converged
    # the same drive as the parameter set's lowering model (built by BuildReelChanger): the same orbit
    assert orbit.period == pytest.approx(orbitChain.period, rel=1e-6)
    assert orbit.info['forceFactor'] == pytest.approx(orbitChain.info['forceFactor'], rel=1e-5)
    # the largest |phi2''| is sampled at 400 steps per period from another start point on the orbit (measured
    # 3.4e-4 apart): the same orbit, sampled at other instants
    assert orbit.info['maxWheelAcceleration'] == pytest.approx(orbitChain.info['maxWheelAcceleration'], rel=1e-3)
    assert orbit.stable == orbitChain.stable
    # a long simulation of the user's system (model=) reaches the same amplitude
    long = LongSimulationAmplitude(None, duration=3.0, stepSize=2e-4, model=model)
    assert orbit.info['forceFactor'] == pytest.approx(long['forceFactor'], rel=0.02)


def test_own_system_bad_input():
    SC, mbs, connector = _HandBuiltThreeMass(CHAIN)
    with pytest.raises(TypeError, match=r"LoweringModelOfSystem: 'connector' must be a WormGearConnector"):
        LoweringModelOfSystem(mbs, 'mesh')
    with pytest.raises(ValueError, match=r"LoweringModelOfSystem: 'coordinates' must be distinct ODE2 indices in "
                                         r"\[0, 3\] including the worm's \(1\)"):
        LoweringModelOfSystem(mbs, connector, coordinates=[2, 3])
    with pytest.raises(TypeError, match=r"LoweringModelOfSystem: 'mbs' must be an exudyn.MainSystem"):
        LoweringModelOfSystem(None, connector)
    mbs.systemData.SetODE2Coordinates_t([0.] * 4, configuration=__import__('exudyn').ConfigurationType.Initial)
    with pytest.raises(ValueError, match=r"LoweringModelOfSystem: the worm's initial speed must be its steady speed"):
        LoweringModelOfSystem(mbs, connector)


def test_cli_chatter_with_a_load_side_chain(capsys):
    # a narrow range inside the unstable interval: two orbits are enough to show the chain goes through
    code = Main(['chatter', '--preset', 'reel-P1', '--set', 'J2=23', '--set', 'JL1=10', '--set', 'kL1=1e7',
                 '--vary', 'J1=0.09:0.1', '--max-points', '2', '--json'])
    out = capsys.readouterr().out
    assert code == 0
    data = json.loads(out)
    assert data['parameter'] == 'J1' and len(data['points']) >= 2
    assert all(p['amplitude']['forceFactor'] > 2. for p in data['points'])


def test_cli_chatter_names_the_unsupported_component(capsys):
    code = Main(['chatter', '--preset', 'reel-P1', '--set', 'motorType=characteristic', '--set', 'stallTorque=300',
                 '--set', 'noLoadSpeed=52.36 rad/s', '--set', 'motorInertia=0.05', '--vary', 'J1=0.09:0.1'])
    err = capsys.readouterr().err
    assert code == 2
    assert 'a motor on its characteristic (motorType characteristic)' in err and 'Traceback' not in err
    assert len(err.strip().splitlines()) == 1


def test_branch_in_a_load_shaft_stiffness():
    branch = AnalyzeChatterBranch(ResolveDrive(parameters=CHAIN), 'kL1', 8e6, 1.2e7, maxPoints=2)
    assert branch.parameter == 'kL1' and len(branch.points) >= 2
    # each value rebuilds the lowering model with its own load shaft: the amplitude changes along the branch
    values = {round(p.value, 3): p.info['forceFactor'] for p in branch.points}
    assert len(set(values.values())) == len(values) and min(values.values()) > 2.
    # a stage the drive does not have cannot be continued; the message lists the drive's own keys
    with pytest.raises(ValueError, match=r"parameter 'kL2' cannot be continued; .* or a key of this drive's chains "
                                         r"and axial bearing \(JL1, kL1\)"):
        AnalyzeChatterBranch(ResolveDrive(parameters=CHAIN), 'kL2', 1e6, 1e7)


def test_own_system_at_rest_is_reported():
    # J1 = 0.3 kg m^2: the chain drive is linearly stable (its own linearization decides, as DriveStability for a
    # parameter set); the kick dies out and the message says so
    p = {**CHAIN, 'J1': 0.3}
    assert AnalyzeDrive(ResolveDrive(parameters=p)).State(-1).stable
    SC, mbs, connector = _HandBuiltThreeMass(p)
    assert _LinearlyStable(LoweringModelOfSystem(mbs, connector))
    SC, mbs, connector = _HandBuiltThreeMass(p)
    with pytest.raises(ValueError, match=r"SteadyChatterOfSystem: the system settles to rest"):
        SteadyChatterOfSystem(mbs, connector, settleTime=0.3)
