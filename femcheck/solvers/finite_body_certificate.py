"""The three-part certificate of a finite-body reference (split influence coefficients,
:mod:`femcheck.fem.compliance_split`): the FE correction's levels, the far field's levels and the contact grid's
lattice-phase levels, each certified with the others held fixed, combined per quantity by
:func:`femcheck.solvers.split_certificate.combine`.

The part rules:

- **Correction**: :func:`correction_certificate`, at the correction's formal order with the measured re-meshing
  floor.
- **Far field**: :func:`femcheck.solvers.convergence.certify` (no expected order: the grading and the largest
  element are refined together, no formal order applies) with the same floor.
- **Contact grid**: :func:`femcheck.solvers.split_certificate.grid_certificate` at the contact solver's order.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Sequence

from .convergence import Certificate, certify, certify_formal
from .split_certificate import CORRECTION_ORDER, combine, grid_certificate, remesh_floor


def correction_certificate(h: Sequence[float], q: Sequence[float], floor: float) -> Certificate:
    """The correction part of one quantity over levels of relative size ``h`` (coarse to fine).

    :func:`certify` at :data:`CORRECTION_ORDER` with the re-meshing ``floor``. Levels that converge monotonically
    *faster* than the formal order (a correction whose near-field error is gone after its first step: changes of
    -0.94 % then -0.06 %) are extrapolated at the formal order (:func:`certify_formal`; Roache 1998 §5.9: never a
    higher order than the scheme has). The estimate is never below ``floor``: every level is one unstructured mesh,
    and the finest carries the re-meshing scatter measured on the coarsest, which no extrapolation removes."""
    c = certify(list(h), list(q), CORRECTION_ORDER, floor=floor)
    if not c.certified and c.order is not None and c.order > CORRECTION_ORDER:
        c = certify_formal(list(h), list(q), CORRECTION_ORDER)
    if c.certified and c.error_estimate < floor:
        c = replace(c, error_estimate=float(floor),
                    note=f"{c.note}; estimate raised to the re-meshing floor {floor:.1e}")
    return c


def certify_parts(names: Sequence[str], corr_levels: list[dict], far_levels: list[dict],
                  scatter_levels: list[dict], grid_levels: list[dict], grid_order: float) -> dict:
    """Certificates of ``names`` from the three families (level dicts holding ``h`` and the quantities; the
    grid levels also ``<q>_phase_spread``). The re-meshing floor of each quantity is measured on the far field's
    first level and ``scatter_levels`` (the same mesh re-meshed). Without far-field levels the far-field part is
    reported missing and no quantity is certified. Returns the ``stats`` entries of the reference:
    ``certificates`` (combined), the per-part certificates and ``remesh_floors``; ``combined`` holds the
    :class:`Certificate` objects."""
    floors = {q: remesh_floor((far_levels or corr_levels)[:1] + list(scatter_levels), q) for q in names}
    hs = {part: [lv["h"] for lv in lvs] for part, lvs in (("corr", corr_levels), ("far", far_levels),
                                                             ("grid", grid_levels))}
    c_corr = {q: correction_certificate(hs["corr"], [lv[q] for lv in corr_levels], floors[q]) for q in names}
    # no far-field levels (a coarse re-solve of level 0 only): the part is missing, so nothing is certified
    c_far = {q: (certify(hs["far"], [lv[q] for lv in far_levels], floor=floors[q]) if far_levels else
                 Certificate(0.0, 0.0, None, 0.0, False, "no far-field levels solved")) for q in names}
    c_grid = {q: grid_certificate(hs["grid"], [lv[q] for lv in grid_levels],
                                  [lv[f"{q}_phase_spread"] for lv in grid_levels], grid_order) for q in names}
    combined = {q: combine({"contact grid": c_grid[q], "correction": c_corr[q], "far field": c_far[q]})
                for q in names}

    def as_dicts(certs: dict[str, Certificate]) -> dict:
        return {q: c.as_dict() for q, c in certs.items()}

    return {"combined": combined, "certificates": as_dicts(combined), "correction_certificates": as_dicts(c_corr),
            "far_field_certificates": as_dicts(c_far), "grid_certificates": as_dicts(c_grid),
            "remesh_floors": floors}
