"""Frictionless plane-strain contact of a rigid cylinder (parabola, radius R) on an elastic layer (E, nu, thickness h)
perfectly bonded to a rigid base, solved by Fourier transform to high accuracy: the line-contact counterpart of
:mod:`femcheck.analytic.layer_axisymmetric`, an independent reference for the layered BEM's strips.

Transform. With p^(xi) = int p(x) cos(xi x) dx (p even), u(x) = (1/pi) int_0^inf (2 Phi(xi h) / (E* xi)) p^(xi)
cos(xi x) dxi (the kernel Phi of :mod:`femcheck.analytic.bonded_layer`), so that, with K = 1 - Phi,

    u'(x) = -(2 / (pi E*)) int_-a^a p(s) [1 / (x - s) - L(x - s)] ds,     L(y) = int_0^inf K(xi h) sin(xi y) dxi

(the half-space part is Johnson 1985 eq. 2.25a; L is smooth, odd, ~ 1/y for |y| >> h: far from a load the layer on
its base does not feel it). Inside the contact u'(x) = -x / R: a Cauchy singular integral equation with a regular
kernel. For a bounded pressure at both edges (smooth indenter) write p = (E* a / (2R)) sqrt(1 - sigma^2) psi(sigma),
sigma = s / a, lambda = a / h:

    (1/pi) PV int_-1^1 sqrt(1 - sigma^2) psi(sigma) / (xi - sigma) dsigma
        - (lambda / pi) int_-1^1 sqrt(1 - sigma^2) psi(sigma) Lh(lambda (xi - sigma)) dsigma = xi,    |xi| < 1,

Lh(Y) = int_0^inf K(u) sin(u Y) du, load W' = (E* a^2 / (2R)) int_-1^1 sqrt(1 - sigma^2) psi dsigma. For the
half-space (K = 0) psi = 1: Hertz, p0 = E* a / (2R), W' = pi E* a^2 / (4R) (Johnson eq. 4.45). The equation
is solved by Gauss-Chebyshev quadrature of the second kind (Erdogan, Gupta & Cook, in *Methods of Analysis and
Solutions of Crack Problems*, 1973): nodes sigma_k = cos(k pi / (n+1)), k = 1..n, collocation points
xi_j = cos((2j - 1) pi / (2(n+1))), j = 1..n+1, weights sin^2(k pi/(n+1)) / (n+1). Of the n + 1 equations one
is the consistency condition, satisfied by symmetry (the right-hand side is odd): with n odd and psi even the
(n+1)/2 equations at xi_j > 0 determine the (n+1)/2 values at sigma_k >= 0; the residual of all n + 1 is reported.
The bounded solution exists for every a; the load fixes lambda (Brent on log lambda). The kernel Lh by composite
Gauss-Legendre panels in u (cut-off 25, K < 1e-18), separated as sin(lambda u xi) cos(lambda u sigma) -
cos(lambda u xi) sin(lambda u sigma).

Approach (the layer's base is fixed, so u is defined absolutely): delta = u(0) = int p(s) G(s) ds with
G(y) = (2 / (pi E*)) int_0^inf Phi(xi h) cos(xi y) / xi dxi, split as (2/(pi E*)) [int_0^inf (e^{-u} - K(u)) / u
cos(u y / h) du + (1/2) ln(1 + h^2 / y^2)] (a Frullani integral carries the logarithmic singularity); the s-integral
by Gauss-Legendre panels graded towards s = 0. Flat punch (p ~ 1/sqrt(a^2 - x^2), Gauss-Chebyshev of the first
kind) gives the stiffness S = W' / delta; for a smooth indenter dW'/d delta = S(a) (Barber, J. Strain Anal. 9, 1974),
the tests' load-displacement check.

Accuracy (measured; tests/test_layer_solutions.py): exponential in n; the default n (about 8 lambda, odd) agrees
with n doubled to 1e-11 in a, p_max and delta for h/a >= 0.03. SI: E, p in Pa; R, h, a, delta in m; W' in N/m.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from . import bonded_layer, hertz, thin_layer

# the (e^-u - K)/u integrand of the approach decays like e^-u: cut off where it is below 1e-19
APPROACH_CUTOFF = 45.0


def _check(E: float, nu: float, thickness: float, radius: float, load: float) -> None:
    for key, v in (("layer.E", E), ("layer.thickness", thickness), ("geometry.radius", radius),
                   ("load.per_length", load)):
        if not (np.isfinite(v) and v > 0):
            raise InputError(key, f"{v!r}; allowed (0, inf)")
    bonded_layer.kappa(nu)


def regular_kernel(x: np.ndarray, s: np.ndarray, lam: float, nu: float) -> np.ndarray:
    """lambda Lh(lambda (x_j - s_k)) (dimensionless), Lh(Y) = int_0^inf K(u) sin(u Y) du."""
    u, w = bonded_layer.panels(bonded_layer.DEFICIT_CUTOFF, lam * max(np.abs(x).max(), np.abs(s).max(), 1e-300))
    wk = w * bonded_layer.deficit(u, nu)
    out = np.zeros((x.size, s.size))
    for lo in range(0, u.size, 4096):
        uu, ww = u[lo:lo + 4096], wk[lo:lo + 4096]
        ax, as_ = lam * np.outer(x, uu), lam * np.outer(s, uu)
        out += (np.sin(ax) * ww) @ np.cos(as_).T - (np.cos(ax) * ww) @ np.sin(as_).T
    return lam * out


def approach_kernel(y: np.ndarray, nu: float) -> np.ndarray:
    """Gt(Y) = int_0^inf Phi(u) cos(u Y) / u du (dimensionless; G = 2 Gt / (pi E*), Y = y / h), Y != 0."""
    y = np.abs(np.asarray(y, dtype=float))
    u, w = bonded_layer.panels(APPROACH_CUTOFF, max(y.max(), 1e-300))
    f = w * (np.exp(-u) - bonded_layer.deficit(u, nu)) / u
    out = np.zeros(y.size)
    for lo in range(0, u.size, 4096):
        out += np.cos(np.outer(y, u[lo:lo + 4096])) @ f[lo:lo + 4096]
    return out + 0.5 * np.log1p(1.0 / (y * y))


def _graded_rule(lam: float, order: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre panels on [0, pi/2] in phi (sigma = sin phi): width <= 0.5/lambda, and geometric panels
    (ratio 0.2, 22 levels) into phi = 0 where the approach kernel has its logarithmic singularity."""
    first = min(0.5 / lam, np.pi / 2)
    n = int(np.ceil((np.pi / 2 - first) / first))
    edges = list(first * 0.2 ** np.arange(22, -1, -1)) + list(np.linspace(first, np.pi / 2, n + 1)[1:])
    edges = np.array([0.0] + edges)
    x, w = np.polynomial.legendre.leggauss(order)
    half = 0.5 * np.diff(edges)
    nodes = (0.5 * (edges[:-1] + edges[1:]))[:, None] + half[:, None] * x[None, :]
    return nodes.ravel(), (half[:, None] * w[None, :]).ravel()


def default_nodes(lam: float) -> int:
    """Gauss-Chebyshev nodes (odd) for a / h = lambda."""
    n = int(max(64, np.ceil(8.0 * lam)))
    return n + 1 if n % 2 == 0 else n


@dataclass
class _Dimensionless:
    lam: float
    psi: np.ndarray          # at sigma_k, k = 1..n (descending sigma)
    sigma: np.ndarray
    weights: np.ndarray      # sin^2 / (n + 1)
    integral: float          # sum W_k psi_k = (1/pi) int sqrt(1 - s^2) psi
    residual: float          # largest residual of all n + 1 collocation equations


def _solve_fixed(lam: float, nu: float, n: int) -> _Dimensionless:
    if n % 2 == 0:
        raise InputError("nodes", f"{n}; the symmetric Gauss-Chebyshev reduction needs an odd number")
    k = np.arange(1, n + 1)
    sigma = np.cos(k * np.pi / (n + 1))
    W = np.sin(k * np.pi / (n + 1)) ** 2 / (n + 1)
    j = np.arange(1, n + 2)
    xi = np.cos((2 * j - 1) * np.pi / (2 * (n + 1)))
    A = W[None, :] * (1.0 / (xi[:, None] - sigma[None, :]) - regular_kernel(xi, sigma, lam, nu))
    # fold the columns of sigma_k and sigma_{n+1-k} = -sigma_k (psi even); keep the rows xi_j > 0
    m = (n + 1) // 2                         # sigma_m = 0 (1-based), unknowns k = 1..m
    fold = A[:, :m].copy()
    fold[:, : m - 1] += A[:, n - 1: m - 1: -1]
    rows = np.arange(m)                      # xi_1 .. xi_m > 0
    half = np.linalg.solve(fold[rows], xi[rows])
    psi = np.concatenate([half, half[-2::-1]])
    resid = float(np.abs(A @ psi - xi).max())
    return _Dimensionless(lam, psi, sigma, W, float(W @ psi), resid)


def _chebyshev_u_coefficients(d: _Dimensionless) -> np.ndarray:
    """psi = sum c_m U_m(sigma), m < n: c_m = 2 sum_k W_k psi_k U_m(sigma_k) (discrete orthogonality)."""
    n = d.sigma.size
    theta = np.arange(1, n + 1) * np.pi / (n + 1)
    U = np.sin(np.outer(np.arange(1, n + 1), theta)) / np.sin(theta)[None, :]      # U_m(sigma_k), m = 0..n-1
    return 2.0 * U @ (d.weights * d.psi)


def _psi_at(coef: np.ndarray, s: np.ndarray) -> np.ndarray:
    """sum c_m U_m(s) by the three-term recurrence (Clenshaw)."""
    b1 = np.zeros_like(s)
    b2 = np.zeros_like(s)
    for c in coef[::-1]:
        b1, b2 = c + 2.0 * s * b1 - b2, b1
    return b1


@dataclass(frozen=True)
class LayerCylinderContact:
    """Rigid cylinder on a bonded layer (plane strain): half-width ``a`` (m), peak pressure ``p_max`` (Pa),
    approach ``approach`` (m), load per length ``load`` (N/m); ``pressure(x)`` (Pa); ``stats``."""

    a: float
    p_max: float
    approach: float
    load: float
    radius: float
    modulus: float
    thickness: float
    nu: float
    _coef: np.ndarray = field(repr=False)
    stats: dict = field(default_factory=dict)

    def pressure(self, x: np.ndarray) -> np.ndarray:
        s = np.atleast_1d(np.asarray(x, dtype=float)) / self.a
        inside = np.abs(s) < 1.0
        out = np.zeros_like(s)
        out[inside] = np.sqrt(1.0 - s[inside] ** 2) * _psi_at(self._coef, s[inside])
        return out * self.modulus * self.a / (2.0 * self.radius)


def _approach(coef: np.ndarray, lam: float, nu: float, scale: float) -> float:
    """(2/pi) int_-1^1 sqrt(1 - s^2) psi(s) Gt(lambda s) ds = (2/pi) 2 int_0^{pi/2} cos^2(phi) psi(sin phi)
    Gt(lambda sin phi) dphi, times ``scale``: the approach in units of a^2 / (2R) (p = (E* a / 2R) sqrt(1 - s^2)
    psi, G = 2 Gt / (pi E*))."""
    phi, w = _graded_rule(lam)
    s = np.sin(phi)
    vals = np.cos(phi) ** 2 * _psi_at(coef, s) * approach_kernel(lam * s, nu)
    return 2.0 * scale * (w @ vals) * (2.0 / np.pi)


def _dimensional(E, nu, h, R, d: _Dimensionless, stats) -> LayerCylinderContact:
    Es = E / (1.0 - nu**2)
    a = d.lam * h
    coef = _chebyshev_u_coefficients(d)
    load = np.pi * Es * a * a / (2.0 * R) * d.integral
    p0 = Es * a / (2.0 * R) * float(_psi_at(coef, np.array([0.0]))[0])
    delta = a * a / (2.0 * R) * _approach(coef, d.lam, nu, 1.0)
    return LayerCylinderContact(a, p0, delta, float(load), R, Es, h, nu, coef, stats)


def contact_at_half_width(E: float, nu: float, thickness: float, radius: float, a: float, n: int | None = None
                          ) -> LayerCylinderContact:
    """The smooth-edge solution of half-width ``a`` (m); its load per length and pressure follow."""
    _check(E, nu, thickness, radius, a)
    lam = a / thickness
    n = n or default_nodes(lam)
    d = _solve_fixed(lam, nu, n)
    return _dimensional(E, nu, thickness, radius, d, {"nodes": n, "residual": d.residual, "iterations": 0})


def flat_punch_stiffness(E: float, nu: float, thickness: float, a: float, n: int | None = None) -> float:
    """W' / delta (N/m per m) of a rigid flat punch of half-width ``a`` (m) on the bonded layer: Gauss-Chebyshev
    of the first kind, p = phi / sqrt(1 - sigma^2), nodes cos((2k - 1) pi / 2n), collocation cos(r pi / n),
    r = 1..n-1, and the load; delta = int p G ds."""
    _check(E, nu, thickness, 1.0, a)
    lam = a / thickness
    n = n or default_nodes(lam) + 1
    k = np.arange(1, n + 1)
    sig = np.cos((2 * k - 1) * np.pi / (2 * n))
    x = np.cos(np.arange(1, n) * np.pi / n)
    A = np.empty((n, n))
    A[:-1] = (1.0 / (x[:, None] - sig[None, :]) - regular_kernel(x, sig, lam, nu)) / n
    A[-1] = np.pi / n                      # W' / a = (pi / n) sum phi_k = 1
    b = np.zeros(n)
    b[-1] = 1.0
    phi = np.linalg.solve(A, b)
    # phi = sum d_m T_m(sigma); with W' = a (pi/n) sum phi = a: delta = a (2/(pi E*)) int phi Gt / sqrt(1 - s^2) ds
    #     = a (2/(pi E*)) 2 int_0^{pi/2} phi(sin t) Gt(lambda sin t) dt
    theta = (2 * k - 1) * np.pi / (2 * n)
    T = np.cos(np.outer(np.arange(n), theta))
    dcoef = (2.0 / n) * T @ phi
    dcoef[0] *= 0.5
    t, w = _graded_rule(lam)
    s = np.sin(t)
    vals = np.polynomial.chebyshev.chebval(s, dcoef) * approach_kernel(lam * s, nu)
    Es = E / (1.0 - nu**2)
    delta_over_a = (2.0 / (np.pi * Es)) * 2.0 * (w @ vals)
    return float(1.0 / delta_over_a)


def contact(E: float, nu: float, thickness: float, radius: float, load_per_length: float, n: int | None = None,
            rtol: float = 1e-13) -> LayerCylinderContact:
    """Rigid cylinder of ``radius`` (m) pressed with ``load_per_length`` W' (N/m) on a layer (``E`` Pa, ``nu``,
    ``thickness`` m) bonded to a rigid base: the half-width solves W'(lambda h) = W' (Brent on log lambda,
    bracketed by stepping out by 1.25 from the smaller of the Hertz half-width of the layer's half-space and
    Johnson's thin-layer half-widths). Raises ConvergenceError if the root is not bracketed."""
    _check(E, nu, thickness, radius, load_per_length)
    Es = E / (1.0 - nu**2)
    target = 2.0 * radius * load_per_length / (np.pi * Es * thickness**2)     # lambda^2 x integral

    def f(loglam: float) -> float:
        lam = float(np.exp(loglam))
        d = _solve_fixed(lam, nu, n or default_nodes(lam))
        return float(np.log(lam**2 * d.integral / target))

    guesses = [hertz.line_contact(load_per_length, radius, Es).half_width / thickness]
    if nu <= thin_layer.NU_COMPRESSIBLE_MAX:
        guesses.append(thin_layer.compressible(E, nu, thickness, radius, load_per_length, "line").a / thickness)
    guesses.append(thin_layer.incompressible(E, thickness, radius, load_per_length, "line").a / thickness)
    root, info, evaluations = bonded_layer.contact_size(f, float(np.log(min(guesses))), rtol, "layer_plane",
                                                        "half-width")
    lam = float(np.exp(root))
    nn = n or default_nodes(lam)
    d = _solve_fixed(lam, nu, nn)
    stats = {"nodes": nn, "residual": d.residual, "iterations": info.iterations,
             "evaluations": evaluations, "load_error": float(lam**2 * d.integral / target - 1.0)}
    return _dimensional(E, nu, thickness, radius, d, stats)


__all__ = ["LayerCylinderContact", "contact", "contact_at_half_width", "flat_punch_stiffness", "regular_kernel",
           "approach_kernel", "default_nodes"]
