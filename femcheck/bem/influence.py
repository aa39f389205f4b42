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


def _corner(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """G(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|): a double antiderivative of 1/sqrt(X^2 + Y^2) (the X ln|X|
    and Y ln|Y| parts of the textbook form cancel between corners). 0 * asinh(inf) is taken as 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        gx = np.where(X != 0, X * np.arcsinh(Y / np.abs(X)), 0.0)
        gy = np.where(Y != 0, Y * np.arcsinh(X / np.abs(Y)), 0.0)
    return gx + gy


def love_rectangle(tx: np.ndarray, ty: np.ndarray, dx: float, dy: float, modulus: float) -> np.ndarray:
    """Normal surface displacement (m, into the body) at offset (tx, ty) (m) from the centre of a dx x dy
    rectangle carrying unit pressure (1 Pa) on an elastic half-space of combined modulus E* (Pa).

    Love (1929); seed 004 eqs 2.23-2.24 (there in dimensionless form); Johnson (1985) eq. 3.25:
    u = 1/(pi E*) int int dA / r = 1/(pi E*) [G(Xp, Yp) - G(Xp, Ym) - G(Xm, Yp) + G(Xm, Ym)],
    Xp,m = tx +/- dx/2, Yp,m = ty +/- dy/2. Works for any aspect ratio dy/dx (very elongated contacts).
    """
    tx, ty = np.asarray(tx, dtype=float), np.asarray(ty, dtype=float)
    xp, xm, yp, ym = tx + 0.5 * dx, tx - 0.5 * dx, ty + 0.5 * dy, ty - 0.5 * dy
    return (_corner(xp, yp) - _corner(xp, ym) - _corner(xm, yp) + _corner(xm, ym)) / (np.pi * modulus)
