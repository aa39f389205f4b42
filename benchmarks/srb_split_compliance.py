"""Split influence coefficients for srb-rolling: half-space tables + a finite-body FE correction interpolated to
any contact grid (:mod:`femcheck.fem.compliance_split`), checked against the pure condensed FE at equal cell
counts and under FE mesh refinement at a fixed correction grid.

For each of the FE reference's levels (9 x 17, 13 x 25, 19 x 35 cells per contact at the CECT pose of Table 2's
case) the pure FE (tables tied to the mesh) is solved, the correction of one level is interpolated to the others,
and the hybrid is solved on the same grids with the same solver: the differences in the Table 2 quantities are
what the interpolation costs. Then the correction of the coarsest grid is recomputed on a finer FE mesh (half the
element size at the contact, two layers per cell) to show how far it has converged.

    python benchmarks/srb_split_compliance.py [--mu 0.1] [--out benchmarks/out/srb_split]

Writes ``<out>/split_mu<mu>_near<n>.json`` (quantities per level and model, table differences, times) and caches the FE
tables in ``<out>/tables_*.npz`` keyed on the grid and mesh settings.
"""
from __future__ import annotations

import argparse
import hashlib
import json
import pathlib
import sys
import time

import numpy as np

from femcheck.cect.influence import combined_constants
from femcheck.errors import ConvergenceError
from femcheck.fem import compliance_split as cs
from femcheck.fem.compliance_store import load as load_tables
from femcheck.fem.compliance_store import save as save_tables
from femcheck.fem.contact_grid import refined_count
from femcheck.fem.rolling_compliance import MeshSettings
from femcheck.fem.rolling_contact import RelativeCompliance
from femcheck.problems import _srb_rolling_fem as srf
from femcheck.problems import srb_rolling as kind
from femcheck.scene import elastic, load_scene

ROOT = pathlib.Path(__file__).resolve().parent.parent
QUANTITIES = ("f_x_inner", "f_x_outer", "f_lat_inner", "f_lat_outer", "f_lat_sum", "omega_m_deviation",
              "omega_R_deviation", "adhesion_fraction_inner", "adhesion_fraction_outer")


def log(msg: str) -> None:
    print(f"[{time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def levels(p: dict, n: int = 3) -> list[dict]:
    """The FE reference's levels (:func:`femcheck.problems.srb_rolling.fem`)."""
    out = []
    for k in range(n):
        f = p["numerics.fem_ratio"] ** k
        nx0 = p["numerics.fem_cells_x"]
        nx, ns = refined_count(nx0, f), refined_count(p["numerics.fem_cells_s"], f)
        mesh = MeshSettings(p["numerics.fem_h_contact"], p["numerics.fem_grading"] / f, 2e-3, 1, 2)
        out.append({"nx": nx, "ns": ns, "mesh": mesh, "half_x": 1.35 * nx / (nx0 * f)})
    return out


def _key(*parts) -> str:
    return hashlib.sha256(repr(parts).encode()).hexdigest()[:16]


def fe_tables(p: dict, cp: dict, lv: dict, mesh: MeshSettings, out: pathlib.Path) -> tuple[dict, RelativeCompliance]:
    grids = srf.pose_grids(p, cp, lv["nx"], lv["ns"], lv["half_x"])
    key = _key(lv["nx"], lv["ns"], lv["half_x"], mesh, cp["s_centre"], {k: v for k, v in p.items()
                                                                         if k.startswith(("geometry.", "materials."))})
    path = out / f"tables_{lv['nx']}x{lv['ns']}_{key}.npz"
    if (stored := load_tables(path, grids)) is not None:     # None: missing or damaged
        return grids, stored
    log(f"FE compliance {lv['nx']} x {lv['ns']} cells, mesh {mesh}")
    from femcheck.fem import srb_rolling as fe

    t = fe.compliance(p, grids, mesh, progress=log)
    save_tables(path, t)
    return grids, t


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mu", type=float, default=0.1)
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "out" / "srb_split"))
    ap.add_argument("--levels", type=int, default=3)
    ap.add_argument("--fine-mesh", action="store_true", help="also the correction on a refined FE mesh")
    ap.add_argument("--near", type=int, default=2, help="near-field fill of the correction (cells; 0: none)")
    ap.add_argument("--base", default="halfspace", choices=cs.BASES, help="analytic part of the split")
    ap.add_argument("--mesh-study", type=int, default=0, metavar="M",
                    help="the pure FE on the coarsest grid with M meshes (h_contact / m, m layers per cell, m = 1..M)")
    a = ap.parse_args(argv)
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    scene = load_scene(ROOT / "femcheck" / "scenes" / "srb-rolling.toml", overrides={"friction.mu": a.mu})
    p = scene.params
    cpath = out / f"cect_pose_mu{a.mu:g}.json"
    if cpath.exists():
        cp = json.loads(cpath.read_text())
    else:
        log("CECT equilibrium (61 x 121)")
        cp = srf.cect_pose(kind.solved(p))
        cpath.write_text(json.dumps(cp))
    constants = combined_constants(elastic(p, "roller"), elastic(p, "ring"))
    lvs = levels(p, a.levels)
    tabs, grids = [], []
    for lv in lvs:
        g, t = fe_tables(p, cp, lv, lv["mesh"], out)
        grids.append(g)
        tabs.append(t)
    results = {"mu": a.mu, "levels": [[lv["nx"], lv["ns"]] for lv in lvs], "fe": [], "hybrid": {}}

    def solve(k, tables, label):
        t0 = time.perf_counter()
        try:
            o = srf.at_cect_pose(p, cp, lvs[k]["nx"], lvs[k]["ns"], lvs[k]["mesh"], half_x=lvs[k]["half_x"],
                                 compliance=lambda _g: tables)
        except ConvergenceError as e:
            log(f"{label} on {lvs[k]['nx']} x {lvs[k]['ns']}: {e}")
            return {"error": str(e)}
        log(f"{label} on {lvs[k]['nx']} x {lvs[k]['ns']}: f_lat_sum {o['quantities']['f_lat_sum']:.5f} "
            f"({time.perf_counter() - t0:.1f} s)")
        return {q: o["quantities"][q] for q in QUANTITIES} | {"solve_s": time.perf_counter() - t0}

    for k in range(len(lvs)):
        results["fe"].append(solve(k, tabs[k], "pure FE"))
    corrs = [cs.correction(t, constants, a.near, a.base) for t in tabs]
    results["near"], results["base"] = a.near, a.base
    for c in range(len(lvs)):
        for k in range(len(lvs)):
            if k == c:
                continue
            t0 = time.perf_counter()
            try:
                h = cs.hybrid(corrs[c], grids[k], constants)
            except ValueError as e:          # a window the correction grid does not cover
                log(f"correction {lvs[c]['nx']} x {lvs[c]['ns']} on {lvs[k]['nx']} x {lvs[k]['ns']}: {e}")
                results["hybrid"][f"{c}->{k}"] = {"error": str(e)}
                continue
            build = time.perf_counter() - t0
            r = solve(k, h, f"hybrid (correction {lvs[c]['nx']} x {lvs[c]['ns']})")
            r["build_s"] = build
            r["table_difference"] = table_difference(h, tabs[k])
            results["hybrid"][f"{c}->{k}"] = r
    if a.fine_mesh:
        m0 = lvs[0]["mesh"]
        fine = MeshSettings(0.5 * m0.h_contact, m0.grading, m0.h_max, 2, m0.order)
        g, t = fe_tables(p, cp, lvs[0], fine, out)
        cf = cs.correction(t, constants, a.near, a.base)
        results["correction_mesh_refinement"] = {
            "coarse": str(m0), "fine": str(fine), "kernels": cs.correction_difference(corrs[0], cf),
            "fine_mesh_pure_fe": solve(0, t, "pure FE on the fine mesh")}
        for k in range(1, len(lvs)):
            try:
                h = cs.hybrid(cf, grids[k], constants)
            except ValueError as e:
                results["hybrid"][f"0fine->{k}"] = {"error": str(e)}
                continue
            r = solve(k, h, "hybrid (fine-mesh correction)")
            r["table_difference"] = table_difference(h, tabs[k])
            results["hybrid"][f"0fine->{k}"] = r
    if a.mesh_study:
        m0, study = lvs[0]["mesh"], []
        for m in range(1, a.mesh_study + 1):
            mesh = MeshSettings(m0.h_contact / m, m0.grading, m0.h_max, m, m0.order)
            t0 = time.perf_counter()
            _, t = fe_tables(p, cp, lvs[0], mesh, out)
            r = solve(0, t, f"pure FE, mesh h/{m}, {m} layers per cell")
            r.update({"m": m, "n_dofs": t.stats.get("n_dofs"), "tables_s": time.perf_counter() - t0 - r["solve_s"]})
            study.append(r)
        results["fixed_grid_mesh_study"] = study
    path = out / f"split_mu{a.mu:g}_near{a.near}_{a.base}.json"
    path.write_text(json.dumps(results, indent=1, default=str))
    log(f"wrote {path}")
    return 0


def table_difference(a: RelativeCompliance, b: RelativeCompliance) -> dict:
    """Per pair, the normal displacement under a smooth (elliptic) pressure on the grid, hybrid vs FE, relative
    to the largest FE value; and the same for the tangential components under a smooth p_x."""
    out = {}
    for (r, s), Ta in a.tables.items():
        Tb = b.tables[(r, s)]
        gs = a.grids[s]
        X, S = np.meshgrid(gs.x, gs.s - gs.s.mean(), indexing="ij")
        load = np.sqrt(np.clip(1 - (X / (0.8 * np.abs(gs.x).max())) ** 2 - (S / (0.8 * np.abs(S).max())) ** 2, 0,
                               None))
        n = gs.nx
        nr = a.grids[r].nx

        def apply(T):
            u = np.zeros((3, 3, nr, T.shape[3]))
            for i in range(nr):
                for j in range(n):
                    u[:, :, i] += T[:, :, i - j + n - 1] @ load[j]
            return u

        ua, ub = apply(Ta), apply(Tb)
        scale = np.abs(ub[2, 2]).max() if r == s else np.abs(ub).max()
        out[f"{r}<-{s}"] = {"nn": float(np.abs(ua[2, 2] - ub[2, 2]).max() / scale),
                            "all": float(np.abs(ua - ub).max() / scale),
                            "xx": float(np.abs(ua[0, 0] - ub[0, 0]).max() / np.abs(ub[0, 0]).max())}
    return out


if __name__ == "__main__":
    sys.exit(main())
