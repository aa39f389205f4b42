"""Multiaxial fatigue measures of a stress history at a material point: Papadopoulos' shear-stress amplitude and
the von Mises measure the thesis of seed 004 uses (§4.2.1, Table 4.1).

Papadopoulos' criterion (Papadopoulos, Davoli, Gorla, Filippini & Bernasconi, "A comparative study of multiaxial
high-cycle fatigue criteria for metals", Int. J. Fatigue 19 (1997) 219-235, the "Papadopoulos" criterion of its
§ on integral approaches; the same measure in Papadopoulos, "Long life fatigue under multiaxial loading",
Int. J. Fatigue 23 (2001) 839-849). The equation numbers of those papers are not checked here (no copy at hand);
the definition implemented is:

    tau(t; n, m) = n . sigma(t) . m                      resolved shear stress on the line m of the plane n
    T_a(n, m)    = (max_t tau - min_t tau) / 2           its amplitude (half its range over the cycle)
    T_sigma      = sqrt( 5/(8 pi^2) int_{phi=0}^{2pi} int_{theta=0}^{pi} int_{chi=0}^{2pi} T_a^2
                         dchi sin(theta) dtheta dphi )
    criterion    : T_sigma + alpha sigma_H,max <= beta,  sigma_H = tr(sigma)/3

n = (sin theta cos phi, sin theta sin phi, cos theta), m = cos chi e_theta + sin chi e_phi. The factor 5/(8 pi^2)
makes T_sigma the root-mean-square of T_a over all (n, m) times sqrt(5), so that fully reversed torsion tau_a gives
T_sigma = tau_a and fully reversed tension sigma_a gives sigma_a/sqrt(3) (both checked in tests/test_multiaxial.py);
for a proportional (in-phase) history T_sigma = sqrt(J2) of the amplitude tensor, i.e. the von Mises amplitude over
sqrt(3): the two criteria differ only on non-proportional histories such as a rolling pass.

Quadrature: (n, m) and (-n, m), (n, -m) give the same T_a, so the normals run over the upper hemisphere and chi
over [0, pi). Product rule: Gauss-Legendre in u = cos(theta) on [0, 1] (``n_theta`` nodes), ``n_phi`` equally
spaced phi on [0, 2 pi), ``n_chi`` equally spaced chi on [0, pi), weights normalised to 1 (the mean). For a
proportional history T_a^2 is a polynomial of degree 4 in (n, m): the rule is exact for n_theta >= 3, n_phi >= 5,
n_chi >= 3. For a non-proportional history T_a is only continuous (a max - min), and the rule converges at a lower
order; :func:`papadopoulos_amplitude` reports the value for the rule it is given.

Von Mises (thesis §4.2.1): the history measure is the largest von Mises stress of the tensor over the cycle,
max_t sigma_VM(sigma(t)) (:func:`von_mises_max`, as in :mod:`femcheck.bem.stress_history`); for a fully reversed
history it is the von Mises amplitude.

Stresses: shape (T, 6) with components (sx, sy, sz, txy, txz, tyz) (femcheck's order, ``COMPONENTS``) or
(T, 3, 3); extra trailing axes (..., material points) are allowed after the component axis in the (T, 6, ...)
form. Pa in, Pa out.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError


@dataclass(frozen=True)
class LineRule:
    """Lines (n, m) of the quadrature: ``weights`` (N,) summing to 1 and ``resolve`` (6, N) such that
    tau = s . resolve[:, k] for stacked components s = (sx, sy, sz, txy, txz, tyz)."""

    weights: np.ndarray
    resolve: np.ndarray
    normals: np.ndarray
    directions: np.ndarray


def line_rule(n_theta: int = 8, n_phi: int = 16, n_chi: int = 8) -> LineRule:
    """Product rule over the hemisphere of normals and the half circle of directions (module docstring)."""
    if min(n_theta, n_phi, n_chi) < 1:
        raise InputError("multiaxial.rule", "every factor of the rule needs at least one node")
    g, gw = np.polynomial.legendre.leggauss(n_theta)
    u, wu = 0.5 * (g + 1.0), 0.5 * gw                     # cos(theta) on [0, 1], weights sum to 1
    phi = 2.0 * np.pi * np.arange(n_phi) / n_phi
    chi = np.pi * np.arange(n_chi) / n_chi
    U, P, C = np.meshgrid(u, phi, chi, indexing="ij")
    W = np.broadcast_to(wu[:, None, None], U.shape) / (n_phi * n_chi)
    st = np.sqrt(1.0 - U * U)
    n = np.stack([st * np.cos(P), st * np.sin(P), U])
    e_t = np.stack([U * np.cos(P), U * np.sin(P), -st])    # d n / d theta
    e_p = np.stack([-np.sin(P), np.cos(P), np.zeros_like(P)])
    m = np.cos(C) * e_t + np.sin(C) * e_p
    n, m = n.reshape(3, -1), m.reshape(3, -1)
    resolve = np.stack([n[0] * m[0], n[1] * m[1], n[2] * m[2], n[0] * m[1] + n[1] * m[0],
                        n[0] * m[2] + n[2] * m[0], n[1] * m[2] + n[2] * m[1]])
    return LineRule(W.reshape(-1).copy(), resolve, n, m)


def as_components(history: np.ndarray) -> np.ndarray:
    """(T, 6, ...) components from (T, 6, ...) or (T, 3, 3)."""
    s = np.asarray(history, dtype=float)
    if s.ndim == 3 and s.shape[1:] == (3, 3):
        if not np.allclose(s, np.swapaxes(s, 1, 2), rtol=1e-12, atol=1e-12 * max(np.abs(s).max(), 1e-300)):
            raise InputError("stress", "the stress tensors of the history are not symmetric")
        return np.stack([s[:, 0, 0], s[:, 1, 1], s[:, 2, 2], s[:, 0, 1], s[:, 0, 2], s[:, 1, 2]], axis=1)
    if s.ndim < 2 or s.shape[1] != 6:
        raise InputError("stress", f"shape {s.shape} is not allowed; allowed: (T, 6, ...) or (T, 3, 3)")
    if not np.all(np.isfinite(s)):
        raise InputError("stress", "non-finite stress in the history")
    return s


AMPLITUDES = ("range", "zero")


def shear_amplitudes(history: np.ndarray, rule: LineRule, about: str = "range") -> np.ndarray:
    """T_a(n, m) on the rule's lines: (N, ...) (Pa). ``about``: "range" is Papadopoulos' amplitude, half the range
    of tau over the cycle; "zero" (not Papadopoulos') measures it from the unloaded state, max_t |tau|, a variant
    for rolling passes that start and end stress-free (reported beside the criterion, never instead of it)."""
    if about not in AMPLITUDES:
        raise InputError("multiaxial.about", f"{about!r} is not allowed; allowed: " + ", ".join(AMPLITUDES))
    s = as_components(history)
    tau = np.tensordot(rule.resolve, s, axes=([0], [1]))          # (N, T, ...)
    if about == "zero":
        return np.abs(tau).max(axis=1)
    return 0.5 * (tau.max(axis=1) - tau.min(axis=1))


def papadopoulos_amplitude(history: np.ndarray, rule: LineRule | None = None, chunk: int = 256,
                           about: str = "range") -> np.ndarray:
    """Papadopoulos' T_sigma = sqrt(5 <T_a^2>) of a stress history (Pa; module docstring): shape of the history's
    trailing axes (a float for one point). Points are processed ``chunk`` at a time (memory N x T x chunk)."""
    rule = line_rule() if rule is None else rule
    s = as_components(history)
    flat = s.reshape(s.shape[0], 6, -1)
    out = np.empty(flat.shape[2])
    for i in range(0, flat.shape[2], chunk):
        ta = shear_amplitudes(flat[:, :, i:i + chunk], rule, about)
        out[i:i + chunk] = np.sqrt(5.0 * (rule.weights @ (ta * ta)))     # 5/(8 pi^2) x measure 8 pi^2 = 5
    return out.reshape(s.shape[2:]) if s.ndim > 2 else float(out[0])


def papadopoulos_critical_plane(history: np.ndarray, rule: LineRule | None = None, chunk: int = 256,
                                about: str = "range") -> np.ndarray:
    """Critical-plane form of Papadopoulos' amplitude (Papadopoulos, "A high-cycle fatigue criterion applied in
    biaxial and triaxial out-of-phase stress conditions", Fatigue Fract. Eng. Mater. Struct. 18 (1995) 79-91, the
    "hard metals" criterion): max over plane normals n of sqrt( (1/pi) int_0^{2 pi} T_a^2(n, chi) dchi ) (Pa).
    Fully reversed torsion tau_a gives tau_a, fully reversed tension sigma_a gives sigma_a / 2 (tests). The max
    runs over the rule's n_theta x n_phi normals (a discrete max: it can only be low)."""
    rule = line_rule() if rule is None else rule
    s = as_components(history)
    flat = s.reshape(s.shape[0], 6, -1)
    n_chi = _n_chi(rule)
    out = np.empty(flat.shape[2])
    for i in range(0, flat.shape[2], chunk):
        ta = shear_amplitudes(flat[:, :, i:i + chunk], rule, about)
        ms = (ta * ta).reshape(-1, n_chi, ta.shape[1]).mean(axis=1)     # chi equally spaced: the mean over chi
        out[i:i + chunk] = np.sqrt(2.0 * ms.max(axis=0))                 # (1/pi) int_0^{2 pi} = 2 x the mean
    return out.reshape(s.shape[2:]) if s.ndim > 2 else float(out[0])


def _n_chi(rule: LineRule) -> int:
    """Directions per normal of a :func:`line_rule` (the normals repeat n_chi times consecutively)."""
    n = rule.normals
    k = 1
    while k < n.shape[1] and np.allclose(n[:, k], n[:, 0]):
        k += 1
    return k


def papadopoulos_criterion(history: np.ndarray, alpha: float, rule: LineRule | None = None) -> np.ndarray:
    """T_sigma + alpha sigma_H,max (Pa), to be compared with beta (Papadopoulos et al. 1997)."""
    return papadopoulos_amplitude(history, rule) + alpha * hydrostatic_max(history)


def hydrostatic_max(history: np.ndarray) -> np.ndarray:
    """max_t tr(sigma(t))/3 (Pa)."""
    s = as_components(history)
    return (s[:, 0] + s[:, 1] + s[:, 2]).max(axis=0) / 3.0


def von_mises(history: np.ndarray) -> np.ndarray:
    """sigma_VM(t) of every state of the history: (T, ...) (Pa)."""
    sx, sy, sz, txy, txz, tyz = np.moveaxis(as_components(history), 1, 0)
    return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2)
                   + 3.0 * (txy * txy + txz * txz + tyz * tyz))


def von_mises_max(history: np.ndarray) -> np.ndarray:
    """The thesis' von Mises history measure max_t sigma_VM(sigma(t)) (Pa)."""
    return von_mises(history).max(axis=0)
