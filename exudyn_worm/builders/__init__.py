"""Exudyn model builders: each takes ``mbs`` and a drive and adds the drive's items.

:mod:`.oneangle` builds the drive with one rotation angle per body, the model of the paper
(:func:`~exudyn_worm.builders.oneangle.BuildReelChanger`).

Imports the layers below (drive, items, model, params).
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
