"""Time simulation: the reel changer of a drive simulated (the one-angle and the 3D rigid-body model) and
the time step it needs.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
