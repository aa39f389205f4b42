"""Layered elastic half-space: frequency response, influence coefficients and frictionless normal contact.

Body: a layer (E1, nu1, thickness h) perfectly bonded to an elastic half-space (E2, nu2), or to a rigid base.
Load: normal pressure on the free top face, no shear (frictionless contact). z points into the body.

Frequency response (Chen 1971; O'Sullivan & King, J. Tribol. 110, 1988, eqs 7-9 in the frictionless case; the
form used by Liu & Wang, J. Tribol. 124, 2002). With the 2D Fourier transform u^(k) = int u e^{-i k.x} dA (3D
body) or the 1D one (plane strain), the surface normal displacement under the pressure p^(k) is

    u^(k) = H(|k|) p^(k),     H(k) = (2 / (E1* k)) Phi(k h),     E1* = E1 / (1 - nu1^2)

    Phi(t) = [1 + 4 kappa t e^{-2t} - lambda kappa e^{-4t}] / [1 - (lambda + kappa + 4 kappa t^2) e^{-2t}
                                                                 + lambda kappa e^{-4t}]

    kappa  = (g - 1) / (g + 3 - 4 nu1),   lambda = 1 - 4 (1 - nu1) / (1 + g (3 - 4 nu2)),   g = G1 / G2.

The same H(|k|) serves the 3D body (|k| = sqrt(kx^2 + ky^2)) and plane strain (|k| = |kx|): for a normal load
the z-dependence of the Fourier-transformed Navier equations only involves |k|. Re-derived here from the
Papkovich-Neuber solution u = grad(phi + z psi) - 4 (1 - nu) psi e_z with phi, psi = (A e^{-kz} + B e^{kz})
e^{i k x} in the layer and decaying terms only in the substrate: traction -p, 0 on z = 0 and continuity of u and
of the traction on z = h give six equations whose solution is the closed form above (the tests solve that 6 x 6
system numerically and compare). Checks: g = 1, nu1 = nu2 gives kappa = lambda = 0 and Phi = 1 (homogeneous);
k h -> 0 gives Phi -> E1*/E2* (the substrate); k h -> inf gives Phi -> 1 (the layer).

Rigid base (its own response, not a huge E2): u = 0 on z = h gives g -> inf in the same form,
kappa = -1/(3 - 4 nu1), lambda = -(3 - 4 nu1), lambda kappa = 1; then Phi(t) -> t (1 - 2 nu1) / (2 (1 - nu1)^2)
as t -> 0, i.e. H -> h (1 + nu1)(1 - 2 nu1) / (E1 (1 - nu1)) = h / M: the Winkler foundation of the constrained
modulus M of Johnson's thin layer (seed 001 eqs 18-21). nu -> 0.5 needs no special case: no denominator vanishes
(g + 3 - 4 nu1 >= 1, 1 + g (3 - 4 nu2) >= 1), and for an incompressible layer on a rigid base Phi = O(t^3).

Influence coefficients of uniform pressure on a cell (dx x dy rectangle, or a strip of width dx). H is split as

    H = C1 / k                       exact: Love's rectangle / the half-plane strip, modulus E1*
      + (C2 - C1) e^{-2kh} / k        exact: "image" term, cell integral of 1/sqrt(r^2 + 4h^2) (3D) or of
                                             -ln sqrt(x^2 + 4h^2) (2D), in closed form below
      + c0 e^{-2kh}                   exact: cell integral of the Poisson kernel 2h / (2 pi (r^2 + 4h^2)^{3/2})
                                             (3D) or 2h / (pi (x^2 + 4h^2)) (2D)
      + R(k)                          sampled: R = H - (the three terms above)

with C1 = 2/E1*, C2 = 2/E2* (0 on a rigid base) and c0 chosen so that R(0) = 0. R is bounded, vanishes at
k = 0 (a cone, slope O(h^2)) and decays like e^{-2kh}: its cell coefficients are computed by an inverse FFT of
R(|k|) S^(k) on a padded, oversampled grid (S^ the cell's transform dx dy sinc sinc, so cell averaging is exact
in the integral), with the period chosen so that the images of the residual's kernel are negligible and the
sample spacing so that R has decayed by the Nyquist wavenumber (``ResidualSampling``). The measured accuracy
of the coefficients against direct quadrature of the Fourier integrals is stated in the tests
(tests/test_layered_bem.py).

Contact: DC-FFT convolution (:class:`femcheck.bem.convolution.DCFFT`) with these coefficients, circulant
preconditioner built from the same coefficients, Polonsky-Keer CG under load control
(:func:`femcheck.bem.polonsky_keer.polonsky_keer`). SI units throughout: Pa, m, N (N/m in 2D).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from scipy import fft

from ..errors import ConvergenceError, InputError
from .convolution import DCFFT, CirculantPreconditioner
from .halfspace import Grid
from .influence import half_plane_strip, love_rectangle
from .polonsky_keer import NormalContactResult, polonsky_keer


# --------------------------------------------------------------------------------------------------------------
# Material and frequency response
# --------------------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class LayeredSolid:
    """Layer (``E_layer`` Pa, ``nu_layer``, ``thickness`` m) bonded to a substrate (``E_substrate`` Pa,
    ``nu_substrate``) or, with ``rigid_substrate=True``, to a rigid base (substrate constants ignored)."""

    E_layer: float
    nu_layer: float
    thickness: float
    E_substrate: float = 1.0
    nu_substrate: float = 0.0
    rigid_substrate: bool = False

    def __post_init__(self):
        checks = [("layer.E", self.E_layer, "(0, inf) Pa"), ("layer.thickness", self.thickness, "(0, inf) m")]
        if not self.rigid_substrate:
            checks.append(("materials.substrate.E", self.E_substrate, "(0, inf) Pa"))
        for key, v, allowed in checks:
            if not (np.isfinite(v) and v > 0):
                raise InputError(key, f"{v!r}; allowed {allowed}")
        for key, v, used in (("layer.nu", self.nu_layer, True),
                             ("materials.substrate.nu", self.nu_substrate, not self.rigid_substrate)):
            if used and not (-1.0 < v <= 0.5):
                raise InputError(key, f"{v!r}; allowed (-1, 0.5]")

    @property
    def modulus_layer(self) -> float:
        """Plane-strain modulus E1* = E1 / (1 - nu1^2) (Pa)."""
        return self.E_layer / (1.0 - self.nu_layer**2)

    @property
    def modulus_substrate(self) -> float:
        """E2* = E2 / (1 - nu2^2) (Pa); inf for a rigid base."""
        return np.inf if self.rigid_substrate else self.E_substrate / (1.0 - self.nu_substrate**2)

    def coefficients(self) -> tuple[float, float]:
        """(kappa, lambda) of the module docstring (dimensionless)."""
        n1 = 3.0 - 4.0 * self.nu_layer
        if self.rigid_substrate:
            return -1.0 / n1, -n1
        g = (self.E_layer / (1.0 + self.nu_layer)) / (self.E_substrate / (1.0 + self.nu_substrate))
        return (g - 1.0) / (g + n1), 1.0 - 4.0 * (1.0 - self.nu_layer) / (1.0 + g * (3.0 - 4.0 * self.nu_substrate))


def response_factor(t: np.ndarray, solid: LayeredSolid) -> np.ndarray:
    """Phi(t), t = |k| h, of the module docstring (dimensionless): H = 2 Phi / (E1* |k|).

    Written with expm1 so that 1 - lambda kappa e^{-4t} keeps full precision when lambda kappa = 1 (rigid base)
    and t is tiny (very thin layers): the numerator then vanishes like t.
    """
    t = np.asarray(t, dtype=float)
    kap, lam = solid.coefficients()
    lk = lam * kap
    e2 = np.exp(-2.0 * t)
    num = (1.0 - lk) - lk * np.expm1(-4.0 * t) + 4.0 * kap * t * e2
    # 1 - (lam + kap) e2 + lk e4 = (1 - lam - kap + lk) - (lam + kap) expm1(-2t) + lk expm1(-4t)
    den = (1.0 - lam) * (1.0 - kap) - (lam + kap) * np.expm1(-2.0 * t) + lk * np.expm1(-4.0 * t) \
        - 4.0 * kap * t * t * e2
    return num / den


def response_factor_slope0(solid: LayeredSolid) -> float:
    """dPhi/dt at t = 0 (from N(0) = 1 - lk, N'(0) = 4 kappa (1 + lambda), D(0) = (1 - lambda)(1 - kappa),
    D'(0) = 2 (lambda + kappa) - 4 lambda kappa)."""
    kap, lam = solid.coefficients()
    n0, n1 = 1.0 - lam * kap, 4.0 * kap * (1.0 + lam)
    d0, d1 = (1.0 - lam) * (1.0 - kap), 2.0 * (lam + kap) - 4.0 * lam * kap
    return (n1 * d0 - n0 * d1) / d0**2


def surface_compliance(k: np.ndarray, solid: LayeredSolid) -> np.ndarray:
    """H(|k|) = u^ / p^ (m/Pa): the surface normal displacement transform per pressure transform,
    2 Phi(|k| h) / (E1* |k|); k in rad/m, k != 0."""
    k = np.abs(np.asarray(k, dtype=float))
    return 2.0 * response_factor(k * solid.thickness, solid) / (solid.modulus_layer * k)


def _image_constants(solid: LayeredSolid) -> tuple[float, float, float]:
    """C1 = 2/E1*, C2 - C1 and c0 (m/Pa) of the decomposition in the module docstring."""
    c1 = 2.0 / solid.modulus_layer
    c2 = 0.0 if solid.rigid_substrate else 2.0 / solid.modulus_substrate
    # R1(k) = C1 (Phi(kh) - 1 - (C2/C1 - 1) e^{-2kh}) / k -> C1 h (Phi'(0) + 2 (C2/C1 - 1)) at k = 0
    c0 = c1 * solid.thickness * (response_factor_slope0(solid) + 2.0 * (c2 / c1 - 1.0))
    return c1, c2 - c1, c0


def residual_response(k: np.ndarray, solid: LayeredSolid) -> np.ndarray:
    """R(|k|) = H - C1/k - (C2 - C1) e^{-2kh}/k - c0 e^{-2kh} (m/Pa); R(0) = 0.

    For k h < 1e-3 the two sides cancel to round-off, so R is taken from its Taylor expansion R ~ r1 k, the
    slope being estimated by a two-point difference at kh = 1e-3 (R is O(h^2 k) there and its error O(h^3 k^2)).
    """
    k = np.abs(np.asarray(k, dtype=float))
    h = solid.thickness
    c1, dc, c0 = _image_constants(solid)

    def exact(kk):
        t = kk * h
        e2 = np.exp(-2.0 * t)
        # C1 (Phi - 1 - (C2/C1 - 1) e2) / k, the bracket combined before dividing by k
        return c1 * (response_factor(t, solid) - 1.0 - (dc / c1) * e2) / kk - c0 * e2

    small = k * h < 1e-3
    out = np.empty_like(k)
    out[~small] = exact(k[~small])
    if small.any():
        t1, t2 = 1e-3 / h, 2e-3 / h
        r1, r2 = exact(np.array([t1, t2]))
        slope = 2.0 * r1 / t1 - r2 / t2          # R = s k + q k^2: s from two points
        quad = (r2 / t2 - r1 / t1) / (t2 - t1)
        out[small] = slope * k[small] + quad * k[small] ** 2
    return out


# --------------------------------------------------------------------------------------------------------------
# Closed-form cell integrals of the image terms
# --------------------------------------------------------------------------------------------------------------

def _corner_image(X: np.ndarray, Y: np.ndarray, a: float) -> np.ndarray:
    """F(X, Y) with d2F/dXdY = 1/sqrt(X^2 + Y^2 + a^2), up to terms in X or Y alone (which cancel between the
    four corners): X asinh(Y / sqrt(X^2 + a^2)) + Y asinh(X / sqrt(Y^2 + a^2)) - a atan(X Y / (a rho))."""
    rho = np.sqrt(X * X + Y * Y + a * a)
    return (X * np.arcsinh(Y / np.sqrt(X * X + a * a)) + Y * np.arcsinh(X / np.sqrt(Y * Y + a * a))
            - a * np.arctan(X * Y / (a * rho)))


def _corner_poisson(X: np.ndarray, Y: np.ndarray, a: float) -> np.ndarray:
    """G(X, Y) with d2G/dXdY = a / (X^2 + Y^2 + a^2)^{3/2}: atan(X Y / (a rho)) (the solid angle)."""
    return np.arctan(X * Y / (a * np.sqrt(X * X + Y * Y + a * a)))


def _four_corners(f, tx, ty, dx, dy, *args):
    xp, xm, yp, ym = tx + 0.5 * dx, tx - 0.5 * dx, ty + 0.5 * dy, ty - 0.5 * dy
    return f(xp, yp, *args) - f(xp, ym, *args) - f(xm, yp, *args) + f(xm, ym, *args)


def image_rectangle(tx: np.ndarray, ty: np.ndarray, dx: float, dy: float, solid: LayeredSolid) -> np.ndarray:
    """Displacement (m) at offset (tx, ty) from a dx x dy cell of unit pressure due to the two image terms:
    (C2 - C1)/(2 pi) int dA / sqrt(r^2 + 4h^2) + c0/(2 pi) int 2h dA / (r^2 + 4h^2)^{3/2} (inverse 2D
    transforms of (C2 - C1) e^{-2kh}/k and c0 e^{-2kh})."""
    _, dc, c0 = _image_constants(solid)
    a = 2.0 * solid.thickness
    tx, ty = np.asarray(tx, dtype=float), np.asarray(ty, dtype=float)
    return (dc * _four_corners(_corner_image, tx, ty, dx, dy, a)
            + c0 * _four_corners(_corner_poisson, tx, ty, dx, dy, a)) / (2.0 * np.pi)


def image_strip(t: np.ndarray, width: float, solid: LayeredSolid, datum: float) -> np.ndarray:
    """Plane-strain counterpart of :func:`image_rectangle` (m per Pa of a strip of ``width``): the inverse 1D
    transforms are -(C2 - C1)/(2 pi) ln((x^2 + a^2)/d^2) and c0 a / (pi (x^2 + a^2)), a = 2h, integrated over
    the strip: int ln(x^2 + a^2) dx = x ln(x^2 + a^2) - 2x + 2a atan(x/a)."""
    _, dc, c0 = _image_constants(solid)
    a = 2.0 * solid.thickness / datum
    t = np.asarray(t, dtype=float) / datum
    w = width / datum

    def log_int(x):
        return x * np.log(x * x + a * a) - 2.0 * x + 2.0 * a * np.arctan(x / a)

    logs = -(dc / (2.0 * np.pi)) * (log_int(t + 0.5 * w) - log_int(t - 0.5 * w)) * datum
    poisson = (c0 / np.pi) * (np.arctan((t + 0.5 * w) / a) - np.arctan((t - 0.5 * w) / a))
    return logs + poisson


# --------------------------------------------------------------------------------------------------------------
# Sampled residual
# --------------------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class ResidualSampling:
    """How the residual R was sampled: per axis the sample spacing ``spacing`` (m), the number of samples
    ``points`` (period = points x spacing), and ``nyquist_decay`` = max |R S^| at the Nyquist wavenumber over
    max |R S^| (a measure of the truncation error)."""

    spacing: tuple[float, ...]
    points: tuple[int, ...]
    nyquist_decay: float


# Largest residual grid per axis: 3D 2048^2 complex samples are 64 MB and about 0.3 s of FFT here.
MAX_POINTS = {1: 1 << 21, 2: 2048}
MAX_OVERSAMPLING = {1: 64, 2: 8}
# Period beyond the grid, in layer thicknesses: the residual's kernel has a tail ~ h^2/x^2 (2D) or h^2/r^3 (3D)
# from its cone at k = 0, so the first image sits this far away (1D samples are cheap: go far).
IMAGE_CLEARANCE = {1: 400.0, 2: 24.0}


def _residual_table(solid: LayeredSolid, shape: tuple[int, ...], spacing: tuple[float, ...]
                    ) -> tuple[np.ndarray, ResidualSampling]:
    """Cell coefficients of the residual R at lags (i dx, j dy), 0 <= i < nx, 0 <= j < ny (even kernel).

    Sample spacing delta = dx / m with m = ceil(2 dx / h) (so that R ~ e^{-2kh} has decayed by e^{-4 pi} at
    the Nyquist wavenumber pi / delta), m capped at MAX_OVERSAMPLING (very thin layers: there R itself is
    O(h^2 k) over the resolved band and its truncation error is negligible next to the exact terms).
    Period L >= 2 n dx and >= n dx + c h (c = IMAGE_CLEARANCE: 400 in 2D, 24 in 3D), so that the residual's kernel (width ~ 2h, tail ~ h^2 / r^3) has
    decayed before its first periodic image. If that asks for more than MAX_POINTS samples, the spacing is
    widened (thick layers: R then lives at k < 1/h and delta stays <= h / 4) and the coefficients are
    interpolated (cubic) to the cell lags.
    """
    from scipy.interpolate import RegularGridInterpolator

    dim = len(shape)
    h = solid.thickness
    m = int(np.clip(np.ceil(2.0 * max(spacing) / h), 1, MAX_OVERSAMPLING[dim]))
    deltas, counts = [], []
    for n, d in zip(shape, spacing):
        period = max(2.0 * n * d, n * d + IMAGE_CLEARANCE[dim] * h)
        delta = d / m
        count = fft.next_fast_len(int(np.ceil(period / delta)), real=True)
        if count > MAX_POINTS[dim]:
            count = MAX_POINTS[dim]
            delta = period / count
            if delta > 0.25 * h:
                raise InputError("numerics.bem_cells", f"layer thickness {h:g} m against a grid of {n} cells of "
                                 f"{d:g} m needs more than {MAX_POINTS[dim]} residual samples per axis; "
                                 "use fewer cells or a smaller domain")
        deltas.append(delta)
        counts.append(count)
    ks = [2.0 * np.pi * (fft.rfftfreq(c, dl) if ax == dim - 1 else fft.fftfreq(c, dl))
          for ax, (c, dl) in enumerate(zip(counts, deltas))]
    K = np.meshgrid(*ks, indexing="ij", sparse=True)
    kabs = np.sqrt(sum(kk * kk for kk in K))
    cell = np.ones(())
    for kk, d in zip(K, spacing):
        cell = cell * (d * np.sinc(kk * d / (2.0 * np.pi)))
    spec = residual_response(kabs, solid) * cell
    peak = float(np.abs(spec).max()) or 1.0
    edge = np.zeros(kabs.shape, dtype=bool)
    for ax, c in enumerate(counts):                     # samples on the Nyquist faces
        idx = [slice(None)] * dim
        idx[ax] = c // 2 if ax < dim - 1 else -1
        edge[tuple(idx)] = True
    decay = float(np.abs(spec[edge]).max()) / peak
    table = fft.irfftn(spec, s=counts) / float(np.prod(deltas))
    exact_lags = all(abs(d / dl - round(d / dl)) < 1e-9 for d, dl in zip(spacing, deltas))
    if exact_lags:
        steps = [int(round(d / dl)) for d, dl in zip(spacing, deltas)]
        out = table[tuple(slice(0, n * s, s) for n, s in zip(shape, steps))]
    else:
        # keep only the lags needed (plus a margin for the cubic stencil), then interpolate
        keep = [int(np.ceil(n * d / dl)) + 3 for n, d, dl in zip(shape, spacing, deltas)]
        sub = table[tuple(slice(0, q) for q in keep)]
        axes = [np.arange(q) * dl for q, dl in zip(keep, deltas)]
        interp = RegularGridInterpolator(axes, sub, method="cubic")
        pts = np.meshgrid(*(np.arange(n) * d for n, d in zip(shape, spacing)), indexing="ij")
        out = interp(np.stack([p.ravel() for p in pts], axis=-1)).reshape(shape)
    return np.ascontiguousarray(out), ResidualSampling(tuple(deltas), tuple(counts), decay)


# --------------------------------------------------------------------------------------------------------------
# Influence coefficients
# --------------------------------------------------------------------------------------------------------------

@dataclass
class LayeredInfluence:
    """Cell influence coefficients of a layered solid on a regular grid: ``table[i, j]`` is the normal surface
    displacement (m) at lag (i dx, j dy) from a cell of unit pressure (1 Pa), i, j >= 0 (the kernel is even).
    Call it with lag arrays (multiples of the spacing) as DC-FFT expects."""

    table: np.ndarray
    spacing: tuple[float, ...]
    sampling: ResidualSampling

    def __call__(self, *lags: np.ndarray) -> np.ndarray:
        idx = tuple(np.abs(np.rint(np.asarray(l) / d)).astype(int) for l, d in zip(lags, self.spacing))
        return self.table[idx]


def rectangle_influence(solid: LayeredSolid, g: Grid) -> LayeredInfluence:
    """3D cell coefficients on grid ``g``: Love's rectangle with E1* + closed-form images + sampled residual."""
    i = np.arange(g.nx)[:, None] * g.dx
    j = np.arange(g.ny)[None, :] * g.dy
    exact = love_rectangle(i, j, g.dx, g.dy, solid.modulus_layer) + image_rectangle(i, j, g.dx, g.dy, solid)
    res, sampling = _residual_table(solid, (g.nx, g.ny), (g.dx, g.dy))
    return LayeredInfluence(exact + res, (g.dx, g.dy), sampling)


def strip_influence(solid: LayeredSolid, n: int, dx: float, datum: float) -> LayeredInfluence:
    """Plane-strain strip coefficients (m per Pa) at lags i dx, 0 <= i < n. The 2D displacement is defined up to
    a constant; ``datum`` (m, larger than the loaded domain) fixes it as in
    :func:`femcheck.bem.influence.half_plane_strip` and keeps the matrix positive definite."""
    t = np.arange(n) * dx
    exact = half_plane_strip(t, dx, solid.modulus_layer, datum) + image_strip(t, dx, solid, datum)
    res, sampling = _residual_table(solid, (n,), (dx,))
    return LayeredInfluence(exact + res, (dx,), sampling)


# --------------------------------------------------------------------------------------------------------------
# Contact solves
# --------------------------------------------------------------------------------------------------------------

@dataclass
class LayeredContactSolution:
    """Contact on a layered solid: cell centres (``x``; ``y`` in 3D, else None), ``spacing`` (m), the
    Polonsky-Keer result and stats (influence sampling, preconditioner, times)."""

    x: np.ndarray
    y: np.ndarray | None
    spacing: tuple[float, ...]
    result: NormalContactResult
    stats: dict = field(default_factory=dict)


def _preconditioner(kernel, shape, spacing) -> tuple[Callable | None, str]:
    try:
        return CirculantPreconditioner(kernel, shape, spacing, workers=1), "circulant"
    except ValueError:
        # a layered kernel's periodic spectrum may fail to be positive on a coarse grid: plain CG then
        return None, "none"


def solve_line(solid: LayeredSolid, gap: Callable[[np.ndarray], np.ndarray], load_per_length: float,
               half_domain: float, n_elements: int, tol: float = 1e-10, max_iter: int = 2000
               ) -> LayeredContactSolution:
    """Plane-strain frictionless contact of a rigid body with initial gap ``gap(x)`` (m) on the layered solid,
    load ``load_per_length`` (N/m), ``n_elements`` strips over [-half_domain, half_domain] (m)."""
    t0 = time.perf_counter()
    dx = 2.0 * half_domain / n_elements
    x = -half_domain + (np.arange(n_elements) + 0.5) * dx
    infl = strip_influence(solid, n_elements, dx, datum=8.0 * half_domain)
    t_infl = time.perf_counter() - t0
    op = DCFFT(infl, (n_elements,), (dx,))
    pc, pc_name = _preconditioner(infl, (n_elements,), (dx,))
    res = polonsky_keer(gap(x), op, load_per_length, dx, tol=tol, max_iter=max_iter, preconditioner=pc)
    stats = {"iterations": res.iterations, "residual": res.residual, "preconditioner": pc_name,
             "influence_time_s": t_infl, "residual_samples": list(infl.sampling.points),
             "residual_spacing": list(infl.sampling.spacing), "residual_nyquist_decay": infl.sampling.nyquist_decay}
    return LayeredContactSolution(x, None, (dx,), res, stats)


def solve_point(solid: LayeredSolid, g: Grid, gap: Callable[[np.ndarray, np.ndarray], np.ndarray], load: float,
                tol: float = 1e-10, max_iter: int = 2000) -> LayeredContactSolution:
    """3D frictionless contact of a rigid body with initial gap ``gap(X, Y)`` (m) on the layered solid, normal
    ``load`` (N), on grid ``g``."""
    t0 = time.perf_counter()
    infl = rectangle_influence(solid, g)
    t_infl = time.perf_counter() - t0
    op = DCFFT(infl, (g.nx, g.ny), (g.dx, g.dy))
    pc, pc_name = _preconditioner(infl, (g.nx, g.ny), (g.dx, g.dy))
    X, Y = g.mesh()
    res = polonsky_keer(gap(X, Y), op, load, g.cell_area, tol=tol, max_iter=max_iter, preconditioner=pc)
    stats = {"iterations": res.iterations, "residual": res.residual, "preconditioner": pc_name,
             "influence_time_s": t_infl, "residual_samples": list(infl.sampling.points),
             "residual_spacing": list(infl.sampling.spacing), "residual_nyquist_decay": infl.sampling.nyquist_decay}
    return LayeredContactSolution(g.x, g.y, (g.dx, g.dy), res, stats)


def touches_edge(contact: np.ndarray) -> bool:
    """True if the contact set reaches the boundary of the grid (the domain is too small)."""
    c = np.asarray(contact)
    if c.ndim == 1:
        return bool(c[0] or c[-1])
    return bool(c[0, :].any() or c[-1, :].any() or c[:, 0].any() or c[:, -1].any())


__all__ = ["LayeredSolid", "response_factor", "response_factor_slope0", "surface_compliance",
           "residual_response", "image_rectangle", "image_strip", "ResidualSampling", "LayeredInfluence",
           "rectangle_influence", "strip_influence", "LayeredContactSolution", "solve_line", "solve_point",
           "touches_edge", "ConvergenceError"]
