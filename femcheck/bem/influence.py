"""Influence coefficients: surface normal displacement of an elastic half-space under uniform patches."""
from __future__ import annotations

import numpy as np


def _xlogx(t: np.ndarray) -> np.ndarray:
    at = np.abs(t)
    return np.where(at > 0, t * np.log(np.where(at > 0, at, 1.0)), 0.0)


def half_plane_strip(t: np.ndarray, width: float, modulus: float, datum: float) -> np.ndarray:
    """Normal surface displacement (m, positive into the body) at offset ``t`` (m) from the centre of a strip of
    ``width`` (m) carrying unit pressure (1 Pa), plane strain.

    Johnson (1985) eq. (2.25b): u_z(x) = -(2/(pi E*)) int p(s) ln|x - s| ds + C. Integrating over the strip,
    u(t) = -(2/(pi E*)) [ (t + w/2) ln|(t + w/2)/d| - (t - w/2) ln|(t - w/2)/d| - w ].
    The 2D displacement is only defined up to a constant; the ``datum`` length d fixes it. Choosing d larger
    than the loaded domain makes the matrix positive definite (log kernel of a set of diameter < d), which the
    conjugate-gradient contact solver needs; the constant is absorbed into the rigid approach.
    """
    t = np.asarray(t, dtype=float) / datum
    w = width / datum
    bracket = _xlogx(t + 0.5 * w) - _xlogx(t - 0.5 * w) - w
    return -(2.0 / (np.pi * modulus)) * bracket * datum
