"""Every public function and class is documented, and every argument of a public function appears in its
docstring (after python-control's docstrings_test)."""
import importlib
import inspect
import pkgutil

import pytest

import exudyn_worm
import validation

MODULES = [importlib.import_module(m.name) for package in (exudyn_worm, validation)
           for m in pkgutil.walk_packages(package.__path__, package.__name__ + '.')
           if not m.name.rsplit('.', 1)[-1].startswith('_')] + [exudyn_worm, validation]
PUBLIC = sorted({(f'{obj.__module__}.{name}', obj) for module in MODULES for name in getattr(module, '__all__', [])
                 for obj in [getattr(module, name)] if inspect.isfunction(obj) or inspect.isclass(obj)},
                key=lambda item: item[0])


def test_every_module_declares_all():
    assert all(hasattr(m, '__all__') for m in MODULES)


@pytest.mark.parametrize('name, obj', PUBLIC, ids=[n for n, _ in PUBLIC])
def test_public_item_is_documented(name, obj):
    doc = inspect.getdoc(obj)
    assert doc and len(doc) > 20, f'{name} has no docstring'
    if inspect.isfunction(obj):
        undocumented = [p for p in inspect.signature(obj).parameters
                        if p not in ('self', 'mbs', 'args', 'kwargs', 'ctx') and p not in doc]
        assert not undocumented, f'{name}: arguments {undocumented} are not documented'
