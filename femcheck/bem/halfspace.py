"""3D frictionless normal contact on an elastic half-space: regular grid of rectangular cells with Love's
influence coefficients, DC-FFT convolution and Polonsky-Keer CG, with a coarse-to-fine warm start.

The warm start follows the full-multigrid idea of seed 004 §2.6.2 in its simplest form: solve on grids coarsened
by 2 per level, interpolate each solution onto the next finer grid, and start CG there. The fine-grid CG then
only removes the interpolation error instead of building the contact from nothing.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Callable

import numpy as np
from scipy import fft
from scipy.interpolate import RegularGridInterpolator

from .convolution import DCFFT, padded_length
from .influence import love_rectangle
from .polonsky_keer import NormalContactResult, polonsky_keer

Gap = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Grid:
    """nx x ny cells of dx x dy (m) centred on the origin; with odd counts a cell is centred at (0, 0)."""

    nx: int
    ny: int
    dx: float
    dy: float

    @property
    def x(self) -> np.ndarray:
        return (np.arange(self.nx) - 0.5 * (self.nx - 1)) * self.dx

    @property
    def y(self) -> np.ndarray:
        return (np.arange(self.ny) - 0.5 * (self.ny - 1)) * self.dy

    @property
    def cell_area(self) -> float:
        return self.dx * self.dy

    def coarser(self) -> "Grid":
        """Every other node: (n + 1)/2 cells of twice the size (keeps a cell centred at the origin)."""
        return Grid((self.nx + 1) // 2, (self.ny + 1) // 2, 2 * self.dx, 2 * self.dy)

    def mesh(self) -> tuple[np.ndarray, np.ndarray]:
        return np.meshgrid(self.x, self.y, indexing="ij")


def grid(half_x: float, half_y: float, nx: int, ny: int) -> Grid:
    """Grid covering [-half_x, half_x] x [-half_y, half_y] (m) with nx x ny cells."""
    return Grid(nx, ny, 2 * half_x / nx, 2 * half_y / ny)


@lru_cache(maxsize=16)
def half_space_operator(g: Grid, modulus: float, workers: int = -1) -> DCFFT:
    """Pressure -> normal displacement operator of the grid; the kernel spectrum is computed once per
    (grid, modulus) and reused across solves (bench sweeps, warm-start levels, stress cases)."""
    return DCFFT(lambda tx, ty: love_rectangle(tx, ty, g.dx, g.dy, modulus), (g.nx, g.ny), (g.dx, g.dy),
                 workers=workers)


@dataclass
class HalfSpaceSolution:
    grid: Grid
    result: NormalContactResult
    stats: dict = field(default_factory=dict)


def _prolong(p: np.ndarray, coarse: Grid, fine: Grid) -> np.ndarray:
    interp = RegularGridInterpolator((coarse.x, coarse.y), p, method="linear", bounds_error=False,
                                     fill_value=0.0)
    X, Y = fine.mesh()
    return np.clip(interp((X, Y)), 0.0, None)


def fft_time(g: Grid, repeats: int = 5, workers: int = -1) -> float:
    """Seconds for one forward + one inverse real FFT of the padded grid (= one convolution; a Polonsky-Keer
    iteration does two, i.e. four FFTs)."""
    shape = (padded_length(g.nx), padded_length(g.ny))
    a = np.random.default_rng(0).random(shape)
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fft.irfftn(fft.rfftn(a, workers=workers), s=shape, workers=workers)
        best = min(best, time.perf_counter() - t0)
    return best


def solve(g: Grid, gap: Gap, modulus: float, load: float | None, tol: float = 1e-10, warm_levels: int = 0,
          min_cells: int = 17, max_iter: int = 2000, workers: int = -1,
          approach: float | None = None) -> HalfSpaceSolution:
    """Contact of two bodies with initial gap ``gap(x, y)`` (m), combined modulus E* (Pa) on grid ``g``, under
    load control (total ``load``, N) or approach control (``approach`` delta, m; pass load=None). ``warm_levels`` coarser grids are solved first (stopping before a
    grid gets fewer than ``min_cells`` cells per side); ``workers`` threads for the FFTs. Stats: iterations
    and time per level."""
    t0 = time.perf_counter()
    chain = [g]
    while len(chain) <= warm_levels and min(chain[-1].nx, chain[-1].ny) // 2 >= min_cells:
        chain.append(chain[-1].coarser())
    chain.reverse()
    p0, levels = None, []
    for k, gk in enumerate(chain):
        tk = time.perf_counter()
        op = half_space_operator(gk, modulus, workers)
        X, Y = gk.mesh()
        if p0 is not None:
            p0 = _prolong(p0, chain[k - 1], gk)
        # Coarse levels only need to be good enough to start the next one.
        res = polonsky_keer(gap(X, Y), op, load, gk.cell_area, p0=p0,
                            tol=tol if gk is g else max(tol, 1e-6), max_iter=max_iter, approach=approach)
        p0 = res.pressure
        levels.append({"nx": gk.nx, "ny": gk.ny, "iterations": res.iterations, "time_s": time.perf_counter() - tk})
    res.time_s = time.perf_counter() - t0
    return HalfSpaceSolution(g, res, {"levels": levels, "iterations": res.iterations,
                                      "total_iterations": sum(lv["iterations"] for lv in levels)})
