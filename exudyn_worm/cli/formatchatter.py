"""Text of ``exudyn-worm chatter``: the chatter branch as a table, or the steady chatter at the lowering operating
point (the numbers come from :mod:`exudyn_worm.analysis.orbits.chatterbranch` and
:func:`~exudyn_worm.analysis.orbits.chatter.SteadyChatterSummary`; this module only formats them).
"""
from __future__ import annotations

from typing import List

from ..analysis.orbits.periodic import TRIVIAL_MULTIPLIER_TOLERANCE
from ..items.bearings import BEARING_LOADS

__all__ = ['FormatBranch', 'FormatSteadyChatter']


def _OrbitVerdict(orbit, stable: bool) -> str:
    """A branch point's stability: decided only where the largest non-trivial multiplier lies farther from the unit
    circle than the trivial multiplier's error (the monodromy's accuracy); else 'undecided' with both numbers."""
    error = orbit.trivialMultiplierError
    if not orbit.accurate:
        return f"INACCURATE (trivial multiplier off by {error:.2g})"
    if not orbit.stabilityDecided:
        mu = max((abs(complex(m)) for m in orbit.nontrivialMultipliers), default=0.)
        return f"undecided (|mu| {mu:.4f}: {abs(mu - 1.):.2g} from 1, error {error:.2g})"
    return 'stable' if stable else 'unstable'


def _Row(value: float, amplitude: dict, frequencyHz: float, loads: list, width: int) -> str:
    """A branch table's row up to its verdict."""
    row = ''.join(f" {amplitude.get(k, float('nan')) / 1e3:15.3f}" for k, _ in loads)
    return (f"  {value:{width}.6g} {amplitude.get('forceFactor', float('nan')):11.3f} "
            f"{amplitude.get('maxWheelAcceleration', float('nan')):16.1f} {frequencyHz:8.2f}{row}  ")


def FormatBranch(branch: 'ChatterBranch', title: str) -> List[str]:
    """Table of a :class:`~exudyn_worm.analysis.orbits.chatterbranch.ChatterBranch`.

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
    # the 3D model's points carry the largest bearing loads: one more column each, in kN
    loads = [(k, text) for k, text in BEARING_LOADS
             if any(k in p.info for p in branch.points) or any(k in s['amplitude'] for s in branch.simulated)]
    head = ''.join(f" {text + ' kN':>15}" for _, text in loads)
    width = max(12, len(branch.parameter))      # a long name (wheelRadialStiffness) widens the first column
    lines = [title, '', f"  {branch.parameter:>{width}} {'Fn/Fstatic':>11} {'|phi2dd| rad/s2':>16} {'f Hz':>8}{head}"
                        f"  orbit"]
    rows = []
    for p in branch.points:
        # an orbit accepted above the shooting tolerance (the 3D model's natural-parameter points) says how closely
        # it closes
        closes = '' if p.orbit.converged is not False else f", residual {p.orbit.residual:.1g}"
        rows.append((p.value, _Row(p.value, p.info, p.orbit.frequencyHz, loads, width)
                     + _OrbitVerdict(p.orbit, p.stable) + closes))
    for s in branch.simulated:        # the 3D model's points without an orbit: the settled run's vibration
        verdict = ('rest (linearly stable; the settled run stays in contact)' if s['method'] == 'rest' else
                   'long simulation, undecided (no orbit: ' + ('the run still in contact' if s['residual'] is None
                                                                else f"shooting residual {s['residual']:.2g}") + ')')
        rows.append((s['value'], _Row(s['value'], s['amplitude'], s['frequencyHz'], loads, width) + verdict))
    lines += [text for _, text in (sorted(rows, key=lambda r: r[0]) if branch.simulated else rows)]
    if loads:
        lines.append('  (bearing loads: the largest over each orbit)')
    if any(not p.orbit.accurate for p in branch.points):
        lines.append(f"  (INACCURATE: the trivial Floquet multiplier, 1 in exact arithmetic, is off by more than "
                     f"{TRIVIAL_MULTIPLIER_TOLERANCE:g}: that orbit's stability is not decided)")
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




def FormatSteadyChatter(summary: dict, title: str) -> List[str]:
    """The lines of one steady chatter orbit: ``title``, the model, the period, the amplitudes, the Floquet
    multipliers and, for the 3D model, the largest bearing loads, from ``summary``.

    Parameters
    ----------
    summary : dict
        From :func:`~exudyn_worm.analysis.orbits.chatter.SteadyChatterSummary` (SI units).
    title : str
        The first line (what was analysed).

    Returns
    -------
    list of str
        The lines to print.
    """
    a = summary['amplitude']
    model = ('3D model (worm and wheel as rigid bodies on their shafts\' bearings)' if summary['model'] == '3D'
             else 'one-angle model')
    orbit = summary.get('method', 'shooting') == 'shooting'
    lines = [title, f"  {model}; motor {summary['motorSpeed']:.6g} rad/s, load torque {summary['loadTorque']:.6g} N*m"]
    if 'method' in summary:                  # the 3D model: how the result was found
        lines.append(f"  method: {summary['method']}; {summary['reason']}")
    lines += ['',
              f"  period                  {summary['periodS'] * 1e3:10.4f} ms ({summary['frequencyHz']:.3f} Hz)",
              f"  max normal force        {summary['maxNormalForce'] / 1e3:10.3f} kN "
              f"({a['forceFactor']:.3f} x the static {summary['staticNormalForce'] / 1e3:.3f} kN)",
              f"  max |phi2''|            {a['maxWheelAcceleration']:10.2f} rad/s^2"]
    if 'maxWormSpeed' in a:
        lines.append(f"  worm speed              {a['minWormSpeed']:10.3f} to {a['maxWormSpeed']:.3f} rad/s")
    else:
        lines.append(f"  min worm speed          {a['minWormSpeed']:10.3f} rad/s")
    if orbit:
        multipliers = ', '.join(f'{m:.4g}' for m in summary['multipliers'][:4])
        error = summary['trivialMultiplierError']
        if not summary.get('accurate', True):
            tail = (f"trivial one off by {error:.2g}, above the tolerance {TRIVIAL_MULTIPLIER_TOLERANCE:g}): INACCURATE "
                    f"orbit, its stability is not decided (exudyn-worm simulate is the better guide here)")
        elif not summary.get('stabilityDecided', True):
            tail = (f"trivial one off by {error:.2g}, no less than the largest's distance from the unit circle): the "
                    f"orbit's stability is not decided")
        else:
            tail = f"trivial one off by {error:.2g}): {'stable' if summary['stable'] else 'unstable'} orbit"
        lines.append(f"  Floquet multipliers     {multipliers} (largest |mu|; {tail}")
    else:
        lines.append('  Floquet multipliers     none (no periodic orbit: values of the settled long simulation)')
    if any(k in a for k, _ in BEARING_LOADS):
        lines.append(f"  bearing loads over the {'orbit' if orbit else 'last 0.5 s'} (largest |F|): " + ', '.join(
            f"{text} {a[k] / 1e3:.3f} kN" for k, text in BEARING_LOADS if k in a))
    return lines
