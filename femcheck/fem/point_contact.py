"""3D FE reference for point (elliptical) contact: a rigid analytic indenter on a quarter block, P1 tetrahedra,
primal-dual active set with AMG-CG solves, several mesh levels and Richardson extrapolation.

Two elastic bodies in frictionless contact are replaced by a rigid indenter with their combined gap on one
elastic block of modulus E*(1 - nu^2) and Poisson's ratio nu, so that its contact modulus is E*. In half-space
theory the normal contact depends on E* only (Johnson 1985 §4.2; with the Dundurs coupling of dissimilar
bodies neglected, as Hertz does), so the comparison with Hertz and the BEM is like with like; stresses
inside the FE block are those of this equivalent body.

Mesh levels form one family: every length of the sizing (contact size, grading, cap) is divided by the same
ratio per level (``numerics.fem_ratio``, 2 by default), so
Richardson's geometric-similarity assumption holds. The block is ``block`` Hertz semi-axes (x) on each side
and deep, clamped at the bottom, with symmetry planes x = 0 and y = 0; the finite size is measured by one extra
solve of the coarsest level on a block twice as large.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from ..analytic import hertz
from ..errors import InputError
from ..geometry import profiles
from ..materials import Elastic, effective_modulus
from ..qoi import symmetric_contact
from ..result import ModelResult
from ..solvers.convergence import certificate_stats, certify_levels
from . import export
from ..meshes.block import BlockSpec, TetMesh
from .quarter_block import solve_quarter

Gap = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class FEMPointSettings:
    """Element sizes in the short Hertz semi-axis, the block and the size cap in the long one. Level k
    (0 = coarsest) has contact element size h_contact r^-k inside the zone of ``contact_zone`` semi-axes,
    grading ``grading`` r^-k and cap ``h_max`` r^-k (r = ``ratio``); the block is ``block`` long semi-axes on
    each side."""

    levels: int = 3
    ratio: float = 2.0
    h_contact: float = 0.125
    grading: float = 0.25
    h_max: float = 2.0
    contact_zone: float = 1.3
    block: float = 20.0
    order: int = 1
    cg_tol: float = 1e-10
    contact_tol: float = 1e-8
    finite_size_check: bool = True
    method: str = "active_set"
    solver: str = "auto"
    penalty_factor: float = 1e3


@dataclass
class FEMPointLevel:
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
    active_nodes: int
    iterations: int
    cg_iterations: list[int]
    residual: float
    mesh_digest: str
    solver: str
    penetration: float
    time_s: float
    times: dict[str, float]
    x: np.ndarray          # contact-face nodes on the x axis (m) and their pressures (Pa), for profiles
    p: np.ndarray
    mesh: TetMesh | None = None
    pressure_nodes: np.ndarray | None = None    # (x, y, p) of every candidate node
    u_nodes: np.ndarray | None = None           # (3, N) displacement of every node (m)
    pressure_all: np.ndarray | None = None      # (N,) contact pressure at every node (Pa), 0 off the patch
    std: dict[str, float] | None = None         # standard errors of the fitted quantities (femcheck.qoi)


def solve_level(gap: Gap, block: Elastic, force: float, ax: float, ay: float, level: int, s: FEMPointSettings,
                block_scale: float = 1.0) -> FEMPointLevel:
    """One mesh level. ``gap(x, y)`` initial gap (m), ``block`` the equivalent elastic body, ``force`` the
    total load (N; the quarter model carries a quarter), ``ax``, ``ay`` Hertz semi-axes (m) for sizing."""
    f = s.ratio**-level
    big = max(ax, ay)
    L = s.block * big * block_scale
    zx, zy = s.contact_zone * ax, s.contact_zone * ay
    # an elongated patch gets a box-shaped fine zone: the ellipse's scaled distance would grade far too slowly
    # along its long axis
    zone = "ellipse" if big <= 2.0 * min(ax, ay) else "box"
    spec = BlockSpec(L, L, L, zx, zy, s.h_contact * min(ax, ay) * f, s.grading * f, s.h_max * big * f, zone)
    c = solve_quarter(spec, gap, block, 0.25 * force,
                      candidates=lambda x, y: (x / zx) ** 2 + (y / zy) ** 2 <= 1.0,
                      initial=lambda x, y: (x / ax) ** 2 + (y / ay) ** 2 < 1.0,
                      rim=lambda x, y: (x / zx) ** 2 + (y / zy) ** 2 > 0.9, cg_tol=s.cg_tol, contact_tol=s.contact_tol,
                      method=s.method, solver=s.solver, penalty_factor=s.penalty_factor)
    # Nodal reactions of P1 tetrahedra scatter node to node on an unstructured face (+-3 % rms at a/16), so the
    # peak and the semi-axes come from local fits that average over many nodes without assuming the field's
    # shape (femcheck.qoi.symmetric_contact: even quartic about the centre, power-law edges with the exponent
    # fitted); the largest nodal value is kept in the stats.
    xc, yc = c.xc, c.yc
    fit = symmetric_contact(xc, yc, c.p)
    axis = np.flatnonzero(np.abs(yc) < 1e-9 * L)
    order = np.argsort(xc[axis])
    return FEMPointLevel(h=s.h_contact * min(ax, ay) * f, p_max=fit["p_max"], semi_axis_x=fit["semi_axis_x"],
                         semi_axis_y=fit["semi_axis_y"], p_max_nodal=float(c.p.max()), approach=c.approach,
                         total_force=4.0 * float(c.lam.sum()), n_nodes=c.mesh.n_nodes, n_dofs=c.n_dofs,
                         n_elements=int(c.mesh.tets.shape[1]), active_nodes=c.active_nodes,
                         iterations=c.iterations, cg_iterations=c.cg_iterations, residual=c.residual,
                         mesh_digest=spec.digest(), solver=c.solver, penetration=c.penetration, time_s=c.time_s,
                         times=c.times,
                         x=xc[axis][order], p=c.p[axis][order], mesh=c.mesh,
                         pressure_nodes=np.stack([xc, yc, c.p]), u_nodes=c.u_nodes, pressure_all=c.pressure_all,
                         std={k: v for k, v in fit.items() if k.endswith("_std")})


QUANTITIES = ("p_max", "semi_axis_x", "semi_axis_y")


# The element size follows the short semi-axis over the whole patch: at b/a = 40 (seed 000's roller) the a/8
# level has about 50k nodes; beyond b/a = 100 even the coarsest level would not fit the budget.
MAX_ASPECT = 100.0


def settings(params: dict[str, Any]) -> FEMPointSettings:
    return FEMPointSettings(levels=params["numerics.fem_levels"], ratio=params.get("numerics.fem_ratio", 2.0),
                            h_contact=params["numerics.fem_h_contact"],
                            grading=params["numerics.fem_grading"], h_max=params["numerics.fem_h_max"],
                            contact_zone=params["numerics.fem_contact_zone"], block=params["numerics.fem_block"],
                            finite_size_check=params["numerics.fem_finite_size_check"],
                            method=params["numerics.fem_method"], solver=params["numerics.fem_solver"],
                            penalty_factor=params["numerics.fem_penalty"])


def _body(params: dict[str, Any], name: str) -> Elastic:
    rigid = bool(params.get(f"materials.{name}.rigid", False))
    return Elastic(float(params.get(f"materials.{name}.E", 1.0)), float(params.get(f"materials.{name}.nu", 0.0)),
                   rigid)


def equivalent_pair(body1: Elastic, body2: Elastic) -> Elastic:
    """The one elastic body that stands for a frictionless pair: E*(1 - nu^2) with the Poisson's ratio of
    ``body2`` (of ``body1`` when body2 is rigid), so that its contact modulus equals the pair's E*."""
    e_star = effective_modulus(body1, body2)
    nu = body1.nu if body2.rigid else body2.nu
    return Elastic(e_star * (1.0 - nu * nu), nu)


def equivalent_block(params: dict[str, Any]) -> Elastic:
    """:func:`equivalent_pair` of the ball (body1) and the flat (body2)."""
    return equivalent_pair(_body(params, "body1"), _body(params, "body2"))


def indenter_setup(params: dict[str, Any], name: str) -> tuple[Gap, Elastic, float, float, float]:
    """(gap, equivalent block, load (N), Hertz semi-axes a_x, a_y (m), which size the meshes) of a point-contact
    scene for the FE model ``name``; refuses contact ellipses beyond the aspect the meshes can resolve."""
    if "geometry.radius" in params:
        rx = ry = params["geometry.radius"]
    else:
        rx, ry = params["geometry.Rx"], params["geometry.Ry"]
    gap = profiles.sphere(rx) if params.get("geometry.profile") == "sphere" else profiles.paraboloid(rx, ry)
    block = equivalent_block(params)
    load = params["load.normal"]
    h = hertz.elliptic_contact(load, rx, ry, block.E / (1.0 - block.nu**2))
    ax, ay = h.semi_axis_x, h.semi_axis_y
    if not 1.0 / MAX_ASPECT <= ay / ax <= MAX_ASPECT:
        raise InputError("models.run", f"{name} needs a contact ellipse with b/a in [{1 / MAX_ASPECT:g}, "
                         f"{MAX_ASPECT:g}]; this one has {ay / ax:.3g}; allowed here: analytic, bem")
    return gap, block, load, ax, ay


def model(params: dict[str, Any], progress=None) -> ModelResult:
    """The ``fem`` model of the point-contact scenes from their flat parameters: per quantity a convergence
    certificate over the ``numerics.fem_levels`` levels (stats["certificates"]: Richardson-extrapolated value
    when the levels are in the asymptotic range, else the finest level with a two-level error bound); stats
    carry every level and the finite-size check."""
    gap, block, load, ax, ay = indenter_setup(params, "fem")
    s = settings(params)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FEM level {k + 1}/{s.levels}")
        levels.append(solve_level(gap, block, load, ax, ay, k, s))
    fine = levels[-1]
    finest = {q: getattr(fine, q) for q in QUANTITIES}
    stats: dict[str, Any] = {
        "method": s.method, "element": f"P{s.order} tetrahedra",
        "solver": "auto: sparse LU up to 3000 DOFs, pyamg SA (rigid-body modes) + CG above" if s.solver == "auto"
        else s.solver,
        "cg_tol": s.cg_tol, "contact_tol": s.contact_tol, "finest": finest,
        "equivalent_block": {"E": block.E, "nu": block.nu},
        "block": {"side": s.block * max(ax, ay), "depth": s.block * max(ax, ay), "model": "quarter"},
        "levels": [{"h": lv.h, "h_over_a": lv.h / min(ax, ay), "n_nodes": lv.n_nodes, "n_dofs": lv.n_dofs,
                    "n_elements": lv.n_elements, "mesh_digest": lv.mesh_digest,
                    **{q: getattr(lv, q) for q in QUANTITIES},
                    "contact_area": float(np.pi * lv.semi_axis_x * lv.semi_axis_y), **(lv.std or {}),
                    "p_max_nodal": lv.p_max_nodal, "approach": lv.approach, "active_nodes": lv.active_nodes,
                    "iterations": lv.iterations, "cg_iterations": lv.cg_iterations, "residual": lv.residual,
                    "linear_solver": lv.solver, "penetration": lv.penetration,
                    "total_force": lv.total_force, "time_s": lv.time_s, **lv.times} for lv in levels],
    }
    certs = certify_levels(stats["levels"], QUANTITIES + ("contact_area",))
    stats.update(certificate_stats(certs))
    q = {k: c.value for k, c in certs.items()}
    if s.finite_size_check:
        if progress:
            progress("FEM finite-size check (block x 2)")
        # on the second level: the coarsest is too coarse to tell the block size from mesh scatter (at a/4 the
        # two meshes differed by 1 % on p_max; at a/16 blocks of 20a, 40a and 80a agree within 0.1 %)
        k = min(1, s.levels - 1)
        big = solve_level(gap, block, load, ax, ay, k, s, block_scale=2.0)
        stats["finite_size"] = {qn: getattr(big, qn) / getattr(levels[k], qn) - 1.0 for qn in QUANTITIES}
        stats["finite_size"].update({"level": k, "block_side": 2 * s.block * max(ax, ay), "time_s": big.time_s})
    q["total_force"] = fine.total_force
    fields = {"x": fine.x, "pressure": fine.p, "pressure_nodes": fine.pressure_nodes}
    fields.update(export.report_views(fine.mesh, fine.u_nodes, fine.pressure_all, block, f"point-{fine.mesh_digest}",
                                      (2.0 * ax, 2.0 * ay, 2.0 * min(ax, ay)), stats))
    return ModelResult("fem", quantities=q, stats=stats, fields=fields)
