"""The analytical check groups of the validation: published numbers of sections 2-3.1 and the eigenvalue forensics.

Groups ``analytical``, ``eigenvalues``, ``forensics`` and ``forensics-slow`` of
:func:`validation.RunValidation`; each function takes the run's :class:`validation.runner.ValidationContext`
and returns one :class:`validation.runner.Check` per row of its group in ``validation/paper/reference.csv``.
"""
from __future__ import annotations

import math
from types import ModuleType
from typing import Dict, List, Tuple

import numpy as np

from exudyn_worm.drive import (MeshDampingFromMeasure, MeshDampingMeasure, TorsionalDampingFromMeasure,
                    TorsionalDampingMeasure)
from exudyn_worm.gear import WormGear
from exudyn_worm.presets import ApplyOverrides, DriveFromParameters, GetPreset
from exudyn_worm.stability import AnalyzeStability, CharacteristicCoefficients, ContactStability, HurwitzConditions
from .paper import eigenvalue_forensics
from .runner import PAPER_MU, Check, HalfUnit, ValidationContext

__all__ = ['Hurwitz19Tolerance', 'AnalyticalChecks', 'EigenvalueChecks', 'ForensicsChecks', 'ForensicsSlowChecks']


# --- the paper's parameter sets -------------------------------------------------------------------------

_deg = math.radians

# printed inputs of the paper that the rows below turn into the printed results
_DV_25 = 1250.          # set (25), N*s/m
_DV_25_FIG4 = 625.      # section 2.3, Figure 4 (D_V = 0.014)
_DV_25_FIG5 = 2500.     # section 2.3, Figure 5 (D_V = 0.056)
_DV_28 = 21470.         # set (28), N*s/m
_DT_28 = 0.741          # set (28), N*m*s
_MU_28_PRINTED = 0.134  # set (28)
_RHO_PRINTED = _deg(8)  # sets (25) and (28)
_D_28 = 0.014           # D_T = D_V of set (28)
_U_PRINTED = 63.        # sets (25), (28)
#: printed rounding of the geometry of (28): gamma to 1e-4 deg, r1 and r2 to 0.01 mm
_GEOMETRY_HALF_UNITS = {'gamma': _deg(0.5e-4), 'r1': 0.5e-5, 'r2': 0.5e-5}


def _Set28(**overrides) -> Dict[str, float]:
    return ApplyOverrides(GetPreset('reel-P1'), {'mu': PAPER_MU, **overrides})


def _Preset(name: str, **overrides) -> Dict[str, float]:
    return ApplyOverrides(GetPreset(name), {'mu': PAPER_MU, **overrides})


def _Gear(p: Dict[str, float], **changes) -> WormGear:
    q = {**p, **changes}
    return WormGear(alphaN=q['alphaN'], gamma=q['gamma'], r1=q['r1'], r2=q['r2'], kV=q['kV'],
                    dV=q.get('dV', 0.), mu=q.get('mu'), rho=q.get('rho'))


def _H19(parameters: Dict[str, float]) -> float:
    return float(HurwitzConditions(CharacteristicCoefficients(DriveFromParameters(parameters), -1))[2])


def Hurwitz19Tolerance(parameters: Dict[str, float], publishedText: str) -> Tuple[float, Dict[str, float]]:
    """Tolerance of the value of (19) for a parameter set of the reel changer.

    Half a unit of the printed result plus, for each printed geometry input (gamma to 1e-4 deg, r1 and
    r2 to 0.01 mm), the change of (19) when that input moves by half a unit of its last printed digit
    (linear worst case). The design values J1, J2, kT, kV, alphaN, D_T, D_V and the friction are
    taken as exact: they are round numbers and the printed b1..b4 pin them (D_T to 1e-6).

    Parameters
    ----------
    parameters : dict
        Flat parameter set of (28) (as in :func:`exudyn_worm.presets.DriveFromParameters`).
    publishedText : str
        The printed value of (19), e.g. ``'-2.607e10'``, whose last digit sets the first part.

    Returns
    -------
    (float, dict)
        Total tolerance in 1/s^6 and its contributions by name.
    """
    parts = {'printed result': HalfUnit(publishedText)}
    for name, h in _GEOMETRY_HALF_UNITS.items():
        up = _H19(ApplyOverrides(parameters, {name: parameters[name] + h}))
        down = _H19(ApplyOverrides(parameters, {name: parameters[name] - h}))
        parts[name] = 0.5 * abs(up - down)
    return sum(parts.values()), parts


# --- group: analytical model ----------------------------------------------------------------------------

def AnalyticalChecks(ctx: ValidationContext) -> List[Check]:
    """Group ``analytical``: b1..b4 and (19) of set (28), the friction readings, damping measures, u, chart point P1 and the stability of the presets."""
    chart, p28 = GetPreset('chart'), _Set28()
    drive28 = DriveFromParameters(p28)
    g28 = drive28.gear
    b28 = CharacteristicCoefficients(drive28, -1)
    checks = []

    def add(rowId, value, tolerance=None, detail=''):
        checks.append(ctx.Compare(rowId, value, tolerance, detail))

    def addH19(rowId, parameters):
        tol, parts = Hurwitz19Tolerance(parameters, ctx.Row(rowId).publishedText)
        add(rowId, _H19(parameters), tol, 'tolerance = ' + ' + '.join(f'{v:.2g} ({k})' for k, v in parts.items()))
        return tol, parts

    add('u_25', _Gear(chart).ratio)
    add('u_28', g28.ratio)
    add('mu_25_from_rho', _Gear(chart, rho=_RHO_PRINTED, mu=None).mu)
    add('rho_25_from_mu', math.degrees(_Gear(chart, mu=PAPER_MU, rho=None).rho))
    add('rho_28_from_mu', math.degrees(_Gear(p28, mu=_MU_28_PRINTED, rho=None).rho))
    add('mu_28_from_rho', _Gear(p28, rho=_RHO_PRINTED, mu=None).mu)
    add('DV_25', MeshDampingMeasure(_DV_25, chart['kV'], chart['r2'], chart['J2']))
    add('DV_25_fig4', MeshDampingMeasure(_DV_25_FIG4, chart['kV'], chart['r2'], chart['J2']))
    add('DV_25_fig5', MeshDampingMeasure(_DV_25_FIG5, chart['kV'], chart['r2'], chart['J2']))
    add('DV_28', MeshDampingMeasure(_DV_28, p28['kV'], p28['r2'], p28['J2']))
    add('DT_28', TorsionalDampingMeasure(_DT_28, p28['kT'], p28['J1']))
    add('dT_28_from_DT', TorsionalDampingFromMeasure(_D_28, p28['kT'], p28['J1']))
    add('dV_28_from_DV', MeshDampingFromMeasure(_D_28, p28['kV'], p28['r2'], p28['J2']))
    for i in range(4):
        add(f'b{i + 1}_28', b28[i])
    tol19, parts19 = addH19('hurwitz19_28', p28)
    p134, p8 = _Set28(mu=_MU_28_PRINTED), _Set28(rho=_RHO_PRINTED)
    add('b1_28_mu134', CharacteristicCoefficients(DriveFromParameters(p134), -1)[0])
    addH19('hurwitz19_28_mu134', p134)
    addH19('hurwitz19_28_rho8', p8)
    add('b1_28_dT0741', CharacteristicCoefficients(DriveFromParameters(_Set28(dT=_DT_28)), -1)[0])
    # b4 of (16) is proportional to u: b4 with u = 63 exactly is b4 * 63 / u
    add('b4_28_u63', b28[3] * _U_PRINTED / g28.ratio)
    add('P1_stiffness_ratio', drive28.stiffnessRatio)
    add('P1_inertia_ratio', drive28.inertiaRatio)
    for name in ('P1', 'P2', 'P3', 'P4', 'P5', 'P6', 'P7'):
        add(f'unstable_{name}', float(not AnalyzeStability(DriveFromParameters(_Preset('reel-' + name))).stable))
    add('unstable_P6_DV056', float(not AnalyzeStability(DriveFromParameters(_Preset('reel-P6', DV=0.056))).stable))

    _FrictionSection(ctx, p28, tol19, parts19)
    return checks


def _FrictionSection(ctx, p28, tol19, parts19):
    pubB = [ctx.Row(f'b{i}_28') for i in range(1, 5)]
    pub19 = ctx.Row('hurwitz19_28')
    unit19 = 2 * HalfUnit(pub19.publishedText)
    cases = {'mu0.132': ('mu = %g (printed with (25))' % PAPER_MU, {'mu': PAPER_MU}),
             'rho8': ('rho exactly 8 deg', {'rho': _RHO_PRINTED}),
             'mu0.134': ('mu = %g (printed with (28))' % _MU_28_PRINTED, {'mu': _MU_28_PRINTED})}
    rows, val = [], {}
    for key, (label, ov) in cases.items():
        p = ApplyOverrides(p28, ov)
        d = DriveFromParameters(p)
        b = CharacteristicCoefficients(d, -1)
        h = _H19(p)
        val[key] = (b, h, math.degrees(d.gear.rho))
        ok = [abs(b[i] - pubB[i].published) <= pubB[i].tolerance for i in range(4)] + [abs(h - pub19.published) <= tol19]
        rows.append(f'| {label}, rho = {math.degrees(d.gear.rho):.4f} deg | '
                    + ' | '.join(f'{x:.6g}{"" if o else " **x**"}' for x, o in zip([*b, h], ok)) + f' | {sum(ok)}/5 |')
    table = '\n'.join(['| friction | b1 | b2 | b3 | b4 | (19) | within |', '|---|---|---|---|---|---|---|',
                       '| printed (section 3.1) | ' + ' | '.join(r.publishedText for r in pubB + [pub19]) + ' | |',
                       *rows])
    gear = _Gear(p28, rho=_RHO_PRINTED, mu=None)
    units = lambda x, pub: abs(x - pub.published) / (2 * HalfUnit(pub.publishedText))
    b1dT = CharacteristicCoefficients(DriveFromParameters(_Set28(dT=_DT_28)), -1)[0]
    d28 = DriveFromParameters(p28)
    b4u63 = CharacteristicCoefficients(d28, -1)[3] * _U_PRINTED / d28.gear.ratio
    ctx.AddSection('Which friction the paper used (mu = 0.134 or rho = 8 deg?)', f"""
Set (28) prints "mu = {_MU_28_PRINTED} (rho = 8 deg)", but through eq. (13), rho = atan(mu/cos alphaN),
mu = {_MU_28_PRINTED} gives rho = {val['mu0.134'][2]:.3f} deg and rho = 8 deg gives mu = {gear.mu:.4f}. Set (25),
taken from the same sources, prints "mu = {PAPER_MU} (rho = 8 deg)", which is consistent
({val['mu0.132'][2]:.3f} deg). The printed b1..b4 and the value of (19) decide (S = -1, D_T = D_V = 0.014,
u from eq. (3); **x** = outside the tolerance of its row):

{table}

Only mu = {PAPER_MU} reproduces all five printed numbers. rho = 8.000 deg exactly reproduces b1..b4 but
misses (19) by {units(val['rho8'][1], pub19):.1f} units of its last digit; mu = {_MU_28_PRINTED} misses b1 by
{units(val['mu0.134'][0][0], pubB[0]):.1f} units and (19) by {units(val['mu0.134'][1], pub19):.0f}. We therefore
read the friction of (28) as mu = {PAPER_MU} (rho = {val['mu0.132'][2]:.3f} deg, printed "8 deg"); the
{_MU_28_PRINTED} is a misprint. The same numbers show that the paper used the damping measures
D_T = D_V = 0.014 as inputs (the printed dT = {_DT_28} gives b1 = {b1dT:.4f}, row `b1_28_dT0741`) and u from
eq. (3) (u = {d28.gear.ratio:.4f}; exactly 63 gives b4 = {b4u63:.5g}, row `b4_28_u63`, a marginal exclusion).

The presets `reel-P1` .. `reel-P7` (and `chart`, set (25)) therefore use mu = {PAPER_MU}; `--set mu=0.134` or
`--set rho=8deg` give the other readings.
""")
    parts = '\n'.join(f'| {k} | {v:.3g} |' for k, v in parts19.items())
    terms = CharacteristicCoefficients(d28, -1)
    b1, b2, b3, b4 = terms
    ctx.AddSection('Tolerance of the value of (19)', f"""
(19) = b1 b2 b3 - b1^2 b4 - b3^2 is the difference of terms of {b1 * b2 * b3:.2g}, {b1**2 * b4:.2g} and
{b3**2:.2g} 1/s^6, so its fourth digit depends on digits of the inputs the paper does not print. Its
tolerance is therefore half a unit of the printed result ({HalfUnit(pub19.publishedText):.3g}) plus the
propagated half-unit rounding of the printed inputs that can hide further digits: the geometry
gamma = 5.3228 deg (+-0.00005 deg), r1 = 18.05 mm and r2 = 105.95 mm (+-0.005 mm). The design values
J1 = 0.1 kg m^2, J2 = 33 kg m^2, kT = 7000 N m, kV = 2e8 N/m, alphaN = 20 deg, D_T = D_V = 0.014 and the
friction are taken as exact: they are round numbers, and the printed b1..b4 confirm them (b1 pins D_T to
about 1e-6; J1, J2, kT, kV to about 1e-4). The contributions (linear worst case, `Hurwitz19Tolerance`):

| contribution | 1/s^6 |
|---|---|
{parts}
| **total** | **{tol19:.3g}** |

This tolerance is fixed by the argument above, the same for every friction reading, and it separates
them: mu = {PAPER_MU} gives {val['mu0.132'][1]:.5g} (|diff| = {abs(val['mu0.132'][1] - pub19.published) / tol19:.2f}
tolerances), rho = 8.000 deg gives {val['rho8'][1]:.5g} ({abs(val['rho8'][1] - pub19.published) / tol19:.2f}
tolerances), mu = {_MU_28_PRINTED} gives {val['mu0.134'][1]:.4g} ({abs(val['mu0.134'][1] - pub19.published) / tol19:.0f}
tolerances). With half a unit of the printed result alone ({unit19 / 2:.3g}) mu = {PAPER_MU} would
{'pass' if abs(val['mu0.132'][1] - pub19.published) <= unit19 / 2 else 'fail'} and rho = 8.000 deg would
{'pass' if abs(val['rho8'][1] - pub19.published) <= unit19 / 2 else 'fail'}.
"""
)


# --- group: published eigenvalues ------------------------------------------------------------------------

def _PrintedEigenvalues(ctx: ValidationContext, S: int) -> np.ndarray:
    s = 'Sp' if S > 0 else 'Sm'
    lam = np.array([complex(ctx.Row(f'lam{k}_re_{s}').published, ctx.Row(f'lam{k}_im_{s}').published)
                    for k in (1, 2)])
    return np.r_[lam, lam.conj()]


def EigenvalueChecks(ctx: ValidationContext) -> List[Check]:
    """Group ``eigenvalues``: the printed eigenvalues, frequencies and Lehr dampings of section 3.1 beside ours (reported, not gated)."""
    checks = []

    def add(rowId, value):
        checks.append(ctx.Compare(rowId, value))

    a28 = AnalyzeStability(DriveFromParameters(_Set28()))
    for S, s in ((+1, 'Sp'), (-1, 'Sm')):
        c = a28.contact[S]
        for k, lam in enumerate(c.oscillating, start=1):
            add(f'lam{k}_re_{s}', lam.real)
            add(f'lam{k}_im_{s}', lam.imag)
            add(f'f{k}_{s}', c.frequenciesHz[k - 1])
        printed = ContactStability.FromEigenvalues(S, _PrintedEigenvalues(ctx, S))
        for k in (1, 2):
            if S > 0:
                add(f'f{k}_Sp_printed', printed.frequenciesHz[k - 1])
                add(f'D{k}_Sp', c.lehrDamping[k - 1])
                add(f'D{k}_Sp_printed', printed.lehrDamping[k - 1])
            else:
                add(f'f{k}_Sm_printed_abs', abs(printed.oscillating[k - 1]) / (2 * math.pi))
                add(f'f{k}_Sm_printed_im', printed.frequenciesHz[k - 1])
    f1 = a28.contact[+1].frequenciesHz
    f7 = AnalyzeStability(DriveFromParameters(_Preset('reel-P7'))).contact[+1].frequenciesHz
    for k in (1, 2):
        add(f'fnat{k}_P1', f1[k - 1])
        add(f'fnat{k}_P7', f7[k - 1])
    return checks


# --- group: eigenvalue forensics ------------------------------------------------------------------------

def _Forensics(ctx: ValidationContext) -> ModuleType:
    """The eigenvalue forensics module (``validation/paper/eigenvalue_forensics.py``)."""
    return eigenvalue_forensics


def ForensicsChecks(ctx: ValidationContext) -> List[Check]:
    """Group ``forensics``: the identified mesh convention (wheel circumference) against the printed frequencies of P1 and P7."""
    fx = _Forensics(ctx)
    printed = {S: _PrintedEigenvalues(ctx, S)[:2] for S in (+1, -1)}
    circ = {name: fx.ScaleMesh(d, fx.WheelCircumferenceFactor(d))
            for name, d in (('P1', DriveFromParameters(_Set28())), ('P7', DriveFromParameters(_Preset('reel-P7'))))}
    checks = []
    for name, d in circ.items():
        f = ContactStability.FromCoefficients(+1, CharacteristicCoefficients(d, +1)).frequenciesHz
        for k in (1, 2):
            checks.append(ctx.Compare(f'fnat{k}_{name}_circ', f[k - 1]))

    results = fx.EvaluateHypotheses(fitted=True, printed=printed)
    byKey = {r.hypothesis.key: r for r in results}
    ratio = fx.B4RatioInterval(printed)
    rhoLo, rhoHi = fx.WheelSideFrictionBound(printed, circ['P1'].gear.gamma)
    ours = {S: CharacteristicCoefficients(DriveFromParameters(_Set28()), S)[3] for S in (+1, -1)}
    implied = {S: fx.ImpliedCoefficients(printed, S) for S in (+1, -1)}
    cls = fx.ModelClassMinimax(printed)
    free = fx.FreeFamilyMinimax(printed)
    k0 = fx.WheelCircumferenceFactor(circ['P1'])
    c = byKey['circ']
    fitMesh, fitRho = byKey['circ+fit-mesh'], byKey['circ+fit-rho']
    circS1 = np.abs(fx.UpperEigenvalues(CharacteristicCoefficients(circ['P1'], -1))) / (2 * math.pi)
    pm = ContactStability.FromEigenvalues(-1, _PrintedEigenvalues(ctx, -1))
    printedAbs, printedIm = np.abs(pm.oscillating) / (2 * math.pi), pm.frequenciesHz
    lam2 = printed[+1][1]
    printedD2 = -lam2.real / lam2.imag
    d2 = [-(lam2.real + a) / (lam2.imag + b) for a in (-fx.HALF_DIGIT, fx.HALF_DIGIT) for b in (-fx.HALF_DIGIT, fx.HALF_DIGIT)]
    d2lo, d2hi = min(d2), max(d2)
    oursD2 = AnalyzeStability(DriveFromParameters(_Set28())).contact[+1].lehrDamping[1]
    b4 = '\n'.join(f'| {S:+d} | {implied[S][0][3]:.5g} | [{implied[S][1][3]:.5g}, {implied[S][2][3]:.5g}] | '
                   f'{ours[S]:.5g} | {implied[S][0][3] / ours[S]:.4f} |' for S in (+1, -1))
    ctx.AddSection('Eigenvalue forensics (section 3.1)', f"""
The eigenvalues printed in section 3.1 are not the roots of eq. (15) with the printed (and reproduced)
b1..b4: the paper model differs from them by up to {byKey['paper'].maxDeviation:.1f} 1/s (rows `lam*`,
verdict DIFFERS). The products of the printed moduli, b4 = |lambda_1|^2 |lambda_3|^2, exceed ours by
{100 * (implied[+1][0][3] / ours[+1] - 1):.1f} % and {100 * (implied[-1][0][3] / ours[-1] - 1):.1f} %:

| S | b4 of the printed eigenvalues | range over their rounding | b4 of eq. (16) | ratio |
|---|---|---|---|---|
{b4}

**Best explanation.** The printed eigenvalues follow from a model in which the mesh spring and damper act
along the wheel circumference (the worm axis) instead of the tooth normal, with the same numbers
kV = 2e8 N/m, dV = 21470 N*s/m; every mesh term of (1)-(2) is then larger by
1/(cos alphaN cos gamma)^2 = {k0:.4f}. This would be the case if the tooth stiffness were entered as a
stiffness referred to the wheel circumference, as gear-mesh elements of system-simulation tools commonly
define it; the paper computed its time-domain results with SimulationX (we could not check that tool's
definition). With no fitted parameter it reproduces all eight printed eigenvalues to within {c.maxDeviation:.3f} 1/s
({c.digits:.1f} units of the printed digit); four of the sixteen components lie outside the rounding
interval +-0.05 1/s:

{fx.DeviationTable(c, printed)}

Fitting a uniform mesh factor on top of it gives s = {fitMesh.value:.4f} (max deviation
{fitMesh.maxDeviation:.3f} 1/s), fitting rho gives {fitRho.value:.3f} deg ({fitRho.maxDeviation:.3f} 1/s):
the optimum sits on the hypothesis itself. The hypothesis was identified on P1 only, yet it also predicts the
natural frequencies printed for P7 in section 3.2.3 (21 and 81 Hz; ours {c.p7FrequenciesHz[0]:.2f} and
{c.p7FrequenciesHz[1]:.2f} Hz, the paper model gives {byKey['paper'].p7FrequenciesHz[1]:.1f} Hz) and for P1 in
section 3.2.2 (33 and 52 Hz); rows `fnat*_circ` (gated). The P7 frequencies alone do not single it out
(dropping cos^2 alphaN gives {byKey['cosA-twice'].p7FrequenciesHz[1]:.2f} Hz as well), the eight eigenvalues do
(`cosA-twice`: {byKey['cosA-twice'].maxDeviation:.2f} 1/s). With |lambda|/(2 pi) the hypothesis also gives the
printed S = -1 frequencies: {', '.join(f'{x:.2f}' for x in circS1)} Hz.

**All hypotheses examined** (max deviation over the 8 components; a fitted parameter is chosen to minimise
it; the last column applies the same change to P7):

{fx.HypothesisTable(results)}

**No consistent explanation within the printed digits.** No parameter set of the paper's model reproduces
all eight printed eigenvalues within +-0.05 1/s. In (16), S enters only through
x(S) = K1 (tan gamma + S tan rho) and y(S) = K2 (1 - S tan gamma tan rho), so a, tauT = dT/kT, eta = dV/kV,
K1, K2 and rho cover every choice of J1, J2, kT, kV, dT, dV, r1, r2, u, alphaN and rho. The best this
six-parameter class can do (gamma = 5.3228 deg) is a max deviation of {cls.maxDeviation:.4f} 1/s, at
rho = {cls.extra['rhoDeg']:.3f} deg (local minimax from the wheel-circumference point; differential evolution,
`python -m validation.paper.eigenvalue_forensics --global`, finds the same optimum). The S-dependence is
what fails: b4(-1)/b4(+1) = cos(gamma - rho)/cos(gamma + rho) for every parameter choice, and the printed
eigenvalues give {ratio[0]:.5f} in [{ratio[1]:.5f}, {ratio[2]:.5f}], i.e. rho between
{math.degrees(rhoLo):.2f} and {math.degrees(rhoHi):.2f} deg on the wheel side, while the worm-side term
needs a larger rho (bound in the slow group's section). A family that does fit is the free seven-parameter model
(a, tauT, eta, x+, y+, x-, y-) with x and y not tied to one friction angle: max deviation
{free.maxDeviation:.4f} 1/s, at mesh terms within 0.5 % of the wheel-circumference model
(x+, y+, x-, y- times {', '.join(f"{free.extra[n + '/start']:.4f}" for n in ('x+', 'y+', 'x-', 'y-'))}) and
a = kT/J1 times {free.extra['a/start']:.4f}, with dT/kT times {free.extra['tauT/start']:.3f} and dV/kV times
{free.extra['eta/start']:.3f}. The residual of about one printed digit is thus not a parameter of (14)-(16);
we cannot tell what produced it (possibly the eigenvalues were computed from the linearized simulation model
of Figure 7, not from (15), or rounded in several steps).

**Other printed numbers.** The S = -1 frequencies 41.9 and 42.0 Hz are |lambda|/(2 pi) of the printed
eigenvalues ({', '.join(f'{x:.2f}' for x in printedAbs)} Hz), not the stated omega/(2 pi)
({', '.join(f'{x:.2f}' for x in printedIm)} Hz); for S = +1 both conventions give the printed 33.3 and 52.2 Hz.
D2 = 0.017 does not follow from the printed lambda_3/4 ({printedD2:.4f}; {d2lo:.4f} .. {d2hi:.4f} over the
rounding) but matches the paper model ({oursD2:.4f}). The paper cites "condition (21), b1 > 0"; it means (17).
""")
    return checks


def ForensicsSlowChecks(ctx: ValidationContext) -> List[Check]:
    """Group ``forensics-slow``: the worm-side friction bound of the reduced model (an optimization, skipped by quick runs)."""
    fx = _Forensics(ctx)
    printed = {S: _PrintedEigenvalues(ctx, S)[:2] for S in (+1, -1)}
    bound = _WormSideBound(fx, printed)
    ctx.AddSection('Eigenvalue forensics: worm-side friction bound (slow group)', f"""
With the worm-side term x(S) and the wheel-side term y(S) given separate friction angles, the printed
eigenvalues can be matched within +-0.05 1/s only if the worm-side friction angle is at least
{bound:.3f} deg (bisection over minimax fits of the remaining six parameters), while the wheel-side
angle must stay below the b4-ratio bound above. One friction angle cannot satisfy both.
""")
    return []


def _WormSideBound(fx: ModuleType, printed) -> float:
    """Smallest worm-side friction angle (deg) for which some parameters fit within +-0.05 1/s."""
    tg = math.tan(_Set28()['gamma'])
    start = fx.ModelClassMinimax(printed).values

    def best(rhoDeg, q0):
        tx = math.tan(math.radians(rhoDeg))

        def dev(q):
            a, tauT, eta, K1, K2, ty = q
            b = {S: fx.ReducedCoefficients(a, tauT, eta, K1 * (tg + S * tx), K2 * (1 - S * tg * ty)) for S in (+1, -1)}
            return fx.EigenvalueDeviations({S: fx.UpperEigenvalues(b[S]) for S in b}, printed)
        q = fx._Minimax(dev, q0)
        return float(np.max(np.abs(dev(q)))), q

    lo, hi = 7.8, 8.0  # deg: lo infeasible, hi feasible (checked below)
    mLo, _ = best(lo, start)
    mHi, q = best(hi, start)
    if not (mLo > fx.HALF_DIGIT >= mHi):
        return float('nan')
    for _ in range(14):
        mid = 0.5 * (lo + hi)
        m, qm = best(mid, q)
        if m <= fx.HALF_DIGIT:
            hi, q = mid, qm
        else:
            lo = mid
    return hi


# --- registry and runner ----------------------------------------------------------------------------------
