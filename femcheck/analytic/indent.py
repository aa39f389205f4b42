"""Analytic zone A/B model of the additional pressure over a dent in a dry contact (seed 004 §3.2.3, App. B).

Dimensionless as in the thesis: lengths in the Hertz contact radius a (b there), heights in a^2/Rx, pressures
in p_H. An indent R(r) = -D exp(-K r^2/Phi^2) cos(pi r/Phi) (eq 2.16) of slope S = D/Phi raises the pressure
around it by the *additional pressure amplitude* dP = max(p_indented - p_smooth). The model (eq 3.6/B.16):

    dP = n S zeta(K) (1 - s F^omega) + m S nu(K)

hole term ~ zeta(K) = 2 sqrt(lambda(K)) / beta(K), lambda = 1 / (32 (1 - exp(-K/16)/sqrt 2))  (B.10-B.11)
shoulder term ~ nu(K) = sqrt(gamma(K) / mu(K)) from the shoulder top r_h = beta Phi: R'(r_h) = 0,
    tan(pi beta) = -(2K/pi) beta (B.5), gamma = R(r_h)/D, mu = D / (Phi^2 |R''(r_h)|)  (B.6-B.8), with R''
    from differentiating B.1 (the printed B.3 lacks a pi^2 cos term)
F = D_d/D_i, the deformed/initial hole depth (B.15): F = k(S - 1/4) / (1 + (k(S - 1/4))^theta)^(1/theta),
    k = 2.1, theta = 1.1 for S > 1/4 (zone B: pressure zero in the hole), F = 0 otherwise (zone A).

The thesis fits n, m by least squares in zone A (B.12-B.13) and s, omega in zone B against its numerical
results, and does not print them; here they are fitted the same way against femcheck's BEM
(:func:`calibrate`, stored in ``indent_zone_ab.json`` with provenance).
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy import optimize

COEFFS = Path(__file__).with_name("indent_zone_ab.json")
F_K, F_THETA, ZONE_B_SLOPE = 2.1, 1.1, 0.25


def shoulder(K: float) -> tuple[float, float, float]:
    """beta, gamma, mu of the shoulder top r_h = beta Phi (B.5-B.7), D = Phi = 1."""
    # R'(r) = 0 <=> tan(pi r) = -(2K/pi) r; tan runs from -inf to +inf on (1/2, 3/2): one root there
    beta = optimize.brentq(lambda b: np.tan(np.pi * b) + 2.0 * K / np.pi * b, 0.5 + 1e-12, 1.5 - 1e-12)
    r = beta
    gamma = -np.exp(-K * r * r) * np.cos(np.pi * r)
    # Second derivative of B.1 (D = Phi = 1). The printed B.3, 2K e^(-K r^2) [cos(pi r)(1 - 2K r^2)
    # - 2 pi r sin(pi r)], drops the + pi^2 cos(pi r) term of differentiating the cosine twice.
    R2 = np.exp(-K * r * r) * (np.cos(np.pi * r) * (2.0 * K - 4.0 * K * K * r * r + np.pi**2)
                               - 4.0 * K * np.pi * r * np.sin(np.pi * r))
    return float(beta), float(gamma), float(1.0 / abs(R2))


def nu(K: float) -> float:
    """Shoulder factor nu(K) = sqrt(gamma/mu) (B.8)."""
    _, gamma, mu = shoulder(K)
    return float(np.sqrt(gamma / mu))


def zeta(K: float) -> float:
    """Hole factor zeta(K) = 2 sqrt(lambda)/beta (B.10-B.11); about 0.78 and nearly constant in K."""
    lam = 1.0 / (32.0 * (1.0 - np.exp(-K / 16.0) / np.sqrt(2.0)))
    return float(2.0 * np.sqrt(lam) / shoulder(K)[0])


def depth_ratio(slope: float) -> float:
    """F = D_d/D_i (B.15): 0 in zone A (slope <= 1/4), rising to an asymptote 1 for steep indents."""
    if slope <= ZONE_B_SLOPE:
        return 0.0
    t = F_K * (slope - ZONE_B_SLOPE)
    return float(t / (1.0 + t**F_THETA) ** (1.0 / F_THETA))


@dataclass(frozen=True)
class ZoneABCoefficients:
    n: float
    m: float
    s: float
    omega: float
    provenance: dict

    @classmethod
    def load(cls, path: Path = COEFFS) -> "ZoneABCoefficients":
        d = json.loads(path.read_text())
        return cls(d["n"], d["m"], d["s"], d["omega"], d.get("provenance", {}))


def additional_pressure(slope: float, K: float, c: ZoneABCoefficients) -> float:
    """dP / p_H of eq 3.6 (B.16)."""
    F = depth_ratio(slope)
    return float(slope * (c.n * zeta(K) * (1.0 - c.s * F**c.omega) + c.m * nu(K)))


def calibrate(samples: list[tuple[float, float, float]]) -> tuple[float, float, float, float]:
    """Fit (n, m) on zone A samples (slope <= 1/4) by linear least squares (B.12-B.13), then (s, omega) on zone
    B samples by nonlinear least squares. ``samples``: (slope, K, dP/p_H) from a numerical model."""
    A = [(S, K, dp) for S, K, dp in samples if S <= ZONE_B_SLOPE]
    B = [(S, K, dp) for S, K, dp in samples if S > ZONE_B_SLOPE]
    if len(A) < 2 or len(B) < 2:
        raise ValueError("calibration needs at least two samples in each of zones A and B")
    x = np.array([S * zeta(K) for S, K, _ in A])
    y = np.array([S * nu(K) for S, K, _ in A])
    f = np.array([dp for *_, dp in A])
    T = (x @ x) * (y @ y) - (x @ y) ** 2
    n = ((y @ y) * (f @ x) - (x @ y) * (f @ y)) / T
    m = ((x @ x) * (f @ y) - (x @ y) * (f @ x)) / T

    def resid(v):
        s, omega = v
        return [S * (n * zeta(K) * (1 - s * depth_ratio(S) ** omega) + m * nu(K)) - dp for S, K, dp in B]

    fit = optimize.least_squares(resid, [0.5, 1.0], bounds=([0.0, 0.05], [2.0, 10.0]))
    return float(n), float(m), float(fit.x[0]), float(fit.x[1])
