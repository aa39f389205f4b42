"""Grid levels for quantities that snap to the cell lattice: exactly geometric cell sizes and the mean over lattice
phases.

Kalker's exact theory on a fixed window (x in +-D a_H with n cells, D = ``numerics.conformal_domain_x``) puts the
contact's leading and trailing edges at a fraction of a cell that changes from grid to grid: the edge lies
e = n / (2 D) cells from the centre (a_H the Hertz semi-axis, the real edge close to it), and its phase
phi = frac(e) jumps between levels. A quantity carried by the cells at the edge then oscillates with the grid:
the srb-rolling roller's sum of lateral forces moves by +-1.2 % at 61 x 121 cells as D runs over one cell
(1.30 -> 1.40), 0.15 % when the lateral window moves instead, so its levels show no order.

The estimator here removes the phase: at every level the quantity is the mean over K windows dilated so that the
Hertz edge moves inward by j/K cells, j = 0..K-1,

    D_j = n / (2 (e - j/K)),        e = n / (2 D),                                       (1)

the mean of a periodic function of phi sampled at K equal steps (the trapezoidal rule, exact for its first K - 1
harmonics); the cell size changes by at most 1/e (4 % at 41 cells, 1 % at 116) within a level. Levels refine by
a constant ratio r with exactly geometric cell sizes: n_k = round(n_0 r^k) cells over a window widened by the
rounding,

    D_k = D_0 n_k / (n_0 r^k)        (dx_k = dx_0 / r^k exactly),                         (2)

so that :func:`femcheck.solvers.convergence.certify` sees a constant ratio. The callers dilate along x only (the
rolling direction, where the leading edge snaps); the same functions serve any axis.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Level:
    """One grid level: ``cells`` (nx, ns), the window factors ``domain`` (D_x, D_s) of its phase 0 and ``h`` the
    cell size relative to level 0 (1 / r^k)."""

    cells: tuple[int, int]
    domain: tuple[float, float]
    h: float


def levels(cells0: tuple[int, int], domain0: tuple[float, float], ratio: float, count: int,
           odd: bool = False) -> list[Level]:
    """``count`` levels from ``cells0`` refining by ``ratio`` with exactly geometric cell sizes (eq 2). ``odd``: the
    counts rounded to the nearest odd number instead, so that a cell stays centred on the window's centre at
    every level (quantities read at the centre cell, or a peak there, would otherwise jump by the half-cell offset
    of an even count)."""
    if count < 1 or ratio <= 1.0:
        raise ValueError("levels needs count >= 1 and ratio > 1")

    def rounded(x: float) -> int:
        return 2 * int(np.floor(0.5 * (x - 1.0) + 0.5)) + 1 if odd else int(round(x))

    out = []
    for k in range(count):
        f = ratio ** k
        n = tuple(rounded(c * f) for c in cells0)
        out.append(Level(n, tuple(d * m / (c * f) for d, m, c in zip(domain0, n, cells0)), 1.0 / f))
    return out


def phase_domains(cells: int, domain: float, phases: int) -> list[float]:
    """The window factors D_j of eq (1) for ``phases`` equal steps of the edge's lattice phase."""
    if phases < 1:
        raise ValueError("phases must be >= 1")
    e = cells / (2.0 * domain)
    if e <= 1.0:
        raise ValueError(f"{cells} cells over +-{domain:g} semi-axes leave less than one cell to the edge")
    return [cells / (2.0 * (e - j / phases)) for j in range(phases)]


def phase_windows(cells: tuple[int, int], domain: tuple[float, float], phases: int, along_s: bool = True
                  ) -> list[tuple[float, float]]:
    """The (D_x, D_s) window factors of ``phases`` lattice phases of a grid of ``cells`` over +-``domain``
    semi-axes: both windows dilated together (phase j moves the edge inward by j/K cells along x and along s), or
    along x only (``along_s`` False: D_s stays ``domain[1]``)."""
    dx = phase_domains(cells[0], domain[0], phases)
    ds = phase_domains(cells[1], domain[1], phases) if along_s else [float(domain[1])] * phases
    return list(zip(dx, ds))


def level_record(level: Level, phases: int, samples: list[dict[str, float]]) -> dict[str, float]:
    """One contact-grid level of a finite-body reference: its cells, size and windows, the phase mean of each
    quantity and its spread (``<quantity>_phase_spread``)."""
    mean, spread = phase_mean(samples)
    return {"nx": level.cells[0], "ns": level.cells[1], "h": level.h, "domain_x": level.domain[0],
            "domain_s": level.domain[1], "phases": phases, **mean,
            **{f"{k}_phase_spread": v for k, v in spread.items()}}


def phase_mean(samples: list[dict[str, float]]) -> tuple[dict[str, float], dict[str, float]]:
    """Mean over the phases of each quantity and its spread (max - min, same units): the level's value and how far
    a single-phase grid could have been from it."""
    keys = [k for k in samples[0] if all(k in s and s[k] is not None for s in samples)]
    arr = {k: np.array([float(s[k]) for s in samples]) for k in keys}
    return {k: float(v.mean()) for k, v in arr.items()}, {k: float(np.ptp(v)) for k, v in arr.items()}
