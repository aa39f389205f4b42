"""Flexibility of a stepped, solid, circular shaft (a mill roll's neck and body) as a Timoshenko beam clamped at one
section, condensed onto the slices of the bearing rows it carries; SI units (m, N, rad).

Each node carries the section's displacement and rotation v = (u_x, u_y, u_z, theta_x, theta_y) (torsion is not
loaded: a contact force along the normal n = (cos(alpha) e_r, s sin(alpha) e_z) at radius R has no moment about the
axis). Bending in the x-z plane uses (u_x, theta_y) with u_x' = theta_y, in the y-z plane (u_y, -theta_x) with
u_y' = -theta_x (right-handed rotations: theta x p moves the axis point p = z e_z by (theta_y z, -theta_x z, 0)).
Element matrices, constant section over the element (exact at the nodes for nodal loads; Przemieniecki,
*Theory of Matrix Structural Analysis*, 1968, sec. 5.6):

    K_b = E I / ((1 + P) L^3) [[12, 6L, -12, 6L], [6L, (4 + P) L^2, -6L, (2 - P) L^2],
                               [-12, -6L, 12, -6L], [6L, (2 - P) L^2, -6L, (4 + P) L^2]],   P = 12 E I / (k G A L^2),
    K_a = E A / L [[1, -1], [-1, 1]],

with I = pi d^4/64, A = pi d^2/4 and Cowper's shear coefficient of a solid circle k = 6 (1 + nu)/(7 + 6 nu) (Cowper
1966, J. Appl. Mech. 33:335, Table 1). The beam is clamped (all five components) at ``z_clamp``: for a mill roll cut at
its symmetry plane (the strip's middle) that section neither rotates nor, relative to the roll's rigid motion,
moves. The flexibility is F = K_ff^-1 on the other nodes.

Condensed onto slices: slice m (row i, roller at psi, axial position z_m on a node) gains the approach

    d_m = (G_loc v(z_m))_m,   G_loc,m = [cos(alpha) cos(psi), cos(alpha) sin(psi), s_i sin(alpha),
                                         s_i sin(alpha) R sin(psi), -s_i sin(alpha) R cos(psi)]

(the rows of :func:`femcheck.analytic.iso16281.row_kinematics` taken at the section itself), and its load q_m
acts on the section as -G_loc,m^T q_m, so the neck's compliance in the slice model d = G u - c - C q is

    C_neck = G_loc F G_loc^T   (symmetric, positive semi-definite; m/N).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .iso16281 import Row, row_kinematics

@dataclass(frozen=True)
class ShaftSegment:
    """Solid circular section of ``diameter`` (m) over z0 <= z <= z1 (m)."""

    z0: float
    z1: float
    diameter: float


def cowper_circle(nu: float) -> float:
    """Shear coefficient of a solid circular section, k = 6 (1 + nu)/(7 + 6 nu) (Cowper 1966, Table 1)."""
    return 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)


def _element(L: float, d: float, E: float, nu: float) -> tuple[np.ndarray, float]:
    """(4x4 bending matrix of the module doc, axial stiffness E A / L) of a solid circular element."""
    I, A = np.pi * d**4 / 64.0, np.pi * d**2 / 4.0
    G = E / (2.0 * (1.0 + nu))
    P = 12.0 * E * I / (cowper_circle(nu) * G * A * L**2)
    kb = E * I / ((1.0 + P) * L**3) * np.array([
        [12.0, 6 * L, -12.0, 6 * L],
        [6 * L, (4 + P) * L**2, -6 * L, (2 - P) * L**2],
        [-12.0, -6 * L, 12.0, -6 * L],
        [6 * L, (2 - P) * L**2, -6 * L, (4 + P) * L**2]])
    return kb, E * A / L


def _diameter_at(segments: list[ShaftSegment], z: float) -> float:
    for s in segments:
        if min(s.z0, s.z1) - 1e-12 <= z <= max(s.z0, s.z1) + 1e-12:
            return s.diameter
    raise ValueError(f"no shaft segment covers z = {z:.6g} m")


def flexibility(nodes: np.ndarray, segments: list[ShaftSegment], z_clamp: float, E: float, nu: float) -> np.ndarray:
    """Flexibility (5 n, 5 n) of the shaft's nodes (module doc), node DOFs (u_x, u_y, u_z, theta_x, theta_y) in the
    order of ``nodes`` (m, unique); the shaft runs between the outermost of ``nodes`` and ``z_clamp``, which must
    lie outside them or on the last one, and its segments must cover that span. Units: m/N, rad/N, m/(N m),
    rad/(N m)."""
    nodes = np.asarray(nodes, dtype=float)
    if np.unique(nodes).size != nodes.size:
        raise ValueError("shaft nodes must be distinct")
    if not (z_clamp >= nodes.max() - 1e-12 or z_clamp <= nodes.min() + 1e-12):
        raise ValueError("the clamp must lie at one end of the shaft, beyond every node")
    breaks = [z for s in segments for z in (s.z0, s.z1)]
    lo, hi = min(nodes.min(), z_clamp), max(nodes.max(), z_clamp)
    grid = np.unique(np.concatenate([nodes, [z_clamp], [b for b in breaks if lo - 1e-12 <= b <= hi + 1e-12]]))
    # merge points closer than round-off
    grid = grid[np.concatenate([[True], np.diff(grid) > 1e-12 * max(abs(hi - lo), 1e-300)])]
    n = grid.size
    K = np.zeros((5 * n, 5 * n))
    for e in range(n - 1):
        L = grid[e + 1] - grid[e]
        kb, ka = _element(L, _diameter_at(segments, 0.5 * (grid[e] + grid[e + 1])), E, nu)
        a, b = 5 * e, 5 * (e + 1)
        # x-z plane: (u_x, theta_y);  y-z plane: (u_y, -theta_x): the sign flip of theta_x is T = diag(1, -1)
        for w, phi, sgn in ((0, 4, 1.0), (1, 3, -1.0)):
            idx = np.array([a + w, a + phi, b + w, b + phi])
            t = np.array([1.0, sgn, 1.0, sgn])
            K[np.ix_(idx, idx)] += t[:, None] * kb * t[None, :]
        idx = np.array([a + 2, b + 2])
        K[np.ix_(idx, idx)] += ka * np.array([[1.0, -1.0], [-1.0, 1.0]])
    clamp = int(np.argmin(np.abs(grid - z_clamp)))
    free = np.setdiff1d(np.arange(5 * n), np.arange(5 * clamp, 5 * clamp + 5))
    F_all = np.zeros((5 * n, 5 * n))
    F_all[np.ix_(free, free)] = np.linalg.inv(K[np.ix_(free, free)])
    pos = np.searchsorted(grid, nodes)
    pos = np.where((pos < n) & (np.abs(grid[np.minimum(pos, n - 1)] - nodes) < 1e-9 * max(hi - lo, 1e-300)),
                   pos, pos - 1)
    sel = (5 * pos[:, None] + np.arange(5)[None, :]).ravel()
    return F_all[np.ix_(sel, sel)]


def slice_map(psi: np.ndarray, z_local: np.ndarray, row_z: np.ndarray, signs: np.ndarray, alpha: float,
              pitch_radius: float) -> tuple[np.ndarray, np.ndarray]:
    """(G_loc (n_slices, 5 n_nodes), node z (n_nodes,)) of the module doc for rows at ``row_z`` with contact-angle
    signs ``signs``, rollers at ``psi`` (rad) and slices at ``z_local`` (m, about each row's middle); slice order
    (row, roller, slice), as in :func:`femcheck.analytic.iso16281.sliced_equilibrium`."""
    z_all = (np.asarray(row_z, dtype=float)[:, None] + np.asarray(z_local, dtype=float)[None, :])
    nodes, inv = np.unique(np.round(z_all.ravel(), 12), return_inverse=True)
    inv = inv.reshape(z_all.shape)
    rows, Z, ns = len(row_z), len(psi), len(z_local)
    # each roller's row of G taken at its own section (z = 0 about it): the rigid kinematics of the section
    at_section = [Row(0.0, alpha, int(sg)) for sg in signs]
    G0, _, _ = row_kinematics(at_section, np.asarray(psi, float), np.zeros(1), pitch_radius, 0.0, np.zeros(1),
                              axial=True, tilt=True)
    G0 = G0.reshape(rows, Z, 5)
    Gl = np.zeros((rows, Z, ns, 5 * nodes.size))
    for i in range(rows):
        for k in range(ns):
            Gl[i, :, k, 5 * inv[i, k]:5 * inv[i, k] + 5] = G0[i]
    return Gl.reshape(rows * Z * ns, -1), nodes


def neck_compliance(psi: np.ndarray, z_local: np.ndarray, row_z: np.ndarray, signs: np.ndarray, alpha: float,
                    pitch_radius: float, segments: list[ShaftSegment], z_clamp: float, E: float,
                    nu: float) -> np.ndarray:
    """C_neck = G_loc F G_loc^T (m/N) of the module doc, slice order (row, roller, slice)."""
    Gl, nodes = slice_map(psi, z_local, row_z, signs, alpha, pitch_radius)
    F = flexibility(nodes, segments, z_clamp, E, nu)
    C = Gl @ F @ Gl.T
    return 0.5 * (C + C.T)
