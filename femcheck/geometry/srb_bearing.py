"""Spherical roller bearing of seed 000 in 3D: frames, roller pose, exact roller and raceway surfaces, the
potential contact surfaces of the two contacts, nominal speeds (eqs 2-3), centrifugal force and gyroscopic
moment (spec srb-rolling §1-§3).

Frames (all vectors in the bearing frame B = {X, Y, Z}, m):
- B: origin O on the ring axis in the bearing mid-plane, Y the ring axis, Z through the roller's centre,
  X = Y x Z. B turns with the cage at omega_m about Y; in steady rolling the roller is stationary in B.
- reference roller frame {x, y, z}: origin C0 = (0, -r_m tan a, r_m); e_x = X, e_y = (0, cos a, sin a) the nominal
  roller axis (towards the mid-plane: the roller sits at Y < 0), e_z = (0, -sin a, cos a) the nominal contact
  normal (the line O - C0 - contact points).
- roller pose (spec §2.1): tilt beta about x, then skew gamma about the new z'; roller axis
  v = -sin g e_x + cos b cos g e_y + sin b cos g e_z; centre C = C0 + d_Y Y + d_Z Z.
  The paper's offset d_y = (C - C0).e_y = d_Y cos a + d_Z sin a; d_z = (C - C0).e_z.
- rings: the outer raceway is a sphere of radius r_E about O; the inner groove circle has its centre on the line
  O + t e_z at t = r_E - D + r_I (185.6 mm), radius r_I; the inner ring may be displaced by a vector (the
  prescribed approach, spec §2.2: delta e_z by default).

Angular velocities in B: ring j turns at omega_j - omega_m about Y, the roller at omega_R about v. The potential
contact surface of contact j is the groove circle of ring j (:func:`femcheck.geometry.conformal_surface
.groove_profile`) with s = 0 on the line through the groove centre parallel to e_z, s increasing towards +e_y,
the rolling direction x_j = -sign(omega_j - omega_m) X (the material flows along -x_j): x_I = -X, x_E = +X for
omega_I > omega_m > 0 = omega_E. Body 1 of the contact is the roller, body 2 the ring. Both local triads
(x_j, t, n) are left-handed: dw_s/dx = -(spin about n) (5.503 / 4.439 rad/s about n at the nominal state).

Typical use (one contact of a roller equilibrium; SI throughout)::

    b = SEED_000
    om, orr = nominal_speeds(b, OMEGA_INNER_SEED_000)                  # or the current Newton iterate
    ci = contact_input(b, Pose(d_Y, d_Z, tilt, skew), "inner", om, orr, OMEGA_INNER_SEED_000, 0.0,
                       1.35 * a_H, 1.25 * b_H, 61, 121, s_centre=s_c, inner_ring_shift=delta * b.e_z)
    res = solve_conformal(ci.grid.grid, ci.gap, constants, mu, np.stack([ci.slip.wx, ci.slip.ws]),
                          ci.speeds.reference, ci.speeds.kappa, s=ci.grid.s, warm=previous)   # cect.conformal
    R = resultants(res, ci.grid, ci.roller.centre)       # force (N) and moment about C (N m), in B
    f_lat = res.force_s / (mu * N)                       # towards the mid-plane; f_x = R.force @ x_p / (mu N)

Keep nx, ns, the half-widths and s_centre fixed within a Newton iteration (the influence spectra are cached per
grid); for a Jacobian column in omega only, pass ``normal=base.normal`` (the gap does not change).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .conformal_surface import (DevelopedGrid, ProfileSurface, RigidSlip, RollingSpeeds, developed_grid,
                                groove_profile, rigid_slip, rolling_speeds, undeformed_distance)
from .revolution import CrownedBody, GroovedRing

X = np.array([1.0, 0.0, 0.0])
Y = np.array([0.0, 1.0, 0.0])
Z = np.array([0.0, 0.0, 1.0])
CONTACTS = ("inner", "outer")


@dataclass(frozen=True)
class BearingGeometry:
    """Roller and raceway data (SI): ``roller_diameter`` D, ``crown_radius`` R, ``groove_radius_inner`` r_I,
    ``groove_radius_outer`` r_E, ``contact_angle`` alpha (rad); ``roller_mass`` m_R (kg) and
    ``roller_inertia`` I_R (kg m^2, spin axis; E9) for the inertia loads; ``roller_length`` L_R (m, not in the
    paper: 27 mm from the mass, spec §1.2)."""

    roller_diameter: float
    crown_radius: float
    groove_radius_inner: float
    groove_radius_outer: float
    contact_angle: float
    roller_mass: float = 0.0656
    roller_inertia: float = 5.87e-6
    roller_length: float = 0.027

    @classmethod
    def from_params(cls, params: dict[str, Any]) -> "BearingGeometry":
        """From srb-normal style keys (geometry.roller_diameter, .crown_radius, .groove_radius_inner|outer,
        .contact_angle; optional roller.mass, roller.inertia, geometry.roller_length)."""
        extra = {k: params[p] for k, p in (("roller_mass", "roller.mass"), ("roller_inertia", "roller.inertia"),
                                           ("roller_length", "geometry.roller_length")) if p in params}
        return cls(params["geometry.roller_diameter"], params["geometry.crown_radius"],
                   params["geometry.groove_radius_inner"], params["geometry.groove_radius_outer"],
                   params["geometry.contact_angle"], **extra)

    # ---- derived numbers (spec §1.2) ------------------------------------------------------------------------
    @property
    def pitch_radius(self) -> float:
        """r_m = (r_E - D/2) cos a (seed 000 §2 with the minus sign the print lost, E1)."""
        return (self.groove_radius_outer - 0.5 * self.roller_diameter) * np.cos(self.contact_angle)

    @property
    def rolling_radii(self) -> dict[str, float]:
        """r_roll = r_m -/+ (D/2) cos a (eq 1), inner / outer (m)."""
        h = 0.5 * self.roller_diameter * np.cos(self.contact_angle)
        return {"inner": self.pitch_radius - h, "outer": self.pitch_radius + h}

    @property
    def e_x(self) -> np.ndarray:
        return X.copy()

    @property
    def e_y(self) -> np.ndarray:
        a = self.contact_angle
        return np.array([0.0, np.cos(a), np.sin(a)])

    @property
    def e_z(self) -> np.ndarray:
        a = self.contact_angle
        return np.array([0.0, -np.sin(a), np.cos(a)])

    @property
    def nominal_centre(self) -> np.ndarray:
        """C0 = (0, -r_m tan a, r_m) = (r_E - D/2) e_z (m)."""
        return (self.groove_radius_outer - 0.5 * self.roller_diameter) * self.e_z

    @property
    def inner_groove_distance(self) -> float:
        """Distance of the inner groove centre from O along e_z: r_E - D + r_I (m)."""
        return self.groove_radius_outer - self.roller_diameter + self.groove_radius_inner

    def nominal_point(self, contact: str) -> np.ndarray:
        """Nominal contact point C0 -/+ (D/2) e_z (inner / outer)."""
        sign = -1.0 if contact == "inner" else 1.0
        return self.nominal_centre + sign * 0.5 * self.roller_diameter * self.e_z


@dataclass(frozen=True)
class Pose:
    """Roller pose (spec §2.1): ``d_Y``, ``d_Z`` (m) offsets of the centre along Y and Z of B from C0, ``tilt``
    beta and ``skew`` gamma (rad)."""

    d_Y: float = 0.0
    d_Z: float = 0.0
    tilt: float = 0.0
    skew: float = 0.0


def roller_frame(b: BearingGeometry, pose: Pose) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Roller axes (u, v, w) in B (pitch rotation excluded): tilt beta about e_x, then skew gamma about z'."""
    cb, sb, cg, sg = np.cos(pose.tilt), np.sin(pose.tilt), np.cos(pose.skew), np.sin(pose.skew)
    y1 = cb * b.e_y + sb * b.e_z
    z1 = -sb * b.e_y + cb * b.e_z
    u = cg * b.e_x + sg * y1
    v = -sg * b.e_x + cg * y1
    return u, v, z1


def roller_centre(b: BearingGeometry, pose: Pose) -> np.ndarray:
    return b.nominal_centre + pose.d_Y * Y + pose.d_Z * Z


def roller_offsets(b: BearingGeometry, pose: Pose) -> tuple[float, float]:
    """(d_y, d_z) = ((C - C0).e_y, (C - C0).e_z) (m): the paper's axial offset d_y and the normal offset."""
    d = roller_centre(b, pose) - b.nominal_centre
    return float(d @ b.e_y), float(d @ b.e_z)


def roller_body(b: BearingGeometry, pose: Pose) -> CrownedBody:
    """The barrel roller as an exact body of revolution (crown radius R, apex radius D/2)."""
    return CrownedBody(roller_centre(b, pose), roller_frame(b, pose)[1], 0.5 * b.roller_diameter, b.crown_radius)


def ring_body(b: BearingGeometry, contact: str, shift=(0.0, 0.0, 0.0)) -> GroovedRing:
    """Raceway ``contact`` ("inner"/"outer") as a grooved ring about Y, displaced by ``shift`` (m, 3-vector)."""
    if contact == "outer":
        return GroovedRing(np.asarray(shift, dtype=float), Y, 0.0, 0.0, b.groove_radius_outer)
    g = b.inner_groove_distance * b.e_z
    return GroovedRing(np.asarray(shift, dtype=float), Y, float(g @ Y), float(np.hypot(g[0], g[2])),
                       b.groove_radius_inner)


def ring_rate(contact: str, omega_m: float, omega_inner: float, omega_outer: float) -> float:
    """Angular velocity of ring ``contact`` about Y in B: omega_j - omega_m (rad/s)."""
    return (omega_inner if contact == "inner" else omega_outer) - omega_m


def contact_surface(b: BearingGeometry, contact: str, ring: GroovedRing, rate: float) -> ProfileSurface:
    """Potential contact surface of ``contact`` (spec §2.3): the groove circle of ``ring`` in the plane X = 0,
    s = 0 on the line through the groove centre parallel to e_z, +s towards +e_y, rolling direction
    x_j = -sign(rate) X with ``rate`` = omega_j - omega_m."""
    G = ring.groove_centre(Z)
    sign = 1.0 if contact == "inner" else -1.0          # the contact lies on the -e_z side of G (inner), +e_z (outer)
    reference = G - sign * ring.groove_radius * b.e_z
    x_dir = -np.sign(rate) * X if rate != 0 else X
    return groove_profile(ring, reference, b.e_y, x_dir)


@dataclass(frozen=True)
class ContactInput:
    """Everything the conformal contact solver needs for one contact at one state (spec §2.3-2.5): the
    developed ``grid``, the undeformed distance ``gap`` h (m, (nx, ns)), the rigid ``slip`` (m/s), the rolling
    ``speeds`` (V(s), V_ref, kappa), the bodies and the ring's rate omega_j - omega_m (rad/s)."""

    grid: DevelopedGrid
    gap: np.ndarray
    slip: RigidSlip
    speeds: RollingSpeeds
    roller: CrownedBody
    ring: GroovedRing
    rate: float
    omega_roller: float


def contact_input(b: BearingGeometry, pose: Pose, contact: str, omega_m: float, omega_R: float,
                  omega_inner: float, omega_outer: float, half_x: float, half_s: float, nx: int, ns: int,
                  s_centre: float = 0.0, inner_ring_shift=(0.0, 0.0, 0.0)) -> ContactInput:
    """Grid, exact gap, rigid slip and rolling speeds of ``contact`` for roller ``pose``, cage speed omega_m and
    roller spin omega_R (rad/s, in B), ring speeds omega_I, omega_E (rad/s) and a ring displacement
    ``inner_ring_shift`` (m, 3-vector; the prescribed approach of the inner ring, spec §2.2: the outer ring is
    fixed, so the shift acts on the inner contact only). Grid: nx x ns elements over
    x in +-half_x, s in s_centre +- half_s (m). V_ref = V(s_centre)."""
    roller = roller_body(b, pose)
    ring = ring_body(b, contact, inner_ring_shift if contact == "inner" else (0.0, 0.0, 0.0))
    rate = ring_rate(contact, omega_m, omega_inner, omega_outer)
    dg = developed_grid(contact_surface(b, contact, ring, rate), half_x, half_s, nx, ns, s_centre)
    return ContactInput(dg, undeformed_distance(dg, roller, ring), rigid_slip(dg, roller, omega_R, ring, rate),
                        rolling_speeds(dg, roller, omega_R, ring, rate), roller, ring, rate, omega_R)


# ---- speeds and inertia loads ------------------------------------------------------------------------------------
def nominal_speeds(b: BearingGeometry, omega_inner: float, omega_outer: float = 0.0) -> tuple[float, float]:
    """(omega_m,o, omega_R,o) (rad/s) for rolling without slip at the nominal points (seed 000 eqs 2-3):
    omega_m = (r_I omega_I + r_E omega_E)/(r_I + r_E), omega_R = -2 r_I r_E (omega_I - omega_E)/(D (r_I + r_E))
    with r_I, r_E the nominal rolling radii (eq 1)."""
    r = b.rolling_radii
    ri, re = r["inner"], r["outer"]
    om = (ri * omega_inner + re * omega_outer) / (ri + re)
    orr = -2.0 * ri * re * (omega_inner - omega_outer) / (b.roller_diameter * (ri + re))
    return float(om), float(orr)


def centrifugal_force(b: BearingGeometry, pose: Pose, omega_m: float) -> np.ndarray:
    """F_c = m_R omega_m^2 (C - ((C.Y) Y)) (N, in B; radial, outward; 2.948 N at the nominal pose, spec §3)."""
    C = roller_centre(b, pose)
    return b.roller_mass * omega_m ** 2 * (C - (C @ Y) * Y)


def gyroscopic_moment(b: BearingGeometry, pose: Pose, omega_m: float, omega_R: float,
                      axial_inertia: float | None = None, transverse_inertia: float | None = None) -> np.ndarray:
    """d'Alembert gyroscopic moment on the roller (N m, in B; spec §3 item 3).

    Default (the paper's usage, E9): M_g = -omega_m Y x (I_R omega_R v), I_R = ``roller_inertia``: 5.880 N mm
    along +X at the nominal state. With ``axial_inertia`` I_a and ``transverse_inertia`` I_t the full rigid-body
    form -omega_m Y x (I_a (Omega.v) v + I_t (Omega - (Omega.v) v)), Omega = omega_m Y + omega_R v."""
    v = roller_frame(b, pose)[1]
    if axial_inertia is None and transverse_inertia is None:
        return -omega_m * np.cross(Y, b.roller_inertia * omega_R * v)
    ia = b.roller_inertia if axial_inertia is None else axial_inertia
    it = b.roller_inertia if transverse_inertia is None else transverse_inertia
    Om = omega_m * Y + omega_R * v
    L = ia * (Om @ v) * v + it * (Om - (Om @ v) * v)
    return -omega_m * np.cross(Y, L)


def hertz_radii(b: BearingGeometry) -> dict[str, tuple[float, float]]:
    """(Rx, Ry) (m) of the nominal contacts: 1/Rx = 2/D +/- cos a / r_roll, 1/Ry = 1/R - 1/r_g (spec §1.2; the
    same numbers as :func:`femcheck.geometry.srb.radii`)."""
    r = b.rolling_radii
    D, R, ca = b.roller_diameter, b.crown_radius, np.cos(b.contact_angle)
    return {"inner": (1.0 / (2.0 / D + ca / r["inner"]), 1.0 / (1.0 / R - 1.0 / b.groove_radius_inner)),
            "outer": (1.0 / (2.0 / D - ca / r["outer"]), 1.0 / (1.0 / R - 1.0 / b.groove_radius_outer))}


SEED_000 = BearingGeometry(0.0198, 0.1003, 0.103, 0.1024, float(np.radians(11.5)))
"""Seed 000 Table 1 (D, R, r_I, r_E, alpha) with m_R = 65.6 g, I_R = 5.87 kg mm^2 (§2) and L_R = 27 mm."""

OMEGA_INNER_SEED_000 = 476.2 * 2.0 * np.pi / 60.0
"""Inner ring speed of seed 000 §2: 476.2 rpm (rad/s); the outer ring is fixed."""
