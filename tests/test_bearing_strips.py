"""The coupled-slice model (femcheck.bem.bearing_strips): the strip influence against the point load and the 2D
Hertz line contact, against a discretised Boussinesq solution, the slice-mean crown against quadrature, and the
solver's equilibrium and symmetry."""
import numpy as np
import pytest
from scipy.integrate import quad

from femcheck.analytic.iso16281 import crown_drop, crown_drop_slice_means
from femcheck.bem import bearing_strips as bs
from femcheck.bem.bearing_condensed3d import SlicedRow
from femcheck.bem.bearing_condensed3d import solve as solve_iso
from femcheck.bem.convolution import DCFFT
from femcheck.bem.influence import love_rectangle
from femcheck.materials import Elastic

E_STAR = 210e9 / (2 * (1 - 0.3**2))
STEEL = Elastic(210e9, 0.3)


def test_far_strip_acts_as_a_point_load():
    """|s| >> slice length, half-width: A = 1/(pi E* s) (1 + O((l/s)^2)): two segments' mean of 1/r is 1/s
    (1 + l^2/(6 s^2) + ...), the strip's width adds b^2/s^2 terms; asserted within (l/s)^2."""
    length, b = 0.96e-3, 0.12e-3
    for ratio in (10.0, 30.0):
        s = ratio * length
        a = bs.strip_influence(s, b, length, E_STAR)
        assert abs(a * np.pi * E_STAR * s - 1.0) < ratio**-2


def test_long_strip_follows_the_2d_hertz_logarithm():
    """For a strip much longer than wide the approach depends on the half-width as the 2D Hertz line contact's,
    d(delta)/d(ln b) = -2 w/(pi E*) (Johnson 1985 eq. 4.45's log term; w = 1/l per unit load): the width-dependent
    part of the mean over the length is 2D up to O(b/l) end terms; asserted within 5 b/l."""
    length = 0.1
    b1, b2 = 0.1e-3, 0.2e-3
    diff = bs.strip_influence(0.0, b1, length, E_STAR) - bs.strip_influence(0.0, b2, length, E_STAR)
    expected = 2.0 / (np.pi * E_STAR * length) * np.log(b2 / b1)
    assert diff == pytest.approx(expected, rel=5 * b2 / length)


def test_strip_influence_matches_a_discretised_boussinesq_solution():
    """Self and neighbour terms against Love's rectangles on a grid (the elliptical strip sampled at cell centres,
    the displacement of the two cells either side of x = 0 averaged along the receiving slice), extrapolated from
    two grids at the grid's second order; asserted within 0.5 % (the extrapolation's remaining error, measured
    0.1 % between the 3-grid and 2-grid estimates)."""
    length, b = 0.96e-3, 0.12e-3

    def grid(nx):
        ny = nx * 2                        # cells of 2 b/nx across, length/ny along: 4 b/nx vs 0.96/(2 nx) mm
        dx, dy = 2 * b / nx, length / ny
        x = (np.arange(nx) - nx / 2 + 0.5) * dx
        p = 2.0 / (np.pi * b) / length * np.sqrt(np.clip(1 - (x / b) ** 2, 0, None))[:, None] * np.ones((1, ny))
        big = np.zeros((nx, 3 * ny))
        big[:, ny:2 * ny] = p                # the loaded slice in the middle of three
        u = DCFFT(lambda tx, ty: love_rectangle(tx, ty, dx, dy, E_STAR), big.shape, (dx, dy))(big)
        mid = 0.5 * (u[nx // 2 - 1] + u[nx // 2])
        return np.array([mid[ny:2 * ny].mean(), mid[2 * ny:].mean()])

    coarse, fine = grid(32), grid(64)
    extrap = fine + (fine - coarse) / 3.0
    exact = bs.strip_influence(np.array([0.0, length]), b, length, E_STAR)
    assert np.allclose(exact, extrap, rtol=5e-3, atol=0)


def test_slice_mean_crown_is_the_mean_of_the_iso_profile():
    """The closed-form slice means of the ISO/TS 16281 logarithmic drop against adaptive quadrature; the last
    slice, which holds the logarithmic singularity at the roller's end, with QUADPACK's log(b - y) weight
    (P = -k D [ln(L/2 - y) + ln(2/L) + ln(1 + 2y/L)]); 1e-9 relative."""
    L, D, n = 9.6e-3, 10e-3, 10
    means = crown_drop_slice_means(L, D, n)
    edges = np.linspace(-L / 2, L / 2, n + 1)
    for k in range(1, n - 1):
        val, _ = quad(lambda y: float(crown_drop(np.array([y]), L, D)[0]), edges[k], edges[k + 1], limit=200)
        assert means[k] == pytest.approx(val / (edges[k + 1] - edges[k]), rel=1e-9)
    a, b, kD = edges[-2], edges[-1], 0.00035 * D
    singular, _ = quad(lambda y: 1.0, a, b, weight="alg-logb", wvar=(0.0, 0.0))
    regular, _ = quad(lambda y: np.log(2 / L) + np.log1p(2 * y / L), a, b)
    assert means[-1] == pytest.approx(-kD * (singular + regular) / (b - a), rel=1e-9)
    assert means[0] == pytest.approx(means[-1], rel=1e-12)


def _row(tilt=0.0, crown="iso", slices=40):
    return SlicedRow(14, 9.6e-3, 10e-3, 0.0, slices, crown, tilt)


def test_equilibrium_symmetry_and_misalignment():
    """Sum Q cos psi = F to 1e-10 F; aligned: slice loads symmetric about the roller's middle (1e-8) and roller
    loads symmetric about the load line; misaligned 0.5 mrad: the loaded end is the one the misalignment presses
    (the same as rigid-ring ISO/TS 16281's), and the roller loads sum the slices."""
    aligned = bs.solve(_row(), 27.516e-3, 37.516e-3, STEEL, None, 8900.0)
    psi = _row().psi
    assert np.sum(aligned.roller_loads * np.cos(psi)) == pytest.approx(8900.0, rel=1e-10)
    q = aligned.slice_loads
    assert np.allclose(q, q[:, ::-1], rtol=0, atol=1e-8 * q.max())
    assert np.allclose(aligned.roller_loads[1:], aligned.roller_loads[1:][::-1], rtol=1e-8)
    tilted = bs.solve(_row(5e-4), 27.516e-3, 37.516e-3, STEEL, None, 8900.0)
    ends = tilted.slice_loads[0, :8].sum() - tilted.slice_loads[0, -8:].sum()
    iso = solve_iso(_row(5e-4, slices=10), None, 8900.0).slice_loads[0]
    assert np.sign(ends) == np.sign(iso[:2].sum() - iso[-2:].sum()) != 0
    assert abs(ends) > 0.1 * tilted.slice_loads[0].sum() / 5     # the tilt is felt (10 % of a fifth's load)
    assert np.allclose(tilted.slice_loads.sum(axis=1), tilted.roller_loads)
    assert tilted.residual < 1e-10


def test_a_stiffer_finite_body_correction_moves_load_to_the_roller_centre():
    """A negative correction on the middle slices of every roller (stiffer there) draws load to them; zero
    correction reproduces D = None exactly. The correction is a fraction f of a slice's own strip compliance; with
    the other slices' coupling ignored the middle share s would rise by f s (1 - s): asserted at least a quarter of
    that (the coupling spreads part of it back)."""
    row = _row(slices=10)
    base = bs.solve(row, 27.516e-3, 37.516e-3, STEEL, None, 8900.0)
    same = bs.solve(row, 27.516e-3, 37.516e-3, STEEL, np.zeros((140, 140)), 8900.0)
    assert np.allclose(same.slice_loads, base.slice_loads, rtol=1e-12, atol=0)
    d = np.zeros(10)
    d[4:6] = -1e-9
    stiff = bs.solve(row, 27.516e-3, 37.516e-3, STEEL, np.diag(np.tile(d, 14)), 8900.0)
    share = lambda r: r.slice_loads[0, 4:6].sum() / r.roller_loads[0]
    f = 1e-9 / bs.strip_influence(0.0, base.half_widths[0, 0, 4], row.length / row.slices, E_STAR)
    s0 = share(base)
    assert share(stiff) > s0 + 0.25 * f * s0 * (1 - s0)
