"""Film thickness of the dimensionless EHL contact (seed 004 eq 2.4 with the indent sign corrected, spec §0):

    H(X, Y, T) = H0(T) + X^2/2 + (Rx/Ry) Y^2/2 - Rbar(X - X_D(T), Y) + c_el sum_kl K_{|i-k|,|j-l|} P_kl

Rbar is the indent *height* (eq 2.16, negative in the hole), so the hole opens the gap. K is the exact integral of
1/r over a square cell of side h around each node (eqs 2.23-2.24; Love's rectangle, :func:`love_rectangle` with
E* = 1/pi), K_00 = 4 h ln(1 + sqrt 2). The discrete convolution is femcheck's exact DC-FFT, one operator per
grid level (seed 004 uses MLMI; DC-FFT has no approximation error and costs less at these sizes).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..bem.convolution import DCFFT
from ..bem.influence import love_rectangle
from ..geometry.profiles import indent_height


def cell_kernel(h: float):
    """K(dx, dy): int int over a h x h cell centred at lag (dx, dy) of 1/r (dimensionless lengths)."""
    return lambda tx, ty: love_rectangle(tx, ty, h, h, 1.0 / np.pi)


@dataclass(frozen=True)
class Indent:
    """A dent (eq 2.16) or a longitudinal groove (eq 2.45) on the surface moving at ``speed_ratio`` u_D/u_m.

    Dimensionless as the film: ``diameter`` Phi = phi/b, ``depth`` D = d Rx/b^2, ``decay`` K, ``x0``/``y0``
    centre at T = 0 (groove: ``y0`` its centre line; it runs along x and does not move)."""

    diameter: float
    depth: float
    decay: float
    x0: float = 0.0
    y0: float = 0.0
    speed_ratio: float = 1.0
    shape: str = "dent"

    def height(self, X: np.ndarray, Y: np.ndarray, T: float) -> np.ndarray:
        if self.shape == "groove":
            return indent_height(Y - self.y0, self.diameter, self.depth, self.decay) + 0.0 * X
        xd = self.x0 + self.speed_ratio * T
        return indent_height(np.hypot(X - xd, Y - self.y0), self.diameter, self.depth, self.decay)

    def centre(self, T: float) -> float:
        return self.x0 + self.speed_ratio * T


class FilmOperator:
    """Elastic deformation and rigid gap on one (n+1) x (ny+1) node grid of spacing h (square cells) starting at
    (x0, y0); ``ny`` = n unless given (an elliptic contact, wider across than along the rolling direction)."""

    def __init__(self, n: int, h: float, x0: float, y0: float, c_el: float, rx_over_ry: float,
                 ny: int | None = None):
        ny = n if ny is None else ny
        self.n, self.ny, self.h, self.c_el = n, ny, h, c_el
        self.x = x0 + h * np.arange(n + 1)
        self.y = y0 + h * np.arange(ny + 1)
        self.X, self.Y = np.meshgrid(self.x, self.y, indexing="ij")
        kern = cell_kernel(h)
        self.conv = DCFFT(kern, (n + 1, ny + 1), (h, h), workers=1)
        m = np.arange(6) * h
        self.K0 = kern(m, 0.0 * m)          # K_{m,0}, m = 0..5 (line-matrix coefficients)
        self.K1 = kern(m, h + 0.0 * m)      # K_{m,1}
        self.base = 0.5 * self.X**2 + 0.5 * rx_over_ry * self.Y**2

    def rigid(self, indent: Indent | None, T: float) -> np.ndarray:
        """X^2/2 + (Rx/Ry) Y^2/2 - Rbar (without H0)."""
        if indent is None:
            return self.base
        return self.base - indent.height(self.X, self.Y, T)

    def deformation(self, P: np.ndarray) -> np.ndarray:
        return self.c_el * self.conv(P)
