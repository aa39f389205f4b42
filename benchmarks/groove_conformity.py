"""Conformity sweep of the groove-rolling scene (issue 11 done-when): groove/crown radius ratio 1.002-1.05 on a
convex ring, a straight rail and a concave ring, each solved by the conformal exact theory (cect), the planar
exact theory with the Hertz gap (planar) and the frictional FE (fem, ``--fem-levels`` levels; 1 = the coarsest,
11 x 21 cells, whose error on the default scene against the 3-level reference is stated in the README).
Writes benchmarks/results/groove_conformity.{json,md}. Run under the shared lock (2 min 33 s and 1.0 GB with one FE level, measured):

    flock /work/heavy.lock python benchmarks/groove_conformity.py [--fem-levels 1]
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from femcheck.errors import InputError
from femcheck.runner import run

RATIOS = (1.002, 1.005, 1.01, 1.027, 1.05)
RINGS = {"convex": 12.10653753, "straight": 0.0, "concave": -9.77}
QUANTITIES = ("approach", "p_max", "contact_half_length_s", "angle_span", "creepage_x", "adhesion_fraction",
              "friction_power")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--fem-levels", type=int, default=1)
    ap.add_argument("--out", default="benchmarks/results/groove_conformity")
    ap.add_argument("--ratios", type=float, nargs="*", default=RATIOS)
    ap.add_argument("--rings", nargs="*", default=list(RINGS), choices=list(RINGS))
    a = ap.parse_args()
    rows = []
    for ratio in a.ratios:
        for ring, k in ((r, RINGS[r]) for r in a.rings):
            t0 = time.perf_counter()
            over = {"geometry.groove_radius": 0.1003 * ratio, "geometry.ring_curvature": k,
                    "numerics.fem_levels": a.fem_levels}
            row = {"ratio": ratio, "ring": ring}
            try:
                res = run("groove-rolling", over, use_cache=False)
            except InputError as err:            # the FE refuses this geometry: say why, run the others
                res = run("groove-rolling", over, models=["cect", "planar"], use_cache=False)
                row["fem"] = {"error": str(err)}
            row["time_s"] = time.perf_counter() - t0
            for m, r in res.models.items():
                if r.status != "ok":
                    row[m] = {"error": r.error}
                    continue
                row[m] = {q: r.quantities.get("body_approach" if (m, q) == ("fem", "approach") else q)
                          for q in QUANTITIES}
                row[m]["time_s"] = r.time_s
            rows.append(row)
            print(json.dumps(row), flush=True)
    out = Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.with_suffix(".json").write_text(json.dumps(rows, indent=1))
    lines = ["| groove/crown | ring | span cect (deg) | p_max fem (GPa) | p_max cect - fem | p_max planar - fem | "
             "span cect - fem | span planar - fem | approach: fem body / cect / planar (um) | creepage fem / cect | "
             "power fem / cect (W) |", "|" + "---|" * 11]
    for r in rows:
        f, c, p = r["fem"], r["cect"], r["planar"]
        if "error" in f:
            lines.append(f"| {r['ratio']} | {r['ring']} | {c['angle_span'] * 57.29578:.2f} | fem not applicable: "
                         f"{f['error']} |||||||| ")
            continue

        def d(m, q):
            return f"{100 * (m[q] / f[q] - 1):+.2f} %"
        lines.append(f"| {r['ratio']} | {r['ring']} | {c['angle_span'] * 57.29578:.2f} | {f['p_max'] / 1e9:.4f} | "
                     f"{d(c, 'p_max')} | {d(p, 'p_max')} | {d(c, 'angle_span')} | {d(p, 'angle_span')} | "
                     f"{f['approach'] * 1e6:.2f} / {c['approach'] * 1e6:.2f} / {p['approach'] * 1e6:.2f} | "
                     f"{f['creepage_x']:.3e} / {c['creepage_x']:.3e} | {f['friction_power']:.2f} / "
                     f"{c['friction_power']:.2f} |")
    out.with_suffix(".md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
