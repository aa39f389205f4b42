"""Papadopoulos' multiaxial criterion beside von Mises on the dented/smooth maximum-amplitude ratio, dry indented
ball contact, full transient (seed 004 §4.2.1, Table 4.1; spec ehl-life B.6).

    flock /tmp/femcheck-cpu.lock python benchmarks/multiaxial_table41.py [--cells 97] [--cases 0,1,...]

Contact: indent-dry's ball (steel, R = 10 mm, 1 kN: p_H = 2.95 GPa, a = 0.402 mm), BEM over +/- 1.6 a (the set-up
of ``benchmarks/life_transient.py``, whose ``Contact`` is reused). Per indent (Phi, K, D/Phi), the indented contact
is solved at every cell position |x_D| <= min(1 + Phi, 1.6 - Phi/2) a (outside, the smooth pressure applies), and
the full stress tensor (Love's rectangles, DC-FFT per depth plane) of every frame is stored for every material point
of a window |xi|, |y| <= 0.7 a around the indent, on the depth planes z = 2a (k/24)^2 with z <= 1 a. Each point's
history is the sequence of its stresses over all contact positions of the (extended) stress grid.

Per point: sigma_VM = max_t sigma_VM(sigma(t)) (the thesis' measure) and Papadopoulos' T_sigma
(:mod:`femcheck.analytic.multiaxial`) on a coarse line rule (4 x 8 x 4 = 128 lines) for every point, then on the
fine rule (16 x 32 x 16 = 8192 lines) for the 12 largest coarse values of each plane. Smooth: the same measures
of the smooth pass on all 24 planes to 2 a (y within 0.7 a). Table 4.1's quantity:

    d = (sigma^PA_Dmax / sigma^PA_Smax - sigma^VM_Dmax / sigma^VM_Smax) / (sigma^VM_Dmax / sigma^VM_Smax)

maxima taken on the grid (no sub-cell refinement). Thesis values (seed 004 Table 4.1, text; spec ehl-life B.6):
Phi = 0.25: K = 3: 5 % (D/Phi = 1), 6 % (D/Phi = 2); K = 8: 3 %, 4 %; Phi = 0.5: K = 3: 8 %, 7 %; K = 8: 7 %, 7 %.
Results are merged into benchmarks/results/multiaxial_table41.json (keyed on cells and case) and the .md rewritten.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import life_transient as lt  # noqa: E402

from femcheck.analytic import multiaxial as mx  # noqa: E402
from femcheck.bem import stress_history as sh  # noqa: E402

A, P0, NU = lt.A, lt.P0, lt.NU
WINDOW, Z_DENTED, PLANES, TOP = 0.7, 1.0, 24, 12
COARSE, FINE = (4, 8, 4), (16, 32, 16)
# (Phi, K, D/Phi) in Table 4.1's order and its values (seed 004 Table 4.1)
CASES = [(0.25, 3.0, 1.0), (0.25, 3.0, 2.0), (0.25, 8.0, 1.0), (0.25, 8.0, 2.0),
         (0.5, 3.0, 1.0), (0.5, 3.0, 2.0), (0.5, 8.0, 1.0), (0.5, 8.0, 2.0)]
THESIS = {(0.25, 3.0, 1.0): 0.05, (0.25, 3.0, 2.0): 0.06, (0.25, 8.0, 1.0): 0.03, (0.25, 8.0, 2.0): 0.04,
          (0.5, 3.0, 1.0): 0.08, (0.5, 3.0, 2.0): 0.07, (0.5, 8.0, 1.0): 0.07, (0.5, 8.0, 2.0): 0.07}


def frames_of(ct, phi, K, S):
    m = int(np.floor(min(1.0 + phi, lt.DOMAIN - 0.5 * phi) * A / ct.g.dx))
    return {s: ct.dented(phi, K, S, s * ct.g.dx) for s in range(-m, m + 1)}


VARIANTS = {"pa": (mx.papadopoulos_amplitude, "range"), "pz": (mx.papadopoulos_amplitude, "zero"),
            "pc": (mx.papadopoulos_critical_plane, "range")}


def measures(hist: np.ndarray, coarse, fine) -> dict:
    """hist (T, 6, P) in units of p_H: VM max; per Papadopoulos variant the coarse rule on all points and the fine
    rule on the TOP largest coarse ones."""
    out = {"vm": mx.von_mises_max(hist), "sh_max": mx.hydrostatic_max(hist)}
    for key, (fn, about) in VARIANTS.items():
        c = fn(hist, coarse, about=about)
        top = np.argsort(c)[-TOP:]
        out[key], out[key + "_top"], out[key + "_fine"] = c, top, fn(hist[:, :, top], fine, about=about)
    return out


def run_case(ct, phi, K, S, coarse, fine) -> dict:
    t0 = time.perf_counter()
    frames = frames_of(ct, phi, K, S)
    t_frames = time.perf_counter() - t0
    shifts = sorted(frames)
    dx = ct.g.dx
    xc0 = ct.pm_s.x[ct.c[0]]
    _, _, g, iD, _, q, _, jw, _, _ = sh._pass_setup(ct.pm_s, ct.c, WINDOW * A, (xc0 + shifts[0] * dx,
                                                    xc0 + shifts[-1] * dx), ct.z, ct.wz)
    pS = g.embed(ct.smooth / P0)
    pf = {s: g.embed(frames[s] / P0) for s in shifts}
    nq, nj = q.size, jw.size
    best = {"D_vm": (-1.0, None), "D_pa": (-1.0, None), "D_pa_coarse": (-1.0, None),
            "S_vm": (-1.0, None), "S_pa": (-1.0, None), "S_pa_coarse": (-1.0, None), "D_pz": (-1.0, None),
            "S_pz": (-1.0, None), "D_pc": (-1.0, None), "S_pc": (-1.0, None)}
    sh_max = -np.inf
    pa_at_vm = {}

    def keep(key, val, where):
        if val > best[key][0]:
            best[key] = (float(val), where)

    for k, z in enumerate(ct.z):
        ops = sh.PlaneStresses((g.nx, g.ny), dx, g.y[1] - g.y[0], z, NU)
        sS = ops(pS)[:, :, jw]                                   # (6, nx, nj), time axis = contact position
        ms = measures(np.moveaxis(sS, 1, 0), coarse, fine)       # smooth pass of the points (y_j, z)
        if ms["vm"].max() > best["S_vm"][0]:
            pa_at_vm["S"] = float(mx.papadopoulos_amplitude(np.moveaxis(sS, 1, 0)[:, :, [int(np.argmax(ms["vm"]))]], fine)[0])
        keep("S_vm", ms["vm"].max(), (z / A, float(g.y[jw][np.argmax(ms["vm"])] / A)))
        keep("S_pa_coarse", ms["pa"].max(), None)
        i = int(np.argmax(ms["pa_fine"]))
        keep("S_pa", ms["pa_fine"][i], (z / A, float(g.y[jw][ms["pa_top"][i]] / A)))
        keep("S_pz", ms["pz_fine"].max(), None)
        keep("S_pc", ms["pc_fine"].max(), None)
        if z > Z_DENTED * A + 1e-12:
            continue
        H = np.broadcast_to(sS[:, :, None, :], (6, g.nx, nq, nj)).copy()
        ar = np.arange(nq)
        for s in shifts:
            X = iD + q + s
            H[:, X, ar, :] = ops(pf[s])[:, X][:, :, jw]
        md = measures(np.moveaxis(H, 1, 0).reshape(g.nx, 6, nq * nj), coarse, fine)
        sh_max = max(sh_max, float(md["sh_max"].max()))

        def pos(p):
            iq, j = np.unravel_index(int(p), (nq, nj))
            return (z / A, float(q[iq] * dx / A), float(g.y[jw][j] / A))
        if md["vm"].max() > best["D_vm"][0]:
            hd = np.moveaxis(H, 1, 0).reshape(g.nx, 6, nq * nj)[:, :, [int(np.argmax(md["vm"]))]]
            pa_at_vm["D"] = float(mx.papadopoulos_amplitude(hd, fine)[0])
        keep("D_vm", md["vm"].max(), pos(np.argmax(md["vm"])))
        keep("D_pa_coarse", md["pa"].max(), None)
        i = int(np.argmax(md["pa_fine"]))
        keep("D_pa", md["pa_fine"][i], pos(md["pa_top"][i]))
        keep("D_pz", md["pz_fine"].max(), None)
        keep("D_pc", md["pc_fine"].max(), None)
    r_vm = best["D_vm"][0] / best["S_vm"][0]
    r_pa = best["D_pa"][0] / best["S_pa"][0]
    r_pa_c = best["D_pa_coarse"][0] / best["S_pa_coarse"][0]
    r_pz = best["D_pz"][0] / best["S_pz"][0]
    r_pc = best["D_pc"][0] / best["S_pc"][0]
    return {"Phi": phi, "K": K, "slope": S, "cells": ct.g.nx, "frames": [shifts[0], shifts[-1]],
            "stress_grid": [g.nx, g.ny], "points_per_plane": nq * nj,
            "VM_Smax": best["S_vm"][0], "VM_Dmax": best["D_vm"][0], "PA_Smax": best["S_pa"][0],
            "PA_Dmax": best["D_pa"][0], "VM_ratio": r_vm, "PA_ratio": r_pa, "difference": r_pa / r_vm - 1,
            "difference_coarse_rule": r_pa_c / r_vm - 1, "PZ_ratio": r_pz, "difference_about_zero": r_pz / r_vm - 1,
            "PZ_Smax": best["S_pz"][0],
            "PA_at_VM_Smax_point": pa_at_vm["S"], "PA_at_VM_Dmax_point": pa_at_vm["D"],
            "PC_ratio": r_pc, "difference_critical_plane": r_pc / r_vm - 1, "PC_Smax": best["S_pc"][0], "thesis": THESIS.get((phi, K, S)),
            "at": {k: v[1] for k, v in best.items() if v[1] is not None},
            "sigma_H_max_over_pH": sh_max, "time_frames_s": t_frames, "time_s": time.perf_counter() - t0}


def rule_check(ct, coarse, fine) -> dict:
    """Quadrature error of T_sigma at the smooth maximum's point: the rules against a 32 x 64 x 32 rule."""
    z = 0.5 * A
    g = ct.g
    ops = sh.PlaneStresses((g.nx, g.ny), g.dx, g.dy, z, NU)
    s = ops(ct.smooth / P0)[:, :, g.ny // 2]
    h = np.moveaxis(s, 1, 0)
    vals = {str(r): mx.papadopoulos_amplitude(h, mx.line_rule(*r)) for r in (coarse, fine, (32, 64, 32))}
    return {"z_over_a": 0.5, "T_sigma_over_pH": vals}


def markdown(res: dict) -> str:
    L = ["# Table 4.1: Papadopoulos beside von Mises, dry indented ball contact, full transient "
         "(benchmarks/multiaxial_table41.py)", "",
         "d = (PA_Dmax/PA_Smax - VM_Dmax/VM_Smax) / (VM_Dmax/VM_Smax); VM = max over the pass of the von Mises "
         "stress, PA = Papadopoulos' T_sigma (RMS over all planes and directions of the resolved-shear amplitude, "
         f"times sqrt 5), fine rule {FINE[0]}x{FINE[1]}x{FINE[2]} lines at each plane's {TOP} largest coarse "
         f"({COARSE[0]}x{COARSE[1]}x{COARSE[2]}) values. BEM over +/- 1.6 a; material window |xi|, |y| <= {WINDOW} a; "
         f"depth planes z = 2a (k/24)^2 (dented: z <= {Z_DENTED} a). Grid maxima. Thesis: seed 004 Table 4.1.", "",
         "| cells | Phi | K | D/Phi | VM_D/VM_S | PA_D/PA_S | d femcheck | d coarse rule | d thesis | PA_Smax/p_H (z/a) "
         "| VM_Smax/p_H | max sigma_H,max/p_H | d, T_a from zero | d, critical plane (1995) "
         "| PA/VM at the VM_Smax point, at the VM_Dmax point | time (s) |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(res["rows"].values(), key=lambda r: (r["cells"], CASES.index((r["Phi"], r["K"], r["slope"])))):
        L.append(f"| {r['cells']} | {r['Phi']} | {r['K']:g} | {r['slope']:g} | {r['VM_ratio']:.4f} | "
                 f"{r['PA_ratio']:.4f} | {100 * r['difference']:+.2f} % | {100 * r['difference_coarse_rule']:+.2f} % | "
                 f"{100 * r['thesis']:.0f} % | {r['PA_Smax']:.4f} ({r['at']['S_pa'][0]:.3f}) | {r['VM_Smax']:.4f} | "
                 f"{r['sigma_H_max_over_pH']:+.2e} | {100 * r['difference_about_zero']:+.2f} % | "
                 f"{100 * r['difference_critical_plane']:+.2f} % | {r['PA_at_VM_Smax_point'] / r['VM_Smax']:.3f}, "
                 f"{r['PA_at_VM_Dmax_point'] / r['VM_Dmax']:.3f} | {r['time_s']:.0f} |")
    if "rule_check" in res:
        rc = res["rule_check"]
        L += ["", f"Quadrature check, smooth pass at z = {rc['z_over_a']} a, y = 0 ({rc['cells']} cells): T_sigma/p_H = "
              + ", ".join(f"{v:.6f} ({k})" for k, v in rc["T_sigma_over_pH"].items()), ""]
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cells", type=int, default=97)
    ap.add_argument("--cases", default=",".join(str(i) for i in range(len(CASES))))
    ap.add_argument("--out", default="benchmarks/results")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "multiaxial_table41.json"
    res = json.loads(path.read_text()) if path.exists() else {"rows": {}}
    coarse, fine = mx.line_rule(*COARSE), mx.line_rule(*FINE)
    ct = lt.Contact(args.cells, PLANES)
    if "rule_check" not in res:
        res["rule_check"] = dict(rule_check(ct, COARSE, FINE), cells=args.cells)
    for i in (int(c) for c in args.cases.split(",")):
        phi, K, S = CASES[i]
        row = run_case(ct, phi, K, S, coarse, fine)
        res["rows"][f"{args.cells}:{phi}:{K:g}:{S:g}"] = row
        print(json.dumps({k: row[k] for k in ("cells", "Phi", "K", "slope", "VM_ratio", "PA_ratio", "difference",
                                               "difference_about_zero", "difference_critical_plane",
                                               "difference_coarse_rule", "thesis", "time_s")}), flush=True)
        path.write_text(json.dumps(res, indent=1, default=float))
        (out / "multiaxial_table41.md").write_text(markdown(res))


if __name__ == "__main__":
    main()
