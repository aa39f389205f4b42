"""A rigid analytic indenter pressed on a quarter block: the solve shared by the 3D point and roller FE models.

Builds (or reads from the mesh cache) the Gmsh quarter block, assembles P1 elasticity, clamps the bottom,
puts the symmetry planes x = 0 and y = 0 on rollers, sets up one AMG hierarchy, and solves the contact with
the primal-dual active set of :mod:`femcheck.solvers.rigid_indenter` under load control. The block stands for the
two bodies with their combined modulus (see :mod:`femcheck.fem.point_contact`).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..materials import Elastic
from ..solvers.elasticity3d import elasticity_solver, make_solid
from ..meshes.block import BlockSpec, TetMesh, cached_block_quarter
from ..solvers.rigid_indenter import active_set, penalty

Gap = Callable[[np.ndarray, np.ndarray], np.ndarray]
Region = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass
class QuarterContact:
    """Solution on one mesh: candidate nodes ``cand`` with coordinates ``xc``, ``yc`` (m), pressures ``p`` (Pa)
    and forces ``lam`` (N); ``u_nodes`` (3, N) displacements (m); ``pressure_all`` (N,) nodal pressures."""

    mesh: TetMesh
    cand: np.ndarray
    xc: np.ndarray
    yc: np.ndarray
    p: np.ndarray
    lam: np.ndarray
    approach: float
    active_nodes: int
    iterations: int
    cg_iterations: list[int]
    residual: float
    n_dofs: int
    u_nodes: np.ndarray
    pressure_all: np.ndarray
    time_s: float
    times: dict[str, float] = field(default_factory=dict)
    solver: str = ""
    penetration: float = 0.0


def tributary_areas(mesh: TetMesh) -> np.ndarray:
    """w_i = int phi_i dA over the face z = 0 (m^2) for P1: a third of each adjacent triangle's area."""
    P, tri = mesh.points, mesh.top
    e1, e2 = P[:, tri[1]] - P[:, tri[0]], P[:, tri[2]] - P[:, tri[0]]
    area = 0.5 * np.linalg.norm(np.cross(e1.T, e2.T), axis=1)
    w = np.zeros(P.shape[1])
    np.add.at(w, tri.ravel(), np.tile(area / 3.0, 3))
    return w


def solve_quarter(spec: BlockSpec, gap: Gap, block: Elastic, quarter_force: float, candidates: Region,
                  initial: Region, rim: Region, cg_tol: float = 1e-10, contact_tol: float = 1e-8,
                  method: str = "active_set", solver: str = "auto", penalty_factor: float = 1e3) -> QuarterContact:
    """Contact of the indenter with initial gap ``gap(x, y)`` (m; +inf where it has no surface) on the quarter
    block ``spec`` carrying ``quarter_force`` (N). ``candidates``: top-face nodes that may touch; ``initial``:
    the starting active set; ``rim``: candidates that must stay open (contact there means the candidate zone
    is too small, raised as an error rather than a truncated answer). ``method``: "active_set" or "penalty"
    (kappa_i = penalty_factor * E' w_i / h, E' = E/(1 - nu^2), w_i the tributary area, h the contact element
    size); ``solver``: "auto", "direct" or "amg" (:func:`femcheck.solvers.elasticity3d.elasticity_solver`)."""
    t0 = time.perf_counter()
    times = {}
    mesh = cached_block_quarter(spec)
    times["mesh_s"] = time.perf_counter() - t0
    t = time.perf_counter()
    solid = make_solid(mesh, block)
    times["assembly_s"] = time.perf_counter() - t
    X = solid.basis.doflocs
    tiny = 1e-9 * spec.depth
    fixed = X[2] < -spec.depth + tiny                 # clamped bottom
    fixed[0::3] |= X[0, 0::3] < tiny                  # symmetry x = 0: u_x = 0
    fixed[1::3] |= X[1, 1::3] < tiny                  # symmetry y = 0: u_y = 0
    free = np.flatnonzero(~fixed)
    t = time.perf_counter()
    lin = elasticity_solver(solid, free, tol=cg_tol, kind=solver)
    times["solver_setup_s"] = time.perf_counter() - t
    position = np.full(solid.n_dofs, -1)
    position[free] = np.arange(free.size)
    top = np.unique(mesh.top)
    xt, yt = mesh.points[0, top], mesh.points[1, top]
    sel = candidates(xt, yt)
    sel[sel] &= np.isfinite(gap(xt[sel], yt[sel]))
    cand = top[sel]
    xc, yc = mesh.points[0, cand], mesh.points[1, cand]
    t = time.perf_counter()
    w = tributary_areas(mesh)[cand]
    z_dofs, h0 = position[3 * cand + 2], gap(xc, yc)
    if method == "active_set":
        sol = active_set(lin, z_dofs, h0, quarter_force, initial(xc, yc), tol=contact_tol)
    elif method == "penalty":
        kappa = penalty_factor * block.E / (1.0 - block.nu**2) * w / spec.h_contact
        sol = penalty(lin, z_dofs, h0, quarter_force, kappa, initial(xc, yc), tol=contact_tol)
    else:
        raise ValueError(f"method must be active_set or penalty, got {method!r}")
    times["contact_s"] = time.perf_counter() - t
    if sol.active[rim(xc, yc)].any():
        raise RuntimeError("FEM contact reached the edge of the candidate zone; raise numerics.fem_contact_zone")
    p = sol.lam / w
    u_all = np.zeros(solid.n_dofs)
    u_all[free] = sol.u
    pressure_all = np.zeros(mesh.n_nodes)
    pressure_all[cand] = p
    return QuarterContact(mesh, cand, xc, yc, p, sol.lam, sol.delta, int(sol.active.sum()), sol.iterations,
                          sol.cg_iterations, sol.residual, int(free.size), u_all.reshape(-1, 3).T, pressure_all,
                          time.perf_counter() - t0, times, type(lin).__name__,
                          float(max(0.0, -sol.gap.min())))
