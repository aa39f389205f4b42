"""The dry additional pressure of an indent in a circular and an elliptic contact (seed 004 §3.2.2, Table 3.2) by
femcheck's half-space BEM, the ellipticity changed at constant b and p_H (:func:`femcheck.ehl.groups.at_ellipticity`,
eq 3.1)."""
import pytest

from femcheck.bem import halfspace
from femcheck.ehl import groups
from femcheck.geometry.profiles import indented, paraboloid

R, NU, W = 0.010, 0.3, 1000.0                    # indent-dry's ball: steel, R = 10 mm, 1 kN
E_STAR = 210e9 / (2 * (1 - NU**2))
CIRCLE = groups.from_physical(R, R, 2 * E_STAR, W, 0.04, 2.2e-8, 1.0)   # lubricant and speed unused here


def dry_dp(kappa, phi, slope, physical=True, cells=65):
    """max(p - p_S)/p_H of an indent (K = 4; Phi = phi/b, D/Phi of the circular contact) over +-1.6 b along x and
    +-1.6 b/kappa across, square cells. ``physical``: the same indent (phi, d) in both contacts, so that
    D/Phi = (d/phi)(Rx/b) scales with Rx; else the dimensionless D/Phi is kept."""
    g = groups.at_ellipticity(CIRCLE, kappa)
    b = g.b
    ny = int(round(cells / kappa)) | 1
    grid = halfspace.grid(1.6 * b, 1.6 * b * ny / cells, cells, ny)
    base = paraboloid(g.Rx, g.Ry)
    depth = slope * phi * b * b / (CIRCLE.Rx if physical else g.Rx)
    smooth = halfspace.solve(grid, base, E_STAR, g.load, tol=1e-10).result.pressure
    dent = halfspace.solve(grid, indented(base, phi * b, depth, 4.0), E_STAR, g.load, tol=1e-10).result.pressure
    return float((dent - smooth).max()) / g.p_hertz


@pytest.mark.parametrize("phi, slope, thesis, band", [(0.5, 1.0, 0.0, 0.01), (1.0, 1.0, 0.03, 0.005)])
def test_table_3_2_same_indent_in_circle_and_ellipse(phi, slope, thesis, band):
    """Seed 004 Table 3.2 (dry, K = 4): |dP(kappa = 1) - dP(kappa = 0.1)|/dP(kappa = 1) is < 1 % at Phi = 0.5,
    D/Phi = 1 and 3 % at Phi = 1, D/Phi = 1 (< 1 % at Phi = 0.5, D/Phi = 2; 7 % at Phi = 1, D/Phi = 2). The thesis
    reproduces when the same physical indent sits in both contacts: femcheck 0.1 % / 3.4-3.5 % on 65 and 129 cells
    along x (D/Phi = 2: 0.4-0.5 % and 8.3-8.5 % against the thesis' < 1 % and 7 %, not asserted). Tolerance: the
    thesis' "< 1 %" as printed; its "3 %" as an integer (+-0.5 %) plus the 65-vs-129 change of the measure (0.1 %)."""
    d1, d01 = dry_dp(1.0, phi, slope), dry_dp(0.1, phi, slope)
    assert abs(d01 - d1) / d1 == pytest.approx(thesis, abs=band + 0.001)


def test_keeping_the_dimensionless_depth_is_not_the_thesis_comparison():
    """With the dimensionless D/Phi kept instead, the ellipse's indent is 1/0.794 times steeper in physical terms
    (Rx shrinks at constant b and p_H, eq 3.1) and its dry additional pressure rises: +18 % at Phi = 0.5, D/Phi = 1,
    kappa = 0.2 (65 cells; 18.3 %), far outside Table 3.2's < 1 %. Checked: the rise exceeds 10 %, and the physical
    comparison stays within the thesis' 1 %."""
    d1 = dry_dp(1.0, 0.5, 1.0)
    assert dry_dp(0.2, 0.5, 1.0, physical=False) > 1.10 * d1
    assert dry_dp(0.2, 0.5, 1.0) == pytest.approx(d1, rel=0.01)
