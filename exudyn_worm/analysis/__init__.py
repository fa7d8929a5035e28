"""Analyses of a drive: the linearization of any Exudyn system with worm gears (:mod:`.linearization`), stability
charts (:mod:`.charts`) and over speed (:mod:`.speedchart`), the design check (:mod:`.design` with
:mod:`.designscan`, :mod:`.designrules`, :mod:`.designchart`, :mod:`.designconfirm`; the stability command's hint
:mod:`.stabilityhint`), the load-side check (:mod:`.loadside`), the time step (:mod:`.stepsize`), the reel changer's
simulation (:mod:`.reelchanger`), parameter studies (:mod:`.study` with :mod:`.studygrid`, :mod:`.studypoint`,
:mod:`.studyfiles`, and the analytical map :mod:`.studymap`), periodic orbits (:mod:`.orbits`,
:mod:`.continuation`, the one-period map :mod:`.exudynflow`), the lowering phase's steady chatter (:mod:`.lowering`,
:mod:`.chatter`, the brute-force check :mod:`.longsimulation`) and the chatter branch (:mod:`.chatterbranch`,
:mod:`.smoothbranch`, :mod:`.disturbance`).

Results that can be drawn have a ``.plot()`` method that imports :mod:`exudyn_worm.plotting` when called; nothing
here imports matplotlib.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
