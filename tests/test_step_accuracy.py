"""The accuracy statement of the recommended step holds in every default window of every reel preset and of the
shipped drives figure19 and load-shaft: the window peaks at the default step against a converged step
(PEAK_ACCURACY, TRANSIENT_PEAK_ACCURACY; docs/simulation.md)."""
import pytest

from exudyn_worm import SimulateReelChanger
from exudyn_worm.analysis.simulation.reelchanger import DefaultWindows
from exudyn_worm.analysis.simulation.stepsize import PEAK_ACCURACY, TRANSIENT_PEAK_ACCURACY, RecommendedStepSize
from exudyn_worm.params.drives import ConfigPath
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.drive.wholedrive import ResolveDrive

#: the reference step of each drive, as a divisor of its recommended step: the halving after it changes no window
#: peak by more than 0.05 % (measured with benchmarks/step_convergence.py); the lift after the lowering chatter of
#: P1 and P6 converges last
REFERENCE_DIVISOR = {'reel-P1': 32, 'reel-P2': 4, 'reel-P3': 4, 'reel-P4': 8, 'reel-P5': 4, 'reel-P6': 32,
                     'reel-P7': 8, 'figure19': 16, 'load-shaft': 16}


@pytest.mark.slow
@pytest.mark.parametrize('drive', sorted(REFERENCE_DIVISOR))
def test_window_peaks_at_the_default_step_are_within_the_stated_bound(drive):
    p = ResolveParameters(drive) if drive.startswith('reel-') else ResolveParameters(config=ConfigPath(drive))
    windows = DefaultWindows(ResolveDrive(parameters=p))
    metrics = SimulateReelChanger(ResolveDrive(parameters=p), progress=False).WindowMetrics(windows)
    reference = SimulateReelChanger(ResolveDrive(parameters=p), stepSize=RecommendedStepSize(ResolveDrive(parameters=p)) / REFERENCE_DIVISOR[drive],
                                    progress=False).WindowMetrics(windows)
    for i, (m, r) in enumerate(zip(metrics, reference)):
        # the wheel's transient after a load reversal in chatter, and every window of the drive files (ringing modes)
        transient = (i > 0 and bool(metrics[i - 1]['chatter'])) or not drive.startswith('reel-')
        for name in ('maxAbsWheelAcceleration', 'maxNormalForce'):
            bound = TRANSIENT_PEAK_ACCURACY if transient and name == 'maxAbsWheelAcceleration' else PEAK_ACCURACY
            error = m[name] / r[name] - 1.
            assert abs(error) <= bound, (f"{drive} window {i} {name}: {m[name]:.5g} against {r[name]:.5g} "
                                         f"converged ({error:+.2%}, stated bound {bound:.0%})")
