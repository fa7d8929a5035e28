"""Zero level sets on a rectilinear grid by marching squares, as polylines (own code: no matplotlib in the
numerical modules). Used for the boundaries of the stability charts (:mod:`exudyn_worm.analysis.charts.stabilitychart`).
"""
from __future__ import annotations

from typing import Dict, List, Optional

import numpy as np

__all__ = ['ContourLines']

# marching squares: corners 0 (i, j), 1 (i, j+1), 2 (i+1, j+1), 3 (i+1, j) with bit k set if corner k is inside;
# cell edges 0 bottom (0-1), 1 right (1-2), 2 top (3-2), 3 left (0-3); segments per case, saddles 5 and 10
# listed for "centre inside" (they connect around the centre) and "centre outside"
_SEGMENTS = {1: [(3, 0)], 2: [(0, 1)], 3: [(3, 1)], 4: [(1, 2)], 6: [(0, 2)], 7: [(3, 2)], 8: [(2, 3)],
             9: [(2, 0)], 11: [(2, 1)], 12: [(1, 3)], 13: [(1, 0)], 14: [(0, 3)]}
_SADDLE = {(5, True): [(3, 2), (1, 0)], (5, False): [(3, 0), (1, 2)],
           (10, True): [(0, 3), (2, 1)], (10, False): [(0, 1), (2, 3)]}


def ContourLines(u: np.ndarray, v: np.ndarray, field: np.ndarray, inside: Optional[np.ndarray] = None
                 ) -> List[np.ndarray]:
    """Zero level set of ``field`` on a rectilinear grid by marching squares, as polylines.

    Parameters
    ----------
    u : ndarray
        Grid abscissae, shape (nx,), increasing.
    v : ndarray
        Grid ordinates, shape (ny,), increasing.
    field : ndarray
        Shape (ny, nx); a point is inside where ``field <= 0``.
    inside : ndarray of bool, optional
        Overrides the inside test (the crossing is still placed by linear interpolation of ``field``,
        clipped to the edge).

    Returns
    -------
    list of ndarray
        Each of shape (N, 2), columns (u, v); closed curves repeat their first point at the end, curves
        that leave the grid are open.
    """
    field = np.asarray(field, dtype=float)
    ny, nx = field.shape
    ins = field <= 0 if inside is None else np.asarray(inside, dtype=bool)
    if ny < 2 or nx < 2 or ins.all() or not ins.any():
        return []
    # crossing points on horizontal edges (i, j)-(i, j+1) and vertical edges (i, j)-(i+1, j)
    def Crossing(f0, f1):
        with np.errstate(divide='ignore', invalid='ignore'):
            t = np.where(f0 != f1, f0 / (f0 - f1), 0.5)
        return np.clip(np.nan_to_num(t, nan=0.5), 0., 1.)
    th = Crossing(field[:, :-1], field[:, 1:])
    tv = Crossing(field[:-1, :], field[1:, :])
    hu = u[:-1][None, :] + th * np.diff(u)[None, :]                     # (ny, nx-1)
    vv = v[:-1][:, None] + tv * np.diff(v)[:, None]                     # (ny-1, nx)
    nh = ny * (nx - 1)

    def EdgeId(i, j, e):
        # global id of edge e of cell (i, j): horizontal ids first, then vertical
        return np.choose(e, [i * (nx - 1) + j, nh + i * nx + j + 1, (i + 1) * (nx - 1) + j, nh + i * nx + j])

    case = (ins[:-1, :-1].astype(np.int8) | (ins[:-1, 1:] << 1) | (ins[1:, 1:] << 2) | (ins[1:, :-1] << 3))
    centre = (field[:-1, :-1] + field[:-1, 1:] + field[1:, 1:] + field[1:, :-1]) <= 0
    segA, segB = [], []
    for key, segments in list(_SEGMENTS.items()) + list(_SADDLE.items()):
        cells = (case == key) if isinstance(key, int) else (case == key[0]) & (centre == key[1])
        i, j = np.nonzero(cells)
        for ea, eb in segments:
            segA.append(EdgeId(i, j, np.full_like(i, ea)))
            segB.append(EdgeId(i, j, np.full_like(i, eb)))
    A = np.concatenate(segA)
    B = np.concatenate(segB)

    points = np.empty((nh + (ny - 1) * nx, 2))
    ih, jh = np.divmod(np.arange(nh), nx - 1)
    points[:nh, 0], points[:nh, 1] = hu.ravel(), v[ih]
    iv, jv = np.divmod(np.arange((ny - 1) * nx), nx)
    points[nh:, 0], points[nh:, 1] = u[jv], vv.ravel()

    # join segments into polylines: each crossing point belongs to one or two segments
    neighbours: Dict[int, List[int]] = {}
    for a, b in zip(A.tolist(), B.tolist()):
        neighbours.setdefault(a, []).append(b)
        neighbours.setdefault(b, []).append(a)
    lines = []
    unvisited = set(neighbours)
    # open curves start at an end (a crossing point with one neighbour), then the closed ones
    starts = [p for p, n in neighbours.items() if len(n) == 1] + list(neighbours)
    for start in starts:
        if start not in unvisited:
            continue
        path = [start]
        unvisited.discard(start)
        previous, current = None, start
        while True:
            following = [n for n in neighbours[current] if n != previous and n in unvisited]
            if not following:
                if len(path) > 2 and start in neighbours[current] and previous is not None:
                    path.append(start)                                  # closed curve
                break
            previous, current = current, following[0]
            path.append(current)
            unvisited.discard(current)
        lines.append(points[path])
    return lines
