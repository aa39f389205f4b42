"""2D plane-strain FE reference for line contact with Coulomb friction: Cattaneo shift and steady rolling.

A cylinder (elastic or rigid) of radius R is pressed by W' (N/m) on a clamped elastic block; both bodies are
meshed whole (:mod:`femcheck.meshes.plane_full`), condensed onto matching contact node pairs at abscissae x_i,
and the frictional contact problem is solved on the condensed system by :mod:`femcheck.solvers.coulomb`.

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
  tangential step is exact. ``shift`` is the micro-slip part delta_t(Q') - delta_t,stick(Q') (the absolute
  shift of a 2D contact depends on the block size, the half-plane displacement growing like log r; this
  difference does not). The adhered case is also solved (mu = inf, same path); for uncoupled problems the
  shift is evaluated by the reciprocal theorem (:func:`reciprocal_slip_shift`), which avoids the unresolved
  edge singularity of the adhered traction, else as the direct difference of the two solves.
* Steady rolling (Kalker 1990 §2.2; Johnson 1985 §8.2): the contact moves in +x at speed V, material flows
  through it in -x (leading edge at +a). The slip velocity of the cylinder relative to the block per unit V is

      s(x) = xi - d u_rel,x / dx          (-)

  discretised on the contact nodes by the upwind difference (the material arrives from +x, the leading edge)
  (u_{i+1} - u_i)/(x_{i+1} - x_i): quasi-static bodies supply the surface flexibility, transport acts on the
  contact line only (Kalker's steady-state Eulerian form). With xi > 0 the cylinder slides forward and
  the friction force on it is negative (Kalker's sign convention, Fx = -G c^2 C11 xi).

Dissimilar materials: the normal and tangential problems are solved together (``coulomb.solve``), so the
normal-tangential coupling of the FE compliances is kept; in the shift problem the normal load is then
applied in ``normal_steps`` increments (Spence's receding stick zone needs the loading history).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError, InputError
from ..materials import Elastic, effective_modulus
from ..result import ModelResult
from ..scene import Key, elastic, fem_line_mesh_keys
from ..qoi import contact_edge, half_width as profile_half_width
from ..solvers import coulomb
from ..solvers.convergence import richardson
from ..solvers.elasticity2d import CondensedBody, boundary_dofs, make_body
from ..meshes.plane import MeshSpec, TriMesh
from ..meshes.plane_full import block_full, cylinder_full


@dataclass
class FrictionLineSettings:
    """Numerics, lengths as multiples of the Hertz half-width a_H. Level k uses element size
    ``h_contact * 2^-k`` on the candidate zone [-``contact_zone``, ``contact_zone``] and grading
    ``grading * 2^-k``. Block ``block_width`` x ``block_depth`` (full), clamped at the bottom.
    ``normal_steps``: increments of the normal load in the shift problem (0: 1 for quasi-identical bodies,
    whose normal loading causes no slip, else 10); ``tangential_steps``: increments of Q'.
    ``coupling``: ``full`` keeps the normal-tangential cross-compliances of the FE bodies; ``johnson`` drops
    them (Johnson's process: exact for quasi-identical half-spaces); ``auto`` = johnson for quasi-identical
    pairs, full otherwise (see :func:`quasi_identical`)."""

    levels: int = 3
    h_contact: float = 0.1
    grading: float = 0.4
    contact_zone: float = 1.3
    block_width: float = 40.0
    block_depth: float = 20.0
    order: int = 2
    formulation: str = "auto"
    coupling: str = "auto"
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
    ``slip`` (m, shift case) accumulated slip since the end of the normal loading;
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
    slip: np.ndarray | None = None


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


def _normal_guess(pair: ContactPair, a_ref: float) -> np.ndarray:
    """Initial contact set of the active-set iteration: the Hertz zone |x| <= a_H."""
    return np.abs(pair.x) <= a_ref


def shift_case(pair: ContactPair, load: float, tangential: float, mu: float, a_ref: float,
               normal_steps: int = 1, tangential_steps: int = 1, tol: float = 1e-9) -> LineFrictionResult:
    """Cattaneo shift: W' = ``load`` (N/m) then Q' = ``tangential`` (N/m, on the cylinder along +x), Coulomb
    ``mu`` (``np.inf``: full adhesion). Quantities: ``delta_t`` (m, absolute rigid shift of the loaded flat
    relative to the clamped block bottom), ``shift`` (m, micro-slip part by the reciprocal theorem, see
    :func:`reciprocal_slip_shift`), ``stick_half_width`` (m), p_max, half_width, total_force.
    ``slip`` field (m): u_rel,x now minus u_rel,x after the normal loading (zero in the stick zone)."""
    n = pair.x.size
    p = np.zeros(n)
    q = np.zeros(n)
    dt = 0.0
    its, res = 0, 0.0
    path = [(load * k / normal_steps, 0.0) for k in range(1, normal_steps + 1)]
    path += [(load, tangential * k / tangential_steps) for k in range(1, tangential_steps + 1)]
    contact = _normal_guess(pair, a_ref)
    u_normal = np.zeros(n)
    for step, (w_k, q_k) in enumerate(path, start=1):
        # slip increment s = u_rel,x - u_rel,x(previous step), u_rel,x = A_xx q + A_xy p + delta_t
        s0 = -(pair.A_xx @ q + pair.A_xy @ p + dt)
        sys = coulomb.FrictionSystem(pair.g0, -np.ones(n), pair.A_yy, pair.A_yx, s0, np.ones(n), pair.A_xy,
                                      pair.A_xx, w_k, -q_k, mu)
        sol = coulomb.solve(sys, contact, tol=tol)
        p, q, dt, contact = sol.p, sol.q, sol.delta_t, sol.contact
        its += sol.iterations
        res = max(res, sol.residual)
        if step == normal_steps:
            u_normal = pair.A_xx @ q + pair.A_xy @ p + dt
    _check_inside(pair, p, its, tol)
    quantities = _base_quantities(pair, p)
    quantities["delta_t"] = dt
    slip = np.where(p > 0, pair.A_xx @ q + pair.A_xy @ p + dt - u_normal, 0.0)
    if np.isfinite(mu):
        left, right = _zone_edges(pair.x, _stick_margin(pair, p, q, sol.stick, mu))
        quantities["stick_half_width"] = 0.5 * (right - left)
        left, right = _zone_edges(pair.x, p / pair.w)
        quantities["shift"] = reciprocal_slip_shift(pair.x, slip, p > 0, left, right)
    return LineFrictionResult(pair.x, p, q, p / pair.w, q / pair.w, sol.stick, quantities, its, res,
                              len(path), slip)


def reciprocal_slip_shift(x: np.ndarray, slip: np.ndarray, contact: np.ndarray, left: float, right: float,
                          n_quad: int = 256) -> float:
    """Micro-slip part of the shift, delta(Q') - delta_stick(Q') (m), from the slip field by the reciprocal
    theorem.

    With q_stick = Q_c phi the adhered traction (sum phi = 1) and u = A q + delta the relative tangential
    displacement of the partial-slip state (symmetric compliance A; A q_stick + delta_stick = 0 on the
    contact), q_stick . u = q . A q_stick + delta Q_c = Q_c (delta - delta_stick), hence

        delta - delta_stick = int phi(x) u_slip(x) dx,    phi = 1 / (pi sqrt(a^2 - x^2))  on |x| < a

    (u_slip vanishes in the stick zone). phi is the adhered traction of a 2D contact of half-width a
    (Johnson 1985 §7.2; the tangential twin of the flat-punch pressure of §2.8; Cattaneo 1938). It is used
    in closed form because the node-to-node FE cannot resolve the edge singularity of the adhered problem:
    the directly differenced delta - delta_stick then jumps by (2 Q'/(pi E*)) (d/a) when the edge moves by
    one node spacing d in the grid, up to 6 % of the Cattaneo slip part at Q'/(mu W') = 0.6 with d = 0.025 a
    (measured). The slip field comes from the FE; the contact ends ``left``, ``right`` (m) from the pressure
    fit. Substituting x = m + a sin(theta) removes the singularity: shift = (1/pi) int u(m + a sin theta)
    dtheta, Gauss-Legendre in theta, u linear between nodes and extrapolated linearly to the ends.
    """
    C = np.flatnonzero(contact)
    if C.size < 2:
        return 0.0
    m, a = 0.5 * (left + right), 0.5 * (right - left)
    xs, us = x[C], slip[C]
    lo = us[0] + (us[0] - us[1]) / (xs[1] - xs[0]) * (xs[0] - left)
    hi = us[-1] + (us[-1] - us[-2]) / (xs[-1] - xs[-2]) * (right - xs[-1])
    xs = np.concatenate([[min(left, xs[0])], xs, [max(right, xs[-1])]])
    us = np.concatenate([[lo], us, [hi]])
    t, wt = np.polynomial.legendre.leggauss(n_quad)
    theta = 0.5 * np.pi * t
    return float(0.5 * np.sum(wt * np.interp(m + a * np.sin(theta), xs, us)))


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
    sys = coulomb.FrictionSystem(pair.g0, -np.ones(n), pair.A_yy, pair.A_yx, np.full(n, float(xi)), None,
                                  -D @ pair.A_xy, -D @ pair.A_xx, load, None, mu)
    sol = coulomb.solve(sys, _normal_guess(pair, a_ref), tol=tol)
    _check_inside(pair, sol.p, sol.iterations, tol)
    quantities = _base_quantities(pair, sol.p)
    left, right = _zone_edges(pair.x, _stick_margin(pair, sol.p, sol.q, sol.stick, mu))
    quantities["creep_force_x"] = float(sol.q.sum())
    quantities["adhesion_length"] = right - left
    quantities["adhesion_fraction"] = (right - left) / (2.0 * quantities["half_width"])
    return LineFrictionResult(pair.x, sol.p, sol.q, sol.p / pair.w, sol.q / pair.w, sol.stick, quantities,
                              sol.iterations, sol.residual, 1)


# ----------------------------------------------------------------------------------------------------------
# Model entry point (problem kind ``line_tangential``)

def quasi_identical(cylinder: Elastic, block: Elastic, rtol: float = 1e-9) -> bool:
    """Dundurs' beta = 0, i.e. (1 - 2 nu1)/G1 = (1 - 2 nu2)/G2 (Johnson 1985 §5.8; Kalker 1990 §1.5): a
    normal load then causes no tangential relative displacement of two half-spaces and vice versa. A rigid
    cylinder is quasi-identical only with an incompressible block."""
    k = [0.0 if m.rigid else (1.0 - 2.0 * m.nu) / m.shear_modulus for m in (cylinder, block)]
    return abs(k[0] - k[1]) <= rtol * max(abs(k[0]), abs(k[1]), 1e-300) or max(k) == 0.0


def decoupled(pair: ContactPair) -> ContactPair:
    """The pair without its normal-tangential cross-compliances (Johnson's process). For quasi-identical
    bodies these vanish for half-spaces; in the FE they hold only the tilt of the finite bodies under a net
    tangential force and node-to-node noise of the lumped P2 surface forces (measured on steel/steel:
    |A_xy| <= 0.5 % of |A_xx|, but ~0.3 % asymmetry between +xi and -xi and an irregular mesh sequence)."""
    from dataclasses import replace

    return replace(pair, A_xy=np.zeros_like(pair.A_xy), A_yx=np.zeros_like(pair.A_yx))


_DEF = FrictionLineSettings()
FEM_SCHEMA = {
    **fem_line_mesh_keys(),
    "numerics.fem_coupling": Key("str", "-", "normal-tangential coupling: auto (johnson for quasi-identical "
                                  "bodies, else full), full, johnson", choices=("auto", "full", "johnson")),
    "numerics.fem_normal_steps": Key("int", "-", "normal load increments of the shift problem (0: auto)", lo=0,
                                      hi=100, lo_closed=True, hi_closed=True),
    "numerics.fem_tangential_steps": Key("int", "-", "tangential load increments of the shift problem", lo=1,
                                          hi=100, lo_closed=True, hi_closed=True),
    "numerics.fem_tol": Key("float", "-", "residual tolerance of the frictional active set", lo=0.0, hi=1e-3,
                             hi_closed=True),
}
FEM_DEFAULTS = {
    "numerics.fem_levels": _DEF.levels,
    "numerics.fem_h_contact": _DEF.h_contact,
    "numerics.fem_grading": _DEF.grading,
    "numerics.fem_contact_zone": _DEF.contact_zone,
    "numerics.fem_block_width": _DEF.block_width,
    "numerics.fem_block_depth": _DEF.block_depth,
    "numerics.fem_order": _DEF.order,
    "numerics.fem_formulation": _DEF.formulation,
    "numerics.fem_coupling": _DEF.coupling,
    "numerics.fem_normal_steps": _DEF.normal_steps,
    "numerics.fem_tangential_steps": _DEF.tangential_steps,
    "numerics.fem_tol": _DEF.tol,
}


def settings_from(params: dict) -> FrictionLineSettings:
    n = {k.split(".", 1)[1][4:]: v for k, v in {**FEM_DEFAULTS, **params}.items()
         if k.startswith("numerics.fem_") and k in FEM_SCHEMA}
    return FrictionLineSettings(**n)


SHIFT_QUANTITIES = ("shift", "stick_half_width", "p_max", "half_width")
ROLLING_QUANTITIES = ("creep_force_x", "adhesion_length", "adhesion_fraction", "p_max", "half_width")


def _present(params: dict, key: str) -> bool:
    return params.get(key) is not None


def model(params: dict, progress=None):
    """FE reference of the ``line_tangential`` kind: steady rolling (``kinematics.xi``) or Cattaneo shift
    (``load.tangential_per_length``) of a cylinder on a block, on ``numerics.fem_levels`` meshes; with >= 3
    levels every quantity is Richardson-extrapolated (stats carry each level and the finest values).

    Quantities (SI): rolling -> creep_force_x (N/m, on the cylinder), adhesion_length (m),
    adhesion_fraction (-), p_max (Pa), half_width (m), total_force (N/m); shift -> shift (m, micro-slip part
    delta - delta_stick), stick_half_width (m), p_max, half_width, total_force. The shift comes from the
    reciprocal theorem (:func:`reciprocal_slip_shift`) for uncoupled problems (quasi-identical bodies or
    ``numerics.fem_coupling = johnson``), else from the direct difference of the partial-slip and adhered
    solves; stats carry both per level.
    """
    from ..analytic import hertz

    t_start = time.perf_counter()
    rolling, shifting = _present(params, "kinematics.xi"), _present(params, "load.tangential_per_length")
    if rolling == shifting:
        raise InputError("kinematics.xi", "give exactly one of kinematics.xi (rolling) and "
                         "load.tangential_per_length (shift)")
    radius, load = float(params["geometry.radius"]), float(params["load.per_length"])
    mu = float(params["friction.mu"])
    if not mu > 0:
        raise InputError("friction.mu", f"{mu:g} is not allowed; allowed: (0, 10]")
    cyl, blk = elastic(params, "cylinder"), elastic(params, "block")
    s = settings_from(params)
    hz = hertz.line_contact(load, radius, effective_modulus(cyl, blk))
    a = hz.half_width
    if shifting:
        Q = float(params["load.tangential_per_length"])
        if not abs(Q) < mu * load:
            raise InputError("load.tangential_per_length", f"{Q:g} N/m is not allowed; allowed: "
                             f"(-{mu * load:.6g}, {mu * load:.6g}) N/m (|Q'| < mu W', else gross sliding)")
    else:
        xi = float(params["kinematics.xi"])
    quasi = quasi_identical(cyl, blk)
    coupling = ("johnson" if quasi else "full") if s.coupling == "auto" else s.coupling
    normal_steps = s.normal_steps or (1 if (quasi or coupling == "johnson") else 10)
    # The reciprocal-theorem shift assumes no normal-tangential coupling; with it (dissimilar bodies) the
    # adhered and partial-slip pressures differ and Spence slip precedes Q', so the shift is then the direct
    # difference of the two FE solves (edge-position jitter of a few %, see reciprocal_slip_shift).
    reciprocal = quasi or coupling == "johnson"

    levels = []
    fine = None
    for k in range(s.levels):
        if progress:
            progress(f"FEM friction level {k + 1}/{s.levels}")
        t0 = time.perf_counter()
        pair = condense(radius, cyl, blk, a, k, s)
        if coupling == "johnson":
            pair = decoupled(pair)
        if shifting:
            r = shift_case(pair, load, Q, mu, a, normal_steps, s.tangential_steps, s.tol)
            r0 = shift_case(pair, load, Q, np.inf, a, normal_steps, s.tangential_steps, s.tol)
            direct = r.quantities["delta_t"] - r0.quantities["delta_t"]
            extra = {"shift_reciprocal": r.quantities["shift"], "shift_direct": direct,
                     "delta_t": r.quantities["delta_t"], "iterations_adhered": r0.iterations}
            if not reciprocal:
                r.quantities["shift"] = direct
            names = SHIFT_QUANTITIES
        else:
            r = rolling_case(pair, load, xi, mu, a, s.tol)
            extra = {}
            names = ROLLING_QUANTITIES
        levels.append({"h": pair.h, "h_over_a": pair.h / a, "n_dofs": pair.n_dofs,
                       "n_elements": pair.n_elements, "n_contact_nodes": int(pair.x.size),
                       "iterations": r.iterations, "residual": r.residual, "load_steps": r.steps,
                       "time_condense_s": pair.time_s, "time_s": time.perf_counter() - t0,
                       **{q: r.quantities[q] for q in names}, "total_force": r.quantities["total_force"], **extra})
        fine = (pair, r)
    pair, r = fine
    q = {name: levels[-1][name] for name in names}
    stats = {"problem": "shift" if shifting else "rolling", "coupling": coupling, "quasi_identical": quasi,
             "normal_steps": normal_steps if shifting else None, "element_order": s.order,
             "formulation": pair.formulations, "finest": dict(q), "levels": levels,
             "block": {"width": s.block_width * a, "depth": s.block_depth * a}, "hertz_half_width": a,
             "derivative": None if shifting else "first-order upwind (Kalker)",
             "shift_method": (("reciprocal theorem with the adhered 2D traction" if reciprocal else
                               "direct difference delta(Q') - delta_stick(Q') of two FE solves")
                              if shifting else None)}
    if s.levels >= 3:
        h = [lv["h"] for lv in levels]
        rich = {name: richardson(h, [lv[name] for lv in levels]) for name in names}
        stats["richardson"] = {k: v.as_dict() for k, v in rich.items()}
        q = {k: v.value for k, v in rich.items()}
    q["total_force"] = r.quantities["total_force"]
    fields = {"x": r.x, "pressure": r.pressure, "traction": r.traction, "stick": r.stick.astype(float)}
    if r.slip is not None:
        fields["slip"] = r.slip
    return ModelResult("fem", time_s=time.perf_counter() - t_start, quantities=q, stats=stats, fields=fields)
