"""Condensed compliances of the bodies of the 2D bearing section (plane strain, P1/P2, SI units): one roller
(geometric similarity: condensed once in its own frame, the same for every roller) and the rings (on their
contact zones, block-circulant when the support is axisymmetric).

Normal directions: all pairs of roller j act along e_j (its radial line). A compliance here is "displacement
along the pair direction, towards the other body, per unit pair force pressing the bodies together" (m per
N/m), so every matrix is symmetric positive (semi-)definite and adds to the gap (femcheck.solvers.bearing_contact).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import BilinearForm, asm
from skfem.helpers import dot

from ..materials import Elastic
from ..meshes.plane import TriMesh
from ..solvers.elasticity2d import Body, CondensedBody, boundary_dofs, make_body


@BilinearForm
def _mass(u, v, w):
    return dot(u, v)


def node_table(body: Body) -> tuple[np.ndarray, np.ndarray]:
    """Locations (2, N) and (x, y) DOFs (2, N) of every node: vertices, then (P2) mid-side nodes."""
    m, b = body.basis.mesh, body.basis
    xy = m.p
    dofs = b.nodal_dofs
    if b.facet_dofs.size:
        xy = np.concatenate([xy, m.p[:, m.facets].mean(axis=1)], axis=1)
        dofs = np.concatenate([dofs, b.facet_dofs], axis=1)
    return xy, dofs


def zone_nodes(xy: np.ndarray, radius: float, angle: float, t_c: float, tol: float, side: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Nodes on the circle of ``radius`` (within ``tol``) whose perpendicular offset t from the radial line at
    ``angle`` is within [-t_c, t_c], on the ``side`` (+1: along e_r, -1: opposite) of the centre; returns
    (node indices sorted by t, t)."""
    c, s = np.cos(angle), np.sin(angle)
    t = -xy[0] * s + xy[1] * c
    along = xy[0] * c + xy[1] * s
    r = np.hypot(xy[0], xy[1])
    sel = np.flatnonzero((np.abs(r - radius) < tol) & (np.abs(t) <= t_c * (1 + 1e-9)) & (side * along > 0))
    order = np.argsort(t[sel], kind="stable")
    return sel[order], t[sel][order]


def expected_offsets(offsets: np.ndarray, order: int) -> np.ndarray:
    """Zone node offsets: the vertices, and for P2 also the chord midpoints, ascending."""
    if order == 1:
        return offsets
    mids = 0.5 * (offsets[1:] + offsets[:-1])
    return np.sort(np.concatenate([offsets, mids]))


def tributary_lengths(t: np.ndarray, order: int) -> np.ndarray:
    """int phi_i ds over a uniform zone polyline (m): P1 h/2 | h; P2 vertices h/6 (ends) | h/3, mid nodes 2h/3
    (h: chord length), i.e. the length each node's pair force acts over."""
    if order == 1:
        h = np.diff(t)
        w = np.zeros_like(t)
        w[:-1] += h / 2
        w[1:] += h / 2
        return w
    h = t[2::2] - t[:-2:2]
    w = np.zeros_like(t)
    w[:-2:2] += h / 6
    w[2::2] += h / 6
    w[1::2] = 2 * h / 3
    return w


def _check_zone(t: np.ndarray, offsets: np.ndarray, order: int, what: str) -> None:
    want = expected_offsets(offsets, order)
    if t.shape != want.shape or np.abs(t - want).max() > 1e-6 * (offsets[1] - offsets[0]):
        raise RuntimeError(f"{what}: contact-zone nodes do not match the zone offsets "
                           f"({t.size} found, {want.size} expected)")


@dataclass
class RollerCompliance:
    """Compliance of one roller at its two contact zones, relative to its mean rigid motion (inertia relief:
    the loads' resultant and moment are balanced by body forces proportional to mass, and the rigid part of the
    displacement is removed). ``W`` (2n, 2n): rows/columns [inner zone (along +e_r), outer zone (along -e_r)],
    ``t`` (n,) offsets, ``n_dofs``, ``mesh``. The inner+outer displacement of the t = 0 nodes is the roller's
    diametral compression Delta_d."""

    W: np.ndarray
    t: np.ndarray
    n_dofs: int
    mesh: TriMesh


def _inertia_relief(body: Body, xy: np.ndarray, dofs: np.ndarray, groups: np.ndarray | None = None):
    """Rigid modes Phi (ndof, 3 g) of every disconnected group of nodes and the projectors' ingredients
    (M Phi, (Phi^T M Phi)^-1)."""
    n = body.n_dofs
    groups = np.zeros(xy.shape[1], int) if groups is None else groups
    g = int(groups.max()) + 1
    Phi = np.zeros((n, 3 * g))
    for k in range(g):
        sel = groups == k
        Phi[dofs[0, sel], 3 * k] = 1.0
        Phi[dofs[1, sel], 3 * k + 1] = 1.0
        Phi[dofs[0, sel], 3 * k + 2] = -xy[1, sel]
        Phi[dofs[1, sel], 3 * k + 2] = xy[0, sel]
    M = asm(_mass, body.basis)
    MPhi = M @ Phi
    inv = np.linalg.inv(Phi.T @ MPhi)
    return Phi, MPhi, inv


def free_body_compliance(body: Body, xy: np.ndarray, dofs: np.ndarray, B: np.ndarray, groups: np.ndarray | None = None,
                         pins: np.ndarray | None = None, measure: np.ndarray | None = None) -> np.ndarray:
    """B^T P_u K_pin^-1 P_f B for the columns of B (ndof, m): loads made self-equilibrated per group (P_f), solved
    with three pinned DOFs per group (any three that stop the rigid motion: the reactions vanish), rigid part
    removed (P_u = P_f^T). ``measure`` (ndof, k): read the displacements with these vectors instead of B."""
    Phi, MPhi, inv = _inertia_relief(body, xy, dofs, groups)
    cb = CondensedBody(body, pins)
    F = B - MPhi @ (inv @ (Phi.T @ B))
    U = np.zeros_like(F)
    for lo in range(0, F.shape[1], 200):
        U[cb.free, lo:lo + 200] = cb._solve(F[cb.free, lo:lo + 200])
    U = U - Phi @ (inv @ (MPhi.T @ U))
    return (B if measure is None else measure).T @ U


def rigid_mode_pins(xy: np.ndarray, dofs: np.ndarray, groups: np.ndarray) -> np.ndarray:
    """Per group: both DOFs of the node nearest the group's centroid, and the DOF normal to the line to the
    node farthest from it."""
    out = []
    for k in range(int(groups.max()) + 1):
        sel = np.flatnonzero(groups == k)
        c = xy[:, sel].mean(axis=1, keepdims=True)
        d = np.hypot(*(xy[:, sel] - c))
        a, b = sel[np.argmin(d)], sel[np.argmax(d)]
        vec = xy[:, b] - xy[:, a]
        out += [dofs[0, a], dofs[1, a], dofs[1, b] if abs(vec[0]) >= abs(vec[1]) else dofs[0, b]]
    return np.array(out)


def roller_compliance(mesh: TriMesh, radius: float, offsets: np.ndarray, material: Elastic, order: int,
                      h_contact: float) -> RollerCompliance:
    """Condense one roller (local frame: centre at the origin, x = e_r) onto its inner and outer zones."""
    body = make_body(mesh, material, order, "displacement")
    xy, dofs = node_table(body)
    t_c = float(offsets[-1])
    tol = 0.25 * h_contact
    inner, t_in = zone_nodes(xy, radius, np.pi, t_c, tol)     # at angle pi, t runs the other way
    inner, t_in = inner[::-1], -t_in[::-1]
    outer, t_out = zone_nodes(xy, radius, 0.0, t_c, tol)
    _check_zone(t_in, offsets, order, "roller inner zone")
    _check_zone(t_out, offsets, order, "roller outer zone")
    n = t_in.size
    B = np.zeros((body.n_dofs, 2 * n))
    B[dofs[0, inner], np.arange(n)] = 1.0            # inner pole: towards the roller centre is +x
    B[dofs[0, outer], n + np.arange(n)] = -1.0       # outer pole: towards the centre is -x
    groups = np.zeros(xy.shape[1], int)
    W = free_body_compliance(body, xy, dofs, B, groups, rigid_mode_pins(xy, dofs, groups))
    return RollerCompliance(0.5 * (W + W.T), t_in, body.n_dofs, mesh)


def rollers_meshed(mesh: TriMesh, radius: float, pitch_radius: float, angles: np.ndarray, offsets: np.ndarray,
                   material: Elastic, order: int, h_contact: float) -> np.ndarray:
    """The similarity check's counterpart: every roller placed by rotating the one roller's nodes (seed 003
    eq 1) into one mesh of Z disconnected discs, assembled and solved as one body. Returns the (Z, 2n, 2n)
    diagonal blocks of its compliance in the pair directions (the off-diagonal blocks vanish: the rollers do
    not touch)."""
    z = len(angles)
    npts = mesh.points.shape[1]
    pts, tris = [], []
    for j, a in enumerate(angles):
        c, s = np.cos(a), np.sin(a)
        p = np.array([[c, -s], [s, c]]) @ mesh.points + pitch_radius * np.array([[c], [s]])
        pts.append(p)
        tris.append(mesh.triangles + j * npts)
    union = TriMesh(np.concatenate(pts, axis=1), np.concatenate(tris, axis=1))
    body = make_body(union, material, order, "displacement")
    xy, dofs = node_table(body)
    # group of each node: the roller whose centre is nearest
    centres = pitch_radius * np.stack([np.cos(angles), np.sin(angles)])
    groups = np.argmin(((xy[:, :, None] - centres[:, None, :]) ** 2).sum(axis=0), axis=1)
    t_c = float(offsets[-1])
    cols, n = [], None
    for j, a in enumerate(angles):
        c, s = np.cos(a), np.sin(a)
        local = np.array([[c, s], [-s, c]]) @ (xy - centres[:, [j]])
        inner, t_in = zone_nodes(local, radius, np.pi, t_c, 0.25 * h_contact)
        inner, t_in = inner[::-1], -t_in[::-1]
        outer, t_out = zone_nodes(local, radius, 0.0, t_c, 0.25 * h_contact)
        _check_zone(t_in, offsets, order, "roller inner zone")
        _check_zone(t_out, offsets, order, "roller outer zone")
        n = t_in.size
        Bj = np.zeros((body.n_dofs, 2 * n))
        Bj[dofs[0, inner], np.arange(n)] = c
        Bj[dofs[1, inner], np.arange(n)] = s
        Bj[dofs[0, outer], n + np.arange(n)] = -c
        Bj[dofs[1, outer], n + np.arange(n)] = -s
        cols.append(Bj)
    B = np.concatenate(cols, axis=1)
    W = free_body_compliance(body, xy, dofs, B, groups, rigid_mode_pins(xy, dofs, groups))
    W = 0.5 * (W + W.T)
    return np.stack([W[j * 2 * n:(j + 1) * 2 * n, j * 2 * n:(j + 1) * 2 * n] for j in range(z)])


@dataclass
class RingCompliance:
    """A ring condensed on its Z contact zones (n nodes each). ``columns(zones)`` -> (Z n, len(zones) n): the
    displacement along e_k at every zone node k per unit normal force at the given zones' nodes;
    ``circulant``: the support is axisymmetric and the mesh Z-fold symmetric, so one zone's columns give all."""

    body: Body
    solver: CondensedBody
    B: np.ndarray                 # (ndof, Z n) unit normal forces at the zone nodes
    t: np.ndarray
    rollers: int
    circulant: bool
    mesh: TriMesh
    _cache: dict

    @property
    def n(self) -> int:
        return self.t.size

    def _solve_columns(self, zones: list[int]) -> np.ndarray:
        n = self.n
        cols = np.concatenate([np.arange(k * n, (k + 1) * n) for k in zones])
        out = np.zeros((self.B.shape[1], cols.size))
        for lo in range(0, cols.size, 200):
            rhs = self.B[:, cols[lo:lo + 200]]
            u = np.zeros((self.body.n_dofs, rhs.shape[1]))
            u[self.solver.free] = self.solver._solve(rhs[self.solver.free])
            out[:, lo:lo + 200] = self.B.T @ u
        return out

    def columns(self, zones: list[int]) -> np.ndarray:
        n, z = self.n, self.rollers
        missing = [k for k in zones if k not in self._cache] if not self.circulant else \
            ([0] if 0 not in self._cache else [])
        if missing:
            got = self._solve_columns(missing)
            for i, k in enumerate(missing):
                self._cache[k] = got[:, i * n:(i + 1) * n]
        if not self.circulant:
            return np.concatenate([self._cache[k] for k in zones], axis=1)
        g0 = self._cache[0].reshape(z, n, n)          # response at zone m to forces at zone 0
        return np.concatenate([np.roll(g0, k, axis=0).reshape(z * n, n) for k in zones], axis=1)

    def displacement(self, lam: np.ndarray) -> np.ndarray:
        """Nodal displacement (ndof,) under pair forces ``lam`` (Z n,) pressing on the ring."""
        u = np.zeros(self.body.n_dofs)
        u[self.solver.free] = self.solver._solve((self.B @ lam)[self.solver.free])
        return u


def ring_compliance(mesh: TriMesh, raceway_radius: float, back_radius: float, angles: np.ndarray,
                    offsets: np.ndarray, material: Elastic, order: int, h_contact: float,
                    support_half_angle: float = np.pi) -> RingCompliance:
    """Condense a ring clamped on its back surface (the bore: tied to a rigid shaft; the OD: in a rigid
    housing, over |theta| <= ``support_half_angle`` about the load direction +x) onto its contact zones at
    ``angles``."""
    body = make_body(mesh, material, order, "displacement")
    xy, dofs = node_table(body)
    thickness = abs(raceway_radius - back_radius)

    def clamped(X):
        r, theta = np.hypot(X[0], X[1]), np.arctan2(X[1], X[0])
        return (np.abs(r - back_radius) < 0.25 * thickness) & (np.abs(theta) <= support_half_angle + 1e-9)

    fixed = np.concatenate([boundary_dofs(body.basis, clamped, 0), boundary_dofs(body.basis, clamped, 1)])
    solver = CondensedBody(body, fixed)
    t_c = float(offsets[-1])
    blocks, t = [], None
    for a in angles:
        idx, tt = zone_nodes(xy, raceway_radius, a, t_c, 0.25 * h_contact)
        _check_zone(tt, offsets, order, "ring zone")
        t = tt
        Bk = np.zeros((body.n_dofs, tt.size))
        Bk[dofs[0, idx], np.arange(tt.size)] = np.cos(a)
        Bk[dofs[1, idx], np.arange(tt.size)] = np.sin(a)
        blocks.append(Bk)
    B = np.concatenate(blocks, axis=1)
    full = support_half_angle >= np.pi - 1e-12
    return RingCompliance(body, solver, B, t, len(angles), full, mesh, {})
