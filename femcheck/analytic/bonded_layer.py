"""Surface compliance of an elastic layer perfectly bonded to a rigid base, loaded by a normal pressure on its free
face (no shear): the transform-domain kernel of the layered contact solutions
(:mod:`femcheck.analytic.layer_axisymmetric`, :mod:`femcheck.analytic.layer_plane`).

Layer: Young's modulus E, Poisson's ratio nu, thickness h; z points into the layer, the base is at z = h. With
the Hankel transform f^(xi) = int_0^inf f(r) J0(xi r) r dr (axisymmetric) or the Fourier transform
f^(xi) = int f(x) e^{-i xi x} dx (plane strain), the surface normal displacement under the pressure p^ is

    u^(xi) = 2 Phi(xi h) p^(xi) / (E* xi),        E* = E / (1 - nu^2)

    Phi(t) = (2 kappa sinh 2t - 4t) / (2 kappa cosh 2t + 1 + kappa^2 + 4 t^2),     kappa = 3 - 4 nu.

This is the classical kernel of the bonded layer (Meijers, Appl. Sci. Res. 18, 1968; Jaffar, 1989; written
here as derived below, not copied from their equation numbers, which were not checked); the Fredholm equations
use its deficit K = 1 - Phi. Derivation (stated so it can be checked; tests/test_layer_solutions.py also solves the
transformed Navier equations numerically by a transfer matrix and compares): Papkovich-Neuber potentials
(Barber, *Elasticity*, solutions A and B), 2 mu u = grad phi + grad(z omega) - 4 (1 - nu) omega e_z with
phi = (A e^{-xi z} + B e^{xi z}) J0(xi r) / xi^2, omega = (C e^{-xi z} + D e^{xi z}) J0(xi r) / xi. Then

    sigma_zz / J0           = A e^- + B e^+ + xi z (C e^- + D e^+) - 2 (1 - nu)(-C e^- + D e^+)
    sigma_rz / (-xi J1)     = [-A e^- + B e^+ - (1 - 2 nu)(C e^- + D e^+)] / xi + z (-C e^- + D e^+)
    2 mu u_z / J0           = [-A e^- + B e^+ - kappa (C e^- + D e^+)] / xi + z (-C e^- + D e^+)
    2 mu u_r / (-xi J1)     = (A e^- + B e^+) / xi^2 + z (C e^- + D e^+) / xi

and the four conditions sigma_zz = -p^, sigma_rz = 0 at z = 0 and u_r = u_z = 0 at z = h give
A = (-p^ - kappa C + D)/2, B = (-p^ - C + kappa D)/2 and, with T = xi h,

    C + D = -2 p^ (kappa sinh 2T - 2T) / (2 kappa cosh 2T + 1 + kappa^2 + 4 T^2),
    2 mu xi u_z(0) = -2 (1 - nu)(C + D)     ->     the Phi above.

The same Phi holds in plane strain (the transformed equations are the same with J0 -> cos, J1 -> sin).

Limits: Phi -> 1 for t -> inf (half-space of the layer material); Phi -> (1 - 2 nu) t / (2 (1 - nu)^2) for
t -> 0, i.e. u^ = h p^ / M with M = (1 - nu) E / ((1 + nu)(1 - 2 nu)) (Johnson's Winkler layer, *Contact
Mechanics* 1985 §5.9); for nu = 1/2, Phi -> (2/3) t^3, i.e. u^ = h^3 xi^2 p^ / (3 G) (the squeeze film with a
frictionless top, k = 3 G / h^3). Dimensionless; t = xi h with xi in rad/m, h in m.
"""
from __future__ import annotations

from typing import Any

import numpy as np
from scipy.optimize import brentq

from ..errors import ConvergenceError, InputError


def kappa(nu: float) -> float:
    """kappa = 3 - 4 nu (Kolosov's constant in plane strain); nu in (-1, 0.5]."""
    if not (-1.0 < nu <= 0.5):
        raise InputError("layer.nu", f"{nu!r}; allowed (-1, 0.5]")
    return 3.0 - 4.0 * nu


def _sinh_minus(x: np.ndarray) -> np.ndarray:
    """sinh x - x without cancellation (series below x = 0.5: terms to x^17, relative error < 1e-17)."""
    out = np.sinh(x) - x
    small = np.abs(x) < 0.5
    if np.any(small):
        xs = x[small]
        term, acc = xs**3 / 6.0, np.zeros_like(xs)
        for k in range(8):
            acc = acc + term
            term = term * xs * xs / ((2 * k + 4) * (2 * k + 5))
        out[small] = acc
    return out


def factor(t: np.ndarray, nu: float) -> np.ndarray:
    """Phi(t), t = xi h >= 0 (module docstring): u^ = 2 Phi p^ / (E* xi). Written with sinh 2t - 2t so that
    Phi keeps its relative precision as t -> 0 (the incompressible layer's numerator is O(t^3)), and with the
    numerator and denominator scaled by e^{-2t} so that it does not overflow as t -> inf."""
    k = kappa(nu)
    t = np.atleast_1d(np.asarray(t, dtype=float))
    out = np.empty_like(t)
    big = t > 5.0
    tb, ts = t[big], t[~big]
    e2, e4 = np.exp(-2.0 * tb), np.exp(-4.0 * tb)
    out[big] = (k * (1.0 - e4) - 4.0 * tb * e2) / (k * (1.0 + e4) + (1.0 + k * k + 4.0 * tb * tb) * e2)
    num = 2.0 * k * _sinh_minus(2.0 * ts) + 4.0 * (k - 1.0) * ts
    out[~big] = num / (2.0 * k * np.cosh(2.0 * ts) + 1.0 + k * k + 4.0 * ts * ts)
    return out


def deficit(t: np.ndarray, nu: float) -> np.ndarray:
    """K(t) = 1 - Phi(t) (dimensionless), the part by which the layer is stiffer than the half-space of its
    material: K = (2 kappa e^{-2t} + 1 + kappa^2 + 4t + 4t^2) / (2 kappa cosh 2t + 1 + kappa^2 + 4t^2), written
    with e^{-2t} factored out (no overflow, no cancellation). K(0) = 1; K ~ (1 + kappa^2 + 4t + 4t^2) e^{-2t} /
    kappa as t -> inf."""
    k = kappa(nu)
    t = np.atleast_1d(np.asarray(t, dtype=float))
    e2, e4 = np.exp(-2.0 * t), np.exp(-4.0 * t)
    return (2.0 * k * e4 + (1.0 + k * k + 4.0 * t + 4.0 * t * t) * e2) / (
        k * (1.0 + e4) + (1.0 + k * k + 4.0 * t * t) * e2)


# Beyond t = DEFICIT_CUTOFF the deficit is below 1e-18 for every nu (kappa >= 1): the transform integrals stop there.
DEFICIT_CUTOFF = 25.0


def panels(cutoff: float, frequency: float, order: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss-Legendre nodes and weights on [0, cutoff] for integrands oscillating up to ``frequency``
    (rad per unit of t): panels of width min(1, pi / frequency), ``order`` points each (a period of the fastest
    oscillation is integrated with 32 points, error below 1e-16 of the integrand's size)."""
    width = min(1.0, np.pi / max(frequency, 1e-300))
    n = int(np.ceil(cutoff / width))
    edges = np.linspace(0.0, cutoff, n + 1)
    x, w = np.polynomial.legendre.leggauss(order)
    half = 0.5 * np.diff(edges)
    nodes = (0.5 * (edges[:-1] + edges[1:]))[:, None] + half[:, None] * x[None, :]
    return nodes.ravel(), (half[:, None] * w[None, :]).ravel()


__all__ = ["kappa", "factor", "deficit", "panels", "DEFICIT_CUTOFF"]


def contact_size(residual, x0: float, rtol: float, model: str, what: str) -> tuple[float, Any, int]:
    """Root of ``residual(log size)`` (the log of computed over applied load of a contact of that size): from
    the first guess ``x0`` step out by a factor 1.25 until the root is bracketed, then Brent to ``rtol``.
    Returns (root, brentq's result, evaluations of ``residual``); a root not bracketed within 1.25^200 of the
    guess is a :class:`femcheck.errors.ConvergenceError` naming ``model`` and ``what`` was sought."""
    count = 0

    def f(x: float) -> float:
        nonlocal count
        count += 1
        return residual(x)

    f0 = f(x0)
    step = np.log(1.25) * (-1.0 if f0 > 0 else 1.0)
    x1, f1 = x0, f0
    for _ in range(200):
        x1 = x1 + step
        f1 = f(x1)
        if f1 * f0 <= 0:
            break
    else:
        raise ConvergenceError(model, count, f1, 0.0, f"the {what} was not bracketed within 1.25^200 of the first "
                                                      "guess")
    root, info = brentq(f, min(x0, x1), max(x0, x1), xtol=1e-15, rtol=rtol, full_output=True)
    return float(root), info, count
