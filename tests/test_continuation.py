"""Pseudo-arclength continuation of periodic orbits (exudyn_worm.analysis.orbits.continuation) on the Hopf normal form.

    x' = mu x - y - x (x^2 + y^2),   y' = x + mu y - y (x^2 + y^2)

In polar coordinates r' = r (mu - r^2), theta' = 1: for mu > 0 the limit cycle is the circle r = sqrt(mu) with
period 2 pi; its non-trivial Floquet multiplier is exp(2 pi d/dr[r (mu - r^2)] at r = sqrt(mu)) = exp(-4 pi mu)
(e.g. Strogatz, Nonlinear Dynamics and Chaos, sec. 8.2; Kuznetsov, Elements of Applied Bifurcation Theory, 3.4).
"""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from exudyn_worm.analysis.orbits.continuation import ContinueOrbits
from exudyn_worm.analysis.orbits.periodic import BroydenUpdate, FindPeriodicOrbit, Monodromy


class Counted:
    """The normal form's flow at parameter mu, counting its runs."""

    runs = 0

    def __init__(self, mu):
        self.mu = mu

    def __call__(self, x0, T):
        Counted.runs += 1
        mu = self.mu

        def Rhs(t, z):
            r2 = z[0]**2 + z[1]**2
            return [mu * z[0] - z[1] - z[0] * r2, z[0] + mu * z[1] - z[1] * r2]
        return solve_ivp(Rhs, (0., T), x0, method='DOP853', rtol=1e-12, atol=1e-12).y[:, -1]


def test_branch_of_the_hopf_normal_form():
    mu0 = 0.5
    start = FindPeriodicOrbit(Counted(mu0), [0.8, 0.05], 6.0, stateScale=0.5)
    Counted.runs = 0
    branch = ContinueOrbits(Counted, start, mu0, (0.1, 0.9), stateScale=[0.5, 0.5], parameterScale=0.1,
                            direction=-1, stepLength=0.3, maxStepLength=0.6, maxPoints=40)
    assert branch.stopReason[-1].startswith('reached the end of the range at p = 0.1')
    assert len(branch.points) >= 5
    for point in branch.points:
        mu, orbit = point.value, point.orbit
        assert np.hypot(*orbit.state) == pytest.approx(math.sqrt(mu), rel=1e-6)
        assert orbit.period == pytest.approx(2 * math.pi, rel=1e-7)
        assert orbit.trivialMultiplierError < 1e-3
        assert abs(orbit.nontrivialMultipliers[0]) == pytest.approx(math.exp(-4 * math.pi * mu), rel=1e-4)
    # the corrector starts from the previous orbit's Jacobian and updates it (Broyden): per orbit the runs of its
    # central-difference monodromy (4), velocity (1), parameter derivative (1) and a few corrector steps; a full
    # finite-difference Jacobian at every Newton step would need 4 runs per step on top
    assert Counted.runs / (len(branch.points) - 1) < 14


def test_monodromy_of_a_linear_flow_is_exact():
    A = np.array([[-0.1, 1.], [-2., -0.3]])
    w, V = np.linalg.eig(A)
    T = 1.7
    exact = (V @ np.diag(np.exp(w * T)) @ np.linalg.inv(V)).real

    def Flow(x0, t):
        return (V @ np.diag(np.exp(w * t)) @ np.linalg.inv(V)).real @ np.asarray(x0)
    for central in (False, True):
        np.testing.assert_allclose(Monodromy(Flow, [0.3, -0.2], T, [1., 1.], 1e-3, central=central), exact,
                                   atol=1e-10)


def test_broyden_update_meets_the_secant_condition_and_keeps_linear_rows():
    rng = np.random.default_rng(1)
    A = rng.normal(size=(3, 3))
    step = rng.normal(size=3)
    change = rng.normal(size=3)
    change[2] = A[2] @ step                          # an exactly linear equation: its row sees no new information
    B = BroydenUpdate(A, step, change)
    np.testing.assert_allclose(B @ step, change, atol=1e-12)
    np.testing.assert_allclose(B[2], A[2], atol=1e-12)
    np.testing.assert_array_equal(BroydenUpdate(A, np.zeros(3), change), A)
