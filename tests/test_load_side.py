"""Load-side chains: the driven machine behind load shafts, wheel J2 --(kL1, dL1)-- JL1 -- ...

The drive of examples/drives/load-shaft.toml: centre distance 40 mm, ratio 40, lead angle 3.5 deg, mu = 0.08, worm-side inertia 2e-4 kg*m^2,
the driven machine (0.5 kg*m^2) behind a 2e4 N*m/rad load shaft, written as examples/drives/load-shaft.toml."""
import json
import math
import subprocess
import sys
from pathlib import Path

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (CoordinateSpringDamper, MarkerNodeCoordinate, Node1D, NodePointGround,
                                  ObjectRotationalMass1D)

from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability
from exudyn_worm.analysis.stability.drivestability import AnalyzeDrive
from exudyn_worm import ContactOptions, CreateWormGear, WormGear
from exudyn_worm.analysis.design.designcheck import DesignCheck
from exudyn_worm.drive.presets import ElasticDriveFromParameters, ExtraComponents, GetPreset, LoadSideChain
from exudyn_worm.cli.main import Main
from exudyn_worm.params.drivefile import StageKey
from exudyn_worm.model.profiles import GravityLeverTorque
from exudyn_worm.items.equilibrium import SteadyInitialState
from exudyn_worm.model.contact import MATH_OPS
from exudyn_worm.analysis.simulation.reelchanger import SimulateReelChanger
from exudyn_worm.items.results import SeriesUnit
from exudyn_worm.analysis.studies.studypoint import RunPoint, RunTask
from exudyn_worm.analysis.stability.loadside import DiagnoseLoadSide, LumpedLoadSide
from exudyn_worm.drive.wholedrive import ResolveDrive

ROOT = Path(__file__).resolve().parents[1]
LOAD_SHAFT = ROOT / 'examples' / 'drives' / 'load-shaft.toml'

# the load-shaft drive, derived by hand: a = r1 + r2 and u = r2 / (r1 tan(gamma)) give r1 = a / (1 + u tan(gamma))
A, U, GAMMA, MU = 0.040, 40., math.radians(3.5), 0.08
R1 = A / (1 + U * math.tan(GAMMA))
R2 = A - R1
J1, JL1, KL1 = 2e-4, 0.5, 2e4
# chosen values (no source; stated in the drive file): wheel-side inertia, mesh and drive-shaft stiffness and damping
J2, KV, DV, KT, DT = 0.02, 3e7, 300., 300., 0.05


@pytest.fixture(scope='module')
def fileParameters():
    return ResolveParameters(config=LOAD_SHAFT)


def _HandBuiltEigenvalues(J2Wheel, load):
    """The drive built by hand in Exudyn: ground --kT-- worm, mesh, wheel --kL1-- load (``load`` None: no load
    shaft, the load lumped into ``J2Wheel``); linearized with the contact state held."""
    gear = WormGear(alphaN=math.radians(20), gamma=GAMMA, r1=R1, r2=R2, kV=KV, dV=DV, backlash=0., mu=MU)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()

    def Rotor(J, name, angle=0.):
        n = mbs.AddNode(Node1D(referenceCoordinates=[0.], initialCoordinates=[angle], initialVelocities=[0.],
                               name=name))
        mbs.AddObject(ObjectRotationalMass1D(nodeNumber=n, inertia=J))
        return n, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n, coordinate=0))

    ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    worm, mWorm = Rotor(J1, 'worm', 1e-6 / gear.normalLever)            # pre-deflected into contact
    wheel, mWheel = Rotor(J2Wheel, 'wheel')
    mbs.AddObject(CoordinateSpringDamper(markerNumbers=[ground, mWorm], stiffness=KT, damping=DT))
    if load is not None:
        _, mLoad = Rotor(load[0], 'load')
        mbs.AddObject(CoordinateSpringDamper(markerNumbers=[mWheel, mLoad], stiffness=load[1], damping=0.))
    CreateWormGear(mbs, [worm, wheel], gear=gear, contactOptions=ContactOptions(), name='mesh')
    mbs.Assemble()
    return AnalyzeLinearStability(mbs)


def test_radii_derived_by_hand():
    assert R1 + R2 == pytest.approx(A, rel=1e-15)
    assert R2 / (R1 * math.tan(GAMMA)) == pytest.approx(U, rel=1e-12)


def test_drive_file_gives_the_three_mass_drive(fileParameters):
    p = fileParameters
    assert (p['JL1'], p['kL1'], p['dL1']) == (JL1, KL1, 0.)
    assert p['r1'] == pytest.approx(R1, rel=1e-9) and p['r2'] == pytest.approx(R2, rel=1e-9)
    for key, value in (('J1', J1), ('J2', J2), ('kV', KV), ('dV', DV), ('kT', KT), ('dT', DT), ('mu', MU)):
        assert p[key] == pytest.approx(value, rel=1e-12), key


def test_drive_file_equals_the_drive_built_by_hand_in_exudyn(fileParameters):
    """Required: same verdict and same eigenvalues (to 1e-6) as the hand-built Exudyn model."""
    fromFile = AnalyzeDrive(ResolveDrive(parameters=fileParameters))
    byHand = _HandBuiltEigenvalues(J2, (JL1, KL1))
    assert fromFile.stable == byHand.stable
    for S in (1, -1):
        a, b = fromFile.State(S), byHand.State(S)
        assert a.stable == b.stable
        np.testing.assert_allclose(a.eigenvalues, b.eigenvalues, rtol=1e-6)


def test_lumping_the_load_into_j2_turns_the_verdict(fileParameters):
    """Lumped into J2 the drive looks stable (with margin), with the load shaft it chatters at
    about 200 Hz in the wheel's mode. Both verdicts from hand-built Exudyn models and from the package."""
    lumped = LumpedLoadSide(ResolveDrive(parameters=fileParameters))
    assert lumped.elastic.J2 == pytest.approx(J2 + JL1) and not lumped.loadSideChain
    assert 'JL1' not in lumped.parameters and 'kL1' not in lumped.parameters
    assert _HandBuiltEigenvalues(J2 + JL1, None).stable and AnalyzeDrive(lumped).stable
    assert DesignCheck(lumped).stableWithMargin
    chained = _HandBuiltEigenvalues(J2, (JL1, KL1))
    assert not chained.stable and chained.State(1).stable
    growing = max(chained.State(-1).modes, key=lambda m: m.eigenvalue.real)
    assert growing.eigenvalue.real > 0 and 150. < growing.frequencyHz < 300.
    assert growing.Participants(0.5) == ['wheel']


def test_set_keys_build_a_chain_of_any_length():
    p = ResolveParameters('reel-P1', sets=['JL1=1 kg*m^2', 'kL1=2 kN*m', 'JL2=2', 'kL2=1e6', 'dL2=3', 'JL3=0.5',
                                           'kL3=5e5'])
    assert LoadSideChain(p) == [(1., 2000., 0.), (2., 1e6, 3.), (0.5, 5e5, 0.)]
    assert ExtraComponents(p) == ['a load-side chain (JL1, ...)']
    assert LoadSideChain(ResolveParameters('reel-P1')) == []


@pytest.mark.parametrize('sets, fragment', [
    (['JL1=0.5'], "LoadSideChain: 'JL1' needs the stiffness 'kL1' (N*m/rad) of the spring-damper on its wheel side"),
    (['JL2=0.5', 'kL2=1e4'], "the load-side chain must be JL1, JL2, ... without gaps"),
    (['JL1=0.5', 'kL1=1e4', 'JL3=1', 'kL3=1'], "missing 'JL2'"),
    (['JL1=-0.5', 'kL1=1e4'], "'JL1' must be > 0 kg*m^2"),
    (['JL1=0.5', 'kL1=1e4', 'dL1=-1'], "'dL1' must be >= 0 N*m*s/rad"),
])
def test_bad_load_side_chain_is_one_line_exit_2(capsys, tmp_path, monkeypatch, sets, fragment):
    monkeypatch.chdir(tmp_path)
    status = Main(['stability', *[a for s in sets for a in ('--set', s)]])
    out, err = capsys.readouterr()
    assert status == 2 and out == '' and err.count('\n') == 1 and fragment in err, err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize('body, fragment', [
    ('[[loadSide]]\n', "line 2: [[loadSide]] number 1: the table is empty; each [[loadSide]] table is one stage of "
                       "the load-side chain (JL1, kL1)"),
    ('[[loadSide]]\ninertia = 1\nstifnes = 3\n', "line 4: [[loadSide]] number 1: unknown key 'stifnes' (did you mean "
                                                 "'stiffness'?)"),
    ('[[loadSide]]\ninertia = 1\nstiffness = 3\n[[loadSide]]\ndamping = 1\n',
     "line 6: [[loadSide]] number 2 damping: LoadSideChain: the load-side chain must be JL1, JL2, ..."),
    ('[[loadSide]]\ninertia = "1 kg"\nstiffness = 3\n', "line 3: [[loadSide]] number 1 inertia"),
])
def test_bad_load_side_table_names_file_line_and_stage(tmp_path, body, fragment):
    path = tmp_path / 'drive.toml'
    path.write_text('preset = "reel-P1"\n' + body)
    with pytest.raises(ValueError) as info:
        ResolveParameters(config=path)
    assert fragment in str(info.value)


def test_stage_keys_of_a_drive_file_in_order(tmp_path):
    path = tmp_path / 'drive.toml'
    path.write_text('preset = "reel-P1"\n[[loadSide]]\ninertia = 1\nstiffness = "3 kN*m"\n'
                    '[[loadSide]]\ninertia = 2\nstiffness = 4e5\ndamping = 7\n')
    p = ResolveParameters(config=path)
    assert (p['JL1'], p['kL1'], p['JL2'], p['kL2'], p['dL2']) == (1., 3000., 2., 4e5, 7.) and 'dL1' not in p
    assert StageKey('loadSide', 'damping', 2) == 'dL3' and StageKey('driveSide', 'inertia', 0) == 'J4'
    with pytest.raises(ValueError, match="StageKey: 'table' must be one of driveSide, loadSide, got 'load'"):
        StageKey('load', 'inertia', 0)


def test_equilibrium_every_load_shaft_carries_the_load_torque():
    p = GetPreset('reel-P2')
    load = GravityLeverTorque(mass=p['loadMass'], leverArm=p['leverArm'])
    stages = ((5., 2e5, 1.), (10., 4e5, 0.))
    state = SteadyInitialState(ElasticDriveFromParameters(p), load, p['motorSpeed'], loadSide=stages)
    torque = load.Torque(state['phiL2'], 0., 0., MATH_OPS)             # the load acts on the last inertia
    assert torque < 0
    assert 2e5 * (state['phiL1'] - state['phi2']) == pytest.approx(torque, rel=1e-9)
    assert 4e5 * (state['phiL2'] - state['phiL1']) == pytest.approx(torque, rel=1e-9)
    assert state['omegaL1'] == state['omegaL2'] == state['omega2']


def test_simulation_starts_in_equilibrium_and_reports_the_load_inertia(fileParameters):
    result = SimulateReelChanger(ResolveDrive(parameters=fileParameters), endTime=0.02)
    for key in ('phiL1', 'omegaL1', 'alphaL1'):
        assert key in result.series
    assert SeriesUnit('alphaL1') == 'rad/s^2' and SeriesUnit('phiL1') == 'rad'
    # released at rest without the equilibrium, the load (39 N*m on 0.5 kg*m^2) would accelerate at about 80 rad/s^2
    assert np.max(np.abs(result.series['alphaL1'])) < 1.
    assert np.max(np.abs(result.series['omegaL1'] - result.series['omega2'])) < 1e-2


def test_cli_stability_and_sweep_treat_the_whole_drive(tmp_path, fileParameters):
    run = subprocess.run([sys.executable, '-m', 'exudyn_worm', 'stability', '--config', str(LOAD_SHAFT), '--json'],
                         capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data['components'] == ['a load-side chain (JL1, ...)'] and 'loadInertia1' in data['coordinates']
    assert data['stable'] is False
    expected = AnalyzeDrive(ResolveDrive(parameters=fileParameters)).State(-1)
    byS = {tuple(s['S']): s for s in data['states']}
    assert byS[(-1,)]['maxRealPart'] == pytest.approx(expected.maxRealPart, rel=1e-9)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize('kL1, stable', [(2e4, False), (2e7, True)])
def test_sweep_point_takes_the_verdict_of_the_whole_drive(fileParameters, kL1, stable):
    """A sweep over the load shaft: the soft one chatters (whole drive), the stiff one is the lumped drive."""
    row = RunPoint(RunTask(0, ResolveDrive(parameters=fileParameters), {'kL1': kL1}, windows=[(0., 0.01)],
                           endTime=0.01))
    assert row['status'] == 'ok', row['error']
    assert row['analyticStable'] is stable and row['analyticStableLowering'] is stable


def test_diagnosis_names_the_soft_load_shaft_as_the_cause(fileParameters):
    d = DiagnoseLoadSide(ResolveDrive(parameters=fileParameters))
    assert d.stages[0].frequencyHz == pytest.approx(math.sqrt(KL1 / JL1) / (2 * math.pi), rel=1e-12)
    assert d.lumpedStable and not d.wholeStable and not d.lumpingSafe and d.cause == 1
    assert d.growingMode['S'] == -1 and d.growingMode['energyShare']['wheel'] > 0.9
    assert d.limitFactor == pytest.approx(1 / math.sqrt(1 - 10 ** -0.1))
    assert 'the cause is load-side stage 1' in d.Text()


def test_second_stage_named_when_it_is_the_soft_one(fileParameters):
    """A stiff first stage and a soft second: the second stage carries the blame."""
    p = {**fileParameters, 'JL1': 0.01, 'kL1': 1e8, 'JL2': JL1, 'kL2': KL1}
    d = DiagnoseLoadSide(ResolveDrive(parameters=p))
    assert not d.wholeStable and d.cause == 2
    assert d.stages[0].inertiaBeyond == pytest.approx(0.01 + JL1) and d.stages[1].inertiaBeyond == JL1


@pytest.mark.parametrize('kL1', [1.2e5, 2e6, 2e8])
def test_lumping_judged_safe_gives_the_lumped_verdict(fileParameters, kL1):
    """Where the criterion calls lumping safe, the whole drive's verdict is the lumped one (the criterion
    includes that check; the stage frequency alone must pass too)."""
    d = DiagnoseLoadSide(ResolveDrive(parameters={**fileParameters, 'kL1': kL1}))
    assert d.lumpingSafe and d.cause is None
    assert all(s.frequencyHz >= d.limitFactor * max(d.wheelModesHz) for s in d.stages)
    assert d.lumpedStable == d.wholeStable


@pytest.mark.slow
def test_design_check_analyses_the_whole_drive_with_its_chain(fileParameters):
    """The design check no longer lumps the chain into J2 (nor refuses a soft one): its verdict is the whole drive's,
    and the chain's own parameters are design parameters."""
    result = DesignCheck(ResolveDrive(parameters=fileParameters))
    assert result.stable is AnalyzeDrive(ResolveDrive(parameters=fileParameters)).stable is False and result.recommendations
    assert {'JL1', 'kL1'} <= set(result.scans)
    stiff = {**fileParameters, 'kL1': 2e6}
    result = DesignCheck(ResolveDrive(parameters=stiff))
    assert result.parameters['J2'] == J2 and result.parameters['JL1'] == JL1
    assert result.stable is AnalyzeDrive(ResolveDrive(parameters=stiff)).stable
    with pytest.raises(ValueError, match=r'DiagnoseLoadSide: the drive has no load-side chain \(JL1, kL1, ...\)'):
        DiagnoseLoadSide(ResolveDrive(parameters={k: v for k, v in fileParameters.items() if k not in ('JL1', 'kL1', 'dL1')}))


@pytest.mark.slow
def test_cli_check_reports_the_whole_drive_and_the_cause(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert Main(['check', '--config', str(LOAD_SHAFT)]) == 0
    out, err = capsys.readouterr()
    assert 'Verdict: UNSTABLE' in out and 'linearized Exudyn model of the whole drive' in out
    assert 'the cause is load-side stage 1' in out
    assert Main(['check', '--config', str(LOAD_SHAFT), '--json']) == 0
    data = json.loads(capsys.readouterr().out)
    assert data['stable'] is False and data['loadSide']['cause'] == 1 and data['recommendations']
    assert list(tmp_path.iterdir()) == []
