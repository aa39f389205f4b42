"""The frictional FE model of the srb-rolling kind (shared helper, not a kind; spec srb-rolling §8.2 item 3): both
contacts of the roller solved with FE compliances (:mod:`femcheck.fem.srb_rolling`: the whole roller and two ring
segments, the FE side's own Coulomb solver) at the CECT equilibrium's pose and speeds.

The CECT state lives in the bearing frame B (:mod:`femcheck.geometry.srb_bearing`); the FE model in the reference
roller frame {x, y, z} with origin C0 (:mod:`femcheck.fem.srb_rolling`): a point P of B is Q (P - C0) there, Q the
rows e_x, e_y, e_z. The roller's centre, axis and the displaced inner ring are carried over exactly; the gaps and
rigid slips are recomputed on the FE's own grids (a common dx and ds for both contacts, windows centred on the
CECT pressure centres) by :mod:`femcheck.fem.rolling_geometry`. Each contact is held at N by its own approach
unknown (the FE compliance differs from the half-space's, so the CECT approach would not carry N); tilt, skew and
the axial offset are the CECT's; the speeds (omega_m, omega_R) are re-balanced so that the FE contacts roll freely
(rolling-direction force and moment about the roller axis zero; at the CECT speeds the FE contacts are left with a
net creep force of order 0.1 mu N). Not a full FE equilibrium: the lateral, radial and tilt/skew equations are not
re-solved with the FE tables; their residual at the CECT pose is reported.

The rigid slip and the gap of the inner contact are taken on the displaced inner ring's groove (the grid moved
with the ring by the CECT's delta along e_z, 25.3 um at Table 2's mu = 0.1), the CECT's contact surface; the FE
compliances stay on the meshes' reference surfaces. The roller spins at 227 rad/s, so its velocity changes by
omega_R |Delta| along the normal: on the undisplaced groove the inner rigid slip was shifted by 2.87e-3 V
(6.4e-3 m/s, uniform over the patch), the inner contact rolled freely at a creepage 3e-3 lower than the CECT's,
and the FE cage speed came out 1.5e-3 below its kinematic value (the CECT's: +1.0e-5).
"""
from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from ..cect.roller_equilibrium import EquilibriumResult
from ..errors import ConvergenceError
from ..fem import srb_rolling as fe
from ..fem.contact_grid import ContactInput
from ..fem.rolling_compliance import MeshSettings
from ..fem.rolling_contact import approach_unknown
from ..fem.rolling_geometry import Crowned, Grooved, gap, kinematics
from ..geometry import srb_bearing as sb
from . import _srb_rolling_out as out


def cect_pose(r: EquilibriumResult) -> dict[str, Any]:
    """What the FE takes from a CECT equilibrium, as plain numbers (SI, bearing frame B): the state ``x``
    (d_Y, d_Z, beta, gamma, omega_m, omega_R), the roller centre ``centre``, the inner ring's displacement
    ``delta`` along e_z, the pressure centres ``s_centre`` per contact (m along the profile) and the inertia
    force (N) and moment (N m). A stored FE reference records it (:func:`femcheck.replay.derived`): it is an
    input of the FE, determined by the CECT solve only to that solve's tolerance."""
    s = r.state
    return {"x": [float(v) for v in r.x], "centre": s.centre.tolist(), "delta": float(s.delta),
            "s_centre": {c: float(s.contacts[c].result.pressure_centre) for c in sb.CONTACTS},
            "inertia_force": s.inertia_force.tolist(), "inertia_moment": s.inertia_moment.tolist()}


def pose_grids(p: dict[str, Any], cp: dict[str, Any], nx: int, ns: int, half_x: float = 1.35) -> dict:
    """The FE's contact grids at the CECT pose ``cp``: nx x ns cells per contact over x in +-half_x a_H (the
    larger contact's), windows on the CECT pressure centres that stay on the roller (the FE meshes the roller's
    length only), on the common cell lattice of :func:`femcheck.fem.srb_rolling.grids`; in the FE's reference
    frame (the inner grid not yet moved with its ring)."""
    N = float(p["load.normal"])
    centres = {c: float(cp["s_centre"][c]) for c in sb.CONTACTS}
    hz = fe.hertz_estimates(p, N)
    b_max = max(h.semi_axis_y for h in hz.values())
    room = 0.5 * fe.ROLLER_LENGTH * ns / (ns + 1) - max(abs(sc) for sc in centres.values())
    return fe.grids(p, nx, ns, N, half_x=half_x, half_s=min(1.3, 0.99 * room / b_max), s_centre=centres)


def at_cect_pose(p: dict[str, Any], cp: dict[str, Any], nx: int, ns: int, mesh: MeshSettings,
                 progress=None, half_x: float = 1.35, compliance=None) -> dict[str, Any]:
    """FE rolling at the CECT pose ``cp`` (:func:`cect_pose`; module docstring) on the grids of
    :func:`pose_grids`. ``compliance``: grids -> :class:`femcheck.fem.rolling_contact.RelativeCompliance`
    (default: the FE tables of :func:`femcheck.fem.srb_rolling.compliance` with ``mesh``; e.g. the split
    half-space + FE-correction tables of :mod:`femcheck.fem.compliance_split`). Returns {"quantities",
    "stats", "solution", "tables"}; stats["dx"] is the cell length (m)."""
    b = sb.BearingGeometry.from_params(p)
    mu, N = float(p["friction.mu"]), float(p["load.normal"])
    Q = np.stack([b.e_x, b.e_y, b.e_z])
    x = np.asarray(cp["x"], dtype=float)
    pose = sb.Pose(*(float(v) for v in x[:4]))
    C = Q @ (np.asarray(cp["centre"], dtype=float) - b.nominal_centre)
    v = Q @ sb.roller_frame(b, pose)[1]
    shift = Q @ (float(cp["delta"]) * b.e_z)
    geo = fe.geometry(p)
    roller = Crowned(C, v, geo["r"], geo["R"])
    rings = {"inner": Grooved(geo["inner"]["G"] + shift, geo["inner"]["rg"], geo["O"] + shift, geo["Y"]),
             "outer": Grooved(geo["outer"]["G"], geo["outer"]["rg"], geo["O"], geo["Y"])}
    om, orr = float(x[4]), float(x[5])
    centres = {c: float(cp["s_centre"][c]) for c in sb.CONTACTS}
    hz = fe.hertz_estimates(p, N)
    grids = pose_grids(p, cp, nx, ns, half_x)
    if progress:
        progress(f"fem: compliances of the roller and both ring segments ({nx} x {ns} cells)")
    tables = (fe.compliance(p, grids, mesh, progress=progress) if compliance is None else compliance(grids))
    # the contact surfaces where the bodies are (module docstring): the inner grid moved with its ring
    grids = {c: dataclasses.replace(g, centre=g.centre + shift) if c == "inner" else g for c, g in grids.items()}
    gaps = {c: gap(g, roller, rings[c]) for c, g in grids.items()}
    extras = [approach_unknown(c, c, g, g.normal(centres[c]), N, hz[c].approach) for c, g in grids.items()]

    def solve(speeds, warm=None):
        inputs = {}
        for c, g in grids.items():
            kin = kinematics(g, roller, speeds[1], rings[c], rates_of(speeds[0])[c], s_ref=centres[c])
            inputs[c] = ContactInput(g, gaps[c], kin.slip, kin.speed, kin.kappa)
        sol = fe.solve_contacts(tables, inputs, mu, extras, centre=C, warm=warm)
        F = sum(res.force for res in sol.contacts.values())
        M = sum(res.moment for res in sol.contacts.values())
        return np.array([F @ sb.X / (mu * N), M @ v / (mu * N * geo["r"])]), sol

    def rates_of(om):
        return {"inner": float(p["kinematics.inner_ring_speed"]) - om,
                "outer": float(p["kinematics.outer_ring_speed"]) - om}

    # free rolling in the FE: (omega_m, omega_R) such that the rolling-direction force and the moment about the
    # roller axis vanish (the CECT speeds leave the FE contacts with a net creep force: its compliance differs)
    if progress:
        progress("fem: two-contact steady rolling on the condensed system, speeds balanced by Newton")
    z = np.array([om, orr])
    res0, sol = solve(z)
    speed_iterations, h = 0, 1e-7 * np.abs(z)
    for speed_iterations in range(1, 9):
        if np.abs(res0).max() < 1e-6:
            break
        J = np.empty((2, 2))
        for k in range(2):
            dz = np.zeros(2)
            dz[k] = h[k]
            J[:, k] = (solve(z + dz, sol)[0] - res0) / h[k]
        dz = np.linalg.solve(J, -res0)
        # damped: the contacts saturate (full slip) a few mu N away from free rolling, where the Jacobian vanishes;
        # halve the step until the residual falls
        for _ in range(12):
            res1, sol1 = solve(z + dz, sol)
            if np.abs(res1).max() < np.abs(res0).max():
                break
            dz = 0.5 * dz
        z, res0, sol = z + dz, res1, sol1
    if np.abs(res0).max() >= 1e-6:
        raise ConvergenceError("FE free rolling (omega_m, omega_R)", speed_iterations, float(np.abs(res0).max()),
                               1e-6)
    xp = -np.sign(float(p["kinematics.inner_ring_speed"]) - float(p["kinematics.outer_ring_speed"])) * sb.X
    q: dict[str, float] = {}
    F, M = np.zeros(3), np.zeros(3)
    speeds = out.speeds(b, float(p["kinematics.inner_ring_speed"]), float(p["kinematics.outer_ring_speed"]),
                        float(z[0]), float(z[1]))
    q["omega_m_deviation"] = speeds["omega_m"] / speeds["omega_m_kinematic"] - 1.0
    q["omega_R_deviation"] = speeds["omega_R"] / speeds["omega_R_kinematic"] - 1.0
    for c, res in sol.contacts.items():
        q[f"f_x_{c}"] = float(res.force @ xp / (mu * N))
        q[f"f_lat_{c}"] = float(res.creep_force_s / (mu * N))
        q[f"friction_power_{c}"] = float(res.friction_power)
        q[f"adhesion_fraction_{c}"] = float(res.adhesion_fraction)
        F, M = F + res.force, M + res.moment
    q["f_lat_sum"] = q["f_lat_inner"] + q["f_lat_outer"]
    F = F + Q @ np.asarray(cp["inertia_force"], dtype=float)
    M = M + Q @ np.asarray(cp["inertia_moment"], dtype=float)
    g0 = grids["inner"]
    stats = {"iterations": sol.iterations, "residual": sol.residual, "grid": [nx, ns], "dx": g0.dx, "ds": g0.ds,
             "speed_iterations": speed_iterations, "speed_residual": float(np.abs(res0).max()),
             "omega_m": float(z[0]), "omega_R": float(z[1]), "omega_m_cect": om, "omega_R_cect": orr, "speeds": speeds,
             "n_dofs": tables.stats.get("n_dofs"), "approaches": {k: float(th) for k, th in sol.theta.items()},
             "equilibrium_residual_force_N": F.tolist(), "equilibrium_residual_moment_Nm": M.tolist(),
             "normal_forces": {c: float(res.normal_force) for c, res in sol.contacts.items()},
             "note": "FE at the CECT pose (tilt, skew, d_y, speeds) with each contact held at N; no FE equilibrium"}
    return {"quantities": q, "stats": stats, "solution": sol, "tables": tables}
