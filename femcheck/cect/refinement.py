"""Grid refinement of Kalker's exact theory: the discretisation error bar of the ``exact`` models.

Kalker's Eulerian scheme (the upwind difference of the steady-rolling slip, seed 000 eq 20) and the uniform
traction elements make the exact theory first-order accurate in the element size (measured:
``benchmarks/exact_scaling.py`` in 3D, the halving errors of the 2D strips in ``tests/test_cect_line.py``). So
the exact models solve on a sequence of grids whose element counts double (coarse to fine), and each quantity
gets the shared convergence certificate of :func:`femcheck.solvers.convergence.certify`: the observed order of
the last three grids, Richardson's extrapolation when it is in the asymptotic range (with the observed order
capped by the scheme's first order, :func:`femcheck.solvers.convergence.certify_formal`), and a conservative
relative error estimate (GCI) either way. A quantity the solver imposes (the normal load under load control,
the friction force of a shift problem) is exact on every grid and is certified as such.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

from ..errors import InputError
from ..solvers.convergence import Certificate, certify_formal

#: Observed order expected of Kalker's scheme (first-order upwind transport, piecewise-constant tractions).
KALKER_ORDER = 1.0


@dataclass
class Refinement:
    """Outcome of :func:`refine`: ``values`` (the certificate value of every quantity: Richardson's
    extrapolation when certified, else the finest grid), ``certificates`` (quantity -> Certificate), ``levels``
    (per grid: ``cells`` and the quantities), ``finest`` (whatever the solve returned for the finest grid)."""

    values: dict[str, float]
    certificates: dict[str, Certificate]
    levels: list[dict[str, Any]] = field(default_factory=list)
    finest: Any = None

    def stats(self) -> dict[str, Any]:
        """The JSON part: ``certificates`` (the shared format), ``levels`` and ``finest`` quantity values."""
        return {"certificates": {k: c.as_dict() for k, c in self.certificates.items()},
                "levels": self.levels, "finest": dict(self.levels[-1]["quantities"]) if self.levels else {}}


def grids(finest: int, levels: int, key: str, minimum: int = 2) -> list[int]:
    """Element counts finest / 2^(levels-1), ..., finest / 2, finest (coarse to fine); InputError naming
    ``key`` when ``finest`` is not divisible or the coarsest grid falls below ``minimum`` elements."""
    step = 2 ** (levels - 1)
    if finest % step or finest // step < minimum:
        raise InputError(key, f"{finest} with {levels} refinement levels; allowed: a multiple of {step} with "
                         f"at least {minimum} elements on the coarsest grid (finest / {step})")
    return [finest // 2 ** k for k in range(levels - 1, -1, -1)]


def refine(solve: Callable[[int], tuple[dict[str, float], Any]], cells: Sequence[int],
           imposed: Sequence[str] = (), expected_order: dict[str, float | None] | None = None,
           negligible: dict[str, float] | None = None) -> Refinement:
    """Solve on every grid of ``cells`` (coarse to fine, each twice the previous) and certify each quantity.

    ``solve(n)`` returns (quantities, payload) for n elements (per axis in 3D). ``imposed``: quantities the
    solver makes exact on every grid (certified with zero error). ``expected_order``: per quantity the
    theoretical order handed to :func:`certify` (default :data:`KALKER_ORDER`; None: any consistent order in
    [0.5, 4], e.g. for the BEM pressure of the normal problem). ``negligible``: per quantity an absolute size
    (its units) below which it is zero to round-off on every grid (a force that vanishes by symmetry, e.g. Fx
    under pure spin): certified as such, since a relative error of round-off means nothing.
    """
    orders = expected_order or {}
    levels, payload = [], None
    for n in cells:
        q, payload = solve(n)
        levels.append({"cells": int(n), "quantities": dict(q)})
    names = list(levels[-1]["quantities"])
    h = [1.0 / lv["cells"] for lv in levels]
    certs: dict[str, Certificate] = {}
    for name in names:
        series = [lv["quantities"][name] for lv in levels]
        if name in imposed:
            certs[name] = Certificate(series[-1], series[-1], None, 0.0, True,
                                      "imposed by the solver on every grid (load control)")
        elif name in (negligible or {}) and max(abs(v) for v in series) <= negligible[name]:
            certs[name] = Certificate(series[-1], series[-1], None, 0.0, True,
                                      f"zero to round-off on every grid (|value| <= {negligible[name]:.1e}): "
                                      "vanishes by symmetry")
        elif len(series) == 1:
            certs[name] = Certificate(series[-1], series[-1], None, float("inf"), False,
                                      "one grid: no refinement, no error estimate")
        else:
            certs[name] = certify_formal(h, series, orders.get(name, KALKER_ORDER))
    return Refinement({k: c.value for k, c in certs.items()}, certs, levels, payload)
