"""2D plane-strain FE reference of a cylindrical-roller-bearing section (spec bearing-load.md §4): inner ring
(bore tied to a rigid shaft that carries the load), Z rollers, outer ring (OD clamped in a rigid housing over a
full circle or an arc), frictionless node-to-node contact along each roller's radial line, load control.

Frame: the load F' = F_r/l (N/m) acts along +x; roller j sits at psi_j = 2 pi j/Z - load_angle; the housing arc
is centred on +x. Rigid rings are exact circles moved rigidly (inner by the shaft translation delta). Bodies are
condensed onto their contact zones (:mod:`femcheck.fem.bearing2d_bodies`): one roller condensed once and rotated
to every position (geometric similarity; ``similarity = "mesh_all"`` meshes all Z rollers as one body instead,
the check of V8), rings block-circulant on an axisymmetric support, otherwise only the zones of the rollers that
may carry load (the rigid-ring load zone plus one roller each side), with an a-posteriori check that no other
roller is squeezed (rollers are added and the solve repeated if one is). Contact by the primal-dual active set
(or penalty), :mod:`femcheck.solvers.bearing_contact`.

Mesh levels k = 0..L-1: every size (zone spacing, grading slope, largest element of rings and roller) shrinks
by ``ratio`` per level, from h_c = ``h_contact`` b (b: Hertz half-width of the rigid-ring Q_max) on the coarsest
level. Measured with rigid raceways (209 bearing, P2): Q_max is +0.19 % off the exact 2D law at h_c = b/2, -0.031 %
at b/4 and -0.0075 % at b/8, so b/2 is not yet in the asymptotic range (the contact spans only two elements) and
the levels start below b/4 (ratio sqrt 2: three levels for the cost of one more halving). At b/4 a lightly
loaded roller (515 N against Q_max = 3484 N, elastic rings: contact half-width 0.38 b) spans only 1.5 elements
and its load is still 0.1 % of Q_max off, so the default levels are b/5.7, b/8, b/11.3.
Quantities per level; certificates (:func:`femcheck.solvers.convergence.certify`) over the levels.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..analytic.bearing_laws import PlaneStrainRoller
from ..analytic.bearing_load import rigid_ring, zone_from_profile
from ..errors import ConvergenceError
from ..materials import Elastic
from ..meshes import bearing2d as meshes
from ..meshes.plane import MeshSpec
from ..qoi import contact_edge
from ..solvers import bearing_contact
from .bearing2d_bodies import (RollerCompliance, ring_compliance, roller_compliance, rollers_meshed,
                               tributary_lengths)


@dataclass(frozen=True)
class BearingSection:
    """Geometry (m), materials and load of the 2D section. ``clearance`` P_d = 2 (r_o - r_i - 2R)."""

    rollers: int
    roller_radius: float
    inner_raceway: float
    outer_raceway: float
    bore: float
    outside: float
    length: float
    load: float                 # N (radial, along +x); per unit length F_r / length
    load_angle: float
    roller_material: Elastic
    ring_material: Elastic
    housing_half_angle: float = np.pi

    @property
    def clearance(self) -> float:
        return 2.0 * (self.outer_raceway - self.inner_raceway - 2.0 * self.roller_radius)

    @property
    def pitch_radius(self) -> float:
        return 0.5 * (self.inner_raceway + self.outer_raceway)

    @property
    def angles(self) -> np.ndarray:
        return 2.0 * np.pi * np.arange(self.rollers) / self.rollers - self.load_angle

    def contact_moduli(self) -> tuple[float, float]:
        """E* of the roller-inner and roller-outer contacts (Pa)."""
        c = self.roller_material.compliance + self.ring_material.compliance
        return 1.0 / c, 1.0 / c

    def roller_law(self) -> PlaneStrainRoller:
        R = self.roller_radius
        rx = (R * self.inner_raceway / (R + self.inner_raceway), R * self.outer_raceway / (self.outer_raceway - R))
        m = self.roller_material
        return PlaneStrainRoller(R, self.length, m.E, m.nu, rx, self.contact_moduli())


@dataclass(frozen=True)
class FESettings:
    levels: int = 3
    ratio: float = 2.0**0.5       # refinement ratio between levels
    h_contact: float = 0.25 / 2**0.5   # coarsest zone spacing / b (levels b/5.7, b/8, b/11.3)
    zone: float = 2.5             # zone half-length / b (the contact must stay inside)
    grading: float = 0.6          # coarsest size growth per unit distance
    h_max_ring: float = 0.5       # coarsest largest ring element / ring thickness
    h_max_roller: float = 0.25    # coarsest largest roller element / roller radius
    order: int = 2
    method: str = "active_set"
    penalty_factor: float = 1.0e3
    similarity: str = "rotate"    # rotate | mesh_all
    tol: float = 1e-9


@dataclass
class Level:
    h: float
    roller_loads: np.ndarray      # N
    interference: np.ndarray      # m: roller compression (loaded) or -free room (unloaded)
    delta: np.ndarray             # m, shaft translation
    q_max: float
    radial_deflection: float
    loaded_rollers: int
    load_zone_angle: float
    load_zone_parameter: float
    total_force: float
    n_dofs: int
    iterations: int
    residual: float
    penetration: float
    time_s: float
    included: list[int]
    detail: dict = field(default_factory=dict)


def reference_half_width(sec: BearingSection) -> tuple[float, object]:
    """b (m): the larger Hertz half-width at the rigid-ring Q_max with the 2D law (sets the zones and sizes)."""
    law = sec.roller_law()
    rr = rigid_ring(sec.rollers, sec.clearance, law, sec.load, sec.load_angle)
    return float(max(law.half_widths(rr.q_max))), rr


def _spec(h: float, t_c: float, grading: float, h_max: float) -> MeshSpec:
    return MeshSpec(h, t_c, grading, max(h, h_max))


def _roller(sec: BearingSection, zone: meshes.ZoneSpec, h: float, grading: float, h_max: float, s: FESettings):
    mesh = meshes.roller(sec.roller_radius, zone, _spec(h, zone.t_c, grading, h_max))
    return roller_compliance(mesh, sec.roller_radius, zone.offsets, sec.roller_material, s.order, h)


def _rings(sec: BearingSection, zone: meshes.ZoneSpec, h: float, grading: float, s: FESettings, scale: float):
    if sec.ring_material.rigid:
        return None, None
    out = []
    for race, back, which in ((sec.inner_raceway, sec.bore, "outer"), (sec.outer_raceway, sec.outside, "inner")):
        t = abs(race - back)
        h_max = s.h_max_ring * t * scale
        support = np.pi if which == "outer" else sec.housing_half_angle
        ends = () if support >= np.pi else (support, -support)
        spec = meshes.RingSpec(min(race, back), max(race, back), sec.rollers, which, -sec.load_angle, ends)
        mesh = meshes.ring(spec, zone, _spec(h, zone.t_c, grading, h_max))
        out.append(ring_compliance(mesh, race, back, sec.angles, zone.offsets, sec.ring_material, s.order, h,
                                   support))
    return out[0], out[1]


def _assemble(sec: BearingSection, roller: RollerCompliance | np.ndarray, rings, included: list[int], t: np.ndarray):
    """Dense system over the pairs of the ``included`` rollers."""
    z, n = len(included), t.size
    W = np.zeros((2 * z * n, 2 * z * n))
    for a, j in enumerate(included):
        Wr = roller[j] if isinstance(roller, np.ndarray) else roller.W
        ii = np.r_[a * n:(a + 1) * n, z * n + a * n:z * n + (a + 1) * n]
        W[np.ix_(ii, ii)] += Wr
    extra = {}
    inner_ring, outer_ring = rings
    for ring, off in ((inner_ring, 0), (outer_ring, z * n)):
        if ring is None:
            continue
        cols = ring.columns(included)                                  # (Z n, z n)
        rows = np.concatenate([np.arange(j * n, (j + 1) * n) for j in included])
        W[off:off + z * n, off:off + z * n] += cols[rows]
        extra[off] = cols                                              # every zone's response, for the check
    R, r_c = sec.roller_radius, sec.pitch_radius
    g_in = r_c - np.sqrt(R**2 - t**2) - np.sqrt(sec.inner_raceway**2 - t**2)
    g_out = np.sqrt(sec.outer_raceway**2 - t**2) - r_c - np.sqrt(R**2 - t**2)
    g0 = np.concatenate([np.tile(g_in, z), np.tile(g_out, z)])
    ang = sec.angles[included]
    dirs = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    sys = bearing_contact.RollerSetContact(g0, 0.5 * (W + W.T), dirs, np.array([sec.load / sec.length, 0.0]), n)
    return sys, extra, (g_in, g_out)


def _excluded_room(sec: BearingSection, sol, extra, gaps0, included: list[int], n: int) -> np.ndarray:
    """Free room (m) of every roller left out of the system, from the included pairs' forces."""
    z = sec.rollers
    g_in0, g_out0 = gaps0
    m = len(included) * n
    room = np.full(z, np.inf)
    for j in sorted(set(range(z)) - set(included)):
        e = np.array([np.cos(sec.angles[j]), np.sin(sec.angles[j])])
        gi = g_in0 - e @ sol.delta
        go = g_out0.copy()
        if 0 in extra:
            gi = gi + extra[0][j * n:(j + 1) * n] @ sol.lam[:m]
        if m in extra:
            go = go + extra[m][j * n:(j + 1) * n] @ sol.lam[m:]
        room[j] = gi.min() + go.min()
    return room


def solve_level(sec: BearingSection, b: float, rr, k: int, s: FESettings, keep_fields: bool = False) -> Level:
    t0 = time.perf_counter()
    scale = s.ratio**-k
    h = s.h_contact * b * scale
    half = max(2, int(round(s.zone / s.h_contact / scale)))
    zone = meshes.ZoneSpec(half * h, 2 * half)          # spacing exactly h: levels keep a constant ratio
    grading = s.grading * scale
    roller = _roller(sec, zone, h, grading, s.h_max_roller * sec.roller_radius * scale, s)
    W_roll = roller
    if s.similarity == "mesh_all":
        W_roll = rollers_meshed(roller.mesh, sec.roller_radius, sec.pitch_radius, sec.angles, zone.offsets,
                                sec.roller_material, s.order, h)
    rings = _rings(sec, zone, h, grading, s, scale)
    t = roller.t
    n = t.size
    z = sec.rollers
    law = sec.roller_law()
    circulant = rings[0] is None or all(r.circulant for r in rings)
    if circulant:
        included = list(range(z))
    else:
        loaded = np.flatnonzero(rr.loads > 0)
        included = sorted({(j + d) % z for j in loaded for d in (-1, 0, 1)})
    while True:
        sys, extra, gaps0 = _assemble(sec, W_roll, rings, included, t)
        # initial active set: the rigid-ring load zone with its Hertz widths
        a_in, a_out = law.half_widths(rr.loads[included])
        act = np.concatenate([(np.abs(t)[None, :] < a_in[:, None]).ravel(), (np.abs(t)[None, :] < a_out[:, None]).ravel()])
        if not act.any():
            act = sys.g0 <= np.median(sys.g0)
        kappa = None
        if s.method == "penalty":
            e_star = 1.0 / (sec.roller_material.compliance + sec.ring_material.compliance)
            w = np.tile(tributary_lengths(t, s.order), 2 * len(included))
            kappa = s.penalty_factor * e_star * w / h
        sol = bearing_contact.solve(sys, act, s.method, kappa, tol=s.tol)
        room = _excluded_room(sec, sol, extra, gaps0, included, n)
        squeezed = [j for j in range(z) if room[j] < 0]
        if not squeezed:
            break
        included = sorted(set(included) | {(j + d) % z for j in squeezed for d in (-1, 0, 1)})
    m = len(included) * n
    lam_in = sol.lam[:m].reshape(len(included), n)
    lam_out = sol.lam[m:].reshape(len(included), n)
    P = np.zeros(z)
    P[included] = lam_in.sum(axis=1)
    loads = P * sec.length
    # interference: loaded rollers: diametral compression; unloaded: minus their free room
    interference = -room.copy()
    roomin = sys.free_room(sol.lam, sol.rho, sol.delta)
    j0 = int(np.argmin(np.abs(t)))
    Wr = roller.W
    for a, j in enumerate(included):
        if P[j] > 0:
            f = np.concatenate([lam_in[a], lam_out[a]])
            u = Wr @ f if not isinstance(W_roll, np.ndarray) else W_roll[j] @ f
            interference[j] = u[j0] + u[n + j0]
        else:
            interference[j] = -roomin[a]
    psi = sec.angles
    zone_angle, eps = zone_from_profile(np.angle(np.exp(1j * psi)), interference)
    e_load = np.cos(psi)
    detail = {}
    jmax = int(np.argmax(loads))
    a = included.index(jmax)
    w = tributary_lengths(t, s.order)
    for side, lam in (("inner", lam_in[a]), ("outer", lam_out[a])):
        p = lam / w
        if p[0] > 0 or p[-1] > 0:
            raise ConvergenceError("bearing FE", sol.iterations, np.inf, s.tol,
                                   "contact reached the end of a contact zone; raise numerics.fem_zone")
        detail[f"p_max_{side}"] = float(p.max())
        detail[f"half_width_{side}"] = 0.5 * (contact_edge(t, p) + contact_edge(-t[::-1], p[::-1]))
    if keep_fields:
        detail["fields"] = _fields(sec, sol, rings, included, n, t, lam_in, lam_out, w)
    n_dofs = roller.n_dofs * z + sum(r.body.n_dofs for r in rings if r is not None)
    return Level(h, loads, interference, sol.delta, float(loads.max()), float(np.hypot(*sol.delta)),
                 int(np.count_nonzero(loads > 0)), zone_angle, eps, float(loads @ e_load), n_dofs,
                 sol.iterations, sol.residual, sol.penetration, time.perf_counter() - t0, included, detail)


def _boundary(mesh, radius: float) -> np.ndarray:
    """Vertex indices on the circle of ``radius``, sorted by angle."""
    r = np.hypot(*mesh.points)
    idx = np.flatnonzero(np.abs(r - radius) < 1e-7 * radius)
    return idx[np.argsort(np.arctan2(mesh.points[1, idx], mesh.points[0, idx]))]


def _fields(sec, sol, rings, included, n, t, lam_in, lam_out, w) -> dict[str, np.ndarray]:
    """Finest-level fields for the report: deformed ring boundaries, roller translations, contact pressures."""
    out: dict[str, np.ndarray] = {"roller_rho": np.full(sec.rollers, np.nan), "contact_t": t,
                                  "pressure_inner": np.zeros((sec.rollers, n)), "pressure_outer": np.zeros((sec.rollers, n))}
    for a, j in enumerate(included):
        out["roller_rho"][j] = sol.rho[a]
        out["pressure_inner"][j] = lam_in[a] / w
        out["pressure_outer"][j] = lam_out[a] / w
    out["shaft_delta"] = sol.delta
    z = sec.rollers
    for name, ring, race, back, lam in (("inner", rings[0], sec.inner_raceway, sec.bore, lam_in),
                                        ("outer", rings[1], sec.outer_raceway, sec.outside, lam_out)):
        if ring is None:
            continue
        full = np.zeros(z * n)
        for a, j in enumerate(included):
            full[j * n:(j + 1) * n] = lam[a]
        u = ring.displacement(full)
        vd = ring.body.basis.nodal_dofs
        for surf, radius in (("raceway", race), ("back", back)):
            idx = _boundary(ring.mesh, radius)
            out[f"ring_{name}_{surf}_xy"] = ring.mesh.points[:, idx]
            shift = sol.delta[:, None] if name == "inner" else 0.0
            out[f"ring_{name}_{surf}_u"] = u[vd[:, idx]] + shift
    return out


# The discrete contact edge (nodes entering and leaving the active set) makes roller loads oscillate from level to
# level at a few 1e-4 relative (measured, 209 bearing: Q_max +-1.5e-4 with rigid, +-1.7e-4 with elastic rings,
# h_c = b/4 ... b/11). Below this the levels cannot show an order; a quantity whose last three levels agree within
# RESOLUTION is converged to within that band and certified with the conservative 3 x (largest change) estimate.
RESOLUTION = 1e-3


def certificate(h: list[float], q: list[float], scale: float | None = None):
    """:func:`femcheck.solvers.convergence.certify`, plus the resolution band above. ``scale``: the magnitude
    the changes are measured against (default |finest|; roller loads use Q_max)."""
    from ..solvers.convergence import Certificate, certify

    cert = certify(h, q)
    ref = scale if scale is not None else (abs(q[-1]) or 1.0)
    changes = [abs(q[i + 1] - q[i]) / ref for i in range(len(q) - 3, len(q) - 1)] if len(q) >= 3 else []
    if cert.certified or not changes or max(changes) > RESOLUTION:
        if scale is not None and cert.certified:
            cert.error_estimate = cert.error_estimate * abs(cert.value) / ref
        return cert
    err = 3.0 * max(changes)
    return Certificate(q[-1], q[-1], cert.order, err, True,
                       f"changes {changes[0]:.1e}, {changes[1]:.1e} over the last three levels are within the "
                       f"contact-edge resolution {RESOLUTION:g}: converged to within it ({cert.note})")


def solve(sec: BearingSection, s: FESettings, progress=None) -> tuple[list[Level], dict]:
    """Every level; returns the levels and the certificates of q_max, radial_deflection, load_zone_angle,
    load_zone_parameter and each loaded roller's load (``roller_loads``: all rollers above 5 % of Q_max)."""
    b, rr = reference_half_width(sec)
    levels = []
    for k in range(s.levels):
        if progress:
            progress(f"FE level {k + 1}/{s.levels}")
        levels.append(solve_level(sec, b, rr, k, s, keep_fields=(k == s.levels - 1)))
    h = [lv.h for lv in levels]
    certs = {}
    for name in ("q_max", "radial_deflection", "load_zone_angle", "load_zone_parameter"):
        certs[name] = certificate(h, [getattr(lv, name) for lv in levels])
    q_max = levels[-1].q_max
    per_roller = [certificate(h, [lv.roller_loads[j] for lv in levels], scale=q_max)
                  for j in range(sec.rollers)]
    heavy = [j for j in range(sec.rollers) if levels[-1].roller_loads[j] >= 0.05 * q_max]
    light = [j for j in range(sec.rollers) if j not in heavy]
    err = max([per_roller[j].error_estimate for j in heavy] +
              [3.0 * abs(levels[-1].roller_loads[j] - levels[-2].roller_loads[j]) / q_max for j in light
               if len(levels) > 1])
    ok = all(per_roller[j].certified for j in heavy) and len(levels) >= 3
    certs["roller_loads"] = {"value": None, "finest": None, "order": None, "error_estimate": float(err),
                             "certified": bool(ok),
                             "note": "every roller above 5 % of Q_max certified; error relative to Q_max" if ok else
                             "not every loaded roller's load is certified",
                             "per_roller": [c.as_dict() for c in per_roller], "b": b}
    return levels, certs
