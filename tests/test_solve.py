"""Chunked solving: same numbers as one Exudyn solve (to the Newton tolerance), independent of the progress
bar, one sample per time, a bar on stderr when asked, and failures with the time reached."""
import numpy as np
import pytest

from exudyn_worm import GetPreset, SimulateReelChanger
from exudyn_worm.reelchanger import BuildReelChanger


def _Plain(parameters, endTime, stepSize):
    """The reference: one mbs.SolveDynamic call with SimulateReelChanger's settings."""
    import exudyn as exu
    model = BuildReelChanger(parameters)
    mbs = model.mbs
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = stepSize
    ss.timeIntegration.endTime = endTime
    ss.timeIntegration.numberOfSteps = int(round(endTime / stepSize))
    ss.timeIntegration.verboseMode = 0
    ss.timeIntegration.newton.useModifiedNewton = True
    printing, exu.config.printToConsole = exu.config.printToConsole, False
    try:
        mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    finally:
        exu.config.printToConsole = printing
    return model.connector.StoredStates(mbs)


def test_chunks_agree_with_one_solve_p1():
    p = GetPreset('reel-P1')
    endTime, h = 3., 5e-4                 # 6000 steps: three chunks; P1 chatters from 2 s
    result = SimulateReelChanger(p, endTime=endTime, stepSize=h, progress=False)
    plain = _Plain(p, endTime, h)
    np.testing.assert_allclose(result.time, plain['time'], rtol=0, atol=1e-9)   # one sample per step, no repeats
    for key in ('phi1', 'omega1', 'phi2', 'omega2', 'alpha2'):
        scale = np.max(np.abs(plain[key]))
        np.testing.assert_allclose(getattr(result, key), plain[key], rtol=0, atol=1e-6 * scale, err_msg=key)


def test_chunks_agree_with_one_solve_p7():
    """P7 halves its step often (worm speed through zero): the chunk ends change where it does, so the
    chattering trajectories differ by about 1 % pointwise; the peaks the metrics use agree to 0.1 %."""
    p = GetPreset('reel-P7')
    result = SimulateReelChanger(p, endTime=3., progress=False)
    plain = _Plain(p, 3., 5e-4)
    assert np.all(np.diff(result.time) > 1e-9)
    for t0, t1 in ((0., 2.), (2., 3.)):
        m, mp = result._Window(t0, t1), (plain['time'] >= t0) & (plain['time'] <= t1)
        assert np.max(np.abs(result.alpha2[m])) == pytest.approx(np.max(np.abs(plain['alpha2'][mp])), rel=1e-3)


def test_numbers_do_not_depend_on_the_progress_bar(capsys):
    p = GetPreset('reel-P1')
    quiet = SimulateReelChanger(p, endTime=2.5, progress=False)
    shown = SimulateReelChanger(p, endTime=2.5, progress=True)
    err = capsys.readouterr().err
    assert 's simulated' in err and '100%' in err
    for key in ('alpha2', 'normalForce', 'S'):
        assert np.array_equal(getattr(quiet, key), getattr(shown, key))


def test_other_solver_types_refused():
    import exudyn as exu
    from exudyn_worm.solve import SolveDynamicInChunks
    with pytest.raises(ValueError, match="'solverType' must be GeneralizedAlpha or TrapezoidalIndex2"):
        SolveDynamicInChunks(None, exu.SimulationSettings(), exu.DynamicSolverType.RK44)
