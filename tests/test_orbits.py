"""Shooting and Floquet multipliers (exudyn_worm.analysis.orbits.periodic) on textbook systems before the worm drive.

- van der Pol, x'' - eps (1 - x^2) x' + x = 0: for small eps the limit cycle has amplitude 2 and period
  2 pi (1 + eps^2/16 + O(eps^4)) (Lindstedt-Poincare, e.g. Nayfeh & Mook, Nonlinear Oscillations, 1979,
  sec. 3.3; Strogatz, Nonlinear Dynamics and Chaos, exercise 7.6); its non-trivial Floquet multiplier is
  exp(integral of the divergence eps (1 - x^2) over one period) (Liouville), exp(-2 pi eps) to leading order.
  For eps = 2 the orbit is compared with a long solve_ivp run.
- Mass on a moving belt, static friction Fs > kinetic Fk: the closed-form stick-slip cycle derived in
  docs/chatter-amplitude.md (amplitude sqrt(d^2 + (vb/w)^2) about Fk/k with d = (Fs - Fk)/k, period
  2 d / vb + (pi + 2 atan(vb / (w d))) / w); the sticking phase collapses the state, so the non-trivial
  multiplier is 0.
"""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp, trapezoid

from exudyn_worm.analysis.orbits.periodic import FindPeriodicOrbit, FloquetMultipliers, ShootingError


def VanDerPolFlow(eps):
    def Rhs(t, z):
        return [z[1], eps * (1 - z[0]**2) * z[1] - z[0]]

    def Flow(x0, T):
        return solve_ivp(Rhs, (0., T), x0, method='DOP853', rtol=1e-12, atol=1e-12).y[:, -1]
    return Rhs, Flow


@pytest.mark.parametrize('eps', [0.05, 0.1])
def test_van_der_pol_small_eps_amplitude_period_multiplier(eps):
    Rhs, Flow = VanDerPolFlow(eps)
    orbit = FindPeriodicOrbit(Flow, [1.5, 0.3], 6.0, stateScale=1.)
    assert orbit.converged
    # period: Lindstedt-Poincare 2 pi (1 + eps^2/16), next term -5 eps^4/3072 * 2 pi (< 1e-6 relative here)
    assert orbit.period == pytest.approx(2 * math.pi * (1 + eps**2 / 16), rel=2e-6)
    t = np.linspace(0., orbit.period, 2001)
    sol = solve_ivp(Rhs, (0., orbit.period), orbit.state, method='DOP853', rtol=1e-12, atol=1e-12, t_eval=t)
    # amplitude 2 + O(eps^2)
    assert np.max(np.abs(sol.y[0])) == pytest.approx(2., abs=eps**2)
    # Liouville: product of multipliers = exp(int div f dt); trivial multiplier 1
    divergence = trapezoid(eps * (1 - sol.y[0]**2), t)
    mu = orbit.multipliers
    assert np.min(np.abs(mu - 1.)) < 1e-5
    assert orbit.nontrivialMultipliers[0].real == pytest.approx(math.exp(divergence), rel=1e-4)
    assert math.exp(divergence) == pytest.approx(math.exp(-2 * math.pi * eps), rel=2 * eps**2)
    assert orbit.stable


def test_van_der_pol_large_eps_matches_long_simulation():
    eps = 2.
    Rhs, Flow = VanDerPolFlow(eps)
    orbit = FindPeriodicOrbit(Flow, [2., 0.], 7.0, stateScale=[2., 3.])
    # a long run from near the origin: period from the last upward zero crossings, amplitude from the last cycle
    t = np.linspace(0., 80., 160001)
    sol = solve_ivp(Rhs, (0., 80.), [0.1, 0.], method='DOP853', rtol=1e-11, atol=1e-11, t_eval=t)
    x = sol.y[0]
    up = np.nonzero((x[:-1] < 0) & (x[1:] >= 0))[0]
    crossings = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    periodLong = crossings[-1] - crossings[-2]
    assert orbit.period == pytest.approx(periodLong, rel=1e-6)
    last = t >= crossings[-2]
    tt = np.linspace(0., orbit.period, 4001)
    cycle = solve_ivp(Rhs, (0., orbit.period), orbit.state, method='DOP853', rtol=1e-12, atol=1e-12, t_eval=tt)
    assert np.max(cycle.y[0]) == pytest.approx(np.max(x[last]), rel=1e-5)
    assert orbit.stable and abs(orbit.nontrivialMultipliers[0]) < 1e-3


class Belt:
    """Mass m on a spring k to ground, on a belt moving at vb; kinetic friction Fk < static Fs."""

    def __init__(self, m=1., k=100., vb=0.2, Fs=10., Fk=6.):
        self.m, self.k, self.vb, self.Fs, self.Fk = m, k, vb, Fs, Fk
        self.w = math.sqrt(k / m)

    def ClosedForm(self):
        d = (self.Fs - self.Fk) / self.k
        A = math.hypot(d, self.vb / self.w)
        period = 2 * d / self.vb + (math.pi + 2 * math.atan(self.vb / (self.w * d))) / self.w
        return self.Fk / self.k, A, period

    def Flow(self, x0, T, samples=None):
        """Event-driven exact stick/slip flow; with ``samples`` also the positions at those times."""
        t, z, out = 0., np.array(x0, dtype=float), []
        sticking = abs(z[1] - self.vb) < 1e-12 and abs(self.k * z[0]) <= self.Fs
        while t < T:
            if sticking:
                tEnd = min(T, t + (self.Fs / self.k - z[0]) / self.vb)
                if samples is not None:
                    s = samples[(samples >= t) & (samples < tEnd)]
                    out.append(z[0] + self.vb * (s - t))
                z = np.array([z[0] + self.vb * (tEnd - t), self.vb])
                t, sticking = tEnd, False
                continue
            s0 = math.copysign(1., self.vb - z[1]) if z[1] != self.vb else 1.

            def Rhs(_, y, s=s0):
                return [y[1], (-self.k * y[0] + s * self.Fk) / self.m]

            def Stuck(_, y):
                return y[1] - self.vb
            Stuck.terminal = True
            Stuck.direction = s0              # v approaches vb from below (s0 = +1) or above (s0 = -1)
            sol = solve_ivp(Rhs, (t, T), z, method='DOP853', rtol=1e-12, atol=1e-13, events=Stuck,
                            dense_output=samples is not None, first_step=1e-6)
            tEnd = sol.t[-1]
            if samples is not None:
                s = samples[(samples >= t) & (samples < tEnd)]
                out.append(sol.sol(s)[0] if s.size else s)
            z = sol.y[:, -1].copy()
            t = tEnd
            if sol.status == 1:                               # relative speed 0
                z[1] = self.vb
                sticking = abs(self.k * z[0]) <= self.Fs
        return (z, np.concatenate(out)) if samples is not None else z


def test_stick_slip_orbit_matches_closed_form():
    belt = Belt()
    center, A, period = belt.ClosedForm()
    # guess inside the slip phase, a bit off the cycle
    orbit = FindPeriodicOrbit(belt.Flow, [center + 0.5 * A, -0.2], 0.9 * period, stateScale=[A, belt.vb])
    assert orbit.period == pytest.approx(period, rel=1e-7)
    samples = np.linspace(0., orbit.period, 20001)
    _, x = belt.Flow(orbit.state, orbit.period, samples)
    assert np.max(x) == pytest.approx(center + A, rel=1e-6)
    assert np.min(x) == pytest.approx(center - A, rel=1e-6)
    # sticking collapses the state: multipliers {1, 0}
    mu = np.sort(np.abs(orbit.multipliers))
    assert mu[1] == pytest.approx(1., abs=1e-5) and mu[0] < 1e-5
    assert orbit.stable


def test_floquet_multipliers_sorted_by_modulus():
    mu = FloquetMultipliers(np.diag([0.5, -2., 1.]))
    np.testing.assert_allclose(mu, [-2., 1., 0.5])


def test_shooting_reports_no_convergence_with_last_iterate():
    _, Flow = VanDerPolFlow(0.1)
    with pytest.raises(ShootingError, match=r"FindPeriodicOrbit: shooting did not converge in 1 Newton steps") as err:
        FindPeriodicOrbit(Flow, [0.5, 0.], 4.0, stateScale=1., maxIterations=1)
    assert err.value.lastOrbit is not None and not err.value.lastOrbit.converged


@pytest.mark.parametrize('kwargs, message', [
    (dict(period=-1.), r"FindPeriodicOrbit: 'period' must be > 0 s, got -1"),
    (dict(x0=[]), r"FindPeriodicOrbit: 'x0' must be a non-empty sequence of finite numbers"),
    (dict(stateScale=[1., 0.]), r"FindPeriodicOrbit: 'stateScale' must hold positive finite values"),
    (dict(maxIterations=0), r"FindPeriodicOrbit: 'maxIterations' must be an integer >= 1, got 0"),
])
def test_shooting_bad_input(kwargs, message):
    _, Flow = VanDerPolFlow(0.1)
    args = dict(x0=[2., 0.], period=6.28)
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        FindPeriodicOrbit(Flow, **args)
