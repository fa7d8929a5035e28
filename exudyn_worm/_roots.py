"""A bracketing scalar root finder (so that the package does not import scipy.optimize, 1 s of start-up)."""
from __future__ import annotations

import math
from typing import Callable

__all__ = ['FindRoot']


def FindRoot(f: Callable[[float], float], a: float, b: float, xtol: float = 1e-15, maxIterations: int = 200) -> float:
    """Root of ``f`` in [a, b] with f(a), f(b) of opposite sign (Illinois regula falsi, bisection fallback).

    Converges in one or two steps where ``f`` is linear (the contact law in contact) and never leaves the
    bracket. Stops when the bracket is narrower than ``xtol`` (absolute, plus 4 ulp of the root) or ``f`` is 0.

    Raises
    ------
    ValueError
        If f(a) and f(b) have the same sign or are not finite.
    """
    fa, fb = f(a), f(b)
    if not (math.isfinite(fa) and math.isfinite(fb)) or (fa != 0 and fb != 0 and (fa > 0) == (fb > 0)):
        raise ValueError(f"FindRoot: f(a) and f(b) must be finite with opposite signs, got f({a:g}) = {fa:g}, "
                         f"f({b:g}) = {fb:g}")
    if fa == 0:
        return a
    if fb == 0:
        return b
    for _ in range(maxIterations):
        tol = xtol + 4 * math.ulp(max(abs(a), abs(b)))
        if abs(b - a) <= tol:
            break
        c = (a * fb - b * fa) / (fb - fa)
        if not (min(a, b) < c < max(a, b)):
            c = 0.5 * (a + b)
        fc = f(c)
        if fc == 0 or abs(c - b) <= tol:
            return c
        if (fc > 0) != (fb > 0):      # root between b and c: b becomes the other end
            a, fa = b, fb
        else:                         # same side as b: halve the stale end's value (Illinois)
            fa *= 0.5
        b, fb = c, fc
    return b if abs(fb) <= abs(fa) else a
