"""Grid levels with exactly geometric cell sizes and the lattice-phase mean (femcheck.cect.lattice_phase), checked
on a model quantity whose lattice dependence and limit are known: q(h, e) = q0 + c h + A cos(2 pi e), e the edge's
position in cells (its fractional part the lattice phase), the form of the srb-rolling lateral forces' grid
dependence (first-order rolling error plus a +-1.2 % snap to the lattice)."""
from __future__ import annotations

import numpy as np
import pytest

from femcheck.cect import lattice_phase as lp
from femcheck.solvers.convergence import certify_formal

Q0, C, A = 5.0e-2, 2.0e-3, 6.0e-4        # limit, first-order coefficient, snap amplitude (1.2 % of Q0)
CELLS0, DOMAIN0 = (41, 81), (1.35, 1.25)


def model(cells: int, domain: float, h: float) -> float:
    e = cells / (2.0 * domain)           # Hertz edge in cells from the window's centre
    return Q0 + C * h + A * np.cos(2.0 * np.pi * e)


def test_levels_have_exactly_geometric_cell_sizes():
    lv = lp.levels(CELLS0, DOMAIN0, np.sqrt(2.0), 4)
    assert [v.cells for v in lv] == [(41, 81), (58, 115), (82, 162), (116, 229)]
    for axis in (0, 1):
        dx = [2.0 * v.domain[axis] / v.cells[axis] for v in lv]
        np.testing.assert_allclose(np.array(dx[:-1]) / np.array(dx[1:]), np.sqrt(2.0), rtol=1e-12)
    np.testing.assert_allclose([v.h for v in lv], [2.0 ** (-k / 2) for k in range(4)], rtol=1e-12)
    # odd counts (a cell centred on the window's centre at every level), nearest to n0 r^k, same cell sizes
    odd = lp.levels(CELLS0, DOMAIN0, np.sqrt(2.0), 4, odd=True)
    assert [v.cells for v in odd] == [(41, 81), (57, 115), (83, 163), (115, 229)]
    for a, b in zip(lv, odd):
        np.testing.assert_allclose([2.0 * d / n for d, n in zip(a.domain, a.cells)],
                                   [2.0 * d / n for d, n in zip(b.domain, b.cells)], rtol=1e-12)


def test_phase_domains_move_the_edge_by_equal_fractions_of_a_cell():
    d = lp.phase_domains(58, 1.3504, 4)
    e = [58 / (2.0 * x) for x in d]
    np.testing.assert_allclose(np.diff(e), -0.25, rtol=1e-12)
    assert d[0] == 1.3504


def test_phase_windows_move_both_edges_or_only_the_rolling_one():
    both = lp.phase_windows((58, 115), (1.3504, 1.2553), 4)
    for axis, (n, d0) in enumerate(((58, 1.3504), (115, 1.2553))):
        e = [n / (2.0 * w[axis]) for w in both]
        np.testing.assert_allclose(np.diff(e), -0.25, rtol=1e-12)
        assert both[0][axis] == d0
    along_x = lp.phase_windows((58, 115), (1.3504, 1.2553), 4, along_s=False)
    assert [w[0] for w in along_x] == [w[0] for w in both]
    assert all(w[1] == 1.2553 for w in along_x)


def test_level_record_holds_the_level_the_mean_and_the_spread():
    v = lp.levels(CELLS0, DOMAIN0, np.sqrt(2.0), 2)[1]
    rec = lp.level_record(v, 2, [{"q": 1.0}, {"q": 3.0}])
    assert rec == {"nx": 58, "ns": 115, "h": v.h, "domain_x": v.domain[0], "domain_s": v.domain[1], "phases": 2,
                   "q": 2.0, "q_phase_spread": 2.0}


def _levels(phases: int) -> tuple[list[float], list[float]]:
    h, q = [], []
    for v in lp.levels(CELLS0, DOMAIN0, np.sqrt(2.0), 4):
        samples = [{"q": model(v.cells[0], dj, v.h)} for dj in lp.phase_domains(v.cells[0], v.domain[0], phases)]
        h.append(v.h)
        q.append(lp.phase_mean(samples)[0]["q"])
    return h, q


def test_phase_mean_removes_the_snap_and_the_levels_show_first_order():
    """Single windows (1 phase) carry the snap: the levels oscillate and are not certified. The mean over 4 phases
    removes it (the trapezoidal rule is exact for a first harmonic), the levels converge at order 1 and the
    extrapolation recovers q0 to round-off."""
    h, q1 = _levels(1)
    single = certify_formal(h, q1, 1.0)
    assert not single.certified or abs(single.value - Q0) > 0.2 * A
    h, q4 = _levels(4)
    c = certify_formal(h, q4, 1.0)
    assert c.certified and c.order == pytest.approx(1.0, abs=0.05)
    assert c.value == pytest.approx(Q0, rel=2e-3)


def test_phase_mean_reports_the_spread():
    mean, spread = lp.phase_mean([{"q": 1.0, "r": 2.0}, {"q": 3.0, "r": 2.0}, {"q": 2.0, "r": None}])
    assert mean == {"q": 2.0} and spread == {"q": 2.0}


def test_bad_levels_and_phases_are_refused():
    with pytest.raises(ValueError):
        lp.levels(CELLS0, DOMAIN0, 1.0, 3)
    with pytest.raises(ValueError):
        lp.phase_domains(3, 1.6, 4)
