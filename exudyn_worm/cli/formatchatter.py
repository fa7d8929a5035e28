"""Text of ``exudyn-worm chatter``: the chatter branch as a table (the numbers come from
:mod:`exudyn_worm.analysis.chatterbranch`; this module only formats them).
"""
from __future__ import annotations

from typing import List


__all__ = ['FormatBranch']


def FormatBranch(branch: 'ChatterBranch', title: str) -> List[str]:
    """Table of a :class:`~exudyn_worm.analysis.chatterbranch.ChatterBranch`.

    Parameters
    ----------
    branch : ChatterBranch
        The result.
    title : str
        First line.

    Returns
    -------
    list of str
    """
    lines = [title, '', f"  {branch.parameter:>12} {'Fn/Fstatic':>11} {'|phi2dd| rad/s2':>16} {'f Hz':>8}  orbit"]
    for p in branch.points:
        lines.append(f"  {p.value:12.6g} {p.info.get('forceFactor', float('nan')):11.3f} "
                     f"{p.info.get('maxWheelAcceleration', float('nan')):16.1f} {p.orbit.frequencyHz:8.2f}  "
                     f"{'stable' if p.stable else 'unstable'}")
    lines.append('')
    for h in branch.hopf:
        lines.append(f"Hopf point at {branch.parameter} = {h['value']:.6g} ({h['type']}); linear boundary "
                     f"{h['linearBoundary']:.6g} (difference {h['relativeDifference']:.2%})")
    if branch.folds:
        lines.append('Folds at ' + ', '.join(f'{f:.6g}' for f in branch.folds))
    for lo, hi in branch.coexistence:
        lines.append(f"Rest and chatter coexist for {branch.parameter} in [{lo:.6g}, {hi:.6g}]: linearly stable, "
                     f"but a disturbance can start chatter")
    for d in branch.disturbances:
        lines.append(f"  at {branch.parameter} = {d['value']:.6g}: linearly stable, but chatters after a worm-speed "
                     f"disturbance of {d['wormSpeed']:.3g} rad/s ({d['wormSpeedFraction']:.1%} of the motor speed)")
    if not branch.coexistence:
        lines.append('No range in which rest and stable chatter coexist was found on this branch.')
    lines += [f"Note: {m}" for m in branch.messages]
    return lines
