"""Line relaxation of the EHL Reynolds equation (seed 004 §2.6.2 eqs 2.39-2.44, App. A.7-A.13 cleaned in the
spec §A.5; Venner & Lubrecht 2000 ch. 17).

Lines run along X, the direction of the strong coupling. Per node the row type follows the largest face
coefficient xi = max eps_face/h^2:
- xi > 0.3 (inlet, outlet: Poiseuille-dominated) or a node whose 5-point star is not pressurised: a
  Gauss-Seidel row, P <- P + omega delta; where xi > 10 omega = 0.4; where xi <= 10 omega = 0.4 min(1, sqrt(h/h_ref))
  steady and omega_T = min(0.4, 0.15 sqrt(h/h_ref)) in a transient (h the level's mesh size, h_ref = 1/64; below);
- otherwise (high-pressure zone, where the film is almost rigid in P): a distributive Jacobi row, P_ij += w delta
  and each of the four neighbours -= w delta/4, which makes the change nearly film-neutral; w = 0.3
  min(1, sqrt(h/h_ref)) steady, 0.3 in a transient.
The line matrix is the derivative of Q - W with respect to the line's unknowns, with the elastic film coupling
of the six nearest line points (i-3 ... i+2) through the cell kernel K_{m,0} (Gauss-Seidel rows) or the
distributed kernel dK_m = K_{m,0} - (K_{m+1,0} + K_{|m-1|,0} + 2 K_{m,1})/4 (Jacobi rows), and the
compressibility: r = rho H changes with P through rho too, by H drho/dP at the points i, i-1, i-2 of the wedge
and time terms (a distributive node k moving P_{k+-1} by -delta_k/4 along the line; transient only, below).
Rows whose points i-2 ... i+2 are not all
pressurised keep the diagonal only (cavitation boundary). Cavitation: P >= 0 after every update (Reynolds /
Swift-Stieber condition by complementarity).

Why the transient Gauss-Seidel rows are under-relaxed more (measured). In the steady equation the elastic
film enters only through the wedge d(rho H)/dX: the kernel is differenced along the line, its smooth far field
cancels, and the six line points of the line matrix carry the coupling. With the NU2 time term (time step = mesh
size; the h > hT branch on the coarse grids) the new time level enters un-differenced, (1.5/hT) rho H: a first-kind
integral operator whose far field (K_{m,l} ~ h/sqrt(m^2 + l^2)) the line matrix does not see. A zebra colour
updates all its lines at once with the film of the others frozen, so for an error smooth along the lines the
same-colour lines and the far part of the own line add film changes the line solve did not count: the Gauss-Seidel
row over-corrects by a factor that grows as the grid is refined, and diverges once omega times it exceeds 2.
Measured with fine-grid relaxation alone on the transient operator (smooth steady start perturbed by 1e-4, 12
sweeps, domain [-2.5, 1.5] b): with omega = 0.4 the mean scaled residual grows x136 (M = 20, L = 8, 129^2), x276 (M
= 100, L = 3, 129^2), x1.3e4 (M = 50, L = 8, 257^2), x5.0e3 (M = 100, L = 3, 257^2); the growing error is smooth
along X, in the contact, on Gauss-Seidel rows with xi = 0.27-3.6. The critical omega falls with the mesh size: >
0.4 on 65^2, about 0.3 on 129^2, 0.22-0.25 on 257^2 (0.25: still x5.2 and x1.7 at M = 100, L = 3 and M = 50, L =
8), i.e. roughly as sqrt(h); omega_T keeps a factor of about 1.4-1.5 below it (0.30, 0.21, 0.15; 0.11 on 513^2 by
the same trend; 513^2 crossings at M = 1200, L = 3 and M = 1000, L = 2 converged with it). It is applied per level
by the level's mesh size (the coarse grids, stable at 0.4, keep about it) and only to rows with xi <= 10 (3 times
the largest xi of a growing row): the Poiseuille-dominated inlet rows (xi up to 1e6) are stable at 0.4:
under-relaxing them too nearly doubled the W-cycles per time step (8.9 instead of 4.8 at M = 100, L = 8, Phi = 0.5,
129^2), and under-relaxing every level by the fine time step stalled them (40 cycles without reaching 1e-7 at step
41). With omega_T the relaxation alone reduces the residual x0.010-0.44 in 12 sweeps on these cases and M = 100, L
= 8, and the ehl-indent crossing at 129^2 takes 5.1 cycles per step instead of 3.8. Raising the switch instead
(distributive rows up to xi = 1.2) cured M = 50 and 100 at L = 8 but not M = 100, L = 3; a switch at 2.4 was stable
but smoothed only x0.64 in 12 sweeps. The distributive rows are stable (their change is nearly film-neutral: the
kernel dK decays as a dipole) and keep omega = 0.3.

The steady relaxation on grids finer than h_ref (measured on 513^2). Up to 257^2 it is unchanged
(0.4 / 0.3). On 513^2 at M = 100, L = 19 the fine-grid relaxation alone diverges from a nearly converged state
(mean scaled residual 1.4e-4 -> 4.9e-3 in 15 sweeps): distributive rows (xi 0.05-0.1) where the pressure builds
up at the inlet edge of the Hertz zone, and Gauss-Seidel rows with xi = 0.45-0.7 at the side edges flipping sign
every sweep (over-correction). The critical distributive omega lies between 0.3 and 0.4 on 257^2 and between 0.25
and 0.3 on 513^2 (fine-grid sweeps alone), again roughly as sqrt(h). With both factors scaled by
min(1, sqrt(h/h_ref)) on the rows with xi <= 10 (0.28 and 0.21 on 513^2) the ten (M, L) points of
benchmarks/results/ehl_robustness.md converge on 513^2 in 6-21 cycles; scaling the Poiseuille-dominated inlet
rows too stalled the iteration near 1e-7 (M = 347, L = 17.2: 150 cycles), and scaling the distributive rows
alone (0.2) stalled at 5e-5. The transient keeps omega_T and 0.3 for its distributive rows (its 513^2 crossing at
M = 1200, L = 3 converged with them).

Why the compressibility term (measured). Venner's line matrix keeps only the elastic change of the film
(rho dH/dP). In an indent's hole the film is some 20 times the contact's (H = 0.19 against 0.01 at M = 1200,
L = 19), and there H drho/dP (Dowson-Higginson drho/dP = 0.37 at P = 0.23: 0.075) is 7 times the elastic
self-coupling c_el K_00 (0.0112 on 257^2): the distributive rows in the hole over-corrected, and the crossing
of ehl-indent's indent stalled at X_D = -0.69 b (257^2, 4 grids: step 149 of 192, residual 5.5e-7 with 98 % of it
on the 100 nodes in the hole). With the term it converges (12-13 cycles on those steps); with it and the weighted
coarse-grid indent (multigrid.Multigrid.set_time) the whole crossing converges on 257^2 at D/Phi = 0.35 and 0.5.
The steady relaxation keeps Venner's matrix: with the term the smooth steady solution at M = 100, L = 19 on 513^2
stalled (residual 1.3e-7 after 60 cycles; without it 30 at most), and no steady case needed it.

Vectorised by zebra ordering: all lines of one parity are solved together as one banded system (lines do not
couple inside a colour, so the stacked matrix keeps bandwidth (3, 2)), then the film is recomputed and the other
parity follows with the latest values.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import solve_banded

from .reynolds import operator, time_weights

XI_LIMIT = 0.3
OMEGA_GS_TRANSIENT = 0.15     # at h = H_REF, scaled as sqrt(h / H_REF)
H_REF = 1.0 / 64.0
XI_FREE = 10.0                # transient Gauss-Seidel rows above this xi keep OMEGA_GS
OMEGA_GS = 0.4
OMEGA_JA = 0.3


def fine_grid_factor(h: float) -> float:
    """min(1, sqrt(h/h_ref)): 1 on every grid up to h_ref = 1/64 (257^2 over 4 b), 1/sqrt(2) on 513^2."""
    return min(1.0, float(np.sqrt(h / H_REF)))


def omega_gs(xi: np.ndarray, h: float, ht: float | None) -> np.ndarray | float:
    """Under-relaxation of the Gauss-Seidel rows with the largest face coefficient xi on a grid of mesh size h:
    where xi <= 10, steady 0.4 min(1, sqrt(h/h_ref)), with the time term min(0.4, 0.15 sqrt(h/h_ref)); 0.4 above."""
    if ht is None:
        inner = OMEGA_GS * fine_grid_factor(h)
    else:
        inner = min(OMEGA_GS, OMEGA_GS_TRANSIENT * np.sqrt(h / H_REF))
    return np.where(xi > XI_FREE, OMEGA_GS, inner)


def omega_ja(h: float, ht: float | None) -> float:
    """Under-relaxation of the distributive rows: steady 0.3 min(1, sqrt(h/h_ref)); with the time term 0.3."""
    return OMEGA_JA * (fine_grid_factor(h) if ht is None else 1.0)


def distributed_kernel(K0: np.ndarray, K1: np.ndarray) -> np.ndarray:
    """dK_m = K_{m,0} - (K_{m+1,0} + K_{|m-1|,0} + 2 K_{m,1})/4 for m = 0 .. len(K0) - 2 (A.10)."""
    m = np.arange(K0.size - 1)
    return K0[m] - 0.25 * (K0[m + 1] + K0[np.abs(m - 1)] + 2.0 * K1[m])


def relax_colour(P: np.ndarray, f: np.ndarray, state, h: float, ht: float | None, r1, r2, c_el: float,
                 K0: np.ndarray, K1: np.ndarray, colour: int, density_slope=None) -> None:
    """One line relaxation of the lines j = colour, colour + 2, ... (interior), P updated in place.

    ``state(P)`` returns (H, rho, eps, r) on the full grid for the current P."""
    n = P.shape[0] - 1                       # intervals along X (the lines); P.shape[1] - 1 across
    ni = n - 1
    J = np.arange(2 - colour, P.shape[1] - 1, 2)   # colour 1: odd lines, colour 0: even lines
    if J.size == 0:
        return
    H, rho, eps, r = state(P)
    res = f - operator(P, eps, r, r1, r2, h, ht)
    ij = (slice(1, n), J)
    s = 0.5 / (h * h)
    eE = ((eps[1:n, J] + eps[2:n + 1, J]) * s).T
    eW = ((eps[1:n, J] + eps[0:n - 1, J]) * s).T
    eN = ((eps[1:n, J] + eps[1:n, J + 1]) * s).T
    eS = ((eps[1:n, J] + eps[1:n, J - 1]) * s).T
    S = eE + eW + eN + eS
    xi = np.maximum(np.maximum(eE, eW), np.maximum(eN, eS))
    pos = P > 0
    star = (pos[1:n, J] & pos[2:n + 1, J] & pos[0:n - 1, J] & pos[1:n, J + 1] & pos[1:n, J - 1]).T
    ja = (xi <= XI_LIMIT) & star
    # rows i-2 .. i+2 pressurised (points outside the grid count as not pressurised)
    padded = np.zeros((n + 5, J.size), dtype=bool)
    padded[2:n + 3] = pos[:, J]
    band = np.ones((ni, J.size), dtype=bool)
    for m in range(-2, 3):
        band &= padded[3 + m:3 + m + ni]        # padded index of node i + m is i + m + 2
    band = band.T
    rho_t = rho[:, J].T                       # (lines, n + 1)
    ri = rho_t[:, 1:n]
    rim1 = rho_t[:, 0:n - 1]
    rim2 = np.concatenate([np.zeros((J.size, 1)), rho_t[:, 0:n - 2]], axis=1)
    first = np.zeros(ni)
    first[0] = 1.0
    a0 = 1.5 - 0.5 * first
    a1 = -2.0 + first
    a2 = 0.5 - 0.5 * first
    wX, wD, wT = time_weights(h, ht)
    dK = distributed_kernel(K0, K1)
    Kr = [np.where(ja, dK[k], K0[k]) for k in range(5)]
    local = (wX + wD) * a0 + wT * 1.5           # coefficient of r_i (new time level)

    def dH(m: int) -> np.ndarray:
        out = local * ri * Kr[abs(m)] + wX * (a1 * rim1 * Kr[abs(m + 1)] + a2 * rim2 * Kr[abs(m + 2)])
        return c_el * out

    # compressibility: r = rho H also changes through rho(P); in a deep film (an indent's hole, H ~ 0.2 against
    # ~0.01 in the contact) H drho/dP outweighs the elastic self-coupling c_el K0 (measured)
    comp = {m: 0.0 for m in range(-3, 3)}
    if density_slope is not None and ht is not None:
        gt = (np.maximum(H, 0.0) * density_slope(P))[:, J].T      # H drho/dP along each line (H < 0 early on)
        g0, g1 = gt[:, 1:n], gt[:, 0:n - 1]
        g2 = np.concatenate([np.zeros((J.size, 1)), gt[:, 0:n - 2]], axis=1)
        c0, c1, c2 = local, wX * a1, wX * a2
        jf = ja.astype(float)
        jm = lambda s: np.concatenate([np.zeros((J.size, s)), jf[:, :ni - s]], axis=1) if s > 0 else (  # noqa: E731
            np.concatenate([jf[:, -s:], np.zeros((J.size, -s))], axis=1) if s < 0 else jf)
        # column k = i + m; a distributive node k moves P_{k+-1} by -delta_k/4 (along the line)
        comp[0] = c0 * g0 - 0.25 * jf * c1 * g1
        comp[-1] = c1 * g1 - 0.25 * jm(1) * (c0 * g0 + c2 * g2)
        comp[-2] = c2 * g2 - 0.25 * jm(2) * c1 * g1
        comp[-3] = -0.25 * jm(3) * c2 * g2
        comp[1] = -0.25 * jm(-1) * c0 * g0
    pois = {-2: np.where(ja, -0.25 * eW, 0.0), -1: np.where(ja, eW + 0.25 * S, eW), 0: np.where(ja, -1.25 * S, -S),
            1: np.where(ja, eE + 0.25 * S, eE), 2: np.where(ja, -0.25 * eE, 0.0), -3: 0.0}
    N = J.size * ni
    ab = np.zeros((6, N))
    ii = np.arange(ni)
    for m in range(-3, 3):
        A = pois[m] - dH(m) - comp[m]
        inside = (ii + m >= 0) & (ii + m < ni)
        A = np.where(inside & (band | (m == 0)), A, 0.0).ravel()
        if m >= 0:
            ab[2 - m, m:N] = A[0:N - m]
        else:
            ab[2 - m, 0:N + m] = A[-m:N]
    delta = solve_banded((3, 2), ab, res[ij].T.ravel(), check_finite=False).reshape(J.size, ni)
    wja = omega_ja(h, ht)
    upd = np.where(~ja, omega_gs(xi, h, ht) * delta, wja * delta)
    P[ij] += upd.T
    dj = np.where(ja, 0.25 * wja * delta, 0.0).T      # distribution to the four neighbours
    if dj.any():
        P[0:n - 1, J] -= dj
        P[2:n + 1, J] -= dj
        P[1:n, J - 1] -= dj
        P[1:n, J + 1] -= dj
    np.maximum(P, 0.0, out=P)
    P[0, :] = P[-1, :] = P[:, 0] = P[:, -1] = 0.0
