"""Frictionless normal contact of seed 000's barrel roller with its inner and outer raceway (Table 1, each contact
carrying the roller load N) on the conformal developed grids, with the developed half-space coefficients alone
(the conformal CECT's normal problem) or with the finite-body correction of
:mod:`femcheck.fem.compliance_split` (the whole roller and two ring segments of :mod:`femcheck.fem.srb_rolling`
minus the half-space), as a fixed point on the pressures.

Per contact c, on the FE's own developed grid (:func:`femcheck.fem.srb_rolling.grids`: the groove circle, x along
the rolling direction, s along the profile, n(s) the local normal from the ring into the roller):

    h_c(x, s; delta) + u_c(x, s) + [A_HS p_c](x, s) >= 0,  p_c >= 0,  complementary,
    sum p_c (n(s) . n(0)) dx ds = N                                              (load along the contact line)

h_c is the exact undeformed distance along n(s) (:func:`femcheck.fem.rolling_geometry.gap`) with the roller moved
rigidly by delta towards the ring along n(0) (seed 000 eq 16: the gap of the real surfaces, no paraboloid);
A_HS the developed half-space (Kalker's combined constants; the CECT's ``halfspace`` option); u_c = 0 for the
conformal CECT, and for the finite bodies the correction's normal displacement under the pressures of *both*
contacts (the roller couples them):

    u_c = sum_d [D(c, d) p_d]_n                         (:func:`femcheck.fem.compliance_split.coarse_field`)

evaluated on the correction grid and splined to the contact grid. Each pass solves both contacts by the conformal
load control (:func:`femcheck.cect.conformal.solve_normal_conformal`, Polonsky-Keer inside a secant on delta),
then u is recomputed; the iteration stops when u changes by less than ``tol`` of its largest value (it converges
in 2-3 passes: D is smooth and small beside A_HS near the contact). Tangential tractions are zero (frictionless),
so only the normal-normal part of D acts.

Quantities per contact (suffix ``_inner`` / ``_outer`` as :mod:`femcheck.problems.srb_contact` names them):
``p_max`` (Pa, the largest cell pressure), ``semi_axis_x`` and ``semi_axis_y`` (m, the power-law edges of
:func:`femcheck.qoi.semi_axes` on the developed coordinates x and s - s_mid, s_mid the middle of the loaded cells
along s: no Hertz shape assumed; the developed s is the arc length along the groove), ``contact_area`` (m^2,
pi a b as the other models of the kind) and ``approach`` (m, the rigid approach delta from first touch; for the
finite bodies it is relative to the correction's datum, so only the half-space one is comparable with Hertz).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from ..bem.halfspace import Grid
from ..cect.conformal import solve_normal_conformal
from ..cect.influence import CombinedConstants
from ..qoi import semi_axes
from . import srb_rolling as fe
from .compliance_split import Correction, coarse_field, field_at, fixed_point
from .contact_grid import ContactGrid
from .rolling_geometry import Crowned, Grooved, gap

CONTACTS = fe.CONTACTS
QUANTITIES = ("p_max", "semi_axis_x", "semi_axis_y", "contact_area")


@dataclass
class ContactSetup:
    """One contact's developed grid ``grid`` (FE frame), the planar ``cells`` of the same counts and sizes, the
    exact gap ``gap(delta)`` (m, (nx, ns)), the load weights n(s).n(0) (nx, ns), the load N (N) and the Hertz
    approach (m, a start for the secant)."""

    grid: ContactGrid
    cells: Grid
    gap: Callable[[float], np.ndarray]
    weights: np.ndarray
    load: float
    approach0: float


def setup(params: dict[str, Any], nx: int, ns: int, domain_x: float, domain_s: float) -> dict[str, ContactSetup]:
    """Both contacts on nx x ns cells over x in +-domain_x a_H and s in +-domain_s b_H (the larger Hertz semi-axes
    of the two contacts, :func:`femcheck.fem.srb_rolling.grids`; the window along s is clipped to the roller)."""
    N = float(params["load.normal"])
    grids = fe.grids(params, nx, ns, N, half_x=domain_x, half_s=domain_s)
    geo = fe.geometry(params)
    hz = fe.hertz_estimates(params, N)
    axis = np.array([0.0, 1.0, 0.0])             # the roller axis at the nominal pose (fe.geometry's frame)
    out = {}
    for c, g in grids.items():
        ring = Grooved(geo[c]["G"], geo[c]["rg"], geo["O"], geo["Y"])
        n0 = g.normal(0.0)

        def gap_of(delta: float, g=g, ring=ring, n0=n0) -> np.ndarray:
            # the roller moved by delta towards the ring along the contact line (the grid stays on the ring)
            return gap(g, Crowned(-delta * n0, axis, geo["r"], geo["R"]), ring)

        w = np.broadcast_to((g.normal(g.s) @ n0)[None, :], (g.nx, g.ns)).copy()
        out[c] = ContactSetup(g, Grid(g.nx, g.ns, g.dx, g.ds), gap_of, w, N, float(hz[c].approach))
    return out


@dataclass
class NormalPair:
    """Pressures (Pa, (nx, ns) per contact) on the setups' grids, the approaches (m), the outer passes and the
    relative change of the correction's displacement per pass (``history``), the Polonsky-Keer iterations and
    residuals of the last pass, and the time (s); ``grids``: the grids it was solved on."""

    pressure: dict[str, np.ndarray]
    approach: dict[str, float]
    grids: dict[str, ContactGrid]
    passes: int = 1
    history: list = field(default_factory=list)
    iterations: dict[str, int] = field(default_factory=dict)
    residual: dict[str, float] = field(default_factory=dict)
    time_s: float = 0.0


def _solve_once(setups: dict[str, ContactSetup], constants: CombinedConstants, extra: dict[str, np.ndarray] | None,
                warm: NormalPair | None, tol: float) -> NormalPair:
    p, d, its, res = {}, {}, {}, {}
    for c, st in setups.items():
        u = 0.0 if extra is None else extra[c]
        same = warm is not None and warm.pressure[c].shape == (st.grid.nx, st.grid.ns)
        base = float((st.gap(0.0) + u).min())         # first touch, the correction's displacement included
        a0 = warm.approach[c] if warm is not None and warm.approach[c] > base else base + st.approach0
        sol = solve_normal_conformal(st.cells, lambda delta, st=st, u=u: st.gap(delta) + u, constants,
                                     load=st.load, load_weights=st.weights, influence="halfspace", tol=tol,
                                     p0=warm.pressure[c] if same else None, approach0=a0)
        p[c], d[c], its[c], res[c] = sol.pressure, float(sol.approach), int(sol.iterations), float(sol.residual)
    return NormalPair(p, d, {c: st.grid for c, st in setups.items()}, iterations=its, residual=res)


def solve_pair(setups: dict[str, ContactSetup], constants: CombinedConstants, corr: Correction | None = None,
               warm: NormalPair | None = None, tol: float = 1e-4, max_passes: int = 20,
               pk_tol: float = 1e-10) -> NormalPair:
    """Both contacts (module docstring); ``corr`` None: the conformal half-space alone. ``warm``: a solution on
    any grid of the same contacts (its pressures start the fixed point through the correction). Raises
    ConvergenceError when the fixed point misses ``tol`` in ``max_passes``."""
    t0 = time.perf_counter()
    if corr is None:
        r = _solve_once(setups, constants, None, warm, pk_tol)
        r.time_s = time.perf_counter() - t0
        return r
    r0 = warm if warm is not None else _solve_once(setups, constants, None, None, pk_tol)

    def solve(u: dict[str, np.ndarray], r: NormalPair) -> NormalPair:
        extra = {c: field_at(corr, u[c], c, st.grid.x, st.grid.s)[2] for c, st in setups.items()}
        return _solve_once(setups, constants, extra, r, pk_tol)

    fp = fixed_point(solve, lambda r: _normal_field(corr, r), r0, tol, max_passes, "finite-body normal contact")
    r = fp.solution
    r.passes, r.history, r.time_s = fp.iterations, fp.history, time.perf_counter() - t0
    return r


def _normal_field(corr: Correction, r: NormalPair) -> dict[str, np.ndarray]:
    """The correction's displacement (3, nx_c, ns_c) on the correction grids under the pressures of ``r`` (on the
    grids it was solved on)."""
    src = {}
    for c, g in r.grids.items():
        p = r.pressure[c]
        src[c] = (corr.grids[c].with_cells(g.x, g.s), np.stack([np.zeros_like(p), np.zeros_like(p), p]))
    return coarse_field(corr, src)


def quantities(setups: dict[str, ContactSetup], r: NormalPair) -> dict[str, float]:
    """The module docstring's quantities of both contacts, suffixed ``_inner`` / ``_outer``, and the loads."""
    out = {}
    for c, st in setups.items():
        g, p = st.grid, r.pressure[c]
        loaded = g.s[p.max(axis=0) > 0]
        mid = 0.5 * float(loaded.min() + loaded.max())
        X, S = np.meshgrid(g.x, g.s - mid, indexing="ij")
        a, b, _ = semi_axes(X, S, p)
        out.update({f"p_max_{c}": float(p.max()), f"semi_axis_x_{c}": float(a), f"semi_axis_y_{c}": float(b),
                    f"contact_area_{c}": float(np.pi * a * b), f"approach_{c}": r.approach[c] - float(st.gap(0.0).min()),
                    f"total_force_{c}": float(np.sum(p * st.weights) * g.cell_area)})
    out["total_force"] = out["total_force_inner"]
    return out
