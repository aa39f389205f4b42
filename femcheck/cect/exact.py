"""Kalker's exact theory on a planar contact (the CECT core): normal and tangential contact of two elastic
half-spaces on an Eulerian grid of rectangular elements, for steady rolling and for shift.

Conventions (conv.md, Kalker 1990): x rolling direction, y lateral, z normal into body 1. ``px, py, pn`` are the
tractions on body 1 (Pa); u = u(body 1) - u(body 2) the tangential displacement difference (m), influence
coefficients from :mod:`femcheck.cect.influence`.

Steady rolling (Kalker 1990 ch. 2; seed 000 eqs 16-17 and 19): the material flows through the contact grid in
the -x direction at the rolling speed V, so the leading edge is at +x. The relative slip (slip velocity / V) is
  s = w + (u - u')/dq,   w = (xi - phi y, eta + phi x),   u'(x, y) = u(x + dq, y),
with dq = dx (one element per time step): the displacement difference u - u' is computed with the difference
matrix [dIC] = ([IC] - [IC'])/dq of eq. 19, [IC'] being the influence coefficients evaluated one element
downstream. This is the first-order Eulerian discretisation of s = w - du/dx used by Kalker's CONTACT.
Shift (Cattaneo-Mindlin; Kalker 1990 §2.3): s = delta + u, where delta (m) is the rigid shift of body 1 relative
to body 2, unknown when the tangential force is prescribed.

Coulomb's law, element by element with traction bound g = mu pn:
  |p_t| <= g;  |p_t| < g  =>  s = 0 (adhesion);  s != 0  =>  p_t = -g s/|s| (slip).
It is solved as the non-smooth equation F(p) = p - Proj_{|q|<=g}(p - r s(p)) = 0 (an Alart-Curnier-type
reformulation; r > 0 per element, here 1/diag of the slip operator) by a semi-smooth Newton method with a
back-tracking line search on |F|^2; the generalised Jacobian is I - Pi + Pi r dS/dp with Pi the derivative of the
projection (I inside the disc, (g/|z|)(I - n n^T) outside). The element-wise Gauss-Seidel solvers of CONTACT
(ConvexGS, SteadyGS) are not used: their per-element sweeps do not vectorise in numpy, while the Newton
Jacobian is a dense matrix assembled by array operations and factorised by LAPACK.

Normal problem: bound-constrained CG (Polonsky-Keer, :func:`femcheck.bem.polonsky_keer.polonsky_keer`) with
Love's rectangles (A_zz = (1 - nu)/(pi G r) = 1/(pi E* r)). Dissimilar bodies (K != 0) couple the problems:
the tangential tractions add A_zt p_t to the gap and the pressure adds A_tz pn to the tangential displacement.
K = 0: Johnson's process (normal, then tangential, once). K != 0: Panagiotopoulos' process (alternate until the
tractions stop changing), as in seed 000 §3.2.2.
"""
from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field
from functools import lru_cache, partial
from typing import Callable

import numpy as np
import scipy.linalg as sla

from ..bem.convolution import DCFFT
from ..bem.halfspace import Grid, half_space_operator, half_space_preconditioner
from ..bem.polonsky_keer import polonsky_keer
from ..errors import ConvergenceError, InputError
from .coulomb import TangentialResult, coulomb_residual, nonmonotone_step, projection_derivative
from .influence import CombinedConstants, influence
from .tangential_fft import solve_tangential_fft

TANGENTIAL_SOLVERS = ("auto", "dense", "fft")
# "auto" switches to the matrix-free solver above this many contact elements: the dense Newton matrix costs
# O(C^3) per step while GMRES with FFT products costs O(C log C) per iteration. Measured on creep-curve
# (benchmarks/exact_scaling.py): equal at C = 168 (0.05 s), dense 18x slower at C = 680 and 50x at C = 1512
AUTO_FFT_ELEMENTS = 300
Gap = Callable[[np.ndarray, np.ndarray], np.ndarray]


# --------------------------------------------------------------------------------------------------------------
# influence-coefficient operators on a grid
# --------------------------------------------------------------------------------------------------------------
def lag_table(component: str, g: Grid, constants: CombinedConstants) -> np.ndarray:
    """A_ij at all lags of grid ``g``: T[kx + nx - 1, ky + ny - 1] = A_ij(kx dx, ky dy) for
    kx in [-(nx-1), nx] (one extra lag downstream, needed by the rolling difference), ky in [-(ny-1), ny-1]."""
    tx, ty = lags(g)
    return influence(component, tx, ty, g.dx, g.dy, constants)


def lags(g: Grid) -> tuple[np.ndarray, np.ndarray]:
    """The lags (m) of :func:`lag_table` as broadcastable columns / rows: kx dx for kx in [-(nx-1), nx], ky dy
    for ky in [-(ny-1), ny-1]."""
    kx = np.arange(-(g.nx - 1), g.nx + 1) * g.dx
    ky = np.arange(-(g.ny - 1), g.ny) * g.dy
    return kx[:, None], ky[None, :]


def dense_operator(g: Grid, cells: tuple[np.ndarray, np.ndarray], constants: CombinedConstants,
                   rows: str, cols: str, rolling: bool) -> np.ndarray:
    """Dense block matrix of displacement differences (shift: u, m/Pa) or relative-slip contributions
    (rolling: (u - u')/dx, 1/Pa) at the element centres ``cells`` = (ix, iy) due to unit tractions on the same
    elements. ``rows`` / ``cols`` are component strings, e.g. "xy" / "xy" for the 2C x 2C tangential block,
    "xy" / "z" for the coupling of pressure into tangential displacement. Blocks ordered component-major."""
    return gather_blocks(g, cells, rows, cols, rolling, lambda i, j: lag_table(i + j, g, constants))


def gather_blocks(g: Grid, cells: tuple[np.ndarray, np.ndarray], rows: str, cols: str, rolling: bool,
                  table) -> np.ndarray:
    """Dense component-major block matrix on the elements ``cells`` = (ix, iy) gathered from lag tables:
    ``table(i, j)`` is the (2 nx, 2 ny - 1) table of component pair (i, j) at lags (k - nx + 1) dx, (l - ny + 1) dy;
    ``rolling`` takes the difference quotient (u(x_I) - u(x_I + dx))/dx (seed 000 eq. 19 with dq = dx)."""
    ix, iy = cells
    dix = ix[:, None] - ix[None, :] + g.nx - 1
    diy = iy[:, None] - iy[None, :] + g.ny - 1
    blocks = []
    for i in rows:
        row = []
        for j in cols:
            t = table(i, j)
            a = t[dix, diy]
            if rolling:
                a = (a - t[dix + 1, diy]) / g.dx
            row.append(a)
        blocks.append(row)
    return np.block(blocks)


@lru_cache(maxsize=8)
def _convolution(component: str, g: Grid, constants: CombinedConstants, extended: bool) -> DCFFT:
    """DC-FFT of A_ij on grid g (extended: one extra downstream column for the rolling difference)."""
    shape = (g.nx + 1, g.ny) if extended else (g.nx, g.ny)
    kernel = partial(influence, component, dx=g.dx, dy=g.dy, constants=constants)
    return DCFFT(lambda tx, ty: kernel(tx, ty), shape, (g.dx, g.dy), workers=1)


def displacement(component: str, traction: np.ndarray, g: Grid, constants: CombinedConstants,
                 rolling: bool = False) -> np.ndarray:
    """sum_J A_ij(x_I - x_J) t_J on the whole grid (m); rolling: the difference (u - u')/dx (-)."""
    if not rolling:
        return _convolution(component, g, constants, False)(traction)
    padded = np.zeros((g.nx + 1, g.ny))
    padded[:-1] = traction
    u = _convolution(component, g, constants, True)(padded)
    return (u[:-1] - u[1:]) / g.dx


# --------------------------------------------------------------------------------------------------------------
# results
# --------------------------------------------------------------------------------------------------------------
@dataclass
class ExactResult:
    """Solution of a rolling or shift contact on grid ``grid``.

    Fields (nx x ny arrays): ``pressure`` pn (Pa), ``px``, ``py`` (Pa), ``contact``, ``adhesion`` (masks),
    ``slip_x``, ``slip_y`` (rolling: slip velocity v = V s in m/s with V = ``rolling_speed``; shift: slip
    displacement s, m), ``power_density`` (rolling: frictional power per unit area -p_t . v, W/m^2).
    Resultants: ``normal_force`` (N), ``creep_force_x``, ``creep_force_y`` (N), ``spin_moment`` Mz =
    sum (x py - y px) dA (N m), ``adhesion_fraction`` (adhesion / contact elements), ``shift`` (m, shift
    problems; (delta_x, delta_y)), ``approach`` (m), solver statistics in ``stats``.
    """

    grid: Grid
    pressure: np.ndarray
    px: np.ndarray
    py: np.ndarray
    contact: np.ndarray
    adhesion: np.ndarray
    slip_x: np.ndarray
    slip_y: np.ndarray
    power_density: np.ndarray | None
    normal_force: float
    creep_force_x: float
    creep_force_y: float
    spin_moment: float
    adhesion_fraction: float
    approach: float
    shift: tuple[float, float] | None = None
    stats: dict = field(default_factory=dict)

    @property
    def frictional_power(self) -> float | None:
        """Total frictional power (W) at rolling speed V (rolling only)."""
        if self.power_density is None:
            return None
        return float(self.power_density.sum() * self.grid.cell_area)


# --------------------------------------------------------------------------------------------------------------
# tangential solver (semi-smooth Newton on the projected Coulomb law)
# --------------------------------------------------------------------------------------------------------------
def solve_tangential(B: np.ndarray, w: np.ndarray, g: np.ndarray, load: np.ndarray | None = None,
                     cell_area: float = 1.0, tol: float = 1e-10, max_iter: int = 200,
                     p0: np.ndarray | None = None, shift0: np.ndarray | None = None,
                     solver: str = "tangential") -> TangentialResult:
    """Coulomb friction on C elements with slip s = w + B p (+ delta for a shift problem).

    ``B`` (2C x 2C) slip per unit traction (block order px of all elements, then py), ``w`` (2, C) slip at zero
    traction (rigid slip, plus the pressure coupling), ``g`` (C,) traction bound mu pn (Pa). ``load`` (2,) given:
    shift problem, the rigid shift delta (2,) is an unknown and the resultants cell_area * sum(p) = load are
    imposed. ``p0`` (2, C) and ``shift0`` (2,) warm-start the tractions and the shift. Raises ConvergenceError when |F| / max g has not dropped below ``tol`` after ``max_iter`` steps.
    """
    C = g.size
    gmax = float(g.max()) if C else 0.0
    if C == 0 or gmax <= 0:
        raise InputError("friction.mu", "no element carries a friction bound (mu pn = 0 everywhere)")
    shift_problem = load is not None
    # per-element regularisation r (Pa per unit slip), one scalar per element: with different r for the two
    # components the fixed point p = Proj(p - r s) would not make p antiparallel to s in slip
    r = np.broadcast_to(1.0 / np.maximum(np.diag(B).reshape(2, C).mean(axis=0), 1e-300), (2, C))
    n = 2 * C + (2 if shift_problem else 0)
    # the rigid shift is carried as x_delta = r_mean * delta (Pa) so that all unknowns share one scale and the
    # Newton matrix stays well conditioned
    r_mean = float(r.mean())

    def slip(x: np.ndarray) -> np.ndarray:
        s = w + (B @ x[:2 * C]).reshape(2, C)
        if shift_problem:
            s = s + x[2 * C:, None] / r_mean
        return s

    def residual_vec(x: np.ndarray) -> tuple[np.ndarray, tuple]:
        return coulomb_residual(x[:2 * C].reshape(2, C), slip(x), r, g, load, cell_area)

    x = np.zeros(n)
    if p0 is not None:
        x[:2 * C] = np.asarray(p0, dtype=float).ravel()
        if shift_problem and shift0 is not None:
            x[2 * C:] = np.asarray(shift0, dtype=float) * r_mean
    # From p = 0 (z = -r w, inside every disc when w = 0) the first Newton step is the full-adhesion solution;
    # later steps move the elements whose adhesion traction exceeds mu pn into slip.
    F, aux = residual_vec(x)
    merit = float(F @ F)
    merits = [merit]
    res = float(np.abs(F).max()) / gmax
    for it in range(1, max_iter + 1):
        if res < tol:
            p = x[:2 * C].reshape(2, C)
            stick, s = aux[2], aux[3]
            return TangentialResult(p.copy(), np.where(stick, 0.0, s), stick,
                                    x[2 * C:] / r_mean if shift_problem else None, it - 1, res)
        z, nz, inside, _ = aux
        # Pi: derivative of the projection, per element 2x2
        pxx, pyy, pxy, _, _ = projection_derivative(z, nz, inside, g)
        # J = I - Pi + Pi r dS/dx  (dS/dp = B, dS/ddelta = I)
        Bx, By = B[:C], B[C:]
        J = np.zeros((n, n))
        J[:C, :2 * C] = (r[0] * pxx)[:, None] * Bx + (r[1] * pxy)[:, None] * By
        J[C:2 * C, :2 * C] = (r[0] * pxy)[:, None] * Bx + (r[1] * pyy)[:, None] * By
        idx = np.arange(C)
        J[idx, idx] += 1.0 - pxx
        J[idx, idx + C] -= pxy
        J[idx + C, idx] -= pxy
        J[idx + C, idx + C] += 1.0 - pyy
        if shift_problem:
            J[idx, 2 * C] = r[0] * pxx / r_mean
            J[idx, 2 * C + 1] = r[1] * pxy / r_mean
            J[idx + C, 2 * C] = r[0] * pxy / r_mean
            J[idx + C, 2 * C + 1] = r[1] * pyy / r_mean
            J[2 * C, :C] = 1.0 / C
            J[2 * C + 1, C:2 * C] = 1.0 / C
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error", sla.LinAlgWarning)
                dx = sla.solve(J, -F, check_finite=False)
        except (sla.LinAlgError, sla.LinAlgWarning):
            # (near-)singular generalised Jacobian, e.g. every element sliding in one direction leaves the
            # shift along it undetermined: take the least-squares (minimum-norm) Newton step instead
            dx = sla.lstsq(J, -F, check_finite=False)[0]
        if not np.all(np.isfinite(dx)):
            raise ConvergenceError(f"{solver} semi-smooth Newton", it, res, tol, "non-finite Newton step")
        x, F, aux, merit = nonmonotone_step(x, dx, residual_vec, merits, first=it == 1)
        merits.append(merit)
        res = float(np.abs(F).max()) / gmax
    raise ConvergenceError(f"{solver} semi-smooth Newton", max_iter, res, tol)


# --------------------------------------------------------------------------------------------------------------
# normal problem
# --------------------------------------------------------------------------------------------------------------
def solve_normal(g: Grid, gap: np.ndarray, constants: CombinedConstants, load: float, tol: float = 1e-10,
                 p0: np.ndarray | None = None, max_iter: int = 2000):
    """Pressure (Pa) for initial gap ``gap`` (m, grid array, may include the coupling term A_zt p_t) under the
    normal ``load`` (N): Polonsky-Keer CG with Love's rectangles and the circulant preconditioner."""
    e_star = constants.contact_modulus
    return polonsky_keer(gap, half_space_operator(g, e_star, 1), load, g.cell_area, p0=p0, tol=tol,
                         max_iter=max_iter, preconditioner=half_space_preconditioner(g, e_star, 1))


# --------------------------------------------------------------------------------------------------------------
# the exact contact solver
# --------------------------------------------------------------------------------------------------------------
def _check_edge(contact: np.ndarray) -> None:
    if contact[0, :].any() or contact[-1, :].any() or contact[:, 0].any() or contact[:, -1].any():
        raise InputError("numerics.exact_domain", "the contact reaches the edge of the potential contact grid; "
                         "enlarge the grid (allowed: half-widths beyond the contact)")


def solve_contact(g: Grid, gap: Gap, constants: CombinedConstants, normal_load: float, mu: float, *,
                  creepages: tuple[float, float, float] | None = None,
                  tangential_load: tuple[float, float] | None = None, rolling_speed: float = 1.0,
                  tol: float = 1e-9, normal_tol: float = 1e-10, max_outer: int = 30,
                  outer_tol: float = 1e-7, tangential_solver: str = "auto") -> ExactResult:
    """Normal + tangential contact of two half-spaces on grid ``g`` (Kalker's exact theory, planar).

    ``gap(x, y)`` undeformed gap (m); ``constants`` combined G, nu, K; ``normal_load`` (N); ``mu`` Coulomb friction
    coefficient. Give exactly one of ``creepages`` = (xi, eta, phi) (steady rolling; xi, eta -, phi 1/m) or
    ``tangential_load`` = (Fx, Fy) (shift; the resultant friction force on body 1, N). Quasi-identical bodies
    (K = 0): one normal and one tangential solve (Johnson's process); otherwise Panagiotopoulos' process until
    the relative change of the tractions drops below ``outer_tol`` (ConvergenceError after ``max_outer``).
    ``tangential_solver``: "dense" (Newton matrix assembled and LU-factorised, :func:`solve_tangential`),
    "fft" (matrix-free Newton-GMRES with DC-FFT products, :mod:`femcheck.cect.tangential_fft`) or "auto" (fft
    above ``AUTO_FFT_ELEMENTS`` contact elements). Both solve the same discrete equations.
    """
    if (creepages is None) == (tangential_load is None):
        raise ValueError("give exactly one of creepages (steady rolling) or tangential_load (shift)")
    if normal_load <= 0:
        raise InputError("load.normal", f"{normal_load:g} N; allowed: > 0")
    if not mu > 0:
        raise InputError("friction.mu", f"{mu:g}; allowed: > 0")
    if tangential_solver not in TANGENTIAL_SOLVERS:
        raise InputError("numerics.exact_solver", f"{tangential_solver!r}; allowed: {', '.join(TANGENTIAL_SOLVERS)}")
    t0 = time.perf_counter()
    rolling = creepages is not None
    X, Y = g.mesh()
    h = gap(X, Y)
    coupled = constants.coupling != 0.0
    px = np.zeros((g.nx, g.ny))
    py = np.zeros((g.nx, g.ny))
    pn_ref = None
    history = []
    normal = None
    tang = None
    prev_cells = None
    for outer in range(1, (max_outer if coupled else 1) + 1):
        extra = 0.0
        if coupled and (px.any() or py.any()):
            extra = displacement("zx", px, g, constants) + displacement("zy", py, g, constants)
        normal = solve_normal(g, h + extra, constants, normal_load, tol=normal_tol,
                              p0=None if normal is None else normal.pressure)
        pn = normal.pressure
        if pn_ref is None:
            pn_ref = pn.copy()              # shift: the frictionless normal state is the reference
        contact = pn > 0
        _check_edge(contact)
        cells = np.nonzero(contact)
        C = cells[0].size
        use_fft = tangential_solver == "fft" or (tangential_solver == "auto" and C > AUTO_FFT_ELEMENTS)
        xc, yc = X[cells], Y[cells]
        if rolling:
            xi, eta, phi = creepages
            w = np.stack([xi - phi * yc, eta + phi * xc])
            if coupled:
                w = w + np.stack([displacement("xz", pn, g, constants, rolling=True)[cells],
                                  displacement("yz", pn, g, constants, rolling=True)[cells]])
            load = None
        else:
            w = np.zeros((2, C))
            if coupled:
                dp = pn - pn_ref
                w = np.stack([displacement("xz", dp, g, constants)[cells], displacement("yz", dp, g, constants)[cells]])
            load = np.asarray(tangential_load, dtype=float)
            if np.hypot(*load) > mu * normal_load * (1.0 - 1e-12):
                raise InputError("load.tangential", f"|Q| = {np.hypot(*load):g} N exceeds the friction limit "
                                 f"mu P = {mu * normal_load:g} N (gross sliding); allowed: < mu P")
        p0 = shift0 = None
        if tang is not None and tang.p.shape[1] == C and _same_cells(prev_cells, cells):
            p0, shift0 = tang.p, tang.shift
        name = "steady rolling" if rolling else "shift"
        if use_fft:
            tang = solve_tangential_fft(g, cells, constants, w, mu * pn[cells], rolling, load=load, tol=tol,
                                        p0=p0, shift0=shift0, solver=name)
        else:
            B = dense_operator(g, cells, constants, "xy", "xy", rolling)
            tang = solve_tangential(B, w, mu * pn[cells], load=load, cell_area=g.cell_area, tol=tol, p0=p0,
                                    shift0=shift0, solver=name)
        new_px, new_py = np.zeros_like(px), np.zeros_like(py)
        new_px[cells], new_py[cells] = tang.p[0], tang.p[1]
        scale = max(float(np.abs(pn).max()), 1e-300)
        change = float(max(np.abs(new_px - px).max(), np.abs(new_py - py).max())) / scale
        px, py = new_px, new_py
        prev_cells = cells
        history.append({"outer": outer, "normal_iterations": normal.iterations, "newton_iterations": tang.iterations,
                        "gmres_iterations": tang.linear_iterations,
                        "traction_change": change, "contact_elements": int(C)})
        if not coupled or (outer > 1 and change < outer_tol):
            break
    else:
        raise ConvergenceError("Panagiotopoulos process", max_outer, history[-1]["traction_change"], outer_tol,
                               "normal and tangential tractions keep changing")
    stick = np.zeros_like(contact)
    stick[cells] = tang.stick
    sx, sy = np.zeros_like(px), np.zeros_like(py)
    sx[cells], sy[cells] = tang.slip[0], tang.slip[1]
    area = g.cell_area
    power = None
    if rolling:
        sx, sy = sx * rolling_speed, sy * rolling_speed          # slip velocity v = V s (m/s)
        power = -(px * sx + py * sy)                            # W/m^2, >= 0 by Coulomb's law
    fx, fy = float(px.sum() * area), float(py.sum() * area)
    mz = float((X * py - Y * px).sum() * area)
    stats = {"grid": [g.nx, g.ny], "dx": g.dx, "dy": g.dy, "contact_elements": int(contact.sum()),
             "process": "Panagiotopoulos" if coupled else "Johnson", "outer_iterations": len(history),
             "newton_iterations": int(sum(h_["newton_iterations"] for h_ in history)),
             "tangential_solver": "fft" if use_fft else "dense",
             "gmres_iterations": int(sum(h_["gmres_iterations"] for h_ in history)),
             "normal_iterations": int(sum(h_["normal_iterations"] for h_ in history)),
             "normal_residual": float(normal.residual), "tangential_residual": float(tang.residual),
             "history": history, "time_s": time.perf_counter() - t0}
    return ExactResult(g, pn, px, py, contact, stick, sx, sy, power, float(normal.load), fx, fy, mz,
                       float(tang.stick.sum() / max(tang.stick.size, 1)), float(normal.approach),
                       None if rolling else (float(tang.shift[0]), float(tang.shift[1])), stats)


def _same_cells(a, b) -> bool:
    return a is not None and a[0].size == b[0].size and bool(np.all(a[0] == b[0]) and np.all(a[1] == b[1]))
