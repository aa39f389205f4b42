"""Split influence coefficients of finite bodies: the conformal half-space tables on any contact grid plus a
finite-body correction computed once by FE and interpolated (spec srb-rolling §8.2; the decoupling of the
contact grid from the FE mesh).

The FE relative tables of :mod:`femcheck.fem.rolling_compliance` tie the contact grid to the mesh (one element
layer per cell along s), so a fine contact grid needs a fine 3D mesh. Writing the finite-body compliance as

    A_FE(c, d) = A_HS(c, d) + D(c, d),       A_HS(c, c) Boussinesq-Cerruti on the developed grid
                                             (:func:`femcheck.fem.halfspace_tables.halfspace_table`),
                                             A_HS(c, d) = 0 for c != d (two contacts share only the roller),

the correction D carries what the half-space lacks: the bodies' finite size, their supports, the roller's global
deflection and mean-axis motion, the cross influence of the roller's two contacts, the conformity of the curved
surfaces. Away from the loaded cell it is a smooth function of the receiver and source positions, because the
half-space and the body share the same singular near field (Johnson 1985 §3.2: the Boussinesq-Cerruti solution is
the local limit of every elastic body's surface Green's function). Per unit force,

    d_ij(x_I - x_J, s_I, s_J) = D_ij[I, J] / (dx ds)_c                  (m/N)

is tabulated on a correction grid c (the FE's own cells) and evaluated on a target grid t by the tensor-product
cubic spline in (lag, s_I, s_J) (the end polynomials extended over the half cell by which a finer grid's outer
centres lie beyond the correction grid's), D_t = d (dx ds)_t. Near the loaded cell d also holds the FE's
discretisation error of the singular response (one P2 layer per cell: up to 12 % on a single cell's self
coefficient, cancelling to 1-2 % on smooth loads; tests/test_fe_rolling.py); that part converges with the FE mesh
at a fixed correction grid, which is how the correction is certified (:func:`correction_difference`).

Translation invariance along x (bodies of revolution, :mod:`femcheck.fem.body_compliance`) makes d a function of
the lag; along s it is not (grooves, roller ends): d depends on s_I and s_J separately.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
from scipy.interpolate import make_interp_spline

from ..cect.influence import CombinedConstants
from ..errors import ConvergenceError
from .contact_grid import ContactGrid
from .halfspace_tables import halfspace_table
from .rolling_contact import RelativeCompliance

Pair = tuple[str, str]


@dataclass
class Correction:
    """Finite-body correction per unit force (module docstring): ``kernels[(receiver, source)]`` (3, 3, n_lag,
    ns_r, ns_s) in m/N at lags ``lags[pair]`` (m) and profile coordinates ``s[name]`` (m) of the correction
    grids ``grids``; ``stats`` of the FE run it came from."""

    grids: dict[str, ContactGrid]
    kernels: dict[Pair, np.ndarray]
    lags: dict[Pair, np.ndarray]
    stats: dict = field(default_factory=dict)

    def s(self, name: str) -> np.ndarray:
        return self.grids[name].s


BASES = ("halfspace", "blanco", "rotated_response")


def _halfspace(grids: dict[str, ContactGrid], r: str, s: str, constants: CombinedConstants,
               base: str = "halfspace") -> tuple[float, np.ndarray]:
    """The analytic part on a pair: the developed half-space (``base`` "halfspace") or the angle-corrected
    coefficients of :mod:`femcheck.cect.influence_conformal` ("blanco", "rotated_response": the normal turning
    along the groove profile of radius r_g, s/r_g), zero between two contacts."""
    gr, gs = grids[r], grids[s]
    if r != s:
        return float(gr.x[0] - gs.x[-1]), np.zeros((3, 3, gr.nx + gs.nx, gr.ns, gs.ns))
    return halfspace_table(gr, gs, constants, base)


def correction(fe: RelativeCompliance, constants: CombinedConstants, near: int = 2,
               base: str = "halfspace") -> Correction:
    """D = A_FE - A_HS on the FE's own grids, per unit force (m/N). ``near`` > 0: on the self pairs the values
    within ``near`` cells of the loaded cell (|lag| <= near dx and |s_I - s_J| <= near ds) are replaced by the
    harmonic fill of their surroundings (:func:`fill_near_field`): there D is the FE's discretisation error of
    the singular response (module docstring), a pattern of the FE's own cells that no other grid shares;
    ``near`` = 0 keeps it (the hybrid then reproduces the FE on its own grid)."""
    kernels, lags = {}, {}
    for (r, s), T in fe.tables.items():
        lag0, H = _halfspace(fe.grids, r, s, constants, base)
        if abs(lag0 - fe.lag0[(r, s)]) > 1e-12:
            raise ValueError(f"pair {(r, s)}: FE and half-space lags differ")
        g = fe.grids[s]
        K = (T - H) / g.cell_area
        lags[(r, s)] = lag0 + fe.grids[r].dx * np.arange(T.shape[2])
        if r == s and near > 0:
            K = fill_near_field(K, lags[(r, s)] / g.dx, near)
        kernels[(r, s)] = K
    return Correction(dict(fe.grids), kernels, lags, {"fe": fe.stats, "near": near, "base": base})


def fill_near_field(K: np.ndarray, lag_cells: np.ndarray, near: int) -> np.ndarray:
    """K (3, 3, n_lag, ns, ns) of a self pair with the entries |lag| <= near, |I - J| <= near replaced, for each
    component pair and receiver row I, by the solution of the discrete Laplace equation in (lag, s_J) whose
    boundary values are the surrounding entries (Dirichlet; at the table's s edge the second difference along
    the lag only). Functions affine in lag and s_J and their product are kept exactly."""
    from scipy.sparse import lil_matrix
    from scipy.sparse.linalg import spsolve

    out = K.copy()
    n_lag, ns = K.shape[2], K.shape[4]
    kl = np.flatnonzero(np.abs(lag_cells) <= near + 1e-9)
    for I in range(ns):
        js = np.arange(max(0, I - near), min(ns, I + near + 1))
        unknown = [(k, j) for k in kl for j in js]
        index = {u: q for q, u in enumerate(unknown)}
        A = lil_matrix((len(unknown), len(unknown)))
        B = np.zeros((len(unknown), 3, 3))
        for q, (k, j) in enumerate(unknown):
            for dk, dj in ((1, 0), (0, 1)):
                pair = ((k + dk, j + dj), (k - dk, j - dj))
                if not all(0 <= kk < n_lag and 0 <= jj < ns for kk, jj in pair):
                    continue            # at the table's edge: the second difference along the other axis only
                for kk, jj in pair:
                    A[q, q] += 1.0
                    if (kk, jj) in index:
                        A[q, index[(kk, jj)]] -= 1.0
                    else:
                        B[q] += K[:, :, kk, I, jj]
        X = spsolve(A.tocsc(), B.reshape(len(unknown), 9)).reshape(len(unknown), 3, 3)
        for q, (k, j) in enumerate(unknown):
            out[:, :, k, I, j] = X[q]
    return out


def _axis(values: np.ndarray, target: np.ndarray, name: str) -> None:
    """The target points may lie beyond the correction grid's centres by at most one correction cell."""
    step = values[1] - values[0] if values.size > 1 else np.inf
    if target.min() < values[0] - step * 1.0001 or target.max() > values[-1] + step * 1.0001:
        raise ValueError(f"the target grid's {name} ({target.min():.4g}, {target.max():.4g}) m lies beyond the "
                         f"correction grid's ({values[0]:.4g}, {values[-1]:.4g}) m by more than one cell")


def evaluate(corr: Correction, pair: Pair, lags: np.ndarray, s_r: np.ndarray, s_s: np.ndarray) -> np.ndarray:
    """d_ij (m/N) of ``pair`` at the tensor product (lags, s_r, s_s), shape (3, 3, n_lag, ns_r, ns_s): the
    tensor-product cubic spline (not-a-knot) through the tabulated values, one axis after the other (exact for a
    tensor-product target; extrapolated by the end polynomials over at most one cell)."""
    K = corr.kernels[pair]
    axes = (corr.lags[pair], corr.s(pair[0]), corr.s(pair[1]))
    out = K
    for a, (ax, t, name) in enumerate(zip(axes, (lags, s_r, s_s), ("lags", "receiver s", "source s"))):
        _axis(ax, t, name)
        out = make_interp_spline(ax, out, k=min(3, ax.size - 1), axis=2 + a)(t, extrapolate=True)
    return out


def hybrid(corr: Correction, grids: dict[str, ContactGrid], constants: CombinedConstants) -> RelativeCompliance:
    """A_HS + D on the target ``grids`` (same contact names and profiles as the correction's; any dx, ds and
    windows inside the correction grids' to within one correction cell)."""
    t0 = time.perf_counter()
    for c, g in grids.items():
        h = corr.grids[c]
        if abs(g.radius - h.radius) > 1e-12 * h.radius or np.linalg.norm(g.centre - h.centre) > 1e-9:
            raise ValueError(f"contact {c!r}: the target grid's profile differs from the correction grid's")
    tables, lag0 = {}, {}
    base = corr.stats.get("base", "halfspace")
    for (r, s) in corr.kernels:
        l0, H = _halfspace(grids, r, s, constants, base)
        lags = l0 + grids[r].dx * np.arange(H.shape[2])
        D = evaluate(corr, (r, s), lags, grids[r].s, grids[s].s)
        tables[(r, s)] = H + D * grids[s].cell_area
        lag0[(r, s)] = l0
    stats = {"model": f"{base} + FE correction", "interpolation": "tensor-product cubic spline",
             "correction_grids": {c: [g.nx, g.ns] for c, g in corr.grids.items()},
             "correction_fe": corr.stats.get("fe", {}), "build_s": time.perf_counter() - t0}
    return RelativeCompliance(dict(grids), tables, lag0, stats)


def correction_difference(a: Correction, b: Correction) -> dict:
    """How far two corrections on the same grids are apart (FE mesh convergence at a fixed correction grid): per
    pair, the largest and the rms difference of the tabulated d relative to the largest |d| of that pair."""
    out = {}
    for pair, Ka in a.kernels.items():
        Kb = b.kernels[pair]
        scale = np.abs(Ka).max()
        out[f"{pair[0]}<-{pair[1]}"] = {"max_rel": float(np.abs(Ka - Kb).max() / scale),
                                        "rms_rel": float(np.sqrt(np.mean((Ka - Kb) ** 2)) / scale)}
    return out


def _tent(nodes: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(n_points, n_nodes) linear-interpolation weights on uniform ``nodes`` (clamped at the ends): the transpose
    spreads point values onto the nodes keeping their sum and, inside, their first moment."""
    h = nodes[1] - nodes[0] if nodes.size > 1 else 1.0
    t = np.clip((points - nodes[0]) / h, 0.0, nodes.size - 1.0)
    i0 = np.minimum(np.floor(t).astype(int), max(nodes.size - 2, 0))
    w1 = t - i0
    W = np.zeros((points.size, nodes.size))
    rows = np.arange(points.size)
    W[rows, i0] = 1.0 - w1
    if nodes.size > 1:
        W[rows, i0 + 1] += w1
    return W


def coarse_field(corr: Correction, tractions: dict[str, tuple[ContactGrid, np.ndarray]]) -> dict[str, np.ndarray]:
    """The correction's displacement (3, nx_c, ns_c) at the correction grids' cell centres under ``tractions``
    (name -> (grid, p (3, nx, ns) in Pa on body 1, local components) on any grid of the correction's profiles):
    the cell forces p dx ds spread onto the correction cells by linear weights (sum and first moment kept: error
    O(h_c^2 d'') of a smooth d), then the correction's own tables."""
    forces = {}
    for name, (g, p) in tractions.items():
        c = corr.grids[name]
        Wx, Ws = _tent(c.x, g.x), _tent(c.s, g.s)
        forces[name] = np.einsum("ia,jb,cij->cab", Wx, Ws, np.asarray(p, dtype=float) * g.cell_area)
    out = {}
    for r, c in corr.grids.items():
        u = np.zeros((3, c.nx, c.ns))
        for s, F in forces.items():
            K, n_s = corr.kernels[(r, s)], corr.grids[s].nx
            k = np.arange(c.nx)[:, None] - np.arange(n_s)[None, :] + n_s - 1        # lag index (receiver, source)
            u += np.einsum("ijabIJ,jbJ->iaI", K[:, :, k], F)
        out[r] = u
    return out


def field_at(corr: Correction, coarse: np.ndarray, name: str, x: np.ndarray, s: np.ndarray) -> np.ndarray:
    """A coarse field (3, nx_c, ns_c) of contact ``name`` (:func:`coarse_field`) at the points x (nx,) and s (ns,)
    (m, tensor product) by the cubic spline: (3, nx, ns)."""
    c = corr.grids[name]
    u = coarse
    for axis, (nodes, t) in enumerate(((c.x, np.asarray(x, dtype=float)), (c.s, np.asarray(s, dtype=float)))):
        _axis(nodes, t, "receiver x" if axis == 0 else "receiver s")
        u = make_interp_spline(nodes, u, k=min(3, nodes.size - 1), axis=1 + axis)(t, extrapolate=True)
    return u


def correction_field(corr: Correction, tractions: dict[str, tuple[ContactGrid, np.ndarray]],
                     receivers: dict[str, ContactGrid]) -> dict[str, np.ndarray]:
    """Displacement (3, nx, ns) (m, local components of each receiving grid) that the finite-body correction
    adds at the cell centres of ``receivers`` under ``tractions`` (:func:`coarse_field`, then :func:`field_at`):
    for the fine contact grids the FE tables cannot reach."""
    coarse = coarse_field(corr, tractions)
    return {r: field_at(corr, coarse[r], r, g.x, g.s) for r, g in receivers.items()}


@dataclass
class FixedPoint:
    """The converged ``solution`` of :func:`fixed_point`, its outer ``iterations``, the relative change of the
    correction's displacement per iteration (``history``) and the time (s)."""

    solution: Any
    iterations: int
    history: list = field(default_factory=list)
    time_s: float = 0.0


def fixed_point(solve: Callable[[dict[str, np.ndarray], Any], Any], fields: Callable[[Any], dict[str, np.ndarray]],
                start: Any, tol: float = 1e-4, max_outer: int = 20, what: str = "finite-body fixed point",
                progress=None) -> FixedPoint:
    """The finite-body correction as a fixed point on the tractions (Picard): from the solution ``start`` (the
    half-space one, or one on another grid), u = ``fields(solution)`` (the correction's coarse displacement per
    contact, :func:`coarse_field`) and solution = ``solve(u, solution)`` (the contact problem with u as extra gap
    and slip, warm-started), until u changes by less than ``tol`` of its largest value. The correction is smooth
    and small beside the half-space near the contact, so the map contracts (2-3 iterations). Raises
    ConvergenceError when ``tol`` is missed in ``max_outer`` iterations."""
    t0 = time.perf_counter()
    sol, last, history = start, None, []
    for it in range(1, max_outer + 1):
        u = fields(sol)
        if last is not None:
            scale = max(float(np.abs(v).max()) for v in u.values()) or 1.0
            change = max(float(np.abs(u[c] - last[c]).max()) for c in u) / scale
            history.append(change)
            if progress:
                progress(f"{what}: outer iteration {it - 1}, correction changed by {change:.2e}")
            if change < tol:
                return FixedPoint(sol, it - 1, history, time.perf_counter() - t0)
        last = u
        sol = solve(u, sol)
    raise ConvergenceError(f"{what} (correction's displacement)", max_outer, history[-1] if history else np.inf, tol)
