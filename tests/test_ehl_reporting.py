"""How EHL runs report failures and what a crossing covers (femcheck/ehl/failures.py, steady.py, transient.py,
model.py, adapter.py): a divergence or a cycle cap reports the residual and load error it stopped at with their
tolerances and where; a coarse grid of the certificate that does not resolve the contact is left out and said so;
every step of a crossing has its film checked; the crossing passes the centre and leaves through the exit."""
import copy
import dataclasses

import numpy as np
import pytest

from femcheck.ehl import adapter, failures, groups, model, relax, steady, transient
from femcheck.ehl.film import Indent
from femcheck.ehl.multigrid import Multigrid
from femcheck.errors import ConvergenceError
from femcheck.scene import load_scene


def setup(M, L, grid=65, x=(-4.5, 1.5)):
    g = groups.from_moes(M, L, 0.01, 0.01, 226e9, 0.04, 2.2e-8)
    return model.make_setup(g, "roelands", "dowson_higginson", grid, None, *x)


# -- (a) a failed solve reports the numbers it stopped at -------------------------------------------------------

def test_divergence_reports_the_last_finite_residual_and_where(monkeypatch):
    """Over-relaxed line relaxation (omega = 3, beyond the Gauss-Seidel stability bound 2) makes the full-multigrid
    start diverge on the 33^2 grid of a 65^2 solve. The error reports the mean scaled residual of the last finite
    stage (the coarsest grid after its start, recomputed here from the same pieces), the tolerance and where it
    diverged. Before: 'residual 0.000e+00 > tolerance 1.0e-07 after 0 iterations' (a non-finite pressure has no
    node with P > 0, so the residual norm read 0)."""
    monkeypatch.setattr(relax, "OMEGA_GS", 3.0)
    monkeypatch.setattr(relax, "OMEGA_JA", 3.0)
    s = setup(100, 10)
    with np.errstate(all="ignore"), pytest.raises(ConvergenceError) as err:
        steady.solve(s.prob, s.n, s.levels, tol=1e-7, load_tol=1e-7)
    with np.errstate(all="ignore"):
        mg = Multigrid(s.prob, s.n, s.levels, gamma=2)
        mg.hertz_start()
        mg.relax_coarsest(200)
        expect, _ = mg.residual_norm(mg.levels[0])
    msg = str(err.value)
    assert np.isfinite(expect) and expect > 1e-7
    assert err.value.residual == pytest.approx(expect, rel=1e-12)
    assert f"{expect:.3e}" in msg and "tolerance 1.0e-07" in msg and "0.000e+00" not in msg
    assert "65^2" in msg and "diverged" in msg and "33^2" in msg and "17^2" in msg


def test_residual_norm_of_a_non_finite_pressure_is_nan():
    s = setup(100, 10, grid=33)
    mg = Multigrid(s.prob, s.n, s.levels)
    mg.hertz_start()
    mg.fine.P[:] = np.nan
    assert all(np.isnan(v) for v in mg.residual_norm(mg.fine))


def test_cycle_cap_reports_the_residual_and_load_error_it_stopped_at():
    """Residual criterion met (tol = 1), load criterion not (1e-14), two cycles allowed: the error carries the
    residual and load error after exactly two cycles, recomputed here by two cycles on a copy of the solver state,
    and says which criterion failed. Before: 'residual ... > tolerance 1.0e+00', false for this residual."""
    s = setup(100, 10)
    _, mg = steady.solve(s.prob, s.n, s.levels, tol=1.0, load_tol=1.0)        # the FMG start, no cycle
    ref = copy.deepcopy(mg)
    for _ in range(2):
        ref.cycle(len(ref.levels) - 1)
    res, _ = ref.residual_norm(ref.fine)
    with pytest.raises(ConvergenceError) as err:
        steady.solve(s.prob, s.n, s.levels, tol=1.0, load_tol=1e-14, max_cycles=2)
    e = err.value
    assert e.iterations == 2
    assert e.residual == pytest.approx(res, rel=1e-12) and res < 1.0
    assert e.load_error == pytest.approx(ref.load_error(), rel=1e-12) and e.load_error > 1e-14
    msg = str(e)
    assert f"mean scaled residual {res:.3e} <= tolerance 1.0e+00" in msg
    assert f"load error {ref.load_error():.3e} > tolerance 1.0e-14" in msg and "65^2" in msg


def test_transient_step_failure_names_grid_step_and_indent_position():
    """One cycle per step cannot reach 1e-12: the first step fails, and says so with the grid, the step, the time
    and the indent centre X_D = X_D0 + hT (unit speed)."""
    s = setup(100, 10, x=(-2.5, 1.5))
    sol, mg = steady.solve(s.prob, s.n, s.levels, tol=1e-8, load_tol=1e-8)
    ind = Indent(0.5, 0.125, 4.0, x0=-1.3)
    mg.prob = dataclasses.replace(s.prob, indent=ind)
    mg.set_time(0.0)
    transient.start(mg)
    with pytest.raises(ConvergenceError) as err:
        transient.march(mg, 5, tol=1e-12, load_tol=1e-12, max_cycles=1, base=sol.P)
    msg = str(err.value)
    xd = -1.3 + mg.fine.h
    assert "EHL transient (65^2 nodes), step 1 of 5" in msg and f"X_D = {xd:.4g} b" in msg
    assert err.value.residual > 1e-12 and f"{err.value.residual:.3e} > tolerance 1.0e-12" in msg


# -- (b) a coarse grid of the certificate that does not resolve the contact --------------------------------------

CERT_CASE = {"ehl.M": 300.0, "ehl.L": 10.0, "numerics.grid": 129, "numerics.refinements": 3}


def test_certificate_starts_at_the_coarsest_grid_that_resolves_the_contact():
    """ehl-smooth at M = 300, L = 10 with the certificate 33^2 / 65^2 / 129^2: the 33^2 solution converges to a
    negative film (under-resolved) and is left out; the run reports the 65^2 / 129^2 certificate, says which grid
    was refused and claims no order (two grids), and its value is the 129^2 solution (the same number as a run on
    129^2 alone). Before: the whole run failed with '33^2 ... refused: ... use a finer numerics.grid'."""
    r = adapter.run(load_scene("ehl-smooth", CERT_CASE).params)
    alone = adapter.run(load_scene("ehl-smooth", {**CERT_CASE, "numerics.refinements": 1}).params)
    st = r.stats
    assert st["certificate_grids"] == [65, 129] and [x["grid"] for x in st["refused_grids"]] == [33]
    assert st["refused_grids"][0]["film_min"] < 0
    c = st["certificates"]["h_central"]
    assert not c["certified"] and c["order"] is None
    assert c["note"].startswith("33^2 refused (negative film") and "certificate over 65^2, 129^2" in c["note"]
    assert r.quantities["h_central"] == alone.quantities["h_central"] == c["finest"]


def test_a_coarse_level_failure_names_the_refinements_key(monkeypatch):
    """Any other failure on a coarse grid of the certificate says which level it was and which
    numerics.refinements leaves it out (the finest grid's own failures keep their message)."""
    real = model.solve_smooth

    def failing_on_33(s, tol, load_tol):
        if s.n + 1 == 33:
            raise failures.not_converged("EHL steady multigrid (33^2 nodes)", 60, 3e-5, tol, 2e-6, load_tol)
        return real(s, tol, load_tol)

    monkeypatch.setattr(model, "solve_smooth", failing_on_33)
    with pytest.raises(ConvergenceError) as err:
        adapter.run(load_scene("ehl-smooth", {"numerics.grid": 129, "numerics.refinements": 3}).params)
    msg = str(err.value)
    assert "33^2 level, 1 of 3 of the grid certificate" in msg
    assert "numerics.refinements = 2 starts the certificate at 65^2" in msg


# -- (c) every step of a crossing has its film checked ------------------------------------------------------------

def _indent_state(grid=65):
    """ehl-indent's contact (M = 400, L = 5, [-2.5, 1.5] b) with its indent (Phi = 0.5, D/Phi = 0.5, K = 4)
    starting at X_D = -1.5 b; on 65^2 the film over its shoulders turns negative as it enters the contact."""
    s = setup(400, 5, grid, x=(-2.5, 1.5))
    sol, mg = steady.solve(s.prob, s.n, s.levels)
    mg.prob = dataclasses.replace(s.prob, indent=Indent(0.5, 0.25, 4.0, x0=-1.5))
    mg.set_time(0.0)
    transient.start(mg)
    return sol, mg


def test_every_crossing_step_has_its_film_checked():
    """Marched without the check, the film over the indent's shoulders is first negative at some step k0 before the
    centre (measured: step 6 of 10, X_D = -1.125 b, the position where the full crossing from the inlet on 65^2
    turns negative too); with the check the march stops at exactly that step and names it
    and the indent position. Before: the film was checked at X_D = 0 only, so this run went on to the centre and
    was refused 'at X_D = 0', and a crossing whose film was negative only away from the centre was reported."""
    sol, mg = _indent_state()
    free = copy.deepcopy(mg)
    hist = transient.march(free, 10, base=sol.P, film_check=False)
    neg = [k for k, h in enumerate(hist.h_min, start=1) if h <= 0]
    assert neg and hist.x_indent[neg[0] - 1] < -0.5, neg       # negative well before the centre
    k0 = neg[0]
    assert k0 > 1 and hist.h_min[k0 - 2] > 0
    with pytest.raises(failures.UnderResolvedFilm) as err:
        transient.march(mg, 10, base=sol.P)
    msg = str(err.value)
    assert f"step {k0} of 10" in msg and f"X_D = {hist.x_indent[k0 - 1]:.4g} b" in msg
    assert err.value.h_min == pytest.approx(hist.h_min[k0 - 1], rel=1e-12) and "negative film" in msg


# -- (d) the full crossing -------------------------------------------------------------------------------------------

@pytest.mark.slow
def test_crossing_goes_through_the_centre_and_out_through_the_exit():
    """M = 100, L = 10, 65^2 over [-2.5, 1.5] b, indent Phi = 0.5, D/Phi = 0.25, K = 4: the indent starts Phi
    upstream of the inlet, passes X_D = 0 on a step (the centred amplitudes are read there) and ends at
    X_D = 1 + 1.5 Phi, one mesh size per step. Once it has left the contact the pressure is back on the smooth steady
    solution (an indent outside the contact is the smooth contact, spec §A.11 check 5c) to 1 % of p_H (measured
    0.15 %; at X_D = 0 the hole holds dP = -0.25 p_H and the shoulders 0.065 p_H); the kept snapshots span the whole crossing and include the centred
    step (the pseudo-transient life pass needs it), and the dP history covers both halves."""
    s = setup(100, 10, x=(-2.5, 1.5))
    c = model.crossing(s, {"diameter": 0.5, "slope": 0.25, "decay": 4.0}, 0.0, 1e-7, 1e-7, snapshots=8)
    x = np.array(c["history"].x_indent)
    h = 4.0 / 64
    assert np.allclose(np.diff(x), h, rtol=0, atol=1e-12)
    assert -2.5 - 0.5 - h < x[0] - h <= -2.5 - 0.5        # X_D0, before the first step
    assert x[c["centre_step"] - 1] == pytest.approx(0.0, abs=1e-12)
    assert 1.75 <= x[-1] < 1.75 + h
    assert c["steps"] == len(x) and c["final"].T == pytest.approx(c["history"].T[-1])
    sm = c["smooth"]
    centred = c["amplitudes"]["amplitude"][c["centre_step"] - 1]
    assert centred > 0.05
    assert np.abs(c["final"].P - sm.P).max() < 0.01
    assert np.allclose(c["centred"].P, c["history"].snapshots[c["history"].kept_steps.index(c["centre_step"])].P)
    kept_x = x[np.array(c["history"].kept_steps) - 1]
    assert kept_x.min() < -1.5 and kept_x.max() >= 1.75 and np.any(kept_x == x[c["centre_step"] - 1])
    rear = np.array(c["amplitudes"]["rear"])
    assert np.isfinite(rear[(x > 0.2) & (x < 1.0)]).all()


@pytest.mark.parametrize("phi, x_start, speed", [(0.5, -2.5, 1.0), (1.0, -4.5, 1.0), (0.25, -2.5, 1.2),
                                                 (0.5, -2.5, 0.7)])
def test_crossing_steps_span_inlet_centre_and_exit(phi, x_start, speed):
    """X_D = X_D0 + k speed h: X_D0 within one step upstream of X_a - Phi, X_D = 0 at the centre step, the last
    step the first one at or beyond 1 + 1.5 Phi."""
    h = 4.0 / 128
    centre, steps = model.crossing_steps(phi, x_start, h, speed)
    x0 = -centre * speed * h
    assert x_start - phi - speed * h < x0 <= x_start - phi + 1e-12
    end = x0 + steps * speed * h
    assert 1.0 + 1.5 * phi - 1e-12 <= end < 1.0 + 1.5 * phi + speed * h
