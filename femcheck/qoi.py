"""Quantities of interest extracted from pressure samples: contact edges and peak pressures (shared by every model).

The estimators do not take their shape from Hertz. They assume only what holds near any contact edge and any
smooth maximum:

* :func:`edge` — near a contact edge the pressure follows a power law of the distance to it,
  p ~ c (a^2 - d^2)^alpha (d the distance from the contact centre), with alpha found from the data: 1/2 for an
  elastic half-space under a smooth profile (Hertz), 1 for a thin compressible layer on a rigid base (Winkler,
  Johnson 1985 §5.9), 2 for a thin incompressible one (squeeze film), -1/2 at the sharp edge of a flat punch
  (Johnson eq. 2.64). The fit uses only the samples within ``band`` of the edge (1D profiles: the outer 20 % of
  the contact; 2D fields, :func:`semi_axes`: the outer half, in strips along the axes, to average the P1 nodal
  scatter of 3D FE). Where the exponent itself varies across the band the band is narrowed, halving while the
  exponent fitted on its outer half drifts (beyond ``DRIFT_FLOOR`` and the fit's noise), down to ``MIN_DEPTH``
  sample distances. A layer of thickness h on a stiff base is the case in point: its pressure falls nearly
  linearly and turns into the square-root edge of any smooth elastic contact only within ~h of the edge; a band
  wider than that extrapolates past the edge (+1.4 % at h/a = 0.1, whatever the grid). With the narrowing the
  edge converges to the transform solution of the layer (docs/notes/layered-edge.md); on Hertz fields nothing
  drifts and the band asked for is kept. ``misfit`` says how well the power law holds; ``bias`` bounds what a
  remaining drift leaves.
* :func:`centre_value`, :func:`centre_value_2d` and :func:`peak` — a smooth maximum (or the value at a centre of
  symmetry) is the constant term of a local even quartic fitted over a window of half the contact size: exact
  for a parabolic field (thin layer), 3e-5 for Hertz, 2e-4 for the flat punch's centre (measured, see
  ``tests/test_qoi.py``). A maximum at a contact edge where the pressure rises into the edge (alpha < 0) is
  singular: it is reported as the largest sample and flagged, never as a converged value.

``contact_edge`` and ``ellipse_fit`` are the former least-squares fits of p^2, exact only for Hertzian fields;
they remain for the callers that locate crossings of other fields (friction_line) and for the peer benchmark.

The module is above 500 lines because the edge estimator, its band adaptation and its covariance share private
fitting helpers with the centre and peak fits; every model's quantities go through this one definition.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

# Edge exponents searched: regular edges (p -> 0) and singular ones (p -> infinity, the flat punch's -1/2).
REGULAR = (0.1, 4.0)
SINGULAR = (-0.95, -0.05)


@dataclass(frozen=True)
class Edge:
    """A contact edge: ``position`` (m, distance from the centre for :func:`edge`), the fitted exponent
    ``exponent`` (p ~ (a^2 - d^2)^alpha), ``misfit`` (rms of the fit in p over the band, relative to the band's
    largest pressure), ``singular`` (alpha < 0: the pressure is unbounded at the edge), ``points`` used,
    ``fitted`` (False when no power law could be fitted: the position is then the midpoint between the last
    loaded and the first unloaded sample), ``std`` (m): the standard error of ``position`` from the scatter of
    the samples about the fit (nonlinear least squares, exponent included; :func:`edge_std`).

    Band adaptation (:func:`edge`): ``band`` the band finally fitted (fraction of the outermost loaded distance),
    ``drift`` the change of the fitted exponent across the halvings that narrowed it (0 when the power law held
    over the band asked for), ``bias`` (m) a bound on what the exponent's drift still leaves in ``position``: the
    change of the edge between the last two bands (0 when not narrowed); ``bracket`` (m) the last loaded and the
    first unloaded sample distances (the count estimate is their midpoint, within half their gap)."""

    position: float
    exponent: float
    misfit: float
    singular: bool
    points: int
    fitted: bool = True
    std: float = float("nan")
    band: float = float("nan")
    drift: float = 0.0
    bias: float = 0.0
    bracket: tuple[float, float] = (float("nan"), float("nan"))

    @property
    def count_position(self) -> float:
        """Midpoint (m) between the last loaded and the first unloaded sample."""
        return 0.5 * (self.bracket[0] + self.bracket[1])

    @property
    def count_std(self) -> float:
        """Half the gap (m) between the last loaded and the first unloaded sample: the count's uncertainty."""
        return 0.5 * (self.bracket[1] - self.bracket[0])


@dataclass(frozen=True)
class Peak:
    """A peak pressure ``value`` (Pa) at ``position`` (m), from ``points`` samples; ``singular``: the maximum is
    at a contact edge where the pressure is unbounded, so ``value`` is the largest sample, mesh-dependent by
    nature; ``misfit`` of the local fit relative to ``value``; ``std`` (Pa): the standard error of ``value`` from
    the scatter of the samples about the fit."""

    value: float
    position: float
    singular: bool
    points: int
    misfit: float = 0.0
    std: float = float("nan")


def _misfit(pred: np.ndarray, p: np.ndarray) -> float:
    return float(np.sqrt(np.mean((pred - p) ** 2)))


def _power_fit(A: np.ndarray, p: np.ndarray, alpha: float) -> tuple[np.ndarray, float]:
    """Least squares of q = p^(1/alpha) on the columns of A; the misfit is measured back in p (comparable
    between exponents)."""
    coef, *_ = np.linalg.lstsq(A, p ** (1.0 / alpha), rcond=None)
    q = A @ coef
    if alpha > 0:
        pred = np.clip(q, 0.0, None) ** alpha
    else:
        if np.any(q <= 0):
            return coef, np.inf
        pred = q**alpha
    return coef, _misfit(pred, p)


def power_law_fit(A: np.ndarray, p: np.ndarray, singular: bool, exponent: float | None = None
                  ) -> tuple[float, np.ndarray, float]:
    """(alpha, coefficients, misfit) of p^(1/alpha) ~ A c with alpha in the regular or singular range (or the
    given ``exponent``): a grid search refined by Brent's method on the misfit in p. ``p`` normalised to ~1."""
    if exponent is not None:
        coef, mis = _power_fit(A, p, exponent)
        return exponent, coef, mis
    lo, hi = SINGULAR if singular else REGULAR
    grid = np.linspace(lo, hi, 40)
    mis = np.array([_power_fit(A, p, a)[1] for a in grid])
    j = int(np.argmin(mis))
    if not np.isfinite(mis[j]):
        return float(grid[j]), _power_fit(A, p, grid[j])[0], float("inf")
    res = minimize_scalar(lambda a: _power_fit(A, p, a)[1], bounds=(grid[max(j - 1, 0)], grid[min(j + 1, 39)]),
                          method="bounded", options={"xatol": 1e-7})
    alpha = float(res.x) if res.fun <= mis[j] else float(grid[j])
    coef, m = _power_fit(A, p, alpha)
    return alpha, coef, m


# Band adaptation of :func:`edge`. A change of the fitted exponent between a band and its outer half larger than
# DRIFT_FLOOR (and than 3 standard errors of the difference) means the power law does not hold across the band:
# the band is halved. 0.02 is above the exponent's wobble on Hertz fields sampled by the BEM (measured below 0.01
# at 65-257 cells and 1024 strips, tests/test_qoi.py) and far below the drift across a thin layer's edge boundary
# layer (0.1-0.3 per halving, docs/notes/layered-edge.md).
DRIFT_FLOOR = 0.02
# The narrowest band holds at least this many distinct sample distances (columns of a grid): three parameters
# (four with the transverse term) and the exponent need them.
MIN_DEPTH = 5


@dataclass(frozen=True)
class _Fit:
    position: float
    alpha: float
    misfit: float
    std: float
    alpha_std: float
    points: int
    fitted: bool


def _fit_band(d: np.ndarray, p: np.ndarray, y: np.ndarray | None, sel: np.ndarray, dk: float, nxt: float,
              singular: bool, exponent: float | None) -> _Fit:
    """The power law of :func:`edge` fitted to the samples ``sel``."""
    pn = p[sel] / p[sel].max()
    cols = [np.ones(sel.size), (d[sel] / dk) ** 2 - 1.0]      # scaled: the columns must be of order one
    if y is not None:
        cols.append((y[sel] / dk) ** 2)
    if sel.size < len(cols) + 1:
        return _Fit(float(0.5 * (dk + nxt)), float("nan"), float("nan"), float("nan"), float("nan"), int(sel.size),
                    False)
    A = np.stack(cols, axis=1)
    alpha, c, mis = power_law_fit(A, pn, singular, exponent)
    if not (np.isfinite(mis) and c[1] < 0 and 1.0 - c[0] / c[1] > 0):
        return _Fit(float(0.5 * (dk + nxt)), alpha, float(mis), float("nan"), float("nan"), int(sel.size), False)
    std, astd = _edge_covariance(A, pn, alpha, c, fit_exponent=exponent is None)
    return _Fit(float(dk * np.sqrt(1.0 - c[0] / c[1])), alpha, float(mis), dk * std, astd, int(sel.size), True)


def edge(d: np.ndarray, p: np.ndarray, band: float = 0.2, min_points: int = 5, transverse: np.ndarray | None = None,
         exponent: float | None = None, adapt: bool = True) -> Edge:
    """Contact edge (m, as a distance from the contact centre) from pressure samples ``p`` (Pa) at distances
    ``d`` >= 0 (m) from the centre on one side of it, to sub-sample accuracy, for any power-law edge.

    Model: p^(1/alpha) = c0 + c1 (d^2 - d_k^2) [+ c2 y^2] over the loaded samples with d >= (1 - band) d_k (d_k
    the outermost loaded sample; at least ``min_points`` samples), alpha fitted (or ``exponent``), edge
    a = sqrt(d_k^2 - c0 / c1). Exact for p = c (a^2 - d^2)^alpha whatever alpha: Hertz, thin layers, flat
    punch. ``transverse``: the samples' distance y (m) from the line on which the edge is sought (samples of a
    2D field in a strip along that line; the c2 y^2 term is the local curvature of the field across it).
    The branch is singular (alpha < 0) when the outermost loaded sample carries the band's largest pressure.
    No clipping to the samples: the root is the estimate (a clipped root would freeze the edge on a node).

    Band adaptation (``adapt``, exponent fitted): where the exponent is not constant across the band the
    power law's extrapolation misses the edge. A thin layer on a stiff base is the case in point: its pressure
    falls almost linearly (alpha ~ 1) and turns into the square-root edge of any smooth elastic contact only
    within ~h of the edge, so a band wider than h extrapolates past the edge (+1.4 % on a layer of h/a = 0.1,
    whatever the grid). The band is therefore halved while the exponent fitted on its outer half differs from the
    band's by more than ``DRIFT_FLOOR`` and 3 standard errors, down to ``MIN_DEPTH`` distinct sample distances:
    the band is chosen by the data's own exponent, not by a length the estimator is told. The result reports the
    band used, the exponent's ``drift`` and a ``bias`` bound (the edge's change over the last halving); as the
    samples refine the narrowest band shrinks into the boundary layer and the edge converges (measured against the
    Hankel-transform solution of the layer, :mod:`femcheck.analytic.layer_axisymmetric`: +0.9, +0.2, +0.06 % at
    65, 129, 257 BEM cells; docs/notes/layered-edge.md). Noisy samples (P1 FE reactions) raise the standard
    errors, so the band narrows only on a drift the noise cannot explain.
    """
    d = np.abs(np.asarray(d, dtype=float))
    p = np.asarray(p, dtype=float)
    y = None if transverse is None else np.asarray(transverse, dtype=float)
    loaded = np.flatnonzero(p > 0)
    if loaded.size == 0:
        raise ValueError("no loaded sample: the contact edge is undefined")
    dk = d[loaded].max()
    beyond = d[(p <= 0) & (d > dk)]
    nxt = beyond.min() if beyond.size else dk
    bracket = (float(dk), float(nxt))

    def select(b: float) -> np.ndarray:
        s = loaded[d[loaded] >= (1.0 - b) * dk]
        if s.size < min_points:
            s = loaded[np.argsort(d[loaded])[-min_points:]]
        return s

    sel = select(band)
    outer = sel[d[sel] >= dk * (1.0 - 1e-12)]
    singular = bool(exponent < 0) if exponent is not None else bool(
        p[outer].max() >= p[sel].max() and sel.size > outer.size
        and p[outer].max() > p[sel][np.argsort(d[sel])][-outer.size - 1])
    fit = _fit_band(d, p, y, sel, dk, nxt, singular, exponent)
    used, drift, bias = band, 0.0, 0.0
    if adapt and exponent is None and fit.fitted:
        # distinct sample distances from the outermost inwards: the narrowest band keeps MIN_DEPTH of them
        cols = np.unique(np.round(d[loaded] / dk, 9))[::-1]
        b_min = (1.0 - cols[MIN_DEPTH - 1]) * (1.0 + 1e-9) if cols.size >= MIN_DEPTH else band
        b = band
        while b > b_min * (1.0 + 1e-6):
            nb = max(0.5 * b, b_min)         # halve; the last step lands on the narrowest band
            inner = select(nb)
            if inner.size == sel.size:
                break
            half = _fit_band(d, p, y, inner, dk, nxt, singular, None)
            if not half.fitted:
                break
            step = abs(half.alpha - fit.alpha)
            noise = 3.0 * np.hypot(fit.alpha_std, half.alpha_std)
            if not (step > DRIFT_FLOOR and step > noise):
                break
            drift += step
            bias = abs(half.position - fit.position)
            fit, sel, b = half, inner, nb
        used = b
    return Edge(fit.position, fit.alpha, fit.misfit, singular, fit.points, fit.fitted, fit.std, float(used),
                float(drift), float(bias), bracket)


def _edge_covariance(A: np.ndarray, p: np.ndarray, alpha: float, c: np.ndarray, fit_exponent: bool = True
                     ) -> tuple[float, float]:
    """(standard error of t_e, standard error of alpha) of the fit p = (A c)^alpha (:func:`edge_std`)."""
    q = A @ c
    ok = q > 0
    n = p.size
    qa = np.where(ok, q, 1.0)
    pred = np.where(ok, qa**alpha, 0.0)
    cols = [np.where(ok, alpha * qa ** (alpha - 1.0), 0.0)[:, None] * A]
    if fit_exponent:
        cols.append(np.where(ok, pred * np.log(qa), 0.0)[:, None])
    J = np.hstack(cols)
    dof = n - J.shape[1]
    if dof <= 0:
        return float("nan"), float("nan")
    s2 = float(np.sum((p - pred) ** 2)) / dof
    try:
        cov = s2 * np.linalg.pinv(J.T @ J)
    except np.linalg.LinAlgError:
        return float("nan"), float("nan")
    te = np.sqrt(1.0 - c[0] / c[1])
    grad = np.zeros(J.shape[1])
    grad[0] = -0.5 / (te * c[1])                       # d t_e / d c0
    grad[1] = 0.5 * c[0] / (te * c[1] ** 2)            # d t_e / d c1
    astd = float(np.sqrt(max(cov[-1, -1], 0.0))) if fit_exponent else 0.0
    return float(np.sqrt(max(grad @ cov @ grad, 0.0))), astd


def edge_std(A: np.ndarray, p: np.ndarray, alpha: float, c: np.ndarray, fit_exponent: bool = True) -> float:
    """Standard error of the edge t_e = sqrt(1 - c0/c1) (in units of the scaling length) of the model
    p = (A c)^alpha: Gauss-Newton covariance s^2 (J^T J)^-1 of the parameters (c, and alpha when it was fitted)
    from the residuals in p, propagated to t_e. A statistical measure of how well the samples fix the edge
    (node-to-node scatter of FE reactions), not of the discretisation error."""
    return _edge_covariance(A, p, alpha, c, fit_exponent)[0]


def edges(x: np.ndarray, p: np.ndarray, centre: float = 0.0, **kw) -> tuple[Edge, Edge | None]:
    """(right, left) edges of a 1D profile about ``centre`` (m); left is None for a profile on x >= centre
    only (a symmetric half model). Keywords go to :func:`edge`."""
    x = np.asarray(x, dtype=float)
    p = np.asarray(p, dtype=float)
    right = x >= centre
    r = edge(x[right] - centre, p[right], **kw)
    left = x <= centre
    if np.count_nonzero(p[left & (x < centre)] > 0) == 0:
        return r, None
    return r, edge(centre - x[left], p[left], **kw)


def semi_axes(X: np.ndarray, Y: np.ndarray, p: np.ndarray, strip: float = 0.5, band: float = 0.5,
              min_points: int = 8) -> tuple[float, float, dict[str, Edge]]:
    """Semi-axes (m) of a 2D contact centred on the origin with the axes x, y as its symmetry lines, from a full
    field (averaging the edges on both sides) or a quarter model's samples (x, y >= 0).

    The edge on each half-axis is :func:`edge` fitted to the samples in a strip along that axis, |y| < ``strip``
    times the contact's extent across (the power law in d^2 with a y^2 term: a local quadratic model of
    p^(1/alpha) near where the edge crosses the axis, with alpha fitted). A strip, not only the samples on the
    axis: the edge then crosses cells (or elements) at every sub-cell position along it, so the discretisation's
    edge bias averages out instead of depending on where the axis meets the grid. Assumes the contact is
    symmetric about both axes and its edge is smooth where it crosses them."""
    X, Y, p = (np.asarray(v, dtype=float).ravel() for v in (X, Y, p))
    loaded = p > 0
    ext = {"x": np.abs(X[loaded]).max(), "y": np.abs(Y[loaded]).max()}
    fits: dict[str, Edge] = {}
    out = []
    for axis, u, v, across in (("x", X, Y, ext["y"]), ("y", Y, X, ext["x"])):
        near = np.abs(v) < strip * across
        sides = []
        for sign, name in ((1.0, "+"), (-1.0, "-")):
            s = near & (sign * u >= 0)
            if np.count_nonzero(s & loaded & (sign * u > 0)) == 0:
                continue
            e = edge(sign * u[s], p[s], band=band, min_points=min_points, transverse=v[s])
            fits[f"{axis}{name}"] = e
            sides.append(e.position)
        out.append(float(np.mean(sides)))
    return out[0], out[1], fits


def mean_std(edges_: list[Edge]) -> float:
    """Standard error (m) of the mean position of independent edge estimates."""
    return float(np.sqrt(sum(e.std**2 for e in edges_)) / len(edges_))


def half_width(x: np.ndarray, p: np.ndarray, centre: float | None = None) -> float:
    """Contact half-width (m) of a 1D profile: half the distance between its two edges (:func:`edge`), about
    the midpoint of the loaded samples (or ``centre``). For a profile on x >= 0 only (symmetric half model,
    x[0] == 0) it is the right edge."""
    x = np.asarray(x, dtype=float)
    p = np.asarray(p, dtype=float)
    if x.min() >= 0 and centre is None:
        return edges(x, p, 0.0)[0].position
    if centre is None:
        loaded = x[p > 0]
        centre = 0.5 * (loaded.min() + loaded.max())
    r, left = edges(x, p, centre)
    return r.position if left is None else 0.5 * (r.position + left.position)


def _even_fit(cols: list[np.ndarray], p: np.ndarray) -> tuple[np.ndarray, float, float]:
    """(coefficients, rms misfit, standard error of the constant term) of a linear least-squares fit."""
    A = np.stack(cols, axis=1)
    c, *_ = np.linalg.lstsq(A, p, rcond=None)
    r = p - A @ c
    dof = p.size - A.shape[1]
    std = float("nan")
    if dof > 0:
        std = float(np.sqrt(max(np.sum(r**2) / dof * np.linalg.pinv(A.T @ A)[0, 0], 0.0)))
    return c, _misfit(A @ c, p), std


def centre_value(x: np.ndarray, p: np.ndarray, radius: float, centre: float = 0.0, min_points: int = 5) -> Peak:
    """Pressure (Pa) at the centre of symmetry ``centre`` (m) of a 1D profile: constant term of
    p = c0 + c1 t^2 + c2 t^4 (t = x - centre) fitted over |t| < ``radius`` (m; at least ``min_points``
    samples). Assumes the field is smooth and even about the centre over the window (exact for a parabola;
    window a/2: 3e-5 for Hertz, 2e-4 for the flat punch's centre). Averages out node-to-node scatter."""
    t = np.asarray(x, dtype=float) - centre
    p = np.asarray(p, dtype=float)
    sel = np.abs(t) < radius
    if sel.sum() < min_points:
        sel = np.argsort(np.abs(t))[:min_points]
    u = t[sel] / radius
    c, mis, std = _even_fit([np.ones(np.size(u)), u**2, u**4], p[sel])
    return Peak(float(c[0]), float(centre), False, int(np.size(u)), mis / max(abs(c[0]), 1e-300), std)


def centre_value_2d(X: np.ndarray, Y: np.ndarray, p: np.ndarray, rx: float, ry: float, min_points: int = 12) -> Peak:
    """Pressure (Pa) at the centre of symmetry (the origin) of a 2D field symmetric in x and y (a quarter
    model's nodes, or a full grid): constant term of p = c0 + c1 x^2 + c2 y^2 + c3 x^4 + c4 x^2 y^2 + c5 y^4
    fitted over the window (x/rx)^2 + (y/ry)^2 < 1 (m). Assumes the field is smooth and even in x and y over
    the window; with rx, ry half the contact's semi-axes the bias is that of :func:`centre_value`."""
    X, Y, p = (np.asarray(v, dtype=float).ravel() for v in (X, Y, p))
    r2 = (X / rx) ** 2 + (Y / ry) ** 2
    sel = np.flatnonzero(r2 < 1.0)
    if sel.size < min_points:
        sel = np.argsort(r2)[:min_points]
    x, y = X[sel] / rx, Y[sel] / ry
    c, mis, std = _even_fit([np.ones(sel.size), x * x, y * y, x**4, x * x * y * y, y**4], p[sel])
    return Peak(float(c[0]), 0.0, False, int(sel.size), mis / max(abs(c[0]), 1e-300), std)


def symmetric_contact(X: np.ndarray, Y: np.ndarray, p: np.ndarray, window: float = 0.5, strip: float = 0.5,
                      band: float = 0.5) -> dict[str, float]:
    """Peak pressure and semi-axes of a contact symmetric about the x and y axes, from a full field or from a
    quarter model's samples (x, y >= 0): ``p_max`` = :func:`centre_value_2d` over ``window`` times the loaded
    extents (the peak of such a contact is at its centre), ``semi_axis_x``, ``semi_axis_y`` =
    :func:`semi_axes`; their standard errors ``<q>_std`` (and ``contact_area_std`` of pi a b); the edge exponents
    ``exponent_x``, ``exponent_y`` and the centre fit's misfit."""
    X, Y, p = (np.asarray(v, dtype=float).ravel() for v in (X, Y, p))
    loaded = p > 0
    ex, ey = np.abs(X[loaded]).max(), np.abs(Y[loaded]).max()
    ax, ay, fits = semi_axes(X, Y, p, strip, band)
    c = centre_value_2d(X, Y, p, window * ax, window * ay)
    sx = mean_std([e for k, e in fits.items() if k[0] == "x"])
    sy = mean_std([e for k, e in fits.items() if k[0] == "y"])
    return {"p_max": c.value, "semi_axis_x": ax, "semi_axis_y": ay,
            "p_max_std": c.std, "semi_axis_x_std": sx, "semi_axis_y_std": sy,
            "contact_area_std": float(np.pi * ax * ay * np.hypot(sx / ax, sy / ay)),
            "exponent_x": float(np.mean([e.exponent for k, e in fits.items() if k[0] == "x"])),
            "exponent_y": float(np.mean([e.exponent for k, e in fits.items() if k[0] == "y"])),
            "centre_misfit": c.misfit, "loaded_extent_x": float(ex), "loaded_extent_y": float(ey)}


def value_on_axis(X: np.ndarray, Y: np.ndarray, p: np.ndarray, y0: float, rx: float, ry: float,
                  min_points: int = 10) -> Peak:
    """Pressure (Pa) at (0, ``y0``) on a symmetry line x = 0 of a 2D field: constant term of
    p = c0 + c1 x^2 + c2 t + c3 t^2 + c4 x^2 t (t = y - y0) over |x| < ``rx``, |t| < ``ry`` (m). Assumes the
    field is smooth over the window (a measure that converges where the peak itself does not: e.g. at a fixed
    distance from a sharp edge whose peak is singular)."""
    X, Y, p = (np.asarray(v, dtype=float).ravel() for v in (X, Y, p))
    sel = np.flatnonzero((np.abs(X) < rx) & (np.abs(Y - y0) < ry))
    if sel.size < min_points:
        raise ValueError(f"{sel.size} samples in the window around y = {y0:g} m; need {min_points}")
    x, t = X[sel] / rx, (Y[sel] - y0) / ry
    c, mis, std = _even_fit([np.ones(sel.size), x * x, t, t * t, x * x * t], p[sel])
    return Peak(float(c[0]), float(y0), False, int(sel.size), mis / max(abs(c[0]), 1e-300), std)


def peak(x: np.ndarray, p: np.ndarray, window: float = 0.5, centre: float | None = None) -> Peak:
    """Peak pressure (Pa) of a 1D profile, whatever its shape.

    If the largest sample is the outermost loaded one on its side and the pressure rises into it, the peak is
    at a singular edge (flat punch, sharp roller end): the largest sample is returned, flagged ``singular``.
    Otherwise a local quartic is fitted over ``window`` times the contact half-size around the largest sample
    (an even one about ``centre`` when the largest sample lies within half the window of it, as for symmetric
    contacts) and its largest value in the window is the peak. Assumes a smooth maximum over the window."""
    x = np.asarray(x, dtype=float)
    p = np.asarray(p, dtype=float)
    loaded = np.flatnonzero(p > 0)
    if loaded.size == 0:
        raise ValueError("no loaded sample: the peak is undefined")
    i = int(loaded[np.argmax(p[loaded])])
    lo, hi = loaded.min(), loaded.max()
    half_model = centre is not None and x[lo] >= centre       # the profile starts on the symmetry line
    ends = ((hi, hi - 1),) if half_model else ((hi, hi - 1), (lo, lo + 1))
    for end, inner in ends:
        if i == end and 0 <= inner < x.size and 0 < p[inner] < p[i]:
            return Peak(float(p[i]), float(x[i]), True, 1)
    if half_model:
        half = x[hi] - centre
    else:
        half = 0.5 * (x[hi] - x[lo])
    w = window * half
    if centre is not None and abs(x[i] - centre) < 0.5 * w:
        t = x - centre
        sel = np.flatnonzero(np.abs(t) < w)
        if sel.size < 5:
            sel = np.argsort(np.abs(t))[:5]
        u = t[sel] / w
        c, mis, std = _even_fit([np.ones(sel.size), u**2, u**4], p[sel])
        uu = np.linspace(0.0, np.abs(u).max(), 1001)
        val = c[0] + c[1] * uu**2 + c[2] * uu**4
        tt = uu * w
        j = int(np.argmax(val))
        # the maximum's standard error is taken as the constant term's (exact when the maximum is the centre)
        return Peak(float(val[j]), float(centre + tt[j]), False, int(sel.size), mis / val[j], std)
    t = x - x[i]
    sel = np.flatnonzero((np.abs(t) < w) & (p > 0))
    if sel.size < 6:
        return Peak(float(p[i]), float(x[i]), False, 1)
    A = np.stack([(t[sel] / w) ** k for k in range(5)], axis=1)
    c, *_ = np.linalg.lstsq(A, p[sel], rcond=None)
    tt = np.linspace(t[sel].min(), t[sel].max(), 2001)
    val = np.polyval(c[::-1], tt / w)
    j = int(np.argmax(val))
    return Peak(float(val[j]), float(x[i] + tt[j]), False, int(sel.size), _misfit(A @ c, p[sel]) / val[j])


def contact_edge(x: np.ndarray, p: np.ndarray, band: float | None = None) -> float:
    """Hertzian edge estimate (m) on the side of increasing x: a least-squares quadratic of p^2 over the loaded
    points within ``band`` (m) of the last loaded one (default 20 % of the loaded extent, at least 4 points),
    root clipped to [x_(k-1), x_(k+1)]. Exact only where p^2 is quadratic (Hertz); kept for locating the
    crossings of other fields (friction_line's stick-slip boundaries). Pressure edges use :func:`edge`."""
    x = np.asarray(x, dtype=float)
    p = np.asarray(p, dtype=float)
    loaded = np.flatnonzero(p > 0)
    if loaded.size == 0:
        raise ValueError("no loaded point: the contact edge is undefined")
    k = loaded[-1]
    if k == x.size - 1:
        return float(x[k])          # contact reaches the end of the domain: the caller must check
    lo, hi = x[max(k - 1, 0)], x[k + 1]
    if band is None:
        band = 0.2 * (x[k] - x[loaded[0]])
    sel = loaded[x[loaded] >= x[k] - band]
    if sel.size < 4:
        sel = loaded[-4:]
    if sel.size < 2:
        return float(0.5 * (lo + hi))
    scale = hi - lo
    t = (x[sel] - lo) / scale           # the root sought lies in t = [0, 1]
    q = (p[sel] / p[sel].max()) ** 2
    coef = np.polyfit(t, q, 2 if sel.size >= 4 else 1)
    roots = np.roots(coef)
    roots = roots[np.isreal(roots)].real
    if roots.size == 0:
        return float(0.5 * (lo + hi))
    edge_ = lo + scale * roots[np.argmin(np.abs(roots - 0.5))]
    return float(np.clip(edge_, lo, hi))


def ellipse_fit(X: np.ndarray, Y: np.ndarray, p: np.ndarray) -> dict[str, float]:
    """Contact ellipse of a 2D pressure field by a least-squares fit of p^2 with a full quadratic (exact only
    for a Hertzian field p^2 = p0^2 (1 - x^2/a^2 - y^2/b^2)); semi-axes from the quadratic's centre to its zero
    level, ``peak`` the fitted maximum (Pa), ``fit_residual`` the rms misfit of p^2 / p_max^2. Not used for
    reference quantities: :func:`edge` and :func:`centre_value_2d` do not assume the shape."""
    q = np.asarray(p, dtype=float) ** 2
    sel = q > 0
    if sel.sum() < 6:
        raise ValueError("fewer than 6 loaded cells: no ellipse can be fitted")
    qm = q.max()
    x, y, z = X[sel], Y[sel], q[sel] / qm
    basis = np.stack([np.ones_like(x), x, y, x * x, x * y, y * y], axis=1)
    c, *_ = np.linalg.lstsq(basis, z, rcond=None)
    M = np.array([[2 * c[3], c[4]], [c[4], 2 * c[5]]])
    x0, y0 = np.linalg.solve(M, -c[1:3])
    top = c[0] + c[1] * x0 + c[2] * y0 + c[3] * x0**2 + c[4] * x0 * y0 + c[5] * y0**2
    if not (top > 0 and c[3] < 0 and c[5] < 0):
        raise ValueError("loaded region is not elliptical (fitted p^2 has no maximum)")
    return {"semi_axis_x": float(np.sqrt(-top / c[3])), "semi_axis_y": float(np.sqrt(-top / c[5])),
            "centre_x": float(x0), "centre_y": float(y0), "peak": float(np.sqrt(top * qm)),
            "fit_residual": float(np.sqrt(np.mean((basis @ c - z) ** 2)))}
