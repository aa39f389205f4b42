"""2D plane-strain FE model of a cylinder pressed on a block (hertz-line scene), node-to-node contact."""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError, InputError
from ..materials import Elastic
from ..qoi import edge, peak
from ..solvers import frictionless
from ..solvers.elasticity2d import CondensedBody, boundary_dofs, make_body
from ..meshes.plane import MeshSpec, TriMesh, block_half, cylinder_half


@dataclass
class FEMLineSettings:
    """Numerics of the 2D FE model, lengths as multiples of the Hertz half-width a_H.

    Level k uses element size ``h_contact * 2^-k`` on the contact zone [0, ``contact_zone``] and grading
    ``grading * 2^-k`` (so every element shrinks by 2 per level). Block: ``block_width`` x ``block_depth``
    (full width; the model is the symmetric half), clamped at the bottom.
    """

    levels: int = 3
    h_contact: float = 0.1
    grading: float = 0.4
    contact_zone: float = 1.3
    block_width: float = 40.0
    block_depth: float = 20.0
    order: int = 2
    formulation: str = "auto"
    method: str = "active_set"
    penalty_factor: float = 1.0e3
    tol: float = 1e-9


@dataclass
class FEMLevel:
    """One mesh level: contact-node abscissae ``x`` (m) and pressures ``p`` (Pa), scalar results, stats."""

    h: float
    x: np.ndarray
    p: np.ndarray
    p_max: float
    half_width: float
    total_force: float
    n_dofs: int
    n_elements: int
    iterations: int
    residual: float
    penetration: float
    time_s: float
    meshes: dict[str, TriMesh] = field(default_factory=dict)
    formulations: dict[str, str] = field(default_factory=dict)
    std: dict[str, float] = field(default_factory=dict)       # standard errors of the fitted quantities


def _tributary_weights(body, dofs: np.ndarray, where) -> np.ndarray:
    """w_i = int phi_i ds over the contact line (m): the length each contact node carries (lumped)."""
    from skfem import FacetBasis, LinearForm, asm

    fb = FacetBasis(body.basis.mesh, body.basis.elem,
                    facets=body.basis.mesh.facets_satisfying(where, boundaries_only=True), intorder=4)
    w = asm(LinearForm(lambda v, _: v[1]), fb)   # y-component of the vector test function
    return w[dofs]


def solve_level(radius: float, cylinder: Elastic, block: Elastic, load_per_length: float, a_ref: float,
                level: int, s: FEMLineSettings) -> FEMLevel:
    """Solve one mesh level. The approach of the loaded flat y = R of the cylinder (or of a rigid cylinder) is
    the extra unknown that balances the applied ``load_per_length`` (N/m)."""
    t0 = time.perf_counter()
    h = s.h_contact * a_ref / 2**level
    x_c = s.contact_zone * a_ref
    grading = s.grading / 2**level
    tiny = 1e-9 * a_ref

    bmesh = block_half(s.block_width * a_ref, s.block_depth * a_ref,
                       MeshSpec(h, x_c, grading, max(h, 2.0 * a_ref)))
    blk = make_body(bmesh, block, s.order, s.formulation)
    on_contact_b = lambda X: (np.abs(X[1]) < tiny) & (X[0] < x_c + tiny)
    bottom = lambda X: np.abs(X[1] + s.block_depth * a_ref) < tiny
    fixed_b = np.concatenate([boundary_dofs(blk.basis, bottom, 0), boundary_dofs(blk.basis, bottom, 1),
                              boundary_dofs(blk.basis, lambda X: np.abs(X[0]) < tiny, 0)])
    cb = CondensedBody(blk, fixed_b)
    dofs_b = boundary_dofs(blk.basis, on_contact_b, 1)
    x = blk.basis.doflocs[0, dofs_b]
    W = cb.compliance(dofs_b)
    g0 = radius - np.sqrt(radius**2 - x**2)      # exact circle, also at P2 mid-edge nodes
    meshes = {"block": bmesh}
    formulations = {"block": blk.formulation}
    n_dofs, n_el = blk.n_dofs, bmesh.triangles.shape[1]

    if cylinder.rigid:
        c = -np.ones_like(x)
    else:
        cmesh = cylinder_half(radius, MeshSpec(h, x_c, grading, max(h, radius / 5.0)))
        cyl = make_body(cmesh, cylinder, s.order, s.formulation)
        top = boundary_dofs(cyl.basis, lambda X: np.abs(X[1] - radius) < 1e-9 * radius, 1)
        fixed_c = np.unique(np.concatenate([top, boundary_dofs(cyl.basis, lambda X: np.abs(X[0]) < tiny, 0)]))
        cc = CondensedBody(cyl, fixed_c)
        # Contact facets: the polyline x in (0, x_c] on the lower surface (facet midpoints; excludes the
        # symmetry line x = 0 and the loaded flat y = R). P2 mid-side nodes sit on the chords.
        dofs_c = boundary_dofs(cyl.basis, lambda X: (X[0] > tiny) & (X[0] < x_c + tiny) & (X[1] < 0.5 * radius), 1)
        xc = cyl.basis.doflocs[0, dofs_c]
        if xc.shape != x.shape or np.abs(xc - x).max() > 1e-6 * h:
            raise RuntimeError("contact nodes of cylinder and block do not match")
        W = W + cc.compliance(dofs_c)
        unit = np.zeros(cyl.n_dofs)
        unit[top] = -1.0                        # approach delta = 1: the loaded flat moves down by 1 m
        c = cc.response(unit, dofs_c)
        meshes["cylinder"] = cmesh
        formulations["cylinder"] = cyl.formulation
        n_dofs += cyl.n_dofs
        n_el += cmesh.triangles.shape[1]

    w = _tributary_weights(blk, dofs_b, on_contact_b)
    sys = frictionless.CondensedContact(g0, c, W, 0.5 * load_per_length)   # half model carries half the load
    active0 = x <= a_ref
    if s.method == "active_set":
        sol = frictionless.active_set(sys, active0, tol=s.tol)
    elif s.method == "penalty":
        e_ref = 1.0 / (block.compliance + cylinder.compliance)
        kappa = s.penalty_factor * e_ref * w / h
        sol = frictionless.penalty(sys, kappa, active0, tol=s.tol)
    else:
        raise InputError("numerics.fem_method", f"'{s.method}' unknown; allowed: active_set, penalty")
    p = sol.lam / w
    if p[-1] > 0:
        raise ConvergenceError("FEM line contact", sol.iterations, np.inf, s.tol,
                               "contact reached the edge of the candidate zone; raise numerics.fem_contact_zone")
    # peak: local even quartic about the symmetry line; edge: power law with its exponent fitted (femcheck.qoi)
    pk, e = peak(x, p, centre=0.0), edge(x, p)
    return FEMLevel(h, x, p, pk.value, e.position, 2.0 * float(sol.lam.sum()), n_dofs, n_el, sol.iterations,
                    sol.residual, sol.penetration, time.perf_counter() - t0, meshes, formulations,
                    {"p_max_std": pk.std, "half_width_std": e.std})
