"""The benchmark's compiled limit (benchmarks/compiled_reference.py) integrates the same model as scipy's.

Its right-hand side is C generated from the package's laws; here it is compared with the Python
right-hand side of the scipy baseline at sample states and on 3 s of P1 (results only, never times).
"""
import shutil

import numpy as np
import pytest

from exudyn_worm.drive.presets import GetPreset

from conftest import LoadScript

pytestmark = pytest.mark.skipif(shutil.which('cc') is None and shutil.which('gcc') is None,
                                reason='no C compiler')


@pytest.fixture(scope='module')
def modules():
    scipyReference = LoadScript('benchmarks/scipy_reference.py', 'scipy_reference')
    return scipyReference, LoadScript('benchmarks/compiled_reference.py', 'compiled_reference')


@pytest.mark.physics
def test_generated_law_is_the_package_law(modules):
    _, compiled = modules
    source = compiled.ReelChangerC(GetPreset('reel-P1'))
    assert 'sgn(' in source and 'fmax(' in source and 'sin(' in source and 'cos(' in source


@pytest.mark.physics
def test_same_trajectory_as_scipy(modules):
    scipyReference, compiled = modules
    p1 = GetPreset('reel-P1')
    ours = compiled.SolveReelChangerCompiled(p1, endTime=3., rtol=1e-9, atol=1e-11)
    ref = scipyReference.SolveReelChangerScipy(p1, endTime=3., method='LSODA', rtol=1e-9, atol=1e-11)
    np.testing.assert_allclose(ours.time, ref.time, atol=1e-12)
    lifting = ref.time <= 2.
    # quasi-static lifting: same forces to 1e-5 (a 0.1 % change of the load gives 1e-3)
    scale = np.max(np.abs(ref.normalForce[lifting]))
    assert np.max(np.abs(ours.normalForce[lifting] - ref.normalForce[lifting])) < 1e-5 * scale
    # chatter onset after the load reversal: same amplitude of phi2'' within 1 %
    late = ref.time >= 2.5
    assert np.max(np.abs(ours.alpha2[late])) == pytest.approx(np.max(np.abs(ref.alpha2[late])), rel=1e-2)
    assert ours.info['steps'] > 0
