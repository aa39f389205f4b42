"""Non-periodic discrete convolution by DC-FFT (Liu, Wang & Liu, Wear 243, 2000).

u_i = sum_j K(x_i - x_j) p_j on a regular grid of n_1 x ... x n_d cells is a linear (not cyclic)
convolution. DC-FFT pads p with zeros to a length L >= 2n - 1 per axis and stores the kernel in wrap-around
order (lags 0..n-1 at indices 0..n-1, lags -(n-1)..-1 at L-n+1..L-1, zeros between), so a cyclic convolution
of length L reproduces the linear one exactly. Liu, Wang & Liu use L = 2n; any L >= 2n - 1 is exact, so L is
taken as scipy's next fast length (2 * 257 = 514 has the prime factor 257: its FFT was 7x slower than 520's).
The kernel spectrum is computed once per grid and reused.
"""
from __future__ import annotations

from typing import Callable, Sequence

import numpy as np
from scipy import fft


def padded_length(n: int) -> int:
    """Smallest fast FFT length >= 2n - 1 (exact linear convolution of n-point sequences)."""
    return fft.next_fast_len(2 * n - 1, real=True)


def wrapped_lags(n: int, spacing: float, length: int) -> tuple[np.ndarray, np.ndarray]:
    """Lag coordinates (m) of a cyclic array of ``length`` in DC-FFT wrap-around order, and the mask of
    entries that hold a real lag (|lag| <= n - 1); the others are padding."""
    k = np.arange(length)
    lag = np.where(k < n, k, k - length)
    valid = np.abs(lag) <= n - 1
    return np.where(valid, lag, 0).astype(float) * spacing, valid


class DCFFT:
    """Linear convolution operator p -> K * p on a regular grid.

    ``kernel(*lags)`` returns the influence of a unit value in a cell at lag (dx, dy, ...) in metres, taking
    broadcastable coordinate arrays. ``shape`` is the grid shape (cells), ``spacing`` the cell size per axis.
    """

    def __init__(self, kernel: Callable[..., np.ndarray], shape: Sequence[int], spacing: Sequence[float],
                 workers: int = -1):
        self.shape = tuple(int(n) for n in shape)
        self.spacing = tuple(float(h) for h in spacing)
        if len(self.shape) != len(self.spacing):
            raise ValueError("shape and spacing must have the same length")
        self.padded = tuple(padded_length(n) for n in self.shape)
        self.workers = workers
        wrapped = [wrapped_lags(n, h, L) for n, h, L in zip(self.shape, self.spacing, self.padded)]
        lags = np.meshgrid(*(w[0] for w in wrapped), indexing="ij", sparse=True)
        valid = np.ones((), dtype=bool)
        for axis, (_, v) in enumerate(wrapped):
            shape = [1] * len(wrapped)
            shape[axis] = v.size
            valid = valid & v.reshape(shape)
        k = np.where(valid, np.asarray(kernel(*lags), dtype=float), 0.0)
        spectrum = fft.rfftn(k, s=self.padded, workers=workers)
        # An even kernel (Love's rectangle, the strip) has a real spectrum: store it real, halving the work
        # and memory traffic of the product in every convolution.
        if np.abs(spectrum.imag).max() <= 1e-13 * np.abs(spectrum.real).max():
            spectrum = np.ascontiguousarray(spectrum.real)
        self.spectrum = spectrum
        self._out = tuple(slice(0, n) for n in self.shape)

    def __call__(self, p: np.ndarray) -> np.ndarray:
        """Return u = K * p (same shape as p). (Pruned per-axis transforms that skip the zero padding were
        measured too: within this machine's timing noise of the plain rfftn/irfftn, so not kept.)"""
        ph = fft.rfftn(p, s=self.padded, workers=self.workers)
        ph *= self.spectrum                      # in place: no second padded-size temporary
        return fft.irfftn(ph, s=self.padded, workers=self.workers, overwrite_x=True)[self._out]
