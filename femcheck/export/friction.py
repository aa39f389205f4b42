"""Deck of the frictional 2D line-contact scenes (kind line_tangential): the Cattaneo shift (cattaneo-2d) as
a plane-strain contact of two meshed bodies with Coulomb friction; steady rolling (carter-2d) is refused.

Bodies (femcheck's meshes, :mod:`femcheck.meshes.plane_full`, sized as
:func:`femcheck.fem.friction_pair.condense` at ``level``): the lower block ``block_full`` (``fem_block_scale``
x 40 a x 20 a, its bottom clamped) and the upper body as the real cylinder ``cylinder_full`` of radius R (the
femcheck option ``numerics.fem_upper_body = "cylinder"``), driven through its diametral flat y = R made a
rigid body. femcheck's default upper body is the mirrored block carrying the cylinder's profile as an initial
gap; a node-by-node initial gap has no keyword both codes read (CalculiX's ``*CLEARANCE`` is one value per
pair), so the deck meshes the cylinder: its finite-body surface strain, O(a/R), is physics the half-plane
theory does not have (the module doc of :mod:`femcheck.fem.friction_pair`). Quadratic decks put the cylinder
boundary's mid-side nodes on the exact circle. A rigid cylinder (``materials.cylinder.rigid``) is one rigid body.

Contact: block top (slave, |x| <= contact_zone a) on the cylinder (master), penalty K = 1e3 E*/h as the other
decks, Coulomb friction mu = ``friction.mu`` with the stick slope lambda = 10 E*/a (CPE3) or E*/a (CPE6)
(Pa/m): the elastic slip before sliding at the largest traction mu p0 is mu p0 a / (lambda a / E*) E*, a tenth
(CPE3) or once (CPE6) the micro-slip scale mu p0 a / E* of Cattaneo's problem (the penalty is chosen as
frictional strength over an admissible pre-slip, the rule of e.g. the Nastran BFRIC entry). Stiffer is more
exact but CalculiX 2.20 did not converge (level 0): CPE3 failed at 100 E*/a (too many cutbacks) and passed at
32 and 10 E*/a; CPE6 stalled at 22 % of Q' with 10 and 3 E*/a (also with increments capped at 2 %) and passed
at E*/a. So the CPE6 deck's stick zone is smeared by its soft stick: read stick zones from the CPE3 deck.
Load control in three steps: push to the estimated approach (x held), the normal load W' at full value (x
held: normal loading of quasi-identical bodies has no tangential traction), then x released and
Q' = ``load.tangential_per_length`` ramped along +x. Unit thickness (1 m): forces are N/m.
"""
from __future__ import annotations

import numpy as np

from ..analytic import hertz
from ..errors import InputError
from ..materials import effective_modulus
from ..meshes.plane import MeshSpec
from ..meshes.plane_full import block_full, cylinder_full
from . import elements
from .assemble import PENALTY, TENSION
from .model import Contact, Deck, ElementBlock, Fixed, RigidIndenter, Step, Surface

SLAVE_ZONE, MASTER_ZONE = 1.0, 1.25
# stick slope lambda = STICK[order] E*/a (Pa/m): see the module doc
STICK = {1: 10.0, 2: 1.0}


def _tri_body(mesh, order: int, circle: tuple[float, float, float] | None = None):
    """(points, cells) of a 2D body, promoted for order 2; with ``circle`` (cx, cy, R) the mid-side nodes of edges
    whose both ends lie on that circle are moved onto it."""
    pts, tris = mesh.points.copy(), elements.orient_tris(mesh.points, mesh.triangles)
    if order == 2:
        lin = tris
        pts, tris = elements.promote(pts, tris, elements.TRI_EDGES)
        if circle is not None:
            cx, cy, R = circle
            d = np.hypot(pts[0] - cx, pts[1] - cy)
            on = np.abs(d - R) < 1e-9 * R
            both = on[lin[elements.TRI_EDGES[:, 0]]] & on[lin[elements.TRI_EDGES[:, 1]]]
            mid = np.unique(tris[3:][both])
            s = R / d[mid]
            pts[0, mid] = cx + (pts[0, mid] - cx) * s
            pts[1, mid] = cy + (pts[1, mid] - cy) * s
    return pts, tris


def approach_estimate(upper, lower, W: float, a: float, R: float, depth: float) -> float:
    """Approach (m) of the cylinder's flat towards the block's clamped bottom under W' (N/m), the two-dimensional
    estimates of Johnson (1985, ch. 5): block (W'/(pi E'))(2 ln(2 d/a) - nu/(1 - nu)), cylinder centre
    (W'/(pi E'))(2 ln(4 R/a) - 1), E' = E/(1 - nu^2). Step 1 pushes by it so that step 2's full load starts
    next to its solution (pushing by a^2/(2R) alone, 18 % of it here, left CalculiX's Newton iterations cutting
    back to failure); measured 0.5 % from CalculiX's approach on cattaneo-2d (CPE6, level 0)."""
    def part(m, log_arg: float, const: float) -> float:
        return 0.0 if m.rigid else W / (np.pi * m.E / (1.0 - m.nu**2)) * (2.0 * np.log(log_arg) - const)

    return part(lower, 2.0 * depth / a, lower.nu / (1.0 - lower.nu)) + part(upper, 4.0 * R / a, 1.0)


def cattaneo(params: dict, level: int, order: int) -> Deck:
    from ..fem.friction_line import settings_from
    from ..scene import elastic

    if params.get("kinematics.xi") is not None:
        raise InputError("kinematics.xi", "steady rolling with creepage (Carter) has no static load history "
                         "in Abaqus or CalculiX (it needs a steady-state transport or a long rolling run with "
                         "large rotations); export covers the Cattaneo shift (load.tangential_per_length, e.g. "
                         "cattaneo-2d)")
    s = settings_from(params)
    if not 0 <= level < s.levels:
        raise InputError("--level", f"{level} is not a mesh level of this scene; allowed 0..{s.levels - 1} "
                         "(numerics.fem_levels; 0 = coarsest)")
    upper, lower = elastic(params, "cylinder"), elastic(params, "block")
    if lower.rigid:
        raise InputError("materials.block.rigid", "the block is the meshed slave body; allowed: false")
    R, W = float(params["geometry.radius"]), float(params["load.per_length"])
    Q, mu = float(params["load.tangential_per_length"]), float(params["friction.mu"])
    e_star = effective_modulus(upper, lower)
    hz = hertz.line_contact(W, R, e_star)
    a = hz.half_width
    h = s.h_contact * a / 2**level
    x_c = s.contact_zone * a
    grading = s.grading / 2**level
    width, depth = s.block_width * a * s.block_scale, s.block_depth * a * s.block_scale
    bmesh = block_full(width, depth, MeshSpec(h, x_c, grading, max(h, 2.0 * a * s.block_scale)))
    cmesh = cylinder_full(R, MeshSpec(h, x_c, grading, max(h, R / 5.0)))
    bp, bt = _tri_body(bmesh, order)
    cp, ct = _tri_body(cmesh, order, (0.0, R, R))
    nb, nc = bp.shape[1], cp.shape[1]
    ref = nb + nc
    pts = np.concatenate([bp, cp, np.array([[0.0, 0.0], [R, R]])], axis=1)
    etype = elements.ELEMENT_TYPE[(2, order)]
    bb = ElementBlock(etype, bt, "EBLOCK", "BLOCK", 1)
    cb = ElementBlock(etype, ct + nb, "ECYLINDER", "CYLINDER", 1 + bt.shape[1])
    tiny = 1e-9 * a
    top = lambda X: (np.abs(X[1]) < tiny) & (np.abs(X[0]) <= SLAVE_ZONE * x_c + tiny)  # noqa: E731
    se, sf = elements.faces_on(bp, bt, elements.TRI_EDGES, top)
    rim = lambda X: (np.abs(np.hypot(X[0], X[1] - R) - R) < 1e-6 * R) & (np.abs(X[0]) <= MASTER_ZONE * x_c)  # noqa
    me, mf = elements.faces_on(cp, ct, elements.TRI_EDGES, rim)
    ntop = np.flatnonzero(top(bp))
    flat = nb + np.flatnonzero(np.abs(cp[1] - R) < 1e-9 * R)
    nsets = {"NBOTTOM": np.flatnonzero(bp[1] < -depth + tiny), "NTOP": ntop,
             "NFLAT": flat if not upper.rigid else nb + np.arange(nc),
             "NREF": np.array([ref]), "NROT": np.array([ref + 1])}
    surfaces = [Surface("SSLAVE", bb.ids[se], sf), Surface("SMASTER", cb.ids[me], mf)]
    fixed = [Fixed("NBOTTOM", (1, 2)), Fixed("NROT", (1, 2, 3))]
    K = PENALTY * e_star / h
    contact = Contact("SSLAVE", "SMASTER", K, TENSION * hz.p_max, friction=mu, stick_slope=STICK[order] * e_star / a)
    rigid = RigidIndenter("NFLAT", "ECYLINDER" if upper.rigid else None, ref, ref + 1, 2)
    steps = [Step("step 1: push the cylinder by the estimated approach, x held",
                  [(ref, 1, 0.0), (ref, 2, -approach_estimate(upper, lower, W, a, R, depth))], increment=0.5),
             Step("step 2: release the push, the normal load W' at full value (load control), x held",
                  [(ref, 1, 0.0)], loads=[(ref, 2, -W)], new=True),
             Step("step 3: x released, the tangential load Q' ramped along +x (load control)",
                  loads=[(ref, 1, Q)], full=False, new=True, increment=0.1)]
    mats = {"BLOCK": (lower.E, lower.nu), "CYLINDER": (upper.E, upper.nu) if not upper.rigid else
            (lower.E, lower.nu)}
    info = {"scene_kind": "line_tangential", "level": level, "order": order, "element": etype, "h_contact": h,
            "h_over_a": h / a, "block_nodes": nb + nc, "block_dofs": 2 * (nb + nc),
            "hertz": {"p_max": hz.p_max, "half_width": a,
                      "stick_half_width": a * np.sqrt(1.0 - Q / (mu * W)) if Q < mu * W else 0.0},
            "block_width": width, "block_depth": depth, "thickness": 1.0, "load_modelled": W,
            "tangential_load": Q, "friction": mu, "symmetry": "none (full model)", "normal": "y",
            "upper_body": "rigid cylinder" if upper.rigid else "cylinder (meshed)"}
    notes = ["upper body: the real cylinder (femcheck's default is the mirrored block with the profile as gap, "
             "which has no portable keyword)", "step 3 result: contact shear CSHEAR1 (CalculiX) / CSHEAR "
             "(Abaqus) on the block's top gives the stick zone (|shear| < mu p)"]
    return Deck(f"femcheck Cattaneo shift (plane strain), level {level} (h = {h / a:.4g} a), {etype}", 2, pts,
                [bb, cb], nsets, surfaces, mats, fixed, contact, rigid, 0.0, W, info, steps=steps,
                prints=[("NREF", "U", False), ("NBOTTOM", "RF", True)], notes=notes)
