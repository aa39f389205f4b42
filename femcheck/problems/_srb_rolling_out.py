"""Outputs of the srb-rolling kind (shared helper, not a kind): seed 000 Table 2 as data, and the Table 2
quantities, consistency checks and report fields of a roller equilibrium (spec srb-rolling §3, §7.1, §10.1).

Conventions (spec §3 "Reporting convention", E10, E11): f = F/(mu N) with N the nominal load; f_x,j = F_j . x_p
with x_p = x_I the direction in which the roller moves relative to the inner ring; f_lat,j = sum p_s dA / (mu N),
positive towards the bearing mid-plane; d_y = (C - C0).e_y (the ring approach acts along e_z, so the frictionless
equilibrium is the nominal pose); tilt beta as it is; skew reported as gamma_p = -gamma. The speeds are graded by
their deviation from the rigid-kinematics speeds of seed 000 eqs 2-3 (``omega_m_deviation`` = omega_m / omega_m,o
- 1, ``omega_R_deviation`` likewise): the creep that the contacts need to carry their forces, 1e-5 and 5e-3 here,
which a band on the raw speed cannot resolve; the raw speeds are in the stats.
"""
from __future__ import annotations

import numpy as np

from ..cect.roller_equilibrium import EquilibriumResult
from ..cect.roller_state import RollerProblem, RollerState
from ..geometry import srb_bearing as sb

# seed 000 Table 2 (N = 5.5 kN): columns full slip, CECT, FEM per mu; d_y in m (None: not given)
TABLE_2 = {
    0.1: {"full_slip": {"f_x_inner": 4.36e-3, "f_x_outer": 7.31e-3, "f_lat_inner": -5.20e-3, "f_lat_outer": 5.63e-3,
                        "f_lat_sum": 4.54e-4},
          "cect": {"f_x_inner": -4.96e-3, "f_x_outer": 4.99e-3, "f_lat_inner": 2.23e-2, "f_lat_outer": 2.87e-2,
                   "f_lat_sum": 5.09e-2, "d_y": 6.3e-6},
          "fem": {"f_x_inner": -4.8e-3, "f_x_outer": 4.8e-3, "f_lat_inner": 5.5e-4, "f_lat_outer": 5.7e-2,
                  "f_lat_sum": 5.8e-2, "d_y": 7.2e-6}},
    0.3: {"full_slip": {"f_x_inner": 2.58e-2, "f_x_outer": -1.28e-2, "f_lat_inner": -1.08e-2, "f_lat_outer": 1.20e-2,
                        "f_lat_sum": 1.17e-3},
          "cect": {"f_x_inner": -5.33e-3, "f_x_outer": 5.33e-3, "f_lat_inner": 2.34e-2, "f_lat_outer": 3.22e-2,
                   "f_lat_sum": 5.55e-2, "d_y": 20.4e-6},
          "fem": {"f_x_inner": -5.2e-3, "f_x_outer": 5.2e-3, "f_lat_inner": 1.3e-2, "f_lat_outer": 5.2e-2,
                  "f_lat_sum": 6.5e-2, "d_y": 23.5e-6}},
}
TABLE_2_LOAD = 5500.0


def table_2(mu: float, load: float) -> dict | None:
    """Table 2's columns for (mu, N) when the paper gives them (mu 0.1 or 0.3 at 5.5 kN), else None."""
    if not np.isclose(load, TABLE_2_LOAD, rtol=1e-9):
        return None
    for m, cols in TABLE_2.items():
        if np.isclose(mu, m, rtol=1e-9):
            return cols
    return None


def x_p(problem: RollerProblem) -> np.ndarray:
    """x_p = x_I = -sign(omega_I - omega_m) X (E10); omega_m lies between the ring speeds."""
    return -np.sign(problem.omega_inner - problem.omega_outer) * sb.X


def drive_power(problem: RollerProblem, state: RollerState) -> float:
    """Power the rings put into the roller (W, inertial frame): sum over the contacts of t . (omega_j Y x (P - O_j))
    dA = omega_j Y . sum (P - O_j) x t dA, t the traction on the roller, O_j on ring j's axis (the displaced inner
    ring centre; O for the outer ring)."""
    cs = state.contacts["inner"]
    t = (cs.result.px[..., None] * cs.inputs.grid.surface.ex + cs.result.ps[..., None] * cs.inputs.grid.tangents[None]
          + cs.result.pressure[..., None] * cs.inputs.grid.normals[None])
    O = state.delta * problem.approach_vector
    T = float(np.cross(cs.inputs.grid.points - O, t).sum(axis=(0, 1)) @ sb.Y * cs.result.cell_area)
    return T * problem.omega_inner + _outer_power(problem, state)


def _outer_power(problem: RollerProblem, state: RollerState) -> float:
    if problem.omega_outer == 0.0:
        return 0.0
    cs = state.contacts["outer"]
    t = (cs.result.px[..., None] * cs.inputs.grid.surface.ex + cs.result.ps[..., None] * cs.inputs.grid.tangents[None]
          + cs.result.pressure[..., None] * cs.inputs.grid.normals[None])
    T = float(np.cross(cs.inputs.grid.points, t).sum(axis=(0, 1)) @ sb.Y * cs.result.cell_area)
    return T * problem.omega_outer


def speed_deviations(problem: RollerProblem, omega_m: float, omega_R: float) -> dict[str, float]:
    """omega_m / omega_m,o - 1 and omega_R / omega_R,o - 1 with (omega_m,o, omega_R,o) the speeds of rolling
    without slip at the nominal points (seed 000 eqs 2-3, :func:`femcheck.geometry.srb_bearing.nominal_speeds`)."""
    s = speeds(problem.bearing, problem.omega_inner, problem.omega_outer, omega_m, omega_R)
    return {"omega_m_deviation": s["omega_m"] / s["omega_m_kinematic"] - 1.0,
            "omega_R_deviation": s["omega_R"] / s["omega_R_kinematic"] - 1.0}


def speeds(b: sb.BearingGeometry, omega_inner: float, omega_outer: float, omega_m: float,
           omega_R: float) -> dict[str, float]:
    """The raw speeds (rad/s) and the kinematic ones they deviate from (the stats' ``speeds``)."""
    om0, or0 = sb.nominal_speeds(b, omega_inner, omega_outer)
    return {"omega_m": float(omega_m), "omega_R": float(omega_R), "omega_m_kinematic": om0,
            "omega_R_kinematic": or0}


def lateral_stiffness(problem: RollerProblem) -> float:
    """N (1/(r_I - R) + 1/(r_E - R)) (N/m): the lateral stiffness of the two conforming pairs (spec §3)."""
    b = problem.bearing
    return problem.load * (1.0 / (b.groove_radius_inner - b.crown_radius)
                           + 1.0 / (b.groove_radius_outer - b.crown_radius))


def quantities(problem: RollerProblem, r: EquilibriumResult) -> dict[str, float]:
    """The Table 2 quantities of a converged equilibrium (module docstring)."""
    s = r.state
    b = problem.bearing
    muN = problem.mu * problem.load
    xp = x_p(problem)
    q: dict[str, float] = {}
    for c in sb.CONTACTS:
        cs = s.contacts[c]
        q[f"f_x_{c}"] = float(cs.force @ xp / muN)
        q[f"f_lat_{c}"] = cs.result.force_s / muN
        q[f"friction_power_{c}"] = cs.result.frictional_power
        q[f"adhesion_fraction_{c}"] = cs.result.adhesion_fraction
    q["f_lat_sum"] = q["f_lat_inner"] + q["f_lat_outer"]
    q["d_y"] = float((s.centre - b.nominal_centre) @ b.e_y)
    q["tilt"] = float(r.x[2])
    q["skew"] = float(-r.x[3])
    q.update(speed_deviations(problem, float(r.x[4]), float(r.x[5])))
    return q


def checks(problem: RollerProblem, r: EquilibriumResult, q: dict[str, float]) -> dict[str, float]:
    """Consistency numbers (spec §10.1 item 10): ``lateral_relation`` (sum F_lat + F_c sin a) / (k_lat d_y
    (1 - 0.015)) - 1; ``tilt_relation`` beta / beta_rigid - 1
    (the tilt of spec §3's rigid-ring relation); ``fx_sum`` |f_x,i + f_x,e|; ``energy_balance`` P_fric / P_drive - 1; the largest scaled
    residual; the inner normal force error."""
    b = problem.bearing
    s = r.state
    Fc = float(np.linalg.norm(s.inertia_force))
    lhs = q["f_lat_sum"] * problem.mu * problem.load + Fc * np.sin(b.contact_angle)
    rhs = lateral_stiffness(problem) * q["d_y"] * (1.0 - 0.015)
    P = q["friction_power_inner"] + q["friction_power_outer"]
    # tilt of rigid rings (spec §3): beta = -((1/(r_E - R) - 1/(r_I - R)) d_y + (D/2)(F_lat,E - F_lat,I)/((R - D/2) N))
    #                                       / ((R - D/2)(1/(r_E - R) + 1/(r_I - R)) + 2)
    R, D = b.crown_radius, b.roller_diameter
    ki, ke = 1.0 / (b.groove_radius_inner - R), 1.0 / (b.groove_radius_outer - R)
    dF = (q["f_lat_outer"] - q["f_lat_inner"]) * problem.mu * problem.load
    beta = -((ke - ki) * q["d_y"] + 0.5 * D * dF / ((R - 0.5 * D) * problem.load)) / ((R - 0.5 * D) * (ke + ki) + 2.0)
    return {"lateral_relation": float(lhs / rhs - 1.0), "tilt_relation": float(q["tilt"] / beta - 1.0), "fx_sum": abs(q["f_x_inner"] + q["f_x_outer"]),
            "energy_balance": float(P / drive_power(problem, s) - 1.0),
            "scaled_residual_max": float(np.max(np.abs(r.scaled_residual))),
            "inner_load_error": float(s.inner_load / problem.load - 1.0)}


def fields(state: RollerState, prefix: str = "") -> dict[str, np.ndarray]:
    """Lateral distributions N*(s), F_x*(s), F_s*(s) and the pressure / adhesion / power maps of both contacts."""
    out = {}
    for c in sb.CONTACTS:
        res, dg = state.contacts[c].result, state.contacts[c].inputs.grid
        out.update({f"{prefix}{c}_s": dg.s, f"{prefix}{c}_x": dg.x, f"{prefix}{c}_lateral_normal": res.lateral_normal,
                    f"{prefix}{c}_lateral_fx": res.lateral_fx, f"{prefix}{c}_lateral_fs": res.lateral_fs,
                    f"{prefix}{c}_pressure_map": res.pressure, f"{prefix}{c}_adhesion_map": res.adhesion.astype(float),
                    f"{prefix}{c}_contact_map": res.contact.astype(float),
                    f"{prefix}{c}_power_density_map": res.power_density})
    return out
