"""FE frictional rolling reference (issue 11 item 6): developed grids, the FE side's Coulomb solver, the FE
compliances against Boussinesq-Cerruti, the seed-000 normal contact against srb-normal's conformal FE, and the
groove-rolling model."""
import numpy as np
import pytest

from femcheck.analytic import hertz
from femcheck.bem.halfspace import Grid
from femcheck.cect import exact
from femcheck.cect.influence import combined_constants
from femcheck.fem.contact_grid import ContactGrid, ContactInput, centred_cells
from femcheck.fem.halfspace_tables import halfspace_compliance, halfspace_table
from femcheck.fem.rolling_contact import approach_unknown, solve_rolling
from femcheck.materials import Elastic

STEEL = Elastic(210e9, 0.28)


def test_developed_coordinates_invert_the_grid():
    g = ContactGrid([0.0, 0.0, 0.093], 0.103, [0, 0, -1.0], [0, 1.0, 0], [-1.0, 0, 0], centred_cells(3e-4, 5),
                    centred_cells(0.012, 7))
    P = g.cell_centres()
    x, s, nu = g.developed(P)
    assert np.allclose(x, g.x[:, None]) and np.allclose(s, g.s[None, :], atol=1e-15) and np.abs(nu).max() < 1e-15
    # the normal points into body 1 (towards the groove centre) and is orthogonal to the tangent and to e_x
    fr = g.frame(g.s)
    assert np.allclose(np.einsum("kij,klj->kil", fr, fr), np.eye(3))
    assert np.allclose(g.normal(0.0), [0, 0, 1.0])


def _planar_case(mu=0.3, creep=(1e-3, 5e-4, 2.0), nx=21):
    cst = combined_constants(STEEL, STEEL)
    Rx, Ry, N = 0.01, 0.03, 1000.0
    hz = hertz.elliptic_contact(N, Rx, Ry, cst.contact_modulus)
    g = Grid(nx, nx, 2.6 * hz.semi_axis_x / nx, 2.6 * hz.semi_axis_y / nx)
    cg = ContactGrid([0, 0, 0], np.inf, [0, 0, -1.0], [0, 1.0, 0], [1.0, 0, 0], g.x, g.y, "c")
    X, Y = g.mesh()
    xi, eta, phi = creep
    inp = ContactInput(cg, X**2 / (2 * Rx) + Y**2 / (2 * Ry), np.stack([xi - phi * Y, eta + phi * X]), 1.0)
    fe = solve_rolling(halfspace_compliance({"c": cg}, cst), {"c": inp}, mu,
                       [approach_unknown("delta", "c", cg, [0, 0, 1.0], N, hz.approach)])
    ref = exact.solve_contact(g, lambda x, y: x**2 / (2 * Rx) + y**2 / (2 * Ry), cst, N, mu, creepages=creep,
                              tangential_solver="dense")
    return fe, ref


def test_fe_coulomb_solver_reproduces_the_planar_exact_theory():
    """Same discrete equations (Boussinesq-Cerruti tables, kappa = 1), independent algorithms: the FE side's
    coupled semi-smooth Newton and the exact theory's Johnson process (PK normal + tangential Newton) agree to
    solver tolerance. Catches a sign flip or a missing 1/dx in the rolling operator, a wrong slip convention and a
    wrong friction bound."""
    fe, ref = _planar_case()
    r = fe.contacts["c"]
    p0 = ref.pressure.max()
    assert fe.residual < 1e-9 and fe.iterations < 30
    assert np.abs(r.pressure - ref.pressure).max() < 1e-7 * p0
    assert np.abs(r.px - ref.px).max() < 1e-7 * p0 and np.abs(r.ps - ref.py).max() < 1e-7 * p0
    assert r.creep_force_x == pytest.approx(ref.creep_force_x, rel=1e-7)
    assert r.spin_moment == pytest.approx(ref.spin_moment, rel=1e-6)
    assert fe.theta["delta"] == pytest.approx(ref.approach, rel=1e-8)
    assert r.adhesion_fraction == ref.adhesion_fraction
    # Coulomb dissipates everywhere; in adhesion the slip vanishes
    assert (r.power_density >= -1e-9 * r.power_density.max()).all()
    assert np.abs(r.slip_velocity[:, r.adhesion]).max() < 1e-9


def test_fe_coulomb_solver_full_slip_limit():
    """Large creepage: every contact cell slides with |p_t| = mu p_n, and the creep force is mu N against the
    slip (Carter's saturation), along -xi up to the small lateral slip of the elastic deformation."""
    fe, ref = _planar_case(mu=0.2, creep=(0.05, 0.0, 0.0))
    r = fe.contacts["c"]
    assert r.adhesion_fraction == 0.0
    assert np.abs(np.hypot(r.px, r.ps) - 0.2 * r.pressure).max() < 1e-9 * r.pressure.max()
    assert r.creep_force_x == pytest.approx(-0.2 * 1000.0, rel=1e-4)


def _layered_block_tables(h_contact=0.5, E=STEEL.E):
    from femcheck.fem.body_compliance import BodyModel, body_compliance
    from femcheck.meshes.layered_bodies import BlockSpec, cell_layers, flat_block

    nx, ns, dx, ds = 9, 9, 1e-4, 1e-3
    grid = ContactGrid([0, 0, 0], np.inf, [0, 0, -1.0], [0, 1.0, 0], [1.0, 0, 0], centred_cells(nx * dx / 2, nx),
                       centred_cells(ns * ds / 2, ns), "c")
    L = 0.16
    layers = cell_layers(grid.s[0] - ds / 2 + ds * np.arange(ns + 1), -L, L, 1)
    mesh = flat_block(BlockSpec(L, L, layers, h_contact * dx, 0.3, L / 8, (dx / 2,)))
    mat = Elastic(E, STEEL.nu)
    bc = body_compliance(BodyModel("block", mesh, mat, ("bottom",), False, 2), {"c": grid})
    return grid, bc


@pytest.mark.slow
def test_fe_influence_coefficients_planar_limit():
    """A large clamped block (0.16 m, 1600 cells) against Boussinesq-Cerruti for one body (body 1 rigid): the
    displacement under a smooth (Hertzian) traction on the 9 x 9 grid within 2 % for every component pair that
    carries it (measured: xx 0.9 %, ss 0.8 %, nn 1.1 % stiff), single-cell self coefficients within 12 % (one
    P2 layer per cell along s: the traction jumps at the cells' s-edges are not resolved; they cancel in smooth
    loads). Catches the stiffness scaled by 1.02 (nn becomes 3 % stiff) and sign errors in the frames."""
    grid, bc = _layered_block_tables()
    T = bc.tables[("c", "c")]
    lag0, B = halfspace_table(grid, grid, combined_constants(Elastic(1.0, 0.0, rigid=True), Elastic(STEEL.E, STEEL.nu)))
    assert lag0 == bc.lag0[("c", "c")]
    X, S = np.meshgrid(grid.x, grid.s, indexing="ij")
    p = np.sqrt(np.clip(1 - (X / (4.4 * grid.dx)) ** 2 - (S / (4.4 * grid.ds)) ** 2, 0, None))
    n = grid.nx

    def apply(tab):
        u = np.zeros((n, grid.ns))
        for i in range(n):
            for j in range(n):
                u[i] += tab[i - j + n - 1] @ p[j]
        return u

    ref_nn = np.abs(apply(B[2, 2])).max()
    for i, j in ((0, 0), (1, 1), (2, 2)):
        uf, ur = apply(T[i, j]), apply(B[i, j])
        k = np.argmax(np.abs(ur))
        assert uf.flat[k] / ur.flat[k] == pytest.approx(1.0, abs=0.02), (i, j)
        self_ratio = T[i, j][n - 1, grid.ns // 2, grid.ns // 2] / B[i, j][n - 1, grid.ns // 2, grid.ns // 2]
        assert abs(self_ratio - 1.0) < 0.12, (i, j, self_ratio)
    for i, j in ((0, 2), (2, 0), (1, 2), (2, 1)):          # normal-tangential coupling of one body
        assert np.abs(apply(T[i, j]) - apply(B[i, j])).max() < 0.01 * ref_nn, (i, j)


SRB = {"geometry.roller_diameter": 0.0198, "geometry.crown_radius": 0.1003, "geometry.groove_radius_inner": 0.103,
       "geometry.groove_radius_outer": 0.1024, "geometry.contact_angle": np.deg2rad(11.5),
       "materials.roller.E": 207e9, "materials.roller.nu": 0.3, "materials.ring.E": 207e9, "materials.ring.nu": 0.3}
# srb-normal's stored fem_conformal reference (references/srb_contact/fem_conformal-*.json): roller and raceway
# segments, two-body node-to-surface P1 contact, 5.5 kN
CONFORMAL = {"inner": (0.21209776e-3, 8.766443e-3), "outer": (0.22907160e-3, 9.549298e-3)}


@pytest.mark.slow
def test_srb_normal_contact_against_conformal_fe_and_hertz():
    """Both contacts of the whole FE roller at 5.5 kN each (mu -> 0, coarse 11 x 21 cells): semi-axes from the
    p^2 ellipse fit within 3 % of srb-normal's conformal FE (measured +2.5/+0.25 % inner, +0.3/+0.55 % outer) and
    of elliptic Hertz (finite-body caveat: the long semi-axis is 2-3 % short in both FE models, the roller
    radius 9.9 mm being about b)."""
    from femcheck.fem import srb_rolling
    from femcheck.fem.rolling_compliance import MeshSettings
    from femcheck.fem.rolling_geometry import Crowned, Grooved, gap
    from femcheck.qoi import ellipse_fit

    N = 5500.0
    grids = srb_rolling.grids(SRB, 11, 21, N, half_s=1.25)
    tables = srb_rolling.compliance(SRB, grids, MeshSettings(0.7, 0.4, 2e-3, 1, 2))
    geo = srb_rolling.geometry(SRB)
    roller = Crowned(np.zeros(3), np.array([0, 1.0, 0]), geo["r"], geo["R"])
    inputs, extras = {}, []
    hz = srb_rolling.hertz_estimates(SRB, N)
    for c, g in grids.items():
        ring = Grooved(geo[c]["G"], geo[c]["rg"], geo["O"], geo["Y"])
        inputs[c] = ContactInput(g, gap(g, roller, ring), np.zeros((2, g.nx, g.ns)), 1.0)
        extras.append(approach_unknown(c, c, g, g.normal(0.0), N, hz[c].approach))
    sol = srb_rolling.solve_contacts(tables, inputs, 1e-6, extras)
    for c, g in grids.items():
        r = sol.contacts[c]
        X, S = np.meshgrid(g.x, g.s, indexing="ij")
        m = r.pressure > 0
        fit = ellipse_fit(X[m], S[m], r.pressure[m])
        assert fit["semi_axis_x"] == pytest.approx(CONFORMAL[c][0], rel=0.03)
        assert fit["semi_axis_y"] == pytest.approx(CONFORMAL[c][1], rel=0.03)
        assert fit["semi_axis_x"] == pytest.approx(hz[c].semi_axis_x, rel=0.03)
        assert fit["semi_axis_y"] == pytest.approx(hz[c].semi_axis_y, rel=0.03)
        assert r.normal_force == pytest.approx(N, rel=1e-9)


GROOVE = {"geometry.rolling_radius": 0.0099, "geometry.crown_radius": 0.1003, "geometry.groove_radius": 0.103,
          "geometry.ring_curvature": 1 / 0.0826, "load.normal": 5500.0, "friction.mu": 0.3,
          "materials.body1.E": 207e9, "materials.body1.nu": 0.3, "materials.body2.E": 207e9,
          "materials.body2.nu": 0.3, "kinematics.speed": 2.234, "numerics.fem_levels": 1}


@pytest.mark.slow
def test_groove_rolling_fem_model_one_level():
    """The seed-000 inner contact as a groove-rolling scene (one level): free rolling (longitudinal force 0),
    load control, angle span within 3 % of the Hertz estimate 2 b_H / r_g (10.0 deg), a partial-slip state
    dissipating power, the free-rolling creepage negative (the crown's apex runs fastest)."""
    from femcheck.fem.groove_rolling import model

    r = model(GROOVE)
    q, lv = r.quantities, r.stats["levels"][0]
    assert lv["normal_force"] == pytest.approx(5500.0, rel=1e-9)
    assert abs(lv["creep_force_x"]) < 1e-6 * 0.3 * 5500.0
    hz = r.stats["hertz"]
    assert q["angle_span"] == pytest.approx(2 * hz["semi_axis_y"] / 0.103, rel=0.03)
    assert 0.05 < q["adhesion_fraction"] < 0.6
    assert q["friction_power"] > 0 and q["creepage_x"] < 0
    assert r.stats["certificates"]["p_max"]["certified"] is False
    # the scene is symmetric about s = 0 and so is the mirrored layered mesh: no spin moment, no lateral force
    # (with the prisms split with one handedness through the whole width: 5.7e-3 N m, 0.8 N)
    assert q["spin_moment"] == 0.0
    assert abs(lv["creep_force_s"]) < 1e-5 * 0.3 * 5500.0
    assert abs(lv["pressure_centre_s"]) < 1e-6 * hz["semi_axis_y"]
    # steady rolling: the frictional power equals the rigid slip's power up to the first-order dissipation of the
    # upwind rolling difference (the exact theory: 2 % at 21 cells along x; here 11 cells: measured -9.1 %)
    assert lv["friction_power"] == pytest.approx(lv["rigid_slip_power"], rel=0.12)
    assert lv["friction_power"] < lv["rigid_slip_power"]


def test_groove_rolling_refuses_bad_input():
    from femcheck.errors import InputError
    from femcheck.fem.groove_rolling import setup

    with pytest.raises(InputError, match="geometry.groove_radius"):
        setup({**GROOVE, "geometry.groove_radius": 0.1})
    with pytest.raises(InputError, match="friction.mu"):
        setup({**GROOVE, "friction.mu": -0.1})
    with pytest.raises(InputError, match="geometry.ring_curvature"):
        setup({**GROOVE, "geometry.ring_curvature": -60.0})


@pytest.mark.parametrize("k", [0.1, 0.36, 0.5, 2.0 / 3.0, 0.69, 0.7, 0.9, 1.0])
def test_crown_map_is_monotone_and_exact_on_the_rim(k):
    """The section map of the crowned body (meshes.layered_bodies._crown_map) carries the disk of radius r onto
    the disk of radius k r: the rim onto the rim, monotone in a with slope >= 0.1 (elements neither fold nor
    flatten; the cubic X = a (1 + (k - 1)(a/r)^2) alone has slope 1 - 3 (1 - k) at the rim: negative below
    k = 2/3, where groove/crown 1.002 brings the roller's ends), and X = a to 1e-3 at the contact (a <= 0.03 r,
    where the influence cells' edges sit) wherever the contact can be (k >= 0.7)."""
    from femcheck.meshes.layered_bodies import _crown_map

    r = 0.0099
    a = np.linspace(0.0, r, 20001)
    th = np.linspace(-0.5 * np.pi, 0.5 * np.pi, 181)
    X, Z = _crown_map(r * np.cos(th), r * np.sin(th), k, r)
    assert np.hypot(X, Z) == pytest.approx(k * r, rel=1e-12)
    X, _ = _crown_map(a, np.zeros_like(a), k, r)
    assert np.diff(X).min() / (a[1] - a[0]) > 0.1 - 1e-6
    near = (a > 0) & (a <= 0.03 * r)
    if k >= 0.7:
        assert np.abs(X[near] / a[near] - 1.0).max() < 1e-3


def test_layered_meshes_are_keyed_on_their_own_module(monkeypatch):
    """The layered bodies' mesh cache key includes the source of meshes.layered_bodies (its maps are part of the
    mesh): keyed on srb_segments only, a changed map kept serving old meshes (a folded 1.002 roller did)."""
    from femcheck.meshes import layered_bodies

    seen = []
    monkeypatch.setattr(layered_bodies, "cached", lambda kind, spec, module, *a, **k: seen.append(module))
    layered_bodies.crowned_body(None)
    assert seen == ["femcheck.meshes.layered_bodies"]


@pytest.mark.slow
def test_groove_rolling_fem_runs_on_the_widest_conformal_patch():
    """groove/crown 1.002 (one level, 11 x 21 cells): the patch spans 2 x 26 mm of a roller 9.9 mm in radius, whose
    section shrinks to 0.36 r at the FE body's ends (the mesh map must not fold there) and whose far side lies
    within the default search depth (5 ds) of the contact profile (it must not be taken for the contact face).
    Checks: load control, free rolling, symmetry, steady-rolling energy balance as on the default scene, and the
    contact longer and lower than the half-space theory's: the finite, slender roller is more compliant than a
    half-space (measured: angle span +10 %, p_max -3.5 % against cect's 26.6 deg, 0.856 GPa)."""
    from femcheck.fem.groove_rolling import model

    r = model({**GROOVE, "geometry.groove_radius": 0.1003 * 1.002})
    q, lv = r.quantities, r.stats["levels"][0]
    assert lv["normal_force"] == pytest.approx(5500.0, rel=1e-9)
    assert abs(lv["creep_force_x"]) < 1e-6 * 0.3 * 5500.0
    assert q["spin_moment"] == 0.0
    assert abs(lv["creep_force_s"]) < 1e-5 * 0.3 * 5500.0
    assert lv["friction_power"] == pytest.approx(lv["rigid_slip_power"], rel=0.12)
    assert 1.05 < q["angle_span"] / np.deg2rad(26.60) < 1.15
    assert 0.93 < q["p_max"] / 0.856e9 < 0.99
