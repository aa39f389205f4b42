"""2D (plane-strain) boundary-integral line contact: piecewise-constant pressure strips on a half-plane."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from .convolution import DCFFT
from .influence import half_plane_strip
from .polonsky_keer import NormalContactResult, polonsky_keer


@dataclass
class LineBEMSolution:
    """Cell centres ``x`` (m), cell width ``dx`` (m) and the normal-contact solution on them."""

    x: np.ndarray
    dx: float
    result: NormalContactResult


def solve_line_contact(gap: Callable[[np.ndarray], np.ndarray], modulus: float, load_per_length: float,
                       half_domain: float, n_elements: int, tol: float = 1e-10,
                       max_iter: int = 2000) -> LineBEMSolution:
    """Frictionless line contact of two bodies with initial gap ``gap(x)`` (m) and combined modulus E* (Pa)
    under ``load_per_length`` (N/m), on ``n_elements`` strips covering [-half_domain, half_domain] (m).

    Influence coefficients: :func:`femcheck.bem.influence.half_plane_strip` (exact for uniform strips);
    convolution by DC-FFT; contact by Polonsky-Keer CG with the load constraint.
    """
    dx = 2.0 * half_domain / n_elements
    x = -half_domain + (np.arange(n_elements) + 0.5) * dx
    datum = 8.0 * half_domain  # > domain length: keeps the log kernel positive definite (see influence)
    op = DCFFT(lambda t: half_plane_strip(t, dx, modulus, datum), (n_elements,), (dx,))
    res = polonsky_keer(gap(x), op, load_per_length, dx, tol=tol, max_iter=max_iter)
    return LineBEMSolution(x, dx, res)
