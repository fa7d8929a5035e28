"""exudyn-worm: worm-gear chatter analysis and simulation for Exudyn.

Analytical theory (:func:`AnalyzeStability`), the Exudyn worm-gear connector (:func:`CreateWormGear`),
drivetrain builders, the paper's reel changer (:func:`SimulateReelChanger`) and presets. SI units,
angles in rad. Plotting lives in :mod:`exudyn_worm.plot` (the only module importing matplotlib).
"""
from .gear import WormGear
from .drive import (ElasticDrive, MeshDampingFromMeasure, MeshDampingMeasure,
                    TorsionalDampingFromMeasure, TorsionalDampingMeasure)
from .stability import AnalyzeStability, StabilityAnalysis, ContactStability
from .contact import ContactOptions, MeshContact, MeshState
from .connector import AxialBearing, CreateWormAxialBearing, CreateWormGear, WormGearConnector
from .drivetrain import CreatePrescribedRotation, CreateRotor, CreateShaft, CreateRotorTorque
from .profiles import (ConstantSpeed, CoulombViscousFriction, GravityLeverTorque, LinearMotorCharacteristic,
                       StartStopProfile)
from .presets import ApplyOverrides, DriveFromParameters, GetPreset, PRESETS
from .linearization import AnalyzeLinearStability, AnalyzeStabilityExudyn, LinearStability
from .reelchanger import BuildReelChanger, SimulateReelChanger
from .results import SimulationResult

__version__ = '0.1.0'

__all__ = ['WormGear', 'ElasticDrive', 'MeshDampingFromMeasure', 'MeshDampingMeasure',
           'TorsionalDampingFromMeasure', 'TorsionalDampingMeasure', 'AnalyzeStability',
           'StabilityAnalysis', 'ContactStability', 'ContactOptions', 'MeshContact', 'MeshState',
           'CreateWormGear', 'WormGearConnector', 'AxialBearing', 'CreateWormAxialBearing', 'CreatePrescribedRotation', 'CreateRotor', 'CreateShaft',
           'CreateRotorTorque', 'ConstantSpeed', 'CoulombViscousFriction', 'GravityLeverTorque',
           'LinearMotorCharacteristic', 'StartStopProfile', 'ApplyOverrides', 'DriveFromParameters', 'GetPreset',
           'PRESETS', 'AnalyzeStabilityExudyn', 'AnalyzeLinearStability', 'LinearStability', 'BuildReelChanger', 'SimulateReelChanger', 'SimulationResult',
           'AddMainSystemMethods', '__version__']

_MAIN_SYSTEM_METHODS = {'CreateWormGear': CreateWormGear, 'CreateWormAxialBearing': CreateWormAxialBearing,
                        'CreateRotor': CreateRotor, 'CreateShaft': CreateShaft,
                        'CreatePrescribedRotation': CreatePrescribedRotation, 'CreateRotorTorque': CreateRotorTorque}


def AddMainSystemMethods() -> None:
    """Attach the builders to ``exudyn.MainSystem`` so that ``mbs.CreateWormGear(...)`` works.

    Explicit on purpose: importing exudyn_worm never changes Exudyn. Existing Exudyn methods of the
    same name are not replaced.

    Raises
    ------
    RuntimeError
        If a different attribute of that name already exists on ``exudyn.MainSystem``.
    """
    import exudyn
    for name, function in _MAIN_SYSTEM_METHODS.items():
        existing = getattr(exudyn.MainSystem, name, None)
        if existing is not None and existing is not function:
            raise RuntimeError(f"AddMainSystemMethods: exudyn.MainSystem already has '{name}'")
        setattr(exudyn.MainSystem, name, function)
