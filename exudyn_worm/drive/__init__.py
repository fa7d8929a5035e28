"""The drive boundary: a preset, a drive file, ``--set`` options or a Python dictionary resolved once into the immutable
:class:`~exudyn_worm.drive.wholedrive.Drive` (:mod:`.wholedrive`); the paper's parameter sets and the flat parameter
set turned into an :class:`~exudyn_worm.model.drive.ElasticDrive` (:mod:`.presets`), config files with units
(:mod:`.config`), duty cycles (:mod:`.duty`) and the operating points of a duty (:mod:`.operatingpoints`).

Imports the layers below (items, model, params).
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
