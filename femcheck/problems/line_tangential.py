"""Plane-strain line contact with friction: a cylinder on a block, steady rolling (Carter) or shift (2D Cattaneo).

Which problem is solved follows from the scene: ``kinematics.xi`` (steady rolling with creepage xi: scene
carter-2d) or ``load.tangential_per_length`` (tangential force Q' on the cylinder, load control: scene
cattaneo-2d) -- exactly one of them. Frame and signs: :mod:`femcheck.analytic.carter` (forces are those on the
cylinder, the creep force opposes xi; the shift is positive in the direction of Q').

Models: ``exact`` (Kalker's exact theory in 2D, :mod:`femcheck.cect.line`, on three grids with a convergence
certificate per quantity; Panagiotopoulos' process for dissimilar bodies), ``analytic`` (Carter / 2D Cattaneo
closed forms, quasi-identical bodies), ``linear`` and ``fastsim`` (rolling only: Kalker's linear theory and 2D
FASTSIM, :mod:`femcheck.cect.simplified_line`), ``full_slip`` (rolling only: traction -mu p sgn(xi)), ``fem``
(2D plane-strain FE reference with Coulomb friction, :mod:`femcheck.fem.friction_line`; stored reference).
Quantities: rolling -- ``creep_force_x`` (N/m), ``adhesion_length`` (m), ``adhesion_fraction`` (-);
shift -- ``shift`` (m, the micro-slip part delta(Q') - delta_stick(Q'), delta_stick the fully adhered state on
the frictionless pressure: :mod:`femcheck.cect.line`), ``stick_half_width`` (m); both -- ``half_width`` (m),
``p_max`` (Pa), ``total_force`` (N/m, normal). The fem model adds ``shift_weighted`` (an alternative estimate,
see :func:`femcheck.fem.friction_pair.weighted_shift`).
"""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from ..analytic import carter, hertz
from ..cect.line import PROCESSES, adhesion_zone, coupling_constant, solve_line_friction
from ..cect.refinement import grids, refine
from ..cect.simplified_line import fastsim_line, linear_line
from ..errors import InputError
from ..fem import friction_line
from ..materials import effective_modulus
from ..qoi import half_width
from ..result import ModelResult
from ..scene import Key, Scene, check_body_pair, elastic, material_keys, model_keys, tolerance_key

MODEL_NAMES = ("exact", "analytic", "linear", "fastsim", "full_slip", "fem")
DESIGN_QUANTITIES = ("creep_force_x", "shift", "stick_half_width", "p_max")
MAX_A_OVER_R = 0.1       # half-space and small-strain limit, as for hertz-line
QUASI_IDENTICAL_TOL = 1e-9   # |kappa E*| below this: no normal-tangential coupling (Carter applies exactly)
STRESS_QUANTITIES = ("creep_force_x", "adhesion_length", "shift", "stick_half_width")

SCHEMA: dict[str, Key] = {
    "geometry.radius": Key("float", "m", "cylinder radius R", lo=0.0),
    "load.per_length": Key("float", "N/m", "normal load per unit length W'", lo=0.0),
    "load.tangential_per_length": Key("float", "N/m", "tangential force per unit length Q' on the cylinder "
                                      "(shift problem; |Q'| < mu W')"),
    **material_keys("cylinder"),
    **{k: v for k, v in material_keys("block").items() if not k.endswith("rigid")},
    "friction.mu": Key("float", "-", "Coulomb friction coefficient", lo=0.0, hi=10.0, hi_closed=True),
    "kinematics.xi": Key("float", "-", "longitudinal creepage (steady-rolling problem)", lo=-0.1, hi=0.1,
                         lo_closed=True, hi_closed=True),
    "kinematics.speed": Key("float", "m/s", "rolling speed V (scales slip velocities and frictional power)",
                            lo=0.0),
    **model_keys(MODEL_NAMES),
    "numerics.exact_elements": Key("int", "-", "strips of the exact solver's finest grid over the domain",
                                   lo=20, hi=8192, lo_closed=True, hi_closed=True),
    "numerics.exact_levels": Key("int", "-", "grids of the exact solver (finest / 2^k strips, k < levels): the "
                                 "discretisation error estimate needs >= 3", lo=1, hi=5, lo_closed=True,
                                 hi_closed=True),
    "numerics.exact_process": Key("str", "-", "exact solver, dissimilar bodies: panagiotopoulos (normal and "
                                  "tangential problems alternate until consistent; auto) or johnson (the "
                                  "tangential traction does not act back on the pressure)", choices=PROCESSES),
    "numerics.exact_domain": Key("float", "a_H", "exact-solver domain half-length / Hertz half-width", lo=1.02,
                                 hi=3.0, hi_closed=True),
    "numerics.exact_tol": Key("float", "-", "relative residual of the exact tangential solver", lo=0.0, hi=1e-4,
                              hi_closed=True),
    "numerics.exact_max_iter": Key("int", "-", "active-set iterations allowed", lo=2, hi=10000, lo_closed=True,
                                   hi_closed=True),
    **friction_line.FEM_SCHEMA,
    "tolerances.*.*": tolerance_key("relative tolerance of model.quantity against the references"),
}

DEFAULTS: dict[str, Any] = {
    **friction_line.FEM_DEFAULTS,
    "materials.cylinder.rigid": False,
    "kinematics.speed": 1.0,
    "models.run": list(MODEL_NAMES),
    "models.references": ["analytic"],
    # 250, 500, 1000 strips over [-1.25 a, 1.25 a] (dx = a/100 ... a/400; Richardson, first order): the Hertz
    # edges fall on cell boundaries on every grid (elements/10 integer), which removes the O(dx) jitter of a
    # partially covered edge cell from the 2D shift.
    "numerics.exact_elements": 1000,
    "numerics.exact_levels": 3,
    "numerics.exact_process": "auto",
    "numerics.exact_domain": 1.25,
    "numerics.exact_tol": 1e-8,
    "numerics.exact_max_iter": 200,
}
REQUIRED = ("geometry.radius", "load.per_length", "materials.block.E", "materials.block.nu", "friction.mu")
# The FE reference (2D plane strain, Coulomb friction, Richardson over mesh levels) is stored in references/ and
# re-solved only when its inputs or the FE code below change. "coarse": its coarsest mesh level alone, on the
# nominal block only (the 2x and 4x blocks are solved on the finest mesh, which a one-level run makes level 0):
# what femcheck.reference_check re-solves (about a second) to prove a stored reference current.
DEPENDS: dict[str, dict] = {
    "fem": {"params": ("geometry.", "load.", "materials.", "friction.", "kinematics.xi", "numerics.fem_"),
            "reference": True, "coarse": {"numerics.fem_levels": 1, "numerics.fem_block_extrapolation": False}},
}


def problem_type(params: dict[str, Any]) -> str:
    """``rolling`` (kinematics.xi given) or ``shift`` (load.tangential_per_length given)."""
    return "rolling" if "kinematics.xi" in params else "shift"


def _modulus(params: dict[str, Any]) -> float:
    return effective_modulus(elastic(params, "cylinder"), elastic(params, "block"))


def _hertz(params: dict[str, Any]) -> hertz.LineContact:
    return hertz.line_contact(params["load.per_length"], params["geometry.radius"], _modulus(params))


def _kappa(params: dict[str, Any]) -> float:
    return coupling_constant(elastic(params, "cylinder"), elastic(params, "block"))


def validate(params: dict[str, Any]) -> None:
    """Exactly one of kinematics.xi / load.tangential_per_length; |Q'| < mu W'; a/R <= MAX_A_OVER_R."""
    has_xi, has_q = "kinematics.xi" in params, "load.tangential_per_length" in params
    if has_xi == has_q:
        raise InputError("kinematics.xi" if has_xi else "load.tangential_per_length",
                         "give exactly one of kinematics.xi (steady rolling) and load.tangential_per_length "
                         "(shift)" + (" -- both are set" if has_xi else " -- neither is set"))
    check_body_pair(params, ("cylinder", "block"))
    h = _hertz(params)
    ratio = h.half_width / params["geometry.radius"]
    if ratio > MAX_A_OVER_R:
        w_max = params["load.per_length"] * (MAX_A_OVER_R / ratio) ** 2
        raise InputError("load.per_length", f"{params['load.per_length']:g} N/m gives a Hertz half-width a/R = "
                         f"{ratio:.3g} > {MAX_A_OVER_R}; allowed (0, {w_max:.4g}] N/m for this radius and these "
                         "materials")
    if has_q:
        limit = params["friction.mu"] * params["load.per_length"]
        if abs(params["load.tangential_per_length"]) >= limit:
            raise InputError("load.tangential_per_length",
                             f"{params['load.tangential_per_length']:g} N/m is not allowed; allowed: |Q'| < mu W' = "
                             f"{limit:.6g} N/m (beyond it the cylinder slides: no partial-slip state)")
    n, dom = params["numerics.exact_elements"], params["numerics.exact_domain"]
    coarsest = grids(n, params["numerics.exact_levels"], "numerics.exact_elements", 20)[0]
    if coarsest * (1.0 - 1.0 / dom) / 2.0 < 2.0:
        raise InputError("numerics.exact_elements", f"{n} leaves fewer than 2 free cells beyond the contact on the "
                         f"coarsest grid ({coarsest} strips); raise it or numerics.exact_domain")


def _common(h: hertz.LineContact) -> dict[str, float]:
    return {"half_width": h.half_width, "p_max": h.p_max, "total_force": h.load}


def exact(scene: Scene, progress=None) -> ModelResult:
    """Kalker's exact theory in 2D: half-plane BEM normal problem, then the tangential problem on the same
    strips (Panagiotopoulos' or Johnson's process for dissimilar bodies), solved by the active-set method on
    ``numerics.exact_levels`` grids of finest / 2^k strips. Every quantity carries a convergence certificate
    (``stats["certificates"]``, :mod:`femcheck.cect.refinement`) and is reported as its certificate value
    (Richardson's extrapolation when the grids are in the asymptotic range, else the finest grid). Fields are
    the finest grid's."""
    p = scene.params
    h = _hertz(p)
    kind = problem_type(p)
    mu, kappa = p["friction.mu"], _kappa(p)

    def solve(n: int):
        if progress:
            progress(f"exact: {n} strips")
        sol = solve_line_friction(lambda x: x**2 / (2.0 * p["geometry.radius"]), h.modulus, p["load.per_length"],
                                  p["numerics.exact_domain"] * h.half_width, n, mu, xi=p.get("kinematics.xi"),
                                  tangential_per_length=p.get("load.tangential_per_length"), kappa=kappa,
                                  speed=p["kinematics.speed"], tol=p["numerics.exact_tol"],
                                  max_iter=p["numerics.exact_max_iter"], process=p["numerics.exact_process"])
        t = sol.tangential
        pressure = sol.normal.pressure
        left, right = adhesion_zone(t.x, pressure, t.traction, t.adhesion, mu)
        q = {"half_width": half_width(t.x, pressure), "p_max": float(pressure.max()), "total_force": sol.normal.load}
        if kind == "rolling":
            q.update(creep_force_x=t.tangential_force, adhesion_length=right - left,
                     adhesion_fraction=(right - left) / (2.0 * q["half_width"]))
        else:
            q.update(shift=t.shift, stick_half_width=0.5 * (right - left))
        return q, sol

    imposed = ("total_force",)
    ref = refine(solve, grids(p["numerics.exact_elements"], p["numerics.exact_levels"], "numerics.exact_elements"),
                 imposed=imposed, expected_order={"p_max": None, "half_width": None})
    sol = ref.finest
    n, t = sol.normal, sol.tangential
    fields = {"x": t.x, "pressure": n.pressure, "traction": t.traction, "adhesion": t.adhesion.astype(float),
              "slip": t.slip}
    if kind == "rolling":
        fields.update(slip_velocity=t.slip_velocity, power_density=t.power_density)
    stats = {"problem": kind, "iterations": t.iterations, "residual": t.residual,
             "normal_iterations": n.iterations, "normal_residual": n.residual, "n_elements": t.x.size,
             "dx": t.dx, "contact_cells": int(t.contact.sum()), "adhesion_cells": int(t.adhesion.sum()),
             "coupling_kappa": kappa, "process": sol.process, "outer_iterations": sol.outer_iterations,
             "solver": "active set (dense LU)", "tangential_force": t.tangential_force,
             "time_tangential_s": t.time_s, **ref.stats()}
    # a zone resolved by fewer than 4 strips makes its length and the shift O(1)-inaccurate: say so
    slip_cells = int(t.contact.sum() - t.adhesion.sum())
    zone = ("slip", slip_cells) if kind == "shift" else ("adhesion", int(t.adhesion.sum()))
    if 0 < zone[1] < 4 or (kind == "shift" and zone[1] == 0):
        stats["resolution_warning"] = (f"the {zone[0]} zone spans {zone[1]} strips on the finest grid: refine "
                                       "numerics.exact_elements for its length" +
                                       (" and the shift" if kind == "shift" else ""))
    if kind == "shift":
        stats.update(rigid_shift=t.rigid_shift, datum=t.datum)
    else:
        stats["frictional_power"] = float(t.dx * t.power_density.sum())   # W/m per unit length
    return ModelResult("exact", quantities=dict(ref.values), stats=stats, fields=fields)


def analytic(scene: Scene, progress=None) -> ModelResult:
    """Carter (rolling) or 2D Cattaneo (shift) closed form, for quasi-identical bodies."""
    p = scene.params
    h = _hertz(p)
    mu = p["friction.mu"]
    x = np.linspace(-1.25 * h.half_width, 1.25 * h.half_width, 1001)
    q = _common(h)
    if problem_type(p) == "rolling":
        beta = abs(_kappa(p)) * h.modulus
        if beta > QUASI_IDENTICAL_TOL:
            return ModelResult("analytic", "skipped", error=f"Carter's solution assumes quasi-identical bodies; "
                               f"here the coupling kappa E* = {beta:.3g} (use the exact model)")
        c = carter.carter_rolling(h.load, h.half_width, h.modulus, mu, p["kinematics.xi"])
        q.update(creep_force_x=c.creep_force, adhesion_length=c.adhesion_length,
                 adhesion_fraction=c.adhesion_fraction)
        fields = {"x": x, "pressure": c.pressure(x), "traction": c.traction(x), "slip": c.slip(x)}
        stats = {"problem": "rolling", "normalized_creepage": c.normalized_creepage, "E_star": h.modulus}
    else:
        beta = abs(_kappa(p)) * h.modulus
        if beta > QUASI_IDENTICAL_TOL:
            # with dissimilar bodies the tangential traction tilts the pressure (Panagiotopoulos' process, the
            # exact and fem default): for a rigid cylinder on steel the micro-slip shift falls to 0.30 of
            # Cattaneo's, which holds only if that action is neglected (Johnson's process)
            return ModelResult("analytic", "skipped", error=f"2D Cattaneo assumes quasi-identical bodies (or "
                               f"Johnson's process); here the coupling kappa E* = {beta:.3g} (use the exact model)")
        c = carter.cattaneo_line(h.load, h.half_width, h.modulus, mu, p["load.tangential_per_length"])
        q.update(shift=c.shift, stick_half_width=c.stick_half_width)
        fields = {"x": x, "pressure": c.pressure(x), "traction": c.traction(x)}
        stats = {"problem": "shift", "E_star": h.modulus}
    return ModelResult("analytic", quantities=q, stats=stats, fields=fields)


def full_slip(scene: Scene, progress=None) -> ModelResult:
    """Full slip (rolling only): the surfaces are taken rigid tangentially, so every point slips with the
    rigid creepage and q = -mu p sgn(xi); F'_x = -mu W' sgn(xi), no adhesion."""
    p = scene.params
    if problem_type(p) != "rolling":
        return ModelResult("full_slip", "skipped", error="full slip applies to steady rolling only, not to a shift")
    h = _hertz(p)
    xi, mu = p["kinematics.xi"], p["friction.mu"]
    x = np.linspace(-1.25 * h.half_width, 1.25 * h.half_width, 1001)
    pr = h.pressure(x)
    q = {**_common(h), "creep_force_x": float(-np.sign(xi) * mu * h.load), "adhesion_length": 0.0,
         "adhesion_fraction": 0.0}
    fields = {"x": x, "pressure": pr, "traction": -np.sign(xi) * mu * pr}
    return ModelResult("full_slip", quantities=q, stats={"problem": "rolling"}, fields=fields)


def _simplified(name: str, scene: Scene) -> ModelResult | tuple:
    p = scene.params
    if problem_type(p) != "rolling":
        return ModelResult(name, "skipped", error=f"{name} applies to steady rolling only, not to a shift")
    return _hertz(p), p["kinematics.xi"], p["friction.mu"]


def linear(scene: Scene, progress=None) -> ModelResult:
    """Kalker's linear theory in 2D (no slip): F'_x = -(pi a E*/2) xi, unbounded by friction."""
    got = _simplified("linear", scene)
    if isinstance(got, ModelResult):
        return got
    h, xi, _ = got
    q = {**_common(h), "creep_force_x": float(linear_line(h.half_width, h.modulus, xi)), "adhesion_length":
         2.0 * h.half_width, "adhesion_fraction": 1.0}
    return ModelResult("linear", quantities=q, stats={"problem": "rolling", "creep_coefficient":
                                                      0.5 * np.pi * h.half_width * h.modulus})


def fastsim(scene: Scene, progress=None) -> ModelResult:
    """2D FASTSIM: springs of flexibility L = 4a/(pi E*) (matching linear theory), traction bound mu p."""
    got = _simplified("fastsim", scene)
    if isinstance(got, ModelResult):
        return got
    h, xi, mu = got
    r = fastsim_line(h.load, h.half_width, h.modulus, mu, xi)
    x = np.linspace(-1.25 * h.half_width, 1.25 * h.half_width, 1001)
    q = {**_common(h), "creep_force_x": r.creep_force_x, "adhesion_length": r.adhesion_length,
         "adhesion_fraction": r.adhesion_fraction}
    fields = {"x": x, "pressure": h.pressure(x), "traction": r.traction(x, h.half_width, h.p_max, mu, xi)}
    return ModelResult("fastsim", quantities=q, stats={"problem": "rolling", "flexibility": r.flexibility,
                                                       "crossing": r.crossing}, fields=fields)


def fem(scene: Scene, progress=None) -> ModelResult:
    """2D plane-strain FE reference with Coulomb friction (:mod:`femcheck.fem.friction_line`): Cattaneo shift
    under load control or steady rolling in the Eulerian contact frame, Richardson over mesh levels."""
    return friction_line.model(scene.params, progress)


MODELS: dict[str, Callable[..., ModelResult]] = {"exact": exact, "analytic": analytic, "linear": linear,
                                                 "fastsim": fastsim, "full_slip": full_slip, "fem": fem}


def load_of(scene: Scene) -> float:
    """Applied normal load (N/m) against which every model's ``total_force`` is checked."""
    return scene["load.per_length"]


def profile_scale(scene: Scene) -> float:
    return _hertz(scene.params).half_width


def saturation_creepage(params: dict[str, Any]) -> float:
    """|xi| = 2 mu p0 / E* at which the contact saturates (Carter, xi* = 1)."""
    h = _hertz(params)
    return 2.0 * params["friction.mu"] * h.p_max / h.modulus


def stress_cases(scene: Scene) -> list:
    """Extremes: friction 0.01-2, creepage from 1e-6 of saturation through 0.99, 1.0, 1.01 and 100x
    saturation (rolling) or Q'/(mu W') from 1e-6 to 0.9999 (shift), nu -> 0.4999, a rigid cylinder
    (dissimilar bodies, Panagiotopoulos' process), loads over six decades down to 1e-6 of the scene's.
    Expected "inaccurate" cases (resolution, not instability): Q'/(mu W') <= 1e-3, whose slip zone
    a (1 - sqrt(1 - Q'/(mu W'))) is thinner than one strip, and 0.99 of saturation, whose adhesion zone is
    four strips long."""
    from ..result import StressCase

    p = scene.params
    shift = problem_type(p) == "shift"
    ratio = p["load.tangential_per_length"] / (p["friction.mu"] * p["load.per_length"]) if shift else 0.0
    cases = []
    for mu in (0.01, 1.0, 2.0):
        # shift: keep Q'/(mu W') of the scene, so the case stays admissible and tests friction alone
        over = {"friction.mu": mu, **({"load.tangential_per_length": ratio * mu * p["load.per_length"]}
                                      if shift else {})}
        cases.append(StressCase(f"mu={mu:g}", over))
    if not shift:
        sat = saturation_creepage(p)
        for f in (1e-6, 1e-3, 0.99, 1.0, 1.01, 100.0):
            xi = float(np.sign(p["kinematics.xi"]) or 1.0) * min(f * sat, 0.1)
            cases.append(StressCase(f"xi={f:g} x saturation", {"kinematics.xi": xi}))
        cases.append(StressCase("xi=0", {"kinematics.xi": 0.0}))
        cases.append(StressCase("xi<0", {"kinematics.xi": -p["kinematics.xi"]}))
    else:
        limit = p["friction.mu"] * p["load.per_length"]
        for f in (1e-6, 1e-3, 0.99, 0.9999):
            cases.append(StressCase(f"Q'={f:g} mu W'", {"load.tangential_per_length": f * limit}))
    for nu in (0.0, 0.45, 0.4999):
        cases.append(StressCase(f"nu={nu:g}", {"materials.cylinder.nu": nu, "materials.block.nu": nu}))
    cases.append(StressCase("rigid cylinder", {"materials.cylinder.rigid": True}))
    for k in (2, 4, 6):
        over = {"load.per_length": p["load.per_length"] * 10.0**-k}
        if shift:
            over["load.tangential_per_length"] = p["load.tangential_per_length"] * 10.0**-k
        cases.append(StressCase(f"load x 1e-{k}", over))
    return cases


def bench_sweeps(scene: Scene) -> dict[str, list[dict[str, Any]]]:
    """Exact solver on one grid (no refinement: the sweep measures a single grid's cost and error): strip counts
    (multiples of 10, so the Hertz edges stay on cell boundaries with the default domain 1.25 a_H). The dense
    active-set solve is O(n^3) per iteration: 3200 strips take seconds."""
    return {"exact": [{"numerics.exact_elements": n, "numerics.exact_levels": 1}
                      for n in (50, 100, 200, 400, 800, 1600, 3200)]}
