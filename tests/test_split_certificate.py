"""femcheck.solvers.split_certificate: the combined certificate of discretisations refined apart, and the contact
grid's part for lattice-phase means."""
import pytest

from femcheck.solvers.convergence import Certificate
from femcheck.solvers.split_certificate import REMESH_SCATTER, combine, grid_certificate, remesh_floor

H = [1.0, 2 ** -0.5, 0.5, 2 ** -1.5]


def test_first_order_levels_extrapolate_at_first_order_whatever_the_spread():
    q = [1.0 + 0.04 * h for h in H]                   # exactly first order: the limit is 1
    c = grid_certificate(H, q, [1e-3] * 4, 1.0)
    assert c.certified and c.value == pytest.approx(1.0, rel=1e-12) and c.order == pytest.approx(1.0)


def test_changes_below_the_phase_spread_are_lattice_residue():
    q = [1.0, 1.0006, 0.9999, 1.0005]                 # +-0.06 % zig-zag: no order
    spreads = [3e-3, 2e-3, 8e-4, 4e-4]
    c = grid_certificate(H, q, spreads, 1.0)
    assert c.certified and c.value == q[-1]
    assert c.error_estimate == pytest.approx(3 * 7e-4 / 1.0005, rel=1e-9)        # the larger change
    assert "lattice phases' spread" in c.note
    # the same zig-zag with phase spreads below it is not residue: no certificate
    tight = grid_certificate(H, q, [1e-4] * 4, 1.0)
    assert not tight.certified


def test_combined_certificate_adds_the_parts_steps_and_estimates():
    """A finite-body reference's combined value is the contact grid's extrapolation plus the correction's and
    the far field's extrapolation steps, its relative estimate the sum of the parts' absolute estimates over it;
    certified only when every part is."""
    grid = Certificate(5.0, 5.1, 1.0, 0.01, True, "grid")                # 0.05 absolute
    corr = Certificate(4.9, 5.0, 2.0, 0.02, True, "corr")                # step -0.1, 0.098 absolute
    far = Certificate(5.02, 5.0, 1.5, 0.005, True, "far")                # step +0.02, 0.0251 absolute
    c = combine({"contact grid": grid, "correction": corr, "far field": far})
    assert c.value == pytest.approx(5.0 - 0.1 + 0.02, rel=1e-12)
    assert c.error_estimate == pytest.approx((0.05 + 0.098 + 0.0251) / 4.92, rel=1e-12)
    assert c.certified
    far_not = Certificate(5.0, 5.0, None, 0.03, False, "far")
    assert not combine({"contact grid": grid, "correction": corr, "far field": far_not}).certified


def test_a_combined_estimate_above_the_value_is_not_certified_whatever_its_parts_say():
    """groove/crown 1.002's adhesion fraction (0.3 % of the cells): the contact grid's levels change by less than
    their lattice-phase spread (290 %), so the part is certified by that floor with a 690 % estimate; the
    combined value is not resolved and must not be certified."""
    grid = Certificate(0.00304, 0.00304, None, 6.9, True, "grid: converged below the lattice phases' spread")
    corr = Certificate(0.0113, 0.0113, 2.0, 0.02, True, "corr")
    c = combine({"contact grid": grid, "correction": corr})
    assert c.error_estimate > 1.0 and not c.certified and "not resolved" in c.note
    # the same parts with a grid estimate of 50 %: resolved, certified
    ok = combine({"contact grid": Certificate(0.00304, 0.00304, None, 0.5, True, "grid"), "correction": corr})
    assert ok.error_estimate < 1.0 and ok.certified


def test_remesh_floor_is_the_measured_spread_but_never_below_the_assumed_one():
    assert remesh_floor([{"q": 2.0}, {"q": 2.01}, {"q": 1.996}], "q") == pytest.approx(0.014 / 2.0)
    assert remesh_floor([{"q": 2.0}, {"q": 2.0001}], "q") == REMESH_SCATTER
