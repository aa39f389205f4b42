"""FASTSIM: Kalker's simplified theory of steady rolling contact with Coulomb friction.

Source: J.J. Kalker, "A fast algorithm for the simplified theory of rolling contact", *Vehicle System Dynamics*
11 (1982) 1-13; Kalker 1990 (*Three-dimensional elastic bodies in rolling contact*, simplified theory).

Simplified theory: the tangential surface displacement difference is proportional to the local traction,
u = L p (L a flexibility, m/Pa). In steady rolling (rolling velocity V along +x, material flowing from the leading
edge x = +a(y) to the trailing edge x = -a(y)) the slip, normalised by V, is

    s = w - du/dx,   w = (xi - phi y,  eta + phi x)      (Kalker's rigid slip; Johnson 1985 §8.4)

Adhesion (s = 0) gives dp/dx = w / L, integrated from p = 0 at the leading edge; where |p| would exceed the
traction bound g = mu p_n the traction is put on the bound in the direction of the trial traction (slip).
For vanishing creepage (complete adhesion) on the Hertz ellipse the traction is p_x = xi (x - a(y)) / L and
p_y = eta (x - a(y)) / L + phi (x^2 - a(y)^2) / (2 L); integrating over the ellipse and equating to Kalker's
linear theory (Fx = -G c^2 C11 xi, Fy = -G c^2 C22 eta - G c^3 C23 phi) fixes the three flexibilities
(Kalker 1982; the same expressions are in CONTACT's ``simpflex``)

    L1 = 8 a / (3 C11 G),   L2 = 8 a / (3 C22 G),   L3 = pi a sqrt(a/b) / (4 C23 G)      (m/Pa)

(derivation: int_{-a(y)}^{a(y)} (x - a(y)) dx = -2 a(y)^2, int a(y)^2 dy = 4 a^2 b / 3 -> Fx = -8 a^2 b xi/(3 L1);
int (x^2 - a(y)^2)/2 dx = -2 a(y)^3/3, int a(y)^3 dy = 3 pi a^3 b / 8 -> Fy = -pi a^3 b phi / (4 L3)).

Two ways to use them (``flexibility``):
- ``"weighted"`` (Kalker 1982): one flexibility L = (|xi| L1 + |eta| L2 + c |phi| L3) / sqrt(xi^2 + eta^2 + c^2 phi^2),
  c = sqrt(a b). The trial traction increment is parallel to the rigid slip w, so at large creepage the traction
  tends to full slip (-mu p w/|w|).
- ``"separate"``: dp_x/dx = xi/L1 - phi y/L3, dp_y/dx = eta/L2 + phi x/L3. Linear in the creepages, so at small
  combined creepage Fx and Fy equal linear theory for any mix; but the slip direction at large combined
  creepage is not that of w (it does not tend to full slip when spin is combined with xi or eta).
Both give linear theory's Fx(xi), Fy(eta), Fy(phi) at small pure creepage. Neither reproduces C23 in Mz(eta)
nor C33 in Mz(phi) (known limitation of the simplified theory: one flexibility per creepage cannot match all
five coefficients): FASTSIM's Mz = 3 pi G C22 a^2 b eta / 32 for pure eta and
Mz = -32 G C23 a^(1/2) b^(7/2) phi / (15 pi) for pure spin.

Discretisation (Kalker's elliptic grid): ny strips of equal width dy = 2b/ny parallel to x, centred at y_j; each
strip |x| <= a_j = a sqrt(1 - y_j^2/b^2) divided into nx equal cells; the traction is marched from the leading
edge (p = 0) through the nx cell centres x_{j,i} = a_j - (i + 1/2) dx_j, with the rigid slip of each step taken
at the middle of the step (exact, the rigid slip being linear in x). Forces: midpoint rule in x and y. The
traction bound is mu times the Hertz pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2) (``bound="elliptic"``) or the
parabolic bound mu (2N/(pi a b)) (1 - x^2/a^2 - y^2/b^2) with the same total load (``bound="parabolic"``,
the bound Kalker used with FASTSIM: it brings the simplified theory closer to the exact one).

Accuracy: for pure xi in complete adhesion the traction is linear in x, the midpoint rule along x is exact and only
the strip rule errs (relative error 1/(2 ny^2)); for spin the traction is quadratic in x (error O(1/nx^2)). In
partial slip the kink where the traction meets the bound and the square-root edge of the elliptic bound lower
the order (measured in tests/test_fastsim.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from femcheck.cect.linear import _check_finite, _check_positive
from femcheck.errors import InputError

BOUNDS = ("elliptic", "parabolic")
FLEXIBILITIES = ("weighted", "separate")


@dataclass(frozen=True, eq=False)
class FastsimResult:
    """FASTSIM solution on the elliptic strip grid.

    Totals (on the reference body, Kalker's sign convention): ``creep_force_x``, ``creep_force_y`` (N),
    ``spin_moment`` (N m, about the contact centre); ``adhesion_fraction`` (-): area of the nodes below the
    traction bound over the sum of the cell areas (midpoint weights).
    Fields, shape (ny, nx), at the cell centres, i = 0 next to the leading edge: ``x`` (m), ``y`` (m),
    ``px``, ``py`` (Pa), ``traction_bound`` mu p (Pa), ``slip`` (bool, traction on the bound), ``weights``
    (m^2, quadrature weight of each node).
    ``flexibilities`` (L1, L2, L3) in m/Pa; ``flexibility_used`` the single L of the weighted variant (None for
    ``"separate"``); ``steps`` the number of marching steps (FASTSIM is direct: no iteration, no residual).
    """

    creep_force_x: float
    creep_force_y: float
    spin_moment: float
    adhesion_fraction: float
    x: np.ndarray
    y: np.ndarray
    px: np.ndarray
    py: np.ndarray
    traction_bound: np.ndarray
    slip: np.ndarray
    weights: np.ndarray
    flexibilities: tuple[float, float, float]
    flexibility_used: float | None
    bound: str
    flexibility: str
    nx: int
    ny: int
    steps: int


def flexibilities(a: float, b: float, G: float, c11: float, c22: float, c23: float) -> tuple[float, float, float]:
    """Kalker's three flexibilities (m/Pa) of the simplified theory (Kalker 1982; derivation in the module doc):
    L1 = 8a/(3 C11 G), L2 = 8a/(3 C22 G), L3 = pi a sqrt(a/b)/(4 C23 G)."""
    return (8.0 * a / (3.0 * c11 * G), 8.0 * a / (3.0 * c22 * G), math.pi * a * math.sqrt(a / b) / (4.0 * c23 * G))


def _check_grid(key: str, n: int) -> int:
    if isinstance(n, bool) or int(n) != n or n < 2:
        raise InputError(key, f"must be an integer >= 2, got {n!r}")
    return int(n)


def fastsim(a: float, b: float, normal_load: float, G: float, c11: float, c22: float, c23: float, mu: float,
            xi: float, eta: float, phi: float, nx: int = 40, ny: int = 40, bound: str = "elliptic",
            flexibility: str = "weighted") -> FastsimResult:
    """Kalker's FASTSIM (Kalker 1982) on an elliptical Hertz contact.

    Parameters (SI): ``a``, ``b`` semi-axes along x (rolling) and y (m); ``normal_load`` N (N); ``G`` combined
    shear modulus (Pa); ``c11``, ``c22``, ``c23`` Kalker's creep coefficients (-, > 0) that set the
    flexibilities; ``mu`` Coulomb friction coefficient (> 0); ``xi``, ``eta`` creepages (-), ``phi`` spin (1/m);
    ``nx`` cells along each strip, ``ny`` strips; ``bound`` "elliptic" (Hertz) or "parabolic" traction bound;
    ``flexibility`` "weighted" (Kalker 1982, single L) or "separate" (L1, L2, L3 per creepage term).
    With "weighted", small *combined* creepages are not exactly linear theory (L is a creepage-weighted mean);
    "separate" superposes them exactly but does not tend to full slip at large combined creepage.

    The marching from the leading edge is vectorised over the strips (one loop over the nx steps).
    Raises :class:`femcheck.errors.InputError` on bad input.
    """
    a = _check_positive("semi_axis_x", a)
    b = _check_positive("semi_axis_y", b)
    normal_load = _check_positive("load.normal", normal_load)
    G = _check_positive("shear_modulus", G)
    c11 = _check_positive("c11", c11)
    c22 = _check_positive("c22", c22)
    c23 = _check_positive("c23", c23)
    mu = _check_positive("friction.mu", mu)
    xi = _check_finite("kinematics.xi", xi)
    eta = _check_finite("kinematics.eta", eta)
    phi = _check_finite("kinematics.phi", phi)
    nx = _check_grid("numerics.nx", nx)
    ny = _check_grid("numerics.ny", ny)
    if bound not in BOUNDS:
        raise InputError("bound", f"must be one of {', '.join(BOUNDS)}, got {bound!r}")
    if flexibility not in FLEXIBILITIES:
        raise InputError("flexibility", f"must be one of {', '.join(FLEXIBILITIES)}, got {flexibility!r}")

    L1, L2, L3 = flexibilities(a, b, G, c11, c22, c23)
    c = math.sqrt(a * b)

    # Elliptic grid: equal-width strips, nx equal cells per strip; the traction lives at the cell centres
    # x_{j,i} = a_j - (i + 1/2) dx_j, i = 0 at the leading edge. (A node-based march would put the last traction
    # on the trailing edge, where the elliptic bound is zero, and lose half a cell of traction: a first-order
    # error even in complete adhesion.)
    dy = 2.0 * b / ny
    y = -b + (np.arange(ny) + 0.5) * dy
    a_strip = a * np.sqrt(1.0 - (y / b) ** 2)
    dx = 2.0 * a_strip / nx
    x = a_strip[:, None] - (np.arange(nx) + 0.5)[None, :] * dx[:, None]
    yy = np.broadcast_to(y[:, None], x.shape)

    rho2 = np.clip(1.0 - (x / a) ** 2 - (yy / b) ** 2, 0.0, None)
    if bound == "elliptic":
        g = mu * (1.5 * normal_load / (math.pi * a * b)) * np.sqrt(rho2)        # mu p0 sqrt(.), p0 = 3N/(2 pi a b)
    else:
        g = mu * (2.0 * normal_load / (math.pi * a * b)) * rho2                 # same total load N

    # Traction increment per unit length dp/dx = (slope_x, slope_y0 + slope_yx * x) in adhesion.
    if flexibility == "weighted":
        norm = math.sqrt(xi**2 + eta**2 + (c * phi) ** 2)
        L = (abs(xi) * L1 + abs(eta) * L2 + c * abs(phi) * L3) / norm if norm > 0.0 else L1
        slope_x = (xi - phi * y) / L
        slope_y0, slope_yx = eta / L, phi / L
        L_used: float | None = L
    else:
        slope_x = xi / L1 - phi * y / L3
        slope_y0, slope_yx = eta / L2, phi / L3
        L_used = None

    px = np.zeros_like(x)
    py = np.zeros_like(x)
    slip = np.zeros(x.shape, dtype=bool)
    prev_x, prev_y = np.zeros(ny), np.zeros(ny)
    for k in range(nx):
        # Step from the previous centre (the leading edge for k = 0, where p = 0) to centre k; the rigid slip is
        # linear in x, so evaluating it at the middle of the step integrates it exactly.
        step = 0.5 * dx if k == 0 else dx
        x_mid = a_strip - (k + 0.25) * dx if k == 0 else a_strip - k * dx
        tx = prev_x - step * slope_x
        ty = prev_y - step * (slope_y0 + slope_yx * x_mid)
        mag = np.hypot(tx, ty)
        over = mag > g[:, k]
        scale = np.where(over, g[:, k] / np.where(over, mag, 1.0), 1.0)
        prev_x, prev_y = tx * scale, ty * scale
        px[:, k], py[:, k], slip[:, k] = prev_x, prev_y, over

    weights = dx[:, None] * dy * np.ones((1, nx))       # midpoint rule along x and across the strips
    fx = float(np.sum(weights * px))
    fy = float(np.sum(weights * py))
    mz = float(np.sum(weights * (x * py - yy * px)))
    adhesion = float(np.sum(weights[~slip]) / np.sum(weights))
    return FastsimResult(creep_force_x=fx, creep_force_y=fy, spin_moment=mz, adhesion_fraction=adhesion,
                         x=x, y=np.array(yy), px=px, py=py, traction_bound=g, slip=slip, weights=weights,
                         flexibilities=(L1, L2, L3), flexibility_used=L_used, bound=bound,
                         flexibility=flexibility, nx=nx, ny=ny, steps=nx)
