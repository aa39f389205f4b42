"""Elastic constants and combined moduli (SI: Pa)."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Elastic:
    """Isotropic linear-elastic body; ``rigid=True`` ignores E and nu."""

    E: float
    nu: float
    rigid: bool = False

    @property
    def compliance(self) -> float:
        """Plane-strain compliance (1 - nu^2)/E in 1/Pa; 0 for a rigid body."""
        return 0.0 if self.rigid else (1.0 - self.nu**2) / self.E

    @property
    def shear_modulus(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))

    def lame(self) -> tuple[float, float]:
        """Lamé constants (lambda, mu) in Pa, 3D (= plane strain in 2D)."""
        lam = self.E * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu))
        return lam, self.shear_modulus


def effective_modulus(body1: Elastic, body2: Elastic) -> float:
    """Combined contact modulus E* (Pa), seed 001 eq (2): 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2.

    A rigid body contributes no compliance, so a rigid indenter on an elastic body gives
    E* = E/(1 - nu^2).
    """
    c = body1.compliance + body2.compliance
    if c <= 0.0:
        raise ValueError("both bodies rigid: the contact has no compliance")
    return 1.0 / c
