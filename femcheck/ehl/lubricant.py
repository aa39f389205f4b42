"""Pressure-viscosity and pressure-density laws of the lubricant, in the dimensionless form the Reynolds
equation uses (P = p/p_H; seed 004 eqs 2.11-2.12; spec §A.1).

Roelands: eta/eta0 = exp{(ln eta0 + 9.67)[-1 + (1 + p/p_r)^z]}, p_r = 1.96e8 Pa, with z fixed by
alpha p_r/z = ln eta0 + 9.67 so that d ln eta/dp = alpha at p = 0 (eta0 in Pa s; 9.67 = -ln 6.31e-5).
Barus: eta/eta0 = exp(alpha p).
Dowson-Higginson: rho/rho0 = (0.59e9 + 1.34 p)/(0.59e9 + p) (p in Pa). Incompressible: rho/rho0 = 1.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

ROELANDS_PR = 1.96e8          # Pa
ROELANDS_LN = 9.67            # -ln(6.31e-5)
VISCOSITY_LAWS = ("roelands", "barus")
DENSITY_LAWS = ("dowson_higginson", "incompressible")


def roelands_z(eta0: float, alpha: float) -> float:
    """Roelands pressure-viscosity index z = alpha p_r/(ln eta0 + 9.67)."""
    s = np.log(eta0) + ROELANDS_LN
    if s <= 0:
        raise ValueError(f"eta0 = {eta0:g} Pa s gives ln eta0 + 9.67 <= 0: Roelands needs eta0 > 6.31e-5 Pa s")
    return alpha * ROELANDS_PR / s


@dataclass(frozen=True)
class Lubricant:
    """Dimensionless lubricant laws for pressures scaled by ``p_hertz`` (Pa)."""

    viscosity_law: str
    density_law: str
    eta0: float          # Pa s
    alpha: float         # 1/Pa
    p_hertz: float       # Pa

    def viscosity(self, P: np.ndarray) -> np.ndarray:
        """eta/eta0 at P = p/p_H (P >= 0)."""
        p = np.maximum(P, 0.0) * self.p_hertz
        if self.viscosity_law == "barus":
            return np.exp(self.alpha * p)
        s = np.log(self.eta0) + ROELANDS_LN
        z = self.alpha * ROELANDS_PR / s
        return np.exp(s * ((1.0 + p / ROELANDS_PR) ** z - 1.0))

    def density(self, P: np.ndarray) -> np.ndarray:
        """rho/rho0 at P = p/p_H."""
        if self.density_law == "incompressible":
            return np.ones_like(P, dtype=float)
        p = np.maximum(P, 0.0) * self.p_hertz
        return (0.59e9 + 1.34 * p) / (0.59e9 + p)

    def density_slope(self, P: np.ndarray) -> np.ndarray:
        """d(rho/rho0)/dP at P = p/p_H: Dowson-Higginson 0.34 a p_H/(a + p)^2, a = 0.59e9 Pa; 0 incompressible."""
        if self.density_law == "incompressible":
            return np.zeros_like(P, dtype=float)
        p = np.maximum(P, 0.0) * self.p_hertz
        return 0.34 * 0.59e9 * self.p_hertz / (0.59e9 + p) ** 2
