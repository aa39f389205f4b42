"""Bound-constrained conjugate gradient for frictionless normal contact (Polonsky & Keer, Wear 231, 1999).

Solves, on a grid of cells of area A, for p >= 0 with  g = h + K p - delta >= 0,  p g = 0  and the load
constraint A sum(p) = F. h is the initial gap (m), K p the elastic normal displacement (m, positive into the
bodies, so it opens the gap), delta the rigid approach (m). Works in any dimension: K is any
linear operator on arrays of the grid's shape (e.g. :class:`femcheck.bem.convolution.DCFFT`).
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import ConvergenceError


@dataclass
class NormalContactResult:
    """Solution of the normal contact problem, in the spirit of ``scipy.optimize.OptimizeResult``.

    ``pressure`` (Pa) and ``gap`` (m) on the grid, ``contact`` mask, ``approach`` delta (m), ``iterations``,
    ``residual`` (max of rms gap on the contact set and largest penetration outside it, relative to the gap
    scale), ``load`` = A sum(p) (N or N/m), ``time_s``.
    """

    pressure: np.ndarray
    gap: np.ndarray
    contact: np.ndarray
    approach: float
    iterations: int
    residual: float
    load: float
    time_s: float
    converged: bool = True


def _residual(g: np.ndarray, contact: np.ndarray, allowed: np.ndarray, scale: float) -> float:
    rms = np.sqrt(np.mean(g[contact] ** 2)) if contact.any() else np.inf
    free = allowed & ~contact
    pen = max(0.0, -float(g[free].min())) if free.any() else 0.0
    return float(max(rms, pen) / scale)


def _self_compliance(operator: Callable[[np.ndarray], np.ndarray], h: np.ndarray) -> float:
    """Displacement of a cell under unit pressure on itself (m/Pa), at the grid centre."""
    unit = np.zeros_like(h)
    unit[tuple(n // 2 for n in h.shape)] = 1.0
    return float(operator(unit).max())


def polonsky_keer(h: np.ndarray, operator: Callable[[np.ndarray], np.ndarray], load: float | None,
                  cell_area: float, p0: np.ndarray | None = None, tol: float = 1e-10, max_iter: int = 1000,
                  approach: float | None = None,
                  preconditioner: Callable[[np.ndarray], np.ndarray] | None = None) -> NormalContactResult:
    """Polonsky-Keer CG under load control (``load`` given) or approach control (``approach`` given).

    Load control: the rigid approach is the mean gap over the contact set and p is rescaled after every step so
    that A sum(p) = F (Polonsky & Keer 1999, §3). Approach control: delta is fixed, the gap is h + K p - delta
    without the mean removed and no rescaling (their displacement-driven variant); the load is an output.
    Parameters: ``h`` initial gap (m) on the grid; ``operator`` p -> surface displacement (m); ``load`` total
    force F (N, or N/m in 2D); ``cell_area`` A (m^2, or m in 2D); ``p0`` warm start (Pa); ``tol`` on the
    relative gap residual. Raises :class:`ConvergenceError` if ``max_iter`` is reached.

    ``preconditioner`` (optional) maps a gap residual to a pressure correction, an approximate inverse of
    ``operator`` such as :class:`femcheck.bem.convolution.CirculantPreconditioner`. It is applied to the residual
    restricted to the contact set and its result restricted again (and, under load control, projected onto zero
    mean so that the load is unchanged), so CG keeps working on the symmetric system of the contact set:
    PK's direction t = g + (G/G_old) t becomes t = z + (g.z / g_old.z_old) t with z = M g.
    """
    if (load is None) == (approach is None):
        raise ValueError("give exactly one of load (load control) or approach (approach control)")
    t0 = time.perf_counter()
    h = np.asarray(h, dtype=float)
    allowed = np.isfinite(h)            # +inf gap: no surface there (beyond a roller's end)
    if not allowed.any():
        raise ValueError("the gap is infinite everywhere: nothing can touch")
    h = np.where(allowed, h, 0.0)
    scale = float(np.ptp(h[allowed])) or 1.0
    if p0 is not None and np.clip(p0, 0.0, None).sum() > 0:
        p = np.where(allowed, np.clip(np.array(p0, dtype=float), 0.0, None), 0.0)
    elif load is not None:
        p = np.where(allowed & (h <= np.quantile(h[allowed], 0.05)), 1.0, 0.0)
    else:
        # start from the overlap divided by the self-compliance of a cell: a Winkler-like first guess
        p = np.where(allowed, np.clip(approach - h, 0.0, None), 0.0) / _self_compliance(operator, h)
        if p.sum() <= 0:
            raise ValueError("the approach does not close the gap anywhere: no contact")
    if load is not None:
        p *= load / (cell_area * p.sum())
    t = np.zeros_like(p)
    g_old, restart = 1.0, True
    residual = np.inf
    for it in range(1, max_iter + 1):
        g = h + operator(p)
        contact = p > 0
        delta = float(g[contact].mean()) if load is not None else approach
        g -= delta
        residual = _residual(g, contact, allowed, scale)
        if residual < tol:
            return NormalContactResult(p, g, contact, delta, it, residual, float(cell_area * p.sum()),
                                       time.perf_counter() - t0)
        if preconditioner is None:
            z = g
        else:
            z = np.where(contact, preconditioner(np.where(contact, g, 0.0)), 0.0)
            if load is not None:
                z[contact] -= z[contact].mean()
        G = float(np.dot(g[contact], z[contact]))
        t = np.where(contact, z + (0.0 if restart else G / g_old) * t, 0.0)
        g_old = G
        r = operator(t)
        if load is not None:
            r -= r[contact].mean()
        denom = float(np.dot(r[contact], t[contact]))
        tau = float(np.dot(g[contact], t[contact])) / denom if denom != 0 else 0.0
        p = p - tau * t
        p[p < 0] = 0.0
        overlap = allowed & (p == 0) & (g < 0)
        restart = bool(overlap.any())
        if restart:
            if tau > 0:
                p[overlap] -= tau * g[overlap]
            else:
                # The gap is uniform over the contact set (e.g. a symmetric start of two cells), so the CG step
                # vanishes and PK's overlap correction -tau g with it: seed the penetrating cells with the
                # Winkler estimate -g / k0 instead, k0 being one cell's self-compliance.
                p[overlap] = -g[overlap] / _self_compliance(operator, h)
        total = p.sum()
        if total <= 0:
            raise ConvergenceError("Polonsky-Keer CG", it, residual, tol, "pressure vanished")
        if load is not None:
            p *= load / (cell_area * total)
    raise ConvergenceError("Polonsky-Keer CG", max_iter, residual, tol)
