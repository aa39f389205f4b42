"""Strip theory "H+C" on the spherical roller bearing (seed 000 §3.1, eqs 4-11 with E4; spec srb-rolling §4.1):
Hertz per contact, Carter per strip, the longitudinal creepage of each strip from the variable rolling radii of
roller and raceway, and the two roller speeds (omega_m, omega_R) from the equilibrium of the rolling-direction
forces and of the moments about the roller axis.

Assumptions (seed 000 §3.1): nominal orientation (no tilt, skew); both contact centres on the same rolling circle
of the roller, at y = s0 along the nominal roller axis e_y from its centre (E13; s0 = 0: the nominal points);
the same normal load N on both contacts. Per contact j:

- Normal (Hertz): lateral radii R (crown) and r_g (groove) with eq 4's correction of the lateral half-curvature,
  B_corr = B + d/(2 r^2), B = (1/R - 1/r_g)/2, d the Hertz approach, r = (R + r_g)/2 (two fixed-point passes;
  +0.49 % on B for the inner contact); longitudinal radii at the contact centre by Meusnier, 1/R_x = cos(psi)/rho
  per body of revolution (2/D -/+ cos a / r_roll at s0 = 0).
- Strips parallel to x over eta in (-b, b) (:mod:`femcheck.cect.strip`'s slicing: exact strip loads dN,
  a' = a sqrt(1 - eta^2/b^2), p'0 = p0 sqrt(1 - eta^2/b^2)), centred at y = s0 + eta.
- Creepage of a strip from the rolling radii at y (eqs 5-7): the roller point P_R(y) = C0 + y e_y -/+ rho_R(y) e_z
  with rho_R(y) = sqrt(R^2 - y^2) - (R - D/2), the raceway point P_j(y) where the line C0 + y e_y + t e_z meets the
  groove; V_c,R = |omega_R| rho_R(y), V_c,j = |omega_m - omega_j| rho_j(P_j) (eqs 5-6), V_c their mean and the
  slip of the roller relative to the ring along X, w_X = v_R,X(P_R) - v_j,X(P_j) (m/s); |xi| = |w_X| / V_c (eq 7).
  Pure longitudinal creepage, constant along each strip (the spin's lateral part is not in H+C).
- Carter per strip (eqs 8-11): xi* = E* xi / (2 mu p'0), E* = E/(2(1 - nu^2)); c' = 1 - min(1, |xi*|); traction
  (eq 9) opposite to the slip, adhesion at the leading edge; the strip force on the roller along X,
  dF_X = -sgn(w_X) (1 - c'^2) mu dN (eq 11: friction opposes the roller's slip; seed 000 prints -sgn(xi) with its
  own axis convention); slip velocity (eq 10 as corrected in E4)
      v/V_c = |xi| [1 + (c' - 1 + sqrt((x' - 1 + c')^2 - c'^2)) / |xi*|]   in slip, 0 in adhesion,
  along the rigid slip; frictional power per unit width int |p_x v| dx and work per width per passage
  int |p_x v| dx / V_c (J/m; seed 000 Fig. 12).
- Speeds: (omega_m, omega_R) by Newton (finite-difference Jacobian) on sum F_X = 0 and
  sum ((P_R - C) x dF_X X).v = 0 over both contacts ("equilibrium of longitudinal forces and moments around the y
  axis"; only the tangential forces enter).

Outputs in SI; ``f_x`` normalised as seed 000 Table 2: F_j . x_p / (mu N) with x_p = x_I the direction in which the
roller moves relative to the inner ring (E10).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import elliptic_contact
from ..errors import ConvergenceError, InputError
from ..geometry.revolution import ray_intersection
from ..geometry.srb_bearing import CONTACTS, BearingGeometry, Pose, X, nominal_speeds, ring_body, ring_rate, roller_body

CARTER_POINTS = 2000          # midpoint rule along each strip for the frictional power (error < 1e-5 relative)


@dataclass
class StripContact:
    """H+C solution of one contact. Per strip (arrays of n): ``y`` (m, along e_y from the roller centre),
    ``half_length`` a' (m), ``p_max`` p'0 (Pa), ``normal_force`` dN (N), ``rigid_slip`` w_X (m/s, roller
    relative to ring along X), ``rolling_speed`` V_c (m/s), ``creepage`` xi = (V_c,R - V_c,j)/V_c (eq 7, -),
    ``normalized_creepage`` xi* (-), ``stick_fraction`` c' (-), ``force_X`` dF_X (N, on the roller along X),
    ``power_per_width`` (W/m), ``work_per_width`` (J/m per passage). Totals: ``force_X`` sum (N), ``moment_v``
    about the roller axis (N m), ``adhesion_fraction``, ``frictional_power`` (W); ``hertz`` (a, b, p0,
    approach); ``zero_slip`` the y (m) where the rigid slip changes sign; ``width`` of a strip (m)."""

    y: np.ndarray
    width: float
    half_length: np.ndarray
    p_max: np.ndarray
    normal_force: np.ndarray
    rigid_slip: np.ndarray
    rolling_speed: np.ndarray
    creepage: np.ndarray
    normalized_creepage: np.ndarray
    stick_fraction: np.ndarray
    strip_force_X: np.ndarray
    strip_moment_v: np.ndarray
    power_per_width: np.ndarray
    work_per_width: np.ndarray
    hertz: dict
    zero_slip: list

    @property
    def force_X(self) -> float:
        return float(self.strip_force_X.sum())

    @property
    def moment_v(self) -> float:
        return float(self.strip_moment_v.sum())

    @property
    def adhesion_fraction(self) -> float:
        return float((self.stick_fraction * self.half_length).sum() / self.half_length.sum())

    @property
    def frictional_power(self) -> float:
        return float(self.power_per_width.sum() * self.width)

    @property
    def normal_per_width(self) -> np.ndarray:
        """N*(y) = dN/dy (N/m)."""
        return self.normal_force / self.width

    @property
    def force_per_width(self) -> np.ndarray:
        """F_X*(y) (N/m)."""
        return self.strip_force_X / self.width


@dataclass
class StripBearingResult:
    """H+C on both contacts at the speeds ``omega_m``, ``omega_R`` (rad/s) that balance them; ``contacts``
    {inner, outer} -> :class:`StripContact`; ``f_x`` {inner, outer} = F_X (x_p . X)/(mu N); ``iterations``,
    ``residual`` (max of |sum F_X| / (mu N) and |sum M_v| / (mu N D/2))."""

    omega_m: float
    omega_R: float
    contacts: dict
    f_x: dict
    iterations: int
    residual: float
    s0: float


def _longitudinal_curvature(body, P: np.ndarray) -> float:
    """Normal curvature (1/m) of a body of revolution along its circumferential direction at P (Meusnier):
    |n . e_rho| / rho with n the surface normal and e_rho the radial unit vector from the axis."""
    n = body.gradient(P)
    n = n / np.linalg.norm(n)
    d = P - (body.centre if hasattr(body, "centre") else body.origin)
    radial = d - (d @ body.axis) * body.axis
    rho = np.linalg.norm(radial)
    return float(abs(n @ radial) / rho ** 2)


def _hertz(b: BearingGeometry, contact: str, N: float, e_star: float, s0: float, correction: bool) -> dict:
    roller = roller_body(b, Pose())
    ring = ring_body(b, contact)
    sign = -1.0 if contact == "inner" else 1.0
    line0 = b.nominal_centre + s0 * b.e_y
    rho_r = np.sqrt(b.crown_radius ** 2 - s0 ** 2) - (b.crown_radius - 0.5 * b.roller_diameter)
    PR = line0 + sign * rho_r * b.e_z
    Pj = line0 + float(ray_intersection(ring, line0, sign * b.e_z)) * sign * b.e_z
    kx = _longitudinal_curvature(roller, PR) + (1.0 if contact == "inner" else -1.0) * _longitudinal_curvature(ring, Pj)
    rg = b.groove_radius_inner if contact == "inner" else b.groove_radius_outer
    B0 = 0.5 * (1.0 / b.crown_radius - 1.0 / rg)
    Bc = B0
    h = elliptic_contact(N, 1.0 / kx, 1.0 / (2.0 * Bc), e_star)
    if correction:                              # eq 4 with the approach of the corrected contact (2 passes)
        for _ in range(2):
            Bc = B0 + h.approach / (2.0 * (0.5 * (b.crown_radius + rg)) ** 2)
            h = elliptic_contact(N, 1.0 / kx, 1.0 / (2.0 * Bc), e_star)
    return {"a": h.semi_axis_x, "b": h.semi_axis_y, "p0": h.p_max, "approach": h.approach, "Rx": 1.0 / kx,
            "Ry": 1.0 / (2.0 * Bc), "B": B0, "B_corr": Bc}


def strip_contact(b: BearingGeometry, contact: str, normal_load: float, mu: float, e_star: float, omega_m: float,
                  omega_R: float, omega_inner: float, omega_outer: float = 0.0, s0: float = 0.0,
                  n_strips: int = 400, correction: bool = True, hertz: dict | None = None,
                  power: bool = True) -> StripContact:
    """H+C on one contact at given speeds (module docstring); ``hertz`` reuses a :func:`_hertz` result;
    ``power`` False skips the frictional power integrals (zeros; used inside the speed iteration)."""
    hz = _hertz(b, contact, normal_load, e_star, s0, correction) if hertz is None else hertz
    a, bb, p0 = hz["a"], hz["b"], hz["p0"]
    n = int(n_strips)
    dy = 2.0 * bb / n
    edges = -bb + dy * np.arange(n + 1)
    eta = 0.5 * (edges[:-1] + edges[1:])
    dN = 0.75 * normal_load / bb * np.diff(edges - edges ** 3 / (3.0 * bb * bb))
    shape = np.sqrt(1.0 - (eta / bb) ** 2)
    a_s, p_s = a * shape, p0 * shape
    y = s0 + eta
    roller = roller_body(b, Pose())
    ring = ring_body(b, contact)
    sign = -1.0 if contact == "inner" else 1.0
    line = b.nominal_centre + y[:, None] * b.e_y
    rho_r = np.sqrt(b.crown_radius ** 2 - y ** 2) - (b.crown_radius - 0.5 * b.roller_diameter)
    PR = line + sign * rho_r[:, None] * b.e_z
    Pj = line + ray_intersection(ring, line, sign * b.e_z)[:, None] * (sign * b.e_z)
    rate = ring_rate(contact, omega_m, omega_inner, omega_outer)
    vR = roller.velocity(PR, omega_R)
    vj = ring.velocity(Pj, rate)
    wX = vR @ X - vj @ X
    VR, Vj = np.linalg.norm(vR, axis=1), np.linalg.norm(vj, axis=1)
    Vc = 0.5 * (VR + Vj)
    # eq 7 in the paper's sign: positive when the roller's surface runs faster than the raceway's
    xi = (VR - Vj) / Vc
    xis = e_star * np.abs(wX) / Vc / (2.0 * mu * p_s)
    cp = 1.0 - np.minimum(1.0, xis)
    dF = -np.sign(wX) * (1.0 - cp ** 2) * mu * dN
    v_axis = roller.axis
    lever = np.cross(PR - roller.centre, X) @ v_axis                   # moment about the roller axis per unit F_X
    if not power:
        return StripContact(y, dy, a_s, p_s, dN, wX, Vc, xi, np.where(wX != 0, xis, 0.0), cp, dF, dF * lever,
                            np.zeros(n), np.zeros(n), hz, [])
    # Carter traction (eq 9) and slip velocity (eq 10, E4) along each strip: midpoint rule in x'
    xp = -1.0 + (np.arange(CARTER_POINTS) + 0.5) * (2.0 / CARTER_POINTS)
    X2, C2 = xp[None, :], cp[:, None]
    slip_zone = X2 <= 1.0 - 2.0 * C2
    with np.errstate(invalid="ignore", divide="ignore"):
        q = np.sqrt(1.0 - X2 ** 2) - np.where(slip_zone, 0.0, C2 * np.sqrt(np.clip(
            1.0 - ((X2 - (1.0 - C2)) / np.where(C2 > 0, C2, 1.0)) ** 2, 0.0, None)))
        vrel = np.where(slip_zone, (np.abs(wX) / Vc)[:, None] * (1.0 + (C2 - 1.0 + np.sqrt(np.clip(
            (X2 - 1.0 + C2) ** 2 - C2 ** 2, 0.0, None))) / np.where(xis > 0, xis, 1.0)[:, None]), 0.0)
    power_w = (mu * p_s[:, None] * q * vrel * Vc[:, None]).sum(axis=1) * a_s * (2.0 / CARTER_POINTS)
    zero = []
    s = np.sign(wX)
    for k in np.flatnonzero(s[:-1] * s[1:] < 0):
        zero.append(float(y[k] - wX[k] * (y[k + 1] - y[k]) / (wX[k + 1] - wX[k])))
    return StripContact(y, dy, a_s, p_s, dN, wX, Vc, xi, np.where(wX != 0, xis, 0.0), cp, dF, dF * lever,
                        power_w, power_w / Vc, hz, zero)


def strip_bearing(b: BearingGeometry, normal_load: float, mu: float, E: float, nu: float, omega_inner: float,
                  omega_outer: float = 0.0, s0: float = 0.0, n_strips: int = 400, correction: bool = True,
                  tol: float = 1e-10, max_iter: int = 30) -> StripBearingResult:
    """H+C on both raceway contacts with the roller speeds found by Newton (module docstring). ``normal_load``
    N on each contact (N), ``E``, ``nu`` of the (identical) bodies, ring speeds (rad/s), contact centres at
    y = ``s0`` (m). Raises ConvergenceError if the residual stays above ``tol``."""
    if not mu > 0:
        raise InputError("friction.mu", f"{mu:g}; allowed: > 0")
    if not normal_load > 0:
        raise InputError("load.normal", f"{normal_load:g} N; allowed: > 0")
    e_star = E / (2.0 * (1.0 - nu ** 2))
    hz = {c: _hertz(b, c, normal_load, e_star, s0, correction) for c in CONTACTS}
    om0, or0 = nominal_speeds(b, omega_inner, omega_outer)
    scale_F, scale_M = mu * normal_load, mu * normal_load * 0.5 * b.roller_diameter

    def solve(z, power=False):
        om, orr = om0 * (1.0 + z[0]), or0 * (1.0 + z[1])
        res = {c: strip_contact(b, c, normal_load, mu, e_star, om, orr, omega_inner, omega_outer, s0, n_strips,
                                correction, hz[c], power) for c in CONTACTS}
        r = np.array([sum(res[c].force_X for c in CONTACTS) / scale_F, sum(res[c].moment_v for c in CONTACTS) / scale_M])
        return r, res

    z = np.zeros(2)
    r, res = solve(z)
    for it in range(1, max_iter + 1):
        J = np.empty((2, 2))
        for k in range(2):
            dz = np.zeros(2)
            dz[k] = 1e-8
            J[:, k] = (solve(z + dz)[0] - r) / 1e-8
        step = np.linalg.solve(J, -r)
        lam = 1.0
        while True:
            r_new, res_new = solve(z + lam * step)
            if np.abs(r_new).max() < np.abs(r).max() or lam < 1e-4:
                break
            lam *= 0.5
        z, r, res = z + lam * step, r_new, res_new
        if np.abs(r).max() < tol:
            res = solve(z, power=True)[1]
            xp = -1.0 if omega_inner - om0 * (1 + z[0]) > 0 else 1.0     # x_p = x_I = -sign(omega_I - omega_m) X
            return StripBearingResult(om0 * (1 + z[0]), or0 * (1 + z[1]), res,
                                      {c: xp * res[c].force_X / scale_F for c in CONTACTS}, it,
                                      float(np.abs(r).max()), s0)
    raise ConvergenceError("H+C speed iteration (Newton on omega_m, omega_R)", max_iter, float(np.abs(r).max()), tol)
