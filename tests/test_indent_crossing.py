"""The additional pressure of a dry indent crossing the contact (seed 004 §3.2.1, Table 3.1), by femcheck's BEM
(the indented contact solved at each indent position) and the two measures of
:func:`femcheck.problems._indent_life.crossing_additional_pressure`."""
import numpy as np
import pytest

from femcheck.analytic import hertz
from femcheck.bem import halfspace
from femcheck.geometry.profiles import indented, paraboloid
from femcheck.problems._indent_life import crossing_additional_pressure

R, NU, W = 0.010, 0.3, 1000.0                   # indent-dry's ball: steel, R = 10 mm, 1 kN
E_STAR = 210e9 / (2 * (1 - NU**2))
HZ = hertz.point_contact(W, R, E_STAR)
A, P0 = HZ.semi_axis_x, HZ.p_max
CELLS, HALF = 129, 2.0                            # 129^2 cells over +-2 a: 16 cells per Phi = 0.5


def _crossing(phi, K, slope, positions):
    g = halfspace.grid(HALF * A, HALF * A, CELLS, CELLS)
    smooth = halfspace.solve(g, paraboloid(R, R), E_STAR, W).result.pressure / P0
    frames = {}
    for xd in positions:
        gap = indented(paraboloid(R, R), phi * A, slope * phi * A * A / R, K, x0=xd * A)
        frames[xd] = halfspace.solve(g, gap, E_STAR, W, tol=1e-10).result.pressure / P0
    return g, smooth, frames


ENTRY = [round(-1.0 + 0.1 * k, 10) for k in range(11)]    # the indent centre from the inlet edge to the centre


@pytest.mark.parametrize("slope", [1.0, 2.0])
def test_inner_shoulder_amplitude_is_constant_over_the_crossing(slope):
    """Seed 004 Table 3.1 (K = 4, Phi = 0.5): |dP(x_D = 0) - max_T dP|/max_T dP < 1 % for D/Phi = 1 and 2. The
    amplitude that stays constant is that of the shoulder on the contact-centre side of the indent (downstream
    while it enters): femcheck 0.2 % / 0.1 % on 129^2 cells, 0.0 % / 0.0 % on 257^2 (indent centre every 0.05 a
    from -1.3 a to 0). Tolerance: the thesis' 1 % plus the measure's change from 129^2 to 257^2 (0.2 %).
    Not asserted, measured at Phi = 1 (thesis < 1 %, 2 %): 1.2 % / 3.5 % on 129^2, 1.2 % / 3.5 % on 257^2."""
    g, smooth, frames = _crossing(0.5, 4.0, slope, ENTRY)
    d = crossing_additional_pressure(g.x / A, g.y / A, smooth, frames, 0.5)
    assert d["table_3_1_difference"] <= 0.01 + 0.002


def test_grid_maximum_rises_where_a_shoulder_meets_the_contact_edge():
    """The largest dP over the grid is not constant over the crossing: when a shoulder of the indent (peak at
    r ~ 0.6 Phi) reaches the edge of the Hertz contact, where the smooth pressure vanishes, it carries its own
    contact pressure. Measured (Phi = 0.5, D/Phi = 0.5, K = 4): 0.469 p_H at x_D = -0.75 a against 0.320 centred
    on 129^2 cells (+46 %), 0.466 against 0.319 on 257^2 (+46 %): grid-converged, a property of the contact, not of
    the grid or of the sampling of the indent positions. Checked: that maximum lies on the Hertz circle r = a
    (Johnson 1985 eq 4.22: a = (3 W R/(4 E*))^(1/3)) within two cells, and it exceeds the centred value by more
    than Table 3.1's 1 % (so it is not the amplitude the thesis finds constant), while the inner shoulder's stays
    within 1 % + 0.2 % (as above)."""
    g, smooth, frames = _crossing(0.5, 4.0, 0.5, [-0.8, -0.75, -0.7, 0.0])
    d = crossing_additional_pressure(g.x / A, g.y / A, smooth, frames, 0.5)
    dp = frames[d["max_at"]] - smooth
    i, j = np.unravel_index(int(np.argmax(dp)), dp.shape)
    r = np.hypot(g.x[i], g.y[j])
    assert r == pytest.approx((3 * W * R / (4 * E_STAR)) ** (1 / 3), abs=2 * g.dx)
    assert d["max"] > 1.01 * d["centred"]
    assert d["table_3_1_difference"] <= 0.01 + 0.002
