"""Linear stability: the linearization of any Exudyn system with worm gears, the verdict of a whole drive at
its operating points and the load-side check.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
