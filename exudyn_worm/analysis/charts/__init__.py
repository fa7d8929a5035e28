"""Stability charts: the analytical chart of the paper over two parameters (with its quartic and contour
lines) and the chart over the speed.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
