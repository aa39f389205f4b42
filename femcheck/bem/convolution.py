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


# Below about 1024^2 padded points one thread is faster than two on the 2-core CI machine (512^2: 4.8 ms with
# one worker, 6.3 ms with two; 2048^2: 116 ms vs 92 ms), so threads are only used above this size.
THREADED_FFT_POINTS = 1 << 20


def fft_workers(shape: Sequence[int], workers: int) -> int:
    """Threads for transforms of ``shape``: ``workers`` for large transforms, 1 for small ones."""
    return workers if int(np.prod(shape)) >= THREADED_FFT_POINTS else 1


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
        self.workers = fft_workers(self.padded, workers)
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

    def __call__(self, p: np.ndarray) -> np.ndarray:
        """Return u = K * p (same shape as p).

        Pruned transforms: the input is zero beyond n along every axis and only the first n outputs are kept,
        so the last-axis transforms run on the n unpadded rows only and each inverse is cut to n right after
        it (at 1024^2, 48 ms instead of 61 ms for the plain padded rfftn/irfftn).
        """
        w, last = self.workers, p.ndim - 1
        ph = fft.rfft(p, n=self.padded[last], axis=last, workers=w)
        for axis in range(last):
            ph = fft.fft(ph, n=self.padded[axis], axis=axis, workers=w, overwrite_x=True)
        ph *= self.spectrum                      # in place: no second padded-size temporary
        for axis in range(last):
            ph = fft.ifft(ph, axis=axis, workers=w, overwrite_x=True)[(slice(None),) * axis
                                                                      + (slice(0, self.shape[axis]),)]
        return fft.irfft(ph, n=self.padded[last], axis=last, workers=w)[..., :self.shape[last]]

class CirculantPreconditioner:
    """Approximate inverse of the convolution with an even, positive-definite kernel (the half-space influence
    coefficients): division by the kernel's spectrum on the unpadded, periodic grid.

    The half-space operator has the symbol 2/(E*|k|), so its condition number, and the number of conjugate
    gradient iterations, grow with the grid size; multiplying the residual by the inverse symbol removes that
    growth up to the contact boundary. This is the FFT-based preconditioner idea of Vollebregt (J. Comput. Phys.
    257, 2014, §4) in its plainest form: the periodic (circulant) inverse, applied to the residual restricted to the
    contact set. Periodic transforms of n instead of 2n points per axis make it a quarter of a DC-FFT convolution.
    """

    def __init__(self, kernel: Callable[..., np.ndarray], shape: Sequence[int], spacing: Sequence[float],
                 workers: int = -1):
        self.shape = tuple(int(n) for n in shape)
        lags = np.meshgrid(*(np.where(np.arange(n) <= n // 2, np.arange(n), np.arange(n) - n) * float(h)
                             for n, h in zip(self.shape, spacing)), indexing="ij", sparse=True)
        spectrum = fft.rfftn(np.asarray(kernel(*lags), dtype=float))
        if np.abs(spectrum.imag).max() > 1e-12 * np.abs(spectrum.real).max():
            raise ValueError("the circulant preconditioner needs an even kernel (real spectrum)")
        spectrum = spectrum.real
        if spectrum.min() <= 0:
            raise ValueError("the kernel's periodic spectrum is not positive: not a preconditioner")
        self.inverse = 1.0 / spectrum
        self.workers = fft_workers(self.shape, workers)

    def __call__(self, r: np.ndarray) -> np.ndarray:
        rh = fft.rfftn(r, workers=self.workers)
        rh *= self.inverse
        return fft.irfftn(rh, s=self.shape, workers=self.workers, overwrite_x=True)
