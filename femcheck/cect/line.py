"""Kalker's exact theory in 2D (plane strain): frictional line contact on a uniform strip grid.

Frame and signs as in :mod:`femcheck.analytic.carter`: body 1 = upper body (cylinder), body 2 = lower body
(block); ``traction`` q (Pa) acts on body 1 and is exerted by body 2; u = u_x1 - u_x2 is the tangential
surface-displacement difference (m). Rolling is in +x (material flows through the contact in -x).

Influence coefficients (uniform strips of width dx, piecewise-constant traction):
  * tangential: u(x) = -(2/(pi E*)) int q(s) ln|x - s| ds + const (Johnson 1985 eq. 2.19b per body, the two
    bodies' compliances adding because each carries the opposite traction), integrated exactly over a strip
    by :func:`femcheck.bem.influence.half_plane_strip` (the same log kernel as the normal displacement);
  * normal-tangential coupling (dissimilar bodies): a pressure p(s) shifts the surfaces tangentially by
        u(x) = -(kappa/2) int p(s) sgn(x - s) ds,     i.e. d u/dx = -kappa p(x),
    and a tangential traction q(s) on body 1 opens the gap by
        u_n(x) = +(kappa/2) int q(s) sgn(x - s) ds,
    kappa = (1 - 2 nu1)/(2 G1) - (1 - 2 nu2)/(2 G2) (1/Pa). Per body this is Johnson 1985 eq. 2.25a (surface
    points move towards a normal load: for x > 0, u_x = -(1 - 2 nu) P/(4 G)); the second kernel follows from the
    first by Betti's reciprocity (the pair's compliance is symmetric: q works on u, p on the gap opening u_n).
    It is the plane-strain form of the 3D coefficients A_xz = -A_zx of :mod:`femcheck.cect.influence`
    (kappa = 2K/G with Kalker's difference parameter K), and kappa E* = 2 beta with Dundurs' beta (Johnson
    1985 p. 110, bodies in the same order; beta < 0 when body 1 is the stiffer one). kappa = 0 for
    quasi-identical bodies. On the strips both kernels are exact for uniform strips:
    u_i = -(kappa/2) dx sum_j sgn(i - j) p_j (no self term).

Coupled processes (Kalker 1990 §5.2; Vollebregt's CONTACT user guide §5.3 on the Bentall-Johnson rollers):
  * **Johnson's process** (``process="johnson"``): the normal problem is solved once without friction and its
    pressure is kept; the tangential problem includes the pressure-induced tangential displacement; the
    effect of the tangential traction on the pressure (second order in kappa mu) is neglected.
  * **Panagiotopoulos' process** (``process="panagiotopoulos"``, the default for kappa != 0): normal and
    tangential problems alternate, the normal one with the gap opened by u_n(q), the tangential one with the
    new pressure, until the tractions stop changing (ConvergenceError otherwise).
In steady rolling the pressure-induced displacement is carried through the contact and enters the slip through
its x-gradient, kappa p. In the shift problem the normal load is applied first without friction (no locked-in
tractions of Spence's type), then Q': the slip increment contains u(p - p_ref), p_ref the frictionless
pressure under the normal load alone (nothing under Johnson's process, where p = p_ref). The 2D shift is
reported as delta(Q') - delta_stick(Q') (the rigid shift alone depends on the datum of the log kernel), with
delta_stick the fully adhered state on p_ref without coupling: any state carrying the same Q' removes the
datum, and the coupled full-stick state has the oscillating edge singularity of dissimilar adhesion (Bufler)
and no usable discrete fixed point. For quasi-identical bodies this is Cattaneo's micro-slip part.

Steady rolling (seed 000 eqs 16-17 and 20): v = w + V du/dx_Lagrangian; discretised in time with
Delta q = V Delta t = dx, the particle now at cell i was at cell i+1 one step earlier (upstream), so
    s_i / V = xi + (u_i - u_{i+1}) / dx    (seed 000 eq 20: (u - u')_t = [IC](p(x) - p(x + dx)))
plus the coupling term kappa (p_i + p_{i+1})/2. Coulomb: |q_i| <= mu p_i; s_i = 0 (adhesion) or
q_i = -mu p_i s_i/|s_i| (slip).
Shift (Cattaneo, load control): body 1 is displaced rigidly by delta (m) relative to body 2; the slip
displacement is S_i = delta + u_i, the same Coulomb law holds and dx sum(q) = -Q' (Q' is the tangential force
applied to body 1; the contact traction on body 1 balances it).

Solver: a primal active-set method (Kalker's KOMBI-type "contact/slip area" iteration): for a guessed
adhesion set and slip directions the linear equations s_A = 0 (plus the force constraint in the shift problem)
are solved directly (dense LU on the adhesion cells); cells whose traction exceeds the traction bound move to
slip, slip cells whose slip opposes their traction direction move to adhesion; repeat until the sets no longer
change, then check the residual. Non-convergence raises :class:`femcheck.errors.ConvergenceError`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from scipy import linalg

from ..bem.influence import half_plane_strip
from ..bem.line import solve_line_contact
from ..bem.polonsky_keer import NormalContactResult
from ..errors import ConvergenceError
from ..materials import Elastic
from ..qoi import contact_edge

#: A traction counts as exceeding the bound only beyond this relative margin (round-off of the direct solve).
BOUND_SLACK = 1e-10


def coupling_constant(body1: Elastic, body2: Elastic) -> float:
    """kappa = (1 - 2 nu1)/(2 G1) - (1 - 2 nu2)/(2 G2) (1/Pa): d u/dx = -kappa p for u = u_x1 - u_x2 under a
    pressure p (Johnson 1985 eq. 2.25a for each body). A rigid body contributes 0. Zero for quasi-identical
    bodies; equal to 2K/G with Kalker's difference parameter K = (G/4)[(1-2nu1)/G1 - (1-2nu2)/G2]."""
    def part(b: Elastic) -> float:
        return 0.0 if b.rigid else (1.0 - 2.0 * b.nu) / (2.0 * b.shear_modulus)
    return part(body1) - part(body2)


def sign_sum(v: np.ndarray) -> np.ndarray:
    """sum_{j < i} v_j - sum_{j > i} v_j for every i: the strip form of int v(s) sgn(x - s) ds / dx."""
    c = np.cumsum(v)
    return 2.0 * c - v - c[-1]


def coupling_displacement(pressure: np.ndarray, dx: float, kappa: float) -> np.ndarray:
    """Tangential displacement difference u_i = -(kappa/2) dx sum_j sgn(i - j) p_j (m) caused by the pressure
    ``pressure`` (Pa) on strips of width ``dx`` (m): the module doc's coupling kernel."""
    return -0.5 * kappa * dx * sign_sum(np.asarray(pressure, float))


def coupling_opening(traction: np.ndarray, dx: float, kappa: float) -> np.ndarray:
    """Gap opening u_n,i = +(kappa/2) dx sum_j sgn(i - j) q_j (m) caused by the tangential traction ``traction``
    (Pa, on body 1): Betti's reciprocal of :func:`coupling_displacement`."""
    return 0.5 * kappa * dx * sign_sum(np.asarray(traction, float))


def tangential_influence(n: int, dx: float, modulus: float, datum: float) -> np.ndarray:
    """Influence coefficients C[k] = u at lag k dx (k = -(n-1) .. n, as an array indexed k + n - 1) per unit
    uniform traction (1 Pa) on a strip of width dx (m): the half-plane log kernel with contact modulus E* (Pa)
    and a datum length (m) fixing the additive constant (it cancels in every slip)."""
    lags = np.arange(-(n - 1), n + 1) * dx
    return half_plane_strip(lags, dx, modulus, datum)


def _toeplitz(kernel: np.ndarray, rows: np.ndarray, cols: np.ndarray, n: int, shift: int = 0) -> np.ndarray:
    """Dense block K[i, j] = kernel[(i + shift) - j + n - 1] for i in rows, j in cols (a gather, no loop)."""
    return kernel[(rows[:, None] + shift) - cols[None, :] + n - 1]


@dataclass
class LineTangentialResult:
    """Solution of a 2D tangential contact problem, in the spirit of ``scipy.optimize.OptimizeResult``.

    Fields on the grid (cell centres ``x``, width ``dx``, m): ``pressure`` p (Pa), ``traction`` q on body 1
    (Pa), ``contact`` and ``adhesion`` masks, ``slip`` (rolling: slip velocity / V, -; shift: slip
    displacement, m), ``slip_velocity`` (m/s, rolling, for rolling speed ``speed``), ``power_density``
    -q v (W/m^2, rolling). Scalars: ``tangential_force`` dx sum(q) (N/m, on body 1), ``adhesion_length``
    (m), ``rigid_shift`` delta (m, shift problem; depends on ``datum``), ``shift`` = delta - delta_stick (m,
    the micro-slip part), ``iterations`` (active-set iterations, summed over the sub-solves), ``residual``
    (relative, see :func:`_active_set`), ``converged``, ``time_s``.
    """

    problem: str
    x: np.ndarray
    dx: float
    pressure: np.ndarray
    traction: np.ndarray
    contact: np.ndarray
    adhesion: np.ndarray
    slip: np.ndarray
    tangential_force: float
    adhesion_length: float
    iterations: int
    residual: float
    converged: bool
    time_s: float
    speed: float | None = None
    rigid_shift: float | None = None
    shift: float | None = None
    datum: float | None = None
    history: list = field(default_factory=list)

    @property
    def slip_velocity(self) -> np.ndarray | None:
        return None if self.problem != "rolling" else self.speed * self.slip

    @property
    def power_density(self) -> np.ndarray | None:
        """Frictional power density -q . v (W/m^2); >= 0 by Coulomb's law."""
        return None if self.problem != "rolling" else -self.traction * self.slip_velocity


@dataclass
class _ActiveSetOutcome:
    q: np.ndarray
    s: np.ndarray
    stick: np.ndarray
    lam: float
    iterations: int
    residual: float
    history: list


def _active_set(A: np.ndarray, b: np.ndarray, g: np.ndarray, s_scale: float, tol: float, max_iter: int,
                force: float | None = None, weight: float = 1.0, solver: str = "active set",
                stick0: np.ndarray | None = None) -> _ActiveSetOutcome:
    """Coulomb complementarity on n cells: s = A q + b (+ lam when ``force`` is given, lam a free unknown
    with the constraint weight * sum(q) = force); |q| <= g; s = 0 where |q| < g; q = -g sgn(s) where s != 0.

    Residual (relative): max of |s| on adhesion cells / s_scale, the bound excess (|q| - g)+ / max g on
    adhesion cells, and the wrong-way slip (s sgn(-q))- / s_scale on slip cells; it must fall below ``tol``
    once the sets are stable. ``stick0`` is the initial adhesion set (default: all cells).
    """
    n = b.size
    stick = np.ones(n, bool) if stick0 is None else stick0.copy()
    direction = np.zeros(n)          # sgn of slip on slip cells (q = -g * direction)
    gmax = float(g.max())
    history: list[tuple[int, int]] = []
    seen: set[bytes] = set()
    # Solve in units of the self-compliance so that the bordered system (compliance block next to the unit
    # column of the rigid shift and the unit row of the force constraint) is well scaled.
    c0 = float(np.abs(np.diag(A)).max()) or 1.0
    for it in range(1, max_iter + 1):
        q = np.zeros(n)
        q[~stick] = -g[~stick] * direction[~stick]
        S = np.flatnonzero(stick)
        L = np.flatnonzero(~stick)
        lam = 0.0
        rhs = (-b[S] - A[np.ix_(S, L)] @ q[L]) / c0
        if force is None:
            if S.size:
                q[S] = linalg.solve(A[np.ix_(S, S)] / c0, rhs, check_finite=False)
        else:
            # bordered system [A_SS/c0 1; 1^T 0] [q_S; lam/c0] = [rhs/c0; F/w - sum(q_L)]
            m = S.size
            if m == 0:
                raise ConvergenceError(solver, it, np.inf, tol, "no adhesion cell left: the load exceeds mu W'")
            M = np.zeros((m + 1, m + 1))
            M[:m, :m] = A[np.ix_(S, S)] / c0
            M[:m, m] = 1.0
            M[m, :m] = 1.0
            r = np.append(rhs, force / weight - q[L].sum())
            sol = linalg.solve(M, r, check_finite=False)
            q[S], lam = sol[:m], float(sol[m]) * c0
        s = A @ q + b + lam
        over = stick & (np.abs(q) > g * (1.0 + BOUND_SLACK))
        wrong = ~stick & (s * direction < 0.0)
        history.append((int(stick.sum()), int(over.sum() + wrong.sum())))
        if not over.any() and not wrong.any():
            s_true = A @ q + b + lam
            res = max(float(np.abs(s_true[stick]).max(initial=0.0)) / s_scale,
                      float(np.clip(np.abs(q[stick]) - g[stick], 0.0, None).max(initial=0.0)) / gmax,
                      float(np.clip(-s_true[~stick] * direction[~stick], 0.0, None).max(initial=0.0)) / s_scale)
            if res > tol:
                raise ConvergenceError(solver, it, res, tol, "active sets stable but equations not met")
            s_true[stick] = 0.0
            return _ActiveSetOutcome(q, s_true, stick, lam, it, res, history)
        # Kalker's area update: over-loaded adhesion cells slip against their traction, wrong-way slip cells
        # stick. Both changes at once; a revisited state means cycling, then only the largest violation moves.
        key = stick.tobytes() + np.sign(direction).astype(np.int8).tobytes()
        seen.add(key)
        new_stick, new_dir = stick.copy(), direction.copy()
        new_stick[over] = False
        new_dir[over] = -np.sign(q[over])
        new_stick[wrong] = True
        new_dir[wrong] = 0.0
        if (new_stick.tobytes() + np.sign(new_dir).astype(np.int8).tobytes()) in seen:
            viol = np.where(over, (np.abs(q) - g) / gmax, 0.0) + np.where(wrong, np.abs(s) / s_scale, 0.0)
            k = int(np.argmax(viol))
            new_stick, new_dir = stick.copy(), direction.copy()
            if over[k]:
                new_stick[k], new_dir[k] = False, -np.sign(q[k])
            else:
                new_stick[k], new_dir[k] = True, 0.0
        stick, direction = new_stick, new_dir
    raise ConvergenceError(solver, max_iter, np.inf, tol, "adhesion/slip areas did not settle")


def _contact_cells(pressure: np.ndarray) -> np.ndarray:
    idx = np.flatnonzero(pressure > 0)
    if idx.size == 0:
        raise ValueError("no cell in contact: the tangential problem needs a positive pressure")
    return idx


def solve_rolling(x: np.ndarray, dx: float, pressure: np.ndarray, modulus: float, mu: float, xi: float,
                  kappa: float = 0.0, speed: float = 1.0, tol: float = 1e-8,
                  max_iter: int = 200) -> LineTangentialResult:
    """Steady rolling with longitudinal creepage ``xi`` (-) on the strip grid ``x`` (cell centres, m, uniform
    width ``dx``) with given ``pressure`` (Pa), contact modulus E* (Pa), friction ``mu`` and coupling
    ``kappa`` (1/Pa, :func:`coupling_constant`). See the module doc for the discretisation (seed 000 eq 20).

    The grid must extend at least one cell beyond the leading edge of the contact (the backward difference
    in time reads the upstream cell). ``speed`` V (m/s) only scales the reported slip velocities and power.
    """
    t0 = time.perf_counter()
    x, pressure = np.asarray(x, float), np.asarray(pressure, float)
    n = x.size
    J = _contact_cells(pressure)
    if J[-1] >= n - 1:
        raise ValueError("the contact reaches the leading edge of the grid; enlarge the grid")
    datum = 8.0 * n * dx
    C = tangential_influence(n, dx, modulus, datum)
    # A[i, j] = (C(i - j) - C(i + 1 - j)) / dx: slip per unit traction (1/Pa), a datum-free difference.
    A = (_toeplitz(C, J, J, n) - _toeplitz(C, J, J, n, shift=1)) / dx
    # coupling: (u_i - u_{i+1})/dx of the pressure-induced displacement = kappa (p_i + p_{i+1})/2
    uc = coupling_displacement(pressure, dx, kappa)
    b = xi + (uc[J] - uc[J + 1]) / dx
    g = mu * pressure[J]
    p0 = float(pressure.max())
    s_scale = max(abs(xi), 2.0 * mu * p0 / modulus)       # creepage at saturation sets the slip scale
    out = _active_set(A, b, g, s_scale, tol, max_iter, solver="CECT-2D rolling (active set)")
    q = np.zeros(n)
    q[J] = out.q
    s = np.zeros(n)
    s[J] = out.s
    adhesion = np.zeros(n, bool)
    adhesion[J] = out.stick
    contact = pressure > 0
    return LineTangentialResult("rolling", x, dx, pressure, q, contact, adhesion, s, float(dx * q.sum()),
                                float(dx * adhesion.sum()), out.iterations, out.residual, True,
                                time.perf_counter() - t0, speed=speed, history=out.history)


@dataclass
class ShiftState:
    """One equilibrium state of the shift problem on the strips: traction ``traction`` on body 1 (Pa), slip
    displacement ``slip`` (m), ``adhesion`` mask, rigid shift ``delta`` (m; with the sign of the slip S =
    delta + u, it depends on the datum of the log kernel), active-set ``iterations``, ``residual``, ``history``."""

    traction: np.ndarray
    slip: np.ndarray
    adhesion: np.ndarray
    delta: float
    iterations: int
    residual: float
    history: list


def shift_state(x: np.ndarray, dx: float, pressure: np.ndarray, modulus: float, mu: float,
                tangential_per_length: float, coupling_slip: np.ndarray | None = None, tol: float = 1e-8,
                max_iter: int = 200) -> ShiftState:
    """Cattaneo shift under load control on a given ``pressure`` (Pa): the tangential force Q' (N/m) is applied
    to body 1; unknowns the traction and the rigid shift delta (m). ``mu = np.inf``: full adhesion.
    ``coupling_slip`` (m, grid array): the pressure-induced part of the slip increment, u(p - p_ref) (module
    doc). Raises ValueError when |Q'| >= mu W' (gross sliding: no static solution)."""
    x, pressure = np.asarray(x, float), np.asarray(pressure, float)
    n = x.size
    J = _contact_cells(pressure)
    load = float(dx * pressure.sum())
    if abs(tangential_per_length) >= mu * load:
        raise ValueError(f"|Q'| = {abs(tangential_per_length):g} N/m >= mu W' = {mu * load:g} N/m: gross sliding")
    C = tangential_influence(n, dx, modulus, 8.0 * n * dx)
    A = _toeplitz(C, J, J, n)                     # S = delta + C q: slip displacement per unit traction (m/Pa)
    b = np.zeros(J.size) if coupling_slip is None else np.asarray(coupling_slip, float)[J]
    F = -tangential_per_length / dx               # sum(q) on body 1 balances the applied force
    d_scale = mu * float(pressure.max()) * 0.5 * dx * J.size / modulus if np.isfinite(mu) else \
        abs(tangential_per_length) / modulus      # micro-slip shift scale (m)
    adhered = not np.isfinite(mu)
    out = _active_set(A, b, np.full(J.size, np.inf) if adhered else mu * pressure[J], d_scale or 1.0, tol,
                      2 if adhered else max_iter, force=F,
                      solver="CECT-2D full-stick shift" if adhered else "CECT-2D shift (active set)")
    q, sl, stick = np.zeros(n), np.zeros(n), np.zeros(n, bool)
    q[J], sl[J], stick[J] = out.q, out.s, out.stick
    return ShiftState(q, sl, stick, float(out.lam), out.iterations, out.residual, out.history)


def solve_shift(x: np.ndarray, dx: float, pressure: np.ndarray, modulus: float, mu: float,
                tangential_per_length: float, tol: float = 1e-8, max_iter: int = 200) -> LineTangentialResult:
    """Cattaneo shift without normal-tangential coupling (quasi-identical bodies, or Johnson's process): the
    partial-slip state (friction ``mu``) and the adhered state (no traction bound) on the same ``pressure``, so
    that ``shift`` = delta - delta_stick is the datum-free micro-slip part (femcheck's 2D shift)."""
    t0 = time.perf_counter()
    out = shift_state(x, dx, pressure, modulus, mu, tangential_per_length, tol=tol, max_iter=max_iter)
    stuck = shift_state(x, dx, pressure, modulus, np.inf, tangential_per_length, tol=tol)
    return _shift_result(x, dx, pressure, out, stuck, time.perf_counter() - t0)


def _shift_result(x, dx, pressure, out: ShiftState, stuck: ShiftState, time_s: float) -> LineTangentialResult:
    return LineTangentialResult("shift", np.asarray(x, float), dx, pressure, out.traction, pressure > 0,
                                out.adhesion, out.slip, float(dx * out.traction.sum()),
                                float(dx * out.adhesion.sum()), out.iterations + stuck.iterations,
                                max(out.residual, stuck.residual), True, time_s, rigid_shift=out.delta,
                                shift=out.delta - stuck.delta, datum=8.0 * np.asarray(x).size * dx,
                                history=out.history)


def adhesion_zone(x: np.ndarray, pressure: np.ndarray, traction: np.ndarray, adhesion: np.ndarray,
                  mu: float) -> tuple[float, float]:
    """Ends (m) of the adhesion zone to sub-cell accuracy: where the traction reserve r = mu p - |q| (Pa, on
    adhesion cells; 0 elsewhere) falls to zero, located like a contact edge (:func:`femcheck.qoi.contact_edge`,
    a fit of r^2 near the last positive cell). In Carter's and Cattaneo's solutions r is an elliptical profile
    over the adhesion zone, mu p0 (c/a) sqrt(1 - (x - d)^2/c^2), whose square is exactly quadratic; counting
    adhesion cells instead would be accurate to one cell only and would not converge smoothly under refinement.
    Returns (0, 0) without adhesion; the largest adhesion zone when there are several."""
    r = np.where(adhesion & (pressure > 0), mu * pressure - np.abs(traction), 0.0) if np.isfinite(mu) else \
        np.where(adhesion, pressure, 0.0)
    idx = np.flatnonzero(r > 0)
    if idx.size == 0:
        return 0.0, 0.0
    runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
    run = max(runs, key=len)
    zone = np.zeros_like(r)
    lo, hi = max(run[0] - 1, 0), min(run[-1] + 2, r.size)
    zone[lo:hi] = r[lo:hi]
    right = contact_edge(x, zone)
    left = -contact_edge(-x[::-1], zone[::-1])
    return float(left), float(right)


PROCESSES = ("auto", "johnson", "panagiotopoulos")


@dataclass
class LineFrictionSolution:
    """Normal + tangential solution on one grid. ``process``: "none" (kappa = 0), "Johnson" or
    "Panagiotopoulos"; ``outer_iterations``: normal/tangential alternations (1 unless Panagiotopoulos)."""

    normal: NormalContactResult
    tangential: LineTangentialResult
    process: str = "none"
    outer_iterations: int = 1

    @property
    def x(self) -> np.ndarray:
        return self.tangential.x


def solve_line_friction(gap: Callable[[np.ndarray], np.ndarray], modulus: float, load_per_length: float,
                        half_domain: float, n_elements: int, mu: float, xi: float | None = None,
                        tangential_per_length: float | None = None, kappa: float = 0.0, speed: float = 1.0,
                        tol: float = 1e-8, normal_tol: float = 1e-10, max_iter: int = 200,
                        process: str = "auto", outer_tol: float = 1e-8, max_outer: int = 50) -> LineFrictionSolution:
    """Normal problem (half-plane BEM, :func:`femcheck.bem.line.solve_line_contact`) then the tangential
    problem on the same strips: steady rolling when ``xi`` is given, shift when ``tangential_per_length`` is
    given (exactly one). ``gap(x)`` initial gap (m), E* (Pa), W' (N/m), grid [-half_domain, half_domain] (m).

    Dissimilar bodies (``kappa`` != 0, 1/Pa): ``process`` "johnson" or "panagiotopoulos" ("auto": the latter),
    see the module doc; the alternation stops when the largest traction change falls below ``outer_tol`` of
    the peak pressure (ConvergenceError after ``max_outer`` alternations).
    """
    if (xi is None) == (tangential_per_length is None):
        raise ValueError("give exactly one of xi (steady rolling) or tangential_per_length (shift)")
    if process not in PROCESSES:
        raise ValueError(f"process must be one of {PROCESSES}, got {process!r}")

    def normal(extra: np.ndarray | float = 0.0) -> tuple[np.ndarray, float, NormalContactResult]:
        sol = solve_line_contact(lambda x: gap(x) + extra, modulus, load_per_length, half_domain, n_elements,
                                 tol=normal_tol)
        r = sol.result
        if r.contact[0] or r.contact[-1]:
            raise ConvergenceError("CECT-2D normal problem", r.iterations, r.residual, normal_tol,
                                   "contact reaches the edge of the grid; enlarge the domain")
        return sol.x, sol.dx, r

    x, dx, r = normal()
    coupled = kappa != 0.0
    name = "none" if not coupled else ("Johnson" if process == "johnson" else "Panagiotopoulos")
    alternate = name == "Panagiotopoulos"
    if xi is not None:
        def tangential(p):
            return solve_rolling(x, dx, p, modulus, mu, xi, kappa, speed, tol, max_iter)
        t, r, outer = _alternate(tangential, lambda t_: t_.traction, normal, r, dx, kappa, alternate,
                                 outer_tol, max_outer)
        return LineFrictionSolution(r, t, name, outer)
    t0 = time.perf_counter()
    p_ref = r.pressure
    states, normals, outers = [], [], 0
    # the partial-slip state (coupled), then the adhered reference state on the frictionless pressure p_ref
    for bound in (mu, np.inf):
        def tangential(p, bound=bound):
            return shift_state(x, dx, p, modulus, bound, tangential_per_length,
                               coupling_displacement(p - p_ref, dx, kappa) if coupled else None, tol, max_iter)
        st, rn, outer = _alternate(tangential, lambda s_: s_.traction, normal, r, dx, kappa,
                                   alternate and np.isfinite(bound), outer_tol, max_outer)
        states.append(st)
        normals.append(rn)
        outers += outer
    t = _shift_result(x, dx, normals[0].pressure, states[0], states[1], time.perf_counter() - t0)
    return LineFrictionSolution(normals[0], t, name, outers)


def _alternate(tangential: Callable, traction_of: Callable, normal: Callable, r: NormalContactResult, dx: float,
               kappa: float, alternate: bool, outer_tol: float, max_outer: int, memory: int = 5):
    """Panagiotopoulos' process: tangential solve on the current pressure, normal solve with the gap opened by
    the traction, until the fixed-point residual |q(p(q)) - q| falls below ``outer_tol`` of the peak pressure.
    Without ``alternate``: one tangential solve (Johnson's process, or no coupling).

    The plain alternation contracts by about 10x per step at mu = 0.3 (measured, rigid cylinder on steel). With
    large kappa mu (mu = 10 on aluminium/steel) it oscillates with a growing amplitude: once the residual stops
    falling, the fixed point q = T(N(q)) is accelerated by Anderson mixing over the last ``memory`` iterates
    (Walker & Ni, SIAM J. Numer. Anal. 49, 2011), restarted from a half step whenever the residual grows (a
    change of the active sets makes the map non-smooth; Anderson from the start diverged on such cases)."""
    t = tangential(r.pressure)
    if not alternate:
        return t, r, 1
    q = traction_of(t)
    dq_hist: list[np.ndarray] = []
    dg_hist: list[np.ndarray] = []
    q_prev = g_prev = None
    change = previous = np.inf
    anderson = False
    for outer in range(2, max_outer + 1):
        r = normal(coupling_opening(q, dx, kappa))[2]
        t = tangential(r.pressure)
        g = traction_of(t) - q                       # fixed-point residual
        change = float(np.abs(g).max()) / float(r.pressure.max())
        if change < outer_tol:
            return t, r, outer
        if not anderson:
            anderson = change >= previous
            previous = change
            q = q + (0.5 if anderson else 1.0) * g
            continue
        if change > previous:                        # safeguard: restart from a damped plain step
            dq_hist.clear()
            dg_hist.clear()
            q_prev = g_prev = None
            previous = change
            q = q + 0.5 * g
            continue
        if q_prev is not None:
            dq_hist.append(q - q_prev)
            dg_hist.append(g - g_prev)
            del dq_hist[:-memory], dg_hist[:-memory]
        q_prev, g_prev, previous = q, g, change
        if dg_hist:
            dG = np.stack(dg_hist, axis=1)
            gamma = np.linalg.lstsq(dG, g, rcond=1e-10)[0]
            q = q + g - (np.stack(dq_hist, axis=1) + dG) @ gamma
        else:
            q = q + g
    raise ConvergenceError("CECT-2D Panagiotopoulos process", max_outer, change, outer_tol,
                           "normal and tangential tractions keep changing")
