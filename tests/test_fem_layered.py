"""Layered (coated-block) FE references: femcheck.meshes.coated, layered_line (2D), layered_point (3D).

Every assertion compares with an independent value: a closed form (1D constrained compression, Hertz, Johnson's
thin-layer solutions, exact edge profiles) with the tolerance and its reason stated next to it.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.sparse import diags
from scipy.sparse.linalg import spsolve
from skfem import FacetBasis, LinearForm, asm

from femcheck.analytic import hertz, thin_layer
from femcheck.errors import InputError
from femcheck.fem import layered_line as L
from femcheck.meshes.coated import LAYER, SUBSTRATE, LayerSizing, coated_block_half, graded_sequence, subdivide
from femcheck.materials import Elastic

STEEL = Elastic(206e9, 0.30)
R = 0.01            # cylinder radius (m)


# ---------------------------------------------------------------- mesh and assembly


def test_nested_sequences_and_conforming_mesh():
    # Level k splits every level-0 interval in 2^k (Richardson needs a nested, similar family): the level-2
    # sequence contains every level-0 node. The mesh must be conforming: each interior edge shared by exactly
    # two triangles, boundary edges only on the four sides of the block.
    s0 = graded_sequence(20.0, 0.0, 0.1, 0.4, 2.0, uniform_to=1.3)
    s2 = subdivide(s0, 4)
    assert s2[0] == 0.0 and s2[-1] == 20.0 and np.all(np.diff(s2) > 0)
    assert np.isin(s0, s2).all()
    assert np.diff(s0)[s0[:-1] < 1.3].max() <= 0.1 + 1e-12
    lm = coated_block_half(40.0, 20.0, 0.02, LayerSizing(0.1, 1.3, 0.4, 2.0, 2), 1)
    t = lm.mesh.triangles
    e = np.sort(np.concatenate([t[[0, 1]], t[[1, 2]], t[[2, 0]]], axis=1), axis=0)
    edges, count = np.unique(e, axis=1, return_counts=True)
    assert set(np.unique(count)) == {1, 2}
    mid = lm.mesh.points[:, edges[:, count == 1]].mean(axis=1)
    on_box = (np.abs(mid[0]) < 1e-12) | (np.abs(mid[0] - 20) < 1e-12) | (np.abs(mid[1]) < 1e-12) | \
        (np.abs(mid[1] + 20) < 1e-12)
    assert on_box.all()
    assert lm.layer_rows == 4                          # 2 rows at level 0, doubled at level 1


@pytest.mark.parametrize("nu_layer", [0.25, 0.5])
def test_constrained_compression_of_a_coated_block(nu_layer):
    # Uniform pressure q on a coated block with rollers on both sides and a clamped bottom: uniaxial strain in
    # each region, so u_y(top) = -q (t/M1 + (D - t)/M2) exactly, M = (1 - nu) E / ((1 + nu)(1 - 2 nu)) the
    # constrained modulus (M1 = inf for an incompressible layer). The FE solution is piecewise linear in y,
    # which P2 (and the mixed P2/P1 form, whose per-region pressure may jump at the interface) represent
    # exactly: agreement to round-off (1e-9) tests the two-material assembly and the bonded interface.
    E1, q, width, depth, t = 500e9, 1e8, 4.0, 2.0, 0.3
    layer = Elastic(E1, nu_layer)
    lm = coated_block_half(width, depth, t, LayerSizing(0.2, 0.5, 0.5, 1.0, 2), 0)
    body, forms = L.assemble_layered(lm, {LAYER: layer, SUBSTRATE: STEEL})
    assert forms["layer"] == ("mixed" if nu_layer > 0.45 else "displacement")
    basis, mesh = body.basis, body.basis.mesh
    top = mesh.facets_satisfying(lambda X: np.abs(X[1]) < 1e-12, boundaries_only=True)
    f = np.zeros(body.n_dofs)
    f[:basis.N] = asm(LinearForm(lambda v, _: -q * v[1]), FacetBasis(mesh, basis.elem, facets=top))
    bfac = mesh.boundary_facets()
    mid = mesh.p[:, mesh.facets[:, bfac]].mean(axis=1)
    sides = bfac[(np.abs(mid[0]) < 1e-12) | (np.abs(mid[0] - 0.5 * width) < 1e-12)]
    bottom = bfac[np.abs(mid[1] + depth) < 1e-12]
    fixed = np.unique(np.concatenate([L._facet_dofs(basis, sides, 0), L._facet_dofs(basis, bottom, 0),
                                      L._facet_dofs(basis, bottom, 1)]))
    free = np.setdiff1d(np.arange(body.n_dofs), fixed)
    u = np.zeros(body.n_dofs)
    # symmetric equilibration as in CondensedBody: the mixed constraint rows are ~1e12 smaller than the
    # force rows, and an unscaled LU loses 6 digits to that
    A = body.K[free][:, free]
    d = 1.0 / np.sqrt(abs(A).max(axis=1).toarray().ravel())
    u[free] = d * spsolve((diags(d) @ A @ diags(d)).tocsc(), d * f[free])
    m1 = 0.0 if nu_layer == 0.5 else t / thin_layer.constrained_modulus(E1, nu_layer)
    expected = -q * (m1 + (depth - t) / thin_layer.constrained_modulus(STEEL.E, STEEL.nu))
    uy_top = u[L._facet_dofs(basis, top, 1)]
    np.testing.assert_allclose(uy_top, expected, rtol=1e-9)


# ---------------------------------------------------------------- 2D contact against closed forms


def _line_params(layer: Elastic, substrate: Elastic | None, thickness: float, load: float, **numerics) -> dict:
    p = {"layer.E": layer.E, "layer.nu": layer.nu, "layer.thickness": thickness, "geometry.radius": R,
         "load.per_length": load}
    if substrate is None:
        p["materials.substrate.rigid"] = True
    else:
        p.update({"materials.substrate.E": substrate.E, "materials.substrate.nu": substrate.nu})
    p.update({f"numerics.fem_{k}": v for k, v in numerics.items()})
    return p


@pytest.mark.slow
def test_layer_of_the_substrate_material_is_homogeneous_hertz():
    # A layer with the substrate's own E, nu is no layer: Hertz line contact (seed 001 eqs 3-4) for a rigid
    # cylinder, E* = E/(1 - nu^2). Issue 5 asks 1 % on the extrapolated p_max and half-width; measured
    # +0.10 % / -0.10 % (the clamped 40a x 20a block alone biases p0 by about +0.1 %, FEM-NOTES).
    load = 1e5
    h = hertz.line_contact(load, R, STEEL.E / (1 - STEEL.nu**2))
    r = L.model(_line_params(STEEL, STEEL, 0.1 * h.half_width, load))
    assert r.quantities["p_max"] == pytest.approx(h.p_max, rel=0.01)
    assert r.quantities["half_width"] == pytest.approx(h.half_width, rel=0.01)
    assert r.quantities["total_force"] == pytest.approx(load, rel=1e-9)     # load control: exact balance
    assert len(r.stats["levels"]) == 3 and all(lv["residual"] < 1e-9 for lv in r.stats["levels"])


@pytest.mark.slow
@pytest.mark.parametrize("t_over_a", [0.1, 0.02])
def test_thin_compressible_layer_on_rigid_base_matches_johnson(t_over_a):
    # Johnson's thin bonded layer (analytic/thin_layer.py, seed 001 eqs 18-22 with exponent 1/3): issue 5
    # asks 5 % for t/a <= 0.1. The closed form neglects O((t/a)^2) terms, so it is tighter at 0.02.
    # Measured (defaults): t/a = 0.1: p_max -0.08 %, a -0.7 %; t/a = 0.02: p_max -0.003 %, a 0.0 %.
    E, nu, t = 200e9, 0.3, 2e-6
    a = t / t_over_a
    load = 2 * thin_layer.constrained_modulus(E, nu) * a**3 / (3 * R * t)     # the load that gives this a
    ref = thin_layer.compressible(E, nu, t, R, load, "line")
    r = L.model(_line_params(Elastic(E, nu), None, t, load))
    tol = 0.05 if t_over_a >= 0.1 else 0.01
    assert r.quantities["p_max"] == pytest.approx(ref.p_max, rel=tol)
    assert r.quantities["half_width"] == pytest.approx(ref.a, rel=tol)


@pytest.mark.slow
def test_thin_incompressible_layer_on_rigid_base_tends_to_squeeze_film():
    # nu = 0.5 through the mixed form: the squeeze-film closed form (frictionless top, k = 3G/t^3) is the
    # t/a -> 0 limit; its p_max error is O((t/a)^2): measured +3.4 % at t/a = 0.1 and +0.9 % at 0.05 (issue 5:
    # 5 % for t/a <= 0.1). The half-width is *not* asserted: the closed form's edge is off by O(t) (measured
    # -13.6 % at t/a = 0.1, -6.6 % at 0.05), which is the formula's limit, reported by the model.
    E, t = 200e9, 2e-6
    errors = []
    for t_over_a in (0.1, 0.05):
        a = t / t_over_a
        load = 2 * (3 * (E / 3) / t**3) * a**5 / (45 * R)
        ref = thin_layer.incompressible(E, t, R, load, "line")
        r = L.model(_line_params(Elastic(E, 0.5), None, t, load))
        assert r.stats["formulation"] == {"layer": "mixed"}
        errors.append(abs(r.quantities["p_max"] / ref.p_max - 1))
    assert errors[0] < 0.05
    assert errors[1] < 0.015 and errors[1] < 0.5 * errors[0]      # O((t/a)^2): halving t/a quarters it


@pytest.mark.slow
def test_very_thick_layer_is_the_layers_hertz():
    # A layer ten substrate-Hertz widths thick (about 14 contact half-widths here) on steel: the substrate lies
    # beyond the stressed zone and the contact is Hertz with the layer's E1* (seed 001 eqs 3-4). Tolerance 1 %:
    # measured -0.05 % (p_max), +0.16 % (half-width) on this coarser family.
    layer, load = Elastic(2 * STEEL.E, 0.21), 1e5
    a_sub = hertz.line_contact(load, R, STEEL.E / (1 - STEEL.nu**2)).half_width
    h1 = hertz.line_contact(load, R, layer.E / (1 - layer.nu**2))
    r = L.model(_line_params(layer, STEEL, 10 * a_sub, load, h_contact=0.2))
    assert r.quantities["p_max"] == pytest.approx(h1.p_max, rel=0.01)
    assert r.quantities["half_width"] == pytest.approx(h1.half_width, rel=0.01)


@pytest.mark.parametrize("key, value", [("layer.nu", 0.6), ("layer.thickness", 0.0), ("layer.E", -1.0),
                                        ("materials.substrate.nu", 0.7)])
def test_bad_input_names_the_key(key, value):
    p = _line_params(Elastic(300e9, 0.21), STEEL, 3e-6, 1e5)
    p[key] = value
    with pytest.raises(InputError) as err:
        L.model(p)
    assert err.value.key == key


# ---------------------------------------------------------------- 3D smoke level


@pytest.mark.slow
def test_3d_thin_layer_on_rigid_base_matches_johnson_circular():
    # Smoke-level 3D check (two coarse levels, a few seconds): rigid sphere on a thin compressible layer
    # bonded to a rigid base, t/a = 0.1, against Johnson's circular thin-layer solution (analytic/thin_layer.py,
    # exponent 1/4 by load balance). Issue 5 asks 5 % for t/a <= 0.1; measured at the a/8 level: p_max -0.15 %,
    # semi-axes -1.4 % / -1.3 %. Also checks the load balance of the quarter model and that both symmetry
    # axes give the same radius (axisymmetric scene) within the mesh's resolution (h/a = 1/8: 2 %).
    from femcheck.fem import layered_point as P

    E, nu, t = 206e9, 0.3, 2e-6
    a = t / 0.1
    load = np.pi * thin_layer.constrained_modulus(E, nu) * a**4 / (4 * R * t)
    ref = thin_layer.compressible(E, nu, t, R, load, "circular")
    r = P.model({"layer.E": E, "layer.nu": nu, "layer.thickness": t, "materials.substrate.rigid": True,
                 "geometry.radius": R, "load.normal": load, "numerics.fem_levels": 2,
                 "numerics.fem_h_contact": 0.125})
    q = r.quantities
    assert q["p_max"] == pytest.approx(ref.p_max, rel=0.05)
    assert q["semi_axis_x"] == pytest.approx(ref.a, rel=0.05)
    assert q["semi_axis_y"] == pytest.approx(ref.a, rel=0.05)
    assert q["semi_axis_x"] == pytest.approx(q["semi_axis_y"], rel=0.02)
    assert q["total_force"] == pytest.approx(load, rel=1e-8)


def test_3d_refuses_nu_where_p1_locks():
    from femcheck.fem import layered_point as P

    with pytest.raises(InputError) as err:
        P.model({"layer.E": 200e9, "layer.nu": 0.49, "layer.thickness": 1e-6, "materials.substrate.rigid": True,
                 "geometry.radius": R, "load.normal": 10.0})
    assert err.value.key == "layer.nu"
