"""2D plane-strain FE reference for line contact with Coulomb friction: Cattaneo shift and steady rolling.

A cylinder (elastic or rigid) of radius R is pressed by W' (N/m) on a clamped elastic block; both bodies are
meshed whole (:mod:`femcheck.fem.mesh2d_full`), condensed onto matching contact node pairs at abscissae x_i,
and the frictional contact problem is solved on the condensed system by :mod:`femcheck.fem.friction`.

Kinematics (x rolling direction, y the common normal pointing into the cylinder, body 1 = cylinder):
the pair forces on the cylinder are (q_i, p_i), on the block (-q_i, -p_i). With the contact compliances
C_cyl (relative to its loaded flat y = R, which moves rigidly by (delta_t, -delta_n)) and C_blk (relative to
its clamped bottom), the displacement of the cylinder surface relative to the block surface is

    u_rel = (C_cyl + C_blk) [q; p] + (delta_t, -delta_n)        (m)

so the gap is g = g0 + u_rel,y (g0 the exact circle, R - sqrt(R^2 - x^2)) and the tangential relative
displacement is u_rel,x.

* Shift (Cattaneo 1938; Johnson 1985 §7.1-7.2, 2D): the normal load W' is applied with Q' = 0, then the
  tangential force Q' (on the cylinder, +x) under load control, delta_t the unknown; each load step solves
  Coulomb's law on the slip increment s = u_rel,x - u_rel,x(previous step). Monotonic loading: a single
  tangential step is exact. ``shift`` is the micro-slip part delta_t(Q') - delta_t,stick(Q'), the second term
  from the same path with full adhesion (mu = inf): the absolute shift of a 2D contact depends on the block
  size (the half-plane displacement grows like log r), this difference does not.
* Steady rolling (Kalker 1990 §2.2; Johnson 1985 §8.2): the contact moves in +x at speed V, material flows
  through it in -x (leading edge at +a). The slip velocity of the cylinder relative to the block per unit V is

      s(x) = xi - d u_rel,x / dx          (-)

  discretised on the contact nodes by the upwind difference (the material arrives from +x, the leading edge)
  (u_{i+1} - u_i)/(x_{i+1} - x_i): quasi-static bodies supply the surface flexibility, transport acts on the
  contact line only (Kalker's steady-state Eulerian form). With xi > 0 the cylinder slides forward and
  the friction force on it is negative (Kalker's sign convention, Fx = -G c^2 C11 xi).

Dissimilar materials: the normal and tangential problems are solved together (``friction.solve``), so the
normal-tangential coupling of the FE compliances is kept; in the shift problem the normal load is then
applied in ``normal_steps`` increments (Spence's receding stick zone needs the loading history).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError, InputError
from ..materials import Elastic
from ..qoi import contact_edge, half_width as profile_half_width
from . import friction
from .convergence import Extrapolation, richardson
from .elasticity import CondensedBody, boundary_dofs, make_body
from .mesh2d import MeshSpec, TriMesh
from .mesh2d_full import block_full, cylinder_full


@dataclass
class FrictionLineSettings:
    """Numerics, lengths as multiples of the Hertz half-width a_H. Level k uses element size
    ``h_contact * 2^-k`` on the candidate zone [-``contact_zone``, ``contact_zone``] and grading
    ``grading * 2^-k``. Block ``block_width`` x ``block_depth`` (full), clamped at the bottom.
    ``normal_steps``: increments of the normal load in the shift problem (0: 1 for quasi-identical bodies,
    whose normal loading causes no slip, else 10); ``tangential_steps``: increments of Q'."""

    levels: int = 3
    h_contact: float = 0.1
    grading: float = 0.4
    contact_zone: float = 1.3
    block_width: float = 40.0
    block_depth: float = 20.0
    order: int = 2
    formulation: str = "auto"
    normal_steps: int = 0
    tangential_steps: int = 1
    tol: float = 1e-9


@dataclass
class ContactPair:
    """Condensed contact of one mesh level: node abscissae ``x`` (m), tributary lengths ``w`` (m), initial
    gaps ``g0`` (m) and the relative compliance blocks (m per N/m): u_rel,x = A_xx q + A_xy p,
    u_rel,y = A_yx q + A_yy p (rigid motion of the loaded flat excluded)."""

    x: np.ndarray
    w: np.ndarray
    g0: np.ndarray
    A_xx: np.ndarray
    A_xy: np.ndarray
    A_yx: np.ndarray
    A_yy: np.ndarray
    h: float
    n_dofs: int
    n_elements: int
    meshes: dict[str, TriMesh] = field(default_factory=dict)
    formulations: dict[str, str] = field(default_factory=dict)
    time_s: float = 0.0


def _tributary_weights(body, dofs: np.ndarray, where) -> np.ndarray:
    """w_i = int phi_i ds over the contact line (m): the length each contact node carries (lumped)."""
    from skfem import FacetBasis, LinearForm, asm

    fb = FacetBasis(body.basis.mesh, body.basis.elem,
                    facets=body.basis.mesh.facets_satisfying(where, boundaries_only=True), intorder=4)
    w = asm(LinearForm(lambda v, _: v[1]), fb)
    return w[dofs]


def _contact_dofs(basis, where) -> tuple[np.ndarray, np.ndarray]:
    dx, dy = boundary_dofs(basis, where, 0), boundary_dofs(basis, where, 1)
    if dx.size != dy.size or np.abs(basis.doflocs[0, dx] - basis.doflocs[0, dy]).max() > 0:
        raise RuntimeError("x and y contact DOFs do not pair up node by node")
    return dx, dy


def condense(radius: float, cylinder: Elastic, block: Elastic, a_ref: float, level: int,
             s: FrictionLineSettings) -> ContactPair:
    """Mesh both bodies at ``level``, assemble, and condense onto the contact node pairs."""
    t0 = time.perf_counter()
    h = s.h_contact * a_ref / 2**level
    x_c = s.contact_zone * a_ref
    grading = s.grading / 2**level
    tiny = 1e-9 * a_ref

    bmesh = block_full(s.block_width * a_ref, s.block_depth * a_ref, MeshSpec(h, x_c, grading, max(h, 2 * a_ref)))
    blk = make_body(bmesh, block, s.order, s.formulation)
    on_contact_b = lambda X: (np.abs(X[1]) < tiny) & (np.abs(X[0]) < x_c + tiny)
    bottom = lambda X: np.abs(X[1] + s.block_depth * a_ref) < tiny
    cb = CondensedBody(blk, np.concatenate([boundary_dofs(blk.basis, bottom, 0), boundary_dofs(blk.basis, bottom, 1)]))
    bx, by = _contact_dofs(blk.basis, on_contact_b)
    x = blk.basis.doflocs[0, by]
    dofs = np.concatenate([bx, by])
    C = cb.compliance(dofs)
    meshes, formulations = {"block": bmesh}, {"block": blk.formulation}
    n_dofs, n_el = blk.n_dofs, bmesh.triangles.shape[1]
    if not cylinder.rigid:
        cmesh = cylinder_full(radius, MeshSpec(h, x_c, grading, max(h, radius / 5.0)))
        cyl = make_body(cmesh, cylinder, s.order, s.formulation)
        top = lambda X: np.abs(X[1] - radius) < 1e-9 * radius
        cc = CondensedBody(cyl, np.concatenate([boundary_dofs(cyl.basis, top, 0), boundary_dofs(cyl.basis, top, 1)]))
        cx, cy = _contact_dofs(cyl.basis, lambda X: (np.abs(X[0]) < x_c + tiny) & (X[1] < 0.5 * radius))
        if cy.size != x.size or np.abs(cyl.basis.doflocs[0, cy] - x).max() > 1e-6 * h:
            raise RuntimeError("contact nodes of cylinder and block do not match")
        # Forces on the cylinder are +(q, p), on the block -(q, p): both compliances add in u_rel.
        C = C + cc.compliance(np.concatenate([cx, cy]))
        meshes["cylinder"], formulations["cylinder"] = cmesh, cyl.formulation
        n_dofs += cyl.n_dofs
        n_el += cmesh.triangles.shape[1]
    n = x.size
    w = _tributary_weights(blk, by, on_contact_b)
    g0 = radius - np.sqrt(radius**2 - x**2)
    return ContactPair(x, w, g0, C[:n, :n], C[:n, n:], C[n:, :n], C[n:, n:], h, n_dofs, n_el, meshes,
                       formulations, time.perf_counter() - t0)


# ----------------------------------------------------------------------------------------------------------
# Load cases on a condensed pair

@dataclass
class LineFrictionResult:
    """One load case on one mesh level. ``p``, ``q``: pair forces (N/m) on the cylinder (normal compressive,
    tangential along +x); ``pressure``, ``traction`` (Pa) = forces / tributary lengths; ``stick`` set;
    scalar quantities in ``quantities`` (SI); ``iterations`` (total semi-smooth Newton iterations over the
    load steps) and ``residual`` (largest final residual)."""

    x: np.ndarray
    p: np.ndarray
    q: np.ndarray
    pressure: np.ndarray
    traction: np.ndarray
    stick: np.ndarray
    quantities: dict[str, float]
    iterations: int
    residual: float
    steps: int


def _check_inside(pair: ContactPair, p: np.ndarray, iterations: int, tol: float) -> None:
    if p[0] > 0 or p[-1] > 0:
        raise ConvergenceError("FEM frictional line contact", iterations, np.inf, tol,
                               "contact reached the edge of the candidate zone; raise numerics.fem_contact_zone")


def _stick_margin(pair: ContactPair, p, q, stick, mu) -> np.ndarray:
    """mu p - |q| (Pa) on stick nodes, 0 elsewhere: the traction reserve. In Cattaneo's and Carter's solutions
    it is an elliptical profile over the stick zone (mu p0 (c/a) sqrt(1 - (x - d)^2/c^2)), so its zero
    crossings are located to sub-node accuracy like a Hertzian contact edge (qoi.contact_edge)."""
    return np.where(stick & (p > 0), (mu * p - np.abs(q)) / pair.w, 0.0)


def _zone_edges(x: np.ndarray, r: np.ndarray) -> tuple[float, float]:
    """Left and right ends (m) of the positive part of profile ``r``."""
    if not (r > 0).any():
        return 0.0, 0.0
    right = contact_edge(x, r)
    left = -contact_edge(-x[::-1], r[::-1])
    return left, right


def _base_quantities(pair: ContactPair, p) -> dict[str, float]:
    pressure = p / pair.w
    return {"p_max": float(pressure.max()), "half_width": profile_half_width(pair.x, pressure),
            "total_force": float(p.sum())}


def _normal_guess(pair: ContactPair, load: float, a_ref: float) -> np.ndarray:
    return np.abs(pair.x) <= a_ref


def shift_case(pair: ContactPair, load: float, tangential: float, mu: float, a_ref: float,
               normal_steps: int = 1, tangential_steps: int = 1, tol: float = 1e-9) -> LineFrictionResult:
    """Cattaneo shift: W' = ``load`` (N/m) then Q' = ``tangential`` (N/m, on the cylinder along +x), Coulomb
    ``mu`` (``np.inf``: full adhesion). Quantities: ``delta_t`` (m, absolute rigid shift of the loaded flat
    relative to the clamped block bottom), ``stick_half_width`` (m), p_max, half_width, total_force."""
    n = pair.x.size
    p = np.zeros(n)
    q = np.zeros(n)
    dt = 0.0
    its, res = 0, 0.0
    path = [(load * k / normal_steps, 0.0) for k in range(1, normal_steps + 1)]
    path += [(load, tangential * k / tangential_steps) for k in range(1, tangential_steps + 1)]
    contact = _normal_guess(pair, load, a_ref)
    for w_k, q_k in path:
        # slip increment s = u_rel,x - u_rel,x(previous step), u_rel,x = A_xx q + A_xy p + delta_t
        s0 = -(pair.A_xx @ q + pair.A_xy @ p + dt)
        sys = friction.FrictionSystem(pair.g0, -np.ones(n), pair.A_yy, pair.A_yx, s0, np.ones(n), pair.A_xy,
                                      pair.A_xx, w_k, -q_k, mu)
        sol = friction.solve(sys, contact, tol=tol)
        p, q, dt, contact = sol.p, sol.q, sol.delta_t, sol.contact
        its += sol.iterations
        res = max(res, sol.residual)
    _check_inside(pair, p, its, tol)
    quantities = _base_quantities(pair, p)
    quantities["delta_t"] = dt
    if np.isfinite(mu):
        left, right = _zone_edges(pair.x, _stick_margin(pair, p, q, sol.stick, mu))
        quantities["stick_half_width"] = 0.5 * (right - left)
    return LineFrictionResult(pair.x, p, q, p / pair.w, q / pair.w, sol.stick, quantities, its, res,
                              len(path))


def upwind_derivative(x: np.ndarray) -> np.ndarray:
    """Matrix D with (D u)_i = (u_{i+1} - u_i)/(x_{i+1} - x_i): d/dx upwind for material flowing in -x (the
    upstream neighbour of node i is i+1, towards the leading edge); last row one-sided backwards (that node is
    outside the contact, checked)."""
    n = x.size
    D = np.zeros((n, n))
    dx = np.diff(x)
    i = np.arange(n - 1)
    D[i, i] = -1.0 / dx
    D[i, i + 1] = 1.0 / dx
    D[n - 1, n - 2], D[n - 1, n - 1] = -1.0 / dx[-1], 1.0 / dx[-1]
    return D


def rolling_case(pair: ContactPair, load: float, xi: float, mu: float, a_ref: float,
                 tol: float = 1e-9) -> LineFrictionResult:
    """Steady rolling with longitudinal creepage ``xi`` (-) under W' = ``load`` (N/m), Coulomb ``mu``.
    Slip per unit rolling distance s = xi - D u_rel,x (module doc). Quantities: creep_force_x (N/m, on the
    cylinder), adhesion_length (m), adhesion_fraction (-), p_max, half_width, total_force."""
    n = pair.x.size
    D = upwind_derivative(pair.x)
    sys = friction.FrictionSystem(pair.g0, -np.ones(n), pair.A_yy, pair.A_yx, np.full(n, float(xi)), None,
                                  -D @ pair.A_xy, -D @ pair.A_xx, load, None, mu)
    sol = friction.solve(sys, _normal_guess(pair, load, a_ref), tol=tol)
    _check_inside(pair, sol.p, sol.iterations, tol)
    quantities = _base_quantities(pair, sol.p)
    left, right = _zone_edges(pair.x, _stick_margin(pair, sol.p, sol.q, sol.stick, mu))
    quantities["creep_force_x"] = float(sol.q.sum())
    quantities["adhesion_length"] = right - left
    quantities["adhesion_fraction"] = (right - left) / (2.0 * quantities["half_width"])
    return LineFrictionResult(pair.x, sol.p, sol.q, sol.p / pair.w, sol.q / pair.w, sol.stick, quantities,
                              sol.iterations, sol.residual, 1)
