"""Dimensionless groups of an EHL point contact and their conversions (seed 004 §2.2-2.3, §3.2.2; spec
ehl-life.md §A.2).

Hertz scaling with b the semi-axis along the rolling direction x, a the transverse one, kappa = b/a:
X = x/b, P = p/p_H, H = h Rx/b^2, T = t u_m/b. The Reynolds equation then carries
lambda_bar = 12 u_m eta0 Rx^2/(b^3 p_H) (eq 2.15) and the film equation the deformation factor
c_el = (1 + Rx/Ry)/(2 pi Ecal) with Ecal = E(m = 1 - kappa^2) the complete elliptic integral of the second kind
(eq 2.6 as corrected in the spec §0: the printed (1 - kappa)^2 is a slip). The load balance reads
int int P dX dY = 2 pi/(3 kappa) (eq 2.10).

Moes groups (u_s = u1 + u2 = 2 u_m, the *sum* speed): U_M = eta0 u_s/(E' Rx), W = w/(E' Rx^2), G = alpha E',
M = W U_M^(-3/4), L = G U_M^(1/4), H_Moes = (h/Rx) U_M^(-1/2). E' = 2 E* (eq 2.3: 2/E' = sum (1 - nu^2)/E).
Hamrock-Dowson use the *mean* speed: U_HD = eta0 u_m/(E' Rx) = U_M/2.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import ellipe

from ..analytic import hertz


def kappa_approx(rx_over_ry: float) -> float:
    """Ellipticity kappa = b/a from the corrected eq 2.5 (Hamrock-Brewe type fit), rho = Rx/Ry <= 1:
    kappa = [1 + sqrt(ln(16/rho)/(2 rho)) - sqrt(ln 4) + 0.16 ln rho]^-1 (within 1 % of exact Hertz)."""
    rho = float(rx_over_ry)
    if not 0.0 < rho <= 1.0:
        raise ValueError("Rx/Ry must be in (0, 1]")
    return 1.0 / (1.0 + np.sqrt(np.log(16.0 / rho) / (2.0 * rho)) - np.sqrt(np.log(4.0)) + 0.16 * np.log(rho))


def ecal(kappa: float) -> float:
    """Ecal = int_0^{pi/2} sqrt(1 - (1 - kappa^2) sin^2 psi) dpsi (eq 2.6 corrected; pi/2 for a circle)."""
    return float(ellipe(1.0 - kappa * kappa))


@dataclass(frozen=True)
class Groups:
    """An operating point in every unit system the EHL code needs.

    Physical (SI): ``Rx``, ``Ry`` (m), ``e_prime`` E' (Pa), ``load`` w (N), ``eta0`` (Pa s), ``alpha`` (1/Pa),
    ``u_mean`` u_m (m/s). Hertz: ``b`` (m, along x), ``a`` (m, across), ``p_hertz`` (Pa), ``kappa`` = b/a.
    Moes: ``M``, ``L``, ``U_moes`` (sum speed). Equation: ``lam`` (lambda_bar), ``alpha_bar`` = alpha p_H,
    ``c_el``, ``load_dimless`` = 2 pi/(3 kappa).
    """

    Rx: float
    Ry: float
    e_prime: float
    load: float
    eta0: float
    alpha: float
    u_mean: float
    b: float
    a: float
    p_hertz: float

    @property
    def kappa(self) -> float:
        return self.b / self.a

    @property
    def U_moes(self) -> float:
        return self.eta0 * 2.0 * self.u_mean / (self.e_prime * self.Rx)

    @property
    def U_hd(self) -> float:
        return self.eta0 * self.u_mean / (self.e_prime * self.Rx)

    @property
    def W(self) -> float:
        return self.load / (self.e_prime * self.Rx**2)

    @property
    def G(self) -> float:
        return self.alpha * self.e_prime

    @property
    def M(self) -> float:
        return self.W * self.U_moes ** -0.75

    @property
    def L(self) -> float:
        return self.G * self.U_moes ** 0.25

    @property
    def lam(self) -> float:
        """lambda_bar = 12 u_m eta0 Rx^2/(b^3 p_H) (eq 2.15)."""
        return 12.0 * self.u_mean * self.eta0 * self.Rx**2 / (self.b**3 * self.p_hertz)

    @property
    def alpha_bar(self) -> float:
        return self.alpha * self.p_hertz

    @property
    def ecal(self) -> float:
        return ecal(self.kappa)

    @property
    def c_el(self) -> float:
        """Deformation factor (1 + Rx/Ry)/(2 pi Ecal) of eq 2.4 (2/pi^2 for a circle)."""
        return (1.0 + self.Rx / self.Ry) / (2.0 * np.pi * self.ecal)

    @property
    def load_dimless(self) -> float:
        return 2.0 * np.pi / (3.0 * self.kappa)

    def film_to_m(self, H: float) -> float:
        """Film thickness in m from H = h Rx/b^2."""
        return H * self.b**2 / self.Rx

    def moes_film(self, H: float) -> float:
        """(h/Rx) U_M^(-1/2) from the dimensionless H."""
        return self.film_to_m(H) / self.Rx / np.sqrt(self.U_moes)


def from_physical(Rx: float, Ry: float, e_prime: float, load: float, eta0: float, alpha: float,
                  u_mean: float) -> Groups:
    """Groups of a physical operating point; the Hertz contact from femcheck's exact elliptic Hertz
    (E* = E'/2)."""
    if Rx > Ry:
        raise ValueError("EHL contacts need Rx <= Ry (the contact is widest across the rolling direction)")
    h = hertz.elliptic_contact(load, Rx, Ry, 0.5 * e_prime)
    return Groups(Rx, Ry, e_prime, load, eta0, alpha, u_mean, h.semi_axis_x, h.semi_axis_y, h.p_max)


def from_moes(M: float, L: float, Rx: float, Ry: float, e_prime: float, eta0: float, alpha: float) -> Groups:
    """Physical load and mean speed that give Moes (M, L) for the radii, modulus and lubricant:
    U_M = (L/G)^4, W = M U_M^(3/4), w = W E' Rx^2, u_m = U_M E' Rx/(2 eta0)."""
    G = alpha * e_prime
    U = (L / G) ** 4
    W = M * U**0.75
    return from_physical(Rx, Ry, e_prime, W * e_prime * Rx**2, eta0, alpha, 0.5 * U * e_prime * Rx / eta0)


def at_ellipticity(g: Groups, kappa: float) -> Groups:
    """The operating point ``g`` with its contact ellipticity changed to ``kappa`` = b/a the way seed 004 varies it
    (§3.2.2 for dry, §3.3.2 for EHL contacts): b (along the rolling direction) and p_H fixed, so the indent's
    dimensionless diameter and the dimensionless pressures are unchanged; E', the lubricant and the mean speed kept.
    Rx/Ry follows from exact Hertz (Johnson 1985 eq 4.39: Ry/Rx = B/A of the ellipse b/a = kappa), Rx from eq 3.1,
        b E'/(pi p_H) = (4/pi) Ecal Rx/(1 + Rx/Ry),   Ecal = E(1 - kappa^2),
    and the load from p_H = 3 w/(2 pi a b), w = (2 pi/3) p_H b^2/kappa. Then alpha_bar = alpha p_H is unchanged and
    lambda_bar = 12 u_m eta0 Rx^2/(b^3 p_H) scales with Rx^2 (at kappa = 0.2: Rx x 0.811, lambda_bar x 0.657);
    the Moes M, L of the new point differ from g's (they are not the thesis' coordinates of the comparison)."""
    if not 0.0 < kappa <= 1.0:
        raise ValueError("kappa = b/a must be in (0, 1]")
    rho = 1.0 if kappa == 1.0 else 1.0 / hertz._curvature_ratio(kappa)
    rx = g.b * g.e_prime * (1.0 + rho) / (4.0 * g.p_hertz * ecal(kappa))
    w = 2.0 * np.pi / 3.0 * g.p_hertz * g.b**2 / kappa
    return from_physical(rx, rx / rho, g.e_prime, w, g.eta0, g.alpha, g.u_mean)


def circular_alpha_bar(M: float, L: float) -> float:
    """alpha_bar = (L/pi) (3M/2)^(1/3) for a circular contact (spec §A.2)."""
    return L / np.pi * (1.5 * M) ** (1.0 / 3.0)


def circular_lambda(M: float) -> float:
    """lambda_bar = (128 pi^3/(3 M^4))^(1/3) for a circular contact (spec §A.2)."""
    return (128.0 * np.pi**3 / (3.0 * M**4)) ** (1.0 / 3.0)
