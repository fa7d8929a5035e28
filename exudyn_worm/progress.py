"""Progress bars for long work: one place decides where they go and when they are shown.

Every long computation of the package (simulations, charts, sweeps, the validation suite) reports progress
through :func:`ProgressBar`, so that ``--quiet`` and a non-terminal stderr silence all of them the same way.
"""
import sys

__all__ = ['ProgressBar', 'ProgressEnabled']


def ProgressEnabled(quiet=None) -> bool:
    """Whether a progress bar is shown.

    Parameters
    ----------
    quiet : bool or None
        True: never shown; False: always shown (even when stderr is not a terminal); None: shown only when
        ``sys.stderr`` is a terminal (so logs, pipes and test runs stay clean).

    Returns
    -------
    bool
        True when a progress bar would be drawn.
    """
    if quiet is not None:
        return not quiet
    isatty = getattr(sys.stderr, 'isatty', None)
    try:
        return bool(isatty and isatty())
    except ValueError:  # closed stream
        return False


def ProgressBar(total=None, desc='', unit='it', quiet=None, **kwargs):
    """A tqdm progress bar on stderr, usable as a context manager.

    Parameters
    ----------
    total : float or None
        Amount of work (in ``unit``); None for an open-ended counter.
    desc : str
        Label printed before the bar.
    unit : str
        Unit of ``total`` and of the updates (for example ``'it'``, ``'s'`` of simulated time, ``'point'``).
    quiet : bool or None
        True: disabled; False: always drawn; None: drawn only when stderr is a terminal
        (see :func:`ProgressEnabled`).
    **kwargs
        Passed on to ``tqdm`` (for example ``leave=False``, ``unit_scale=True``).

    Returns
    -------
    tqdm.tqdm
        The bar; a disabled bar accepts ``update``/``set_postfix``/``close`` and does nothing.

    Examples
    --------
    >>> with ProgressBar(total=3, desc='cases', quiet=True) as bar:
    ...     for _ in range(3):
    ...         bar.update(1)
    """
    from tqdm import tqdm         # lazy: start-up (tests/test_startup.py), imported when a bar is made
    kwargs.setdefault('file', sys.stderr)
    kwargs.setdefault('dynamic_ncols', True)
    return tqdm(total=total, desc=desc, unit=unit, disable=not ProgressEnabled(quiet), **kwargs)
