"""Coulomb's law on a set of contact elements, shared by the dense and the matrix-free exact solvers
(:mod:`femcheck.cect.exact`, :mod:`femcheck.cect.tangential_fft`).

Element by element, with traction bound g = mu pn: |p_t| <= g; |p_t| < g => s = 0 (adhesion); s != 0 =>
p_t = -g s/|s| (slip). Written as the fixed point p = Proj_{|q|<=g}(p - r s(p)) (an Alart-Curnier-type
reformulation) whose semi-smooth Newton derivative needs the derivative of the disc projection; the merit
function is |F|^2 with a non-monotone line search.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

NONMONOTONE_MEMORY = 8


@dataclass
class TangentialResult:
    """Tangential solution on the contact elements (like scipy's OptimizeResult).

    ``p`` (2, C) tractions px, py (Pa) on the C contact elements, ``slip`` (2, C) relative slip s (rolling: slip
    velocity / V, -; shift: m), ``stick`` (C,) adhesion mask, ``shift`` (2,) rigid shift (m; shift problems),
    ``iterations`` Newton steps, ``residual`` max |F| / max g, ``converged``, ``linear_iterations`` GMRES
    iterations summed over the Newton steps (matrix-free solver only; 0 for the dense LU).
    """

    p: np.ndarray
    slip: np.ndarray
    stick: np.ndarray
    shift: np.ndarray | None
    iterations: int
    residual: float
    converged: bool = True
    linear_iterations: int = 0


def project_disc(z: np.ndarray, g: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Projection of the (2, C) vectors z onto the discs |q| <= g; returns (proj, |z|, inside mask)."""
    nz = np.hypot(z[0], z[1])
    inside = nz <= g
    scale = np.where(inside, 1.0, g / np.where(nz > 0, nz, 1.0))
    return z * scale, nz, inside


def coulomb_residual(p: np.ndarray, s: np.ndarray, r, g: np.ndarray, load: np.ndarray | None,
                     cell_area: float) -> tuple[np.ndarray, tuple]:
    """Residual F of the Coulomb law as the fixed point p = Proj_g(p - r s) (tractions p (2, C) in Pa, slips
    s (2, C), regularisation r in Pa per unit slip, bounds g = mu pn); with ``load`` (shift problem) the force
    balance cell_area * sum(p) = load is appended, scaled so that a force error reads like a traction error.
    Returns (F, (z, |z|, inside, s)) with z = p - r s, the state the Newton derivative needs."""
    z = p - r * s
    proj, nz, inside = project_disc(z, g)
    F = (p - proj).ravel()
    if load is not None:
        F = np.concatenate([F, (cell_area * p.sum(axis=1) - load) / (cell_area * p.shape[1])])
    return F, (z, nz, inside, s)


def projection_derivative(z: np.ndarray, nz: np.ndarray, inside: np.ndarray, g: np.ndarray):
    """Per-element 2 x 2 derivative of the projection onto the disc |q| <= g at z: I inside, (g/|z|)(I - n n^T)
    outside, n = z/|z|. Returns (pxx, pyy, pxy, nx, ny)."""
    nzs = np.where(nz > 0, nz, 1.0)
    ex, ey = z[0] / nzs, z[1] / nzs
    fac = np.where(inside, 1.0, g / nzs)
    pxx = np.where(inside, 1.0, fac * (1.0 - ex * ex))
    pyy = np.where(inside, 1.0, fac * (1.0 - ey * ey))
    pxy = np.where(inside, 0.0, -fac * ex * ey)
    return pxx, pyy, pxy, ex, ey


def nonmonotone_step(x: np.ndarray, dx: np.ndarray, residual_vec: Callable, merits: list[float],
                     first: bool) -> tuple[np.ndarray, np.ndarray, object, float]:
    """Back-track along the Newton step ``dx`` until the merit |F|^2 improves on the worst of the last
    NONMONOTONE_MEMORY merits (Grippo, Lampariello & Lucidi 1986). A monotone search cut most steps here (the
    active set of the Coulomb law then grows by one ring of elements per step); the full steps converge in a
    few. The first step from p = 0 is the full-adhesion solution: taken whole whatever its merit. Returns
    (x, F, aux, merit) at the accepted point."""
    step = 1.0
    reference = np.inf if first else max(merits[-NONMONOTONE_MEMORY:])
    for _ in range(40):
        x_new = x + step * dx
        F_new, aux_new = residual_vec(x_new)
        m_new = float(F_new @ F_new)
        if m_new < (1.0 - 1e-4 * step) * reference or m_new == 0.0:
            break
        step *= 0.5
    return x_new, F_new, aux_new, m_new
