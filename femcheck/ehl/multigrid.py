"""FAS multigrid with a full-multigrid start for the EHL point contact (seed 004 §2.6.2 eqs 2.25-2.33; Venner &
Lubrecht 2000; spec §A.5).

Unknowns: the nodal pressures P on (n+1) x (ny+1) nodes over [x_start, x_end] x [-ny h/2, ny h/2] with square
cells h = (x_end - x_start)/n; ny = n (a square domain, w = x_end - x_start wide across) unless the problem asks
for another half-width across (``Problem.y_half``: an elliptic contact is 1/kappa times wider across than along the
rolling direction), then ny is the smallest even multiple of the coarsening that covers it; and the film constant H0, fixed by the load balance h^2 sum P = 2 pi/(3 kappa).
Grids are nested: n = n_coarsest 2^l. Full approximation scheme: the coarse problem is
    L^H(P^H) = L^H(I P^h) + I (f^h - L^h(P^h)),   h_H^2 sum P^H = h_H^2 sum I P^h + (g^h - h^2 sum P^h)
with injection I for P, full weighting of the residual where the 3 x 3 fine patch is pressurised (injection
elsewhere), bilinear prolongation of the correction added only where the fine 3 x 3 patch is pressurised (not on the
cavitation boundary), negatives clipped. H0 is one
number shared by every level and is relaxed on the coarsest grid only, after every relaxation sweep there:
H0 <- H0 + c_h (h^2 sum P - g) (more load than wanted opens the gap). FMG: the coarsest problem is solved from
the Hertz pressure, each solution is interpolated (cubic) to the next grid and improved by V(2,1) cycles.

Transient problems keep the time step of the finest grid on every level (the coarse grids use the h > hT branch
of NU2), with the old time levels rho H injected from the finest grid.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .film import FilmOperator, Indent
from .lubricant import Lubricant
from .relax import relax_colour
from .reynolds import faces, operator, time_weights


@dataclass(frozen=True)
class Problem:
    """The dimensionless EHL problem: lubricant laws, lambda_bar, deformation factor, Rx/Ry, load 2 pi/(3 kappa),
    the X range of the domain, the half-width of the centred Y range ``y_half`` (None: as wide as the X range,
    a square), an optional indent, the H0 relaxation factor c_h and a first guess of the central film
    ``hc_start`` (H0 then follows from the Hertz deflection)."""

    lubricant: Lubricant
    lam: float
    c_el: float
    rx_over_ry: float
    kappa: float
    x_start: float = -4.5
    x_end: float = 1.5
    indent: Indent | None = None
    h0_factor: float = 0.1
    hc_start: float = 0.1
    y_half: float | None = None

    @property
    def load(self) -> float:
        return 2.0 * np.pi / (3.0 * self.kappa)


class Level:
    """One grid: nodes (n intervals along X, ny across), film operator, P, FAS right-hand sides f (field) and g
    (load), old time levels."""

    def __init__(self, n: int, prob: Problem, ny: int | None = None):
        width = prob.x_end - prob.x_start
        self.n, self.h = n, width / n
        self.ny = n if ny is None else ny
        self.film = FilmOperator(n, self.h, prob.x_start, -0.5 * self.ny * self.h, prob.c_el, prob.rx_over_ry,
                                 self.ny)
        self.P = np.zeros((n + 1, self.ny + 1))
        self.f = np.zeros_like(self.P)
        self.g = prob.load
        self.rigid = self.film.rigid(prob.indent, 0.0)
        self.r1: np.ndarray | None = None
        self.r2: np.ndarray | None = None
        self.ht: float | None = None

    def load_sum(self, P: np.ndarray | None = None) -> float:
        return float(self.h * self.h * (self.P if P is None else P).sum())


def cross_intervals(n: int, prob: Problem) -> int:
    """Intervals across (Y) on a grid of n intervals along X: n for a square domain (``prob.y_half`` None), else the
    smallest even count whose half-width reaches ``y_half`` (even: a node line on Y = 0)."""
    if prob.y_half is None:
        return n
    h = (prob.x_end - prob.x_start) / n
    return 2 * max(1, int(np.ceil(prob.y_half / h - 1e-9)))


def inject(fine: np.ndarray) -> np.ndarray:
    return fine[::2, ::2].copy()


def pressurised_patch(P: np.ndarray) -> np.ndarray:
    """Interior nodes whose 3 x 3 patch (the node and its eight neighbours) has P > 0."""
    pos = P > 0
    full = np.zeros_like(pos)
    n, m = P.shape[0] - 1, P.shape[1] - 1
    full[1:n, 1:m] = True
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            full[1:n, 1:m] &= pos[1 + di:n + di, 1 + dj:m + dj]
    return full


def full_weighting(r: np.ndarray) -> np.ndarray:
    """Full weighting (1/16)[1 2 1; 2 4 2; 1 2 1] at the interior coarse nodes, injection on the boundary."""
    rc = r[::2, ::2].copy()
    c = (slice(2, -2, 2), slice(2, -2, 2))
    rc[1:-1, 1:-1] = (4.0 * r[c] + 2.0 * (r[1:-3:2, 2:-2:2] + r[3:-1:2, 2:-2:2] + r[2:-2:2, 1:-3:2]
                                          + r[2:-2:2, 3:-1:2])
                      + r[1:-3:2, 1:-3:2] + r[3:-1:2, 1:-3:2] + r[1:-3:2, 3:-1:2] + r[3:-1:2, 3:-1:2]) / 16.0
    return rc


def restrict_residual(r: np.ndarray, P: np.ndarray) -> np.ndarray:
    """Full weighting of the fine residual where the 3 x 3 fine patch is pressurised, injection elsewhere."""
    rc = np.where(pressurised_patch(P)[::2, ::2], full_weighting(r), r[::2, ::2])
    rc[0, :] = rc[-1, :] = rc[:, 0] = rc[:, -1] = 0.0
    return rc


def prolong_bilinear(c: np.ndarray) -> np.ndarray:
    n, m = 2 * (c.shape[0] - 1), 2 * (c.shape[1] - 1)
    f = np.zeros((n + 1, m + 1))
    f[::2, ::2] = c
    f[1::2, ::2] = 0.5 * (c[:-1] + c[1:])
    f[:, 1::2] = 0.5 * (f[:, :-1:2] + f[:, 2::2])
    return f


def _cubic_midpoints(c: np.ndarray, axis: int) -> np.ndarray:
    """Values at the midpoints along ``axis``: 4-point cubic (-1, 9, 9, -1)/16, linear at the two ends."""
    c = np.moveaxis(c, axis, 0)
    mid = 0.5 * (c[:-1] + c[1:])
    if c.shape[0] >= 4:
        mid[1:-1] = (-c[:-3] + 9.0 * c[1:-2] + 9.0 * c[2:-1] - c[3:]) / 16.0
    return np.moveaxis(mid, 0, axis)


def prolong_cubic(c: np.ndarray) -> np.ndarray:
    """FMG interpolation of a coarse solution (cubic in each direction), clipped at 0."""
    n, m = 2 * (c.shape[0] - 1), 2 * (c.shape[1] - 1)
    rows = np.zeros((n + 1, c.shape[1]))
    rows[::2] = c
    rows[1::2] = _cubic_midpoints(c, 0)
    f = np.zeros((n + 1, m + 1))
    f[:, ::2] = rows
    f[:, 1::2] = _cubic_midpoints(rows, 1)
    return np.maximum(f, 0.0)


@dataclass
class CycleLog:
    residual: list[float] = field(default_factory=list)
    load_error: list[float] = field(default_factory=list)
    h0: list[float] = field(default_factory=list)


class Multigrid:
    """FAS/FMG solver state: levels (0 = coarsest), H0, time T."""

    def __init__(self, prob: Problem, n: int, levels: int, coarsest_sweeps: int = 4, pre: int = 2,
                 post: int = 1, gamma: int = 1):
        if n & (n - 1) or n < 16:
            raise ValueError(f"grid intervals {n}: need a power of two >= 16")
        if n >> (levels - 1) < 8:
            raise ValueError(f"{levels} levels on n = {n}: the coarsest grid would have fewer than 8 intervals")
        self.prob = prob
        nc = n >> (levels - 1)
        ny_c = cross_intervals(nc, prob)
        self.levels = [Level(nc << l, prob, ny_c << l) for l in range(levels)]
        self.H0 = 0.0
        self.T = 0.0
        self.coarsest_sweeps, self.pre, self.post, self.gamma = coarsest_sweeps, pre, post, gamma
        self.sweeps = 0        # work counter in finest-grid sweep equivalents
        self.set_time(0.0)

    @property
    def fine(self) -> Level:
        return self.levels[-1]

    # -- evaluation -------------------------------------------------------------------------------------------
    def state(self, lv: Level, P: np.ndarray | None = None):
        """(H, rho, eps, r = rho H) of level ``lv`` at its P (or the given P)."""
        P = lv.P if P is None else P
        lub = self.prob.lubricant
        H = self.H0 + lv.rigid + lv.film.deformation(P)
        rho = lub.density(P)
        eps = rho * np.maximum(H, 0.0) ** 3 / (lub.viscosity(P) * self.prob.lam)
        return H, rho, eps, rho * H

    def residual(self, lv: Level) -> np.ndarray:
        H, rho, eps, r = self.state(lv)
        return lv.f - operator(lv.P, eps, r, lv.r1, lv.r2, lv.h, lv.ht)

    def residual_norm(self, lv: Level) -> tuple[float, float]:
        """Mean and max of the scaled residual |f - L(P)|/d over the pressurised interior nodes, d the diagonal
        of the point Jacobian (sum of the four face coefficients + the local elastic wedge term): the pressure
        change a point relaxation would still make, comparable between the Poiseuille-dominated inlet (d ~ 1e6)
        and the elastic contact (d ~ 1). NaN when P is not finite everywhere (a diverged iteration)."""
        if not np.isfinite(lv.P).all():
            # NaN nodes are not "P > 0": without this a wholly non-finite P read as a zero residual
            return float("nan"), float("nan")
        H, rho, eps, r = self.state(lv)
        res = (lv.f - operator(lv.P, eps, r, lv.r1, lv.r2, lv.h, lv.ht))[1:-1, 1:-1]
        wX, wD, wT = time_weights(lv.h, lv.ht)
        d = sum(faces(eps, lv.h)) + self.prob.c_el * ((wX + wD) * 1.5 + wT * 1.5) * rho[1:-1, 1:-1] * lv.film.K0[0]
        m = lv.P[1:-1, 1:-1] > 0
        if not m.any():
            return 0.0, 0.0
        s = np.abs(res[m]) / d[m]
        return float(s.mean()), float(s.max())

    def load_error(self) -> float:
        lv = self.fine
        return abs(lv.load_sum() - lv.g) / lv.g

    def set_time(self, T: float) -> None:
        """Rigid gap of every level at time T: the finest grid samples the indent at its nodes; each coarser grid
        takes the full weighting of the next finer grid's indent part (the paraboloid stays exact).

        Why not sample the indent on the coarse grids too (measured): a coarse grid that samples a
        narrow indent at its nodes (Phi = 0.5 on the 16-interval coarsest grid: two cells) sees a hole or a
        shoulder depending on where the nodes fall, and its correction misleads the fine grid: the crossing at
        M = 1200, L = 19 on 257^2 stalled as the indent entered the inlet (D/Phi = 0.35: step 125 of 192,
        residual 6.7e-4); with the weighted indent it converges (7.2 cycles per step)."""
        self.T = T
        fine = self.fine
        fine.rigid = fine.film.rigid(self.prob.indent, T)
        dent = fine.rigid - fine.film.base
        for lv in self.levels[-2::-1]:
            dent = full_weighting(dent)
            lv.rigid = lv.film.base + dent

    # -- smoothing ----------------------------------------------------------------------------------------------
    def relax(self, l: int, sweeps: int) -> None:
        lv = self.levels[l]
        f0 = lv.film
        st = lambda P: self.state(lv, P)   # noqa: E731
        for _ in range(sweeps):
            for colour in (1, 0):
                relax_colour(lv.P, lv.f, st, lv.h, lv.ht, lv.r1, lv.r2, self.prob.c_el, f0.K0, f0.K1, colour,
                             self.prob.lubricant.density_slope)
        self.sweeps += sweeps * 4.0 ** (l - len(self.levels) + 1)

    def relax_coarsest(self, sweeps: int, load_tol: float = 1e-9, max_sweeps: int = 8) -> None:
        """``sweeps`` relaxations with an H0 update after each, continued (up to ``max_sweeps``) until the
        coarse load balance holds to ``load_tol``: the fine load error after a cycle is the coarse one. A W-cycle
        visits the coarsest grid 2^(levels-1) times, so a few sweeps per visit suffice (8 at most: same cycle
        counts as 40, a third of the time, measured at 65^2 and 129^2)."""
        lv = self.levels[0]
        for k in range(max_sweeps):
            self.relax(0, 1)
            err = lv.load_sum() - lv.g
            self.H0 += self.prob.h0_factor * err
            if k + 1 >= sweeps and abs(err) <= load_tol * lv.g:
                break

    # -- cycles -------------------------------------------------------------------------------------------------
    def cycle(self, l: int) -> None:
        """One FAS cycle (V for gamma = 1, W for 2) from level l down."""
        if l == 0:
            self.relax_coarsest(self.coarsest_sweeps)
            return
        lv, cv = self.levels[l], self.levels[l - 1]
        self.relax(l, self.pre)
        res = self.residual(lv)
        cv.P = inject(lv.P)
        start = cv.P.copy()
        H, rho, eps, r = self.state(cv)
        cv.f = operator(cv.P, eps, r, cv.r1, cv.r2, cv.h, cv.ht) + restrict_residual(res, lv.P)
        cv.g = cv.load_sum() + (lv.g - lv.load_sum())
        for _ in range(self.gamma):
            self.cycle(l - 1)
        corr = prolong_bilinear(cv.P - start)
        # only inside the pressurised zone, not on its rim: at the cavitation boundary (the outlet spike, the
        # side edges) the coarse grid does not see the free boundary, and its correction there overshot and
        # diverged on 513^2 at high L (measured)
        lv.P += np.where(pressurised_patch(lv.P), corr, 0.0)
        np.maximum(lv.P, 0.0, out=lv.P)
        self.relax(l, self.post)

    def hertz_start(self) -> None:
        """Hertz pressure on the coarsest grid, H0 from the first guess."""
        lv = self.levels[0]
        X, Y = lv.film.X, lv.film.Y
        lv.P = np.sqrt(np.clip(1.0 - X**2 - (self.prob.kappa * Y) ** 2, 0.0, None))
        lv.P[0, :] = lv.P[-1, :] = lv.P[:, 0] = lv.P[:, -1] = 0.0
        i0, j0 = np.argmin(np.abs(lv.film.x)), np.argmin(np.abs(lv.film.y))
        self.H0 = self.prob.hc_start - lv.film.deformation(lv.P)[i0, j0]
