"""3D FE engine: assembly and AMG-CG against an exact linear solution, tributary areas, the rigid-indenter
active set against Hertz, and the stored certified reference of the shipped hertz-point scene."""
import numpy as np
import pytest

from femcheck import references
from femcheck.runner import model_key
from femcheck.analytic.hertz import point_contact
from femcheck.errors import InputError
from femcheck.solvers.elasticity3d import AMGElasticity, make_solid, rigid_body_modes
from femcheck.meshes.block import BlockSpec, block_quarter
from femcheck.fem.quarter_block import tributary_areas
from femcheck.materials import Elastic
from femcheck.problems import problem
from femcheck.result import ModelResult
from femcheck.scene import load_scene

SPEC = BlockSpec(2.0, 1.5, 1.0, 0.3, 0.3, 0.08, 0.5, 0.4)


@pytest.fixture(scope="module")
def small_block():
    return block_quarter(SPEC)


def test_tributary_areas_sum_to_the_top_face(small_block):
    w = tributary_areas(small_block)
    assert w.sum() == pytest.approx(SPEC.length_x * SPEC.length_y, rel=1e-12)
    assert np.all(w[np.abs(small_block.points[2]) > 1e-12] == 0.0)


def test_rigid_body_modes_have_zero_strain_energy(small_block):
    solid = make_solid(small_block, Elastic(200e9, 0.3))
    B = rigid_body_modes(solid.basis.doflocs[:, ::3])
    energy = np.einsum("ij,ij->j", B, solid.K @ B)
    assert np.abs(energy).max() < 1e-6 * abs(solid.K.diagonal()).max()


def test_amg_cg_reproduces_uniaxial_compression_exactly(small_block):
    # Top pressed down by d, bottom on rollers (u_z = 0), symmetry planes on rollers: the exact solution is
    # linear (u_z = -d (z + H)/H, lateral expansion nu d/H x), which P1 reproduces to solver precision.
    E, nu, d, H = 200e9, 0.3, 1e-5, SPEC.depth
    solid = make_solid(small_block, Elastic(E, nu))
    X = solid.basis.doflocs
    tiny = 1e-9
    fixed = np.zeros(solid.n_dofs, dtype=bool)
    fixed[0::3] |= X[0, 0::3] < tiny
    fixed[1::3] |= X[1, 1::3] < tiny
    fixed[2::3] |= X[2, 2::3] < -H + tiny
    free = np.flatnonzero(~fixed)
    top_z = np.flatnonzero(np.isin(np.arange(solid.n_dofs), free) & (np.arange(solid.n_dofs) % 3 == 2)
                           & (np.abs(X[2]) < tiny))
    pos = np.full(solid.n_dofs, -1)
    pos[free] = np.arange(free.size)
    solver = AMGElasticity(solid, free, tol=1e-12)
    u, info = solver.solve(np.zeros(free.size), pos[top_z], np.full(top_z.size, -d))
    exact = np.zeros(solid.n_dofs)
    exact[0::3] = nu * d / H * X[0, 0::3]
    exact[1::3] = nu * d / H * X[1, 1::3]
    exact[2::3] = -d * (X[2, 2::3] + H) / H
    assert np.abs(u - exact[free]).max() < 1e-9 * d
    assert info.iterations < 60                             # measured 20-30: the AMG hierarchy works
    # reaction: sigma_zz = -E d / H over the top face
    reaction = -(solver.A @ u)[pos[top_z]].sum()
    assert reaction == pytest.approx(E * d / H * SPEC.length_x * SPEC.length_y, rel=1e-9)


# two cheap levels, a/8 and a/16 (the stored reference runs a/16, a/22.6, a/32)
TWO_LEVELS = {"numerics.fem_levels": 2, "numerics.fem_h_contact": 0.125, "numerics.fem_ratio": 2.0,
              "numerics.fem_finite_size_check": False}


@pytest.mark.slow
def test_two_fem_levels_approach_hertz(femcheck_run):
    # two levels a/8, a/16 in the contact (about 8 s). Issue 4 asks the finest level of a reference to be within
    # 3 % of Hertz; the stored reference (to a/32) is checked against 1 % below. Shape-agnostic estimators
    # (femcheck.qoi, no Hertz fit): measured at a/16 p_max +0.19 %, semi-axes -0.69 % / -0.43 %.
    res = femcheck_run("hertz-point", TWO_LEVELS, models=["analytic", "fem"])
    fem, ref = res.models["fem"], res.models["analytic"].quantities
    assert fem.status == "ok", fem.error
    assert fem.quantities["p_max"] == pytest.approx(ref["p_max"], rel=0.03)
    for q in ("semi_axis_x", "semi_axis_y"):
        assert fem.quantities[q] == pytest.approx(ref[q], rel=0.01)
    coarse, fine = fem.stats["levels"]
    assert abs(fine["p_max"] / ref["p_max"] - 1) < abs(coarse["p_max"] / ref["p_max"] - 1)
    assert fem.quantities["total_force"] == pytest.approx(1000.0, rel=1e-9)
    levels = fem.stats["levels"]
    assert [lv["n_nodes"] for lv in levels] == sorted(lv["n_nodes"] for lv in levels)
    assert all(lv["residual"] < 1e-8 for lv in levels)


def test_fem_refuses_contacts_beyond_its_aspect_budget():
    # Ry/Rx = 1e4 gives b/a ~ 330, beyond the 100 the element budget allows (srb-normal's 40 is inside)
    sc = load_scene("hertz-elliptic", {"geometry.Ry": 95.0})
    with pytest.raises(InputError, match="models.run"):
        problem(sc.kind).MODELS["fem"](sc)


def test_shipped_hertz_point_reference_is_current_and_certified():
    # The stored reference must match the current FEM code and inputs (else suites would solve again): if
    # this fails after a change to the FEM code, regenerate it with `femcheck run hertz-point --rebuild`.
    sc = load_scene("hertz-point")
    key = model_key(sc, "fem")
    ref = references.load(sc.kind, "fem", key)
    assert ref is not None, "references/ has no entry for the current FEM code; run femcheck run hertz-point"
    hz = point_contact(sc["load.normal"], sc["geometry.radius"], 210e9 / (2 * (1 - 0.3**2)))
    # issue 4: extrapolated within 1 %, finest level within 3 %, fine reference < 5 min
    for q, exact in (("p_max", hz.p_max), ("semi_axis_x", hz.semi_axis_x), ("semi_axis_y", hz.semi_axis_y)):
        assert ref.quantities[q] == pytest.approx(exact, rel=0.01)
        assert ref.stats["finest"][q] == pytest.approx(exact, rel=0.03)
    assert len(ref.stats["levels"]) >= 3
    assert abs(ref.stats["finite_size"]["p_max"]) < 0.01
    assert ref.stats["reference"]["run_time_s"] < 300


def test_reference_round_trip_and_key_mismatch(tmp_path, monkeypatch):
    monkeypatch.setenv("FEMCHECK_REFERENCES", str(tmp_path))
    res = ModelResult("fem", "ok", 1.5, {"p_max": 2.0e9}, {"levels": [1, 2, 3]}, {"x": np.arange(3.0)})
    path = references.store("point_contact", "fem", "a" * 32, res, "demo", {"load.normal": 1.0})
    assert path is not None and path.is_file()
    back = references.load("point_contact", "fem", "a" * 32)
    assert back.quantities == {"p_max": 2.0e9} and back.cached
    np.testing.assert_array_equal(back.fields["x"], np.arange(3.0))
    assert back.stats["reference"]["params"] == {"load.normal": 1.0}
    # same 16-character file prefix, different full key: not this reference
    assert references.load("point_contact", "fem", "a" * 16 + "b" * 16) is None


@pytest.mark.slow
def test_report_has_3d_pictures_of_the_fem_solution(femcheck_run, tmp_path):
    pytest.importorskip("pyvista")            # installed with the test extra
    from PIL import Image

    from femcheck.report.html import write_report

    res = femcheck_run("hertz-point", TWO_LEVELS, models=["analytic", "fem"])
    fem = res.models["fem"]
    # the surface view is the contact face and the two symmetry sections; its pressure integrates to the load
    # carried by the quarter model within the resolution of the face triangles
    pts, tri, p = fem.fields["view_points"].astype(float), fem.fields["view_triangles"], fem.fields["view_pressure"]
    top = tri[:, (np.abs(pts[2][tri]) < 1e-12).all(axis=0)]
    e1, e2 = pts[:, top[1]] - pts[:, top[0]], pts[:, top[2]] - pts[:, top[0]]
    area = 0.5 * np.linalg.norm(np.cross(e1.T, e2.T), axis=1)
    force = float(np.sum(area * p[top].mean(axis=0)))
    assert force == pytest.approx(250.0, rel=0.02)
    index = write_report([res], tmp_path / "report", "pictures", 0.0)
    for key in ("mesh3d", "pressure3d"):
        png = index.parent / f"00-hertz-point-{key}.png"
        img = np.asarray(Image.open(png).convert("L"), dtype=float)
        assert img.shape == (640, 900) and img.std() > 10.0          # a rendered scene, not a blank frame
        assert png.name in index.read_text()


@pytest.mark.slow
def test_roller_fem_coarse_level_against_bem(femcheck_run):
    # one level (a/4 over the footprint, block 2L beyond it; about 16 s): the sharp-edge peak sits at the
    # roller end within one BEM cell (dy = L/129) and the centre pressure is within the 3 % of the BEM
    # (measured +2.3 % at this level, +1 % expected at a/8)
    res = femcheck_run("roller-finite", {"numerics.fem_levels": 1}, models=["bem", "fem"])
    fem, bem = res.models["fem"], res.models["bem"]
    assert fem.status == "ok", fem.error
    dy = bem.stats["dy"]
    assert abs(fem.quantities["edge_peak_y"] - bem.quantities["edge_peak_y"]) <= dy
    assert fem.quantities["p_centre"] == pytest.approx(bem.quantities["p_centre"], rel=0.03)
    assert fem.quantities["total_force"] == pytest.approx(3683.6, rel=1e-9)


def test_fem_roller_refuses_tilt():
    sc = load_scene("roller-finite", {"geometry.tilt": 1e-3})
    with pytest.raises(InputError, match="geometry.tilt"):
        problem(sc.kind).MODELS["fem"](sc)


def test_shipped_roller_reference_is_current_and_agrees_with_bem(femcheck_run):
    sc = load_scene("roller-finite")
    ref = references.load(sc.kind, "fem", model_key(sc, "fem"))
    assert ref is not None, "references/ has no roller-finite entry for the current FEM code; run femcheck run roller-finite"
    bem = femcheck_run("roller-finite", models=["bem"]).models["bem"]
    # issue 4: centre pressure within 3 % of the BEM, edge-peak position within one BEM element
    assert ref.quantities["p_centre"] == pytest.approx(bem.quantities["p_centre"], rel=0.03)
    assert abs(ref.quantities["edge_peak_y"] - bem.quantities["edge_peak_y"]) <= bem.stats["dy"]


def _level0(**kw):
    from femcheck.fem import point_contact as fp

    sc = load_scene("hertz-point")
    block = fp.equivalent_block(sc.params)
    hz = point_contact(1000.0, 0.01, block.E / (1 - block.nu**2))
    gap = lambda x, y: (x * x + y * y) / 0.02                  # noqa: E731
    return fp.solve_level(gap, block, 1000.0, hz.semi_axis_x, hz.semi_axis_x, 0, fp.FEMPointSettings(**kw))


@pytest.mark.slow
def test_direct_and_amg_solvers_give_the_same_contact():
    direct, amg = _level0(solver="direct"), _level0(solver="amg")    # 6k DOFs each
    assert direct.p_max == pytest.approx(amg.p_max, rel=1e-8)
    assert direct.approach == pytest.approx(amg.approach, rel=1e-8)


@pytest.mark.slow
def test_penalty_tends_to_the_active_set_as_one_over_kappa():
    exact = _level0()
    d2, d3 = (abs(_level0(method="penalty", penalty_factor=f).p_max / exact.p_max - 1) for f in (1e2, 1e3))
    assert 7.0 < d2 / d3 < 13.0                                     # measured 9.9 (1.0e-3 -> 1.0e-4)


def test_displacement_control_returns_the_load_of_load_control(small_block):
    from femcheck.solvers.elasticity3d import DirectElasticity
    from femcheck.solvers.rigid_indenter import active_set

    solid = make_solid(small_block, Elastic(200e9, 0.3))
    X = solid.basis.doflocs
    fixed = X[2] < -SPEC.depth + 1e-9
    fixed[0::3] |= X[0, 0::3] < 1e-9
    fixed[1::3] |= X[1, 1::3] < 1e-9
    free = np.flatnonzero(~fixed)
    pos = np.full(solid.n_dofs, -1)
    pos[free] = np.arange(free.size)
    top = np.unique(small_block.top)
    x, y = small_block.points[0, top], small_block.points[1, top]
    cand = top[x**2 + y**2 < 0.3**2]
    h = (small_block.points[0, cand] ** 2 + small_block.points[1, cand] ** 2) / 2.0     # R = 1 m
    solver = DirectElasticity(solid, free)
    first = np.hypot(small_block.points[0, cand], small_block.points[1, cand]) < 0.1
    load = active_set(solver, pos[3 * cand + 2], h, 1e7, first)
    disp = active_set(solver, pos[3 * cand + 2], h, None, first, approach=load.delta)
    assert disp.lam.sum() == pytest.approx(1e7, rel=1e-9)
    np.testing.assert_array_equal(disp.active, load.active)
