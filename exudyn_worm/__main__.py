"""``python -m exudyn_worm``: the ``exudyn-worm`` command line."""
import sys

from .cli.main import Main

if __name__ == '__main__':
    sys.exit(Main())
