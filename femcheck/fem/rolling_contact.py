"""Steady rolling contact with Coulomb friction on FE compliance tables: one contact, or several contacts coupled
through a common body 1 (the two contacts of a bearing roller), solved by the FE side's own semi-smooth Newton
(:mod:`femcheck.solvers.coulomb3d`), independently of the exact theory's solvers.

Kinematics (Kalker 1990 §2.2; seed 000 eqs 16-21; spec srb-rolling §4.2). On every contact c the material flows
along -e_x at the reference speed V_c; the relative slip of body 1 over body 2 per unit V_c at cell I is

    s_I = w_I / V_c + kappa_c(s_I) [(u - u')/dx]_I,   (u - u')_I = sum_J [A(x_I - x_J) - A(x_I + dx - x_J)] p_J

(u = u(body 1) - u(body 2) from the relative tables, u' one cell downstream, kappa the variable rolling step,
eq 21), and the gap g_I = h_I + u_n,I (+ sum_k theta_k dh/dtheta_k). The tractions p on body 1 in the local frames
(e_x, t(s), n(s)) of every contact are the unknowns; body 1 is common, so p on one contact displaces the other
through the cross tables (the roller's global deflection).

Extra unknowns (:class:`ExtraUnknown`): scalars theta_k with their gap and slip derivatives and one linear
constraint each on the tractions: a rigid approach under load control (dh/dtheta = -n(s).e, constraint
sum p.e dA = N), a free-rolling creepage (d(w_x/V)/dtheta = the caller's slip derivative, constraint
sum p_x dA = 0), anything the equilibrium needs.

Outputs per contact (:class:`ContactResult`; arrays (nx, ns), local components, tractions on body 1): pressure,
p_x, p_s, contact and adhesion masks, slip velocity V s (m/s), frictional power density -p_t . v (W/m^2),
lateral distributions N*(s) = sum_x p_n dx and F_x*(s) = sum_x p_x dx (N/m), 3D resultant force and moment about
a given centre (model frame, N and N m), the normal load along the reference normal, the spin moment about the
reference normal through the grid's reference point P0(0, 0), frictional power (W), adhesion fraction (adhesion
cells / contact cells), contact extent along s.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError, InputError
from ..solvers.coulomb3d import ContactSystem, solve as solve_system
from .contact_grid import ContactGrid, ContactInput


@dataclass
class RelativeCompliance:
    """Tables of u = u(body 1) - u(body 2) per unit traction on body 1 (m/Pa): ``tables[(receiver, source)]``
    (3, 3, n_r + n_s, ns_r, ns_s) with the lag of index k = lag0 + k dx (see
    :mod:`femcheck.fem.body_compliance`), ``grids`` by contact name, ``stats`` of the FE runs."""

    grids: dict[str, ContactGrid]
    tables: dict[tuple[str, str], np.ndarray]
    lag0: dict[tuple[str, str], float]
    stats: dict = field(default_factory=dict)


def relative_compliance(body1, bodies2: dict, grids: dict[str, ContactGrid]) -> RelativeCompliance:
    """Combine the FE tables of body 1 (``BodyCompliance`` with every contact) and of each contact's body 2
    (``bodies2[name]``): A(c, c) = C_1(c, c) + C_2,c(c, c) (body 2 carries -p: u_rel = C_1 p - C_2 (-p)) and
    A(c, d) = C_1(c, d) for c != d (only body 1 is common)."""
    tables, lag0 = {}, {}
    for key, T in body1.tables.items():
        r, s = key
        A = T.copy()
        if r == s:
            A += bodies2[r].tables[(r, r)]
        tables[key] = A
        lag0[key] = body1.lag0[key]
    stats = {"body1": body1.stats, **{f"body2_{k}": v.stats for k, v in bodies2.items()}}
    return RelativeCompliance(dict(grids), tables, lag0, stats)


@dataclass
class ExtraUnknown:
    """A scalar unknown theta with ``gap[c]`` = dh/dtheta (nx, ns), ``slip[c]`` = d(w/V)/dtheta (2, nx, ns),
    and its constraint sum_c sum_I coef[c][:, I] . p_I = ``target`` with ``constraint[c]`` (3, nx, ns) (units:
    N per Pa, i.e. m^2 times direction cosines); ``start`` initial value; ``theta_coefficient`` the
    constraint's own dependence on theta (usually 0)."""

    name: str
    gap: dict = field(default_factory=dict)
    slip: dict = field(default_factory=dict)
    constraint: dict = field(default_factory=dict)
    target: float = 0.0
    start: float = 0.0
    theta_coefficient: float = 0.0


def approach_unknown(name: str, contact: str, grid: ContactGrid, direction: np.ndarray, load: float,
                     start: float) -> ExtraUnknown:
    """Load control of one contact: body 1 translates rigidly by theta along -``direction`` (the closing
    direction, unit, model frame), so dh/dtheta = -n(s).direction, and the resultant of the tractions along
    ``direction`` equals ``load`` (N)."""
    e = np.asarray(direction, dtype=float)
    e = e / np.linalg.norm(e)
    fr = grid.frame(grid.s)                                     # (ns, 3, 3) rows e_x, t, n
    cos = fr @ e                                                # (ns, 3): e_x.e, t.e, n.e
    dh = -np.broadcast_to(cos[:, 2], (grid.nx, grid.ns))
    coef = np.broadcast_to(cos.T[:, None, :], (3, grid.nx, grid.ns)) * grid.cell_area
    return ExtraUnknown(name, gap={contact: dh.copy()}, constraint={contact: coef.copy()}, target=float(load),
                        start=float(start))


def creepage_unknown(name: str, contact: str, grid: ContactGrid, slip_derivative: np.ndarray | None = None,
                     force: float = 0.0) -> ExtraUnknown:
    """Free rolling: theta shifts the rigid slip per unit V by ``slip_derivative`` (2, nx, ns) (default a
    uniform longitudinal creepage, (1, 0)) and the longitudinal force sum p_x dA equals ``force`` (N)."""
    d = np.zeros((2, grid.nx, grid.ns))
    if slip_derivative is None:
        d[0] = 1.0
    else:
        d[:] = slip_derivative
    coef = np.zeros((3, grid.nx, grid.ns))
    coef[0] = grid.cell_area
    return ExtraUnknown(name, slip={contact: d}, constraint={contact: coef}, target=float(force))


@dataclass
class ContactResult:
    """One contact's solution (module docstring)."""

    name: str
    grid: ContactGrid
    pressure: np.ndarray
    px: np.ndarray
    ps: np.ndarray
    contact: np.ndarray
    adhesion: np.ndarray
    slip_velocity: np.ndarray
    power_density: np.ndarray
    gap: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    normal_force: float
    spin_moment: float
    friction_power: float
    adhesion_fraction: float
    creep_force_x: float
    creep_force_s: float
    lateral_normal: np.ndarray
    lateral_longitudinal: np.ndarray
    s_extent: tuple[float, float]

    @property
    def p_max(self) -> float:
        return float(self.pressure.max())


@dataclass
class RollingSolution:
    contacts: dict[str, ContactResult]
    theta: dict[str, float]
    iterations: int
    residual: float
    stats: dict = field(default_factory=dict)


def _gather(T: np.ndarray, rows: tuple, cols: tuple, n_src: int, shift: int = 0) -> np.ndarray:
    """Dense (3 R, 3 C) block (component-major) of table T at receiver cells rows = (ix, is) and source cells
    cols = (jx, js); ``shift`` = 1 takes the lag one cell downstream (u')."""
    k = rows[0][:, None] - cols[0][None, :] + n_src - 1 + shift
    ir, js = rows[1][:, None], cols[1][None, :]
    return np.block([[T[i, j][k, ir, js] for j in range(3)] for i in range(3)])


def _check_edge(name: str, grid: ContactGrid, contact: np.ndarray) -> None:
    if contact[0].any() or contact[-1].any() or contact[:, 0].any() or contact[:, -1].any():
        raise InputError("numerics.fem_grid", f"the {name} contact reaches the edge of its potential contact grid; "
                         "enlarge the grid (allowed: half-widths beyond the contact)")


def solve_rolling(compliance: RelativeCompliance, inputs: dict[str, ContactInput], mu: float,
                  extras: list[ExtraUnknown] = (), centre=(0.0, 0.0, 0.0), candidate_gap: float = np.inf,
                  tol: float = 1e-9, max_iter: int = 200, warm: RollingSolution | None = None,
                  check_edge: bool = True) -> RollingSolution:
    """Steady rolling of the contacts ``inputs`` (name -> :class:`ContactInput`, grids as in ``compliance``)
    with Coulomb ``mu`` (> 0; np.inf: full adhesion is not supported), the ``extras`` unknowns, moments about
    ``centre`` (model frame, m). Cells with h >= ``candidate_gap`` (m) or h = inf are never in contact.
    ``warm``: start from a previous solution on the same grids."""
    t0 = time.perf_counter()
    if not mu > 0:
        raise InputError("friction.mu", f"{mu:g}; allowed: > 0")
    names = list(inputs)
    cand, offsets, n = {}, {}, 0
    for c in names:
        inp = inputs[c]
        if inp.grid is not compliance.grids[c] and not np.allclose(inp.grid.x, compliance.grids[c].x):
            raise ValueError(f"contact {c!r}: the input grid differs from the compliance grid")
        m = np.isfinite(inp.gap) & (inp.gap < candidate_gap)
        cand[c] = np.nonzero(m)
        offsets[c] = n
        n += cand[c][0].size
    k = len(extras)
    G = np.zeros((n, 3 * n))
    S = np.zeros((2 * n, 3 * n))
    g0 = np.zeros(n)
    s0 = np.zeros(2 * n)
    Cg = np.zeros((n, k))
    Cs = np.zeros((2 * n, k))
    L = np.zeros((k, 3 * n))
    comp = lambda c, i: slice(i * n + offsets[c], i * n + offsets[c] + cand[c][0].size)  # noqa: E731
    for c in names:
        gc, rc = compliance.grids[c], cand[c]
        kap = inputs[c].kappa[rc[1]]
        g0[comp(c, 0)] = inputs[c].gap[rc]
        for i in range(2):
            s0[comp(c, i)] = inputs[c].slip[i][rc] / inputs[c].speed
        for d in names:
            T = compliance.tables[(c, d)]
            cd = cand[d]
            A = _gather(T, rc, cd, compliance.grids[d].nx)
            A1 = _gather(T, rc, cd, compliance.grids[d].nx, shift=1)
            nr, ns_ = rc[0].size, cd[0].size
            for j in range(3):
                G[comp(c, 0), comp(d, j)] = A[2 * nr:3 * nr, j * ns_:(j + 1) * ns_]
                for i in range(2):
                    blk = (A[i * nr:(i + 1) * nr, j * ns_:(j + 1) * ns_]
                           - A1[i * nr:(i + 1) * nr, j * ns_:(j + 1) * ns_]) / gc.dx
                    S[comp(c, i), comp(d, j)] = kap[:, None] * blk
        for q, ex in enumerate(extras):
            if c in ex.gap:
                Cg[comp(c, 0), q] = np.asarray(ex.gap[c])[rc]
            if c in ex.slip:
                for i in range(2):
                    Cs[comp(c, i), q] = np.asarray(ex.slip[c])[i][rc]
            if c in ex.constraint:
                for j in range(3):
                    L[q, comp(c, j)] = np.asarray(ex.constraint[c])[j][rc]
    b = np.array([ex.target for ex in extras], dtype=float)
    Lt = np.diag([ex.theta_coefficient for ex in extras]) if k else np.zeros((0, 0))
    area = float(np.mean([compliance.grids[c].cell_area for c in names]))
    sysm = ContactSystem(g0, G, Cg, s0, S, Cs, L, Lt, b, mu, force_scale=area * max(1, n // 4))
    theta0 = np.array([ex.start for ex in extras], dtype=float)
    p0 = None
    if warm is not None:
        p0 = np.zeros(3 * n)
        for c in names:
            r = warm.contacts[c]
            for j, f in enumerate((r.px, r.ps, r.pressure)):
                p0[comp(c, j)] = f[cand[c]]
        theta0 = np.array([warm.theta.get(ex.name, ex.start) for ex in extras])
    t_build = time.perf_counter() - t0
    sol = solve_system(sysm, p0, theta0, tol=tol, max_iter=max_iter)
    contacts = {}
    ctr = np.asarray(centre, dtype=float)
    for c in names:
        gc, rc, inp = compliance.grids[c], cand[c], inputs[c]
        fields = []
        for arr, i in ((sol.p, 0), (sol.p, 1), (sol.p, 2)):
            f = np.zeros((gc.nx, gc.ns))
            f[rc] = arr[comp(c, i)]
            fields.append(f)
        px, ps, pn = fields
        contact = np.zeros((gc.nx, gc.ns), dtype=bool)
        contact[rc] = sol.contact[comp(c, 0)]
        stick = np.zeros_like(contact)
        stick[rc] = sol.stick[comp(c, 0)]
        slip = np.zeros((2, gc.nx, gc.ns))
        for i in range(2):
            slip[i][rc] = sol.slip[comp(c, i)]
        slip = np.where(contact[None], slip * inp.speed, 0.0)
        gap = np.full((gc.nx, gc.ns), np.inf)
        gap[rc] = sol.gap[comp(c, 0)]
        if check_edge:
            _check_edge(c, gc, contact)
        contacts[c] = _resultants(c, gc, px, ps, pn, contact, stick & contact, slip, gap, ctr)
    stats = {"cells": int(n), "unknowns": int(3 * n + k), "iterations": sol.iterations, "residual": sol.residual,
             "build_s": t_build, "solve_s": time.perf_counter() - t0 - t_build, "history": sol.history}
    return RollingSolution(contacts, {ex.name: float(v) for ex, v in zip(extras, sol.theta)}, sol.iterations,
                           sol.residual, stats)


def _resultants(name, grid: ContactGrid, px, ps, pn, contact, adhesion, slip, gap, centre) -> ContactResult:
    dA = grid.cell_area
    fr = grid.frame(grid.s)                                              # (ns, 3, 3)
    t = (px[..., None] * fr[None, :, 0] + ps[..., None] * fr[None, :, 1] + pn[..., None] * fr[None, :, 2])
    P = grid.cell_centres()
    force = t.sum(axis=(0, 1)) * dA
    moment = np.cross(P - centre, t).sum(axis=(0, 1)) * dA
    n_ref = grid.normal(0.0)
    P_ref = grid.point(0.0, 0.0)
    spin = float(n_ref @ np.cross(P - P_ref, t).sum(axis=(0, 1)) * dA)
    power = -(px * slip[0] + ps * slip[1])
    n_contact = int(contact.sum())
    rows = np.flatnonzero(contact.any(axis=0))
    extent = ((float(grid.s[rows[0]] - 0.5 * grid.ds), float(grid.s[rows[-1]] + 0.5 * grid.ds))
              if rows.size else (0.0, 0.0))
    return ContactResult(name, grid, pn, px, ps, contact, adhesion, slip, power, gap, force, moment,
                         float(force @ n_ref), spin, float(power.sum() * dA),
                         float(adhesion.sum() / n_contact) if n_contact else 0.0, float(px.sum() * dA),
                         float(ps.sum() * dA), pn.sum(axis=0) * grid.dx, px.sum(axis=0) * grid.dx, extent)


def check_converged(sol: RollingSolution, tol: float) -> None:
    if not sol.residual <= tol:
        raise ConvergenceError("FE rolling contact", sol.iterations, sol.residual, tol)
