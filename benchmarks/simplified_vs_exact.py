"""FASTSIM, strip theory, linear theory and full slip against Kalker's exact theory (issue 6, item 5).

Runs the creep-curve scene over contact shapes a/b and creepage cases (pure xi, eta, phi and combinations,
from small creepage to near saturation), with the exact solver as the reference, and writes the relative
errors of the creep forces and spin moment and the run times to benchmarks/results/simplified_vs_exact.json
plus a markdown table. FASTSIM is run in its three-flexibility form with Kalker's parabolic bound (the
scene default) and, for contrast, with the single weighted flexibility.

    python benchmarks/simplified_vs_exact.py
"""
from __future__ import annotations

import json
import time
from pathlib import Path

from femcheck.runner import run
from femcheck.scene import load_scene

# Rx along rolling, Ry across: a/b ~ 0.40 (the scene), ~1.0 and ~2.5 at 1 kN steel on steel
SHAPES = {"a/b=0.40": {"geometry.Rx": 0.005, "geometry.Ry": 0.020},
          "a/b=1.00": {"geometry.Rx": 0.010, "geometry.Ry": 0.010},
          "a/b=2.50": {"geometry.Rx": 0.020, "geometry.Ry": 0.004}}
CASES = {"xi small": (0.0005, 0.0, 0.0), "xi mid": (0.004, 0.0, 0.0), "xi high": (0.012, 0.0, 0.0),
         "eta mid": (0.0, 0.004, 0.0), "phi mid": (0.0, 0.0, 10.0), "xi+eta": (0.004, 0.002, 0.0),
         "xi+eta+phi": (0.005, 0.002, 10.0), "eta+phi": (0.0, 0.003, 10.0)}
MODELS = {"fastsim": {}, "fastsim(weighted)": {"numerics.fastsim_flexibility": "weighted"},
          "strip": {}, "linear": {}, "full_slip": {}}
QUANTITIES = ("creep_force_x", "creep_force_y", "spin_moment")


def main() -> None:
    rows = []
    for shape, geo in SHAPES.items():
        for case, (xi, eta, phi) in CASES.items():
            over = {**geo, "kinematics.xi": xi, "kinematics.eta": eta, "kinematics.phi": phi}
            ref = run(load_scene("creep-curve", over), models=["exact"]).models["exact"]
            row = {"shape": shape, "case": case, "creepages": [xi, eta, phi], "exact": ref.quantities,
                   "exact_time_s": ref.time_s, "exact_iterations": ref.stats.get("iterations"), "models": {}}
            for label, extra in MODELS.items():
                name = label.split("(")[0]
                t0 = time.perf_counter()
                m = run(load_scene("creep-curve", {**over, **extra}), models=[name]).models[name]
                entry = {"time_s": time.perf_counter() - t0, "status": m.status}
                for q in QUANTITIES:
                    r = ref.quantities.get(q, 0.0)
                    # a quantity the reference gives as ~0 (e.g. Fy under pure xi) has no relative error
                    if abs(r) > 1e-6 * max(abs(v) for k, v in ref.quantities.items() if k in QUANTITIES[:2]) \
                            and q in m.quantities:
                        entry[f"err_{q}"] = m.quantities[q] / r - 1.0
                row["models"][label] = entry
            rows.append(row)
            print(shape, case, {k: {q: round(100 * v, 1) for q, v in e.items() if q.startswith("err_")}
                                for k, e in row["models"].items()}, flush=True)
    out = Path(__file__).parent / "results"
    out.mkdir(exist_ok=True)
    (out / "simplified_vs_exact.json").write_text(json.dumps({"rows": rows}, indent=1))
    lines = ["| a/b | case | " + " | ".join(f"{m} Fx / Fy / Mz (%)" for m in MODELS) + " |",
             "|---|---|" + "---|" * len(MODELS)]
    for r in rows:
        cells = []
        for m in MODELS:
            e = r["models"][m]
            cells.append(" / ".join(f"{100 * e[f'err_{q}']:+.1f}" if f"err_{q}" in e else "–" for q in QUANTITIES))
        lines.append(f"| {r['shape'][4:]} | {r['case']} | " + " | ".join(cells) + " |")
    (out / "simplified_vs_exact.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
