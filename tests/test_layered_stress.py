"""Sub-surface stresses of the layered half-space (femcheck.bem.layered_stress).

Independent references: the closed-form surface compliance Phi(kh) of bem/layered.py (Chen / O'Sullivan & King),
the homogeneous half-space transform (Johnson 1985 §2.6), Hooke's law at the interface and in the long-wave
limit, Fourier / Hankel quadrature of the stress transform for a Hertz pressure (independent of the field
machinery: DC-FFT kernels, image terms, sampled residual), McEwen's line-contact field and Hertz's sphere axis
(analytic/stress.py) in the limits h -> 0 and h -> inf, and global equilibrium."""
import numpy as np
import pytest
from scipy import integrate

from femcheck.analytic import hertz
from femcheck.analytic import stress as closed
from femcheck.bem import layered_stress as ls
from femcheck.bem.halfspace import grid as make_grid
from femcheck.bem.layered import LayeredSolid, response_factor, solve_line, solve_point
from femcheck.errors import InputError

A, P0 = 1e-4, 1e9          # contact size (m) and peak pressure (Pa) of the prescribed Hertz pressures
CASES = [(300e9, 0.21, 206e9, 0.30), (20e9, 0.45, 200e9, 0.25), (100e9, 0.10, 10e9, 0.499),
         (200e9, 0.30, None, None), (100e9, 0.50, None, None)]


def _solid(E1, nu1, h, E2, nu2):
    return LayeredSolid(E1, nu1, h, E2 or 1.0, nu2 or 0.0, rigid_substrate=E2 is None)


# ---------------------------------------------------------------------------------------------------------------
# Frequency response
# ---------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("E1,nu1,E2,nu2", CASES)
def test_surface_displacement_is_the_closed_form_compliance(E1, nu1, E2, nu2):
    h = 1e-5
    s = _solid(E1, nu1, h, E2, nu2)
    t = np.array([1e-6, 1e-3, 0.1, 1.0, 3.0, 30.0])
    m = ls.modal_profiles(t / h, 0.0, s)
    # 2 mu1 k u_z(0) = 2 (1 - nu1) Phi(kh) with Phi the closed form of bem/layered.py (O'Sullivan & King); the
    # 6 x 6 solve is well conditioned (cond ~ 20): round-off level agreement relative to the O(1) stresses the
    # constants carry (atol: an incompressible layer on a rigid base has Phi = O(t^3), 7e-19 at t = 1e-6)
    np.testing.assert_allclose(m.Uz, 2 * (1 - nu1) * response_factor(t, s), rtol=1e-9, atol=1e-13)
    # traction-free top apart from the unit pressure: sigma_zz = -1, sigma_az = 0
    np.testing.assert_allclose(m.W - 2 * (1 - m.nu) * m.G, -1.0, rtol=1e-12)
    np.testing.assert_allclose(m.T, 0.0, atol=1e-12)


@pytest.mark.parametrize("E1,nu1,E2,nu2", CASES[:3])
def test_interface_conditions_and_long_wave_limit(E1, nu1, E2, nu2):
    h = 1e-5
    s = _solid(E1, nu1, h, E2, nu2)
    k = np.array([1e-3, 0.3, 1.0, 4.0]) / h
    up, lo = ls.modal_profiles(k, h, s, in_layer=True), ls.modal_profiles(k, h, s, in_layer=False)
    mu1, mu2 = E1 / (2 * (1 + nu1)), E2 / (2 * (1 + nu2))
    # bonded interface: displacements (2 mu k u / 2 mu) and tractions sigma_zz, sigma_az continuous
    np.testing.assert_allclose(up.W / mu1, lo.W / mu2, rtol=1e-9)
    np.testing.assert_allclose(up.Uz / mu1, lo.Uz / mu2, rtol=1e-9)
    np.testing.assert_allclose(up.W - 2 * (1 - nu1) * up.G, lo.W - 2 * (1 - nu2) * lo.G, rtol=1e-9)
    np.testing.assert_allclose(up.T, lo.T, rtol=1e-9, atol=1e-12)
    # long-wave limit (Hooke's law with the substrate surface's in-plane strain, module docstring) vs the BVP
    c1, c2 = ls.long_wave_limit(s)
    m = ls.modal_profiles(np.array([1e-9 / h]), 0.5 * h, s)
    # O(kh) = 1e-9 plus round-off of the O(1) constants (c1 = 0.027 for nu2 = 0.499 comes out of a cancellation)
    assert m.W[0] == pytest.approx(c1, abs=1e-7) and 2 * nu1 * m.G[0] == pytest.approx(c2, abs=1e-7)


def test_uniform_body_is_the_homogeneous_half_space_and_limits():
    k = np.array([0.1, 1.0, 5.0]) / 1e-5
    nu = 0.3
    # same material above and below: Johnson's homogeneous transform, at any layer thickness, both sides
    s = LayeredSolid(200e9, nu, 1e-5, 200e9, nu)
    for z, lay in ((0.3e-5, True), (1e-5, True), (1e-5, False), (2.5e-5, False)):
        m, ref = ls.modal_profiles(k, z, s, lay), ls.homogeneous_profiles(k, z, nu)
        for a, b in ((m.W, ref.W), (m.G, ref.G), (m.T, ref.T)):
            np.testing.assert_allclose(a, b, rtol=1e-10, atol=1e-14)
    # h -> inf: the layer's half-space; h -> 0: the substrate's (depth z below the surface)
    thick = LayeredSolid(300e9, 0.21, 1.0, 100e9, 0.35)
    m, ref = ls.modal_profiles(k, 1e-5, thick), ls.homogeneous_profiles(k, 1e-5, 0.21)
    np.testing.assert_allclose(m.W, ref.W, rtol=1e-9)
    thin = LayeredSolid(300e9, 0.21, 1e-12, 100e9, 0.35)
    m, ref = ls.modal_profiles(k, 1e-5, thin), ls.homogeneous_profiles(k, 1e-5, 0.35)
    np.testing.assert_allclose(m.W, ref.W, rtol=1e-6)       # O(k h) = 5e-7 correction


# ---------------------------------------------------------------------------------------------------------------
# Fields against quadrature of the transform (prescribed Hertz pressures)
# ---------------------------------------------------------------------------------------------------------------

def _line_reference(solid, x, z, in_layer):
    """sigma_x, sigma_z, tau_xz at (x, z) by quadrature of (1/pi) int_0^inf Re[S(k, z) p^(k) e^{ikx}] dk,
    p^ = pi a p0 J1(ka)/(ka) the transform of p0 sqrt(1 - x^2/a^2)."""
    from scipy.special import j1
    k = np.linspace(1e-9, 80.0 / max(z, 0.05 * A), 100001)
    ph = np.pi * A * P0 * j1(k * A) / (k * A)
    r = ls.plane_strain_response(k, z, solid, in_layer)
    e = np.exp(1j * np.outer(x, k))
    return {c: integrate.simpson((r[c] * ph * e).real, x=k) / np.pi for c in ("sigma_x", "sigma_z", "tau_xz")}


def _hertz_line(n=1024):
    dx = 2.5 * A / n
    x = -1.25 * A + (np.arange(n) + 0.5) * dx
    return x, dx, P0 * np.sqrt(np.clip(1 - (x / A) ** 2, 0, None))


@pytest.mark.parametrize("E1,nu1,E2,nu2,h", [(600e9, 0.21, 206e9, 0.30, 0.1 * A), (20e9, 0.45, 200e9, 0.25, 0.5 * A),
                                             (200e9, 0.30, None, None, 0.3 * A)])
def test_line_field_matches_fourier_quadrature(E1, nu1, E2, nu2, h):
    s = _solid(E1, nu1, h, E2, nu2)
    x, dx, p = _hertz_line()
    f = ls.line_stresses(p, dx, s, np.array([0.5 * h, 1.5 * h, 0.6 * A]), x=x)
    cols = np.array([512, 600, 700, 800])                   # x = 0 .. 1.1 a
    for i, (z, lay) in enumerate(zip(f.depths, f.in_layer)):
        ref = _line_reference(s, x[cols], z, lay)
        for c in ("sigma_x", "sigma_z", "tau_xz"):
            # reference: the smooth Hertz pressure; the field: its strip-wise uniform sampling (a/dx = 410), whose
            # discretisation error is O(dx^2); measured <= 2e-4 p0
            np.testing.assert_allclose(f.components[c][i, cols], ref[c], atol=1e-3 * P0, err_msg=f"{c} z={z}")


def _axis_reference(solid, z, in_layer):
    """sigma_x (= sigma_y) and sigma_z on the axis of a Hertz sphere pressure by Hankel quadrature:
    (1/2pi) int_0^inf S(k, z) p^(k) k dk, angular mean of n_x^2 = 1/2,
    p^ = 2 pi p0 a^2 (sin ka - ka cos ka)/(ka)^3."""
    k = np.linspace(1e-9, 60.0 / max(z, 0.05 * A), 200001)
    ka = k * A
    ph = 2 * np.pi * P0 * A * A * (np.sin(ka) - ka * np.cos(ka)) / ka ** 3
    m = ls.modal_profiles(k, z, solid, in_layer)
    w = ph * k / (2 * np.pi)
    return (integrate.simpson((-0.5 * m.W - 2 * m.nu * m.G) * w, x=k),
            integrate.simpson((m.W - 2 * (1 - m.nu) * m.G) * w, x=k))


@pytest.mark.parametrize("E1,nu1,E2,nu2,h", [(600e9, 0.21, 206e9, 0.30, 0.1 * A), (20e9, 0.45, 200e9, 0.25, 0.5 * A)])
def test_point_field_on_the_axis_matches_hankel_quadrature(E1, nu1, E2, nu2, h):
    s = _solid(E1, nu1, h, E2, nu2)
    n = 65
    g = make_grid(1.25 * A, 1.25 * A, n, n)
    X, Y = g.mesh()
    p = P0 * np.sqrt(np.clip(1 - (X * X + Y * Y) / A ** 2, 0, None))
    f = ls.point_stresses(p, g, s, np.array([0.5 * h, 0.6 * A]))
    j = n // 2
    for i, (z, lay) in enumerate(zip(f.depths, f.in_layer)):
        sx, sz = _axis_reference(s, z, lay)
        # a/dx = 26 cells: measured |error| <= 6e-4 p0 (pressure discretisation); the residual's periodic images
        # were 9e-3 p0 with a period of 2 n dx for the stiff layer before the period followed its cone length
        assert f.components["sigma_x"][i, j, j] == pytest.approx(sx, abs=1.5e-3 * P0)
        assert f.components["sigma_y"][i, j, j] == pytest.approx(sx, abs=1.5e-3 * P0)
        assert f.components["sigma_z"][i, j, j] == pytest.approx(sz, abs=1.5e-3 * P0)


# ---------------------------------------------------------------------------------------------------------------
# Surface, interface, equilibrium
# ---------------------------------------------------------------------------------------------------------------

def _plane_strain_exx(sx, sz, E, nu):
    return ((1 - nu * nu) * sx - nu * (1 + nu) * sz) / E


def test_line_surface_interface_and_equilibrium():
    E1, nu1, E2, nu2, h = 300e9, 0.21, 206e9, 0.30, 0.2 * A
    s = LayeredSolid(E1, nu1, h, E2, nu2)
    x, dx, p = _hertz_line(512)
    # zero-pad to 64x the contact grid so that the plane integrals see the tails (sigma_zz ~ z^3/x^4)
    n = 512 * 64
    pw = np.zeros(n)
    pw[(n - 512) // 2:(n + 512) // 2] = p
    f = ls.line_stresses(pw, dx, s, np.array([0.0, 0.5 * h, 1.0 * A]))
    W = p.sum() * dx
    # surface: sigma_zz = -p and tau_xz = 0 at the cell centres (exact for strip-wise uniform pressure)
    np.testing.assert_allclose(f.components["sigma_z"][0], -pw, atol=1e-9 * P0)
    np.testing.assert_allclose(f.components["tau_xz"][0], 0.0, atol=1e-9 * P0)
    for i, z in enumerate(f.depths):
        # equilibrium of the slab above the plane: int sigma_zz dx = -W', int tau_xz dx = 0; the tail beyond
        # the padded width 40 a is ~ (2/(3 pi)) (z/X)^3 W' < 1e-5 W'
        assert f.components["sigma_z"][i].sum() * dx == pytest.approx(-W, rel=2e-5), z
        assert abs(f.components["tau_xz"][i].sum() * dx) < 1e-6 * W
    side = f.interface()
    lay, sub = side["layer"], side["substrate"]
    # bonded interface: normal and shear tractions continuous
    np.testing.assert_allclose(lay["sigma_z"], sub["sigma_z"], atol=1e-6 * P0)
    np.testing.assert_allclose(lay["tau_xz"], sub["tau_xz"], atol=1e-6 * P0)
    # sigma_xx jumps so that the in-plane strain is continuous: the layer's sigma_xx predicted by plane-strain
    # Hooke's law from the substrate's strain and sigma_zz; tolerance: the residual's periodic-image error
    # O(l a / L^2) ~ 2e-6 p0 here (L = 320 a), amplified by E1/E2
    exx = _plane_strain_exx(sub["sigma_x"], sub["sigma_z"], E2, nu2)
    predicted = (E1 / (1 - nu1 ** 2)) * exx + nu1 / (1 - nu1) * lay["sigma_z"]
    np.testing.assert_allclose(lay["sigma_x"], predicted, atol=1e-5 * P0)
    jump = np.abs(lay["sigma_x"] - sub["sigma_x"]).max()
    assert jump > 0.05 * P0            # alumina on steel: a real jump, not continuity by accident


def test_point_surface_and_interface():
    E1, nu1, E2, nu2, h = 20e9, 0.45, 200e9, 0.25, 0.3 * A
    s = LayeredSolid(E1, nu1, h, E2, nu2)
    n = 33
    g = make_grid(1.25 * A, 1.25 * A, n, n)
    X, Y = g.mesh()
    p = P0 * np.sqrt(np.clip(1 - (X * X + Y * Y) / A ** 2, 0, None))
    f = ls.point_stresses(p, g, s, np.array([0.0, 0.5 * A]))
    assert f.depths[0] == 0.0
    np.testing.assert_allclose(f.components["sigma_z"][0], -p, atol=1e-6 * P0)
    np.testing.assert_allclose(f.components["tau_xz"][0], 0.0, atol=1e-6 * P0)
    side = f.interface()
    lay, sub = side["layer"], side["substrate"]
    for c in ("sigma_z", "tau_xz", "tau_yz"):
        np.testing.assert_allclose(lay[c], sub[c], atol=1e-6 * P0, err_msg=c)
    # continuous in-plane strains: the soft layer's in-plane stresses predicted by Hooke's law from the stiff
    # substrate's strains eps_ab and sigma_zz, sigma_ab = 2 mu1 eps_ab + delta_ab (E1 nu1/(1 - nu1^2) eps_cc
    # + nu1/(1 - nu1) sigma_zz). Tolerance: the field's accuracy at a/dx = 13 (measured 1.4e-3 p0 on the axis
    # against Hankel quadrature at the interface, layer side)
    tr = sub["sigma_x"] + sub["sigma_y"] + sub["sigma_z"]
    exx, eyy = ((1 + nu2) * sub["sigma_x"] - nu2 * tr) / E2, ((1 + nu2) * sub["sigma_y"] - nu2 * tr) / E2
    exy = (1 + nu2) * sub["tau_xy"] / E2
    mu1, lam1 = E1 / (2 * (1 + nu1)), E1 * nu1 / (1 - nu1 ** 2)
    iso = lam1 * (exx + eyy) + nu1 / (1 - nu1) * lay["sigma_z"]
    np.testing.assert_allclose(lay["sigma_x"], 2 * mu1 * exx + iso, atol=3e-3 * P0)
    np.testing.assert_allclose(lay["sigma_y"], 2 * mu1 * eyy + iso, atol=3e-3 * P0)
    np.testing.assert_allclose(lay["tau_xy"], 2 * mu1 * exy, atol=3e-3 * P0)
    assert np.abs(lay["sigma_x"] - sub["sigma_x"]).max() > 0.05 * P0


def test_thin_layer_on_rigid_base_is_in_uniaxial_strain():
    # Johnson's thin layer (seed 001 eqs 18-21): for h << a the layer is laterally constrained, so under the
    # contact centre sigma_xx = sigma_yy = nu/(1 - nu) sigma_zz, sigma_zz = -p(0)
    nu = 0.3
    s = LayeredSolid(200e9, nu, 0.01 * A, rigid_substrate=True)
    x, dx, p = _hertz_line(1024)
    f = ls.line_stresses(p, dx, s, np.array([0.5 * s.thickness]))
    assert not (~f.in_layer).any()                      # no planes in the rigid base
    i = np.flatnonzero(f.depths == 0.5 * s.thickness)[0]
    # O(h/a) = 1 % bending correction
    assert f.components["sigma_x"][i, 512] == pytest.approx(-nu / (1 - nu) * p[512], rel=2e-2)
    assert f.components["sigma_z"][i, 512] == pytest.approx(-p[512], rel=1e-3)


def test_bad_depths_are_refused():
    s = LayeredSolid(200e9, 0.3, 1e-5, 200e9, 0.3)
    with pytest.raises(InputError, match="depths"):
        ls.depth_planes(np.array([-1e-6, 1e-6]), s)
    r = LayeredSolid(200e9, 0.3, 1e-5, rigid_substrate=True)
    with pytest.raises(InputError, match="rigid base"):
        ls.modal_profiles(np.array([1.0]), 2e-5, r)


# ---------------------------------------------------------------------------------------------------------------
# Limits h -> 0 and h -> inf from contact solves: McEwen and the Hertz sphere axis
# ---------------------------------------------------------------------------------------------------------------

R = 0.01
E1, NU1, E2, NU2 = 300e9, 0.21, 206e9, 0.30


@pytest.mark.parametrize("h_factor,which", [(1e-3, 2), (1e3, 1)])
def test_line_contact_limits_recover_mcewen(h_factor, which):
    nu = NU2 if which == 2 else NU1
    ref = hertz.line_contact(1e5, R, (E2 if which == 2 else E1) / (1 - nu * nu))
    a = ref.half_width
    s = LayeredSolid(E1, NU1, h_factor * a, E2, NU2)
    sol = solve_line(s, lambda x: x * x / (2 * R), 1e5, 1.25 * a, 1024)
    f = ls.line_stresses(sol.result.pressure, sol.spacing[0], s, ls.default_depths(s, a, n=60, depth_max=1.5),
                         x=sol.x)
    # h -> 0: the substrate's field (the vanishing layer keeps its own in-plane stresses, see maxima())
    m = f.maxima("substrate" if which == 2 else "all")
    exact = closed.line_contact_field(ref, nu).maxima          # McEwen (Johnson eq 4.49)
    # issue 5 asks for 1 %; measured (1024 strips, a/dx = 410): maxima within 0.004 %, depths within 0.1 %
    for key in ("von_mises_max", "tau_max", "tau_xz_max"):
        assert m[key] == pytest.approx(exact[key], rel=2e-3), key
    assert m["von_mises_max_depth"] == pytest.approx(exact["von_mises_max_depth"], rel=5e-3)
    assert m["tau_xz_max_depth"] == pytest.approx(exact["tau_xz_max_depth"], rel=5e-3)


@pytest.mark.parametrize("h_factor,which", [(1e-3, 2), (1e2, 1)])
def test_point_contact_limits_recover_the_hertz_axis(h_factor, which):
    nu = NU2 if which == 2 else NU1
    ref = hertz.elliptic_contact(100.0, R, R, (E2 if which == 2 else E1) / (1 - nu * nu))
    a = ref.semi_axis_x
    s = LayeredSolid(E1, NU1, h_factor * a, E2, NU2)
    n = 65
    g = make_grid(1.25 * a, 1.25 * a, n, n)
    sol = solve_point(s, g, lambda X, Y: (X * X + Y * Y) / (2 * R), 100.0)
    f = ls.point_stresses(sol.result.pressure, g, s, np.linspace(0.3 * a, 0.7 * a, 9), interface=False)
    m = f.maxima("substrate" if which == 2 else "all")
    exact = closed.hertz_sphere_maxima(a, ref.p_max, nu)       # Johnson eq 3.45 on the axis
    # issue 5 asks for 1 %; measured (65^2 cells, a/dx = 26): -0.009 % / -0.004 %, depth +0.18 % / +0.33 %
    assert m["von_mises_max"] == pytest.approx(exact["von_mises_max"], rel=2e-3)
    assert m["tau_max"] == pytest.approx(exact["tau_max"], rel=2e-3)
    assert m["von_mises_max_depth"] == pytest.approx(exact["von_mises_max_depth"], rel=1e-2)


def test_layer_line_scene_reports_the_thin_coating_surface_stress():
    from femcheck.runner import run
    res = run("layer-line", overrides={"outputs.subsurface_stress": True, "layer.h_over_a": 2e-3}, models=["bem"],
              use_cache=False)
    m = res.models["bem"]
    assert m.status == "ok", m.error
    q = m.quantities
    E1, nu1, E2, nu2 = 420e9, 0.25, 210e9, 0.30                # layer-line.toml
    p = q["p_max"]
    # a coating much thinner than the contact takes the substrate surface's in-plane strain (plane strain,
    # sigma_xx = sigma_zz = -p: eps = -(1 + nu2)(1 - 2 nu2) p / E2) with its own moduli (Hooke's law):
    eps = -(1 + nu2) * (1 - 2 * nu2) * p / E2
    sx = (E1 * eps / (1 + nu1) - nu1 * p) / (1 - nu1)
    sz, sy = -p, nu1 * (sx - p)
    vm = np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2))
    # 0.72 p0 at the surface, above the substrate's McEwen 0.56 p0: the maximum sits in the coating at z = 0;
    # O(h/a) = 0.2 % corrections
    assert q["von_mises_max"] == pytest.approx(vm, rel=5e-3)
    assert q["von_mises_max_depth"] == 0.0
    assert q["interface_normal_max"] == pytest.approx(p, rel=5e-3)        # sigma_zz ~ -p through a thin layer
    f = m.fields
    assert f["von_mises"].shape == (f["stress_z"].size, f["stress_x"].size)
