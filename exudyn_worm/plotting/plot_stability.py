"""Plot of a linear stability result: the eigenvalues in the plane of growth rate and frequency.

Draws what a result hands it (:meth:`~exudyn_worm.analysis.stability.drivestability.DriveAnalysis.plot`,
:meth:`~exudyn_worm.model.stability.StabilityAnalysis.plot`,
:meth:`~exudyn_worm.analysis.stability.linearization.LinearStability.plot`); it computes nothing. matplotlib is
imported inside the function, so importing the package never pulls it in.
"""
from __future__ import annotations

import math
import textwrap
from typing import Mapping, Optional, Sequence, Tuple

import numpy as np

from . import plot

__all__ = ['PlotEigenvalues']

_MARKERS = ('o', 's', '^', 'D', 'v', 'P', 'X', '<', '>')


def PlotEigenvalues(groups: Mapping[str, Sequence[complex]], deciding: Optional[Tuple[str, complex]] = None,
                    title: Optional[str] = None, ax=None):
    """Draw eigenvalues as growth rate (real part, 1/s) against frequency (``|imaginary part| / 2 pi``, Hz): right
    of the line Re = 0 a mode grows (shaded), on the frequency axis 0 a real eigenvalue (a divergence where it grows).

    Parameters
    ----------
    groups : mapping of str to sequence of complex
        Eigenvalues in 1/s by label (an operating point or a contact state), one marker each; a complex pair is
        drawn once.
    deciding : (str, complex), optional
        The label and eigenvalue that decide the verdict: circled and named in the legend.
    title : str, optional
        Title of the axes.
    ax : matplotlib.axes.Axes, optional
        Draw into this axes (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        fig, axes = plot._NewFigure(figsize=(8., 6.))
        ax = axes[0, 0]
    rates = []
    for k, (label, eigenvalues) in enumerate(groups.items()):
        lam = np.asarray(eigenvalues, dtype=complex).ravel()
        lam = lam[lam.imag >= 0.]                         # one of each complex pair, every real eigenvalue
        rates += list(lam.real)
        ax.plot(lam.real, lam.imag / (2 * math.pi), linestyle='none', marker=_MARKERS[k % len(_MARKERS)],
                markersize=6, markerfacecolor='none', label=label)
    if deciding is not None:
        label, lam = deciding
        ax.plot([lam.real], [abs(lam.imag) / (2 * math.pi)], linestyle='none', marker='o', markersize=14,
                markerfacecolor='none', markeredgecolor='k', markeredgewidth=1.5,
                label=f"deciding: {label}, {lam.real:.3g} 1/s at {abs(lam.imag) / (2 * math.pi):.4g} Hz")
    span = 1.15 * max([abs(r) for r in rates] + [1e-3])     # symmetric about Re = 0, every marker inside
    ax.set_xlim(-span, span)
    ax.axvline(0., color='k', linewidth=0.8)
    ax.axvspan(0., span, color='tab:red', alpha=0.08, label='growing (Re > 0)')
    ax.set_xlabel('real part (growth rate) in 1/s')
    ax.set_ylabel('frequency in Hz')
    top = max([float(np.max(np.abs(l.get_ydata()))) for l in ax.get_lines() if len(l.get_ydata())] + [1.])
    ax.set_ylim(0., 1.08 * top)
    ax.grid(True, alpha=0.3)
    ax.legend(loc='upper center', bbox_to_anchor=(0.5, -0.13), fontsize='small', ncol=1)   # below the data
    if title:
        ax.set_title(textwrap.fill(title, 90), fontsize='medium')
    return ax
