"""The Exudyn items: the worm-gear connector (:mod:`.connector`) and the recording of its user functions
(:mod:`._userfunctions`), rotors, shafts, motors and loads (:mod:`.drivetrain`), the static equilibrium under
load (:mod:`.equilibrium`), the solver call with progress and clear failures (:mod:`.solve`) and the
simulation results (:mod:`.results`).

Imports :mod:`exudyn_worm.model`, :mod:`exudyn_worm.params` and the helpers.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
