"""The small-displacement 3D model (exudyn_worm/items/smallmesh.py) held against the exact rigid-body model: the
same drive (examples/drives/reel-3d.toml's bearings under P1 and P7) built both ways by BuildRigidBodyReelChanger.

The exact model is the reference (its bearing reactions are the textbook forces, tests/test_rigid_mesh.py; its
eigenvalues an independent numpy model's, tests/test_rigid_mesh_linear.py). P1: the peaks of the normal force,
phi2'' and the four bearing loads within 1 %. P7 chatters through 650 sticking phases, and its peaks are set by
single chatter events: the exact model's own peaks move by up to 1.6 % between Newton tolerances 1e-6 and 1e-8
(docs/mesh-3d.md, "The small-displacement model"), so P7 is held on the root mean squares of the same series over the
run, within 1 %.
"""
import exudyn as exu
import numpy as np
import pytest

from exudyn_worm.analysis.simulation import reelchanger3d
from exudyn_worm.analysis.simulation.reelchanger import SolverSettings
from exudyn_worm.analysis.simulation.stepsize import RecommendedStepSize
from exudyn_worm.builders.rigidbody import BodyInertiaTensors, BuildRigidBodyReelChanger, DefaultModel
from exudyn_worm.drive.presets import GetPreset
from exudyn_worm.drive.wholedrive import ResolveDrive
from exudyn_worm.items.smallmesh import SmallWormGearConnector

pytest.importorskip('exudyn')
DRIVE_3D = 'examples/drives/reel-3d.toml'
SERIES = ('normalForce', 'alpha2', 'wormAxialLoad', 'wormRadialLoad', 'wheelAxialLoad', 'wheelRadialLoad')


def _Drive(preset):
    """The preset with the bearings and masses of examples/drives/reel-3d.toml (the keys the file adds)."""
    bearings = {k: v for k, v in ResolveDrive(config=DRIVE_3D).parameters.items() if k not in GetPreset('reel-P1')}
    return ResolveDrive(parameters={**GetPreset(preset), **bearings})


def _Series(drive, model):
    """8 s of the drive with the default solver settings: the series of SERIES."""
    built = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), drive, model=model)
    reelchanger3d.AddSeriesSensors(built)
    built.mbs.Assemble()
    ss, solverType = SolverSettings(8., RecommendedStepSize(drive))
    built.mbs.SolveDynamic(ss, solverType=solverType)
    series = reelchanger3d.StoredSeries(built)
    series['normalForce'] = np.asarray(reelchanger3d.StoredMeshState(built).normalForce, dtype=float)
    return built, series


def test_bearing_tables_build_the_small_displacement_model_by_default():
    drive = ResolveDrive(config=DRIVE_3D)
    model = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), drive)
    assert model.model == 'small' and isinstance(model.connector, SmallWormGearConnector)
    assert DefaultModel(None, drive.shaftSupports.wheelBearings) == 'exact'
    exact = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), drive, model='exact')
    assert exact.model == 'exact' and not isinstance(exact.connector, SmallWormGearConnector)
    inertias = BodyInertiaTensors(drive)        # both models take the bodies' inertias from here
    for body, J in (('worm', drive.elastic.J1), ('wheel', drive.elastic.J2)):
        t = inertias[body]
        assert t.tiltGiven and t.tensor[0, 0] == t.tensor[1, 1] > 0.
        assert t.tensor[2, 2] + t.shaftInertia == pytest.approx(J, rel=1e-12)


@pytest.mark.messages
def test_a_model_that_does_not_fit_is_refused_with_its_argument():
    drive = ResolveDrive(parameters=GetPreset('reel-P1'))
    with pytest.raises(ValueError, match=r"'model' must be one of 'small', 'exact' or None, got 'linear'"):
        BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), drive, model='linear')
    wormOnly = ResolveDrive(parameters={**GetPreset('reel-P1'), 'wormRadialStiffness': 5e8, 'wormAxialStiffness': 5e8,
                                        'wormBearingSpan': 0.12, 'wormMass': 5., 'wormTiltInertia': 0.1})
    with pytest.raises(ValueError, match=r"model='small' needs both shafts on linear bearings"):
        BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), wormOnly, model='small')


@pytest.mark.physics
def test_the_start_is_the_exact_models_static_equilibrium():
    """Both models start with the bearings deflected by the static mesh force: the shafts' loads agree to 2e-4 (the
    tilts are below 4e-4 rad, so the terms the small-displacement model leaves out, a bearing point's
    b (1 - cos(theta)) against its b sin(theta), are below theta / 2 = 2e-4 of the first-order ones)."""
    drive = ResolveDrive(config=DRIVE_3D)
    loads = {}
    for model in ('small', 'exact'):
        built = BuildRigidBodyReelChanger(exu.SystemContainer().AddSystem(), drive, model=model)
        reelchanger3d.AddSeriesSensors(built)
        built.mbs.Assemble()
        ss, solverType = SolverSettings(1e-3, RecommendedStepSize(drive))
        built.mbs.SolveDynamic(ss, solverType=solverType)
        loads[model] = reelchanger3d.StoredShaftLoads(built)
    for key in ('wormAxialLoad', 'wormRadialLoad', 'wheelAxialLoad', 'wheelRadialLoad'):
        assert loads['small'][key][0] == pytest.approx(loads['exact'][key][0], rel=2e-4), key


@pytest.mark.physics
def test_p1_peaks_and_bearing_loads_are_the_exact_models():
    drive = _Drive('reel-P1')
    (_, small), (_, exact) = (_Series(drive, model) for model in ('small', 'exact'))
    for key in SERIES:
        assert np.max(np.abs(small[key])) == pytest.approx(np.max(np.abs(exact[key])), rel=0.01), key


@pytest.mark.physics
def test_p7_chatter_loads_are_the_exact_models():
    """P7's root mean squares over the run (module docstring), within 1 %; both models stick and slip."""
    drive = _Drive('reel-P7')
    (smallModel, small), (exactModel, exact) = (_Series(drive, model) for model in ('small', 'exact'))
    for key in SERIES:
        rms = [np.sqrt(np.mean(np.square(series[key]))) for series in (small, exact)]
        assert rms[0] == pytest.approx(rms[1], rel=0.01), key
    for built in (smallModel, exactModel):
        assert built.connector.stickSlip.switches > 100
