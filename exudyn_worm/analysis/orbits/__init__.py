"""Periodic orbits and the chatter amplitude: orbits by shooting and their continuation, the one-period map of an
Exudyn system, the lowering phase as an autonomous model, its steady chatter, the brute-force check by a long
simulation, the chatter branch and the smallest disturbance that starts chatter.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
