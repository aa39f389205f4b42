"""Load-deflection laws of one roller between its two raceways (both contacts in series), SI units.

Every law maps the roller's total elastic deflection delta (m: the sum of both contact approaches along the
contact normal) to its load Q (N) and back, and gives the stiffness dQ/d delta and the strain energy
int_0^delta Q d delta (the potential the rigid-ring equilibrium minimises, :mod:`femcheck.analytic.bearing_load`).
A negative deflection is an open roller: Q = 0.

- :class:`PowerLaw`   Q = K delta^n (Stribeck; n = 3/2 point, 10/9 line contact).
- :func:`palmgren`    Palmgren (1959) via Harris & Kotzalas (2007, *Essential Concepts*, ch. 7), two line contacts
  in series: delta = 7.68e-5 Q^0.9 / l^0.8 (mm, N), i.e. Q = 3.736e4 l^(8/9) delta^(10/9) (N, mm).
- :func:`iso16281`    ISO/TS 16281:2008 whole roller (steel, both contacts): Q = 35948 L_we^(8/9) delta^(10/9) (N, mm);
  its slices are in :mod:`femcheck.analytic.iso16281`.
- :class:`PlaneStrainRoller` the exact 2D plane-strain law of a roller under two diametrically opposite Hertz
  pressures (spec bearing-load.md §3.4; Johnson 1985, *Contact Mechanics*, 2D contact of cylinders):
      Delta_d = P (1 - nu^2)/(pi E) [ (2 ln(4R/a_1) - 1) + (2 ln(4R/a_2) - 1) ],  a_k = sqrt(4 P R_x,k/(pi E*_k)),
  P = Q/l (N/m). It is the compression of the roller from its two contact centres to its centre: the rings'
  own deformation is not in it (rigid raceways, or the ring compliance of the condensed model).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import lambertw

# Palmgren's two-contact constant (mm, N): delta = 7.68e-5 Q^0.9 / l^0.8; SI: Q = K l^(8/9) delta^(10/9) with
# K = (7.68e-5)^(-10/9) * 1e3^(10/9) * 1e3^(8/9) (delta, l from m to mm).
PALMGREN_DEFLECTION_MM = 7.68e-5
ISO16281_C_MM = 35948.0          # N / mm^(10/9) per mm^(8/9) of roller length (ISO/TS 16281 eq. 37, steel)
LINE_EXPONENT = 10.0 / 9.0


@dataclass(frozen=True)
class PowerLaw:
    """Q = K max(delta, 0)^n; K in N/m^n."""

    stiffness_constant: float
    exponent: float
    name: str = "power"

    def load(self, delta):
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        return self.stiffness_constant * d**self.exponent

    def stiffness(self, delta):
        d = np.asarray(delta, dtype=float)
        pos = d > 0
        safe = np.where(pos, d, 1.0)
        return np.where(pos, self.stiffness_constant * self.exponent * safe ** (self.exponent - 1.0), 0.0)

    def energy(self, delta):
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        return self.stiffness_constant * d ** (self.exponent + 1.0) / (self.exponent + 1.0)

    def deflection(self, load):
        q = np.maximum(np.asarray(load, dtype=float), 0.0)
        return (q / self.stiffness_constant) ** (1.0 / self.exponent)


def palmgren(length: float) -> PowerLaw:
    """Palmgren's line-contact law for a roller of effective length ``length`` (m) between two raceways."""
    k = PALMGREN_DEFLECTION_MM ** (-1.0 / 0.9) * 1e3 ** (1.0 / 0.9) * 1e3 ** (0.8 / 0.9)
    return PowerLaw(k * length ** (8.0 / 9.0), LINE_EXPONENT, "palmgren")


def iso16281(length: float) -> PowerLaw:
    """ISO/TS 16281 whole-roller law (steel) for effective length ``length`` (m): 3.5948e10 L^(8/9) delta^(10/9)."""
    return PowerLaw(ISO16281_C_MM * 1e6 * length ** (8.0 / 9.0), LINE_EXPONENT, "iso16281")


@dataclass(frozen=True)
class PlaneStrainRoller:
    """Exact 2D law (module doc). ``radius`` R (m), ``length`` l (m) converting N <-> N/m, roller ``E``, ``nu``;
    ``rx`` = (R_x,1, R_x,2) reduced radii of the two contacts (m); ``e_star`` = (E*_1, E*_2) their contact moduli
    (Pa): E/(1 - nu^2) against a rigid raceway, half that against a steel one.

    With P = Q/l and c = (1 - nu^2)/(pi E):  Delta_d = c P (B - 2 ln P),  B = sum_k [ln(4 pi R^2 E*_k/R_x,k) - 1].
    Inverse in closed form: u = B - 2 ln P solves u e^(-u/2) = (Delta_d/c) e^(-B/2), so u = -2 W_-1(z) with
    z = -(Delta_d/2c) e^(-B/2) (Lambert's W, lower branch: the one with u > 2, where Delta_d grows with P).
    The law holds while u = sum_k (2 ln(4R/a_k) - 1) > 2, i.e. a_k well below R.
    """

    radius: float
    length: float
    E: float
    nu: float
    rx: tuple[float, float]
    e_star: tuple[float, float]
    name: str = "plane_strain"
    offset: float = 0.0           # added to B: a compliance measured otherwise (FE roller), as c * offset / P

    @property
    def c(self) -> float:
        return (1.0 - self.nu**2) / (np.pi * self.E)

    @property
    def B(self) -> float:
        return float(sum(np.log(4.0 * np.pi * self.radius**2 * e / r) - 1.0 for r, e in zip(self.rx, self.e_star))
                     + self.offset)

    @property
    def max_deflection(self) -> float:
        """The largest deflection the law covers (u = 2, z = -1/e): beyond it Delta_d(P) would fall with P."""
        return 2.0 * self.c * np.exp(0.5 * self.B - 1.0)

    def half_widths(self, load):
        """Hertz half-widths (a_1, a_2) in m of the two contacts at roller load Q (N)."""
        p = np.maximum(np.asarray(load, dtype=float), 0.0) / self.length
        return tuple(np.sqrt(4.0 * p * r / (np.pi * e)) for r, e in zip(self.rx, self.e_star))

    def deflection(self, load):
        p = np.maximum(np.asarray(load, dtype=float), 0.0) / self.length
        with np.errstate(divide="ignore", invalid="ignore"):
            d = self.c * p * (self.B - 2.0 * np.log(p))
        return np.where(p > 0, d, 0.0)

    def _u(self, delta):
        d = np.maximum(np.asarray(delta, dtype=float), 0.0)
        if np.any(d > self.max_deflection * (1 + 1e-12)):
            raise ValueError(f"roller deflection {float(np.max(d)):.4g} m beyond the 2D law's range "
                             f"({self.max_deflection:.4g} m: contact widths no longer small against R)")
        z = -0.5 * (d / self.c) * np.exp(-0.5 * self.B)
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.where(d > 0, -2.0 * np.real(lambertw(np.minimum(z, -1e-300), k=-1)), np.inf)
        return d, u

    def load(self, delta):
        d, u = self._u(delta)
        return np.where(d > 0, self.length * np.exp(0.5 * (self.B - u)), 0.0)

    def stiffness(self, delta):
        """dQ/d delta = l / (c (u - 2))."""
        d, u = self._u(delta)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(d > 0, self.length / (self.c * (u - 2.0)), 0.0)

    def energy(self, delta):
        """int_0^delta Q d delta = l c P^2 (u - 1)/2."""
        d, u = self._u(delta)
        p = np.where(d > 0, np.exp(0.5 * (self.B - u)), 0.0)
        with np.errstate(invalid="ignore"):
            return np.where(d > 0, self.length * self.c * p**2 * (u - 1.0) / 2.0, 0.0)

    def effective_exponent(self, load):
        """n_eff = d ln Q / d ln delta = u/(u - 2) = 1/(1 - 2/S) (spec §3.4)."""
        p = np.asarray(load, dtype=float) / self.length
        u = self.B - 2.0 * np.log(p)
        return u / (u - 2.0)


def power_law_matched(length: float, exponent: float, load: float) -> PowerLaw:
    """A power law Q = K delta^n that agrees with the ISO/TS 16281 whole-roller law at roller load ``load`` (N):
    K = Q / delta_iso(Q)^n. Used when a scene asks for ``power`` without a stiffness constant, so that exponents
    can be compared at the same load level."""
    iso = iso16281(length)
    d = float(iso.deflection(load))
    return PowerLaw(load / d**exponent, exponent)
