"""The linearized model of the paper written out from its equations, independently of exudyn_worm.

Tests compare the package with these closed forms instead of with numbers the package once printed. Only
numpy and the printed equations are used: eqs. (3), (9), (11), (13), (14)-(16), (19), (22), (23) of the paper
*Stability Analysis and Simulation of the Vibration Behavior of Worm Gears in Drive Systems* (section 2, the worm
gear with elastic drive shaft). Keys are those of the parameter sets
(``GetPreset('reel-P1')``): alphaN, gamma, mu, r1, r2, kV, DV, J1, J2, kT, DT; SI units, angles in rad.
"""
import math

import numpy as np

__all__ = ['Ratio', 'FrictionAngle', 'Dampings', 'MeshCoefficients', 'BCoefficients', 'Eigenvalues',
           'HurwitzStable', 'ChainEigenvalues', 'BoundaryDecades',
           'AxialBearingEigenvalues', 'FrictionSlopeEigenvalues']


def Ratio(p) -> float:
    """Transmission ratio u = r2 / (r1 tan gamma), eq. (3)."""
    return p['r2'] / (p['r1'] * math.tan(p['gamma']))


def FrictionAngle(p) -> float:
    """rho = arctan(mu / cos alphaN), eq. (13)."""
    return math.atan(p['mu'] / math.cos(p['alphaN']))


def Dampings(p):
    """(dT, dV) from the damping measures: eq. (22) dT = 2 DT sqrt(kT J1), eq. (23) dV r2^2 = 2 DV sqrt(kV r2^2 J2)."""
    dT = 2 * p['DT'] * math.sqrt(p['kT'] * p['J1'])
    dV = 2 * p['DV'] * math.sqrt(p['kV'] * p['r2']**2 * p['J2']) / p['r2']**2
    return dT, dV


def MeshCoefficients(p, S: int):
    """(c1, c3) of eqs. (9) and (11) for the contact state S = +1 or -1."""
    a, g, rho = p['alphaN'], p['gamma'], FrictionAngle(p)
    c1 = p['r1']**2 * math.cos(a)**2 * math.sin(g) * math.sin(g + rho * S) / math.cos(rho)
    c3 = p['r1'] * p['r2'] * math.cos(a)**2 * math.sin(g) * math.cos(g + rho * S) / math.cos(rho)
    return c1, c3


def BCoefficients(p, S: int) -> np.ndarray:
    """[b1, b2, b3, b4] of the characteristic polynomial (15), written out as eq. (16)."""
    u, (dT, dV), (c1, c3) = Ratio(p), Dampings(p), MeshCoefficients(p, S)
    J1, J2, kT, kV = p['J1'], p['J2'], p['kT'], p['kV']
    return np.array([(dT + c1 * dV) / J1 + u * c3 * dV / J2,
                     (kT + c1 * kV) / J1 + u * c3 * kV / J2 + u * c3 * dT * dV / (J1 * J2),
                     u * c3 * (dT * kV + dV * kT) / (J1 * J2),
                     u * c3 * kT * kV / (J1 * J2)])


def Eigenvalues(p, S: int) -> np.ndarray:
    """The four roots of P(lambda) = lambda^4 + b1 lambda^3 + b2 lambda^2 + b3 lambda + b4, eq. (15)."""
    return np.roots(np.concatenate([[1.], BCoefficients(p, S)]))


def HurwitzStable(p) -> bool:
    """Both contact states satisfy (17) b1 > 0 and (19) b1 b2 b3 - b1^2 b4 - b3^2 > 0 (b3, b4 > 0 always)."""
    for S in (+1, -1):
        b1, b2, b3, b4 = BCoefficients(p, S)
        if not (b1 > 0 and b1 * b2 * b3 - b1**2 * b4 - b3**2 > 0):
            return False
    return True


def _AddSpring(K, C, i, j, k, d):
    """A spring-damper (k, d) between coordinates i and j (j None: to a held body) into K and C."""
    for A, v in ((K, k), (C, d)):
        A[i, i] += v
        if j is not None:
            A[j, j] += v
            A[i, j] -= v
            A[j, i] -= v


def ChainEigenvalues(p, chain, S: int) -> np.ndarray:
    """Eigenvalues of the linearized drive with a drive-side chain (Figure 19), from its mass, damping and
    stiffness matrices: motor (held) --(k_n, d_n)-- J_n -- ... --(k4, d4)-- J4 --(kT, dT)-- J1 --mesh-- J2.

    ``chain`` lists (J, k, d) from the worm side outwards (J4, k4, d4 first). The mesh rows are those of the
    determinant (14): J1 row ``+kV c1 phi1 - kV c1 u phi2``, J2 row ``-kV c3 phi1 + kV c3 u phi2``.
    """
    u, (dT, dV), (c1, c3) = Ratio(p), Dampings(p), MeshCoefficients(p, S)
    n = 2 + len(chain)                                   # coordinates: phi1, phi2, phi4, phi5, ...
    M, C, K = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n))
    M[0, 0], M[1, 1] = p['J1'], p['J2']
    kV = p['kV']
    for (i, j), kk, dd in [((0, 0), kV * c1, dV * c1), ((0, 1), -kV * c1 * u, -dV * c1 * u),
                           ((1, 0), -kV * c3, -dV * c3), ((1, 1), kV * c3 * u, dV * c3 * u)]:
        K[i, j] += kk
        C[i, j] += dd
    springs = [(0, 2, p['kT'], dT)] + [(2 + m, 3 + m, k, d) for m, (_, k, d) in enumerate(chain)]
    for m, (J, _, _) in enumerate(chain):
        M[2 + m, 2 + m] = J
    for i, j, k, d in springs:
        _AddSpring(K, C, i, j if j < n else None, k, d)      # the last spring ends on the (held) motor
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    return np.linalg.eigvals(A)


def BoundaryDecades(p, key: str, stable: float, unstable: float, tol: float = 1e-12) -> float:
    """The stability boundary t (in decades of ``p[key]``, other keys held) between a stable ``stable`` and an
    unstable ``unstable`` value of t, by bisection of :func:`HurwitzStable`."""
    def Stable(t):
        q = dict(p)
        q[key] = p[key] * 10.**t
        return HurwitzStable(q)
    assert Stable(stable) and not Stable(unstable)
    while abs(stable - unstable) > tol:
        mid = 0.5 * (stable + unstable)
        stable, unstable = (mid, unstable) if Stable(mid) else (stable, mid)
    return 0.5 * (stable + unstable)


def AxialBearingEigenvalues(p, S: int) -> np.ndarray:
    """Eigenvalues of the two-mass drive whose worm sits in an axial bearing (kA, dA, mA; not in the paper, the
    package's extension): coordinates [phi1, phi2, xA]. The normal displacement is eq. (5) plus the axial part,
    Delta s = r1 cos(alphaN) sin(gamma) (phi1 - u phi2) + cos(alphaN) cos(gamma) xA, the mesh force
    F = kV Delta s + dV Delta s' acts on the worm with the lever c2 of eq. (10), on the wheel with c4 of eq. (12)
    and on the axial coordinate as -c4 F / r2 (the axial share of the tooth force)."""
    a, g, rho, u = p['alphaN'], p['gamma'], FrictionAngle(p), Ratio(p)
    dT, dV = Dampings(p)
    c2 = p['r1'] * math.cos(a) * math.sin(g + rho * S) / math.cos(rho)
    c4 = p['r2'] * math.cos(a) * math.cos(g + rho * S) / math.cos(rho)
    L = p['r1'] * math.cos(a) * math.sin(g)
    lever = np.array([c2, -c4, c4 / p['r2']])               # generalized force per unit F is -lever
    gradient = np.array([L, -L * u, math.cos(a) * math.cos(g)])
    K = np.diag([p['kT'], 0., p['kA']]) + p['kV'] * np.outer(lever, gradient)
    C = np.diag([dT, 0., p.get('dA', 0.)]) + dV * np.outer(lever, gradient)
    Minv = np.diag(1. / np.array([p['J1'], p['J2'], p['mA']]))
    return np.linalg.eigvals(np.block([[np.zeros((3, 3)), np.eye(3)], [-Minv @ K, -Minv @ C]]))


def FrictionSlopeEigenvalues(p, loadChain, S: int, mu0: float, dmuDv: float, Fn0: float) -> np.ndarray:
    """Eigenvalues of the drive linearized at a steady operating point with a speed-dependent friction: motor held
    --(kT, dT)-- J1 --mesh-- J2 --(kL1, dL1)-- JL1 -- ... (a load-side chain, wheel side first).

    The mesh coefficients c1, c3 of eqs. (9), (11) are taken at mu0 (rho of eq. (13) at mu0), and the friction
    force mu(v) Fn with v = r1 |phi1'| / cos(gamma) adds the damping of its slope: the worm torque -c2 sigma Fn and
    the wheel torque c4 sigma Fn change with phi1' through mu, c2 = r1 (cos(alphaN) sin(gamma) + S mu cos(gamma)),
    c4 = r2 (cos(alphaN) cos(gamma) - S mu sin(gamma)) (eqs. (10), (12) with (13)), i.e. Fn0 r1^2 mu' in the worm
    row and Fn0 r1 r2 tan(gamma) mu' in the wheel row, both in the worm-speed column.
    """
    q = {**p, 'mu': mu0}
    u, (dT, dV), (c1, c3) = Ratio(q), Dampings(q), MeshCoefficients(q, S)
    n = 2 + len(loadChain)                               # coordinates: phi1, phi2, phiL1, ...
    M, C, K = np.zeros((n, n)), np.zeros((n, n)), np.zeros((n, n))
    M[0, 0], M[1, 1] = q['J1'], q['J2']
    kV = q['kV']
    for (i, j), kk, dd in [((0, 0), q['kT'], dT), ((0, 0), kV * c1, dV * c1), ((0, 1), -kV * c1 * u, -dV * c1 * u),
                           ((1, 0), -kV * c3, -dV * c3), ((1, 1), kV * c3 * u, dV * c3 * u)]:
        K[i, j] += kk
        C[i, j] += dd
    C[0, 0] += Fn0 * q['r1']**2 * dmuDv
    C[1, 0] += Fn0 * q['r1'] * q['r2'] * math.tan(q['gamma']) * dmuDv
    for m, (J, k, d) in enumerate(loadChain):
        i, j = 1 + m, 2 + m                              # shaft m between wheel (or stage m) and stage m + 1
        M[j, j] = J
        _AddSpring(K, C, i, j, k, d)
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    return np.linalg.eigvals(A)
