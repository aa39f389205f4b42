"""The three-part certificate of a finite-body reference (split influence coefficients,
:mod:`femcheck.fem.compliance_split`): the FE correction's levels, the far field's levels and the contact grid's
lattice-phase levels, each certified with the others held fixed, combined per quantity by
:func:`femcheck.solvers.split_certificate.combine`.

The part rules (:func:`family_certificate`):

- **Correction**: at the correction's formal order with the measured re-meshing floor.
- **Far field**: no expected order (the grading and the largest element are refined together, no formal order
  applies), the same floor.
- **Contact grid**: :func:`femcheck.solvers.split_certificate.grid_certificate` at the contact solver's order.

Combined by :func:`~femcheck.solvers.split_certificate.combine`, the far field's step taken from its first level:
the correction and contact-grid levels are all solved on the far field's first mesh settings. A reference without a
far-field family (groove-rolling's) combines two parts.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Sequence

from .convergence import SAFETY_UNCERTIFIED, Certificate, certify, certify_formal
from .split_certificate import CORRECTION_ORDER, combine, grid_certificate, remesh_floor


def settled(h: Sequence[float], q: Sequence[float], floor: float) -> Certificate | None:
    """Levels converged after one step: the last change is below the re-meshing ``floor`` and at most 1/r^2 of the
    change before it (r the refinement ratio: the family contracts at least as fast as a second-order one). A change
    below the floor is re-meshing scatter, so its sign says nothing, and a step of +0.46 % followed by one of
    -0.02 % is convergence, not an oscillation. ``value`` = finest level (no order is observed, none is used),
    estimate the larger of the floor and 3 x the last change (certify's factor without a verified order).
    None when the levels do not show it."""
    if len(q) < 3:
        return None
    r = float(h[-2]) / float(h[-1])
    scale = abs(q[-1]) if q[-1] else 1.0
    before, last = abs(q[-2] - q[-3]) / scale, abs(q[-1] - q[-2]) / scale
    if not (last < floor and last * r ** CORRECTION_ORDER <= before):
        return None
    return Certificate(float(q[-1]), float(q[-1]), None, max(float(floor), SAFETY_UNCERTIFIED * last), True,
                       f"converged after one step: the last change {last:.1e} is below the re-meshing floor "
                       f"{floor:.1e} and at most 1/r^{CORRECTION_ORDER:g} of the one before ({before:.1e})")


def family_certificate(h: Sequence[float], q: Sequence[float], floor: float,
                       formal_order: float | None = CORRECTION_ORDER) -> Certificate:
    """One re-meshed family's part of a quantity over levels of relative size ``h`` (coarse to fine).

    :func:`certify` at ``formal_order`` (None: no expected order) with the re-meshing ``floor``. Levels that
    converge monotonically *faster* than the formal order (a correction whose near-field error is gone after its
    first step: changes of -0.94 % then -0.06 %) are extrapolated at the formal order (:func:`certify_formal`;
    Roache 1998 §5.9: never a higher order than the scheme has); levels whose last change is below the floor are
    :func:`settled`. The estimate is never below ``floor``: every level is one unstructured mesh, and the finest
    carries the re-meshing scatter measured on the coarsest, which no extrapolation removes."""
    h, q = [float(x) for x in h], [float(x) for x in q]
    c = certify(h, q, formal_order, floor=floor)
    if formal_order is not None and not c.certified and c.order is not None and c.order > formal_order:
        c = certify_formal(h, q, formal_order)
    if not c.certified:
        c = settled(h, q, floor) or c
    if c.certified and c.error_estimate < floor:
        c = replace(c, error_estimate=float(floor),
                    note=f"{c.note}; estimate raised to the re-meshing floor {floor:.1e}")
    return c


def correction_certificate(h: Sequence[float], q: Sequence[float], floor: float) -> Certificate:
    """The correction part (FE mesh and correction grid refined together) at :data:`CORRECTION_ORDER`."""
    return family_certificate(h, q, floor, CORRECTION_ORDER)


def certify_parts(names: Sequence[str], corr_levels: list[dict], far_levels: list[dict] | None,
                  scatter_levels: list[dict], grid_levels: list[dict], grid_order: float) -> dict:
    """Certificates of ``names`` from the families (level dicts holding ``h`` and the quantities; the grid levels
    also ``<q>_phase_spread``; the far field's first level is the correction's first, on which every other level is
    solved). The re-meshing floor of each quantity is measured on the correction's first level and
    ``scatter_levels`` (the same mesh re-meshed); :func:`correction_certificate` certifies the correction part.
    ``far_levels`` None: the reference has no far-field family (two parts); empty: its far-field part is missing (a
    coarse re-solve of level 0 only) and no quantity is certified. Returns the ``stats`` entries of the reference:
    ``certificates`` (combined), the per-part certificates and ``remesh_floors``; ``combined`` holds the
    :class:`Certificate` objects."""
    floors = {q: remesh_floor(corr_levels[:1] + list(scatter_levels), q) for q in names}
    h_corr, h_grid = [lv["h"] for lv in corr_levels], [lv["h"] for lv in grid_levels]
    c_corr = {q: correction_certificate(h_corr, [lv[q] for lv in corr_levels], floors[q]) for q in names}
    c_grid = {q: grid_certificate(h_grid, [lv[q] for lv in grid_levels],
                                  [lv[f"{q}_phase_spread"] for lv in grid_levels], grid_order) for q in names}
    parts = {q: {"contact grid": c_grid[q], "correction": c_corr[q]} for q in names}
    out: dict = {}
    if far_levels is not None:
        h_far = [lv["h"] for lv in far_levels]
        c_far = {q: (family_certificate(h_far, [lv[q] for lv in far_levels], floors[q], None) if far_levels else
                     Certificate(0.0, 0.0, None, 0.0, False, "no far-field levels solved")) for q in names}
        for q in names:
            parts[q]["far field"] = c_far[q]
        out["far_field_certificates"] = _as_dicts(c_far)
    # the far field's step from its first level: the correction's and the contact grid's levels are solved on it
    combined = {q: combine(parts[q], solved_at={"far field": far_levels[0][q]} if far_levels else None)
                for q in names}
    return {"combined": combined, "certificates": _as_dicts(combined), "correction_certificates": _as_dicts(c_corr),
            **out, "grid_certificates": _as_dicts(c_grid), "remesh_floors": floors}


def _as_dicts(certs: dict[str, Certificate]) -> dict:
    return {q: c.as_dict() for q, c in certs.items()}
