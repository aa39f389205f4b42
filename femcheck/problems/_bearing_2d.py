"""The bearing_load kind's 2D section models' inputs: the plane-strain FE's and the condensed model's numerics keys
(schema and defaults) and the 2D section (:class:`femcheck.fem.bearing2d.BearingSection`) built from a scene."""
from __future__ import annotations

from typing import Any

from ..materials import Elastic
from ..scene import Key

SCHEMA_2D: dict[str, Key] = {
    "numerics.fem_levels": Key("int", "-", "FE mesh levels (>= 3 for certificates)", lo=1, hi=6, lo_closed=True,
                               hi_closed=True),
    "numerics.fem_ratio": Key("float", "-", "FE refinement ratio between levels", lo=1.1, hi=2.0, lo_closed=True,
                              hi_closed=True),
    "numerics.fem_h_contact": Key("float", "b", "coarsest contact-zone spacing / Hertz half-width", lo=0.01,
                                  hi=1.0, lo_closed=True, hi_closed=True),
    "numerics.fem_zone": Key("float", "b", "contact-zone half-length / Hertz half-width", lo=1.2, hi=10.0,
                             lo_closed=True, hi_closed=True),
    "numerics.fem_grading": Key("float", "-", "coarsest mesh growth per unit distance", lo=0.05, hi=2.0,
                                lo_closed=True, hi_closed=True),
    "numerics.fem_h_max_ring": Key("float", "t", "coarsest largest ring element / ring thickness", lo=0.05, hi=2.0,
                                   lo_closed=True, hi_closed=True),
    "numerics.fem_h_max_roller": Key("float", "R", "coarsest largest roller element / roller radius", lo=0.02,
                                     hi=1.0, lo_closed=True, hi_closed=True),
    "numerics.fem_order": Key("int", "-", "element order", lo=1, hi=2, lo_closed=True, hi_closed=True),
    "numerics.fem_method": Key("str", "-", "contact algorithm", choices=("active_set", "penalty")),
    "numerics.fem_penalty": Key("float", "-", "penalty stiffness / (E* w / h)", lo=1.0, hi=1e9, hi_closed=True),
    "numerics.fem_similarity": Key("str", "-", "rollers: one condensed and rotated, or all meshed as one body",
                                   choices=("rotate", "mesh_all")),
    "numerics.condensed_h_contact": Key("float", "b", "condensed model: patch-zone spacing / b_0", lo=0.02, hi=1.0,
                                        lo_closed=True, hi_closed=True),
    "numerics.condensed_roller": Key("str", "-", "condensed model: roller compliance",
                                     choices=("closed_form", "fem")),
}

DEFAULTS_2D: dict[str, Any] = {
    "numerics.fem_levels": 3,
    "numerics.fem_ratio": 2.0**0.5,
    "numerics.fem_h_contact": 0.25 / 2**0.5,
    "numerics.fem_zone": 2.5,
    "numerics.fem_grading": 0.6,
    "numerics.fem_h_max_ring": 0.5,
    "numerics.fem_h_max_roller": 0.25,
    "numerics.fem_order": 2,
    "numerics.fem_method": "active_set",
    "numerics.fem_penalty": 1.0e3,
    "numerics.fem_similarity": "rotate",
    "numerics.condensed_h_contact": 0.25,
    "numerics.condensed_roller": "closed_form",
}


def section(params: dict[str, Any]):
    """The 2D section (:class:`femcheck.fem.bearing2d.BearingSection`) of a single-row scene."""
    from ..fem.bearing2d import BearingSection

    rings = Elastic(params.get("materials.rings.E", 1.0), params.get("materials.rings.nu", 0.0),
                    params["materials.rings.rigid"])
    return BearingSection(params["bearing.rollers"], 0.5 * params["geometry.roller_diameter"],
                          0.5 * params["geometry.inner_raceway_diameter"],
                          0.5 * params["geometry.outer_raceway_diameter"],
                          0.5 * params.get("geometry.bore_diameter", 0.0),
                          0.5 * params.get("geometry.outside_diameter", 0.0),
                          params["geometry.roller_length"], params["load.radial"], params["load.angle"],
                          Elastic(params["materials.rollers.E"], params["materials.rollers.nu"]), rings,
                          params["support.housing_half_angle"])
