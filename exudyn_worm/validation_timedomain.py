"""Time-domain checks of the paper's statements (section 3.2) against our simulations.

The published statements and their acceptance bands live in ``validation/paper/time_domain.csv``;
this module only computes our value for each row id. Simulations are shared between rows.
"""
from __future__ import annotations

import math
from functools import lru_cache
from typing import Callable, Dict, Tuple

import numpy as np

from .contact import ContactOptions
from .presets import ApplyOverrides, DriveFromParameters, GetPreset
from .reelchanger import DEFAULT_STEP_SIZE, DefaultWindows, SimulateReelChanger
from .stability import AnalyzeStability

__all__ = ['TIME_DOMAIN_CHECKS', 'Simulate', 'PaperMeshConvention']

_RPM = 2 * math.pi / 60


def PaperMeshConvention(parameters):
    """Parameters with kV and dV divided by cos^2(alphaN): the mesh convention identified from the
    paper's printed eigenvalues (see validation/REPORT.md)."""
    p = dict(parameters)
    f = 1. / math.cos(p['alphaN'])**2
    dV = DriveFromParameters(p).gear.dV
    return ApplyOverrides(p, {'kV': p['kV'] * f, 'dV': dV * f})


@lru_cache(maxsize=None)
def Simulate(preset: str, overrides: Tuple = (), stepSize: float = DEFAULT_STEP_SIZE,
             frictionSpeed: float = ContactOptions().frictionSpeed, paperMesh: bool = False):
    """Cached simulation of one rotation of a reel preset with ``overrides`` ((key, value), ...)."""
    p = ApplyOverrides(GetPreset(preset), dict(overrides))
    if paperMesh:
        p = PaperMeshConvention(p)
    return SimulateReelChanger(p, stepSize=stepSize, contactOptions=ContactOptions(frictionSpeed=frictionSpeed))


def _Windows(preset, overrides=()):
    return DefaultWindows(ApplyOverrides(GetPreset(preset), dict(overrides)))


def _Metrics(preset, overrides=(), **kw):
    return Simulate(preset, tuple(overrides), **kw).WindowMetrics(_Windows(preset, overrides))


def _Lowering(preset, overrides=(), **kw):
    return _Metrics(preset, overrides, **kw)[1]


def _YesNo(flags):
    return ','.join('yes' if f else 'no' for f in flags)


def _Window(r, t0, t1):
    return (r.time >= t0) & (r.time <= t1)


def _ChatterFrequencyVsLinear():
    f = _Lowering('reel-P1')['dominantFrequencyHz']
    fLin = float(np.mean(AnalyzeStability(DriveFromParameters(GetPreset('reel-P1'))).contact[-1].frequenciesHz))
    return 100. * (f / fLin - 1.)


def _ForceFactor():
    r = Simulate('reel-P1')
    return _Lowering('reel-P1')['maxNormalForce'] / abs(r.series['normalForce'][0])


def _BacklashFactor(backlash):
    def Compute():
        base = Simulate('reel-P1')
        other = Simulate('reel-P1', (('backlash', backlash),))
        return (np.max(np.abs(other.series['normalForce'][_Window(other, 2, 3)]))
                / np.max(np.abs(base.series['normalForce'][_Window(base, 2, 3)])))
    return Compute


def _SignChangesPerPeriod():
    r = Simulate('reel-P7')
    m = _Window(r, 2, 6)
    s = np.sign(r.series['S'][m])
    changes = np.count_nonzero(np.diff(s[s != 0]))
    periods = 4. * _Lowering('reel-P7')['dominantFrequencyHz']
    return changes / periods


def _FractionSNegativeLifting():
    r = Simulate('reel-P7')
    return 100. * float(np.mean(r.series['S'][_Window(r, 7.9, 8.0)] < 0))


def _StickingFraction():
    r = Simulate('reel-P7')
    return 100. * float(np.mean(np.abs(r.series['sf'][_Window(r, 2, 6)]) < 1))


def _BacklashIndependence():
    peaks = [np.max(np.abs(Simulate('reel-P7', (('backlash', b),)).series['normalForce']))
             for b in (0., 0.25e-3, 0.5e-3, 0.75e-3)]
    return max(peaks) / min(peaks)


def _Robustness(preset):
    def Compute():
        base = _Lowering(preset)
        variants = [_Lowering(preset, stepSize=DEFAULT_STEP_SIZE / 2),
                    _Lowering(preset, frictionSpeed=ContactOptions().frictionSpeed / 10)]
        return 100. * max(abs(v[k] / base[k] - 1.) for v in variants
                          for k in ('maxAbsWheelAcceleration', 'maxNormalForce'))
    return Compute


def _P7Frequency(index, paperMesh=False):
    p = GetPreset('reel-P7')
    p = PaperMeshConvention(p) if paperMesh else p
    return lambda: float(AnalyzeStability(DriveFromParameters(p)).contact[1].frequenciesHz[index])


#: row id of validation/paper/time_domain.csv -> function computing our value
TIME_DOMAIN_CHECKS: Dict[str, Callable[[], object]] = {
    'P1_chatter_windows': lambda: _YesNo(m['chatter'] for m in _Metrics('reel-P1')),
    'P1_chatter_frequency_band': lambda: _Lowering('reel-P1')['dominantFrequencyHz'],
    'P1_chatter_frequency': lambda: _Lowering('reel-P1')['dominantFrequencyHz'],
    'P1_chatter_frequency_vs_linear': _ChatterFrequencyVsLinear,
    'P1_max_acceleration': lambda: _Lowering('reel-P1')['maxAbsWheelAcceleration'],
    'P1_max_acceleration_paper_mesh': lambda: _Lowering('reel-P1', paperMesh=True)['maxAbsWheelAcceleration'],
    'P1_chatter_frequency_paper_mesh': lambda: _Lowering('reel-P1', paperMesh=True)['dominantFrequencyHz'],
    'P1_force_factor': _ForceFactor,
    'P1_load_doubling': lambda: (_Lowering('reel-P1', (('loadMass', 350.),))['maxAbsWheelAcceleration']
                                 / _Lowering('reel-P1')['maxAbsWheelAcceleration']),
    'P1_speed_doubling': lambda: (_Lowering('reel-P1', (('motorSpeed', 945. * _RPM),))['maxAbsWheelAcceleration']
                                  / _Lowering('reel-P1')['maxAbsWheelAcceleration']),
    'P1_backlash_0.25': _BacklashFactor(0.25e-3),
    'P1_backlash_0.5': _BacklashFactor(0.5e-3),
    'P1_backlash_0.75': _BacklashFactor(0.75e-3),
    'P7_max_acceleration': lambda: _Lowering('reel-P7')['maxAbsWheelAcceleration'],
    'P7_to_P1_ratio': lambda: (_Lowering('reel-P7')['maxAbsWheelAcceleration']
                               / _Lowering('reel-P1')['maxAbsWheelAcceleration']),
    'P7_lifting_chatter': lambda: _YesNo([_Metrics('reel-P7')[2]['chatter']]),
    'P7_worm_speed_zero': lambda: _Lowering('reel-P7')['minWormSpeed'],
    'P7_S_sign_changes': _SignChangesPerPeriod,
    'P7_S_negative_lifting': _FractionSNegativeLifting,
    'P7_sticking': _StickingFraction,
    'P7_peak_normal_force': lambda: _Lowering('reel-P7')['maxNormalForce'] / 1e3,
    'P7_backlash_independence': _BacklashIndependence,
    'P7_speed_doubling': lambda: (_Lowering('reel-P7', (('motorSpeed', 945. * _RPM),))['maxAbsWheelAcceleration']
                                  / _Lowering('reel-P7')['maxAbsWheelAcceleration']),
    'P7_natural_frequencies_low': _P7Frequency(0),
    'P7_natural_frequencies_high': _P7Frequency(1),
    'P7_natural_frequency_high_paper_mesh': _P7Frequency(1, paperMesh=True),
    'P2_P5_no_chatter': lambda: _YesNo(any(m['chatter'] for m in _Metrics(p))
                                       for p in ('reel-P2', 'reel-P3', 'reel-P4', 'reel-P5')),
    'P6_chatter': lambda: _YesNo([_Lowering('reel-P6')['chatter']]),
    'P6_no_chatter_DV0.056': lambda: _YesNo([any(m['chatter'] for m in _Metrics('reel-P6', (('DV', 0.056),)))]),
    'P1_step_robustness': _Robustness('reel-P1'),
    'P7_step_robustness': _Robustness('reel-P7'),
}
