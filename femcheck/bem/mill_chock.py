"""A multi-row tapered roller bearing in an elastic chock on a flexible roll neck (spec bearing-load.md P3, seed 003's
four-row mill bearing, Table 3); SI units (m, N, rad).

The bearing's rows share the load according to three compliances, each condensed onto the ISO/TS 16281 slices
(row i, roller j, slice k; order as in :func:`femcheck.analytic.iso16281.row_kinematics`):

- ``C_chock``: the cups and the chock as one elastic thick cylinder r_o <= r <= R_c over the bearing width, clamped
  on its back surface over the support patch (a screw or load cell: |theta| <= theta_s about the load line,
  z_s0 <= z <= z_s1), loaded along the contact normals (:mod:`femcheck.fem.ring3d_compliance`, coarse 3D FE);
- ``C_cones``: the inner rings (cones) as one thick cylinder r_b <= r <= r_i with the bore clamped (they sit on the
  neck, whose deformation is the next term);
- ``C_neck``: the roll neck and body as a stepped Timoshenko beam clamped at the mill's symmetry plane (the
  strip's middle, where the roll neither rotates nor, relative to its rigid motion, deflects; seed 003 models the
  roll as a cantilever fixed at the roll-strip contact) (:mod:`femcheck.analytic.roll_neck`).

With the chock held at its support and the roll's section at the symmetry plane translating by
u = (delta_x, delta_y, delta_a) without rotating (symmetry), the slice deflections are

    d = G u - c - (C_chock + C_cones + C_neck) q(d),   G^T q = (F_r, 0, F_a),

solved by :func:`femcheck.bem.bearing_condensed3d.newton` from the rigid-ring start (C = 0). Two supports:

- clamped chock: the moment of the load about the bearing is taken by the chock's support and the roll's symmetry
  section, and where the rows' loads act follows from the two elastic bodies and the support's position;
- spherical seat at z_seat (``seat`` in :func:`solve`): the chock turns freely about it, so the relative tilt
  (theta_x, theta_y) joins u and the chock's moment balance puts the rows' resultant through the seat,
  G^T q = (F_r, 0, F_a, 0, z_seat F_r), with the axial reaction (the chock's end cover bearing on the cups' whole
  face) along the axis, so F_a adds no moment: the rigid 5-DOF model with its load line at z_seat, plus the
  bodies' elasticity.

Row shares: each row's force along the load line over their sum (%), as in seed 003 Table 3.

Model definition, stated: the chock is a cylinder (a real chock is a block; only the material behind the load
zone carries the load to the support); the cups are merged with it and the cones are one ring (press fits, no
separation between parts); the cup raceway is the cylinder r = r_o loaded along the cone's normal (a coarse
compliance of the body, not its contact); the rollers' own compliance is the ISO slice law's.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..analytic.bearing_load import solve_rigid
from ..analytic.iso16281 import Row, crown_drop, rigid_start, row_kinematics, slice_law, slice_positions
from ..analytic.roll_neck import neck_compliance
from ..fem.ring3d_compliance import RingCompliance, RingFE, ring_compliance
from ..materials import Elastic
from ..meshes.ring3d import RingMeshSpec
from .bearing_condensed3d import newton


@dataclass(frozen=True)
class MillBearing:
    """Rows of tapered rollers: Z ``rollers`` per row at ``row_z`` (m, row middles) with contact-angle directions
    ``signs`` (+-1), ``contact_angle`` alpha (rad), ``pitch_radius`` (m), roller effective ``length`` and mean
    ``diameter`` (m), ISO ``slices`` per roller, diametral ``clearance`` (m), ``crown`` "none" | "iso"; ring radii
    (m): cup raceway ``outer_race``, cone raceway ``inner_race``, cone ``bore``; bearing ``width`` (m)."""

    rollers: int
    row_z: tuple
    signs: tuple
    contact_angle: float
    pitch_radius: float
    length: float
    diameter: float
    slices: int
    outer_race: float
    inner_race: float
    bore: float
    width: float
    clearance: float = 0.0
    crown: str = "none"

    @property
    def rows(self) -> list[Row]:
        return [Row(float(z), self.contact_angle, int(s)) for z, s in zip(self.row_z, self.signs)]

    @property
    def psi(self) -> np.ndarray:
        return 2.0 * np.pi * np.arange(self.rollers) / self.rollers

    @property
    def x(self) -> np.ndarray:
        return slice_positions(self.length, self.slices)


@dataclass(frozen=True)
class Chock:
    """The cups + chock cylinder: ``outer_radius`` R_c (m), support patch ``support_z`` (z_s0, z_s1) (m) and
    ``support_half_angle`` theta_s (rad) about the load line, ``material``."""

    outer_radius: float
    support_z: tuple
    support_half_angle: float
    material: Elastic


@dataclass(frozen=True)
class RollNeck:
    """The roll as a stepped shaft (``segments``), clamped at ``z_clamp`` (m, the symmetry plane), ``material``."""

    segments: tuple
    z_clamp: float
    material: Elastic


@dataclass(frozen=True)
class Mesh3D:
    """Cell counts of the two 3D FE cylinders (times ``refine``): ``between`` cells from a patch edge to its sector
    edge, ``radial`` through the chock (the cones get ``radial_cones``), ``ends``/``gaps`` axially;
    ``patch_half_angle`` a_c (rad) of the raceway patches."""

    refine: int = 1
    patch_half_angle: float = 0.04
    between: int = 1
    radial: int = 2
    radial_cones: int = 1
    ends: int = 1
    gaps: int = 2


def _spec(b: MillBearing, r_race: float, r_back: float, mesh: Mesh3D, radial: int, breaks: tuple = ()) -> RingMeshSpec:
    return RingMeshSpec(r_race, r_back, b.width, b.length, b.rollers, b.slices, mesh.patch_half_angle,
                        refine=mesh.refine, between=mesh.between, ends=mesh.ends, radial=radial,
                        row_centres=tuple(float(z) for z in b.row_z), gaps=mesh.gaps, z_breaks=breaks)


def chock_compliance(b: MillBearing, chock: Chock, mesh: Mesh3D = Mesh3D()) -> RingCompliance:
    """C_chock (m/N) of the module doc."""
    spec = _spec(b, b.outer_race, chock.outer_radius, mesh, mesh.radial, tuple(chock.support_z))
    fe = RingFE(spec, chock.material, "housing", chock.support_half_angle, support_z=tuple(chock.support_z),
                contact_angle=b.contact_angle, row_signs=tuple(b.signs))
    return ring_compliance(fe)


def cone_compliance(b: MillBearing, material: Elastic, mesh: Mesh3D = Mesh3D()) -> RingCompliance:
    """C_cones (m/N) of the module doc: the cones' bore clamped all round."""
    spec = _spec(b, b.inner_race, b.bore, mesh, mesh.radial_cones)
    fe = RingFE(spec, material, "housing", np.pi, contact_angle=b.contact_angle, row_signs=tuple(b.signs))
    return ring_compliance(fe)


def roll_compliance(b: MillBearing, neck: RollNeck) -> np.ndarray:
    """C_neck (m/N) of the module doc."""
    return neck_compliance(b.psi, b.x, np.asarray(b.row_z, float), np.asarray(b.signs, float), b.contact_angle,
                           b.pitch_radius, list(neck.segments), neck.z_clamp, neck.material.E, neck.material.nu)


@dataclass
class MillResult:
    """``slice_loads`` q[i, j, k] (N), ``roller_loads`` Q[i, j] (N), ``row_radial`` (N: each row's force along the
    load line), ``row_shares`` (%), ``u`` (m, rad) with ``dofs``, Newton ``iterations``, scaled ``residual``,
    ``time_s``."""

    slice_loads: np.ndarray
    roller_loads: np.ndarray
    row_radial: np.ndarray
    row_shares: np.ndarray
    u: np.ndarray
    dofs: tuple
    iterations: int
    residual: float
    time_s: float


def solve(b: MillBearing, C: np.ndarray | None, radial_load: float, axial_load: float = 0.0,
          seat: float | None = None, tol: float = 1e-11) -> MillResult:
    """The equilibrium of the module doc for the total compliance ``C`` (None: rigid bodies). ``seat`` None: the
    chock is held at its support against rotation (u = (delta_x, delta_y, delta_a)); a position z_seat (m): the
    chock sits on a spherical seat there and turns freely about it, so the relative tilt (theta_x, theta_y) joins
    u and the rows' loads carry no moment about z_seat (G^T q = (F_r, 0, F_a, 0, z_seat F_r), as the rigid 5-DOF
    model with its load line at z_seat)."""
    t0 = time.perf_counter()
    xk = b.x
    drop = 2.0 * crown_drop(xk, b.length, b.diameter, tapered=True) if b.crown == "iso" else np.zeros(b.slices)
    axial = b.contact_angle != 0
    G, c, dofs = row_kinematics(b.rows, b.psi, xk, b.pitch_radius, b.clearance, drop, axial=axial,
                                tilt=seat is not None)
    law = slice_law(b.length, b.slices)
    F = np.zeros(G.shape[1])
    F[0] = radial_load
    if axial:
        F[2] = axial_load
    if seat is not None:
        F[dofs.index("theta_y")] = seat * radial_load
    u0 = rigid_start(law, len(dofs), radial_load, b.rollers, len(b.row_z), b.slices, b.clearance, b.contact_angle,
                     drop)
    rig = solve_rigid(G, c, law, F, u0)
    if C is None:
        d, u, it, res = rig.delta, rig.u, rig.iterations, rig.residual
    else:
        d, u, it, res = newton(G, c, law, F, np.asarray(C, float), rig, tol)
    q = law.load(d).reshape(len(b.row_z), b.rollers, b.slices)
    Q = q.sum(axis=2)
    row_radial = (Q * np.cos(b.psi)[None, :]).sum(axis=1) * np.cos(b.contact_angle)
    shares = 100.0 * row_radial / row_radial.sum()
    return MillResult(q, Q, row_radial, shares, u, dofs, it, res, time.perf_counter() - t0)
