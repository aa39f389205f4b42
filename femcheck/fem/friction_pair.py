"""2D plane-strain contact pair with Coulomb friction: meshes, condensation onto the contact node pairs, and the
two load cases (Cattaneo shift, steady rolling) of :mod:`femcheck.fem.friction_line`.

Model (x rolling direction, y the common normal pointing into body 1 = the upper body): two bodies meshed
whole and condensed onto matching contact node pairs at abscissae x_i, whose relative displacement is

    u_rel = (C_1 + C_2) [q; p] + (delta_t, -delta_n)        (m)

(q, p the tangential and compressive normal pair forces on body 1, N/m; body 2 carries -(q, p); C_i the contact
compliance of body i relative to its clamped far boundary, which moves rigidly). The gap is g = g0 + u_rel,y
with g0 = R - sqrt(R^2 - x^2) the cylinder's profile, the tangential relative displacement u_rel,x.

Upper body (``upper_body``):
* ``block`` (default): the mirror image (y -> -y) of the lower block, clamped at its top, carrying the
  cylinder's profile as the initial gap g0 -- the two-half-plane idealisation of Hertz, Carter, Cattaneo and
  Kalker's theory, which the FE is there to check. For identical materials the mirrored meshes make the
  normal-tangential cross compliances of the pair cancel exactly, as they do for two half-planes.
* ``cylinder``: the real cylinder of radius R loaded through its diametral flat. Its finite-body surface strain
  under the normal load (O(a/R)) is physics a half-plane theory does not have; shown as an option.
A rigid upper body contributes no compliance either way.

Finite blocks: a block of depth D clamped at its far face adds a uniform surface strain of order W'/(G D) under
the normal load (measured: 6.3 % of the coupling strain kappa p0 at D = 20 a, halving with each doubling of
the block), which only the normal-tangential coupling of dissimilar bodies sees. The model therefore uses large
blocks (``block_scale`` = 32 x 40 a x 20 a by default) and extrapolates over blocks 2x and 4x larger in
1/scale (:mod:`femcheck.fem.friction_line`); the far-field element size grows with the block (cap 2 a x scale),
so the cost stays about flat (21k DOFs at 40 a x 20 a, 33k at 32x that, finest level).

Load cases (Kalker 1990 §2.2-2.3; Johnson 1985 §7.2, §8.2), solved on the condensed system by the semi-smooth
Newton / primal-dual active set of :mod:`femcheck.solvers.coulomb` (normal and tangential problems together):
* Shift (load control): W' first, then Q' on body 1 along +x. ``normal_loading`` "frictionless" (default):
  the normal load is applied without friction, as in the exact theory (no locked-in tractions); "frictional":
  in ``normal_steps`` increments with friction (Spence's receding stick zone needs the loading history).
  Each step solves Coulomb's law on the slip increment s = u_rel,x - u_rel,x(previous step).
* Steady rolling: s(x) = xi - d u_rel,x/dx, the upwind difference on the contact nodes (material arrives from
  +x, the leading edge); xi > 0 slides body 1 forward and the friction force on it is negative.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import ConvergenceError
from ..materials import Elastic
from ..meshes.plane import MeshSpec, TriMesh
from ..meshes.plane_full import block_full, cylinder_full
from ..qoi import contact_edge, half_width as profile_half_width
from ..solvers import coulomb
from ..solvers.elasticity2d import CondensedBody, boundary_dofs, make_body

UPPER_BODIES = ("block", "cylinder")
COUPLINGS = ("full", "johnson", "none")
NORMAL_LOADINGS = ("frictionless", "frictional")


@dataclass
class FrictionLineSettings:
    """Numerics, lengths as multiples of the Hertz half-width a_H. Level k uses element size
    ``h_contact * 2^-k`` on the candidate zone [-``contact_zone``, ``contact_zone``] and grading
    ``grading * 2^-k``. Blocks ``block_scale`` x (``block_width`` x ``block_depth``), clamped at the far face;
    with ``block_extrapolation`` blocks 2x and 4x larger are solved on the finest level for the finite-block
    extrapolation. ``upper_body``, ``coupling``, ``normal_loading``: see the module doc and :func:`coupled`;
    ``normal_steps`` (frictional normal loading), ``tangential_steps``: load increments."""

    levels: int = 3
    h_contact: float = 0.1
    grading: float = 0.4
    contact_zone: float = 1.3
    block_width: float = 40.0
    block_depth: float = 20.0
    block_scale: float = 32.0
    block_extrapolation: bool = True
    order: int = 2
    formulation: str = "auto"
    upper_body: str = "block"
    coupling: str = "full"
    normal_loading: str = "frictionless"
    normal_steps: int = 10
    tangential_steps: int = 1
    tol: float = 1e-9


@dataclass
class ContactPair:
    """Condensed contact of one mesh level: node abscissae ``x`` (m), tributary lengths ``w`` (m), initial
    gaps ``g0`` (m) and the relative compliance blocks (m per N/m): u_rel,x = A_xx q + A_xy p,
    u_rel,y = A_yx q + A_yy p (rigid motion of the clamped far faces excluded). ``h`` element size on the
    contact (m), ``scale`` the block scale."""

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
    scale: float = 1.0
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


def mirror_y(mesh: TriMesh) -> TriMesh:
    """The mesh reflected about y = 0, triangles reordered to keep the original orientation."""
    return TriMesh(mesh.points * np.array([[1.0], [-1.0]]), mesh.triangles[::-1].copy())


def _condensed(mesh: TriMesh, material: Elastic, s: FrictionLineSettings, clamped, contact, x_ref=None,
               tol: float = 0.0):
    """Assemble ``mesh`` and condense onto its contact DOFs with the ``clamped`` boundary fixed; returns
    (compliance over [x-dofs, y-dofs], contact abscissae, body)."""
    body = make_body(mesh, material, s.order, s.formulation)
    cb = CondensedBody(body, np.concatenate([boundary_dofs(body.basis, clamped, 0),
                                             boundary_dofs(body.basis, clamped, 1)]))
    bx, by = _contact_dofs(body.basis, contact)
    x = body.basis.doflocs[0, by]
    if x_ref is not None and (x.size != x_ref.size or np.abs(x - x_ref).max() > tol):
        raise RuntimeError("contact nodes of the two bodies do not match")
    return cb.compliance(np.concatenate([bx, by])), x, body


def condense(radius: float, upper: Elastic, lower: Elastic, a_ref: float, level: int, s: FrictionLineSettings,
             scale: float | None = None) -> ContactPair:
    """Mesh both bodies at ``level`` with blocks ``scale`` (default ``s.block_scale``) times the nominal size,
    assemble, and condense onto the contact node pairs (module doc)."""
    scale = s.block_scale if scale is None else scale
    t0 = time.perf_counter()
    h = s.h_contact * a_ref / 2**level
    x_c = s.contact_zone * a_ref
    grading = s.grading / 2**level
    tiny = 1e-9 * a_ref
    width, depth = s.block_width * a_ref * scale, s.block_depth * a_ref * scale
    # the far-field size cap grows with the block: the element count stays about constant across scales
    bmesh = block_full(width, depth, MeshSpec(h, x_c, grading, max(h, 2.0 * a_ref * scale)))
    on_contact = lambda X: (np.abs(X[1]) < tiny) & (np.abs(X[0]) < x_c + tiny)  # noqa: E731
    C, x, blk = _condensed(bmesh, lower, s, lambda X: np.abs(X[1] + depth) < tiny, on_contact)
    meshes, formulations = {"block": bmesh}, {"block": blk.formulation}
    n_dofs, n_el = blk.n_dofs, bmesh.triangles.shape[1]
    n = x.size
    if not upper.rigid:
        if s.upper_body == "block" and upper.nu == lower.nu:
            # the mirror image of the lower block: C_upper = (E_lower/E_upper) M C_lower M, M flipping y (linear
            # elasticity at a fixed Poisson ratio scales with 1/E), without assembling it again
            M = np.concatenate([np.ones(n), -np.ones(n)])
            C = C + (lower.E / upper.E) * (M[:, None] * C * M[None, :])
            meshes["upper block"], formulations["upper block"] = mirror_y(bmesh), blk.formulation
            n_dofs, n_el = 2 * n_dofs, 2 * n_el
        else:
            if s.upper_body == "block":
                umesh, name = mirror_y(bmesh), "upper block"
                clamped = lambda X: np.abs(X[1] - depth) < tiny  # noqa: E731
                where = on_contact
            else:
                umesh, name = cylinder_full(radius, MeshSpec(h, x_c, grading, max(h, radius / 5.0))), "cylinder"
                clamped = lambda X: np.abs(X[1] - radius) < 1e-9 * radius  # noqa: E731
                where = lambda X: (np.abs(X[0]) < x_c + tiny) & (X[1] < 0.5 * radius)  # noqa: E731
            Cu, _, ub = _condensed(umesh, upper, s, clamped, where, x_ref=x, tol=1e-6 * h)
            # forces on body 1 are +(q, p), on body 2 -(q, p): both compliances add in u_rel
            C = C + Cu
            meshes[name], formulations[name] = umesh, ub.formulation
            n_dofs += ub.n_dofs
            n_el += umesh.triangles.shape[1]
    w = _tributary_weights(blk, boundary_dofs(blk.basis, on_contact, 1), on_contact)
    g0 = radius - np.sqrt(radius**2 - x**2)
    return ContactPair(x, w, g0, C[:n, :n], C[:n, n:], C[n:, :n], C[n:, n:], h, n_dofs, n_el, scale, meshes,
                       formulations, time.perf_counter() - t0)


def coupled(pair: ContactPair, coupling: str) -> ContactPair:
    """The pair under a normal-tangential coupling process: ``full`` keeps both cross compliances (normal and
    tangential problems solved together, the converged Panagiotopoulos process); ``johnson`` drops A_yx, so
    tangential tractions do not act back on the pressure while the pressure-induced tangential displacement
    A_xy p stays (Johnson's process, Kalker 1990 §5.2); ``none`` drops both (exact for quasi-identical
    half-planes only)."""
    if coupling == "full":
        return pair
    if coupling == "johnson":
        return replace(pair, A_yx=np.zeros_like(pair.A_yx))
    if coupling == "none":
        return replace(pair, A_xy=np.zeros_like(pair.A_xy), A_yx=np.zeros_like(pair.A_yx))
    raise ValueError(f"coupling must be one of {COUPLINGS}, got {coupling!r}")


def quasi_identical(upper: Elastic, lower: Elastic, rtol: float = 1e-9) -> bool:
    """Dundurs' beta = 0, i.e. (1 - 2 nu1)/G1 = (1 - 2 nu2)/G2 (Johnson 1985 §5.8; Kalker 1990 §1.5): a
    normal load then causes no tangential relative displacement of two half-spaces and vice versa. A rigid
    body is quasi-identical only with an incompressible one."""
    k = [0.0 if m.rigid else (1.0 - 2.0 * m.nu) / m.shear_modulus for m in (upper, lower)]
    return abs(k[0] - k[1]) <= rtol * max(abs(k[0]), abs(k[1]), 1e-300) or max(k) == 0.0


# ----------------------------------------------------------------------------------------------------------
# Load cases on a condensed pair

@dataclass
class LineFrictionResult:
    """One load case on one mesh level. ``p``, ``q``: pair forces (N/m) on body 1 (normal compressive,
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
    crossings are located to sub-node accuracy like a contact edge (qoi.contact_edge)."""
    return np.where(stick & (p > 0), (mu * p - np.abs(q)) / pair.w, 0.0)


def zone_edges(x: np.ndarray, r: np.ndarray) -> tuple[float, float]:
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
               normal_loading: str = "frictionless", normal_steps: int = 1, tangential_steps: int = 1,
               tol: float = 1e-9) -> LineFrictionResult:
    """Cattaneo shift: W' = ``load`` (N/m) then Q' = ``tangential`` (N/m, on body 1 along +x), Coulomb ``mu``
    (``np.inf``: full adhesion). ``normal_loading``: "frictionless" (one normal step without friction) or
    "frictional" (``normal_steps`` increments with ``mu``). Quantities: ``delta_t`` (m, rigid shift of body 1's
    clamped face relative to body 2's), ``stick_half_width`` (m), p_max, half_width, total_force. ``slip``
    field (m): u_rel,x now minus u_rel,x after the normal loading (zero in the stick zone)."""
    n = pair.x.size
    p = np.zeros(n)
    q = np.zeros(n)
    dt = 0.0
    its, res = 0, 0.0
    if normal_loading == "frictionless":
        path = [(load, 0.0, 0.0)]
    else:
        path = [(load * k / normal_steps, 0.0, mu) for k in range(1, normal_steps + 1)]
    n_normal = len(path)
    path += [(load, tangential * k / tangential_steps, mu) for k in range(1, tangential_steps + 1)]
    contact = _normal_guess(pair, a_ref)
    u_normal = np.zeros(n)
    for step, (w_k, q_k, mu_k) in enumerate(path, start=1):
        # slip increment s = u_rel,x - u_rel,x(previous step), u_rel,x = A_xx q + A_xy p + delta_t
        s0 = -(pair.A_xx @ q + pair.A_xy @ p + dt)
        frictionless = mu_k == 0.0              # no traction at all: delta_t is not an unknown (it stays 0)
        sys = coulomb.FrictionSystem(pair.g0, -np.ones(n), pair.A_yy, pair.A_yx, s0,
                                      None if frictionless else np.ones(n), pair.A_xy, pair.A_xx, w_k,
                                      None if frictionless else -q_k, mu_k)
        sol = coulomb.solve(sys, contact, tol=tol)
        p, q, dt, contact = sol.p, sol.q, sol.delta_t, sol.contact
        its += sol.iterations
        res = max(res, sol.residual)
        if step == n_normal:
            u_normal = pair.A_xx @ q + pair.A_xy @ p + dt
    _check_inside(pair, p, its, tol)
    quantities = _base_quantities(pair, p)
    quantities["delta_t"] = dt
    slip = np.where(p > 0, pair.A_xx @ q + pair.A_xy @ p + dt - u_normal, 0.0)
    if np.isfinite(mu):
        left, right = zone_edges(pair.x, _stick_margin(pair, p, q, sol.stick, mu))
        quantities["stick_half_width"] = 0.5 * (right - left)
    return LineFrictionResult(pair.x, p, q, p / pair.w, q / pair.w, sol.stick, quantities, its, res,
                              len(path), slip)


def weighted_shift(x: np.ndarray, slip: np.ndarray, contact: np.ndarray, left: float, right: float,
                   n_quad: int = 256) -> float:
    """An alternative estimate of the micro-slip shift delta(Q') - delta_stick(Q') (m): the FE slip field
    weighted with the closed-form adhered traction of a 2D contact, by the reciprocal theorem.

    With q_stick = Q_c phi the adhered traction (sum phi = 1) and u = A q + delta the relative tangential
    displacement of the partial-slip state (symmetric compliance A; A q_stick + delta_stick = 0 on the
    contact), q_stick . u = q . A q_stick + delta Q_c = Q_c (delta - delta_stick), hence

        delta - delta_stick = int phi(x) u_slip(x) dx,    phi = 1 / (pi sqrt(a^2 - x^2))  on |x| < a

    (u_slip vanishes in the stick zone; Johnson 1985 §7.2, Cattaneo 1938). It is NOT the FE's own result: phi
    is the half-plane closed form, not the FE's adhered traction, so the value inherits an analytic
    ingredient; it holds only without normal-tangential coupling. It avoids the unresolved inverse-square-root
    edge of the adhered traction, which makes the FE's direct difference converge at first order only (see
    :mod:`femcheck.fem.friction_line`). The contact ends ``left``, ``right`` (m) come from the pressure;
    x = m + a sin(theta) removes the singularity: (1/pi) int u(m + a sin theta) dtheta, Gauss-Legendre in
    theta, u linear between nodes and extrapolated linearly to the ends.
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
    Slip per unit rolling distance s = xi - D u_rel,x (module doc). Quantities: creep_force_x (N/m, on
    body 1), adhesion_length (m), adhesion_fraction (-), p_max, half_width, total_force."""
    n = pair.x.size
    D = upwind_derivative(pair.x)
    sys = coulomb.FrictionSystem(pair.g0, -np.ones(n), pair.A_yy, pair.A_yx, np.full(n, float(xi)), None,
                                  -D @ pair.A_xy, -D @ pair.A_xx, load, None, mu)
    sol = coulomb.solve(sys, _normal_guess(pair, a_ref), tol=tol)
    _check_inside(pair, sol.p, sol.iterations, tol)
    quantities = _base_quantities(pair, sol.p)
    left, right = zone_edges(pair.x, _stick_margin(pair, sol.p, sol.q, sol.stick, mu))
    quantities["creep_force_x"] = float(sol.q.sum())
    quantities["adhesion_length"] = right - left
    quantities["adhesion_fraction"] = (right - left) / (2.0 * quantities["half_width"])
    return LineFrictionResult(pair.x, sol.p, sol.q, sol.p / pair.w, sol.q / pair.w, sol.stick, quantities,
                              sol.iterations, sol.residual, 1)
