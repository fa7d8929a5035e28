"""The reel changer with worm and wheel as 3D rigid bodies in elastic bearings: bearing loads, stability, a picture.

Model: :func:`~exudyn_worm.builders.rigidbody.BuildRigidBodyReelChanger`: with both shafts on their bearings the
small-displacement model (:mod:`exudyn_worm.items.smallmesh`, the default), otherwise worm and wheel from
``mbs.CreateRigidBody`` coupled by :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`, each shaft on two
radial bearings and an axial bearing (:func:`~exudyn_worm.items.bearings.CreateShaftBearings`) or on ideal revolute
joints. The drive is ``examples/drives/reel-3d.toml``: P1 with the worm's radial bearings 5e8 N/m each, 0.12 m
apart, the wheel's 1e9 N/m, 0.15 m apart (rolling bearings are about 1e8..1e9 N/m), damping 1e3 N*s/m, and the
bodies as steel cylinders (their own polar and tilt inertia; the rest of J1 and J2 turns with them without tilting).

- :func:`BearingLoads`: a run of P1 and the peak loads of the worm's axial and radial bearings and of the wheel's
  bearings, with the peak normal force of the mesh; the worm's axial bearing carries the wheel's tangential force,
  W (cos(alphaN) cos(gamma) -+ mu sin(gamma)), the worm's radial bearings the separating and the worm's tangential
  force.
- :func:`AxialStiffnessScan`: the largest real part of the linearized drive (S = -1, lowering) against the worm's
  axial bearing stiffness, with the worm's radial bearings stiff (1e11 N/m, undamped) and the wheel on an ideal
  joint, next to the one-angle model with the worm's axial degree of freedom
  (:func:`~exudyn_worm.items.connector.CreateWormAxialBearing`): the two agree, and P1 becomes stable when the axial
  bearing is softer than about 7e8 N/m (examples/worm_axial_bearing.py).
- :func:`TiltInertiaScan`: the verdict while lowering against the wheel's tilt inertia (docs/mesh-3d.md, "Inertia").

Run ``python examples/worm_gear_3d.py`` for the tables; ``--out DIR`` writes the bearing-load figure and a frame of
the run rendered by Exudyn (under a virtual display, ``xvfb-run``, where no display is set); ``--show`` opens
Exudyn's viewer on the run.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from typing import Dict, List, Mapping, Optional, Sequence

import exudyn as exu
import numpy as np

from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability
from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.builders.oneangle import BuildReelChanger
from exudyn_worm.builders.rigidbody import BuildRigidBodyReelChanger
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.analysis.simulation.reelchanger3d import StoredShaftLoads
from exudyn_worm.items.meshgraphics import AddRigidMeshGraphics, RecordSolution, SaveFrame
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import Drive, ResolveDrive

#: the drive of the example (module docstring)
DRIVE_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'drives', 'reel-3d.toml')
#: the worm body of the drive file for the scan over the axial bearing: 5 kg, a steel cylinder 21 mm x 0.46 m
WORM_BODY = {'wormMass': 5., 'wormRadius': 0.021, 'wormLength': 0.46}
#: the picture of the run: its file name in ``--out``
FRAME = 'reel_3d_frame.png'


def Run(drive: Optional[Drive] = None, endTime: float = 8., record: Optional[str] = None):
    """A run of the rigid-body reel changer with the mesh's graphics and sensors (at the drive's recommended step).

    Parameters
    ----------
    drive : Drive, optional
        The drive (default :data:`DRIVE_FILE`).
    endTime : float
        Simulated time in s.
    record : str, optional
        A folder: record the run there for the viewer (:func:`~exudyn_worm.items.meshgraphics.RecordSolution`).

    Returns
    -------
    (RigidBodyReelChanger, str or None)
        The solved model and the recorded solution file.
    """
    drive = ResolveDrive(config=DRIVE_FILE) if drive is None else drive
    # the exact model (rigid bodies): the bodies carry the graphics (the small-displacement model, simulate's default
    # for such a drive, has no bodies to draw; its peaks agree within 1 %, docs/mesh-3d.md)
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), drive, model='exact')
    model.connector.AddSensors(model.mbs)
    AddRigidMeshGraphics(model.mbs, model.connector)
    model.mbs.Assemble()
    ss, solverType = SolverSettings(endTime, RecommendedStepSize(drive))
    path = None if record is None else RecordSolution(ss, folder=record)
    model.mbs.SolveDynamic(ss, solverType=solverType)
    return model, path


def BearingLoadSeries(drive: Optional[Drive] = None, endTime: float = 8.) -> Dict[str, np.ndarray]:
    """Time series of a run of the rigid-body reel changer in elastic bearings: mesh normal force and bearing loads.

    Parameters
    ----------
    drive : Drive, optional
        The drive (default :data:`DRIVE_FILE`).
    endTime : float
        Simulated time in s.

    Returns
    -------
    dict
        ``time`` (s), ``normalForce`` (N), and per body ``wormAxial``, ``wormRadial`` (magnitude of the vector sum
        of the two radial bearings), ``wheelAxial``, ``wheelRadial`` in N, one value per stored step.
    """
    model, _ = Run(drive, endTime)
    mesh = model.connector.StoredMeshState(model.mbs)
    out = {'normalForce': np.asarray(mesh.normalForce, dtype=float)}
    loads = StoredShaftLoads(model)
    out['time'] = np.asarray(loads['time'], dtype=float)
    for body in ('worm', 'wheel'):
        out[body + 'Axial'] = np.abs(np.asarray(loads[body + 'AxialLoad'], dtype=float))
        out[body + 'Radial'] = np.asarray(loads[body + 'RadialLoad'], dtype=float)
    return out


def BearingLoads(drive: Optional[Drive] = None, endTime: float = 8.,
                 series: Optional[Dict[str, np.ndarray]] = None) -> Dict[str, float]:
    """Peak bearing loads and mesh force in N of a run of the rigid-body reel changer in elastic bearings.

    Parameters
    ----------
    drive : Drive, optional
        The drive (default :data:`DRIVE_FILE`).
    endTime : float
        Simulated time in s.
    series : dict, optional
        The run's :func:`BearingLoadSeries` if already computed (the other arguments are then not used).

    Returns
    -------
    dict
        ``normalForce`` (peak mesh normal force), ``wormAxial``, ``wormRadial`` (vector sum of the two radial
        bearings), ``wheelAxial``, ``wheelRadial``: peak magnitudes in N; ``initialNormalForce`` in N.
    """
    if series is None:
        series = BearingLoadSeries(drive, endTime)
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
        worm = {**WORM_BODY, 'wormRadialStiffness': 1e11, 'wormAxialStiffness': kA, 'wormBearingSpan': 0.12}
        model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters={**parameters, **worm}))
        model.mbs.Assemble()
        rigid = AnalyzeLinearStability(model.mbs).State(-1)
        oneAngle = AnalyzeLinearStability(BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters={
            **parameters, 'kA': kA, 'dA': 0., 'mA': WORM_BODY['wormMass']})).mbs)
        rows.append({'axialStiffness': kA, 'rigidBodies': _DriveModeRate(rigid),
                     'oneAngle': _DriveModeRate(oneAngle.State(-1))})
    return rows


#: wheel tilt inertias of :func:`TiltInertiaScan` besides the wheel's own, kg*m^2
TILTS = (1., 5., 16.5, 22., 33., 45., 60.)


def TiltInertiaScan(tilts: Optional[Sequence[float]] = None, drive: Optional[Drive] = None) -> List[Dict[str, float]]:
    """The linearized drive while lowering (S = -1) against the wheel's tilt inertia, the wheel's own polar inertia
    kept (the reel turns with the wheel without tilting with it).

    Parameters
    ----------
    tilts : sequence of float, optional
        The wheel's tilt inertias in kg*m^2 (each >= half its polar inertia); default the wheel's own, then
        :data:`TILTS`.
    drive : Drive, optional
        The drive (default :data:`DRIVE_FILE`).

    Returns
    -------
    list of dict
        ``tiltInertia`` (kg*m^2), ``realPart`` (1/s) and ``frequencyHz`` of the largest real part below
        :data:`DRIVE_MODES_HZ`, ``stable`` (bool, of the whole linearized drive).
    """
    drive = ResolveDrive(config=DRIVE_FILE) if drive is None else drive
    polar = drive.shaftSupports.wheelInertia.polar
    tilts = (drive.shaftSupports.wheelInertia.tilt,) + TILTS if tilts is None else tilts
    rows = []
    for tilt in tilts:
        varied = drive.Replace(wheelTiltInertia=tilt, wheelPolarInertia=polar)
        model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), varied, model='exact')
        model.mbs.Assemble()
        state = AnalyzeLinearStability(model.mbs).State(-1)
        mode = max((m for m in state.modes if m.frequencyHz < DRIVE_MODES_HZ), key=lambda m: m.eigenvalue.real)
        rows.append({'tiltInertia': tilt, 'realPart': mode.eigenvalue.real, 'frequencyHz': mode.frequencyHz,
                     'stable': bool(state.stable)})
    return rows


def WriteFrame(outDir: str) -> str:
    """A frame of a 1 s run (its end: lifting) rendered by Exudyn into ``outDir`` (:data:`FRAME`): with a
    display directly, else under a virtual one (``xvfb-run``, Debian's package xvfb) in a new process; where
    neither is there, a picture that says why. Returns what happened, one line.

    Parameters
    ----------
    outDir : str
        The folder.
    """
    path = os.path.join(outDir, FRAME)
    if os.environ.get('DISPLAY'):
        model, solution = Run(endTime=1., record=outDir)
        SaveFrame(model.mbs, solution, path)
        os.remove(solution)
        return f'wrote {path} (rendered by Exudyn on display {os.environ["DISPLAY"]})'
    xvfb = shutil.which('xvfb-run')
    reason = 'no display is set and xvfb-run (Debian package xvfb) is not installed'
    if xvfb is not None:
        done = subprocess.run([xvfb, '-a', '-s', '-screen 0 1280x800x24', sys.executable, os.path.abspath(__file__),
                               '--frame', outDir], capture_output=True, text=True, timeout=600)
        if done.returncode == 0 and os.path.isfile(path):
            return done.stdout.strip().splitlines()[-1].replace('display', 'virtual display (xvfb-run)', 1)
        reason = f'xvfb-run failed (exit status {done.returncode}: {(done.stderr.strip().splitlines() or [""])[-1]})'
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig = plt.figure(figsize=(8, 2))
    fig.text(0.5, 0.5, f'No rendered frame: {reason}.', ha='center', va='center', wrap=True)
    fig.savefig(path, dpi=100), plt.close(fig)
    return f'wrote {path} without a rendered frame: {reason}'


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
    axes[0].set_title('P1 with worm and wheel in elastic bearings (examples/drives/reel-3d.toml)')
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
    parser.add_argument('--out', help='folder for the PNG figures (created if missing): the bearing loads and a '
                        'rendered frame of the run')
    parser.add_argument('--show', action='store_true', help="open Exudyn's viewer on a 2 s run (needs a display)")
    parser.add_argument('--frame', help=argparse.SUPPRESS)      # render the frame into FRAME (under xvfb-run)
    args = parser.parse_args(argv)
    if args.frame is not None:
        model, solution = Run(endTime=1., record=args.frame)
        SaveFrame(model.mbs, solution, os.path.join(args.frame, FRAME))
        os.remove(solution)
        print(f'wrote {os.path.join(args.frame, FRAME)} (rendered by Exudyn on display {os.environ.get("DISPLAY")})')
        return 0
    try:                                                   # check the output folder before computing
        outDir = None if args.out is None else CheckOutputFolder(parser.prog, '--out', args.out)
    except ValueError as error:
        print(f'{parser.prog}: error: {str(error).split(": ", 1)[1]}', file=sys.stderr)
        return 2
    print('worm axial bearing stiffness vs largest real part (S = -1), 1/s')
    for row in AxialStiffnessScan():
        print(f"  kA = {row['axialStiffness']:8.3g} N/m   rigid bodies {row['rigidBodies']:+8.3f}   "
              f"one-angle + axial DOF {row['oneAngle']:+8.3f}")
    print('wheel tilt inertia vs the drive while lowering (S = -1), the wheel polar inertia kept: largest real part')
    print('below 200 Hz; the wheel bearings 0.15 m apart (reel-3d.toml) and 0.05 m apart')
    drive = ResolveDrive(config=DRIVE_FILE)
    for wide, narrow in zip(TiltInertiaScan(drive=drive), TiltInertiaScan(drive=drive.Replace(wheelBearingSpan=0.05))):
        print(f"  tilt {wide['tiltInertia']:7.4g} kg*m^2   " + '   '.join(
            f"{row['realPart']:+7.3f} 1/s at {row['frequencyHz']:5.1f} Hz {'stable  ' if row['stable'] else 'UNSTABLE'}"
            for row in (wide, narrow)))
    series = BearingLoadSeries()
    print('peak loads in N over 8 s of examples/drives/reel-3d.toml (elastic bearings):')
    for key, value in BearingLoads(series=series).items():
        print(f'  {key:20s} {value:10.1f}')
    if outDir is not None:
        print(f'\nwrote {_WriteFigure(outDir, series)}')
        print(WriteFrame(outDir))
    if args.show:
        import tempfile
        model, _ = Run(endTime=2., record=tempfile.mkdtemp(prefix='worm_gear_3d_'))
        renderer = model.mbs.GetSystemContainer().renderer
        renderer.Attach()
        renderer.Start()
        model.mbs.SolutionViewer()                        # plays the recorded run
        renderer.Stop()
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
