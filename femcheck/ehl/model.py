"""The EHL model of the ``ehl_contact`` kind: physical or Moes inputs -> dimensionless problem -> steady smooth
solution (with grid refinement and a convergence certificate) and, with an indent, the full transient crossing:
the indent enters at the inlet (X_D0 = X_a - Phi), passes the centre, where the additional pressures are taken
(X_D = 0, spec §A.5), and leaves through the exit (X_D = 1 + 1.5 Phi, :func:`crossing_steps`). Outputs in SI; the pressure field on the grid
and per kept time step for the fatigue-life model."""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ConvergenceError
from ..geometry.profiles import indent_height
from . import failures, formulas, groups, outputs, steady, transient
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


def default_y_half(g: groups.Groups, x_start: float, x_end: float) -> float | None:
    """Half-width across (Y, in b) of the domain: for a circle None (the square [x_start, x_end] x +-(x_end -
    x_start)/2 of Venner & Lubrecht and seed 004 §2.6.4); for an ellipse the same half-width counted in the
    transverse semi-axis a = b/kappa, (x_end - x_start)/(2 kappa), so that the lateral margin around the contact
    is the circle's in units of a. Measured (M = 100, L = 10, Barus, 129 nodes along [-4.5, 1.5]): at
    Ry/Rx = 4 (a = 2.50 b) the square's +-3 b = 1.20 a gave H_min 5.8 % and H_c 0.5 % below the values with
    +-2.55 a (side lobes cut by the P = 0 edge); +-2.10 a was within 0.15 % (H_min) and 0.03 % (H_c)."""
    if g.Ry <= g.Rx:
        return None
    return 0.5 * (x_end - x_start) / g.kappa


def make_setup(g: groups.Groups, viscosity_law: str, density_law: str, grid: int, levels: int | None,
               x_start: float, x_end: float, indent: Indent | None = None, y_half: float | None = None) -> Setup:
    """The dimensionless problem of ``g`` on ``grid`` nodes along X over [x_start, x_end] (in b) and across over
    +-``y_half`` (in b; None: :func:`default_y_half`)."""
    n = grid - 1
    if levels is None:
        levels = int(np.log2(n // 16)) + 1        # coarsest grid: 16 intervals
    lub = Lubricant(viscosity_law, density_law, g.eta0, g.alpha, g.p_hertz)
    # first guess of H0: the Nijenbanning central film minus the Hertzian central deflection
    hc = formulas.moes_central(g.M, g.L, g.Rx / g.Ry) * np.sqrt(g.U_moes) * g.Rx**2 / g.b**2
    if y_half is None:
        y_half = default_y_half(g, x_start, x_end)
    prob = Problem(lub, g.lam, g.c_el, g.Rx / g.Ry, g.kappa, x_start, x_end, indent, h0_factor(g.M, g.L), hc,
                   y_half)
    return Setup(g, prob, n, levels)


def check_film(sol: steady.Solution, what: str, tol: float = 0.0) -> None:
    """A converged discrete solution with a negative film in the pressurised zone is under-resolved, not a film:
    refuse it (:class:`~femcheck.ehl.failures.UnderResolvedFilm`) rather than report it."""
    failures.check_film(sol.P, sol.H, what, sol.cycles, sol.residual, tol)


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
    check_film(sol, f"EHL steady ({s.n + 1}^2 nodes)", tol)
    return sol, mg


def snapshot_steps(steps: int, kept: int = 16, centre: int | None = None) -> set[int]:
    """About ``kept`` evenly spaced steps of 1 .. ``steps``, the last one and the centred one (``centre``)."""
    every = max(1, int(np.ceil(steps / kept)))
    return set(range(every, steps + 1, every)) | {steps} | ({centre} if centre else set())


EXIT_DISC = 1.5   # the crossing ends when the indent's disc r <= 1.5 Phi has left the contact |X| <= 1


def crossing_steps(phi: float, x_start: float, h: float, speed: float) -> tuple[int, int]:
    """(steps from the inlet to the centre, steps in all) of a crossing with time step h and X_D moving by
    ``speed`` h per step. It starts with the indent centre Phi upstream of the inlet X_a (X_D0 = X_a - Phi, rounded
    to whole steps so that X_D = 0 is a step) and ends at X_D >= 1 + 1.5 Phi, when the disc r <= 1.5 Phi over which
    the additional pressure is read (:func:`outputs.additional_pressure`; eq 2.16's height there is 1.2e-4 of the
    depth at K = 4) has left the Hertz contact |X| <= 1. Measured on ehl-indent (M = 400, L = 5, Phi = 0.5, 129^2):
    max |P - P_smooth| = 0.070 p_H at X_D = 1 + Phi (on the outlet, X = 0.97: the indent's tail still meets the
    outlet constriction), 0.0019 p_H at 1 + 1.5 Phi, 8e-4 p_H at 3 b."""
    to_centre = int(np.ceil((phi - x_start) / (speed * h) - 1e-9))
    out = int(np.ceil((1.0 + EXIT_DISC * phi) / (speed * h) - 1e-9))
    return to_centre, to_centre + out


def crossing(s: Setup, indent_keys: dict[str, float], slide_roll: float, tol: float, load_tol: float,
             progress=None, snapshots: int = 16) -> dict[str, Any]:
    """Smooth steady solution, then the indent (Phi, D/Phi, K) enters at the inlet, is marched through the centre
    and out through the exit (:func:`crossing_steps`). Every step's film is checked (negative where P > 0:
    refused, naming the step and the indent position).

    Returns the smooth solution, the history (per step: T, X_D, dP amplitudes of :func:`outputs.additional_pressure`,
    load error, cycles, film minimum), the step of the centred indent ``centre_step`` (1-based) and its solution
    ``centred``, the last step's solution ``final`` and the kept pressure snapshots (``snapshots`` evenly spaced
    steps over the whole crossing, plus the centred and the last step)."""
    t0 = time.perf_counter()
    phi, slope, K = indent_keys["diameter"], indent_keys["slope"], indent_keys["decay"]
    smooth, mg = solve_smooth(s, tol, load_tol)
    h = mg.fine.h
    speed = 1.0 + slide_roll
    centre, steps = crossing_steps(phi, s.prob.x_start, h, speed)
    ind = Indent(phi, slope * phi, K, x0=-centre * speed * h, speed_ratio=speed)
    mg.prob = dataclasses.replace(s.prob, indent=ind)
    mg.set_time(0.0)
    transient.start(mg)
    amps: dict[str, list[float]] = {k: [] for k in ("front", "rear", "lateral", "centre", "amplitude",
                                                  "disc_max")}
    kept = snapshot_steps(steps, snapshots, centre)
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
    except ConvergenceError as err:
        H_min = outputs.film_measures(smooth.x, smooth.y, smooth.P, smooth.H)["H_min"]
        if hint := collapse_hint(indent_keys, H_min):
            err.args = (f"{err.args[0]}; {hint}",)
        raise
    centred = hist.snapshots[hist.kept_steps.index(centre)]
    return {"smooth": smooth, "history": hist, "amplitudes": amps, "indent": ind, "centred": centred,
            "centre_step": centre, "final": hist.snapshots[-1], "steps": steps,
            "time_s": time.perf_counter() - t0}
