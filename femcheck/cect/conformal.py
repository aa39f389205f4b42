"""Kalker's exact theory on a conformal contact (CECT; seed 000 §3.2, eqs 16-22; spec srb-rolling §4.2): one
contact on the developed (x, s) grid of a prismatic potential contact surface, with the exact conformal gap,
the 3D rigid slip and the variable rolling step dq(s) = kappa(s) dq0.

Inputs (see :mod:`femcheck.geometry.conformal_surface` for how to build them from a pose):
- ``grid``: the planar :class:`femcheck.bem.halfspace.Grid` of the developed grid (x along the rolling direction
  e_x, y = s - s_centre along the profile), cells dx x ds (m).
- ``gap``: undeformed distance h (m, (nx, ns), > 0 open), or a callable delta -> h for load control by a rigid
  approach delta (m) of the roller (recomputing the exact gap for each delta).
- ``slip``: rigid slip (w_x, w_s) (m/s, (2, nx, ns)) of body 1 (roller) relative to body 2 (ring); ``speed`` V_ref
  (m/s); ``kappa`` (ns,) = V(s)/V_ref (None: 1).
- ``constants``: Kalker's combined G, nu, K (:func:`femcheck.cect.influence.combined_constants`); ``mu``.
- ``influence``: "halfspace" (developed half-space, default), "blanco" or "rotated_response" (angle-corrected,
  :mod:`femcheck.cect.influence_conformal`; they need ``radius`` = the profile radius r_g).

Equations. Normal: h + u_n - delta >= 0, p_n >= 0, complementary (Polonsky-Keer CG: approach control with delta
given, or load control). Tangential, steady rolling with the variable dq (eqs 17, 19, 21):

    s_I = w_I / V_ref + kappa(s_I) [(u - u')/dx]_I,   (u - u')_I = sum_J ([IC] - [IC'])_IJ p_J,

i.e. the planar rolling operator of :mod:`femcheck.cect.exact` with its rows scaled by kappa (dense: diag(kappa) B;
matrix-free: the convolution output times kappa, the preconditioner S^-1 diag(1/kappa)). Coulomb's law and its
semi-smooth Newton solvers are the planar ones (:func:`femcheck.cect.exact.solve_tangential`,
:func:`femcheck.cect.tangential_fft.solve_tangential_fft`), so kappa = 1 with the half-space coefficients and
an array gap under load control is the planar solver bit for bit. Quasi-identical bodies and half-space
coefficients: Johnson's process (one normal, one tangential solve); otherwise (K != 0 or angle-corrected
coefficients) Panagiotopoulos' process, the pressure's rolling part scaled by the same kappa (eq 21 for
(u - u')_n).

Outputs (:class:`ConformalResult`, local (x, s, n) components, tractions on body 1 = roller): pressure, p_x, p_s
(Pa), adhesion map, slip velocity v = V_ref s (m/s), frictional power density -p_t . v (W/m^2), lateral
distributions N*(s) = sum_x p_n dx, F_x*(s) = sum_x p_x dx (N/m; seed 000 Figs 8-9), frictional work per unit
width per passage sum_x (-p_t . v) dx / V(s) (J/m; Fig. 12). 3D resultants (force, moment about any point, spin
moment about a normal) by :func:`resultants` with the developed grid's frames.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..bem.halfspace import Grid, half_space_operator, half_space_preconditioner
from ..bem.polonsky_keer import polonsky_keer
from ..errors import ConvergenceError, InputError
from ..geometry.conformal_surface import DevelopedGrid
from .exact import AUTO_FFT_ELEMENTS, TANGENTIAL_SOLVERS, dense_operator, solve_normal, solve_tangential
from .influence import CombinedConstants
from .influence_conformal import INFLUENCE_OPTIONS, block_operator, dense_block
from .tangential_fft import solve_tangential_fft, tangential_operators

GapOfApproach = Callable[[float], np.ndarray]
# Load control resolves the force only as finely as the Polonsky-Keer gap tolerance allows (a warm start that
# meets the tolerance is returned unchanged): when the approach bracket has collapsed to round-off, the load is
# accepted within this relative error (the runner's load-balance check is 1e-6)
LOAD_FLOOR = 1e-7


class GridTooSmall(InputError):
    """The contact reaches the edge of the potential contact grid. ``edges`` names the sides touched ("x-",
    "x+", "s-", "s+") so that a caller can enlarge or re-centre the grid."""

    def __init__(self, edges: list[str]):
        self.edges = edges
        super().__init__("numerics.conformal_domain", f"the contact reaches the grid edge(s) {', '.join(edges)}; "
                         "enlarge the grid (allowed: half-widths beyond the contact)")


def _edges(contact: np.ndarray) -> list[str]:
    out = []
    for name, sl in (("x-", contact[0, :]), ("x+", contact[-1, :]), ("s-", contact[:, 0]), ("s+", contact[:, -1])):
        if sl.any():
            out.append(name)
    return out


# --------------------------------------------------------------------------------------------------------------
# normal problem
# --------------------------------------------------------------------------------------------------------------
@dataclass
class NormalSolution:
    """Normal contact: ``pressure`` (Pa, (nx, ns)), ``gap`` h (m) the undeformed distance used, ``approach``
    delta (m), ``load`` = sum p_n dA (N), ``iterations`` (Polonsky-Keer CG, summed), ``residual``, ``solves``
    (PK solves: > 1 under load control with an exact gap)."""

    pressure: np.ndarray
    gap: np.ndarray
    approach: float
    load: float
    iterations: int
    residual: float
    solves: int = 1


def _normal_operator(g: Grid, constants: CombinedConstants, option: str, radius: float | None):
    e_star = constants.contact_modulus
    pre = half_space_preconditioner(g, e_star, 1)
    if option == "halfspace":
        return half_space_operator(g, e_star, 1), pre
    op = block_operator(g, constants, "n", "n", False, option, radius)
    return (lambda p: op(p[None])[0]), pre


def solve_normal_conformal(g: Grid, gap: np.ndarray | GapOfApproach, constants: CombinedConstants, *,
                           load: float | None = None, approach: float = 0.0, load_weights: np.ndarray | None = None,
                           influence: str = "halfspace", radius: float | None = None,
                           extra_gap: np.ndarray | float = 0.0, tol: float = 1e-10, p0: np.ndarray | None = None,
                           approach0: float | None = None, load_rtol: float = 1e-9,
                           max_solves: int = 40) -> NormalSolution:
    """Normal contact on the developed grid (module docstring).

    - ``gap`` array, ``load`` None: approach control, h + u_n - ``approach`` (default 0: the pose is in h).
    - ``gap`` array, ``load`` given: Polonsky-Keer load control with a uniform approach (the planar solver's
      normal problem, :func:`femcheck.cect.exact.solve_normal`, for the half-space coefficients).
    - ``gap`` callable delta -> h, ``load`` given: the rigid approach delta of the roller that makes
      sum p_n w dA = load (w = ``load_weights``, e.g. n(s).e_ref for the resultant along a reference
      direction; default 1) within ``load_rtol``: secant on log F versus log(delta - min h0) (F ~ delta^1.5),
      safeguarded by bisection, each step an approach-controlled solve warm-started from the last.
    ``extra_gap`` (m) adds the normal displacement of the tangential tractions (coupled coefficients).
    """
    op, pre = _normal_operator(g, constants, influence, radius)
    area = g.cell_area
    if not callable(gap):
        h = np.asarray(gap, dtype=float) + extra_gap
        if load is not None:
            if load_weights is not None:
                raise ValueError("load_weights need a callable gap (the approach is a rigid motion)")
            if influence == "halfspace":
                r = solve_normal(g, h, constants, load, tol=tol, p0=p0)
            else:
                r = polonsky_keer(h, op, load, area, p0=p0, tol=tol, max_iter=2000, preconditioner=pre)
        else:
            r = polonsky_keer(h, op, None, area, p0=p0, tol=tol, max_iter=2000, approach=approach,
                              preconditioner=pre)
        return NormalSolution(r.pressure, h, float(r.approach), float(r.load), r.iterations, float(r.residual))
    if load is None:
        return solve_normal_conformal(g, gap(approach), constants, approach=approach, influence=influence,
                                      radius=radius, extra_gap=extra_gap, tol=tol, p0=p0)
    if not load > 0:
        raise InputError("load.normal", f"{load:g} N; allowed: > 0")
    wts = 1.0 if load_weights is None else np.asarray(load_weights, dtype=float)
    h0 = gap(0.0)
    base = float(h0.min())                    # the approach at first touch (for delta measured from h0 = 0)
    iterations, solves = 0, 0
    cache: dict[float, tuple[float, NormalSolution]] = {}
    p_warm = p0

    def force(delta: float) -> float:
        nonlocal iterations, solves, p_warm
        h = gap(delta) + extra_gap
        r = polonsky_keer(h, op, None, area, p0=p_warm, tol=tol, max_iter=2000, approach=0.0, preconditioner=pre)
        iterations += r.iterations
        solves += 1
        p_warm = r.pressure
        f = float(area * np.sum(r.pressure * wts))
        cache[delta] = (f, NormalSolution(r.pressure, h, delta, float(r.load), iterations, float(r.residual)))
        return f

    d = approach0 if approach0 is not None and approach0 > base else None
    if d is None:
        raise ValueError("load control with an exact gap needs a first approach estimate approach0 > min h0")
    lo, hi = base, None                      # bracket: F(lo) < load <= F(hi)
    pts: list[tuple[float, float]] = []
    for _ in range(max_solves):
        f = force(d)
        collapsed = hi is not None and hi - lo <= 1e-13 * (d - base)
        if abs(f / load - 1.0) < (load_rtol if not collapsed else LOAD_FLOOR):
            sol = cache[d][1]
            sol.iterations, sol.solves = iterations, solves
            return sol
        if collapsed:
            break
        if f < load:
            lo = max(lo, d)
        else:
            hi = d if hi is None else min(hi, d)
        if f > 0:
            pts.append((np.log(d - base), np.log(f)))
        if len(pts) >= 2 and pts[-1][0] != pts[-2][0] and pts[-1][1] != pts[-2][1]:
            (u0, f0), (u1, f1) = pts[-2], pts[-1]
            u = u1 + (np.log(load) - f1) * (u1 - u0) / (f1 - f0)
        elif f > 0:
            u = np.log(d - base) + (np.log(load) - np.log(f)) / 1.5      # Hertz: F ~ (delta - delta_0)^1.5
        else:
            u = np.log(2.0 * (d - base))
        d_new = base + float(np.exp(u))
        if not (lo < d_new and (hi is None or d_new < hi)):
            d_new = 0.5 * (lo + hi) if hi is not None else base + 2.0 * (d - base)
        d = d_new
    raise ConvergenceError("conformal load control (secant on the approach)", max_solves,
                           abs(f / load - 1.0), load_rtol)


# --------------------------------------------------------------------------------------------------------------
# the conformal contact solver
# --------------------------------------------------------------------------------------------------------------
@dataclass
class ConformalResult:
    """Solution of one conformal rolling contact on the developed grid (module docstring). Arrays (nx, ns):
    ``pressure``, ``px``, ``ps`` (Pa, on body 1, local components), ``contact``, ``adhesion`` (masks), ``slip_x``,
    ``slip_s`` (slip velocity, m/s), ``power_density`` (W/m^2). ``x`` (nx,), ``s`` (ns,) element centres (m);
    ``kappa`` (ns,); ``speed`` V_ref (m/s); ``approach`` (m); ``stats`` (iterations, residuals, timing)."""

    grid: Grid
    x: np.ndarray
    s: np.ndarray
    pressure: np.ndarray
    px: np.ndarray
    ps: np.ndarray
    contact: np.ndarray
    adhesion: np.ndarray
    slip_x: np.ndarray
    slip_s: np.ndarray
    power_density: np.ndarray
    kappa: np.ndarray
    speed: float
    approach: float
    normal: NormalSolution
    stats: dict = field(default_factory=dict)

    @property
    def cell_area(self) -> float:
        return self.grid.cell_area

    @property
    def normal_force(self) -> float:
        """sum p_n dA (N): the magnitude of the pressure integral (not projected)."""
        return float(self.pressure.sum() * self.cell_area)

    @property
    def force_x(self) -> float:
        """sum p_x dA (N), along the rolling direction e_x."""
        return float(self.px.sum() * self.cell_area)

    @property
    def force_s(self) -> float:
        """sum p_s dA (N), along the profile (+s): the paper's lateral force F_lat (before normalisation)."""
        return float(self.ps.sum() * self.cell_area)

    @property
    def adhesion_fraction(self) -> float:
        n = int(self.contact.sum())
        return float(self.adhesion.sum() / n) if n else 0.0

    @property
    def frictional_power(self) -> float:
        """Total frictional power (W)."""
        return float(self.power_density.sum() * self.cell_area)

    @property
    def lateral_normal(self) -> np.ndarray:
        """N*(s) = sum_x p_n dx (N/m)."""
        return self.pressure.sum(axis=0) * self.grid.dx

    @property
    def lateral_fx(self) -> np.ndarray:
        """F_x*(s) = sum_x p_x dx (N/m)."""
        return self.px.sum(axis=0) * self.grid.dx

    @property
    def lateral_fs(self) -> np.ndarray:
        return self.ps.sum(axis=0) * self.grid.dx

    @property
    def pressure_centre(self) -> float:
        """s_c = sum s N*(s) / sum N*(s) (m)."""
        n = self.lateral_normal
        return float((self.s * n).sum() / n.sum())

    def work_per_width(self, rolling_speed: np.ndarray) -> np.ndarray:
        """Frictional work per unit width per passage (J/m, over s): sum_x (power density) dx / V(s); seed 000
        Fig. 12. ``rolling_speed`` V(s) (m/s, (ns,))."""
        return self.power_density.sum(axis=0) * self.grid.dx / np.asarray(rolling_speed, dtype=float)


def solve_conformal(g: Grid, gap: np.ndarray | GapOfApproach, constants: CombinedConstants, mu: float,
                    slip: np.ndarray, speed: float, kappa: np.ndarray | None = None, *, load: float | None = None,
                    approach: float = 0.0, load_weights: np.ndarray | None = None, approach0: float | None = None,
                    influence: str = "halfspace", radius: float | None = None, s: np.ndarray | None = None,
                    tol: float = 1e-9, normal_tol: float = 1e-10, load_rtol: float = 1e-9,
                    tangential_solver: str = "auto", warm: ConformalResult | None = None,
                    normal: NormalSolution | None = None, max_outer: int = 30,
                    outer_tol: float = 1e-7) -> ConformalResult:
    """Normal + tangential steady rolling of one conformal contact (module docstring).

    ``slip`` (2, nx, ns) rigid slip (w_x, w_s) in m/s, divided by ``speed`` V_ref (m/s) inside; ``kappa`` (ns,)
    or (nx, ns) rolling-step factor (None: 1); ``load``/``approach``/``load_weights``/``approach0`` as in
    :func:`solve_normal_conformal`; ``s`` (ns,) the profile coordinates of the grid's columns (m, only stored;
    default grid.y). ``warm`` a previous result on the same grid (warm start of both problems); ``normal`` a
    normal solution to reuse when only the rigid slip changed (uncoupled problems only). ``tangential_solver``
    "dense", "fft" or "auto" (fft above 300 contact elements). Raises GridTooSmall when the contact reaches the
    grid edge, ConvergenceError when a solver misses its tolerance.
    """
    if not mu > 0:
        raise InputError("friction.mu", f"{mu:g}; allowed: > 0")
    if influence not in INFLUENCE_OPTIONS:
        raise InputError("numerics.conformal_influence", f"{influence!r}; allowed: {', '.join(INFLUENCE_OPTIONS)}")
    if tangential_solver not in TANGENTIAL_SOLVERS:
        raise InputError("numerics.conformal_solver", f"{tangential_solver!r}; allowed: {', '.join(TANGENTIAL_SOLVERS)}")
    t0 = time.perf_counter()
    slip = np.asarray(slip, dtype=float)
    w_rel = slip / speed
    kap_grid = None if kappa is None else np.broadcast_to(
        np.asarray(kappa, dtype=float)[None, :] if np.ndim(kappa) == 1 else np.asarray(kappa, dtype=float),
        (g.nx, g.ny))
    coupled = constants.coupling != 0.0 or influence != "halfspace"
    opts = dict(load=load, approach=approach, load_weights=load_weights, influence=influence, radius=radius,
                tol=normal_tol, load_rtol=load_rtol)
    px = np.zeros((g.nx, g.ny)) if warm is None or not coupled else warm.px.copy()
    ps = np.zeros((g.nx, g.ny)) if warm is None or not coupled else warm.ps.copy()
    history = []
    tang = None
    for outer in range(1, (max_outer if coupled else 1) + 1):
        extra = 0.0
        if coupled and (px.any() or ps.any()):
            extra = block_operator(g, constants, "n", "xs", False, influence, radius)(np.stack([px, ps]))[0]
        if normal is not None and not coupled:
            nsol = normal
        else:
            p_start = (warm.pressure if warm is not None else None) if outer == 1 else nsol.pressure
            a_start = (warm.approach if warm is not None else approach0) if outer == 1 else nsol.approach
            nsol = solve_normal_conformal(g, gap, constants, extra_gap=extra, p0=p_start, approach0=a_start, **opts)
        pn = nsol.pressure
        contact = pn > 0
        if (edges := _edges(contact)):
            raise GridTooSmall(edges)
        cells = np.nonzero(contact)
        C = cells[0].size
        if C == 0:
            raise InputError("load.normal", "no element is in contact (the gap does not close)")
        kc = None if kap_grid is None else kap_grid[cells]
        w = w_rel[:, cells[0], cells[1]]
        if coupled:
            un = block_operator(g, constants, "xs", "n", True, influence, radius)(pn[None])
            w = w + (1.0 if kc is None else kc) * un[:, cells[0], cells[1]]
        use_fft = tangential_solver == "fft" or (tangential_solver == "auto" and C > AUTO_FFT_ELEMENTS)
        p0 = None
        if tang is not None or warm is not None:
            src_x, src_s = (px, ps) if tang is not None else (warm.px, warm.ps)
            p0 = np.stack([src_x[cells], src_s[cells]])
        if use_fft:
            ops = None
            if influence != "halfspace":
                ops = (block_operator(g, constants, "xs", "xs", True, influence, radius),
                       tangential_operators(g, constants, True)[1])
            tang = solve_tangential_fft(g, cells, constants, w, mu * pn[cells], True, tol=tol, p0=p0,
                                        solver="conformal rolling", kappa=kc, operators=ops)
        else:
            if influence == "halfspace":
                B = dense_operator(g, cells, constants, "xy", "xy", True)
            else:
                B = dense_block(g, cells, constants, "xs", "xs", True, influence, radius)
            if kc is not None:
                B = B * np.concatenate([kc, kc])[:, None]
            tang = solve_tangential(B, w, mu * pn[cells], cell_area=g.cell_area, tol=tol, p0=p0,
                                    solver="conformal rolling")
        new_px, new_ps = np.zeros((g.nx, g.ny)), np.zeros((g.nx, g.ny))
        new_px[cells], new_ps[cells] = tang.p[0], tang.p[1]
        scale = max(float(pn.max()), 1e-300)
        change = float(max(np.abs(new_px - px).max(), np.abs(new_ps - ps).max())) / scale
        px, ps = new_px, new_ps
        history.append({"outer": outer, "normal_iterations": nsol.iterations, "normal_solves": nsol.solves,
                        "newton_iterations": tang.iterations, "gmres_iterations": tang.linear_iterations,
                        "traction_change": change, "contact_elements": int(C)})
        if not coupled or (outer > 1 and change < outer_tol):
            break
    else:
        raise ConvergenceError("Panagiotopoulos process (conformal)", max_outer, history[-1]["traction_change"],
                               outer_tol, "normal and tangential tractions keep changing")
    stick = np.zeros_like(contact)
    stick[cells] = tang.stick
    sx, ss = np.zeros((g.nx, g.ny)), np.zeros((g.nx, g.ny))
    sx[cells], ss[cells] = tang.slip[0] * speed, tang.slip[1] * speed          # slip velocity v = V_ref s
    power = -(px * sx + ps * ss)
    stats = {"grid": [g.nx, g.ny], "dx": g.dx, "ds": g.dy, "contact_elements": int(C),
             "influence": influence, "process": "Panagiotopoulos" if coupled else "Johnson",
             "outer_iterations": len(history),
             "iterations": int(sum(h["newton_iterations"] for h in history)),
             "residual": float(tang.residual),
             "normal_iterations": int(sum(h["normal_iterations"] for h in history)),
             "normal_solves": int(sum(h["normal_solves"] for h in history)),
             "normal_residual": float(nsol.residual),
             "gmres_iterations": int(sum(h["gmres_iterations"] for h in history)),
             "tangential_solver": "fft" if use_fft else "dense", "history": history,
             "time_s": time.perf_counter() - t0}
    kap_out = np.ones(g.ny) if kappa is None else np.asarray(kappa, dtype=float)
    return ConformalResult(g, g.x.copy(), g.y.copy() if s is None else np.asarray(s, dtype=float), pn, px, ps,
                           contact, stick, sx, ss, power, kap_out, float(speed), float(nsol.approach), nsol, stats)


# --------------------------------------------------------------------------------------------------------------
# 3D resultants
# --------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Resultants:
    """Resultants of the tractions on body 1 (roller), in the frame of the grid's points (the bearing frame B):
    ``force`` (N, 3), ``moment`` (N m, 3) about ``moment_point``, ``spin_moment`` (N m) about the normal
    ``spin_axis`` through ``spin_point``."""

    force: np.ndarray
    moment: np.ndarray
    spin_moment: float


def traction_vectors(res: ConformalResult, dg: DevelopedGrid) -> np.ndarray:
    """(nx, ns, 3) traction vectors on body 1: p_x e_x + p_s t(s) + p_n n(s) (Pa)."""
    return (res.px[..., None] * dg.surface.ex + res.ps[..., None] * dg.tangents[None]
            + res.pressure[..., None] * dg.normals[None])


def resultants(res: ConformalResult, dg: DevelopedGrid, moment_point: np.ndarray,
               spin_point: np.ndarray | None = None, spin_axis: np.ndarray | None = None,
               tractions: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None) -> Resultants:
    """F = sum t dA, M = sum (P0 - moment_point) x t dA and the spin moment ((P0 - spin_point) x t).spin_axis dA
    summed (spec §3 item 1; defaults: the grid's reference point P0(0, 0) and its normal n(0)). ``tractions``
    (px, ps, pn) replaces the solution's (e.g. the full-slip tractions of
    :func:`femcheck.cect.full_slip.full_slip_tractions`)."""
    if tractions is not None:
        px, ps, pn = tractions
        t = px[..., None] * dg.surface.ex + ps[..., None] * dg.tangents[None] + pn[..., None] * dg.normals[None]
    else:
        t = traction_vectors(res, dg)
    dA = dg.grid.cell_area
    P = dg.points
    F = t.sum(axis=(0, 1)) * dA
    M = np.cross(P - np.asarray(moment_point, dtype=float), t).sum(axis=(0, 1)) * dA
    sp = dg.surface.point(0.0) if spin_point is None else np.asarray(spin_point, dtype=float)
    ax = dg.surface.normal(0.0) if spin_axis is None else np.asarray(spin_axis, dtype=float)
    Ms = float(np.cross(P - sp, t).sum(axis=(0, 1)) @ ax * dA)
    return Resultants(F, M, Ms)
