"""The design check: is a drive stable, how far is it from the stability boundary and what would make it stable
(the search, its scans, rules and local charts, the confirmation by simulation; the stability command's hint).
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
