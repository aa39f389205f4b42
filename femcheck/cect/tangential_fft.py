"""Matrix-free tangential solver for Kalker's exact theory: the 2 x 2 block of tangential influence coefficients
applied by DC-FFT, Coulomb's law by semi-smooth Newton with each Newton system solved by right-preconditioned
flexible GMRES.

The discrete problem is the one of :mod:`femcheck.cect.exact` (same grid, same element equations, same
Alart-Curnier reformulation F(p) = p - Proj_{|q| <= g}(p - r s(p)) = 0 with the same per-element r), so both
solvers converge to the same solution; only the linear algebra differs. For C contact elements the dense path
stores and factorises a 2C x 2C matrix (O(C^3) per Newton step, C ~ 2000 at 51 x 51); here the slip operator
is never formed:

* **Block convolution** (Liu, Wang & Liu 2000, DC-FFT; as :mod:`femcheck.bem.convolution`): the slip per unit
  traction is, component by component, a linear convolution on the grid,
    shift:    u_i(x_I) = sum_J A_ij(x_I - x_J) p_j(x_J)                                  (m/Pa * Pa = m)
    rolling:  s_i(x_I) = sum_J [A_ij(x_I - x_J) - A_ij(x_I + dx - x_J)]/dx p_j(x_J)       (1/Pa * Pa = -)
  (Kalker 1990 §2.2; seed 000 eq. 19 with dq = dx: the rolling kernel is the influence-coefficient difference
  between an element and its downstream neighbour). The rolling kernel is not even, so its spectrum is complex;
  A_xy = A_yx, so the block needs three spectra. One product costs two forward and two inverse real FFTs of the
  zero-padded (2n)^2 grid.
* **Preconditioner** (the circulant idea of Vollebregt, J. Comput. Phys. 257 (2014) §4, extended to the
  tangential block and to rolling): the shift operator is u = A p with A's symbol ~ 1/|k|, so its inverse is
  approximated by the periodic (circulant) inverse of the 2 x 2 block [A_xx A_xy; A_xy A_yy], inverted
  frequency by frequency. The steady-rolling operator is s = D A p with D the upwind difference
  (D u)(x) = (u(x) - u(x + dx))/dx; D is inverted exactly by summing along x from the leading edge,
  u(x_I) = dx sum_{K >= I} s(x_K) (Kalker's Eulerian scheme integrates from the leading edge), and A by its
  circulant inverse. Measured on full-adhesion solves (a/b = 1, nu = 0.25): 28, 31, 38, 43 GMRES iterations on
  24^2, 32^2, 64^2, 128^2 grids to 1e-10 (471 unpreconditioned at 64^2).
* **Newton system**: J = I - Pi + Pi r dS/dp (dS/dp the operator above, Pi the derivative of the projection on
  the friction disc). Its right preconditioner applies the approximate inverse of r dS/dp above on the
  adhering elements; a sliding element gets the identity along the normal of its friction circle (its Newton
  row there) and its own diagonal coefficient along the tangent. The GMRES tolerance follows an inexact-Newton
  forcing sequence (Eisenstat & Walker 1996, choice 2) bounded by ``linear_rtol_max``. GMRES iterations per
  Newton step measured on a partial-slip rolling case (xi, eta, phi all set): 14 at 41^2, 25 at 129^2, 32 at
  257^2.

Units: tractions Pa, slip rolling - (slip velocity / V) or shift m, grids m.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache, partial

import numpy as np
from scipy import fft

from ..bem.convolution import DCFFT
from ..bem.halfspace import Grid
from ..errors import ConvergenceError, InputError
from .coulomb import TangentialResult, coulomb_residual, nonmonotone_step, projection_derivative
from .influence import CombinedConstants, influence



# --------------------------------------------------------------------------------------------------------------
# block convolution and its preconditioner
# --------------------------------------------------------------------------------------------------------------
def slip_kernel(component: str, tx: np.ndarray, ty: np.ndarray, g: Grid, constants: CombinedConstants,
                rolling: bool) -> np.ndarray:
    """Slip at lag (tx, ty) (m) per unit traction on one element: A_ij (m/Pa, shift) or the rolling difference
    (A_ij(t) - A_ij(t + dx))/dx (1/Pa; seed 000 eq. 19), A_ij from :func:`femcheck.cect.influence.influence`."""
    a = influence(component, tx, ty, g.dx, g.dy, constants)
    if rolling:
        a = (a - influence(component, tx + g.dx, ty, g.dx, g.dy, constants)) / g.dx
    return a


class TangentialConvolution:
    """p = (px, py) on the grid -> slip (s_x, s_y) on the grid: the 2 x 2 block of :func:`slip_kernel` applied by
    zero-padded DC-FFT (exact linear convolution). ``self_coefficients`` = (S_xx(0), S_yy(0)), the slip of an
    element per unit traction on itself."""

    def __init__(self, g: Grid, constants: CombinedConstants, rolling: bool):
        self.grid, self.rolling = g, rolling
        spectra = {}
        for c in ("xx", "xy", "yy"):
            conv = DCFFT(partial(slip_kernel, c, g=g, constants=constants, rolling=rolling), (g.nx, g.ny),
                         (g.dx, g.dy), workers=1)
            spectra[c] = conv.spectrum
            self.padded = conv.padded
        self.sxx, self.sxy, self.syy = spectra["xx"], spectra["xy"], spectra["yy"]
        self.self_coefficients = (float(slip_kernel("xx", 0.0, 0.0, g, constants, rolling)),
                                  float(slip_kernel("yy", 0.0, 0.0, g, constants, rolling)))

    def __call__(self, p: np.ndarray) -> np.ndarray:
        """(2, nx, ny) tractions (Pa) -> (2, nx, ny) slip. Pruned transforms as in DCFFT: the last axis is
        transformed on the nx unpadded rows only and each inverse is cut right after it."""
        nx, ny = self.grid.nx, self.grid.ny
        ph = fft.rfft(p, n=self.padded[1], axis=-1)
        ph = fft.fft(ph, n=self.padded[0], axis=1, overwrite_x=True)
        u = np.empty(ph.shape, dtype=np.result_type(ph, self.sxx, self.sxy))
        u[0] = self.sxx * ph[0] + self.sxy * ph[1]
        u[1] = self.sxy * ph[0] + self.syy * ph[1]
        u = fft.ifft(u, axis=1, overwrite_x=True)[:, :nx]
        return fft.irfft(u, n=self.padded[1], axis=-1)[..., :ny]


class TangentialPreconditioner:
    """Approximate inverse of :class:`TangentialConvolution`: (rolling only) the exact inverse of the upwind
    difference, u_I = dx sum_{K >= I} s_K along x from the leading edge (+x), then the periodic 2 x 2 block
    inverse of A on the unpadded grid, [A_xx A_xy; A_xy A_yy]^-1 per frequency (A_xx, A_yy even and A_xy odd in
    both lags: a real symmetric symbol, positive definite for -1 < nu < 1/2 and at nu = 1/2)."""

    def __init__(self, g: Grid, constants: CombinedConstants, rolling: bool):
        self.grid, self.rolling = g, rolling
        lags = [np.where(np.arange(n) <= n // 2, np.arange(n), np.arange(n) - n) * h
                for n, h in ((g.nx, g.dx), (g.ny, g.dy))]
        X, Y = np.meshgrid(*lags, indexing="ij", sparse=True)
        k = {c: fft.rfft2(influence(c, X, Y, g.dx, g.dy, constants)).real for c in ("xx", "xy", "yy")}
        det = k["xx"] * k["yy"] - k["xy"] ** 2
        if det.min() <= 0 or k["xx"].min() <= 0:
            raise ValueError("the periodic tangential symbol is not positive definite: not a preconditioner")
        self.ixx, self.ixy, self.iyy = k["yy"] / det, -k["xy"] / det, k["xx"] / det

    def __call__(self, s: np.ndarray) -> np.ndarray:
        """(2, nx, ny) slip -> (2, nx, ny) traction (Pa)."""
        g = self.grid
        if self.rolling:
            s = g.dx * np.cumsum(s[:, ::-1], axis=1)[:, ::-1]
        sh = fft.rfft2(s)
        out = np.stack([self.ixx * sh[0] + self.ixy * sh[1], self.ixy * sh[0] + self.iyy * sh[1]])
        return fft.irfft2(out, s=(g.nx, g.ny))


@lru_cache(maxsize=8)
def tangential_operators(g: Grid, constants: CombinedConstants,
                         rolling: bool) -> tuple[TangentialConvolution, TangentialPreconditioner]:
    """Operator and preconditioner of a grid, built once (kernel spectra) and reused across solves."""
    return TangentialConvolution(g, constants, rolling), TangentialPreconditioner(g, constants, rolling)


# --------------------------------------------------------------------------------------------------------------
# flexible GMRES
# --------------------------------------------------------------------------------------------------------------
@dataclass
class GMRESResult:
    """``x`` solution, ``iterations`` (matrix-vector products), ``residual`` |b - A x| / |b| (true residual,
    recomputed at every restart and at the end), ``converged``."""

    x: np.ndarray
    iterations: int
    residual: float
    converged: bool


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    """a . b of two vectors without BLAS: OpenBLAS threads its level-1 routines, and on the shared 2-core
    machine under load one 12 000-long ddot took 0.2-11 ms instead of 5 us (81 x 161 conformal solve: 16 s
    instead of 1.4 s, nearly all of it in the Arnoldi dot products); numpy's einsum loop does not thread."""
    return float(np.einsum("i,i->", a, b))


def fgmres(matvec, b: np.ndarray, precondition, rtol: float = 1e-10, restart: int = 60,
           max_iter: int = 1000) -> GMRESResult:
    """Right-preconditioned restarted GMRES (Saad 1993, FGMRES): minimises |b - A x| over x = x0 + Z y with
    Z_j = M(v_j) stored, so the preconditioner may vary (here it does not, but the residual minimised is the
    true, unpreconditioned one). Modified Gram-Schmidt Arnoldi with Givens rotations."""
    n = b.size
    x = np.zeros(n)
    bnorm = np.sqrt(_dot(b, b))
    if bnorm == 0.0:
        return GMRESResult(x, 0, 0.0, True)
    r = b.copy()
    it = 0
    while True:
        beta = np.sqrt(_dot(r, r))
        if beta <= rtol * bnorm or it >= max_iter:
            return GMRESResult(x, it, beta / bnorm, beta <= rtol * bnorm)
        m = min(restart, max_iter - it)
        V = np.empty((m + 1, n))
        Z = np.empty((m, n))
        H = np.zeros((m + 1, m))
        cs, sn = np.zeros(m), np.zeros(m)
        gvec = np.zeros(m + 1)
        V[0] = r / beta
        gvec[0] = beta
        k = 0
        for j in range(m):
            it += 1
            Z[j] = precondition(V[j])
            w = matvec(Z[j])
            for i in range(j + 1):
                H[i, j] = _dot(w, V[i])
                w -= H[i, j] * V[i]
            H[j + 1, j] = hnext = np.sqrt(_dot(w, w))
            if hnext > 0:
                V[j + 1] = w / hnext
            for i in range(j):
                t = cs[i] * H[i, j] + sn[i] * H[i + 1, j]
                H[i + 1, j] = -sn[i] * H[i, j] + cs[i] * H[i + 1, j]
                H[i, j] = t
            d = np.hypot(H[j, j], H[j + 1, j])
            cs[j], sn[j] = (H[j, j] / d, H[j + 1, j] / d) if d > 0 else (1.0, 0.0)
            H[j, j], H[j + 1, j] = d, 0.0
            gvec[j + 1] = -sn[j] * gvec[j]
            gvec[j] = cs[j] * gvec[j]
            k = j + 1
            if abs(gvec[j + 1]) <= rtol * bnorm or hnext == 0.0:      # converged or happy breakdown
                break
        diag = np.abs(np.diag(H[:k, :k]))
        k = int(np.argmax(diag == 0)) if np.any(diag == 0) else k        # breakdown: keep the regular part
        if k == 0:
            return GMRESResult(x, it, beta / bnorm, False)
        y = np.linalg.solve(np.triu(H[:k, :k]), gvec[:k])
        x = x + np.einsum("i,ij->j", y, Z[:k])
        r = b - matvec(x)


# --------------------------------------------------------------------------------------------------------------
# full adhesion (linear) and Coulomb friction (semi-smooth Newton)
# --------------------------------------------------------------------------------------------------------------
class _Restricted:
    """Scatter/gather between the (2, C) contact-element vectors and (2, nx, ny) grid arrays."""

    def __init__(self, g: Grid, cells: tuple[np.ndarray, np.ndarray]):
        self.shape = (g.nx, g.ny)
        self.flat = np.ravel_multi_index(cells, self.shape)
        self.C = self.flat.size

    def scatter(self, v: np.ndarray) -> np.ndarray:
        out = np.zeros((2, self.shape[0] * self.shape[1]))
        out[:, self.flat] = v.reshape(2, self.C)
        return out.reshape(2, *self.shape)

    def gather(self, a: np.ndarray) -> np.ndarray:
        return a.reshape(2, -1)[:, self.flat]


def solve_adhesion(g: Grid, cells: tuple[np.ndarray, np.ndarray], constants: CombinedConstants,
                   w: np.ndarray, rolling: bool = True, rtol: float = 1e-11,
                   max_iter: int = 2000) -> tuple[np.ndarray, GMRESResult]:
    """Full adhesion: tractions p (2, C) (Pa) with w + S p = 0 on the C elements ``cells`` (S the slip operator of
    :class:`TangentialConvolution`, w (2, C) the rigid slip). ``w`` may be (k, 2, C) for k right-hand sides
    (then p is (k, 2, C) and the GMRES result is the last one). Kalker's linear theory solves exactly this
    (Kalker 1990 §3.2). Raises ConvergenceError if GMRES misses ``rtol``."""
    op, prec = tangential_operators(g, constants, rolling)
    R = _Restricted(g, cells)
    W = np.asarray(w, dtype=float)
    many = W.ndim == 3
    out, res = [], None
    for wk in (W if many else W[None]):
        res = fgmres(lambda v: R.gather(op(R.scatter(v))).ravel(), -wk.ravel(),
                     lambda v: R.gather(prec(R.scatter(v))).ravel(), rtol=rtol, max_iter=max_iter)
        if not res.converged:
            raise ConvergenceError("full-adhesion GMRES", res.iterations, res.residual, rtol)
        out.append(res.x.reshape(2, R.C))
    return (np.stack(out) if many else out[0]), res


def solve_tangential_fft(g: Grid, cells: tuple[np.ndarray, np.ndarray], constants: CombinedConstants,
                         w: np.ndarray, bound: np.ndarray, rolling: bool, load: np.ndarray | None = None,
                         tol: float = 1e-10, max_iter: int = 200, p0: np.ndarray | None = None,
                         shift0: np.ndarray | None = None, solver: str = "tangential",
                         linear_rtol_max: float = 1e-2, linear_max_iter: int = 1500,
                         kappa: np.ndarray | None = None, operators: tuple | None = None):
    """Coulomb friction on the C contact elements ``cells`` of grid ``g`` with slip s = w + S p (+ delta for a
    shift problem); the matrix-free counterpart of :func:`femcheck.cect.exact.solve_tangential`, same equations
    and the same result object (:class:`femcheck.cect.coulomb.TangentialResult`, with ``linear_iterations`` the
    total GMRES iterations).

    ``w`` (2, C) slip at zero traction (rolling: (xi - phi y, eta + phi x) plus the pressure coupling, -; shift:
    m), ``bound`` (C,) traction bound g = mu pn (Pa), ``rolling`` selects the operator (steady rolling or shift),
    ``load`` (2,) the resultant on body 1 (N) for a shift problem, whose rigid shift delta (m) is then an
    unknown. ``p0``, ``shift0`` warm start. Newton stops when max|F| / max g < ``tol``; ConvergenceError after
    ``max_iter`` Newton steps or when a Newton system cannot be solved by GMRES to its forcing tolerance.

    ``kappa`` (C,) optional row scaling of the slip operator, s = w + kappa S p: the variable rolling step
    dq_I/dq0 = V(s_I)/V_ref of seed 000 eq 21 (conformal contacts, :mod:`femcheck.cect.conformal`); the
    preconditioner of the adhesion rows becomes S^-1 diag(1/kappa). None (default) is the planar solver
    unchanged. ``operators`` (op, prec) replaces the half-space slip operator and its preconditioner (e.g. the
    angle-corrected coefficients of :mod:`femcheck.cect.influence_conformal`; op needs ``self_coefficients``).
    """
    op, prec = tangential_operators(g, constants, rolling) if operators is None else operators
    R = _Restricted(g, cells)
    C = R.C
    gbound = np.asarray(bound, dtype=float)
    gmax = float(gbound.max()) if C else 0.0
    if C == 0 or gmax <= 0:
        raise InputError("friction.mu", "no element carries a friction bound (mu pn = 0 everywhere)")
    w = np.asarray(w, dtype=float).reshape(2, C)
    shift_problem = load is not None
    # one r for every element (Pa per unit slip): the operator is translation invariant, so the dense path's
    # 1/mean(diag) is the same number for all elements
    r = 1.0 / (0.5 * (op.self_coefficients[0] + op.self_coefficients[1]))
    cell_area = g.cell_area
    n = 2 * C + (2 if shift_problem else 0)

    if kappa is None:
        def apply_s(p: np.ndarray) -> np.ndarray:
            return R.gather(op(R.scatter(p)))
        kap = 1.0
    else:
        kap = np.asarray(kappa, dtype=float).reshape(C)

        def apply_s(p: np.ndarray) -> np.ndarray:
            return kap * R.gather(op(R.scatter(p)))

    def slip(x: np.ndarray) -> np.ndarray:
        s = w + apply_s(x[:2 * C])
        if shift_problem:
            s = s + x[2 * C:, None] / r          # the shift is carried as r delta (Pa), as in the dense path
        return s

    def residual_vec(x: np.ndarray):
        return coulomb_residual(x[:2 * C].reshape(2, C), slip(x), r, gbound, load, cell_area)

    x = np.zeros(n)
    if p0 is not None:
        x[:2 * C] = np.asarray(p0, dtype=float).ravel()
        if shift_problem and shift0 is not None:
            x[2 * C:] = np.asarray(shift0, dtype=float) * r
    F, aux = residual_vec(x)
    merits = [float(F @ F)]
    res = float(np.abs(F).max()) / gmax
    linear_iterations = 0
    fnorm_prev = None
    eta_k = linear_rtol_max
    for it in range(1, max_iter + 1):
        if res < tol:
            p = x[:2 * C].reshape(2, C)
            stick = aux[2]
            return TangentialResult(p.copy(), np.where(stick, 0.0, aux[3]), stick,
                                    x[2 * C:] / r if shift_problem else None, it - 1, res,
                                    linear_iterations=linear_iterations)
        z, nz, inside, _ = aux
        pxx, pyy, pxy, ex, ey = projection_derivative(z, nz, inside, gbound)
        fac = gbound / np.where(nz > 0, nz, 1.0)          # g/|z|, used on sliding elements only
        sliding = ~inside
        nx_, ny_ = np.where(sliding, ex, 0.0), np.where(sliding, ey, 0.0)
        tx_, ty_ = -ny_, nx_

        def jac(v: np.ndarray) -> np.ndarray:
            vp = v[:2 * C].reshape(2, C)
            q = r * apply_s(vp)
            if shift_problem:
                q = q + v[2 * C:, None]
            d = vp - q
            # J v = v_p - Pi (v_p - r S v_p - r dS/ddelta v_delta)
            out = np.stack([vp[0] - (pxx * d[0] + pxy * d[1]), vp[1] - (pxy * d[0] + pyy * d[1])]).ravel()
            if shift_problem:
                out = np.concatenate([out, vp.sum(axis=1) / C])
            return out

        # local tangential Newton coefficient of a sliding element: (1 - f) + f r S_tt(0), f = g/|z|
        local = np.where(sliding, (1.0 - fac) + fac * r * kap * (tx_ ** 2 * op.self_coefficients[0]
                                                                 + ty_ ** 2 * op.self_coefficients[1]), 1.0)

        def precondition(v: np.ndarray) -> np.ndarray:
            vp = v[:2 * C].reshape(2, C)
            # adhesion rows r S dq = v: the approximate inverse of S applied to the adhesion residual alone
            dq = R.gather(prec(R.scatter(np.where(sliding, 0.0, vp) / (r * kap))))
            # sliding rows: identity along the normal n of the friction circle, the element's own coefficient
            # along the tangent t (coupling to the other elements neglected). Feeding sliding residuals to the
            # adhesion inverse instead took 2.4x more GMRES iterations at 129^2 under spin
            vn = nx_ * vp[0] + ny_ * vp[1]
            vt = (tx_ * vp[0] + ty_ * vp[1]) / local
            dq = np.where(sliding, np.stack([nx_ * vn + tx_ * vt, ny_ * vn + ty_ * vt]), dq)
            out = dq.ravel()
            if shift_problem:
                out = np.concatenate([out, v[2 * C:]])
            return out

        fnorm = float(np.sqrt(F @ F))
        if fnorm_prev is not None:
            # Eisenstat-Walker choice 2 (gamma = 0.9, alpha = 2), safeguarded
            eta_k = min(linear_rtol_max, max(0.9 * (fnorm / fnorm_prev) ** 2, 0.9 * eta_k ** 2, 1e-10))
        fnorm_prev = fnorm
        lin = fgmres(jac, -F, precondition, rtol=eta_k, max_iter=linear_max_iter)
        linear_iterations += lin.iterations
        if not lin.converged and lin.residual > 0.5:
            raise ConvergenceError(f"{solver} Newton-GMRES", it, res, tol,
                                   f"GMRES reached only {lin.residual:.2e} of its tolerance {eta_k:.1e} "
                                   f"after {lin.iterations} iterations")
        dx = lin.x
        if not np.all(np.isfinite(dx)):
            raise ConvergenceError(f"{solver} Newton-GMRES", it, res, tol, "non-finite Newton step")
        x, F, aux, m_new = nonmonotone_step(x, dx, residual_vec, merits, first=it == 1)
        merits.append(m_new)
        res = float(np.abs(F).max()) / gmax
    raise ConvergenceError(f"{solver} Newton-GMRES", max_iter, res, tol)
