"""Graphics of a rigid-body worm mesh for Exudyn's renderer (``mbs.SolutionViewer()``, ``exu.StartRenderer()``).

:func:`AddRigidMeshGraphics` gives the worm its pitch cylinder and the helix of its thread, the wheel its pitch
cylinder and tooth lines on the rim (both drawn in body coordinates, so they turn with the bodies), and adds a
ground object that draws the mesh force on the wheel as an arrow at the pitch point, looked up in the stored
results of the run at the time shown.
"""
from __future__ import annotations

import math
from typing import Any, Dict, Optional

import numpy as np

from .._checks import CheckPositive, CheckSystem

__all__ = ['AddRigidMeshGraphics']


def _Basis(axis: np.ndarray):
    """Two unit vectors perpendicular to ``axis`` and to each other."""
    helper = np.array([1., 0., 0.]) if abs(axis[0]) < 0.9 else np.array([0., 1., 0.])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    return u, np.cross(axis, u)


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
    # worm: pitch cylinder and the thread's helix (lead 2 pi r1 tan(gamma) per turn)
    u, v = _Basis(worm.axis)
    start = worm.axisPoint - 0.5 * wormLength * worm.axis
    lead = 2. * math.pi * r1 * math.tan(gear.gamma)
    angles = np.linspace(0., 2. * math.pi * wormLength / lead, int(48 * wormLength / lead) + 2)
    helix = [start + (a / (2. * math.pi)) * lead * worm.axis + 1.01 * r1 * (math.cos(a) * u + math.sin(a) * v)
             for a in angles]
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

    def Arrow(mbs, t: float):
        """The mesh force on the wheel as an arrow at the pitch point at time t (nearest stored step)."""
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
        return [exu.graphics.Arrow(pAxis=list(connector.geometry.meshPoint), vAxis=list(F), radius=0.05 * r1,
                                   color=color.red)]

    def ArrowGraphics(mbs, itemNumber):
        return Arrow(mbs, mbs.systemData.GetTime(exu.ConfigurationType.Visualization))

    arrow = mbs.AddObject(ObjectGround(visualization=VObjectGround(graphicsDataUserFunction=ArrowGraphics)))
    return {'worm': wormGraphics, 'wheel': wheelGraphics, 'arrowObject': arrow, 'Arrow': Arrow}
