"""The EHL model of the ``ehl_contact`` kind: physical or Moes inputs -> dimensionless problem -> steady smooth
solution (with grid refinement and a convergence certificate) and, with an indent, the transient crossing up to
the centred position (spec §A.5: the indent enters at the inlet, X_D0 = X_a - Phi, and the result is taken at
X_D = 0). Outputs in SI; the pressure field on the grid and per kept time step for the fatigue-life model."""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ConvergenceError
from ..geometry.profiles import indent_height
from . import formulas, groups, outputs, steady, transient
from .film import Indent
from .lubricant import Lubricant
from .multigrid import Problem


@dataclass(frozen=True)
class Setup:
    """Everything a run needs: groups (SI <-> dimensionless), the dimensionless problem, the grid."""

    g: groups.Groups
    prob: Problem
    n: int
    levels: int


def h0_factor(M: float, L: float) -> float:
    """Venner's H0 relaxation factor for W-cycles: 0.1, x 0.25 when L > 10 or M > 1000."""
    return 0.1 * (0.25 if (L > 10 or M > 1000) else 1.0)


def make_setup(g: groups.Groups, viscosity_law: str, density_law: str, grid: int, levels: int | None,
               x_start: float, x_end: float, indent: Indent | None = None) -> Setup:
    n = grid - 1
    if levels is None:
        levels = int(np.log2(n // 16)) + 1        # coarsest grid: 16 intervals
    lub = Lubricant(viscosity_law, density_law, g.eta0, g.alpha, g.p_hertz)
    # first guess of H0: the Nijenbanning central film minus the Hertzian central deflection
    hc = formulas.moes_central(g.M, g.L, g.Rx / g.Ry) * np.sqrt(g.U_moes) * g.Rx**2 / g.b**2
    prob = Problem(lub, g.lam, g.c_el, g.Rx / g.Ry, g.kappa, x_start, x_end, indent, h0_factor(g.M, g.L), hc)
    return Setup(g, prob, n, levels)


def check_film(sol: steady.Solution, what: str) -> None:
    """A converged discrete solution with a negative film in the pressurised zone is under-resolved, not a film:
    refuse it rather than report it."""
    pos = sol.P > 0
    if pos.any() and sol.H[pos].min() <= 0:
        err = ConvergenceError(what, sol.cycles, sol.residual, 0.0)
        # the iteration met its tolerance: say that, not "did not converge", and why the result is refused
        err.args = (f"{what} refused: it converged ({sol.cycles} cycles, residual {sol.residual:.1e}) to a "
                    f"negative film H_min = {sol.H[pos].min():.3g} in the pressurised zone: the grid does not "
                    "resolve this (M, L); use a finer numerics.grid",)
        raise err


def shoulder_height(diameter: float, depth: float, decay: float) -> float:
    """Height of the rim around the hole of seed 004 eq 2.16, max_r R(r) (>= 0; same units as ``depth``): about
    0.0845 D at K = 4, at r = 0.65 Phi."""
    r = np.linspace(0.0, 2.0 * diameter, 4001)
    return max(float(indent_height(r, diameter, depth, decay).max()), 0.0)


def collapse_hint(indent_keys: dict[str, float], H_min_smooth: float) -> str:
    """What a failed crossing should try when the indent's shoulders are taller than the smooth film's minimum
    (both in units of b^2/Rx). Measured (benchmarks/results/ehl_robustness.md): ehl-indent's indent (shoulders
    0.021) at ratios 5.8-6.5 was refused for a negative film on 129^2 and 257^2 and converged with a positive film
    on 513^2 ((1200, 3), (1000, 2)); at ratio 1.9 ((1200, 19)) it converges on 257^2 with the film minimum 0.0062
    over the shoulder. No measured case closed the film; a film that does close (mixed lubrication) is outside this
    full-film model. "" when the ratio is below 1."""
    phi = indent_keys["diameter"]
    sh = shoulder_height(phi, indent_keys["slope"] * phi, indent_keys["decay"])
    ratio = sh / H_min_smooth
    if ratio < 1.0:
        return ""
    return (f"the indent's shoulders rise {sh:.3g} b^2/Rx, {ratio:.1f} times the smooth film's minimum "
            f"{H_min_smooth:.3g}: resolving them needs a finer numerics.grid (513^2 at 6.5 times); if that fails "
            "too the film may close over them (mixed lubrication, outside this full-film model)")


def film_quantities(s: Setup, sol: steady.Solution) -> dict[str, float]:
    g = s.g
    m = outputs.film_measures(sol.x, sol.y, sol.P, sol.H)
    return {"h_central": g.film_to_m(m["H_central"]), "h_min": g.film_to_m(m["H_min"]),
            "p_max": m["P_max"] * g.p_hertz, "H_central_moes": g.moes_film(m["H_central"]),
            "H_min_moes": g.moes_film(m["H_min"]), "load_error": sol.load_error,
            "spike_x": m["X_spike"] * g.b}


def solve_smooth(s: Setup, tol: float, load_tol: float):
    prob = dataclasses.replace(s.prob, indent=None)
    sol, mg = steady.solve(prob, s.n, s.levels, tol=tol, load_tol=load_tol)
    check_film(sol, f"EHL steady ({s.n + 1}^2 nodes)")
    return sol, mg


def snapshot_steps(steps: int, kept: int = 16) -> set[int]:
    every = max(1, int(np.ceil(steps / kept)))
    return set(range(every, steps + 1, every)) | {steps}


def crossing(s: Setup, indent_keys: dict[str, float], slide_roll: float, tol: float, load_tol: float,
             progress=None, snapshots: int = 16) -> dict[str, Any]:
    """Smooth steady solution, then the indent (Phi, D/Phi, K) enters at the inlet and is marched to X_D = 0.

    Returns the smooth solution, the history (per step: T, X_D, dP amplitudes of :func:`outputs.additional_pressure`,
    load error, cycles) and the kept pressure snapshots (``snapshots`` evenly spaced steps, the last at X_D = 0)."""
    t0 = time.perf_counter()
    phi, slope, K = indent_keys["diameter"], indent_keys["slope"], indent_keys["decay"]
    smooth, mg = solve_smooth(s, tol, load_tol)
    h = mg.fine.h
    speed = 1.0 + slide_roll
    steps = int(np.ceil((phi - s.prob.x_start) / (speed * h)))
    ind = Indent(phi, slope * phi, K, x0=-steps * speed * h, speed_ratio=speed)
    mg.prob = dataclasses.replace(s.prob, indent=ind)
    mg.set_time(0.0)
    transient.start(mg)
    amps: dict[str, list[float]] = {k: [] for k in ("front", "rear", "lateral", "centre", "amplitude",
                                                  "disc_max")}
    kept = snapshot_steps(steps, snapshots)
    lv = mg.fine

    def on_step(msg):
        a = outputs.additional_pressure(lv.film.x, lv.film.y, lv.P - smooth.P, ind.centre(mg.T), 0.0, phi)
        for k in amps:
            amps[k].append(a[k])
        if progress:
            progress(msg)

    try:
        hist = transient.march(mg, steps, tol=tol, load_tol=load_tol, keep=lambda k, T: k in kept,
                               progress=on_step, base=smooth.P)
        final = hist.snapshots[-1]
        check_film(final, f"EHL transient ({s.n + 1}^2 nodes) at X_D = 0")
    except ConvergenceError as err:
        H_min = outputs.film_measures(smooth.x, smooth.y, smooth.P, smooth.H)["H_min"]
        if hint := collapse_hint(indent_keys, H_min):
            err.args = (f"{err.args[0]}; {hint}",)
        raise
    return {"smooth": smooth, "history": hist, "amplitudes": amps, "indent": ind, "final": final, "steps": steps,
            "time_s": time.perf_counter() - t0}
