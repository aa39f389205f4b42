"""Rolling-contact fatigue life from a stress-amplitude history: risk integral, Weibull life, weakest link, the
life ratio of a dented track, and the load-life exponents of a smooth Hertzian contact.

Source: Biboulet 2008 (seed 004) ch. 4, as cleaned in the shared spec ``specs/ehl-life.md`` part B. The thesis'
printed eqs 4.1-4.2 drop the exponential of the Weibull law and eq 4.7 has the wrong sign; the forms below are the
corrected ones.

Risk integral (eqs 4.2-4.4; Ioannides-Harris with a fatigue limit, Lubrecht's variant without depth weight)

    I = sum over the volume of max(tau - tau_inf, 0)^c  w_h(z)  dV            (Pa^c m^(3 - h))
    w_h(z) = max(z, Z_FLOOR b)^(-h)   (m^-h; h = 0 is the thesis' choice, h > 0 reproduces Lundberg-Palmgren)

tau is the stress-amplitude history (here: the largest von Mises stress a material point sees in a rolling pass),
tau_inf the fatigue limit (Pa). The depth weight needs a floor because z^-h is not integrable at the surface for
h >= 1 (Lubrecht, Jacobson & Ioannides 1990); the floor scales with the contact size b, so the self-similarity of
Hertzian contacts (hence the load-life exponents below) is kept.

Weibull life (eqs 4.7-4.10 corrected): an element i of the track with risk integral I_i has survival
S_i(L) = (1 - theta)^((L / L_i)^e) (failure probability theta at L = L_i) with L_i^-e proportional to I_i; the
track fails when its first element fails (weakest link), so S = prod S_i and L^-e = sum L_i^-e.

Relative life: only ratios of lives are physical (the constant of eq 4.2 is a material constant). femcheck reports
the life of one unit of *track length* (the risk per unit length of the raceway, which is what a bearing ring
carries), L = (R / R_REF)^(-1/e), R = I / l_w the risk per unit track length (l_w: the integration window's
length in the rolling direction), R_REF = (1 GPa)^c (1 mm)^(2 - h): the life of 1 mm of track relative to a 1 mm^2
cross-section stressed 1 GPa above the fatigue limit. L = inf when nothing exceeds the fatigue limit.

Load-life exponents (spec B.5, self-similarity of a smooth Hertzian contact, tau_inf = 0): point contact
L ~ Q^-(c - h + 2)/(3e), line contact of fixed length L ~ Q^-(c - h + 1)/(2e). Lundberg-Palmgren's c = 31/3,
h = 7/3, e = 10/9 (point) or 9/8 (line) give 3 and 4 (ISO 281); so do c = 8, h = 0 (the defaults here).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..errors import InputError

Z_FLOOR = 0.05                 # depth-weight floor, in units of the contact semi-axis b (h > 0 only)
REFERENCE_STRESS = 1e9         # Pa: R_REF = REFERENCE_STRESS^c REFERENCE_LENGTH^(2 - h)
REFERENCE_LENGTH = 1e-3        # m
LP_POINT = {"c": 31.0 / 3.0, "h": 7.0 / 3.0, "e": 10.0 / 9.0}      # Lundberg-Palmgren, ball (point) contact
LP_LINE = {"c": 31.0 / 3.0, "h": 7.0 / 3.0, "e": 9.0 / 8.0}        # roller (line) contact
C_MAX = 25.0                   # (5 GPa)^25 m^3 stays far from float overflow


@dataclass(frozen=True)
class LifeConstants:
    """Stress exponent c, Weibull slope e, depth exponent h and fatigue limit tau_inf (Pa) (spec B.4; defaults
    c = 8, h = 0, e = 10/9 keep the Lundberg-Palmgren load-life exponents without a depth weight)."""

    c: float = 8.0
    e: float = 10.0 / 9.0
    h: float = 0.0
    fatigue_limit: float = 0.0

    def __post_init__(self):
        check_constants(self.c, self.e, self.h, self.fatigue_limit)


def check_constants(c: float, e: float, h: float, fatigue_limit: float, prefix: str = "life.") -> None:
    """One InputError naming the first bad constant and its allowed range."""
    for key, v, ok, allowed in (("c", c, 1.0 <= c <= C_MAX, f"[1, {C_MAX:g}]"), ("e", e, 0.0 < e <= 10.0, "(0, 10]"),
                                ("h", h, 0.0 <= h <= 10.0, "[0, 10]"),
                                ("fatigue_limit", fatigue_limit, 0.0 <= fatigue_limit < np.inf, "[0, inf) Pa")):
        if not np.isfinite(v) or not ok:
            raise InputError(prefix + key, f"{v} is not allowed; allowed: {allowed}")


def risk_density(tau: np.ndarray, fatigue_limit: float, c: float) -> np.ndarray:
    """max(tau - tau_inf, 0)^c (Pa^c), the integrand of eq 4.2/4.3."""
    return np.maximum(np.asarray(tau, dtype=float) - fatigue_limit, 0.0) ** c


def depth_weight(z: np.ndarray, h: float, b: float) -> np.ndarray:
    """max(z, Z_FLOOR b)^-h (m^-h): the Lundberg-Palmgren / Ioannides-Harris depth weight, 1 for h = 0."""
    z = np.asarray(z, dtype=float)
    if h == 0.0:
        return np.ones_like(z)
    return np.maximum(z, Z_FLOOR * b) ** (-h)


def depth_planes(z_max: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Depth planes z_k = z_max (k/n)^2, k = 1..n, and their quadrature weights (m).

    The trapezoid rule in s = sqrt(z / z_max) (uniform s, dz = 2 z_max s ds): planes crowd at the surface, where
    an indent's stresses peak, and the rule stays second order because z(s) is smooth; the s = 0 plane carries
    zero weight and is not evaluated. The weights sum to z_max exactly."""
    if n < 2:
        raise InputError("numerics.life_depths", f"{n} is not allowed; allowed: at least 2 depth planes")
    s = np.arange(1, n + 1) / n
    w = 2.0 * z_max * s / n
    w[-1] *= 0.5
    return z_max * s * s, w


def window_weights(centres: np.ndarray, spacing: float, half: float, centre: float = 0.0) -> np.ndarray:
    """Length (m) of each cell [x - dx/2, x + dx/2] inside the window [centre - half, centre + half]: exact window
    length for any half-width, not only multiples of the cell size."""
    x = np.asarray(centres, dtype=float) - centre
    return np.clip(np.minimum(x + 0.5 * spacing, half) - np.maximum(x - 0.5 * spacing, -half), 0.0, spacing)


def risk_integral(tau: np.ndarray, weights: np.ndarray, constants: LifeConstants,
                  depth_factor: np.ndarray | None = None) -> float:
    """sum tau-density x quadrature weight (x depth weight): the discrete eq 4.3 (Pa^c m^(3 - h)).

    ``tau`` and ``weights`` broadcast (e.g. tau[k, i, j] with weights wz[k] wx[i] wy[j]); ``depth_factor`` (same
    broadcasting) is :func:`depth_weight` of the planes, needed only for h > 0."""
    f = risk_density(tau, constants.fatigue_limit, constants.c) * weights
    if depth_factor is not None and constants.h != 0.0:
        f = f * depth_factor
    return float(np.sum(f))


def relative_life(risk_per_length: float, constants: LifeConstants) -> float:
    """Life of one unit of track length, L = (R / R_REF)^(-1/e) (module docstring); inf when R = 0."""
    if risk_per_length < 0 or not np.isfinite(risk_per_length):
        raise ValueError(f"risk per track length must be finite and >= 0, got {risk_per_length}")
    if risk_per_length == 0.0:
        return np.inf
    # logarithms: R and R_REF are both ~1e60 for c = 8; their ratio is what matters
    log_ref = constants.c * np.log(REFERENCE_STRESS) + (2.0 - constants.h) * np.log(REFERENCE_LENGTH)
    return float(np.exp(-(np.log(risk_per_length) - log_ref) / constants.e))


def dimensionless_risk(risk: float, p_hertz: float, b: float, constants: LifeConstants) -> float:
    """I-bar = (I / (b^(3 - h) p_H^c))^(1/c), the thesis' dimensionless risk integral (notation list, eq 4.3)."""
    return float((risk / (b ** (3.0 - constants.h) * p_hertz ** constants.c)) ** (1.0 / constants.c))


# ---------------------------------------------------------------------------------------------------------------
# Weibull law and the weakest link (eqs 4.7-4.10, corrected)
# ---------------------------------------------------------------------------------------------------------------

def survival(life: float | np.ndarray, life_theta: float, e: float, theta: float = 0.1) -> np.ndarray:
    """S(L) = (1 - theta)^((L / L_theta)^e): eq 4.7 with the sign fixed (failure probability theta at L_theta;
    the printed form gives a survival above 1)."""
    if not 0.0 < theta < 1.0:
        raise ValueError(f"theta must be in (0, 1), got {theta}")
    if np.isinf(life_theta):
        return np.ones_like(np.asarray(life, dtype=float))
    return np.exp(np.log1p(-theta) * (np.asarray(life, dtype=float) / life_theta) ** e)


def failure_probability(life, life_theta: float, e: float, theta: float = 0.1) -> np.ndarray:
    """F(L) = 1 - S(L) (eq 4.7 corrected), without cancellation for small F."""
    if np.isinf(life_theta):
        return np.zeros_like(np.asarray(life, dtype=float))
    return -np.expm1(np.log1p(-theta) * (np.asarray(life, dtype=float) / life_theta) ** e)


def weakest_link_life(lives: Sequence[float], e: float) -> float:
    """L^-e = sum L_i^-e (eq 4.9): the life at which the whole surface reaches the common failure probability
    theta when every element i reaches it at L_i. Infinite elements do not count; all infinite -> inf."""
    lives = np.asarray(lives, dtype=float)
    if np.any(lives <= 0):
        raise ValueError("element lives must be positive")
    finite = lives[np.isfinite(lives)]
    if finite.size == 0:
        return np.inf
    m = finite.min()       # scale out the smallest life: no overflow of L^-e for large e
    return float(m * np.sum((finite / m) ** (-e)) ** (-1.0 / e))


def life_ratio_from_risks(smooth_risks: Sequence[float], risks: Sequence[float], e: float) -> float:
    """L / L_S = (sum I_Si / sum I_i)^(1/e) (eq 4.10; I_i = p_Hi^c b_i^3 I-bar_i^c). Both sums zero: 1 (both
    lives infinite); only the smooth sum zero: 0 (the smooth track never fails, the dented one does)."""
    s, d = float(np.sum(smooth_risks)), float(np.sum(risks))
    if d == 0.0:
        return 1.0 if s == 0.0 else np.inf
    return (s / d) ** (1.0 / e)


def dented_life_ratio(risk_ratio: float, indent_fraction: float, e: float) -> float:
    """L / L_S = [1 + f_d ((I_D / I_S) - 1)]^(-1/e) (spec B.3, from eq 4.10): a track of windows of equal area,
    a fraction f_d of them holding one indent whose window has the risk integral I_D instead of I_S.

    ``risk_ratio`` = I_D / I_S = (I-bar_D / I-bar_S)^c (inf when I_S = 0 < I_D; 1 when both vanish)."""
    if not 0.0 <= indent_fraction <= 1.0:
        raise InputError("life.indent_fraction", f"{indent_fraction} is not allowed; allowed: [0, 1]")
    if risk_ratio < 0 or np.isnan(risk_ratio):
        raise ValueError(f"risk ratio must be >= 0, got {risk_ratio}")
    if indent_fraction == 0.0 or risk_ratio == 1.0:
        return 1.0
    if np.isinf(risk_ratio):
        return 0.0
    return float((1.0 + indent_fraction * (risk_ratio - 1.0)) ** (-1.0 / e))


def risk_ratio(dented: float, smooth: float) -> float:
    """I_D / I_S with the infinite-life cases made explicit (0/0 -> 1, x/0 -> inf)."""
    if smooth == 0.0:
        return 1.0 if dented == 0.0 else np.inf
    return dented / smooth


# ---------------------------------------------------------------------------------------------------------------
# Load-life exponents of a smooth Hertzian contact (spec B.5)
# ---------------------------------------------------------------------------------------------------------------

def load_life_exponent(c: float, h: float, e: float, contact: str) -> float:
    """n in L ~ Q^-n without fatigue limit: (c - h + 2)/(3e) for a point contact (p_H, b ~ Q^1/3, risk per track
    length ~ p_H^c b^(2 - h)), (c - h + 1)/(2e) for a line contact of fixed length (p_H, b ~ Q^1/2, risk per track
    length ~ p_H^c b^(1 - h))."""
    if contact == "point":
        return (c - h + 2.0) / (3.0 * e)
    if contact == "line":
        return (c - h + 1.0) / (2.0 * e)
    raise ValueError(f"contact must be 'point' or 'line', got {contact!r}")


def local_exponents(loads: Sequence[float], lives: Sequence[float]) -> np.ndarray:
    """-d ln L / d ln Q between consecutive loads (inf where the lighter load's life is infinite)."""
    q, life = np.log(np.asarray(loads, float)), np.asarray(lives, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return -np.diff(np.log(life)) / np.diff(q)


# ---------------------------------------------------------------------------------------------------------------
# Line contact: the stress-amplitude history of McEwen's closed form
# ---------------------------------------------------------------------------------------------------------------

def mcewen_history(half_width: float, p_max: float, nu: float, depths: np.ndarray,
                   samples: int = 4001) -> np.ndarray:
    """T_S(z) = max over x of the von Mises stress of a Hertz line contact at each depth (Pa): McEwen's closed form
    (Johnson eq 4.49, :func:`femcheck.analytic.stress.mcewen`) on a dense x grid over +/- 3a, the maximum polished
    by a parabola through its neighbours (error ~1e-9 relative at 4001 samples)."""
    from .stress import mcewen, von_mises

    a = half_width
    x = np.linspace(-3.0 * a, 3.0 * a, samples)
    z = np.asarray(depths, dtype=float)
    vm = von_mises(mcewen(x[None, :], z[:, None], a, p_max, nu))
    k = np.clip(np.argmax(vm, axis=1), 1, samples - 2)
    rows = np.arange(z.size)
    f0, f1, f2 = vm[rows, k - 1], vm[rows, k], vm[rows, k + 1]
    curv = f0 - 2.0 * f1 + f2
    with np.errstate(divide="ignore", invalid="ignore"):
        peak = np.where(curv < 0, f1 - (f2 - f0) ** 2 / (8.0 * curv), f1)
    return np.maximum(peak, f1)
