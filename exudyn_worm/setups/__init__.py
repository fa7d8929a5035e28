"""Parameter sets resolved into a drive: the paper's presets and a flat parameter set turned into an
:class:`~exudyn_worm.model.drive.ElasticDrive` (:mod:`.presets`), config files with units (:mod:`.config`) and
duty cycles (:mod:`.duty`).

Imports the layers below (items, model, params).
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
