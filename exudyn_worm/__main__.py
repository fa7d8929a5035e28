"""``python -m exudyn_worm``: the ``exudyn-worm`` command line."""
import sys

from .cli import Main

if __name__ == '__main__':
    sys.exit(Main())
