"""femcheck.solvers.finite_body_certificate: the parts of a finite-body reference (formal order, the re-meshing
floor, convergence after one step) and the three parts assembled."""
import pytest

from femcheck.solvers.finite_body_certificate import certify_parts, correction_certificate, family_certificate, settled
from femcheck.solvers.split_certificate import CORRECTION_ORDER

H = [1.0, 1 / 1.5, 1 / 2.25]            # the correction levels' ratio 1.5


def test_second_order_levels_extrapolate_to_their_limit():
    q = [2.0 + 0.3 * h ** 2 for h in H]                # exactly second order, limit 2
    c = correction_certificate(H, q, 2e-3)
    assert c.certified and c.value == pytest.approx(2.0, rel=1e-12) and c.order == pytest.approx(2.0)
    # the GCI 1.25 |2 - q[-1]| / 2 = 1.85 % is above the floor: kept
    assert c.error_estimate == pytest.approx(1.25 * 0.3 / 2.25 ** 2 / 2.0, rel=1e-9)


def test_faster_than_formal_is_extrapolated_at_the_formal_order():
    """The measured family's shape: -0.94 % then -0.06 % (observed order 6.8, outside a factor 2 of 2). Richardson
    at the observed order would claim 0.004 %; at the formal order the step is (q3 - q2) / (1.5^2 - 1)."""
    q = [5.4367, 5.3856, 5.3823]
    c = correction_certificate(H, q, 2e-3)
    assert c.certified and c.order > 2 * CORRECTION_ORDER
    assert c.value == pytest.approx(5.3823 + (5.3823 - 5.3856) / (1.5 ** 2 - 1), rel=1e-12)
    # the formal-order GCI (0.061 %) is below the floor: the estimate is the floor
    assert c.error_estimate == 2e-3 and "re-meshing floor" in c.note


def test_oscillating_levels_above_the_floor_are_not_certified():
    c = correction_certificate(H, [1.0, 1.02, 0.99], 2e-3)
    assert not c.certified


def test_a_step_below_the_floor_after_a_larger_one_is_convergence_not_oscillation():
    """The far field on the correction's near field, sum f_lat at mu 0.1 (1e-2): +0.46 % then -0.02 % against a
    0.2 % floor. The second change is re-meshing scatter: settled at the finest level, estimate the floor."""
    q = [5.4367, 5.4616, 5.4608]
    for c in (family_certificate(H, q, 2e-3, None), correction_certificate(H, q, 2e-3)):
        assert c.certified and c.value == q[-1] and c.error_estimate == 2e-3 and "after one step" in c.note
    # 3 x the last change when that is above the floor
    assert settled(H, [1.0, 1.01, 1.0098], 5e-4).error_estimate == pytest.approx(3 * 0.0002 / 1.0098, rel=1e-9)


def test_a_last_change_above_the_floor_or_contracting_slower_than_second_order_is_not_settled():
    # +1 % then -0.30 %: contracting fast enough (0.30 x 1.5^2 < 1), but the last change is above the floor
    assert settled(H, [1.0, 1.01, 1.007], 2e-3) is None
    assert not family_certificate(H, [1.0, 1.01, 1.007], 2e-3, None).certified
    # -0.18 %: below the floor, but 0.18 x 1.5^2 = 0.40 > 0.30 %: not contracting as a second-order family
    assert settled(H, [1.0, 1.003, 1.0012], 2e-3) is None
    assert not family_certificate(H, [1.0, 1.003, 1.0012], 2e-3, None).certified


def test_parts_combine_the_far_field_step_from_its_first_level():
    """The correction's and the contact grid's levels are solved on the far field's first mesh (the coarsest
    correction's), so the far field's step is its value minus its first level, not minus its finest."""
    corr = [{"h": h, "q": 2.0 + 0.3 * h ** 2} for h in H]
    far = [dict(corr[0]), {"h": H[1], "q": corr[0]["q"] * 1.005}, {"h": H[2], "q": corr[0]["q"] * 1.00501}]
    scatter = [{"q": corr[0]["q"] * 1.004}]                                # 0.4 % scatter: the floor
    grid = [{"h": h, "q": 3.0 + 0.1 * h, "q_phase_spread": 1e-4} for h in (1.0, 2 ** -0.5, 0.5)]
    out = certify_parts(["q"], corr, far, scatter, grid, 1.0)
    assert out["remesh_floors"]["q"] == pytest.approx(0.004, rel=1e-9)
    c = out["combined"]["q"]
    assert c.certified and out["far_field_certificates"]["q"]["certified"]
    # the grid's limit 3.0, plus the correction's step 2.0 - q_corr[-1], plus the far field's: finest - first
    assert c.value == pytest.approx(3.0 + (2.0 - corr[-1]["q"]) + (far[-1]["q"] - far[0]["q"]), rel=1e-12)
    assert set(out) == {"combined", "certificates", "correction_certificates", "far_field_certificates",
                        "grid_certificates", "remesh_floors"}


def test_parts_without_a_far_field_family_or_with_it_missing():
    """The groove's reference has no far-field family: two parts, the correction certified by the srb family's
    rule (a family that converges faster than second order is extrapolated at order 2). A reference whose far-field
    family is missing (a coarse re-solve of level 0 only) certifies nothing."""
    corr = [{"h": h, "q": 2.0 + 0.3 * h ** 6} for h in H]          # order 6: beyond twice the formal order 2
    scatter = [{"q": corr[0]["q"] * 1.0001}]
    grid = [{"h": h, "q": 3.0 + 0.1 * h, "q_phase_spread": 1e-4} for h in (1.0, 2 ** -0.5, 0.5)]
    two = certify_parts(["q"], corr, None, scatter, grid, 1.0)
    assert "far_field_certificates" not in two and two["combined"]["q"].certified
    r2 = (H[-2] / H[-1]) ** 2     # extrapolated at the formal order 2, not at the observed 6
    assert two["correction_certificates"]["q"]["value"] == pytest.approx(
        corr[-1]["q"] + (corr[-1]["q"] - corr[-2]["q"]) / (r2 - 1.0), rel=1e-12)
    assert two["combined"]["q"].value == pytest.approx(3.0 + (two["correction_certificates"]["q"]["value"]
                                                              - corr[-1]["q"]), rel=1e-12)
    missing = certify_parts(["q"], corr, [], scatter, grid, 1.0)
    assert not missing["far_field_certificates"]["q"]["certified"] and not missing["combined"]["q"].certified
