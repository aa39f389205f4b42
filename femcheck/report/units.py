"""SI unit of every quantity shown in a report or a summary (quantity -> unit).

Names follow DESIGN.md. A quantity of one contact among several carries its contact as a suffix
(``p_max_inner``, ``half_width_al2o3``): the unit is that of the base name. Forces and moments are per unit length
in plane (2D) scenes, which give their load as ``load.per_length``. A kind may declare units of its own quantities
in ``UNITS`` (name -> unit); it is consulted first.
"""
from __future__ import annotations

from typing import Any

UNITS: dict[str, str] = {
    "p_max": "Pa", "p_centre": "Pa", "p_end": "Pa", "additional_pressure": "Pa",
    "von_mises_max": "Pa", "tau_max": "Pa", "tau_xz_max": "Pa",
    "half_width": "m", "semi_axis_x": "m", "semi_axis_y": "m", "approach": "m", "edge_peak_y": "m",
    "von_mises_max_depth": "m", "tau_max_depth": "m", "tau_xz_max_depth": "m",
    "shift": "m", "stick_radius": "m", "stick_half_width": "m", "adhesion_length": "m",
    "contact_area": "m²",
    "total_force": "N", "creep_force_x": "N", "creep_force_y": "N",
    "spin_moment": "N·m",
    "adhesion_fraction": "-", "indent_depth_ratio": "-",
    "pressure_profile_l2": "- (relative)", "pressure_profile_max": "- (relative)",
}
PER_LENGTH = {"N": "N/m", "N·m": "N·m/m", "m²": "m²/m"}


def unit_of(quantity: str, params: dict[str, Any] | None = None, kind: str = "") -> str:
    """SI unit of ``quantity`` (``?`` when no table knows it: the kind should declare it in ``UNITS``)."""
    declared: dict[str, str] = {}
    if kind:
        from ..problems import problem

        try:
            declared = getattr(problem(kind), "UNITS", {})
        except (KeyError, ValueError):    # a toy kind in a test, or a kind this version does not know
            declared = {}
    for table in (declared, UNITS):
        name = quantity.partition("@")[0]
        while name:
            if name in table:
                unit = table[name]
                plane = params is not None and "load.per_length" in params
                return PER_LENGTH.get(unit, unit) if plane else unit
            name = name.rpartition("_")[0]        # p_max_inner -> p_max
    return "?"
