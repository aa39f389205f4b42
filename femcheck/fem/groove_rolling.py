"""FE reference (``fem``) of the groove-rolling scene: a crowned body of revolution rolling freely in a grooved
ring (or on a grooved straight rail) with Coulomb friction, one conformal contact.

Geometry (FE roller frame, m): crowned body about the y axis through the origin, rolling radius r0 at its crown
apex, crown radius R_c; the ring touches it at (0, 0, -r0); the groove circle (radius r_g > R_c) has its centre
at (0, 0, r_g - r0); the ring's longitudinal curvature kappa (``geometry.ring_curvature``, 1/m) puts the ring
axis (parallel to y) at (0, 0, -r0 - 1/kappa): kappa > 0 convex along x (an inner ring), < 0 concave (an outer
ring, |1/kappa| > 2 r0), 0 a straight rail. Relative radii at the nominal point: 1/Rx = 1/r0 + kappa,
1/Ry = 1/R_c - 1/r_g; ``load.normal`` N along the nominal normal +z (load control: the approach is an unknown).

Kinematics: the contact is stationary, the ring's surface moves at -V e_x at the reference point
(``kinematics.speed`` V), the crowned body turns at omega = (V/r0)(1 + theta) about +y; free rolling: theta is the
unknown that makes the longitudinal force zero (:func:`femcheck.fem.rolling_contact.creepage_unknown` with the
exact slip derivative). The rigid slip, V_ref and kappa(s) come from :mod:`femcheck.fem.rolling_geometry`.

FE model: whole crowned body (length ``numerics.fem_body_length`` x b_H, free: inertia relief, mean axes) and a
ring segment (clamped bottom and far end), P2 layered meshes aligned with the influence cells
(:mod:`femcheck.fem.rolling_compliance`), steady rolling solved on the condensed tables by the FE side's
semi-smooth Newton (:mod:`femcheck.solvers.coulomb3d`). Levels refine grid and mesh together (cells and the
section's element size by ``numerics.fem_ratio``); certificates by :func:`femcheck.solvers.convergence.certify`.

Quantities (SI): ``p_max`` (Pa, largest cell pressure), ``contact_half_length_s`` (m, half the distance between
the power-law edges of the lateral load distribution, :func:`femcheck.cect.groove_contact.lateral_extent`, the
estimator every model of the scene goes through), ``angle_span`` (rad, 2 half-length / r_g),
``adhesion_fraction`` (adhesion cells / contact cells), ``creepage_x`` (free-rolling longitudinal creepage
w_x / V_ref at the reference point), ``spin_moment`` (N m, about the nominal normal through the reference point),
``friction_power`` (W), ``body_approach`` (m, the approach of the crowned body's axis towards the ring
segment's clamped base: it holds the compliance of the finite bodies, so it is not the half-space models'
``approach``, whose datum lies at infinite depth, and is reported, not compared).
"""
from __future__ import annotations

import time
from typing import Any

import numpy as np
from scipy.optimize import brentq

from ..analytic import hertz
from ..cect.groove_contact import FREE_ROLLING_TOL, SPIN_NOISE, lateral_extent
from ..errors import ConvergenceError, InputError
from ..materials import Elastic, effective_modulus
from ..meshes.layered_bodies import MIN_CROWN_RATIO
from ..result import ModelResult
from ..scene import Key
from ..solvers.convergence import certify
from .contact_grid import ContactGrid, ContactInput, centred_cells, refined_count
from .rolling_compliance import MeshSettings, RingBody, RollerBody, fe_compliance
from .rolling_contact import approach_unknown, creepage_unknown, solve_rolling
from .rolling_geometry import Crowned, Grooved, gap, kinematics

QUANTITIES = ("body_approach", "p_max", "contact_half_length_s", "angle_span", "adhesion_fraction", "creepage_x",
              "spin_moment", "friction_power")

FEM_SCHEMA: dict[str, Key] = {
    "numerics.fem_levels": Key("int", "-", "FE levels (grid and mesh refined together)", lo=1, hi=4,
                               lo_closed=True, hi_closed=True),
    "numerics.fem_nx": Key("int", "-", "cells along x on the coarsest level", lo=5, hi=61, lo_closed=True,
                           hi_closed=True),
    "numerics.fem_ns": Key("int", "-", "cells along s on the coarsest level", lo=5, hi=121, lo_closed=True,
                           hi_closed=True),
    "numerics.fem_ratio": Key("float", "-", "refinement ratio between levels", lo=1.1, hi=2.0, lo_closed=True,
                              hi_closed=True),
    "numerics.fem_half_x": Key("float", "a_H", "grid half-width along x", lo=1.1, hi=3.0, lo_closed=True,
                               hi_closed=True),
    "numerics.fem_half_s": Key("float", "b_H", "grid half-width along s", lo=1.05, hi=2.0, lo_closed=True,
                               hi_closed=True),
    "numerics.fem_h_contact": Key("float", "dx", "section element size at the contact line", lo=0.2, hi=2.0,
                                  lo_closed=True, hi_closed=True),
    "numerics.fem_grading": Key("float", "-", "section element growth per unit distance (coarsest level)",
                                lo=0.05, hi=1.0, lo_closed=True, hi_closed=True),
    "numerics.fem_body_length": Key("float", "b_H", "length of the crowned body", lo=2.2, hi=20.0,
                                    lo_closed=True, hi_closed=True),
    "numerics.fem_ring_length": Key("float", "b_H", "ring segment half-length along x", lo=0.1, hi=5.0,
                                    lo_closed=True, hi_closed=True),
    "numerics.fem_ring_depth": Key("float", "b_H", "ring material below the groove", lo=0.1, hi=5.0,
                                   lo_closed=True, hi_closed=True),
    "numerics.fem_ring_width": Key("float", "b_H", "ring segment half-extent along the groove", lo=1.1, hi=5.0,
                                   lo_closed=True, hi_closed=True),
    "numerics.fem_tol": Key("float", "-", "residual tolerance of the frictional semi-smooth Newton", lo=0.0,
                            hi=1e-3, hi_closed=True),
}
FEM_DEFAULTS: dict[str, Any] = {
    "numerics.fem_levels": 3,
    "numerics.fem_nx": 11,
    "numerics.fem_ns": 21,
    "numerics.fem_ratio": 1.4142135623730951,
    "numerics.fem_half_x": 1.35,
    "numerics.fem_half_s": 1.25,
    "numerics.fem_h_contact": 0.7,
    "numerics.fem_grading": 0.4,
    "numerics.fem_body_length": 3.0,
    "numerics.fem_ring_length": 0.5,
    "numerics.fem_ring_depth": 1.0,
    "numerics.fem_ring_width": 1.5,
    "numerics.fem_tol": 1e-9,
}


def _params(scene) -> dict[str, Any]:
    p = dict(getattr(scene, "params", scene))
    return {**FEM_DEFAULTS, **p}


def setup(p: dict[str, Any]) -> dict[str, Any]:
    """Bodies, Hertz estimate and frames from the scene keys (see the module docstring); raises InputError."""
    r0, Rc = float(p["geometry.rolling_radius"]), float(p["geometry.crown_radius"])
    rg, kap = float(p["geometry.groove_radius"]), float(p["geometry.ring_curvature"])
    if not rg > Rc:
        raise InputError("geometry.groove_radius", f"{rg:g} m must exceed the crown radius {Rc:g} m; "
                         f"allowed: ({Rc:g}, inf) m")
    if kap < 0 and not 1.0 / -kap > 2.0 * r0:
        raise InputError("geometry.ring_curvature", f"{kap:g} 1/m: a concave ring must enclose the body; "
                         f"allowed: > {-1.0 / (2.0 * r0):g} 1/m")
    if float(p["friction.mu"]) <= 0:
        raise InputError("friction.mu", f"{p['friction.mu']:g}; allowed: (0, 10]")
    m1 = Elastic(float(p["materials.body1.E"]), float(p["materials.body1.nu"]))
    m2 = Elastic(float(p["materials.body2.E"]), float(p["materials.body2.nu"]))
    Rx = 1.0 / (1.0 / r0 + kap)
    Ry = 1.0 / (1.0 / Rc - 1.0 / rg)
    hz = hertz.elliptic_contact(float(p["load.normal"]), Rx, Ry, effective_modulus(m1, m2))
    return {"r0": r0, "Rc": Rc, "rg": rg, "kappa": kap, "m1": m1, "m2": m2, "hertz": hz, "Rx": Rx, "Ry": Ry}


def _grid(g: dict, p: dict, level: int) -> ContactGrid:
    """Cells of ``level``: odd counts (:func:`femcheck.fem.contact_grid.refined_count`), dx and ds exactly the
    coarsest level's / ratio^level, the window widened by the rounding."""
    a, b = g["hertz"].semi_axis_x, g["hertz"].semi_axis_y
    f = p["numerics.fem_ratio"] ** level
    nx0, ns0 = p["numerics.fem_nx"], p["numerics.fem_ns"]
    nx, ns = refined_count(nx0, f), refined_count(ns0, f)
    G = np.array([0.0, 0.0, g["rg"] - g["r0"]])
    return ContactGrid(G, g["rg"], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0],
                       centred_cells(p["numerics.fem_half_x"] * a * nx / (nx0 * f), nx),
                       centred_cells(p["numerics.fem_half_s"] * b * ns / (ns0 * f), ns), "groove")


def _free_rolling(comp, inp: ContactInput, dslip: np.ndarray, mu: float, load_extra, tol: float):
    """Steady free rolling: (solution, theta). First the coupled semi-smooth Newton with theta as an unknown
    (:func:`femcheck.fem.rolling_contact.creepage_unknown`). On wide conformal patches (groove/crown <= 1.01 on
    the coarse levels) nearly every cell slides, the longitudinal force hardly depends on theta and that Newton
    step throws theta far away; then theta is found by Brent's method on F_x(theta) / (mu N) (monotone), each
    evaluation a load-controlled solve at a fixed body speed, bracketed from theta = 0 by steps growing 4-fold.
    Same equations, a safer path; free rolling to |F_x| < 1e-9 mu N (Newton) or 1e-7 mu N (Brent)."""
    free = creepage_unknown("theta", "groove", inp.grid, dslip, 0.0)
    try:
        sol = solve_rolling(comp, {"groove": inp}, mu, [load_extra, free], tol=tol)
        return sol, sol.theta["theta"]
    except ConvergenceError:
        pass
    N = load_extra.target
    cache: dict[float, Any] = {}

    def fx(theta: float) -> float:
        if theta not in cache:
            shifted = ContactInput(inp.grid, inp.gap, inp.slip + theta * dslip * inp.speed, inp.speed, inp.kappa)
            warm = cache[min(cache, key=lambda t: abs(t - theta))] if cache else None
            cache[theta] = solve_rolling(comp, {"groove": shifted}, mu, [load_extra], tol=tol, warm=warm)
        return cache[theta].contacts["groove"].creep_force_x / (mu * N)

    f0, step = fx(0.0), 1e-3
    direction = -np.sign(f0) * np.sign(fx(1e-6) - f0)         # towards F_x = 0
    lo, hi = 0.0, direction * step
    while np.sign(fx(hi)) == np.sign(f0):
        if abs(hi) > 1.0:
            raise ConvergenceError("FE free rolling (bracket on the body speed)", len(cache), abs(fx(hi)), 0.0,
                                   "no sign change of F_x within |theta| <= 1")
        lo, hi = hi, 4.0 * hi
    theta = brentq(fx, min(lo, hi), max(lo, hi), xtol=1e-14, rtol=4 * np.finfo(float).eps, maxiter=100)
    residual = abs(fx(theta))
    sol = cache[theta]
    # each evaluation is converged to the contact tolerance, so F_x(theta) carries noise of that order: the root
    # is accepted at |F_x| < 1e-7 mu N (the conformal exact theory's free-rolling tolerance)
    if residual > FREE_ROLLING_TOL:
        raise ConvergenceError("FE free rolling (Brent on the body speed)", len(cache), residual, FREE_ROLLING_TOL)
    sol.theta["theta"] = float(theta)
    sol.stats["free_rolling"] = f"Brent on the body speed, {len(cache)} contact solves"
    return sol, float(theta)


def _ring_axis(g: dict[str, Any], grid: ContactGrid) -> tuple[tuple, tuple | None, tuple | None]:
    """The groove centre (the grid's profile centre), a point of the ring's axis and its direction (m, the body
    frame; None for a straight rail, kappa = 0): the ring's axis lies 1/kappa beyond the body's axis."""
    r0, kap = g["r0"], g["kappa"]
    G = tuple(float(v) for v in grid.centre)
    if kap == 0:
        return G, None, None
    return G, (0.0, 0.0, -r0 - 1.0 / kap), (0.0, 1.0, 0.0)


def compliance(p: dict[str, Any], grid: ContactGrid, level: int, progress=None, h_contact: float | None = None,
               layers_per_cell: int = 1):
    """The FE relative compliance of the crowned body and the ring segment (module docstring) on ``grid``, meshed
    as FE level ``level`` (the section's grading divided by ``numerics.fem_ratio`` per level) with ``h_contact``
    x dx at the contact line (None: ``numerics.fem_h_contact``) and ``layers_per_cell`` element layers per cell
    along s; raises InputError when the body is longer than its mesh can follow."""
    g = setup(p)
    f = p["numerics.fem_ratio"] ** level
    a, b = g["hertz"].semi_axis_x, g["hertz"].semi_axis_y
    r0 = g["r0"]
    # the layered mesh maps the disk section of radius r0 onto the crown's smaller sections; where the crown radius
    # falls below MIN_CROWN_RATIO r0 its elements would be too flat (meshes.layered_bodies._crown_map)
    half_max = float(np.sqrt(g["Rc"] ** 2 - (g["Rc"] - (1.0 - MIN_CROWN_RATIO) * r0) ** 2))
    if 0.5 * p["numerics.fem_body_length"] * b > half_max:
        wide = " (the contact spans most of the crown: groove/crown too close to 1 for the FE body)" \
            if 2.0 * half_max / b < 2.2 else ""
        raise InputError("numerics.fem_body_length", f"{p['numerics.fem_body_length']:g} b_H reaches where the "
                         f"crowned body's radius is below {MIN_CROWN_RATIO:g} of {r0:g} m, where its mesh cannot "
                         f"follow{wide}; allowed: [2.2, {2.0 * half_max / b:.3g}] b_H")
    roller = RollerBody(r0, g["Rc"], p["numerics.fem_body_length"] * b, g["m1"])
    G, axis_point, axis_dir = _ring_axis(g, grid)
    ring = RingBody(G, g["rg"], axis_point, axis_dir, g["m2"], p["numerics.fem_ring_length"] * b,
                    p["numerics.fem_ring_depth"] * b, p["numerics.fem_ring_width"] * b)
    h = p["numerics.fem_h_contact"] if h_contact is None else h_contact
    mesh = MeshSettings(h, p["numerics.fem_grading"] / f, max(b, 2 * a), layers_per_cell, 2)
    return fe_compliance(roller, {"groove": ring}, {"groove": grid}, mesh, progress=progress)


def solve_level(p: dict[str, Any], level: int, progress=None, comp=None) -> dict[str, Any]:
    """One level: compliance (``comp``: already computed on this level's grid), free rolling under load control;
    returns quantities, stats and fields."""
    g = setup(p)
    grid = _grid(g, p, level)
    nx, ns = grid.x.size, grid.s.size
    b = g["hertz"].semi_axis_y
    r0, rg, kap = g["r0"], g["rg"], g["kappa"]
    G, axis_point, axis_dir = _ring_axis(g, grid)
    t0 = time.perf_counter()
    comp = compliance(p, grid, level, progress) if comp is None else comp
    t_comp = time.perf_counter() - t0
    V = float(p["kinematics.speed"])
    body = Crowned(np.zeros(3), np.array([0.0, 1.0, 0.0]), r0, g["Rc"])
    if kap == 0:
        groove = Grooved(np.asarray(G), rg, rail_direction=np.array([1.0, 0.0, 0.0]))
        rate = -V
    else:
        groove = Grooved(np.asarray(G), rg, np.asarray(axis_point), np.asarray(axis_dir),
                         reference=np.array([0.0, 0.0, -r0]))
        rate = -V * kap                        # ring surface at the reference point moves at -V e_x
    kin = kinematics(grid, body, V / r0, groove, rate)
    kin_w = kinematics(grid, body, 0.0, groove, rate)
    dslip = (kin.slip - kin_w.slip) / kin.speed                    # d(w/V_ref)/dtheta with omega = V/r0 (1 + theta)
    h = gap(grid, body, groove)
    inp = ContactInput(grid, h, kin.slip, kin.speed, kin.kappa)
    load = approach_unknown("approach", "groove", grid, [0.0, 0.0, 1.0], float(p["load.normal"]),
                            g["hertz"].approach)
    t1 = time.perf_counter()
    sol, theta = _free_rolling(comp, inp, dslip, float(p["friction.mu"]), load, p["numerics.fem_tol"])
    t_solve = time.perf_counter() - t1
    r = sol.contacts["groove"]
    left, right = lateral_extent(grid.s, r.pressure)
    half, centre = 0.5 * (right - left), 0.5 * (right + left)
    # steady rolling: the frictional power equals the power of the rigid slip, -sum p.w dA, when the elastic part
    # <p, d/dx A p> vanishes (a reciprocal, translation-invariant compliance): a check of the FE tables
    w = kin.slip + theta * dslip * kin.speed
    rigid_power = float(-(r.px * w[0] + r.ps * w[1]).sum() * grid.cell_area)
    Pref = grid.point(0.0, 0.0)
    w_ref = (body.velocity(Pref, V / r0 * (1.0 + theta)) - groove.velocity(Pref, rate)) @ grid.ex
    q = {"body_approach": sol.theta["approach"], "p_max": r.p_max, "contact_half_length_s": half,
         "angle_span": 2.0 * half / rg, "adhesion_fraction": r.adhesion_fraction,
         "creepage_x": float(w_ref / kin.speed), "friction_power": r.friction_power,
         # zero by symmetry (the scene and the mirrored mesh): below the exact theory's noise level it is zero
         "spin_moment": r.spin_moment if abs(r.spin_moment) > SPIN_NOISE * float(p["friction.mu"])
         * float(p["load.normal"]) * b else 0.0}
    stats = {"level": level, "nx": nx, "ns": ns, "dx": grid.dx, "ds": grid.ds, "h": grid.dx,
             "n_dofs": comp.stats["n_dofs"], "iterations": sol.iterations, "residual": sol.residual,
             "time_compliance_s": t_comp, "time_solve_s": t_solve, "pressure_centre_s": centre,
             "rigid_slip_power": rigid_power,
             "normal_force": r.normal_force, "creep_force_x": r.creep_force_x, "creep_force_s": r.creep_force_s,
             "bodies": {k: {kk: v[kk] for kk in ("n_nodes", "n_dofs", "times", "factorisations")}
                        for k, v in comp.stats.items() if isinstance(v, dict) and "n_dofs" in v}, **q}
    fields = {"x": grid.x, "s": grid.s, "pressure": r.pressure, "px": r.px, "ps": r.ps,
              "adhesion": r.adhesion.astype(float), "contact": r.contact.astype(float),
              "slip_x": r.slip_velocity[0], "slip_s": r.slip_velocity[1], "power_density": r.power_density,
              "lateral_normal": r.lateral_normal, "lateral_fx": r.lateral_longitudinal}
    return {"quantities": q, "stats": stats, "fields": fields}


def model(scene, progress=None) -> ModelResult:
    """The ``fem`` model of the groove-rolling scene (module docstring); ``scene`` a Scene or a params dict."""
    t0 = time.perf_counter()
    p = _params(scene)
    n_levels = int(p["numerics.fem_levels"])
    levels = []
    for k in range(n_levels):
        if progress:
            progress(f"FE groove rolling, level {k + 1}/{n_levels}")
        levels.append(solve_level(p, k, progress))
    fine = levels[-1]
    hz = setup(p)["hertz"]
    h = [lv["stats"]["h"] for lv in levels]
    certificates = {}
    q = dict(fine["quantities"])
    for name in QUANTITIES:
        # p_max is the smooth Hertz-like peak of a conformal contact, not an edge singularity: certified like the rest
        c = certify(h, [lv["quantities"][name] for lv in levels])
        certificates[name] = c.as_dict()
        q[name] = c.value
    stats = {"method": "FE compliances (P2 layered meshes, unit cell loads, Pardiso) + semi-smooth Newton "
                       "steady rolling (free rolling, load control)",
             "levels": [lv["stats"] for lv in levels], "level_quantities": list(QUANTITIES),
             "certificates": certificates, "iterations": fine["stats"]["iterations"],
             "residual": fine["stats"]["residual"], "finest": dict(fine["quantities"]),
             "hertz": {"semi_axis_x": hz.semi_axis_x, "semi_axis_y": hz.semi_axis_y, "p_max": hz.p_max,
                       "approach": hz.approach}}
    return ModelResult("fem", time_s=time.perf_counter() - t0, quantities=q, stats=stats, fields=fine["fields"])
