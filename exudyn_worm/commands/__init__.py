"""The subcommands of ``exudyn-worm``, one module each (registered in :data:`exudyn_worm.cli.COMMAND_MODULES`)."""

__all__: list = []
