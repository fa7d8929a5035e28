"""The module paths before the subpackages (issue 17): ``exudyn_worm.presets`` is now
``exudyn_worm.setups.presets`` and so on. Scripts that import an old path get the new module and a
``DeprecationWarning`` that names it; ``import exudyn_worm as ew`` and the names it exports never changed.
"""
from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings

__all__ = ['MOVED', 'InstallMovedModuleFinder']

#: old module (below ``exudyn_worm.``) -> its subpackage path since the package has layers
MOVED = {
    **{name: f'params.{name}' for name in ('parameters', 'drivefile', 'drives', 'plausibility')},
    **{name: f'model.{name}' for name in ('gear', 'friction', 'geometry', 'drive', 'contact', 'selflocking',
                                          'profiles', 'stability')},
    **{name: f'items.{name}' for name in ('connector', '_userfunctions', 'drivetrain', 'equilibrium', 'solve',
                                          'results')},
    **{name: f'setups.{name}' for name in ('presets', 'config', 'duty')},
    **{name: f'analysis.{name}' for name in ('charts', 'charttable', 'linearization', 'speedchart', 'loadside',
                                             'stepsize', 'design', 'study', 'studymap', 'reelchanger', 'orbits',
                                             'continuation', 'chatter', 'chatterbranch')},
    **{name: f'plotting.{name}' for name in ('plot', 'plot_charts', 'plot_design', 'plot_orbits', 'plot_study')},
    'commands': 'cli',
    **{f'commands.{name}': f'cli.{name}' for name in ('chart', 'chatter', 'check', 'simulate', 'stability', 'sweep')},
}
_PREFIX = 'exudyn_worm.'


class _MovedModuleFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds ``exudyn_worm.<old>`` and hands out the module at its new path."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname.startswith(_PREFIX) and fullname[len(_PREFIX):] in MOVED:
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        new = _PREFIX + MOVED[spec.name[len(_PREFIX):]]
        warnings.warn(f"{spec.name} is now {new} (the package is split into subpackages, docs/development.md); import the new path",
                      DeprecationWarning, stacklevel=2)
        return importlib.import_module(new)

    def exec_module(self, module):
        pass                                # the module at the new path is already executed


def InstallMovedModuleFinder() -> None:
    """Put the finder of the old module paths on ``sys.meta_path`` (once)."""
    if not any(isinstance(finder, _MovedModuleFinder) for finder in sys.meta_path):
        sys.meta_path.insert(0, _MovedModuleFinder())     # first: the path finder would load a second copy
