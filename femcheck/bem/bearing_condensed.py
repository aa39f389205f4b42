"""Condensed bearing model (``condensed``): seed 003's GSC-BBEM idea in 2D plane strain (spec bearing-load.md
§5.2). The rings are condensed onto the roller contact centres, the roller compliance comes from one roller
(geometric similarity), and the contact tractions are assumed Hertzian with widths revised from the current
roller loads (the role of seed 003 eq 17, corrected: b = sqrt(4 P R_x/(pi E*)) per contact, relative test).

Unknowns: line loads P_j >= 0 (N/m) and the shaft translation delta (m). Roller j (direction e_j):

    delta . e_j - P_d/2 = Delta_d(P_j) + sum_k (C^in_jk(b) + C^out_jk(b)) P_k      (loaded rollers)
    delta . e_j - P_d/2 <= sum_k C_jk P_k                                          (unloaded: free room)
    sum_j P_j e_j = F' = F_r / l

Delta_d is the roller's diametral compression: the exact 2D law (``closed_form``), or the one-roller FE under
two unit Hertz patches with the same log-width dependence (``fem``). C_jk is the ring's displacement along e_j
at zone j's centre under a unit Hertz patch of half-width b_0 at zone k (FE, ring clamped on its bore / on the
housing arc); block-circulant rings need one patch, an arc-supported ring one per roller. Width revision of the
self term: C_kk(b) = C_kk(b_0) + 2 (1 - nu^2)/(pi E) ln(b_0/b) (the half-plane displacement under a Hertz patch of
unit load at its centre grows like -2(1-nu^2)/(pi E) ln b). Fixed-point iteration on the widths (the paper's
loop of flow-chart steps 3-10), each step an active-set Newton solve of the compatibility equations.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analytic.bearing_laws import PlaneStrainRoller
from ..errors import ConvergenceError
from ..fem.bearing2d import BearingSection, reference_half_width
from ..fem.bearing2d_bodies import (rigid_mode_pins, free_body_compliance, node_table, tributary_lengths, zone_nodes)
from ..meshes import bearing2d as meshes
from ..meshes.plane import MeshSpec
from ..solvers.elasticity2d import CondensedBody, boundary_dofs, make_body


@dataclass(frozen=True)
class CondensedSettings:
    h_contact: float = 0.25      # ring (and FE roller) zone spacing / b_0
    zone: float = 1.5            # patch zone half-length / b_0
    grading: float = 0.6
    h_max_ring: float = 0.5      # / ring thickness
    h_max_roller: float = 0.25   # / roller radius
    order: int = 2
    roller: str = "closed_form"  # closed_form | fem
    tol: float = 1e-10


@dataclass
class CondensedResult:
    loads: np.ndarray            # N
    interference: np.ndarray     # m: roller compression (loaded) or -free room
    delta: np.ndarray            # m
    width_iterations: int
    newton_iterations: int
    residual: float
    b0: float
    ring_dofs: int
    widths: np.ndarray           # (2, Z) inner / outer half-widths (m)


def _hertz_patch(t: np.ndarray, w: np.ndarray, b: float) -> np.ndarray:
    """Nodal forces of an elliptical pressure of half-width b and unit resultant on zone nodes at offsets t."""
    p = np.sqrt(np.clip(1.0 - (t / b) ** 2, 0.0, None))
    f = w * p
    return f / f.sum()


def _zone(b0: float, s: CondensedSettings) -> tuple[meshes.ZoneSpec, float]:
    h = s.h_contact * b0
    half = max(2, int(round(s.zone / s.h_contact)))
    return meshes.ZoneSpec(half * h, 2 * half), h


def ring_centre_compliance(sec: BearingSection, which: str, b0: float, s: CondensedSettings) -> tuple[np.ndarray, int]:
    """C (Z, Z): displacement along e_j at zone j's centre per unit Hertz patch (N/m) at zone k, for the inner
    ("inner": bore clamped) or outer ring ("outer": OD clamped on the housing arc)."""
    zone, h = _zone(b0, s)
    if which == "inner":
        race, back, kind, support = sec.inner_raceway, sec.bore, "outer", np.pi
    else:
        race, back, kind, support = sec.outer_raceway, sec.outside, "inner", sec.housing_half_angle
    thickness = abs(race - back)
    ends = () if support >= np.pi else (support, -support)
    spec = meshes.RingSpec(min(race, back), max(race, back), sec.rollers, kind, -sec.load_angle, ends)
    mesh = meshes.ring(spec, zone, MeshSpec(h, zone.t_c, s.grading, max(h, s.h_max_ring * thickness)))
    body = make_body(mesh, sec.ring_material, s.order, "displacement")
    xy, dofs = node_table(body)

    def clamped(X):
        r, theta = np.hypot(X[0], X[1]), np.arctan2(X[1], X[0])
        return (np.abs(r - back) < 0.25 * thickness) & (np.abs(theta) <= support + 1e-9)

    solver = CondensedBody(body, np.concatenate([boundary_dofs(body.basis, clamped, 0),
                                                 boundary_dofs(body.basis, clamped, 1)]))
    z = sec.rollers
    angles = sec.angles
    loads = np.zeros((body.n_dofs, z))
    probes = np.zeros((body.n_dofs, z))
    for j, a in enumerate(angles):
        idx, t = zone_nodes(xy, race, a, zone.t_c, 0.25 * h)
        f = _hertz_patch(t, tributary_lengths(t, s.order), b0)
        c0 = idx[np.argmin(np.abs(t))]
        loads[dofs[0, idx], j] = f * np.cos(a)
        loads[dofs[1, idx], j] = f * np.sin(a)
        probes[dofs[0, c0], j] = np.cos(a)
        probes[dofs[1, c0], j] = np.sin(a)
    circulant = support >= np.pi - 1e-12
    cols = [0] if circulant else list(range(z))
    u = np.zeros((body.n_dofs, len(cols)))
    u[solver.free] = solver._solve(loads[solver.free][:, cols])
    G = probes.T @ u                                   # (Z, len(cols))
    if circulant:
        C = np.stack([np.roll(G[:, 0], k) for k in range(z)], axis=1)
    else:
        C = G
    return 0.5 * (C + C.T), body.n_dofs


def roller_fem_offset(sec: BearingSection, law: PlaneStrainRoller, b0: float, s: CondensedSettings) -> tuple[float, int]:
    """The one-roller FE under two opposite unit Hertz patches (half-widths a_k(P0) of the law at the load P0
    that gives b_0), compression read at the two pole nodes; returned as the offset on the law's B that makes
    the closed form reproduce it (same log-width dependence)."""
    zone, h = _zone(b0, s)
    mesh = meshes.roller(sec.roller_radius, zone, MeshSpec(h, zone.t_c, s.grading,
                                                          max(h, s.h_max_roller * sec.roller_radius)))
    body = make_body(mesh, sec.roller_material, s.order, "displacement")
    xy, dofs = node_table(body)
    p0 = np.pi * law.e_star[0] * b0**2 / (4.0 * law.rx[0])       # the line load whose inner width is b0
    a_in, a_out = law.half_widths(p0 * law.length)
    B = np.zeros((body.n_dofs, 1))
    Mv = np.zeros((body.n_dofs, 1))
    for angle, a, sign in ((np.pi, a_in, 1.0), (0.0, a_out, -1.0)):
        idx, t = zone_nodes(xy, sec.roller_radius, angle, zone.t_c, 0.25 * h)
        B[dofs[0, idx], 0] += sign * _hertz_patch(t, tributary_lengths(t, s.order), a)
        Mv[dofs[0, idx[np.argmin(np.abs(t))]], 0] += sign
    groups = np.zeros(xy.shape[1], int)
    d_fe = float(free_body_compliance(body, xy, dofs, B, groups, rigid_mode_pins(xy, dofs, groups), Mv)[0, 0])
    d_law = float(law.deflection(p0 * law.length)) / p0
    return (d_fe - d_law) / law.c, body.n_dofs


def _newton(law, C: np.ndarray, dirs: np.ndarray, half_clear: float, F: np.ndarray, P: np.ndarray,
            delta: np.ndarray, tol: float, max_iter: int = 100):
    """Active-set Newton for the compatibility equations with C fixed; returns (P, delta, iterations, residual)."""
    z = len(P)
    active = P > 0
    it_total = 0
    scale = max(float(np.abs(delta).max()), 1e-12)
    for outer in range(4 * z + 4):
        for it in range(max_iter):
            it_total += 1
            A = np.flatnonzero(active)
            r = law.deflection(P[A] * law.length) + C[np.ix_(A, A)] @ P[A] - dirs[A] @ delta + half_clear
            eq = dirs[A].T @ P[A] - F
            res = max(float(np.abs(r).max()) / scale, float(np.linalg.norm(eq)) / float(np.linalg.norm(F)))
            if res < tol:
                break
            Pa = P[A]
            dd = law.c * (law.B - 2.0 * np.log(Pa) - 2.0)      # d Delta_d / dP (per unit length)
            n = A.size
            J = np.zeros((n + 2, n + 2))
            J[:n, :n] = np.diag(dd) + C[np.ix_(A, A)]
            J[:n, n:] = -dirs[A]
            J[n:, :n] = dirs[A].T
            step = np.linalg.lstsq(J, -np.concatenate([r, eq]), rcond=None)[0]
            dP, dD = step[:n], step[n:]
            neg = dP < 0
            frac = 1.0
            if neg.any():
                frac = min(1.0, float(np.min(0.9 * Pa[neg] / -dP[neg])))
            P[A] = Pa + frac * dP
            delta = delta + frac * dD
            if frac < 1.0 and np.min(P[A] / P[A].max()) < 1e-12:
                drop = A[np.argmin(P[A])]
                P[drop] = 0.0
                active[drop] = False
        else:
            raise ConvergenceError("condensed bearing (Newton)", it_total, res, tol, "no convergence")
        gap = law.deflection(np.zeros(z)) + C @ P - dirs @ delta + half_clear
        gap[active] = 0.0
        if gap.min() >= -tol * scale:
            return P, delta, it_total, res
        j = int(np.argmin(gap))
        active[j] = True
        P[j] = 1e-6 * P.max()
    raise ConvergenceError("condensed bearing (active set)", it_total, np.inf, tol, "active set did not settle")


def revised_compliance(C: np.ndarray, b0: float, widths: np.ndarray, k_in: float, k_out: float) -> np.ndarray:
    """The rings' compliance C (Z, Z; computed under Hertz patches of half-width b0) revised for the current
    half-widths ``widths`` (2, Z: inner, outer contact of each roller): the self terms become
    C_kk + k_in ln(b0/b_in,k) + k_out ln(b0/b_out,k), k = 2 (1 - nu^2)/(pi E) per ring. The displacement at the
    centre of a Hertz patch of unit load on an elastic half-plane is -(2 (1 - nu^2)/(pi E)) ln b + const (the
    patch's far field does not depend on b), so a narrower patch (less load) is more compliant; cross terms
    keep their b0 values (seed 003 eq 17's width revision, in the relative form of the module docstring)."""
    return C + np.diag(k_in * np.log(b0 / widths[0]) + k_out * np.log(b0 / widths[1]))


def solve(sec: BearingSection, s: CondensedSettings, progress=None) -> CondensedResult:
    law = sec.roller_law()
    b0, rr = reference_half_width(sec)
    dofs = 0
    if s.roller == "fem":
        off, n = roller_fem_offset(sec, law, b0, s)
        law = PlaneStrainRoller(law.radius, law.length, law.E, law.nu, law.rx, law.e_star, offset=off)
        dofs += n
    z = sec.rollers
    C_in = C_out = np.zeros((z, z))
    k_in = k_out = 0.0
    if not sec.ring_material.rigid:
        if progress:
            progress("condensed: ring compliances")
        C_in, n1 = ring_centre_compliance(sec, "inner", b0, s)
        C_out, n2 = ring_centre_compliance(sec, "outer", b0, s)
        dofs += n1 + n2
        k_in = k_out = 2.0 * sec.ring_material.compliance / np.pi
    dirs = np.stack([np.cos(sec.angles), np.sin(sec.angles)], axis=1)
    F = np.array([sec.load / sec.length, 0.0])
    P = rr.loads / sec.length
    delta = rr.displacement[:2].copy()
    widths = np.full((2, z), b0)
    newton = 0
    for it in range(1, 101):
        a_in, a_out = law.half_widths(np.maximum(P, 1e-300) * sec.length)
        new = np.stack([np.where(P > 0, a_in, b0), np.where(P > 0, a_out, b0)])
        C = revised_compliance(C_in + C_out, b0, new, k_in, k_out) if not sec.ring_material.rigid else C_in + C_out
        P, delta, n_it, res = _newton(law, C, dirs, 0.5 * sec.clearance, F, P.copy(), delta, s.tol)
        newton += n_it
        change = float(np.abs(new / widths - 1.0).max())
        widths = new
        if change < s.tol or sec.ring_material.rigid:
            break
    else:
        raise ConvergenceError("condensed bearing (width revision)", 100, change, s.tol, "widths keep changing")
    loads = P * sec.length
    comp = law.deflection(loads)
    room = C @ P - dirs @ delta + 0.5 * sec.clearance          # free room of unloaded rollers
    interference = np.where(P > 0, comp, -room)
    return CondensedResult(loads, interference, delta, it, newton, res, b0, dofs, widths)
