"""Two meshed bodies in frictionless contact (femcheck.solvers.two_body) and the conformal SRB sub-model
(femcheck.fem.srb_conformal), checked against closed forms: uniaxial compression (patch test), Hertz sphere on
flat (Johnson 1985 eq 4.22-4.23), elliptic Hertz for seed 000's raceway contacts. Coarse meshes only (the fine
levels and their numbers are in the H7 report)."""
import numpy as np
import pytest

from femcheck.analytic import hertz
from femcheck.errors import ConvergenceError, InputError
from femcheck.meshes.block import BlockSpec
from femcheck.meshes.srb_segments import block_body, flipped_block_body
from femcheck.solvers.two_body import ContactBody, ball_on_block, outward_normals, project, solve_two_body
from femcheck.materials import Elastic, effective_modulus

STEEL, ALU = Elastic(210e9, 0.3), Elastic(70e9, 0.33)


@pytest.fixture(autouse=True)
def _cache(tmp_path_factory, monkeypatch):
    monkeypatch.setenv("FEMCHECK_CACHE", str(tmp_path_factory.getbasetemp() / "cache"))


def _stacked_blocks(h_master, h_slave, lower=STEEL, upper=ALU):
    """Unit quarter blocks: master [0,1]^2 x [-1,0] on rollers at its bottom, slave [0,1]^2 x [0,1] driven at
    its top (u_z only), symmetry planes x = 0, y = 0: under a load F the exact state is uniaxial stress F/A."""
    mb = block_body(BlockSpec(1.0, 1.0, 1.0, 0.5, 0.5, h_master, 0.0, h_master))
    sb = flipped_block_body(BlockSpec(1.0, 1.0, 1.0, 0.5, 0.5, h_slave, 0.0, h_slave))
    master = ContactBody(mb, lower, {0: mb.mask("x0"), 1: mb.mask("y0"), 2: mb.mask("bottom")})
    slave = ContactBody(sb, upper, {0: sb.mask("x0"), 1: sb.mask("y0")}, driven=sb.mask("top"))
    return master, slave


def _everywhere(x):
    return np.ones(x.shape[1], dtype=bool)


@pytest.mark.parametrize("order", [1, 2])
def test_patch_uniform_pressure_matching_meshes(order):
    # steel block under an aluminium block, same mesh on both sides of the interface: the uniaxial stress state
    # is exactly representable (linear displacement; the frictionless interface lets the two Poisson expansions
    # slide), so the discrete solution must be it: p = F/A at every slave node and the approach
    # delta = p H (1/E1 + 1/E2) (closed form, H = 1 m for both blocks), to solver precision.
    F = 1.0e6
    master, slave = _stacked_blocks(0.3, 0.3)
    sol = solve_two_body(master, slave, F, candidates=_everywhere, initial=_everywhere, order=order)
    assert np.allclose(sol.pressure, F, rtol=1e-7)
    assert sol.approach == pytest.approx(F * (1 / STEEL.E + 1 / ALU.E), rel=1e-7)
    assert sol.active.all()


def test_patch_non_matching_meshes_known_node_to_surface_error():
    # single-pass node-to-surface contact does not pass the patch test on non-matching meshes (Taylor &
    # Papadopoulos, IJNME 1991; Wriggers 2006 §9.1): the pressure scatters about F/A while the approach (an
    # integral quantity) stays close to the uniaxial closed form. Measured here: approach within 0.06 %, nodal
    # pressures within -9 %/+3 % of F/A (mesh 0.23 on 0.3).
    F = 1.0e6
    master, slave = _stacked_blocks(0.3, 0.23)
    sol = solve_two_body(master, slave, F, candidates=_everywhere, initial=_everywhere)
    assert sol.approach == pytest.approx(F * (1 / STEEL.E + 1 / ALU.E), rel=2e-3)
    assert np.sum(sol.lam) / np.sum(sol.weight) == pytest.approx(F, rel=1e-9)   # flat faces: sum w = A exactly
    assert np.all(np.abs(sol.pressure / F - 1.0) < 0.15)


def test_projection_on_a_plane_triangle():
    # closed-form geometry: the triangle (0,0,0), (1,0,0), (0,1,0) with normal +z; a point (x, y, z) above it
    # projects to (x, y, 0) with barycentrics (1 - x - y, x, y) and gap z.
    P = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]])
    tri = np.array([[0], [1], [2]])
    x = np.array([[0.2, 0.5, 2.0], [0.3, 0.1, 2.0], [0.05, -0.01, 0.1]])
    pr = project(x, P, tri, np.array([[0.0], [0.0], [1.0]]))
    assert np.array_equal(pr.valid, [True, True, False])          # the third point is off the triangle
    assert np.allclose(pr.gap[:2], [0.05, -0.01])
    assert np.allclose(pr.bary[:, 0], [0.5, 0.2, 0.3]) and np.allclose(pr.bary[:, 1], [0.4, 0.5, 0.1])


def test_outward_normals_of_block_faces():
    # the top face z = 0 of the block [0,1]^2 x [-1,0] has the outward normal +z; of the flipped block, -z
    for body, nz in ((block_body(BlockSpec(1.0, 1.0, 1.0, 0.5, 0.5, 0.4, 0.0, 0.4)), 1.0),
                     (flipped_block_body(BlockSpec(1.0, 1.0, 1.0, 0.5, 0.5, 0.4, 0.0, 0.4)), -1.0)):
        n = outward_normals(body.points, body.tets, body.top)
        assert np.allclose(n[2], nz)


R_BALL = 0.01


def _load(ball, block, a_over_r=0.05):
    return 4.0 * effective_modulus(ball, block) * (a_over_r * R_BALL) ** 3 / (3.0 * R_BALL)


@pytest.mark.parametrize("block", [STEEL, ALU], ids=["steel-steel", "steel-aluminium"])
def test_ball_on_block_hertz(block):
    # Hertz sphere on flat (Johnson 1985 eqs 4.22-4.23): a^3 = 3 F R / (4 E*), p0 = 3 F / (2 pi a^2), with
    # a/R = 0.05 and a block of 20 a. Measured (steel on steel, P1): p_max +1.6 % / +0.8 % / +0.19 % and radius
    # -0.07 % / +0.57 % / +0.11 % at a/4, a/8, a/16; steel on aluminium p_max +0.94 / +0.55 / +0.31 %, radius
    # +2.1 / +2.3 / +0.11 %. At a/8 p_max must be within 1.5 %; the radius within 1.5 % (steel-steel) and 3 %
    # (steel-aluminium: single-pass node-to-surface pressures scatter on the non-matching meshes, see the patch
    # test above, and at a/8 the scatter at the patch edge biases the p^2 fit; it is gone at a/16).
    F = _load(STEEL, block)
    h = hertz.point_contact(F, R_BALL, effective_modulus(STEEL, block))
    r = ball_on_block(R_BALL, STEEL, block, F, 0.125)
    assert r.hertz_p_max == pytest.approx(h.p_max, rel=1e-12)
    assert r.p_max == pytest.approx(h.p_max, rel=0.015)
    assert r.radius == pytest.approx(h.semi_axis_x, rel=0.015 if block is STEEL else 0.03)
    assert r.solution.total_force == pytest.approx(0.25 * F, rel=1e-9)


def test_active_set_that_cannot_settle_raises():
    # the uniform-pressure state needs every node active; one active-set iteration from a corner of the face
    # cannot reach it: ConvergenceError (with the iteration count), never a returned state
    master, slave = _stacked_blocks(0.3, 0.3)
    with pytest.raises(ConvergenceError, match="after 1 iterations"):
        solve_two_body(master, slave, 1.0e6, candidates=_everywhere,
                       initial=lambda x: (x[0] < 0.2) & (x[1] < 0.2), max_iter=1)


SRB = {"geometry.roller_diameter": 0.0198, "geometry.crown_radius": 0.1003, "geometry.groove_radius_inner": 0.103,
       "geometry.groove_radius_outer": 0.1024, "geometry.contact_angle": np.radians(11.5), "load.normal": 5500.0,
       "materials.roller.E": 207e9, "materials.roller.nu": 0.3, "materials.ring.E": 207e9,
       "materials.ring.nu": 0.3}


@pytest.mark.slow
def test_srb_conformal_inner_semi_axes_vs_elliptic_hertz():
    # seed 000 inner raceway (roller on the real ring segment), coarse mesh (0.5 a_H): the semi-axes must be within
    # issue 4's 5 % of elliptic Hertz with srb_contact's radii (measured -2.2 % / -2.5 %; at 0.7 a_H the short
    # semi-axis is mesh noise, -1.6 % to -9.4 % between meshes); the load balance exact.
    from femcheck.fem import srb_conformal
    from femcheck.problems.srb_contact import radii

    rx, ry = radii(SRB)["inner"]
    h = hertz.elliptic_contact(5500.0, rx, ry, effective_modulus(Elastic(207e9, 0.3), Elastic(207e9, 0.3)))
    lv = srb_conformal.solve_contact({**SRB, "numerics.conformal_h_contact": 0.5}, "inner", 0)
    assert lv["semi_axis_x"] == pytest.approx(h.semi_axis_x, rel=0.05)
    assert lv["semi_axis_y"] == pytest.approx(h.semi_axis_y, rel=0.05)
    assert lv["total_force"] == pytest.approx(5500.0, rel=1e-9)


def test_srb_conformal_refuses_rigid_ring():
    from femcheck.fem import srb_conformal

    with pytest.raises(InputError, match="materials.ring.rigid"):
        srb_conformal.solve_contact({**SRB, "materials.ring.rigid": True}, "inner", 0)


@pytest.mark.parametrize("stretch", [1.0, 4.0])
def test_srb_roller_segment_volume_stretched_mesh(stretch):
    # the y-stretched mesh (meshed in y / stretch coordinates, mapped back) must be the same solid: the 90 deg
    # sector of the barrel about its axis has the closed-form volume (pi/4) int rho(y)^2 dy over |y| <= L,
    # rho(y) = D/2 - (R - sqrt(R^2 - y^2)) (seed 000 Table 1 roller). Faceting of the P1 boundary removes
    # about (4/3) h^2 / (8 rho^2) of it: h = 0.6 mm everywhere on rho ~ 9.9 mm gives 0.06 %; tolerance 0.2 %.
    from scipy.integrate import quad

    from femcheck.meshes.srb_segments import RollerSegmentSpec, roller_segment

    D, R, L = 0.0198, 0.1003, 0.012
    rho = lambda y: 0.5 * D - (R - np.sqrt(R * R - y * y))
    exact = 0.25 * np.pi * quad(lambda y: rho(y) ** 2, -L, L)[0]
    m = roller_segment(RollerSegmentSpec(D, R, L, 0.0003, 0.009, 0.0006, 0.3, 0.0006 * stretch, stretch))
    P, T = m.points, m.tets
    vol = np.einsum("ij,ij->j", np.cross((P[:, T[1]] - P[:, T[0]]).T, (P[:, T[2]] - P[:, T[0]]).T).T,
                    P[:, T[3]] - P[:, T[0]]) / 6.0
    assert np.all(vol > 0) or np.all(vol < 0)                  # no inverted tetrahedron after the map back
    assert abs(vol.sum()) == pytest.approx(exact, rel=2e-3)
    # contact-face nodes on the barrel: distance from the roller axis equals rho(y) (closed form), to rounding
    top = np.unique(m.top)
    r_axis = np.hypot(P[0, top], P[2, top] - 0.5 * D)
    assert np.allclose(r_axis, rho(P[1, top]), rtol=0.0, atol=1e-12)
