"""Free rolling of a crowned body in a grooved ring (:mod:`femcheck.geometry.groove`) by the conformal exact
theory (:mod:`femcheck.cect.conformal`) and, as its contrast, by the planar exact theory with the Hertz quadratic
gap (:mod:`femcheck.cect.exact`).

Free rolling: the ring's surface speed V is given; the body's angular velocity omega is the
unknown that makes the rolling-direction force F_x = sum p_x dA vanish (1-D root find: Brent's method on a
bracket from the rigid slip, every solve warm-started from the last; the normal problem is solved once under
load control when it does not couple to the tangential one). The load is the resultant of the contact pressures
along the nominal normal Z. In the conformal contact the rolling radii of body and groove vary across the
patch (crown and groove curvature, seed 000 eqs 5-7), so free rolling leaves a longitudinal creepage at the
centre and two zero-slip bands (Heathcote slip); the planar theory with Kalker's creepages at the nominal
point has no such slip (no spin either: both axes are parallel to Y) and rolls freely at zero creepage.

Reported (SI): ``approach`` the rigid approach (m), ``p_max`` (Pa), ``half_length_s`` half the lateral extent of
the contact along the groove (m; sub-cell power-law edges of the lateral load distribution,
:func:`lateral_extent`), ``angle_span`` its angle on the groove circle (rad), ``adhesion_fraction``,
``creepage_x`` = w_x(0, 0)/V_ref (Kalker's sign: the body's slip relative to the ring along x),
``spin_moment`` about the normal at the nominal point (N m), ``friction_power`` (W), and the body's axle torque
sum ((P - C) x t).Y dA (N m; the rolling resistance moment that free rolling at F_x = 0 leaves).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ..analytic.hertz import elliptic_contact
from ..bem.halfspace import grid as planar_grid
from ..errors import ConvergenceError, InputError
from ..geometry.conformal_surface import DevelopedGrid, developed_grid, rolling_speeds, undeformed_distance
from ..geometry.groove import Y, Z, GrooveRolling
from ..qoi import edges
from .conformal import GridTooSmall, resultants, solve_conformal, solve_normal_conformal
from .exact import solve_contact
from .influence import CombinedConstants

MAX_ENLARGEMENTS = 5
ENLARGE = 1.3
FREE_ROLLING_TOL = 1e-7          # |F_x| / (mu N) at the root
SPIN_NOISE = 1e-7                # |M_spin| below SPIN_NOISE mu N b_H is zero within the solver's tolerance


@dataclass
class GridSpec:
    """``cells_x`` x ``cells_s`` elements over +-``domain_x`` a_H and +-``domain_s`` b_H (Hertz semi-axes)."""

    cells_x: int = 41
    cells_s: int = 81
    domain_x: float = 1.35
    domain_s: float = 1.25


@dataclass
class GrooveSolution:
    """One free-rolling solution: the ``quantities`` of the module docstring, the contact ``result``, its
    ``grid`` (None for the planar model), ``stats`` (iterations, residuals, grid, enlargements, timing)."""

    quantities: dict
    result: object
    grid: DevelopedGrid | None
    stats: dict = field(default_factory=dict)


def lateral_extent(s: np.ndarray, pressure: np.ndarray) -> tuple[float, float]:
    """(left, right) lateral edges (m) of a pressure field (nx, ns) on cells along s: the power-law edges of
    :func:`femcheck.qoi.edges` (exponent fitted, no Hertz shape) of the lateral load distribution
    N*(s) ~ sum_x p(x, s), about the middle of its loaded cells. N* averages over the rolling direction, so it
    scatters less from level to level than the pressure ridge max_x p (FE levels 11 x 21 -> 23 x 43 of the
    default scene: 8.809, 8.817, 8.825 mm against 8.903, 8.961, 8.860 mm). Every model of the groove-rolling
    scene goes through it (like with like)."""
    load = pressure.sum(axis=0)
    loaded = s[load > 0]
    centre = 0.5 * float(loaded.min() + loaded.max())
    right, left = edges(s, load, centre)
    return centre - left.position, centre + right.position


class _Found(Exception):
    """|F_x| is below the tolerance: stop Brent's iteration."""


def _free_rolling(evaluate, guess: float, step: float, lo: float, hi: float, scale: float, what: str,
                  ftol: float = 1e-10, max_evaluations: int = 40):
    """Root of evaluate(u) -> (F_x, result) in u (free rolling, F_x = 0): from ``guess``, steps of ``step``
    growing 4-fold downhill until F_x changes sign (within the bounds [lo, hi]), then Brent's method on the
    bracket with the u-tolerance that |F_x| < ftol scale asks for (the bracket's mean slope). Returns (u, result,
    evaluations, |F_x|/scale)."""
    cache = {}

    def f(u):
        if u not in cache:
            if len(cache) >= max_evaluations:
                raise ConvergenceError(f"{what} free rolling", len(cache), np.nan, FREE_ROLLING_TOL,
                                       "too many contact solves")
            cache[u] = evaluate(u)
        return cache[u][0] / scale

    a, fa = guess, f(guess)
    if abs(fa) >= ftol:
        b, fb = a + step, f(a + step)
        if abs(fb) > abs(fa):                       # walk downhill: towards smaller |F_x|
            a, b, fa, fb, step = b, a, fb, fa, -step
        while fa * fb > 0 and lo < b < hi:
            step *= 4.0
            a, fa = b, fb
            b = min(max(b + step, lo), hi)
            fb = f(b)
        if fa * fb > 0:
            raise ConvergenceError(f"{what} free rolling", len(cache), abs(fb), FREE_ROLLING_TOL,
                                   "no sign change of F_x within the bounds")
        if abs(fb) >= ftol:
            def g(u):
                v = f(u)
                if abs(v) < ftol:
                    raise _Found
                return v

            slope = abs(fb - fa) / abs(b - a)
            try:
                brentq(g, min(a, b), max(a, b), xtol=max(0.1 * ftol / slope, 4e-16 * abs(b)), rtol=1e-15,
                       maxiter=max_evaluations)
            except _Found:
                pass
    best = min(cache, key=lambda v: abs(f(v)))
    res = abs(f(best))
    if res > FREE_ROLLING_TOL:
        raise ConvergenceError(f"{what} free rolling (Brent on the body speed)", len(cache), res, FREE_ROLLING_TOL)
    return best, cache[best][1], len(cache), res


def solve_groove_cect(geom: GrooveRolling, load: float, mu: float, constants: CombinedConstants, speed: float,
                      spec: GridSpec = GridSpec(), influence: str = "halfspace", variable_dq: bool = True,
                      solver: str = "auto", tol: float = 1e-9,
                      compliance_weights: tuple[float, float] = (1.0, 1.0), extra_displacement=None,
                      omega0: float | None = None) -> GrooveSolution:
    """Free rolling by the conformal exact theory on the developed groove grid (module docstring); the grid is
    enlarged (x 1.3 per touched side, up to 5 times) when the contact reaches its edge. ``compliance_weights``
    (body, ring) weight the two rolling speeds in V(s) (E8: 1/E* of each body, 0 for a rigid one). When the
    normal and tangential problems couple (dissimilar bodies, angle-corrected coefficients) every solve is a
    Panagiotopoulos process under load control.

    ``extra_displacement``: optional dg -> (u, u_down), a given elastic displacement (3, nx, ns) (m; local
    components (x, s, n), u = u(body) - u(ring)) at the cell centres and one cell downstream (x + dx), added to
    the one the contact's own tractions make through the half-space coefficients (a finite-body correction,
    :mod:`femcheck.fem.groove_finite_body`): the gap opens by u_n and the slip gains the rolling difference
    V_ref kappa (u_t - u_t') / dx (seed 000 eqs 17-21). ``omega0``: the body speed (rad/s) to start the free-rolling
    search from (a previous solution's), instead of the full-slip estimate."""
    t0 = time.perf_counter()
    rx, ry = geom.hertz_radii
    h = elliptic_contact(load, rx, ry, constants.contact_modulus)
    dom = [spec.domain_x, spec.domain_s]
    ring = geom.ring()
    rate = geom.ring_rate(speed)
    surface = geom.surface()
    coupled = influence != "halfspace" or constants.coupling != 0.0
    for enlargement in range(MAX_ENLARGEMENTS + 1):
        dg = developed_grid(surface, dom[0] * h.semi_axis_x, dom[1] * h.semi_axis_y, spec.cells_x, spec.cells_s)
        wts = np.broadcast_to(dg.normals @ Z, (spec.cells_x, spec.cells_s))

        u_extra = u_down = None
        if extra_displacement is not None:
            u_extra, u_down = extra_displacement(dg)

        def gap(d, dg=dg, u_extra=u_extra):
            h = undeformed_distance(dg, geom.body(d), ring)
            return h if u_extra is None else h + u_extra[2]

        try:
            normal = solve_normal_conformal(dg.grid, gap, constants, load=load, load_weights=wts,
                                            influence=influence, radius=surface.radius, approach0=h.approach)
            body = geom.body(normal.approach)
            P = dg.points
            ring_part = -ring.velocity(P, rate)
            body_unit = body.velocity(P, 1.0)
            # a warm start helps only near the previous state: from tractions of a body speed more than a
            # quarter of the saturation creepage away the semi-smooth Newton took 47 steps instead of 8 cold
            sat = 2.0 * mu * h.p_max / constants.contact_modulus
            state = {"warm": None, "omega": None}

            def evaluate(omega, dg=dg, normal=normal, body=body, ring_part=ring_part, body_unit=body_unit):
                near = state["omega"] is not None and \
                    abs(omega - state["omega"]) * geom.rolling_radius < 0.25 * sat * speed
                w = ring_part + omega * body_unit
                slip = np.stack([w @ dg.surface.ex, np.einsum("ijk,jk->ij", w, dg.tangents)])
                sp = rolling_speeds(dg, body, omega, ring, rate, compliance_weights=compliance_weights)
                if u_extra is not None:
                    kap = np.asarray(sp.kappa, dtype=float) if variable_dq else np.ones(1)
                    kap = kap[None, :] if kap.ndim == 1 else kap
                    slip = slip + sp.reference * kap[None] * (u_extra[:2] - u_down[:2]) / dg.grid.dx
                r = solve_conformal(dg.grid, gap if coupled else normal.gap, constants, mu, slip,
                                    sp.reference, sp.kappa if variable_dq else None,
                                    load=load if coupled else None, load_weights=wts if coupled else None,
                                    approach0=normal.approach, influence=influence, radius=surface.radius,
                                    s=dg.s, tol=tol, tangential_solver=solver,
                                    warm=state["warm"] if near else None, normal=None if coupled else normal)
                state["warm"], state["omega"] = r, omega
                return r.force_x, (r, sp)

            # bounds: the body speeds at which the rigid slip at x = 0 vanishes somewhere on the patch (beyond
            # them every element slips the same way); first guess: the mean rigid slip weighted by the lateral
            # load distribution vanishes (the full-slip estimate)
            i0 = dg.grid.nx // 2
            v_ring = ring_part[i0] @ dg.surface.ex
            reach = -(body_unit[i0] @ dg.surface.ex)
            loaded = normal.pressure.sum(axis=0)
            om = v_ring[loaded > 0] / reach[loaded > 0]
            guess = float((loaded * v_ring).sum() / (loaded * reach).sum()) if omega0 is None else float(omega0)
            step = (0.5 if omega0 is None else 0.02) * sat * speed / geom.rolling_radius
            omega, (res, sp), evals, residual = _free_rolling(evaluate, guess, step,
                                                              om.min() * (1 - 1e-3),
                                                              om.max() * (1 + 1e-3), mu * load, "conformal")
            break
        except GridTooSmall as err:
            if enlargement == MAX_ENLARGEMENTS:
                raise
            if any(e.startswith("x") for e in err.edges):
                dom[0] *= ENLARGE
            if any(e.startswith("s") for e in err.edges):
                dom[1] *= ENLARGE
    left, right = lateral_extent(dg.s, res.pressure)
    Rs = resultants(res, dg, body.centre, spin_point=np.zeros(3), spin_axis=Z)
    spin = Rs.spin_moment if abs(Rs.spin_moment) > SPIN_NOISE * mu * load * h.semi_axis_y else 0.0
    i0 = int(np.argmin(np.abs(dg.x)))
    j0 = int(np.argmin(np.abs(dg.s)))
    w00 = (ring_part[i0, j0] + omega * body_unit[i0, j0]) @ dg.surface.ex
    q = {"approach": res.approach, "p_max": float(res.pressure.max()), "half_length_s": 0.5 * (right - left),
         "angle_span": (right - left) / surface.radius, "adhesion_fraction": res.adhesion_fraction,
         "creepage_x": float(w00 / sp.reference), "spin_moment": float(spin),
         "friction_power": res.frictional_power}
    # the load condition is on the pressure resultant along Z (the friction's share is reported apart)
    q["total_force"] = float(resultants(res, dg, body.centre, tractions=(0 * res.px, 0 * res.ps, res.pressure)).force @ Z)
    stats = {**{k: v for k, v in res.stats.items() if k != "history"}, "free_rolling_evaluations": evals,
             "free_rolling_residual": residual, "body_angular_velocity": omega,
             "body_speed_over_ring_speed": omega * geom.rolling_radius / speed,
             "axle_torque": float(Rs.moment @ Y), "friction_force_z": float(Rs.force @ Z) - q["total_force"],
             "lateral_force": res.force_s, "pressure_centre_s": res.pressure_centre,
             "grid_half_widths": [dom[0] * h.semi_axis_x, dom[1] * h.semi_axis_y], "grid_enlargements": enlargement,
             "kappa_range": [float(sp.kappa.min()), float(sp.kappa.max())], "V_ref": sp.reference,
             "hertz": {"a": h.semi_axis_x, "b": h.semi_axis_y, "p0": h.p_max, "approach": h.approach,
                       "Rx": rx, "Ry": ry},
             "time_s": time.perf_counter() - t0}
    return GrooveSolution(q, res, dg, stats)


def solve_groove_planar(geom: GrooveRolling, load: float, mu: float, constants: CombinedConstants, speed: float,
                        spec: GridSpec = GridSpec(), solver: str = "auto", tol: float = 1e-9) -> GrooveSolution:
    """Free rolling by the planar exact theory: Hertz quadratic gap x^2/(2 Rx) + y^2/(2 Ry) on the same cell
    counts and Hertz-relative domain, Kalker's creepages at the nominal point (xi unknown, eta = phi = 0: the
    axes are parallel); lateral extent and angle span mapped onto the groove radius."""
    t0 = time.perf_counter()
    rx, ry = geom.hertz_radii
    h = elliptic_contact(load, rx, ry, constants.contact_modulus)
    dom = [spec.domain_x, spec.domain_s]
    for enlargement in range(MAX_ENLARGEMENTS + 1):
        g = planar_grid(dom[0] * h.semi_axis_x, dom[1] * h.semi_axis_y, spec.cells_x, spec.cells_s)

        def evaluate(xi, g=g):
            try:
                r = solve_contact(g, lambda x, y: x * x / (2 * rx) + y * y / (2 * ry), constants, load, mu,
                                  creepages=(xi, 0.0, 0.0), rolling_speed=speed, tol=tol, tangential_solver=solver)
            except InputError as err:
                if err.key == "numerics.exact_domain":
                    raise GridTooSmall(["x-", "s-"]) from None
                raise
            return r.creep_force_x, r

        try:
            sat = 3.0 * mu * load / (constants.shear_modulus * h.semi_axis_x * h.semi_axis_y * 4.0)
            # dissimilar bodies (K != 0) shift the free-rolling creepage by up to a few saturation creepages
            # (Bentall & Johnson): bounds +-20 sat
            xi, res, evals, residual = _free_rolling(evaluate, 0.0, 0.1 * sat, -20 * sat, 20 * sat, mu * load,
                                                     "planar")
            break
        except GridTooSmall:
            if enlargement == MAX_ENLARGEMENTS:
                raise
            dom = [d * ENLARGE for d in dom]
    left, right = lateral_extent(g.y, res.pressure)
    q = {"approach": res.approach, "p_max": float(res.pressure.max()), "half_length_s": 0.5 * (right - left),
         "angle_span": (right - left) / geom.groove_radius, "adhesion_fraction": res.adhesion_fraction,
         "creepage_x": float(xi), "spin_moment": res.spin_moment, "friction_power": float(res.frictional_power),
         "total_force": res.normal_force}
    stats = {**{k: v for k, v in res.stats.items() if k != "history"}, "free_rolling_evaluations": evals,
             "free_rolling_residual": residual, "iterations": res.stats.get("newton_iterations"),
             "residual": res.stats.get("tangential_residual"), "grid_enlargements": enlargement,
             "grid_half_widths": [dom[0] * h.semi_axis_x, dom[1] * h.semi_axis_y],
             "hertz": {"a": h.semi_axis_x, "b": h.semi_axis_y, "p0": h.p_max, "approach": h.approach,
                       "Rx": rx, "Ry": ry}, "time_s": time.perf_counter() - t0}
    return GrooveSolution(q, res, None, stats)
