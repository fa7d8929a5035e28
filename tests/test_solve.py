"""Solving with a progress bar (in chunks): the same numbers as one Exudyn solve to the Newton tolerance, one
sample per time, the bar on stderr; without a bar exactly one solve; failures with the time reached."""
import exudyn as exu
import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm import GetPreset, SimulateReelChanger
from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.items.solve import SolveDynamicInChunks, SolverDivergedError
from exudyn_worm.items.solve import IncompleteSolveError
from exudyn_worm.drive.wholedrive import ResolveDrive


def _Plain(parameters, endTime, stepSize):
    """The reference: one mbs.SolveDynamic call with SimulateReelChanger's settings."""
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=parameters))
    mbs = model.mbs
    mbs.Assemble()
    ss, solverType = SolverSettings(endTime, stepSize)
    printing, exu.config.printToConsole = exu.config.printToConsole, False
    try:
        mbs.SolveDynamic(ss, solverType=solverType)
    finally:
        exu.config.printToConsole = printing
    return model.connector.StoredStates(mbs)


@pytest.mark.physics
@pytest.mark.parametrize('preset', ['reel-P1', 'reel-P7'])
def test_chunks_agree_with_one_solve(preset, capsys):
    """Chunks restart the modified-Newton Jacobian (and P7's step halvings move), so the trajectories agree
    with one solve to the Newton tolerance (relativeTolerance 1e-6 of SOLVER_SETTINGS) until the chatter
    amplifies it; the peaks the window metrics use agree to 0.1 %."""
    p = GetPreset(preset)
    result = SimulateReelChanger(ResolveDrive(parameters=p), endTime=3., stepSize=5e-4, progress=True)     # 6000 steps: three chunks
    assert 's simulated' in capsys.readouterr().err
    plain = _Plain(p, 3., 5e-4)
    assert np.all(np.diff(result.time) > 1e-9)                                   # one sample per time
    if preset == 'reel-P1':                                                      # fixed steps: the same grid
        np.testing.assert_allclose(result.time, plain['time'], rtol=0, atol=1e-9)
        early = plain['time'] < 2.                                               # lifting, no chatter
        for key in ('phi1', 'omega1', 'phi2', 'omega2'):
            np.testing.assert_allclose(getattr(result, key)[early], plain[key][early], rtol=0,
                                       atol=1e-5 * np.max(np.abs(plain[key])), err_msg=key)
    for t0, t1 in ((0., 2.), (2., 3.)):
        m, mp = result._Window(t0, t1), (plain['time'] >= t0) & (plain['time'] <= t1)
        assert np.max(np.abs(result.alpha2[m])) == pytest.approx(np.max(np.abs(plain['alpha2'][mp])), rel=1e-3)


def test_without_a_bar_exactly_one_solve(capsys):
    p = GetPreset('reel-P1')
    result = SimulateReelChanger(ResolveDrive(parameters=p), endTime=2.5, stepSize=5e-4, progress=False)
    plain = _Plain(p, 2.5, 5e-4)
    assert capsys.readouterr().err == ''
    for key in ('phi1', 'omega2', 'alpha2'):
        assert np.array_equal(getattr(result, key), plain[key])


@pytest.mark.messages
def test_bad_solver_type_refused():
    with pytest.raises(TypeError, match="'solverType' must be an exudyn.DynamicSolverType"):
        SolveDynamicInChunks(None, exu.SimulationSettings(), 'RK44')


@pytest.mark.messages
def test_failure_reports_the_time_reached():
    """A solve that cannot converge: one Newton iteration allowed, unreachable tolerance, no step reduction."""
    options = {'timeIntegration.newton.maxIterations': 1, 'timeIntegration.newton.useModifiedNewton': False,
               'timeIntegration.adaptiveStep': False, 'timeIntegration.newton.relativeTolerance': 1e-30,
               'timeIntegration.newton.absoluteTolerance': 1e-30}
    with pytest.raises(SolverDivergedError, match=r'SimulateReelChanger: the Exudyn solver failed at t = 0.0005 s of '
                                                  r'0.05 s \(step size 0.0005 s\).*likely cause') as info:
        SimulateReelChanger(ResolveDrive(parameters=GetPreset('reel-P1')), endTime=0.05, stepSize=5e-4, solverOptions=options,
                            progress=False)
    assert info.value.timeReached == pytest.approx(5e-4) and info.value.endTime == pytest.approx(0.05)


def test_explicit_solver_runs_in_one_piece():
    """Without constraints an explicit solver runs (one piece); two rotors on a shaft keep their speed."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    a, b = ew.CreateRotor(mbs, 0.1, initialSpeed=10.), ew.CreateRotor(mbs, 0.2, initialSpeed=10.)
    ew.CreateShaft(mbs, [a, b], stiffness=1e3, damping=1.)
    ss, _ = SolverSettings(0.05, 5e-4)
    solver = SolveDynamicInChunks(mbs, ss, exu.DynamicSolverType.RK44, progress=True)
    assert isinstance(solver, exu.MainSolverExplicit)
    assert float(mbs.GetNodeOutput(b['nodeNumber'], exu.OutputVariableType.Coordinates_t)) == pytest.approx(10.)


@pytest.mark.messages
def test_explicit_solver_refused_with_a_prescribed_motor():
    """Exudyn's explicit solvers ignore constraints: the reel changer's motor stood still (phi1 = -0.01 rad
    after 0.5 s instead of 24.7 rad) and the run returned normally. (A constant motor speed is a flywheel in
    SimulateReelChanger, without a constraint; a start-up profile keeps the constraint.)"""
    with pytest.raises(ValueError, match=r"explicit solver .*RK44 ignores constraints, and this system has "
                                         r"motorDrive \(ConnectorCoordinate\)"):
        SimulateReelChanger(ResolveDrive(parameters=GetPreset('reel-P1')), endTime=0.05, stepSize=5e-4, solverOptions={'solverType': 'RK44'},
                            profile=ew.StartStopProfile(speed=49.48, rampTime=0.5), progress=False)


@pytest.mark.parametrize('computationTime', [False, True])
def test_chunked_solve_switches_timers_as_solve_system_does(computationTime, capsys):
    """Exudyn's per-step timers made a chunked (progress bar) run 7-16 % slower: they are off in a chunked run
    exactly when SolveSystem switches them off (show.computationTime False)."""
    timers = []
    for progress in (True, False):
        model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
        ss, solverType = SolverSettings(0.02, 5e-4)
        ss.show.computationTime = computationTime
        printing, exu.config.printToConsole = exu.config.printToConsole, False
        try:
            solver = SolveDynamicInChunks(model.mbs, ss, solverType, progress=progress, chunkSteps=10)
        finally:
            exu.config.printToConsole = printing
        timers.append(solver.timer.useTimer)
    capsys.readouterr()
    assert timers == [computationTime, computationTime]


@pytest.mark.parametrize('endTime', [4., 8.0003])
def test_a_sample_every_step(endTime):
    """The recommended step does not divide the end time: the solver's step is endTime / numberOfSteps, and a
    sensor period equal to the requested step skipped samples by round-off (0, 2h, 3h, ...)."""
    result = SimulateReelChanger(ResolveDrive(parameters=GetPreset('reel-P1')), endTime=endTime, progress=False)
    h = endTime / round(endTime / result.info['stepSize'])
    assert result.time[1] == pytest.approx(h, rel=1e-6)
    assert np.max(np.diff(result.time)) < 1.001 * h


@pytest.mark.messages
@pytest.mark.parametrize('progress', [False, True])
def test_a_run_stopped_before_its_end_time_raises(progress, capsys):
    """A pre-step user function that stops the solver at 0.02 s: Exudyn returns normally with a truncated run;
    SolveDynamicInChunks refuses it (without and with a bar, i.e. one solve or chunks), naming both times."""
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    mbs = model.mbs
    mbs.SetPreStepUserFunction(lambda mbs, t: t < 0.02)
    mbs.Assemble()
    ss, solverType = SolverSettings(0.05, 5e-4)
    with pytest.raises(IncompleteSolveError, match=r"SolveDynamicInChunks: the run ended at t = 0.02 s, before its "
                                                   r"end time 0.05 s \(step size 0.0005 s\)") as info:
        SolveDynamicInChunks(mbs, ss, solverType, progress=progress, chunkSteps=20)
    assert info.value.timeReached == pytest.approx(0.02) and info.value.endTime == pytest.approx(0.05)
    assert isinstance(info.value, SolverDivergedError)         # callers that handle a failed solve handle it too


def test_a_run_that_reaches_its_end_time_is_accepted():
    model = BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=GetPreset('reel-P1')))
    mbs = model.mbs
    mbs.SetPreStepUserFunction(lambda mbs, t: True)
    mbs.Assemble()
    ss, solverType = SolverSettings(0.05, 5e-4)
    solver = SolveDynamicInChunks(mbs, ss, solverType, progress=False)
    assert solver.it.currentTime == pytest.approx(0.05)
