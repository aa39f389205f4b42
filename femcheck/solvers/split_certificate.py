"""One certificate from several discretisations refined apart (split influence coefficients: the FE correction's
mesh and grid, the far field, the contact grid; :mod:`femcheck.fem.compliance_split`).

Each part is certified on its own levels with the others held fixed (:mod:`femcheck.solvers.convergence`); the
combined value is the base part's (the contact grid, solved at the finest correction) plus the other parts'
extrapolation steps, each from the level the base part's levels were solved on (the correction's finest; the far
field's first: every other level keeps the far field's first mesh), and its relative error estimate the sum of the
parts' absolute estimates over the combined value: GCI bounds of separate discretisations add (Roache 1998 §5.9
applied part by part; the cross term, the correction's effect changing with the contact grid, is carried by the base
part's levels, which are solved with the finest correction in place). Certified when every part is and the estimate
is below the value itself (a bound larger than the value leaves it unresolved, whatever floors certified the parts).
"""
from __future__ import annotations

import numpy as np

from .convergence import Certificate, certify, certify_formal

# Formal order of a finite-body correction on its grid: the linear (tent) spreading of the contact tractions onto
# the correction cells and the harmonic near-field fill are second order (the cubic splines fourth); certify
# accepts observed orders within a factor 2 of it and extrapolates at the observed order.
CORRECTION_ORDER = 2.0
# Correction and far-field levels re-mesh the bodies: unstructured re-meshing scatters local FE quantities by
# 0.05-0.15 % from level to level (hertz-point, docs/kinds/point_contact.md); changes below 0.2 % are that scatter,
# no order can be observed in them (certify's floor), and the estimate is 3 x the larger of the last two changes.
REMESH_SCATTER = 2e-3


def scatter_scales(count: int) -> list[float]:
    """The element-size factors of the ``count`` re-meshed copies of the coarsest correction: 1 + 0.01 (j + 1),
    the contact-line element size scaled by 1 %, 2 %, ...: enough for Gmsh to move every element, far too little to
    change the discretisation's error (its first-order change is 1 % of one level step)."""
    return [1.0 + 0.01 * (j + 1) for j in range(int(count))]


def remesh_floor(samples: list[dict[str, float]], q: str) -> float:
    """The floor of a re-meshed family for ``q``: the larger of the assumed re-meshing scatter (REMESH_SCATTER)
    and the spread (max - min, relative to the first) of ``q`` over ``samples``, one level solved on several
    meshes (the local quantities of a contact, a peak or a count of cells, scatter by more than 0.2 %)."""
    v = np.array([s[q] for s in samples], dtype=float)
    if v.size < 2 or v[0] == 0:
        return REMESH_SCATTER
    return max(REMESH_SCATTER, float(np.ptp(v) / abs(v[0])))


def combine(parts: dict[str, Certificate], base: str = "contact grid",
            solved_at: dict[str, float] | None = None) -> Certificate:
    """The combined certificate of ``parts`` (name -> certificate of one quantity; module docstring).
    ``solved_at``: per part, its level's value that the base part's levels were solved with (default: the part's
    finest level), from which the part's extrapolation step is taken."""
    grid = parts[base]
    at = solved_at or {}
    value = grid.value + sum(c.value - at.get(name, c.finest) for name, c in parts.items() if name != base)
    scale = abs(value) if value else 1.0
    err = sum(c.error_estimate * abs(c.value) for c in parts.values()) / scale
    note = "; ".join(f"{name}: {'certified' if c.certified else 'not certified'} ({c.note}; estimate "
                     f"{c.error_estimate:.2%})" for name, c in parts.items())
    # every part may be certified by a floor (re-meshing, lattice phases) yet the sum bound the value by more than
    # itself (an adhesion fraction of a few cells: lattice spread 290 %): a value not resolved is not certified
    resolved = err < 1.0
    if not resolved:
        note = f"the combined estimate {err:.0%} is not below the value itself: not resolved; {note}"
    return Certificate(float(value), grid.finest, grid.order, float(err),
                       resolved and all(c.certified for c in parts.values()), note)


def grid_certificate(h: list[float], q: list[float], spreads: list[float], formal_order: float) -> Certificate:
    """The contact grid's part for a quantity whose levels are lattice-phase means (:mod:`femcheck.cect.lattice_phase`)
    with phase spreads ``spreads`` (max - min over the phases, same units as ``q``): :func:`certify_formal` at the
    grid's ``formal_order``; where that finds no order, the changes between the last three levels are held
    against the lattice's own resolution, the largest relative phase spread of those levels (a single phase can
    lie that far from the mean it enters): changes below it are lattice residue, no order can be observed in
    them, and the quantity is certified as converged (certify's floor; estimate 3 x the larger change)."""
    c = certify_formal(h, q, formal_order)
    if c.certified or len(q) < 3:
        return c
    floor = max(abs(s) / abs(v) for s, v in zip(spreads[-3:], q[-3:]) if v != 0) if any(q[-3:]) else 0.0
    f = certify(h, q, formal_order, floor=floor)
    if f.certified:
        return Certificate(f.value, f.finest, f.order, f.error_estimate, True,
                           f.note.replace("below the solvers' and estimators' resolution",
                                          "below the lattice phases' spread"))
    return c
