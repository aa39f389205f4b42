"""Layered half-space BEM (femcheck.bem.layered): the closed-form frequency response against a numerical
solution of the layer/substrate boundary-value problem, the cell influence coefficients against direct
quadrature of the Fourier integrals, and the contact limits h -> 0 (substrate Hertz), h -> inf (layer Hertz)
and the thin layer on a rigid base (Johnson's closed forms)."""
import numpy as np
import pytest
from scipy import integrate

from femcheck.analytic import hertz, thin_layer
from femcheck.bem.halfspace import Grid, grid
from femcheck.bem.influence import half_plane_strip, love_rectangle
from femcheck.bem.layered import (LayeredSolid, image_rectangle, rectangle_influence, response_factor,
                                  solve_line, solve_point, strip_influence, surface_compliance)
from femcheck.errors import InputError
from femcheck.problems.layer_contact import _half_width

R = 0.01


def _pn_compliance(k, h, E1, nu1, E2=None, nu2=None):
    """Independent reference: u_z(0) per unit pressure of one Fourier mode, from the Papkovich-Neuber solution
    2 mu u = grad(phi + z psi) - 4 (1 - nu) psi e_z (Barber, Elasticity, ch. 20) with phi, psi in {e^{-kz},
    e^{kz}} in the layer and decaying terms in the substrate; the 6 x 6 (rigid base: 4 x 4) boundary and
    interface conditions are solved numerically."""
    def rows(z, nu, mu, terms):
        out = []
        for kind, s in terms:
            e = np.exp(s * k * z)
            f, fp, g, gp = (e, s * k * e, 0.0, 0.0) if kind == "f" else (0.0, 0.0, e, s * k * e)
            out.append([(f + z * g) / (2 * mu), (fp + z * gp - (3 - 4 * nu) * g) / (2 * mu),
                        k * k * (f + z * g) - (2 - 2 * nu) * gp, fp + z * gp - (1 - 2 * nu) * g])
        return np.array(out).T            # rows: u_x/(ik), u_z, sigma_zz, sigma_xz/(ik)
    layer = [("f", -1), ("f", 1), ("g", -1), ("g", 1)]
    mu1 = E1 / (2 * (1 + nu1))
    top = rows(0.0, nu1, mu1, layer)
    if E2 is None:
        A = np.vstack([top[2:], rows(h, nu1, mu1, layer)[:2]])
        c = np.linalg.solve(A, [-1.0, 0, 0, 0])
    else:
        A = np.zeros((6, 6))
        A[:2, :4] = top[2:]
        A[2:, :4] = rows(h, nu1, mu1, layer)
        A[2:, 4:] = -rows(h, nu2, E2 / (2 * (1 + nu2)), [("f", -1), ("g", -1)])
        c = np.linalg.solve(A, [-1.0, 0, 0, 0, 0, 0])
    return top[1] @ c[:4]


CASES = [(300e9, 0.21, 206e9, 0.30), (20e9, 0.45, 200e9, 0.25), (100e9, 0.10, 10e9, 0.499),
         (200e9, 0.30, None, None), (100e9, 0.50, None, None)]


@pytest.mark.parametrize("E1,nu1,E2,nu2", CASES)
@pytest.mark.parametrize("kh", [0.1, 1.0, 3.0])
def test_frequency_response_matches_the_boundary_value_problem(E1, nu1, E2, nu2, kh):
    h = 1e-5
    s = LayeredSolid(E1, nu1, h, E2 or 1.0, nu2 or 0.0, rigid_substrate=E2 is None)
    ref = _pn_compliance(kh / h, h, E1, nu1, E2, nu2)
    # the 6 x 6 solve is conditioned like e^{2kh}; 1e-9 is far above its round-off at kh <= 3
    assert surface_compliance(np.array([kh / h]), s)[0] == pytest.approx(ref, rel=1e-9)


def test_frequency_response_limits():
    s = LayeredSolid(300e9, 0.21, 1e-5, 206e9, 0.3)
    # k h -> 0: the substrate, Phi -> E1*/E2*; k h -> inf: the layer, Phi -> 1
    assert response_factor(np.array([1e-9]), s)[0] == pytest.approx(s.modulus_layer / s.modulus_substrate, rel=1e-8)
    assert response_factor(np.array([40.0]), s)[0] == pytest.approx(1.0, rel=1e-12)
    # rigid base, k h -> 0: Johnson's Winkler layer u = h p / M, M the constrained modulus (seed 001 eqs 18-21)
    E, nu, h = 200e9, 0.3, 1e-5
    r = LayeredSolid(E, nu, h, rigid_substrate=True)
    assert surface_compliance(np.array([1e-3 / h]), r)[0] == pytest.approx(
        h / thin_layer.constrained_modulus(E, nu), rel=1e-2)      # O(kh) = 1e-3 correction
    assert surface_compliance(np.array([1e-7 / h]), r)[0] == pytest.approx(
        h / thin_layer.constrained_modulus(E, nu), rel=1e-6)
    # incompressible layer on a rigid base: finite, and O((kh)^3) small (no Winkler term): no division by zero
    inc = LayeredSolid(E, 0.5, h, rigid_substrate=True)
    phi = response_factor(np.array([1e-3, 2e-3]), inc)
    assert np.all(np.isfinite(phi)) and phi[1] / phi[0] == pytest.approx(8.0, rel=1e-2)


def test_bad_layer_input_is_refused():
    with pytest.raises(InputError, match="layer.thickness"):
        LayeredSolid(200e9, 0.3, 0.0, 200e9, 0.3)
    with pytest.raises(InputError, match="layer.nu"):
        LayeredSolid(200e9, 0.51, 1e-6, 200e9, 0.3)


def test_image_cell_integral_matches_quadrature():
    # closed form of int int over a cell of (C2 - C1)/(2 pi sqrt(r^2 + 4h^2)) + c0 2h / (2 pi (r^2+4h^2)^1.5)
    s = LayeredSolid(100e9, 0.3, 2e-6, 300e9, 0.25)
    from femcheck.bem.layered import _image_constants
    _, dc, c0 = _image_constants(s)
    a, dx, dy = 2 * s.thickness, 3e-6, 5e-6
    for tx, ty in ((0.0, 0.0), (4e-6, -7e-6)):
        f = lambda y, x: (dc / np.sqrt(x * x + y * y + a * a) + c0 * a / (x * x + y * y + a * a) ** 1.5) / (2 * np.pi)
        ref = integrate.dblquad(f, tx - dx / 2, tx + dx / 2, ty - dy / 2, ty + dy / 2, epsabs=0, epsrel=1e-11)[0]
        assert image_rectangle(np.array(tx), np.array(ty), dx, dy, s) == pytest.approx(ref, rel=1e-9)


def _strip_reference(solid, dx, x, nint=20000, ng=8):
    """(1/pi) int_0^inf (H - C1/k) S(k) (cos kx - 1) dk by Gauss-Legendre panels (S = dx sinc)."""
    edges = np.linspace(0.0, 60.0 / solid.thickness, nint + 1)
    xg, wg = np.polynomial.legendre.leggauss(ng)
    k = (0.5 * (edges[1:] + edges[:-1])[:, None] + 0.5 * np.diff(edges)[:, None] * xg).ravel()
    wk = (0.5 * np.diff(edges)[:, None] * wg).ravel()
    hm = surface_compliance(k, solid) - 2.0 / (solid.modulus_layer * k)
    return np.sum(wk * hm * dx * np.sinc(k * dx / (2 * np.pi)) * (np.cos(k * x) - 1.0)) / np.pi


@pytest.mark.parametrize("E1,nu1,E2,nu2", [(300e9, 0.21, 206e9, 0.3), (20e9, 0.3, 200e9, 0.3),
                                           (100e9, 0.5, None, None)])
@pytest.mark.parametrize("h_over_dx", [0.1, 1.0, 30.0])
def test_strip_coefficients_match_fourier_quadrature(E1, nu1, E2, nu2, h_over_dx):
    dx, n = 1e-5, 64
    s = LayeredSolid(E1, nu1, h_over_dx * dx, E2 or 1.0, nu2 or 0.0, rigid_substrate=E2 is None)
    datum = 8 * n * dx
    infl = strip_influence(s, n, dx, datum)
    layer_part = infl.table - half_plane_strip(np.arange(n) * dx, dx, s.modulus_layer, datum)
    scale = infl.table[0] - infl.table[1]
    for i in (1, 3, 10, 40):
        ref = _strip_reference(s, dx, i * dx)
        # 2D coefficients are defined up to a constant: compare differences to lag 0. Measured <= 1.6e-4 of the
        # neighbour difference (nu = 0.5, h = 0.1 dx, where the residual is truncated), <= 5e-6 otherwise.
        assert (layer_part[i] - layer_part[0]) == pytest.approx(ref, abs=3e-4 * scale)


@pytest.mark.slow
def test_rectangle_coefficients_match_polar_quadrature():
    dx, n = 1e-5, 33
    s = LayeredSolid(20e9, 0.3, 1.0 * dx, 200e9, 0.3)
    infl = rectangle_influence(s, Grid(n, n, dx, dx))
    layer_part = infl.table - love_rectangle(np.arange(n)[:, None] * dx, np.arange(n)[None, :] * dx, dx, dx,
                                             s.modulus_layer)
    th, wt = np.polynomial.legendre.leggauss(128)
    th, wt = (th + 1) * np.pi / 4, wt * np.pi / 4
    edges = np.linspace(0.0, 40.0 / s.thickness, 3001)
    xg, wg = np.polynomial.legendre.leggauss(12)
    k = (0.5 * (edges[1:] + edges[:-1])[:, None] + 0.5 * np.diff(edges)[:, None] * xg).ravel()
    wk = (0.5 * np.diff(edges)[:, None] * wg).ravel()
    kx, ky = k[:, None] * np.cos(th), k[:, None] * np.sin(th)
    cell = dx * np.sinc(kx * dx / (2 * np.pi)) * dx * np.sinc(ky * dx / (2 * np.pi))
    hm = surface_compliance(k, s) - 2.0 / (s.modulus_layer * k)
    for i, j in ((0, 0), (1, 0), (3, 2), (10, 0)):
        ang = (cell * np.cos(kx * i * dx) * np.cos(ky * j * dx)) @ wt * 4 / (2 * np.pi)
        ref = np.sum(wk * hm * ang * k) / (2 * np.pi)       # (1/4pi^2) int int (H - C1/k) S^ e^{ik.x} dk
        # measured 1.3e-5 of the self coefficient (an offset common to all lags, absorbed by the approach)
        assert layer_part[i, j] == pytest.approx(ref, abs=5e-5 * infl.table[0, 0])


E1, NU1, E2, NU2 = 100e9, 0.3, 300e9, 0.25
ES1, ES2 = E1 / (1 - NU1**2), E2 / (1 - NU2**2)


@pytest.mark.parametrize("h_factor,which", [(1e-3, 2), (1e3, 1)])
def test_line_contact_thin_and_thick_limits_recover_hertz(h_factor, which):
    W = 1e5
    ref = hertz.line_contact(W, R, ES2 if which == 2 else ES1)
    sol = solve_line(LayeredSolid(E1, NU1, h_factor * ref.half_width, E2, NU2), lambda x: x * x / (2 * R), W,
                     1.25 * ref.half_width, 1024)
    r = sol.result
    # issue 5: h -> 0 gives the substrate, h -> inf the layer, within 0.5 % (measured 0.05 % / 0.09 % at h/a = 1e-3)
    assert r.pressure.max() == pytest.approx(ref.p_max, rel=5e-3)
    assert _half_width(sol.x, r.pressure) == pytest.approx(ref.half_width, rel=5e-3)
    assert r.load == pytest.approx(W, rel=1e-12) and np.sum(r.pressure) * sol.spacing[0] == pytest.approx(W, rel=1e-12)


@pytest.mark.parametrize("h_factor,which", [(1e-3, 2), (1e3, 1)])
def test_point_contact_thin_and_thick_limits_recover_hertz(h_factor, which):
    P = 100.0
    ref = hertz.elliptic_contact(P, R, R, ES2 if which == 2 else ES1)
    a = ref.semi_axis_x
    g = grid(1.25 * a, 1.25 * a, 65, 65)
    sol = solve_point(LayeredSolid(E1, NU1, h_factor * a, E2, NU2), g, lambda X, Y: (X * X + Y * Y) / (2 * R), P)
    r = sol.result
    # measured: p_max -0.08 % (h/a = 1e-3) / +0.008 % (h/a = 1e3), radius +0.19 % / +0.16 % at a/dx = 26
    assert r.pressure.max() == pytest.approx(ref.p_max, rel=5e-3)
    assert _half_width(g.x, r.pressure[:, 32]) == pytest.approx(a, rel=5e-3)
    assert _half_width(g.y, r.pressure[32, :]) == pytest.approx(a, rel=5e-3)
    assert np.sum(r.pressure) * g.cell_area == pytest.approx(P, rel=1e-12)


def _thickness_for(h_over_a, contact):
    b = 1e-6
    for _ in range(60):                  # fixed point b = (h/a) a(b): a grows like b^(1/3) or b^(1/4)
        b = h_over_a * contact(b).a
    return b


def test_rigid_base_line_approaches_johnson_thin_layer():
    E, nu, W = 200e9, 0.3, 1e5
    contact = lambda b: thin_layer.compressible(E, nu, b, R, W, "line")
    errors = []
    for h_over_a in (0.1, 0.01):
        tl = contact(_thickness_for(h_over_a, contact))
        b = h_over_a * tl.a
        sol = solve_line(LayeredSolid(E, nu, b, rigid_substrate=True), lambda x: x * x / (2 * R), W, 1.5 * tl.a,
                         1024)
        errors.append((sol.result.pressure.max() / tl.p_max - 1, _half_width(sol.x, sol.result.pressure) / tl.a - 1))
    # The closed form is the h/a -> 0 asymptote (issue 5: thin-layer vs reference within 5 % for h/a <= 0.1).
    # measured: p_max -0.08 % / +2e-6 and half-width -1.7 % / +1e-4 at h/a = 0.1 / 0.01
    assert abs(errors[0][0]) < 0.05 and abs(errors[0][1]) < 0.05
    assert abs(errors[1][0]) < 1e-4 and abs(errors[1][1]) < 1e-3
    assert abs(errors[1][1]) < abs(errors[0][1]) and abs(errors[1][0]) < abs(errors[0][0])


def test_rigid_base_circular_approaches_johnson_thin_layer():
    E, nu, P = 200e9, 0.3, 100.0
    contact = lambda b: thin_layer.compressible(E, nu, b, R, P, "circular")
    tl = contact(_thickness_for(0.01, contact))
    g = grid(1.25 * tl.a, 1.25 * tl.a, 65, 65)
    sol = solve_point(LayeredSolid(E, nu, tl.a * 0.01, rigid_substrate=True), g,
                      lambda X, Y: (X * X + Y * Y) / (2 * R), P)
    # measured: p_max +2e-5, radius +0.18 % at a/dx = 26
    assert sol.result.pressure.max() == pytest.approx(tl.p_max, rel=1e-3)
    assert _half_width(g.x, sol.result.pressure[:, 32]) == pytest.approx(tl.a, rel=5e-3)


def test_incompressible_layer_on_rigid_base_approaches_the_squeeze_film():
    E, W = 200e9, 1e5
    contact = lambda b: thin_layer.incompressible(E, b, R, W, "line", top="frictionless")
    b = _thickness_for(0.03, contact)
    tl = contact(b)
    sol = solve_line(LayeredSolid(E, 0.5, b, rigid_substrate=True), lambda x: x * x / (2 * R), W, 1.5 * tl.a, 1024)
    # nu = 0.5 exactly (no Winkler term): measured p_max +0.33 % at h/a = 0.03 (+3.5 % at 0.1)
    assert sol.result.pressure.max() == pytest.approx(tl.p_max, rel=1e-2)
    assert np.all(sol.result.pressure >= 0) and sol.result.load == pytest.approx(W, rel=1e-12)
