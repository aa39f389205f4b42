"""Contact-resolved equilibrium of a cylindrical roller bearing: every roller's inner and outer contact solved as a
3D normal contact problem on a fine grid, the bodies' compliance split into the half-space's exact near field and
the FE's finite-body correction (:mod:`femcheck.fem.crb_corrections`); the reference for the 3D condensed model
(:mod:`femcheck.bem.bearing_condensed3d`), which lumps each slice into the ISO/TS 16281 law instead; SI units.

Geometry (the condensed model's frame): roller j at psi_j, axial coordinate y along the roller (|y| <= L_we/2),
x across the contact line. Per contact c (inner, outer) of roller j, on the grid (x_i, y_l):

    g = x^2/(2 R_c) + P(y) [+ G_r/2 at the outer contact] - (a_c + b_c y) + u_HS + u_D >= 0,   p >= 0,  p g = 0,
    1/R_i = 2/D + 1/r_i (inner raceway, convex),   1/R_o = 2/D - 1/r_o (outer, conformal),
    inner:  a = delta . e_r(psi_j) - rho_j,   b = -tan(theta_mis) cos(psi_j) - phi_j,
    outer:  a = rho_j,                         b = phi_j,

with P the ISO/TS 16281 logarithmic crown drop of the roller (TS eqs 42-44) at each contact, rho_j and phi_j the
roller's radial displacement and tilt (its mean axes, as the free-roller FE defines them), delta the inner ring's
displacement with the prescribed misalignment theta_mis (the condensed model's kinematics), the outer ring held by
its housing. u_HS = Boussinesq's (Love's rectangle) influence of the contact's own pressures for two steel bodies
(E* = E/(2(1 - nu^2))); u_D = the finite-body corrections (D per unit force on the FE's axial bins, interpolated linearly between
the bins' centres onto the axial cells and loaded by the cells' forces with the same weights).

Equilibrium: each roller carries equal force and moment at its two contacts (no flanges, no centrifugal load),
the inner ring the applied radial load: sum_j F_in,j e_r(psi_j) = F.

Solver: Newton on (rho, phi, delta) with the exact tangent of each contact (active set A fixed: dF, dM / d(a, b)
= dA [1, y]_A^T A_AA^-1 [1, y]_A), every contact's LCP solved by Polonsky-Keer under approach control with its own
finite-body self-correction in the operator, the corrections between different contacts (the roller's two
contacts, the rings' other rollers) lagged in an outer fixed point. A roller with both contacts open is centred
between its raceways. Iterations and residuals are reported; non-convergence raises ConvergenceError.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse.linalg import LinearOperator, cg

from ..analytic.bearing_load import roller_angles
from ..analytic.iso16281 import crown_drop
from ..errors import ConvergenceError
from ..materials import Elastic
from .convolution import DCFFT
from .influence import love_rectangle
from .polonsky_keer import polonsky_keer


@dataclass(frozen=True)
class ResolvedRow:
    """The row: Z ``rollers``, roller ``diameter`` D_we and effective ``length`` L_we, raceway radii
    ``inner_race`` r_i and ``outer_race`` r_o (m), diametral ``clearance`` G_r (m), prescribed ``misalignment``
    (rad), ``load_angle`` (rad), ``crown`` "iso" | "none", ``material`` of all bodies."""

    rollers: int
    diameter: float
    length: float
    inner_race: float
    outer_race: float
    clearance: float = 0.0
    misalignment: float = 0.0
    load_angle: float = 0.0
    crown: str = "iso"
    material: Elastic = Elastic(210e9, 0.3)

    @property
    def psi(self) -> np.ndarray:
        return roller_angles(self.rollers, self.load_angle)

    def curvature_radius(self, contact: str) -> float:
        r = 0.5 * self.diameter
        return 1.0 / (1.0 / r + 1.0 / self.inner_race) if contact == "inner" else 1.0 / (1.0 / r - 1.0 / self.outer_race)


@dataclass(frozen=True)
class FineGrid:
    """Cells of every contact: ``across`` n_x over |x| <= ``half_width`` (m, per contact: inner, outer) and
    ``along`` n_y over L_we."""

    across: int
    along: int
    half_width: tuple[float, float]


@dataclass
class CorrectionTables:
    """Finite-body corrections per unit bin force (m/N; :mod:`femcheck.fem.crb_corrections`): ``roller``
    (2 n_r, 2 n_r; inner contact's bins then the outer's) on ``roller_bins`` axial bins, ``inner_ring`` and
    ``outer_ring`` (Z n_g, Z n_g; index j n_g + k) on ``ring_bins``; equal bins along L_we. A ring's table may be
    None (that ring rigid beyond its half-space near field)."""

    roller: np.ndarray
    inner_ring: np.ndarray | None
    outer_ring: np.ndarray | None
    roller_bins: int
    ring_bins: int


@dataclass
class ResolvedResult:
    """``pressure[c][j]`` (n_x, n_y) Pa (c: 0 inner, 1 outer); ``roller_loads`` Q_j (N); ``strip_loads``
    (Z, n_y) N per axial cell (inner contact); ``rho``, ``phi`` (m, rad) per roller, ``delta`` (m); Newton and
    fixed-point iterations, residuals, ``time_s``."""

    pressure: list
    roller_loads: np.ndarray
    strip_loads: np.ndarray
    moments: np.ndarray
    rho: np.ndarray
    phi: np.ndarray
    delta: np.ndarray
    y: np.ndarray
    iterations: int
    outer_iterations: int
    residual: float
    time_s: float
    stats: dict = field(default_factory=dict)

    @property
    def q_max(self) -> float:
        return float(self.roller_loads.max())

    def slice_loads(self, slices: int) -> np.ndarray:
        """Loads (N) on ``slices`` equal slices along the roller (the strips summed), shape (Z, slices)."""
        per = self.y.size // slices
        if per * slices != self.y.size:
            raise ValueError(f"{self.y.size} axial cells do not split into {slices} slices")
        return self.strip_loads.reshape(self.strip_loads.shape[0], slices, per).sum(axis=2)


def bin_map(ny: int, bins: int) -> np.ndarray:
    """P (n_y, n_b): linear interpolation from the bins' centres to the axial cells' centres (held constant beyond
    the end bins' centres); rows sum to 1, so P^T carries a cell's force to its two nearest bins unchanged in sum.
    Linear, not bin-wise constant: a correction held constant over each bin steps at the bin edges, and a step in
    the gap gives a logarithmic pressure peak that the contact grid never resolves (measured on crb-3d-misaligned:
    end-slice loads changed by 0.24 % then 0.19 % of the largest slice under grid doubling, against 0.03 % then
    0.01 % with this map)."""
    yc = (np.arange(ny) + 0.5) * bins / ny - 0.5          # cell centres in units of bins, from the first centre
    k = np.clip(np.floor(yc).astype(int), 0, max(bins - 2, 0))
    t = np.clip(yc - k, 0.0, 1.0) if bins > 1 else np.zeros(ny)
    P = np.zeros((ny, bins))
    rows = np.arange(ny)
    np.add.at(P, (rows, k), 1.0 - t)
    np.add.at(P, (rows, np.minimum(k + 1, bins - 1)), t)
    return P


def fine_corrections(rollers: int, corr: CorrectionTables, ny: int) -> np.ndarray:
    """The corrections on the fine axial cells, Dfine (2 Z n_y, 2 Z n_y) m/N, index (c Z + j) n_y + l:
    D_fine = P D P^T with P the bins-to-cells linear interpolation (:func:`bin_map`), symmetric when D is;
    the bins' resolution converges with n_b at second order for a smooth correction."""
    Z = rollers
    D = np.zeros((2 * Z * ny, 2 * Z * ny))
    n, Pr = corr.roller_bins, bin_map(ny, corr.roller_bins)
    for j in range(Z):
        for a in (0, 1):
            for b in (0, 1):
                ia, ib = (a * Z + j) * ny, (b * Z + j) * ny
                D[ia:ia + ny, ib:ib + ny] += Pr @ corr.roller[a * n:(a + 1) * n, b * n:(b + 1) * n] @ Pr.T
    n, Pg = corr.ring_bins, bin_map(ny, corr.ring_bins)
    PZ = np.kron(np.eye(Z), Pg)
    for c, ring in ((0, corr.inner_ring), (1, corr.outer_ring)):
        if ring is not None:
            D[c * Z * ny:(c + 1) * Z * ny, c * Z * ny:(c + 1) * Z * ny] += PZ @ ring @ PZ.T
    return D


def halfspace_operator(nx: int, ny: int, dx: float, dy: float, material: Elastic) -> DCFFT:
    """p (n_x, n_y) Pa -> normal displacement (m) of two equal elastic half-spaces (Love's rectangle,
    E* = E/(2(1 - nu^2))), a linear convolution by DC-FFT."""
    e_star = material.E / (2.0 * (1.0 - material.nu**2))
    return DCFFT(lambda tx, ty: love_rectangle(tx, ty, dx, dy, e_star), (nx, ny), (dx, dy))


class _Contact:
    """One contact's grid, operator (the half-space + its own finite-body self-correction ``blk``, m/N between
    axial cells) and state."""

    def __init__(self, conv: DCFFT, blk: np.ndarray | None, h0: np.ndarray, y: np.ndarray, dA: float):
        self.conv, self.blk, self.h0, self.y, self.dA = conv, blk, h0, y, dA
        self.p = np.zeros(h0.shape)
        self.Y = np.broadcast_to(y, h0.shape)

    def op(self, p: np.ndarray) -> np.ndarray:
        u = self.conv(p)
        if self.blk is not None:
            u = u + self.blk @ (self.dA * p.sum(axis=0))
        return u

    def solve(self, a: float, b: float, w: np.ndarray, tol: float) -> tuple[float, float, np.ndarray]:
        """(F, M, K) at rigid approach a + b y with the lagged displacement w (n_y,) (module doc)."""
        h = self.h0 + (w - b * self.y)[None, :]
        if np.all(h - a >= 0.0):
            self.p[:] = 0.0
            return 0.0, 0.0, np.zeros((2, 2))
        res = polonsky_keer(h, self.op, None, self.dA, p0=self.p if self.p.any() else None, tol=tol, approach=a)
        self.p = res.pressure
        act = self.p > 0.0
        n = int(act.sum())

        def matvec(v):
            full = np.zeros(self.p.shape)
            full[act] = v.ravel()
            return self.op(full)[act]

        Aop = LinearOperator((n, n), matvec=matvec, dtype=float)
        E = np.stack([np.ones(n), self.Y[act]], axis=1)
        X = np.empty_like(E)
        for k in range(2):
            X[:, k], info = cg(Aop, E[:, k], rtol=1e-10, atol=0.0, maxiter=10 * n)
            if info != 0:
                raise ConvergenceError("contact tangent (CG on the active set)", info, float("nan"), 1e-10)
        return float(self.dA * self.p.sum()), float(self.dA * (self.p * self.Y).sum()), self.dA * (E.T @ X)


def solve(row: ResolvedRow, grid: FineGrid, corr: CorrectionTables | None, radial_load: float,
          start: tuple[float, float] | None = None, tol: float = 1e-8, pk_tol: float = 1e-11,
          max_iter: int = 60, max_outer: int = 40, progress=None) -> ResolvedResult:
    """Equilibrium of the module doc under the radial load F (N, along the load line). ``corr`` None: half-spaces
    only (no finite-body correction). ``start``: (delta_x, approach scale) guess (m); default from the ISO law.
    ``tol`` on the force residuals relative to F and on the lagged displacements relative to the largest
    approach."""
    t0 = time.perf_counter()
    Z, nx, ny = row.rollers, grid.across, grid.along
    dy = row.length / ny
    y = (np.arange(ny) - 0.5 * ny + 0.5) * dy
    psi = row.psi
    er = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    drop = crown_drop(y, row.length, row.diameter) if row.crown == "iso" else np.zeros(ny)
    Dfine = fine_corrections(Z, corr, ny) if corr is not None else None
    contacts = []
    for c, name in enumerate(("inner", "outer")):
        dx = 2.0 * grid.half_width[c] / nx
        x = (np.arange(nx) - 0.5 * nx + 0.5) * dx
        conv = halfspace_operator(nx, ny, dx, dy, row.material)
        h0 = x[:, None] ** 2 / (2.0 * row.curvature_radius(name)) + drop[None, :]
        if c == 1:
            h0 = h0 + 0.5 * row.clearance
        for j in range(Z):
            blk = None
            if Dfine is not None:
                blk = Dfine[(c * Z + j) * ny:(c * Z + j + 1) * ny, (c * Z + j) * ny:(c * Z + j + 1) * ny]
            contacts.append(_Contact(conv, blk, h0, y, dx * dy))
    # start: the ISO/TS 16281 line law's approach for a rough Q_max = 5 F/Z on rigid rings (a start only)
    if start is None:
        q0 = 5.0 * radial_load / Z
        start = (0.5 * row.clearance + 2.0 * (q0 / (3.5948e10 * row.length ** (8 / 9))) ** 0.9, 0.0)
    delta = np.array([start[0], 0.0])
    ar = er @ delta
    rho = 0.5 * (ar + 0.5 * row.clearance)
    tan_cos = np.tan(row.misalignment) * np.cos(psi)
    phi = -0.5 * tan_cos
    F = radial_load * np.array([np.cos(row.load_angle), np.sin(row.load_angle)])
    w = np.zeros((2, Z, ny))              # lagged displacements from the other contacts' corrections
    k_ref = radial_load / max(start[0], 1e-9)
    total_it, outer = 0, 0
    approach_scale = max(start[0], 1e-9)
    while True:
        outer += 1
        for it in range(1, max_iter + 1):
            total_it += 1
            R = np.zeros(2 * Z + 2)
            J = np.zeros((2 * Z + 2, 2 * Z + 2))
            loads = np.zeros((2, Z, 2))
            for j in range(Z):
                a_in, b_in = float(er[j] @ delta) - rho[j], -tan_cos[j] - phi[j]
                a_out, b_out = rho[j], phi[j]
                Fi, Mi, Ki = contacts[j].solve(a_in, b_in, w[0, j], pk_tol)
                Fo, Mo, Ko = contacts[Z + j].solve(a_out, b_out, w[1, j], pk_tol)
                loads[0, j], loads[1, j] = (Fi, Mi), (Fo, Mo)
                r = slice(2 * j, 2 * j + 2)
                if not (Ki.any() or Ko.any()):          # a free roller: centred between its raceways
                    R[r] = k_ref * np.array([a_in - a_out - 0.5 * row.clearance, (b_in - b_out) * row.length])
                    J[r, r] = -2.0 * k_ref * np.diag([1.0, row.length])
                    J[2 * j, 2 * Z:] = k_ref * er[j]
                    continue
                R[r] = (Fi - Fo, Mi - Mo)
                J[r, r] = -Ki - Ko
                J[r, 2 * Z:] = np.outer(Ki[:, 0], er[j])
                R[2 * Z:] += Fi * er[j]
                J[2 * Z:, 2 * j:2 * j + 2] = -np.outer(er[j], Ki[0])
                J[2 * Z:, 2 * Z:] += Ki[0, 0] * np.outer(er[j], er[j])
            R[2 * Z:] -= F
            res = float(np.abs(R).max() / radial_load)
            if res < tol:
                break
            step = np.linalg.solve(J, -R)
            # limit the step to a fraction of the approach scale: the contact sets change
            scale = max(float(np.abs(step[0:2 * Z:2]).max()), float(np.abs(step[2 * Z:]).max()), 1e-300)
            t = min(1.0, 0.5 * approach_scale / scale)
            rho, phi, delta = rho + t * step[0:2 * Z:2], phi + t * step[1:2 * Z:2], delta + t * step[2 * Z:]
        else:
            raise ConvergenceError("contact-resolved bearing (Newton)", total_it, res, tol, "iterations exhausted")
        approach_scale = max(float(np.abs(er @ delta).max()), 1e-9)
        if Dfine is None:
            break
        # lagged corrections between different contacts: w = D_cross f (own block excluded, it is in A)
        f = np.stack([np.stack([contacts[c * Z + j].p.sum(axis=0) * contacts[c * Z + j].dA
                                for j in range(Z)]) for c in (0, 1)]).ravel()
        w_all = Dfine @ f
        own = np.concatenate([Dfine[b * ny:(b + 1) * ny, b * ny:(b + 1) * ny] @ f[b * ny:(b + 1) * ny]
                              for b in range(2 * Z)])
        w_new = (w_all - own).reshape(2, Z, ny)
        change = float(np.abs(w_new - w).max()) / approach_scale
        w = w_new
        if progress:
            progress(f"resolved bearing: outer {outer}, Newton {total_it}, lagged change {change:.1e}")
        if change < tol:
            break
        if outer >= max_outer:
            raise ConvergenceError("contact-resolved bearing (lagged corrections)", outer, change, tol,
                                   "fixed point not reached")
    strips = np.stack([contacts[j].p.sum(axis=0) * contacts[j].dA for j in range(Z)])
    pressure = [[contacts[c * Z + j].p.copy() for j in range(Z)] for c in (0, 1)]
    for c in (0, 1):
        for j in range(Z):
            p = pressure[c][j]
            if p.any() and (p[0].max() > 0 or p[-1].max() > 0):
                raise ConvergenceError("contact-resolved bearing", total_it, float(p.max()), 0.0,
                                       f"contact {('inner', 'outer')[c]} of roller {j} reaches the grid's edge across: "
                                       f"widen half_width")
    return ResolvedResult(pressure, loads[0, :, 0].copy(), strips, loads[0, :, 1].copy(), rho, phi, delta, y,
                          total_it, outer, res, time.perf_counter() - t0,
                          {"cells_per_contact": nx * ny, "dx": [2 * g / nx for g in grid.half_width], "dy": dy})
