"""The ``exudyn-worm`` command line: what every subcommand shares (:mod:`.main`, with the entry point
:func:`~exudyn_worm.cli.main.Main`) and one module per subcommand (:mod:`.stability`, :mod:`.check`,
:mod:`.chart`, :mod:`.simulate`, :mod:`.sweep`, :mod:`.chatter`). The top layer.
"""

__all__ = []      # the modules of this subpackage are the API; nothing is re-exported here
