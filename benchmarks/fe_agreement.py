"""Agreement and cost of the FE references: femcheck P1, femcheck P2 and CalculiX (where installed) on the same
scenes, in one run, each model solved from scratch in its own process so that its CPU time (user + system, the
process and everything it waits for: ccx included) and peak resident memory are its own.

    flock /tmp/femcheck-cpu.lock python benchmarks/fe_agreement.py [--cases hertz-point:fem,hertz-point:fem_p2]

Per (scene, model): every quantity with its certificate (value, error estimate, certified), the finest level's
DOFs, CPU seconds and peak memory; each quantity also relative to the scene's analytic model where it has one.
Writes benchmarks/results/fe_agreement.json and .md. Run it alone: two solves at once share the 2 cores.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CASES = ("hertz-point:fem", "hertz-point:fem_p2", "hertz-point:ccx-C3D10@0", "hertz-point:ccx-C3D10@1",
         "hertz-point:ccx-C3D4@0", "hertz-point:ccx-C3D4@1", "hertz-line:fem", "hertz-line:ccx-CPE6@0",
         "hertz-line:ccx-CPE6@1", "layer-point:fem", "layer-point:fem_p2", "layer-point:fem_axisym",
         "srb-normal:fem_conformal", "srb-normal:ccx-C3D4@0", "roller-finite:fem", "roller-finite:ccx-C3D4@0",
         "layer-line:fem", "layer-line:ccx-CPE6@0", "layer-line:ccx-CPE6@1")
# the independent value each scene's FE quantities are set against: Hertz, or the layered half-space BEM
COMPARATOR = {"layer-point": "bem", "layer-line": "bem"}
# CalculiX rows set against: Hertz, or femcheck's FE reference where no closed form holds (srb-normal: the
# conformal FE on the same meshes; roller-finite, layer-line: the certified FE reference)
CCX_COMPARATOR = {"srb-normal": "fem_conformal", "roller-finite": "fem", "layer-line": "fem"}
# CalculiX decks of hertz-point on its a/8 family (level 0 = a/8, ratio sqrt 2); hertz-line on its own levels
CCX_OVERRIDES = {"hertz-point": {"numerics.fem_h_contact": 0.125}}
OUT = Path(__file__).resolve().parent / "results"

CCX_CHILD = r"""
import json, subprocess, sys, tempfile
from pathlib import Path
import femcheck
from femcheck.export.pressure import read, read_roller, read_srb
from femcheck.export.write import export
from femcheck.runner import resolve_scene
scene, element, level, over = sys.argv[1], sys.argv[2], int(sys.argv[3]), json.loads(sys.argv[4])
comparator = sys.argv[5]
order = 2 if element in ("C3D10", "CPE6") else 1
with tempfile.TemporaryDirectory() as out:
    info = export(resolve_scene(scene, over), "calculix", level, order, Path(out))
    deck = Path(info["deck"])
    r = subprocess.run(["ccx", "-i", deck.with_suffix("").name], cwd=deck.parent, capture_output=True, text=True)
    if "Job finished" not in r.stdout:
        print("RESULT" + json.dumps({"status": "failed", "error": r.stdout[-300:]}))
        raise SystemExit(0)
    sc = resolve_scene(scene, over)
    if sc.kind == "srb_contact":
        q = {f"{k}_{c}": v for c, qc in read_srb(deck).items() for k, v in qc.items()}
    elif sc.kind == "roller_contact":
        a_h = femcheck.run(scene, over, models=["analytic"]).models["analytic"].quantities["half_width"]
        q = read_roller(deck, a_h, sc["geometry.length"])
    else:
        q = read(deck)
ref = femcheck.run(scene, over, models=[comparator]).models[comparator].quantities
base = ("p_max", "p_centre", "semi_axis_x", "semi_axis_y", "half_width", "approach")
names = [k for k in (*base, *(f"{b}_{c}" for c in ("inner", "outer") for b in base)) if k in q]
print("RESULT" + json.dumps({"status": "ok", "error": None, "element": element,
                             "certificates": {k: {"value": q[k], "error_estimate": float("nan"), "certified": False}
                                              for k in names},
                             "n_dofs": (2 if element.startswith("CPE") else 3) * info["nodes"], "analytic": ref,
                             "comparator": comparator,
                             "level": level},
                            default=float))
"""

CHILD = r"""
import json, sys
import femcheck
scene, model = sys.argv[1], sys.argv[2]
r = femcheck.run(scene, {}, models=[model], use_cache=False, rebuild=True)
m = r.models[model]
lv = (m.stats.get("levels") or [{}])[-1]
comparator = sys.argv[3]
ref = femcheck.run(scene, {}, models=[comparator]).models[comparator].quantities
print("RESULT" + json.dumps({"status": m.status, "error": m.error,
                             "quantities": m.quantities, "certificates": m.stats.get("certificates", {}),
                             "n_dofs": lv.get("n_dofs"), "element": m.stats.get("element"),
                             "comparator": comparator, "analytic": ref}, default=float))
"""


def run_case(scene: str, model: str) -> dict:
    """Solve one (scene, model) in a child process; its CPU time (user + system, including the processes it
    waited for, ccx among them) and peak resident memory from os.wait4."""
    t0 = time.perf_counter()
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        if model.startswith("ccx-"):
            element, level = model[4:].split("@")
            args = ["-c", CCX_CHILD, scene, element, level, json.dumps(CCX_OVERRIDES.get(scene, {})),
                    CCX_COMPARATOR.get(scene, "analytic")]
        else:
            args = ["-c", CHILD, scene, model, COMPARATOR.get(scene, "analytic")]
        proc = subprocess.Popen([sys.executable, *args], stdout=out, stderr=err, text=True)
        _, status, ru = os.wait4(proc.pid, 0)
        proc.returncode = status
        out.seek(0)
        err.seek(0)
        stdout, stderr = out.read(), err.read()
    row = {"scene": scene, "model": model, "wall_s": time.perf_counter() - t0,
           "cpu_s": ru.ru_utime + ru.ru_stime, "peak_gb": ru.ru_maxrss / 1024**2}
    line = next((x for x in stdout.splitlines() if x.startswith("RESULT")), None)
    if line is None:
        row["error"] = (stderr.strip().splitlines() or ["no output"])[-1]
        return row
    row.update(json.loads(line[len("RESULT"):]))
    return row


def _pct(v) -> str:
    return "-" if v is None or v != v else f"{v:.2%}"


def table(rows: list[dict]) -> str:
    out = ["| scene | model | element | quantity | value | vs independent | estimate | certified | DOFs | CPU s | "
           "peak GB |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r.get("error") or r.get("status", "ok") != "ok":
            out.append(f"| {r['scene']} | {r['model']} | | {r.get('status', 'failed')}: {r.get('error')} | | | | | | | |")
            continue
        ref = r.get("analytic") or {}
        for q, c in r.get("certificates", {}).items():
            v = c["value"]
            rel = f"{v / ref[q] - 1:+.3%} ({r.get('comparator', 'analytic')})" if q in ref and ref[q] else ""
            out.append(f"| {r['scene']} | {r['model']} | {(r.get('element') or '').split(' (')[0]} | {q} | {v:.6g} | {rel} | "
                       f"{_pct(c['error_estimate'])} | {'yes' if c['certified'] else 'no'} | {r.get('n_dofs') or ''} | "
                       f"{r['cpu_s']:.0f} | {r['peak_gb']:.2f} |")
    return "\n".join(out) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default=",".join(CASES), help="comma-separated scene:model pairs")
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--merge", action="store_true", help="replace the rows of these cases in the stored JSON, keep "
                    "the others, and rewrite the table")
    a = ap.parse_args(argv)
    rows = []
    for case in a.cases.split(","):
        scene, model = case.split(":")
        print(f"{scene} {model} ...", flush=True)
        rows.append(run_case(scene, model))
        r = rows[-1]
        print(f"  {r.get('error') or 'ok'}: CPU {r['cpu_s']:.0f} s, peak {r['peak_gb']:.2f} GB", flush=True)
    a.out.mkdir(parents=True, exist_ok=True)
    stored = a.out / "fe_agreement.json"
    if a.merge and stored.exists():
        new = {(r["scene"], r["model"]): r for r in rows}
        old = json.loads(stored.read_text())
        rows = [new.pop((r["scene"], r["model"]), r) for r in old] + list(new.values())
    (a.out / "fe_agreement.json").write_text(json.dumps(rows, indent=1, default=float))
    (a.out / "fe_agreement.md").write_text(table(rows))
    print(table(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
