"""Analyses of a drive: the linearization of any Exudyn system with worm gears (:mod:`.linearization`), stability
charts (:mod:`.charts`, :mod:`.charttable`) and over speed (:mod:`.speedchart`), the design check
(:mod:`.design`), the load-side check (:mod:`.loadside`), the time step (:mod:`.stepsize`), the reel changer's
simulation (:mod:`.reelchanger`), parameter studies (:mod:`.study` with :mod:`.studygrid`, :mod:`.studyrun`,
:mod:`.studyfiles`, and the analytical map :mod:`.studymap`), periodic orbits (:mod:`.orbits`,
:mod:`.continuation`) and the chatter branch (:mod:`.chatter`, :mod:`.chatterbranch`).

Results that can be drawn have a ``.plot()`` method that imports :mod:`exudyn_worm.plotting` when called; nothing
here imports matplotlib.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
