"""The bearing_load kind's 3D single-row models: the 3D condensed model (ring compliances from a coarse 3D FE,
ISO/TS 16281 slices; :mod:`femcheck.bem.bearing_condensed3d`), the coupled-slice model (Hertz strips coupled along
the rollers through the half-space, with the reference's base-level FE corrections; :mod:`femcheck.bem.bearing_strips`)
and their contact-resolved reference (every roller's
two contacts solved on fine grids with half-space + FE-correction compliances; :mod:`femcheck.bem.bearing_resolved`,
:mod:`femcheck.fem.crb_corrections`). Rings: the outer ring clamped in its housing over
``support.housing_half_angle``, the inner ring's bore clamped to a rigid shaft.

The reference's certificate has four parts, each refined alone about the base level (ratio 2, three levels,
:func:`femcheck.solvers.convergence.certify` per quantity); value = base + each certified part's extrapolation
step, error estimate = the sum of the parts' (N). Parts: the roller FE (element layers per bin x 1, 2, 4), the
rings' FE (axial cells per bin x 1, 2, 4), the roller's correction bins (x 1, 2, 4, layers per bin held; the rings'
band-filled corrections are smooth and stay on the base bins) and the fine contact grid (x 1, 2, 4 cells per
direction). Level 0 (the coarse check's) is the base.
"""
from __future__ import annotations

import time
from typing import Any

import numpy as np

from ..analytic.bearing_load import roller_angles
from ..errors import InputError
from ..materials import Elastic
from ..meshes.cache import cached_builder
from ..result import ModelResult
from ..scene import Key

SCHEMA_3D: dict[str, Key] = {
    "geometry.roller_overall_length": Key("float", "m", "roller length end face to end face (>= roller_length)",
                                          lo=0.0),
    "numerics.condensed3d_patch": Key("float", "m", "3D condensed model: raceway patch width", lo=0.0),
    "numerics.condensed3d_refine": Key("int", "-", "3D condensed model: ring mesh level m", lo=1, hi=3,
                                       lo_closed=True, hi_closed=True),
    "numerics.resolved_patch": Key("float", "m", "resolved reference: FE correction patch width", lo=0.0),
    "numerics.resolved_bins": Key("int", "-", "resolved reference: correction bins along the roller (base)", lo=2,
                                  hi=80, lo_closed=True, hi_closed=True),
    "numerics.resolved_roller_layers": Key("int", "-", "resolved reference: roller FE layers per bin (base)", lo=1,
                                           hi=16, lo_closed=True, hi_closed=True),
    "numerics.resolved_ring_cells": Key("int", "-", "resolved reference: ring FE axial cells per bin (base)", lo=1,
                                        hi=8, lo_closed=True, hi_closed=True),
    "numerics.resolved_across": Key("int", "-", "resolved reference: contact cells across (base)", lo=4, hi=128,
                                    lo_closed=True, hi_closed=True),
    "numerics.resolved_along": Key("int", "-", "resolved reference: contact cells along (base)", lo=4, hi=640,
                                   lo_closed=True, hi_closed=True),
    "numerics.resolved_half_width": Key("float", "b", "resolved reference: grid half-width across / Hertz b at "
                                        "5 F_r/Z", lo=1.1, hi=5.0, lo_closed=True, hi_closed=True),
    "numerics.resolved_levels": Key("int", "-", "resolved reference: 1 (base only) or 3 (certificate)", lo=1, hi=3,
                                    lo_closed=True, hi_closed=True),
    "numerics.strips_per_slice": Key("int", "-", "coupled-slice model: Hertz strips per slice", lo=1, hi=32,
                                     lo_closed=True, hi_closed=True),
}
DEFAULTS_3D: dict[str, Any] = {
    "numerics.condensed3d_patch": 2.0e-3,
    "numerics.condensed3d_refine": 1,
    "numerics.resolved_patch": 0.8e-3,
    "numerics.resolved_bins": 10,
    "numerics.resolved_roller_layers": 2,
    "numerics.resolved_ring_cells": 1,
    "numerics.resolved_across": 24,
    "numerics.resolved_along": 80,
    "numerics.resolved_half_width": 1.75,
    "numerics.resolved_levels": 3,
    # 8 strips: the slice loads move by 0.3 % of the largest slice from 8 to 16 strips (crb-3d-misaligned)
    "numerics.strips_per_slice": 8,
}
# the roller FE's element size at the contact line per level of layers (fraction of the patch width): refined with
# the layers so that the elements stay about as long across as along
_H_CONTACT = {1: 0.5, 2: 0.35, 4: 0.25, 8: 0.18, 16: 0.13}
_ROLLER_RING_CELLS = 3          # ring mesh: cells from a patch to the sector edge (times m)


def validate_3d(params: dict[str, Any], run: set[str]) -> None:
    """Inputs of the 3D models: a single row of cylindrical rollers, elastic rings with their sections."""
    if params["bearing.rows"] > 1 or params["bearing.contact_angle"] > 0 or params["load.axial"] > 0:
        raise InputError("models.run", "the 3D models: a single-row cylindrical roller bearing (rows 1, "
                         "contact angle 0, no axial load)")
    for key in ("geometry.bore_diameter", "geometry.outside_diameter", "geometry.width", "materials.rings.E",
                "materials.rings.nu"):
        if key not in params:
            raise InputError(key, "required by the 3D models (condensed3d, coupled_slices, resolved)")
    if params["geometry.width"] < params["geometry.roller_length"]:
        raise InputError("geometry.width", f"{params['geometry.width']:g} m; allowed: >= geometry.roller_length "
                         f"({params['geometry.roller_length']:g} m)")
    if "coupled_slices" in run and params["bearing.crown"] == "iso" and \
            params["geometry.roller_length"] > 2.5 * params["geometry.roller_diameter"]:
        raise InputError("geometry.roller_length", f"{params['geometry.roller_length']:g} m with the ISO crown in "
                         f"coupled_slices; allowed: <= 2.5 roller diameters (one logarithmic arc)")
    if run & {"resolved", "coupled_slices"}:
        lo = params["geometry.roller_length"]
        if params.get("geometry.roller_overall_length", 0.0) < lo:
            raise InputError("geometry.roller_overall_length", f"required by the resolved reference; allowed: >= "
                             f"geometry.roller_length ({lo:g} m)")
        step = 4 if params["numerics.resolved_levels"] > 1 else 1      # the bins part goes to 4 x the bins
        if params["numerics.resolved_along"] % (step * params["numerics.resolved_bins"]):
            raise InputError("numerics.resolved_bins", f"{params['numerics.resolved_bins']}; allowed: "
                             f"{step} x bins must divide numerics.resolved_along ({params['numerics.resolved_along']})")


def _geometry(p: dict[str, Any]) -> dict[str, float]:
    d_i, d_o, D = p["geometry.inner_raceway_diameter"], p["geometry.outer_raceway_diameter"], p["geometry.roller_diameter"]
    return {"Z": p["bearing.rollers"], "D": D, "L": p["geometry.roller_length"], "r_i": 0.5 * d_i, "r_o": 0.5 * d_o,
            "bore": 0.5 * p["geometry.bore_diameter"], "od": 0.5 * p["geometry.outside_diameter"],
            "width": p["geometry.width"], "clearance": d_o - d_i - 2.0 * D, "arc": p["support.housing_half_angle"]}


def _rings(p: dict[str, Any]) -> Elastic:
    return Elastic(p["materials.rings.E"], p["materials.rings.nu"])


def _slice_fields(psi, loads, slices) -> tuple[dict, dict]:
    q = {"q_max": float(loads.max()), "loaded_rollers": float(np.count_nonzero(loads > 1e-9 * loads.max())),
         "stribeck_factor": None, "total_force": float(np.sum(loads * np.cos(psi)))}
    fields = {"roller_angle": np.angle(np.exp(1j * psi)), "roller_loads": loads, "slice_loads": slices}
    return q, fields


def condensed3d(scene, progress=None) -> ModelResult:
    """The 3D condensed model (:mod:`femcheck.bem.bearing_condensed3d`) with C = C_outer + C_inner."""
    from ..bem import bearing_condensed3d as bc
    from ..fem import ring3d_compliance as rc
    from ..meshes.ring3d import RingMeshSpec

    p = scene.params
    g = _geometry(p)
    t0 = time.perf_counter()
    C, dofs = 0.0, 0
    for name, r_race, r_back, arc in (("outer", g["r_o"], g["od"], g["arc"]), ("inner", g["r_i"], g["bore"], np.pi)):
        if progress:
            progress(f"3D condensed: {name} ring compliance (3D FE)")
        spec = RingMeshSpec(r_race, r_back, g["width"], g["L"], g["Z"], p["bearing.slices"],
                            0.5 * p["numerics.condensed3d_patch"] / r_race, refine=p["numerics.condensed3d_refine"],
                            between=_ROLLER_RING_CELLS, ends=2, radial=1)
        comp = rc.ring_compliance(rc.RingFE(spec, _rings(p), "housing", arc))
        C, dofs = C + comp.C, dofs + comp.n_dofs
    build = time.perf_counter() - t0
    row = bc.SlicedRow(g["Z"], g["L"], g["D"], g["clearance"], p["bearing.slices"], p["bearing.crown"],
                       p["bearing.tilt"], load_angle=p["load.angle"])
    sol = bc.solve(row, C, p["load.radial"])
    q, fields = _slice_fields(row.psi, sol.roller_loads, sol.slice_loads)
    q["stribeck_factor"] = g["Z"] * q["q_max"] / p["load.radial"]
    q["radial_deflection"] = float(np.hypot(*sol.u[:2]))
    stats = {"iterations": sol.iterations, "residual": sol.residual, "ring_dofs": int(dofs),
             "compliance_time_s": build, "solve_time_s": sol.time_s, "displacement": sol.u.tolist()}
    return ModelResult("condensed3d", quantities=q, stats=stats, fields=fields)


def coupled_slices(scene, progress=None) -> ModelResult:
    """Hertz strips coupled along the rollers through the half-space, with the finite-body corrections of the
    resolved reference's base level (:mod:`femcheck.bem.bearing_strips`); each slice split into
    ``numerics.strips_per_slice`` strips, the loads summed per slice."""
    from ..bem import bearing_condensed3d as bc
    from ..bem import bearing_strips as bs
    from ..bem.bearing_resolved import fine_corrections

    p = scene.params
    g = _geometry(p)
    _one_material(p, "coupled_slices")
    Z, ns, m = g["Z"], p["bearing.slices"], p["numerics.strips_per_slice"]
    base = _levels({**p, "numerics.resolved_levels": 1})[0]
    t0 = time.perf_counter()
    if progress:
        progress("coupled slices: finite-body corrections (roller and ring FE; cached across loads)")
    corr, dofs = _cached_corrections({k: v for k, v in sorted(p.items()) if k.startswith(_CORRECTION_KEYS)}, base)
    build = time.perf_counter() - t0
    # the slice load is the same at a roller's two contacts: its compliance is the sum of the contacts' four blocks
    N = Z * ns * m
    Df = fine_corrections(Z, corr, ns * m)
    D = Df[:N, :N] + Df[:N, N:] + Df[N:, :N] + Df[N:, N:]
    row = bc.SlicedRow(Z, g["L"], g["D"], g["clearance"], ns * m, p["bearing.crown"], p["bearing.tilt"],
                       load_angle=p["load.angle"])
    if progress:
        progress(f"coupled slices: {Z} rollers x {ns * m} strips")
    sol = bs.solve(row, g["r_i"], g["r_o"], _rings(p), D, p["load.radial"])
    slices = sol.slice_loads.reshape(Z, ns, m).sum(axis=2)
    q, fields = _slice_fields(row.psi, sol.roller_loads, slices)
    q["stribeck_factor"] = Z * q["q_max"] / p["load.radial"]
    q["radial_deflection"] = float(np.hypot(*sol.u[:2]))
    stats = {"iterations": sol.iterations, "width_iterations": sol.width_iterations, "residual": sol.residual,
             "strips": ns * m, **dofs, "corrections_time_s": build, "solve_time_s": sol.time_s,
             "displacement": sol.u.tolist()}
    return ModelResult("coupled_slices", quantities=q, stats=stats, fields=fields)


def _one_material(p: dict[str, Any], model: str) -> None:
    if (p["materials.rings.E"], p["materials.rings.nu"]) != (p["materials.rollers.E"], p["materials.rollers.nu"]):
        raise InputError("materials.rings.E", f"{model} takes rollers and rings of one material; allowed: "
                         "materials.rings = materials.rollers")


def _hertz_half_width(p: dict[str, Any], g: dict[str, float], radius: float) -> float:
    """Hertz half-width (m) of a line contact of relative radius ``radius`` at the roller load 5 F_r/Z (Johnson 1985
    eq. 4.45; a grid extent only: the solver refuses a contact that reaches the grid's edge)."""
    mat = Elastic(p["materials.rollers.E"], p["materials.rollers.nu"])
    e_star = mat.E / (2.0 * (1.0 - mat.nu**2))
    q = 5.0 * p["load.radial"] / g["Z"] / g["L"]
    return float(np.sqrt(4.0 * q * radius / (np.pi * e_star)))


def _levels(p: dict[str, Any]) -> list[dict[str, int]]:
    """The runs of the reference: the base, then each part's two other levels (module doc)."""
    base = {"layers": p["numerics.resolved_roller_layers"], "cells": p["numerics.resolved_ring_cells"],
            "bins": p["numerics.resolved_bins"], "across": p["numerics.resolved_across"],
            "along": p["numerics.resolved_along"], "part": "base", "index": 1}
    runs = [base]
    if p["numerics.resolved_levels"] == 1:
        return runs
    for k in (2, 4):
        runs.append({**base, "layers": k * base["layers"], "part": "roller", "index": 1 + k // 2})
        runs.append({**base, "cells": k * base["cells"], "part": "ring", "index": 1 + k // 2})
        runs.append({**base, "across": k * base["across"], "along": k * base["along"], "part": "grid",
                     "index": 1 + k // 2})
        # the roller's bins doubled, its layers per bin held (the rings' smooth, band-filled corrections stay on
        # the base bins)
        runs.append({**base, "bins": k * base["bins"], "part": "bins", "index": 1 + k // 2})
    return runs


def _corrections(p, g, lv: dict[str, int], cache: dict, progress=None):
    """The finite-body corrections (:class:`femcheck.bem.bearing_resolved.CorrectionTables`) of level ``lv`` and the
    FE sizes; the roller and ring FE are solved once per distinct mesh (``cache``)."""
    from ..bem import bearing_resolved as br
    from ..fem import crb_corrections as cc
    from ..fem.rolling_compliance import MeshSettings
    from ..meshes.ring3d import RingMeshSpec

    rings = _rings(p)
    patch = p["numerics.resolved_patch"]
    ring_bins = p["numerics.resolved_bins"]
    rkey = ("roller", lv["layers"], lv["bins"])
    if rkey not in cache:
        if progress:
            progress(f"resolved reference: roller FE ({lv['bins']} bins, {lv['layers']} layers per bin)")
        cache[rkey] = cc.roller_correction(0.5 * g["D"], p["geometry.roller_overall_length"],
                                           cc.Bins(g["L"], lv["bins"], patch),
                                           Elastic(p["materials.rollers.E"], p["materials.rollers.nu"]),
                                           MeshSettings(h_contact=_H_CONTACT.get(lv["layers"], 0.13), grading=0.3,
                                                        h_max=0.1 * g["D"], layers_per_cell=lv["layers"]))
    for name, r_race, r_back, arc in (("inner", g["r_i"], g["bore"], np.pi), ("outer", g["r_o"], g["od"], g["arc"])):
        gkey = (name, lv["cells"])
        if gkey not in cache:
            if progress:
                progress(f"resolved reference: {name} ring FE ({lv['cells']} axial cells per bin)")
            spec = RingMeshSpec(r_race, r_back, g["width"], g["L"], g["Z"], ring_bins, 0.5 * patch / r_race,
                                refine=1, between=_ROLLER_RING_CELLS, ends=2 * lv["cells"], radial=4,
                                radial_growth=3.0, per_slice=lv["cells"])
            cache[gkey] = cc.ring_correction(spec, rings, arc, cc.Bins(g["L"], ring_bins, patch))
    rol, ri, ro = cache[rkey], cache[("inner", lv["cells"])], cache[("outer", lv["cells"])]
    corr = br.CorrectionTables(rol.D, cc.filled(ri.D, g["Z"], 1), cc.filled(ro.D, g["Z"], 1), lv["bins"], ring_bins)
    dofs = {"roller_dofs": rol.stats["n_dofs"], "inner_ring_dofs": ri.stats["n_dofs"],
            "outer_ring_dofs": ro.stats["n_dofs"]}
    return corr, dofs


# what the corrections depend on (not the load, the misalignment or the crown): a load sweep reuses them
_CORRECTION_KEYS = ("geometry.", "materials.", "support.", "bearing.rollers", "numerics.resolved_")


@cached_builder("crb-corrections")
def _cached_corrections(params: dict[str, Any], lv: dict[str, int]):
    """:func:`_corrections` through the content-keyed cache (the fast model's, never the reference's: a stored
    reference re-solves its FE when checked)."""
    return _corrections(params, _geometry(params), lv, {})


def _run(p, g, lv: dict[str, int], cache: dict, progress=None) -> dict:
    """One run of the reference at level ``lv`` (module doc): roller and slice loads and the solver's record."""
    from ..bem import bearing_resolved as br

    t0 = time.perf_counter()
    corr, dofs = _corrections(p, g, lv, cache, progress)
    t_corr = time.perf_counter() - t0
    row = br.ResolvedRow(g["Z"], g["D"], g["L"], g["r_i"], g["r_o"], g["clearance"], p["bearing.tilt"],
                         p["load.angle"], p["bearing.crown"], _rings(p))
    hw = tuple(p["numerics.resolved_half_width"] * _hertz_half_width(p, g, row.curvature_radius(c))
               for c in ("inner", "outer"))
    if progress:
        progress(f"resolved reference: contacts {lv['across']} x {lv['along']} cells")
    r = br.solve(row, br.FineGrid(lv["across"], lv["along"], hw), corr, p["load.radial"])
    psi = row.psi
    return {"part": lv["part"], "index": lv["index"], "layers": lv["layers"], "cells": lv["cells"],
            "bins": lv["bins"], "across": lv["across"], "along": lv["along"], **dofs,
            "roller_loads": r.roller_loads, "slice_loads": r.slice_loads(p["bearing.slices"]),
            "q_max": r.q_max, "total_force": float(np.sum(r.roller_loads * np.cos(psi))),
            "radial_deflection": float(np.hypot(*r.delta)), "newton": r.iterations, "outer": r.outer_iterations,
            "residual": r.residual, "corrections_s": t_corr, "solve_s": r.time_s}


# formal orders of the parts (certify_formal caps the observed order by them, Roache 1998 §5.9): P2 and S2 elements
# (2) for the FE parts; the bins interpolate the correction linearly (2); the contact grid's moving contact
# edge (1)
FORMAL_ORDER = {"roller": 2.0, "ring": 2.0, "bins": 2.0, "grid": 1.0}
# Below this fraction of the family's scale (Q_max for roller loads, the largest slice load for slice loads: the
# scales the comparisons are normalised by) a part's changes carry no order: the re-meshed roller FE (Gmsh) and the
# contact sets moving across cells scatter by up to ~5e-4 of the scale between levels (measured on the 209 case).
CONVERGED_FLOOR = 1e-3


def part_certificate(part: str, qs: list[float], scale: float):
    """Certificate of one part's three levels: :func:`certify_formal` at the part's formal order; otherwise
    certified as converged when both changes are below ``CONVERGED_FLOOR`` x ``scale`` or the last is and is a
    quarter or less of the previous one (contracting faster than the formal order: converged at the middle
    level); then value = finest, estimate = 3 x the largest change that counts (Roache's factor without a
    verified order)."""
    from ..solvers.convergence import SAFETY_UNCERTIFIED, Certificate, certify_formal

    c = certify_formal([4.0, 2.0, 1.0], qs, FORMAL_ORDER[part])
    if c.certified:
        return c
    last, prev = abs(qs[2] - qs[1]), abs(qs[1] - qs[0])
    floor = CONVERGED_FLOOR * scale
    if last < floor and (prev < floor or last <= 0.25 * prev):
        worst = max(last, prev) if prev < floor else last
        return Certificate(qs[2], qs[2], None, SAFETY_UNCERTIFIED * worst / (abs(qs[2]) or 1.0), True,
                           f"converged: changes {prev / scale:.1e}, {last / scale:.1e} of the scale (floor "
                           f"{CONVERGED_FLOOR:g}{'' if prev < floor else ', contracting'})")
    return c


def _certify_parts(runs: list[dict], names: list[str], get, scale) -> dict[str, dict]:
    """Per quantity: value = base + certified parts' steps, estimate (absolute) = sum of the parts'; ``scale(n)``
    the family scale of quantity n (:func:`part_certificate`)."""
    base = runs[0]
    out = {}
    for n in names:
        value, est, cert_all, parts = get(base, n), 0.0, True, {}
        for part in ("roller", "ring", "bins", "grid"):
            lv = sorted((r for r in runs if r["part"] in (part, "base")), key=lambda r: r["index"])
            if len(lv) < 3:
                continue
            qs = [get(r, n) for r in lv]
            if not any(qs):             # no contact at any level (a roller outside the load zone): exactly zero
                parts[part] = {"levels": qs, "order": None, "certified": True, "note": "zero at every level"}
                continue
            c = part_certificate(part, qs, scale(n))
            if c.certified:
                value += c.value - get(base, n)
            est += c.error_estimate * abs(c.value)
            cert_all &= c.certified
            parts[part] = {"levels": qs, "order": c.order, "certified": c.certified, "note": c.note}
        out[n] = {"value": value, "estimate": est, "certified": cert_all and len(parts) == 4, "parts": parts}
    return out


def resolved(scene, progress=None) -> ModelResult:
    """The contact-resolved reference (module doc): roller and slice loads with their certificates."""
    p = scene.params
    g = _geometry(p)
    _one_material(p, "the resolved reference")
    cache: dict = {}
    runs = [_run(p, g, lv, cache, progress) for lv in _levels(p)]
    base = runs[0]
    Z, ns = g["Z"], p["bearing.slices"]
    names = [f"Q_{j}" for j in range(Z)] + [f"q_{j}_{k}" for j in range(Z) for k in range(ns)]

    def get(r, n):
        parts = n.split("_")
        return float(r["roller_loads"][int(parts[1])]) if len(parts) == 2 else \
            float(r["slice_loads"][int(parts[1]), int(parts[2])])

    loads, slices = base["roller_loads"].copy(), base["slice_loads"].copy()
    stats: dict[str, Any] = {"levels": [{k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in r.items()}
                                        for r in runs]}
    certs: dict[str, dict] = {}
    estimates = None
    if len(runs) > 1:
        q_scale = max(float(np.max(r["roller_loads"])) for r in runs)
        s_scale = max(float(np.max(r["slice_loads"])) for r in runs)
        c = _certify_parts(runs, names, get, lambda n: q_scale if n.startswith("Q_") else s_scale)
        loads = np.array([c[f"Q_{j}"]["value"] for j in range(Z)])
        slices = np.array([[c[f"q_{j}_{k}"]["value"] for k in range(ns)] for j in range(Z)])
        estimates = np.array([[c[f"q_{j}_{k}"]["estimate"] for k in range(ns)] for j in range(Z)])
        q_max = float(loads.max())
        big = float(slices.max())
        e_roll = max(c[f"Q_{j}"]["estimate"] for j in range(Z)) / q_max
        e_slice = max(c[f"q_{j}_{k}"]["estimate"] for j in range(Z) for k in range(ns)) / big
        ok_roll = all(c[f"Q_{j}"]["certified"] for j in range(Z))
        ok_slice = all(c[f"q_{j}_{k}"]["certified"] for j in range(Z) for k in range(ns))
        j0 = int(np.argmax(loads))
        certs = {"q_max": {"value": q_max, "finest": base["q_max"], "order": None,
                           "error_estimate": c[f"Q_{j0}"]["estimate"] / q_max,
                           "certified": c[f"Q_{j0}"]["certified"], "note": "sum of four parts, each refined alone"},
                 "stribeck_factor": {"value": Z * q_max / p["load.radial"], "finest": Z * base["q_max"] / p["load.radial"],
                                     "order": None, "error_estimate": c[f"Q_{j0}"]["estimate"] / q_max,
                                     "certified": c[f"Q_{j0}"]["certified"], "note": "Z q_max / F_r"},
                 "roller_loads_max": {"value": None, "finest": None, "order": None, "error_estimate": e_roll,
                                      "certified": ok_roll, "note": "largest roller estimate / Q_max"},
                 "slice_loads_max": {"value": None, "finest": None, "order": None, "error_estimate": e_slice,
                                     "certified": ok_slice, "note": "largest slice estimate / largest slice load"}}
        stats["parts"] = {n: c[n] for n in names[:4] + [f"q_0_{k}" for k in range(ns)]}
    stats["certificates"] = certs
    psi = roller_angles(Z, p["load.angle"])
    q, fields = _slice_fields(psi, loads, slices)
    q["stribeck_factor"] = Z * q["q_max"] / p["load.radial"]
    q["total_force"] = base["total_force"]
    if estimates is not None:
        fields["slice_load_estimates"] = estimates
    stats["cost_s"] = float(sum(r["corrections_s"] + r["solve_s"] for r in runs))
    return ModelResult("resolved", quantities=q, stats=stats, fields=fields)
