"""Seed 001's finite-line method for roller contacts (Johns-Rahnejat, Dolatabadi & Rahnejat 2023, eqs 8-17).

The footprint is covered by overlapping elements centred on stations y_j = -L/2 + j c (j = 0..N, c = L/N):
element j carries p_mj (1 - |y - y_j|/c) sqrt(1 - x^2/a_j^2), a semi-elliptical profile across (width 2 a_j)
times an isosceles triangle along the axis (clipped at the roller ends). Deflections are collocated at (0, y_j):

    delta - h(0, y_j) = sum_i p_mi C_ij(a_i),   C_ij = 1/(pi E*) int int tri_i(y1) sqrt(1 - x1^2/a_i^2) / r dA

(eqs 8, 13-16), with the y-integral in closed form (eq 12) and the x-integral by Gauss-Chebyshev quadrature
of the second kind after subtracting its logarithmic singularity analytically. The load balance (eq 24)
W = sum_j p_mj (pi a_j / 2) w_j, w_j = int tri_j dy, closes the system for the approach delta.

The seed does not state how the element half-widths a_j follow the pressure. Here each strip is taken as
locally Hertzian, a_j = 2 R p_mj / E* (Hertz line: p0 = E* a / (2R)), and the pressures and half-widths are
iterated to a fixed point (eq 23), stations with p_m <= 0 leaving the contact. This makes the half-width grow
where the pressure rises, which is what gives the dog-bone footprint.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import ConvergenceError

_LN_WEIGHT = -0.5 * np.pi * (np.log(2.0) + 0.5)     # int_-1^1 sqrt(1 - t^2) ln|t| dt


@dataclass
class FiniteLineResult:
    """Stations ``y`` (m), peak pressures ``p_m`` (Pa) and half-widths ``a`` (m) per station, approach (m),
    iterations, residual (relative change of p_m at the last iteration), load (N), time (s)."""

    y: np.ndarray
    p_m: np.ndarray
    a: np.ndarray
    approach: float
    iterations: int
    residual: float
    load: float
    time_s: float

    def pressure(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """p(x, y): piecewise-linear interpolation of p_m and a along y, elliptical across."""
        pm = np.interp(y, self.y, self.p_m, left=0.0, right=0.0)
        a = np.interp(y, self.y, self.a, left=0.0, right=0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(a > 0, 1.0 - (x / np.where(a > 0, a, 1.0)) ** 2, 0.0)
        return pm * np.sqrt(np.clip(s, 0.0, None))


def _tri_integral(X: np.ndarray, Y: np.ndarray, yi: np.ndarray, c: float, lo: float, hi: float) -> np.ndarray:
    """J = int tri_i(y1) / sqrt(X^2 + (Y - y1)^2) dy1, tri_i = (1 - |y1 - yi|/c) on [yi - c, yi + c] clipped to
    [lo, hi] (roller ends). Closed form per linear piece (seed 001 eq 12): with s = y1 - Y,
    int (alpha + beta s) / sqrt(X^2 + s^2) ds = alpha asinh(s/|X|) + beta sqrt(X^2 + s^2)."""
    ax = np.abs(X)
    out = np.zeros(np.broadcast(X, Y, yi).shape)
    for ya, yb, slope in ((np.clip(yi - c, lo, hi), np.clip(yi, lo, hi), 1.0 / c),      # rising piece
                          (np.clip(yi, lo, hi), np.clip(yi + c, lo, hi), -1.0 / c)):    # falling piece
        alpha = 1.0 + slope * (Y - yi)               # the piece's line evaluated at y1 = Y (s = 0)
        s0, s1 = ya - Y, yb - Y
        out = out + alpha * (np.arcsinh(s1 / ax) - np.arcsinh(s0 / ax)) \
            + slope * (np.sqrt(ax * ax + s1 * s1) - np.sqrt(ax * ax + s0 * s0))
    return out


def influence(y: np.ndarray, a: np.ndarray, c: float, lo: float, hi: float, modulus: float,
              m: int = 48) -> np.ndarray:
    """C[j, i]: deflection at (0, y_j) per unit p_mi of element i with half-width a_i (m/Pa), eq 13.

    x1 = a_i t; int_-1^1 sqrt(1 - t^2) J(a_i t) dt by Gauss-Chebyshev (2nd kind, m nodes) after removing
    J's singular part -n tri_i(Y) ln|X| (as X -> 0), whose weighted integral is done exactly; the remainder
    converges as O(1/m^2) (checked against polar quadrature: 2e-5 at m = 48).
    """
    k = np.arange(1, m + 1)
    t = np.cos(k * np.pi / (m + 1))
    w = np.pi / (m + 1) * np.sin(k * np.pi / (m + 1)) ** 2
    Y = y[:, None, None]
    yi = y[None, :, None]
    ai = a[None, :, None]
    X = ai * t[None, None, :]
    # Singular part of J as X -> 0: -n tri_i(Y) ln|X|, n = number of sides of the support [ya, yb] around Y
    # (2 inside, 1 when Y is a roller end, where the clipped support is one-sided).
    ya, yb = np.clip(yi - c, lo, hi), np.clip(yi + c, lo, hi)
    sides = (Y > ya).astype(float) + (Y < yb).astype(float)
    coef = np.clip(1.0 - np.abs(Y - yi) / c, 0.0, None) * ((Y >= ya) & (Y <= yb)) * sides
    J = _tri_integral(X, Y, yi, c, lo, hi)
    regular = np.tensordot(J + coef * np.log(np.abs(X)), w, axes=([2], [0]))
    exact = -coef[..., 0] * (0.5 * np.pi * np.log(a[None, :]) + _LN_WEIGHT)
    return a[None, :] * (regular + exact) / (np.pi * modulus)


def solve(gap_at_axis: Callable[[np.ndarray], np.ndarray], radius: float, length: float, modulus: float,
          load: float, n_elements: int = 64, tol: float = 1e-9, max_iter: int = 200,
          relaxation: float = 0.7) -> FiniteLineResult:
    """Finite-line contact of a roller of reduced ``radius`` R (m) and ``length`` L (m) under ``load`` W (N).

    ``gap_at_axis(y)``: initial gap on the centre line x = 0 (crown, tilt), finite on [-L/2, L/2].
    Fixed point on (p_m, a): solve the collocation + load system for fixed a, update
    a <- a + relaxation (2 R p_m / E* - a), until max|dp_m| / max p_m < tol.
    """
    t0 = time.perf_counter()
    lo, hi = -0.5 * length, 0.5 * length
    c = length / n_elements
    y = lo + c * np.arange(n_elements + 1)
    w = np.full(y.size, c)
    w[[0, -1]] = 0.5 * c                            # end triangles are halved by the roller ends
    h = np.asarray(gap_at_axis(y), dtype=float)
    if not np.all(np.isfinite(h)):
        raise ValueError("the gap must be finite along the whole roller")
    w_line = load / length
    a0 = np.sqrt(4.0 * w_line * radius / (np.pi * modulus))      # Hertz trial (seed: 'a trial load')
    a = np.full(y.size, a0)
    active = np.ones(y.size, dtype=bool)
    p = np.zeros(y.size)
    residual = np.inf
    for it in range(1, max_iter + 1):
        C = influence(y, np.where(active, a, a0), c, lo, hi, modulus)
        for _ in range(y.size):                     # active set on the stations
            idx = np.flatnonzero(active)
            n = idx.size
            A = np.zeros((n + 1, n + 1))
            A[:n, :n] = C[np.ix_(idx, idx)]
            A[:n, n] = -1.0
            A[n, :n] = 0.5 * np.pi * a[idx] * w[idx]
            rhs = np.concatenate([-h[idx], [load]])
            sol = np.linalg.solve(A, rhs)
            p_new = np.zeros(y.size)
            p_new[idx] = sol[:n]
            delta = sol[n]
            if (p_new[idx] > 0).all():
                break
            active[idx[p_new[idx] <= 0]] = False
            if not active.any():
                raise ConvergenceError("finite-line method", it, np.inf, tol, "no station stays in contact")
        a_target = np.where(active, 2.0 * radius * p_new / modulus, 0.0)
        residual = float(max(np.abs(p_new - p).max() / np.abs(p_new).max(),
                             np.abs(np.where(active, a, 0.0) - a_target).max() / a_target.max()))
        p = p_new
        if residual < tol:
            # (p, a, delta) is the triple that was solved: collocation and load balance hold exactly
            a_used = np.where(active, a, 0.0)
            load_out = float(np.sum(p * 0.5 * np.pi * a_used * w))
            return FiniteLineResult(y, p, a_used, float(delta), it, residual, load_out, time.perf_counter() - t0)
        a = np.where(active, a + relaxation * (a_target - a), a)
    raise ConvergenceError("finite-line method", max_iter, residual, tol)
