"""Plots: they take result objects and draw, and compute nothing of their own. The only subpackage that imports
matplotlib (when a plot is drawn). Time series of simulations (:mod:`.plot`), stability charts
(:mod:`.plot_charts`), the design check (:mod:`.plot_design`), chatter branches (:mod:`.plot_orbits`) and
parameter studies (:mod:`.plot_study`).
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
