"""2D FE of the bearing section (coarse levels only): against rigid-ring theory with the exact 2D law, geometric
similarity against meshing every roller, the rings' circulant compliance, penalty against active set, and the
condensed model against the FE (spec bearing-load.md V4, V7-V10)."""
import numpy as np
import pytest

from femcheck.analytic.bearing_load import rigid_ring
from femcheck.bem import bearing_condensed as cd
from femcheck.fem import bearing2d as fe
from femcheck.materials import Elastic

STEEL = Elastic(210e9, 0.3)
RIGID = Elastic(1.0, 0.0, True)
COARSE = fe.FESettings(h_contact=0.5, grading=1.2, h_max_ring=1.0, h_max_roller=0.5)


def section(rings=RIGID, arc=np.pi, roller=STEEL, angle=0.0, z=14):
    """The 209-type bearing of the scenes: Z = 14, D = 10 mm, l = 9.6 mm, P_d = 41 um, 8900 N."""
    return fe.BearingSection(z, 5e-3, 27.4955e-3, 37.516e-3, 22.5e-3, 42.5e-3, 9.6e-3, 8900.0, angle, roller,
                             rings, arc)


def level(sec, s=fe.FESettings(), k=0):
    b, rr = fe.reference_half_width(sec)
    return fe.solve_level(sec, b, rr, k, s), rr


def test_rigid_raceways_reproduce_rigid_ring_theory_with_the_2d_law():
    """V7 at h_c = b/4: each Q_j within 0.5 % of Q_max (measured 1.5e-4), delta_r within 1 %, same loaded set;
    V4: equilibrium and the sign of every roller's interference."""
    lv, rr = level(section())
    assert np.abs(lv.roller_loads - rr.loads).max() / rr.q_max < 0.005
    assert lv.radial_deflection == pytest.approx(rr.radial_deflection, rel=0.01)
    assert np.array_equal(lv.roller_loads > 0, rr.loads > 0)
    assert abs(lv.total_force - 8900.0) / 8900.0 < 1e-8
    assert np.all((lv.interference > 0) == (lv.roller_loads > 0))
    assert lv.load_zone_angle == pytest.approx(rr.load_zone_angle, rel=0.01)
    # the most loaded roller's compression (delta_r minus half the clearance): the roller law itself
    assert lv.interference[0] == pytest.approx(rr.deflection[0], rel=0.005)


def test_a_stiffer_roller_is_seen():
    """Mutation check of the test above: 2 % stiffer rollers in the FE change the loaded roller's compression
    by ~2 %, four times its tolerance (delta_r, two thirds clearance, moves by only 0.7 %)."""
    lv, _ = level(section(roller=Elastic(1.02 * 210e9, 0.3)), COARSE)
    _, rr = level(section(), COARSE)
    assert abs(lv.interference[0] / rr.deflection[0] - 1) > 0.015


@pytest.mark.slow
def test_geometric_similarity_equals_meshing_every_roller():
    """V8: one roller condensed and rotated = all Z rollers meshed (by rotating the one roller's nodes, seed 003
    eq 1) and solved as one body: roller loads to 1e-8 (Z = 8, load line off the rollers' symmetry)."""
    sec = section(angle=0.1, z=8)
    rot, _ = level(sec, COARSE)
    mesh_all = fe.FESettings(**{**COARSE.__dict__, "similarity": "mesh_all"})
    full, _ = level(sec, mesh_all)
    assert np.abs(rot.roller_loads - full.roller_loads).max() / rot.q_max < 1e-8
    assert np.abs(rot.delta - full.delta).max() / np.abs(rot.delta).max() < 1e-8


def test_ring_compliance_is_block_circulant():
    """V9: on an axisymmetric support the Z-fold symmetric ring mesh gives C_jk = C_0,k-j (to 1e-6)."""
    from femcheck.fem.bearing2d_bodies import ring_compliance
    from femcheck.meshes import bearing2d as meshes
    from femcheck.meshes.plane import MeshSpec

    sec = section(STEEL)
    b = 1.2e-4
    zone = meshes.ZoneSpec(2.5 * b, 10)
    spec = meshes.RingSpec(sec.bore, sec.inner_raceway, 14, "outer", 0.0)
    mesh = meshes.ring(spec, zone, MeshSpec(0.5 * b, zone.t_c, 1.2, 2.5e-3))
    ring = ring_compliance(mesh, sec.inner_raceway, sec.bore, sec.angles, zone.offsets, STEEL, 2, 0.5 * b)
    assert ring.circulant
    direct = ring._solve_columns([3, 9])
    predicted = ring.columns([3, 9])
    assert np.abs(direct - predicted).max() / np.abs(direct).max() < 1e-6


def test_penalty_agrees_with_the_active_set():
    act, _ = level(section(), COARSE)
    pen, _ = level(section(), fe.FESettings(**{**COARSE.__dict__, "method": "penalty", "penalty_factor": 1e4}))
    assert np.abs(act.roller_loads - pen.roller_loads).max() / act.q_max < 2e-3
    assert 0 < pen.penetration < 1e-3 * act.radial_deflection


def test_condensed_model_against_the_fe_elastic_rings():
    """V10 (coarse FE level): each roller within 2 % of the FE Q_max, delta within 2 %, same loaded set."""
    sec = section(STEEL)
    lv, rr = level(sec, COARSE)
    r = cd.solve(sec, cd.CondensedSettings())
    assert np.abs(r.loads - lv.roller_loads).max() / lv.q_max < 0.02
    assert np.hypot(*r.delta) == pytest.approx(lv.radial_deflection, rel=0.02)
    assert np.array_equal(r.loads > 0, lv.roller_loads > 0)
    # and the rings matter: rigid-ring theory with the roller's own law is far from both
    assert abs(rr.q_max / lv.q_max - 1) > 0.05


@pytest.mark.slow
def test_condensed_model_against_the_fe_housing_arc():
    """V10 with the outer ring clamped over +-30 deg only (non-circulant outer ring)."""
    sec = section(STEEL, arc=np.radians(30.0))
    lv, _ = level(sec, COARSE)
    r = cd.solve(sec, cd.CondensedSettings())
    assert np.abs(r.loads - lv.roller_loads).max() / lv.q_max < 0.02
    assert np.hypot(*r.delta) == pytest.approx(lv.radial_deflection, rel=0.02)


def test_condensed_roller_fe_equals_closed_form():
    """The one-roller FE compliance under Hertz patches reproduces the exact 2D law (rigid rings: the condensed
    model is then the rigid-ring model)."""
    sec = section()
    law = sec.roller_law()
    b, _ = fe.reference_half_width(sec)
    off, _ = cd.roller_fem_offset(sec, law, b, cd.CondensedSettings())
    p = 3000.0 / law.length
    assert abs(law.c * off * p) / float(law.deflection(3000.0)) < 0.005
    r = cd.solve(sec, cd.CondensedSettings())
    rr = rigid_ring(14, sec.clearance, law, 8900.0)
    assert np.allclose(r.loads, rr.loads, rtol=1e-8, atol=1e-8)


def test_thin_ring_against_roark():
    """Spec §3.7: a free thin ring (t/R = 0.05) squeezed by two opposite loads P: inner-fibre diameter changes
    (pi/4 - 2/pi) and (2/pi - 1/2) P R^3/(E' I) (Roark, bending only); FE +0.32 % / +0.06 % (spec: +0.33 / +0.08 %,
    shear and normal force). Checks the sector-replicated ring mesh, P2 elasticity and the inertia relief."""
    from femcheck.bem.bearing_condensed import _hertz_patch
    from femcheck.fem.bearing2d_bodies import rigid_mode_pins, free_body_compliance, node_table, tributary_lengths, zone_nodes
    from femcheck.meshes import bearing2d as meshes
    from femcheck.meshes.plane import MeshSpec
    from femcheck.solvers.elasticity2d import make_body

    R, t, b = 35e-3, 1.75e-3, 0.1e-3
    r_in, r_out = R - t / 2, R + t / 2
    zone = meshes.ZoneSpec(2 * b, 8)
    mesh = meshes.ring(meshes.RingSpec(r_in, r_out, 4, "outer", 0.0, (0.0,)), zone, MeshSpec(b / 4, 2 * b, 0.3, t / 4))
    body = make_body(mesh, STEEL, 2)
    xy, dofs = node_table(body)
    B, M = np.zeros((body.n_dofs, 1)), np.zeros((body.n_dofs, 2))
    for a in (0.0, np.pi):                                   # unit loads pressing inwards at 0 and pi
        idx, tt = zone_nodes(xy, r_out, a, zone.t_c, b / 16)
        f = _hertz_patch(tt, tributary_lengths(tt, 2), b)
        B[dofs[0, idx], 0] -= f * np.cos(a)
        B[dofs[1, idx], 0] -= f * np.sin(a)
    r, th = np.hypot(*xy), np.arctan2(xy[1], xy[0])
    for a, col, sign in ((0.0, 0, -1), (np.pi, 0, -1), (np.pi / 2, 1, 1), (-np.pi / 2, 1, 1)):
        k = np.flatnonzero((np.abs(r - r_in) < 1e-9) & (np.abs(np.angle(np.exp(1j * (th - a)))) < 1e-9))[0]
        M[dofs[0, k], col] += sign * np.cos(a)
        M[dofs[1, k], col] += sign * np.sin(a)
    groups = np.zeros(xy.shape[1], int)
    along, across = free_body_compliance(body, xy, dofs, B, groups, rigid_mode_pins(xy, dofs, groups), M)[:, 0]
    unit = R**3 / (STEEL.E / (1 - STEEL.nu**2) * t**3 / 12)
    assert along / ((np.pi / 4 - 2 / np.pi) * unit) == pytest.approx(1.0033, abs=0.002)
    assert across / ((2 / np.pi - 0.5) * unit) == pytest.approx(1.0008, abs=0.002)


@pytest.mark.parametrize("name", ["crb-rigid-rings", "crb-elastic-rings", "crb-housing-arc"])
def test_shipped_reference_is_current_certified_and_agrees(name):
    """The stored FE references (regenerate with `femcheck run SCENE` under the lock after an FE change): current,
    q_max certified with < 0.2 % between the two finest levels, solved in < 5 min, and issue 13's agreements:
    rigid raceways = rigid-ring theory with the 2D law (0.5 % of Q_max per roller), condensed = FE (2 %)."""
    from femcheck import references
    from femcheck.problems import problem
    from femcheck.runner import model_key
    from femcheck.scene import load_scene

    sc = load_scene(name)
    ref = references.load(sc.kind, "fem", model_key(sc, "fem"))
    assert ref is not None, f"references/ has no entry for the current FE code; run femcheck run {name}"
    cert = ref.stats["certificates"]
    assert cert["q_max"]["certified"] and cert["roller_loads"]["certified"]
    levels = ref.stats["levels"]
    assert len(levels) >= 3 and abs(levels[-1]["q_max"] / levels[-2]["q_max"] - 1) < 0.002
    assert ref.stats["reference"]["run_time_s"] < 300
    model = "rigid_ring" if name == "crb-rigid-rings" else "condensed"
    res = problem(sc.kind).MODELS[model](sc)
    q, qref = res.fields["roller_loads"], ref.fields["roller_loads"]
    assert np.abs(q - qref).max() / qref.max() < (0.005 if model == "rigid_ring" else 0.02)
    if model == "condensed":
        # measured 0.04 % (full housing) and 0.07 % (arc); without the width revision (seed 003 eq 17's role)
        # the condensed model is 0.8 % off: this bound tells the two apart
        assert np.abs(q - qref).max() / qref.max() < 0.003
