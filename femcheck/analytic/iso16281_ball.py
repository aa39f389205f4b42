"""ISO/TS 16281:2008 for single-row radial ball bearings: point-contact stiffness from the osculations, rigid-ring
equilibrium under radial load, axial load and tilting moment with the contact angle following the displacement,
and the basic reference rating life L10r. SI units in and out (m, N, Pa, rad); pure functions.

Equation numbers are those of ISO/TS 16281:2008 as quoted in the comments of the public implementation
``minzhun/ISO16281`` (``BallBearing.py``): osculation and ellipse ratio eqs 2-4, element deflection and load
eqs 10 and 12, equilibrium eqs 16-18, element ratings eqs 19-24, equivalent element loads eqs 25-28, L10r eq 29.
The element ratings are those of ISO 281's background (ISO/TR 1281-1) for balls. The TS formulas in N, mm are
dimensionally homogeneous (the constant 1.48 of the spring constant is dimensionless), so they are used here in
SI directly.

Geometry (deep-groove or angular-contact ball bearing, one row, Z balls of diameter D_w on the pitch diameter
D_pw, groove radii r_i, r_e, diametral (radial) operating clearance s_r; the published example is named in spec
bearing-load.md §3.6 D and reproduced in tests/test_iso16281_example.py):

    A = r_i + r_e - D_w                          distance of the groove curvature centres when in contact
    alpha_0 = arccos(1 - s_r/(2A))               free contact angle, s_a = 2 A sin(alpha_0) axial clearance
    R_i = D_pw/2 + (r_i - D_w/2) cos(alpha_0)    radius of the inner groove's curvature centre

Ball j at azimuth psi_j from the radial load line; the inner ring moves by delta_r (along the load), delta_t
(normal to it), delta_a (axially, measured from the axially centred position, as the example's ``Delta_a_MASTA``) and tilts
by theta_1 (in the plane of the radial load) and theta_2 (in the normal plane). The groove curvature centres then
lie apart by (eq 10, small tilts)

    x_j = A - s_r/2 + delta_r cos(psi_j) + delta_t sin(psi_j),
    y_j = delta_a + R (theta_1 cos(psi_j) + theta_2 sin(psi_j)),
    delta_j = sqrt(x_j^2 + y_j^2) - A,   alpha_j = atan2(y_j, x_j),   Q_j = c_p max(delta_j, 0)^(3/2)   (eq 12)

with R = D_pw/2, the TS's moment arm (eq 18), in both the kinematics and the moment balance (so that the balance
is the gradient of one convex potential, :func:`ball_equilibrium`). The published example
(tests/test_iso16281_example.py) has its tilts reproduced with R = D_pw/2; R = R_i, the radius of the inner
groove's curvature centre (``radius="groove"``), gives them 1 % smaller.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize
from scipy.special import ellipe, ellipk

RADIAL_GROOVE_RATIOS = (0.52, 0.53)   # r_i/D_w, r_e/D_w of radial ball bearings (ISO 281's f_c basis)
# Hertz's exact value of the TS's 1.48 (sphere on flat: Q = (4/3) E* R^(1/2) delta^(3/2), E* = E/(2(1 - nu^2))).
HERTZ_CONSTANT = float(np.sqrt(2.0) * np.pi / 3.0)


def curvature(diameter: float, pitch_diameter: float, groove_radius: float, contact_angle: float,
              ring: str) -> tuple[float, float]:
    """Curvature sum Sigma rho (1/m) and relative curvature difference F(rho) (-) of the ball on the inner
    (``ring="inner"``) or outer raceway (TS eq 2 and the definitions before it), gamma = D_w cos(alpha)/D_pw:

        inner: Sigma rho = (2/D_w)(2 + gamma/(1 - gamma) - D_w/(2 r_i)),
               F(rho) = (gamma/(1 - gamma) + D_w/(2 r_i)) / (2 + gamma/(1 - gamma) - D_w/(2 r_i))
        outer: gamma -> -gamma, r_i -> r_e."""
    g = diameter * np.cos(contact_angle) / pitch_diameter
    t = g / (1.0 - g) if ring == "inner" else -g / (1.0 + g)
    osc = diameter / (2.0 * groove_radius)
    return float(2.0 / diameter * (2.0 + t - osc)), float((t + osc) / (2.0 + t - osc))


def ellipse_ratio(f_rho: float) -> float:
    """chi = a/b >= 1 of the contact ellipse from F(rho) (TS eqs 2-4):
    F(rho) = 1 - 2/(chi^2 - 1) (K(chi)/E(chi) - 1), K, E complete elliptic integrals of modulus
    k^2 = 1 - 1/chi^2 (scipy's parameter m = k^2)."""
    def residual(log_chi):
        chi = np.exp(log_chi)
        m = 1.0 - 1.0 / chi**2
        return 1.0 - 2.0 / (chi**2 - 1.0) * (ellipk(m) / ellipe(m) - 1.0) - f_rho
    return float(np.exp(brentq(residual, 1e-9, np.log(1e4), xtol=1e-15, rtol=1e-15)))


def spring_constant(modulus: float, poisson: float, diameter: float, pitch_diameter: float, inner_groove: float,
                    outer_groove: float, contact_angle: float = 0.0, constant: float = 1.48) -> float:
    """c_p (N/m^(3/2)) of one ball between both raceways, Q = c_p delta^(3/2) (TS eq 12), both bodies steel-like
    with the same E (Pa), nu:

        c_p = 1.48 E/(1 - nu^2) [ sum_{i,e} K(chi) (Sigma rho / (chi^2 E(chi)))^(1/3) ]^(-3/2).

    Each term is Hertz's approach of one elliptical contact; ``constant`` is the TS's rounded 1.48 of Hertz's
    exact sqrt(2) pi/3 = 1.480961 (:data:`HERTZ_CONSTANT`; c_p 0.065 % stiffer, radial deflections 0.043 % smaller)."""
    total = 0.0
    for ring, r in (("inner", inner_groove), ("outer", outer_groove)):
        srho, frho = curvature(diameter, pitch_diameter, r, contact_angle, ring)
        chi = ellipse_ratio(frho)
        m = 1.0 - 1.0 / chi**2
        total += ellipk(m) * (srho / (chi**2 * ellipe(m))) ** (1.0 / 3.0)
    return float(constant * modulus / (1.0 - poisson**2) * total ** -1.5)


@dataclass(frozen=True)
class BallBearing:
    """One row of ``balls`` balls of ``diameter`` D_w (m) on ``pitch_diameter`` D_pw (m); groove radii r_i, r_e (m);
    ``clearance`` s_r (m, diametral); ``contact_angle`` alpha (rad) the nominal angle of the ratings (0 for a
    deep-groove bearing); ``first_ball`` azimuth of ball 0 from the radial load line (rad); ``rows`` i."""

    balls: int
    diameter: float
    pitch_diameter: float
    inner_groove: float
    outer_groove: float
    clearance: float = 0.0
    contact_angle: float = 0.0
    first_ball: float = 0.0
    rows: int = 1

    @property
    def groove_distance(self) -> float:
        """A = r_i + r_e - D_w (m)."""
        return self.inner_groove + self.outer_groove - self.diameter

    @property
    def free_contact_angle(self) -> float:
        """alpha_0 = arccos(1 - s_r/(2A)) (rad)."""
        return float(np.arccos(1.0 - self.clearance / (2.0 * self.groove_distance)))

    @property
    def axial_clearance(self) -> float:
        """s_a = 2 A sin(alpha_0) (m)."""
        return float(2.0 * self.groove_distance * np.sin(self.free_contact_angle))

    @property
    def inner_groove_centre_radius(self) -> float:
        """R_i = D_pw/2 + (r_i - D_w/2) cos(alpha_0) (m)."""
        return float(0.5 * self.pitch_diameter + (self.inner_groove - 0.5 * self.diameter)
                     * np.cos(self.free_contact_angle))

    @property
    def azimuths(self) -> np.ndarray:
        """psi_j (rad) of the balls from the radial load line."""
        return self.first_ball + 2.0 * np.pi * np.arange(self.balls) / self.balls


def radial_ball_bearing(balls: int, diameter: float, pitch_diameter: float, clearance: float = 0.0,
                        first_ball: float = 0.0) -> BallBearing:
    """A deep-groove ball bearing with r_i = 0.52 D_w, r_e = 0.53 D_w."""
    ri, re = RADIAL_GROOVE_RATIOS
    return BallBearing(balls, diameter, pitch_diameter, ri * diameter, re * diameter, clearance, 0.0, first_ball)


@dataclass
class BallEquilibrium:
    """Solution of :func:`ball_equilibrium`: inner-ring displacement ``delta_r`` along the radial load line,
    ``delta_t`` normal to it in the radial plane, ``delta_a`` axial (m; from the axially centred position), and
    tilts ``tilt`` theta_1 (rad; axial shift R theta_1 cos(psi), in the plane of the radial load) and
    ``tilt_normal`` theta_2 (R theta_2 sin(psi)); per ball ``deflection`` delta_j (m), ``contact_angles``
    alpha_j (rad), ``loads`` Q_j (N); ``residual`` the largest force/moment imbalance over the load scale."""

    delta_r: float
    delta_t: float
    delta_a: float
    tilt: float
    tilt_normal: float
    deflection: np.ndarray
    contact_angles: np.ndarray
    loads: np.ndarray
    residual: float

    @property
    def radial_displacement(self) -> float:
        """|(delta_r, delta_t)| (m)."""
        return float(np.hypot(self.delta_r, self.delta_t))

    @property
    def misalignment(self) -> float:
        """|(theta_1, theta_2)| (rad), the total tilt."""
        return float(np.hypot(self.tilt, self.tilt_normal))


def tilt_radius(b: BallBearing, kind: str = "pitch") -> float:
    """R (m) at which a tilt theta shifts the inner groove axially by R theta: ``"pitch"`` D_pw/2 (the TS's moment
    arm, eq 18) or ``"groove"`` R_i (the inner groove's curvature centre)."""
    return 0.5 * b.pitch_diameter if kind == "pitch" else b.inner_groove_centre_radius


def _groove_offsets(b: BallBearing, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """x_j = x0_j + B_j u for u = (delta_r, delta_t, delta_a, theta_1, theta_2): x0 (Z, 2), B (Z, 2, 5)."""
    c, s = np.cos(b.azimuths), np.sin(b.azimuths)
    z = np.zeros_like(c)
    x0 = np.stack([np.full_like(c, b.groove_distance - 0.5 * b.clearance), z], axis=1)
    B = np.stack([np.stack([c, s, z, z, z], axis=1),
                  np.stack([z, z, 1.0 + z, radius * c, radius * s], axis=1)], axis=1)
    return x0, B


def ball_kinematics(b: BallBearing, c_p: float, u: np.ndarray, radius: float | None = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(delta_j, alpha_j, Q_j) of every ball for u = (delta_r, delta_t, delta_a, theta_1, theta_2) (TS eqs 10, 12;
    module doc; small tilts: the axial shift of the groove centre is R theta)."""
    x0, B = _groove_offsets(b, tilt_radius(b) if radius is None else radius)
    x = x0 + B @ np.asarray(u, dtype=float)
    delta = np.hypot(x[:, 0], x[:, 1]) - b.groove_distance
    return delta, np.arctan2(x[:, 1], x[:, 0]), c_p * np.clip(delta, 0.0, None) ** 1.5


def ball_equilibrium(b: BallBearing, c_p: float, radial_load: float = 0.0, axial_load: float = 0.0,
                     moment: float = 0.0, moment_normal: float = 0.0, radius: str = "pitch") -> BallEquilibrium:
    """Displacements and tilts u = (delta_r, delta_t, delta_a, theta_1, theta_2) of the inner ring that carry F_r
    (N, along psi = 0), F_a (N), the moment M_1 (N m) that tilts the ring in the plane of the radial load and M_2
    (N m) that tilts it in the normal plane (TS eqs 16-18 with both tilt directions; a positive M_1, M_2 moves the
    inner groove at psi = 0, psi = 90 deg towards +axial):

        F_r = sum Q_j cos(alpha_j) cos(psi_j),  0 = sum Q_j cos(alpha_j) sin(psi_j),  F_a = sum Q_j sin(alpha_j),
        M_1 = R sum Q_j sin(alpha_j) cos(psi_j),  M_2 = R sum Q_j sin(alpha_j) sin(psi_j),

    R = :func:`tilt_radius` (``radius``). These are the stationarity conditions of the potential
    Pi(u) = sum_j (2/5) c_p max(delta_j, 0)^(5/2) - F . u, which is convex (delta_j = |x0_j + B_j u| - A is convex
    in u), so it is minimised by Newton's method with a trust region (analytic gradient and Hessian), in units of
    the Hertz deflection scale (F/(Z c_p))^(2/3)."""
    R = tilt_radius(b, radius)
    x0, B = _groove_offsets(b, R)
    F = np.array([radial_load, 0.0, axial_load, moment, moment_normal])
    scale_f = max(abs(radial_load), abs(axial_load), abs(moment) / R, abs(moment_normal) / R, 1e-12)
    d0 = (scale_f / (b.balls * c_p)) ** (2.0 / 3.0)
    unit = np.array([d0, d0, d0, d0 / R, d0 / R])
    A = b.groove_distance

    def parts(v):
        x = x0 + B @ (v * unit)
        r = np.hypot(x[:, 0], x[:, 1])
        n = x / r[:, None]
        delta = np.clip(r - A, 0.0, None)
        return x, r, n, delta

    def energy(v):
        delta = parts(v)[3]
        return (0.4 * c_p * np.sum(delta**2.5) - F @ (v * unit)) / (scale_f * d0)

    def gradient(v):
        _, _, n, delta = parts(v)
        g = np.einsum("j,ji,jik->k", c_p * delta**1.5, n, B) - F
        return g * unit / (scale_f * d0)

    def hessian(v):
        _, r, n, delta = parts(v)
        q = c_p * delta**1.5
        kn = 1.5 * c_p * np.sqrt(delta)
        eye = np.eye(2)[None]
        nn = n[:, :, None] * n[:, None, :]
        k = kn[:, None, None] * nn + (q / r)[:, None, None] * (eye - nn)
        H = np.einsum("jik,jil,jlm->km", B, k, B)
        return H * np.outer(unit, unit) / (scale_f * d0)

    v0 = np.zeros(5)                                   # a start in which the loaded balls touch
    v0[0] = np.sign(radial_load) * (1.0 + 0.5 * b.clearance / d0)
    v0[2] = np.sign(axial_load) * np.sqrt(2.0 * A / d0)
    v0[3], v0[4] = np.sign(moment), np.sign(moment_normal)
    v = minimize(energy, v0, jac=gradient, hess=hessian, method="trust-exact", options={"gtol": 1e-13}).x
    for _ in range(10):          # Newton polish: the energy's round-off stalls the trust region near the minimum
        g = gradient(v)
        if np.abs(g).max() < 1e-15:
            break
        v = v - np.linalg.lstsq(hessian(v), g, rcond=1e-14)[0]
    u = v * unit
    delta, alpha, q = ball_kinematics(b, c_p, u, R)
    _, _, n, dl = parts(v)
    carried = np.einsum("j,ji,jik->k", c_p * dl**1.5, n, B)        # sum Q_j n_j . B_j: (F_r, F_t, F_a, M_1, M_2)
    res = float(np.abs((carried - F) / (scale_f * np.array([1.0, 1.0, 1.0, R, R]))).max())
    return BallEquilibrium(*(float(t) for t in u), delta, alpha, q, res)


def element_ratings(b: BallBearing, rating: float) -> tuple[float, float]:
    """Basic dynamic load ratings of one ball on the inner and outer raceway, Q_ci and Q_ce (N) (TS eqs 19-24,
    radial ball bearings; ISO/TR 1281-1), from the bearing's basic dynamic load rating C (N) of ISO 281:

        Q_ci = C/(0.407 Z cos(alpha)^0.7 i^0.7) [1 + X^(10/3)]^0.3,
        Q_ce = C/(0.389 Z cos(alpha)^0.7 i^0.7) [1 + X^(-10/3)]^0.3,
        X = 1.044 ((1 - g)/(1 + g))^1.72 (r_i (2 r_e - D_w)/(r_e (2 r_i - D_w)))^0.41,   g = D_w cos(alpha)/D_pw."""
    g = b.diameter * np.cos(b.contact_angle) / b.pitch_diameter
    ri, re, dw = b.inner_groove, b.outer_groove, b.diameter
    ratio = 1.044 * ((1.0 - g) / (1.0 + g)) ** 1.72 * (ri / re * (2.0 * re - dw) / (2.0 * ri - dw)) ** 0.41
    base = rating / (b.balls * np.cos(b.contact_angle) ** 0.7 * b.rows ** 0.7)
    qci = base / 0.407 * (1.0 + ratio ** (10.0 / 3.0)) ** 0.3
    qce = base / 0.389 * (1.0 + ratio ** (-10.0 / 3.0)) ** 0.3
    return float(qci), float(qce)


def equivalent_loads(loads: np.ndarray, rotating: str = "inner") -> tuple[float, float]:
    """Dynamic equivalent ball loads (Q_ei, Q_ee) (N) of the inner and outer raceway (TS eqs 25-28): the rotating
    ring's (Sum Q_j^3 / Z)^(1/3), the stationary ring's (Sum Q_j^(10/3) / Z)^(3/10)."""
    q = np.asarray(loads, dtype=float)
    rot = float((np.sum(q**3) / q.size) ** (1.0 / 3.0))
    fixed = float((np.sum(q ** (10.0 / 3.0)) / q.size) ** 0.3)
    return (rot, fixed) if rotating == "inner" else (fixed, rot)


def reference_rating_life(loads: np.ndarray, b: BallBearing, rating: float, rotating: str = "inner") -> float:
    """Basic reference rating life L10r (million revolutions) of TS eq 29:

        L10r = [ (Q_ci/Q_ei)^(-10/3) + (Q_ce/Q_ee)^(-10/3) ]^(-9/10)

    from the ball loads Q_j (N) and the basic dynamic load rating C (N)."""
    qci, qce = element_ratings(b, rating)
    qei, qee = equivalent_loads(loads, rotating)
    total = (qci / qei) ** (-10.0 / 3.0) + (qce / qee) ** (-10.0 / 3.0) if qei > 0 else 0.0
    return float(total ** (-9.0 / 10.0)) if total > 0 else float("inf")
