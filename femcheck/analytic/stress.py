"""Sub-surface stresses under a frictionless Hertz line contact (plane strain).

Closed form of McEwen (1949), as written in Johnson, *Contact Mechanics* (1985) eq. (4.49), equivalent to the
Smith-Liu expressions of seed 004 App. C (C.1). Coordinates: x along the surface, z >= 0 depth into the
solid; tension positive, so contact stresses are negative. All stresses in Pa.

The orthogonal shear tau_xz follows the Flamant superposition of seed 001 eq (25)
tau_zx = -(2/pi) z^2 int p(s) (x - s) / ((x - s)^2 + z^2)^2 ds (with the square root on the pressure that the
printed equation drops), i.e. it is negative for x > 0.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import optimize

from .hertz import LineContact


def mcewen(x, z, half_width: float, p_max: float, nu: float) -> dict[str, np.ndarray]:
    """Stress components sigma_x, sigma_z, sigma_y (plane strain), tau_xz at points (x, z), z >= 0.

    m^2, n^2 = 1/2 [ sqrt((a^2 - x^2 + z^2)^2 + 4 x^2 z^2) +/- (a^2 - x^2 + z^2) ], sign(m) = sign(z),
    sign(n) = sign(x);  sigma_x = -(p0/a)[m (1 + (z^2 + n^2)/(m^2 + n^2)) - 2z],
    sigma_z = -(p0/a) m (1 - (z^2 + n^2)/(m^2 + n^2)),  tau_xz = -(p0/a) n (m^2 - z^2)/(m^2 + n^2).
    """
    a = half_width
    x = np.asarray(x, dtype=float)
    z = np.asarray(z, dtype=float)
    s = a * a - x * x + z * z
    root = np.sqrt(s * s + 4.0 * x * x * z * z)
    m = np.sqrt(np.clip(0.5 * (root + s), 0.0, None))
    n = np.sign(x) * np.sqrt(np.clip(0.5 * (root - s), 0.0, None))
    mn = m * m + n * n
    # On the surface outside the contact m = 0 and (z^2 + n^2)/(m^2 + n^2) = 1; guard the 0/0 at the edge.
    ratio = np.divide(z * z + n * n, mn, out=np.ones_like(mn), where=mn > 0)
    shear = np.divide(m * m - z * z, mn, out=np.zeros_like(mn), where=mn > 0)
    c = p_max / a
    sx = -c * (m * (1.0 + ratio) - 2.0 * z)
    sz = -c * m * (1.0 - ratio)
    txz = -c * n * shear
    return {"sigma_x": sx, "sigma_z": sz, "sigma_y": nu * (sx + sz), "tau_xz": txz}


def von_mises(s: dict[str, np.ndarray]) -> np.ndarray:
    """Equivalent stress sqrt(1/2[(sx-sy)^2 + (sy-sz)^2 + (sz-sx)^2] + 3 txz^2) (Pa)."""
    sx, sy, sz, t = s["sigma_x"], s["sigma_y"], s["sigma_z"], s["tau_xz"]
    return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3.0 * t * t)


def tresca(s: dict[str, np.ndarray]) -> np.ndarray:
    """Maximum shear stress (sigma_1 - sigma_3)/2 over the three principal stresses (Pa)."""
    mean = 0.5 * (s["sigma_x"] + s["sigma_z"])
    radius = np.sqrt((0.5 * (s["sigma_x"] - s["sigma_z"])) ** 2 + s["tau_xz"] ** 2)
    p = np.stack([mean + radius, mean - radius, s["sigma_y"]])
    return 0.5 * (p.max(axis=0) - p.min(axis=0))


@dataclass
class LineStressField:
    """Stress field on a grid and its extrema (positions in m, stresses in Pa)."""

    x: np.ndarray
    z: np.ndarray
    components: dict[str, np.ndarray]
    von_mises: np.ndarray
    tresca: np.ndarray
    maxima: dict[str, float] = field(default_factory=dict)


def _refine_max(fun, x0: float, z0: float, a: float) -> tuple[float, float, float]:
    """Polish a grid maximum of ``fun(x, z)`` with Nelder-Mead (grid spacing alone limits accuracy)."""
    res = optimize.minimize(lambda v: -fun(v[0] * a, abs(v[1]) * a), [x0 / a, z0 / a], method="Nelder-Mead",
                            options={"xatol": 1e-7, "fatol": 1e-12, "maxiter": 2000})
    return float(-res.fun), float(res.x[0] * a), float(abs(res.x[1]) * a)


def line_contact_field(hertz: LineContact, nu: float, nx: int = 161, nz: int = 121,
                       x_extent: float = 2.0, z_extent: float = 3.0) -> LineStressField:
    """Sub-surface stresses of a Hertz line contact on an (x, z) grid, with the maxima located precisely.

    Grid: x in [-x_extent a, x_extent a], z in (0, z_extent a]. Reported maxima: ``von_mises_max`` and its
    depth, ``tau_max`` (Tresca) and its depth, ``tau_xz_max`` (largest |tau_xz|) with its x and depth.
    """
    a, p0 = hertz.half_width, hertz.p_max
    x = np.linspace(-x_extent * a, x_extent * a, nx)
    z = np.linspace(z_extent * a / nz, z_extent * a, nz)
    X, Z = np.meshgrid(x, z, indexing="xy")
    comps = mcewen(X, Z, a, p0, nu)
    vm = von_mises(comps)
    tr = tresca(comps)

    def at(fn):
        return lambda xx, zz: float(fn(mcewen(np.array(xx), np.array(zz), a, p0, nu)))

    maxima = {}
    for key, grid, fn in (("von_mises_max", vm, von_mises), ("tau_max", tr, tresca),
                          ("tau_xz_max", np.abs(comps["tau_xz"]), lambda c: np.abs(c["tau_xz"]))):
        k = np.unravel_index(np.argmax(grid), grid.shape)
        val, xm, zm = _refine_max(at(fn), X[k], Z[k], a)
        maxima[key] = val
        maxima[f"{key}_depth"] = zm
        maxima[f"{key}_x"] = abs(xm)
    return LineStressField(x, z, comps, vm, tr, maxima)


def hertz_sphere_axis(z: np.ndarray, a: float, p0: float, nu: float) -> dict[str, np.ndarray]:
    """Stresses on the axis below a Hertz sphere contact (Johnson 1985 eq. 3.45): sigma_r = sigma_theta =
    p0 [-(1 + nu)(1 - (z/a) atan(a/z)) + 1/2 (1 + z^2/a^2)^-1], sigma_z = -p0 (1 + z^2/a^2)^-1 (Pa)."""
    zeta = np.asarray(z, dtype=float) / a
    sz = -p0 / (1.0 + zeta * zeta)
    sr = p0 * (-(1.0 + nu) * (1.0 - zeta * np.arctan(1.0 / zeta)) + 0.5 / (1.0 + zeta * zeta))
    return {"sigma_r": sr, "sigma_z": sz}


def hertz_sphere_maxima(a: float, p0: float, nu: float) -> dict[str, float]:
    """Maximum von Mises (= |sigma_z - sigma_r| on the axis) and maximum shear (half of it), with depth."""
    def minus_vm(zeta: float) -> float:
        s = hertz_sphere_axis(np.array(zeta * a), a, p0, nu)
        return -float(abs(s["sigma_z"] - s["sigma_r"]))

    res = optimize.minimize_scalar(minus_vm, bounds=(0.05, 3.0), method="bounded", options={"xatol": 1e-10})
    vm = -float(res.fun)
    return {"von_mises_max": vm, "von_mises_max_depth": float(res.x * a), "tau_max": 0.5 * vm,
            "tau_max_depth": float(res.x * a)}
