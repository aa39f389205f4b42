"""The ``calculix`` model of the point-contact (hertz-point), line-contact (hertz-line) and conformal SRB
(srb-normal) scenes: CalculiX as an independent FE code beside femcheck's own.

Where ``ccx`` is on PATH, the scene's deck (:mod:`femcheck.export.scenes`: femcheck's mesh family, rigid indenter,
node-to-surface penalty contact, push then the load under load control) is written at each of the scene's mesh
levels (``numerics.fem_levels``, 0 = coarsest), solved by ``ccx`` (one thread), its ``.frd`` / ``.dat`` read
with femcheck's own reader and the contact quantities taken with femcheck's estimators
(:func:`femcheck.export.pressure.read`): 3D linear tetrahedra C3D4 with the contact pressure CPRESS (p_max the
fitted centre value of :func:`femcheck.qoi.symmetric_contact`, semi-axes its power-law edges); 2D quadratic
triangles CPE6 with -sigma_yy at the contact-face nodes (:func:`femcheck.qoi.peak`, :func:`femcheck.qoi.edge`).
Element choice (measured, tests/test_export.py): C3D10 at a/8 takes 70 s of ccx (17x C3D4 at a/8, 3.3x C3D4 at
a/16, the scene's level 0) and only its -sigma_zz is usable (CPRESS +418 %); CPE6 is < 5 s at every hertz-line
level.

srb-normal: both raceway contacts in one deck per level of the conformal sub-model
(``numerics.conformal_levels``; :mod:`femcheck.export.srb`, the meshes of ``fem_conformal``), C3D4, CPRESS at
the roller's face nodes (:func:`femcheck.export.pressure.read_srb`); quantities with suffixes ``_inner`` /
``_outer`` like ``fem_conformal``'s, so the two codes meet on the same meshes.

Per quantity a convergence certificate over the levels (:func:`femcheck.solvers.convergence.certify_levels`,
with the estimators' standard errors) -- the certificate's value is the model's quantity. stats carry every
level (h, DOFs, ccx CPU s, Newton iterations, the raw nodal peak, the indenter's approach, the load carried).
Where ``ccx`` is absent the model is ``skipped`` with the reason (:data:`femcheck.export.run.MISSING`), never a
failure of the scene. Decks and results go to a temporary folder removed afterwards.
"""
from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

from ..result import ModelResult
from ..solvers.convergence import certificate_stats, certify_levels
from . import deck as deck_writer
from . import pressure, run, scenes
from .srb import SRB_PENALTY

ORDER = {"point_contact": 1, "line_contact": 2, "srb_contact": 1}
QUANTITIES = {"point_contact": ("p_max", "semi_axis_x", "semi_axis_y"), "line_contact": ("p_max", "half_width"),
              "srb_contact": ("p_max", "semi_axis_x", "semi_axis_y", "contact_area")}
LEVELS_KEY = {"srb_contact": "numerics.conformal_levels"}
CONTACTS = ("inner", "outer")
TIMEOUT_S = 1800.0


def model(scene, progress=None) -> ModelResult:
    """CalculiX on ``scene`` (a validated Scene of kind point_contact, line_contact or srb_contact), see the module
    doc."""
    if run.ccx() is None:
        return ModelResult("calculix", "skipped", error=run.MISSING)
    t0 = time.perf_counter()
    kind = scene.kind
    order = ORDER[kind]
    names = QUANTITIES[kind]
    n_levels = int(scene[LEVELS_KEY.get(kind, "numerics.fem_levels")])
    levels = []
    with tempfile.TemporaryDirectory(prefix="femcheck-ccx-") as tmp:
        for k in range(n_levels):
            if progress:
                progress(f"CalculiX level {k + 1}/{n_levels}")
            d = scenes.build(scene, k, order)
            path = deck_writer.write_deck(d, "calculix", Path(tmp) / f"{scene.name}-L{k}.inp")
            r = run.run(path, TIMEOUT_S)
            if not r.finished:
                raise RuntimeError(f"ccx did not finish level {k}: {'; '.join(r.errors) or 'no Job finished'}")
            run_stats = {"n_dofs": d.info["block_dofs"], "n_nodes": d.info["block_nodes"],
                         "element": d.info["element"], "ccx_cpu_s": r.cpu_s, "ccx_wall_s": r.wall_s,
                         "iterations": r.iterations}
            if kind == "srb_contact":
                per = pressure.read_srb(path)
                levels.append({c: {"h": d.info["hertz"][c]["h_contact"],
                                   "h_over_a": d.info["hertz"][c]["h_contact"] / d.info["hertz"][c]["semi_axis_x"],
                                   **per[c]} for c in CONTACTS} | run_stats)
                continue
            q = pressure.read(path)
            levels.append({"h": d.info["h_contact"], "h_over_a": d.info["h_over_a"], **run_stats,
                           **{n: q[n] for n in names}, **{k_: v for k_, v in q.items() if k_.endswith("_std") and math.isfinite(v)},
                           "p_max_nodal": q["p_max_nodal"], "pressure_from": q["pressure_from"],
                           "contact_nodes": q["contact_nodes"], "approach": q["approach"],
                           "total_force": q["total_force"]})
    if kind == "srb_contact":
        return _srb_result(levels, names, t0)
    certs = certify_levels(levels, names)
    stats = {"code": "CalculiX (ccx, one thread)", "element": levels[-1]["element"],
             "pressure_from": levels[-1]["pressure_from"],
             "contact": "node-to-surface, linear penalty K = 1e3 E*/h, rigid indenter, load control",
             "levels": levels, "ccx_cpu_s": sum(lv["ccx_cpu_s"] for lv in levels)}
    stats.update(certificate_stats(certs))
    quantities = {n: c.value for n, c in certs.items()}
    quantities["total_force"] = levels[-1]["total_force"]
    return ModelResult("calculix", time_s=time.perf_counter() - t0, quantities=quantities, stats=stats)


def _srb_result(levels: list[dict], names: tuple[str, ...], t0: float) -> ModelResult:
    """srb-normal: a certificate per contact and quantity over the levels (one level: the level itself, no
    estimate), quantities ``<name>_<contact>`` as :func:`femcheck.fem.srb_conformal.model` names them."""
    q: dict[str, float] = {}
    stats: dict = {"code": "CalculiX (ccx, one thread)", "element": levels[-1]["element"], "pressure_from": "CPRESS",
                   "contact": f"node-to-surface (roller nodes on the raceway), linear penalty K = {SRB_PENALTY:g} "
                              "E*/h, load control", "levels": levels,
                   "ccx_cpu_s": sum(lv["ccx_cpu_s"] for lv in levels)}
    for c in CONTACTS:
        per = [lv[c] for lv in levels]
        certs = certify_levels(per, names)
        for key, part in certificate_stats(certs).items():
            stats.setdefault(key, {}).update({f"{n}_{c}": v for n, v in part.items()})
        q.update({f"{n}_{c}": cert.value for n, cert in certs.items()})
        q[f"total_force_{c}"] = per[-1]["total_force"]
    q["total_force"] = q["total_force_inner"]
    return ModelResult("calculix", time_s=time.perf_counter() - t0, quantities=q, stats=stats)
