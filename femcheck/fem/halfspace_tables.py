"""Boussinesq-Cerruti influence tables in the layout of the FE compliance tables (:mod:`femcheck.fem.body_compliance`),
for the checks of the FE rolling reference (the planar large-body limit of the FE coefficients, the FE contact
solver against the planar exact theory on identical discrete equations) and as the analytic part of the split
finite-body coefficients (:mod:`femcheck.fem.compliance_split`). The pure FE reference never uses them.

T[i, j, k, I, J] = A_ij(lag0 + k dx, s_I - s_J) of :func:`femcheck.cect.influence.influence` (collocation at the
receiving element's centre, uniform traction on the source element; components x, s -> y, n -> z).
"""
from __future__ import annotations

import numpy as np

from ..cect.influence import CombinedConstants
from ..cect.influence_conformal import AXES, kernel
from .contact_grid import ContactGrid
from .rolling_contact import RelativeCompliance

def halfspace_table(receiver: ContactGrid, source: ContactGrid, constants: CombinedConstants,
                    option: str = "halfspace") -> tuple[float, np.ndarray]:
    """(lag0, T) with T (3, 3, n_r + n_s, ns_r, ns_s) in m/Pa: the developed half-space (s as a planar coordinate)
    or, with ``option`` "blanco" / "rotated_response", the angle-corrected coefficients of
    :func:`femcheck.cect.influence_conformal.kernel` on the receiver's profile radius."""
    lag0 = float(receiver.x[0] - source.x[-1])
    lags = lag0 + receiver.dx * np.arange(receiver.nx + source.nx)
    ds = receiver.s[:, None] - source.s[None, :]
    T = np.empty((3, 3, lags.size, receiver.ns, source.ns))
    for i in range(3):
        for j in range(3):
            T[i, j] = kernel(AXES[i], AXES[j], lags[:, None, None], ds[None], receiver.dx, receiver.ds, constants,
                             option, receiver.radius)
    return lag0, T


def halfspace_compliance(grids: dict[str, ContactGrid], constants: CombinedConstants) -> RelativeCompliance:
    """Half-space relative compliance of each contact on its own grid (no cross influence between contacts)."""
    tables, lag0 = {}, {}
    for c, g in grids.items():
        lag0[(c, c)], tables[(c, c)] = halfspace_table(g, g, constants)
        for d, h in grids.items():
            if d != c:
                lag0[(c, d)] = float(g.x[0] - h.x[-1])
                tables[(c, d)] = np.zeros((3, 3, g.nx + h.nx, g.ns, h.ns))
    return RelativeCompliance(dict(grids), tables, lag0, {"model": "Boussinesq-Cerruti half-space"})
