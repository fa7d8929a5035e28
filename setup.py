"""Build hook: the wheel carries the example drive files and the user documentation.

``examples/drives/*.toml`` are copied to ``exudyn_worm/drives/`` and ``docs/*.md`` to ``exudyn_worm/docs/``
of the built package (:mod:`exudyn_worm.params.drives` finds them there; in a checkout it reads the originals, so
the repository keeps one copy of each). Everything else is in pyproject.toml.
"""
import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent
SHIPPED = (('examples/drives', '*.toml', 'drives'), ('docs', '*.md', 'docs'))


class BuildPyWithData(build_py):
    """build_py, then the shipped drives and docs into the built package."""

    def run(self):
        super().run()
        for source, pattern, target in SHIPPED:
            folder = Path(self.build_lib) / 'exudyn_worm' / target
            folder.mkdir(parents=True, exist_ok=True)
            for path in sorted((ROOT / source).glob(pattern)):
                shutil.copy2(path, folder / path.name)


setup(cmdclass={'build_py': BuildPyWithData})
