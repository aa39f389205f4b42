"""Convergence certificates (solvers.convergence.certify) on sequences with known behaviour."""
from __future__ import annotations

import math

import pytest

from femcheck.solvers.convergence import certify


def _levels(q_exact, c, p, n=3, r=2.0, h0=0.1):
    h = [h0 / r**i for i in range(n)]
    return h, [q_exact + c * x**p for x in h]


def test_second_order_sequence_is_certified_and_extrapolated_exactly():
    h, q = _levels(1.0, 5.0, 2.0)
    c = certify(h, q, expected_order=2.0)
    assert c.certified and c.order == pytest.approx(2.0, rel=1e-9) and c.value == pytest.approx(1.0, rel=1e-12)
    assert c.error_estimate == pytest.approx(1.25 * abs(q[-1] - 1.0), rel=1e-9)       # GCI of the finest level


def test_slowly_falling_sequence_is_not_certified():
    # roller-finite's centre pressure (issue 12): -0.75 % and -0.72 % per sqrt(2) level -> order 0.12
    h = [1.0, 1 / math.sqrt(2), 0.5]
    q = [1.0, 0.9925, 0.9925 * (1 - 0.0072)]
    c = certify(h, q)
    assert not c.certified and c.value == q[-1] and "outside" in c.note and c.order < 0.2
    assert c.error_estimate >= 3 * 0.0072 * 0.999


def test_oscillating_and_flat_sequences_are_not_certified():
    assert not certify([1, 0.5, 0.25], [1.0, 1.02, 1.01]).certified
    flat = certify([1, 0.5, 0.25], [2.0, 2.0, 2.0])
    assert not flat.certified and "mesh node" in flat.note


def test_order_far_from_the_expected_one_is_not_certified():
    h, q = _levels(1.0, 5.0, 1.0)
    assert certify(h, q).certified                        # first order is plausible without expectation
    assert not certify(h, q, expected_order=3.0, order_band=1.5).certified


def test_inconsistent_orders_over_four_levels_are_not_certified():
    h = [0.1, 0.05, 0.025, 0.0125]
    q = [1.2, 1.1, 1.05, 1.04]            # orders 1.0, then 2.3
    assert not certify(h, q).certified
    h, q = _levels(1.0, 5.0, 2.0, n=4)
    assert certify(h, q).certified


def test_singular_quantity_is_flagged():
    c = certify([1, 0.5, 0.25], [9.1e9, 9.4e9, 9.7e9], singular=True)
    assert not c.certified and "mesh-dependent" in c.note and c.value == 9.7e9


def test_levels_that_agree_below_the_floor_are_converged_whatever_the_sign():
    # layer-line's p_max on four levels (2D P2): 8.894851, 8.894771, 8.894815 (x 1e8 Pa): changes of 1e-5 carry no
    # order, the quantity no longer sees the mesh
    c = certify([0.05, 0.025, 0.0125], [8.894851e8, 8.894771e8, 8.894815e8])
    assert c.certified and c.value == 8.894815e8 and "converged" in c.note
    assert c.error_estimate == pytest.approx(3 * 8.0e3 / 8.894815e8, rel=1e-6)
    # the same pattern 50 times larger is an oscillation, not convergence
    assert not certify([0.05, 0.025, 0.0125], [1.0, 1.0 - 4.5e-4, 1.0 - 2e-4]).certified


def test_a_monotone_sequence_below_the_floor_is_still_extrapolated():
    h, q = _levels(1.0, 1e-3, 2.0)          # changes of 7.5e-6 and 1.9e-6: below the floor, but asymptotic
    c = certify(h, q)
    assert c.certified and c.value == pytest.approx(1.0, rel=1e-12) and "observed order" in c.note


def test_changes_within_the_scatter_of_the_estimates_certify_nothing():
    # hertz-point's FE semi-axis along x on three levels looked second-order (order 3.3, GCI 0.04 %) while the
    # y semi-axis of the same axisymmetric contact differed from it by 0.5 %: the last change (7e-4) was within
    # the scatter of the edge fits over P1 nodal reactions
    h = [0.0625, 0.0625 / 2**0.5, 0.03125]
    q = [3.990091e-4, 3.999419e-4, 4.002399e-4]
    assert certify(h, q).certified
    noisy = certify(h, q, sigma=[1.0e-6, 0.8e-6, 0.6e-6])
    assert not noisy.certified and "scatter" in noisy.note
    assert noisy.error_estimate >= 2 * 0.6e-6 / 4.002399e-4
    # the same levels with a scatter ten times smaller than the changes are certified, the error at least 2 sigma
    sharp = certify(h, q, sigma=[1e-8, 1e-8, 1e-8])
    assert sharp.certified and sharp.error_estimate >= 2e-8 / 4.0e-4
