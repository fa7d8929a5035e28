"""Linearized stability of any Exudyn system that contains worm-gear connectors.

:func:`AnalyzeLinearStability` takes a system built with ordinary Exudyn items and one or more
:func:`~exudyn_worm.items.connector.CreateWormGear` connectors (and, optionally, the worm's axial bearing). For every
combination of contact states (S = +1 or -1 for each mesh; 2^n states for n meshes) it holds S in each
connector (full flank contact, the paper's linear law: ``ContactOptions(fixedS=S, dampingCanPull=True)``),
lets Exudyn linearize the system about its *initial* state (``mbs.ComputeLinearizedSystem``, constraints such
as a prescribed motor projected out) and returns eigenvalues, damped natural frequencies, Lehr damping, the
verdict and the mode shapes (which coordinates take part in each mode). The connectors' options are restored
afterwards.

The initial state must have every mesh in contact (``|Delta s|`` beyond half the backlash), e.g. the static
equilibrium under load that :func:`~exudyn_worm.builders.oneangle.BuildReelChanger` starts from; for a model of your
own, start every rotor from :func:`~exudyn_worm.items.equilibrium.SteadyInitialState` (docs/equilibrium.md). With S held and
``dampingCanPull`` the mesh law is linear on either flank, so the result does not depend on how deep the
pre-deflection is.

For the 2-DOF drive of Figure 2, :func:`ExudynStabilityAnalysis` builds the model and returns the same type
as :func:`exudyn_worm.model.stability.AnalyzeStability`; the two agree to 1e-6 (tests/test_linearization.py).
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from ..._checks import CheckSystem, JsonNumber
from ...items.connector import CONNECTORS_KEY, WormGearConnector
from ...items.rigidmesh import RIGID_CONNECTORS_KEY, RigidBodyWormGearConnector
from ...model.contact import ContactOptions
from ...model.drive import ElasticDrive
from ...model.gear import WormGear
from ...model.stability import (CONTACT_STATES, SortEigenvalues, AnalyzeStability, ContactStability,
                        OperatingPoint, OperatingPointFromParameters, StabilityAnalysis)
from ...builders.oneangle import BuildReelChanger, ReelChangerModel
from ...builders.rigidbody import BuildRigidBodyReelChanger, RigidBodyReelChanger
from ...builders.start import LinearizationPoint
from ...drive.wholedrive import CheckDrive, Drive

__all__ = ['LinearMode', 'ContactStateLinearization', 'LinearStability', 'AnalyzeLinearStability',
           'LinearizationModel', 'LinearStabilityOfDrive',
           'ExudynStabilityAnalysis']

#: smallest pre-deflection in m beyond half the backlash that AnalyzeLinearStability accepts: Exudyn's
#: numerical differentiation must not cross the kink of the law at contact loss
MINIMUM_PENETRATION = 1e-9
#: eigenvalues with ``|lambda|`` below this fraction of the largest |lambda| count as rigid-body modes
RIGID_BODY_TOLERANCE = 1e-9

_NO_ODE2_NODE_TYPES = ('Ground', 'GenericData', 'GenericODE1', 'GenericAE')


@dataclass(frozen=True)
class LinearMode:
    """One mode of a linearized system: an oscillating pair (reported by its eigenvalue with Im > 0) or a
    real eigenvalue (an overdamped or creeping motion).

    Attributes
    ----------
    eigenvalue : complex
        Eigenvalue in 1/s.
    shape : dict
        Magnitude of each coordinate in the mode shape (position part), divided by the largest one
        (1 for the coordinate that moves most). Coordinates keep their units (rad, m), so compare
        coordinates of one kind, or use ``energyShare``.
    energyShare : dict
        Share of each coordinate in the mode's kinetic energy, ``M_ii |x_i|^2 / sum_j M_jj |x_j|^2`` (sums to 1;
        unit-free, so rotations and axial displacements compare).
    """
    eigenvalue: complex
    shape: Dict[str, float]
    energyShare: Dict[str, float]

    @property
    def frequencyHz(self) -> float:
        """Damped natural frequency ``|Im(lambda)| / (2 pi)`` in Hz (0 for a real eigenvalue)."""
        return abs(self.eigenvalue.imag) / (2 * math.pi)

    @property
    def lehrDamping(self) -> float:
        """Lehr damping ``-Re/|Im|`` as the paper defines it (section 3.1); negative: growing; +-inf if real."""
        lam = self.eigenvalue
        return -lam.real / abs(lam.imag) if lam.imag != 0 else math.copysign(math.inf, -lam.real)

    @property
    def stable(self) -> bool:
        """True if the mode decays (Re(lambda) < 0)."""
        return self.eigenvalue.real < 0

    def Participants(self, threshold: float = 0.1) -> List[str]:
        """Coordinates whose kinetic-energy share is at least ``threshold``, largest first.

        Parameters
        ----------
        threshold : float
            Smallest share in [0, 1].
        """
        return [k for k, v in sorted(self.energyShare.items(), key=lambda kv: -kv[1]) if v >= threshold]

    def ToDict(self) -> Dict:
        """JSON-ready dictionary."""
        return {'eigenvalue': [float(self.eigenvalue.real), float(self.eigenvalue.imag)],
                'frequencyHz': self.frequencyHz, 'lehrDamping': JsonNumber(self.lehrDamping), 'stable': self.stable,
                'shape': dict(self.shape), 'energyShare': dict(self.energyShare)}


@dataclass(frozen=True)
class ContactStateLinearization:
    """The linearized system for one combination of contact states (one S per mesh).

    Attributes
    ----------
    S : tuple of int
        Contact parameter of each mesh, in the order of the analysis' connectors.
    eigenvalues : ndarray
        All eigenvalues of the first-order system in 1/s (conjugate pairs, +Im first, by frequency).
    modes : list of LinearMode
        One per conjugate pair (by increasing frequency), then one per real eigenvalue; rigid-body
        modes (lambda = 0) are left out.
    rigidBodyModes : int
        Number of eigenvalues with ``|lambda|`` below :data:`RIGID_BODY_TOLERANCE` times the largest (free
        rotation of an undriven system); they do not enter the verdict.
    massMatrix, stiffnessMatrix, dampingMatrix : ndarray
        M, K, D of the linearized system in the independent coordinates (constraints projected out).
    nullspace : ndarray
        Rows map the independent coordinates onto all ODE2 coordinates: q = nullspace.T @ q_independent.
    """
    S: Tuple[int, ...]
    eigenvalues: np.ndarray
    modes: List[LinearMode]
    rigidBodyModes: int
    massMatrix: np.ndarray = field(repr=False)
    stiffnessMatrix: np.ndarray = field(repr=False)
    dampingMatrix: np.ndarray = field(repr=False)
    nullspace: np.ndarray = field(repr=False)

    @property
    def stable(self) -> bool:
        """True iff every (non-rigid-body) eigenvalue has a negative real part."""
        return all(m.stable for m in self.modes)

    @property
    def maxRealPart(self) -> float:
        """Largest real part of the (non-rigid-body) eigenvalues in 1/s; > 0: unstable."""
        return max(m.eigenvalue.real for m in self.modes)

    @property
    def frequenciesHz(self) -> np.ndarray:
        """Damped natural frequencies of the oscillating modes in Hz, increasing."""
        return np.array([m.frequencyHz for m in self.modes if m.eigenvalue.imag != 0])

    @property
    def characteristicCoefficients(self) -> np.ndarray:
        """Coefficients b1..b2n of the characteristic polynomial prod(lambda - lambda_i), all eigenvalues."""
        return np.real(np.poly(self.eigenvalues))[1:]

    def ToDict(self) -> Dict:
        """JSON-ready dictionary."""
        return {'S': list(self.S), 'stable': self.stable, 'maxRealPart': self.maxRealPart,
                'eigenvalues': [[float(l.real), float(l.imag)] for l in self.eigenvalues],
                'frequenciesHz': [float(f) for f in self.frequenciesHz], 'rigidBodyModes': self.rigidBodyModes,
                'modes': [m.ToDict() for m in self.modes]}


@dataclass(frozen=True)
class LinearStability:
    """Linear stability of a system with worm-gear meshes, for every combination of contact states.

    Attributes
    ----------
    meshes : list of str
        Names of the connectors (S tuples follow this order).
    coordinates : list of str
        Labels of the system's ODE2 coordinates (node names; ``name[j]`` for multi-coordinate nodes).
    states : dict
        ``{S tuple: ContactStateLinearization}``.
    operatingPoint : OperatingPoint or None
        The steady state the system was linearized about when its friction depends on speed
        (:func:`LinearStabilityOfDrive`); None: as built (the initial state).
    """
    meshes: List[str]
    coordinates: List[str]
    states: Dict[Tuple[int, ...], ContactStateLinearization]
    operatingPoint: Optional[OperatingPoint] = None

    @property
    def stable(self) -> bool:
        """True iff the system is stable in every contact state."""
        return all(s.stable for s in self.states.values())

    def State(self, *S: int) -> ContactStateLinearization:
        """The linearization for contact states ``S`` (one +-1 per mesh), e.g. ``State(-1)``.

        Parameters
        ----------
        S : int
            One contact parameter per mesh, +1 or -1 (``State(-1)``, ``State(1, -1)``); one tuple or list of them
            is accepted too (``State((1, -1))``, a key of :attr:`states`).

        Returns
        -------
        ContactStateLinearization

        Raises
        ------
        TypeError
            If a contact parameter is not a number.
        ValueError
            If ``S`` is not one of the analysed combinations (:attr:`states`).
        """
        w = 'LinearStability.State'
        if len(S) == 1 and isinstance(S[0], (tuple, list, np.ndarray)):
            S = tuple(S[0])
        for s in S:
            if isinstance(s, bool) or not isinstance(s, (int, float, np.integer, np.floating)):
                raise TypeError(f"{w}: each contact parameter 'S' must be +1 or -1 (one per mesh, e.g. State(-1) or "
                                f"State(1, -1)), got {type(s).__name__} {s!r}")
        key = tuple(int(s) if s in CONTACT_STATES else s for s in S)
        if key not in self.states:
            raise ValueError(f"LinearStability.State: expected one of {sorted(self.states)}, got {key}")
        return self.states[key]

    def plot(self, title: Optional[str] = None, ax=None):
        """Draw the eigenvalues of every combination of contact states as growth rate against frequency
        (:func:`exudyn_worm.plotting.plot_stability.PlotEigenvalues`); returns the axes.

        Parameters
        ----------
        title : str, optional
            Title of the axes.
        ax : matplotlib.axes.Axes, optional
            Draw into this axes.
        """
        from ...plotting.plot_stability import PlotEigenvalues
        label = {key: 'S = ' + ', '.join(f'{s:+d}' for s in key) for key in self.states}
        groups = {label[key]: state.eigenvalues for key, state in self.states.items()}
        key = max(self.states, key=lambda k: self.states[k].maxRealPart)
        state = self.states[key]
        lam = np.asarray(state.eigenvalues)
        deciding = complex(lam[int(np.argmin(np.abs(lam.real - state.maxRealPart)))])
        return PlotEigenvalues(groups, (label[key], deciding), title, ax)

    def ToDict(self) -> Dict:
        """JSON-ready dictionary: ``{"meshes", "coordinates", "stable", "states": [...]}``."""
        return {'meshes': list(self.meshes), 'coordinates': list(self.coordinates), 'stable': self.stable,
                'states': [s.ToDict() for s in self.states.values()],
                'operatingPoint': None if self.operatingPoint is None else self.operatingPoint.ToDict()}


def _CoordinateLabels(mbs, size: int) -> List[str]:
    labels = [f'q{i}' for i in range(size)]
    for n in range(mbs.systemData.NumberOfNodes()):
        info = mbs.GetNode(n)
        if any(t in info.get('nodeType', '') for t in _NO_ODE2_NODE_TYPES):
            continue
        count = len(np.ravel(info.get('referenceCoordinates', [])))
        start = mbs.GetNodeODE2Index(n)
        name = info.get('name') or f'node{n}'
        for j in range(count):
            if start + j < size:
                labels[start + j] = name if count == 1 else f'{name}[{j}]'
    return labels


def _MasslessCoordinates(mbs) -> List[int]:
    """ODE2 indices of coordinates without mass of their own: the auxiliary law inputs of rigid-body meshes with the
    law in C++ (tied to the bodies' coordinates, they would take a share of the bodies' kinetic energy)."""
    out = []
    for connector in mbs.variables.get(RIGID_CONNECTORS_KEY, []):
        for node in (connector.compiled or {}).get('nodes', []):
            start = mbs.GetNodeODE2Index(node)
            out += range(start, start + len(np.ravel(mbs.GetNode(node)['referenceCoordinates'])))
    return out


def _LinearizeState(mbs, S, labels) -> ContactStateLinearization:
    linear = mbs.ComputeLinearizedSystem(projectIntoConstraintNullspace=True, returnConstraintNullspace=True)
    if len(linear) == 3:             # a system without constraints: Exudyn returns no nullspace (all independent)
        M, K, D = linear
        N = np.eye(np.atleast_2d(M).shape[0])
    else:
        M, K, D, _, N = linear
    M, K, D, N = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (M, K, D, N))
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ D]])
    values, vectors = np.linalg.eig(A)
    scale = np.max(np.abs(values)) if values.size else 1.
    massDiagonal = np.abs(np.diag(N.T @ M @ N)) if N.shape[0] == n else np.ones(len(labels))
    massDiagonal[_MasslessCoordinates(mbs)] = 0.
    modes, rigid = [], 0
    for k in range(values.size):
        lam = values[k]
        if abs(lam) <= RIGID_BODY_TOLERANCE * scale:
            rigid += 1
            continue
        if lam.imag < 0:
            continue                                              # reported by its conjugate
        x = np.abs(N.T @ vectors[:n, k])
        energy = massDiagonal * x**2
        modes.append(LinearMode(eigenvalue=complex(lam),
                                shape={c: float(v) for c, v in zip(labels, x / np.max(x))},
                                energyShare={c: float(v) for c, v in zip(labels, energy / np.sum(energy))}))
    modes.sort(key=lambda m: (m.eigenvalue.imag == 0, m.frequencyHz, m.eigenvalue.real))
    return ContactStateLinearization(S=tuple(S), eigenvalues=SortEigenvalues(values), modes=modes,
                                     rigidBodyModes=rigid, massMatrix=M, stiffnessMatrix=K, dampingMatrix=D,
                                     nullspace=N)


def _System(where: str, mbs):
    """``mbs`` itself, or the MainSystem a model holds as ``.mbs`` (e.g. a ReelChangerModel)."""
    import exudyn
    inner = getattr(mbs, 'mbs', None)
    return inner if not isinstance(mbs, exudyn.MainSystem) and isinstance(inner, exudyn.MainSystem) else \
        CheckSystem(where, mbs)


def AnalyzeLinearStability(mbs, connectors: Optional[Sequence[WormGearConnector]] = None,
                           contactStates: Optional[Sequence[Sequence[int]]] = None) -> LinearStability:
    """Linearized stability of an Exudyn system with worm-gear meshes, for each combination of contact states.

    Parameters
    ----------
    mbs : exudyn.MainSystem, or an object with one as ``.mbs``
        The system, built with :func:`~exudyn_worm.items.connector.CreateWormGear` (and any Exudyn items), or a model
        that holds it (e.g. the :class:`~exudyn_worm.builders.oneangle.ReelChangerModel` of
        :func:`~exudyn_worm.builders.oneangle.BuildReelChanger`). It is linearized about its initial state, in which
        every mesh must be in contact: build your own model at :func:`~exudyn_worm.items.equilibrium.SteadyInitialState`
        (docs/equilibrium.md).
    connectors : sequence of WormGearConnector or RigidBodyWormGearConnector, optional
        The meshes whose contact state is held; default: every connector built in ``mbs`` (also the meshes between
        rigid bodies of :func:`~exudyn_worm.items.rigidmesh.CreateRigidBodyWormGear`, whose nodes' coordinates,
        ``name[0]`` ... , appear in the mode shapes: positions x, y, z, then the rotation parameters).
    contactStates : sequence of sequences of int, optional
        The combinations to analyse, one +-1 per connector; default: all 2^n combinations,
        ``(+1, ..., +1)`` first.

    Returns
    -------
    LinearStability
        Per state: eigenvalues, modes (frequency, Lehr damping, shape, energy shares), verdict.

    Raises
    ------
    ValueError
        If the system has no connector, a contact state is not +-1 per mesh, or a mesh is not in contact
        (open backlash) at the initial state.
    TypeError
        If ``mbs`` is neither an ``exudyn.MainSystem`` nor holds one as ``.mbs``.

    Notes
    -----
    A gear with a speed-dependent friction law (:mod:`exudyn_worm.model.friction`) is linearized at its initial
    speed and normal force: start the system in the operating state. The friction slope enters with the sign of
    sigma sign(phi1') S, so only the contact state with S = sigma sign(phi1') of the initial state (S = -1 for a
    system that starts lowering) has the physical damping; :func:`LinearizationModel` at a
    :class:`~exudyn_worm.builders.start.LinearizationPoint` with an operating point builds one consistent model per
    contact state.

    Examples
    --------
    >>> import exudyn as exu
    >>> import exudyn_worm as ew
    >>> from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability
    >>> mbs = exu.SystemContainer().AddSystem()
    >>> model = ew.BuildReelChanger(mbs, ew.ResolveDrive('reel-P1'))
    >>> analysis = AnalyzeLinearStability(mbs)
    >>> [round(f, 1) for f in analysis.State(-1).frequenciesHz], analysis.State(-1).stable
    ([40.3, 40.5], False)
    """
    w = 'AnalyzeLinearStability'
    mbs = _System(w, mbs)
    if connectors is None:          # the one-angle meshes, then the meshes between rigid bodies
        connectors = list(mbs.variables.get(CONNECTORS_KEY, [])) + list(mbs.variables.get(RIGID_CONNECTORS_KEY, []))
    connectors = list(connectors)
    if not connectors:
        raise ValueError(f"{w}: the system has no worm-gear connector (build one with CreateWormGear)")
    for c in connectors:
        if not isinstance(c, (WormGearConnector, RigidBodyWormGearConnector)):
            raise TypeError(f"{w}: 'connectors' must hold WormGearConnector objects (or RigidBodyWormGearConnector), "
                            f"got {type(c).__name__}")
    n = len(connectors)
    states = list(itertools.product(CONTACT_STATES, repeat=n)) if contactStates is None else \
        [tuple(s) for s in contactStates]
    for s in states:
        if len(s) != n or any(x not in CONTACT_STATES for x in s):
            raise ValueError(f"{w}: each contact state must be {n} value(s) of +1 or -1 (one per mesh), got {s!r}")
    for c in connectors:
        deltaS = float(c.InitialMeshState(mbs).deltaS)
        if abs(deltaS) - 0.5 * c.gear.backlash < MINIMUM_PENETRATION:
            raise ValueError(f"{w}: mesh '{c.name}' is not in contact at the initial state (|Delta s| = {abs(deltaS):.3g} m, "
                             f"half backlash {0.5 * c.gear.backlash:.3g} m; need {MINIMUM_PENETRATION:g} m more): start "
                             f"from a pre-deflected state, e.g. the static equilibrium under load")
    original = [c.options for c in connectors]
    results = {}
    try:
        for S in states:
            for c, s, o in zip(connectors, S, original):
                c.SetContactOptions(mbs, ContactOptions(frictionSpeed=o.frictionSpeed, dampingCanPull=True, fixedS=s))
            mbs.Assemble()
            labels = _CoordinateLabels(mbs, mbs.systemData.ODE2Size())
            results[tuple(S)] = _LinearizeState(mbs, S, labels)
    finally:
        for c, o in zip(connectors, original):
            c.SetContactOptions(mbs, o)
        mbs.Assemble()
    return LinearStability(meshes=[c.name or f'mesh{i}' for i, c in enumerate(connectors)], coordinates=labels,
                           states=results)


def LinearizationModel(drive: Drive, point: LinearizationPoint = LinearizationPoint(), useSymbolic: bool = True
                       ) -> Union[ReelChangerModel, RigidBodyReelChanger]:
    """The Exudyn model of a drive to linearize, built by its model's builder and assembled: the 3D model
    (:func:`~exudyn_worm.builders.rigidbody.BuildRigidBodyReelChanger`) for a drive with shaft bearings, else the
    one-angle model (:func:`~exudyn_worm.builders.oneangle.BuildReelChanger`) with its chains, axial bearing and
    free motor; no load, the motor at the point's speed, the worm turned into contact.

    Parameters
    ----------
    drive : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`); it needs no duty.
    point : LinearizationPoint
        Where (:class:`~exudyn_worm.builders.start.LinearizationPoint`: at rest, or at an operating point with the
        contact state S held).
    useSymbolic : bool
        Symbolic (C++) or Python user function for the one-angle model's connector (the 3D model's law is
        linearized in Python).

    Returns
    -------
    ReelChangerModel or RigidBodyReelChanger
        The builder's record; its ``mbs`` is assembled.
    """
    import exudyn as exu
    CheckDrive('LinearizationModel', drive)
    mbs = exu.SystemContainer().AddSystem()
    if drive.isRigidBody:
        # the plain-Python law: the C++ law's auxiliary coordinates give the same eigenvalues, but which
        # coordinates Exudyn keeps independent then shifts the modes' energy shares between the bodies' coordinates
        model = BuildRigidBodyReelChanger(mbs, drive, useSymbolic=False, linearization=point)
    else:
        model = BuildReelChanger(mbs, drive, useSymbolic=useSymbolic, linearization=point)
    mbs.Assemble()
    return model


def LinearStabilityOfDrive(whole: Drive, useSymbolic: bool = True) -> LinearStability:
    """:func:`AnalyzeLinearStability` of the Exudyn model of a drive (:func:`LinearizationModel`), with its modes:
    the drive-side and load-side chains, the worm's axial bearing and a free motor where the drive has them; no
    load.

    Parameters
    ----------
    whole : Drive
        The drive (:func:`~exudyn_worm.drive.wholedrive.ResolveDrive`).
    useSymbolic : bool
        Symbolic (C++) or Python user function for the connector.

    Returns
    -------
    LinearStability
        For S = +1 and S = -1; coordinates ``motor, worm, wheel`` (+ ``inertia4``, ..., ``loadInertia1``, ...,
        ``wormAxial``). With the reel-changer keys ``loadMass, leverArm, motorSpeed`` its ``operatingPoint`` is
        steady lowering (:func:`~exudyn_worm.model.stability.OperatingPointFromParameters`); a speed-dependent friction
        law is then linearized there (one model per contact state,
        :class:`~exudyn_worm.builders.start.LinearizationPoint`).
    """
    CheckDrive('LinearStabilityOfDrive', whole, 'whole')
    drive = whole.elastic
    operatingPoint = OperatingPointFromParameters(whole.parameters, drive.gear)
    if operatingPoint is None or not drive.gear.speedDependentFriction:
        mbs = LinearizationModel(whole, LinearizationPoint(), useSymbolic).mbs
        return replace(AnalyzeLinearStability(mbs), operatingPoint=operatingPoint)
    states = {}
    for S in CONTACT_STATES:
        mbs = LinearizationModel(whole, LinearizationPoint(S, operatingPoint), useSymbolic).mbs
        linear = AnalyzeLinearStability(mbs, contactStates=[(S,)])
        states.update(linear.states)
    return replace(linear, states=states, operatingPoint=operatingPoint)


def ExudynStabilityAnalysis(drive: ElasticDrive, useSymbolic: bool = True,
                           operatingPoint: Optional[OperatingPoint] = None) -> StabilityAnalysis:
    """Same result type as :func:`~exudyn_worm.model.stability.AnalyzeStability`, from the Exudyn linearization.

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    useSymbolic : bool
        Evaluate the connector as symbolic (default) or Python user function.
    operatingPoint : OperatingPoint, optional
        Linearize each contact state S in the steady state of that point
        (:class:`~exudyn_worm.builders.start.LinearizationPoint`: speed, normal force on the flank sigma = S); Exudyn differentiates the connector's mu(v) numerically. None: at rest.

    Returns
    -------
    StabilityAnalysis
        b-coefficients are those of prod(lambda - lambda_i) over the Exudyn eigenvalues.
    """
    if not isinstance(drive, ElasticDrive):
        raise TypeError(f"ExudynStabilityAnalysis: 'drive' must be an ElasticDrive, got {type(drive).__name__}")
    twoMass = Drive.OfTwoMass(drive)
    if operatingPoint is not None:
        contact = {}
        for S in CONTACT_STATES:
            mbs = LinearizationModel(twoMass, LinearizationPoint(S, operatingPoint), useSymbolic).mbs
            eigenvalues = AnalyzeLinearStability(mbs, contactStates=[(S,)]).State(S).eigenvalues
            contact[S] = ContactStability.FromEigenvalues(S, eigenvalues)
        return StabilityAnalysis(drive, contact, operatingPoint)
    mbs = LinearizationModel(twoMass, LinearizationPoint(), useSymbolic).mbs
    linear = AnalyzeLinearStability(mbs)
    return StabilityAnalysis(drive, {S: ContactStability.FromEigenvalues(S, linear.State(S).eigenvalues)
                                     for S in CONTACT_STATES})

