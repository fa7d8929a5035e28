"""exudyn-worm: worm-gear chatter analysis and simulation for Exudyn.

Analytical theory (:func:`AnalyzeStability`), the Exudyn worm-gear connector (:func:`CreateWormGear`),
drivetrain builders, the paper's reel changer (:func:`SimulateReelChanger`) and presets. SI units,
angles in rad. Plotting lives in :mod:`exudyn_worm.plot` (the only module importing matplotlib).
"""
import importlib

#: public name -> submodule that defines it; imported on first access (PEP 562), so that
#: ``import exudyn_worm.cli`` and light subcommands do not pay for exudyn, scipy, pint or matplotlib
_LAZY = {'WormGear': 'gear',
         **dict.fromkeys(('ElasticDrive', 'MeshDampingFromMeasure', 'MeshDampingMeasure', 'TorsionalDampingFromMeasure',
                          'TorsionalDampingMeasure'), 'drive'),
         **dict.fromkeys(('AnalyzeStability', 'StabilityAnalysis', 'ContactStability'), 'stability'),
         **dict.fromkeys(('ContactOptions', 'MeshContact', 'MeshState'), 'contact'),
         **dict.fromkeys(('AxialBearing', 'CreateWormAxialBearing', 'CreateWormGear', 'WormGearConnector'), 'connector'),
         **dict.fromkeys(('CreatePrescribedRotation', 'CreateRotor', 'CreateShaft', 'CreateRotorTorque',
                          'CreateLoadSideChain'), 'drivetrain'),
         **dict.fromkeys(('ConstantSpeed', 'CoulombViscousFriction', 'GravityLeverTorque', 'LinearMotorCharacteristic',
                          'StartStopProfile'), 'profiles'),
         **dict.fromkeys(('ApplyOverrides', 'DriveFromParameters', 'GetPreset', 'PRESETS', 'LoadSideChain'), 'presets'),
         **dict.fromkeys(('AnalyzeLinearStability', 'AnalyzeStabilityExudyn', 'LinearStability'), 'linearization'),
         **dict.fromkeys(('BuildReelChanger', 'SimulateReelChanger'), 'reelchanger'),
         'SteadyInitialState': 'equilibrium',
         'SimulationResult': 'results',
         **dict.fromkeys(('ConstantFriction', 'StribeckFriction', 'AgmaFriction', 'TableFriction', 'FrictionLaw'),
                         'friction'),
         **dict.fromkeys(('OperatingPoint', 'OperatingPointAt'), 'stability'),
         'SelfLocking': 'selflocking',
         **dict.fromkeys(('FindPeriodicOrbit', 'PeriodicOrbit'), 'orbits'),
         'FindSteadyChatter': 'chatter', 'AnalyzeChatterBranch': 'chatterbranch',
         **dict.fromkeys(('RecommendedStepSize', 'CheckStepSize'), 'stepsize')}


def __getattr__(name):
    if name in _LAZY:
        value = getattr(importlib.import_module(f'.{_LAZY[name]}', __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


__version__ = '0.1.0'

__all__ = ['WormGear', 'ElasticDrive', 'MeshDampingFromMeasure', 'MeshDampingMeasure',
           'TorsionalDampingFromMeasure', 'TorsionalDampingMeasure', 'AnalyzeStability',
           'StabilityAnalysis', 'ContactStability', 'ContactOptions', 'MeshContact', 'MeshState',
           'CreateWormGear', 'WormGearConnector', 'AxialBearing', 'CreateWormAxialBearing', 'CreatePrescribedRotation', 'CreateRotor', 'CreateShaft',
           'CreateLoadSideChain', 'LoadSideChain',
           'CreateRotorTorque', 'ConstantSpeed', 'CoulombViscousFriction', 'GravityLeverTorque',
           'LinearMotorCharacteristic', 'StartStopProfile', 'ApplyOverrides', 'DriveFromParameters', 'GetPreset',
           'PRESETS', 'AnalyzeStabilityExudyn', 'AnalyzeLinearStability', 'LinearStability', 'BuildReelChanger',
           'SimulateReelChanger', 'SteadyInitialState', 'SimulationResult', 'RecommendedStepSize', 'CheckStepSize', 'AddMainSystemMethods',
           'ConstantFriction', 'StribeckFriction', 'AgmaFriction', 'TableFriction', 'FrictionLaw', 'OperatingPoint',
           'OperatingPointAt', 'SelfLocking', 'FindPeriodicOrbit', 'PeriodicOrbit', 'FindSteadyChatter',
           'AnalyzeChatterBranch', '__version__']

_MAIN_SYSTEM_METHODS = ('CreateWormGear', 'CreateWormAxialBearing', 'CreateRotor', 'CreateShaft',
                        'CreatePrescribedRotation', 'CreateRotorTorque')


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
    for name in _MAIN_SYSTEM_METHODS:
        function = __getattr__(name)
        existing = getattr(exudyn.MainSystem, name, None)
        if existing is not None and existing is not function:
            raise RuntimeError(f"AddMainSystemMethods: exudyn.MainSystem already has '{name}'")
        setattr(exudyn.MainSystem, name, function)
