"""The worm-gear model without Exudyn: gear geometry and mesh coefficients (:mod:`.gear`, :mod:`.geometry`),
the contact law (:mod:`.contact`, the one place where mesh forces are computed), the friction laws
(:mod:`.friction`), self-locking (:mod:`.selflocking`), prescribed motions and load laws (:mod:`.profiles`), the
elastic drive of Figure 2 (:mod:`.drive`) and its analytical stability, eqs. (14)-(21) (:mod:`.stability`).

Imports :mod:`exudyn_worm.params` and the helpers only.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
