"""How large a disturbance starts the chatter of a drive that is linearly stable while lowering: the smallest
worm-speed kick that ends in chatter (:func:`SmallestDisturbance`, by bisection on time simulations from the steady
state) and the verdict of ``exudyn-worm check --disturbance`` (:func:`ChattersAfterDisturbance`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict

import numpy as np

from .chatter import FindSteadyChatter
from .lowering import BuildLoweringModel, SettleLowering, _MeshAt
from .periodic import ShootingError
from ..._checks import JsonNumber
from ...drive.wholedrive import CheckDrive, Drive
from ..stability.drivestability import AnalyzeDrive

__all__ = ['COEXISTENCE_KICK', 'SmallestDisturbance', 'DisturbanceVerdict', 'ChattersAfterDisturbance']
#: worm-speed kick (fraction of the motor speed) tried when the drive is linearly stable on the whole range
COEXISTENCE_KICK = 0.5


def SmallestDisturbance(drive: Drive, duration: float = 3.0, largest: float = 0.5,
                        steps: int = 8) -> float:
    """Smallest initial worm-speed disturbance (fraction of the motor speed) after which the lowering phase ends
    in chatter, by bisection on time simulations from the steady state; ``math.inf`` if ``largest`` does not.

    A run ends in chatter if the mesh still loses contact (largest normal force at least twice the static force)
    in its last 0.2 s. The basin of chatter need not be an interval of kicks; the bisection assumes it is.

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty (linearly stable but it may chatter).
    duration : float
        Simulated time in s per trial, >= 0.5.
    largest : float
        Largest disturbance tried.
    steps : int
        Bisection steps.

    Returns
    -------
    float
    """
    if not duration >= 0.5:
        raise ValueError(f"SmallestDisturbance: 'duration' must be >= 0.5 s, got {duration!r}")
    model = BuildLoweringModel(drive)

    def Chatters(kick):
        # chatter: the mesh still loses contact (largest normal force >= twice the static force) in the last 0.2 s;
        # a decaying transient of a linearly stable drive has long stayed in contact by then
        SettleLowering(model, duration, kick=kick, store=True)
        s = model.connector.StoredStates(model.mbs)
        last = s['time'] >= s['time'][-1] - 0.2
        mesh = _MeshAt(model.connector, s, last)
        return float(np.max(np.abs(mesh.normalForce))) >= 2. * model.staticNormalForce

    if not Chatters(largest):
        return math.inf
    a, b = 0., largest
    for _ in range(steps):
        m = 0.5 * (a + b)
        a, b = (a, m) if Chatters(m) else (m, b)
    return b


@dataclass
class DisturbanceVerdict:
    """Result of :func:`ChattersAfterDisturbance`.

    Attributes
    ----------
    linearlyStable : bool
        Verdict of the linearized lowering phase (S = -1).
    chatterFound : bool
        Whether a steady chatter orbit was found (after a kick of :data:`COEXISTENCE_KICK` if linearly stable).
    smallestDisturbance : float
        Smallest worm-speed kick in rad/s that ends in chatter (``inf`` if none up to the largest tried; 0 if the
        drive is linearly unstable).
    forceFactor, maxWheelAcceleration, frequencyHz : float
        Amplitude and frequency of the chatter orbit (nan if none).
    text : str
        One line for a report, e.g. "linearly stable, but chatters after a worm-speed disturbance of 8.3 rad/s".
    """
    linearlyStable: bool
    chatterFound: bool
    smallestDisturbance: float
    forceFactor: float
    maxWheelAcceleration: float
    frequencyHz: float
    text: str

    def ToDict(self) -> Dict:
        """JSON-ready dictionary (the ``disturbance`` object of ``exudyn-worm check --json``); infinite or
        undefined numbers are None.

        Returns
        -------
        dict
        """
        return {'linearlyStable': self.linearlyStable, 'chatterFound': self.chatterFound,
                'smallestDisturbance': JsonNumber(self.smallestDisturbance), 'forceFactor': JsonNumber(self.forceFactor),
                'maxWheelAcceleration': JsonNumber(self.maxWheelAcceleration), 'frequencyHz': JsonNumber(self.frequencyHz),
                'text': self.text}


def ChattersAfterDisturbance(drive: Drive) -> DisturbanceVerdict:
    """Does a drive chatter in the lowering phase, and if it is linearly stable, after which disturbance?

    Meant for a design check: a linearly stable drive may still chatter after a disturbance where rest and chatter
    coexist (e.g. with backlash, see docs/chatter-amplitude.md).

    Parameters
    ----------
    drive : Drive
        A drive with the reel changer's duty.

    Returns
    -------
    DisturbanceVerdict
    """
    drive = CheckDrive('ChattersAfterDisturbance', drive)
    stable = bool(AnalyzeDrive(drive).State(-1).stable)
    nan = math.nan
    try:
        orbit = FindSteadyChatter(drive, kick=COEXISTENCE_KICK if stable else 0.01)
    except ShootingError:
        text = ('linearly stable, and a worm-speed kick of {:.0%} of the motor speed dies out'.format(COEXISTENCE_KICK)
                if stable else 'linearly unstable, but no steady chatter orbit was found')
        return DisturbanceVerdict(stable, False, math.inf if stable else nan, nan, nan, nan, text)
    speed = float(drive.motor.speed)
    kick = SmallestDisturbance(drive) * speed if stable else 0.
    amplitude = (f"normal force up to {orbit.info['forceFactor']:.2f} times the static force, |phi2''| up to "
                 f"{orbit.info['maxWheelAcceleration']:.3g} rad/s^2, {orbit.frequencyHz:.1f} Hz")
    if not stable:
        text = f"linearly unstable: chatters ({amplitude})"
    elif math.isfinite(kick):
        text = f"linearly stable, but chatters after a worm-speed disturbance of {kick:.3g} rad/s ({amplitude})"
    else:
        text = (f"linearly stable; a chatter orbit exists ({amplitude}), but no kick from rest up to "
                f"{0.5 * speed:.3g} rad/s reached it")
    return DisturbanceVerdict(stable, True, kick, orbit.info['forceFactor'], orbit.info['maxWheelAcceleration'],
                              orbit.frequencyHz, text)
