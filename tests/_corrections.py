"""Finite-body corrections with known kernels for the tests of the split influence coefficients."""
from __future__ import annotations

import numpy as np

from femcheck.fem import compliance_split as cs


def correction_with(grids, kernel):
    """A :class:`femcheck.fem.compliance_split.Correction` on ``grids`` whose kernels are zero except what
    ``kernel(kernels, lags, grids)`` writes into them (m/N)."""
    kernels, lags = {}, {}
    for r, gr in grids.items():
        for s, gs in grids.items():
            lags[(r, s)] = float(gr.x[0] - gs.x[-1]) + gr.dx * np.arange(gr.nx + gs.nx)
            kernels[(r, s)] = np.zeros((3, 3, gr.nx + gs.nx, gr.ns, gs.ns))
    kernel(kernels, lags, grids)
    return cs.Correction(dict(grids), kernels, lags, {})
