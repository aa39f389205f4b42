"""Contact edges located from the separation of the surfaces outside the contact, not from the pressure.

Where a discrete pressure is accurate inside the contact but not at its edge (the nodal values of a mortar
multiplier overshoot at the last active nodes and undershoot at the last one: +7 % and -17 % of p0 at a/8 in
hertz-point), the primal field locates the edge better: the separation g = h - delta - u_z is a displacement,
continuous and resolved to the displacement's order by quadratic elements.

Near the edge of any contact whose pressure has a square-root edge (every smooth, non-conforming elastic contact:
Johnson 1985 §4.2 and eq. 3.42b for the separation outside the Hertz contact; layered bodies included, whose
pressure turns square-root within the layer's boundary layer) the separation grows as the 3/2 power of the
distance from the edge. In the variable t = d^2 + k y^2 - a^2 (d the distance from the centre along the axis,
y across it, k the local curvature of the edge where it crosses the axis) the model is

    g = c max(t, 0)^(3/2) (1 + c1 t + c2 t^2),

the regular expansion of the separation in t; samples inside the contact carry g ~ 0 and fix the edge from the
other side. On the exact Hertz separation sampled every a/16 over a band of 0.3 a beyond the edge the model
finds the edge within 2e-4 of a (1e-2 with the pure power law, 1.5e-3 with one correction term): see
tests/test_qoi_separation.py.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

EXPONENT = 1.5      # separation ~ distance^(3/2) outside a square-root pressure edge (Johnson eq. 3.42b)
TERMS = 2           # correction terms c1 t, c2 t^2


@dataclass(frozen=True)
class SeparationEdge:
    """Edge position (m) along one half-axis, its standard error (m, from the fit's covariance), the number of
    samples and the relative rms misfit of the model."""

    position: float
    std: float
    points: int
    misfit: float


def separation_edge(d: np.ndarray, g: np.ndarray, rough: float, band: float = 0.3, inside: float = 0.15,
                    transverse: np.ndarray | None = None) -> SeparationEdge:
    """Edge (m) from separations ``g`` (m) at distances ``d`` >= 0 (m) from the contact centre along one
    half-axis, optionally at distances ``transverse`` (m) across it (a strip of samples). ``rough``: an edge
    estimate (m, e.g. the outermost loaded node); the samples used lie within [1 - ``inside``, 1 + ``band``]
    times it."""
    d = np.abs(np.asarray(d, dtype=float))
    g = np.asarray(g, dtype=float)
    y = np.zeros_like(d) if transverse is None else np.asarray(transverse, dtype=float)
    sel = (d >= (1.0 - inside) * rough) & (d <= (1.0 + band) * rough)
    d, g, y = d[sel], g[sel], y[sel]
    n_par = 3 + TERMS
    if d.size < n_par + 2 or not (g > 0).any():
        raise ValueError(f"separation edge: {d.size} samples in the band, {n_par + 2} needed")
    scale = rough * rough
    s, yy, gs = d**2 / scale, y**2 / scale, g / g.max()

    def model(q):
        t = np.maximum(s + q[2] * yy - q[0], 0.0)
        poly = 1.0 + sum(q[3 + k] * t ** (k + 1) for k in range(TERMS))
        return q[1] * t**EXPONENT * poly

    q0 = np.array([1.0, 1.0 / max(s.max() - 1.0, 1e-3) ** EXPONENT, 0.0] + [0.0] * TERMS)
    fit = least_squares(lambda q: model(q) - gs, q0, x_scale="jac", method="lm")
    if not fit.success or fit.x[0] <= 0:
        raise ValueError("separation edge: the fit did not converge")
    res = fit.fun
    dof = max(d.size - n_par, 1)
    s2 = float(res @ res) / dof
    try:
        cov = np.linalg.inv(fit.jac.T @ fit.jac) * s2
        var_a2 = max(float(cov[0, 0]), 0.0)
    except np.linalg.LinAlgError:
        var_a2 = np.inf
    a = rough * np.sqrt(fit.x[0])
    std = 0.5 * rough * np.sqrt(var_a2) / np.sqrt(fit.x[0])
    misfit = float(np.sqrt(np.mean(res**2)))
    return SeparationEdge(float(a), float(std), int(d.size), misfit)


def semi_axes(X: np.ndarray, Y: np.ndarray, g: np.ndarray, rough_x: float, rough_y: float, strip: float = 0.3, inside: float = 0.15,
              band: float = 0.3) -> dict[str, float]:
    """Semi-axes (m) of a contact symmetric about x = 0 and y = 0 from the separation ``g`` (m) sampled at
    (``X``, ``Y``) (m; a quarter model's face, x, y >= 0), each from the samples in a strip |y| < ``strip`` times
    the other semi-axis along its axis. ``rough_x``, ``rough_y``: edge estimates (m) that place the bands.
    Returns ``semi_axis_x``, ``semi_axis_y`` and their ``_std`` (m) and sample counts."""
    X, Y, g = (np.abs(np.asarray(v, dtype=float)).ravel() if i < 2 else np.asarray(v, dtype=float).ravel()
               for i, v in enumerate((X, Y, g)))
    out: dict[str, float] = {}
    for axis, u, v, rough, across in (("x", X, Y, rough_x, rough_y), ("y", Y, X, rough_y, rough_x)):
        near = v < strip * across
        e = separation_edge(u[near], g[near], rough, band=band, inside=inside, transverse=v[near])
        out[f"semi_axis_{axis}"] = e.position
        out[f"semi_axis_{axis}_std"] = e.std
        out[f"semi_axis_{axis}_points"] = e.points
        out[f"semi_axis_{axis}_misfit"] = e.misfit
    return out
