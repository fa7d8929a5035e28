"""The reel changer with worm and wheel as 3D rigid bodies in elastic bearings: bearing loads and stability.

Model: :func:`~exudyn_worm.builders.rigidbody.BuildRigidBodyReelChanger`: with both shafts on their bearings the
small-displacement model (:mod:`exudyn_worm.items.smallmesh`, the default), otherwise worm and wheel from
``mbs.CreateRigidBody`` coupled by :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`, each shaft on two
radial bearings and an axial bearing (:func:`~exudyn_worm.items.bearings.CreateShaftBearings`) or on ideal revolute
joints. Bearing values: the worm's radial bearings 5e8 N/m each, 0.12 m apart, the wheel's 1e9 N/m, 0.05 m apart
(rolling bearings are about 1e8..1e9 N/m); no bearing damping.

- :func:`BearingLoads`: a run of P1 and the peak loads of the worm's axial and radial bearings and of the wheel's
  bearings, with the peak normal force of the mesh; the worm's axial bearing carries the wheel's tangential force,
  W (cos(alphaN) cos(gamma) -+ mu sin(gamma)), the worm's radial bearings the separating and the worm's tangential
  force.
- :func:`AxialStiffnessScan`: the largest real part of the linearized drive (S = -1, lowering) against the worm's
  axial bearing stiffness, with the worm's radial bearings stiff (1e11 N/m), next to the one-angle model with the
  worm's axial degree of freedom (:func:`~exudyn_worm.items.connector.CreateWormAxialBearing`): the two agree, and
  P1 becomes stable when the axial bearing is softer than about 7e8 N/m (examples/worm_axial_bearing.py).

Run ``python examples/worm_gear_3d.py`` for the table (a few seconds: the rigid-body mesh's law runs in C++,
docs/mesh-3d.md, "Speed").
"""
from __future__ import annotations

from typing import Dict, List, Mapping, Optional, Sequence

import exudyn as exu
import numpy as np

from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability
from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.items.bearings import ShaftBearings
from exudyn_worm.analysis.simulation.reelchanger3d import StoredShaftLoads
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive

#: the bearings of the example (module docstring)
WORM_BEARINGS = ShaftBearings(radialStiffness=5e8, axialStiffness=5e8, span=0.12)
WHEEL_BEARINGS = ShaftBearings(radialStiffness=1e9, axialStiffness=1e9, span=0.05)
#: worm mass in kg (the worm moves axially as a whole)
WORM_MASS = 5.


def BearingLoadSeries(parameters: Optional[Mapping[str, float]] = None, endTime: float = 8.,
                      wormBearings: ShaftBearings = WORM_BEARINGS,
                      wheelBearings: ShaftBearings = WHEEL_BEARINGS) -> Dict[str, np.ndarray]:
    """Time series of a run of the rigid-body reel changer in elastic bearings: mesh normal force and bearing loads.

    Parameters
    ----------
    parameters : mapping, optional
        Parameter set (default reel-P1).
    endTime : float
        Simulated time in s.
    wormBearings, wheelBearings : ShaftBearings
        The bearings.

    Returns
    -------
    dict
        ``time`` (s), ``normalForce`` (N), and per body ``wormAxial``, ``wormRadial`` (magnitude of the vector sum
        of the two radial bearings), ``wheelAxial``, ``wheelRadial`` in N, one value per stored step.
    """
    parameters = dict(GetPreset('reel-P1') if parameters is None else parameters)
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=parameters), wormBearings=wormBearings, wheelBearings=wheelBearings,
                                      wormMass=WORM_MASS)
    model.connector.AddSensors(model.mbs)
    model.mbs.Assemble()
    ss, solverType = SolverSettings(endTime, RecommendedStepSize(ResolveDrive(parameters=parameters)))
    model.mbs.SolveDynamic(ss, solverType=solverType)
    mesh = model.connector.StoredMeshState(model.mbs)
    out = {'normalForce': np.asarray(mesh.normalForce, dtype=float)}
    loads = StoredShaftLoads(model)           # the small-displacement model's or the rigid bodies' (model=...)
    out['time'] = np.asarray(loads['time'], dtype=float)
    for body in ('worm', 'wheel'):
        out[body + 'Axial'] = np.abs(np.asarray(loads[body + 'AxialLoad'], dtype=float))
        out[body + 'Radial'] = np.asarray(loads[body + 'RadialLoad'], dtype=float)
    return out


def BearingLoads(parameters: Optional[Mapping[str, float]] = None, endTime: float = 8.,
                 wormBearings: ShaftBearings = WORM_BEARINGS,
                 wheelBearings: ShaftBearings = WHEEL_BEARINGS,
                 series: Optional[Dict[str, np.ndarray]] = None) -> Dict[str, float]:
    """Peak bearing loads and mesh force in N of a run of the rigid-body reel changer in elastic bearings.

    Parameters
    ----------
    parameters : mapping, optional
        Parameter set (default reel-P1).
    endTime : float
        Simulated time in s.
    wormBearings, wheelBearings : ShaftBearings
        The bearings.
    series : dict, optional
        The run's :func:`BearingLoadSeries` if already computed (the other arguments are then not used).

    Returns
    -------
    dict
        ``normalForce`` (peak mesh normal force), ``wormAxial``, ``wormRadial`` (vector sum of the two radial
        bearings), ``wheelAxial``, ``wheelRadial``: peak magnitudes in N; ``initialNormalForce`` in N.
    """
    if series is None:
        series = BearingLoadSeries(parameters, endTime, wormBearings, wheelBearings)
    out = {'normalForce': float(np.max(np.abs(series['normalForce']))),
           'initialNormalForce': float(abs(series['normalForce'][0]))}
    for key in ('wormAxial', 'wormRadial', 'wheelAxial', 'wheelRadial'):
        out[key] = float(np.max(series[key]))
    return out


#: modes below this frequency in Hz are the drive's torsional modes (the bearings' own modes are above 900 Hz)
DRIVE_MODES_HZ = 200.


def _DriveModeRate(state) -> float:
    """Largest real part in 1/s of the drive's torsional modes (below :data:`DRIVE_MODES_HZ`)."""
    return max(m.eigenvalue.real for m in state.modes if m.frequencyHz < DRIVE_MODES_HZ)


def AxialStiffnessScan(stiffnesses: Sequence[float] = (2e9, 1e9, 7e8, 5e8),
                       parameters: Optional[Mapping[str, float]] = None) -> List[Dict[str, float]]:
    """Largest real part in 1/s of the drive's modes (S = -1) against the worm's axial bearing stiffness: 3D model and
    one-angle model (the undamped bearings' own modes, above 900 Hz, are left out).

    Parameters
    ----------
    stiffnesses : sequence of float
        Axial bearing stiffnesses in N/m.
    parameters : mapping, optional
        Parameter set (default reel-P1).

    Returns
    -------
    list of dict
        ``axialStiffness`` (N/m), ``rigidBodies`` and ``oneAngle``: the largest real parts in 1/s.
    """
    parameters = dict(GetPreset('reel-P1') if parameters is None else parameters)
    rows = []
    for kA in stiffnesses:
        model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=parameters), wormMass=WORM_MASS,
                                          wormBearings=ShaftBearings(radialStiffness=1e11, axialStiffness=kA, span=0.12))
        model.mbs.Assemble()
        rigid = AnalyzeLinearStability(model.mbs).State(-1)
        oneAngle = AnalyzeLinearStability(BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters={**parameters, 'kA': kA, 'dA': 0., 'mA': WORM_MASS})).mbs)
        rows.append({'axialStiffness': kA, 'rigidBodies': _DriveModeRate(rigid),
                     'oneAngle': _DriveModeRate(oneAngle.State(-1))})
    return rows


def _WriteFigure(outDir: str, series: Dict[str, np.ndarray]) -> str:
    """The bearing loads over time (PNG); returns its path."""
    import os
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(9.5, 6), layout='constrained')
    t = series['time']
    axes[0].plot(t, np.abs(series['normalForce']) / 1e3, color='k', lw=0.6, label='mesh normal force')
    axes[0].set_ylabel('force [kN]'), axes[0].legend(fontsize=9, loc='upper left', bbox_to_anchor=(1.01, 1.), frameon=False)
    for key, label in (('wormAxial', 'worm axial bearing'), ('wormRadial', 'worm radial bearings'),
                       ('wheelAxial', 'wheel axial bearing'), ('wheelRadial', 'wheel radial bearings')):
        axes[1].plot(t, series[key] / 1e3, lw=0.6, label=label)
    axes[1].set_xlabel('time [s]'), axes[1].set_ylabel('bearing load [kN]'), axes[1].legend(fontsize=9, loc='upper left', bbox_to_anchor=(1.01, 1.), frameon=False)
    axes[0].set_title('P1 with worm and wheel in elastic bearings: what the chatter puts into the bearings')
    path = os.path.join(outDir, 'bearing_loads_P1.png')
    fig.savefig(path, dpi=120), plt.close(fig)
    return path


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line: print the numbers; with ``--out DIR`` also write the bearing-load figure. Returns the exit status.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).
    """
    import argparse
    import sys
    from exudyn_worm._checks import CheckOutputFolder
    parser = argparse.ArgumentParser(prog='worm_gear_3d.py', description=__doc__.split('\n')[0])
    parser.add_argument('--out', help='folder for the PNG figure (created if missing)')
    args = parser.parse_args(argv)
    try:                                                   # check the output folder before computing
        outDir = None if args.out is None else CheckOutputFolder(parser.prog, '--out', args.out)
    except ValueError as error:
        print(f'{parser.prog}: error: {str(error).split(": ", 1)[1]}', file=sys.stderr)
        return 2
    print('worm axial bearing stiffness vs largest real part (S = -1), 1/s')
    for row in AxialStiffnessScan():
        print(f"  kA = {row['axialStiffness']:8.3g} N/m   rigid bodies {row['rigidBodies']:+8.3f}   "
              f"one-angle + axial DOF {row['oneAngle']:+8.3f}")
    series = BearingLoadSeries()
    print('peak loads in N over 8 s of P1 (elastic bearings):')
    for key, value in BearingLoads(series=series).items():
        print(f'  {key:20s} {value:10.1f}')
    if outDir is not None:
        print(f'\nwrote {_WriteFigure(outDir, series)}')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
