"""Influence coefficients on the developed (x, s) grid of a conformal contact (spec srb-rolling §4.3).

Components are ordered (x, s, n): x rolling direction, s along the profile, n the normal into body 1; the
traction p = (p_x, p_s, p_n) acts on body 1, u is the displacement difference u(body 1) - u(body 2) (m/Pa per
unit traction on a dx x ds element), as in :mod:`femcheck.cect.influence` with (y, z) -> (s, n).

Options (``INFLUENCE_OPTIONS``):
- ``"halfspace"`` (default, "developed half-space"): the Boussinesq-Cerruti rectangles of
  :func:`femcheck.cect.influence.influence` with s used as a planar coordinate, A(x_I - x_J, s_I - s_J).
- ``"blanco"`` (CONTACT ``influe_blanco`` version 1; our reading of seed 000's "approximation B-hat", Blanco-
  Lorenzo et al. 2021): the source traction, given in the source element J's local frame, is rotated into the
  receiver I's frame before the half-space coefficients are applied, B_IJ = A(x_I - x_J, s_I - s_J) R_IJ.
- ``"rotated_response"`` (CONTACT version 3): the half-space response is computed in J's frame and rotated into
  I's frame, B_IJ = R_IJ A. It is the adjoint of "blanco": B3_IJ = B1_JI^T (Betti).
R_IJ[a, b] = e_a(I) . e_b(J) for a, b in (x, s, n). On a circular profile of radius r_g with t' = n / r_g (the
normal pointing to the profile's centre, :mod:`femcheck.geometry.conformal_surface`), the frame at J is the
frame at I turned about e_x by D = (s_J - s_I)/r_g:
    R = [[1, 0, 0], [0, cos D, -sin D], [0, sin D, cos D]]
(e_s(J) = cos D e_s(I) + sin D e_n(I)). R depends on the lag s_I - s_J only, so on a uniform grid the corrected
coefficients stay translation invariant in x and s and DC-FFT applies, like the half-space ones. (The paper's
footnote stores (2 n_s - 1) x n_s blocks; not needed for a circular profile.) The sign of D is the geometric one,
fixed by a test: a uniform traction field that is constant in 3D (the same vector at every element) must act in
"blanco" exactly as the half-space response to that vector resolved in the receiver's frame.

With either correction the normal and tangential problems couple even for identical materials (B_sn, B_ns != 0).

Where the developed half-space stops being valid (groove-rolling, a ball of radius 100.3 mm in a groove 1.002
times wider, free rolling, mu = 0.1; docs/notes/groove-deep.md): against the FE reference at solved half-angles
of 40-45 deg "halfspace" is within 0.5 % (half-angle), 0.8 % (p_max) and 2.8 % (frictional power), "blanco"
within 1.7 %, 1.4 % and 3.1 %: the corrections are not closer to the finite bodies. Against each other they
differ in frictional power by 1.3 % at 30 deg, 2.6 % at 40, 3.3 % at 45, 4.8 % at 50 and 8.7 % at 60 deg (half-angle
0.7, 1.2, 1.8, 2.2, 3.6 %): beyond 50 deg the choice of coefficients alone exceeds a 5 % band, the scene's
applicability limit.
"""
from __future__ import annotations

from functools import lru_cache, partial

import numpy as np
from scipy import fft

from ..bem.convolution import DCFFT
from ..bem.halfspace import Grid
from ..errors import InputError
from .exact import gather_blocks, lags
from .influence import CombinedConstants, influence

INFLUENCE_OPTIONS = ("halfspace", "blanco", "rotated_response")
AXES = "xsn"
_PLANAR = {"x": "x", "s": "y", "n": "z"}


def _halfspace(i: str, j: str, tx, ts, dx: float, ds: float, constants: CombinedConstants) -> np.ndarray:
    return influence(_PLANAR[i] + _PLANAR[j], tx, ts, dx, ds, constants)


def _rotation(ts, radius: float) -> dict[tuple[str, str], np.ndarray]:
    """Non-trivial entries of R_IJ at s-lag ts = s_I - s_J (D = -ts / r_g); R_xx = 1, R_x. = R_.x = 0."""
    d = -np.asarray(ts, dtype=float) / radius
    c, s = np.cos(d), np.sin(d)
    return {("s", "s"): c, ("s", "n"): -s, ("n", "s"): s, ("n", "n"): c}


def kernel(i: str, j: str, tx, ts, dx: float, ds: float, constants: CombinedConstants, option: str = "halfspace",
           radius: float | None = None) -> np.ndarray:
    """B_ij (m/Pa) at lag (tx, ts) = (x_I - x_J, s_I - s_J) (m): displacement difference along i at I per unit
    traction along j (in J's frame) on element J; i, j in "x", "s", "n". See the module docstring."""
    if option == "halfspace":
        return _halfspace(i, j, tx, ts, dx, ds, constants)
    if option not in INFLUENCE_OPTIONS:
        raise InputError("numerics.conformal_influence", f"{option!r}; allowed: {', '.join(INFLUENCE_OPTIONS)}")
    if not (radius and radius > 0):
        raise ValueError("the angle-corrected influence coefficients need the profile radius")
    R = _rotation(ts, radius)

    def r(a: str, b: str):
        if a == b == "x":
            return 1.0
        return R.get((a, b), 0.0)

    out = 0.0
    for k in AXES:
        if option == "blanco":               # B = A R: sum_k A_ik R_kj
            f = r(k, j)
            if not (np.isscalar(f) and f == 0.0):
                out = out + _halfspace(i, k, tx, ts, dx, ds, constants) * f
        else:                                # B = R A: sum_k R_ik A_kj
            f = r(i, k)
            if not (np.isscalar(f) and f == 0.0):
                out = out + f * _halfspace(k, j, tx, ts, dx, ds, constants)
    return out * np.ones(np.broadcast(np.asarray(tx), np.asarray(ts)).shape)


def rolling_kernel(i: str, j: str, tx, ts, dx: float, ds: float, constants: CombinedConstants, option: str,
                   radius: float | None) -> np.ndarray:
    """(B_ij(t) - B_ij(t + dx)) / dx (1/Pa): the steady-rolling difference of seed 000 eq 19 with dq0 = dx."""
    return (kernel(i, j, tx, ts, dx, ds, constants, option, radius)
            - kernel(i, j, np.asarray(tx) + dx, ts, dx, ds, constants, option, radius)) / dx


class BlockConvolution:
    """Block operator q_i = sum_j K_ij * p_j on a grid (DC-FFT per block, exact linear convolution): ``rows``,
    ``cols`` component strings (e.g. "xs", "xs"); ``rolling``: the kernels are the rolling differences.
    ``self_coefficients`` = the diagonal entries K_ii(0) of the row components (used by the Coulomb solver's
    regularisation). Call with p (len(cols), nx, ny) -> (len(rows), nx, ny)."""

    def __init__(self, g: Grid, constants: CombinedConstants, rows: str, cols: str, rolling: bool,
                 option: str = "halfspace", radius: float | None = None):
        self.grid, self.rows, self.cols, self.rolling = g, rows, cols, rolling
        f = rolling_kernel if rolling else kernel
        self.spectra = {}
        for i in rows:
            for j in cols:
                conv = DCFFT(partial(self._lagged, f, i, j, g, constants, option, radius), (g.nx, g.ny),
                             (g.dx, g.dy), workers=1)
                self.spectra[i, j] = conv.spectrum
                self.padded = conv.padded
        self.self_coefficients = tuple(float(f(i, i, 0.0, 0.0, g.dx, g.dy, constants, option, radius))
                                       for i in rows)

    @staticmethod
    def _lagged(f, i, j, g, constants, option, radius, tx, ty):
        return f(i, j, tx, ty, g.dx, g.dy, constants, option, radius)

    def __call__(self, p: np.ndarray) -> np.ndarray:
        nx, ny = self.grid.nx, self.grid.ny
        p = np.asarray(p, dtype=float).reshape(len(self.cols), nx, ny)
        ph = fft.rfft(p, n=self.padded[1], axis=-1)
        ph = fft.fft(ph, n=self.padded[0], axis=1, overwrite_x=True)
        out = np.zeros((len(self.rows),) + ph.shape[1:], dtype=complex)
        for a, i in enumerate(self.rows):
            for b, j in enumerate(self.cols):
                out[a] += self.spectra[i, j] * ph[b]
        out = fft.ifft(out, axis=1, overwrite_x=True)[:, :nx]
        return fft.irfft(out, n=self.padded[1], axis=-1)[..., :ny]


@lru_cache(maxsize=16)
def block_operator(g: Grid, constants: CombinedConstants, rows: str, cols: str, rolling: bool,
                   option: str = "halfspace", radius: float | None = None) -> BlockConvolution:
    """Cached :class:`BlockConvolution` (built once per grid, option and radius)."""
    return BlockConvolution(g, constants, rows, cols, rolling, option, radius)


def dense_block(g: Grid, cells: tuple[np.ndarray, np.ndarray], constants: CombinedConstants, rows: str, cols: str,
                rolling: bool, option: str = "halfspace", radius: float | None = None) -> np.ndarray:
    """Dense matrix of the block on the elements ``cells`` = (ix, is), component-major (all x rows, then all s
    rows ...), the counterpart of :func:`femcheck.cect.exact.dense_operator` for the corrected coefficients."""
    tx, ty = lags(g)
    return gather_blocks(g, cells, rows, cols, rolling,
                         lambda i, j: kernel(i, j, tx, ty, g.dx, g.dy, constants, option, radius))
