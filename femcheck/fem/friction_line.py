"""2D plane-strain FE reference for line contact with Coulomb friction: Cattaneo shift and steady rolling
(scenes carter-2d, cattaneo-2d; kind ``line_tangential``).

The contact pair, its meshes and the two load cases are in :mod:`femcheck.fem.friction_pair`: two bodies
(by default two mirrored half-plane blocks carrying the cylinder's profile as the initial gap, the idealisation
of Carter's, Cattaneo's and Kalker's theories) condensed onto matching contact node pairs, Coulomb friction
solved together with the normal problem (full normal-tangential coupling of dissimilar bodies).

Error bars (the shared certificate format, :func:`femcheck.solvers.convergence.certify`):
* **mesh**: ``numerics.fem_levels`` meshes, element size h_contact 2^-k on the contact; the observed order of
  the last three levels and Richardson's extrapolation. Expected order 1 for the friction quantities: the
  adhered traction has an inverse-square-root edge that node-to-node P2 contact does not resolve (the shift,
  measured order 0.85), and the stick/slip boundary is located to sub-node accuracy from the traction reserve;
  none imposed on p_max and the half-width.
* **block**: the meshes use blocks ``numerics.fem_block_scale`` (32) x 40 a x 20 a; on the finest mesh blocks
  2x and 4x larger are solved too and extrapolated in 1/scale (order 1, measured 0.97-1.0): a clamped block adds
  a uniform surface strain of order W'/(G D) under the normal load, which the normal-tangential coupling of
  dissimilar bodies turns into a creepage. For a rigid cylinder on steel at xi = 0.005 the creep force is -82.3
  kN/m on a 40 a x 20 a block, -50.5 at 16x, -48.9 at 64x, -48.5 at 256x (finest mesh): the former 2D FE
  reference's disagreement with the exact theory (-52.3, Johnson's process) was this effect.
The reported value of a quantity is the mesh-extrapolated value plus the block correction (extrapolated minus
the finest mesh's block); its error estimate is the sum of the two relative estimates, and it is certified
when both are (a scattering block sequence bounded below the mesh error counts as negligible, :func:`combine`).
stats carry both certificates per quantity, every level and every block.

Quantities: rolling -- creep_force_x (N/m, on body 1), adhesion_length (m), adhesion_fraction (-); shift --
``shift`` (m): the FE's own micro-slip shift, the direct difference delta(Q') - delta_stick(Q') of the
partial-slip state and of the fully adhered state on the frictionless pressure (without coupling; for
quasi-identical bodies Cattaneo's micro-slip part, and the same definition as the exact model), and
``stick_half_width`` (m); both -- p_max (Pa), half_width (m), total_force (N/m). ``shift_weighted``
(uncoupled pairs only): the alternative of :func:`femcheck.fem.friction_pair.weighted_shift`, the FE slip
weighted with the closed-form adhered traction -- documented, certified like the others, never the reference.
"""
from __future__ import annotations

import time

import numpy as np

from ..errors import InputError
from ..materials import effective_modulus
from ..result import ModelResult
from ..scene import Key, elastic, fem_line_mesh_keys
from ..solvers.convergence import Certificate, certify_formal
from .friction_pair import (COUPLINGS, NORMAL_LOADINGS, UPPER_BODIES, FrictionLineSettings, condense, coupled,
                            quasi_identical, rolling_case, shift_case, weighted_shift, zone_edges)

_DEF = FrictionLineSettings()
FEM_SCHEMA = {
    **fem_line_mesh_keys(),
    "numerics.fem_block_scale": Key("float", "-", "blocks are this many times fem_block_width x fem_block_depth",
                                    lo=1.0, hi=1024.0, lo_closed=True, hi_closed=True),
    "numerics.fem_block_extrapolation": Key("bool", "-", "solve blocks 2x and 4x larger on the finest mesh and "
                                            "extrapolate the finite-block effect"),
    "numerics.fem_upper_body": Key("str", "-", "upper body: block (mirrored half-plane block with the cylinder's "
                                   "profile as gap) or cylinder (the real cylinder)", choices=UPPER_BODIES),
    "numerics.fem_coupling": Key("str", "-", "normal-tangential coupling: full (solved together), johnson "
                                 "(tangential tractions do not act on the pressure), none (both cross "
                                 "compliances dropped)", choices=COUPLINGS),
    "numerics.fem_normal_loading": Key("str", "-", "shift problem: normal load applied frictionless (as the exact "
                                       "theory) or frictional (in fem_normal_steps increments, Spence)",
                                       choices=NORMAL_LOADINGS),
    "numerics.fem_normal_steps": Key("int", "-", "normal load increments of a frictional normal loading", lo=1,
                                     hi=100, lo_closed=True, hi_closed=True),
    "numerics.fem_tangential_steps": Key("int", "-", "tangential load increments of the shift problem", lo=1,
                                         hi=100, lo_closed=True, hi_closed=True),
    "numerics.fem_tol": Key("float", "-", "residual tolerance of the frictional active set", lo=0.0, hi=1e-3,
                            hi_closed=True),
}
FEM_DEFAULTS = {
    "numerics.fem_levels": _DEF.levels,
    "numerics.fem_h_contact": _DEF.h_contact,
    "numerics.fem_grading": _DEF.grading,
    "numerics.fem_contact_zone": _DEF.contact_zone,
    "numerics.fem_block_width": _DEF.block_width,
    "numerics.fem_block_depth": _DEF.block_depth,
    "numerics.fem_block_scale": _DEF.block_scale,
    "numerics.fem_block_extrapolation": _DEF.block_extrapolation,
    "numerics.fem_order": _DEF.order,
    "numerics.fem_formulation": _DEF.formulation,
    "numerics.fem_upper_body": _DEF.upper_body,
    "numerics.fem_coupling": _DEF.coupling,
    "numerics.fem_normal_loading": _DEF.normal_loading,
    "numerics.fem_normal_steps": _DEF.normal_steps,
    "numerics.fem_tangential_steps": _DEF.tangential_steps,
    "numerics.fem_tol": _DEF.tol,
}


def settings_from(params: dict) -> FrictionLineSettings:
    n = {k.split(".", 1)[1][4:]: v for k, v in {**FEM_DEFAULTS, **params}.items()
         if k.startswith("numerics.fem_") and k in FEM_SCHEMA}
    return FrictionLineSettings(**n)


SHIFT_QUANTITIES = ("shift", "stick_half_width", "p_max", "half_width", "total_force")
ROLLING_QUANTITIES = ("creep_force_x", "adhesion_length", "adhesion_fraction", "p_max", "half_width", "total_force")
IMPOSED = ("total_force",)
# expected orders: first for everything friction-related (module doc); none imposed on the pressure peak and the
# contact half-width of the normal problem
ORDERS = {"p_max": None, "half_width": None}


def _present(params: dict, key: str) -> bool:
    return params.get(key) is not None


def solve_level(pair, problem: str, load: float, drive: float, mu: float, a: float, s: FrictionLineSettings,
                coupling: str, weighted: bool) -> tuple[dict[str, float], dict, object]:
    """The scene's load case on one condensed pair: (quantities, extra stats, result for the fields).
    ``drive``: xi (rolling) or Q' (shift, N/m)."""
    work = coupled(pair, coupling)
    if problem == "rolling":
        r = rolling_case(work, load, drive, mu, a, s.tol)
        return {k: r.quantities[k] for k in ROLLING_QUANTITIES}, {"iterations": r.iterations,
                                                                   "residual": r.residual}, r
    r = shift_case(work, load, drive, mu, a, s.normal_loading, s.normal_steps, s.tangential_steps, s.tol)
    # the adhered reference state: on the frictionless pressure, without coupling (the exact model's definition)
    r0 = shift_case(coupled(pair, "none"), load, drive, np.inf, a, "frictionless", 1, s.tangential_steps, s.tol)
    q = {k: r.quantities[k] for k in SHIFT_QUANTITIES if k != "shift"}
    q["shift"] = r.quantities["delta_t"] - r0.quantities["delta_t"]
    extra = {"iterations": r.iterations + r0.iterations, "residual": max(r.residual, r0.residual),
             "delta_t": r.quantities["delta_t"], "delta_t_adhered": r0.quantities["delta_t"]}
    if weighted:
        left, right = zone_edges(pair.x, r.pressure)
        q["shift_weighted"] = weighted_shift(pair.x, r.slip, r.p > 0, left, right)
    return q, extra, r


def combine(mesh: Certificate, block: Certificate | None, nominal_finest: float) -> Certificate:
    """The reported certificate of a quantity: mesh-extrapolated value plus the finite-block correction
    (block-extrapolated minus the finest mesh's block), relative error estimates added. Certified when both
    parts are; a block sequence that does not converge monotonically but whose conservative bound (3 x its
    largest change) is below the mesh's error estimate counts as negligible -- without normal-tangential
    coupling the block effect is at the 1e-5 level and scatters with the mesh (measured on steel/steel), which
    no larger block can resolve -- and then only the mesh certificate decides."""
    if block is None:
        return mesh
    value = mesh.value + (block.value - nominal_finest)
    scale = abs(value) if value != 0 else 1.0
    mesh_err, block_err = mesh.error_estimate * abs(mesh.value), block.error_estimate * abs(block.value)
    negligible = not block.certified and block_err <= mesh_err
    certified = mesh.certified and (block.certified or negligible)
    note = f"mesh: {mesh.note}; block: {block.note}" + (" (below the mesh error: negligible)" if negligible else "")
    return Certificate(float(value), mesh.finest, mesh.order, float((mesh_err + block_err) / scale), certified, note)


def _certify(h: list[float], values: list[float], name: str) -> Certificate:
    """Certificate of ``name`` over levels ``h`` (:func:`certify_formal`: the observed order is capped by the
    expected first order -- three FE levels scatter, e.g. the direct shift of steel/steel gives 1.82 on
    0.1/0.05/0.025 a and 0.44 on 0.05/0.025/0.0125 a, while its error against Cattaneo halves, 1.66x and
    1.94x, from level to level)."""
    if name in IMPOSED:
        return Certificate(values[-1], values[-1], None, 0.0, True, "imposed by the solver (load control)")
    return certify_formal(h, values, ORDERS.get(name, 1.0))


def block_certificate(scales: list[float], values: list[float], name: str) -> Certificate:
    """Certificate of the finite-block extrapolation over blocks ``scales`` (module doc): the block error decays
    like 1/scale under the normal-tangential coupling (the uniform surface strain W'/(G D)) and faster without
    it (measured order 4.5 on steel/steel, the tangential correction being odd about the load): formal order 1,
    a faster decay extrapolated at first order (:func:`_certify`)."""
    return _certify([1.0 / sc for sc in scales], values, name)


def model(params: dict, progress=None):
    """FE reference of the ``line_tangential`` kind (module doc): steady rolling (``kinematics.xi``) or
    Cattaneo shift (``load.tangential_per_length``) on ``numerics.fem_levels`` meshes and three block sizes
    (``numerics.fem_block_scale`` x 1, 2, 4); quantities are the certificate values (stats["certificates"]),
    stats carry every level (``levels``), every block (``blocks``) and both certificates (``mesh_certificates``,
    ``block_certificates``)."""
    from ..analytic import hertz

    t_start = time.perf_counter()
    rolling, shifting = _present(params, "kinematics.xi"), _present(params, "load.tangential_per_length")
    if rolling == shifting:
        raise InputError("kinematics.xi", "give exactly one of kinematics.xi (rolling) and "
                         "load.tangential_per_length (shift)")
    radius, load = float(params["geometry.radius"]), float(params["load.per_length"])
    mu = float(params["friction.mu"])
    if not mu > 0:
        raise InputError("friction.mu", f"{mu:g} is not allowed; allowed: (0, 10]")
    upper, lower = elastic(params, "cylinder"), elastic(params, "block")
    s = settings_from(params)
    hz = hertz.line_contact(load, radius, effective_modulus(upper, lower))
    a = hz.half_width
    problem = "rolling" if rolling else "shift"
    if shifting:
        drive = float(params["load.tangential_per_length"])
        if not abs(drive) < mu * load:
            raise InputError("load.tangential_per_length", f"{drive:g} N/m is not allowed; allowed: "
                             f"(-{mu * load:.6g}, {mu * load:.6g}) N/m (|Q'| < mu W', else gross sliding)")
    else:
        drive = float(params["kinematics.xi"])
    quasi = quasi_identical(upper, lower)
    # the weighted shift assumes no normal-tangential coupling
    weighted = shifting and (quasi or s.coupling == "none")

    levels, blocks, fine = [], [], None
    for k in range(s.levels):
        if progress:
            progress(f"FEM friction level {k + 1}/{s.levels}")
        t0 = time.perf_counter()
        pair = condense(radius, upper, lower, a, k, s)
        q, extra, r = solve_level(pair, problem, load, drive, mu, a, s, s.coupling, weighted)
        levels.append({"h": pair.h, "h_over_a": pair.h / a, "n_dofs": pair.n_dofs, "n_elements": pair.n_elements,
                       "n_contact_nodes": int(pair.x.size), "load_steps": r.steps, "time_condense_s": pair.time_s,
                       "time_s": time.perf_counter() - t0, **q, **extra})
        fine = (pair, r)
    names = list(q)
    blocks.append({"scale": s.block_scale, **{n: levels[-1][n] for n in names}})
    for factor in ((2.0, 4.0) if s.block_extrapolation else ()):
        if progress:
            progress(f"FEM friction block x{factor:g} (finest mesh)")
        t0 = time.perf_counter()
        pair = condense(radius, upper, lower, a, s.levels - 1, s, scale=factor * s.block_scale)
        q, extra, _ = solve_level(pair, problem, load, drive, mu, a, s, s.coupling, weighted)
        blocks.append({"scale": factor * s.block_scale, "n_dofs": pair.n_dofs, "time_s": time.perf_counter() - t0,
                       **q, **extra})
    h = [lv["h"] for lv in levels]
    mesh_certs = {n: _certify(h, [lv[n] for lv in levels], n) for n in names}
    block_certs = {}
    if len(blocks) > 1:
        block_certs = {n: block_certificate([b["scale"] for b in blocks], [b[n] for b in blocks], n) for n in names}
    certs = {n: combine(mesh_certs[n], block_certs.get(n), levels[-1][n]) for n in names}
    pair, r = fine
    stats = {"problem": problem, "coupling": s.coupling, "quasi_identical": quasi, "upper_body": s.upper_body,
             "normal_loading": s.normal_loading if shifting else None, "element_order": s.order,
             "formulation": pair.formulations, "finest": {n: levels[-1][n] for n in names}, "levels": levels,
             "blocks": blocks, "block": {"width": s.block_scale * s.block_width * a,
                                          "depth": s.block_scale * s.block_depth * a,
                                          "scales": [b["scale"] for b in blocks]},
             "hertz_half_width": a, "iterations": levels[-1]["iterations"], "residual": levels[-1]["residual"],
             "derivative": None if shifting else "first-order upwind (Kalker)",
             "certificates": {n: c.as_dict() for n, c in certs.items()},
             "mesh_certificates": {n: c.as_dict() for n, c in mesh_certs.items()},
             "block_certificates": {n: c.as_dict() for n, c in block_certs.items()},
             # the report's mesh-convergence plot reads the mesh extrapolation under this name
             "richardson": {n: c.as_dict() for n, c in mesh_certs.items() if n not in IMPOSED},
             "shift_method": ("direct difference delta(Q') - delta_stick(Q') of two FE solves" if shifting else None)}
    quantities = {n: c.value for n, c in certs.items()}
    fields = {"x": r.x, "pressure": r.pressure, "traction": r.traction, "stick": r.stick.astype(float)}
    if r.slip is not None:
        fields["slip"] = r.slip
    return ModelResult("fem", time_s=time.perf_counter() - t_start, quantities=quantities, stats=stats,
                       fields=fields)
