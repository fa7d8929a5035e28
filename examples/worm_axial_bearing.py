"""The worm's axial bearing: a soft bearing moves P1 off the unstable region (and P2, P5 onto it).

Model: the drive of Figure 2 plus the worm's axial coordinate xA, the worm's axially moving mass mA on the
bearing's axial spring-damper kA, dA to the housing, in series with the mesh:
Delta s = r1 cos(alphaN) sin(gamma) (phi1 - u phi2) + cos(alphaN) cos(gamma) xA, and the worm takes the axial
reaction -c4 F / r2 (derivation in :func:`exudyn_worm.model.contact.MeshContact`). Linearized by Exudyn with S held
(:func:`~exudyn_worm.analysis.stability.linearization.AnalyzeLinearStability` on
:func:`~exudyn_worm.analysis.stability.linearization.LinearizationModel` of a drive with ``kA, dA, mA``): a 3-DOF characteristic
problem in (phi1, phi2, xA), six eigenvalues, a characteristic polynomial of degree 6.

Values: mA = 5 kg (worm, shaft and bearing inner rings of a worm with r1 = 18 mm; the P1 boundary below moves by
0.2 % between 1 and 20 kg), dA = 0 (the bearing's damping is not known; 1e4 N*s/m changes the boundary by less
than 1 %). kA from rigid down to 1e8 N/m: rolling bearings are about 1e8..1e9 N/m (100..1000 N/um) axially,
the order of the mesh stiffness kV = 2e8 N/m.

Findings (numbers from :func:`RunExample`, checked by tests/test_example_worm_axial_bearing.py):

- P1 (set (28)) becomes stable when kA falls below 7.12e8 N/m: the largest real part for S = -1 is
  19.8 1/s with a rigid bearing, 15.9 at 2e9, 10.0 at 1e9 and -1.7 at 5e8 N/m.
- The bearing acts as a spring in series with the mesh: a two-mass drive with
  kV_eff = 1 / (1/kV + cos^2(alphaN) cos^2(gamma) / kA) has its boundary at 7.05e8 N/m (1 % off). At the
  boundary kV_eff = 1.61e8 N/m: the chart point moves from x = kT/(kV r1^2) = 0.107 to 0.134 and leaves
  the unstable region, as a stiffer shaft (P4, x = 0.21) does.
- A soft bearing can also do harm: P2 (J1 tripled) and P5 (kT / 5), stable with a rigid bearing, become
  unstable in a window of soft bearings, P2 for kA between 6.9e7 and 1.90e8 N/m, P5 below 1.30e8 N/m
  (largest real part at 1e8 N/m: +7.0 and +3.5 1/s); P7 needs kA below 1.0e8 N/m to become stable. Much
  softer bearings leave the mesh almost no stiffness and every drive tends to marginal stability.
- The simulations agree: P1 with kA = 5e8 N/m does not chatter (max ``|phi2''|`` while lowering 0.25 rad/s^2),
  with 1e9 N/m it does (77 rad/s^2); P2 with 1e8 N/m vibrates while lowering (112 rad/s^2, the normal force
  swinging across both flanks), which the time-domain verdict reads as decaying: the lever's load falls within the
  lowering window and the swing's rate is then measured uncorrected for it (validation/CHATTER_RULE.md, "What it
  cannot do"); the printed line gives the verdict with its state.

Run ``python examples/worm_axial_bearing.py`` for the table; ``--out DIR`` also writes
axial_bearing_scan.png.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np
from scipy.optimize import brentq

import exudyn_worm as ew
from exudyn_worm._checks import CheckOutputFolder
from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability, LinearizationModel, LinearStability
from exudyn_worm.analysis.simulation.reelchanger import DefaultWindows
from exudyn_worm.drive.wholedrive import ResolveDrive

__all__ = ['AXIAL_MASS', 'AXIAL_DAMPING', 'STIFFNESSES', 'AxialParameters', 'AxialLinearStability',
           'MaxRealPart', 'BoundaryStiffness', 'EquivalentMeshStiffness', 'EquivalentTwoMassMaxRealPart',
           'StabilityTable', 'SimulationCheck', 'RunExample', 'main']

AXIAL_MASS = 5.           #: kg, the worm's axially moving mass
AXIAL_DAMPING = 0.        #: N*s/m, the bearing's axial damping (unknown: none assumed)
#: axial stiffnesses of the table, N/m (None: rigid, no axial degree of freedom)
STIFFNESSES = (None, 2e9, 1e9, 5e8, 2e8, 1e8)


def AxialParameters(preset: str, kA: Optional[float], mA: float = AXIAL_MASS,
                    dA: float = AXIAL_DAMPING) -> Dict[str, float]:
    """Preset plus the axial bearing ``kA, dA, mA`` (``kA`` None: rigid, keys absent).

    Parameters
    ----------
    preset : str
        Preset name, e.g. ``'reel-P1'``.
    kA : float or None
        Axial stiffness in N/m.
    mA : float
        Axially moving mass in kg.
    dA : float
        Axial damping in N*s/m.
    """
    p = ew.GetPreset(preset)
    return p if kA is None else ew.ApplyOverrides(p, {'kA': kA, 'dA': dA, 'mA': mA})


def AxialLinearStability(parameters: Mapping[str, float]) -> LinearStability:
    """The 3-DOF linear problem (phi1, phi2, xA) from the Exudyn model, for S = +1 and S = -1.

    Parameters
    ----------
    parameters : mapping
        Flat parameter set; with ``kA, dA, mA`` the worm has its axial coordinate (else 2 DOF).
    """
    return AnalyzeLinearStability(LinearizationModel(ResolveDrive(parameters=parameters)).mbs)


def MaxRealPart(preset: str, kA: Optional[float], S: int = -1, mA: float = AXIAL_MASS,
                dA: float = AXIAL_DAMPING) -> float:
    """Largest real part (1/s) of the 3-DOF problem in contact state ``S``.

    Parameters
    ----------
    preset : str
        Preset name.
    kA : float or None
        Axial stiffness in N/m (None: rigid).
    S : int
        Contact state, +1 or -1.
    mA, dA : float
        Axially moving mass in kg and axial damping in N*s/m.
    """
    return AxialLinearStability(AxialParameters(preset, kA, mA, dA)).State(S).maxRealPart


def BoundaryStiffness(preset: str, low: float, high: float, mA: float = AXIAL_MASS,
                      dA: float = AXIAL_DAMPING) -> float:
    """The kA in N/m in [low, high] at which the largest real part for S = -1 crosses zero.

    Parameters
    ----------
    preset : str
        Preset name.
    low, high : float
        Bracket in N/m (the verdicts at its ends must differ).
    mA, dA : float
        Axially moving mass in kg and axial damping in N*s/m.
    """
    return brentq(lambda k: MaxRealPart(preset, k, -1, mA, dA), low, high, xtol=1e-4 * low)


def EquivalentMeshStiffness(gear: ew.WormGear, kA: float) -> float:
    """Mesh stiffness in N/m of the mesh in series with the axial bearing: 1/(1/kV + axialLever^2/kA).

    Parameters
    ----------
    gear : WormGear
        The mesh (kV, axialLever = cos(alphaN) cos(gamma)).
    kA : float
        Axial stiffness in N/m.
    """
    return 1. / (1. / gear.kV + gear.axialLever**2 / kA)


def EquivalentTwoMassMaxRealPart(preset: str, kA: float) -> float:
    """Largest real part (1/s, S = -1) of the analytical two-mass drive with kV replaced by
    :func:`EquivalentMeshStiffness` (dV kept): the quasi-static reading of the axial bearing.

    Parameters
    ----------
    preset : str
        Preset name.
    kA : float
        Axial stiffness in N/m.
    """
    p = ew.GetPreset(preset)
    gear = ew.ElasticDriveFromParameters(p).gear
    drive = ew.ElasticDriveFromParameters(ew.ApplyOverrides(p, {'kV': EquivalentMeshStiffness(gear, kA), 'dV': gear.dV}))
    return float(np.max(ew.AnalyzeStability(drive).contact[-1].eigenvalues.real))


def StabilityTable(presets: Sequence[str] = tuple(f'reel-P{i}' for i in range(1, 8)),
                   stiffnesses: Sequence[Optional[float]] = STIFFNESSES) -> Dict[str, List[float]]:
    """Largest real part for S = -1 (1/s) of each preset at each axial stiffness.

    Parameters
    ----------
    presets : sequence of str
        Preset names.
    stiffnesses : sequence of float or None
        Axial stiffnesses in N/m (None: rigid).
    """
    return {name: [MaxRealPart(name, kA) for kA in stiffnesses] for name in presets}


def SimulationCheck(preset: str, kA: float) -> Dict[str, Any]:
    """One rotation of the reel changer with the axial bearing: the lowering window's metrics.

    Parameters
    ----------
    preset : str
        Preset to simulate (mA and dA: the module's defaults).
    kA : float
        The bearing's axial stiffness in N/m.
    """
    p = AxialParameters(preset, kA)
    result = ew.SimulateReelChanger(ResolveDrive(parameters=p))
    lowering = result.WindowMetrics(DefaultWindows(ResolveDrive(parameters=p)))[1]
    return {'preset': preset, 'kA': kA, 'linearStable': MaxRealPart(preset, kA) < 0, **lowering}


def RunExample(simulate: bool = True) -> Dict[str, Any]:
    """Everything the example shows: boundaries, the table, the two-mass reading and the simulations.

    Parameters
    ----------
    simulate : bool
        Also run the three simulations (about 2 s each).
    """
    gear = ew.ElasticDriveFromParameters(ew.GetPreset('reel-P1')).gear
    boundary = BoundaryStiffness('reel-P1', 5e8, 1e9)
    kVeff = EquivalentMeshStiffness(gear, boundary)
    kT, r1 = ew.GetPreset('reel-P1')['kT'], gear.r1
    out = {'boundaryP1': boundary,
           'boundaryP1Mass1kg': BoundaryStiffness('reel-P1', 5e8, 1e9, mA=1.),
           'boundaryP1Mass20kg': BoundaryStiffness('reel-P1', 5e8, 1e9, mA=20.),
           'boundaryP1Damped': BoundaryStiffness('reel-P1', 5e8, 1e9, dA=1e4),
           'twoMassBoundaryP1': brentq(lambda k: EquivalentTwoMassMaxRealPart('reel-P1', k), 5e8, 1e9),
           'boundaryP2': BoundaryStiffness('reel-P2', 1.5e8, 3e8),
           'boundaryP2Low': BoundaryStiffness('reel-P2', 5e7, 8.3e7),
           'boundaryP7': BoundaryStiffness('reel-P7', 9e7, 1.2e8),
           'boundaryP5': BoundaryStiffness('reel-P5', 1.1e8, 3e8),
           'kVeffAtBoundary': kVeff, 'chartXRigid': kT / (gear.kV * r1**2), 'chartXAtBoundary': kT / (kVeff * r1**2),
           'stiffnesses': STIFFNESSES, 'table': StabilityTable()}
    if simulate:
        out['simulations'] = [SimulationCheck(*case) for case in (('reel-P1', 5e8), ('reel-P1', 1e9), ('reel-P2', 1e8))]
    return out


def _Print(run: Dict[str, Any]) -> None:
    print(f"P1 stable for kA < {run['boundaryP1']:.4g} N/m (mA = 1 kg: {run['boundaryP1Mass1kg']:.4g}, 20 kg: "
          f"{run['boundaryP1Mass20kg']:.4g}; dA = 1e4 N*s/m: {run['boundaryP1Damped']:.4g}); two-mass drive with the "
          f"series stiffness: {run['twoMassBoundaryP1']:.4g} N/m")
    print(f"at the boundary kV_eff = {run['kVeffAtBoundary']:.4g} N/m: chart x {run['chartXRigid']:.3f} -> "
          f"{run['chartXAtBoundary']:.3f}")
    print(f"P2 unstable for {run['boundaryP2Low']:.4g} < kA < {run['boundaryP2']:.4g} N/m, P5 for kA < "
          f"{run['boundaryP5']:.4g} N/m; P7 stable for kA < {run['boundaryP7']:.4g} N/m")
    header = ''.join(f"{'rigid' if k is None else f'{k:.0e}':>9}" for k in run['stiffnesses'])
    print(f"\nlargest real part for S = -1 [1/s] against kA [N/m]\n{'':8}{header}")
    for name, row in run['table'].items():
        print(f'{name:8}' + ''.join(f'{x:9.2f}' for x in row))
    for s in run.get('simulations', []):
        rate = '' if s['envelopeRate'] is None else f", rate {s['envelopeRate']:+.2f} 1/s"
        amplitude = '' if s['chatterAmplitude'] is None else f", amplitude {s['chatterAmplitude']:.2f}"
        print(f"simulation {s['preset']} kA = {s['kA']:.0e} N/m: chatter while lowering {s['chatter']} "
              f"({s['chatterState']}{rate}{amplitude}) "
              f"(max |phi2''| {s['maxAbsWheelAcceleration']:.2f} rad/s^2, {s['dominantFrequencyHz']:.1f} Hz); "
              f"linear: {'stable' if s['linearStable'] else 'unstable'}")


def _WriteFigure(outDir: Path) -> Path:
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    kA = np.geomspace(3e7, 1e11, 40)
    fig, ax = plt.subplots(figsize=(7.6, 4), layout='constrained')
    for name in ('reel-P1', 'reel-P2', 'reel-P5', 'reel-P7'):
        ax.semilogx(kA, [MaxRealPart(name, k) for k in kA], label=name.split('-')[1])
    ax.axhline(0, color='k', lw=0.8)
    ax.set(xlabel='axial bearing stiffness kA [N/m]', ylabel='largest real part, S = -1 [1/s]',
           title=f'worm axial bearing (mA = {AXIAL_MASS:g} kg): unstable above 0')
    ax.legend(loc='upper left', bbox_to_anchor=(1.01, 1.), frameon=False)          # beside the axes, over no data
    path = outDir / 'axial_bearing_scan.png'
    fig.savefig(path, dpi=120), plt.close(fig)
    return path


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line: print the numbers; with ``--out DIR`` also write the figure. Returns the exit status.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).
    """
    parser = argparse.ArgumentParser(prog='worm_axial_bearing.py', description=__doc__.split('\n')[0])
    parser.add_argument('--out', help='folder for the PNG figure (created if missing)')
    parser.add_argument('--no-simulation', action='store_true', help='skip the three simulations')
    args = parser.parse_args(argv)
    try:                                                   # check the output folder before computing
        outDir = None if args.out is None else CheckOutputFolder(parser.prog, '--out', args.out)
    except ValueError as error:
        print(f'{parser.prog}: error: {str(error).split(": ", 1)[1]}', file=sys.stderr)
        return 2
    _Print(RunExample(simulate=not args.no_simulation))
    if outDir is not None:
        print(f'\nwrote {_WriteFigure(outDir)}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
