"""3D point / elliptical contact with Coulomb friction: shift (Cattaneo-Mindlin, scene ``cattaneo``) or steady
rolling with creepages xi, eta and spin phi (scene ``creep-curve``).

Which problem is solved follows from the scene: ``load.tangential`` (shift; the tangential force applied to
body 1, which the friction force on body 1 balances, so creep_force_x = -load.tangential) or any of
``kinematics.xi|eta|phi`` (steady rolling) -- not both. Frame and signs: conv.md (x rolling direction, the creep
force on body 1 opposes the creepage, Kalker 1990). ``shift`` is the rigid shift of body 1 relative to body 2 in
the direction of load.tangential (m).

Models:
- ``exact``: Kalker's exact theory on a planar grid (:mod:`femcheck.cect.exact`; Johnson's process for
  quasi-identical bodies, Panagiotopoulos' otherwise).
- ``analytic``: Cattaneo-Mindlin (shift, :mod:`femcheck.analytic.mindlin`); Hertz semi-axes (rolling).
- ``linear``: Kalker's linear theory with coefficients from the exact solver (:mod:`femcheck.cect.creep`).
- ``fastsim``: Kalker's FASTSIM with the same coefficients (:mod:`femcheck.cect.fastsim`).
- ``full_slip``: traction -mu p w/|w| everywhere (:mod:`femcheck.cect.full_slip`).
- ``strip``: strip theory, Hertz + Carter per strip (:mod:`femcheck.cect.strip`, seed 000 eqs 4-11).
The simplified rolling models work on the Hertz ellipse with Kalker's combined G and nu; they need
quasi-identical bodies (they have no normal-tangential coupling) and are skipped otherwise.
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from ..analytic import hertz, mindlin as mindlin_closed_form
from ..bem.halfspace import grid as make_grid
from ..cect import creep as creep_coefficients_module
from ..cect.exact import solve_contact
from ..cect.refinement import grids, refine
from ..cect.influence import combined_constants
from ..errors import InputError
from ..qoi import ellipse_fit
from ..result import ModelResult
from ..scene import Key, Scene, check_body_pair, elastic, material_keys, model_keys, tolerance_key

MODEL_NAMES = ("exact", "analytic", "linear", "fastsim", "full_slip", "strip")
# a sphere radius or the two radii of curvature: the one given last (an override) wins
ALTERNATIVES = (("geometry.radius", ("geometry.Rx", "geometry.Ry")),)
DESIGN_QUANTITIES = ("creep_force_x", "creep_force_y", "shift", "spin_moment", "p_max")
ROLLING_ONLY = ("linear", "fastsim", "full_slip", "strip")
# what `femcheck stress` judges against the reference (where the scene sets a tolerance)
STRESS_QUANTITIES = ("shift", "stick_radius", "semi_axis_x", "semi_axis_y", "creep_force_x", "creep_force_y")
MAX_A_OVER_R = 0.1
MAX_DENSE_CELLS = 61             # dense Newton matrix of a 61 x 61 grid: ~2900 elements, 0.5 GB, minutes per step
QUASI_IDENTICAL_TOL = 1e-9       # |K| below this: no normal-tangential coupling

SCHEMA: dict[str, Key] = {
    "geometry.radius": Key("float", "m", "sphere radius R (sets Rx = Ry = R)", lo=0.0),
    "geometry.Rx": Key("float", "m", "relative radius of curvature in the rolling direction x", lo=0.0),
    "geometry.Ry": Key("float", "m", "relative radius of curvature across, y", lo=0.0),
    "load.normal": Key("float", "N", "normal load P", lo=0.0),
    "load.tangential": Key("float", "N", "tangential force Q on body 1 along x (shift problem; |Q| < mu P)"),
    **material_keys("body1"),
    **material_keys("body2"),
    "friction.mu": Key("float", "-", "Coulomb friction coefficient", lo=0.0, hi=10.0, hi_closed=True),
    "kinematics.xi": Key("float", "-", "longitudinal creepage", lo=-0.1, hi=0.1, lo_closed=True, hi_closed=True),
    "kinematics.eta": Key("float", "-", "lateral creepage", lo=-0.1, hi=0.1, lo_closed=True, hi_closed=True),
    "kinematics.phi": Key("float", "1/m", "spin creepage", lo=-1e4, hi=1e4, lo_closed=True, hi_closed=True),
    "kinematics.speed": Key("float", "m/s", "rolling speed V (scales slip velocities and frictional power)",
                            lo=0.0),
    **model_keys(MODEL_NAMES),
    "numerics.exact_cells": Key("int", "-", "exact solver: elements per axis of the finest potential contact "
                                f"grid (dense solver: at most {MAX_DENSE_CELLS})", lo=9, hi=513, lo_closed=True,
                                hi_closed=True),
    "numerics.exact_levels": Key("int", "-", "exact solver: grids of finest / 2^k elements per axis (k < levels); "
                                 "the discretisation error estimate needs >= 3", lo=1, hi=5, lo_closed=True,
                                 hi_closed=True),
    "numerics.exact_solver": Key("str", "-", "exact solver's tangential problem: dense (LU of the Newton matrix), "
                                 "fft (matrix-free Newton-GMRES with DC-FFT products) or auto (fft above "
                                 "300 contact elements)", choices=("auto", "dense", "fft")),
    "numerics.exact_domain": Key("float", "a_H", "exact solver: grid half-width / Hertz semi-axis (each axis)",
                                 lo=1.02, hi=3.0, hi_closed=True),
    "numerics.exact_tol": Key("float", "-", "exact solver: Coulomb residual / max(mu p)", lo=0.0, hi=1e-4,
                              hi_closed=True),
    "numerics.creep_cells": Key("int", "-", "creep coefficients: elements per axis of the coarsest of three "
                                "grids (n, 2n, 4n; Richardson; grids above 40 solved matrix-free)", lo=6, hi=64,
                                lo_closed=True, hi_closed=True),
    "numerics.fastsim_cells": Key("int", "-", "FASTSIM: cells per strip and strips", lo=2, hi=1000,
                                  lo_closed=True, hi_closed=True),
    "numerics.fastsim_flexibility": Key("str", "-", "FASTSIM: separate (L1, L2, L3 for the xi, eta, phi terms; "
                                        "exact linear theory at small combined creepage) or weighted (Kalker "
                                        "1982's single creepage-weighted L)", choices=("separate", "weighted")),
    "numerics.fastsim_bound": Key("str", "-", "FASTSIM traction bound: parabolic (Kalker 1982) or elliptic "
                                  "(the Hertz pressure)", choices=("parabolic", "elliptic")),
    "numerics.full_slip_cells": Key("int", "-", "full slip: quadrature nodes per axis", lo=2, hi=1000,
                                    lo_closed=True, hi_closed=True),
    "numerics.strips": Key("int", "-", "strip theory: number of strips", lo=2, hi=10000, lo_closed=True,
                           hi_closed=True),
    "tolerances.*.*": tolerance_key("relative tolerance of model.quantity against the references"),
}
DEFAULTS: dict[str, Any] = {
    "materials.body1.rigid": False,
    "materials.body2.rigid": False,
    "kinematics.speed": 1.0,
    "models.run": ["exact", "analytic"],
    "models.references": ["analytic"],
    # 24^2, 48^2, 96^2 elements over +/- 1.1 semi-axes, Richardson at first order (Kalker's scheme; measured in
    # benchmarks/exact_scaling.py): on creep-curve the extrapolated forces and spin moment are within 0.02 % of
    # the extrapolation from 64^2, 128^2, 256^2 (the 96^2 grid alone: 0.4 %, 0.35 %, 0.8 %); 0.7 s
    "numerics.exact_cells": 96,
    "numerics.exact_levels": 3,
    "numerics.exact_domain": 1.1,
    "numerics.exact_tol": 1e-9,
    "numerics.exact_solver": "auto",
    "numerics.creep_cells": 12,
    "numerics.fastsim_cells": 40,
    # three flexibilities and Kalker's parabolic bound: measured against the exact solver on creep-curve, the
    # single weighted L is 20-40 % off at combined xi + eta (its L exceeds L1 by (|xi|+|eta|)/|(xi, eta)|)
    "numerics.fastsim_flexibility": "separate",
    "numerics.fastsim_bound": "parabolic",
    "numerics.full_slip_cells": 40,
    "numerics.strips": 200,
}
REQUIRED = ("load.normal", "friction.mu")
DEPENDS: dict[str, dict] = {}


def radii(params: dict[str, Any]) -> tuple[float, float]:
    if "geometry.radius" in params:
        return params["geometry.radius"], params["geometry.radius"]
    return params["geometry.Rx"], params["geometry.Ry"]


def problem_type(params: dict[str, Any]) -> str:
    """``shift`` (load.tangential given) or ``rolling`` (any kinematics.xi|eta|phi given)."""
    return "shift" if "load.tangential" in params else "rolling"


def creepages(params: dict[str, Any]) -> tuple[float, float, float]:
    return (float(params.get("kinematics.xi", 0.0)), float(params.get("kinematics.eta", 0.0)),
            float(params.get("kinematics.phi", 0.0)))


def _constants(params: dict[str, Any]):
    return combined_constants(elastic(params, "body1"), elastic(params, "body2"))


def _hertz(params: dict[str, Any]) -> hertz.EllipticContact:
    rx, ry = radii(params)
    return hertz.elliptic_contact(params["load.normal"], rx, ry, _constants(params).contact_modulus)


def validate(params: dict[str, Any]) -> None:
    """Radius xor (Rx, Ry); exactly one of load.tangential / kinematics; |Q| < mu P; small a/R."""
    has_r, has_xy = "geometry.radius" in params, ("geometry.Rx" in params, "geometry.Ry" in params)
    if has_r and any(has_xy):
        raise InputError("geometry.radius", "give either geometry.radius or geometry.Rx and geometry.Ry")
    if not has_r and not all(has_xy):
        raise InputError("geometry.Rx" if not has_xy[0] else "geometry.Ry",
                         "required (or give geometry.radius for a sphere)")
    has_q = "load.tangential" in params
    has_kin = any(k in params for k in ("kinematics.xi", "kinematics.eta", "kinematics.phi"))
    if has_q == has_kin:
        raise InputError("load.tangential", "give exactly one of load.tangential (shift) and "
                         "kinematics.xi|eta|phi (steady rolling)" + (" -- both are set" if has_q else
                                                                     " -- neither is set"))
    check_body_pair(params, ("body1", "body2"))
    grids(params["numerics.exact_cells"], params["numerics.exact_levels"], "numerics.exact_cells", 8)
    if params.get("numerics.exact_solver") == "dense" and params.get("numerics.exact_cells", 0) > MAX_DENSE_CELLS:
        raise InputError("numerics.exact_cells", f"{params['numerics.exact_cells']} with numerics.exact_solver = dense;"
                         f" allowed: <= {MAX_DENSE_CELLS} (or exact_solver = fft / auto)")
    if params["friction.mu"] <= 0:
        raise InputError("friction.mu", f"{params['friction.mu']:g}; allowed: (0, 10]")
    if has_q:
        limit = params["friction.mu"] * params["load.normal"]
        if abs(params["load.tangential"]) >= limit:
            raise InputError("load.tangential", f"{params['load.tangential']:g} N is not allowed; allowed: |Q| < "
                             f"mu P = {limit:.6g} N (beyond it the contact slides: no partial-slip state)")
    h = _hertz(params)
    rx, ry = radii(params)
    ratio = max(h.semi_axis_x / rx, h.semi_axis_y / ry)
    if ratio > MAX_A_OVER_R:
        w_max = params["load.normal"] * (MAX_A_OVER_R / ratio) ** 3
        raise InputError("load.normal", f"{params['load.normal']:g} N gives Hertz semi-axes up to a/R = {ratio:.3g}"
                         f" > {MAX_A_OVER_R}; allowed (0, {w_max:.4g}] N for these radii and materials")


def _hertz_quantities(h: hertz.EllipticContact) -> dict[str, float]:
    return {"semi_axis_x": h.semi_axis_x, "semi_axis_y": h.semi_axis_y, "p_max": h.p_max, "total_force": h.load}


def exact(scene: Scene, progress=None) -> ModelResult:
    """Kalker's exact theory on n x n grids over +/- exact_domain Hertz semi-axes, n = exact_cells / 2^k for
    k < exact_levels: every quantity carries a convergence certificate (``stats["certificates"]``,
    :mod:`femcheck.cect.refinement`) and is reported as its certificate value (Richardson's extrapolation when
    the grids are in the asymptotic range, else the finest grid). Fields and solver statistics are the finest
    grid's."""
    p = scene.params
    h = _hertz(p)
    cc = _constants(p)
    rx, ry = radii(p)
    dom = p["numerics.exact_domain"]
    gap = lambda X, Y: X * X / (2.0 * rx) + Y * Y / (2.0 * ry)  # noqa: E731
    kind = problem_type(p)

    def solve(n: int):
        if progress:
            progress(f"exact: {n} x {n} elements")
        g = make_grid(dom * h.semi_axis_x, dom * h.semi_axis_y, n, n)
        if kind == "shift":
            sol = solve_contact(g, gap, cc, p["load.normal"], p["friction.mu"],
                                tangential_load=(-p["load.tangential"], 0.0), tol=p["numerics.exact_tol"],
                                tangential_solver=p["numerics.exact_solver"])
        else:
            sol = solve_contact(g, gap, cc, p["load.normal"], p["friction.mu"], creepages=creepages(p),
                                rolling_speed=p["kinematics.speed"], tol=p["numerics.exact_tol"],
                                tangential_solver=p["numerics.exact_solver"])
        X, Y = g.mesh()
        fit = ellipse_fit(X, Y, sol.pressure)
        q = {"p_max": float(sol.pressure.max()), "total_force": sol.normal_force,
             "semi_axis_x": fit["semi_axis_x"], "semi_axis_y": fit["semi_axis_y"],
             "creep_force_x": sol.creep_force_x, "creep_force_y": sol.creep_force_y}
        if kind == "shift":
            # the stick zone's equivalent radius from its area (model-free; within ~dx of the true boundary)
            q.update(shift=float(np.sign(p["load.tangential"]) * sol.shift[0]) if p["load.tangential"] else 0.0,
                     stick_radius=float(np.sqrt(sol.adhesion.sum() * g.cell_area / np.pi)))
        else:
            q.update(spin_moment=sol.spin_moment, adhesion_fraction=sol.adhesion_fraction)
        return q, (g, sol)

    # the shift problem imposes the friction force (load control); the normal load is imposed in both
    imposed = ("total_force", "creep_force_x", "creep_force_y") if kind == "shift" else ("total_force",)
    # forces and moment that vanish by symmetry (Fx under pure spin, ...): round-off relative to mu P (N) and
    # mu P c (N m)
    zero = 1e-9 * p["friction.mu"] * p["load.normal"]
    negligible = {"creep_force_x": zero, "creep_force_y": zero,
                  "spin_moment": zero * np.sqrt(h.semi_axis_x * h.semi_axis_y)}
    ref = refine(solve, grids(p["numerics.exact_cells"], p["numerics.exact_levels"], "numerics.exact_cells"),
                 imposed=imposed, expected_order={"p_max": None, "semi_axis_x": None, "semi_axis_y": None},
                 negligible=negligible)
    g, sol = ref.finest
    stats = {**{k: v for k, v in sol.stats.items() if k != "history"}, "problem": kind,
             # the keys every model reports (report table, bench): Newton iterations and the Coulomb residual
             "iterations": sol.stats.get("newton_iterations"), "residual": sol.stats.get("tangential_residual"),
             "n_elements": g.nx * g.ny,
             "coupling_K": cc.coupling, "G": cc.shear_modulus, "nu": cc.poisson,
             "a_over_dx": h.semi_axis_x / g.dx,
             "solver": ("semi-smooth Newton (matrix-free FGMRES, DC-FFT)" if sol.stats["tangential_solver"] == "fft"
                        else "semi-smooth Newton (dense LU)") + " + Polonsky-Keer CG", **ref.stats()}
    if kind == "rolling":
        stats["frictional_power"] = sol.frictional_power
    j = g.ny // 2
    fields = {"x": g.x, "pressure": sol.pressure[:, j], "traction_x": sol.px[:, j], "pressure_map": sol.pressure,
              "map_x": g.x, "map_y": g.y, "adhesion_map": sol.adhesion.astype(float), "px_map": sol.px,
              "py_map": sol.py, "slip_x_map": sol.slip_x, "slip_y_map": sol.slip_y}
    if sol.power_density is not None:
        fields["power_density_map"] = sol.power_density
    return ModelResult("exact", quantities=dict(ref.values), stats=stats, fields=fields)


def analytic(scene: Scene, progress=None) -> ModelResult:
    """Cattaneo-Mindlin (shift, sphere only) or the Hertz semi-axes (rolling)."""
    p = scene.params
    h = _hertz(p)
    q = _hertz_quantities(h)
    if problem_type(p) == "rolling":
        return ModelResult("analytic", quantities=q, stats={"problem": "rolling", "E_star": h.modulus})
    rx, ry = radii(p)
    if rx != ry:
        return ModelResult("analytic", "skipped", error="Cattaneo-Mindlin is the sphere solution (Rx = Ry)")
    cc = _constants(p)
    Q = abs(p["load.tangential"])
    m = mindlin_closed_form.mindlin(p["load.normal"], Q, rx, p["friction.mu"], h.modulus,
                                    2.0 * (2.0 - cc.poisson) / cc.shear_modulus)
    q.update(shift=float(np.sign(p["load.tangential"]) * m.shift), stick_radius=m.stick_radius,
             creep_force_x=-p["load.tangential"])
    # the centre line y = 0 across the whole contact, as the exact model's fields; the traction is the friction
    # force on body 1, which opposes load.tangential (the sign of creep_force_x)
    x = np.linspace(-1.1 * m.contact_radius, 1.1 * m.contact_radius, 601)
    stats = {"problem": "shift", "E_star": h.modulus}
    if abs(cc.coupling) > QUASI_IDENTICAL_TOL:
        stats["note"] = f"dissimilar bodies (K = {cc.coupling:.3g}): Mindlin neglects the normal-tangential coupling"
    return ModelResult("analytic", quantities=q, stats=stats,
                       fields={"x": x, "pressure": h.pressure(x, 0 * x),
                               "traction_x": -np.sign(p["load.tangential"]) * m.traction(np.abs(x))})


def _coefficients(params: dict[str, Any]):
    h = _hertz(params)
    cc = _constants(params)
    n = params["numerics.creep_cells"]
    return creep_coefficients_module.creep_coefficients(round(h.semi_axis_x / h.semi_axis_y, 12),
                                                        round(cc.poisson, 12), (n, 2 * n, 4 * n))


def _rolling_only(name: str, params: dict[str, Any]) -> str | None:
    if problem_type(params) != "rolling":
        return f"{name} is a steady-rolling model; this scene is a shift problem"
    if abs(_constants(params).coupling) > QUASI_IDENTICAL_TOL:
        return f"{name} assumes quasi-identical bodies (no normal-tangential coupling); here K != 0"
    return None


def _simplified(name: str, params: dict[str, Any], compute: Callable[..., Any], stats: dict) -> ModelResult:
    if (why := _rolling_only(name, params)) is not None:
        return ModelResult(name, "skipped", error=why)
    h = _hertz(params)
    res = compute(h)
    q = {**_hertz_quantities(h), "creep_force_x": float(res.creep_force_x),
         "creep_force_y": float(res.creep_force_y), "spin_moment": float(res.spin_moment)}
    if res.adhesion_fraction is not None:
        q["adhesion_fraction"] = float(res.adhesion_fraction)
    fields = {}
    if all(isinstance(getattr(res, k, None), np.ndarray) and getattr(res, k).ndim == 2 for k in ("x", "y", "px")):
        # the traction along the rolling direction on the row of nodes nearest the centre line y = 0, for the
        # report's traction overlay beside the exact theory's
        j = int(np.argmin(np.abs(res.y[:, 0])))
        order = np.argsort(res.x[j])
        fields = {"x": res.x[j][order], "traction_x": res.px[j][order]}
    return ModelResult(name, quantities=q, stats=stats, fields=fields)


def linear(scene: Scene, progress=None) -> ModelResult:
    """Kalker's linear theory; C11..C33 from :func:`femcheck.cect.creep.creep_coefficients` (cached)."""
    from ..cect.linear import linear_creep

    p = scene.params
    if (why := _rolling_only("linear", p)) is not None:
        return ModelResult("linear", "skipped", error=why)
    k = _coefficients(p)
    G = _constants(p).shear_modulus
    stats = {"c11": k.c11, "c22": k.c22, "c23": k.c23, "c33": k.c33, "coefficient_error": k.error,
             "creep_grids": list(k.grids)}
    return _simplified("linear", p, lambda h: linear_creep(h.semi_axis_x, h.semi_axis_y, G, k.c11, k.c22, k.c23,
                                                           k.c33, *creepages(p)), stats)


def fastsim(scene: Scene, progress=None) -> ModelResult:
    """FASTSIM with flexibilities from the exact solver's C11, C22, C23."""
    from ..cect.fastsim import fastsim as fastsim_solve

    p = scene.params
    if (why := _rolling_only("fastsim", p)) is not None:
        return ModelResult("fastsim", "skipped", error=why)
    k = _coefficients(p)
    G = _constants(p).shear_modulus
    n = p["numerics.fastsim_cells"]
    return _simplified("fastsim", p, lambda h: fastsim_solve(h.semi_axis_x, h.semi_axis_y, p["load.normal"], G,
                                                             k.c11, k.c22, k.c23, p["friction.mu"], *creepages(p),
                                                             nx=n, ny=n, bound=p["numerics.fastsim_bound"],
                                                             flexibility=p["numerics.fastsim_flexibility"]),
                       {"c11": k.c11, "c22": k.c22, "c23": k.c23, "nx": n, "ny": n,
                        "bound": p["numerics.fastsim_bound"], "flexibility": p["numerics.fastsim_flexibility"]})


def full_slip(scene: Scene, progress=None) -> ModelResult:
    """Full slip: traction -mu p w/|w| on the Hertz ellipse."""
    from ..cect.full_slip import full_slip as full_slip_solve

    p = scene.params
    n = p["numerics.full_slip_cells"]
    return _simplified("full_slip", p, lambda h: full_slip_solve(h.semi_axis_x, h.semi_axis_y, p["load.normal"],
                                                                 p["friction.mu"], *creepages(p), nx=n, ny=n),
                       {"nx": n, "ny": n})


def strip(scene: Scene, progress=None) -> ModelResult:
    """Strip theory (Hertz + Carter per strip)."""
    from ..cect.strip import strip_theory

    p = scene.params
    cc = _constants(p)
    n = p["numerics.strips"]
    return _simplified("strip", p, lambda h: strip_theory(h.semi_axis_x, h.semi_axis_y, p["load.normal"],
                                                          cc.shear_modulus, cc.poisson, p["friction.mu"],
                                                          *creepages(p), n_strips=n), {"n_strips": n})


MODELS: dict[str, Callable[..., ModelResult]] = {"exact": exact, "analytic": analytic, "linear": linear,
                                                 "fastsim": fastsim, "full_slip": full_slip, "strip": strip}


def load_of(scene: Scene) -> float:
    """Applied normal load (N) against which every model's ``total_force`` is checked."""
    return scene["load.normal"]


def profile_scale(scene: Scene) -> float:
    return _hertz(scene.params).semi_axis_x


def stress_cases(scene: Scene) -> list:
    """Extremes: friction 0.01-2, tangential load up to 0.999 mu P (shift) or creepages from 1e-6 to 100 x
    saturation and large spin (rolling), very elongated contacts (Ry/Rx up to 100), nu -> 0.5, a rigid body
    (dissimilar: Panagiotopoulos), loads down to 1e-6 of the scene's."""
    from ..result import StressCase

    p = scene.params
    # a shift problem keeps Q / (mu P) when mu changes (a fixed Q would just leave the partial-slip range)
    scale = (lambda mu: {"load.tangential": p["load.tangential"] * mu / p["friction.mu"]}) \
        if problem_type(p) == "shift" else (lambda mu: {})
    cases = [StressCase(f"mu={mu:g}", {"friction.mu": mu, **scale(mu)}) for mu in (0.01, 1.0, 2.0)]
    h = _hertz(p)
    cc = _constants(p)
    if problem_type(p) == "shift":
        limit = p["friction.mu"] * p["load.normal"]
        for f in (1e-6, 1e-3, 0.9, 0.999):
            cases.append(StressCase(f"Q={f:g} mu P", {"load.tangential": f * limit}))
    else:
        c = np.sqrt(h.semi_axis_x * h.semi_axis_y)
        # creepage at which linear theory reaches mu N (C11 ~ 4): the saturation scale
        sat = 3.0 * p["friction.mu"] * p["load.normal"] / (cc.shear_modulus * c * c * 4.0)
        for f in (1e-6, 1e-2, 1.0, 100.0):
            cases.append(StressCase(f"xi={f:g} x saturation", {"kinematics.xi": min(f * sat, 0.1),
                                                                "kinematics.eta": 0.0, "kinematics.phi": 0.0}))
        for f in (1.0, 10.0, 100.0):
            cases.append(StressCase(f"spin={f:g} x saturation", {"kinematics.xi": 0.0, "kinematics.eta": 0.0,
                                                                  "kinematics.phi": min(f * sat / c, 1e4)}))
        rx, ry = radii(p)
        for ratio in (10.0, 100.0):
            over = {"geometry.Rx": rx, "geometry.Ry": rx * ratio}
            if "geometry.radius" in p:
                over["geometry.radius"] = None
            cases.append(StressCase(f"Ry/Rx={ratio:g}", over))
    for nu in (0.0, 0.45, 0.4999):
        cases.append(StressCase(f"nu={nu:g}", {"materials.body1.nu": nu, "materials.body2.nu": nu}))
    cases.append(StressCase("rigid body1", {"materials.body1.rigid": True}))
    for k in (3, 6):
        over = {"load.normal": p["load.normal"] * 10.0**-k}
        if problem_type(p) == "shift":
            over["load.tangential"] = p["load.tangential"] * 10.0**-k
        cases.append(StressCase(f"load x 1e-{k}", over))
    return cases


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    """Exact solver on one grid (no refinement: the sweep measures a single grid's cost and error): elements per
    axis (the dense Newton costs O(n^6) per step and the matrix-free one
    O(n^2 log n) per GMRES iteration: "auto" switches to it above 300 contact elements, so the sweep reaches
    129 x 129); FASTSIM: cells per strip and strips."""
    sweeps = {"exact": [{"numerics.exact_cells": n, "numerics.exact_levels": 1} for n in (15, 21, 31, 41, 65, 129)]}
    if problem_type(scene.params) == "rolling":
        sweeps["fastsim"] = [{"numerics.fastsim_cells": n} for n in (5, 10, 20, 40, 80, 160)]
        sweeps["strip"] = [{"numerics.strips": n} for n in (10, 20, 50, 100, 200, 400)]
    return sweeps
