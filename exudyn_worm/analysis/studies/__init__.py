"""Parameter studies: a grid of variations of a drive run point by point (in parallel, resumable), their
files, and the analytical map.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
