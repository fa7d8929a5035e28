"""Bad input to the Python API gives a TypeError/ValueError that names the function, the argument, what was
expected and what was received, instead of an error from deep inside (pybind11, numpy, a dict lookup).

Each case was reproduced by a QA pass before its fix (the failure it gave then is in the comment)."""
import math

import exudyn as exu
import numpy as np
import pytest

import exudyn_worm as ew
from exudyn_worm.analysis.charts.stabilitychart import ComputeStabilityChart, PresetChartPoints
from exudyn_worm.model.contact import MeshContact
from exudyn_worm.model.friction import NUMPY_OPS
from exudyn_worm.analysis.design.designcheck import DesignCheck
from exudyn_worm.analysis.stability.linearization import AnalyzeLinearStability
from exudyn_worm.model.friction import AgmaFriction
from exudyn_worm.drive.config import ResolveParameters
from exudyn_worm.drive.presets import GearFromParameters
from exudyn_worm.drive.wholedrive import ResolveDrive

P1 = ew.GetPreset('reel-P1')


def _System():
    SC = exu.SystemContainer()
    return SC, SC.AddSystem()


def _Two(mbs):
    return ew.CreateRotor(mbs, 0.1, name='worm'), ew.CreateRotor(mbs, 33., name='wheel')


def _Linearized():
    return AnalyzeLinearStability(ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=P1)).mbs, contactStates=[(1,), (-1,)])


def _Chart():
    gear = GearFromParameters(ew.GetPreset('chart'), meshDamping=False)
    return ComputeStabilityChart(gear, 0.1, 0.014, 1., resolution=8)


def _Law(law, useSymbolic=True):
    SC, mbs = _System()
    ew.CreateRotorTorque(mbs, ew.CreateRotor(mbs, 1.), law, useSymbolic=useSymbolic)


def _Unsolved():
    SC, mbs = _System()
    worm, wheel = _Two(mbs)
    connector = ew.CreateWormGear(mbs, [worm['nodeNumber'], wheel['nodeNumber']], gear=ew.DriveFromParameters(P1).gear)
    connector.AddSensors(mbs)
    mbs.Assemble()
    return connector.StoredMeshState(mbs)


def _ForeignRotor():
    SC, mbs = _System()
    SC2, other = _System()
    ew.CreateRotor(other, 1.)
    far = ew.CreateRotor(other, 2.)           # marker 1 of the other system; this system has only marker 0
    return ew.CreateShaft(mbs, [ew.CreateRotor(mbs, 1.), far], stiffness=1.)


def _SwappedForeignRotor():
    SC, mbs = _System()
    SC2, other = _System()
    ew.CreateRotor(mbs, 1.)
    ew.CreateRotor(mbs, 1.)
    ground = ew.CreateRotor(other, 1.)
    # same marker number as in 'other', but in 'mbs' that marker is on another node
    foreign = {'nodeNumber': 5, 'objectNumber': ground['objectNumber'], 'markerNumber': ground['markerNumber']}
    return ew.CreateShaft(mbs, [foreign, ew.CreateRotor(mbs, 1.)], stiffness=1.)


def _Shaft(rotors):
    SC, mbs = _System()
    a, b = _Two(mbs)
    return ew.CreateShaft(mbs, rotors(a, b), stiffness=1.)


def _Gear(nodes):
    SC, mbs = _System()
    a, b = _Two(mbs)
    return ew.CreateWormGear(mbs, nodes(a, b), gear=ew.DriveFromParameters(P1).gear)


CASES = {
    # ExudynTypeError from Node1D
    'rotor name not a string': (lambda: ew.CreateRotor(_System()[1], inertia=1, name=5), TypeError,
                                "CreateRotor: 'name' must be a string (the name of the Exudyn item), got int 5"),
    # AttributeError: 'NoneType' object has no attribute 'AddNode'
    'rotor without a system': (lambda: ew.CreateRotor(None, inertia=1.), TypeError,
                               "CreateRotor: 'mbs' must be an exudyn.MainSystem (SC = exudyn.SystemContainer(); "
                               "mbs = SC.AddSystem()), got NoneType"),
    # "object of type 'NoneType' has no len()"
    'shaft rotors None': (lambda: _Shaft(lambda a, b: None), TypeError,
                          "CreateShaft: 'rotors' must be a list of two rotors from CreateRotor, got NoneType None"),
    'shaft one rotor': (lambda: _Shaft(lambda a, b: [a]), ValueError,
                        "CreateShaft: 'rotors' must hold two rotors from CreateRotor, got 1"),
    'worm gear nodes None': (lambda: _Gear(lambda a, b: None), TypeError,
                             "CreateWormGear: 'nodeNumbers' must be a list [worm, wheel] of two node numbers or rotors "
                             "from CreateRotor, got NoneType None"),
    'worm gear node a string': (lambda: _Gear(lambda a, b: ['worm', b]), TypeError,
                                "CreateWormGear: 'nodeNumbers[0] (worm)' must be a node number or a dict with "
                                "'nodeNumber'"),
    # IndexError from the empty sensor arrays
    'mesh state before the solve': (_Unsolved, ValueError,
                                    "WormGearConnector: no stored sensor data: solve the system first"),
    # "not iterable" / "missing loadMass..." / "dictionary update sequence element"
    'simulate None': (lambda: ew.SimulateReelChanger(None), TypeError,
                      "SimulateReelChanger: 'drive' must be a Drive (exudyn_worm.ResolveDrive), got NoneType; a preset "
                      "or a drive file becomes one with exudyn_worm.ResolveDrive(preset=..., config=...)"),
    'simulate a flat set': (lambda: ew.SimulateReelChanger(P1), TypeError,
                            "SimulateReelChanger: 'drive' must be a Drive (exudyn_worm.ResolveDrive), got dict; a flat "
                            "parameter set becomes one with exudyn_worm.ResolveDrive(parameters=...)"),
    'simulate a preset name': (lambda: ew.SimulateReelChanger('reel-P1'), TypeError,
                               "SimulateReelChanger: 'drive' must be a Drive (exudyn_worm.ResolveDrive), got str; a "
                               "preset or a drive file becomes one with exudyn_worm.ResolveDrive(preset=..., config=...)"),
    'simulate an ElasticDrive': (lambda: ew.SimulateReelChanger(ew.DriveFromParameters(P1)), TypeError,
                                 "SimulateReelChanger: 'drive' must be a Drive (exudyn_worm.ResolveDrive), got "
                                 "ElasticDrive; the two-mass core alone is analysed with AnalyzeStability"),
    'build a preset name': (lambda: ew.BuildReelChanger(exu.SystemContainer().AddSystem(), 'reel-P1'), TypeError,
                            "BuildReelChanger: 'drive' must be a Drive"),
    'design check a preset name': (lambda: DesignCheck('reel-P1'), TypeError,
                                   "DesignCheck: 'drive' must be a Drive (exudyn_worm.ResolveDrive), got str; a preset "
                                   "or a drive file becomes one with exudyn_worm.ResolveDrive(preset=..., config=...)"),
    'drive from a preset name': (lambda: ew.DriveFromParameters('reel-P1'), TypeError,
                                 "DriveFromParameters: 'parameters' must be a mapping"),
    # "'NoneType' object has no attribute 'dampingCanPull'"
    'simulate contactOptions None': (lambda: ew.SimulateReelChanger(ResolveDrive(parameters=P1), contactOptions=None), TypeError,
                                     "SimulateReelChanger: 'contactOptions' must be a ContactOptions "
                                     "(e.g. ContactOptions(frictionSpeed=0.05)), got NoneType None"),
    # "'int' object has no attribute 'AngleAndSpeed'"
    'simulate profile 5': (lambda: ew.SimulateReelChanger(ResolveDrive(parameters=P1), profile=5), TypeError,
                           "SimulateReelChanger: 'profile' must be None (constant motor speed) or have "
                           "AngleAndSpeed(t, ops) (e.g. ConstantSpeed, StartStopProfile), got int 5"),
    'build profile 5': (lambda: ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=P1), profile=5), TypeError, "BuildReelChanger: 'profile' must be"),
    # "'list' object has no attribute 'items'"
    'chart points unknown preset': (lambda: _Chart().plot(points=['P9']), ValueError,
                                    "PlotStabilityChart: 'points': unknown preset 'P9'; expected preset names: chart, "
                                    "reel-P1"),
    'chart points a number': (lambda: _Chart().plot(points=5), TypeError,
                              "PlotStabilityChart: 'points' must be a mapping {label: (x, y), a dict with 'x' and "
                              "'y', or an ElasticDrive} or a list of preset names"),
    # "only 0-dimensional arrays can be converted to Python scalars"
    'mesh contact on arrays without NUMPY_OPS': (
        lambda: MeshContact(ew.DriveFromParameters(P1).gear, np.zeros(3), np.zeros(3), np.ones(3), np.ones(3)),
        TypeError, "MeshContact: 'phi1', 'phi2', 'omega1', 'omega2' (and the axial state) include arrays, but 'ops' "
                   "is MATH_OPS (plain Python floats, the default): pass ops=NUMPY_OPS for arrays"),
    # pybind11 "Unable to cast Python instance of type <class 'str'> to C++ type"
    'torque law returns a string': (lambda: _Law(lambda phi, omega, t, ops: 'abc'), TypeError,
                                    "CreateRotorTorque: the law must return a number, got str 'abc' when called in "
                                    "plain Python"),
    'torque law returns a string (Python)': (lambda: _Law(lambda phi, omega, t, ops: 'abc', False), TypeError,
                                             "CreateRotorTorque: the law must return a number, got str 'abc'"),
    # was blamed on the symbolic recording ("the law cannot be recorded as a symbolic (C++) user function")
    'torque law with three arguments': (lambda: _Law(lambda phi, omega, t: 0.), TypeError,
                                        ("CreateRotorTorque: calling the law in plain Python failed with TypeError: ",
                                         "takes 3 positional arguments but 4 were given; it must be callable as "
                                         "law(phi, omega, t, ops)")),
    # "int() argument must be a string, a bytes-like object or a real number, not 'list'" came from State([[-1]])
    'linear state of a string': (lambda: _Linearized().State('-1'), TypeError,
                                 "LinearStability.State: each contact parameter 'S' must be +1 or -1 (one per mesh, "
                                 "e.g. State(-1) or State(1, -1)), got str '-1'"),
    'linear state out of range': (lambda: _Linearized().State(2), ValueError,
                                  "LinearStability.State: expected one of [(-1,), (1,)], got (2,)"),
    # odd input accepted silently
    'shaft from a rotor to itself': (lambda: _Shaft(lambda a, b: [a, a]), ValueError,
                                     "CreateShaft: 'rotors' must be two different rotors, got the same rotor twice "
                                     "(marker 0): a shaft from a rotor to itself does nothing"),
    'shaft with a rotor of another system': (_ForeignRotor, ValueError,
                                             "CreateShaft: 'rotors[1]' is not a rotor of this system: its marker 1 does "
                                             "not exist in 'mbs'"),
    'shaft with a rotor of another system (same marker number)': (
        _SwappedForeignRotor, ValueError, "CreateShaft: 'rotors[0]' is not a rotor of this system: in 'mbs' its "
                                          "marker 0 is not on node 5"),
    'dampingCanPull a string': (lambda: ew.ContactOptions(dampingCanPull='yes'), TypeError,
                                "ContactOptions: 'dampingCanPull' must be True or False, got str 'yes'"),
    'fixedS True': (lambda: ew.ContactOptions(fixedS=True), ValueError,
                    "ContactOptions: 'fixedS' must be None, +1 or -1, got True"),
    # "can't multiply sequence by non-int of type 'float'"
    'friction speed a string': (lambda: AgmaFriction().Mu('1'), TypeError,
                                ("AgmaFriction.Mu: 'v' (sliding speed) must be a number >= 0 in m/s", "got str '1'")),
    # taken as the default preset
    'empty preset name': (lambda: ResolveParameters(preset=''), ValueError,
                          ("ResolveParameters: 'preset' must name a preset, got an empty name ''",
                           'expected one of: chart, reel-P1')),
    # "ElasticDrive: 'dT' must be finite (N*m*s/rad), got inf"
    'inertia that overflows the damping': (lambda: ew.DriveFromParameters({**P1, 'J1': 1e308}), ValueError,
                                           ("parameter set: 'J1' = 1e+308 kg*m^2 is out of range (it must be > 0 "
                                            "kg*m^2", 'dT = 2 DT sqrt(kT J1)')),
    # "missing parameter(s) mx, z2, q" although z1 itself is out of range
    'fractional starts': (lambda: ew.DriveFromParameters(ew.ApplyOverrides(P1, {'z1': 1.5})), ValueError,
                          "parameter set: 'z1' must be a whole number >= 1 (a count of teeth or starts), got 1.5"),
    # a list of 1e8 floats per axis, then 48 GB of coefficients
    'chart grid too large': (lambda: ComputeStabilityChart(GearFromParameters(ew.GetPreset('chart'), meshDamping=False),
                                                           0.1, 0.014, 1., resolution=20000), ValueError,
                             ("ComputeStabilityChart: 'resolution' 20000 x 20000 = 400,000,000 grid points is above "
                              "the limit of 4,000,000",)),
}


@pytest.mark.messages
@pytest.mark.parametrize('name', list(CASES))
def test_bad_input_gets_a_clear_message(name):
    call, error, message = CASES[name]
    start, *parts = (message,) if isinstance(message, str) else message
    with pytest.raises(error) as info:
        call()
    assert str(info.value).startswith(start), str(info.value)
    assert all(part in str(info.value) for part in parts), str(info.value)


@pytest.mark.messages
def test_analyze_linear_stability_takes_a_model_with_mbs():
    """A ReelChangerModel instead of model.mbs raised AttributeError; it is accepted now, with the same result."""
    model = ew.BuildReelChanger(exu.SystemContainer().AddSystem(), ResolveDrive(parameters=P1))
    a = AnalyzeLinearStability(model, contactStates=[(-1,)])
    b = AnalyzeLinearStability(model.mbs, contactStates=[(-1,)])
    np.testing.assert_allclose(a.State(-1).eigenvalues, b.State(-1).eigenvalues)
    with pytest.raises(TypeError, match=r"^AnalyzeLinearStability: 'mbs' must be an exudyn.MainSystem .*got dict"):
        AnalyzeLinearStability({'mbs': 1})


def test_linear_state_takes_a_tuple_or_list():
    """State([-1]) raised "int() argument must be ... not 'list'"; a key of .states as one argument works too."""
    analysis = _Linearized()
    assert analysis.State([-1]) is analysis.State(-1) is analysis.State((-1,)) is analysis.State(np.int64(-1))


def test_chart_points_take_preset_names():
    """points=['P1'] raised "'list' object has no attribute 'items'"; preset names are marked at their coordinates."""
    pytest.importorskip('matplotlib')
    ax = _Chart().plot(points=['P1', 'reel-P7'])
    texts = {t.get_text(): t.xy for t in ax.texts}
    expected = PresetChartPoints(['reel-P1', 'reel-P7'])
    assert set(texts) == {'P1', 'P7'}
    for label, point in expected.items():
        assert texts[label] == pytest.approx((point['x'], point['y']))


def test_worm_gear_takes_rotor_dicts():
    """CreateWormGear(mbs, [worm, wheel]) with the rotors of CreateRotor said the dict 'is not a node of this system';
    rotors and node numbers give the same connector."""
    gear = ew.DriveFromParameters(P1).gear
    connectors = []
    for byRotor in (True, False):
        SC, mbs = _System()
        worm, wheel = _Two(mbs)
        nodes = [worm, wheel] if byRotor else [worm['nodeNumber'], wheel['nodeNumber']]
        connectors.append(ew.CreateWormGear(mbs, nodes, gear=gear, name='mesh'))
    a, b = connectors
    assert [int(n) for n in a.nodeNumbers] == [int(n) for n in b.nodeNumbers] == [0, 1]
    state = dict(phi1=0.01, phi2=0., omega1=50., omega2=0.8)
    assert a.Evaluate(**state).wheelTorque == b.Evaluate(**state).wheelTorque


def test_worm_gear_takes_the_axial_bearing_dict():
    SC, mbs = _System()
    worm, wheel = _Two(mbs)
    axial = ew.CreateWormAxialBearing(mbs, ew.AxialBearing(stiffness=1e8, damping=0., mass=3.))
    connector = ew.CreateWormGear(mbs, [worm, wheel], gear=ew.DriveFromParameters(P1).gear, axialNodeNumber=axial)
    assert int(connector.axialNodeNumber) == int(axial['nodeNumber'])


@pytest.mark.messages
def test_worm_gear_refuses_one_rotor_twice():
    SC, mbs = _System()
    worm, _ = _Two(mbs)
    with pytest.raises(ValueError, match=r"^CreateWormGear: worm, wheel \(and axial\) nodes must be different"):
        ew.CreateWormGear(mbs, [worm, worm], gear=ew.DriveFromParameters(P1).gear)


def test_rotor_errors_add_nothing():
    """A refused call leaves the system as it was."""
    SC, mbs = _System()
    a, b = _Two(mbs)
    before = (mbs.systemData.NumberOfNodes(), mbs.systemData.NumberOfObjects(), mbs.systemData.NumberOfMarkers())
    for call, error, message in ((lambda: ew.CreateRotor(mbs, 1., name=5), TypeError, "CreateRotor: 'name'"),
                                 (lambda: ew.CreateShaft(mbs, [a, a], stiffness=1.), ValueError, "CreateShaft: 'rotors'"),
                                 (lambda: ew.CreateRotorTorque(mbs, a, lambda phi, omega, t: 0.), TypeError,
                                  'CreateRotorTorque: calling the law')):
        with pytest.raises(error, match=message):
            call()
    assert (mbs.systemData.NumberOfNodes(), mbs.systemData.NumberOfObjects(),
            mbs.systemData.NumberOfMarkers()) == before


def test_mesh_contact_arrays_with_numpy_ops_still_work():
    gear = ew.DriveFromParameters(P1).gear
    state = MeshContact(gear, np.full(3, 1e-4), np.zeros(3), np.ones(3), np.ones(3), ops=NUMPY_OPS)
    assert state.normalForce.shape == (3,) and math.isfinite(float(state.normalForce[0]))
