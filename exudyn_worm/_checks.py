"""Argument checks shared by every public constructor and builder.

Each check raises ``ValueError`` (or ``TypeError``) whose message names the calling
function, the argument, the allowed range with its unit and the value received, e.g.
``WormGear: 'backlash' must be >= 0 m, got -0.001``.
"""
import difflib
import math
import re
from collections.abc import Mapping
from pathlib import Path
from numbers import Real
from typing import Optional

import numpy as np

__all__ = ['JsonNumber', 'CheckReal', 'CheckPositive', 'CheckNonNegative', 'CheckAngle', 'CheckRange', 'CheckArray',
           'CheckOutputFolder', 'CheckBool', 'CheckMapping', 'CheckName', 'CheckSystem', 'Suggest', 'WarningText']


#: a warning's leading Python name (``SimulateReelChanger: ...``): what a Python caller reads, not a command-line user
_API_PREFIX = re.compile(r'^[A-Z][A-Za-z0-9]*(?:\.[A-Za-z_][A-Za-z0-9_]*)?: ')


def WarningText(message: str) -> str:
    """A warning's text for a user of the command line or of a study: the leading name of the Python function or
    class that issued it (``SimulateReelChanger: ``) left out; the rest names the drive's quantity.

    Parameters
    ----------
    message : str
        The warning's message.
    """
    return _API_PREFIX.sub('', ' '.join(str(message).split()), count=1)


def JsonNumber(x) -> Optional[float]:
    """``float(x)``, or None where it is not finite: JSON has no inf or nan.

    Parameters
    ----------
    x : float
        A number.
    """
    x = float(x)
    return x if math.isfinite(x) else None


def _Format(value) -> str:
    return repr(value) if not isinstance(value, float) else f'{value:g}'


def CheckReal(where: str, name: str, value, unit: str = '') -> float:
    """Return ``value`` as float; raise if it is not a finite real number."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{where}: '{name}' must be a real number{' in ' + unit if unit else ''}, "
                        f"got {type(value).__name__} {value!r}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{where}: '{name}' must be finite{' (' + unit + ')' if unit else ''}, got {value}")
    return value


def CheckRange(where: str, name: str, value, low=None, high=None, unit: str = '',
               lowOpen: bool = False, highOpen: bool = False) -> float:
    """Check ``low <= value <= high`` (open ends when ``lowOpen``/``highOpen``)."""
    value = CheckReal(where, name, value, unit)
    badLow = low is not None and (value <= low if lowOpen else value < low)
    badHigh = high is not None and (value >= high if highOpen else value > high)
    if badLow or badHigh:
        u = ' ' + unit if unit else ''
        if low is not None and high is not None:
            text = f"in {'(' if lowOpen else '['}{_Format(low)}, {_Format(high)}{')' if highOpen else ']'}{u}"
        elif low is not None:
            text = f"{'>' if lowOpen else '>='} {_Format(low)}{u}"
        else:
            text = f"{'<' if highOpen else '<='} {_Format(high)}{u}"
        raise ValueError(f"{where}: '{name}' must be {text}, got {_Format(value)}{u}")
    return value


def CheckPositive(where: str, name: str, value, unit: str = '') -> float:
    """Check ``value > 0``."""
    return CheckRange(where, name, value, low=0., unit=unit, lowOpen=True)


def CheckNonNegative(where: str, name: str, value, unit: str = '') -> float:
    """Check ``value >= 0``."""
    return CheckRange(where, name, value, low=0., unit=unit)


def CheckAngle(where: str, name: str, value) -> float:
    """Check an angle in the open interval (0, 90 deg), given in radians."""
    value = CheckReal(where, name, value, 'rad')
    if not 0. < value < 0.5 * math.pi:
        raise ValueError(f"{where}: '{name}' must be in (0, pi/2) rad, i.e. (0, 90) deg, "
                         f"got {value:g} rad ({math.degrees(value):g} deg)")
    return value


def CheckArray(where: str, name: str, value, low: float = 0., unit: str = '', lowOpen: bool = True):
    """Scalar or array argument of a broadcasting function: a scalar goes through :func:`CheckRange` and
    comes back as float; an array must be real, finite and ``> low`` (``>= low`` if not ``lowOpen``)
    everywhere and comes back as a float ndarray. The message names the first offending value."""
    if np.ndim(value) == 0 and not isinstance(value, np.ndarray):
        return CheckRange(where, name, value, low=low, unit=unit, lowOpen=lowOpen)
    array = np.asarray(value)
    if array.dtype.kind not in 'iuf':
        raise TypeError(f"{where}: '{name}' must be real numbers{' in ' + unit if unit else ''}, "
                        f"got an array of dtype {array.dtype}")
    array = array.astype(float, copy=False)
    bad = ~np.isfinite(array) | ((array <= low) if lowOpen else (array < low))
    if bad.any():
        u = ' ' + unit if unit else ''
        raise ValueError(f"{where}: '{name}' must be finite and {'>' if lowOpen else '>='} {_Format(float(low))}{u} "
                         f"everywhere, got {_Format(float(array[bad].flat[0]))}{u}")
    return array


def CheckOutputFolder(where: str, name: str, path) -> Path:
    """Create folder ``path`` if missing and check that it is writable, before any computation.

    Returns the resolved ``pathlib.Path``; raises ``ValueError`` with one line naming ``where`` and ``name``.
    """
    folder = Path(path).resolve()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        probe = folder / '.write-test'
        probe.touch()
        probe.unlink()
    except OSError as error:
        raise ValueError(f"{where}: cannot write to {name} {str(path)!r}: {error.strerror or error}") from None
    return folder


def CheckBool(where: str, name: str, value) -> bool:
    """Return ``value`` if it is a bool (numpy bools included); raise ``TypeError`` otherwise (``'yes'``, 1)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{where}: '{name}' must be True or False, got {type(value).__name__} {value!r}")
    return bool(value)


def CheckMapping(where: str, name: str, value, example: str = "GetPreset('reel-P1')", preset: bool = True) -> Mapping:
    """Return ``value`` if it is a mapping (a flat parameter dictionary); raise ``TypeError`` otherwise.

    With ``preset``, a string is taken for a preset name: the message suggests ``GetPreset(value)``.
    """
    if isinstance(value, Mapping):
        return value
    hint = (f"; for the preset {value!r} pass GetPreset({value!r})" if preset and isinstance(value, str) else
            f", e.g. {example}")
    raise TypeError(f"{where}: '{name}' must be a mapping of parameter names to values (SI){hint}, "
                    f"got {type(value).__name__}{'' if isinstance(value, str) else ' ' + _Short(value)}")


def _Short(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + '...'


def Suggest(word, choices) -> str:
    """`` (did you mean 'X'?)`` for a near miss of ``word`` among ``choices`` (case is ignored first), else ''."""
    choices = [str(c) for c in choices]
    same = [c for c in choices if c.lower() == str(word).lower()]
    close = same or difflib.get_close_matches(str(word), choices, n=1, cutoff=0.75)
    if not close:
        return ''
    return f" (did you mean {' or '.join(repr(c) for c in close)}?)"


def CheckName(where: str, name: str, value) -> str:
    """Return ``value`` if it is a string (an Exudyn item name); raise ``TypeError`` otherwise."""
    if not isinstance(value, str):
        raise TypeError(f"{where}: '{name}' must be a string (the name of the Exudyn item), got "
                        f"{type(value).__name__} {value!r}")
    return value


def CheckSystem(where: str, mbs, name: str = 'mbs'):
    """Return ``mbs`` if it is an ``exudyn.MainSystem``; raise ``TypeError`` otherwise.

    An object with a MainSystem attribute ``mbs`` (e.g. a :class:`~exudyn_worm.builders.oneangle.ReelChangerModel`)
    is named in the message, so that the caller can pass ``model.mbs``.
    """
    import exudyn
    if isinstance(mbs, exudyn.MainSystem):
        return mbs
    hint = (f" (this {type(mbs).__name__} holds one: pass its .mbs)"
            if isinstance(getattr(mbs, 'mbs', None), exudyn.MainSystem) else
            " (SC = exudyn.SystemContainer(); mbs = SC.AddSystem())")
    raise TypeError(f"{where}: '{name}' must be an exudyn.MainSystem{hint}, got {type(mbs).__name__}")
