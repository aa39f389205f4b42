"""Compliance of an elastic bearing ring from a coarse 3D FE, condensed onto the raceway slices (spec
bearing-load.md P3), SI units (m, N, Pa).

The ring (:mod:`femcheck.meshes.ring3d`: structured hexahedra, 20-node serendipity elements ``ElementHexS2``) is
loaded on its raceway by one patch per roller position j and ISO/TS 16281 slice k,

    patch (j, k) = {r = r_race, |theta - psi_j| <= a_c, |z - x_k| <= L/(2 n_s)},   area A = 2 a_c r_race L/n_s,

with a uniform pressure of unit resultant magnitude pushing the raceway away from the roller (outer ring: along
+e_r(theta)): load vector b_jk = int_patch N^T e_r dS / A. Several rows (``mesh.row_centres``) number the patches
(i Z + j) n_s + k; with a contact angle alpha (tapered rows) the load acts along the contact normal
n_i = cos(alpha) e_r + s_i sin(alpha) e_z of row i (the direction in which the inner ring's displacement raises the
approach, :func:`femcheck.analytic.iso16281.sliced_equilibrium`; the raceway stays the cylinder r = r_race: the
cone of a real cup is not meshed, a coarse-compliance approximation). The generalised displacement work-conjugate to that load
is the patch-averaged radial displacement w_jk = b_jk . U = (1/A) int_patch u . e_r dS, so the condensed
compliance (m/N) is

    C = B^T K_ff^-1 B    (B = [b_jk], K_ff: stiffness on the DOFs not held by the support),

symmetric by Maxwell-Betti (C_ab = C_ba; checked numerically in the tests: it measures the solve's accuracy).
K_ff is factorised once (:class:`femcheck.solvers.multirhs.SPDFactor`: PARDISO, or SuperLU for small systems) and
the Z n_s loads are solved as one multi-right-hand-side block; C is then reused for every load case.

What C contains: the ring's bending, shear and hoop deformation and its local compression under a patch of
circumferential width 2 a_c r_race (chosen of the order of the mesh, not of the Hertz width b ~ 0.1 mm); the
Hertz approach of the roller contacts is the slice law's. The raceway's local compression under the real
contact strip (width 2b) minus that under the patch is therefore not in the model; for a half-plane it is
(2 (1 - nu^2)/(pi E)) ln(a_c r_race / b) per unit line load, and the ISO/TS 16281 constant (a whole roller between
two steel raceways) already carries a local flattening of both raceways. Model definition, stated: the patch
width is an input (``patch_half_angle``), and the checks hold C fixed across the models they compare.

Supports (``support``):
- ``"housing"``: the back surface r = r_back clamped (all three components) where the angle from the load line
  theta = 0 is within ``housing_half_angle`` (pi: a rigid housing all round; less: a housing arc, the
  Jones-Harris flexibly supported ring) and, with ``support_z``, only over that axial range (a chock held at a
  screw or load cell);
- ``"plane_strain"``: u_z = 0 on both end faces and three pins (u_x, u_y at theta = pi/2 and u_x at -pi/2 on the
  back surface, mid-width) that stop the in-plane rigid motion without reacting to a self-equilibrated load:
  the free ring in plane strain, for the curved-beam check of :func:`diametral_changes`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import coo_matrix, csr_matrix
from skfem import Basis, ElementHexS2, ElementVector, FacetBasis, asm

from ..materials import Elastic
from ..meshes.ring3d import RingMeshSpec, ring_mesh
from ..solvers.multirhs import SPDFactor

SUPPORTS = ("housing", "plane_strain")


@dataclass(frozen=True)
class RingFE:
    """Inputs of :func:`ring_fe`: the mesh spec, the ring ``material``, the ``support`` (module doc) and, for
    ``"housing"``, its half-angle (rad) about the load line."""

    mesh: RingMeshSpec
    material: Elastic
    support: str = "housing"
    housing_half_angle: float = np.pi
    support_z: tuple | None = None      # (z_lo, z_hi): the housing support only over this axial range (m)
    contact_angle: float = 0.0          # alpha (rad): the patch loads act along the contact normal
    row_signs: tuple = (1,)             # s_i = +-1 per row: the normal's axial component s_i sin(alpha)

    def __post_init__(self):
        if self.support not in SUPPORTS:
            raise ValueError(f"support must be one of {SUPPORTS}, got {self.support!r}")
        if len(self.row_signs) != self.mesh.rows:
            raise ValueError(f"row_signs needs one sign per row ({self.mesh.rows}), got {self.row_signs}")


@dataclass
class RingSystem:
    """The assembled ring: ``K`` (all DOFs), ``free`` DOFs, load matrix ``B`` (n_dofs, Z n_s; column j n_s + k is
    patch (j, k)), ``n_dofs``, ``cells``, timings (s)."""

    spec: RingFE
    K: csr_matrix
    free: np.ndarray
    B: np.ndarray
    n_dofs: int
    cells: int
    times: dict = field(default_factory=dict)


@dataclass
class RingCompliance:
    """``C`` (Z n_s, Z n_s) m/N, symmetrised; ``asymmetry`` max |C - C^T| / max |C| before that; ``n_dofs``,
    ``cells``, ``times`` (s: mesh, assembly, factorisation, solves), ``backend``, ``residual`` of the solves."""

    C: np.ndarray
    asymmetry: float
    n_dofs: int
    cells: int
    times: dict
    backend: str
    residual: float


def _patch_labels(spec: RingMeshSpec, centres: np.ndarray) -> np.ndarray:
    """Patch index (i Z + j) n_s + k (row i, roller j, slice k) of raceway facets with centroids ``centres``
    (3, n), -1 outside every patch."""
    sector = 2.0 * np.pi / spec.rollers
    rel = np.mod(np.arctan2(centres[1], centres[0]) - spec.first_angle + 0.5 * sector, 2.0 * np.pi) - 0.5 * sector
    j = np.floor((rel + 0.5 * sector) / sector).astype(int) % spec.rollers
    off = rel - j * sector
    zc = np.asarray(spec.row_centres, dtype=float)
    i = np.argmin(np.abs(centres[2][None, :] - zc[:, None]), axis=0)
    zl = centres[2] - zc[i]
    k = np.floor((zl + 0.5 * spec.length) / (spec.length / spec.slices)).astype(int)
    inside = (np.abs(off) < spec.patch_half_angle) & (k >= 0) & (k < spec.slices) & \
        (np.abs(zl) < 0.5 * spec.length)
    return np.where(inside, (i * spec.rollers + j) * spec.slices + k, -1)


def stiffness(mesh, material: Elastic, chunk: int = 2000) -> csr_matrix:
    """Stiffness (N/m) of 20-node serendipity hexahedra, 27-point Gauss rule, vector DOFs interleaved
    (3 n + i), the same matrix as skfem's ``asm(linear_elasticity(lam, mu), basis)`` (checked in the tests) but
    vectorised over the elements (skfem's form takes 14-20 s for 1.6k cells; this 0.3 s):

        K_e[(a, i), (b, j)] = int lam G_ai G_bj + mu (delta_ij G_ak G_bk + G_aj G_bi) dV,   G_ai = d N_a / d x_i."""
    lam, mu = material.lame()
    sb = Basis(mesh, ElementHexS2(), intorder=4)
    nb = sb.Nbfun
    G = np.stack([sb.basis[a][0].grad for a in range(nb)])        # (nb, 3, n_el, n_q)
    dx = sb.dx
    rows, cols, vals = [], [], []
    eye = np.eye(3)
    for e0 in range(0, dx.shape[0], chunk):
        g = G[:, :, e0:e0 + chunk]
        w = dx[e0:e0 + chunk]
        T = np.einsum("aieq,bjeq->eaibj", g, g * w[None, None], optimize=True)
        lap = np.einsum("eakbk->eab", T)
        Ke = lam * T + mu * (lap[:, :, None, :, None] * eye[None, None, :, None, :] + T.transpose(0, 1, 4, 3, 2))
        dofs = (3 * sb.element_dofs[:, e0:e0 + chunk].T[:, :, None] + np.arange(3)[None, None, :]).reshape(-1, 3 * nb)
        rows.append(np.repeat(dofs, 3 * nb, axis=1).ravel())
        cols.append(np.tile(dofs, (1, 3 * nb)).ravel())
        vals.append(Ke.reshape(-1))
    n = 3 * sb.N
    return coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)).tocsr()


def ring_system(fe: RingFE) -> RingSystem:
    """Mesh, stiffness, supports and patch loads of the ring (module doc)."""
    s = fe.mesh
    times = {}
    t0 = time.perf_counter()
    mesh = ring_mesh(s)
    times["mesh"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    basis = Basis(mesh, ElementVector(ElementHexS2()), intorder=4)
    K = stiffness(mesh, fe.material)
    # raceway facets and their patches
    bf = mesh.boundary_facets()
    cen = mesh.p[:, mesh.facets[:, bf]].mean(axis=1)
    r_f = np.hypot(mesh.p[0, mesh.facets[:, bf]], mesh.p[1, mesh.facets[:, bf]])
    thick = abs(s.r_back - s.r_race)
    on_race = np.all(np.abs(r_f - s.r_race) < 1e-6 * thick, axis=0)
    facets = bf[on_race]
    labels = _patch_labels(s, cen[:, on_race])
    facets, labels = facets[labels >= 0], labels[labels >= 0]
    npatch = s.rows * s.rollers * s.slices
    if np.bincount(labels, minlength=npatch).min() != (2 * s.refine) * s.refine * s.per_slice:
        raise RuntimeError("ring mesh: a patch is not the expected union of raceway facets")
    fb = FacetBasis(mesh, basis.elem, facets=facets, intorder=4)
    area = 2.0 * s.patch_half_angle * s.r_race * s.length / s.slices
    sign = 1.0 if s.r_back > s.r_race else -1.0      # push the raceway away from the roller
    # b_ijk = int N^T n dS / A by the facet basis' own quadrature, every facet added to its patch's column; the
    # contact normal n = cos(alpha) e_r + s_i sin(alpha) e_z of the facet's row (e_r for a radial bearing)
    x = fb.global_coordinates().value                # (3, n_facets, n_q)
    er = x[:2] / np.hypot(x[0], x[1])
    ca, sa = np.cos(fe.contact_angle), np.sin(fe.contact_angle)
    sz = (sa * np.asarray(fe.row_signs, dtype=float)[labels // (s.rollers * s.slices)])[:, None]
    local = np.stack([np.sum((ca * (phi[0].value[0] * er[0] + phi[0].value[1] * er[1]) + sz * phi[0].value[2])
                             * fb.dx, axis=1) for phi in fb.basis])          # (n_local, n_facets)
    B = np.zeros((basis.N, npatch))
    np.add.at(B, (fb.element_dofs, np.broadcast_to(labels, fb.element_dofs.shape)), sign * local / area)
    # supports
    loc = basis.doflocs
    rad = np.hypot(loc[0], loc[1])
    comp = np.tile(np.arange(3), basis.N // 3)      # interleaved x, y, z per node
    back = np.abs(rad - s.r_back) < 1e-6 * thick
    if fe.support == "housing":
        ang = np.abs(np.arctan2(loc[1], loc[0]))
        on = back & (ang <= fe.housing_half_angle + 1e-9)
        if fe.support_z is not None:
            on &= (loc[2] >= fe.support_z[0] - 1e-9 * s.width) & (loc[2] <= fe.support_z[1] + 1e-9 * s.width)
        held = np.flatnonzero(on)
    else:
        ends = np.abs(np.abs(loc[2]) - 0.5 * s.width) < 1e-9 * s.width
        held = [np.flatnonzero(ends & (comp == 2))]
        for angle, comps in ((0.5 * np.pi, (0, 1)), (-0.5 * np.pi, (0,))):
            target = np.array([s.r_back * np.cos(angle), s.r_back * np.sin(angle), 0.0])
            d = np.linalg.norm(loc - target[:, None], axis=0)
            node = d < d.min() + 1e-9 * s.width
            for c in comps:
                held.append(np.flatnonzero(node & (comp == c)))
        held = np.unique(np.concatenate(held))
    free = np.setdiff1d(np.arange(basis.N), held)
    times["assembly"] = time.perf_counter() - t0
    return RingSystem(fe, K, free, B, basis.N, mesh.t.shape[1], times)


def ring_compliance(fe: RingFE, backend: str = "auto", system: RingSystem | None = None) -> RingCompliance:
    """C = B^T K_ff^-1 B (module doc): one factorisation, Z n_s right-hand sides."""
    sys_ = system or ring_system(fe)
    times = dict(sys_.times)
    Kff = sys_.K[sys_.free][:, sys_.free].tocsr()
    Bf = sys_.B[sys_.free]
    t0 = time.perf_counter()
    fac = SPDFactor(Kff, backend=backend, tol=1e-8)
    times["factor"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    X = fac.solve(Bf)
    times["solve"] = time.perf_counter() - t0
    stats = fac.stats
    fac.free()
    C = Bf.T @ X
    asym = float(np.abs(C - C.T).max() / np.abs(C).max())
    return RingCompliance(0.5 * (C + C.T), asym, sys_.n_dofs, sys_.cells, times, stats.backend, stats.residual)


def curved_beam_diametral(load_per_length: float, mean_radius: float, thickness: float, material: Elastic):
    """Thin ring (bending only; Timoshenko, *Strength of Materials* I, curved bars; Roark, *Formulas for Stress
    and Strain*, thin rings) under two equal and opposite line loads P (N/m) along a diameter, plane strain
    (E' = E/(1 - nu^2)), I = t^3/12 per unit length (m^3):

        Delta D_along = (pi/4 - 2/pi) P R^3/(E' I),   Delta D_across = (2/pi - 1/2) P R^3/(E' I)

    (diameter change along the loads and across them, m; opposite signs, magnitudes returned)."""
    e_prime = material.E / (1.0 - material.nu**2)
    k = load_per_length * mean_radius**3 / (e_prime * thickness**3 / 12.0)
    return (np.pi / 4 - 2 / np.pi) * k, (2 / np.pi - 0.5) * k
