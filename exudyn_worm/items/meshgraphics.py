"""Graphics of a rigid-body worm mesh for Exudyn's renderer (``mbs.SolutionViewer()``, ``exu.StartRenderer()``).

:func:`AddRigidMeshGraphics` gives the worm its pitch cylinder and the helix of its thread, with the hand the
mechanics use (:attr:`~exudyn_worm.items.rigidmesh.MeshGeometry.rightHanded`), the wheel its pitch cylinder and
tooth lines on the rim (both drawn in body coordinates, so they turn with the bodies), and adds a ground object that
draws the mesh force on the wheel as an arrow, looked up in the stored results of the run at the time shown. The
arrow starts beside the pitch point, moved along the wheel's axis out of the wheel's face that looks towards +z
(the renderer's default view looks along -z), so that neither body hides it.

:func:`RecordSolution` makes a solve write the coordinates that ``mbs.SolutionViewer()`` plays (into a temporary
folder, not the current directory), so that the viewer shows the run after the solve, and :func:`SaveFrame`
renders one state of a recorded run into a PNG file (it needs a display: a desktop, or a virtual one such as Xvfb).
"""
from __future__ import annotations

import math
import os
import tempfile
from typing import Any, Dict, Optional, Sequence

import numpy as np

from .._checks import CheckPositive, CheckSystem
from .rigidmesh import RigidBodyWormGearConnector

__all__ = ['AddRigidMeshGraphics', 'ThreadHelix', 'ArrowStart', 'RecordSolution', 'SaveFrame']


def _Basis(axis: np.ndarray):
    """Two unit vectors perpendicular to ``axis`` and to each other."""
    helper = np.array([1., 0., 0.]) if abs(axis[0]) < 0.9 else np.array([0., 1., 0.])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    return u, np.cross(axis, u)


def ThreadHelix(connector: RigidBodyWormGearConnector, wormLength: float, pointsPerTurn: int = 48) -> np.ndarray:
    """Points of the worm thread's helix in the worm's body coordinates, on 1.01 r1 over ``wormLength``, with the
    lead ``2 pi r1 tan(gamma)`` per turn and the hand of the mechanics: turning positively about the worm's axis the
    helix advances along the axis for a right-handed thread, against it for a left-handed one.

    Parameters
    ----------
    connector : RigidBodyWormGearConnector
        The mesh.
    wormLength : float
        Length in m of the helix along the axis (> 0), centred on the worm's axis point.
    pointsPerTurn : int
        Points per turn of the helix.

    Returns
    -------
    numpy.ndarray
        The points (n x 3), body coordinates.
    """
    gear, worm = connector.gear, connector._kinematics.bodies[0]
    r1 = gear.r1
    u, v = _Basis(worm.axis)
    sense = 1. if connector.geometry.rightHanded else -1.
    lead = 2. * math.pi * r1 * math.tan(gear.gamma)
    angles = np.linspace(0., 2. * math.pi * wormLength / lead, int(pointsPerTurn * wormLength / lead) + 2)
    start = worm.axisPoint - 0.5 * sense * wormLength * worm.axis
    return np.array([start + sense * (a / (2. * math.pi)) * lead * worm.axis
                     + 1.01 * r1 * (math.cos(a) * u + math.sin(a) * v) for a in angles])


def ArrowStart(connector: RigidBodyWormGearConnector, wheelWidth: float) -> np.ndarray:
    """Where the mesh-force arrow starts (global): the pitch point moved along the wheel's axis by half the wheel's
    drawn width plus r1, out of the face that looks towards +z (the default view), so that neither body hides it.

    Parameters
    ----------
    connector : RigidBodyWormGearConnector
        The mesh.
    wheelWidth : float
        Width in m of the wheel's drawn pitch cylinder.

    Returns
    -------
    numpy.ndarray
        The point (3,), global coordinates of the reference configuration.
    """
    g = connector.geometry
    side = 1. if g.wheelAxis[2] >= 0. else -1.
    return g.meshPoint + side * (0.5 * wheelWidth + connector.gear.r1) * g.wheelAxis


def AddRigidMeshGraphics(mbs, connector, wormLength: Optional[float] = None, wheelWidth: Optional[float] = None,
                         teeth: int = 40, forceScale: Optional[float] = None) -> Dict[str, Any]:
    """Set the bodies' graphics of a rigid-body mesh and add the mesh-force arrow (module docstring).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The system, before ``mbs.Assemble()``.
    connector : RigidBodyWormGearConnector
        The mesh (:func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`); call its ``AddSensors`` too, the
        arrow shows the stored results.
    wormLength, wheelWidth : float, optional
        Length of the worm's and width of the wheel's pitch cylinder in m (default 8 r1 and 2 r1).
    teeth : int
        Number of tooth lines drawn on the wheel's rim (> 0).
    forceScale : float, optional
        Arrow length per force in m/N (default: r2 for the largest stored normal force).

    Returns
    -------
    dict
        ``worm``, ``wheel``: the graphics lists set on the bodies; ``arrowObject``: the ground object of the arrow;
        ``Arrow(mbs, t)``: the arrow's graphics at time t (empty before a solve).

    Raises
    ------
    ValueError
        For a length, width, scale or tooth count that is not positive.
    """
    import exudyn as exu
    from exudyn.itemInterface import ObjectGround, VObjectGround
    w = 'AddRigidMeshGraphics'
    CheckSystem(w, mbs)
    gear, kin = connector.gear, connector._kinematics
    r1, r2 = gear.r1, gear.r2
    wormLength = 8. * r1 if wormLength is None else CheckPositive(w, 'wormLength', wormLength, 'm')
    wheelWidth = 2. * r1 if wheelWidth is None else CheckPositive(w, 'wheelWidth', wheelWidth, 'm')
    if isinstance(teeth, bool) or not isinstance(teeth, int) or teeth < 1:
        raise ValueError(f"{w}: 'teeth' must be an integer > 0, got {teeth!r}")
    if forceScale is not None:
        forceScale = CheckPositive(w, 'forceScale', forceScale, 'm/N')
    color = exu.graphics.color
    worm, wheel = kin.bodies
    # worm: pitch cylinder and the thread's helix (lead 2 pi r1 tan(gamma) per turn, the mechanics' hand)
    start = worm.axisPoint - 0.5 * wormLength * worm.axis
    helix = ThreadHelix(connector, wormLength)
    wormGraphics = [exu.graphics.Cylinder(pAxis=list(start), vAxis=list(wormLength * worm.axis), radius=r1,
                                          color=color.steelblue, nTiles=32),
                    exu.graphics.Lines([list(p) for p in helix], color=color.black)]
    # wheel: pitch cylinder and tooth lines across the rim
    u, v = _Basis(wheel.axis)
    face = wheel.axisPoint - 0.5 * wheelWidth * wheel.axis
    wheelGraphics = [exu.graphics.Cylinder(pAxis=list(face), vAxis=list(wheelWidth * wheel.axis), radius=r2,
                                           color=color.lightgrey, nTiles=64)]
    for k in range(teeth):
        a = 2. * math.pi * k / teeth
        radial = 1.01 * r2 * (math.cos(a) * u + math.sin(a) * v)
        wheelGraphics.append(exu.graphics.Lines([list(face + radial), list(face + wheelWidth * wheel.axis + radial)],
                                                color=color.black))
    for body, graphics in zip(connector.bodyNumbers, (wormGraphics, wheelGraphics)):
        mbs.SetObjectParameter(body, 'VgraphicsData', graphics)

    cache = {}
    arrowStart = ArrowStart(connector, wheelWidth)

    def Arrow(mbs, t: float):
        """The mesh force on the wheel as an arrow beside the pitch point (:func:`ArrowStart`) at time t (nearest
        stored step)."""
        if 'forces' not in cache:
            try:
                cache['forces'] = connector.StoredMeshForces(mbs)
            except ValueError:             # not solved yet (or no sensors): nothing to draw
                return []
        forces = cache['forces']
        k = int(np.argmin(np.abs(forces['time'] - t)))
        scale = forceScale
        if scale is None:
            peak = float(np.max(np.maximum(forces['normalForceFlank1'], forces['normalForceFlank2'])))
            scale = r2 / peak if peak > 0 else 0.
        F = np.asarray(forces['wheelForce'])[k] * scale
        if not np.any(F):
            return []
        return [exu.graphics.Arrow(pAxis=list(arrowStart), vAxis=list(F), radius=0.08 * r1, color=color.red)]

    def ArrowGraphics(mbs, itemNumber):
        return Arrow(mbs, mbs.systemData.GetTime(exu.ConfigurationType.Visualization))

    arrow = mbs.AddObject(ObjectGround(visualization=VObjectGround(graphicsDataUserFunction=ArrowGraphics)))
    return {'worm': wormGraphics, 'wheel': wheelGraphics, 'arrowObject': arrow, 'Arrow': Arrow}


def RecordSolution(simulationSettings: Any, folder: Optional[str] = None, period: float = 0.01) -> str:
    """Make the next solve with ``simulationSettings`` write the coordinates that ``mbs.SolutionViewer()`` plays,
    so that the viewer shows the run (without a written solution it has nothing to play).

    Parameters
    ----------
    simulationSettings : exudyn.SimulationSettings
        The settings of the solve (changed here: ``solution.file`` on, its name and write period).
    folder : str, optional
        Folder of the file (default: a new temporary folder, never the current directory).
    period : float
        Write period in s (> 0): one frame of the viewer per period.

    Returns
    -------
    str
        The path of the solution file the solve writes.

    Raises
    ------
    ValueError
        For a period that is not positive.
    """
    period = CheckPositive('RecordSolution', 'period', period, 's')
    folder = tempfile.mkdtemp(prefix='exudyn_worm_run_') if folder is None else folder
    path = os.path.abspath(os.path.join(folder, 'coordinatesSolution.txt'))
    simulationSettings.solution.file.write = True
    simulationSettings.solution.file.name = path
    simulationSettings.solution.file.binary = False
    simulationSettings.solution.file.writePeriod = period
    return path


def SaveFrame(mbs: Any, solutionFile: str, path: str, time: Optional[float] = None,
              windowSize: Sequence[int] = (1024, 640)) -> str:
    """Render one state of a recorded run (:func:`RecordSolution`) into a PNG file with Exudyn's renderer: the
    renderer opens a window, so this needs a display (a desktop, or a virtual one: ``xvfb-run``).

    Parameters
    ----------
    mbs : exudyn.MainSystem
        The solved system, with its graphics (:func:`AddRigidMeshGraphics`).
    solutionFile : str
        The recorded solution.
    path : str
        The PNG file to write.
    time : float, optional
        The time shown (the nearest recorded one; default the end of the run).
    windowSize : (int, int)
        Width and height of the picture in pixels.

    Returns
    -------
    str
        ``path``.

    Raises
    ------
    RuntimeError
        If no display is set (``DISPLAY``) or the renderer wrote no picture.
    """
    import exudyn as exu
    from exudyn.utilities import LoadSolutionFile, SetSolutionState
    if not os.environ.get('DISPLAY') and not os.environ.get('WAYLAND_DISPLAY'):
        raise RuntimeError('SaveFrame: no display (DISPLAY is not set): run under a desktop or a virtual one '
                           '(xvfb-run)')
    solution = LoadSolutionFile(solutionFile, verbose=False)
    times = np.asarray(solution['data'])[:, 0]
    row = len(times) - 1 if time is None else int(np.argmin(np.abs(times - time)))
    SC = mbs.GetSystemContainer()
    settings = SC.visualizationSettings
    settings.window.renderWindowSize = [int(windowSize[0]), int(windowSize[1])]
    settings.general.autoFitScene = True
    settings.general.drawCoordinateSystem = False
    settings.general.drawWorldBasis = False
    settings.openGL.multiSampling = 4
    for items in (settings.nodes, settings.markers, settings.connectors, settings.loads, settings.sensors):
        items.show = False                    # the bodies, their graphics and the arrow alone
    stem = os.path.splitext(os.path.abspath(path))[0]
    settings.exportImages.saveImageFileName = stem
    settings.exportImages.saveImageFormat = 'PNG'
    settings.exportImages.saveImageSingleFile = True
    SC.renderer.Attach()
    SC.renderer.Start()
    try:
        SetSolutionState(mbs, solution, row, exu.ConfigurationType.Visualization)
        SC.renderer.ZoomAll()
        for _ in range(3):                    # let the renderer fit the scene before the picture
            SC.renderer.DoIdleTasks(0.1)
        SC.renderer.RedrawAndSaveImage()
    finally:
        SC.renderer.Stop()
    written = stem + '.png'
    if not os.path.isfile(written):
        raise RuntimeError(f'SaveFrame: the renderer wrote no picture {written}')
    if written != os.path.abspath(path):
        os.replace(written, path)
    return path
