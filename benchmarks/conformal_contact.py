"""Cost of one conformal contact solve (femcheck.cect.conformal) on seed 000's bearing at 5.5 kN, mu = 0.1, on the
grids the roller equilibrium uses (41 x 81, 61 x 121, 81 x 161 over +-1.35 a_H x +-1.25 b_H).

State: the roller displaced by the outer contact's Hertz approach along e_z and the inner ring by the sum of
both (so each contact carries about 5.5 kN under approach control, as in the equilibrium), speeds of strip theory
H+C (near the equilibrium: partial slip with two zero-slip bands). Per contact and grid:
- ``geometry``: developed grid, exact gap (ray intersection), rigid slip, kappa;
- ``cold``: normal (Polonsky-Keer, approach control) + tangential (matrix-free Newton-FGMRES) from zero;
- ``omega``: omega_R perturbed by 1e-7 (a Jacobian column of the equilibrium): tangential only, the normal
  solution reused, warm start;
- ``pose``: d_Y perturbed by 1 nm (a Jacobian column): new gap, both problems warm-started;
- ``step``: a Newton-size change (omega_R +1e-4, d_Y +0.1 um, tilt 1 urad): both problems warm-started.
An equilibrium Newton step needs, per contact, one base solve (``step``-like) and six Jacobian columns (two
``omega``-like, four ``pose``-like): the estimate printed is 4 Newton steps of that, both contacts.
Timings are wall-clock on the shared machine (indicative; the lead re-measures alone).

Run: OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python benchmarks/conformal_contact.py
Writes benchmarks/results/conformal_contact.json and .md.
"""
from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np

from femcheck.analytic.hertz import elliptic_contact
from femcheck.cect.conformal import solve_conformal
from femcheck.cect.influence import combined_constants
from femcheck.cect.strip_bearing import strip_bearing
from femcheck.geometry import srb_bearing as sb
from femcheck.materials import Elastic

GRIDS = ((41, 81), (61, 121), (81, 161))
REPEATS = 3
MU = 0.1
STEEL = combined_constants(Elastic(207e9, 0.3), Elastic(207e9, 0.3))
B = sb.SEED_000
OMEGA_I = sb.OMEGA_INNER_SEED_000


def _best(f):
    out, best = None, np.inf
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return out, best


def main() -> dict:
    hz = {c: elliptic_contact(5500.0, *sb.hertz_radii(B)[c], STEEL.contact_modulus) for c in sb.CONTACTS}
    shift = (hz["inner"].approach + hz["outer"].approach) * B.e_z
    d = hz["outer"].approach * B.e_z                     # the roller moves towards the outer ring
    P0 = sb.Pose(d_Y=float(d[1]), d_Z=float(d[2]))
    hc = strip_bearing(B, 5500.0, MU, 207e9, 0.3, OMEGA_I)
    om, orr = hc.omega_m, hc.omega_R
    rows = []
    for nx, ns in GRIDS:
        for c in sb.CONTACTS:
            h = hz[c]

            def inputs(pose=P0, o_r=orr):
                return sb.contact_input(B, pose, c, om, o_r, OMEGA_I, 0.0, 1.35 * h.semi_axis_x,
                                        1.25 * h.semi_axis_y, nx, ns, inner_ring_shift=shift)

            def solve(ci, **kw):
                return solve_conformal(ci.grid.grid, ci.gap, STEEL, MU, np.stack([ci.slip.wx, ci.slip.ws]),
                                       ci.speeds.reference, ci.speeds.kappa, s=ci.grid.s, **kw)

            ci, t_geom = _best(inputs)
            base, t_cold = _best(lambda: solve(ci))
            ci_w, _ = _best(lambda: inputs(o_r=orr * (1 + 1e-7)))
            r_w, t_omega = _best(lambda: solve(ci_w, warm=base, normal=base.normal))
            ci_p, _ = _best(lambda: inputs(pose=sb.Pose(P0.d_Y + 1e-9, P0.d_Z)))
            r_p, t_pose = _best(lambda: solve(ci_p, warm=base))
            ci_s, _ = _best(lambda: inputs(pose=sb.Pose(P0.d_Y + 1e-7, P0.d_Z, tilt=1e-6), o_r=orr * (1 + 1e-4)))
            r_s, t_step = _best(lambda: solve(ci_s, warm=base))
            row = {"grid": [nx, ns], "contact": c, "contact_elements": base.stats["contact_elements"],
                   "normal_force_N": base.normal_force, "adhesion_fraction": base.adhesion_fraction,
                   "geometry_s": t_geom, "cold_s": t_cold, "omega_s": t_omega, "pose_s": t_pose, "step_s": t_step,
                   "cold_newton": base.stats["iterations"], "cold_gmres": base.stats["gmres_iterations"],
                   "cold_pk": base.stats["normal_iterations"],
                   "omega_newton": r_w.stats["iterations"], "omega_gmres": r_w.stats["gmres_iterations"],
                   "pose_newton": r_p.stats["iterations"], "pose_gmres": r_p.stats["gmres_iterations"],
                   "pose_pk": r_p.stats["normal_iterations"],
                   "step_newton": r_s.stats["iterations"], "step_gmres": r_s.stats["gmres_iterations"],
                   "dFx_omega_N": r_w.force_x - base.force_x, "dFx_pose_N": r_p.force_x - base.force_x}
            rows.append(row)
            print({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}, flush=True)
    est = {}
    for nx, ns in GRIDS:
        sel = [r for r in rows if r["grid"] == [nx, ns]]
        per_step = sum(r["step_s"] + 2 * r["omega_s"] + 4 * (r["pose_s"] + r["geometry_s"]) for r in sel)
        est[f"{nx}x{ns}"] = {"newton_step_s": per_step, "equilibrium_4_steps_s": 4 * per_step}
    out = {"rows": rows, "equilibrium_estimate": est, "repeats": REPEATS,
           "note": "best of 3, wall clock, shared 2-core machine under load (indicative)"}
    root = Path(__file__).parent / "results"
    (root / "conformal_contact.json").write_text(json.dumps(out, indent=1))
    lines = ["# Conformal contact solve (seed 000 bearing, 5.5 kN, mu = 0.1)", "",
             "Generated by `benchmarks/conformal_contact.py` (best of 3, wall clock, shared machine: indicative).",
             "", "| grid | contact | elements in contact | geometry (s) | cold (s) | omega col. (s) | pose col. (s) | "
             "Newton-size step (s) | cold Newton / GMRES / PK | warm Newton / GMRES |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['grid'][0]} x {r['grid'][1]} | {r['contact']} | {r['contact_elements']} | "
                     f"{r['geometry_s']:.3f} | {r['cold_s']:.3f} | {r['omega_s']:.3f} | {r['pose_s']:.3f} | "
                     f"{r['step_s']:.3f} | {r['cold_newton']} / {r['cold_gmres']} / {r['cold_pk']} | "
                     f"{r['pose_newton']} / {r['pose_gmres']} |")
    lines += ["", "Estimated equilibrium (per Newton step: both contacts, one base solve and six Jacobian columns):", ""]
    for k, v in est.items():
        lines.append(f"- {k}: {v['newton_step_s']:.2f} s per Newton step, {v['equilibrium_4_steps_s']:.1f} s for 4 steps")
    (root / "conformal_contact.md").write_text("\n".join(lines) + "\n")
    return out


if __name__ == "__main__":
    main()
