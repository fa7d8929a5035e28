"""Largest real part of the roots of many quartics at once: the eigenvalue of a stability chart's grid point.

A vectorized closed-form quartic solution (Ferrari, real arithmetic) on the time-scaled polynomial, polished by
Newton steps; points whose residual stays large fall back to numpy's batched eigenvalues of the companion matrix.
Used by :mod:`exudyn_worm.analysis.charts.stabilitychart` (the paper's polynomial (15)); numpy only.
"""
from __future__ import annotations

import numpy as np

__all__ = ['MaxRealPart']

#: relative residual above which a polished closed-form root is recomputed with numpy's eigvals
_ROOT_RESIDUAL_TOL = 1e-10


def _LargestCubicRoot(B, C, D):
    """Largest real root of m^3 + B m^2 + C m + D (real arrays), trigonometric / Cardano form."""
    # (numpy's power is slow for exponents other than 2: cubes are written as products)
    B2 = B * B
    P = C - B2 / 3.
    Q = B * (2. * B2 / 27. - C / 3.) + D
    delta = Q * Q / 4. + P * P * P / 27.
    three = delta < 0                                                   # three real roots (then P < 0)
    Pn = np.where(three, P, -1.)
    arg = np.clip(1.5 * Q / Pn * np.sqrt(-3. / Pn), -1., 1.)
    wThree = 2. * np.sqrt(-Pn / 3.) * np.cos(np.arccos(arg) / 3.)
    u = np.cbrt(-Q / 2. - np.copysign(np.sqrt(np.where(three, 0., delta)), Q))
    wOne = np.where(u != 0, u - P / (3. * np.where(u != 0, u, 1.)), 0.)
    m = np.where(three, wThree, wOne) - B / 3.
    for _ in range(2):                                                  # Newton polish of the real root
        f = ((m + B) * m + C) * m + D
        df = (3. * m + 2. * B) * m + C
        m = m - np.where(df != 0, f / np.where(df != 0, df, 1.), 0.)
    return m


def _MaxRealPartScaled(a):
    """Largest real part of the roots of t^4 + a0 t^3 + a1 t^2 + a2 t + a3 (real arrays (4, N)).

    Ferrari with the resolvent's largest real root m (m > 0 whenever q != 0, since the resolvent is
    -q^2/8 < 0 at m = 0), all in real arithmetic; the root of largest real part is then polished by three
    complex Newton steps on the quartic. Returns (value, relative residual).
    """
    a0, a1, a2, a3 = a
    sq = a0 * a0
    p = a1 - 3. * sq / 8.
    q = a2 - a0 * a1 / 2. + sq * a0 / 8.
    r = a3 - a0 * a2 / 4. + sq * a1 / 16. - 3. * sq * sq / 256.
    m = np.maximum(_LargestCubicRoot(p, p * p / 4. - r, -q * q / 8.), 0.)
    s = np.sqrt(2. * m)
    h = np.where(s > 0, q / (2. * np.where(s > 0, s, 1.)), 0.)
    s2 = s * s
    best_re = np.full(a0.shape, -np.inf)
    best_im = np.zeros(a0.shape)
    for sign in (+1., -1.):
        # t^2 - sign s t + (p/2 + m + sign h) = 0: roots sign s/2 +- sqrt(disc)/2
        disc = s2 - 4. * (p / 2. + m + sign * h)
        root = np.sqrt(np.abs(disc)) / 2.
        re = sign * s / 2. + np.where(disc >= 0, root, 0.)
        im = np.where(disc >= 0, 0., root)
        better = re > best_re
        best_re = np.where(better, re, best_re)
        best_im = np.where(better, im, best_im)
    z = (best_re - a0 / 4.) + 1j * best_im
    for _ in range(3):                                                  # Newton polish (Horner)
        P = (((z + a0) * z + a1) * z + a2) * z + a3
        dP = ((4. * z + 3. * a0) * z + 2. * a1) * z + a2
        ok = dP != 0
        z = z - np.where(ok, P / np.where(ok, dP, 1.), 0.)
    P = (((z + a0) * z + a1) * z + a2) * z + a3
    mag = np.abs(z)
    scale = (((mag + np.abs(a0)) * mag + np.abs(a1)) * mag + np.abs(a2)) * mag + np.abs(a3)
    with np.errstate(divide='ignore', invalid='ignore'):
        residual = np.abs(P) / np.where(scale > 0, scale, 1.)
    return z.real, np.where(np.isfinite(residual), residual, np.inf)


def MaxRealPart(b, returnFallback: bool = False):
    """Largest real part of the roots of the quartic (15) for many coefficient sets at once, in 1/s.

    Time is scaled by omega = b4^(1/4) (the largest ``|b_k|^(1/k)`` if b4 <= 0), the scaled quartic is
    solved in closed form (Ferrari, real arithmetic), the root of largest real part is polished by three
    Newton steps, and where its relative residual stays above 1e-10 (or where a root of nearly equal real
    part could have been missed) numpy's batched ``eigvals`` of the companion matrix is used instead.

    Parameters
    ----------
    b : array_like
        Coefficients b1..b4, shape ``(4, ...)``, finite.
    returnFallback : bool, optional
        Also return where the ``eigvals`` fallback was used.

    Returns
    -------
    ndarray
        Shape ``(...)``; with ``returnFallback`` a pair (values, bool array of the same shape).
    """
    b = np.asarray(b, dtype=float)
    if b.shape[:1] != (4,):
        raise ValueError(f"MaxRealPart: 'b' must have shape (4, ...), got {b.shape}")
    if not np.all(np.isfinite(b)):
        raise ValueError("MaxRealPart: 'b' must be finite")
    shape = b.shape[1:]
    bf = b.reshape(4, -1)
    absb = np.abs(bf)
    omega = np.sqrt(np.sqrt(absb[3]))
    other = np.maximum(np.maximum(absb[0], np.sqrt(absb[1])), np.cbrt(absb[2]))
    omega = np.where(bf[3] > 0, omega, np.maximum(omega, other))
    omega = np.where(omega > 0, omega, 1.)
    o2 = omega * omega
    a = np.array([bf[0] / omega, bf[1] / o2, bf[2] / (o2 * omega), bf[3] / (o2 * o2)])   # scaled coefficients
    value, residual = _MaxRealPartScaled(a)
    bad = ~(residual <= _ROOT_RESIDUAL_TOL)
    if bad.any():
        idx = np.nonzero(bad)[0]
        comp = np.zeros((idx.size, 4, 4))
        comp[:, 0, :] = -a[:, idx].T
        comp[:, 1, 0] = comp[:, 2, 1] = comp[:, 3, 2] = 1.
        value[idx] = np.linalg.eigvals(comp).real.max(axis=1)
    value = (value * omega).reshape(shape)
    return (value, bad.reshape(shape)) if returnFallback else value
