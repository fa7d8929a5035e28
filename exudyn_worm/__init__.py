"""exudyn-worm: worm-gear chatter analysis and simulation for Exudyn.

Analytical theory (:func:`AnalyzeStability`), the Exudyn worm-gear connector (:func:`CreateWormGear`),
drivetrain builders, the paper's reel changer (:func:`SimulateReelChanger`) and presets. SI units,
angles in rad. Plotting lives in :mod:`exudyn_worm.plotting` (the only subpackage importing matplotlib).

The subpackages are the layers of the package, lowest first (docs/development.md): :mod:`~exudyn_worm.params`
(the parameter registry and drive files), :mod:`~exudyn_worm.model` (gear, contact and friction laws, the
analytical theory), :mod:`~exudyn_worm.items` (the Exudyn items and the solver), :mod:`~exudyn_worm.drive`
(the drive boundary: the Drive, the resolver, preset data, duty), :mod:`~exudyn_worm.builders` (Exudyn model
builders), :mod:`~exudyn_worm.analysis` (stability, charts, simulation, periodic orbits, design check,
studies), :mod:`~exudyn_worm.plotting`
and :mod:`~exudyn_worm.cli`.
"""
import importlib

#: public name -> submodule that defines it; imported on first access (PEP 562), so that
#: ``import exudyn_worm.cli.main`` and light subcommands do not pay for exudyn, scipy, pint or matplotlib
_LAZY = {'WormGear': 'model.gear',
         **dict.fromkeys(('ElasticDrive', 'AxialBearing', 'MeshDampingFromMeasure', 'MeshDampingMeasure', 'TorsionalDampingFromMeasure',
                          'TorsionalDampingMeasure'), 'model.drive'),
         **dict.fromkeys(('AnalyzeStability', 'StabilityAnalysis', 'ContactStability'), 'model.stability'),
         **dict.fromkeys(('ContactOptions', 'MeshContact', 'MeshState'), 'model.contact'),
         **dict.fromkeys(('CreateWormAxialBearing', 'CreateWormGear', 'WormGearConnector'), 'items.connector'),
         **dict.fromkeys(('CreatePrescribedRotation', 'CreateRotor', 'CreateShaft', 'CreateRotorTorque',
                          'CreateLoadSideChain', 'CreateDriveSideChain'), 'items.drivetrain'),
         **dict.fromkeys(('ConstantSpeed', 'CoulombViscousFriction', 'GravityLeverTorque', 'LinearMotorCharacteristic',
                          'StartStopProfile'), 'model.profiles'),
         **dict.fromkeys(('ApplyOverrides', 'DriveFromParameters', 'ElasticDriveFromParameters', 'GetPreset', 'PRESETS', 'LoadSideChain'), 'drive.presets'),
         **dict.fromkeys(('AnalyzeLinearStability', 'LinearStability'), 'analysis.stability.linearization'),
         **dict.fromkeys(('Drive', 'ResolveDrive', 'Component'), 'drive.wholedrive'),
         **dict.fromkeys(('ValueSource', 'SourceKind'), 'drive.config'),
         **dict.fromkeys(('CreateRigidBodyWormGear', 'RigidBodyWormGearConnector'), 'items.rigidmesh'),
         **dict.fromkeys(('CreateShaftBearings', 'ShaftBearings', 'StoredBearingLoads'), 'items.bearings'),
         **dict.fromkeys(('BuildRigidBodyReelChanger', 'BodyInertiaTensors'), 'builders.rigidbody'),
         **dict.fromkeys(('CreateSmallDisplacementWormGear', 'SmallWormGearConnector', 'SmallDisplacementBody'),
                         'items.smallmesh'),
         **dict.fromkeys(('BodyInertia', 'CylinderInertia'), 'model.bodies'),
         **dict.fromkeys(('AddRigidMeshGraphics', 'RecordSolution', 'SaveFrame'), 'items.meshgraphics'),
         **dict.fromkeys(('DutyOperatingPoints', 'DutyPoint'), 'drive.operatingpoints'),
         **dict.fromkeys(('AnalyzeDrive', 'DriveAnalysis', 'OperatingPointStability', 'StabilityModel'),
                         'analysis.stability.drivestability'),
         'BuildReelChanger': 'builders.oneangle', 'SimulateReelChanger': 'analysis.simulation.reelchanger',
         'SteadyInitialState': 'items.equilibrium',
         'SimulationResult': 'items.results',
         **dict.fromkeys(('ConstantFriction', 'StribeckFriction', 'AgmaFriction', 'TableFriction', 'FrictionLaw'),
                         'model.friction'),
         **dict.fromkeys(('OperatingPoint', 'OperatingPointAt'), 'model.stability'),
         'SelfLocking': 'model.selflocking',
         **dict.fromkeys(('FindPeriodicOrbit', 'PeriodicOrbit'), 'analysis.orbits.periodic'),
         'FindSteadyChatter': 'analysis.orbits.chatter', 'SteadyChatterOfSystem': 'analysis.orbits.chatter', 'AnalyzeChatterBranch': 'analysis.orbits.chatterbranch',
         **dict.fromkeys(('RecommendedStepSize', 'CheckStepSize'), 'analysis.simulation.stepsize')}


def __getattr__(name):
    if name in _LAZY:
        value = getattr(importlib.import_module(f'.{_LAZY[name]}', __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


__version__ = '0.1.0'

__all__ = ['CreateRigidBodyWormGear', 'RigidBodyWormGearConnector', 'CreateShaftBearings', 'ShaftBearings',
           'StoredBearingLoads', 'BuildRigidBodyReelChanger', 'BodyInertiaTensors', 'CreateSmallDisplacementWormGear',
           'SmallWormGearConnector', 'SmallDisplacementBody', 'BodyInertia', 'CylinderInertia',
           'AddRigidMeshGraphics', 'RecordSolution', 'SaveFrame', 'Drive', 'ResolveDrive', 'Component', 'ValueSource', 'SourceKind', 'DutyOperatingPoints', 'DutyPoint', 'AnalyzeDrive', 'DriveAnalysis',
           'OperatingPointStability', 'StabilityModel', 'WormGear', 'ElasticDrive', 'MeshDampingFromMeasure', 'MeshDampingMeasure',
           'TorsionalDampingFromMeasure', 'TorsionalDampingMeasure', 'AnalyzeStability',
           'StabilityAnalysis', 'ContactStability', 'ContactOptions', 'MeshContact', 'MeshState',
           'CreateWormGear', 'WormGearConnector', 'AxialBearing', 'CreateWormAxialBearing', 'CreatePrescribedRotation', 'CreateRotor', 'CreateShaft',
           'CreateLoadSideChain', 'CreateDriveSideChain', 'LoadSideChain',
           'CreateRotorTorque', 'ConstantSpeed', 'CoulombViscousFriction', 'GravityLeverTorque',
           'LinearMotorCharacteristic', 'StartStopProfile', 'ApplyOverrides', 'DriveFromParameters', 'ElasticDriveFromParameters', 'GetPreset',
           'PRESETS', 'AnalyzeLinearStability', 'LinearStability', 'BuildReelChanger',
           'SimulateReelChanger', 'SteadyInitialState', 'SimulationResult', 'RecommendedStepSize', 'CheckStepSize', 'AddMainSystemMethods',
           'ConstantFriction', 'StribeckFriction', 'AgmaFriction', 'TableFriction', 'FrictionLaw', 'OperatingPoint',
           'OperatingPointAt', 'SelfLocking', 'FindPeriodicOrbit', 'PeriodicOrbit', 'FindSteadyChatter',
           'AnalyzeChatterBranch', 'SteadyChatterOfSystem', '__version__']

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
