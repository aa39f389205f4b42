"""One state of the roller between the two raceways of seed 000's spherical roller bearing: both conformal
contacts solved by CECT (:mod:`femcheck.cect.conformal`) at a given pose and speeds, and the residual of the six
equilibrium equations (seed 000 §3.2, Fig. 5; spec srb-rolling §3).

State vector (SI) x = (d_Y, d_Z, beta, gamma, omega_m, omega_R): roller-centre offsets along Y and Z of the
bearing frame (m), tilt beta and skew gamma (rad), cage speed omega_m and roller spin omega_R (rad/s)
(:mod:`femcheck.geometry.srb_bearing` for the frames). The inner ring is displaced by the prescribed approach
``delta`` along e_z (spec §2.2, ``approach_direction = "normal"``; E11) or along Z ("radial").

Residual (on the roller, components in the reference roller frame {e_x, e_y, e_z}):

    R = [F_I + F_E + F_c + F_add ;  M_I + M_E + M_g + M_add]     (N; N m, moments about the roller centre C)

F_j, M_j the resultants of the CECT tractions of contact j (:func:`femcheck.cect.conformal.resultants`), F_c the
centrifugal force and M_g the gyroscopic moment (:func:`femcheck.geometry.srb_bearing.centrifugal_force`,
``gyroscopic_moment``). Scaled residual: forces / tol_F, moments / tol_M with tol_F = ``tol_scale`` mu N
(default 1e-5 mu N) and tol_M = tol_F D/2 (spec §3): converged when every scaled component is below 1.

Grids (spec §2.3): per contact nx x ns elements over x in +-domain_x a_H and s in s_c +- domain_s b_H, with the
Hertz semi-axes a_H, b_H of the target load N; the cell sizes are fixed for a whole solve and the centre s_c is
snapped to the lattice of ds, so that re-centring the grid on the pressure centre between Newton iterations moves
the window without changing the discretisation (the residual is then the same function of the state before and
after re-centring, as long as the contact stays inside the window).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..analytic.hertz import elliptic_contact
from ..errors import InputError
from ..geometry import srb_bearing as sb
from .conformal import ConformalResult, GridTooSmall, resultants, solve_conformal
from .influence import CombinedConstants

N_UNKNOWNS = 6
UNKNOWNS = ("d_Y", "d_Z", "tilt", "skew", "omega_m", "omega_R")
RESIDUALS = ("F_x", "F_y", "F_z", "M_x", "M_y", "M_z")


@dataclass(frozen=True)
class RollerProblem:
    """The physical data of one roller equilibrium: ``bearing`` geometry, combined elastic ``constants``,
    friction ``mu``, ring speeds ``omega_inner``, ``omega_outer`` (rad/s, about +Y), target inner normal load
    ``load`` N (N), ``approach_direction`` "normal" (e_z) or "radial" (Z), additional force / moment on the
    roller ``force_add`` (N), ``moment_add`` (N m) in B (cage, churning: 0 in the paper). ``offsets``: optional
    (contact, ContactInput) -> (gap (nx, ns) in m, slip (2, nx, ns) in m/s) added to the exact gap and the
    rigid slip of every contact solve: displacements the half-space coefficients do not carry (the finite
    bodies' correction, :mod:`femcheck.fem.srb_finite_body`)."""

    bearing: sb.BearingGeometry
    constants: CombinedConstants
    mu: float
    omega_inner: float
    omega_outer: float
    load: float
    approach_direction: str = "normal"
    force_add: tuple[float, float, float] = (0.0, 0.0, 0.0)
    moment_add: tuple[float, float, float] = (0.0, 0.0, 0.0)
    offsets: object = field(default=None, compare=False)

    @property
    def approach_vector(self) -> np.ndarray:
        return self.bearing.e_z if self.approach_direction == "normal" else sb.Z.copy()

    def hertz(self, load: float | None = None) -> dict:
        """Elliptic Hertz of both nominal contacts at ``load`` (default N)."""
        N = self.load if load is None else load
        return {c: elliptic_contact(N, *sb.hertz_radii(self.bearing)[c], self.constants.contact_modulus)
                for c in sb.CONTACTS}


@dataclass(frozen=True)
class Numerics:
    """Discretisation and solver options: ``nx`` x ``ns`` elements per contact, half-widths ``domain_x`` a_H,
    ``domain_s`` b_H; ``variable_dq`` (kappa(s) of eq 21, else kappa = 1); ``influence`` (as in
    :func:`femcheck.cect.conformal.solve_conformal`); solver tolerances ``tangential_tol`` (of max mu p),
    ``normal_tol``; ``tol_scale`` (tol_F = tol_scale mu N); ``solver`` "auto"/"dense"/"fft"."""

    nx: int = 41
    ns: int = 81
    domain_x: float = 1.35
    domain_s: float = 1.25
    variable_dq: bool = True
    influence: str = "halfspace"
    tangential_tol: float = 1e-9
    normal_tol: float = 1e-11
    tol_scale: float = 1e-5
    solver: str = "auto"


@dataclass(frozen=True)
class GridSpec:
    """Fixed cell sizes of both contacts' windows: ``half_x``, ``half_s`` (m) per contact and the window centres
    ``s_centre`` (m, on the lattice of ds)."""

    half_x: dict
    half_s: dict
    s_centre: dict

    @classmethod
    def of(cls, problem: RollerProblem, num: Numerics) -> "GridSpec":
        hz = problem.hertz()
        return cls({c: num.domain_x * hz[c].semi_axis_x for c in sb.CONTACTS},
                   {c: num.domain_s * hz[c].semi_axis_y for c in sb.CONTACTS}, {c: 0.0 for c in sb.CONTACTS})

    def ds(self, contact: str, ns: int) -> float:
        return 2.0 * self.half_s[contact] / ns

    def predicted(self, problem: RollerProblem, x, ns: int) -> "GridSpec":
        """Windows centred where a rigid axial offset d_y of the roller moves the contacts: s_c = d_y r_g /
        (r_g - R) (spec §10.1 check 3; 38.1 d_y inner, 48.8 d_y outer)."""
        b = problem.bearing
        d_y = float(np.asarray(x[:2]) @ b.e_y[1:])
        rg = {"inner": b.groove_radius_inner, "outer": b.groove_radius_outer}
        return self.recentred({c: d_y * rg[c] / (rg[c] - b.crown_radius) for c in sb.CONTACTS}, ns)

    def moved(self, contact: str, cells: int, ns: int) -> "GridSpec":
        s = dict(self.s_centre)
        s[contact] += cells * self.ds(contact, ns)
        return replace(self, s_centre=s)

    def recentred(self, centres: dict, ns: int) -> "GridSpec":
        """Windows moved to the lattice point nearest each pressure centre ``centres`` (m)."""
        return replace(self, s_centre={c: float(np.round(centres[c] / self.ds(c, ns)) * self.ds(c, ns))
                                       for c in sb.CONTACTS})


@dataclass
class ContactState:
    """One contact at one state: the solver ``inputs`` (:class:`femcheck.geometry.srb_bearing.ContactInput`), the
    CECT ``result``, the 3D ``force`` and ``moment`` about C (N, N m, in B) on the roller."""

    inputs: sb.ContactInput
    result: ConformalResult
    force: np.ndarray
    moment: np.ndarray


@dataclass
class RollerState:
    """Both contacts at state ``x`` and approach ``delta`` (m): ``contacts`` {"inner", "outer": ContactState},
    ``residual`` (6: F in N, M in N m, components along e_x, e_y, e_z), ``scaled`` (residual / (tol_F, tol_M)),
    ``centre`` C (m), ``inertia_force`` F_c and ``inertia_moment`` M_g (in B)."""

    x: np.ndarray
    delta: float
    contacts: dict
    residual: np.ndarray
    scaled: np.ndarray
    centre: np.ndarray
    inertia_force: np.ndarray
    inertia_moment: np.ndarray
    stats: dict = field(default_factory=dict)

    @property
    def norm(self) -> float:
        return float(np.max(np.abs(self.scaled)))

    @property
    def inner_load(self) -> float:
        return self.contacts["inner"].result.normal_force


def _shift(a: np.ndarray, k: int) -> np.ndarray:
    out = np.zeros_like(a)
    if k >= 0:
        out[:, :a.shape[1] - k] = a[:, k:]
    else:
        out[:, -k:] = a[:, :a.shape[1] + k]
    return out


def _aligned(w: ConformalResult, ci: sb.ContactInput) -> ConformalResult | None:
    """The warm start ``w`` moved onto the window of ``ci`` (same cells, window shifted by whole cells), or
    None when the cells differ."""
    g = ci.grid.grid
    if (w.grid.nx, w.grid.ny) != (g.nx, g.ny) or not np.isclose(w.grid.dx, g.dx, rtol=1e-12) \
            or not np.isclose(w.grid.dy, g.dy, rtol=1e-12):
        return None
    k = int(np.round((ci.grid.s[0] - w.s[0]) / g.dy))
    if k == 0:
        return w
    if abs(k) >= g.ny:
        return None
    return replace(w, pressure=_shift(w.pressure, k), px=_shift(w.px, k), ps=_shift(w.ps, k), s=ci.grid.s.copy(),
                   normal=replace(w.normal, pressure=_shift(w.normal.pressure, k)))


def pose_of(x) -> tuple[sb.Pose, float, float]:
    return sb.Pose(float(x[0]), float(x[1]), float(x[2]), float(x[3])), float(x[4]), float(x[5])


def tolerances(problem: RollerProblem, num: Numerics) -> tuple[float, float]:
    """(tol_F, tol_M) = (tol_scale mu N, tol_F D/2) (N, N m; spec §3)."""
    tf = num.tol_scale * problem.mu * problem.load
    return tf, tf * 0.5 * problem.bearing.roller_diameter


def evaluate(problem: RollerProblem, num: Numerics, grids: GridSpec, x, delta: float,
             warm: RollerState | None = None, reuse_normal: bool = False) -> RollerState:
    """Both contacts and the residual at state ``x`` with the inner ring displaced by ``delta`` (m) along the
    approach direction. ``warm`` a state on the same grids (warm start of both contact problems);
    ``reuse_normal`` takes warm's normal solutions as they are (valid when only the speeds changed)."""
    b = problem.bearing
    pose, om, orr = pose_of(x)
    shift = delta * problem.approach_vector
    C = sb.roller_centre(b, pose)
    contacts = {}
    for c in sb.CONTACTS:
        ci = sb.contact_input(b, pose, c, om, orr, problem.omega_inner, problem.omega_outer, grids.half_x[c],
                              grids.half_s[c], num.nx, num.ns, s_centre=grids.s_centre[c], inner_ring_shift=shift)
        w = _aligned(warm.contacts[c].result, ci) if warm is not None else None
        hz_approach = None
        if w is None:
            hz_approach = problem.hertz()[c].approach
        gap, slip = ci.gap, np.stack([ci.slip.wx, ci.slip.ws])
        if problem.offsets is not None:
            dg, dw = problem.offsets(c, ci)
            gap, slip = gap + dg, slip + dw
        try:
            res = solve_conformal(ci.grid.grid, gap, problem.constants, problem.mu, slip, ci.speeds.reference,
                                  ci.speeds.kappa if num.variable_dq else None, s=ci.grid.s,
                                  influence=num.influence, radius=ci.ring.groove_radius, tol=num.tangential_tol,
                                  normal_tol=num.normal_tol, tangential_solver=num.solver, warm=w,
                                  normal=w.normal if (reuse_normal and w is not None) else None,
                                  approach0=hz_approach)
        except GridTooSmall as err:
            err.contact = c           # which window to move (see :func:`fitted`)
            raise
        r = resultants(res, ci.grid, C)
        contacts[c] = ContactState(ci, res, r.force, r.moment)
    Fc = sb.centrifugal_force(b, pose, om)
    Mg = sb.gyroscopic_moment(b, pose, om, orr)
    F = contacts["inner"].force + contacts["outer"].force + Fc + np.asarray(problem.force_add)
    M = contacts["inner"].moment + contacts["outer"].moment + Mg + np.asarray(problem.moment_add)
    E = np.stack([b.e_x, b.e_y, b.e_z])
    R = np.concatenate([E @ F, E @ M])
    tf, tm = tolerances(problem, num)
    return RollerState(np.asarray(x, dtype=float).copy(), float(delta), contacts, R,
                       R / np.array([tf, tf, tf, tm, tm, tm]), C, Fc, Mg)


def fitted(problem: RollerProblem, num: Numerics, grids: GridSpec, x, delta: float, max_moves: int = 8):
    """:func:`evaluate` on windows moved (by ns/8 cells at a time) until both contacts lie inside them: for a
    start far from the last state. Returns (state, grids); GridTooSmall when the contact touches both ends or
    an x edge."""
    for _ in range(max_moves):
        try:
            return evaluate(problem, num, grids, x, delta), grids
        except GridTooSmall as err:
            if any(e.startswith("x") for e in err.edges) or len(err.edges) != 1:
                raise
            grids = grids.moved(err.contact, (1 if err.edges[0] == "s+" else -1) * max(1, num.ns // 8), num.ns)
    return evaluate(problem, num, grids, x, delta), grids


def nominal_start(problem: RollerProblem) -> tuple[np.ndarray, float]:
    """Start of configuration 1 (spec §6): the nominal orientation, the roller moved towards the outer ring by the
    outer Hertz approach (so that both contacts carry about N), nominal speeds (eqs 2-3); the approach delta =
    sum of both Hertz approaches (m). Returns (x0, delta0)."""
    hz = problem.hertz()
    e = problem.bearing.e_z * hz["outer"].approach
    om, orr = sb.nominal_speeds(problem.bearing, problem.omega_inner, problem.omega_outer)
    delta = hz["inner"].approach + hz["outer"].approach
    if problem.approach_direction != "normal":
        delta /= float(problem.bearing.e_z @ sb.Z)
    return np.array([e[1], e[2], 0.0, 0.0, om, orr]), float(delta)


def check_problem(problem: RollerProblem) -> None:
    """mu > 0, N > 0, a rolling inner ring, a known approach direction (InputError otherwise)."""
    if not problem.mu > 0:
        raise InputError("friction.mu", f"{problem.mu:g}; allowed: > 0")
    if not problem.load > 0:
        raise InputError("load.normal", f"{problem.load:g} N; allowed: > 0")
    if problem.omega_inner == problem.omega_outer:
        raise InputError("kinematics.inner_ring_speed", "equal to the outer ring speed; allowed: a relative speed "
                         "!= 0 (the roller must roll)")
    if problem.approach_direction not in ("normal", "radial"):
        raise InputError("equilibrium.approach_direction", f"{problem.approach_direction!r}; allowed: normal, radial")
