"""Physical sanity checks applied to every model result: a wrong answer must never pass silently."""
from __future__ import annotations

import numpy as np

from .result import ModelResult

LOAD_BALANCE_TOL = 1e-6
UNBOUNDED = ("fatigue_life",)     # +inf is a valid answer: nothing exceeds the fatigue limit (infinite life)


def physical_violations(res: ModelResult, applied_load: float) -> list[str]:
    """Non-finite quantities (except +inf for ``UNBOUNDED`` ones), negative pressures or roller loads, and load
    imbalance |total_force - W| / W > 1e-6."""
    issues = [f"non-finite {k}" for k, v in res.quantities.items()
              if not np.isfinite(v) and not (k in UNBOUNDED and v == np.inf)]
    p = res.fields.get("pressure")
    if p is not None:
        if not np.all(np.isfinite(p)):
            issues.append("non-finite pressure field")
        elif p.min() < 0:
            issues.append(f"negative pressure {p.min():.3e} Pa")
    q = res.fields.get("roller_loads")
    if q is not None:
        if not np.all(np.isfinite(q)):
            issues.append("non-finite roller loads")
        elif np.min(q) < 0:
            issues.append(f"negative roller load {np.min(q):.3e} N")
    f = res.quantities.get("total_force")
    if f is not None and np.isfinite(f):
        imbalance = abs(f - applied_load) / applied_load
        if imbalance > LOAD_BALANCE_TOL:
            issues.append(f"load imbalance {imbalance:.2e} > {LOAD_BALANCE_TOL:g}")
    return issues
