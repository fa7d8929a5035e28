"""Drivetrain builders: rotors, shafts, prescribed motion, motor, load and bearing torques.

Everything here is an ordinary Exudyn item (``Node1D`` + ``ObjectRotationalMass1D``,
``CoordinateSpringDamper``, ``CoordinateConstraint``, ``ObjectGenericODE2``), so users can mix these
builders with their own items. Torque laws come from :mod:`exudyn_worm.model.profiles` (or any object with
a ``Torque(phi, omega, t, ops)`` method) and run as symbolic (C++) user functions by default.
"""
from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

from .._checks import CheckBool, CheckName, CheckNonNegative, CheckPositive, CheckReal, CheckSystem
from ._userfunctions import AddCoordinateForce, CheckOffsetLaw, CheckPlainOffsetLaw, SetOffsetFunction
from ..model.profiles import ConstantSpeed

__all__ = ['CreateRotor', 'CreateShaft', 'CreateDriveSideChain', 'CreateLoadSideChain', 'CreatePrescribedRotation', 'CreateRotorTorque',
           'FLYWHEEL_INERTIA']

#: inertia in kg*m^2 of a rotor kept at constant speed as a flywheel (``CreatePrescribedRotation(...,
#: constraint=False)``): a torque ``T`` changes its speed by ``T * h / FLYWHEEL_INERTIA`` in a step ``h``, less than
#: half a rounding unit of any speed above 1e-6 rad/s while ``abs(T) * h < 1e8`` N*m*s, so the rotor turns exactly as
#: prescribed
FLYWHEEL_INERTIA = 1e30


def _Marker(mbs, rotor, where, name):
    """The marker number of a rotor dict (from :func:`CreateRotor`), checked against ``mbs``: the marker must exist
    there and sit on the rotor's node (a rotor of another system fails one of the two in all but coincidences)."""
    if not isinstance(rotor, dict) or 'markerNumber' not in rotor:
        raise TypeError(f"{where}: '{name}' must be a rotor returned by CreateRotor (a dict with 'markerNumber' and "
                        f"'nodeNumber'), got {type(rotor).__name__} {rotor!r}")
    marker = rotor['markerNumber']
    try:
        info = mbs.GetMarker(marker)
    except Exception as err:   # exudyn raises its own index/type errors for an invalid marker
        raise ValueError(f"{where}: '{name}' is not a rotor of this system: its marker {marker!r} does not exist in "
                         f"'mbs' ({err}); was it created in another system?") from None
    if 'nodeNumber' in rotor and ('nodeNumber' not in info or int(info['nodeNumber']) != int(rotor['nodeNumber'])):
        raise ValueError(f"{where}: '{name}' is not a rotor of this system: in 'mbs' its marker {marker!r} is not on "
                         f"node {rotor['nodeNumber']!r} (marker {info!r}); was it created in another system?")
    return marker


def _Pair(where: str, name: str, value, what: str) -> list:
    """``value`` as a list of two items (a sequence, not a string or a mapping)."""
    if isinstance(value, (str, bytes, dict)) or not hasattr(value, '__len__') or not hasattr(value, '__getitem__'):
        raise TypeError(f"{where}: '{name}' must be a list of two {what}, got {type(value).__name__} {value!r}")
    if len(value) != 2:
        raise ValueError(f"{where}: '{name}' must hold two {what}, got {len(value)}: {list(value)!r}")
    return list(value)


def CreateRotor(mbs, inertia: float, initialAngle: float = 0., initialSpeed: float = 0., name: str = '') -> Dict[str, Any]:
    """Add a rotor: ``Node1D`` + ``ObjectRotationalMass1D`` + coordinate marker.

    Parameters
    ----------
    mbs : exudyn.MainSystem
    inertia : float
        Moment of inertia in kg*m^2, > 0.
    initialAngle, initialSpeed : float
        Initial rotation in rad and speed in rad/s.
    name : str

    Returns
    -------
    dict
        ``nodeNumber``, ``objectNumber``, ``markerNumber``.

    Raises
    ------
    TypeError, ValueError
        If ``mbs`` is not an ``exudyn.MainSystem``, ``inertia`` is not > 0, an initial value is not a finite
        number or ``name`` is not a string; nothing is added then.
    """
    from exudyn.itemInterface import MarkerNodeCoordinate, Node1D, ObjectRotationalMass1D
    w = 'CreateRotor'
    CheckSystem(w, mbs)
    inertia = CheckPositive(w, 'inertia', inertia, 'kg*m^2')
    angle, speed = CheckReal(w, 'initialAngle', initialAngle, 'rad'), CheckReal(w, 'initialSpeed', initialSpeed, 'rad/s')
    CheckName(w, 'name', name)
    nNode = mbs.AddNode(Node1D(referenceCoordinates=[0.], initialCoordinates=[angle], initialVelocities=[speed],
                               name=name))
    oBody = mbs.AddObject(ObjectRotationalMass1D(nodeNumber=nNode, inertia=inertia, name=name))
    mNode = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nNode, coordinate=0))
    return {'nodeNumber': nNode, 'objectNumber': oBody, 'markerNumber': mNode}


def CreateShaft(mbs, rotors, stiffness: float, damping: float = 0., name: str = '') -> Dict[str, Any]:
    """Torsional spring-damper (``CoordinateSpringDamper``) between two rotors.

    Parameters
    ----------
    mbs : exudyn.MainSystem
    rotors : [rotor0, rotor1]
        Two different rotors of ``mbs`` from :func:`CreateRotor`.
    stiffness : float
        Torsional stiffness in N*m/rad, > 0.
    damping : float
        Torsional damping in N*m*s/rad, >= 0.

    name : str
        Name of the Exudyn object.

    Returns
    -------
    dict
        ``objectNumber``.

    Raises
    ------
    TypeError, ValueError
        If ``mbs`` is not an ``exudyn.MainSystem``, ``rotors`` is not two different rotors of ``mbs``, or a value
        is out of range; nothing is added then.
    """
    from exudyn.itemInterface import CoordinateSpringDamper
    w = 'CreateShaft'
    CheckSystem(w, mbs)
    rotors = _Pair(w, 'rotors', rotors, 'rotors from CreateRotor')
    markers = [_Marker(mbs, r, w, f'rotors[{i}]') for i, r in enumerate(rotors)]
    if int(markers[0]) == int(markers[1]):
        raise ValueError(f"{w}: 'rotors' must be two different rotors, got the same rotor twice "
                         f"(marker {markers[0]!r}): a shaft from a rotor to itself does nothing")
    stiffness = CheckPositive(w, 'stiffness', stiffness, 'N*m/rad')
    damping = CheckNonNegative(w, 'damping', damping, 'N*m*s/rad')
    o = mbs.AddObject(CoordinateSpringDamper(markerNumbers=markers, stiffness=stiffness, damping=damping,
                                             name=CheckName(w, 'name', name)))
    return {'objectNumber': o}


def CreateLoadSideChain(mbs, wheel, stages: Sequence[Tuple[float, float, float]],
                        initial: Optional[Mapping[str, float]] = None) -> List[Dict[str, Any]]:
    """Add the load-side chain behind ``wheel``: wheel --(kL1, dL1)-- JL1 --(kL2, dL2)-- JL2 -- ...

    Rotor *i* is named ``loadInertia<i>``, the shaft on its wheel side ``loadShaft<i>`` (i from 1). A load
    torque belongs on the last rotor (:func:`CreateRotorTorque`).

    Parameters
    ----------
    mbs : exudyn.MainSystem
    wheel : dict
        The wheel's rotor from :func:`CreateRotor`.
    stages : sequence of (float, float, float)
        ``(J, k, d)`` of each stage, wheel side first: inertia in kg*m^2 (> 0), stiffness in N*m/rad (> 0) and
        damping in N*m*s/rad (>= 0) of the shaft on its wheel side
        (:func:`~exudyn_worm.drive.presets.LoadSideChain` gives them from a parameter set).
    initial : mapping, optional
        Initial angles ``phiL1, ...`` in rad and speeds ``omegaL1, ...`` in rad/s (default 0), e.g. from
        :func:`~exudyn_worm.items.equilibrium.SteadyInitialState`.

    Returns
    -------
    list of dict
        The rotors (:func:`CreateRotor`), wheel side first; empty for no stages.

    Raises
    ------
    TypeError, ValueError
        For a stage that is not three numbers, or a value out of range (:func:`CreateRotor`, :func:`CreateShaft`).
    """
    w = 'CreateLoadSideChain'
    if isinstance(stages, (str, bytes, dict)) or not hasattr(stages, '__iter__'):
        raise TypeError(f"{w}: 'stages' must be a list of (J, k, d) tuples, got {type(stages).__name__} {stages!r}")
    stages = list(stages)
    for i, stage in enumerate(stages):
        if isinstance(stage, (str, bytes, dict)) or not hasattr(stage, '__len__') or len(stage) != 3:
            raise ValueError(f"{w}: 'stages[{i}]' must be (J in kg*m^2, k in N*m/rad, d in N*m*s/rad), got {stage!r}")
    initial = {} if initial is None else initial
    rotors, previous = [], wheel
    for i, (J, k, d) in enumerate(stages, start=1):
        rotor = CreateRotor(mbs, J, initialAngle=initial.get(f'phiL{i}', 0.), initialSpeed=initial.get(f'omegaL{i}', 0.),
                            name=f'loadInertia{i}')
        CreateShaft(mbs, [previous, rotor], stiffness=k, damping=d, name=f'loadShaft{i}')
        rotors.append(rotor)
        previous = rotor
    return rotors


def CreateDriveSideChain(mbs, motor, worm, shaftStiffness: float, shaftDamping: float,
                         stages: Sequence[Tuple[float, float, float]],
                         initial: Optional[Mapping[str, float]] = None) -> List[Dict[str, Any]]:
    """Add the drive shaft and the drive-side chain of Figure 19 between ``worm`` and ``motor``:
    worm --(kT, dT)-- J4 --(k4, d4)-- J5 ... --(kn, dn)-- motor; without stages the drive shaft joins worm and motor.

    Rotor *i* is named ``inertia<i>`` (i from 4), the drive shaft ``driveShaft`` and the shaft on rotor *i*'s motor
    side ``springDamper<i>``. Both one-angle builders (the time simulation's and the linearization's) add the chain
    with this function.

    Parameters
    ----------
    mbs : exudyn.MainSystem
    motor : dict
        The motor's rotor from :func:`CreateRotor`.
    worm : dict
        The worm's rotor from :func:`CreateRotor`.
    shaftStiffness : float
        kT of the drive shaft in N*m/rad, > 0.
    shaftDamping : float
        dT of the drive shaft in N*m*s/rad, >= 0.
    stages : sequence of (float, float, float)
        ``(J, k, d)`` of each stage, worm side first: inertia in kg*m^2, and stiffness and damping of the shaft on its
        motor side (:func:`~exudyn_worm.drive.presets.DriveSideChain` gives them from a parameter set).
    initial : mapping, optional
        Initial angles ``phi4, ...`` in rad and speeds ``omega4, ...`` in rad/s (default 0).

    Returns
    -------
    list of dict
        The chain's rotors (:func:`CreateRotor`), worm side first; empty for no stages.
    """
    initial = {} if initial is None else initial
    rotors = [CreateRotor(mbs, J, initialAngle=initial.get(f'phi{i}', 0.), initialSpeed=initial.get(f'omega{i}', 0.),
                          name=f'inertia{i}') for i, (J, _, _) in enumerate(stages, start=4)]
    CreateShaft(mbs, [(rotors + [motor])[0], worm], stiffness=shaftStiffness, damping=shaftDamping, name='driveShaft')
    for i, (rotor, motorSide, (_, k, d)) in enumerate(zip(rotors, rotors[1:] + [motor], stages), start=4):
        CreateShaft(mbs, [motorSide, rotor], stiffness=k, damping=d, name=f'springDamper{i}')
    return rotors


def CreatePrescribedRotation(mbs, rotor, profile, name: str = '', useSymbolic: bool = True,
                             constraint: bool = True) -> Dict[str, Any]:
    """Prescribe the rotation of ``rotor`` to ``profile`` (e.g. :class:`~exudyn_worm.model.profiles.ConstantSpeed`).

    Uses a ``CoordinateConstraint`` to ground with an offset user function, which the implicit
    solvers (generalized-alpha, trapezoidal index 2) honour. A :class:`~exudyn_worm.model.profiles.ConstantSpeed`
    whose initial angle and speed the rotor already has is prescribed on velocity level instead
    (``velocityLevel=True``, ``offset`` = the speed): the same motion without a user function. Explicit solvers ignore it (they pin the
    coordinate to 0): use an implicit solver, or a stiff shaft to a driven rotor.

    With ``constraint=False`` such a rotor (a :class:`~exudyn_worm.model.profiles.ConstantSpeed` it starts on) is
    kept at its speed by its inertia instead: it becomes a flywheel of :data:`FLYWHEEL_INERTIA`, whose speed no
    torque of a drive changes by a rounding unit, so it turns exactly as prescribed, without the constraint's
    algebraic equation. A time simulation gets the same numbers with fewer instructions (the reel changer's P1 and
    P7: bit for bit, 12 % fewer for P1; benchmarks/README.md); a linearization needs the constraint (the flywheel is a
    free rotation). Other profiles always get the constraint.

    Parameters
    ----------
    mbs : exudyn.MainSystem
    rotor : dict
        Rotor from :func:`CreateRotor`.
    profile : object with ``AngleAndSpeed(t, ops)``
        E.g. :class:`~exudyn_worm.model.profiles.ConstantSpeed` or :class:`~exudyn_worm.model.profiles.StartStopProfile`.
    name : str
        Name of the constraint.
    useSymbolic : bool
        Symbolic (C++) offset user functions (default) or plain Python.
    constraint : bool
        True (default): a ``CoordinateConstraint``; False: a constant speed the rotor starts on by the rotor's
        inertia (set to :data:`FLYWHEEL_INERTIA`), other profiles by the constraint.

    Returns
    -------
    dict
        ``objectNumber``, ``groundNodeNumber`` (both None for a flywheel).

    Raises
    ------
    ValueError
        With ``useSymbolic``, if the recorded profile differs from the profile evaluated in Python at a few
        sample times (a Python ``if`` or ``math`` function on ``t`` records a constant); nothing is added then.
        Also if ``rotor`` is not a rotor of ``mbs``.
    TypeError
        If ``mbs`` is not an ``exudyn.MainSystem``, ``rotor`` is not a rotor dict, ``profile`` has no
        ``AngleAndSpeed`` or ``name`` is not a string.
    """
    from exudyn.itemInterface import CoordinateConstraint, MarkerNodeCoordinate, NodePointGround
    w = 'CreatePrescribedRotation'
    CheckSystem(w, mbs)
    marker = _Marker(mbs, rotor, w, 'rotor')
    CheckName(w, 'name', name)
    CheckBool(w, 'useSymbolic', useSymbolic)
    CheckBool(w, 'constraint', constraint)
    if not callable(getattr(profile, 'AngleAndSpeed', None)):
        raise TypeError(f"{w}: 'profile' must have AngleAndSpeed(t, ops) (e.g. ConstantSpeed), got {type(profile).__name__}")
    constantSpeed = _ConstantSpeedFromStart(mbs, rotor, profile)
    if constantSpeed is not None and not constraint:
        if 'objectNumber' not in rotor:
            raise TypeError(f"{w}: with constraint=False 'rotor' must be a rotor returned by CreateRotor (a dict with "
                            f"'objectNumber', its ObjectRotationalMass1D), got {rotor!r}")
        # the rotor keeps its speed to the last bit: the same motion as the constraint's, without its equation
        mbs.SetObjectParameter(rotor['objectNumber'], 'inertia', FLYWHEEL_INERTIA)
        return {'objectNumber': None, 'groundNodeNumber': None}
    if useSymbolic and constantSpeed is None:   # before anything is added: a law recorded wrongly is refused
        CheckOffsetLaw(w, profile.AngleAndSpeed, 'profile.AngleAndSpeed(t, ops)')
    elif constantSpeed is None:
        CheckPlainOffsetLaw(w, profile.AngleAndSpeed, 'profile.AngleAndSpeed(t, ops)')
    nGround = mbs.AddNode(NodePointGround())
    mGround = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nGround, coordinate=0))
    if constantSpeed is not None:
        # phi0' = speed with phi0(0) already right: the same motion without user functions, 5-7 % faster
        # (benchmarks/README.md, lever 'velocity-level motor constraint')
        o = mbs.AddObject(CoordinateConstraint(markerNumbers=[mGround, marker], velocityLevel=True,
                                               offset=constantSpeed, name=name))
    else:
        o = mbs.AddObject(CoordinateConstraint(markerNumbers=[mGround, marker], name=name))
        SetOffsetFunction(mbs, o, profile.AngleAndSpeed, useSymbolic=useSymbolic, check=False)
    return {'objectNumber': o, 'groundNodeNumber': nGround}


def _ConstantSpeedFromStart(mbs, rotor, profile):
    """The speed of a :class:`~exudyn_worm.model.profiles.ConstantSpeed` profile if the rotor starts exactly on it
    (initial angle and speed equal the profile's), else None (then the angle is prescribed by a user function)."""
    if type(profile) is not ConstantSpeed:
        return None
    node = mbs.GetNode(mbs.GetMarker(rotor['markerNumber'])['nodeNumber'])
    angle, speed = float(node['initialCoordinates'][0]), float(node['initialVelocities'][0])
    return profile.speed if (angle, speed) == (profile.initialAngle, profile.speed) else None


def CreateRotorTorque(mbs, rotor, law, name: str = '', useSymbolic: bool = True) -> Dict[str, Any]:
    """Apply a torque M(phi, omega, t) to ``rotor``.

    Use it for the reel changer's load (:class:`~exudyn_worm.model.profiles.GravityLeverTorque`), a motor
    characteristic (:class:`~exudyn_worm.model.profiles.LinearMotorCharacteristic`), bearing friction
    (:class:`~exudyn_worm.model.profiles.CoulombViscousFriction`) or your own law. Implemented as an
    ``ObjectConnectorCoordinateSpringDamper`` from ground with a user-function force (the torque may depend on
    angle, speed and time; cheaper in Exudyn than a one-node ``ObjectGenericODE2``, with the same forces).

    Parameters
    ----------
    mbs : exudyn.MainSystem
    rotor : dict
        Rotor from :func:`CreateRotor`.
    law : object with ``Torque(phi, omega, t, ops)``, or a callable ``law(phi, omega, t, ops)``
        Torque in N*m. Write it with the functions of ``ops`` (``ops.sin``, ``ops.max``, ``ops.where`` ...)
        instead of ``math``/``if`` so that it can be recorded as a C++ symbolic user function.
    name : str
    useSymbolic : bool
        Symbolic (C++) user function (default) or plain Python.

    Returns
    -------
    dict
        ``objectNumber``.

    Raises
    ------
    ValueError
        With ``useSymbolic``, if the recorded law differs from the law evaluated in Python at a few sample
        states (a Python ``if`` or ``math.cos`` on the arguments records a constant); nothing is added then.
    TypeError
        If ``mbs`` is not an ``exudyn.MainSystem``, ``rotor`` is not a rotor dict, ``law`` is not a torque law,
        raises a TypeError when called (e.g. the wrong number of arguments), returns something else than a
        number, or cannot be recorded (e.g. numpy functions on the arguments).

    Examples
    --------
    A torque ramp of 10 N*m/s, capped at 50 N*m::

        CreateRotorTorque(mbs, wheel, lambda phi, omega, t, ops: ops.min(10. * t, 50.))
    """
    w = 'CreateRotorTorque'
    CheckSystem(w, mbs)
    torque = law.Torque if hasattr(law, 'Torque') else law
    if not callable(torque):
        raise TypeError(f"{w}: 'law' must have Torque(phi, omega, t, ops) or be a callable (phi, omega, t, ops), "
                        f"got {type(law).__name__}")
    marker = _Marker(mbs, rotor, w, 'rotor')
    node = mbs.GetMarker(marker)['nodeNumber']
    CheckName(w, 'name', name)
    CheckBool(w, 'useSymbolic', useSymbolic)
    o, _ = AddCoordinateForce(mbs, node, marker, lambda t, phi, omega, ops: torque(phi, omega, t, ops),
                              name=name, useSymbolic=useSymbolic, where=w,
                              signature='law.Torque(phi, omega, t, ops)' if torque is not law
                              else 'law(phi, omega, t, ops)')
    return {'objectNumber': o}
