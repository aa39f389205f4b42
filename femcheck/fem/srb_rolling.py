"""FE frictional rolling reference of seed 000's spherical roller bearing at a prescribed roller pose: the
two contacts of the roller coupled through the roller's FE compliance (spec srb-rolling §8.2 items 2-3). The
roller equilibrium (its own Newton over the pose) calls :func:`solve_contacts` with ICs fixed
(:func:`compliance` once per grid).

Frame: the reference roller frame {x, y, z} of spec §2.1 at the nominal pose (origin C0, e_x = X, e_y the nominal
roller axis towards the bearing mid-plane, e_z the nominal contact normal from the bearing axis outwards), m.
With r = D/2: bearing centre O = -(r_E - r) e_z, bearing axis Y = cos(a) e_y - sin(a) e_z; outer groove centre
G_E = O, inner groove centre G_I = (r_I - r) e_z; inner contact at -r e_z (n into the roller = +e_z), outer at
+r e_z (n = -e_z); profiles: the groove circles, s = 0 on the z axis, t(0) = +e_y; rolling directions
x_I = -e_x, x_E = +e_x (omega_I > omega_m > 0 = omega_E, spec §2.3). Bodies: the whole roller (L_R = 27 mm by
default, spec §1.2) and one ring segment per contact (x in +-5 mm, s in +-15 mm, depth 10 mm below the groove,
clamped at its bottom and far ends; the rings' sections are not in the paper).

Inputs per contact (:class:`femcheck.fem.contact_grid.ContactInput` on the grids of :func:`grids`): the exact gap
h(x, s) at the pose (m, the approach included), the rigid slip (w_x, w_s) (m/s) along e_x, t(s), V_ref (m/s) and
kappa(s). Outputs (:class:`femcheck.fem.rolling_contact.RollingSolution`): per contact pressures, tractions
(p_x, p_s on the roller along e_x, t(s)), adhesion map, slip velocities, power density, N*(s), F_x*(s), force and
moment on the roller about the roller centre C0 (or ``centre``) in the roller frame, frictional power.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..analytic import hertz
from ..materials import Elastic, effective_modulus
from .contact_grid import ContactGrid, ContactInput, centred_cells
from .rolling_compliance import MeshSettings, RelativeCompliance, RingBody, RollerBody, fe_compliance
from .rolling_contact import ExtraUnknown, RollingSolution, solve_rolling

CONTACTS = ("inner", "outer")
ROLLER_LENGTH = 0.027


def geometry(params: dict[str, Any]) -> dict[str, Any]:
    """Seed-000 geometry in the roller frame (module docstring) from the srb-normal keys
    (``geometry.roller_diameter``, ``crown_radius``, ``groove_radius_inner|outer``, ``contact_angle``)."""
    D, R = float(params["geometry.roller_diameter"]), float(params["geometry.crown_radius"])
    rI, rE = float(params["geometry.groove_radius_inner"]), float(params["geometry.groove_radius_outer"])
    al = float(params["geometry.contact_angle"])
    r = 0.5 * D
    O = np.array([0.0, 0.0, -(rE - r)])
    Y = np.array([0.0, np.cos(al), -np.sin(al)])
    return {"r": r, "R": R, "O": O, "Y": Y,
            "inner": {"G": np.array([0.0, 0.0, rI - r]), "rg": rI, "m0": np.array([0.0, 0.0, -1.0]),
                      "ex": np.array([-1.0, 0.0, 0.0])},
            "outer": {"G": O.copy(), "rg": rE, "m0": np.array([0.0, 0.0, 1.0]), "ex": np.array([1.0, 0.0, 0.0])}}


def hertz_estimates(params: dict[str, Any], load: float) -> dict[str, Any]:
    """Elliptic Hertz per contact at ``load`` (N) with the seed-000 radii (for grid sizes and starts)."""
    from ..geometry.srb import radii

    m = [Elastic(float(params[f"materials.{b}.E"]), float(params[f"materials.{b}.nu"])) for b in ("roller", "ring")]
    es = effective_modulus(*m)
    return {c: hertz.elliptic_contact(load, *radii(params)[c], es) for c in CONTACTS}


def grids(params: dict[str, Any], nx: int, ns: int, load: float, half_x: float = 1.35, half_s: float = 1.3,
          s_centre: dict[str, float] | None = None) -> dict[str, ContactGrid]:
    """Developed grids of both contacts with a common dx (FE cross tables need it) and a common ds on a common
    lattice (the roller's layers then follow the cells of both): x in +-half_x max(a_H), s in s_centre +- half_s
    max(b_H) (clipped to the roller length less one cell), each centre moved to the nearest multiple of ds (two
    lattices offset by a fraction of ds would double the roller's layers with slivers)."""
    g = geometry(params)
    hz = hertz_estimates(params, load)
    a = max(h.semi_axis_x for h in hz.values())
    b = max(h.semi_axis_y for h in hz.values())
    dx = 2.0 * half_x * a / nx
    half = min(half_s * b, 0.5 * ROLLER_LENGTH * ns / (ns + 1))
    ds = 2.0 * half / ns
    out = {}
    for c in CONTACTS:
        sc = 0.0 if s_centre is None else ds * round(float(s_centre.get(c, 0.0)) / ds)
        x = (np.arange(nx) - 0.5 * (nx - 1)) * dx
        out[c] = ContactGrid(g[c]["G"], g[c]["rg"], g[c]["m0"], [0.0, 1.0, 0.0], g[c]["ex"], x,
                             centred_cells(half, ns, sc), c)
    return out


def bodies(params: dict[str, Any], roller_length: float = ROLLER_LENGTH, ring_length_x: float = 5e-3,
           ring_depth: float = 10e-3, ring_half_s: float = 15e-3) -> tuple[RollerBody, dict[str, RingBody]]:
    g = geometry(params)
    mr = Elastic(float(params["materials.roller.E"]), float(params["materials.roller.nu"]))
    mg = Elastic(float(params["materials.ring.E"]), float(params["materials.ring.nu"]))
    roller = RollerBody(g["r"], g["R"], roller_length, mr)
    rings = {c: RingBody(tuple(float(v) for v in g[c]["G"]), g[c]["rg"], tuple(float(v) for v in g["O"]),
                         tuple(float(v) for v in g["Y"]), mg, ring_length_x, ring_depth, ring_half_s)
             for c in CONTACTS}
    return roller, rings


def compliance(params: dict[str, Any], contact_grids: dict[str, ContactGrid], mesh: MeshSettings = MeshSettings(),
               progress=None, **body_options) -> RelativeCompliance:
    """FE relative compliance tables of both contacts (roller cross influence included), computed once."""
    roller, rings = bodies(params, **body_options)
    return fe_compliance(roller, rings, contact_grids, mesh, progress=progress)


def solve_contacts(tables: RelativeCompliance, inputs: dict[str, ContactInput], mu: float,
                   extras: list[ExtraUnknown] = (), centre=(0.0, 0.0, 0.0), warm: RollingSolution | None = None,
                   tol: float = 1e-9) -> RollingSolution:
    """Both contacts at a prescribed pose (gaps, rigid slips, kappas in ``inputs``), coupled through the roller.
    ``extras``: optional unknowns (e.g. :func:`femcheck.fem.rolling_contact.approach_unknown` for load control of
    the ring approach); ``centre``: moment point (m, roller frame; the roller centre at the pose)."""
    return solve_rolling(tables, inputs, mu, list(extras), centre=centre, warm=warm, tol=tol)
