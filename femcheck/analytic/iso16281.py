"""ISO/TS 16281:2008 slice (lamina) model of roller bearings, multi-row rigid-ring equilibrium with tilt, and the
reference rating life L10r (TS eqs 38-65, as also implemented in the public code ``minzhun/ISO16281``; spec
bearing-load.md §3.5), SI units in and out (the TS constants are in N and mm; converted here).

Roller j, slice k (n_s slices of width L_we/n_s at x_k = (k - n_s/2 + 1/2) L_we/n_s along the roller):

    delta_jk = G_jk . u - c_jk,    q_jk = (c_L/n_s) max(delta_jk, 0)^(10/9),    c_L = 35948 L_we^(8/9) (N, mm)

with u = (delta_x, delta_y, delta_a, theta_x, theta_y) the inner ring's displacement and tilt relative to the outer
ring. The contact normal of row r is n = (cos alpha e_r, s_r sin alpha e_z) (s_r = +-1: which way the row carries
axial load); a point of the inner ring at p = r_p e_r + z e_z moves by delta + theta x p, so
delta_jk = n . (delta + theta x p_jk) and c_jk = (G_r/2) cos alpha + 2 P(x_k) (clearance and the crown drop P
of both contacts). Every slice is one contact of :func:`femcheck.analytic.bearing_load.solve_rigid`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .bearing_laws import ISO16281_C_MM, LINE_EXPONENT, PowerLaw
from .bearing_load import Equilibrium, roller_angles, solve_rigid


def slice_positions(length: float, slices: int) -> np.ndarray:
    """Slice centres x_k (m) along the roller, symmetric about its middle."""
    return (np.arange(slices) - slices / 2 + 0.5) * length / slices


def crown_drop(x: np.ndarray, length: float, diameter: float, tapered: bool = False) -> np.ndarray:
    """ISO/TS 16281 logarithmic profile drop P(x) (m) of the roller (TS eqs 42-44): for L_we <= 2.5 D_we,
    P = k D_we ln(1/(1 - (2x/L_we)^2)) with k = 0.00035 (cylindrical) or 0.00045 (tapered); for longer rollers
    a straight middle of length L_we - 2.5 D_we and the same logarithmic ends over 1.25 D_we each (k = 0.0005)."""
    x = np.abs(np.asarray(x, dtype=float))
    if length <= 2.5 * diameter:
        return _short_k(tapered) * diameter * np.log(1.0 / (1.0 - (2.0 * x / length) ** 2))
    flat = 0.5 * (length - 2.5 * diameter)
    s = np.clip((x - flat) / (1.25 * diameter), 0.0, None)
    return 0.0005 * diameter * np.log(1.0 / (1.0 - s**2))


def _short_k(tapered: bool) -> float:
    """k of the one-arc profile (L_we <= 2.5 D_we), TS eq. 42."""
    return 0.00045 if tapered else 0.00035


def crown_drop_slice_means(length: float, diameter: float, slices: int, tapered: bool = False) -> np.ndarray:
    """:func:`crown_drop` averaged over each of ``slices`` equal slices (m), for the one-arc profile
    (L_we <= 2.5 D_we): int ln(1 - s^2) ds = (1+s) ln(1+s) - (1-s) ln(1-s) - 2 s (s = 2x/L_we), finite at the
    roller's ends where P itself is not."""
    if length > 2.5 * diameter:
        raise ValueError("the slice means are written for L_we <= 2.5 D_we (one logarithmic arc)")
    edges = np.linspace(-1.0, 1.0, slices + 1)

    def prim(s):
        a, c = 1.0 + s, 1.0 - s
        return np.where(a > 0, a * np.log(np.where(a > 0, a, 1.0)), 0.0) \
            - np.where(c > 0, c * np.log(np.where(c > 0, c, 1.0)), 0.0) - 2.0 * s

    return -_short_k(tapered) * diameter * np.diff(prim(edges)) / np.diff(edges)


def slice_law(length: float, slices: int) -> PowerLaw:
    """One slice: q = (c_L/n_s) delta^(10/9), c_L = 35948 L_we^(8/9) (N, mm) = 3.5948e10 L^(8/9) (SI)."""
    return PowerLaw(ISO16281_C_MM * 1e6 * length ** (8.0 / 9.0) / slices, LINE_EXPONENT, "iso16281_slice")


@dataclass(frozen=True)
class Row:
    """One row: ``z`` axial position of the roller middle (m), ``contact_angle`` alpha (rad), ``sign`` s = +-1."""

    z: float = 0.0
    contact_angle: float = 0.0
    sign: int = 1


@dataclass
class SlicedBearing:
    """Solution of :func:`sliced_equilibrium`: ``slice_loads`` q[r, j, k] (N), ``roller_loads`` Q[r, j] (N),
    ``psi`` (rad), the equilibrium (u, iterations, residual), and ``row_radial`` (N): each row's force along the
    radial load line."""

    psi: np.ndarray
    slice_loads: np.ndarray
    roller_loads: np.ndarray
    deflection: np.ndarray
    equilibrium: Equilibrium
    row_radial: np.ndarray
    dofs: tuple[str, ...]


def row_layout(rows: int, spacing: float, arrangement: str, contact_angle: float) -> list[Row]:
    """Rows at z = (r - (rows - 1)/2) ``spacing`` (row 1 first, on the operating side of a mill bearing), contact-angle
    directions s = +, -, +, ... (``arrangement`` "alternate") or all + ("same")."""
    return [Row(float((r - 0.5 * (rows - 1)) * spacing), contact_angle,
                (-1) ** r if arrangement == "alternate" else 1) for r in range(rows)]


def rigid_start(law: PowerLaw, n_dofs: int, radial_load: float, rollers: int, rows: int, slices: int,
                clearance: float, contact_angle: float, drop: np.ndarray) -> np.ndarray:
    """Starting displacement of the rigid-ring Newton: delta_x of a row whose most loaded roller carries about
    5 F_r/(rows Z) (Stribeck's 4.08 rounded up), the other DOFs 0."""
    u0 = np.zeros(n_dofs)
    ca = np.cos(contact_angle)
    qmax_est = 5.0 * radial_load / (rollers * rows)
    u0[0] = (0.5 * clearance * ca + float(law.deflection(qmax_est / slices)) + drop.max()) / ca
    return u0


def row_kinematics(rows: list[Row], psi: np.ndarray, xk: np.ndarray, pitch_radius: float, clearance: float,
                   drop: np.ndarray, axial: bool, tilt: bool) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """(G (rows Z n_s, n_dof), c (rows Z n_s,), dof names) of the module doc: slice (row r, roller j at psi_j,
    slice k at z_r + x_k) has delta = G . u - c with u = (delta_x, delta_y[, delta_a][, theta_x, theta_y]) (``axial``
    and ``tilt`` select the optional DOFs) and c = (G_r/2) cos alpha + ``drop``(x_k); order (row, roller, slice)."""
    dofs = ("delta_x", "delta_y") + (("delta_a",) if axial else ()) + (("theta_x", "theta_y") if tilt else ())
    rollers, slices = len(psi), len(xk)
    G, c = [], []
    cp, sp = np.cos(psi)[:, None], np.sin(psi)[:, None]
    for r in rows:
        ca, sa = np.cos(r.contact_angle), r.sign * np.sin(r.contact_angle)
        z = r.z + xk[None, :]                         # (1, n_s) axial position of each slice
        cols = [ca * cp + 0 * z, ca * sp + 0 * z]
        if axial:
            cols.append(np.full((rollers, slices), sa))
        if tilt:
            cols.append(-ca * z * sp + sa * pitch_radius * sp)
            cols.append(ca * z * cp - sa * pitch_radius * cp)
        G.append(np.stack(cols, axis=-1).reshape(-1, len(dofs)))
        c.append((0.5 * clearance * ca + drop[None, :] + np.zeros((rollers, 1))).ravel())
    return np.vstack(G), np.concatenate(c), dofs


def sliced_equilibrium(rows: list[Row], rollers: int, pitch_radius: float, length: float, diameter: float,
                       clearance: float, slices: int, radial_load: float, axial_load: float = 0.0,
                       load_offset: float = 0.0, load_angle: float = 0.0, tilt: float = 0.0,
                       crown: str = "none", tapered: bool = False) -> SlicedBearing:
    """Rigid-ring equilibrium of a (multi-row) bearing with sliced rollers (module doc).

    The radial load acts along x at axial position ``load_offset`` (m), i.e. with the moment M_y = e F_r.
    Unknowns: (delta_x, delta_y) always; delta_a when a row has a contact angle; (theta_x, theta_y) when there
    are several rows. A single row with ``tilt`` gets a prescribed misalignment theta_y = tilt (the inner ring
    tilted about the axis normal to the load line) instead of a free one.
    """
    psi = roller_angles(rollers, load_angle)
    xk = slice_positions(length, slices)
    drop = 2.0 * crown_drop(xk, length, diameter, tapered) if crown == "iso" else np.zeros(slices)
    angled = any(r.contact_angle != 0 for r in rows)
    multi = len(rows) > 1
    G, c, dofs = row_kinematics(rows, psi, xk, pitch_radius, clearance, drop, axial=angled, tilt=multi)
    if tilt and not multi:                            # prescribed misalignment theta_y = tilt
        ca = np.cos(rows[0].contact_angle)            # delta_jk = ... - x_k tan(theta) cos(psi_j)
        c = c + (ca * np.tan(tilt) * xk[None, :] * np.cos(psi)[:, None]).ravel()
    F = np.zeros(len(dofs))
    F[0] = radial_load
    if angled:
        F[2] = axial_load
    if multi:
        F[4] = load_offset * radial_load
    law = slice_law(length, slices)
    u0 = rigid_start(law, len(dofs), radial_load, rollers, len(rows), slices, clearance, rows[0].contact_angle, drop)
    sol = solve_rigid(G, c, law, F, u0)
    q = sol.q.reshape(len(rows), rollers, slices)
    ca_rows = np.array([np.cos(r.contact_angle) for r in rows])
    row_radial = (q.sum(axis=2) * np.cos(psi)[None, :]).sum(axis=1) * ca_rows
    return SlicedBearing(psi, q, q.sum(axis=2), sol.delta.reshape(q.shape), sol, row_radial, dofs)


def load_rating_factor(gamma: float, lambda_nu: float = 0.83) -> float:
    """f_c of ISO 281 for radial roller bearings, closed form (ISO/TR 1281-1):
    f_c = 207.9 lambda nu gamma^(2/9) (1 - gamma)^(29/27) (1 + gamma)^(-1/4)
          [1 + (1.04 ((1 - gamma)/(1 + gamma))^(143/108))^(9/2)]^(-2/9); gamma = D_we cos alpha / D_pw.
    At gamma = 0.1 this gives 84.3 (ISO 281 Table 7: 84.2)."""
    ratio = ((1.0 - gamma) / (1.0 + gamma)) ** (143.0 / 108.0)
    return float(207.9 * lambda_nu * gamma ** (2.0 / 9.0) * (1.0 - gamma) ** (29.0 / 27.0) * (1.0 + gamma) ** -0.25
                 * (1.0 + (1.04 * ratio) ** 4.5) ** (-2.0 / 9.0))


def dynamic_load_rating(rollers: int, diameter: float, pitch_diameter: float, length: float,
                        contact_angle: float = 0.0, rows: int = 1) -> float:
    """Basic dynamic radial load rating C_r (N) of ISO 281: b_m f_c (i L_we cos alpha)^(7/9) Z^(3/4) D_we^(29/27)
    (N, mm), b_m = 1.1."""
    gamma = diameter * np.cos(contact_angle) / pitch_diameter
    return float(1.1 * load_rating_factor(gamma) * (rows * length * 1e3 * np.cos(contact_angle)) ** (7.0 / 9.0)
                 * rollers**0.75 * (diameter * 1e3) ** (29.0 / 27.0))


def reference_rating_life(slice_loads: np.ndarray, rating: float, diameter: float, pitch_diameter: float,
                          contact_angle: float = 0.0, rows: int = 1) -> float:
    """L10r (million revolutions, inner ring rotating) of ISO/TS 16281 eqs 47-65 from the lamina loads
    q[j, k] (N) of one row (rollers x slices) and the rating C (N):
    Q_ci = C/(0.83 * 0.378 Z cos alpha i^(7/9)) [1 + (1.038 ((1-g)/(1+g))^(143/108))^(9/2)]^(2/9), Q_ce with 0.364
    and exponent -9/2; lamina ratings q_c = Q_c n_s^(-7/9); equivalent lamina loads
    q_kei = (sum_j q_jk^4/Z)^(1/4) (rotating inner ring), q_kee = (sum_j q_jk^4.5/Z)^(1/4.5);
    L10r = [sum_k (q_kei/q_ci)^(9/2) + (q_kee/q_ce)^(9/2)]^(-8/9)."""
    q = np.asarray(slice_loads, dtype=float)
    z, ns = q.shape
    g = diameter * np.cos(contact_angle) / pitch_diameter
    ratio = ((1.0 - g) / (1.0 + g)) ** (143.0 / 108.0)
    base = rating / (0.83 * z * np.cos(contact_angle) * rows ** (7.0 / 9.0))
    qci = base / 0.378 * (1.0 + (1.038 * ratio) ** 4.5) ** (2.0 / 9.0) * ns ** (-7.0 / 9.0)
    qce = base / 0.364 * (1.0 + (1.038 * ratio) ** -4.5) ** (2.0 / 9.0) * ns ** (-7.0 / 9.0)
    qkei = (np.sum(q**4, axis=0) / z) ** 0.25
    qkee = (np.sum(q**4.5, axis=0) / z) ** (1.0 / 4.5)
    total = float(np.sum((qkei / qci) ** 4.5 + (qkee / qce) ** 4.5))
    return float(total ** (-8.0 / 9.0)) if total > 0 else float("inf")
