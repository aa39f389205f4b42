"""The contact-resolved reference of the 209-type cylindrical roller bearing (scene crb-3d-misaligned) against the
3D condensed model at two ring meshes, the coupled-slice model at 1-16 strips per slice and rigid-ring ISO/TS 16281:
per-roller and per-slice loads, the reference's four-part certificate, cost (femcheck.problems._bearing_3d).

Run: flock /tmp/femcheck-cpu.lock python benchmarks/bearing_resolved.py
Writes benchmarks/results/bearing_resolved.json and .md. Timings: wall time on the shared 2-core machine.
"""
from __future__ import annotations

import json
import resource
import time
from pathlib import Path

import numpy as np

from femcheck.problems import _bearing_3d as b3
from femcheck.problems.bearing_load import rigid_ring
from femcheck.scene import load_scene

OUT = Path(__file__).parent / "results"
SCENE = "crb-3d-misaligned"


def main() -> dict:
    t0 = time.perf_counter()
    ref = b3.resolved(load_scene(SCENE), progress=lambda s: print(s, flush=True))
    t_ref = time.perf_counter() - t0
    cond = {}
    for m in (1, 2):
        t = time.perf_counter()
        r = b3.condensed3d(load_scene(SCENE, {"numerics.condensed3d_refine": m}))
        cond[m] = {"roller_loads": r.fields["roller_loads"].tolist(), "slice_loads": r.fields["slice_loads"].tolist(),
                   "time_s": time.perf_counter() - t, "ring_dofs": r.stats["ring_dofs"]}
    strips = {}
    for m in (1, 2, 4, 8, 16):
        t = time.perf_counter()
        r = b3.coupled_slices(load_scene(SCENE, {"numerics.strips_per_slice": m}))
        strips[m] = {"roller_loads": r.fields["roller_loads"].tolist(), "slice_loads": r.fields["slice_loads"].tolist(),
                     "time_s": time.perf_counter() - t, "corrections_s": r.stats["corrections_time_s"],
                     "solve_s": r.stats["solve_time_s"]}
    rig = rigid_ring(load_scene(SCENE))
    out = {"reference": {"roller_loads": ref.fields["roller_loads"].tolist(),
                         "slice_loads": ref.fields["slice_loads"].tolist(),
                         "slice_load_estimates": ref.fields["slice_load_estimates"].tolist(),
                         "certificates": ref.stats["certificates"], "parts": ref.stats["parts"],
                         "levels": ref.stats["levels"], "time_s": t_ref},
           "condensed3d": cond, "coupled_slices": strips,
           "rigid_ring": {"roller_loads": rig.fields["roller_loads"].tolist(),
                          "slice_loads": rig.fields["slice_loads"].tolist()},
           "peak_rss_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6}
    OUT.mkdir(exist_ok=True)
    (OUT / "bearing_resolved.json").write_text(json.dumps(out, indent=1))
    write_md(out)
    return out


def write_md(out: dict) -> None:
    ref = out["reference"]
    Q = np.asarray(ref["roller_loads"])
    S = np.asarray(ref["slice_loads"])
    E = np.asarray(ref["slice_load_estimates"])
    c1, c2 = (np.asarray(out["condensed3d"][m]["roller_loads"]) for m in (1, 2))
    cond = out["condensed3d"][2]
    rig = out["rigid_ring"]
    est = [ref["parts"][f"Q_{j}"]["estimate"] for j in range(4)]
    lines = ["# Contact-resolved reference vs 3D condensed model (crb-3d-misaligned: 209 CRB, 0.5 mrad, 8900 N)", "",
             "| roller | resolved (N) | estimate (N) | condensed3d m=1 | m=2 | rigid ISO | m=2 - resolved (% Q_max) |",
             "|---|---|---|---|---|---|---|"]
    for j in range(4):
        lines.append(f"| {j} | {Q[j]:.1f} | {est[j]:.1f} | {c1[j]:.1f} | {c2[j]:.1f} | {rig['roller_loads'][j]:.1f} | "
                     f"{100 * (c2[j] - Q[j]) / Q.max():+.2f} |")
    for j in (0, 1):
        big = S.max()
        lines += ["", f"Roller {j} (psi = {360 * j / 14:.1f} deg), slice loads (N):", "",
                  "| slice | resolved | estimate | condensed3d m=2 | rigid ISO | m=2 - resolved (% of largest) |",
                  "|---|---|---|---|---|---|"]
        for k in range(S.shape[1]):
            cq = cond["slice_loads"][j][k]
            lines.append(f"| {k + 1} | {S[j, k]:.1f} | {E[j, k]:.1f} | {cq:.1f} | {rig['slice_loads'][j][k]:.1f} | "
                         f"{100 * (cq - S[j, k]) / big:+.1f} |")
    lines += ["", "Coupled slices (errors against the reference: max over rollers / Q_max, max over slices / largest):",
              "", "| strips per slice | time (s) | solve (s) | Q_0 (N) | roller error | slice error |", "|---|---|---|---|---|---|"]
    for m, r in out["coupled_slices"].items():
        q, s = np.asarray(r["roller_loads"]), np.asarray(r["slice_loads"])
        lines.append(f"| {m} | {r['time_s']:.1f} | {r['solve_s']:.2f} | {q[0]:.2f} | "
                     f"{100 * np.abs(q - Q).max() / Q.max():.3f} % | {100 * np.abs(s - S).max() / S.max():.2f} % |")
    c = ref["certificates"]
    lines += ["", f"Certificate: roller loads estimate {100 * c['roller_loads_max']['error_estimate']:.2f} % of Q_max "
              f"(certified: {c['roller_loads_max']['certified']}), slice loads "
              f"{100 * c['slice_loads_max']['error_estimate']:.2f} % of the largest (certified: "
              f"{c['slice_loads_max']['certified']}).",
              "", "| run | part | roller DOFs | ring DOFs (outer) | contact cells | corrections (s) | solve (s) |",
              "|---|---|---|---|---|---|---|"]
    for i, lv in enumerate(ref["levels"]):
        lines.append(f"| {i} | {lv['part']} x{2 ** (lv['index'] - 1) if lv['part'] != 'base' else 1} | "
                     f"{lv['roller_dofs']} | {lv['outer_ring_dofs']} | {lv['across']} x {lv['along']} | "
                     f"{lv['corrections_s']:.1f} | {lv['solve_s']:.1f} |")
    lines += ["", f"Reference {ref['time_s']:.0f} s in all; peak RSS {out['peak_rss_gb']:.1f} GB."]
    (OUT / "bearing_resolved.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
