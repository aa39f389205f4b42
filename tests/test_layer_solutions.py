"""The transform solutions of contact on an elastic layer bonded to a rigid base (femcheck.analytic.bonded_layer,
layer_axisymmetric, layer_plane) against their limits: the transformed Navier equations solved by a transfer
matrix (the kernel), Hertz (thick layer), Johnson's thin compressible and incompressible layers (thin layer),
Barber's dP/d delta = flat-punch stiffness (load-displacement consistency), equilibrium, and their own
discretisation. Numbers measured when written are quoted beside each tolerance."""
import numpy as np
import pytest
from scipy.linalg import expm

from femcheck.analytic import bonded_layer, hertz, layer_axisymmetric as axi, layer_plane as plane, thin_layer
from femcheck.bem.layered import LayeredSolid, response_factor

E, R = 210e9, 0.01


def _transfer_matrix_factor(t: float, nu: float) -> float:
    """Phi(t) from the plane-strain Navier equations transformed in x (u_x = U(z) sin x, u_z = W(z) cos x, xi = 1),
    integrated across the layer by the matrix exponential: traction (-1, 0) on z = 0, U = W = 0 on z = t.
    Independent of the closed form: no potentials, no algebra by hand."""
    mu, lam = 0.5 / (1 + nu), nu / ((1 + nu) * (1 - 2 * nu))          # E = 1
    M = np.zeros((4, 4))
    M[0, 2] = M[1, 3] = 1.0
    M[2, 0], M[2, 3] = (lam + 2 * mu) / mu, (lam + mu) / mu            # mu U'' = (lam+2mu) U + (lam+mu) W'
    M[3, 1], M[3, 2] = mu / (lam + 2 * mu), -(lam + mu) / (lam + 2 * mu)
    A = np.zeros((4, 4))
    A[0] = [lam, 0, 0, lam + 2 * mu]                 # sigma_zz = lam (U + W') + 2 mu W' = -1
    A[1] = [0, -1, 1, 0]                             # sigma_xz / mu = U' - W = 0
    A[2:] = expm(M * t)[:2]                          # U(t) = W(t) = 0
    Y = np.linalg.solve(A, [-1.0, 0, 0, 0])
    return Y[1] / (2 * (1 - nu**2))                  # W(0) = 2 Phi / E*, E* = 1 / (1 - nu^2)


@pytest.mark.parametrize("nu", [0.0, 0.25, 0.3, 0.45, 0.4999])
def test_kernel_against_the_transformed_navier_equations(nu):
    # closed form (derived by Papkovich-Neuber potentials) against the transfer matrix: measured <= 3e-14 for
    # nu <= 0.45; 5.5e-8 at nu = 0.4999, the transfer matrix's own conditioning (lambda / mu = 5000)
    t = np.array([0.01, 0.1, 0.5, 1.0, 2.0, 5.0])
    closed = bonded_layer.factor(t, nu)
    numeric = np.array([_transfer_matrix_factor(x, nu) for x in t])
    assert np.max(np.abs(closed / numeric - 1)) < (1e-11 if nu < 0.49 else 2e-7)
    assert np.allclose(closed + bonded_layer.deficit(t, nu), 1.0, rtol=0, atol=1e-15)


def test_kernel_limits_winkler_squeeze_film_half_space():
    t = np.array([1e-6, 1e-4])
    for nu in (0.0, 0.3, 0.45):    # Winkler: u^ = h p^ / M, Phi -> (1 - 2 nu) t / (2 (1 - nu)^2)
        assert bonded_layer.factor(t, nu) == pytest.approx((1 - 2 * nu) * t / (2 * (1 - nu) ** 2), rel=1e-3)
    # incompressible: Phi -> (2/3) t^3 (squeeze film, k = 3G/h^3), kept to full relative precision at t = 1e-6
    assert bonded_layer.factor(t, 0.5) == pytest.approx(2 * t**3 / 3, rel=1e-3)
    assert bonded_layer.factor(np.array([30.0, 400.0]), 0.3) == pytest.approx(1.0, abs=1e-20)


def test_the_layered_bem_kernel_agrees_with_the_independent_derivation():
    # femcheck.bem.layered writes the rigid base as g -> inf in Chen's two-layer form; the same function. Measured
    # 5e-16 (nu = 0.25, 0.3); 1.3e-10 for nu = 0.5 at t = 1e-3, where Phi = O(t^3) and that form loses digits
    t = np.geomspace(1e-3, 20, 40)
    for nu, tol in ((0.25, 1e-13), (0.3, 1e-13), (0.5, 1e-9)):
        bem = response_factor(t, LayeredSolid(1.0, nu, 1.0, rigid_substrate=True))
        assert np.max(np.abs(bem / bonded_layer.factor(t, nu) - 1)) < tol


# --------------------------------------------------------------------------------------------------------------
# Sphere (axisymmetric, Hankel transform)
# --------------------------------------------------------------------------------------------------------------

def test_sphere_thick_layer_is_hertz():
    # h / a = 84 and 842: radius and peak approach Hertz as (a/h)^3 (measured 2.8e-7, 2.8e-10); the approach
    # as a/h (the base's uniform shift: measured -6.70e-3, -6.70e-4)
    nu, P = 0.25, 100.0
    hz = hertz.point_contact(P, R, E / (1 - nu**2))
    errs = []
    for h in (1e-2, 1e-1):
        c = axi.contact(E, nu, h, R, P)
        assert c.a == pytest.approx(hz.semi_axis_x, rel=1e-6)
        assert c.p_max == pytest.approx(hz.p_max, rel=2e-6)
        errs.append(c.approach / hz.approach - 1)
    assert errs[0] < 0 and errs[0] / errs[1] == pytest.approx(10.0, rel=0.01)


def _extrapolated(xs, es, order):
    """Value at x = 0 of the polynomial of degree ``order`` (no constant dropped) through (x, e)."""
    return float(np.polyfit(xs, es, order)[-1])


def test_sphere_thin_compressible_layer_is_johnson():
    # a / a_J - 1 = c h/a with c = -0.1216 (nu = 0.3; measured at h/a = 0.062, 0.037, 0.022: -0.1215, -0.1216,
    # -0.1216); extrapolated to h -> 0: |.| < 2e-5 (measured 8e-6). p0 and delta converge as (h/a)^2.
    nu, P = 0.3, 100.0
    xs, ea, ep = [], [], []
    for h in (4e-6, 2e-6):
        c = axi.contact(E, nu, h, R, P)
        j = thin_layer.compressible(E, nu, h, R, P, "circular")
        xs.append(h / c.a)
        ea.append(c.a / j.a - 1)
        ep.append(c.p_max / j.p_max - 1)
    assert ea[0] / xs[0] == pytest.approx(ea[1] / xs[1], rel=5e-3)
    assert abs(_extrapolated(xs, ea, 1)) < 2e-5
    assert abs(ep[1]) < 3e-4 and abs(ep[1]) < abs(ep[0]) / 2.5


def test_sphere_thin_incompressible_layer_is_the_squeeze_film():
    # nu = 1/2: a / a_J - 1 = -1.16, -1.25, -1.32 x h/a at h/a = 0.15, 0.10, 0.068; the quadratic through the
    # three extrapolates to h -> 0 within 1e-2 (measured -3e-3: the next order of the expansion)
    P = 100.0
    xs, ea = [], []
    for h in (8e-6, 4e-6, 2e-6):
        c = axi.contact(E, 0.5, h, R, P)
        xs.append(h / c.a)
        ea.append(c.a / thin_layer.incompressible(E, h, R, P, "circular").a - 1)
    assert all(e < 0 for e in ea) and abs(ea[2]) < abs(ea[1]) < abs(ea[0])
    assert abs(_extrapolated(xs, ea, 2)) < 1e-2


@pytest.mark.parametrize("nu", [0.25, 0.5])
def test_sphere_load_displacement_is_the_flat_punch_stiffness(nu):
    # Barber (1974): dP/d delta of a smooth indenter = stiffness of the flat punch of the current radius.
    # Central difference over +-1e-4 in a (truncation ~ step^2: measured 1.0e-8 for nu = 0.25, 2.7e-8 for 0.5;
    # +-1e-3 gives 1e-6, 2.6e-6)
    h, a = 6e-6, 6e-5
    lo, hi = (axi.contact_at_radius(E, nu, h, R, a * f) for f in (1 - 1e-4, 1 + 1e-4))
    slope = (hi.load - lo.load) / (hi.approach - lo.approach)
    assert slope == pytest.approx(axi.flat_punch_stiffness(E, nu, h, a), rel=1e-7)


def test_sphere_equilibrium_and_own_convergence():
    # the pressure integrates to the load (r = a sin theta smooths the square-root edge for the quadrature);
    # N default vs 10 lambda + 16 (measured 1e-13)
    nu, h, P = 0.25, 6e-6, 100.0
    c = axi.contact(E, nu, h, R, P)
    x, w = np.polynomial.legendre.leggauss(600)
    th = 0.25 * np.pi * (x + 1)
    r = c.a * np.sin(th)
    assert 2 * np.pi * np.sum(0.25 * np.pi * w * c.a * np.cos(th) * r * c.pressure(r)) == pytest.approx(P, rel=1e-9)
    fine = axi.contact(E, nu, h, R, P, n=int(10 * c.a / h) + 16)
    for q in ("a", "p_max", "approach"):
        assert getattr(c, q) == pytest.approx(getattr(fine, q), rel=1e-11)
    assert c.stats["residual"] < 1e-12 and abs(c.stats["load_error"]) < 1e-12


# --------------------------------------------------------------------------------------------------------------
# Cylinder (plane strain, Fourier transform)
# --------------------------------------------------------------------------------------------------------------

def test_cylinder_thick_layer_is_hertz():
    # h / a = 13.5 and 135: half-width and peak approach Hertz as (a/h)^2 (measured 1.96e-3, 1.97e-5)
    nu, W = 0.3, 1e5
    hz = hertz.line_contact(W, R, E / (1 - nu**2))
    errs = []
    for h in (1e-3, 1e-2):
        c = plane.contact(E, nu, h, R, W)
        errs.append((c.a / hz.half_width - 1, c.p_max / hz.p_max - 1))
    assert abs(errs[1][0]) < 3e-5 and abs(errs[1][1]) < 3e-5
    assert errs[0][0] / errs[1][0] == pytest.approx(100.0, rel=0.02)


def test_cylinder_thin_compressible_layer_is_johnson():
    nu, W = 0.3, 1e5
    xs, ea, ed = [], [], []
    for h in (2e-6, 1e-6):
        c = plane.contact(E, nu, h, R, W)
        j = thin_layer.compressible(E, nu, h, R, W, "line")
        xs.append(h / c.a)
        ea.append(c.a / j.a - 1)
        ed.append(c.approach / j.approach - 1)
    # measured: a / a_J - 1 = -0.1222, -0.1221 x h/a at h/a = 0.092, 0.061; extrapolated limit -3e-6
    assert ea[0] / xs[0] == pytest.approx(ea[1] / xs[1], rel=5e-3)
    assert abs(_extrapolated(xs, ea, 1)) < 5e-5
    assert abs(ed[1]) < abs(ed[0]) and abs(ed[1]) < 1e-3


def test_cylinder_thin_incompressible_layer_is_the_squeeze_film():
    W = 1e5
    xs, ea = [], []
    for h in (4e-6, 2e-6, 1e-6):
        c = plane.contact(E, 0.5, h, R, W)
        xs.append(h / c.a)
        ea.append(c.a / thin_layer.incompressible(E, h, R, W, "line").a - 1)
    assert all(e < 0 for e in ea) and abs(ea[2]) < abs(ea[1]) < abs(ea[0])
    assert abs(_extrapolated(xs, ea, 2)) < 1e-2


@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_cylinder_load_displacement_is_the_flat_punch_stiffness(nu):
    # as for the sphere; measured 3.0e-9 (nu = 0.3), 5.6e-9 (nu = 0.5)
    h, a = 2e-6, 2e-5
    lo, hi = (plane.contact_at_half_width(E, nu, h, R, a * f) for f in (1 - 1e-4, 1 + 1e-4))
    slope = (hi.load - lo.load) / (hi.approach - lo.approach)
    assert slope == pytest.approx(plane.flat_punch_stiffness(E, nu, h, a), rel=1e-7)


def test_cylinder_equilibrium_and_own_convergence():
    nu, h, W = 0.3, 2e-6, 1e5
    c = plane.contact(E, nu, h, R, W)
    x, w = np.polynomial.legendre.leggauss(600)
    th = 0.25 * np.pi * (x + 1)            # x = a sin(theta): the square-root edge becomes smooth
    assert 2 * np.sum(0.25 * np.pi * w * c.a * np.cos(th) * c.pressure(c.a * np.sin(th))) == pytest.approx(W, rel=1e-9)
    fine = plane.contact(E, nu, h, R, W, n=2 * plane.default_nodes(c.a / h) + 1)
    for q in ("a", "p_max", "approach"):
        assert getattr(c, q) == pytest.approx(getattr(fine, q), rel=1e-10)
    assert c.stats["residual"] < 1e-10
