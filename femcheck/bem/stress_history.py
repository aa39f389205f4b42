"""Stress-amplitude history of a rolling pass from surface pressures: smooth contact, pseudo-transient
superposition and full transient (seed 004 §4.2.2; spec ``specs/ehl-life.md`` B.1).

Input: pressures on a regular grid of cells (:class:`PressureMap`, cell centres x, y in m, pressure in Pa; the
contact centre at x = y = 0, x the rolling direction). The pressure must vanish at the edges of its grid (dry: the
contact does not reach them; EHL: ambient pressure on the boundary), so the stresses are computed on a grid
extended with zero pressure wherever the pass needs them. Stresses: Love's rectangle kernels
(:func:`femcheck.bem.stress.rectangle_stress`, homogeneous elastic half-space, frictionless surface, residual
stresses left out: they do not change a stress amplitude), DC-FFT per depth plane. The stress-amplitude criterion
is the thesis' choice: the largest von Mises stress of the *tensor sum* a material point sees during the pass.

Smooth contact: every material point of the track sees the same field pass, so the history
T_S(y, z) = max over x of sigma_VM(x, y, z) does not depend on the rolling coordinate.

Dented contact, pseudo-transient (eq 4.5): with sigma_S the smooth field and sigma_D the field of the additional
pressure dP = p_dented - p_smooth of the indent at its *centred* position (x_D0, y_D), a material point at
xi = x - x_D from the indent (it moves with the surface in pure rolling) sees, when the indent is at x_D,

    sigma(xi, y, z; x_D) = sigma_S(xi + x_D, y, z) + chi(x_D) sigma_D(xi + x_D0, y, z)   (+ contact correction)
    T(xi, y, z) = max over x_D of sigma_VM[sigma(xi, y, z; x_D)]

Two choices the thesis leaves open, fixed here:

- chi ("sigma_D has no meaning when the indent is out of the contact"): chi = 1 while the indent centre is inside
  the contact, |x_D| <= X_chi, 0 otherwise; X_chi = the contact's half-length at the indent's y (b for y_D = 0) by
  default. The benchmark ``benchmarks/life_transient.py`` reports the sensitivity (X_chi = 0.5 b).
- the contact condition ("some special care is needed when the two stress distributions are assembled"): the
  emulated pressure p_S(x) + chi dP(x - x_D) must stay >= 0. It does not for a zone-B indent (the hole is unloaded,
  dP = -p_S(0) there) away from the centre, where p_S < p_S(0): the plain sum makes the hole pull on the surface
  and overestimates sigma_Dmax by 4-10 % against the full transient. The "contact" form (default) adds the stress
  of the clipped part max(0, -(p_S + chi dP)) at that position (one extra convolution per position where it is
  non-zero); the "linear" form is eq 4.5 as printed. For zone-A indents the two coincide.

x_D runs over the grid's cell positions (the pass is sampled at the cell size). Without clipping the cross term is
evaluated as sigma_VM(A + B)^2 = sigma_VM(A)^2 + sigma_VM(B)^2 + 3 dev A : dev B (+ shear terms), one dot product
per shift.

Full transient: the pressure of the indent solved at every position x_D in a range (``frames``); outside that
range the indent is out of the contact and the smooth field applies. Same max over the pass.

What an EHL model must provide to use this module unchanged: (a) the smooth pressure and the pressure with the
indent centred, on the same uniform grid (:class:`PressureMap`: cell centres x, y in m with the contact centre at
x = y = 0, any extent, dx and dy need not be equal, the indent centre on a cell centre, p = 0 on the grid's edges),
for the pseudo-transient; or (b) for the full transient, the pressures with the indent moved by whole cells along
x (the NU2 scheme's Courant number 1 moves it exactly one cell per time step), as ``{shift: pressure}``; plus the
Poisson ratio of the indented body, and for the life quantities the Hertz semi-axis b and p_H
(:func:`femcheck.problems._life_output.indent_life`). Surface tractions (sliding, EHL shear) are not included: the
kernels are those of a normal pressure only, so a traction field cannot be passed yet.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from ..errors import InputError
from .convolution import DCFFT
from .layered_stress import strip_stress
from .stress import COMPONENTS, rectangle_stress

EDGE_TOL = 1e-9      # pressure allowed on the edge of a grid the stresses extend (relative to its maximum)
# weights turning a stress tensor B into the vector w such that A . w = 3 dev A : dev B + 6 (shear A . shear B)
_CROSS_SHEAR = 6.0


@dataclass(frozen=True)
class PressureMap:
    """Pressure (Pa) on cells of a regular grid: centres ``x`` (nx,), ``y`` (ny,) in m (uniform, increasing),
    ``pressure`` (nx, ny). The contact centre is x = y = 0; the pressure must vanish on the grid's edges."""

    x: np.ndarray
    y: np.ndarray
    pressure: np.ndarray

    def __post_init__(self):
        x, y, p = (np.asarray(v, dtype=float) for v in (self.x, self.y, self.pressure))
        if x.ndim != 1 or y.ndim != 1 or x.size < 3 or y.size < 3:
            raise InputError("pressure", "x and y must be 1D arrays of at least 3 cell centres")
        if p.shape != (x.size, y.size):
            raise InputError("pressure", f"shape {p.shape} does not match the grid ({x.size}, {y.size})")
        for name, c in (("x", x), ("y", y)):
            d = np.diff(c)
            if d.min() <= 0 or np.ptp(d) > 1e-6 * d.mean():
                raise InputError("pressure", f"cell centres {name} must be uniform and increasing")
        if not np.all(np.isfinite(p)):
            raise InputError("pressure", "non-finite pressure")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)
        object.__setattr__(self, "pressure", p)

    @property
    def dx(self) -> float:
        return float(self.x[1] - self.x[0])

    @property
    def dy(self) -> float:
        return float(self.y[1] - self.y[0])

    @classmethod
    def on_grid(cls, grid, pressure: np.ndarray) -> "PressureMap":
        """From a :class:`femcheck.bem.halfspace.Grid` (cells centred on the origin)."""
        return cls(grid.x, grid.y, pressure)


@dataclass
class StressHistory:
    """Stress-amplitude history of one pass (Pa), on depth planes ``depths`` (m) with quadrature weights
    ``depth_weights`` (m), across-track cells ``y`` (m) with window weights ``y_weights`` (m).

    ``smooth[k, j]`` = T_S(y_j, z_k) of the smooth contact. For a dented contact also ``amplitude[k, i, j]`` =
    T(xi_i, y_j, z_k) at material positions ``xi`` (m, from the indent centre) with weights ``xi_weights`` (m);
    None for a smooth contact (T_S is the same for every xi)."""

    depths: np.ndarray
    depth_weights: np.ndarray
    y: np.ndarray
    y_weights: np.ndarray
    smooth: np.ndarray
    xi: np.ndarray | None = None
    xi_weights: np.ndarray | None = None
    amplitude: np.ndarray | None = None
    stats: dict = field(default_factory=dict)


# ---------------------------------------------------------------------------------------------------------------
# stresses on one depth plane
# ---------------------------------------------------------------------------------------------------------------

class PlaneStresses:
    """The six stress components (Pa per Pa) on depth plane ``z`` (m) of cell-wise uniform pressure on an
    (nx, ny) grid of dx x dy cells: one DC-FFT operator per component, the kernel evaluated once."""

    def __init__(self, shape: tuple[int, int], dx: float, dy: float, z: float, nu: float, workers: int = -1):
        cache: dict[str, np.ndarray] = {}

        def kernel(name):
            def f(tx, ty):
                if not cache:
                    cache.update(rectangle_stress(tx, ty, z, dx, dy, nu))
                return cache[name]
            return f

        self.ops = [DCFFT(kernel(name), shape, (dx, dy), workers=workers) for name in COMPONENTS]

    def __call__(self, p: np.ndarray) -> np.ndarray:
        return np.stack([op(p) for op in self.ops])


def von_mises_squared(s: np.ndarray) -> np.ndarray:
    """sigma_VM^2 of stacked components s[0..5] = (sx, sy, sz, txy, txz, tyz) (Pa^2)."""
    sx, sy, sz, txy, txz, tyz = s
    return 0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3.0 * (txy * txy + txz * txz + tyz * tyz)


def cross_weights(s: np.ndarray) -> np.ndarray:
    """w(B) with A . w(B) = sigma_VM(A + B)^2 - sigma_VM(A)^2 - sigma_VM(B)^2 = 3 dev A : dev B + 6 shear terms."""
    mean = (s[0] + s[1] + s[2]) / 3.0
    return np.stack([3.0 * (s[0] - mean), 3.0 * (s[1] - mean), 3.0 * (s[2] - mean),
                     _CROSS_SHEAR * s[3], _CROSS_SHEAR * s[4], _CROSS_SHEAR * s[5]])


# ---------------------------------------------------------------------------------------------------------------
# grids
# ---------------------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class _StressGrid:
    """The pressure grid extended by whole cells: stress-grid index = pressure-grid index + (ox, oy)."""

    nx: int
    ny: int
    ox: int
    oy: int
    x: np.ndarray
    y: np.ndarray

    def embed(self, p: np.ndarray) -> np.ndarray:
        out = np.zeros((self.nx, self.ny))
        out[self.ox:self.ox + p.shape[0], self.oy:self.oy + p.shape[1]] = p
        return out


def _extend(pm: PressureMap, x_range: tuple[float, float], y_range: tuple[float, float]) -> _StressGrid:
    """Smallest extension of pm's grid by whole cells covering [x_range] x [y_range] (m) and pm itself."""
    nx, ny = pm.x.size, pm.y.size
    i_lo = min(0, int(np.floor((x_range[0] - pm.x[0]) / pm.dx + 1e-9)))
    i_hi = max(nx - 1, int(np.ceil((x_range[1] - pm.x[0]) / pm.dx - 1e-9)))
    j_lo = min(0, int(np.floor((y_range[0] - pm.y[0]) / pm.dy + 1e-9)))
    j_hi = max(ny - 1, int(np.ceil((y_range[1] - pm.y[0]) / pm.dy - 1e-9)))
    p, top = pm.pressure, max(float(np.abs(pm.pressure).max()), 1e-300)
    # along x always (the pass must cover the whole contact), across y where the grid is extended
    edges = [p[0], p[-1]] + ([p[:, 0], p[:, -1]] if (j_lo < 0 or j_hi > ny - 1) else [])
    worst = max((float(np.abs(e).max()) for e in edges), default=0.0) / top
    if worst > EDGE_TOL:
        raise InputError("pressure", f"the pressure on the edge of its grid is {worst:.3g} of its maximum; the pass "
                         f"must cover the whole contact and the stress grid extends the pressure with zeros, so it "
                         f"must vanish there (allowed: <= {EDGE_TOL:g})")
    x = pm.x[0] + np.arange(i_lo, i_hi + 1) * pm.dx
    y = pm.y[0] + np.arange(j_lo, j_hi + 1) * pm.dy
    return _StressGrid(x.size, y.size, -i_lo, -j_lo, x, y)


def _window(coords: np.ndarray, spacing: float, centre: float, half: float | None) -> tuple[np.ndarray, np.ndarray]:
    """Indices of the cells overlapping [centre - half, centre + half] and their overlap lengths (m); every cell
    with its full length when ``half`` is None."""
    if half is None:
        return np.arange(coords.size), np.full(coords.size, spacing)
    from ..analytic.life import window_weights

    w = window_weights(coords, spacing, half, centre)
    idx = np.flatnonzero(w > 0)
    return idx, w[idx]


def _check_window(y_half: float | None, depths: np.ndarray, depth_weights: np.ndarray) -> None:
    if y_half is not None and not (0 < y_half < np.inf):
        raise InputError("life.window", f"{y_half} m is not allowed; allowed: (0, inf) m")
    if depths.ndim != 1 or depths.shape != depth_weights.shape or depths.min() <= 0:
        raise InputError("numerics.life_depths", "depth planes must be positive with one weight each")


def _edge_pressure(pm: PressureMap) -> float:
    p = pm.pressure
    return float(max(np.abs(p[0]).max(), np.abs(p[-1]).max(), np.abs(p[:, 0]).max(), np.abs(p[:, -1]).max()))


def _complement_max(vm2: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """max of vm2[X, j] over X outside [lo_q, hi_q] (per material point q; indices may leave the grid), for
    every q and j: prefix and suffix maxima along X. Returns (nq, ny); 0 where nothing is left."""
    n = vm2.shape[0]
    pre = np.maximum.accumulate(vm2, axis=0)
    suf = np.maximum.accumulate(vm2[::-1], axis=0)[::-1]
    left = np.where((lo - 1 >= 0)[:, None], pre[np.clip(lo - 1, 0, n - 1)], 0.0)
    right = np.where((hi + 1 <= n - 1)[:, None], suf[np.clip(hi + 1, 0, n - 1)], 0.0)
    return np.maximum(left, right)


# ---------------------------------------------------------------------------------------------------------------
# histories
# ---------------------------------------------------------------------------------------------------------------

def smooth_history(pm: PressureMap, nu: float, depths: np.ndarray, depth_weights: np.ndarray,
                   y_half: float | None, y_centre: float = 0.0, workers: int = -1) -> StressHistory:
    """T_S(y, z) = max over x of sigma_VM below a smooth contact, on the cells within ``y_half`` (m) of
    ``y_centre`` (None: every cell of the grid across)."""
    depths, depth_weights = np.asarray(depths, float), np.asarray(depth_weights, float)
    _check_window(y_half, depths, depth_weights)
    yr = (y_centre - y_half, y_centre + y_half) if y_half is not None else (pm.y[0], pm.y[-1])
    g = _extend(pm, (pm.x[0], pm.x[-1]), yr)
    jw, wy = _window(g.y, pm.dy, y_centre, y_half)
    p = g.embed(pm.pressure)
    T = np.empty((depths.size, jw.size))
    for k, z in enumerate(depths):
        s = PlaneStresses((g.nx, g.ny), pm.dx, pm.dy, z, nu, workers)(p)[:, :, jw]
        T[k] = np.sqrt(von_mises_squared(s).max(axis=0))
    return StressHistory(depths, depth_weights, g.y[jw], wy, T,
                         stats={"stress_grid": [g.nx, g.ny], "edge_pressure": _edge_pressure(pm)})


def _pass_setup(pm: PressureMap, centre: tuple[int, int], window: float, reach: tuple[float, float],
                depths, depth_weights):
    """Stress grid and material window for a pass of an indent centred at pressure cell ``centre``: material
    points xi in [-window, window], y within ``window`` of the indent's track, indent positions x_D in
    [reach] (m). Returns the grid, the indent's stress-grid indices, material offsets q (cells) with weights, and
    the across-track window."""
    depths, depth_weights = np.asarray(depths, float), np.asarray(depth_weights, float)
    _check_window(window, depths, depth_weights)
    xc, yc = pm.x[centre[0]], pm.y[centre[1]]
    g = _extend(pm, (reach[0] - window - pm.dx, reach[1] + window + pm.dx), (yc - window, yc + window))
    iD, jD = centre[0] + g.ox, centre[1] + g.oy
    m = int(np.floor(window / pm.dx + 0.5))
    q = np.arange(-m, m + 1)
    from ..analytic.life import window_weights

    wq = window_weights(q * pm.dx, pm.dx, window)
    keep = wq > 0
    q, wq = q[keep], wq[keep]
    jw, wy = _window(g.y, pm.dy, yc, window)
    return depths, depth_weights, g, iD, jD, q, wq, jw, wy, xc


SUPERPOSITIONS = ("contact", "linear")


def _shifted(a: np.ndarray, s: int) -> np.ndarray:
    """a moved by s cells along x (zeros enter; the stress grid is wide enough that nothing nonzero leaves)."""
    out = np.zeros_like(a)
    if s >= 0:
        out[s:] = a[:a.shape[0] - s]
    else:
        out[:s] = a[-s:]
    return out


def pseudo_transient_history(smooth: PressureMap, dented: PressureMap, centre: tuple[int, int], nu: float,
                             depths: np.ndarray, depth_weights: np.ndarray, window: float, chi_extent: float,
                             superposition: str = "contact", workers: int = -1) -> StressHistory:
    """T(xi, y, z) of a pass of the indent whose centred solution is ``dented`` (indent at pressure cell
    ``centre``), superposed on the smooth field; chi = 1 while |x_D| <= ``chi_extent`` (m).

    ``superposition``: "linear" is eq 4.5 as printed, sigma_S(xi + x_D) + chi sigma_D(xi). "contact" (default)
    superposes the same two fields and then restores the contact condition of the emulated pressure
    p_S(x) + chi dP(x - x_D) >= 0: where it is negative (an unloaded hole, dP = -p_S(0), moved to where the smooth
    pressure is lower than at the centre: zone-B indents), the stress of the clipped part is added. The plain
    superposition then makes the hole pull on the surface; it overestimates sigma_Dmax by 4-10 % against the
    full transient for D/Phi = 1-2 (measured, femcheck ``benchmarks/life_transient.py``), while for zone-A
    indents (the hole stays loaded) both forms coincide."""
    if superposition not in SUPERPOSITIONS:
        raise InputError("life.superposition", f"{superposition!r} is not allowed; allowed: one of "
                         + ", ".join(SUPERPOSITIONS))
    if dented.pressure.shape != smooth.pressure.shape or not (np.allclose(dented.x, smooth.x)
                                                           and np.allclose(dented.y, smooth.y)):
        raise InputError("pressure", "the smooth and dented pressures must be on the same grid")
    if not chi_extent > 0:
        raise InputError("life.chi_extent", f"{chi_extent} is not allowed; allowed: (0, inf) m")
    depths, depth_weights, g, iD, jD, q, wq, jw, wy, xc = _pass_setup(
        smooth, centre, window, (-chi_extent, chi_extent), depths, depth_weights)
    dx = smooth.dx
    # shifts s: indent at x_D = xc + s dx with chi = 1
    s_lo = int(np.ceil((-chi_extent - xc) / dx - 1e-9))
    s_hi = int(np.floor((chi_extent - xc) / dx + 1e-9))
    pS, dP = g.embed(smooth.pressure), g.embed(dented.pressure - smooth.pressure)
    clipped = {}
    if superposition == "contact":
        for s in range(s_lo, s_hi + 1):
            deficit = -np.minimum(pS + _shifted(dP, s), 0.0)
            if deficit.any():
                clipped[s] = deficit
    T = np.empty((depths.size, q.size, jw.size))
    Ts = np.empty((depths.size, jw.size))
    for k, z in enumerate(depths):
        ops = PlaneStresses((g.nx, g.ny), dx, smooth.dy, z, nu, workers)
        sS = ops(pS)[:, :, jw]
        sD = ops(dP)[:, iD + q][:, :, jw]
        vS = von_mises_squared(sS)
        Ts[k] = np.sqrt(vS.max(axis=0))
        best = _complement_max(vS, iD + q + s_lo, iD + q + s_hi)           # chi = 0: smooth only
        vD, wD = von_mises_squared(sD), cross_weights(sD)
        for s in range(s_lo, s_hi + 1):
            a = sS[:, iD + q + s]
            if s in clipped:
                v = von_mises_squared(a + sD + ops(clipped[s])[:, iD + q + s][:, :, jw])
            else:
                v = vS[iD + q + s] + vD + np.einsum("c...,c...->...", a, wD)
            best = np.maximum(best, v)
        T[k] = np.sqrt(np.maximum(best, 0.0))
    return StressHistory(depths, depth_weights, g.y[jw], wy, Ts, q * dx, wq, T,
                         stats={"stress_grid": [g.nx, g.ny], "chi_shifts": [s_lo, s_hi], "chi_extent": chi_extent,
                                "superposition": superposition, "clipped_shifts": len(clipped),
                                "clipped_load_max": max((float(c.sum()) * dx * smooth.dy for c in clipped.values()),
                                                        default=0.0),
                                "edge_pressure": max(_edge_pressure(smooth), _edge_pressure(dented))})


def transient_history(smooth: PressureMap, frames: Mapping[int, np.ndarray], centre: tuple[int, int], nu: float,
                      depths: np.ndarray, depth_weights: np.ndarray, window: float,
                      workers: int = -1) -> StressHistory:
    """T(xi, y, z) of a full transient pass: ``frames[s]`` is the pressure (on the smooth grid) with the indent at
    pressure cell (centre[0] + s, centre[1]), for consecutive shifts s; at every other position the indent is out
    of the contact and the smooth pressure applies."""
    shifts = sorted(frames)
    if not shifts or shifts != list(range(shifts[0], shifts[-1] + 1)):
        raise InputError("frames", "the transient needs frames at consecutive cell shifts")
    dx = smooth.dx
    xc0 = smooth.x[centre[0]]
    depths, depth_weights, g, iD, jD, q, wq, jw, wy, xc = _pass_setup(
        smooth, centre, window, (xc0 + shifts[0] * dx, xc0 + shifts[-1] * dx), depths, depth_weights)
    pS = g.embed(smooth.pressure)
    pf = {s: g.embed(np.asarray(frames[s], float)) for s in shifts}
    T = np.empty((depths.size, q.size, jw.size))
    Ts = np.empty((depths.size, jw.size))
    for k, z in enumerate(depths):
        ops = PlaneStresses((g.nx, g.ny), dx, smooth.dy, z, nu, workers)
        vS = von_mises_squared(ops(pS)[:, :, jw])
        Ts[k] = np.sqrt(vS.max(axis=0))
        best = _complement_max(vS, iD + q + shifts[0], iD + q + shifts[-1])
        for s in shifts:
            v = von_mises_squared(ops(pf[s])[:, iD + q + s][:, :, jw])
            best = np.maximum(best, v)
        T[k] = np.sqrt(best)
    edge = max([_edge_pressure(smooth)] + [_edge_pressure(PressureMap(smooth.x, smooth.y, f)) for f in frames.values()])
    return StressHistory(depths, depth_weights, g.y[jw], wy, Ts, q * dx, wq, T,
                         stats={"stress_grid": [g.nx, g.ny], "frames": [shifts[0], shifts[-1]], "edge_pressure": edge})


def line_history(pressure: np.ndarray, dx: float, nu: float, depths: np.ndarray) -> np.ndarray:
    """T_S(z) = max over x of sigma_VM below a plane-strain pressure on strips of width ``dx`` (m) (uniform
    pressure per strip, Johnson 1985 §2.6 strip kernels of :func:`femcheck.bem.layered_stress.strip_stress`,
    sigma_y = nu (sigma_x + sigma_z)). Pa, shape (nz,)."""
    p = np.asarray(pressure, dtype=float)
    T = np.empty(len(depths))
    for k, z in enumerate(depths):
        cache: dict[str, np.ndarray] = {}

        def kernel(name, z=z, cache=cache):
            def f(t):
                if not cache:
                    cache.update(strip_stress(t, z, dx))
                return cache[name]
            return f

        sx, sz, txz = (DCFFT(kernel(n), (p.size,), (dx,), workers=1)(p) for n in ("sigma_x", "sigma_z", "tau_xz"))
        sy = nu * (sx + sz)
        vm2 = 0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3.0 * txz * txz
        T[k] = np.sqrt(vm2.max())
    return T


def refined_max(values: np.ndarray, coords: list[np.ndarray]) -> dict:
    """Largest value of values[k, i, ...] and its position, each coordinate refined by the parabola through the
    neighbours of the grid maximum along that axis (non-uniform coordinates allowed). Returns value and pos."""
    idx = np.unravel_index(np.argmax(values), values.shape)
    best = float(values[idx])
    pos = []
    for axis, c in enumerate(coords):
        i = idx[axis]
        if 0 < i < values.shape[axis] - 1:
            pts = [list(idx) for _ in range(3)]
            for j, off in enumerate((-1, 0, 1)):
                pts[j][axis] = i + off
            (x0, x1, x2), (f0, f1, f2) = c[i - 1:i + 2], [values[tuple(t)] for t in pts]
            d = (x0 - x1) * (x0 - x2) * (x1 - x2)
            A = (x2 * (f1 - f0) + x1 * (f0 - f2) + x0 * (f2 - f1)) / d
            B = (x2 * x2 * (f0 - f1) + x1 * x1 * (f2 - f0) + x0 * x0 * (f1 - f2)) / d
            if A < 0:
                xv = float(np.clip(-B / (2 * A), x0, x2))
                best = max(best, float(f1 + A * (xv * xv - x1 * x1) + B * (xv - x1)))
                pos.append(xv)
                continue
        pos.append(float(c[i]))
    return {"value": best, "position": pos}
