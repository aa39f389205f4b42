"""How an EHL solve reports that it failed: the numbers it stopped at, the tolerances, and where (grid, time step,
indent position). Every failure is a :class:`~femcheck.errors.ConvergenceError` whose ``iterations`` and
``residual`` are the cycles run and the mean scaled residual it stopped at (never a placeholder), with one of three
messages:

- not converged: the cycle cap was reached; the message gives the mean scaled residual and the load error it
  stopped at, each against its tolerance (and says which of the two was met);
- diverged: the pressure became non-finite; the message gives the cycle and the stage where that happened and the
  last finite residual before it (``residual`` is that last finite value, NaN when there was none);
- :class:`UnderResolvedFilm`: the iteration met both tolerances, but the film is negative in the pressurised zone
  (the grid does not resolve this (M, L)); the solution is refused, not reported.
"""
from __future__ import annotations

import numpy as np

from ..errors import ConvergenceError


def _with_message(err: ConvergenceError, message: str) -> ConvergenceError:
    # ConvergenceError's own message always reads "residual r > tolerance t", which is false for a load-error
    # failure and meaningless for a divergence: the EHL failures state what happened instead
    err.args = (message,)
    return err


def not_converged(where: str, cycles: int, residual: float, tol: float, load_error: float, load_tol: float,
                  hint: str = "") -> ConvergenceError:
    """The cycle cap ``cycles`` was reached at mean scaled residual ``residual`` and relative load error
    ``load_error`` (kept on the error as ``load_error`` and ``load_tolerance`` too)."""
    def verdict(name, value, limit):
        return f"{name} {value:.3e} {'<=' if value <= limit else '>'} tolerance {limit:.1e}"

    met = [n for n, v, t in (("residual", residual, tol), ("load error", load_error, load_tol)) if v <= t]
    msg = (f"{where} did not converge in {cycles} cycles: {verdict('mean scaled residual', residual, tol)}, "
           f"{verdict('load error', load_error, load_tol)}" + (f" (the {met[0]} criterion is met)" if met else ""))
    err = _with_message(ConvergenceError(where, cycles, residual, tol), msg + (f"; {hint}" if hint else ""))
    err.load_error, err.load_tolerance = load_error, load_tol
    return err


def diverged(where: str, cycles: int, stage: str, last_residual: float | None, last_stage: str,
             tol: float) -> ConvergenceError:
    """The pressure became non-finite in ``stage`` (after ``cycles`` cycles on the finest grid); ``last_residual``
    is the last finite mean scaled residual, measured at ``last_stage`` (None: there was none)."""
    last = (f"last finite mean scaled residual {last_residual:.3e} ({last_stage}), tolerance {tol:.1e}"
            if last_residual is not None and np.isfinite(last_residual) else
            f"no finite residual before it, tolerance {tol:.1e}")
    msg = f"{where} diverged: the pressure became non-finite {stage}; {last}"
    res = float(last_residual) if last_residual is not None else float("nan")
    return _with_message(ConvergenceError(where, cycles, res, tol), msg)


class UnderResolvedFilm(ConvergenceError):
    """A converged discrete solution with a negative film ``h_min`` in the pressurised zone at ``where``: the grid
    does not resolve the contact at this (M, L). Refused rather than reported; a coarse level of a grid certificate
    that is refused this way can be left out of the certificate (:mod:`femcheck.ehl.adapter`)."""

    def __init__(self, where: str, cycles: int, residual: float, tol: float, h_min: float):
        super().__init__(where, cycles, residual, tol)
        self.h_min = h_min
        self.args = (f"{where} refused: it converged ({cycles} cycles, mean scaled residual {residual:.1e} <= "
                     f"tolerance {tol:.1e}) to a negative film H_min = {h_min:.3g} in the pressurised zone: the grid "
                     "does not resolve this (M, L); use a finer numerics.grid",)


def film_minimum(P: np.ndarray, H: np.ndarray) -> float:
    """Smallest film over the pressurised nodes (NaN when none is pressurised)."""
    pos = P > 0
    return float(H[pos].min()) if pos.any() else float("nan")


def check_film(P: np.ndarray, H: np.ndarray, where: str, cycles: int, residual: float, tol: float) -> float:
    """Raise :class:`UnderResolvedFilm` when the film is negative (or closed, H <= 0) where P > 0; else return the
    film minimum there."""
    h_min = film_minimum(P, H)
    if h_min <= 0:
        raise UnderResolvedFilm(where, cycles, residual, tol, h_min)
    return h_min
