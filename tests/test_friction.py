"""Friction laws mu(v): closed forms, the AGMA curve, slopes, the three backends, bad input."""
import math
import warnings

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

import exudyn as exu
from exudyn_worm.model.contact import MATH_OPS, NUMPY_OPS, ContactOptions, MeshContact, SymbolicOps
from exudyn_worm.model.friction import (FT_PER_MIN, AgmaFriction, ConstantFriction, FrictionLaw,
                                        FrictionTableRangeWarning, ReadFrictionTable, StribeckFriction, TableFriction)
from exudyn_worm.model.gear import WormGear
from exudyn_worm.drive.presets import ElasticDriveFromParameters, GetPreset

STRIBECK = StribeckFriction(mu=0.05, muStatic=0.15, stribeckVelocity=0.1)
TABLE = TableFriction([(0., 0.15), (0.05, 0.10), (0.5, 0.06), (2., 0.04)])
LAWS = [ConstantFriction(0.132), STRIBECK, AgmaFriction(), TABLE]
GEAR = ElasticDriveFromParameters(GetPreset('reel-P1')).gear


def _Symbolic(law, v):
    esym = exu.symbolic
    rec = esym.GetRecording()
    esym.SetRecording(True)
    try:
        x = esym.Real('v', 0.)
        expression = law.Mu(x, SymbolicOps())
    finally:
        esym.SetRecording(rec)
    x.SetValue(v)
    return expression.Evaluate() if hasattr(expression, 'Evaluate') else expression


def test_stribeck_closed_form():
    assert STRIBECK.Mu(0.) == 0.15 and STRIBECK.muStatic == 0.15
    assert STRIBECK.Mu(0.1) == pytest.approx(0.05 + 0.10 / math.e, rel=1e-15)
    assert STRIBECK.Mu(0.2) == pytest.approx(0.05 + 0.10 * math.exp(-4.), rel=1e-15)
    assert STRIBECK.Mu(10.) == pytest.approx(0.05, rel=1e-15)
    assert STRIBECK.Slope(0.1) == pytest.approx(-2 * 0.10 * 0.1 / 0.01 / math.e, rel=1e-14)


def test_constant_law():
    law = ConstantFriction(0.132)
    assert law.Mu(0.) == law.Mu(3.) == law.muStatic == 0.132 and law.Slope(1.) == 0.
    np.testing.assert_array_equal(law.Mu(np.array([0., 1.])), [0.132, 0.132])


# AGMA 6034-B92, metric form printed by engineersedge.com ("AGMA WormGear Equations For Rating Factors"):
# 0.15 at rest; 0.124 exp(-2.233 V^0.645) for 0 < V <= 0.0508 m/s; 0.103 exp(-1.185 V^0.45) above (V in m/s,
# without the + 0.012 that the ft/min form of Shigley's text has). The printed exponent factors have 4 digits,
# so each value may differ by exp(0.0005 z) - 1 ~ 0.0005 z relative, z = V^0.645 or V^0.45.
@pytest.mark.parametrize('v', [0.001, 0.01, 0.03, 0.0508])
def test_agma_low_branch_matches_the_metric_form(v):
    z = v**0.645
    assert AgmaFriction().Mu(v) == pytest.approx(0.124 * math.exp(-2.233 * z), rel=0.0005 * z + 1e-12)


@pytest.mark.parametrize('v', [0.06, 0.3, 0.9, 2., 5.])
def test_agma_high_branch_matches_the_metric_form_plus_0012(v):
    z = v**0.45
    assert AgmaFriction().Mu(v) - 0.012 == pytest.approx(0.103 * math.exp(-1.185 * z), rel=0.0005 * z + 1e-12)


def test_agma_at_rest_and_units():
    law = AgmaFriction()
    assert law.Mu(0.) == 0.150 == law.muStatic
    assert FT_PER_MIN == 0.3048 / 60 and 10 * FT_PER_MIN == pytest.approx(0.0508, rel=1e-15)
    assert law.Mu(1 * FT_PER_MIN) == pytest.approx(0.124 * math.exp(-0.074), rel=1e-15)      # V = 1 ft/min
    assert law.Mu(100 * FT_PER_MIN) == pytest.approx(0.103 * math.exp(-0.110 * 100**0.45) + 0.012, rel=1e-15)
    # a reading of the AGMA curve: 0.15 at rest, about 0.124 just above, a few hundredths at 0.9 m/s
    assert law.Mu(1e-9) == pytest.approx(0.124, abs=5e-4) and 0.03 < law.Mu(0.9) < 0.06


def test_table_is_pchip():
    reference = PchipInterpolator(TABLE.speeds, TABLE.values)
    v = np.linspace(0., 2., 401)
    np.testing.assert_allclose(TABLE.Mu(v, NUMPY_OPS), reference(v), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(TABLE.Slope(v[1:-1]), reference(v[1:-1], 1), rtol=1e-9, atol=1e-12)
    assert np.all(np.diff(TABLE.Mu(v, NUMPY_OPS)) <= 1e-15)          # falling data: falling interpolant
    assert TABLE.muStatic == 0.15


def test_table_holds_its_end_values_with_a_warning():
    with pytest.warns(FrictionTableRangeWarning, match=r'outside the table.*0.04 is held'):
        assert TABLE.Mu(3.) == 0.04
    table = TableFriction([(0.1, 0.12), (1., 0.05)])
    with pytest.warns(FrictionTableRangeWarning, match='0.12 is held'):
        assert table.Mu(0.) == 0.12
    assert table.muStatic == 0.12 and table.Slope(5.) == 0.


@pytest.mark.parametrize('law', LAWS, ids=lambda l: l.kind)
def test_slope_is_the_derivative(law):
    for v in (0.02, 0.0301, 0.3, 0.897, 1.7):
        h = 1e-6 * max(v, 1e-3)
        numeric = (law.Mu(v + h) - law.Mu(v - h)) / (2 * h)
        assert law.Slope(v) == pytest.approx(numeric, rel=1e-6, abs=1e-9)


@pytest.mark.parametrize('law', LAWS, ids=lambda l: l.kind)
def test_python_numpy_and_symbolic_agree(law):
    speeds = [0., 0.004, 0.0508, 0.07, 0.9, 1.99, 2.5]
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', FrictionTableRangeWarning)
        python = [law.Mu(v) for v in speeds]
        array = law.Mu(np.array(speeds), NUMPY_OPS)
    np.testing.assert_allclose(array, python, rtol=1e-15)
    np.testing.assert_allclose([_Symbolic(law, v) for v in speeds], python, rtol=1e-13)


def test_gear_carries_the_law():
    assert GEAR.friction is None and GEAR.muStatic == GEAR.mu and not GEAR.speedDependentFriction
    gear = GEAR.Replace(mu=0.05, friction=STRIBECK)
    assert gear.muStatic == 0.15 and gear.speedDependentFriction
    assert gear.SlidingSpeed(-50.) == pytest.approx(gear.r1 * 50. / math.cos(gear.gamma), rel=1e-15)
    assert WormGear(**{**_GearArgs(), 'friction': STRIBECK}).mu == 0.05          # the law's mu is the gear's
    for S in (1, -1):   # c2 = r1 (cos(alphaN) sin(gamma) + S mu cos(gamma)), c4 = r2 (cos(alphaN) cos(gamma) - S mu sin(gamma))
        c1, c2, c3, c4 = GEAR.Coefficients(S, mu=0.08)
        cosA, g = math.cos(GEAR.alphaN), GEAR.gamma
        assert c2 == pytest.approx(GEAR.r1 * (cosA * math.sin(g) + S * 0.08 * math.cos(g)), rel=1e-14)
        assert c4 == pytest.approx(GEAR.r2 * (cosA * math.cos(g) - S * 0.08 * math.sin(g)), rel=1e-14)
        np.testing.assert_allclose(GEAR.Coefficients(S, mu=GEAR.mu), GEAR.Coefficients(S), rtol=1e-14)


def _GearArgs():
    return {k: getattr(GEAR, k) for k in ('alphaN', 'gamma', 'r1', 'r2', 'kV', 'dV', 'backlash')}


def test_constant_law_records_todays_expression():
    """A gear with ConstantFriction records exactly the expression of a gear without a law."""
    def Recorded(gear):
        esym = exu.symbolic
        rec = esym.GetRecording()
        esym.SetRecording(True)
        try:
            v = [esym.Real(name, 0.) for name in ('phi1', 'phi2', 'omega1', 'omega2')]
            s = MeshContact(gear, *v, ContactOptions(), SymbolicOps())
        finally:
            esym.SetRecording(rec)
        return str(s.wormTorque), str(s.wheelTorque)
    assert Recorded(GEAR.Replace(friction=ConstantFriction(GEAR.mu), mu=GEAR.mu)) == Recorded(GEAR)


@pytest.mark.parametrize('law', LAWS[1:], ids=lambda l: l.kind)
def test_contact_law_reads_mu_of_v(law):
    gear = GEAR.Replace(friction=law, mu=getattr(law, 'mu', GEAR.mu))
    esym = exu.symbolic
    rec = esym.GetRecording()
    esym.SetRecording(True)
    try:
        v = [esym.Real(name, 0.) for name in ('phi1', 'phi2', 'omega1', 'omega2')]
        sym = MeshContact(gear, *v, ContactOptions(), SymbolicOps())
    finally:
        esym.SetRecording(rec)
    for state in ((-0.05, 0., 30., 30. / gear.ratio), (0.02, 1e-4, -3., 0.), (0.01, 0., 0.02, 0.)):
        for var, value in zip(v, state):
            var.SetValue(value)
        with warnings.catch_warnings():
            warnings.simplefilter('ignore', FrictionTableRangeWarning)
            ref = MeshContact(gear, *state, ContactOptions(), MATH_OPS)
            arr = MeshContact(gear, *(np.array([x]) for x in state), ContactOptions(), NUMPY_OPS)
        mu = law.Mu(gear.SlidingSpeed(state[2]))
        expected = gear.LeverArms(ref.S, math, mu)[0]          # worm torque = -c2(S, mu(v)) sigma Fn
        assert ref.wormTorque == pytest.approx(-expected * ref.normalForce, rel=1e-14)
        assert arr.wormTorque[0] == pytest.approx(ref.wormTorque, rel=1e-13)
        assert sym.wormTorque.Evaluate() == pytest.approx(ref.wormTorque, rel=1e-12)
        assert sym.wheelTorque.Evaluate() == pytest.approx(ref.wheelTorque, rel=1e-12)


@pytest.mark.parametrize('make, match', [
    (lambda: StribeckFriction(0.1, 0.05, 0.1), r"StribeckFriction: 'muStatic' .* must be >= the kinetic 'mu' = 0.1, got 0.05"),
    (lambda: StribeckFriction(-0.1, 0.15, 0.1), r"StribeckFriction: 'mu' must be >= 0, got -0.1"),
    (lambda: StribeckFriction(0.05, 0.15, -0.1), r"StribeckFriction: 'stribeckVelocity' must be > 0 m/s, got -0.1 m/s"),
    (lambda: ConstantFriction(-0.01), r"ConstantFriction: 'mu' must be >= 0, got -0.01"),
    (lambda: STRIBECK.Mu(-1.), r"StribeckFriction.Mu: 'v' must be >= 0 m/s, got -1 m/s"),
    (lambda: AgmaFriction().Mu(np.array([0.1, -0.2]), NUMPY_OPS), r"AgmaFriction.Mu: 'v' .* >= 0 m/s everywhere, got -0.2 m/s"),
    (lambda: TableFriction([]), r"TableFriction: 'points' must hold at least 2 .* got 0"),
    (lambda: TableFriction([(0., 0.1)]), r"TableFriction: 'points' must hold at least 2 .* got 1"),
    (lambda: TableFriction([(0., 0.1), (1., 0.05), (0.5, 0.07)]), r"sorted by sliding speed .* 0.5 m/s after 1 m/s"),
    (lambda: TableFriction([(0., 0.1), (1., 0.05), (1., 0.07)]), r"increase strictly .* points 1 and 2 both have 1 m/s"),
    (lambda: TableFriction([(0., 0.1), (-1., 0.05)]), r"'points\[1\] speed' must be >= 0 m/s, got -1 m/s"),
    (lambda: TableFriction([(0., 0.1), (1., -0.05)]), r"'points\[1\] mu' must be >= 0, got -0.05"),
    (lambda: FrictionLaw('stribek', mu=0.05), r"FrictionLaw: 'kind' \(frictionLaw\) must be one of constant, stribeck, "
                                              r"agma, table, got 'stribek' \(did you mean 'stribeck'\?\)"),
    (lambda: FrictionLaw('stribeck', mu=0.05), r"the 'stribeck' law needs 'muStatic', 'stribeckVelocity'"),
    (lambda: FrictionLaw('constant', mu=0.05, muStatic=0.1), r"the 'constant' law does not use 'muStatic'"),
    (lambda: WormGear(**_GearArgs(), mu=0.1, friction=STRIBECK), r"WormGear: 'mu' = 0.1 differs from the stribeck"),
    (lambda: WormGear(**_GearArgs(), friction=AgmaFriction()), r"WormGear: with the 'agma' friction law give the nominal"),
])
def test_bad_input_names_argument_range_and_value(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_bad_types():
    with pytest.raises(TypeError, match=r"TableFriction: 'points\[0\]' must be a \(sliding speed in m/s, mu\) pair"):
        TableFriction([(0., 0.1, 3.), (1., 0.05)])
    with pytest.raises(TypeError, match=r"WormGear: 'friction' must be a friction law"):
        WormGear(**_GearArgs(), mu=0.1, friction='stribeck')


def test_friction_law_factory():
    assert FrictionLaw('stribeck', mu=0.05, muStatic=0.15, stribeckVelocity=0.1) == STRIBECK
    assert FrictionLaw('table', table=[(0., 0.15), (0.05, 0.10), (0.5, 0.06), (2., 0.04)]) == TABLE
    assert isinstance(FrictionLaw('agma', mu=0.05), AgmaFriction)
    assert FrictionLaw(mu=0.1) == ConstantFriction(0.1)
    assert STRIBECK.ToDict() == {'frictionLaw': 'stribeck', 'mu': 0.05, 'muStatic': 0.15, 'stribeckVelocity': 0.1}


def test_read_friction_table(tmp_path):
    path = tmp_path / 'rig.csv'
    path.write_text('# test rig, oil X\nv_m_s, mu\n0, 0.15\n0.05; 0.10\n\n0.5 0.06\n2.0,0.04\n')
    assert ReadFrictionTable(path) == TABLE
    assert ReadFrictionTable([(0., 0.15), (0.05, 0.10), (0.5, 0.06), (2., 0.04)]) == TABLE
    path.write_text('0, 0.15\n0.05, 0.10, 3\n')
    with pytest.raises(ValueError, match=r"rig.csv, line 2: expected 2 numbers .* got 3"):
        ReadFrictionTable(path)
    path.write_text('0, 0.15\nfast, 0.10\n')
    with pytest.raises(ValueError, match=r"rig.csv, line 2: expected 'sliding speed \(m/s\), mu', got 'fast, 0.10'"):
        ReadFrictionTable(path)
    with pytest.raises(ValueError, match=r"ReadFrictionTable: the friction table .*: cannot read it: "):
        ReadFrictionTable(tmp_path / 'missing.csv')
    path.write_text('v, mu\n')
    with pytest.raises(ValueError, match=r"TableFriction: 'points' must hold at least 2 .* got 0"):
        ReadFrictionTable(path)
