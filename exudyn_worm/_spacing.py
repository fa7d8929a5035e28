"""How a varied key's values are spaced: shared by the chatter map's grid (:mod:`exudyn_worm.analysis.studies.studymap`) and
the axes of the study plots (:mod:`exudyn_worm.plotting.plot_study`). numpy only."""
from __future__ import annotations

from typing import Sequence, Union

import numpy as np

__all__ = ['IsLogSpaced']


def IsLogSpaced(values: Union[Sequence[float], np.ndarray]) -> bool:
    """True for at least three positive, log-spaced (and not linearly spaced) values.

    Parameters
    ----------
    values : array_like
        The values of one varied key.

    Returns
    -------
    bool
    """
    v = np.unique(np.asarray(values, float))
    if v.size < 3 or np.any(v <= 0):
        return False
    ratios = v[1:] / v[:-1]
    return bool(np.allclose(ratios, ratios[0], rtol=1e-6) and not np.allclose(np.diff(v), np.diff(v)[0], rtol=1e-6))
