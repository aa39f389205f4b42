"""The contact-resolved reference of the 209-type cylindrical roller bearing against the 3D condensed model
(femcheck.bem.bearing_resolved, femcheck.fem.crb_corrections, femcheck.bem.bearing_condensed3d).

Case (the condensed model's benchmark, benchmarks/bearing_condensed3d.py): Z = 14, D_we = 10 mm, L_we = 9.6 mm
(roller 10 mm long), raceways r_i 27.516 / r_o 37.516 mm, zero clearance, ISO crown, inner ring misaligned by
0.5 mrad, F_r = 8900 N; outer ring (85 mm OD, 19 mm wide) on a housing arc of +-60 deg, inner ring (45 mm bore)
clamped to a rigid shaft; steel.

Certificate in four parts, each refined alone about the base (ratio 2, three levels, certify() per quantity), the
value = base + the parts' extrapolation steps, the estimate = the sum of the parts' (absolute, N):
  A roller FE: element layers per bin 2 / 4 / 8 (h_contact 0.35 / 0.25 / 0.18 of the patch width)
  B ring FE: axial cells per bin 1 / 2 / 4 (m = 1, 4 radial cells growing x3, band fill |k - l| <= 1)
  C correction bins: 5 / 10 / 20 along L_we (roller layers and ring cells per bin held)
  D fine contact grid: 12 x 40 / 24 x 80 / 48 x 160 cells per contact
Quantities: the loaded rollers' loads Q_0..Q_3 and roller 0's 10 slice loads (N).
The condensed model: the same rings (outer on the arc, inner bore clamped) condensed at its own patch
(a_c r = 1 mm, m = 1 and m = 2), ISO/TS 16281 slices (10).

Run: flock /tmp/femcheck-cpu.lock python benchmarks/bearing_resolved.py [--quick]
Writes benchmarks/results/bearing_resolved.json and .md. Timings: wall time on the shared 2-core machine.
"""
from __future__ import annotations

import argparse
import json
import resource
import time
from pathlib import Path

import numpy as np

from femcheck.bem import bearing_condensed3d as bc
from femcheck.bem import bearing_resolved as br
from femcheck.fem import crb_corrections as cc
from femcheck.fem import ring3d_compliance as rc
from femcheck.fem.rolling_compliance import MeshSettings
from femcheck.materials import Elastic
from femcheck.meshes.ring3d import RingMeshSpec
from femcheck.solvers.convergence import certify

STEEL = Elastic(210e9, 0.3)
Z, D, L, L_ROLLER = 14, 10e-3, 9.6e-3, 10e-3
R_IN, R_OUT, BORE, OD, WIDTH = 27.516e-3, 37.516e-3, 22.5e-3, 42.5e-3, 19e-3
LOAD, TILT, ARC = 8900.0, 5e-4, np.pi / 3
PATCH = 0.8e-3                    # correction patch width across the contact line (m)
HALF_WIDTH = (0.2e-3, 0.25e-3)    # fine grid half-widths across (m): 1.7-1.9 x Hertz b at Q_max
OUT = Path(__file__).parent / "results"
ROLLER_LEVELS = ((2, 0.35), (4, 0.25), (8, 0.18))   # (layers per bin, h_contact)
RING_LEVELS = (1, 2, 4)                               # axial cells per bin
BIN_LEVELS = (5, 10, 20)
GRID_LEVELS = ((12, 40), (24, 80), (48, 160))
BASE = {"roller": 1, "ring": 1, "bins": 1, "grid": 1}


def ring_spec(r_race, r_back, bins, per_slice):
    return RingMeshSpec(r_race, r_back, WIDTH, L, Z, bins, 0.5 * PATCH / r_race, refine=1, radial=4,
                        radial_growth=3.0, per_slice=per_slice, between=3, ends=2 * per_slice)


_cache: dict = {}


def corrections(roller_level: int, ring_level: int, nbins: int) -> tuple[br.CorrectionTables, dict]:
    key = (roller_level, ring_level, nbins)
    if key in _cache:
        return _cache[key]
    # bins coarser than the base keep the base's element sizes: layers and cells per bin scale with the bin
    scale = nbins / BIN_LEVELS[BASE["bins"]]
    layers, hc = ROLLER_LEVELS[roller_level]
    layers = max(1, int(round(layers / scale)))
    per_slice = max(1, int(round(RING_LEVELS[ring_level] / scale)))
    bins = cc.Bins(L, nbins, PATCH)
    t0 = time.perf_counter()
    rol = cc.roller_correction(0.5 * D, L_ROLLER, bins, STEEL, MeshSettings(h_contact=hc, grading=0.3, h_max=1.0e-3,
                                                                           layers_per_cell=layers))
    ro = cc.ring_correction(ring_spec(R_OUT, OD, nbins, per_slice), STEEL, ARC, bins)
    ri = cc.ring_correction(ring_spec(R_IN, BORE, nbins, per_slice), STEEL, np.pi, bins)
    tables = br.CorrectionTables(rol.D, cc.filled(ri.D, Z, 1), cc.filled(ro.D, Z, 1), nbins, nbins)
    info = {"roller_dofs": rol.stats["n_dofs"], "outer_dofs": ro.stats["n_dofs"], "inner_dofs": ri.stats["n_dofs"],
            "layers_per_bin": layers, "ring_cells_per_bin": per_slice, "time_s": time.perf_counter() - t0}
    _cache[key] = (tables, info)
    return tables, info


def solve(level: dict) -> dict:
    tables, info = corrections(level["roller"], level["ring"], BIN_LEVELS[level["bins"]])
    nx, ny = GRID_LEVELS[level["grid"]]
    row = br.ResolvedRow(Z, D, L, R_IN, R_OUT, 0.0, TILT)
    r = br.solve(row, br.FineGrid(nx, ny, HALF_WIDTH), tables, LOAD)
    return {"level": dict(level), "corrections": info, "solve_s": r.time_s, "newton": r.iterations,
            "outer": r.outer_iterations, "residual": r.residual, "roller_loads": r.roller_loads.tolist(),
            "slice_loads": r.slice_loads(10).tolist(), "rho": r.rho.tolist(), "phi": r.phi.tolist(),
            "delta": r.delta.tolist()}


def quantities(run: dict) -> dict[str, float]:
    q = {f"Q_{j}": run["roller_loads"][j] for j in range(4)}
    q.update({f"q_0_{k}": run["slice_loads"][0][k] for k in range(10)})
    q.update({f"q_1_{k}": run["slice_loads"][1][k] for k in range(10)})
    return q


def condensed(refine: int) -> dict:
    t0 = time.perf_counter()
    C = 0.0
    for r_race, r_back, arc in ((R_OUT, OD, ARC), (R_IN, BORE, np.pi)):
        spec = RingMeshSpec(r_race, r_back, WIDTH, L, Z, 10, 1.0e-3 / r_race, refine=refine, between=3, ends=2,
                            radial=1)
        C = C + rc.ring_compliance(rc.RingFE(spec, STEEL, "housing", arc)).C
    build = time.perf_counter() - t0
    sol = bc.solve(bc.SlicedRow(Z, L, D, slices=10, crown="iso", misalignment=TILT), C, LOAD)
    rigid = bc.solve(bc.SlicedRow(Z, L, D, slices=10, crown="iso", misalignment=TILT), None, LOAD)
    return {"refine": refine, "build_s": build, "solve_s": sol.time_s, "roller_loads": sol.roller_loads.tolist(),
            "slice_loads": sol.slice_loads.tolist(), "rigid_roller_loads": rigid.roller_loads.tolist(),
            "rigid_slice_loads": rigid.slice_loads.tolist()}


def main() -> dict:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="the base level only")
    args = ap.parse_args()
    t_all = time.perf_counter()
    base = solve(BASE)
    print(f"base: Q {np.round(base['roller_loads'][:4], 1)} in {base['solve_s']:.1f} s", flush=True)
    parts = {}
    if not args.quick:
        for part, n in (("roller", 3), ("ring", 3), ("bins", 3), ("grid", 3)):
            runs = []
            for i in range(n):
                lv = dict(BASE)
                lv[part] = i
                runs.append(base if lv == BASE else solve(lv))
                print(f"{part} {i}: Q {np.round(runs[-1]['roller_loads'][:4], 1)}", flush=True)
            parts[part] = runs
    out = {"case": {"Z": Z, "D": D, "L": L, "load": LOAD, "misalignment": TILT, "housing_half_angle": ARC,
                    "patch": PATCH, "half_width": HALF_WIDTH}, "base": base, "parts": parts}
    if parts:
        names = list(quantities(base))
        value = {n: quantities(base)[n] for n in names}
        est = {n: 0.0 for n in names}
        certs = {}
        for part, runs in parts.items():
            for n in names:
                qs = [quantities(r)[n] for r in runs]
                c = certify([4.0, 2.0, 1.0], qs, floor=1e-4)
                step = c.value - quantities(base)[n] if c.certified else 0.0
                value[n] += step
                est[n] += c.error_estimate * abs(c.value)
                certs.setdefault(n, {})[part] = {"levels": qs, **c.as_dict()}
        out["reference"] = {n: {"value": value[n], "estimate_N": est[n],
                                "certified": all(certs[n][p]["certified"] for p in parts)} for n in names}
        out["certificates"] = certs
    out["condensed"] = [condensed(1), condensed(2)]
    out["total_s"] = time.perf_counter() - t_all
    out["peak_rss_gb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6
    OUT.mkdir(exist_ok=True)
    (OUT / "bearing_resolved.json").write_text(json.dumps(out, indent=1))
    write_md(out)
    return out


def write_md(out: dict) -> None:
    lines = ["# Contact-resolved reference vs 3D condensed model (209 CRB, 0.5 mrad, 8900 N)", ""]
    ref = out.get("reference")
    cond = out["condensed"]
    qmax = (ref["Q_0"]["value"] if ref else out["base"]["roller_loads"][0])
    lines += ["| roller | resolved (N) | estimate (N) | condensed m=1 | m=2 | rigid ISO | condensed - resolved (% Q_max) |",
              "|---|---|---|---|---|---|---|"]
    for j in range(4):
        v = ref[f"Q_{j}"]["value"] if ref else out["base"]["roller_loads"][j]
        e = ref[f"Q_{j}"]["estimate_N"] if ref else float("nan")
        c1, c2, rg = cond[0]["roller_loads"][j], cond[1]["roller_loads"][j], cond[0]["rigid_roller_loads"][j]
        lines.append(f"| {j} | {v:.1f} | {e:.1f} | {c1:.1f} | {c2:.1f} | {rg:.1f} | {100 * (c2 - v) / qmax:+.2f} |")
    for j in (0, 1):
        vals = [(ref[f"q_{j}_{k}"]["value"] if ref else out["base"]["slice_loads"][j][k]) for k in range(10)]
        big = max(vals)
        lines += ["", f"Roller {j}, slice loads (N):", "",
                  "| slice | resolved | estimate | condensed m=2 | difference (% of largest) |", "|---|---|---|---|---|"]
        for k in range(10):
            e = ref[f"q_{j}_{k}"]["estimate_N"] if ref else float("nan")
            c = cond[1]["slice_loads"][j][k]
            lines.append(f"| {k} | {vals[k]:.1f} | {e:.1f} | {c:.1f} | {100 * (c - vals[k]) / big:+.1f} |")
    lines += ["", f"Total {out['total_s']:.0f} s, peak RSS {out['peak_rss_gb']:.1f} GB; base solve "
              f"{out['base']['solve_s']:.1f} s ({out['base']['newton']} Newton, {out['base']['outer']} lagged), "
              f"corrections {out['base']['corrections']['time_s']:.0f} s "
              f"(DOFs roller {out['base']['corrections']['roller_dofs']}, outer ring "
              f"{out['base']['corrections']['outer_dofs']}, inner ring {out['base']['corrections']['inner_dofs']})."]
    (OUT / "bearing_resolved.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
