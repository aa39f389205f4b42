"""Finite-body corrections of a cylindrical roller bearing's contacts at the scale of axial bins, for the
contact-resolved reference :mod:`femcheck.bem.bearing_resolved` (the split of :mod:`femcheck.fem.compliance_split`
applied to a whole bearing); SI units (m, N).

The surface compliance of a finite body is written as the half-space's plus a correction,

    u_n(receiver) = int A_HS(receiver - source) p dA + sum_bins D[bin(receiver), b] F_b,

with A_HS Boussinesq's single-body kernel on the fine contact grid and D (m/N) per unit force on a bin (a patch
of width w across the contact line and length L_we/n_b along the roller). D is the FE's patch response minus the
half-space's response to the same patch, both averaged over the receiving patch:

    D = C_FE - C_HS     (C_HS = 0 between patches of different contacts: they share no half-space),

so the two add up to the FE exactly at the bins' scale, and the fine grid keeps the half-space's exact near field.
D is smooth (the Boussinesq solution is the local limit of every elastic body's surface Green's function,
Johnson 1985 §3.2): it varies over the body's thickness (mm), not over the contact width 2b (0.1-0.2 mm), which
is why a bin's force may act on D as if spread over the patch. What remains of the FE's near-field
discretisation error sits in D's self terms and converges with the FE mesh at fixed bins; the bins' own
resolution converges with n_b (:mod:`benchmarks.bearing_resolved` measures both).

Bodies:
- the roller: a free cylinder (inertia relief, mean axes: :mod:`femcheck.fem.body_compliance`), patches on its
  two generators facing the rings (z = +r outer, z = -r inner); D_roller couples the roller's own two contacts;
- a ring: the structured 3D ring of :mod:`femcheck.fem.ring3d_compliance` (outer ring on a housing arc, inner
  ring with its bore clamped to a rigid shaft), patches = its raceway patches of half-angle a_c = w/(2 r_race).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.special import roots_legendre

from ..bem.influence import love_rectangle
from ..materials import Elastic
from ..meshes.ring3d import RingMeshSpec
from .body_compliance import BodyModel, body_compliance
from .contact_grid import ContactGrid
from .ring3d_compliance import RingFE, ring_compliance
from .rolling_compliance import MeshSettings, RollerBody, roller_mesh

# the roller's FE mesh is the crowned body of revolution of the SRB reference with a crown radius this many
# roller radii: a cylinder to within (L/2)^2/(2 R) = 1 um of crown at the 209's roller ends, far below a patch
_CYLINDER_CROWN = 2000.0


@dataclass(frozen=True)
class Bins:
    """Axial bins of one contact: ``count`` n_b over the effective ``length`` L_we (m), patch ``width`` w (m)
    across the contact line."""

    length: float
    count: int
    width: float

    @property
    def centres(self) -> np.ndarray:
        return (np.arange(self.count) - 0.5 * self.count + 0.5) * self.length / self.count

    @property
    def pitch(self) -> float:
        return self.length / self.count


@dataclass
class Correction:
    """``D`` (n, n) m/N per unit bin force and what it came from (``stats``: DOFs, times)."""

    D: np.ndarray
    stats: dict = field(default_factory=dict)


def patch_halfspace(bins: Bins, material: Elastic, order: int = 12) -> np.ndarray:
    """C_HS (n_b, n_b), m/N: mean normal displacement over receiving patch k of a single elastic half-space
    (modulus E/(1 - nu^2)) per unit force spread uniformly on patch l (Love 1929, :func:`love_rectangle`),
    the receiver mean by an order x order Gauss rule on each of 2 x 2 sub-squares of the patch (the integrand
    has log-type edge singularities only: relative error < 1e-4 at order 12, checked against order 24)."""
    e_star = material.E / (1.0 - material.nu**2)
    w, h = bins.width, bins.pitch
    t, wt = roots_legendre(order)
    # receiver points: 2 sub-intervals per direction, Gauss points in each (the kernel is smooth inside them)
    pts_x = np.concatenate([0.25 * w * (t + s) for s in (-1.0, 1.0)])
    pts_y = np.concatenate([0.25 * h * (t + s) for s in (-1.0, 1.0)])
    wx = np.concatenate([wt, wt]) / 4.0
    wy = np.concatenate([wt, wt]) / 4.0
    lags = (np.arange(bins.count)[:, None] - np.arange(bins.count)[None, :]) * h
    X, Y = np.meshgrid(pts_x, pts_y, indexing="ij")
    Wq = wx[:, None] * wy[None, :]
    out = np.empty(2 * bins.count - 1)
    for i, lag in enumerate((np.arange(2 * bins.count - 1) - bins.count + 1) * h):
        out[i] = float(np.sum(Wq * love_rectangle(X, Y + lag, w, h, e_star)))
    return out[(lags / h).round().astype(int) + bins.count - 1] / (w * h)


def roller_correction(radius: float, roller_length: float, bins: Bins, material: Elastic,
                      mesh: MeshSettings = MeshSettings(h_contact=0.5, grading=0.3, h_max=1.5e-3),
                      progress=None) -> Correction:
    """D_roller (2 n_b, 2 n_b), index c n_b + k with c = 0 the inner contact (z = -r), 1 the outer (z = +r): the
    free roller's FE patch compliance minus the half-space's on its own contact (module doc). ``mesh``: element
    size at the contact line h_contact x w, growth ``grading``, largest element ``h_max`` (m), P2 tetrahedra."""
    t0 = time.perf_counter()
    x = np.array([-bins.width, 0.0, bins.width])
    s = bins.centres
    grids = {"inner": ContactGrid((0, 0, -radius), np.inf, (0, 0, -1), (0, 1, 0), (1, 0, 0), x, s, "inner"),
             "outer": ContactGrid((0, 0, radius), np.inf, (0, 0, 1), (0, 1, 0), (1, 0, 0), x, s, "outer")}
    body = RollerBody(radius, _CYLINDER_CROWN * radius, roller_length, material)
    rm = roller_mesh(body, grids, MeshSettings(mesh.h_contact, mesh.grading, mesh.h_max, mesh.layers_per_cell, 2))
    fe = body_compliance(BodyModel("roller", rm, material, (), True, 2, 2.0 * radius), grids,
                         receivers="average", progress=progress)
    n = bins.count
    area = bins.width * bins.pitch
    C = np.empty((2 * n, 2 * n))
    for a, ra in enumerate(("inner", "outer")):
        for b, sb in enumerate(("inner", "outer")):
            T = fe.tables[(ra, sb)][2, 2]
            k0 = int(round(-fe.lag0[(ra, sb)] / fe.dx))
            C[a * n:(a + 1) * n, b * n:(b + 1) * n] = T[k0] / area
    asym = float(np.abs(C - C.T).max() / np.abs(C).max())
    C = 0.5 * (C + C.T)
    hs = patch_halfspace(bins, material)
    D = C.copy()
    D[:n, :n] -= hs
    D[n:, n:] -= hs
    return Correction(D, {"n_dofs": int(fe.stats["n_dofs"]), "elements": int(fe.stats["n_elements"]),
                          "asymmetry": asym, "self_fe": float(C[n // 2, n // 2]),
                          "self_halfspace": float(hs[n // 2, n // 2]), "time_s": time.perf_counter() - t0})


def ring_correction(spec: RingMeshSpec, material: Elastic, support_half_angle: float, bins: Bins,
                    progress=None) -> Correction:
    """D_ring (Z n_b, Z n_b), index j n_b + k: the ring's condensed patch compliance
    (:func:`femcheck.fem.ring3d_compliance.ring_compliance`; ``support_half_angle`` of the housing arc for an
    outer ring, pi for a clamped bore) minus the half-space's on each roller's own patches (module doc). The
    spec's slices and patch angle must be the bins'."""
    t0 = time.perf_counter()
    if spec.slices != bins.count or abs(2.0 * spec.patch_half_angle * spec.r_race - bins.width) > 1e-9 * bins.width \
            or abs(spec.length - bins.length) > 1e-12:
        raise ValueError("the ring mesh's slices, patch width and length must be the bins'")
    if progress:
        progress(f"ring correction: 3D FE of the ring (r_race {spec.r_race * 1e3:.3f} mm, refine {spec.refine})")
    comp = ring_compliance(RingFE(spec, material, "housing", support_half_angle))
    hs = patch_halfspace(bins, material)
    D = comp.C - np.kron(np.eye(spec.rollers), hs)
    return Correction(D, {"n_dofs": int(comp.n_dofs), "cells": int(comp.cells), "asymmetry": comp.asymmetry,
                          "self_fe": float(comp.C[bins.count // 2, bins.count // 2]),
                          "self_halfspace": float(hs[bins.count // 2, bins.count // 2]),
                          "time_s": time.perf_counter() - t0})


def fill_band(D: np.ndarray, near: int) -> np.ndarray:
    """A self block D (n, n) with the entries |k - l| <= near replaced by the solution of the discrete Laplace
    equation in (k, l) whose boundary values are the entries outside the band (mirror images at the table's
    edges: zero normal derivative). Why: there D holds the FE's discretisation error of the singular patch
    response (its self term is 20-50 % stiff at one element layer per patch), not the smooth finite-body
    correction; functions affine in (k, l) are kept exactly away from the edges."""
    from scipy.sparse import lil_matrix
    from scipy.sparse.linalg import spsolve

    n = D.shape[0]
    unknown = [(k, l) for k in range(n) for l in range(n) if abs(k - l) <= near]
    index = {u: q for q, u in enumerate(unknown)}
    A = lil_matrix((len(unknown), len(unknown)))
    rhs = np.zeros(len(unknown))

    def mirror(i):
        return -i if i < 0 else (2 * (n - 1) - i if i > n - 1 else i)

    for q, (k, l) in enumerate(unknown):
        for dk, dl in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            kk, ll = mirror(k + dk), mirror(l + dl)
            A[q, q] += 1.0
            if (kk, ll) in index:
                A[q, index[(kk, ll)]] -= 1.0
            else:
                rhs[q] += D[kk, ll]
    x = spsolve(A.tocsc(), rhs)
    out = D.copy()
    for q, (k, l) in enumerate(unknown):
        out[k, l] = x[q]
    return out


def filled(D: np.ndarray, blocks: int, near: int) -> np.ndarray:
    """D (blocks n, blocks n) with :func:`fill_band` applied to each diagonal block (a contact's own patches)."""
    n = D.shape[0] // blocks
    out = D.copy()
    for b in range(blocks):
        sl = slice(b * n, (b + 1) * n)
        out[sl, sl] = fill_band(D[sl, sl], near)
    return out
