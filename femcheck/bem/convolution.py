"""Non-periodic discrete convolution by DC-FFT (Liu, Wang & Liu, Wear 243, 2000).

u_i = sum_j K(x_i - x_j) p_j on a regular grid of n_1 x ... x n_d cells is a linear (not cyclic)
convolution. DC-FFT pads p with zeros to 2n per axis and stores the kernel in wrap-around order
(lags 0..n-1 at indices 0..n-1, lag -(n-1)..-1 at n+1..2n-1, index n unused), so a cyclic convolution of
length 2n reproduces the linear one exactly. The kernel spectrum is computed once per grid and reused.
"""
from __future__ import annotations

from typing import Callable, Sequence

import numpy as np
from scipy import fft


def wrapped_lags(n: int, spacing: float) -> np.ndarray:
    """Lag coordinates (m) of length 2n in DC-FFT wrap-around order; entry n is a dummy lag set to 0."""
    k = np.arange(2 * n)
    lag = np.where(k < n, k, k - 2 * n).astype(float)
    lag[n] = 0.0
    return lag * spacing


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
        self.padded = tuple(2 * n for n in self.shape)
        self.workers = workers
        lags = np.meshgrid(*(wrapped_lags(n, h) for n, h in zip(self.shape, self.spacing)),
                           indexing="ij", sparse=True)
        k = np.asarray(kernel(*lags), dtype=float)
        # The dummy lag n (index n per axis) never contributes to the first n outputs; zero it for clarity.
        for axis, n in enumerate(self.shape):
            idx = [slice(None)] * k.ndim
            idx[axis] = n
            k[tuple(idx)] = 0.0
        self.spectrum = fft.rfftn(k, s=self.padded, workers=workers)
        self._out = tuple(slice(0, n) for n in self.shape)

    def __call__(self, p: np.ndarray) -> np.ndarray:
        """Return u = K * p (same shape as p)."""
        ph = fft.rfftn(p, s=self.padded, workers=self.workers)
        return fft.irfftn(ph * self.spectrum, s=self.padded, workers=self.workers)[self._out]
