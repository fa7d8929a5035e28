"""Parameters and files: the parameter registry (:mod:`.parameters`, every key declared once), the whole-drive
TOML files (:mod:`.drivefile`), the drive files and docs that ship with the package (:mod:`.drives`) and the
plausibility of a gear's values (:mod:`.plausibility`).

The lowest layer above the helpers: it imports nothing else of the package.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
