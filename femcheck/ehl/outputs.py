"""Outputs of an EHL solution (spec §A.6; seed 004 Figs 2.9 and 3.13 are missing, so the definitions are here).

- H_c = H(0, 0) (central film), H_m = min H over the pressurised nodes (side lobes), P_max and its X (the
  outlet spike).
- Additional pressure dP = P_indented - P_smooth on the same grid at the same T. Around the indent centre
  (X_D, Y_D), within r <= 1.5 Phi (the shoulders sit at r ~ 0.6-0.8 Phi for K = 3-8):
  dP_FRONT = max dP downstream (X - X_D > |Y - Y_D|: "first in the contact"), dP_REAR = max dP upstream
  (X_D - X > |Y - Y_D|), dP_LAT = max dP on the sides (|Y - Y_D| >= |X - X_D|), dP_CENT = min dP in the hole
  (r <= Phi/2, negative), and the amplitude max dP over r <= 1.5 Phi (the dry model's single amplitude).
"""
from __future__ import annotations

import numpy as np


def film_measures(x: np.ndarray, y: np.ndarray, P: np.ndarray, H: np.ndarray) -> dict[str, float]:
    i0, j0 = int(np.argmin(np.abs(x))), int(np.argmin(np.abs(y)))
    pos = P > 0
    i, _ = np.unravel_index(int(np.argmax(P)), P.shape)
    return {"H_central": float(H[i0, j0]), "H_min": float(H[pos].min()) if pos.any() else float("nan"),
            "P_max": float(P.max()), "X_spike": float(x[i])}


def additional_pressure(x: np.ndarray, y: np.ndarray, dP: np.ndarray, xd: float, yd: float,
                        phi: float) -> dict[str, float]:
    """dP amplitudes (dimensionless, as dP) around an indent centred at (xd, yd) of diameter phi."""
    X, Y = np.meshgrid(x - xd, y - yd, indexing="ij")
    r = np.hypot(X, Y)
    near = r <= 1.5 * phi

    def mx(mask):
        m = near & mask
        return float(dP[m].max()) if m.any() else float("nan")

    hole = r <= 0.5 * phi
    return {"front": mx(X > np.abs(Y)), "rear": mx(-X > np.abs(Y)), "lateral": mx(np.abs(Y) >= np.abs(X)),
            "centre": float(dP[hole].min()) if hole.any() else float("nan"), "amplitude": mx(near)}
