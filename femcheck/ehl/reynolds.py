"""Discrete Reynolds operator of the dimensionless EHL problem (seed 004 eqs 2.14-2.15, App. A; spec §A.4):

    d/dX(eps dP/dX) + d/dY(eps dP/dY) - d(rho H)/dX - d(rho H)/dT = 0,   eps = rho H^3/(eta lambda_bar)

on a uniform node grid (spacing h in X and Y), P = 0 on the boundary.

Poiseuille part, conservative 5-point (faces eps_{i+-1/2} = mean of the two nodes, applied with 1/h^2 once: the
double rh^2 of App. A.2-A.3 is a slip):
    Q_ij = [eps_E (P_{i+1} - P_i) - eps_W (P_i - P_{i-1}) + eps_N (P_{j+1} - P_j) - eps_S (P_j - P_{j-1})]/h^2

Wedge + squeeze, the NU2 scheme (App. A as re-derived in the spec), r = rho H at time levels k, k-1, k-2:
    W = wX (1.5 r_i - 2 r_{i-1} + 0.5 r_{i-2})_k + wD (1.5 r_{i,k} - 2 r_{i-1,k-1} + 0.5 r_{i-2,k-2})
        + wT (1.5 r_{i,k} - 2 r_{i,k-1} + 0.5 r_{i,k-2})
with (wX, wD, wT) = (1/h, 0, 0) steady, (1/h - 1/hT, 1/hT, 0) if h <= hT, (0, 1/h, 1/hT - 1/h) if h > hT.
Each is a second-order approximation of dr/dX + dr/dT; the "diagonal" BDF2 along (h, hT) makes W vanish exactly
on any film translating at unit speed when hT = h (no numerical damping of a travelling indent). The first
interior line i = 1 uses first-order upwind differences (1, -1, 0) in place of (1.5, -2, 0.5).

The discrete equation at interior nodes is Q - W = f (f: FAS right-hand side; zero on the finest grid).
"""
from __future__ import annotations

import numpy as np

STENCIL = (1.5, -2.0, 0.5)     # BDF2 upwind
STENCIL_FIRST = (1.0, -1.0, 0.0)


def time_weights(h: float, ht: float | None) -> tuple[float, float, float]:
    """(wX, wD, wT) of the NU2 scheme for mesh size h and time step ht (None: steady)."""
    if ht is None:
        return 1.0 / h, 0.0, 0.0
    if h <= ht:
        return 1.0 / h - 1.0 / ht, 1.0 / ht, 0.0
    return 0.0, 1.0 / h, 1.0 / ht - 1.0 / h


def wedge_squeeze(r: np.ndarray, r1: np.ndarray | None, r2: np.ndarray | None, h: float,
                  ht: float | None) -> np.ndarray:
    """W at the nodes i >= 1 (axis 0 = X, the rolling direction); W[0] = 0. r, r1, r2: rho H at the new and the
    two previous time levels (r1, r2 unused when steady)."""
    wX, wD, wT = time_weights(h, ht)
    W = np.zeros_like(r)
    a0, a1, a2 = STENCIL
    W[2:] = wX * (a0 * r[2:] + a1 * r[1:-1] + a2 * r[:-2])
    W[1] = wX * (r[1] - r[0])
    if wD:
        W[2:] += wD * (a0 * r[2:] + a1 * r1[1:-1] + a2 * r2[:-2])
        W[1] += wD * (r[1] - r1[0])
    if wT:
        W[1:] += wT * (a0 * r[1:] + a1 * r1[1:] + a2 * r2[1:])
    return W


def faces(eps: np.ndarray, h: float) -> tuple[np.ndarray, ...]:
    """Face coefficients eps_{i+1/2}/h^2, eps_{i-1/2}/h^2, eps_{j+1/2}/h^2, eps_{j-1/2}/h^2 at interior nodes."""
    c = eps[1:-1, 1:-1]
    s = 0.5 / (h * h)
    return ((c + eps[2:, 1:-1]) * s, (c + eps[:-2, 1:-1]) * s, (c + eps[1:-1, 2:]) * s, (c + eps[1:-1, :-2]) * s)


def poiseuille(P: np.ndarray, eps: np.ndarray, h: float) -> np.ndarray:
    """Q at interior nodes (shape (n-1, n-1))."""
    e, w, nn, s = faces(eps, h)
    c = P[1:-1, 1:-1]
    return e * (P[2:, 1:-1] - c) - w * (c - P[:-2, 1:-1]) + nn * (P[1:-1, 2:] - c) - s * (c - P[1:-1, :-2])


def operator(P: np.ndarray, eps: np.ndarray, r: np.ndarray, r1, r2, h: float, ht: float | None) -> np.ndarray:
    """L(P) = Q - W on the full grid (zero on the boundary)."""
    out = np.zeros_like(P)
    out[1:-1, 1:-1] = poiseuille(P, eps, h) - wedge_squeeze(r, r1, r2, h, ht)[1:-1, 1:-1]
    return out
