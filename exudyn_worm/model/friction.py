"""Friction laws of the worm mesh: the flank friction coefficient mu as a function of the sliding speed.

A law gives ``mu(v)`` for the three arithmetic backends of :mod:`exudyn_worm.model.contact` (plain Python floats,
numpy arrays, Exudyn symbolic expressions), its analytic slope ``dmu/dv`` and the friction at rest
``muStatic = mu(0)``. ``v`` is the sliding speed of the flanks in m/s, ``v = r1 |phi1'| / cos(gamma)``
(:meth:`~exudyn_worm.model.gear.WormGear.SlidingSpeed`): the worm's circumferential speed on its reference
radius divided by the cosine of the lead angle (the paper's friction state follows the worm speed, eq. (8);
so does the law).

Laws (``kind``)

- ``constant`` (:class:`ConstantFriction`): ``mu(v) = mu``; the paper's model and the default.
- ``stribeck`` (:class:`StribeckFriction`): ``mu(v) = mu + (muStatic - mu) exp(-(v / stribeckVelocity)^2)``.
- ``agma`` (:class:`AgmaFriction`): the sliding-speed curve of ANSI/AGMA 6034-B92 for a case-hardened steel
  worm and a bronze wheel, with ``V`` in ft/min::

      f = 0.150                                  V = 0
      f = 0.124 exp(-0.074 V^0.645)              0 < V <= 10 ft/min
      f = 0.103 exp(-0.110 V^0.450) + 0.012      V > 10 ft/min

  Source: ANSI/AGMA 6034-B92 as printed in Budynas and Nisbett, *Shigley's Mechanical Engineering Design*
  (chapter on worm gears). We could not open the standard or the book; the formula is checked against two
  secondary sources that we could open (see docs/friction.md): engineersedge.com, "AGMA WormGear Equations For
  Rating Factors" (metric form from ANSI/AGMA 6034-B92: 0.15 at rest, ``0.124 exp(-2.233 V^0.645)`` up to
  0.0508 m/s, ``0.103 exp(-1.185 V^0.45)`` above, V in m/s; its coefficients are ours converted exactly,
  but it omits the ``+ 0.012``) and a public implementation of Shigley's chapter 15 that has the ft/min form
  above including ``+ 0.012``. We follow the ft/min form with ``+ 0.012``. It is never a default.
  1 ft/min = 0.3048/60 m/s = 0.00508 m/s exactly.
- ``table`` (:class:`TableFriction`): measured ``(sliding speed in m/s, mu)`` points interpolated by a
  monotone piecewise cubic (PCHIP, Fritsch-Carlson: the interpolant does not overshoot the data between two
  points); outside the table's speed range the end value is held, and evaluating there with Python or
  numpy warns (:class:`FrictionTableRangeWarning`).

:func:`FrictionLaw` builds a law from its name and keyword values (the parameter keys ``frictionLaw``,
``mu``, ``muStatic``, ``stribeckVelocity``, ``frictionTable``).
"""
from __future__ import annotations

import math
import os
import re
import warnings
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from .._checks import CheckNonNegative, CheckPositive, Suggest
from .._files import MAX_TABLE_FILE_BYTES, ReadRegularFile

__all__ = ['FRICTION_LAWS', 'FT_PER_MIN', 'ConstantFriction', 'StribeckFriction', 'AgmaFriction', 'TableFriction',
           'FrictionLaw', 'FrictionTableRangeWarning', 'ReadFrictionTable']

#: names of the friction laws (the ``frictionLaw`` parameter)
FRICTION_LAWS = ('constant', 'stribeck', 'agma', 'table')
#: one foot per minute in m/s, exactly (international foot 0.3048 m)
FT_PER_MIN = 0.3048 / 60.


def _Sign(x):
    return float(x > 0) - float(x < 0)      # also for numpy scalars (their bools do not subtract)


#: plain-Python backend (floats)
MATH_OPS = SimpleNamespace(sin=math.sin, cos=math.cos, abs=abs, sign=_Sign, max=max, min=min,
                           where=lambda c, a, b: a if c else b, exp=math.exp, atan=math.atan)
#: numpy backend (arrays, element-wise)
NUMPY_OPS = SimpleNamespace(sin=np.sin, cos=np.cos, abs=np.abs, sign=np.sign, max=np.maximum, min=np.minimum,
                            where=np.where, exp=np.exp, atan=np.arctan)


class FrictionTableRangeWarning(UserWarning):
    """A friction table was evaluated outside its speed range: the end value was held."""


def _Ops(ops):
    """The backend: ``None`` means plain Python floats, :data:`~exudyn_worm.model.friction.MATH_OPS`."""
    if ops is None:
        return MATH_OPS
    return ops


def _IsSymbolic(v) -> bool:
    return not isinstance(v, (int, float, np.ndarray, np.number, list, tuple))


def _CheckSpeed(where: str, v):
    """Python and numpy speeds must be >= 0 m/s (symbolic ones are recorded as given)."""
    if v is None or isinstance(v, (str, bytes, bool, Mapping)):        # no speed, and not symbolic either
        raise TypeError(f"{where}: 'v' (sliding speed) must be a number >= 0 in m/s, an array of them or a "
                        f"symbolic expression, got {type(v).__name__} {v!r}")
    if _IsSymbolic(v):
        return v
    if np.ndim(v) == 0 and not isinstance(v, np.ndarray):
        return CheckNonNegative(where, 'v', v, 'm/s')
    array = np.asarray(v, dtype=float)
    bad = ~np.isfinite(array) | (array < 0)
    if bad.any():
        raise ValueError(f"{where}: 'v' (sliding speed) must be finite and >= 0 m/s everywhere, "
                         f"got {float(array[bad].flat[0]):g} m/s")
    return array


@dataclass(frozen=True)
class ConstantFriction:
    """Constant friction coefficient: ``mu(v) = mu`` (the paper's model; the default of every gear).

    Parameters
    ----------
    mu : float
        Flank friction coefficient, >= 0 (dimensionless).

    Raises
    ------
    ValueError, TypeError
        If ``mu`` is negative, non-finite or not a number.
    """
    mu: float
    kind = 'constant'

    def __post_init__(self):
        object.__setattr__(self, 'mu', CheckNonNegative('ConstantFriction', 'mu', self.mu, ''))

    @property
    def muStatic(self) -> float:
        """Friction coefficient at rest, mu(0) = mu."""
        return self.mu

    def Mu(self, v, ops=None):
        """Friction coefficient at sliding speed ``v`` (m/s): ``mu`` (a float, whatever the backend).

        Parameters
        ----------
        v : float, ndarray or symbolic
            Sliding speed in m/s, >= 0.
        ops : namespace, optional
            Arithmetic backend of :mod:`exudyn_worm.model.contact` (unused: the value is constant).
        """
        _CheckSpeed('ConstantFriction.Mu', v)
        return self.mu if np.ndim(v) == 0 or _IsSymbolic(v) else np.full(np.shape(v), self.mu)

    def Slope(self, v):
        """Slope dmu/dv in s/m at sliding speed ``v`` (m/s): 0.

        Parameters
        ----------
        v : float or ndarray
            Sliding speed in m/s, >= 0.
        """
        v = _CheckSpeed('ConstantFriction.Slope', v)
        return 0. if np.ndim(v) == 0 else np.zeros(np.shape(v))

    def ToDict(self) -> dict:
        """The law's parameters as the parameter keys name them (JSON-ready)."""
        return {'frictionLaw': self.kind, 'mu': self.mu}


@dataclass(frozen=True)
class StribeckFriction:
    """Stribeck friction: ``mu(v) = mu + (muStatic - mu) exp(-(v / stribeckVelocity)^2)``.

    Parameters
    ----------
    mu : float
        Kinetic friction coefficient (reached at high sliding speed), >= 0.
    muStatic : float
        Friction coefficient at rest, >= ``mu``.
    stribeckVelocity : float
        Sliding speed in m/s over which mu falls from ``muStatic`` towards ``mu``, > 0.

    Raises
    ------
    ValueError, TypeError
        For a negative or non-numeric value, ``muStatic < mu`` or ``stribeckVelocity <= 0``.
    """
    mu: float
    muStatic: float
    stribeckVelocity: float
    kind = 'stribeck'

    def __post_init__(self):
        w = 'StribeckFriction'
        object.__setattr__(self, 'mu', CheckNonNegative(w, 'mu', self.mu, ''))
        object.__setattr__(self, 'muStatic', CheckNonNegative(w, 'muStatic', self.muStatic, ''))
        object.__setattr__(self, 'stribeckVelocity', CheckPositive(w, 'stribeckVelocity', self.stribeckVelocity, 'm/s'))
        if self.muStatic < self.mu:
            raise ValueError(f"{w}: 'muStatic' (friction at rest) must be >= the kinetic 'mu' = {self.mu:g}, "
                             f"got {self.muStatic:g}")

    def Mu(self, v, ops=None):
        """Friction coefficient at sliding speed ``v`` in m/s.

        Parameters
        ----------
        v : float, ndarray or symbolic
            Sliding speed in m/s, >= 0.
        ops : namespace, optional
            Arithmetic backend (:data:`~exudyn_worm.model.friction.MATH_OPS`, ``NUMPY_OPS``, ``SymbolicOps()``); None:
            Python floats.
        """
        v = _CheckSpeed('StribeckFriction.Mu', v)
        ops = _Ops(ops)
        x = v * (1. / self.stribeckVelocity)
        return self.mu + (self.muStatic - self.mu) * ops.exp(-(x * x))

    def Slope(self, v):
        """Slope dmu/dv in s/m: ``-2 (muStatic - mu) v / stribeckVelocity^2 exp(-(v/stribeckVelocity)^2)``.

        Parameters
        ----------
        v : float or ndarray
            Sliding speed in m/s, >= 0.
        """
        v = _CheckSpeed('StribeckFriction.Slope', v)
        vs = self.stribeckVelocity
        return -2. * (self.muStatic - self.mu) * v / vs**2 * np.exp(-(v / vs)**2)

    def ToDict(self) -> dict:
        """The law's parameters as the parameter keys name them (JSON-ready)."""
        return {'frictionLaw': self.kind, 'mu': self.mu, 'muStatic': self.muStatic,
                'stribeckVelocity': self.stribeckVelocity}


@dataclass(frozen=True)
class AgmaFriction:
    """The ANSI/AGMA 6034-B92 friction curve over sliding speed (steel worm, bronze wheel); see the module text.

    ``mu(0) = 0.150``; ``0.124 exp(-0.074 V^0.645)`` for ``0 < V <= 10 ft/min``;
    ``0.103 exp(-0.110 V^0.450) + 0.012`` above, with ``V = v / FT_PER_MIN`` (v in m/s). The curve jumps at
    rest (0.150 to 0.124) and, slightly, at 10 ft/min (0.0894 to 0.0875): the source gives it so.
    """
    kind = 'agma'
    #: the source's coefficients: (factor, exponent coefficient, power, offset) below and above 10 ft/min
    LOW = (0.124, 0.074, 0.645, 0.)
    HIGH = (0.103, 0.110, 0.450, 0.012)
    REST = 0.150
    #: sliding speed in ft/min where the source switches branch
    SWITCH = 10.

    @property
    def muStatic(self) -> float:
        """Friction coefficient at rest, 0.150."""
        return self.REST

    def Mu(self, v, ops=None):
        """Friction coefficient at sliding speed ``v`` in m/s.

        Parameters
        ----------
        v : float, ndarray or symbolic
            Sliding speed in m/s, >= 0.
        ops : namespace, optional
            Arithmetic backend; None: Python floats.
        """
        v = _CheckSpeed('AgmaFriction.Mu', v)
        ops = _Ops(ops)
        V = v * (1. / FT_PER_MIN)
        branch = lambda a, b, p, c: a * ops.exp(-b * V**p) + c
        return ops.where(V > self.SWITCH, branch(*self.HIGH),
                         ops.where(V > 0., branch(*self.LOW), self.REST))

    def Slope(self, v):
        """Slope dmu/dv in s/m (analytic; -inf at v = 0, where the branch's power law has infinite slope).

        Parameters
        ----------
        v : float or ndarray
            Sliding speed in m/s, >= 0.
        """
        v = _CheckSpeed('AgmaFriction.Slope', v)
        V = np.asarray(v, dtype=float) / FT_PER_MIN
        with np.errstate(divide='ignore', invalid='ignore'):
            d = lambda a, b, p: -a * b * p * np.power(V, p - 1.) * np.exp(-b * V**p) / FT_PER_MIN
            s = np.where(V > self.SWITCH, d(*self.HIGH[:3]), np.where(V > 0., d(*self.LOW[:3]), -np.inf))
        return float(s) if np.ndim(v) == 0 else s

    def ToDict(self) -> dict:
        """The law's parameters as the parameter keys name them (JSON-ready)."""
        return {'frictionLaw': self.kind}


def _PchipSlopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Node slopes of the monotone cubic (Fritsch-Carlson with the weighted harmonic mean, as scipy's
    ``PchipInterpolator``; shape-preserving end conditions)."""
    h = np.diff(x)
    delta = np.diff(y) / h
    n = x.size
    if n == 2:
        return np.array([delta[0], delta[0]])
    d = np.zeros(n)
    for k in range(1, n - 1):
        if delta[k - 1] * delta[k] > 0:
            w1, w2 = 2 * h[k] + h[k - 1], h[k] + 2 * h[k - 1]
            d[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k])

    def End(h0, h1, m0, m1):
        s = ((2 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
        if np.sign(s) != np.sign(m0):
            return 0.
        if np.sign(m0) != np.sign(m1) and abs(s) > abs(3 * m0):
            return 3 * m0
        return s
    d[0] = End(h[0], h[1], delta[0], delta[1])
    d[-1] = End(h[-1], h[-2], delta[-1], delta[-2])
    return d


@dataclass(frozen=True)
class TableFriction:
    """Measured friction: ``(sliding speed in m/s, mu)`` points, interpolated by a monotone cubic (PCHIP).

    Between the points the interpolant keeps the data's shape (no overshoot: where mu falls from one point to the
    next it falls in between). Outside the table's speed range the end value is held; evaluating there with Python
    or numpy warns (:class:`FrictionTableRangeWarning`), a symbolic (recorded) law holds the end value silently.

    Parameters
    ----------
    points : sequence of (float, float)
        At least two ``(v, mu)`` pairs, speeds in m/s strictly increasing and >= 0, mu >= 0.

    Raises
    ------
    ValueError, TypeError
        For an empty or one-point table, pairs that are not two numbers, negative or non-finite values,
        speeds out of order (unsorted) or repeated (not strictly increasing).
    """
    points: Tuple[Tuple[float, float], ...]
    _segments: tuple = field(init=False, repr=False, compare=False)
    kind = 'table'

    def __post_init__(self):
        w = 'TableFriction'
        pts = self.points
        if isinstance(pts, (str, bytes)) or not isinstance(pts, (Sequence, np.ndarray)):
            raise TypeError(f"{w}: 'points' must be a sequence of (sliding speed in m/s, mu) pairs, got "
                            f"{type(pts).__name__} {pts!r}")
        if len(pts) < 2:
            raise ValueError(f"{w}: 'points' must hold at least 2 (sliding speed in m/s, mu) pairs, got {len(pts)}"
                             + ('' if len(pts) == 0 else f": {[tuple(p) for p in pts]!r}"))
        clean = []
        for i, p in enumerate(pts):
            if isinstance(p, (str, bytes)) or np.ndim(p) != 1 or len(p) != 2:
                raise TypeError(f"{w}: 'points[{i}]' must be a (sliding speed in m/s, mu) pair, got {p!r}")
            clean.append((CheckNonNegative(w, f'points[{i}] speed', p[0], 'm/s'),
                          CheckNonNegative(w, f'points[{i}] mu', p[1], '')))
        for i in range(1, len(clean)):
            if clean[i][0] < clean[i - 1][0]:
                raise ValueError(f"{w}: 'points' must be sorted by sliding speed (increasing, m/s): point {i} has "
                                 f"{clean[i][0]:g} m/s after {clean[i - 1][0]:g} m/s")
            if clean[i][0] == clean[i - 1][0]:
                raise ValueError(f"{w}: the sliding speeds of 'points' must increase strictly (m/s): points {i - 1} "
                                 f"and {i} both have {clean[i][0]:g} m/s")
        object.__setattr__(self, 'points', tuple(clean))
        object.__setattr__(self, '_segments', self._Segments())        # the cubic pieces, computed once

    @property
    def speeds(self) -> np.ndarray:
        """Table speeds in m/s."""
        return np.array([p[0] for p in self.points])

    @property
    def values(self) -> np.ndarray:
        """Table friction coefficients."""
        return np.array([p[1] for p in self.points])

    @property
    def muStatic(self) -> float:
        """Friction coefficient at rest, mu(0): the first point's value (held below the first speed)."""
        return float(self.points[0][1])

    def _Segments(self):
        """Per interval i: (x_i, a, b, c, d) with mu = a + b t + c t^2 + d t^3, t = v - x_i."""
        x, y = self.speeds, self.values
        m = _PchipSlopes(x, y)
        h = np.diff(x)
        delta = np.diff(y) / h
        c = (3 * delta - 2 * m[:-1] - m[1:]) / h
        d = (m[:-1] + m[1:] - 2 * delta) / h**2
        return tuple((float(x[i]), float(y[i]), float(m[i]), float(c[i]), float(d[i])) for i in range(h.size))

    def _Warn(self, v):
        x = self.speeds
        outside = np.asarray(v) > x[-1]
        below = np.asarray(v) < x[0]
        if np.any(outside) or np.any(below):
            vv = np.asarray(v, dtype=float)
            bad = float(vv[outside | below].flat[0])
            warnings.warn(f"TableFriction: sliding speed {bad:g} m/s is outside the table's range "
                          f"[{x[0]:g}, {x[-1]:g}] m/s; the end value mu = "
                          f"{self.values[-1] if bad > x[-1] else self.values[0]:g} is held",
                          FrictionTableRangeWarning, stacklevel=3)

    def Mu(self, v, ops=None):
        """Friction coefficient at sliding speed ``v`` in m/s (end values held outside the table).

        Parameters
        ----------
        v : float, ndarray or symbolic
            Sliding speed in m/s, >= 0.
        ops : namespace, optional
            Arithmetic backend; None: Python floats. The symbolic backend records a piecewise expression.
        """
        v = _CheckSpeed('TableFriction.Mu', v)
        ops = _Ops(ops)
        if not _IsSymbolic(v):
            self._Warn(v)
        x = self.speeds
        result = float(self.values[-1])                     # held above the last speed
        for i, (x0, a, b, c, d) in reversed(list(enumerate(self._segments))):
            t = v - x0
            result = ops.where(v <= float(x[i + 1]), a + t * (b + t * (c + t * d)), result)
        return ops.where(v < x[0], float(self.values[0]), result)

    def Slope(self, v):
        """Slope dmu/dv in s/m of the interpolant (0 outside the table's range).

        Parameters
        ----------
        v : float or ndarray
            Sliding speed in m/s, >= 0.
        """
        v = _CheckSpeed('TableFriction.Slope', v)
        vv = np.asarray(v, dtype=float)
        s = np.zeros(vv.shape)
        x = self.speeds
        for i, (x0, a, b, c, d) in enumerate(self._segments):
            inside = (vv >= x0) & (vv <= x[i + 1]) if i == 0 else (vv > x0) & (vv <= x[i + 1])
            t = vv - x0
            s = np.where(inside, b + t * (2 * c + 3 * d * t), s)
        return float(s) if np.ndim(v) == 0 else s

    def ToDict(self) -> dict:
        """The law's parameters as the parameter keys name them (JSON-ready)."""
        return {'frictionLaw': self.kind, 'frictionTable': [list(p) for p in self.points]}


def ReadFrictionTable(source: Union[str, os.PathLike, Sequence[Sequence[float]]]) -> TableFriction:
    """A :class:`TableFriction` from a text file of measured points, or from the pairs themselves.

    Parameters
    ----------
    source : str, os.PathLike or sequence of (float, float)
        A file with one ``sliding speed (m/s), mu`` pair per line, separated by a comma, a semicolon or blanks
        (blank lines, lines starting with ``#`` and a first line that is not numeric, a header, are skipped); or
        the pairs.

    Returns
    -------
    TableFriction

    Raises
    ------
    ValueError
        If the file cannot be read or a line is not two numbers (the message gives the file and line), or the
        table is invalid (:class:`TableFriction`).
    """
    if not isinstance(source, (str, os.PathLike)):
        return TableFriction(tuple(source))
    w = 'ReadFrictionTable'
    raw = ReadRegularFile(source, MAX_TABLE_FILE_BYTES, f"{w}: the friction table {str(source)!r}", 'a table file')
    try:
        lines = raw.decode('utf-8').splitlines()
    except UnicodeDecodeError as error:
        raise ValueError(f"{w}: the friction table {str(source)!r} is not UTF-8 text ({error.reason})") from None
    points, first = [], True
    for number, line in enumerate(lines, start=1):
        text = line.strip()
        if not text or text.startswith('#'):
            continue
        fields = [f for f in re.split(r'[,;\s]+', text) if f]
        header, first = first, False
        try:
            values = [float(f) for f in fields]
        except ValueError:
            if header:
                continue                                        # the first line may name the columns
            raise ValueError(f"{w}: {source}, line {number}: expected 'sliding speed (m/s), mu', "
                             f"got {text!r}") from None
        if len(values) != 2:
            raise ValueError(f"{w}: {source}, line {number}: expected 2 numbers 'sliding speed (m/s), mu', "
                             f"got {len(values)}: {text!r}")
        points.append(tuple(values))
    return TableFriction(tuple(points))


def FrictionLaw(kind: str = 'constant', mu: Optional[float] = None, muStatic: Optional[float] = None,
                stribeckVelocity: Optional[float] = None, table: Optional[Sequence[Tuple[float, float]]] = None
                ) -> Union['ConstantFriction', 'StribeckFriction', 'AgmaFriction', 'TableFriction']:
    """Build a friction law from its name and values (the parameter keys ``frictionLaw mu muStatic
    stribeckVelocity frictionTable``).

    Parameters
    ----------
    kind : str
        One of :data:`FRICTION_LAWS`: ``constant`` (needs ``mu``), ``stribeck`` (``mu``, ``muStatic``,
        ``stribeckVelocity``), ``agma`` (no values), ``table`` (``table``).
    mu : float, optional
        Constant or kinetic friction coefficient, >= 0.
    muStatic : float, optional
        Friction at rest (Stribeck), >= ``mu``.
    stribeckVelocity : float, optional
        Stribeck sliding speed in m/s, > 0.
    table : sequence of (float, float), optional
        ``(sliding speed in m/s, mu)`` points.

    Returns
    -------
    ConstantFriction, StribeckFriction, AgmaFriction or TableFriction

    Raises
    ------
    ValueError
        For an unknown law (with the nearest name), a missing value, or a value the law does not use.
    """
    w = 'FrictionLaw'
    if not isinstance(kind, str):
        raise TypeError(f"{w}: 'kind' (frictionLaw) must be one of {', '.join(FRICTION_LAWS)}, got "
                        f"{type(kind).__name__} {kind!r}")
    if kind not in FRICTION_LAWS:
        raise ValueError(f"{w}: 'kind' (frictionLaw) must be one of {', '.join(FRICTION_LAWS)}, got {kind!r}"
                         f"{Suggest(kind, FRICTION_LAWS)}")
    given = {'mu': mu, 'muStatic': muStatic, 'stribeckVelocity': stribeckVelocity, 'table': table}
    needs = {'constant': ('mu',), 'stribeck': ('mu', 'muStatic', 'stribeckVelocity'), 'agma': (), 'table': ('table',)}
    allowed = needs[kind] + (('mu',) if kind in ('agma', 'table') else ())   # mu stays the gear's nominal value
    missing = [k for k in needs[kind] if given[k] is None]
    if missing:
        raise ValueError(f"{w}: the '{kind}' law needs {', '.join(repr(k) for k in missing)}, got none")
    unused = [k for k, v in given.items() if v is not None and k not in allowed]
    if unused:
        raise ValueError(f"{w}: the '{kind}' law does not use {', '.join(repr(k) for k in unused)}; it takes "
                         f"{', '.join(repr(k) for k in needs[kind]) or 'no values'}")
    if kind == 'constant':
        return ConstantFriction(mu)
    if kind == 'stribeck':
        return StribeckFriction(mu=mu, muStatic=muStatic, stribeckVelocity=stribeckVelocity)
    if kind == 'agma':
        return AgmaFriction()
    return TableFriction(tuple(table))
