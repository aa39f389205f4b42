"""3D FE reference for a rigid sphere pressed on a coated block (layer_contact, point scenes).

A layer (E1, nu1, thickness t) is perfectly bonded to an elastic substrate (E2, nu2), or to a rigid base (the
layer's bottom clamped, no substrate mesh). The indenter is a rigid sphere of radius R with the exact gap
g0 = R - sqrt(R^2 - r^2); frictionless, small strain, load control (the approach is the extra unknown that makes
the force equal ``load.normal``). The scene is axisymmetric, so the model is a quarter block with symmetry
planes x = 0 and y = 0, clamped at the bottom.

Mesh (:func:`femcheck.meshes.coated.coated_block_quarter`): the top face is meshed by Gmsh, refined over the
candidate zone; the layer is that surface mesh extruded through the thickness in element layers (so a layer
of t/a = 0.02 still has 2^k * ``layer_elements`` tetrahedra through it without shrinking its in-plane size),
the substrate below is meshed unstructured (HXT) on the shared interface. P1 tetrahedra, each region with its
own constants (matrices assembled per region and added), pyamg smoothed-aggregation preconditioned CG with
the rigid-body modes, and the primal-dual active set of :mod:`femcheck.solvers.rigid_indenter`.

Limits (stated, not hidden): P1 tetrahedra only, so nu <= 0.45 in both materials (locking above; the 2D model
:mod:`femcheck.fem.layered_line` has the mixed form for nu -> 0.5), and a stiff thin layer bending over a soft
substrate converges slower in P1 (shear locking of flat elements) — the levels' observed order and the
Richardson error estimate in the stats say how far the reference can be trusted in a given case.

Quantities (:func:`femcheck.qoi.symmetric_contact`, no shape assumed; P1 nodal reactions scatter node to node on
an unstructured face, so each is a local fit over many nodes): p_max, the centre value of an even quartic over
half the contact; semi-axes, power-law edges with the exponent fitted in strips along the symmetry lines. Per
quantity a convergence certificate over the levels (stats["certificates"]), as in :mod:`femcheck.fem.point_contact`.
SI units throughout.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from skfem import Basis, ElementTetP1, ElementTetP2, ElementVector, MeshTet, asm
from skfem.models.elasticity import linear_elasticity

from ..analytic import hertz, thin_layer
from ..errors import ConvergenceError, InputError
from ..materials import Elastic
from ..result import ModelResult
from ..scene import Key
from ..qoi import symmetric_contact
from ..solvers.convergence import certificate_stats, certify_levels
from ..solvers.elasticity3d import Solid, elasticity_solver
from .layered_line import materials_of
from ..meshes.coated import LAYER, SUBSTRATE, LayeredTetMesh, LayerSizing, coated_block_quarter
from .quarter_block import tributary_areas
from ..solvers.rigid_indenter import active_set

# P1 tetrahedra lock as nu -> 1/2 (elasticity.py measured the 2D displacement form drifting above 0.45).
NU_MAX_P1 = 0.45


@dataclass(frozen=True)
class FEMLayeredPointSettings:
    """Numerics, lengths in units of the reference contact radius a_ref (coarsest level; level k divides every
    length by 2^k): element size ``h_contact`` over the candidate disc of radius ``contact_zone``, growth
    ``grading``, cap ``h_max``; quarter block ``block`` a_ref on each side and deep (deeper than 2 t)."""

    levels: int = 3
    h_contact: float = 0.25
    grading: float = 0.25
    h_max: float = 2.0
    contact_zone: float = 1.3
    block: float = 20.0
    layer_elements: int = 2
    cg_tol: float = 1e-10
    contact_tol: float = 1e-8
    solver: str = "auto"


@dataclass
class LayeredPointLevel:
    h: float
    p_max: float
    semi_axis_x: float
    semi_axis_y: float
    p_max_nodal: float
    approach: float
    total_force: float
    n_nodes: int
    n_dofs: int
    n_elements: int
    layer_rows: int
    active_nodes: int
    iterations: int
    cg_iterations: list[int]
    residual: float
    solver: str
    time_s: float
    times: dict[str, float] = field(default_factory=dict)
    x: np.ndarray | None = None        # x-axis contact nodes (m) and their pressures (Pa)
    p: np.ndarray | None = None
    edge_exponent: float = 0.5         # fitted p ~ (a^2 - r^2)^alpha near the edge
    std: dict[str, float] = field(default_factory=dict)   # standard errors of the fitted quantities


def assemble_layered_solid(lm: LayeredTetMesh, materials: dict[int, Elastic], order: int = 1) -> Solid:
    """P1 or P2 (``order``) stiffness (N/m) of the coated block: sum over regions of int C_r eps(u) : eps(v) dx,
    with the quadrature exact for the order on straight tetrahedra. Shared interface nodes make the bond
    perfect."""
    elem, intorder = {1: (ElementTetP1, 1), 2: (ElementTetP2, 2)}[order]
    m = MeshTet(np.ascontiguousarray(lm.mesh.points), np.ascontiguousarray(lm.mesh.tets))
    basis = Basis(m, ElementVector(elem()), intorder=intorder)
    K = None
    for r, mat in materials.items():
        idx = np.flatnonzero(lm.region == r)
        if idx.size:
            lam, mu = mat.lame()
            Kr = asm(linear_elasticity(lam, mu), basis.with_elements(idx))
            K = Kr if K is None else K + Kr
    return Solid(basis, K.tocsr(), materials[LAYER])


def solve_level(radius: float, layer: Elastic, substrate: Elastic, thickness: float, load: float, a_ref: float,
                level: int, s: FEMLayeredPointSettings, contact_zone: float | None = None) -> LayeredPointLevel:
    """One mesh level (0 = coarsest) scaled by ``a_ref`` (m); the quarter model carries load/4. Raises
    ConvergenceError if the contact reaches the rim of the candidate zone."""
    t0 = time.perf_counter()
    times: dict[str, float] = {}
    zone = (s.contact_zone if contact_zone is None else contact_zone) * a_ref
    L = s.block * a_ref
    depth = max(L, 2.0 * thickness)
    sizing = LayerSizing(s.h_contact * a_ref, zone, s.grading, s.h_max * a_ref, s.layer_elements)
    lm = coated_block_quarter(L, depth, thickness, sizing, level, rigid_substrate=substrate.rigid)
    times["mesh_s"] = time.perf_counter() - t0
    t = time.perf_counter()
    mats = {LAYER: layer} if substrate.rigid else {LAYER: layer, SUBSTRATE: substrate}
    solid = assemble_layered_solid(lm, mats)
    times["assembly_s"] = time.perf_counter() - t
    X = solid.basis.doflocs
    tiny = 1e-9 * L
    fixed = X[2] < -lm.depth + tiny                   # clamped bottom (the layer's, on a rigid base)
    fixed[0::3] |= X[0, 0::3] < tiny                  # symmetry x = 0: u_x = 0
    fixed[1::3] |= X[1, 1::3] < tiny                  # symmetry y = 0: u_y = 0
    free = np.flatnonzero(~fixed)
    t = time.perf_counter()
    lin = elasticity_solver(solid, free, tol=s.cg_tol, kind=s.solver)
    times["solver_setup_s"] = time.perf_counter() - t
    position = np.full(solid.n_dofs, -1)
    position[free] = np.arange(free.size)
    mesh = lm.mesh
    top = np.unique(mesh.top)
    xt, yt = mesh.points[0, top], mesh.points[1, top]
    cand = top[xt**2 + yt**2 <= zone**2]
    xc, yc = mesh.points[0, cand], mesh.points[1, cand]
    r2 = xc**2 + yc**2
    w = tributary_areas(mesh)[cand]
    g0 = radius - np.sqrt(radius**2 - r2)
    t = time.perf_counter()
    sol = active_set(lin, position[3 * cand + 2], g0, 0.25 * load, r2 < a_ref**2, tol=s.contact_tol)
    times["contact_s"] = time.perf_counter() - t
    if sol.active[r2 > (0.9 * zone) ** 2].any():
        raise ConvergenceError("FEM layered point contact", sol.iterations, np.inf, s.contact_tol,
                               "contact reached the rim of the candidate zone; raise numerics.fem_contact_zone")
    p = sol.lam / w
    on_x = np.flatnonzero(np.abs(yc) < tiny)
    ox = on_x[np.argsort(xc[on_x])]
    fit = symmetric_contact(xc, yc, p)
    return LayeredPointLevel(
        h=s.h_contact * a_ref / 2**level, p_max=fit["p_max"], semi_axis_x=fit["semi_axis_x"],
        semi_axis_y=fit["semi_axis_y"], p_max_nodal=float(p.max()), approach=sol.delta,
        total_force=4.0 * float(sol.lam.sum()), n_nodes=mesh.n_nodes, n_dofs=int(free.size),
        n_elements=int(mesh.tets.shape[1]), layer_rows=lm.layer_rows, active_nodes=int(sol.active.sum()),
        iterations=sol.iterations, cg_iterations=sol.cg_iterations, residual=sol.residual,
        solver=type(lin).__name__, time_s=time.perf_counter() - t0, times=times, x=xc[ox], p=p[ox],
        edge_exponent=0.5 * (fit["exponent_x"] + fit["exponent_y"]),
        std={k: v for k, v in fit.items() if k.endswith("_std") and k != "contact_area_std"})


QUANTITIES = ("p_max", "semi_axis_x", "semi_axis_y")


def radius_guess(radius: float, layer: Elastic, substrate: Elastic, thickness: float, load: float) -> float:
    """First guess of the contact radius (m) for the pilot: Hertz of the layer and of the substrate (the
    larger), or on a rigid base the smaller of the layer's Hertz and Johnson's thin-layer radius."""
    a_layer = hertz.point_contact(load, radius, layer.E / (1.0 - layer.nu**2)).semi_axis_x
    if substrate.rigid:
        return min(a_layer, thin_layer.compressible(layer.E, layer.nu, thickness, radius, load, "circular").a)
    return max(a_layer, hertz.point_contact(load, radius, substrate.E / (1.0 - substrate.nu**2)).semi_axis_x)


def reference_radius(radius: float, layer: Elastic, substrate: Elastic, thickness: float, load: float,
                     s: FEMLayeredPointSettings, max_pilots: int = 4) -> tuple[float, list[float]]:
    """a_ref (m) for the mesh family: pilot solves on the coarsest mesh with a candidate zone of 2 a_guess,
    repeated with the measured radius until two agree within 10 %."""
    a = radius_guess(radius, layer, substrate, thickness, load)
    history = [a]
    for _ in range(max_pilots):
        try:
            lv = solve_level(radius, layer, substrate, thickness, load, a, 0, s, contact_zone=2.0)
        except ConvergenceError:
            a *= 2.0
            history.append(a)
            continue
        a_new = 0.5 * (lv.semi_axis_x + lv.semi_axis_y)
        history.append(a_new)
        if abs(a_new / a - 1.0) < 0.1:
            # the mesh family's length scale, rounded to 4 digits: the pilot's radius varies from run to run in
            # the 11th digit (iterative solves), enough to move a node and the coarse level's p_max by 1 %; a
            # rounded scale keeps every mesh reproducible (the stored reference's coarse re-solve depends on it)
            return float(f"{a_new:.4g}"), history
        a = a_new
    raise ConvergenceError("FEM layered pilot (contact radius)", max_pilots, abs(history[-1] / history[-2] - 1),
                           0.1, "the pilot radii did not settle")


FEM_SCHEMA: dict[str, Key] = {
    "numerics.fem_levels": Key("int", "-", "FEM mesh levels (>= 3 for Richardson extrapolation)", lo=1, hi=4,
                               lo_closed=True, hi_closed=True),
    "numerics.fem_h_contact": Key("float", "a_ref", "FEM element size over the contact zone, coarsest level",
                                  lo=0.005, hi=0.5, lo_closed=True, hi_closed=True),
    "numerics.fem_grading": Key("float", "-", "FEM element growth per unit distance, coarsest level", lo=0.0,
                                hi=2.0, hi_closed=True),
    "numerics.fem_h_max": Key("float", "a_ref", "largest FEM element, coarsest level", lo=0.05, hi=20.0,
                              hi_closed=True),
    "numerics.fem_contact_zone": Key("float", "a_ref", "FEM candidate contact zone / reference radius", lo=1.05,
                                     hi=3.0, hi_closed=True),
    "numerics.fem_block": Key("float", "a_ref", "FEM quarter-block side and depth / reference radius", lo=10.0,
                              hi=1000.0, lo_closed=True, hi_closed=True),
    "numerics.fem_layer_elements": Key("int", "-", "FEM element rows through the layer, coarsest level (doubled "
                                       "per level)", lo=1, hi=32, lo_closed=True, hi_closed=True),
    "numerics.fem_solver": Key("str", "-", "FEM linear solver (auto: LU up to 3000 DOFs, AMG-CG above)",
                               choices=("auto", "direct", "amg")),
}
FEM_DEFAULTS: dict[str, Any] = {
    "numerics.fem_levels": 3,
    "numerics.fem_h_contact": 0.25,
    "numerics.fem_grading": 0.25,
    "numerics.fem_h_max": 2.0,
    "numerics.fem_contact_zone": 1.3,
    "numerics.fem_block": 20.0,
    "numerics.fem_layer_elements": 2,
    "numerics.fem_solver": "auto",
}


def settings(params: dict[str, Any]) -> FEMLayeredPointSettings:
    p = {**FEM_DEFAULTS, **{k: v for k, v in params.items() if k.startswith("numerics.fem_")}}
    return FEMLayeredPointSettings(levels=int(p["numerics.fem_levels"]), h_contact=p["numerics.fem_h_contact"],
                                   grading=p["numerics.fem_grading"], h_max=p["numerics.fem_h_max"],
                                   contact_zone=p["numerics.fem_contact_zone"], block=p["numerics.fem_block"],
                                   layer_elements=int(p["numerics.fem_layer_elements"]),
                                   solver=p["numerics.fem_solver"])


def model(params: dict[str, Any], progress=None) -> ModelResult:
    """The ``fem`` model of the layered point scenes (rigid sphere on a coated block) from flat parameters:
    ``layer.E|nu|thickness``, ``materials.substrate.E|nu|rigid``, ``geometry.radius``, ``load.normal`` (N) and
    the ``numerics.fem_*`` keys of FEM_SCHEMA. Quantities p_max (Pa), semi_axis_x, semi_axis_y (m): the
    certificate's value (Richardson-extrapolated when the levels are in the asymptotic range, else the finest
    level), total_force (N, finest level)."""
    t_start = time.perf_counter()
    layer, sub, t = materials_of(params)
    for name, mat in (("layer.nu", layer), ("materials.substrate.nu", sub)):
        if not mat.rigid and mat.nu > NU_MAX_P1:
            raise InputError(name, f"{mat.nu:g} for the 3D FEM (P1 tetrahedra lock above); allowed (-1, "
                             f"{NU_MAX_P1}] (the 2D model takes nu up to 0.5)")
    R, load = float(params["geometry.radius"]), float(params["load.normal"])
    if R <= 0:
        raise InputError("geometry.radius", f"{R:g}; allowed (0, inf) m")
    if load <= 0:
        raise InputError("load.normal", f"{load:g}; allowed (0, inf) N")
    s = settings(params)
    if progress:
        progress("FEM pilot solves (contact radius)")
    a_ref, pilots = reference_radius(R, layer, sub, t, load, s)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FEM level {k + 1}/{s.levels}")
        levels.append(solve_level(R, layer, sub, t, load, a_ref, k, s))
    fine = levels[-1]
    finest = {q: getattr(fine, q) for q in QUANTITIES}
    stats: dict[str, Any] = {
        "method": "active_set", "element": "P1 tetrahedra (layer: extruded, structured through the thickness)",
        "solver": s.solver, "cg_tol": s.cg_tol, "contact_tol": s.contact_tol, "finest": finest,
        "a_ref": a_ref, "pilot_radii": pilots, "thickness_over_a": t / fine.semi_axis_x,
        "substrate": "rigid" if sub.rigid else {"E": sub.E, "nu": sub.nu},
        "block": {"side": s.block * a_ref, "depth": max(s.block * a_ref, 2.0 * t), "model": "quarter"},
        "levels": [{"h": lv.h, "h_over_a": lv.h / a_ref, "layer_rows": lv.layer_rows, "n_nodes": lv.n_nodes,
                    "n_dofs": lv.n_dofs, "n_elements": lv.n_elements,
                    **{q: getattr(lv, q) for q in QUANTITIES}, "p_max_nodal": lv.p_max_nodal,
                    "approach": lv.approach, "edge_exponent": lv.edge_exponent, **lv.std,
                    "active_nodes": lv.active_nodes, "iterations": lv.iterations,
                    "cg_iterations": lv.cg_iterations, "residual": lv.residual, "linear_solver": lv.solver,
                    "total_force": lv.total_force, "time_s": lv.time_s, **lv.times} for lv in levels],
    }
    certs = certify_levels(stats["levels"], QUANTITIES)
    stats.update(certificate_stats(certs))
    q = {k: c.value for k, c in certs.items()}
    q["total_force"] = fine.total_force
    return ModelResult("fem", time_s=time.perf_counter() - t_start, quantities=q, stats=stats,
                       fields={"x": fine.x, "pressure": fine.p})
