"""Frictionless contact of a rigid sphere (paraboloid, radius R) on an elastic layer (E, nu, thickness h) perfectly
bonded to a rigid base: the axisymmetric problem solved by Hankel transform, to high accuracy. An independent
reference for the layered BEM (:mod:`femcheck.bem.layered`), written from the transform solution of the layer,
not from the BEM's influence coefficients.

Transform (Sneddon, *Fourier Transforms*, 1951; the kernel of :mod:`femcheck.analytic.bonded_layer`). With
p^(xi) = int_0^a p(r) J0(xi r) r dr, the surface displacement is u(r) = int_0^inf (2 Phi(xi h) / (E* xi))
p^(xi) J0(xi r) xi dxi. Represent the pressure by an auxiliary function g on [0, a] (Sneddon's representation
for axisymmetric mixed problems; Jaffar 1989 uses the same reduction for the bonded layer):

    p^(xi) = int_0^a g(t) cos(xi t) dt,        p(r) = g(a) / sqrt(a^2 - r^2) - int_r^a g'(t) dt / sqrt(t^2 - r^2)

(from int_0^inf sin(xi t) J0(xi r) dxi = H(t - r) / sqrt(t^2 - r^2)). A bounded pressure that vanishes at the
edge (the smooth-edge condition) is g(a) = 0; the load is P = 2 pi p^(0) = 2 pi int_0^a g dt. Inside the
contact u(r) = delta - r^2 / (2R); Abel's operator (2/pi) d/dt int_0^t r f(r) dr / sqrt(t^2 - r^2) applied to
both sides (it maps J0(xi r) to (2/pi) cos(xi t), 1 to (2/pi) and r^2 to (4/pi) t^2) turns the mixed problem into
a Fredholm equation of the second kind with a smooth kernel (K = 1 - Phi, the layer's deficit):

    g(t) - int_0^a k(t, s) g(s) ds = (E* / pi)(delta - t^2 / R),    0 <= t <= a,
    k(t, s) = (2 / pi) int_0^inf K(xi h) cos(xi t) cos(xi s) dxi.

For the half-space (K = 0) g = (E*/pi)(delta - t^2/R), g(a) = 0 gives delta = a^2/R and P = 4 E* a^3 / (3R): Hertz
(Johnson 1985 eq. 4.22). In dimensionless form, t = a tau, lambda = a / h, g = (E* a^2 / (pi R)) gamma:

    gamma - K_lambda gamma = D - tau^2,   gamma(1) = 0,   P = (2 E* a^3 / R) int_0^1 gamma dtau,   delta = D a^2/R,
    p(r) = -(E* a / (pi R)) int_0^sqrt(1 - rho^2) gamma'(tau) / tau domega,  tau = sqrt(rho^2 + omega^2), rho = r/a.

Discretisation: Nystrom on the positive half of a 2N-point Gauss-Legendre rule on [-1, 1] (gamma is even and
analytic: its Legendre interpolant of degree 2N - 1 converges exponentially); the kernel's xi-integral by
composite Gauss-Legendre panels resolving cos(lambda u tau) up to the cut-off u = 25 where K < 1e-18
(:func:`femcheck.analytic.bonded_layer.panels`), assembled as (2 lambda / pi) C W C^T with C = cos(lambda u tau).
Two solves (right-hand sides 1 and tau^2) give gamma for any D; gamma(1) = 0 (by the Nystrom interpolant) fixes D;
the load fixes lambda by Brent's method on log lambda. The flat punch of radius a (same equation, right-hand side
constant, g(a) free) gives the stiffness S = 2 E* a int_0^1 gamma_1 dtau (gamma_1 - K gamma_1 = 1): for a smooth
indenter dP/d delta = S(a) (Barber, J. Strain Anal. 9, 1974: holds for any linear elastic body; the tests use it
as a load-displacement check).

Accuracy (measured; tests/test_layer_solutions.py): the error falls exponentially with N; with the default
N = max(48, 6 lambda) + 16 the load at a given radius, the peak pressure and the approach agree with N = 10 lambda + 16
to 2e-12 for nu = 0.3 and 2e-10 for nu = 0.5 up to lambda = 46 (N = 2 lambda + 16: 2e-4 and 2e-2). SI units: E, p in Pa; R, h, a, delta in m; P in N.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from . import bonded_layer, hertz, thin_layer


def _check(E: float, nu: float, thickness: float, radius: float, load: float) -> None:
    for key, v in (("layer.E", E), ("layer.thickness", thickness), ("geometry.radius", radius), ("load.normal", load)):
        if not (np.isfinite(v) and v > 0):
            raise InputError(key, f"{v!r}; allowed (0, inf)")
    bonded_layer.kappa(nu)


def nodes(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Positive half (tau > 0, ascending) of the 2n-point Gauss-Legendre rule on [-1, 1] and its weights: a rule on
    [0, 1] exact for even polynomials of degree up to 4n - 1."""
    x, w = np.polynomial.legendre.leggauss(2 * n)
    return x[n:], w[n:]


def kernel(tau: np.ndarray, sigma: np.ndarray, lam: float, nu: float, derivative: bool = False) -> np.ndarray:
    """k(tau, sigma) a = (2 lambda / pi) int_0^inf K(u) cos(lambda u tau) cos(lambda u sigma) du (dimensionless),
    or with ``derivative`` its tau-derivative (cos(lambda u tau) -> -lambda u sin(lambda u tau))."""
    u, w = bonded_layer.panels(bonded_layer.DEFICIT_CUTOFF, lam * max(np.max(tau), np.max(sigma), 1e-300))
    wk = w * bonded_layer.deficit(u, nu)
    out = np.zeros((tau.size, sigma.size))
    for lo in range(0, u.size, 4096):          # blocks of the xi-rule: C is (points x block), not (points x all)
        uu, ww = u[lo:lo + 4096], wk[lo:lo + 4096]
        cs = np.cos(lam * np.outer(sigma, uu))
        ct = -lam * uu * np.sin(lam * np.outer(tau, uu)) if derivative else np.cos(lam * np.outer(tau, uu))
        out += (ct * ww) @ cs.T
    return (2.0 * lam / np.pi) * out


@dataclass
class _Dimensionless:
    """gamma = D gamma_1 - gamma_2 at the nodes, D, int gamma, and the pieces for interpolation."""

    lam: float
    tau: np.ndarray
    w: np.ndarray
    gamma: np.ndarray
    D: float
    integral: float
    stiffness_integral: float        # int_0^1 gamma_1 dtau (flat punch)
    residual: float


def _solve_fixed(lam: float, nu: float, n: int) -> _Dimensionless:
    """The Fredholm equation at a fixed lambda = a / h."""
    tau, w = nodes(n)
    Kmat = kernel(tau, tau, lam, nu) * w[None, :]
    A = np.eye(n) - Kmat
    rhs = np.stack([np.ones(n), tau**2], axis=1)
    sol = np.linalg.solve(A, rhs)
    resid = float(np.abs(A @ sol - rhs).max())
    k1 = kernel(np.array([1.0]), tau, lam, nu)[0] * w          # Nystrom interpolant at tau = 1
    g1_at_1 = 1.0 + k1 @ sol[:, 0]
    g2_at_1 = 1.0 + k1 @ sol[:, 1]
    D = g2_at_1 / g1_at_1
    gamma = D * sol[:, 0] - sol[:, 1]
    return _Dimensionless(lam, tau, w, gamma, float(D), float(w @ gamma), float(w @ sol[:, 0]), resid)


def default_nodes(lam: float) -> int:
    """Nystrom nodes on [0, 1] for a / h = lambda: the kernel varies over h, i.e. 1/lambda of the contact radius."""
    return int(max(48, np.ceil(6.0 * lam)) + 16)


@dataclass(frozen=True)
class LayerSphereContact:
    """Rigid sphere on a bonded layer: contact radius ``a`` (m), peak pressure ``p_max`` (Pa, at the centre),
    approach ``approach`` delta (m), ``load`` P (N); ``pressure(r)`` (Pa); ``stats``: Nystrom nodes, xi-rule
    points, largest residual of the linear solves, root-finding iterations."""

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

    def _gamma_prime_over_tau(self, tau: np.ndarray) -> np.ndarray:
        d = np.polynomial.legendre.legder(self._coef)
        t = np.asarray(tau, dtype=float)
        safe = np.where(t > 1e-12, t, 1e-12)
        # gamma is even: gamma'(tau)/tau -> gamma''(0) as tau -> 0
        return np.where(t > 1e-12, np.polynomial.legendre.legval(safe, d) / safe,
                        np.polynomial.legendre.legval(0.0, np.polynomial.legendre.legder(d)))

    def pressure(self, r: np.ndarray) -> np.ndarray:
        """p(r) (Pa) at distances ``r`` (m) from the axis: the Abel integral of the module docstring by
        Gauss-Legendre in omega (points enough to resolve the layer's scale h)."""
        rho = np.abs(np.atleast_1d(np.asarray(r, dtype=float))) / self.a
        out = np.zeros_like(rho)
        inside = rho < 1.0
        m = int(max(64, 4 * self.a / self.thickness))
        x, w = np.polynomial.legendre.leggauss(m)
        for i in np.flatnonzero(inside):
            top = np.sqrt(1.0 - rho[i] ** 2)
            om = 0.5 * top * (x + 1.0)
            tau = np.sqrt(rho[i] ** 2 + om * om)
            out[i] = -0.5 * top * (w @ self._gamma_prime_over_tau(tau))
        return out * self.modulus * self.a / (np.pi * self.radius)


def _dimensional(E: float, nu: float, h: float, R: float, d: _Dimensionless, stats: dict) -> LayerSphereContact:
    Es = E / (1.0 - nu**2)
    a = d.lam * h
    tt = np.concatenate([-d.tau[::-1], d.tau])
    gg = np.concatenate([d.gamma[::-1], d.gamma])
    coef = np.polynomial.legendre.legfit(tt, gg, tt.size - 1)
    coef[1::2] = 0.0                     # gamma is even; odd coefficients are round-off
    load = 2.0 * Es * a**3 / R * d.integral
    c = LayerSphereContact(a, 0.0, d.D * a * a / R, load, R, Es, h, nu, coef, stats)
    p0 = float(c.pressure(np.array([0.0]))[0])
    return LayerSphereContact(a, p0, c.approach, load, R, Es, h, nu, coef, stats)


def contact_at_radius(E: float, nu: float, thickness: float, radius: float, a: float, n: int | None = None
                      ) -> LayerSphereContact:
    """The smooth-edge solution whose contact radius is ``a`` (m): its load and pressure follow."""
    _check(E, nu, thickness, radius, a)
    lam = a / thickness
    n = n or default_nodes(lam)
    d = _solve_fixed(lam, nu, n)
    return _dimensional(E, nu, thickness, radius, d, {"nodes": n, "residual": d.residual, "iterations": 0})


def flat_punch_stiffness(E: float, nu: float, thickness: float, a: float, n: int | None = None) -> float:
    """dP/d delta (N/m) of a rigid flat punch of radius ``a`` (m) on the bonded layer: 2 E* a int_0^1 gamma_1,
    gamma_1 - K gamma_1 = 1 (2 E* a for the half-space: Boussinesq's flat punch, P = 2 a E* delta)."""
    _check(E, nu, thickness, 1.0, a)
    lam = a / thickness
    d = _solve_fixed(lam, nu, n or default_nodes(lam))
    return float(2.0 * E / (1.0 - nu**2) * a * d.stiffness_integral)


def contact(E: float, nu: float, thickness: float, radius: float, load: float, n: int | None = None,
            rtol: float = 1e-13) -> LayerSphereContact:
    """Rigid sphere of ``radius`` (m) pressed with ``load`` P (N) on a layer (``E`` Pa, ``nu``, ``thickness`` m)
    bonded to a rigid base. The contact radius solves P(lambda h) = P (Brent on log lambda, relative
    tolerance ``rtol``), bracketed by stepping out by 1.25 from the smaller of the Hertz radius of the layer's
    half-space and Johnson's thin-layer radii. ``n`` Nystrom nodes (default :func:`default_nodes`). Raises
    ConvergenceError if the root is not bracketed."""
    _check(E, nu, thickness, radius, load)
    Es = E / (1.0 - nu**2)
    target = load * radius / (2.0 * Es * thickness**3)          # lambda^3 int gamma at the solution
    lam_hi = hertz.point_contact(load, radius, Es).semi_axis_x / thickness

    def f(loglam: float) -> float:
        lam = float(np.exp(loglam))
        d = _solve_fixed(lam, nu, n or default_nodes(lam))
        return float(np.log(lam**3 * d.integral / target))

    # first guess: the smaller of the Hertz radius and Johnson's thin-layer radius (the stiffer of the two limits
    # bounds the contact from above in each regime); then step out by 1.25 until the root is bracketed
    guesses = [lam_hi]
    if nu <= thin_layer.NU_COMPRESSIBLE_MAX:
        guesses.append(thin_layer.compressible(E, nu, thickness, radius, load, "circular").a / thickness)
    guesses.append(thin_layer.incompressible(E, thickness, radius, load, "circular").a / thickness)
    root, info, evaluations = bonded_layer.contact_size(f, float(np.log(min(guesses))), rtol, "layer_axisymmetric",
                                                        "contact radius")
    lam = float(np.exp(root))
    nn = n or default_nodes(lam)
    d = _solve_fixed(lam, nu, nn)
    stats = {"nodes": nn, "residual": d.residual, "iterations": info.iterations,
             "evaluations": evaluations, "load_error": float(lam**3 * d.integral / target - 1.0)}
    return _dimensional(E, nu, thickness, radius, d, stats)


__all__ = ["LayerSphereContact", "contact", "contact_at_radius", "flat_punch_stiffness", "kernel", "nodes",
           "default_nodes"]
