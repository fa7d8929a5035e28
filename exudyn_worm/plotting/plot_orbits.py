"""Plot of a chatter branch (:class:`~exudyn_worm.analysis.orbits.chatterbranch.ChatterBranch`): amplitude over the parameter.

Draws a result object only; matplotlib is imported inside the function, so importing the package never pulls it in.
"""
from __future__ import annotations

from typing import Optional

import numpy as np

from . import plot
from ..items.bearings import BEARING_LOADS

__all__ = ['PlotChatterBranch']


def PlotChatterBranch(branch: 'ChatterBranch', fileName: Optional[str] = None, ax=None):
    """Draw the normal-force factor and the largest ``|phi2''|`` of a branch over its parameter, and for a branch
    of the 3D model the largest bearing loads in a third row.

    Stable orbits are solid lines, unstable ones dashed; Hopf points are marked, the linear boundaries are
    dotted vertical lines, folds are marked with x, coexistence ranges are shaded.

    Parameters
    ----------
    branch : ChatterBranch
        From :func:`~exudyn_worm.analysis.orbits.chatterbranch.AnalyzeChatterBranch`.
    fileName : str, optional
        Save the figure there (format from the suffix).
    ax : sequence of matplotlib.axes.Axes, optional
        Axes for the force factor and the wheel acceleration, and a third for the bearing loads where the branch's
        points carry them (default: a new figure with two rows, or three).

    Returns
    -------
    list of matplotlib.axes.Axes
    """
    from matplotlib.figure import Figure
    loads = [(k, text) for k, text in BEARING_LOADS if any(k in p.info for p in branch.points)]
    rows = 3 if loads else 2
    if ax is None:
        fig = Figure(figsize=(7., 6. if rows == 2 else 8.5), layout='constrained')
        axes = list(fig.subplots(rows, 1, sharex=True))
    else:
        axes = list(ax)
        fig = axes[0].figure
        if len(axes) < rows:
            raise ValueError(f"PlotChatterBranch: 'ax' must hold {rows} axes for this branch, got {len(axes)}")
    values = np.array([p.value for p in branch.points])
    stable = np.array([p.stable for p in branch.points])
    for a, key, label in ((axes[0], 'forceFactor', 'largest normal force / static'),
                          (axes[1], 'maxWheelAcceleration', "largest |phi2''| (rad/s^2)")):
        y = np.array([p.info.get(key, np.nan) for p in branch.points])
        for k in range(len(values) - 1):
            both = stable[k] and stable[k + 1]
            a.plot(values[k:k + 2], y[k:k + 2], '-' if both else '--', color='#1f4e79' if both else '#c0392b')
        a.plot([], [], '-', color='#1f4e79', label='stable chatter')
        a.plot([], [], '--', color='#c0392b', label='unstable orbit')
        for v in branch.linearBoundaries:
            a.axvline(v, linestyle=':', color='0.3')
        for h in branch.hopf:
            a.plot([h['value']], [0. if key != 'forceFactor' else 1.], 'o', color='k')
        for f in branch.folds:
            a.axvline(f, linestyle='-', color='#8e24aa', alpha=0.3)
        for lo, hi in branch.coexistence:
            a.axvspan(lo, hi, color='#f5b041', alpha=0.25)
        a.set_ylabel(label)
        a.grid(True, alpha=0.3)
    axes[0].plot([], [], ':', color='0.3', label='linear boundary')
    axes[0].plot([], [], 'o', color='k', label='Hopf point')
    axes[0].legend(loc='best', fontsize='small')
    if loads:
        for (key, text), color in zip(loads, ('#1f4e79', '#5dade2', '#c0392b', '#f5b041')):
            axes[2].plot(values, [p.info.get(key, np.nan) / 1e3 for p in branch.points], '.-', color=color,
                         label=text)
        for v in branch.linearBoundaries:
            axes[2].axvline(v, linestyle=':', color='0.3')
        axes[2].set_ylabel('largest bearing load (kN)')
        axes[2].grid(True, alpha=0.3)
        axes[2].legend(loc='best', fontsize='small')
    axes[rows - 1].set_xlabel(branch.parameter)
    axes[0].set_title(f'steady chatter of the lowering phase over {branch.parameter}')
    if fileName is not None:
        plot.SaveFigure(fig, fileName)
    return axes
