"""Kalker's linear-theory creep coefficients C11, C22, C23, C33 computed by the exact steady-rolling solver in the
small-creepage limit (full adhesion), extrapolated in the element size.

Linear theory (Kalker 1990 §3.2; Johnson 1985 §8.4; sign convention of conv.md), c = sqrt(a b):
  Fx = -G c^2 C11 xi,   Fy = -G c^2 C22 eta - G c^3 C23 phi,   Mz = G c^3 C23 eta - G c^4 C33 phi.
With no slip anywhere the tangential problem is linear and independent of the pressure and of mu: on the
elements of the Hertz ellipse (x/a)^2 + (y/b)^2 < 1 the discrete steady-rolling equations of
:mod:`femcheck.cect.exact` (s = w + [dIC] p = 0) are solved for unit xi, eta and phi. The grid has n x n
elements over the ellipse's bounding box [-a, a] x [-b, b] (so dx/dy = a/b and the element mask is the same for
every a/b), G = 1 and c = 1 (a = sqrt(a/b), b = 1/sqrt(a/b)): the resultants are the coefficients themselves.

Kalker's Eulerian discretisation is first order in dx (the backward difference of the convective term) and the
staircase ellipse adds an irregular part, so the coefficients are computed on several grids and extrapolated by
Richardson with the observed order: with h_k = 1/n_k and n_k doubling, q = log2((C1 - C2)/(C2 - C3)) and
C_inf = C3 + (C3 - C2)/(2^q - 1); the error estimate is |C_inf - C3| together with the spread of the
extrapolation from the two coarsest pairs.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
import scipy.linalg as sla

from ..bem.halfspace import Grid
from ..errors import InputError
from .exact import dense_operator
from .influence import CombinedConstants

COEFFICIENTS = ("c11", "c22", "c23", "c33")


@dataclass(frozen=True)
class CreepCoefficients:
    """Kalker coefficients (-) for ellipse axis ratio ``a_over_b`` and Poisson's ratio ``poisson``.

    ``c11, c22, c23, c33``: extrapolated values; ``error``: estimated absolute error of each (dict); ``grids``:
    element counts n used; ``raw``: the coefficients on each grid (dict of lists); ``order``: observed
    convergence order of each coefficient (None with two grids).
    """

    a_over_b: float
    poisson: float
    c11: float
    c22: float
    c23: float
    c33: float
    error: dict = field(default_factory=dict)
    grids: tuple = ()
    raw: dict = field(default_factory=dict)
    order: dict = field(default_factory=dict)


SOLVERS = ("auto", "dense", "fft")
AUTO_FFT_CELLS = 40      # "auto": dense LU up to 40 x 40 elements (C ~ 1250), matrix-free GMRES above


@lru_cache(maxsize=64)
def coefficients_on_grid(a_over_b: float, poisson: float, n: int, solver: str = "auto") -> dict[str, float]:
    """C11, C22, C23, C33 from one full-adhesion solve on an n x n grid (see module docstring). Also returns the
    second estimate of C23 from the spin moment under eta (``c32``; equal to C23 in the continuum by Betti's
    reciprocity), a discretisation check. ``solver``: "dense" (2C x 2C LU), "fft" (matrix-free GMRES with DC-FFT
    products and the upwind-sum + circulant preconditioner, :func:`femcheck.cect.tangential_fft.solve_adhesion`;
    relative residual 1e-11) or "auto" (fft for n > AUTO_FFT_CELLS). Cached."""
    if not 0.0 < a_over_b < np.inf:
        raise InputError("a_over_b", f"{a_over_b}; allowed: > 0")
    if not -1.0 < poisson <= 0.5:
        raise InputError("nu", f"{poisson}; allowed: (-1, 0.5]")
    if n < 4:
        raise InputError("n", f"{n}; allowed: >= 4 elements per axis")
    if solver not in SOLVERS:
        raise InputError("numerics.exact_solver", f"{solver!r}; allowed: {', '.join(SOLVERS)}")
    a, b = np.sqrt(a_over_b), 1.0 / np.sqrt(a_over_b)          # c = sqrt(a b) = 1
    g = Grid(n, n, 2.0 * a / n, 2.0 * b / n)
    X, Y = g.mesh()
    inside = (X / a) ** 2 + (Y / b) ** 2 < 1.0
    cells = np.nonzero(inside)
    constants = CombinedConstants(1.0, float(poisson), 0.0)
    xc, yc = X[cells], Y[cells]
    C = xc.size
    one, zero = np.ones(C), np.zeros(C)
    # rigid slip w = (xi - phi y, eta + phi x) for unit xi, eta, phi; full adhesion: B p = -w
    W = np.stack([np.concatenate([one, zero]), np.concatenate([zero, one]), np.concatenate([-yc, xc])], axis=1)
    if solver == "dense" or (solver == "auto" and n <= AUTO_FFT_CELLS):
        B = dense_operator(g, cells, constants, "xy", "xy", rolling=True)
        P = sla.solve(B, -W, check_finite=False)
    else:
        from .tangential_fft import solve_adhesion
        P = solve_adhesion(g, cells, constants, W.T.reshape(3, 2, C), rolling=True)[0].reshape(3, 2 * C).T
    area = g.cell_area
    fx = P[:C].sum(axis=0) * area
    fy = P[C:].sum(axis=0) * area
    mz = (xc[:, None] * P[C:] - yc[:, None] * P[:C]).sum(axis=0) * area
    # c from the area actually discretised (c^2 = A/pi, as for any non-Hertzian contact in Kalker's theory):
    # the staircase ellipse's area fluctuates by several % between grids, and normalising by it removes that
    # irregular part of the discretisation error (the coefficients scale with c^2, c^3, c^4)
    c = np.sqrt(C * area / np.pi)
    return {"c11": float(-fx[0] / c**2), "c22": float(-fy[1] / c**2), "c23": float(-fy[2] / c**3),
            "c33": float(-mz[2] / c**4), "c32": float(mz[1] / c**3), "elements": int(C),
            "area_ratio": float(C * area / np.pi)}


def richardson(values: list[float], ratio: float = 2.0) -> tuple[float, float, float | None]:
    """Extrapolate values on grids refined by ``ratio``: returns (limit, error estimate, observed order).

    Three or more values: observed order q from the last three (kept within [0.5, 3]: outside that the sequence
    is not in its asymptotic range and first order, Kalker's scheme order, is assumed), limit
    C3 + (C3 - C2)/(ratio^q - 1), error = max(|limit - C3|, |limit - limit from the previous triple|) when
    available. Two values: first order.
    """
    v = [float(x) for x in values]
    if len(v) < 2:
        raise ValueError("Richardson extrapolation needs at least two grids")
    q = None
    if len(v) >= 3:
        d1, d2 = v[-3] - v[-2], v[-2] - v[-1]
        if d1 != 0 and d2 != 0 and d1 / d2 > 0:
            q = float(np.log(d1 / d2) / np.log(ratio))
            if not 0.5 <= q <= 3.0:
                q = None
    order = 1.0 if q is None else q
    limit = v[-1] + (v[-1] - v[-2]) / (ratio ** order - 1.0)
    err = abs(limit - v[-1])
    if len(v) >= 3:
        prev = v[-2] + (v[-2] - v[-3]) / (ratio ** order - 1.0)
        err = max(err, abs(limit - prev))
    return float(limit), float(err), q


@lru_cache(maxsize=64)
def creep_coefficients(a_over_b: float, poisson: float, grids: tuple[int, ...] = (12, 24, 48),
                       solver: str = "auto") -> CreepCoefficients:
    """Kalker's C11, C22, C23, C33 at a/b = ``a_over_b`` and nu = ``poisson`` from full-adhesion solves on the
    n x n ``grids`` (each twice the previous), Richardson-extrapolated (see :func:`richardson`); ``solver`` as
    in :func:`coefficients_on_grid`. Cached on its arguments (lru_cache): the linear and FASTSIM models of a
    scene reuse one computation."""
    grids = tuple(int(n) for n in grids)
    if len(grids) < 2 or any(grids[k + 1] != 2 * grids[k] for k in range(len(grids) - 1)):
        raise InputError("numerics.creep_grids", f"{grids}; allowed: two or more element counts, each twice the "
                         "previous (Richardson extrapolation)")
    per_grid = [coefficients_on_grid(float(a_over_b), float(poisson), n, solver) for n in grids]
    raw = {k: [r[k] for r in per_grid] for k in COEFFICIENTS}
    out, err, order = {}, {}, {}
    for k in COEFFICIENTS:
        out[k], err[k], order[k] = richardson(raw[k])
    raw["c32"] = [r["c32"] for r in per_grid]
    raw["elements"] = [r["elements"] for r in per_grid]
    return CreepCoefficients(float(a_over_b), float(poisson), out["c11"], out["c22"], out["c23"], out["c33"],
                             err, grids, raw, order)
