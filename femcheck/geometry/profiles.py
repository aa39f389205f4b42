"""Gap profiles: sphere, ellipsoid (paraboloid), finite rollers with flat, circular or logarithmic crowns,
raceway curvature, misalignment tilt, and measured height maps."""
from __future__ import annotations

from typing import Callable

import numpy as np

Gap = Callable[[np.ndarray, np.ndarray], np.ndarray]


def sphere(radius: float) -> Gap:
    """Exact sphere over a flat: h = R - sqrt(R^2 - r^2)."""
    return lambda X, Y: radius - np.sqrt(np.clip(radius**2 - X * X - Y * Y, 0.0, None))


def paraboloid(Rx: float, Ry: float) -> Gap:
    """Hertz's gap h = x^2/(2 Rx) + y^2/(2 Ry) (an ellipsoid near its apex)."""
    return lambda X, Y: X * X / (2.0 * Rx) + Y * Y / (2.0 * Ry)


def crown_drop(y: np.ndarray, length: float, crown: str, crown_radius: float | None = None,
               flat_length: float = 0.0, design_load: float | None = None, modulus: float | None = None,
               ) -> np.ndarray:
    """Drop of a roller generatrix below its flat line at axial position y (m), |y| <= length/2.

    ``none``: 0 (flat-ended, sharp edges). ``circular``: (|y| - flat_length/2)^2 / (2 crown_radius) outside
    a central flat of ``flat_length`` (full crown when 0). ``log``: Lundberg's logarithmic profile
    z = (2 Q / (pi E* L)) ln(1 / (1 - (2y/L)^2)) (Lundberg 1939; Harris & Kotzalas, *Rolling Bearing
    Analysis*, 2007, §6) for a design load Q (N) and the combined modulus E* (Pa); it is infinite at the
    very end, where the roller's end chamfer begins.
    """
    y = np.abs(np.asarray(y, dtype=float))
    if crown == "none":
        return np.zeros_like(y)
    if crown == "circular":
        if not crown_radius or crown_radius <= 0:
            raise ValueError("circular crown needs crown_radius > 0")
        return np.clip(y - 0.5 * flat_length, 0.0, None) ** 2 / (2.0 * crown_radius)
    if crown == "log":
        if not design_load or not modulus:
            raise ValueError("logarithmic crown needs design_load and modulus")
        s = np.clip(1.0 - (2.0 * y / length) ** 2, 1e-300, None)
        return 2.0 * design_load / (np.pi * modulus * length) * np.log(1.0 / s)
    raise ValueError(f"crown {crown!r} unknown (none, circular, log)")


def roller(radius: float, length: float, crown: str = "none", crown_radius: float | None = None,
           flat_length: float = 0.0, design_load: float | None = None, modulus: float | None = None,
           race_radius: float = np.inf, tilt: float = 0.0) -> Gap:
    """A roller of ``radius`` and ``length`` (m) on a raceway: h = x^2/(2 R) + crown_drop(y) + y tan(tilt).

    ``race_radius`` (m): raceway radius in the rolling plane, positive convex (inner ring), negative concave
    (outer ring); 1/R = 1/r_roller + 1/r_race (seed 001 eq 1). ``tilt`` (rad): misalignment about x, raising
    one end (the rigid approach absorbs the constant). Beyond |y| > L/2 the gap is +inf (no roller).
    """
    curvature = 1.0 / radius + (0.0 if np.isinf(race_radius) else 1.0 / race_radius)
    if curvature <= 0:
        raise ValueError("roller and raceway do not close towards each other")
    R = 1.0 / curvature

    def gap(X, Y):
        inside = np.abs(Y) <= 0.5 * length * (1 + 1e-12)
        drop = crown_drop(np.where(inside, Y, 0.0), length, crown, crown_radius, flat_length, design_load,
                          modulus)
        h = X * X / (2.0 * R) + drop + np.tan(tilt) * Y
        return np.where(inside, h, np.inf)

    return gap


def height_map(x: np.ndarray, y: np.ndarray, h: np.ndarray, base: Gap | None = None) -> Gap:
    """A measured or computed height map h[i, j] at (x[i], y[j]) (m), bilinear between samples and +inf
    outside, optionally added to a ``base`` gap. Load one from ``.npz`` with keys x, y, h via ``np.load``."""
    from scipy.interpolate import RegularGridInterpolator

    interp = RegularGridInterpolator((np.asarray(x), np.asarray(y)), np.asarray(h, dtype=float),
                                     bounds_error=False, fill_value=np.inf)

    def gap(X, Y):
        v = interp((X, Y))
        return v + base(X, Y) if base is not None else v

    return gap


def indent_height(r: np.ndarray, diameter: float, depth: float, decay: float) -> np.ndarray:
    """Surface height (m) of an indent, seed 004 eq 2.16 / B.1: R(r) = -D exp(-K r^2/phi^2) cos(pi r / phi):
    a hole of depth D (R(0) = -D) surrounded by shoulders whose shape the decay K controls (K = 3: high
    shoulders, K = 8: nearly none)."""
    r = np.asarray(r, dtype=float)
    return -depth * np.exp(-decay * r * r / diameter**2) * np.cos(np.pi * r / diameter)


def indented(base: Gap, diameter: float, depth: float, decay: float, x0: float = 0.0, y0: float = 0.0) -> Gap:
    """``base`` gap with an indent centred at (x0, y0) on one surface: the hole opens the gap, the shoulders
    close it (gap = base - R)."""
    return lambda X, Y: base(X, Y) - indent_height(np.hypot(X - x0, Y - y0), diameter, depth, decay)
