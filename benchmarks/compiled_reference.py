"""The compiled limit of the benchmark: equations (1)-(2) of the reel changer in C, built at benchmark time.

Not part of the package. The right-hand side is *generated* from the package's own laws, not re-written:
:func:`exudyn_worm.model.contact.MeshContact`, :meth:`ConstantSpeed.AngleAndSpeed` and
:meth:`GravityLeverTorque.Torque` are evaluated with a backend (:data:`C_OPS`) whose numbers are C
expressions, exactly as the Exudyn connector records them as symbolic expressions. The C file holds that
right-hand side and an adaptive Dormand-Prince 5(4) integrator (the method of scipy's ``RK45``, with its
standard step-size control) that writes the states on a fixed output grid by cubic Hermite
interpolation; it is compiled with ``cc -O2`` into a temporary folder (removed again) and called through
``ctypes``. So the compiled model is the same model as :mod:`scipy_reference` and the Exudyn one, at
native speed: the limit against which our time is reported.

Requires a C compiler (``cc``; ``CC`` overrides it). Nothing is left on disk.
"""
from __future__ import annotations

import ctypes
import math
import os
import shutil
import subprocess
import tempfile
import time as _time
from types import SimpleNamespace
from typing import Mapping, Optional

import numpy as np

from exudyn_worm.model.contact import ContactOptions, MeshContact
from exudyn_worm.analysis.simulation.reelchanger import DEFAULT_STEP_SIZE, RotationPeriod
from exudyn_worm.items.results import SimulationResult
from exudyn_worm.drive.wholedrive import ResolveDrive
from scipy_reference import ReelChangerOde, ResultFromStates

#: the reference models have no stick state: they use the regularized friction law (docs/friction-sticking.md);
#: where the worm never stops (P1) it gives the same results as the package's default sticking law
REGULARIZED = ContactOptions(frictionModel='regularized')

__all__ = ['C_OPS', 'CExpr', 'ReelChangerC', 'CompiledReelChanger', 'SolveReelChangerCompiled']


class CExpr:
    """A C expression (text) that supports the arithmetic the laws use."""

    def __init__(self, text):
        self.text = text if isinstance(text, str) else _Literal(text)

    def __str__(self):
        return self.text

    def _Bin(self, other, op, swap=False):
        a, b = (_C(other), self) if swap else (self, _C(other))
        return CExpr(f'({a} {op} {b})')

    def __add__(self, o): return self._Bin(o, '+')
    def __radd__(self, o): return self._Bin(o, '+', True)
    def __sub__(self, o): return self._Bin(o, '-')
    def __rsub__(self, o): return self._Bin(o, '-', True)
    def __mul__(self, o): return self._Bin(o, '*')
    def __rmul__(self, o): return self._Bin(o, '*', True)
    def __truediv__(self, o): return self._Bin(o, '/')
    def __rtruediv__(self, o): return self._Bin(o, '/', True)
    def __neg__(self): return CExpr(f'(-{self})')
    def __gt__(self, o): return self._Bin(o, '>')
    def __lt__(self, o): return self._Bin(o, '<')
    def __ge__(self, o): return self._Bin(o, '>=')
    def __le__(self, o): return self._Bin(o, '<=')


def _Literal(x) -> str:
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"compiled_reference: non-finite constant {x!r} in a law")
    return repr(x)


def _C(x) -> CExpr:
    return x if isinstance(x, CExpr) else CExpr(x)


def _Fn(name):
    return lambda *args: CExpr(f"{name}({', '.join(str(_C(a)) for a in args)})")


#: C backend for the laws (same names as MATH_OPS / NUMPY_OPS / SymbolicOps)
C_OPS = SimpleNamespace(sin=_Fn('sin'), cos=_Fn('cos'), abs=_Fn('fabs'), sign=_Fn('sgn'), max=_Fn('fmax'),
                        min=_Fn('fmin'), where=lambda c, a, b: CExpr(f'({_C(c)} ? {_C(a)} : {_C(b)})'))

_C_TEMPLATE = r"""
#include <math.h>
static inline double sgn(double x) { return (double)(x > 0) - (double)(x < 0); }

static void rhs(double t, const double *y, double *f)
{
    const double phi1 = y[0], phi2 = y[1], omega1 = y[2], omega2 = y[3];
    const double phi0 = %(phi0)s, omega0 = %(omega0)s;
    const double wormTorque = %(worm)s, wheelTorque = %(wheel)s, loadTorque = %(load)s;
    f[0] = omega1;
    f[1] = omega2;
    f[2] = (%(kT)s * (phi0 - phi1) + %(dT)s * (omega0 - omega1) + wormTorque) / %(J1)s;
    f[3] = (wheelTorque + loadTorque) / %(J2)s;
}

/* Dormand-Prince 5(4) with the standard error control (as scipy's RK45); states written at
   t = k*dtOut by cubic Hermite interpolation. Returns the number of accepted steps (negative: failure). */
long solve(const double *y0, double endTime, double dtOut, long nOut, double rtol, double atol, double h0,
           double *out, long *rejected)
{
    static const double c2 = 1./5, c3 = 3./10, c4 = 4./5, c5 = 8./9;
    static const double a21 = 1./5, a31 = 3./40, a32 = 9./40, a41 = 44./45, a42 = -56./15, a43 = 32./9,
        a51 = 19372./6561, a52 = -25360./2187, a53 = 64448./6561, a54 = -212./729,
        a61 = 9017./3168, a62 = -355./33, a63 = 46732./5247, a64 = 49./176, a65 = -5103./18656,
        b1 = 35./384, b3 = 500./1113, b4 = 125./192, b5 = -2187./6784, b6 = 11./84,
        e1 = 71./57600, e3 = -71./16695, e4 = 71./1920, e5 = -17253./339200, e6 = 22./525, e7 = -1./40;
    double y[4], yn[4], k1[4], k2[4], k3[4], k4[4], k5[4], k6[4], k7[4], tmp[4];
    double t = 0., h = h0;
    long steps = 0, iOut = 0;
    int i;
    *rejected = 0;
    for (i = 0; i < 4; ++i) y[i] = y0[i];
    rhs(t, y, k1);
    for (i = 0; i < 4; ++i) out[i] = y[i];
    iOut = 1;
    while (iOut < nOut) {
        double err = 0., hNew;
        if (t + h > endTime) h = endTime - t;
        for (i = 0; i < 4; ++i) tmp[i] = y[i] + h * a21 * k1[i];
        rhs(t + c2 * h, tmp, k2);
        for (i = 0; i < 4; ++i) tmp[i] = y[i] + h * (a31 * k1[i] + a32 * k2[i]);
        rhs(t + c3 * h, tmp, k3);
        for (i = 0; i < 4; ++i) tmp[i] = y[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
        rhs(t + c4 * h, tmp, k4);
        for (i = 0; i < 4; ++i) tmp[i] = y[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
        rhs(t + c5 * h, tmp, k5);
        for (i = 0; i < 4; ++i) tmp[i] = y[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
        rhs(t + h, tmp, k6);
        for (i = 0; i < 4; ++i) yn[i] = y[i] + h * (b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i]);
        rhs(t + h, yn, k7);
        for (i = 0; i < 4; ++i) {
            double e = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
            double sc = atol + rtol * fmax(fabs(y[i]), fabs(yn[i]));
            err += (e / sc) * (e / sc);
        }
        err = sqrt(err / 4.);
        if (!(err == err)) return -1;
        if (err <= 1.) {
            double tn = t + h;
            while (iOut < nOut && iOut * dtOut <= tn + 1e-12 * dtOut) {
                double s = (iOut * dtOut - t) / h, s2 = s * s, s3 = s2 * s;
                double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
                for (i = 0; i < 4; ++i)
                    out[4 * iOut + i] = h00 * y[i] + h10 * h * k1[i] + h01 * yn[i] + h11 * h * k7[i];
                ++iOut;
            }
            t = tn;
            for (i = 0; i < 4; ++i) { y[i] = yn[i]; k1[i] = k7[i]; }
            ++steps;
            hNew = h * fmin(10., 0.9 * pow(err > 1e-10 ? err : 1e-10, -0.2));
        } else {
            ++*rejected;
            hNew = h * fmax(0.2, 0.9 * pow(err, -0.2));
        }
        h = hNew;
        if (h < 1e-14) return -2;
    }
    return steps;
}

/* Generalized-alpha (Chung-Hulbert / Arnold-Bruels parameters from the spectral radius rho, as Exudyn's
   solver) at the fixed step h with full Newton on the two accelerations (Jacobian by finite differences).
   A step whose Newton iteration does not converge in 25 iterations is repeated as two half steps (down to
   h / 2^20), as Exudyn's adaptive step does. Writes states and accelerations after every step of h;
   returns the number of halved steps (-1: no convergence even at the smallest step). */
typedef struct { double q[2], v[2], acc[2], a[2]; } GAState;
static double gaAm, gaAf, gaGam, gaBet, gaRtol;

static int gaStep(GAState *s, double t, double h)      /* 1: converged, state advanced to t + h */
{
    const double cq = h * h * gaBet * (1. - gaAf) / (1. - gaAm), cv = h * gaGam * (1. - gaAf) / (1. - gaAm);
    double qb[2], vb[2], x[2] = {s->acc[0], s->acc[1]}, r[2], J[2][2], y[4], f[4];
    int i, it;
    for (i = 0; i < 2; ++i) {      /* the parts of q, v that do not depend on the new acceleration */
        double aPart = (gaAf * s->acc[i] - gaAm * s->a[i]) / (1. - gaAm);
        qb[i] = s->q[i] + h * s->v[i] + h * h * (0.5 - gaBet) * s->a[i] + h * h * gaBet * aPart;
        vb[i] = s->v[i] + h * (1. - gaGam) * s->a[i] + h * gaGam * aPart;
    }
    for (it = 0; it < 25; ++it) {
        int j;
        double det, dx0, dx1;
        for (i = 0; i < 2; ++i) { y[i] = qb[i] + cq * x[i]; y[2 + i] = vb[i] + cv * x[i]; }
        rhs(t + h, y, f);
        r[0] = x[0] - f[2]; r[1] = x[1] - f[3];
        if (fabs(r[0]) + fabs(r[1]) <= gaRtol * (fabs(f[2]) + fabs(f[3]) + 1.)) {
            for (i = 0; i < 2; ++i) {
                s->a[i] = (gaAf * s->acc[i] + (1. - gaAf) * x[i] - gaAm * s->a[i]) / (1. - gaAm);
                s->q[i] = qb[i] + cq * x[i];
                s->v[i] = vb[i] + cv * x[i];
                s->acc[i] = x[i];
            }
            return 1;
        }
        for (j = 0; j < 2; ++j) {      /* dR/dx by forward differences */
            double xs[2] = {x[0], x[1]}, g[4], eps = 1e-7 * (fabs(x[j]) + 1.);
            xs[j] += eps;
            for (i = 0; i < 2; ++i) { y[i] = qb[i] + cq * xs[i]; y[2 + i] = vb[i] + cv * xs[i]; }
            rhs(t + h, y, g);
            J[0][j] = (xs[0] - g[2] - r[0]) / eps;
            J[1][j] = (xs[1] - g[3] - r[1]) / eps;
        }
        det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        dx0 = (J[1][1] * r[0] - J[0][1] * r[1]) / det;
        dx1 = (J[0][0] * r[1] - J[1][0] * r[0]) / det;
        x[0] -= dx0; x[1] -= dx1;
    }
    return 0;
}

static long gaAdvance(GAState *s, double t, double h, int depth)   /* halved steps, or -1 */
{
    GAState trial = *s;
    long n1, n2;
    if (gaStep(&trial, t, h)) { *s = trial; return 0; }
    if (depth >= 20) return -1;
    n1 = gaAdvance(s, t, 0.5 * h, depth + 1);
    if (n1 < 0) return -1;
    n2 = gaAdvance(s, t + 0.5 * h, 0.5 * h, depth + 1);
    if (n2 < 0) return -1;
    return 1 + n1 + n2;
}

long solveGA(const double *y0, double h, long nSteps, double rho, double rtol, double *out, double *alphaOut)
{
    GAState s;
    double y[4], f[4];
    long k, halved = 0;
    int i;
    gaAm = (2. * rho - 1.) / (rho + 1.); gaAf = rho / (rho + 1.);
    gaGam = 0.5 + gaAf - gaAm; gaBet = 0.25 * (gaGam + 0.5) * (gaGam + 0.5); gaRtol = rtol;
    for (i = 0; i < 4; ++i) y[i] = y0[i];
    rhs(0., y, f);
    s.q[0] = y0[0]; s.q[1] = y0[1]; s.v[0] = y0[2]; s.v[1] = y0[3];
    s.acc[0] = s.a[0] = f[2]; s.acc[1] = s.a[1] = f[3];
    for (i = 0; i < 4; ++i) out[i] = y[i];
    alphaOut[0] = s.acc[0]; alphaOut[1] = s.acc[1];
    for (k = 1; k <= nSteps; ++k) {
        long n = gaAdvance(&s, (k - 1) * h, h, 0);
        if (n < 0) return -1;
        halved += n;
        out[4 * k] = s.q[0]; out[4 * k + 1] = s.q[1]; out[4 * k + 2] = s.v[0]; out[4 * k + 3] = s.v[1];
        alphaOut[2 * k] = s.acc[0]; alphaOut[2 * k + 1] = s.acc[1];
    }
    return halved;
}

void accelerations(const double *states, long n, double dtOut, double *alpha)
{
    long k;
    double f[4];
    for (k = 0; k < n; ++k) {
        rhs(k * dtOut, states + 4 * k, f);
        alpha[2 * k] = f[2];
        alpha[2 * k + 1] = f[3];
    }
}
"""


def ReelChangerC(parameters: Mapping[str, float], contactOptions: ContactOptions = REGULARIZED) -> str:
    """C source of the reel changer (right-hand side generated from the package's laws + integrator).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set (e.g. ``GetPreset('reel-P1')``).
    contactOptions : ContactOptions
        Options of the contact law.
    """
    _, _, drive, load, motor = ReelChangerOde(parameters, contactOptions)
    phi1, phi2, omega1, omega2, t = (CExpr(n) for n in ('phi1', 'phi2', 'omega1', 'omega2', 't'))
    phi0, omega0 = motor.AngleAndSpeed(t, C_OPS)
    mesh = MeshContact(drive.gear, phi1, phi2, omega1, omega2, contactOptions, C_OPS)
    return _C_TEMPLATE % {'phi0': _C(phi0), 'omega0': _C(omega0), 'worm': mesh.wormTorque,
                          'wheel': mesh.wheelTorque, 'load': load.Torque(phi2, omega2, t, C_OPS),
                          'kT': _Literal(drive.kT), 'dT': _Literal(drive.dT), 'J1': _Literal(drive.J1),
                          'J2': _Literal(drive.J2)}


class CompiledReelChanger:
    """The compiled model of one parameter set: build once (``cc -O2``), solve many times.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    contactOptions : ContactOptions
        Options of the contact law.
    """

    def __init__(self, parameters: Mapping[str, float], contactOptions: ContactOptions = REGULARIZED):
        self.parameters, self.contactOptions = dict(parameters), contactOptions
        source = ReelChangerC(parameters, contactOptions)
        folder = tempfile.mkdtemp(prefix='exudyn_worm_bench_')
        try:
            src, lib = os.path.join(folder, 'reel.c'), os.path.join(folder, 'reel.so')
            with open(src, 'w') as f:
                f.write(source)
            compiler = os.environ.get('CC') or shutil.which('cc') or shutil.which('gcc')
            if compiler is None:
                raise RuntimeError("CompiledReelChanger: no C compiler found (set CC)")
            subprocess.run([compiler, '-O2', '-shared', '-fPIC', '-o', lib, src, '-lm'], check=True,
                           capture_output=True)
            self._lib = ctypes.CDLL(lib)          # the mapping outlives the deleted file
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        D, L = ctypes.POINTER(ctypes.c_double), ctypes.c_long
        self._lib.solve.restype = L
        self._lib.solve.argtypes = [D, ctypes.c_double, ctypes.c_double, L, ctypes.c_double, ctypes.c_double,
                                    ctypes.c_double, D, ctypes.POINTER(L)]
        self._lib.solveGA.restype = L
        self._lib.solveGA.argtypes = [D, ctypes.c_double, L, ctypes.c_double, ctypes.c_double, D, D]
        self._lib.accelerations.restype = None
        self._lib.accelerations.argtypes = [D, L, ctypes.c_double, D]

    def Solve(self, endTime: Optional[float] = None, rtol: float = 1e-6, atol: float = 1e-8,
              outputStep: float = DEFAULT_STEP_SIZE) -> SimulationResult:
        """Integrate with the compiled Dormand-Prince 5(4) method; same result type as the other models.

        Parameters
        ----------
        endTime : float, optional
            Simulated time in s (default one wheel rotation).
        rtol, atol : float
            Error-control tolerances (as in scipy).
        outputStep : float
            Output grid in s.

        Returns
        -------
        SimulationResult
            ``solveSeconds`` is the compiled solve alone; ``info`` holds steps and rejected steps.
        """
        endTime = RotationPeriod(ResolveDrive(parameters=self.parameters)) if endTime is None else float(endTime)
        _, y0, drive, _, motor = ReelChangerOde(self.parameters, self.contactOptions)
        n = int(math.floor(endTime / outputStep + 1e-9)) + 1
        out = np.zeros((n, 4))
        rejected = ctypes.c_long(0)
        D = ctypes.POINTER(ctypes.c_double)
        y0 = np.ascontiguousarray(y0, dtype=float)
        t0, c0 = _time.perf_counter(), _time.process_time()
        steps = self._lib.solve(y0.ctypes.data_as(D), endTime, outputStep, n, rtol, atol, 1e-5,
                                out.ctypes.data_as(D), ctypes.byref(rejected))
        solveSeconds, solveCpuSeconds = _time.perf_counter() - t0, _time.process_time() - c0
        if steps < 0:
            raise RuntimeError(f"CompiledReelChanger.Solve: the integration failed (code {steps})")
        alpha = np.zeros((n, 2))
        self._lib.accelerations(out.ctypes.data_as(D), n, outputStep, alpha.ctypes.data_as(D))
        time = np.arange(n) * outputStep
        return ResultFromStates(time, out.T, alpha, drive, motor, self.contactOptions, solveSeconds,
                                {'method': 'C DOPRI5', 'rtol': rtol, 'atol': atol, 'steps': int(steps),
                                 'rejectedSteps': int(rejected.value), 'outputStep': outputStep,
                                 'solveCpuSeconds': solveCpuSeconds})


def _SolveGeneralizedAlpha(self, stepSize: float, endTime: Optional[float] = None, spectralRadius: float = 0.9,
                           newtonTolerance: float = 1e-8) -> SimulationResult:
    """Integrate with the compiled generalized-alpha method at a fixed step (full Newton per step).

    Parameters
    ----------
    stepSize : float
        Time step in s; the output holds every step.
    endTime : float, optional
        Simulated time in s (default one wheel rotation).
    spectralRadius : float
        Spectral radius at infinity (Exudyn's default 0.9).
    newtonTolerance : float
        Newton stops when the acceleration residual is below this fraction of the accelerations.

    Returns
    -------
    SimulationResult
        ``info`` holds the steps and the number of steps repeated as two halves (Newton not converged).
    """
    endTime = RotationPeriod(ResolveDrive(parameters=self.parameters)) if endTime is None else float(endTime)
    _, y0, drive, _, motor = ReelChangerOde(self.parameters, self.contactOptions)
    nSteps = int(round(endTime / stepSize))
    out, alpha = np.zeros((nSteps + 1, 4)), np.zeros((nSteps + 1, 2))
    D = ctypes.POINTER(ctypes.c_double)
    y0 = np.ascontiguousarray(y0, dtype=float)
    t0, c0 = _time.perf_counter(), _time.process_time()
    halved = self._lib.solveGA(y0.ctypes.data_as(D), stepSize, nSteps, spectralRadius, newtonTolerance,
                                 out.ctypes.data_as(D), alpha.ctypes.data_as(D))
    solveSeconds, solveCpuSeconds = _time.perf_counter() - t0, _time.process_time() - c0
    if halved < 0:
        raise RuntimeError("CompiledReelChanger.SolveGeneralizedAlpha: Newton did not converge at stepSize / 2^20")
    time = np.arange(nSteps + 1) * stepSize
    return ResultFromStates(time, out.T, alpha, drive, motor, self.contactOptions, solveSeconds,
                            {'method': 'C generalized-alpha', 'stepSize': stepSize, 'spectralRadius': spectralRadius,
                             'steps': nSteps, 'halvedSteps': int(halved), 'solveCpuSeconds': solveCpuSeconds})


CompiledReelChanger.SolveGeneralizedAlpha = _SolveGeneralizedAlpha


def SolveReelChangerCompiled(parameters: Mapping[str, float], endTime: Optional[float] = None, rtol: float = 1e-6,
                             atol: float = 1e-8, outputStep: float = DEFAULT_STEP_SIZE,
                             contactOptions: ContactOptions = REGULARIZED) -> SimulationResult:
    """Build the compiled model and solve it once (see :class:`CompiledReelChanger`).

    Parameters
    ----------
    parameters : mapping
        Flat parameter set.
    endTime, rtol, atol, outputStep
        See :meth:`CompiledReelChanger.Solve`.
    contactOptions : ContactOptions
        Options of the contact law.
    """
    return CompiledReelChanger(parameters, contactOptions).Solve(endTime, rtol, atol, outputStep)
