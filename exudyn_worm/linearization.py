"""Stability of the elastic worm drive from the Exudyn model itself (``--method exudyn``).

The 2-DOF drive of Figure 2 is built from ordinary Exudyn items and the worm-gear connector with the
contact parameter S held at +1 or -1 (full flank contact, the paper's linear law), then linearized
with ``mbs.ComputeODE2Eigenvalues``. Agreement with :func:`exudyn_worm.stability.AnalyzeStability`
shows that the connector implements eqs. (1)-(2).
"""
from __future__ import annotations

import numpy as np

from .connector import CreateWormGear
from .contact import ContactOptions
from .drive import ElasticDrive
from .drivetrain import CreatePrescribedRotation, CreateRotor, CreateShaft
from .profiles import ConstantSpeed
from .stability import CONTACT_STATES, ContactStability, StabilityAnalysis, _SortEigenvalues

__all__ = ['BuildLinearizationModel', 'ExudynEigenvalues', 'AnalyzeStabilityExudyn']

#: normal pre-deflection in m beyond half the backlash at which the model is linearized (any value > 0
#: gives the same result: with S held the law is linear in the deflection)
_PRELOAD = 1e-6


def BuildLinearizationModel(drive: ElasticDrive, S: int, useSymbolic: bool = True):
    """Exudyn system of Figure 2 (motor held still) with S held at ``S``; returns ``(SC, mbs)``, assembled.

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter held during the linearization, +1 or -1.
    useSymbolic : bool
        Symbolic (C++) or Python user function for the connector.
    """
    import exudyn as exu
    if S not in CONTACT_STATES:
        raise ValueError(f"BuildLinearizationModel: 'S' must be +1 or -1, got {S!r}")
    g = drive.gear
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    deltaPhi = (0.5 * g.backlash + _PRELOAD) / g.normalLever
    motor = CreateRotor(mbs, 1e-3, name='motor')
    worm = CreateRotor(mbs, drive.J1, initialAngle=deltaPhi, name='worm')
    wheel = CreateRotor(mbs, drive.J2, name='wheel')
    CreatePrescribedRotation(mbs, motor, ConstantSpeed(0.), useSymbolic=useSymbolic)
    CreateShaft(mbs, [motor, worm], stiffness=drive.kT, damping=drive.dT)
    CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=g, useSymbolic=useSymbolic,
                   contactOptions=ContactOptions(fixedS=S, dampingCanPull=True))
    mbs.Assemble()
    return SC, mbs


def ExudynEigenvalues(drive: ElasticDrive, S: int, useSymbolic: bool = True) -> np.ndarray:
    """Complex eigenvalues (1/s) of the Exudyn model linearized about the pre-deflected state.

    Parameters
    ----------
    drive : ElasticDrive
        The 2-DOF drive of Figure 2.
    S : int
        Contact parameter held during the linearization, +1 or -1.
    useSymbolic : bool
        Symbolic (C++) or Python user function for the connector.
    """
    SC, mbs = BuildLinearizationModel(drive, S, useSymbolic)
    values, _ = mbs.ComputeODE2Eigenvalues(computeComplexEigenvalues=True, useAbsoluteValues=False)
    return _SortEigenvalues(np.asarray(values, dtype=complex))


def AnalyzeStabilityExudyn(drive: ElasticDrive, useSymbolic: bool = True) -> StabilityAnalysis:
    """Same result type as :func:`~exudyn_worm.stability.AnalyzeStability`, from the Exudyn linearization.

    Parameters
    ----------
    drive : ElasticDrive
    useSymbolic : bool
        Evaluate the connector as symbolic (default) or Python user function.

    Returns
    -------
    StabilityAnalysis
        b-coefficients are those of prod(lambda - lambda_i) over the Exudyn eigenvalues.
    """
    if not isinstance(drive, ElasticDrive):
        raise TypeError(f"AnalyzeStabilityExudyn: 'drive' must be an ElasticDrive, got {type(drive).__name__}")
    return StabilityAnalysis(drive, {S: ContactStability.FromEigenvalues(S, ExudynEigenvalues(drive, S, useSymbolic))
                                     for S in CONTACT_STATES})
