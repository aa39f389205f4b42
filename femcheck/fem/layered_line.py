"""2D plane-strain FE reference for a rigid cylinder pressed on a coated block (layer_contact, line scenes).

A layer (E1, nu1, thickness t) is perfectly bonded to an elastic substrate (E2, nu2) or to a rigid base (the
layer's bottom clamped, no substrate mesh). The indenter is a rigid circular cylinder of radius R; the gap is
the exact circle g0(x) = R - sqrt(R^2 - x^2). Frictionless, small strain, load control: the approach is the
extra unknown that makes the contact force equal W' (N/m); the model is the symmetric half x >= 0.

Discretisation (see :mod:`femcheck.meshes.coated`): structured layer with element rows through the
thickness, Gmsh-graded substrate, shared interface nodes. Each region is assembled with its own constants and
the matrices are added (perfect bond = shared DOFs). P2 triangles by default; a region with nu > 0.45 uses the
Taylor-Hood P2/P1 mixed u-p form (locking-free, nu = 0.5 included) with its own pressure field, so the pressure
may jump across the interface as the physics requires (p = lambda div u, and lambda jumps there).

Contact: the block is condensed on the contact DOFs (:class:`femcheck.solvers.elasticity2d.CondensedBody`) and the
primal-dual active set of :mod:`femcheck.solvers.frictionless` solves the Signorini problem; nodal pressure p_i =
lam_i / w_i with w_i = int phi_i ds the node's tributary length.

Mesh family: lengths in units of a reference half-width a_ref found by pilot solves on coarse meshes (a layered
contact's width lies anywhere between the layer's and the substrate's Hertz width, or far below both on a rigid
base) and aligned so that a vertex lies on the contact edge measured on level 1 (:func:`reference_width`); level k
halves every length (nested in the layer); per quantity a convergence certificate over the levels
(:mod:`femcheck.solvers.convergence`). SI units throughout.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.sparse import bmat, csc_matrix
from skfem import (Basis, BilinearForm, ElementTriP1, ElementTriP2, ElementVector, FacetBasis, LinearForm,
                   MeshTri, asm)
from skfem.models.elasticity import linear_elasticity

from ..analytic import hertz, thin_layer
from ..errors import ConvergenceError, InputError
from ..materials import Elastic
from ..result import ModelResult
from ..scene import Key
from ..solvers import frictionless
from ..qoi import edge, peak
from ..qoi_separation import EXCLUDE, OUTER
from ..qoi_separation import radial as separation_edge
from ..solvers.convergence import certificate_stats, certify_levels
from ..solvers.elasticity2d import MIXED_ABOVE_NU, Body, CondensedBody, _deviatoric_part, _divergence, _mass
from ..meshes.coated import LAYER, SUBSTRATE, LayeredTriMesh, LayerSizing, coated_block_half

_ELEMENTS = {1: ElementTriP1, 2: ElementTriP2}
OUTER_WINDOW = OUTER - 1.0      # length of the separation window beyond the edge, in contact radii


@dataclass(frozen=True)
class FEMLayeredLineSettings:
    """Numerics, lengths in units of the reference half-width a_ref (coarsest level; level k divides every
    length by 2^k). Block ``block_width`` x ``block_depth`` (full width; the model is the half x >= 0), clamped
    at the bottom; the depth grows to 2 t when the layer is thicker than half of it."""

    levels: int = 3
    h_contact: float = 0.1
    grading: float = 0.4
    h_max: float = 2.0
    contact_zone: float = 1.3
    block_width: float = 40.0
    block_depth: float = 20.0
    layer_elements: int = 2
    order: int = 2
    formulation: str = "auto"
    tol: float = 1e-9
    geometry: str = "plane"        # "plane" (strain, per unit length) or "axisymmetric" (x = r, a sphere)


@dataclass
class LayeredLineLevel:
    """One mesh level: contact-node abscissae ``x`` (m), pressures ``p`` (Pa), scalar results and stats."""

    h: float
    x: np.ndarray
    p: np.ndarray
    p_max: float
    half_width: float
    total_force: float
    approach: float
    n_dofs: int
    n_elements: int
    layer_rows: int
    iterations: int
    residual: float
    time_s: float
    formulations: dict[str, str] = field(default_factory=dict)
    mesh: LayeredTriMesh | None = None
    edge_exponent: float = 0.5        # fitted p ~ (a^2 - x^2)^alpha near the edge
    edge_misfit: float = 0.0
    p_max_std: float = float("nan")   # standard errors of the fitted quantities (femcheck.qoi)
    half_width_std: float = float("nan")


def inverse_lame_lambda(m: Elastic) -> float:
    """1/lambda = (1 + nu)(1 - 2 nu) / (E nu) in 1/Pa: finite (zero) at nu = 1/2, where lambda is not."""
    return (1.0 + m.nu) * (1.0 - 2.0 * m.nu) / (m.E * m.nu)


def axisymmetric_elasticity(lam: float, mu: float) -> BilinearForm:
    """Axisymmetric linear elasticity (x = r, y = z; N/m for the whole ring): int (lam tr e(u) tr e(v)
    + 2 mu (e_rr e_rr + e_zz e_zz + e_tt e_tt) + mu g_rz g_rz) 2 pi r dr dz, with e_rr = du_r/dr, e_zz = du_z/dz,
    the hoop strain e_tt = u_r / r and g_rz = du_r/dz + du_z/dr (Zienkiewicz & Taylor, The Finite Element Method,
    vol. 1, 6th ed., §9.2, eqs 9.3-9.5). The quadrature points lie inside the triangles, never on the axis."""
    @BilinearForm
    def form(u, v, w):
        r = w.x[0]
        eu = (u.grad[0][0], u.grad[1][1], u[0] / r)
        ev = (v.grad[0][0], v.grad[1][1], v[0] / r)
        gu, gv = u.grad[0][1] + u.grad[1][0], v.grad[0][1] + v.grad[1][0]
        normal = lam * sum(eu) * sum(ev) + 2.0 * mu * sum(a * b for a, b in zip(eu, ev))
        return 2.0 * np.pi * r * (normal + mu * gu * gv)
    return form


def assemble_layered(lmesh: LayeredTriMesh, materials: dict[int, Elastic], order: int = 2,
                     formulation: str = "auto", geometry: str = "plane") -> tuple[Body, dict[str, str]]:
    """Plane-strain system of the coated block: sum over regions r of int C_r eps(u) : eps(v) dx (N/m).

    A region in the ``mixed`` form (``auto``: nu > MIXED_ABOVE_NU; needs P2) contributes instead
        [ int_r 2 mu_r eps(u):eps(v)   int_r p_r div v   ]
        [ int_r q_r div u             -int_r p_r q_r / lambda_r ]
    with its own continuous P1 pressure p_r on the region's nodes (appended after the displacement DOFs).
    Returns the :class:`Body` (displacement DOFs first) and the formulation used per region.
    ``geometry`` "axisymmetric": :func:`axisymmetric_elasticity`, displacement form only.
    """
    if order not in _ELEMENTS:
        raise InputError("numerics.fem_order", f"{order}; allowed: 1, 2")
    m = MeshTri(lmesh.mesh.points, lmesh.mesh.triangles)
    # the axisymmetric integrand (weight r, hoop term u_r v_r / r) is not a polynomial of the element's degree
    intorder = max(1, 2 * (order - 1)) if geometry == "plane" else 2 * order + 1
    basis = Basis(m, ElementVector(_ELEMENTS[order]()), intorder=intorder)
    K = None
    constraint_rows, constraint_diag = [], []
    used = {}
    names = {LAYER: "layer", SUBSTRATE: "substrate"}
    for r, mat in materials.items():
        idx = np.flatnonzero(lmesh.region == r)
        if idx.size == 0:
            continue
        form = formulation
        if form == "auto":
            form = "mixed" if mat.nu > MIXED_ABOVE_NU else "displacement"
        if form == "mixed" and order != 2:
            raise InputError("numerics.fem_order", f"the {names[r]} (nu = {mat.nu:g}) needs the mixed "
                             "Taylor-Hood form, which needs element order 2")
        if form == "displacement" and mat.nu >= 0.5:
            raise InputError("numerics.fem_formulation", f"nu = 0.5 in the {names[r]} needs the mixed form")
        if form == "mixed" and geometry != "plane":
            raise InputError(f"{'layer' if r == LAYER else 'materials.substrate'}.nu",
                             f"{mat.nu:g} in the axisymmetric FE; allowed (-1, {MIXED_ABOVE_NU:g}] (no mixed "
                             "axisymmetric form)")
        rb = basis.with_elements(idx)
        if form == "displacement":
            lam, mu = mat.lame()
            Kr = asm(linear_elasticity(lam, mu) if geometry == "plane" else axisymmetric_elasticity(lam, mu), rb)
        else:
            Kr = mat.shear_modulus * asm(_deviatoric_part, rb)
            pb = rb.with_element(ElementTriP1())
            nodes = np.unique(m.t[:, idx])                 # the region's own pressure nodes
            constraint_rows.append(asm(_divergence, rb, pb).tocsr()[nodes])
            constraint_diag.append(-inverse_lame_lambda(mat) * asm(_mass, pb).tocsr()[nodes][:, nodes])
        K = Kr if K is None else K + Kr
        used[names[r]] = form
    if constraint_rows:
        nb = len(constraint_rows)
        blocks = [[K] + [B.T for B in constraint_rows]]
        for i in range(nb):
            blocks.append([constraint_rows[i]] + [constraint_diag[i] if j == i else None for j in range(nb)])
        K = bmat(blocks)
    layer = materials[LAYER]
    return Body(basis, csc_matrix(K), layer, "+".join(f"{k}:{v}" for k, v in used.items())), used


def _facet_dofs(basis: Basis, facets: np.ndarray, component: int) -> np.ndarray:
    d = basis.get_dofs(facets)
    name = f"u^{component + 1}"
    dofs = np.unique(np.concatenate([d.nodal.get(name, np.empty(0, int)), d.facet.get(name, np.empty(0, int))]))
    return dofs[np.argsort(basis.doflocs[0, dofs], kind="stable")]


def tributary_lengths(basis: Basis, facets: np.ndarray, dofs: np.ndarray, geometry: str = "plane") -> np.ndarray:
    """w_i = int phi_i ds over the contact facets (m): the length each contact DOF carries (lumped); for
    ``geometry`` "axisymmetric" the area of its ring, w_i = int phi_i 2 pi r ds (m^2)."""
    fb = FacetBasis(basis.mesh, basis.elem, facets=facets, intorder=4 if geometry == "plane" else 6)
    if geometry == "plane":
        return asm(LinearForm(lambda v, _: v[1]), fb)[dofs]
    return asm(LinearForm(lambda v, w: 2.0 * np.pi * w.x[0] * v[1]), fb)[dofs]


def solve_level(radius: float, layer: Elastic, substrate: Elastic, thickness: float, load_per_length: float,
                a_ref: float, level: int, s: FEMLayeredLineSettings, contact_zone: float | None = None
                ) -> LayeredLineLevel:
    """Solve one mesh level (``level`` 0 = coarsest) with lengths scaled by ``a_ref`` (m). The half model
    carries W'/2 (plane strain; ``load_per_length`` N/m); the axisymmetric model (``s.geometry``, a sphere of
    ``radius`` on the coated block, x = r) the whole load (N). Raises ConvergenceError if the contact reaches the
    end of the candidate zone."""
    t0 = time.perf_counter()
    zone = (s.contact_zone if contact_zone is None else contact_zone) * a_ref
    sizing = LayerSizing(s.h_contact * a_ref, zone, s.grading, s.h_max * a_ref, s.layer_elements)
    depth = max(s.block_depth * a_ref, 2.0 * thickness)
    lm = coated_block_half(s.block_width * a_ref, depth, thickness, sizing, level, rigid_substrate=substrate.rigid)
    mats = {LAYER: layer} if substrate.rigid else {LAYER: layer, SUBSTRATE: substrate}
    body, forms = assemble_layered(lm, mats, s.order, s.formulation, s.geometry)
    basis, mesh = body.basis, body.basis.mesh
    tiny = 1e-9 * a_ref
    bottom_y = -thickness if substrate.rigid else -lm.depth
    X = basis.doflocs
    bfac = mesh.boundary_facets()
    mid = mesh.p[:, mesh.facets[:, bfac]].mean(axis=1)
    f_bottom = bfac[np.abs(mid[1] - bottom_y) < tiny]
    f_sym = bfac[np.abs(mid[0]) < tiny]
    f_contact = bfac[(np.abs(mid[1]) < tiny) & (mid[0] < zone + tiny)]
    fixed = np.concatenate([_facet_dofs(basis, f_bottom, 0), _facet_dofs(basis, f_bottom, 1),
                            _facet_dofs(basis, f_sym, 0)])
    cb = CondensedBody(body, fixed)
    dofs = _facet_dofs(basis, f_contact, 1)
    x = X[0, dofs]
    W = cb.compliance(dofs)
    g0 = radius - np.sqrt(radius**2 - x**2)          # exact circle, at P2 mid-side nodes too
    w = tributary_lengths(basis, f_contact, dofs, s.geometry)
    share = 0.5 if s.geometry == "plane" else 1.0      # the half model of the plane section; the whole ring
    sys = frictionless.CondensedContact(g0, -np.ones_like(x), W, share * load_per_length)
    sol = frictionless.active_set(sys, x <= a_ref, tol=s.tol)
    # a P2 corner on the axis carries no ring area (int phi 2 pi r ds = 0) and no force: it has no pressure of
    # its own; the estimators read the field from the other nodes (the peak's even fit reaches r = 0)
    has_area = w > 1e-12 * w.max()
    r_all = x
    x, p = x[has_area], sol.lam[has_area] / w[has_area]
    if p[-1] > 0:
        raise ConvergenceError("FEM layered line contact", sol.iterations, np.inf, s.tol,
                               "contact reached the edge of the candidate zone; raise numerics.fem_contact_zone")
    h = s.h_contact * a_ref / 2**level
    # shape-agnostic estimators (femcheck.qoi): the edge is a power law with its exponent fitted (1/2 on a thick
    # layer, 1 on a thin compressible one, 2 on a thin incompressible one), the peak a local quartic
    e, pk = edge(x, p), peak(x, p, centre=0.0)
    position, std = e.position, e.std
    # the edge from the separation beyond it (femcheck.qoi_separation.radial), where the family's coarsest level
    # puts 4 elements within the layer's thickness: the 3/2 law of the separation holds within about t of the edge
    # (the pressure's edge turns square-root within the layer's boundary layer), so the window is at most t long
    # and needs 4 elements in it. The lumped P2 pressures' edge fit stays 0.14 % inside Hertz's radius down to a/40
    # on the axisymmetric section and left layer-rigid's levels (t/a 0.09) oscillating (estimate 3 %); where 4
    # coarsest elements overrun t (coated-roller's coatings, t/a 0.02-0.06 at a/20) the window would overrun the
    # boundary layer and the separation's levels oscillated (estimates 0.05-0.3 %): the pressure fit stays there.
    # (the candidate zone must hold the window too: exclusion, half an element and 4 elements beyond the edge)
    h0 = s.h_contact * a_ref
    if s.geometry != "plane" or (4.0 * h0 <= thickness and zone - a_ref >= (EXCLUDE + 4.5) * h0):
        rough = float(x[p > 0].max())
        sep = separation_edge(r_all, sol.gap, rough, h, outer=1.0 + min(OUTER_WINDOW, thickness / rough))
        position, std = sep["edge"], sep["edge_std"]
    return LayeredLineLevel(h, x, p, pk.value, position, float(sol.lam.sum()) / share, sol.delta,
                            body.n_dofs, int(mesh.t.shape[1]), lm.layer_rows, sol.iterations, sol.residual,
                            time.perf_counter() - t0, forms, lm, e.exponent, e.misfit, pk.std, std)


def width_guess(radius: float, layer: Elastic, substrate: Elastic, thickness: float, load: float,
                geometry: str = "plane") -> float:
    """A first guess of the half-width (m) for the pilot solve: the layer's Hertz width, the substrate's, and
    on a rigid base the thin-layer width (Johnson 1985 §5.9; compressible or squeeze-film) — the largest of the
    ones that can apply, so that the pilot's candidate zone covers the contact. ``geometry`` "axisymmetric":
    the contact radius of a sphere (load in N)."""
    point = geometry != "plane"

    def hertz_size(mat):
        if point:
            return hertz.point_contact(load, radius, mat.E / (1.0 - mat.nu**2)).semi_axis_x
        return hertz.line_contact(load, radius, mat.E / (1.0 - mat.nu**2)).half_width

    a_layer = hertz_size(layer)
    kind = "circular" if point else "line"
    if substrate.rigid:
        if layer.nu <= thin_layer.NU_COMPRESSIBLE_MAX:
            a_thin = thin_layer.compressible(layer.E, layer.nu, thickness, radius, load, kind).a
        else:
            a_thin = thin_layer.incompressible(layer.E, thickness, radius, load, kind).a
        return min(a_layer, a_thin)
    return max(a_layer, hertz_size(substrate))


# The family is aligned on level 1's edge whatever the number of levels (so level 0 is the same mesh and solution
# when a reference's coarsest level is re-solved alone).
ALIGN_LEVEL = 1


def reference_width(radius: float, layer: Elastic, substrate: Elastic, thickness: float, load: float,
                    s: FEMLayeredLineSettings, max_pilots: int = 5, align_tol: float = 1e-3,
                    max_align: int = 3) -> tuple[float, list[float]]:
    """Reference half-width a_ref (m) that scales the mesh family, which then has a vertex at a_ref on every level
    (the contact zone is meshed uniformly from x = 0 in steps of h_contact a_ref / 2^k).

    First pilot solves on the coarsest mesh with a candidate zone of 2 a_guess, repeated with a_guess <- measured
    width until two agree within 10 %; then the family is *aligned*: level 1 is solved on a_ref and a_ref is set
    to its measured edge (:func:`femcheck.qoi.edge`) until it moves by less than ``align_tol``. An edge-aligned
    family keeps the contact edge at the same place relative to the nodes on every level, which the discrete
    contact's edge is sensitive to (measured on layer-line: edges over four unaligned levels scattered by 1 %,
    aligned by 0.04 %); the edge itself is still the estimator's value on each level, never the node."""
    a = width_guess(radius, layer, substrate, thickness, load, s.geometry)
    history = [a]
    for _ in range(max_pilots):
        try:
            lv = solve_level(radius, layer, substrate, thickness, load, a, 0, s, contact_zone=2.0)
        except ConvergenceError:
            a *= 2.0                                   # contact wider than the pilot's zone
            history.append(a)
            continue
        history.append(lv.half_width)
        if abs(lv.half_width / a - 1.0) < 0.1:
            a = lv.half_width
            break
        a = lv.half_width
    else:
        raise ConvergenceError("FEM layered pilot (contact width)", max_pilots, abs(history[-1] / history[-2] - 1),
                               0.1, "the pilot widths did not settle")
    for _ in range(max_align):
        edge_ = solve_level(radius, layer, substrate, thickness, load, a, ALIGN_LEVEL, s).half_width
        history.append(edge_)
        moved = abs(edge_ / a - 1.0)
        a = edge_
        if moved < align_tol:
            break
    return a, history


FEM_SCHEMA: dict[str, Key] = {
    "numerics.fem_levels": Key("int", "-", "FEM mesh levels (>= 3 for Richardson extrapolation)", lo=1, hi=6,
                               lo_closed=True, hi_closed=True),
    "numerics.fem_h_contact": Key("float", "a_ref", "FEM element size over the contact zone, coarsest level",
                                  lo=0.005, hi=0.5, lo_closed=True, hi_closed=True),
    "numerics.fem_grading": Key("float", "-", "FEM element growth per unit distance, coarsest level", lo=0.0,
                                hi=2.0, hi_closed=True),
    "numerics.fem_h_max": Key("float", "a_ref", "largest FEM element, coarsest level", lo=0.05, hi=20.0,
                              hi_closed=True),
    "numerics.fem_contact_zone": Key("float", "a_ref", "FEM candidate contact zone / reference width", lo=1.05,
                                     hi=3.0, hi_closed=True),
    "numerics.fem_block": Key("float", "a_ref", "FEM block size (2D: width; depth is half of it) / reference "
                              "width", lo=20.0, hi=1000.0, lo_closed=True, hi_closed=True),
    "numerics.fem_layer_elements": Key("int", "-", "FEM element rows through the layer, coarsest level (doubled "
                                       "per level)", lo=1, hi=32, lo_closed=True, hi_closed=True),
    "numerics.fem_order": Key("int", "-", "FEM element order (2D: P1 or P2; 3D: P1 only)", lo=1, hi=2,
                              lo_closed=True, hi_closed=True),
    "numerics.fem_formulation": Key("str", "-", "auto: mixed u-p (Taylor-Hood) in a region with nu > 0.45",
                                    choices=("auto", "displacement", "mixed")),
}
FEM_DEFAULTS: dict[str, Any] = {
    "numerics.fem_levels": 3,
    "numerics.fem_h_contact": 0.1,
    "numerics.fem_grading": 0.4,
    "numerics.fem_h_max": 2.0,
    "numerics.fem_contact_zone": 1.3,
    "numerics.fem_block": 40.0,
    "numerics.fem_layer_elements": 2,
    "numerics.fem_order": 2,
    "numerics.fem_formulation": "auto",
}


def settings(params: dict[str, Any]) -> FEMLayeredLineSettings:
    p = {**FEM_DEFAULTS, **{k: v for k, v in params.items() if k.startswith("numerics.fem_")}}
    return FEMLayeredLineSettings(levels=int(p["numerics.fem_levels"]), h_contact=p["numerics.fem_h_contact"],
                                  grading=p["numerics.fem_grading"], h_max=p["numerics.fem_h_max"],
                                  contact_zone=p["numerics.fem_contact_zone"], block_width=p["numerics.fem_block"],
                                  block_depth=0.5 * p["numerics.fem_block"],
                                  layer_elements=int(p["numerics.fem_layer_elements"]),
                                  order=int(p["numerics.fem_order"]), formulation=p["numerics.fem_formulation"])


def materials_of(params: dict[str, Any]) -> tuple[Elastic, Elastic, float]:
    """(layer, substrate, thickness) from the layer_contact keys, checked: E > 0, -1 < nu <= 0.5 in the layer
    (0.5 through the mixed form), -1 < nu < 0.5 in an elastic substrate, thickness > 0."""
    def num(key):
        if key not in params:
            raise InputError(key, "required key is missing")
        v = float(params[key])
        if not np.isfinite(v):
            raise InputError(key, f"{v!r}; allowed: a finite number")
        return v

    E1, nu1, t = num("layer.E"), num("layer.nu"), num("layer.thickness")
    if E1 <= 0:
        raise InputError("layer.E", f"{E1:g}; allowed (0, inf) Pa")
    if not -1.0 < nu1 <= 0.5:
        raise InputError("layer.nu", f"{nu1:g}; allowed (-1, 0.5]")
    if t <= 0:
        raise InputError("layer.thickness", f"{t:g}; allowed (0, inf) m")
    if bool(params.get("materials.substrate.rigid", False)):
        sub = Elastic(1.0, 0.0, True)
    else:
        E2, nu2 = num("materials.substrate.E"), num("materials.substrate.nu")
        if E2 <= 0:
            raise InputError("materials.substrate.E", f"{E2:g}; allowed (0, inf) Pa")
        if not -1.0 < nu2 <= 0.5:
            raise InputError("materials.substrate.nu", f"{nu2:g}; allowed (-1, 0.5]")
        sub = Elastic(E2, nu2)
    return Elastic(E1, nu1), sub, t


def solve_family(params: dict[str, Any], s: FEMLayeredLineSettings, first_level: int = 0, progress=None
                 ) -> tuple[Elastic, Elastic, float, float, list[float], list[LayeredLineLevel]]:
    """(layer, substrate, thickness (m), a_ref (m), pilot widths (m), levels) of the family of ``s`` from flat
    parameters (``geometry.radius`` and ``load.per_length`` (N/m), or ``load.normal`` (N) for the axisymmetric
    section): pilots, alignment, then ``s.levels`` levels from ``first_level``."""
    layer, sub, t = materials_of(params)
    load_key, unit = ("load.per_length", "N/m") if s.geometry == "plane" else ("load.normal", "N")
    R, load = float(params["geometry.radius"]), float(params[load_key])
    if R <= 0:
        raise InputError("geometry.radius", f"{R:g}; allowed (0, inf) m")
    if load <= 0:
        raise InputError(load_key, f"{load:g}; allowed (0, inf) {unit}")
    if progress:
        progress("FEM pilot solves (contact size)")
    a_ref, pilots = reference_width(R, layer, sub, t, load, s)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FEM level {k + 1}/{s.levels}")
        levels.append(solve_level(R, layer, sub, t, load, a_ref, first_level + k, s))
    return layer, sub, t, a_ref, pilots, levels


def model(params: dict[str, Any], progress=None) -> ModelResult:
    """The ``fem`` model of the layered line scenes (rigid cylinder on a coated block) from flat parameters:
    ``layer.E|nu|thickness``, ``materials.substrate.E|nu|rigid``, ``geometry.radius``, ``load.per_length`` and
    the ``numerics.fem_*`` keys of FEM_SCHEMA. Quantities p_max (Pa, :func:`femcheck.qoi.peak`), half_width (m,
    :func:`femcheck.qoi.edge`): the certificate's value (Richardson-extrapolated when the levels are in the
    asymptotic range, else the finest level), total_force (N/m, finest level)."""
    t_start = time.perf_counter()
    s = settings(params)
    layer, sub, t, a_ref, pilots, levels = solve_family(params, s, progress=progress)
    fine = levels[-1]
    quantities = ("p_max", "half_width")
    finest = {q: getattr(fine, q) for q in quantities}
    stats: dict[str, Any] = {
        "method": "active_set", "element_order": s.order, "formulation": fine.formulations, "finest": finest,
        "a_ref": a_ref, "pilot_widths": pilots, "thickness_over_a": t / fine.half_width,
        "substrate": "rigid" if sub.rigid else {"E": sub.E, "nu": sub.nu},
        "block": {"width": s.block_width * a_ref, "depth": max(s.block_depth * a_ref, 2.0 * t)},
        "levels": [{"h": lv.h, "h_over_a": lv.h / a_ref, "layer_rows": lv.layer_rows, "n_dofs": lv.n_dofs,
                    "n_elements": lv.n_elements, "p_max": lv.p_max, "half_width": lv.half_width,
                    "edge_exponent": lv.edge_exponent, "edge_misfit": lv.edge_misfit, "approach": lv.approach,
                    "p_max_std": lv.p_max_std, "half_width_std": lv.half_width_std,
                    "iterations": lv.iterations, "residual": lv.residual, "total_force": lv.total_force,
                    "time_s": lv.time_s} for lv in levels],
    }
    certs = certify_levels(stats["levels"], quantities)
    stats.update(certificate_stats(certs))
    q = {k: c.value for k, c in certs.items()}
    q["total_force"] = fine.total_force
    return ModelResult("fem", time_s=time.perf_counter() - t_start, quantities=q, stats=stats,
                       fields={"x": fine.x, "pressure": fine.p})
