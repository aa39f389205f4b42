"""Convergence certificates from four or more mesh levels whose values scatter: least-squares power-series fits
(Eca & Hoekstra, J. Comput. Phys. 262, 2014, 104-130, §3-4).

Three-level Richardson extrapolation (:mod:`femcheck.solvers.convergence`) assumes the values follow
q(h) = q0 + alpha h^p exactly. On unstructured meshes that are not nested (every Gmsh level is meshed anew) a
local quantity also carries a mesh-to-mesh scatter: where the contact edge falls between nodes, how the mesh is
oriented near the centre. Three levels cannot tell the scatter from the trend, and the observed order swings.
Eca and Hoekstra fit the expansion to all levels in the least-squares sense and let the fit's standard
deviation carry the scatter into the uncertainty:

* fits: q0 + alpha h^p (p free), q0 + alpha h, q0 + alpha h^2 and q0 + alpha1 h + alpha2 h^2;
* the free-order fit is used when its order lies in [0.5, formal + 0.1); otherwise the fixed-order fit with the
  smallest standard deviation;
* error estimate eps = |q_fine - q0|; data range Delta = max |q_i - q_j|; standard deviation sigma of the fit;
* uncertainty U = Fs eps + sigma + |q_fine - fit(h_fine)| with Fs = 1.25 when the order is in range and 3
  otherwise, when sigma < Delta; else U = 3 (sigma / Delta) (eps + sigma + |q_fine - fit(h_fine)|) (their eq. 30).

The certificate (femcheck's :class:`femcheck.solvers.convergence.Certificate`) is "certified" when the free-order
fit is in range and sigma < Delta: the levels converge at an order the discretisation can have, with a
scatter smaller than the trend. Its value is then the extrapolated q0, else the finest level; its
``error_estimate`` is U / |value| (relative), never below twice the finest level's own standard error when
the levels carry one.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import minimize_scalar

from .convergence import Certificate

SAFETY_IN_RANGE = 1.25       # Eca & Hoekstra 2014 §4 (Roache's GCI factor), order in range and sigma < Delta
SAFETY_OUT_OF_RANGE = 3.0
MIN_ORDER = 0.5


def _fit(cols: list[np.ndarray], q: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """Least squares q ~ c0 + sum c_k cols[k]: (coefficients, fitted values, standard deviation)."""
    A = np.column_stack([np.ones_like(q)] + cols)
    c, *_ = np.linalg.lstsq(A, q, rcond=None)
    fit = A @ c
    dof = max(q.size - A.shape[1], 1)
    return c, fit, float(np.sqrt(np.sum((q - fit) ** 2) / dof))


def _free_order(h: np.ndarray, q: np.ndarray, max_order: float) -> tuple[float, np.ndarray, np.ndarray, float]:
    """q0 + alpha h^p with p minimising the residual over (0.05, max_order)."""
    hs = h / h.max()

    def rss(p):
        _, fit, _ = _fit([hs**p], q)
        return float(np.sum((q - fit) ** 2))

    p = float(minimize_scalar(rss, bounds=(0.05, max_order), method="bounded",
                              options={"xatol": 1e-6}).x)
    c, fit, sigma = _fit([hs**p], q)
    return p, c, fit, sigma


def certify_least_squares(h: list[float], q: list[float], formal_order: float = 2.0,
                          sigma_levels: list[float] | None = None) -> Certificate:
    """Certificate of a quantity on four or more levels of mesh size ``h`` (any order, any ratios) with values
    ``q``; ``formal_order`` the discretisation's order for the quantity; ``sigma_levels`` the standard errors
    of the levels' values when they are estimated from scattered samples (module docstring)."""
    h = np.asarray(h, dtype=float)
    q = np.asarray(q, dtype=float)
    if h.size < 4 or h.size != q.size:
        raise ValueError("the least-squares certificate needs at least four levels, one value each")
    fine = int(np.argmin(h))
    q_fine = float(q[fine])
    scale = abs(q_fine) if q_fine != 0 else 1.0
    delta_m = float(q.max() - q.min())
    floor = 2.0 * float(sigma_levels[fine]) if sigma_levels is not None else 0.0
    if delta_m == 0.0:
        return Certificate(q_fine, q_fine, None, floor / scale, False, "all levels equal: the quantity does not see "
                           "the mesh")
    hs = h / h.max()
    p, c, fit, sigma = _free_order(h, q, max(2.0 * formal_order, 4.0))
    in_range = MIN_ORDER <= p < formal_order + 0.1
    how = f"least-squares order {p:.2f}"
    if not in_range:
        fixed = {"h": [hs], "h^2": [hs**2], "h + h^2": [hs, hs**2]}
        fits = {k: _fit(cols, q) for k, cols in fixed.items()}
        name = min(fits, key=lambda k: fits[k][2])
        c, fit, sigma = fits[name]
        how += f" outside [{MIN_ORDER}, {formal_order + 0.1:g}); fixed-order fit {name}"
    q0 = float(c[0])
    eps = abs(q_fine - q0)
    resid = abs(q_fine - float(fit[fine]))
    if sigma < delta_m:
        fs = SAFETY_IN_RANGE if in_range else SAFETY_OUT_OF_RANGE
        u = fs * eps + sigma + resid
    else:
        u = 3.0 * sigma / delta_m * (eps + sigma + resid)
    certified = in_range and sigma < delta_m
    value = q0 if certified else q_fine
    u = max(u, floor)
    note = (f"{how}; fit standard deviation {sigma / scale:.1e} vs data range {delta_m / scale:.1e} "
            f"({h.size} levels, Eca & Hoekstra 2014)")
    if not certified:
        note += ": not in the asymptotic range" if not in_range else ": scatter as large as the trend"
    return Certificate(value, q_fine, p if in_range else None, float(u / (abs(value) or 1.0)), certified, note)


def certify_levels_lsq(levels: list[dict], names: tuple[str, ...] | list[str], formal_order: dict[str, float],
                       h_key: str = "h") -> dict[str, Certificate]:
    """:func:`certify_least_squares` for each quantity over level dicts (coarse to fine), with the levels'
    ``<name>_std`` when all carry one."""
    h = [lv[h_key] for lv in levels]
    out = {}
    for n in names:
        s = [lv.get(f"{n}_std") for lv in levels]
        out[n] = certify_least_squares(h, [lv[n] for lv in levels], formal_order.get(n, 2.0),
                                       s if all(x is not None for x in s) else None)
    return out
