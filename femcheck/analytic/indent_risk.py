"""The risk integral of a dented contact as a closed-form model (seed 004 eq 4.6) and over a population of indents
(seed 004 §4.3, Figs 4.10-4.11).

Eq 4.6 (Biboulet 2008, §4.3; spec ``specs/ehl-life.md`` B.2): the dented-to-smooth risk ratio of a window holding one
indent (diameter Phi = phi/b, slope D/Phi, shoulder decay K of eq 2.16) is

    (I-bar_D / I-bar_S)^c = q_K(K) q_Tinf(T_inf/T_Smax) Phi^3 [(T_Dmax/T_Smax - T_inf/T_Smax) / (1 - T_inf/T_Smax)]^c + 1

(dimensionless; I-bar = (I / (b^3 p_H^c))^(1/c) of eq 4.3, so the left side is I_D / I_S, the ratio of the
dimensional risk integrals over the same window), T_Dmax, T_Smax the largest stress-amplitude history of the dented
and the smooth contact, T_inf the fatigue limit (all in p_H). Phi^3 is the stressed volume of the indent's
near-surface peak (it scales like Phi^3), the bracket its amplitude above the fatigue limit, made relative to the
smooth one; q_K and q_Tinf carry the shape: the thesis gives them only as curves (Fig 4.6, figure only), so femcheck
fits them to its own risk integrals (:func:`fit_eq46`) with q_Tinf(0) = 1 (the product q_K q_Tinf is otherwise
determined only up to one constant).

Populations (eqs 4.9-4.10, closed form of spec B.3): a track whose windows of equal area hold one indent each with
probability f_d, the indents' diameter and slope drawn from independent distributions, has the expected risk ratio
E[I_D/I_S] over the population (the weakest link sums risks, eq 4.9, so the population enters linearly) and the life
ratio L/L_S = [1 + f_d (E[I_D/I_S] - 1)]^(-1/e). femcheck integrates E[.] over log-normal diameter and slope
distributions (medians and geometric standard deviations as inputs; seed 004's medians Phi = 0.56, D/Phi = 0.6,
§4.3.1) by Gauss-Hermite quadrature in the logarithms (:func:`lognormal_rule`, :func:`population_mean`) for a
smooth I_D/I_S(Phi, D/Phi) such as eq 4.6, and over a computed map (:func:`map_interpolant`, kinked at its nodes)
by Gauss-Legendre between the nodes (:func:`map_population_mean`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

THESIS_MEDIANS = {"diameter": 0.56, "slope": 0.6}      # seed 004 §4.3.1 (dimensionless Phi and D/Phi)


def eq46_excess(phi, stress_ratio, limit_ratio, c: float):
    """Phi^3 [(T_Dmax/T_Smax - t)/(1 - t)]^c, t = T_inf/T_Smax: eq 4.6 without q_K q_Tinf (dimensionless).

    NaN where the bracket is not positive (the indent's peak does not exceed the fatigue limit: the model's
    excess term has no meaning there) or t >= 1."""
    phi, r, t = np.asarray(phi, float), np.asarray(stress_ratio, float), np.asarray(limit_ratio, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        s = (r - t) / (1.0 - t)
        return np.where((s > 0) & (t < 1), phi ** 3 * np.abs(s) ** c, np.nan)


def eq46_risk_ratio(phi, stress_ratio, limit_ratio, c: float, q_k, q_t):
    """(I-bar_D/I-bar_S)^c = I_D/I_S = q_K q_Tinf Phi^3 [(T_Dmax/T_Smax - t)/(1 - t)]^c + 1 (seed 004 eq 4.6;
    dimensionless; ``q_k``, ``q_t`` the factors of the case's K and t = T_inf/T_Smax)."""
    return np.asarray(q_k, float) * np.asarray(q_t, float) * eq46_excess(phi, stress_ratio, limit_ratio, c) + 1.0


@dataclass
class Eq46Fit:
    """q_K per decay K and q_Tinf per limit ratio t (q_Tinf(t_ref) = 1, t_ref the smallest t), the samples used,
    and the misfit of log(I_D/I_S - 1) (natural log) on them."""

    c: float
    q_k: dict[float, float]
    q_t: dict[float, float]
    used: int
    rms_log: float
    max_log: float

    def predict(self, phi, stress_ratio, limit_ratio, K) -> np.ndarray:
        qk = np.array([self.q_k[float(k)] for k in np.atleast_1d(K)])
        qt = np.array([self.q_t[float(t)] for t in np.atleast_1d(limit_ratio)])
        return eq46_risk_ratio(phi, stress_ratio, limit_ratio, self.c, qk, qt)


def fit_eq46(phi: Sequence[float], K: Sequence[float], limit_ratio: Sequence[float], stress_ratio: Sequence[float],
             risk_ratio: Sequence[float], c: float, min_excess: float = 1e-3) -> Eq46Fit:
    """Least squares of ln(I_D/I_S - 1) - ln(Phi^3 [...]^c) = ln q_K(K) + ln q_Tinf(t) over the samples (one per
    indent and fatigue limit; seed 004 eq 4.6, fitted as the thesis fits it, per K and per t). The log makes the
    misfit a relative error of the indent's excess risk I_D/I_S - 1, which spans decades. Samples whose excess
    I_D/I_S - 1 is below ``min_excess`` (the indent does not change the risk: a log of round-off) or whose bracket
    is not positive are left out; ``used`` says how many remain. q_Tinf = 1 at the smallest t."""
    phi, K, t = (np.asarray(v, float) for v in (phi, K, limit_ratio))
    r, R = np.asarray(stress_ratio, float), np.asarray(risk_ratio, float)
    ex = eq46_excess(phi, r, t, c)
    ok = np.isfinite(ex) & (ex > 0) & np.isfinite(R) & (R - 1.0 > min_excess)
    ks, ts = sorted(set(K[ok].tolist())), sorted(set(t[ok].tolist()))
    if not ok.any() or len(ks) == 0:
        raise ValueError("no sample with a positive excess risk and bracket")
    A = np.zeros((int(ok.sum()), len(ks) + len(ts) - 1))
    for row, (k, tt) in enumerate(zip(K[ok], t[ok])):
        A[row, ks.index(k)] = 1.0
        j = ts.index(tt)
        if j > 0:
            A[row, len(ks) + j - 1] = 1.0
    y = np.log(R[ok] - 1.0) - np.log(ex[ok])
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    res = A @ coef - y
    q_k = {float(k): float(np.exp(coef[i])) for i, k in enumerate(ks)}
    q_t = {float(ts[0]): 1.0, **{float(tt): float(np.exp(coef[len(ks) + j - 1])) for j, tt in enumerate(ts) if j}}
    return Eq46Fit(c, q_k, q_t, int(ok.sum()), float(np.sqrt(np.mean(res ** 2))), float(np.abs(res).max()))


# ---------------------------------------------------------------------------------------------------------------
# populations of indents
# ---------------------------------------------------------------------------------------------------------------

def lognormal_rule(median: float, gsd: float, n: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights (summing to 1) of E[f(X)] for ln X ~ N(ln median, ln(gsd)^2) (dimensionless X):
    Gauss-Hermite in ln X. Checked on the closed-form moments E[X^k] = median^k exp(k^2 ln(gsd)^2 / 2): at
    gsd = 1.6, 32 nodes give 2e-16 up to k = 8 (16 nodes: 5e-6 at k = 8; eq 4.6 carries [.]^c, c = 8).
    gsd = 1: the single node ``median``."""
    if median <= 0 or gsd < 1:
        raise ValueError(f"median must be > 0 and gsd >= 1 (got {median}, {gsd})")
    if gsd == 1.0:
        return np.array([float(median)]), np.array([1.0])
    z, w = np.polynomial.hermite_e.hermegauss(n)
    return median * np.exp(np.log(gsd) * z), w / w.sum()


def population_mean(ratio: Callable[[np.ndarray, np.ndarray], np.ndarray], diameter: tuple[float, float],
                    slope: tuple[float, float], n: int = 32) -> float:
    """E[I_D/I_S] over independent log-normal diameter Phi and slope D/Phi distributions, each given as
    (median, geometric standard deviation): sum_ij w_i w_j ratio(Phi_i, s_j) (spec B.3, eq 4.10)."""
    xd, wd = lognormal_rule(*diameter, n)
    xs, ws = lognormal_rule(*slope, n)
    P, S = np.meshgrid(xd, xs, indexing="ij")
    return float(np.sum(np.outer(wd, ws) * ratio(P, S)))


def population_life_ratio(mean_ratio: float, indent_fraction: float, e: float) -> float:
    """L/L_S = [1 + f_d (E[I_D/I_S] - 1)]^(-1/e) (eq 4.10 for windows of equal area, spec B.3)."""
    return float((1.0 + indent_fraction * (mean_ratio - 1.0)) ** (-1.0 / e))


def map_interpolant(phis: Sequence[float], slopes: Sequence[float], ratio: np.ndarray
                    ) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """I_D/I_S(Phi, D/Phi) from a computed map ratio[i, j] at phis[i] x slopes[j]: bilinear in (ln Phi, ln D/Phi)
    on ln(I_D/I_S), held constant beyond the map's edges (a population's tails outside the map get the edge
    value; :func:`mass_outside` says how much probability that is)."""
    from scipy.interpolate import RegularGridInterpolator

    lp, ls = np.log(np.asarray(phis, float)), np.log(np.asarray(slopes, float))
    f = RegularGridInterpolator((lp, ls), np.log(np.asarray(ratio, float)), method="linear")

    def ratio_at(P, S):
        P, S = np.asarray(P, float), np.asarray(S, float)
        q = np.stack([np.clip(np.log(P), lp[0], lp[-1]), np.clip(np.log(S), ls[0], ls[-1])], axis=-1)
        return np.exp(f(q))

    return ratio_at


def map_rule(median: float, gsd: float, knots: Sequence[float], m: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights (summing to 1) of E[f(X)], ln X ~ N(ln median, ln(gsd)^2), for f smooth between the
    ``knots`` (increasing) and constant beyond them, as :func:`map_interpolant` is along each axis: ``m``
    Gauss-Legendre nodes in u = ln(X/median)/ln(gsd) on each interval between knots, weighted by the normal
    density, and one node at each edge knot carrying the tail's probability. Gauss-Hermite over the whole line
    (:func:`lognormal_rule`) converges slowly across the kinks: on seed 004's §4.3.1 dry map (fatigue limit
    0.7 T_Smax, medians 0.56 / 0.6, gsd 1.5) 32 nodes give E[I_D/I_S] 4.2938, 64 4.2812, 256 4.2632 against
    4.259729 from a 4001-point trapezoid rule over +-8 sigma; this rule with m = 16 gives the trapezoid's value.
    gsd = 1: the single node ``median``."""
    from scipy.stats import norm

    if median <= 0 or gsd < 1:
        raise ValueError(f"median must be > 0 and gsd >= 1 (got {median}, {gsd})")
    if gsd == 1.0:
        return np.array([float(median)]), np.array([1.0])
    knots = np.asarray(knots, float)
    u = np.log(knots / median) / np.log(gsd)
    g, gw = np.polynomial.legendre.leggauss(m)
    xs, ws = [knots[:1], knots[-1:]], [np.array([norm.cdf(u[0])]), np.array([norm.sf(u[-1])])]
    for a, b in zip(u[:-1], u[1:]):
        t = 0.5 * (b - a) * g + 0.5 * (a + b)
        xs.append(median * gsd ** t)
        ws.append(0.5 * (b - a) * gw * norm.pdf(t))
    return np.concatenate(xs), np.concatenate(ws)


def map_population_mean(phis: Sequence[float], slopes: Sequence[float], ratio: np.ndarray,
                        diameter: tuple[float, float], slope: tuple[float, float], m: int = 16) -> float:
    """E[I_D/I_S] of independent log-normal diameter and slope (median, geometric standard deviation each) over
    the map ratio[i, j] at phis[i] x slopes[j] (:func:`map_interpolant`), by :func:`map_rule` on both axes."""
    f = map_interpolant(phis, slopes, ratio)
    xd, wd = map_rule(*diameter, phis, m)
    xs, ws = map_rule(*slope, slopes, m)
    P, S = np.meshgrid(xd, xs, indexing="ij")
    return float(np.sum(np.outer(wd, ws) * f(P, S)))


def mass_outside(lo: float, hi: float, median: float, gsd: float) -> float:
    """Probability that a log-normal (median, gsd) variable falls outside [lo, hi]."""
    from scipy.stats import norm

    s = np.log(gsd)
    if s == 0:
        return 0.0 if lo <= median <= hi else 1.0
    return float(norm.cdf(np.log(lo / median) / s) + norm.sf(np.log(hi / median) / s))
