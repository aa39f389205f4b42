"""FE compliances of a crowned roller (or wheel) and its grooved rings on the contacts' developed grids: the
meshes, the body compliances and their combination into the relative tables u = u(roller) - u(ring)
(spec srb-rolling §8.2 items 1-2).

Frame (the "roller frame" of the FE model, m): roller centre at the origin, roller axis = y, contacts in the plane
x = 0 (at z = -rho for an inner-type contact, +rho for an outer-type one), rolling direction +-x. Bodies:
- :class:`RollerBody`: rolling radius r (at the crown apex), crown radius R, length (whole roller, both contact
  zones meshed; free body: inertia relief and mean axes, :mod:`femcheck.fem.body_compliance`);
- :class:`RingBody` per contact: the groove circle (centre G, radius r_g) in the plane x = 0 - the same circle as
  the contact's developed grid (spec §2.3) - and the ring axis (point, direction; None for a straight rail);
  segment length along x, depth below the groove, lateral half-extent along s; clamped on its bottom and on its
  far end face x = length.
Every body is a half model x >= 0 meshed as a section extruded in layers (:mod:`femcheck.meshes.layered_bodies`)
with one (or ``layers_per_cell``) layer(s) per influence cell along s, aligned with the cell edges; the section is
fine (``h_contact`` x dx) at the contact line and grows by ``grading`` per unit distance up to ``h_max``.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..materials import Elastic
from ..meshes.layered_bodies import CrownedSpec, RingSpec, cell_layers, crown_rho, crowned_body, grooved_ring
from .body_compliance import BodyModel, body_compliance
from .contact_grid import ContactGrid
from .rolling_contact import RelativeCompliance, relative_compliance


@dataclass(frozen=True)
class RollerBody:
    rolling_radius: float
    crown_radius: float
    length: float
    material: Elastic


@dataclass(frozen=True)
class RingBody:
    """``axis_point``/``axis_dir`` in the roller frame (None: straight rail along x); ``length_x`` (m), ``depth``
    (m), ``half_s`` (m, lateral half-extent along the groove from the grid's reference point)."""

    groove_centre: tuple[float, float, float]
    groove_radius: float
    axis_point: tuple[float, float, float] | None
    axis_dir: tuple[float, float, float] | None
    material: Elastic
    length_x: float
    depth: float
    half_s: float


@dataclass(frozen=True)
class MeshSettings:
    """``h_contact`` (x dx, the section's element size at the contact line), ``grading`` (-), ``h_max`` (m),
    ``layers_per_cell`` (along s), element ``order`` (1, 2)."""

    h_contact: float = 0.5
    grading: float = 0.3
    h_max: float = 2e-3
    layers_per_cell: int = 1
    order: int = 2


def _edges(grid: ContactGrid) -> np.ndarray:
    return grid.s[0] - 0.5 * grid.ds + grid.ds * np.arange(grid.ns + 1)


def roller_mesh(roller: RollerBody, grids: dict[str, ContactGrid], mesh: MeshSettings):
    dx = next(iter(grids.values())).dx
    ys = np.concatenate([grid.profile_point(_edges(grid))[:, 1] for grid in grids.values()])
    half = 0.5 * roller.length
    if ys.min() < -half or ys.max() > half:
        raise ValueError("a contact grid extends beyond the roller's length")
    zones = tuple(float(np.sign(grid.profile_point(0.0)[2])) for grid in grids.values())
    layers = cell_layers(_merge(ys, min(g.ds for g in grids.values())), -half, half, mesh.layers_per_cell)
    spec = CrownedSpec(roller.rolling_radius, roller.crown_radius, half, zones, layers, mesh.h_contact * dx,
                       mesh.grading, min(mesh.h_max, 0.5 * roller.rolling_radius), (0.5 * dx,))
    return crowned_body(spec)


def _merge(values: np.ndarray, ds: float) -> np.ndarray:
    """Sorted values with near-duplicates merged into their mean: the cell edges of several grids mapped onto the
    roller's axis. Grids on a common s-lattice (ds, centres on multiples of ds) differ there only by the
    profiles' s^3/(6 r_g^2) (inner and outer grooves of seed 000: <= 2 % of ds): edges closer than 0.1 ds are one
    layer boundary, so the layers do not double with slivers; element faces then follow each grid's cell edges
    to within that."""
    v = np.sort(values)
    group = np.concatenate([[0], np.cumsum(np.diff(v) > 0.1 * ds)])
    return np.bincount(group, weights=v) / np.bincount(group)


def ring_mesh(ring: RingBody, grid: ContactGrid, mesh: MeshSettings):
    if abs(grid.radius - ring.groove_radius) > 1e-9 * ring.groove_radius or \
            np.linalg.norm(grid.centre - np.asarray(ring.groove_centre)) > 1e-9 * ring.groove_radius:
        raise ValueError("the contact grid's profile must be the ring's groove circle")
    edges = _edges(grid)
    if edges[0] < -ring.half_s or edges[-1] > ring.half_s:
        raise ValueError("a contact grid extends beyond the ring segment")
    layers = cell_layers(edges, -ring.half_s, ring.half_s, mesh.layers_per_cell)
    spec = RingSpec(tuple(float(v) for v in grid.centre), ring.groove_radius, tuple(float(v) for v in grid.m0),
                    tuple(float(v) for v in grid.tau0), ring.axis_point, ring.axis_dir, ring.length_x, ring.depth,
                    layers, mesh.h_contact * grid.dx, mesh.grading, mesh.h_max, (0.5 * grid.dx,))
    return grooved_ring(spec)


def fe_compliance(roller: RollerBody, rings: dict[str, RingBody], grids: dict[str, ContactGrid],
                  mesh: MeshSettings = MeshSettings(), backend: str = "auto", progress=None) -> RelativeCompliance:
    """Relative compliance tables of the contacts ``grids`` (name -> grid in the roller frame; the same names
    as ``rings``): roller with every contact zone (cross influence included), each ring with its own.
    ``stats`` holds per body the mesh size, DOFs, factorisation and solve times."""
    t0 = time.perf_counter()
    if progress:
        progress("FE rolling compliance: meshing the roller")
    rm = roller_mesh(roller, grids, mesh)
    t_mesh = time.perf_counter() - t0
    thickness = 2.0 * float(crown_rho(0.5 * roller.length, roller.rolling_radius, roller.crown_radius))
    c1 = body_compliance(BodyModel("roller", rm, roller.material, (), True, mesh.order, thickness), grids, backend,
                         progress=progress)
    c2 = {}
    for name, ring in rings.items():
        t = time.perf_counter()
        if progress:
            progress(f"FE rolling compliance: meshing the {name} ring")
        gm = ring_mesh(ring, grids[name], mesh)
        t_mesh += time.perf_counter() - t
        c2[name] = body_compliance(BodyModel(f"ring_{name}", gm, ring.material, ("bottom", "xend"), False,
                                             mesh.order), {name: grids[name]}, backend, progress=progress)
    out = relative_compliance(c1, c2, grids)
    out.stats["mesh_s"] = t_mesh
    out.stats["total_s"] = time.perf_counter() - t0
    out.stats["n_dofs"] = int(c1.stats["n_dofs"] + sum(c.stats["n_dofs"] for c in c2.values()))
    return out
