"""Outputs of an EHL solution (spec §A.6; seed 004 Figs 2.9 and 3.13 are missing, so the definitions are here).

- H_c = H(0, 0) (central film), H_m = min H over the pressurised nodes (side lobes), P_max and its X (the
  outlet spike).
- Additional pressure dP = P_indented - P_smooth on the same grid at the same T. Seed 004 gives the amplitudes
  "over the shoulders" of the indent (§3.3.1, Fig 3.16: the rear shoulder) and neglects the outlet Newtonian
  pressure spike (§3.3.1 after Table 3.4, and its conclusion). The shoulder zone: along rays from the indent
  centre (X_D, Y_D) out to r = 1.5 Phi, dP read outwards up to its first positive local maximum beyond the hole's
  edge r = Phi/2, plus one cell. dP_FRONT, dP_REAR, dP_LAT are the largest nodal dP of that zone downstream
  (X - X_D > |Y - Y_D|, "first in the contact"), upstream (X_D - X > |Y - Y_D|) and on the sides
  (|Y - Y_D| >= |X - X_D|); the amplitude is the largest of the three (where the disc holds nothing beyond the
  shoulders it equals the maximum of dP, the dry model's single amplitude). dP_CENT = min dP in the hole
  (r <= Phi/2, negative).
- ``disc_max``: max dP over the whole disc r <= 1.5 Phi. It is not an amplitude: for an indent as large as the
  contact it also catches features beyond the shoulders -- at M = 50, L = 8, Phi = 1 the outlet spike, which the
  indent shifts 0.03 b downstream, gives dP = 0.17 / 0.28 / 0.43 p_H on 65^2 / 129^2 / 257^2, one or two cells
  wide (shoulders 0.10; README, EHL) -- and is kept for the record only.
"""
from __future__ import annotations

import numpy as np
from scipy.ndimage import map_coordinates


def film_measures(x: np.ndarray, y: np.ndarray, P: np.ndarray, H: np.ndarray) -> dict[str, float]:
    i0, j0 = int(np.argmin(np.abs(x))), int(np.argmin(np.abs(y)))
    pos = P > 0
    i, _ = np.unravel_index(int(np.argmax(P)), P.shape)
    return {"H_central": float(H[i0, j0]), "H_min": float(H[pos].min()) if pos.any() else float("nan"),
            "P_max": float(P.max()), "X_spike": float(x[i])}


def shoulder_peaks(x: np.ndarray, y: np.ndarray, dP: np.ndarray, xd: float, yd: float, reach: float,
                   start: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Along rays from (xd, yd) (angles ``theta``, spacing at most one cell at r = ``reach``; dP bilinear, sampled
    every half cell out to ``reach``): the first positive local maximum of dP at r >= ``start`` (``peak``, NaN on a
    ray without one) and its radius ``r_peak``."""
    h = x[1] - x[0]
    nray = 8 * max(1, int(np.ceil(2.0 * np.pi * reach / (8.0 * h))))
    theta = 2.0 * np.pi * np.arange(nray) / nray
    s = np.arange(0.0, reach + 1e-12 * reach, 0.5 * h)
    ix = (xd + np.outer(np.cos(theta), s) - x[0]) / h
    iy = (yd + np.outer(np.sin(theta), s) - y[0]) / (y[1] - y[0])
    q = map_coordinates(dP, [ix, iy], order=1, mode="nearest")
    mid = q[:, 1:-1]
    peak = (mid > 0) & (mid >= q[:, :-2]) & (mid > q[:, 2:]) & (s[1:-1] >= start)
    found = peak.any(axis=1)
    first = np.argmax(peak, axis=1) + 1
    rows = np.arange(nray)
    return theta, np.where(found, q[rows, first], np.nan), np.where(found, s[first], np.nan)


def additional_pressure(x: np.ndarray, y: np.ndarray, dP: np.ndarray, xd: float, yd: float,
                        phi: float) -> dict[str, float]:
    """dP amplitudes (dimensionless, as dP) around an indent centred at (xd, yd) of diameter phi."""
    reach = 1.5 * phi
    # the shoulders lie outside the hole, r > Phi/2 (eq 2.16: the height changes sign at r = Phi/2); an EHL hole
    # can carry small positive ripples that are not shoulders
    theta, _, r_peak = shoulder_peaks(x, y, dP, xd, yd, reach, start=0.5 * phi)
    X, Y = np.meshgrid(x - xd, y - yd, indexing="ij")
    r = np.hypot(X, Y)
    ray = np.rint(np.mod(np.arctan2(Y, X), 2.0 * np.pi) / (2.0 * np.pi) * theta.size).astype(int) % theta.size
    limit = r_peak[ray] + (x[1] - x[0])              # NaN (no shoulder on the ray) compares False
    zone = (r <= limit) & (r <= reach)

    def largest(mask):
        m = zone & mask
        return float(dP[m].max()) if m.any() else float("nan")

    out = {"front": largest(X > np.abs(Y)), "rear": largest(-X > np.abs(Y)), "lateral": largest(np.abs(Y) >= np.abs(X))}
    sides = [v for v in out.values() if np.isfinite(v)]
    out["amplitude"] = max(sides) if sides else float("nan")
    hole, near = r <= 0.5 * phi, r <= reach
    out["centre"] = float(dP[hole].min()) if hole.any() else float("nan")
    out["disc_max"] = float(dP[near].max()) if near.any() else float("nan")
    return out
