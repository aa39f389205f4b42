"""SI unit of every quantity shown in a report or a summary (quantity -> unit).

Names follow DESIGN.md. A quantity of one contact among several carries its contact as a suffix
(``p_max_inner``, ``half_width_al2o3``): the unit is that of the base name. Forces and moments are per unit length
in plane (2D) scenes, which give their load as ``load.per_length``. A kind may declare units of its own quantities
in ``UNITS`` (name -> unit); it is consulted first. A unit that depends on the scene's parameters (the risk
integral's, Pa^c m^(3-h)) is a function of them in ``PARAMETRIC``.
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
    # lubricated contacts: films, Moes' dimensionless film h / Rx U_M^-1/2, the load balance, the outlet spike
    "h_central": "m", "h_min": "m", "H_central_moes": "- (Moes H)", "H_min_moes": "- (Moes H)",
    "load_error": "- (relative)", "spike_x": "m",
    # rolling-contact fatigue life (seed 004 ch. 4): only ratios of lives are physical
    "stress_history_max": "Pa", "stress_ratio": "- (T_D / T_S)", "life_ratio": "- (L / L_smooth)",
    "fatigue_life": "- (life of 1 mm of track relative to the Weibull constant)",
    # rolling of bodies: creepage, angles, power
    "creepage_x": "-", "angle_span": "rad", "body_approach": "m", "contact_half_length_s": "m",
    "friction_power": "W",
}


def _risk_integral(params: dict[str, Any] | None) -> str:
    """Pa^c m^(3-h) (seed 004 eq 4.3), per metre of a line contact."""
    p = params or {}
    c, h = float(p.get("life.c", 8.0)), float(p.get("life.h", 0.0))
    return f"Pa^{c:g}·m^{3.0 - h:g}" + ("/m" if "load.per_length" in p else "")


PARAMETRIC = {"risk_integral": _risk_integral}
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
    for table in (declared, UNITS, PARAMETRIC):
        name = quantity.partition("@")[0]
        while name:
            if table is PARAMETRIC and name in table:
                return table[name](params)
            if name in table:
                unit = table[name]
                plane = params is not None and "load.per_length" in params
                return PER_LENGTH.get(unit, unit) if plane else unit
            name = name.rpartition("_")[0]        # p_max_inner -> p_max
    return "?"
