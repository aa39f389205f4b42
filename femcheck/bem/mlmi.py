"""Multilevel multi-integration (MLMI; Brandt & Lubrecht, J. Comput. Phys. 90, 1990; seed 004 §2.6.1,
eqs 2.17-2.22): the discrete convolution u_i = sum_j K(x_i - x_j) p_j evaluated on a hierarchy of grids,
a second back-end next to DC-FFT (:mod:`femcheck.bem.convolution`) with the same call signature.

The kernel is smooth away from its singularity, the pressure need not be. One level replaces the kernel's
dependence on the source point by its order-``order`` Lagrange interpolation from the coarse grid
(every other point), which moves the sum onto coarse sources U = I^T p (anterpolation, eq 2.20), then does the
same for the target point, which moves it onto coarse targets (eq 2.19, recursively). Both interpolations
are exact only where the kernel is smooth, so each is corrected by the exact local difference within
``correction`` points (eqs 2.21-2.22). The coarsest grid is summed directly. Work is O(N) per level (the
corrections are fixed small stencils), so O(N) overall instead of DC-FFT's O(N log N) -- at the price of an
approximation error that falls with ``order`` and ``correction`` and that this module measures rather than
assumes (:func:`femcheck.bem.mlmi.error_against`).

Index bookkeeping: every level holds values on an index range [lo, hi] per axis of its own lattice; index 0 of
every level sits at the first fine cell and level l has spacing 2^l h. Coarse point J coincides with fine point
2J. The ranges grow by order/2 points per level, enough to hold every anterpolated source and every coarse
point a fine interpolation stencil touches.
"""
from __future__ import annotations

import itertools
from typing import Callable, Sequence

import numpy as np
from scipy import ndimage, sparse


def lagrange_midpoint_weights(order: int) -> np.ndarray:
    """Weights of the centred order-``order`` Lagrange interpolation at the midpoint of the two central
    nodes (order 4: (-1, 9, 9, -1)/16; order 6: (3, -25, 150, 150, -25, 3)/256)."""
    if order < 2 or order % 2:
        raise ValueError("order must be an even integer >= 2")
    nodes = np.arange(order) - (order / 2 - 1)        # coarse offsets, midpoint at 0.5
    w = np.ones(order)
    for k in range(order):
        for j in range(order):
            if j != k:
                w[k] *= (0.5 - nodes[j]) / (nodes[k] - nodes[j])
    return w


def _interpolation_matrix(f_lo: int, f_hi: int, c_lo: int, c_hi: int, weights: np.ndarray) -> sparse.csr_matrix:
    """1D coarse -> fine interpolation on index ranges: fine point 2J takes coarse J, fine point 2J + 1 the
    midpoint stencil over coarse J - order/2 + 1 .. J + order/2."""
    order = weights.size
    fine = np.arange(f_lo, f_hi + 1)
    rows, cols, vals = [], [], []
    even = fine % 2 == 0
    rows.append(np.flatnonzero(even))
    cols.append(fine[even] // 2)
    vals.append(np.ones(even.sum()))
    odd = np.flatnonzero(~even)
    base = (fine[odd] - 1) // 2 - (order // 2 - 1)
    for k in range(order):
        rows.append(odd)
        cols.append(base + k)
        vals.append(np.full(odd.size, weights[k]))
    rows, cols, vals = (np.concatenate(a) for a in (rows, cols, vals))
    if cols.min() < c_lo or cols.max() > c_hi:
        raise ValueError("coarse range does not cover the interpolation stencils")
    return sparse.csr_matrix((vals, (rows, cols - c_lo)), shape=(fine.size, c_hi - c_lo + 1))


def _along(matrix: sparse.spmatrix, a: np.ndarray, axis: int) -> np.ndarray:
    """Apply ``matrix`` to axis ``axis`` of ``a``."""
    moved = np.moveaxis(a, axis, 0)
    out = matrix @ moved.reshape(moved.shape[0], -1)
    return np.moveaxis(out.reshape((matrix.shape[0],) + moved.shape[1:]), 0, axis)


def _window(a: np.ndarray, start: Sequence[int], shape: Sequence[int]) -> np.ndarray:
    """b[k] = a[k + start] for k in [0, shape), zero where k + start falls outside a."""
    out = np.zeros(shape)
    src, dst = [], []
    for s0, n_out, n_in in zip(start, shape, a.shape):
        lo, hi = max(0, -s0), min(n_out, n_in - s0)
        dst.append(slice(lo, max(lo, hi)))
        src.append(slice(lo + s0, max(lo, hi) + s0))
    out[tuple(dst)] = a[tuple(src)]
    return out


class MLMI:
    """Operator p -> K * p on a regular grid by multilevel multi-integration.

    ``kernel(*lags)`` as for :class:`femcheck.bem.convolution.DCFFT` (influence of a unit value at lag in
    metres; here it must be symmetric and smooth away from lag 0). ``order`` of the Lagrange interpolation
    (even), ``correction`` half-width m of the local correction stencils in points of the level (eq 2.21's
    |j - i| <= m), ``coarsest`` the number of points per axis below which a level is summed directly.
    """

    def __init__(self, kernel: Callable[..., np.ndarray], shape: Sequence[int], spacing: Sequence[float],
                 order: int = 6, correction: int = 10, coarsest: int = 32):
        self.shape = tuple(int(n) for n in shape)
        self.spacing = tuple(float(h) for h in spacing)
        self.order, self.correction = int(order), int(correction)
        # Full coarsening interpolates every axis with the coarse spacing of that axis, so a source close in
        # one direction but a few fine points away along a much finer axis is outside the (index-square)
        # correction stencil yet closer than one coarse spacing of the coarse axis: measured error 1.3e-5 at
        # dy/dx = 2, 7e-5 at 3, 3 % at 20 (order 6, correction 10). Such grids need semi-coarsening; refuse.
        if max(self.spacing) > 2.0 * min(self.spacing):
            raise ValueError(f"MLMI needs near-square cells (spacing ratio <= 2), got spacing {self.spacing}; "
                             "use the dcfft convolution for elongated grids")
        if self.correction < self.order // 2:
            raise ValueError("correction must be at least order/2 points")
        # scipy.ndimage skips stencil weights below machine epsilon in absolute value, which would silently
        # drop a physical kernel (metres per pascal, ~1e-16): work with the kernel over its value at lag 0.
        self.scale = float(np.abs(kernel(*([np.zeros(1)] * len(self.shape)))).max())
        self.kernel = lambda *lags: kernel(*lags) / self.scale
        self.weights = lagrange_midpoint_weights(self.order)
        self.levels = self._build(coarsest)

    # -- set-up: per level its ranges, interpolation matrices and correction stencils --------------------
    def _build(self, coarsest: int) -> list[dict]:
        d, half = len(self.shape), self.order // 2
        lo, hi = [0] * d, [n - 1 for n in self.shape]
        levels, level = [], 0
        while True:
            h = tuple(s * 2**level for s in self.spacing)
            lv = {"lo": lo, "hi": hi, "h": h}
            if max(b - a + 1 for a, b in zip(lo, hi)) <= coarsest:
                lv["direct"] = self._lag_kernel(lo, hi, h)
                levels.append(lv)
                return levels
            c_lo = [a // 2 - half for a in lo]
            c_hi = [(b + 1) // 2 + half for b in hi]
            lv["interp"] = [_interpolation_matrix(a, b, ca, cb, self.weights)
                            for a, b, ca, cb in zip(lo, hi, c_lo, c_hi)]
            lv["anterp"] = [P.T.tocsr() for P in lv["interp"]]
            lv["source"], lv["target"] = self._stencils(h)
            lv["sub"], lv["source_off"], lv["target_slices"] = self._lattices(lo, hi, c_lo)
            levels.append(lv)
            lo, hi, level = c_lo, c_hi, level + 1

    @staticmethod
    def _lattices(lo, hi, c_lo) -> tuple[dict, dict, dict]:
        """Index bookkeeping of the parity sub-lattices of a level with range [lo, hi] (coarse range from
        c_lo). Fine point i = 2 I + q has parity q (0/1 per axis) and sub-lattice coordinate I.

        sub[q]: slices of the level's array that select parity q; source_off[(pi, sigma)]: offset between the
        sub-lattice coordinates of parity-sigma targets and parity-pi sources; target_slices[q]: slices pairing
        fine targets of parity q with their coarse point I in the coarse array.
        """
        d = len(lo)
        sub, first_index, off, target = {}, {}, {}, {}
        for q in itertools.product((0, 1), repeat=d):
            start = [(q[a] - lo[a]) % 2 for a in range(d)]
            sub[q] = tuple(slice(st, None, 2) for st in start)
            first_index[q] = [(lo[a] + start[a] - q[a]) // 2 for a in range(d)]
            count = [(hi[a] - lo[a] - start[a]) // 2 + 1 for a in range(d)]
            target[q] = (sub[q], tuple(slice(first_index[q][a] - c_lo[a], first_index[q][a] - c_lo[a] + count[a])
                                       for a in range(d)))
        for pi in sub:
            for sigma in sub:
                off[(pi, sigma)] = [first_index[sigma][a] - first_index[pi][a] for a in range(d)]
        return sub, off, target

    def _lag_kernel(self, lo, hi, h) -> np.ndarray:
        lags = np.meshgrid(*(np.arange(-(b - a), b - a + 1) * s for a, b, s in zip(lo, hi, h)),
                           indexing="ij", sparse=True)
        return np.asarray(self.kernel(*lags), dtype=float)

    def _stencils(self, h) -> tuple[dict, dict]:
        """Correction stencils per parity class pi (0/1 per axis, not all 0).

        source (eq 2.22): S_pi(delta) = K(delta h) - sum_J w_J K((pi + delta - 2J) h), the error of
        interpolating the kernel's source dependence, for a fine source of parity pi at offset delta.
        target: T_pi(Delta) = K((pi + 2 Delta) h) - sum_I w_I K(2 (I + Delta) h), the error of interpolating
        the target dependence, for a fine target of parity pi and a coarse source Delta coarse points away.
        The source stencil covers |delta| <= m fine points, the target one the same distance in coarse points.
        """
        d, m, half = len(h), self.correction, self.order // 2
        offsets = np.arange(self.order) - (half - 1)      # coarse nodes of the midpoint stencil
        delta = np.arange(-m, m + 1)
        coarse_delta = np.arange(-((m + 1) // 2), (m + 1) // 2 + 1)   # the same physical reach, coarse points
        source, target = {}, {}
        for pi in itertools.product((0, 1), repeat=d):
            if not any(pi):
                continue
            # tensor-product stencil: per axis the coarse offsets and weights (injection on even axes)
            nodes = [offsets if p else np.zeros(1, dtype=int) for p in pi]
            wts = [self.weights if p else np.ones(1) for p in pi]
            exact_s = self._k([(delta * 1.0)] * d, h)
            exact_t = self._k([(p + 2.0 * coarse_delta) for p in pi], h)
            approx_s, approx_t = np.zeros_like(exact_s), np.zeros_like(exact_t)
            for combo in itertools.product(*(range(n.size) for n in nodes)):
                w = np.prod([wts[a][c] for a, c in enumerate(combo)])
                node = [nodes[a][c] for a, c in enumerate(combo)]
                approx_s += w * self._k([p + delta - 2.0 * J for p, J in zip(pi, node)], h)
                approx_t += w * self._k([2.0 * (J + coarse_delta) for J in node], h)
            target[pi] = exact_t - approx_t
            # the source stencil split by target parity sigma, on the sub-lattices: a parity-pi source and a
            # parity-sigma target D sub-lattice points apart are 2D + sigma - pi fine points apart
            full = exact_s - approx_s
            reach = (m + 1) // 2
            for sigma in itertools.product((0, 1), repeat=d):
                idx = [2 * np.arange(-reach, reach + 1) + sg - p + m for sg, p in zip(sigma, pi)]
                inside = [(i >= 0) & (i <= 2 * m) for i in idx]
                st = full[np.ix_(*[np.clip(i, 0, 2 * m) for i in idx])]
                keep = np.ones(st.shape, dtype=bool)
                for a, ins in enumerate(inside):
                    keep &= ins.reshape([-1 if b == a else 1 for b in range(d)])
                source[(pi, sigma)] = np.where(keep, st, 0.0)
        return source, target

    def _k(self, lags_in_points: list[np.ndarray], h) -> np.ndarray:
        grids = np.meshgrid(*(np.asarray(t, dtype=float) * s for t, s in zip(lags_in_points, h)), indexing="ij",
                            sparse=True)
        return np.asarray(self.kernel(*grids), dtype=float)

    # -- evaluation --------------------------------------------------------------------------------------
    def __call__(self, p: np.ndarray) -> np.ndarray:
        """Return u = K * p (same shape as p), approximately (see :func:`error_against`)."""
        if p.shape != self.shape:
            raise ValueError(f"pressure shape {p.shape} != grid {self.shape}")
        return self.scale * self._apply(np.asarray(p, dtype=float), 0)

    def _apply(self, u: np.ndarray, k: int) -> np.ndarray:
        lv = self.levels[k]
        if "direct" in lv:                                  # coarsest level: direct sum
            return ndimage.convolve(u, lv["direct"], mode="constant", cval=0.0)
        coarse = u
        for axis, R in enumerate(lv["anterp"]):             # anterpolation U = I^T u (eq 2.20)
            coarse = _along(R, coarse, axis)
        w = self._apply(coarse, k + 1)                      # coarse targets, coarse sources (eq 2.19)
        for axis, P in enumerate(lv["interp"]):             # coarse targets -> fine targets
            w = _along(P, w, axis)
        for pi, T in lv["target"].items():                  # target-interpolation error, on the coarse lattice
            fine, crs = lv["target_slices"][pi]
            w[fine] += ndimage.convolve(coarse, T, mode="constant", cval=0.0)[crs]
        for (pi, sigma), S in lv["source"].items():         # source-interpolation error (eqs 2.21-2.22)
            # sources within the stencil's reach of the targets, including those beyond the targets' range
            target, r = w[lv["sub"][sigma]], S.shape[0] // 2
            src = _window(u[lv["sub"][pi]], [o - r for o in lv["source_off"][(pi, sigma)]],
                          [n + 2 * r for n in target.shape])
            target += ndimage.convolve(src, S, mode="constant", cval=0.0)[(slice(r, -r),) * target.ndim]
        return w


def error_against(reference: Callable[[np.ndarray], np.ndarray], approx: Callable[[np.ndarray], np.ndarray],
                  p: np.ndarray) -> float:
    """max |approx(p) - reference(p)| / max |reference(p)|."""
    ref = reference(p)
    return float(np.abs(approx(p) - ref).max() / np.abs(ref).max())
