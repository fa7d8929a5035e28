"""FindRoot (replaces scipy.optimize.brentq in the package)."""
import math

import pytest

from exudyn_worm._roots import FindRoot


@pytest.mark.physics
@pytest.mark.parametrize('f, a, b, root', [
    (lambda x: x**3 - 2, 0., 2., 2**(1 / 3)),
    (lambda x: math.cos(x) - x, 0., 1., 0.7390851332151607),
    (lambda x: 3e8 * max(x - 1e-6, 0.) - 5e3, 0., 1e-3, 1e-6 + 5e3 / 3e8),     # clipped linear law
    (lambda x: math.exp(x) - 1e-300, -800., 1., math.log(1e-300)),             # products would underflow
    (lambda x: x, 0., 1., 0.),
])
def test_find_root(f, a, b, root):
    assert FindRoot(f, a, b) == pytest.approx(root, rel=1e-14, abs=1e-15)


@pytest.mark.messages
def test_find_root_needs_a_bracket():
    with pytest.raises(ValueError, match='opposite signs'):
        FindRoot(lambda x: x * x + 1., -1., 1.)
