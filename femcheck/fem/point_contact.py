"""3D FE reference for point (elliptical) contact: a rigid analytic indenter on a quarter block, P1 tetrahedra,
primal-dual active set with AMG-CG solves, several mesh levels and Richardson extrapolation.

Two elastic bodies in frictionless contact are replaced by a rigid indenter with their combined gap on one
elastic block of modulus E*(1 - nu^2) and Poisson's ratio nu, so that its contact modulus is E*. In half-space
theory the normal contact depends on E* only (Johnson 1985 §4.2; with the Dundurs coupling of dissimilar
bodies neglected, as Hertz does), so the comparison with Hertz and the BEM is like with like; stresses
inside the FE block are those of this equivalent body.

Mesh levels form one family: every length of the sizing (contact size, grading, cap) halves per level, so
Richardson's geometric-similarity assumption holds. The block is ``block`` Hertz semi-axes (x) on each side
and deep, clamped at the bottom, with symmetry planes x = 0 and y = 0; the finite size is measured by one extra
solve of the coarsest level on a block twice as large.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from ..analytic import hertz
from ..errors import InputError
from ..geometry import profiles
from ..materials import Elastic, effective_modulus
from ..qoi import ellipse_fit
from ..result import ModelResult
from .convergence import Extrapolation, richardson
from .elasticity3d import AMGElasticity, make_solid
from .mesh3d import BlockSpec, TetMesh, block_quarter
from .rigid_contact import active_set

Gap = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class FEMPointSettings:
    """Lengths in Hertz semi-axes a_x. Level k (0 = coarsest) has contact element size h_contact 2^-k inside
    the zone of ``contact_zone`` semi-axes, grading ``grading`` 2^-k and cap ``h_max`` 2^-k."""

    levels: int = 3
    h_contact: float = 0.125
    grading: float = 0.25
    h_max: float = 2.0
    contact_zone: float = 1.3
    block: float = 20.0
    order: int = 1
    cg_tol: float = 1e-10
    contact_tol: float = 1e-8
    finite_size_check: bool = True


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
    time_s: float
    times: dict[str, float]
    x: np.ndarray          # contact-face nodes on the x axis (m) and their pressures (Pa), for profiles
    p: np.ndarray
    mesh: TetMesh | None = None
    pressure_nodes: np.ndarray | None = None    # (x, y, p) of every candidate node


def tributary_areas(mesh: TetMesh) -> np.ndarray:
    """w_i = int phi_i dA over the face z = 0 (m^2) for P1: a third of each adjacent triangle's area."""
    P, tri = mesh.points, mesh.top
    e1, e2 = P[:, tri[1]] - P[:, tri[0]], P[:, tri[2]] - P[:, tri[0]]
    area = 0.5 * np.linalg.norm(np.cross(e1.T, e2.T), axis=1)
    w = np.zeros(P.shape[1])
    np.add.at(w, tri.ravel(), np.tile(area / 3.0, 3))
    return w


def solve_level(gap: Gap, block: Elastic, force: float, ax: float, ay: float, level: int, s: FEMPointSettings,
                block_scale: float = 1.0, threads: int = 1) -> FEMPointLevel:
    """One mesh level. ``gap(x, y)`` initial gap (m), ``block`` the equivalent elastic body, ``force`` the
    total load (N; the quarter model carries a quarter), ``ax``, ``ay`` Hertz semi-axes (m) for sizing."""
    t0 = time.perf_counter()
    times = {}
    f = 2.0**-level
    L = s.block * ax * block_scale
    spec = BlockSpec(L, L, L, s.contact_zone * ax, s.contact_zone * ay, s.h_contact * ax * f, s.grading * f,
                     s.h_max * ax * f)
    mesh = block_quarter(spec, threads)
    times["mesh_s"] = time.perf_counter() - t0
    t = time.perf_counter()
    solid = make_solid(mesh, block, s.order)
    times["assembly_s"] = time.perf_counter() - t
    X = solid.basis.doflocs
    tiny = 1e-9 * L
    fixed = X[2] < -L + tiny                          # clamped bottom
    fixed[0::3] |= X[0, 0::3] < tiny                  # symmetry x = 0: u_x = 0
    fixed[1::3] |= X[1, 1::3] < tiny                  # symmetry y = 0: u_y = 0
    free = np.flatnonzero(~fixed)
    t = time.perf_counter()
    solver = AMGElasticity(solid, free, tol=s.cg_tol)
    times["amg_setup_s"] = time.perf_counter() - t
    position = np.full(solid.n_dofs, -1)
    position[free] = np.arange(free.size)
    top = np.unique(mesh.top)
    xt, yt = mesh.points[0, top], mesh.points[1, top]
    cand = top[(xt / (s.contact_zone * ax)) ** 2 + (yt / (s.contact_zone * ay)) ** 2 <= 1.0]
    xc, yc = mesh.points[0, cand], mesh.points[1, cand]
    h = gap(xc, yc)
    t = time.perf_counter()
    sol = active_set(solver, position[3 * cand + 2], h, 0.25 * force, (xc / ax) ** 2 + (yc / ay) ** 2 < 1.0,
                     tol=s.contact_tol)
    times["contact_s"] = time.perf_counter() - t
    rim = (xc / (s.contact_zone * ax)) ** 2 + (yc / (s.contact_zone * ay)) ** 2 > 0.9
    if sol.active[rim].any():
        raise RuntimeError("FEM contact reached the edge of the candidate zone; raise numerics.fem_contact_zone")
    p = sol.lam / tributary_areas(mesh)[cand]
    # Nodal reactions of P1 tetrahedra scatter node to node on an unstructured face (+-2 % at a/16), so the
    # peak and the semi-axes come from a least-squares fit of p^2 (exact for Hertz) over the quarter mirrored
    # to the full patch; the largest nodal value is kept in the stats.
    XX, YY, PP = (np.concatenate([xc, -xc, xc, -xc]), np.concatenate([yc, yc, -yc, -yc]), np.tile(p, 4))
    fit = ellipse_fit(XX, YY, PP)
    axis = np.flatnonzero(np.abs(yc) < 1e-9 * L)
    order = np.argsort(xc[axis])
    return FEMPointLevel(h=s.h_contact * ax * f, p_max=fit["peak"], semi_axis_x=fit["semi_axis_x"],
                         semi_axis_y=fit["semi_axis_y"], p_max_nodal=float(p.max()), approach=sol.delta,
                         total_force=4.0 * float(sol.lam.sum()), n_nodes=mesh.n_nodes, n_dofs=int(free.size),
                         n_elements=int(mesh.tets.shape[1]), active_nodes=int(sol.active.sum()),
                         iterations=sol.iterations, cg_iterations=sol.cg_iterations, residual=sol.residual,
                         mesh_digest=spec.digest(), time_s=time.perf_counter() - t0, times=times,
                         x=xc[axis][order], p=p[axis][order], mesh=mesh,
                         pressure_nodes=np.stack([xc, yc, p]))


QUANTITIES = ("p_max", "semi_axis_x", "semi_axis_y")


def extrapolate(levels: list[FEMPointLevel], quantity: str) -> Extrapolation:
    return richardson([lv.h for lv in levels], [getattr(lv, quantity) for lv in levels])


MAX_ASPECT = 4.0     # the quarter block is sized on a_x; beyond this the fine zone would be a strip


def settings(params: dict[str, Any]) -> FEMPointSettings:
    return FEMPointSettings(levels=params["numerics.fem_levels"], h_contact=params["numerics.fem_h_contact"],
                            grading=params["numerics.fem_grading"], h_max=params["numerics.fem_h_max"],
                            contact_zone=params["numerics.fem_contact_zone"], block=params["numerics.fem_block"],
                            finite_size_check=params["numerics.fem_finite_size_check"])


def _body(params: dict[str, Any], name: str) -> Elastic:
    rigid = bool(params.get(f"materials.{name}.rigid", False))
    return Elastic(float(params.get(f"materials.{name}.E", 1.0)), float(params.get(f"materials.{name}.nu", 0.0)),
                   rigid)


def equivalent_block(params: dict[str, Any]) -> Elastic:
    """The one elastic body of the FE model: E*(1 - nu^2) with the Poisson's ratio of the flat (body2), or of
    the ball when the flat is rigid, so that its contact modulus equals the pair's E*."""
    e_star = effective_modulus(_body(params, "body1"), _body(params, "body2"))
    nu = params["materials.body1.nu"] if params.get("materials.body2.rigid", False) else params["materials.body2.nu"]
    return Elastic(e_star * (1.0 - nu * nu), nu)


def model(params: dict[str, Any], progress=None) -> ModelResult:
    """The ``fem`` model of the point-contact scenes from their flat parameters: quantities Richardson-
    extrapolated over ``numerics.fem_levels`` >= 3 levels (finest values otherwise); stats carry every level,
    the error estimates and the finite-size check."""
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
        raise InputError("models.run", f"fem needs a contact ellipse with b/a in [{1 / MAX_ASPECT:g}, "
                         f"{MAX_ASPECT:g}]; this one has {ay / ax:.3g}; allowed here: analytic, bem")
    s = settings(params)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FEM level {k + 1}/{s.levels}")
        levels.append(solve_level(gap, block, load, ax, ay, k, s))
    fine = levels[-1]
    finest = {q: getattr(fine, q) for q in QUANTITIES}
    stats: dict[str, Any] = {
        "method": "active_set", "element": f"P{s.order} tetrahedra", "solver": "pyamg SA (rigid-body modes) + CG",
        "cg_tol": s.cg_tol, "contact_tol": s.contact_tol, "finest": finest,
        "equivalent_block": {"E": block.E, "nu": block.nu},
        "block": {"side": s.block * ax, "depth": s.block * ax, "model": "quarter"},
        "levels": [{"h": lv.h, "h_over_a": lv.h / ax, "n_nodes": lv.n_nodes, "n_dofs": lv.n_dofs,
                    "n_elements": lv.n_elements, "mesh_digest": lv.mesh_digest,
                    **{q: getattr(lv, q) for q in QUANTITIES},
                    "p_max_nodal": lv.p_max_nodal, "approach": lv.approach, "active_nodes": lv.active_nodes,
                    "iterations": lv.iterations, "cg_iterations": lv.cg_iterations, "residual": lv.residual,
                    "total_force": lv.total_force, "time_s": lv.time_s, **lv.times} for lv in levels],
    }
    q = dict(finest)
    if s.levels >= 3:
        rich = {name: extrapolate(levels, name) for name in QUANTITIES}
        stats["richardson"] = {k: v.as_dict() for k, v in rich.items()}
        q = {k: v.value for k, v in rich.items()}
    if s.finite_size_check:
        if progress:
            progress("FEM finite-size check (block x 2)")
        # on the second level: the coarsest is too coarse to tell the block size from mesh scatter (at a/4 the
        # two meshes differed by 1 % on p_max; at a/16 blocks of 20a, 40a and 80a agree within 0.1 %)
        k = min(1, s.levels - 1)
        big = solve_level(gap, block, load, ax, ay, k, s, block_scale=2.0)
        stats["finite_size"] = {qn: getattr(big, qn) / getattr(levels[k], qn) - 1.0 for qn in QUANTITIES}
        stats["finite_size"].update({"level": k, "block_side": 2 * s.block * ax, "time_s": big.time_s})
    q["contact_area"] = float(np.pi * q["semi_axis_x"] * q["semi_axis_y"])
    q["total_force"] = fine.total_force
    fields = {"x": fine.x, "pressure": fine.p, "pressure_nodes": fine.pressure_nodes}
    return ModelResult("fem", quantities=q, stats=stats, fields=fields)
