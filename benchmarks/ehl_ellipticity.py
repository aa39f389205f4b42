"""Seed 004 Table 3.5: the additional pressure over the rear shoulder of a centred indent in a circular (kappa = 1)
and an elliptic (kappa = b/a = 0.2) EHL contact, the ellipticity changed at constant b and p_H (seed 004 §3.3.2,
:func:`femcheck.ehl.groups.at_ellipticity`).

    flock /tmp/femcheck-cpu.lock python benchmarks/ehl_ellipticity.py OUT.jsonl GRID CASE [CASE ...]

The indent is the same physical one in both contacts (diameter phi and depth d; seed 004 §3.2.2: "how do the
pressure perturbations induced by a given indent evolve"): Phi = phi/b is unchanged and D/Phi = (d/phi)(Rx/b)
scales with Rx (x 0.811 at kappa = 0.2). Keeping the dimensionless D/Phi instead raises even the dry additional
pressure by 18-27 % (the dry Table 3.2 check in docs/notes/seed004-ellipticity-and-crossing.md).

CASE = M:L:Phi:D/Phi:kappa[:y_half], (M, L) the Moes point of the circular contact, D/Phi its slope (steel E' = 226 GPa, Rx = 10 mm,
Roelands and Dowson-Higginson, eta0 = 0.04 Pa s, alpha = 22 GPa^-1), K = 4, pure rolling, thesis domain
[-2.5, 1.5] b along X; across, +-y_half b (default: femcheck's, +-2 a = +-2/kappa b). The indent enters at the
inlet and is marched (NU2, time step = mesh size) to the centre, X_D = 0, where the amplitudes are read
(:func:`femcheck.ehl.outputs.additional_pressure`). One JSON line per case (a failed case records its error
and the others go on)."""
from __future__ import annotations

import dataclasses
import json
import sys
import time

import numpy as np

from femcheck.ehl import groups, model, outputs, transient
from femcheck.ehl.film import Indent

E_PRIME, ETA0, ALPHA, RX = 226e9, 0.04, 2.2e-8, 0.01


def centred(g: groups.Groups, grid: int, phi: float, slope: float, K: float, x_start: float = -2.5,
            x_end: float = 1.5, tol: float = 1e-7, load_tol: float = 1e-7, y_half: float | None = None) -> dict:
    """dP amplitudes (p/p_H) of the indent (Phi, D/Phi, K) marched from the inlet to X_D = 0."""
    s = model.make_setup(g, "roelands", "dowson_higginson", grid, None, x_start, x_end, y_half=y_half)
    smooth, mg = model.solve_smooth(s, tol, load_tol)
    h = mg.fine.h
    centre, _ = model.crossing_steps(phi, x_start, h, 1.0)
    ind = Indent(phi, slope * phi, K, x0=-centre * h, speed_ratio=1.0)
    mg.prob = dataclasses.replace(s.prob, indent=ind)
    mg.set_time(0.0)
    transient.start(mg)
    hist = transient.march(mg, centre, tol=tol, load_tol=load_tol, keep=lambda k, T: k == centre, base=smooth.P)
    sol = hist.snapshots[-1]
    a = outputs.additional_pressure(sol.x, sol.y, sol.P - smooth.P, ind.centre(mg.T), 0.0, phi)
    return {"xd": ind.centre(mg.T), "steps": centre, "cycles": float(np.mean(hist.cycles)),
            "max_load_error": float(max(hist.load_error)), "shape": list(sol.P.shape), "y_half": float(sol.y[-1]),
            **{k: a[k] for k in ("rear", "front", "lateral", "centre", "amplitude")}}


def main(argv: list[str]) -> None:
    out, grid = argv[0], int(argv[1])
    for case in argv[2:]:
        vals = [float(v) for v in case.split(":")]
        M, L, phi, slope, kappa = vals[:5]
        y_half = vals[5] if len(vals) > 5 else None
        g1 = groups.from_moes(M, L, RX, RX, E_PRIME, ETA0, ALPHA)
        g = groups.at_ellipticity(g1, kappa)
        t = time.perf_counter()
        try:
            # the physical indent (phi, d) is kept: Phi = phi/b is unchanged, D = d Rx/b^2 scales with Rx
            r = centred(g, grid, phi, slope * g.Rx / g1.Rx, 4.0, y_half=y_half)
        except Exception as err:            # noqa: BLE001 - recorded; the other cases go on
            r = {"error": str(err)[:300]}
        r.update({"M": M, "L": L, "phi": phi, "slope": slope, "kappa": kappa, "grid": grid, "lam": g.lam,
                  "alpha_bar": g.alpha_bar, "slope_used": slope * g.Rx / g1.Rx, "Rx": g.Rx, "Ry": g.Ry, "time_s": time.perf_counter() - t})
        print(json.dumps(r), flush=True)
        with open(out, "a") as f:
            f.write(json.dumps(r) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
