"""Analyses of a drive, one subpackage per job, lowest layer first: linear stability (:mod:`.stability`),
stability charts (:mod:`.charts`), time simulation (:mod:`.simulation`), periodic orbits and the chatter
amplitude (:mod:`.orbits`), the design check (:mod:`.design`) and parameter studies (:mod:`.studies`). A
module imports at its top only modules of its own subpackage or of a lower one.

Results that can be drawn have a ``.plot()`` method that imports :mod:`exudyn_worm.plotting` when called; nothing
here imports matplotlib.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
