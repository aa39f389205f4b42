"""Split influence coefficients (half-space + interpolated finite-body correction) on seed 000's contact grids.

The FE side is replaced by tables built from a known smooth correction d(lag, s_I, s_J) (m/N) of the magnitude the
FE gives for seed 000 (2.5e-11 m/N cross, 5e-10 m/N self: benchmarks/srb_split_compliance.py), so the tests
check the split itself exactly: what the FE puts in comes back out on any grid to the cubic interpolation's
error. The FE's own side (hybrid vs pure condensed FE at equal cell counts) is measured by the benchmark.
"""
from __future__ import annotations

import numpy as np
import pytest

from femcheck.cect.influence import combined_constants
from femcheck.fem import compliance_split as cs
from femcheck.fem import srb_rolling as fe
from femcheck.fem.halfspace_tables import halfspace_table
from femcheck.fem.rolling_contact import RelativeCompliance
from femcheck.materials import Elastic

SRB = {"geometry.roller_diameter": 0.0198, "geometry.crown_radius": 0.1003, "geometry.groove_radius_inner": 0.103,
       "geometry.groove_radius_outer": 0.1024, "geometry.contact_angle": np.deg2rad(11.5),
       "materials.roller.E": 207e9, "materials.roller.nu": 0.3, "materials.ring.E": 207e9, "materials.ring.nu": 0.3}
STEEL = Elastic(207e9, 0.3)
CONSTANTS = combined_constants(STEEL, STEEL)
L_X, L_S = 1.0e-3, 8.0e-3          # m: the correction's length scales (the roller's radius is 9.9 mm)


def smooth_kernel(pair, i, j, lag, s_r, s_s):
    """A smooth stand-in for the finite-body correction (m/N), different per pair and component."""
    amp = (5e-10 if pair[0] == pair[1] else 2.5e-11) * (1.0 + 0.1 * (3 * i + j))
    return amp * np.cos(lag / L_X + 0.1 * j) * (1.0 + (s_r - 0.5 * s_s) / L_S + (s_r * s_s) / L_S ** 2)


def synthetic_fe(grids):
    """Tables of a 'finite body' whose correction is :func:`smooth_kernel` exactly."""
    tables, lag0 = {}, {}
    for r, gr in grids.items():
        for s, gs in grids.items():
            l0 = float(gr.x[0] - gs.x[-1])
            lags = l0 + gr.dx * np.arange(gr.nx + gs.nx)
            L, SR, SS = np.meshgrid(lags, gr.s, gs.s, indexing="ij")
            D = np.stack([np.stack([smooth_kernel((r, s), i, j, L, SR, SS) for j in range(3)]) for i in range(3)])
            H = halfspace_table(gr, gs, CONSTANTS)[1] if r == s else 0.0
            tables[(r, s)] = H + D * gs.cell_area
            lag0[(r, s)] = l0
    return RelativeCompliance(dict(grids), tables, lag0, {"model": "synthetic"})


def grids_of(nx, ns):
    return fe.grids(SRB, nx, ns, 5500.0)


def test_correction_is_the_finite_body_minus_half_space_per_unit_force():
    g = grids_of(9, 17)
    corr = cs.correction(synthetic_fe(g), CONSTANTS, near=0)
    for pair, K in corr.kernels.items():
        L, SR, SS = np.meshgrid(corr.lags[pair], g[pair[0]].s, g[pair[1]].s, indexing="ij")
        exact = np.stack([np.stack([smooth_kernel(pair, i, j, L, SR, SS) for j in range(3)]) for i in range(3)])
        # the half-space part cancels to round-off of the tables (1e-7 m/Pa scale, 16 digits)
        assert np.abs(K - exact).max() <= 1e-9 * np.abs(exact).max(), pair


def test_hybrid_on_the_correction_grid_is_the_fe():
    """Cubic interpolation through its own nodes: the hybrid on the correction's grid is the FE (to round-off)."""
    g = grids_of(9, 17)
    f = synthetic_fe(g)
    h = cs.hybrid(cs.correction(f, CONSTANTS, near=0), g, CONSTANTS)
    for pair, T in f.tables.items():
        assert h.lag0[pair] == f.lag0[pair]
        assert np.abs(h.tables[pair] - T).max() <= 1e-9 * np.abs(T).max(), pair


@pytest.mark.parametrize("target", [(13, 25), (19, 35)])
def test_hybrid_on_a_finer_grid_carries_the_correction_and_the_cross_influence(target):
    """From 9 x 17 to the FE reference's finer levels: every pair, the cross pairs included (the roller's only
    coupling of its two contacts), within the cubic spline's error. Bound: (5/384) h^4 max|f''''| (de Boor 1978,
    ch. 5) with h = dx = 0.068 mm and L_X = 1 mm gives 3e-7 relative inside; over the half cell by which the
    finer grid's outer centres lie beyond the coarse ones the cubic is extrapolated (error (h/L)^4 / 24 ~ 1e-6);
    along s (h = 1.45 mm, a quadratic in s) exact. 1e-5 of the largest entry."""
    g0, g1 = grids_of(9, 17), grids_of(*target)
    corr = cs.correction(synthetic_fe(g0), CONSTANTS, near=0)
    h = cs.hybrid(corr, g1, CONSTANTS)
    f1 = synthetic_fe(g1)
    for pair, T in f1.tables.items():
        H = halfspace_table(g1[pair[0]], g1[pair[1]], CONSTANTS)[1] if pair[0] == pair[1] else 0.0
        D_f = T - H
        assert np.abs(h.tables[pair] - H - D_f).max() <= 1e-5 * np.abs(D_f).max(), pair


def test_target_beyond_the_correction_grid_is_refused():
    g0 = grids_of(9, 17)
    corr = cs.correction(synthetic_fe(g0), CONSTANTS)
    wide = fe.grids(SRB, 9, 17, 5500.0, half_x=2.0)
    with pytest.raises(ValueError, match="beyond the correction grid"):
        cs.hybrid(corr, wide, CONSTANTS)


def test_near_field_fill_removes_the_fe_pattern_and_keeps_a_harmonic_correction():
    """The near-field fill (|lag|, |s_I - s_J| <= 2 cells of a self pair) returns a discrete-harmonic correction
    (affine in lag and s_J, plus lag s_J) exactly, whatever the FE put on the loaded cell and its neighbours (a
    +-12 % pattern of the self coefficient, as the one-layer P2 mesh gives: tests/test_fe_rolling.py), and leaves
    every entry outside the zone and every cross pair untouched."""
    g = grids_of(9, 17)
    f = synthetic_fe(g)
    corr0 = cs.correction(f, CONSTANTS, near=0)
    pair = ("inner", "inner")
    lags = corr0.lags[pair]
    L, SR, SS = np.meshgrid(lags, g["inner"].s, g["inner"].s, indexing="ij")
    harmonic = 3e-10 * (1.0 + L / L_X + 0.5 * SS / L_S + (L / L_X) * (SS / L_S))
    H = halfspace_table(g["inner"], g["inner"], CONSTANTS)[1]
    k = np.rint(lags / g["inner"].dx).astype(int)
    I, J = np.meshgrid(np.arange(17), np.arange(17), indexing="ij")
    zone = (np.abs(k)[:, None, None] <= 2) & (np.abs(I - J) <= 2)[None]
    pattern = np.where(zone, 0.12 * H[2, 2, np.argmin(np.abs(k))][None] * np.cos(np.pi * (k[:, None, None] + J)), 0)
    tables = dict(f.tables)
    tables[pair] = H + (harmonic[None, None] + pattern[None, None]) * g["inner"].cell_area
    fe_like = RelativeCompliance(f.grids, tables, f.lag0, {})
    K = cs.correction(fe_like, CONSTANTS, near=2).kernels
    assert np.abs(K[pair] - harmonic[None, None]).max() <= 1e-9 * np.abs(harmonic).max()
    assert np.array_equal(K[("inner", "outer")], corr0.kernels[("inner", "outer")])


def test_correction_field_on_a_fine_grid_equals_the_tables_of_that_grid():
    """The correction's displacement on a grid finer than the FE's (the route to fine contact grids): forces
    spread onto the 9 x 17 correction cells, the correction's own tables, a spline back to the 21 x 41 cells.
    Against the direct sum over the fine cells with the exact smooth correction, every pair and component.
    Bound: the linear spreading keeps the force and its first moment, leaving (h_c^2 / 8) max|d''| / |d| =
    (0.068 mm)^2 / 8 / (1 mm)^2 = 6e-4 along the lag (the kernel is affine in each s); the spline back adds
    (5/384)(h_c / L_X)^4 < 1e-6. 2e-3 of the largest displacement."""
    g0, g1 = grids_of(9, 17), grids_of(21, 41)
    corr = cs.correction(synthetic_fe(g0), CONSTANTS, near=0)
    p = {}
    for name, g in g1.items():
        X, S = np.meshgrid(g.x, g.s - g.s.mean(), indexing="ij")
        e = np.sqrt(np.clip(1 - (X / (0.8 * np.abs(g.x).max())) ** 2 - (S / (0.8 * np.abs(S).max())) ** 2, 0, None))
        p[name] = np.stack([0.1 * e, -0.05 * e, e]) * 2e9
    u = cs.correction_field(corr, {n: (g1[n], p[n]) for n in g1}, g1)
    for r, gr in g1.items():
        exact = np.zeros((3, gr.nx, gr.ns))
        for s, gs in g1.items():
            L = gr.x[:, None, None, None] - gs.x[None, None, :, None]
            SR, SS = gr.s[None, :, None, None], gs.s[None, None, None, :]
            for i in range(3):
                for j in range(3):
                    d = smooth_kernel((r, s), i, j, L, SR, SS)
                    exact[i] += np.einsum("aIbJ,bJ->aI", d, p[s][j]) * gs.cell_area
        assert np.abs(u[r] - exact).max() <= 2e-3 * np.abs(exact).max(), r
