"""Plots of worm-drive simulations: the time functions of the paper's Figures 8-18.

This is the only module of the package that uses matplotlib, and it imports it inside the functions,
so ``import exudyn_worm`` never pulls matplotlib in.

Figures are created with the object-oriented API (:class:`matplotlib.figure.Figure`), which needs no
GUI and no backend choice: :func:`SaveFigure` writes them anywhere, also on a machine without a
display. If the caller already works with ``matplotlib.pyplot`` (it is imported), the figure is
created through pyplot instead, so it shows up with ``plt.show()`` and in notebooks as usual; the
user's backend is never changed.

=========================  ============================================================  ===========
``PlotSimulation`` kind    content                                                       paper
=========================  ============================================================  ===========
``'acceleration'``         wheel acceleration phi2'' over time                           Fig. 8, 13
``'zoom'``                 phi2'' and contact parameter S (twin axis) over ``tZoom``     Fig. 9, 14, 16
``'speed'``                worm speed phi1' and friction state sf (panel below)          Fig. 10, 15
``'normalForce'``          normal force on the two tooth flanks                          Fig. 11
``'driveTorque'``          drive-shaft torque M_an (eq. (6)) and S (twin axis)           Fig. 18
``'overview'``             2 x 2: acceleration, speed, normal force, drive torque
=========================  ============================================================  ===========

:func:`PlotComparison` stacks one panel per simulation (Fig. 12 and 17: normal force for three backlashes).
"""
from __future__ import annotations

import sys
from pathlib import Path
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
from .._files import WriteAtomically
from ..items.results import SERIES_UNITS

__all__ = ['PLOT_KINDS', 'COMPARISON_QUANTITIES', 'MEAN_WINDOW', 'S_SIGN_LABEL', 'S_SIGN_NOTE',
           'DENSE_SWITCHES_PER_INCH', 'PlotSimulation', 'PlotComparison', 'SaveFigure', 'TorqueSignNote',
           'PhaseMeans', 'MergePhases', 'FrictionStateDrawn']

#: the kinds :func:`PlotSimulation` draws
PLOT_KINDS = ('overview', 'acceleration', 'zoom', 'speed', 'normalForce', 'driveTorque', 'bearingLoads')
#: named quantities of :func:`PlotComparison` (any key of ``result.series`` works too)
COMPARISON_QUANTITIES = ('normalForce', 'acceleration', 'speed', 'driveTorque')

# series name -> (axis label, unit shown, factor from SI to the unit shown)
_AXES = {
    'alpha2': (r'wheel acceleration $\ddot\varphi_2$', 'rad/s²', 1.),
    'alpha1': (r'worm acceleration $\ddot\varphi_1$', 'rad/s²', 1.),
    'omega1': (r'worm speed $\dot\varphi_1$', 'rad/s', 1.),
    'omega2': (r'wheel speed $\dot\varphi_2$', 'rad/s', 1.),
    'normalForce': (r'normal force $F_n$', 'kN', 1e-3),
    'driveTorque': (r'drive shaft torque $M_{an}$ (eq. 6)', 'N·m', 1.),
    'wormTorque': (r'mesh torque on worm', 'N·m', 1.),
    'wheelTorque': (r'mesh torque on wheel', 'N·m', 1.),
    'tangentialForce': (r'tangential force $F_V$', 'kN', 1e-3),
    'deltaS': (r'normal displacement $\Delta s$', 'µm', 1e6),
    'deltaPhi': (r'relative angle $\Delta\varphi$', 'mrad', 1e3),
    'S': ('contact parameter $S$', '–', 1.),
    'sf': ('friction state $s_f$', '–', 1.),
}
_QUANTITY_SERIES = {'acceleration': 'alpha2', 'speed': 'omega1', 'driveTorque': 'driveTorque',
                    'normalForce': 'normalForce'}
_DEFAULT_TITLES = {'acceleration': r'Wheel acceleration $\ddot\varphi_2$',
                   'zoom': r'Wheel acceleration $\ddot\varphi_2$ and contact parameter $S$',
                   'speed': r'Worm speed $\dot\varphi_1$ and flank friction state $s_f$',
                   'normalForce': 'Normal force on the tooth flanks',
                   'driveTorque': r'Drive shaft torque $M_{an}$ and contact parameter $S$',
                   'overview': 'Simulation overview',
                   'bearingLoads': 'Bearing loads (3D model: worm and wheel as rigid bodies)'}
_PHASE_COLORS = {'lift': '#dcebf7', 'lower': '#fbe6cf'}
_C_MAIN, _C_SECOND, _C_FLANK1, _C_FLANK2 = '#1f4e79', '#c0392b', '#1f77b4', '#d62728'
_LINE_WIDTH = 0.6


# ----------------------------------------------------------------------------------------- helpers

def _Label(name: str) -> str:
    if name in _AXES:
        text, unit, _ = _AXES[name]
        return f'{text} [{unit}]'
    return f"{name} [{SERIES_UNITS.get(name, '–')}]"


def _Factor(name: str) -> float:
    return _AXES[name][2] if name in _AXES else 1.


def _NewFigure(nrows: int = 1, ncols: int = 1, figsize=(8., 4.2), sharex: bool = False, sharey: bool = False,
               heightRatios=None):
    """A figure with a grid of axes: through pyplot if the caller uses pyplot, else a plain Figure."""
    if 'matplotlib.pyplot' in sys.modules:
        import matplotlib.pyplot as plt
        fig = plt.figure(figsize=figsize, layout='constrained')
    else:
        from matplotlib.figure import Figure
        fig = Figure(figsize=figsize, layout='constrained')
    axes = fig.subplots(nrows, ncols, sharex=sharex, sharey=sharey, squeeze=False,
                        gridspec_kw=None if heightRatios is None else {'height_ratios': heightRatios})
    return fig, axes


def _CheckResult(where: str, result, names: Sequence[str]):
    series = getattr(result, 'series', None)
    if not isinstance(series, Mapping) or not hasattr(result, 'time'):
        raise TypeError(f"{where}: 'result' must be a SimulationResult, got {type(result).__name__}")
    missing = [n for n in names if n not in series]
    if missing:
        raise ValueError(f"{where}: the result has no series {', '.join(missing)}; "
                         f"available: {', '.join(series)}")


def _Interval(where: str, result, tZoom) -> Tuple[np.ndarray, Tuple[float, float]]:
    """Mask of the output times in ``tZoom`` (whole record if None) and the interval itself."""
    t = np.asarray(result.time)
    if tZoom is None:
        return np.ones(t.shape, bool), (float(t[0]), float(t[-1]))
    try:
        t0, t1 = (float(v) for v in tZoom)
    except (TypeError, ValueError):
        raise TypeError(f"{where}: 'tZoom' must be a pair (t0, t1) of times in s, got {tZoom!r}") from None
    if not t0 < t1:
        raise ValueError(f"{where}: 'tZoom' must satisfy t0 < t1, got ({t0:g}, {t1:g}) s")
    mask = (t >= t0) & (t <= t1)
    if mask.sum() < 2:
        raise ValueError(f"{where}: 'tZoom' = ({t0:g}, {t1:g}) s holds fewer than 2 output times "
                         f"(simulated {t[0]:g} to {t[-1]:g} s)")
    return mask, (t0, t1)


def _Phases(result) -> list:
    """The lift / lower phases the simulation recorded (``result.info['phases']``, from the duty:
    :func:`~exudyn_worm.analysis.simulation.reelchanger.DefaultPhases`); idle phases are not shaded."""
    return MergePhases([(a, b, kind) for a, b, kind in getattr(result, 'info', {}).get('phases', ())
                        if kind in _PHASE_COLORS])


def MergePhases(phases: Sequence) -> list:
    """Phases with each run of adjoining phases of the same kind joined into one window.

    The reel changer's duty lists the lift at the end of a rotation and the lift at the start of the next one
    as two phases (6-8 s and 8-10 s at 472.5 rpm); the motor lifts without a break from 6 to 10 s, so a figure
    shades one window.

    Parameters
    ----------
    phases : sequence of (float, float, str)
        ``(t0, t1, kind)`` in time order, times in s.

    Returns
    -------
    list of (float, float, str)
        The windows, in time order.
    """
    merged = []
    for a, b, kind in phases:
        a, b = float(a), float(b)
        if merged and merged[-1][2] == kind and abs(a - merged[-1][1]) <= 1e-9 * max(1., abs(b)):
            merged[-1] = (merged[-1][0], b, kind)
        else:
            merged.append((a, b, kind))
    return merged


def _ShadePhases(ax, phases, interval, labels: bool = True):
    """Shade lift / lower phases inside ``interval``; name them in a strip just above the axes (outside the
    data, so no curve runs through a name) if there is room."""
    import matplotlib.transforms as mtransforms
    t0, t1 = interval
    span = t1 - t0
    trans = mtransforms.blended_transform_factory(ax.transData, ax.transAxes)
    for a, b, kind in phases:
        a, b = max(a, t0), min(b, t1)
        if b <= a:
            continue
        ax.axvspan(a, b, color=_PHASE_COLORS[kind], alpha=0.6, lw=0, zorder=0)
        if labels and (b - a) > 0.08 * span:
            ax.text(0.5 * (a + b), 1.005, kind, transform=trans, ha='center', va='bottom', fontsize=8,
                    color='0.35', clip_on=False, gid='phase label')
            ax._phaseLabels = True


def _SetTitle(ax, text: str, **kwargs):
    """Axes title; above the phase names of :func:`_ShadePhases` where the axes has them."""
    if getattr(ax, '_phaseLabels', False):
        kwargs.setdefault('pad', 14.)
    ax.set_title(text, **kwargs)


def _Decorate(ax, interval):
    ax.grid(True, color='0.85', lw=0.5)
    t0, t1 = interval
    # a limit just past a round tick (e.g. a zoom from 4.00015 s) would hide the first or last time tick:
    # widen the view to that tick when it lies within 2 % of the span
    ticks = ax.xaxis.get_major_locator().tick_values(t0, t1)
    below, above = [v for v in ticks if v <= t0], [v for v in ticks if v >= t1]
    if below and t0 - below[-1] <= 0.02 * (t1 - t0):
        t0 = float(below[-1])
    if above and above[0] - t1 <= 0.02 * (t1 - t0):
        t1 = float(above[0])
    ax.set_xlim(t0, t1)
    ax.margins(y=0.08)


#: label of the contact state as drawn: the paper's S = +-1 (eq. (8)) is the sign of the regularized S
S_SIGN_LABEL = _S_LABEL = r'contact state sign$(S)$'
#: the note under every figure that draws sign(S) (for your own figures of ``result.series['S']`` too)
S_SIGN_NOTE = _S_NOTE = (r"$|S| = |\sigma s_f| < 1$ only while the flanks stick (regularized friction: while the worm "
                         r"nearly stands); drawn: its sign, the paper's $S = \pm 1$")


def FrictionStateDrawn(result: 'SimulationResult', mask: Optional[np.ndarray] = None) -> np.ndarray:
    """The friction state s_f as drawn: one value per output time (the solver's steps), within [-1, 1].

    While the flanks stick, s_f is the sticking force over ``mu * abs(F_n)``. The switch from sticking to sliding
    is decided after a converged step, so in the one step before it the sticking force may exceed the friction
    limit and the recorded ``abs(s_f)`` exceed 1; the flanks slide from the next step, at s_f = +-1, which is
    what the figure shows. The value holds over its step (drawn as steps, not joined by slopes).

    Parameters
    ----------
    result : SimulationResult
        With the series ``sf``.
    mask : array of bool, optional
        Output times to use (default: all).

    Returns
    -------
    ndarray
        s_f at the output times, clipped to [-1, 1].
    """
    sf = np.asarray(result.series['sf'], dtype=float)
    return np.clip(sf if mask is None else sf[np.asarray(mask, bool)], -1., 1.)


def _ContactSign(result, mask):
    """The paper's contact parameter S = +-1 (eq. (8)): the sign of the regularized S (0 inside the backlash)."""
    return np.sign(np.asarray(result.series['S'])[mask])


def _TwinStep(ax, t, values, label: str, color: str, limits=(-1.6, 1.6)):
    """Draw a contact/friction state on a twin y axis with ticks at -1, 0, 1."""
    twin = ax.twinx()
    twin.plot(t, values, color=color, lw=0.9, label=label, drawstyle='steps-post')
    twin.set_ylim(*limits)
    twin.set_yticks([-1, 0, 1])
    twin.set_ylabel(label, color=color)
    twin.tick_params(axis='y', colors=color)
    return twin


def _DrawSeries(ax, result, name, mask, color=_C_MAIN, label=None, lw=_LINE_WIDTH):
    t = np.asarray(result.time)[mask]
    return ax.plot(t, np.asarray(result.series[name])[mask] * _Factor(name), color=color, lw=lw, label=label)


def _RunningMean(t, x, width: float):
    """Centered moving average of ``x`` over ``width`` seconds (same length as ``x``); near the ends it
    averages the samples there are (padding with the last value made the mean of an oscillation drift)."""
    if t.size < 3:
        return x
    n = max(1, int(round(width / max(float(np.median(np.diff(t))), 1e-12))))
    i = np.arange(x.size)
    lo, hi = np.maximum(i - n // 2, 0), np.minimum(i + n - n // 2, x.size)
    total = np.concatenate(([0.], np.cumsum(x, dtype=float)))
    return (total[hi] - total[lo]) / (hi - lo)


#: averaging time in s of the mean normal force drawn with the flank forces (longer than a chatter period)
MEAN_WINDOW = 0.25


def _DrawFlank(ax, result, mask, flank: int):
    """One flank's normal force (kN) with its running mean (the quasi-static level the chatter exceeds)."""
    t = np.asarray(result.time)[mask]
    f = np.asarray(result.normalForceFlanks[flank - 1])[mask] * 1e-3
    color = _C_FLANK1 if flank == 1 else _C_FLANK2
    text = r'flank 1 ($\Delta s > 0$, worm drives)' if flank == 1 else r'flank 2 ($\Delta s < 0$)'
    ax.plot(t, f, color=color, lw=_LINE_WIDTH, label=text)
    ax.plot(t, _RunningMean(t, f, MEAN_WINDOW), color='black', lw=1.2, ls='--',
            label=f'mean over {MEAN_WINDOW:g} s')
    ax.set_ylabel(f'flank {flank} $F_n$ [kN]')


def _DrawNormalForce(ax, result, mask, legend=True):
    t = np.asarray(result.time)[mask]
    f1, f2 = (np.asarray(f)[mask] * 1e-3 for f in result.normalForceFlanks)
    ax.plot(t, f1, color=_C_FLANK1, lw=_LINE_WIDTH, label=r'flank 1 ($\Delta s > 0$, worm drives)')
    # the second flank is drawn downward so that the two dense traces do not cover each other
    ax.plot(t, -f2, color=_C_FLANK2, lw=_LINE_WIDTH, label=r'flank 2 ($\Delta s < 0$), drawn downward')
    ax.axhline(0., color='0.4', lw=0.6)
    ax.set_ylabel('$F_n$ [kN] (flank 1 up, flank 2 down)')
    if legend:                                 # in the title, over no data
        _SetTitle(ax, 'Normal force: flank 1 (blue) up, flank 2 (red) down', fontsize=10)


def _FigureLegend(fig, axes, loc='outside lower center', **kwargs):
    """One legend for ``axes`` outside them (constrained layout makes room), one entry per label."""
    handles = {}
    for ax in axes:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(label, handle)
    return fig.legend(list(handles.values()), list(handles), loc=loc, ncols=min(len(handles), 3),
                      fontsize=kwargs.pop('fontsize', 8.5), frameon=False, **kwargs)


def _Draw(kind, ax, result, mask, interval, phases, twin: bool = True):
    """Draw one panel of ``kind`` on ``ax``."""
    t = np.asarray(result.time)[mask]
    if phases:
        _ShadePhases(ax, phases, interval, labels=(kind not in ('sf', 'S')))
    if kind in ('acceleration', 'zoom'):
        _DrawSeries(ax, result, 'alpha2', mask)
        ax.set_ylabel(_Label('alpha2'), color=_C_MAIN if kind == 'zoom' and twin else 'black')
        if kind == 'zoom' and twin:
            _TwinStep(ax, t, _ContactSign(result, mask), _S_LABEL, _C_SECOND)
    elif kind == 'speed':
        omega = np.asarray(result.series['omega1'])[mask]
        _DrawSeries(ax, result, 'omega1', mask)
        ax.set_ylabel(_Label('omega1'))
        if omega.min() < 0.25 * max(omega.max(), 0.):          # near standstill: show the zero line
            ax.axhline(0., color='0.4', lw=0.6)
    elif kind == 'S':
        ax.plot(t, _ContactSign(result, mask), color=_C_SECOND, lw=0.9, drawstyle='steps-post')
        ax.set_ylim(-1.3, 1.3)
        ax.set_yticks([-1, 0, 1])
        ax.set_ylabel('sign$(S)$ [–]')
    elif kind == 'sf':
        ax.plot(t, FrictionStateDrawn(result, mask), color=_C_SECOND, lw=0.9, drawstyle='steps-post', gid='sf')
        ax.set_ylim(-1.3, 1.3)
        ax.set_yticks([-1, 0, 1])
        ax.set_ylabel('$s_f$ [–]')
    elif kind == 'normalForce':
        _DrawNormalForce(ax, result, mask)
    elif kind == 'driveTorque':
        _DrawSeries(ax, result, 'driveTorque', mask)
        ax.set_ylabel(_Label('driveTorque'), color=_C_MAIN)
        ax.axhline(0., color='0.4', lw=0.6)
        _ExplainTorqueSign(ax, result, mask, phases)
        if twin:
            _TwinStep(ax, t, _ContactSign(result, mask), _S_LABEL, _C_SECOND)
    else:                                                             # any series by name
        _DrawSeries(ax, result, kind, mask)
        ax.set_ylabel(_Label(kind))
    _Decorate(ax, interval)
    ax.set_xlabel('time $t$ [s]')


def PhaseMeans(result: 'SimulationResult', phases: Sequence, mask: Optional[np.ndarray] = None,
               name: str = 'driveTorque') -> list:
    """The mean of a series over each kind of phase and direction of the worm, in order of first appearance.

    A lift with the worm turning forward and one with it turning backward have drive torques of opposite sign:
    their common mean says nothing, so they are averaged apart. The direction of a phase is the sign of the mean
    worm speed phi1' in it (forward without ``omega1``).

    Parameters
    ----------
    result : SimulationResult
        With the series ``name`` (and ``omega1`` for the direction).
    phases : sequence of (float, float, str)
        ``(t0, t1, kind)``, kind ``'lift'`` or ``'lower'``, times in s.
    mask : array of bool, optional
        Output times to use (default: all).
    name : str
        The series averaged (default ``'driveTorque'``).

    Returns
    -------
    list of (str, int, float)
        ``(kind, direction, mean)``: direction +1 forward, -1 backward; the mean in the series' SI unit.
    """
    t = np.asarray(result.time)
    mask = np.ones(t.shape, bool) if mask is None else np.asarray(mask, bool)
    values = np.asarray(result.series[name])
    omega = np.asarray(result.series['omega1']) if 'omega1' in result.series else None
    parts = {}
    for a, b, kind in phases:               # [a, b): a boundary sample belongs to the phase it starts
        inside = mask & (t >= a) & ((t < b) | (b >= t[-1]))
        if inside.any():
            direction = 1 if omega is None or float(np.mean(omega[inside])) >= 0. else -1
            parts.setdefault((kind, direction), []).append(values[inside])
    return [(kind, direction, float(np.mean(np.concatenate(v)))) for (kind, direction), v in parts.items()]


def TorqueSignNote(result: 'SimulationResult', mask: Optional[np.ndarray] = None, phases: Sequence = ()) -> str:
    """What the sign of the drive-shaft torque M_an (eq. (6)) means in ``result``, one line per statement.

    M_an = kT (phi1 - phi0) + dT (phi1' - phi0') is positive when the worm runs ahead of the motor. With the
    worm turning forward (mean phi1' > 0), M_an < 0 means the shaft pulls the worm along: the motor drives
    the gear; M_an > 0 means the worm drives the motor; turning backward, the other way round. With ``phases``
    (lift / lower intervals), the mean torque of each phase and direction follows (:func:`PhaseMeans`: a forward
    and a backward lift are averaged apart), and a remark where the motor drives while the load is lowered
    (self-locking).

    Parameters
    ----------
    result : SimulationResult
        With the series ``driveTorque`` (and ``omega1`` for the direction of the worm).
    mask : array of bool, optional
        Output times to use (default: all).
    phases : sequence of (t0, t1, 'lift' | 'lower'), optional
        Phase intervals, e.g. of a reel-changer run.

    Returns
    -------
    str
    """
    t = np.asarray(result.time)
    mask = np.ones(t.shape, bool) if mask is None else np.asarray(mask, bool)
    lines = [r'$M_{an} = k_T(\varphi_1-\varphi_0) + d_T(\dot\varphi_1-\dot\varphi_0)$ (eq. 6)']
    if 'omega1' not in result.series:
        lines.append(r'$M_{an} < 0$: the worm lags behind the motor')
        return '\n'.join(lines)
    means = PhaseMeans(result, phases, mask)
    directions = sorted({d for _, d, _ in means}, reverse=True) or \
        [1 if float(np.mean(np.asarray(result.series['omega1'])[mask])) >= 0. else -1]
    for d in directions:
        lines.append(fr'worm turning {"forward" if d > 0 else "backward"}: $M_{{an}}$ {"<" if d > 0 else ">"} 0 = the '
                     fr'motor drives the worm, $M_{{an}}$ {">" if d > 0 else "<"} 0 = the worm drives the motor')
    if means:
        both = len(directions) > 1
        texts = []
        for kind, d, value in sorted(means, key=lambda m: (m[0], -m[1])):
            phase = 'lifting' if kind == 'lift' else 'lowering'
            texts.append(f"{phase}{(' forward' if d > 0 else ' backward') if both else ''}: mean {value:+.3g} N·m"
                         + (' (self-locking: the motor drives while lowering too)'
                            if kind == 'lower' and (value < 0) == (d > 0) else ''))
        lines.append(', '.join(texts))
    return '\n'.join(lines)


def _ExplainTorqueSign(ax, result, mask, phases):
    """The meaning of the torque's sign as a legend without handles, below the figure's axes (over no data)."""
    from matplotlib.lines import Line2D
    note = TorqueSignNote(result, mask, phases)
    legend = ax.figure.legend([Line2D([], [], ls='none')], [note], loc='outside lower center', fontsize=7.5,
                              handlelength=0, handletextpad=0, frameon=False, title='sign of $M_{an}$',
                              title_fontsize=8)
    legend.set_gid('torque sign')


#: more sign changes of S per inch of figure width than this: drawn as the share of time per bin and a zoom
DENSE_SWITCHES_PER_INCH = 15.


def _DrawDenseSign(share, zoom, result, mask, interval, phases):
    """sign(S) switching too often for a step line: its share of time per bin (``share``) and a step plot
    over a short window with about 20 switches (``zoom``), marked on ``share``."""
    t = np.asarray(result.time)[mask]
    sign = _ContactSign(result, mask)
    switches = t[1:][np.diff(sign) != 0]
    if phases:
        _ShadePhases(share, phases, interval, labels=False)
    bins = int(min(200, max(20, t.size // 20)))
    edges = np.linspace(interval[0], interval[1], bins + 1)
    index = np.clip(np.searchsorted(edges, t, side='right') - 1, 0, bins - 1)
    count = np.maximum(np.bincount(index, minlength=bins), 1)
    minus = np.bincount(index, weights=(sign < 0), minlength=bins) / count
    plus = np.bincount(index, weights=(sign > 0), minlength=bins) / count
    x = edges
    step = lambda v: np.append(v, v[-1])
    share.fill_between(x, 0., step(minus), step='post', color=_C_SECOND, lw=0, label='$S = -1$', gid='share S=-1')
    share.fill_between(x, step(minus), step(minus + plus), step='post', color=_C_MAIN, lw=0, alpha=0.85,
                       label='$S = +1$', gid='share S=+1')
    share.set_ylim(0., 1.)
    share.set_yticks([0., 0.5, 1.])
    share.set_ylabel('share of time')
    _Decorate(share, interval)
    share.margins(y=0.)
    share.legend(loc='center left', bbox_to_anchor=(1.0, 0.5), fontsize=7.5, frameon=False)
    share.set_title(fr'sign$(S)$ changes {switches.size} times: its share of time per '
                    fr'{1e3 * (edges[1] - edges[0]):.3g} ms (zoom below, window shaded)', loc='left', fontsize=8)
    span = interval[1] - interval[0]
    width = float(np.clip(20. * span / max(switches.size, 1), 20 * np.median(np.diff(t)), span / 10))
    centre = float(switches[switches.size // 2]) if switches.size else 0.5 * sum(interval)
    w0 = min(max(centre - 0.5 * width, interval[0]), interval[1] - width)
    share.axvspan(w0, w0 + width, fc='none', ec='black', lw=0.8, zorder=3)
    inside = (t >= w0) & (t <= w0 + width)
    if phases:
        _ShadePhases(zoom, phases, (w0, w0 + width), labels=False)
    zoom.plot(t[inside], sign[inside], color=_C_SECOND, lw=0.9, drawstyle='steps-post', gid='sign zoom')
    zoom.set_ylim(-1.3, 1.3)
    zoom.set_yticks([-1, 0, 1])
    zoom.set_ylabel('sign$(S)$ [–]')
    zoom.grid(True, color='0.85', lw=0.5)
    zoom.set_xlim(w0, w0 + width)
    zoom.set_xlabel('time $t$ [s] (zoom)')
    zoom.set_title(_S_NOTE, loc='left', fontsize=8)


_REQUIRED = {'acceleration': ('alpha2',), 'zoom': ('alpha2', 'S'), 'speed': ('omega1', 'sf'),
             'normalForce': ('normalForce',), 'driveTorque': ('driveTorque', 'S'),
             'overview': ('alpha2', 'omega1', 'normalForce', 'driveTorque'),
             'bearingLoads': ('wormAxialLoad', 'wormRadialLoad', 'wheelAxialLoad', 'wheelRadialLoad')}


# ---------------------------------------------------------------------------------- public functions

def PlotSimulation(result, kind: str = 'overview', tZoom: Optional[Tuple[float, float]] = None,
                   title: Optional[str] = None, phases: Union[bool, Sequence] = True, figsize=None,
                   subtitle: Optional[str] = None):
    """Plot the time functions of one simulation (the paper's Figures 8-11, 13-16, 18).

    The contact parameter is drawn as the paper's S = +-1, the sign of the model's S
    (``|S| < 1`` only while the flanks stick, or with the regularized friction while the worm speed is within
    frictionSpeed of zero). Over a
    whole run (``'driveTorque'``) it gets its own panel below the torque, so it never covers the torque;
    the normal force shows each flank in its own panel with its running mean over :data:`MEAN_WINDOW`.

    Parameters
    ----------
    result : SimulationResult
        Result of e.g. :func:`exudyn_worm.analysis.simulation.reelchanger.SimulateReelChanger`.
    kind : str
        One of :data:`PLOT_KINDS`: ``'acceleration'`` (Fig. 8/13), ``'zoom'`` (phi2'' and S, Fig. 9/14/16),
        ``'speed'`` (phi1' and sf, Fig. 10/15), ``'normalForce'`` (both flanks, Fig. 11),
        ``'driveTorque'`` (M_an and S, Fig. 18), ``'overview'`` (2 x 2 panels) or ``'bearingLoads'`` (a run of
        the 3D model: the axial and radial load of each shaft's bearings).
    tZoom : (float, float), optional
        Time interval in s to show. Default: the whole record, except for ``'zoom'``, which shows
        0.1 s in the middle of the record.
    title : str, optional
        Figure title (e.g. with the paper's figure number); default: a description of ``kind``.
    phases : bool or sequence of (t0, t1, 'lift' | 'lower')
        Shade the lift / lower phases. True (default): the phases of the duty the simulation recorded
        (``result.info['phases']``; none for a result without them); False: no shading; or give the intervals
        explicitly.
    figsize : (float, float), optional
        Figure size in inches.
    subtitle : str, optional
        Second title line, e.g. the preset and overrides of the run.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        For an unknown ``kind``, a ``tZoom`` outside the record or a result without the needed series.
    TypeError
        If ``result`` is not a simulation result or ``tZoom`` is not a pair of numbers.
    """
    w = 'PlotSimulation'
    if kind not in PLOT_KINDS:
        raise ValueError(f"{w}: 'kind' must be one of {', '.join(map(repr, PLOT_KINDS))}, got {kind!r}")
    _CheckResult(w, result, _REQUIRED[kind])
    if kind == 'zoom' and tZoom is None:
        tm = 0.5 * (float(result.time[0]) + float(result.time[-1]))
        tZoom = (tm, min(tm + 0.1, float(result.time[-1])))
    mask, interval = _Interval(w, result, tZoom)
    if phases is True:
        phases = _Phases(result)
    elif phases is False or phases is None:
        phases = []
    else:
        phases = [(float(a), float(b), str(k)) for a, b, k in phases]
        bad = [k for _, _, k in phases if k not in _PHASE_COLORS]
        if bad:
            raise ValueError(f"{w}: phase names must be 'lift' or 'lower', got {bad[0]!r}")
        phases = MergePhases(phases)
    title = _DEFAULT_TITLES[kind] if title is None else str(title)
    if subtitle:
        title = f'{title}\n{subtitle}'

    if kind == 'overview':
        fig, axes = _NewFigure(2, 2, figsize=figsize or (12., 7.), sharex=True)
        for ax, k in zip(axes.flat, ('acceleration', 'speed', 'normalForce', 'driveTorque')):
            _Draw(k, ax, result, mask, interval, phases, twin=False)
            if k != 'normalForce':             # its title names the flanks' colours
                _SetTitle(ax, _DEFAULT_TITLES[k].split(' and ')[0], fontsize=10)
        for ax in axes[0]:
            ax.set_xlabel('')
        fig.suptitle(title)
        return fig

    if kind == 'bearingLoads':             # one panel per shaft: axial and radial load (magnitudes)
        fig, axes = _NewFigure(2, 1, figsize=figsize or (8., 5.6), sharex=True)
        t = np.asarray(result.time)[mask]
        for body, ax in (('worm', axes[0, 0]), ('wheel', axes[1, 0])):
            if phases:
                _ShadePhases(ax, phases, interval, labels=(body == 'worm'))
            for direction, color in (('Axial', _C_MAIN), ('Radial', _C_SECOND)):
                ax.plot(t, 1e-3 * np.abs(np.asarray(result.series[body + direction + 'Load'])[mask]), color=color,
                        lw=_LINE_WIDTH, label=f'{direction.lower()} bearing' if direction == 'Axial'
                        else 'radial bearings (vector sum)')
            ax.set_ylabel(f'{body} bearing load [kN]')
            ax.legend(loc='upper left', bbox_to_anchor=(1.01, 1.), fontsize=8, frameon=False)
            _Decorate(ax, interval)
        axes[0, 0].set_xlabel('')
        axes[1, 0].set_xlabel('time $t$ [s]')
        _SetTitle(axes[0, 0], title, fontsize=11)
        return fig
    if kind == 'speed':                    # speed on top, friction state below: both stay readable
        fig, axes = _NewFigure(2, 1, figsize=figsize or (8., 5.), sharex=True, heightRatios=(3, 1))
        _Draw('speed', axes[0, 0], result, mask, interval, phases)
        _Draw('sf', axes[1, 0], result, mask, interval, phases)
        axes[0, 0].set_xlabel('')
        step = float(np.median(np.diff(np.asarray(result.time)[mask]))) if mask.sum() > 1 else 0.
        axes[1, 0].set_title(fr'friction state $s_f$ (±1 sliding, |$s_f$| < 1 sticking; one value per time step '
                             fr'of {1e3 * step:.3g} ms)', loc='left', fontsize=9)
        _SetTitle(axes[0, 0], title, fontsize=11)
        return fig
    if kind == 'normalForce':              # one panel per flank: the dense second flank stays legible
        fig, axes = _NewFigure(2, 1, figsize=figsize or (8., 5.6), sharex=True)
        for flank, ax in ((1, axes[0, 0]), (2, axes[1, 0])):
            if phases:
                _ShadePhases(ax, phases, interval, labels=(flank == 1))
            _DrawFlank(ax, result, mask, flank)
            _Decorate(ax, interval)
        _FigureLegend(fig, axes[:, 0])
        axes[1, 0].set_xlabel('time $t$ [s]')
        _SetTitle(axes[0, 0], title, fontsize=11)
        return fig
    if kind == 'driveTorque' and tZoom is None:   # whole run: S in its own panel, never over the torque
        width = (figsize or (8., 5.))[0]
        if np.count_nonzero(np.diff(_ContactSign(result, mask))) > DENSE_SWITCHES_PER_INCH * width:
            # a step line of S would be a solid block: share of time per bin, and a zoom with readable steps
            fig, axes = _NewFigure(3, 1, figsize=figsize or (8., 6.4), heightRatios=(3, 1, 1.1))
            axes[1, 0].sharex(axes[0, 0])
            _Draw('driveTorque', axes[0, 0], result, mask, interval, phases, twin=False)
            _DrawDenseSign(axes[1, 0], axes[2, 0], result, mask, interval, phases)
            axes[0, 0].set_xlabel('')
            axes[1, 0].set_xlabel('time $t$ [s]')
            _SetTitle(axes[0, 0], title, fontsize=11)
            return fig
        fig, axes = _NewFigure(2, 1, figsize=figsize or (8., 5.), sharex=True, heightRatios=(3, 1))
        _Draw('driveTorque', axes[0, 0], result, mask, interval, phases, twin=False)
        _Draw('S', axes[1, 0], result, mask, interval, phases)
        axes[0, 0].set_xlabel('')
        axes[1, 0].set_title(_S_NOTE, loc='left', fontsize=8)
        _SetTitle(axes[0, 0], title, fontsize=11)
        return fig
    fig, axes = _NewFigure(1, 1, figsize=figsize or (8., 4.2))
    ax = axes[0, 0]
    _Draw(kind, ax, result, mask, interval, phases)
    if kind in ('zoom', 'driveTorque'):
        ax.text(0.0, -0.2, _S_NOTE, transform=ax.transAxes, fontsize=7, color='0.3', va='top')
    _SetTitle(ax, title, fontsize=11)
    return fig


def PlotComparison(results: Mapping[str, Any], quantity: str = 'normalForce',
                   tZoom: Optional[Tuple[float, float]] = None, title: Optional[str] = None,
                   sharey: bool = True, phases: bool = True, figsize=None):
    """Stacked panels of one quantity for several simulations, top to bottom in the mapping's order
    (Fig. 12 and 17: normal force for the backlashes 0.25, 0.5 and 0.75 mm).

    Parameters
    ----------
    results : mapping of str to SimulationResult
        Panel label -> result.
    quantity : str
        ``'normalForce'`` (both flanks), ``'acceleration'`` (phi2''), ``'speed'`` (phi1'),
        ``'driveTorque'`` (M_an), or any key of ``result.series``.
    tZoom : (float, float), optional
        Time interval in s (default: the whole record of each result).
    title : str, optional
        Figure title.
    sharey : bool
        Same y scale in all panels (default), so amplitudes compare at a glance.
    phases : bool
        Shade lift / lower phases of reel-changer results.
    figsize : (float, float), optional
        Figure size in inches (default: 8 wide, 2.3 per panel).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        For an empty ``results``, an unknown ``quantity`` or a ``tZoom`` outside a record.
    TypeError
        If ``results`` is not a mapping of results.
    """
    w = 'PlotComparison'
    if not isinstance(results, Mapping):
        raise TypeError(f"{w}: 'results' must be a dict of label -> SimulationResult, got {type(results).__name__}")
    if not results:
        raise ValueError(f"{w}: 'results' is empty")
    series = _QUANTITY_SERIES.get(quantity, quantity)
    for label, result in results.items():
        _CheckResult(w, result, (series,))
    n = len(results)
    fig, axes = _NewFigure(n, 1, figsize=figsize or (8., 1.2 + 2.3 * n), sharex=True, sharey=sharey)
    for i, (ax, (label, result)) in enumerate(zip(axes[:, 0], results.items())):
        mask, interval = _Interval(w, result, tZoom)
        if phases:
            _ShadePhases(ax, _Phases(result), interval, labels=(i == 0))
        if series == 'normalForce':
            _DrawNormalForce(ax, result, mask, legend=False)
            ax.set_ylabel('$F_n$ [kN]')
            if i == 0:
                _FigureLegend(fig, [ax], fontsize=9)
        else:
            _DrawSeries(ax, result, series, mask)
            ax.set_ylabel(_Label(series) if n == 1 else f"[{_Label(series).rsplit('[', 1)[-1]}")
        _Decorate(ax, interval)
        m = np.max(np.abs(np.asarray(result.series[series])[mask])) * _Factor(series)
        unit = _Label(series).rsplit('[', 1)[-1].rstrip(']')
        _SetTitle(ax, str(label), loc='left', fontsize=10, fontweight='bold')
        _SetTitle(ax, f'max |{series if series not in _AXES else _AXES[series][0].split(" ")[-1]}| = {m:.4g} {unit}',
                     loc='right', fontsize=9)
    axes[-1, 0].set_xlabel('time $t$ [s]')
    if title is None:
        title = _DEFAULT_TITLES.get(quantity, _Label(series))
    fig.suptitle(title)
    return fig


def SaveFigure(fig, path, dpi: int = 150) -> Path:
    """Save ``fig`` to ``path`` (format from the suffix, e.g. ``.png``, ``.pdf``), creating the folder; the file is
    written atomically (:func:`~exudyn_worm._files.WriteAtomically`: complete or absent).

    Works without a display: a plain :class:`~matplotlib.figure.Figure` renders with Agg.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        Figure to save (e.g. from :func:`PlotSimulation`).
    path : str or Path
        Output file.
    dpi : int
        Resolution in dots per inch (default 150).

    Returns
    -------
    Path
        The path written.

    Raises
    ------
    TypeError
        If ``fig`` is not a matplotlib figure.
    """
    from matplotlib.figure import Figure
    if not isinstance(fig, Figure):
        raise TypeError(f"SaveFigure: 'fig' must be a matplotlib Figure, got {type(fig).__name__}")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return WriteAtomically(path, lambda tmp: fig.savefig(tmp, dpi=dpi))   # never half a file (a full disk)
