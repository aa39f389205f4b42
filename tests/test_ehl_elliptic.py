"""Elliptic EHL contacts (Ry > Rx) and the transient line matrix: checks that catch the physics mutations no other
fast test saw (the deformation factor of an elliptic contact, Hamrock-Dowson's ellipticity, the compressibility
term of the transient line relaxation). Every value is checked against Hertz theory, a published film formula or
the discrete operator itself (spec ehl-life.md §A.2, §A.4, §A.5, §A.8)."""
import dataclasses

import numpy as np
import pytest

from femcheck.analytic import hertz
from femcheck.ehl import formulas, groups, model, relax, reynolds, steady, transient
from femcheck.ehl.film import FilmOperator, Indent
from femcheck.problems import ehl_contact
from femcheck.scene import load_scene

RATIOS = (2.0, 4.0)          # Ry/Rx


@pytest.mark.parametrize("ratio", RATIOS)
def test_hertz_pressure_gives_the_hertz_gap_on_an_ellipse(ratio):
    """Hertz theory (Johnson 1985, §3.9 / §4.2): under p_H sqrt(1 - (x/b)^2 - (y/a)^2) the elastic displacement of
    the two half-spaces complements the quadratic gap exactly inside the ellipse, so the film equation's
    H_el + X^2/2 + (Rx/Ry) Y^2/2 equals the Hertz approach delta Rx/b^2 everywhere in the contact (film units
    H = h Rx/b^2). The approach comes from femcheck's exact elliptic Hertz (complete elliptic integrals), the
    deformation from the EHL film operator with c_el = (1 + Rx/Ry)/(2 pi Ecal) (seed 004 eq 2.4, corrected eq 2.6).

    Tolerance 2e-3 (absolute, against ~1.1-1.3): the cell-kernel discretisation on 65^2 nodes over +-1.3 a
    (measured 4e-4 at Ry = 2 Rx, 1.1e-3 at 4 Rx; 2.6e-4 and 3.3e-4 on 129^2). The deformation factor inverted
    ((1 + Ry/Rx) in place of (1 + Rx/Ry)) doubles (Ry = 2 Rx) or quadruples the deflection: off by ~1."""
    Rx, load, e_star = 0.01, 500.0, 113e9
    g = groups.from_physical(Rx, ratio * Rx, 2.0 * e_star, load, 0.04, 2e-8, 1.0)
    hz = hertz.elliptic_contact(load, Rx, ratio * Rx, e_star)
    half = 1.3 / g.kappa                       # the ellipse's long semi-axis a/b = 1/kappa, with a margin
    f = FilmOperator(64, 2.0 * half / 64, -half, -half, g.c_el, g.Rx / g.Ry)
    P = np.sqrt(np.clip(1.0 - f.X**2 - (g.kappa * f.Y) ** 2, 0.0, None))
    H = f.deformation(P) + f.base
    inside = f.X**2 + (g.kappa * f.Y) ** 2 < 0.5
    approach = hz.approach * Rx / g.b**2
    assert np.abs(H - approach)[inside].max() < 2e-3


def _elliptic_solution(ratio, grid=129):
    g = groups.from_moes(100.0, 10.0, 0.01, 0.01 * ratio, 226e9, 0.04, 2.2e-8)
    s = model.make_setup(g, "barus", "incompressible", grid, None, -4.5, 1.5)
    sol, _ = model.solve_smooth(s, 1e-8, 1e-8)
    return g, s, sol


# Nijenbanning, Venner & Moes (1994, Wear 176:217-229) give the accuracy of their central-film formula only through
# their survey graphs (no figure retrievable here; spec ehl-life.md §A.8, §D). The fit band used below is what
# femcheck's grid-converged circle (M = 100, L = 10, Barus, incompressible; Richardson over 65^2/129^2/257^2,
# observed order 1.95) measures against the same formula: +3.4 %, the formula's best-established limit (Moes'
# circular formula). Measured (femcheck, same domain [-4.5, 1.5] b along X):
#   Ry/Rx  a/b    kappa=b/a  H_c 65 / 129 / 257        Richardson (order)  formula  Richardson vs formula
#   1      1.000  1.000      3.974 / 4.475 / 4.604     4.650 (1.95)        4.497    +3.4 %
#   2      1.586  0.631      4.728 / 5.059 / 5.143     5.172 (1.97)        5.146    +0.5 %
#   4      2.501  0.400      5.263 / 5.484 / 5.539     5.558 (1.98)        5.607    -0.9 %
FIT_BAND = 0.035
# discretisation error of the 129-node value against the Richardson value above: 2.2 % (Ry = 2 Rx), 1.3 % (4 Rx)
GRID_ERROR_129 = {2.0: 0.022, 4.0: 0.013}


@pytest.mark.parametrize("ratio", RATIOS)
def test_elliptic_ehl_centre_pressure_and_central_film(ratio):
    """An elliptic EHL solve (M = 100, L = 10, Barus viscosity, incompressible: the lubricant of the fit) on 129
    nodes along [-4.5, 1.5] b and, across, over +-3 a (the circle's lateral margin in units of the transverse
    semi-axis a = b/kappa: :func:`femcheck.ehl.model.default_y_half`):

    - the pressure at the contact centre is Hertz's p_H within 5 %: at M = 100 the central film is ~15 % of the
      Hertz deflection, the film is nearly parallel there and the pressure follows the dry contact (measured
      +1.0 % at Ry = 2 Rx, +0.5 % at 4 Rx; the circle: +3 %). With the deformation factor inverted the pressure
      falls to 0.63 p_H (2 Rx) and 0.40 p_H (4 Rx);
    - the central film H_c = (h_c/Rx) U_M^-1/2 is Nijenbanning, Venner & Moes (1994) with D = Rx/Ry within the fit
      band (3.5 %, see ``FIT_BAND``) plus the 129-node discretisation error measured by grid refinement (2.2 % /
      1.3 %, ``GRID_ERROR_129``); measured -1.7 % (2 Rx), -2.2 % (4 Rx);
    - the pressure peak (outlet spike) is at least the centre pressure and the load balance holds."""
    g, s, sol = _elliptic_solution(ratio)
    i0, j0 = int(np.argmin(np.abs(sol.x))), int(np.argmin(np.abs(sol.y)))
    assert sol.load_error <= 1e-7
    assert sol.P[i0, j0] == pytest.approx(1.0, abs=0.05)
    assert sol.P.max() >= sol.P[i0, j0]
    hc = model.film_quantities(s, sol)["H_central_moes"]
    assert hc == pytest.approx(formulas.moes_central(g.M, g.L, g.Rx / g.Ry), rel=FIT_BAND + GRID_ERROR_129[ratio])


def test_elliptic_domain_holds_the_side_lobes():
    """At Ry = 4 Rx the contact is a = 2.50 b wide across. A square domain over [-4.5, 1.5] b reaches +-3 b =
    1.2 a across, and its P = 0 edge cuts the side lobes, where the minimum film lies: measured on 129 nodes along X,
    H_min 3.645 there against 3.868 with +-2.55 a (-5.8 %; H_c -0.5 %). femcheck widens the domain across to the
    circle's margin in units of a (+-3 a = +-7.5 b, rounded up to whole cells of the 16-interval coarsest grid: +-7.875 b,
    337 nodes across); the minimum film then changes by less
    than 0.5 % when the domain is widened further to +-4 a (measured 0.02 %). Tolerance 0.5 %: the measured
    convergence in the half-width (+-2.1 a: 0.15 %), well below the 5.8 % of the cut lobes."""
    g, s, sol = _elliptic_solution(4.0)
    assert 3.0 <= sol.y[-1] * g.kappa <= 3.0 + 6.0 / 16 * g.kappa + 1e-9
    wide = model.make_setup(g, "barus", "incompressible", 129, None, -4.5, 1.5, y_half=4.0 / g.kappa)
    sol_w, _ = model.solve_smooth(wide, 1e-8, 1e-8)
    hm, hm_w = (model.film_quantities(x, y)["H_min_moes"] for x, y in ((s, sol), (wide, sol_w)))
    assert hm == pytest.approx(hm_w, rel=0.005)


@pytest.mark.slow
@pytest.mark.parametrize("ratio", RATIOS)
def test_elliptic_central_film_converges_to_nijenbanning(ratio):
    """The Richardson value of H_c over 65, 129 and 257 nodes along X (second order expected; observed
    1.97 / 1.98) against Nijenbanning, Venner & Moes (1994): within the fit band (3.5 %, ``FIT_BAND``) plus the
    Richardson value's own uncertainty, taken as its distance to the 257-node value (0.6 % / 0.3 %). Measured
    +0.5 % (Ry = 2 Rx), -0.9 % (4 Rx). About 10 s per ratio."""
    hs = [model.film_quantities(s, sol)["H_central_moes"]
          for s, sol in (_elliptic_solution(ratio, n)[1:] for n in (65, 129, 257))]
    g = _elliptic_solution(ratio, 65)[0]
    order = np.log2((hs[1] - hs[0]) / (hs[2] - hs[1]))
    assert 1.5 <= order <= 2.5
    rich = hs[2] + (hs[2] - hs[1]) / (2.0**order - 1.0)
    ref = formulas.moes_central(g.M, g.L, g.Rx / g.Ry)
    assert rich == pytest.approx(ref, rel=FIT_BAND + abs(rich / hs[2] - 1.0))


@pytest.mark.parametrize("ratio", [1.0, 2.0, 4.0, 10.0])
def test_hamrock_dowson_model_uses_k_a_over_b(ratio):
    """The ``hamrock_dowson`` model of the ehl_contact kind against Hamrock & Dowson (1977, ASME J. Lubr. Technol.
    99:264-276) evaluated here from the scene's physical inputs, with their ellipticity k = a/b (transverse over
    rolling semi-axis) from Hamrock & Brewe's fit k = 1.0339 (Ry/Rx)^0.636 (Hamrock & Brewe 1983, ASME J. Lubr.
    Technol. 105:171-177; against exact Hertz: +3.4 % at Ry = Rx, +1.3 % at 2, -0.2 % at 4, -0.6 % at 10, +3.1 % at
50, computed here with femcheck's Hertz):
        h_c = 2.69 Rx U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k)),
        h_min = 3.63 Rx U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)),   U = eta0 u_m/(E' Rx), G = alpha E', W = w/(E' Rx^2).
    The model uses femcheck's exact Hertz a/b; the tolerance is the fit's 3.5 % in k carried through each
    ellipticity factor f(k) (0.035 k |f'(k)|/f(k): 1.1 % / 2.5 % at k = 1, 0.6 % / 0.7 % at Ry = 4 Rx) plus 1e-3.
    With k inverted (b/a) the factors fall from 0.90 to 0.54 (h_c) and 0.82 to 0.24 (h_min) at Ry = 4 Rx (at
    Ry = Rx the inversion does nothing: that case checks the formula and the units). And the fit itself:
    femcheck's exact a/b within 3.5 % of 1.0339 (Ry/Rx)^0.636."""
    Rx, E, nu, w, um, eta0, alpha = 0.01, 210e9, 0.3, 200.0, 1.0, 0.04, 2.2e-8
    sc = load_scene("ehl-smooth", {"ehl.M": None, "ehl.L": None, "load.normal": w, "kinematics.mean_speed": um,
                                   "geometry.Ry": ratio * Rx, "numerics.x_start": -10.0})
    q = ehl_contact.hamrock_dowson(sc).quantities
    e_prime = E / (1.0 - nu**2)                # 2/E' = 2 (1 - nu^2)/E for two equal bodies
    U, G, W = eta0 * um / (e_prime * Rx), alpha * e_prime, w / (e_prime * Rx**2)
    k = 1.0339 * ratio**0.636
    fc, dfc = 1.0 - 0.61 * np.exp(-0.73 * k), 0.61 * 0.73 * np.exp(-0.73 * k)
    fm, dfm = 1.0 - np.exp(-0.68 * k), 0.68 * np.exp(-0.68 * k)
    hc = 2.69 * Rx * U**0.67 * G**0.53 * W**-0.067 * fc
    hm = 3.63 * Rx * U**0.68 * G**0.49 * W**-0.073 * fm
    assert q["h_central"] == pytest.approx(hc, rel=0.035 * k * dfc / fc + 1e-3)
    assert q["h_min"] == pytest.approx(hm, rel=0.035 * k * dfm / fm + 1e-3)
    h = hertz.elliptic_contact(w, Rx, ratio * Rx, 0.5 * e_prime)
    assert h.semi_axis_y / h.semi_axis_x == pytest.approx(k, rel=0.035)


# -- the transient line matrix -----------------------------------------------------------------------------------
def _indented_transient_state():
    """A converged steady solution with a dent (Phi = 0.5 b, D/Phi = 0.35, K = 4) at the contact centre, turned
    into a transient (time step = mesh size): M = 100, L = 10, Roelands / Dowson-Higginson, 65^2 over
    [-2.5, 1.5] b. In the dent the film is ~2 times the contact's, where the compressibility matters."""
    g = groups.from_moes(100.0, 10.0, 0.01, 0.01, 226e9, 0.04, 2.2e-8)
    s = model.make_setup(g, "roelands", "dowson_higginson", 65, None, -2.5, 1.5)
    prob = dataclasses.replace(s.prob, indent=Indent(0.5, 0.35 * 0.5, 4.0, x0=0.0))
    _, mg = steady.solve(prob, s.n, s.levels, tol=1e-6, load_tol=1e-6)
    transient.start(mg)
    return mg


def test_transient_line_matrix_is_the_jacobian_of_the_discrete_operator(monkeypatch):
    """The line relaxation (seed 004 §2.6.2, App. A.7-A.13; Venner & Lubrecht 2000 ch. 17) solves, per line, the
    linearisation of the discrete Reynolds operator L(P) = Q(P; eps frozen) - W(rho(P) H(P)) in the line's six
    nearest unknowns: each matrix entry A_ik is dL_i/dP_k for a Gauss-Seidel row (a unit change of P_k), or the
    change of L_i under the distributive pattern of column k (P_k + 1, its four neighbours - 1/4) for a
    distributive row. With the time term (NU2, transient) W depends on P through rho too: the term H drho/dP of
    the line matrix. Checked on the rows through the dent of :func:`_indented_transient_state` where every point of
    the band has the same row type, against central differences (step 1e-6) of :func:`reynolds.operator`'s parts
    evaluated by the multigrid's own state (film, density) - an independent evaluation of the same discrete
    equation.

    Tolerance 1e-6 of the row's diagonal (measured 2e-10 Gauss-Seidel, 5e-9 distributive: the differences'
    truncation and round-off). Without the compressibility term the entries are off by 7 % (Gauss-Seidel) and
    46 % (distributive rows in the dent). The converged solution does not depend on this matrix, only the
    convergence does: without the term the ehl-indent crossing at M = 1200, L = 19 stalls on 257^2 (relax.py)."""
    mg = _indented_transient_state()
    lv = mg.fine
    P = lv.P.copy()
    captured = {}
    real = relax.solve_banded

    def spy(l_and_u, ab, b, **kw):
        captured["ab"] = ab.copy()
        return real(l_and_u, ab, b, **kw)

    monkeypatch.setattr(relax, "solve_banded", spy)
    colour = 1
    relax.relax_colour(P.copy(), lv.f, lambda Q: mg.state(lv, Q), lv.h, lv.ht, lv.r1, lv.r2, mg.prob.c_el,
                       lv.film.K0, lv.film.K1, colour, mg.prob.lubricant.density_slope)
    ab = captured["ab"]
    n = P.shape[0] - 1
    ni = n - 1
    J = np.arange(2 - colour, n, 2)
    H, rho, eps, r = mg.state(lv, P)
    # row types as the relaxation decides them: distributive where xi <= 0.3 and the 5-point star is pressurised
    s2 = 0.5 / lv.h**2
    xi = np.maximum.reduce([(eps[1:n, J] + eps[2:, J]) * s2, (eps[1:n, J] + eps[:n - 1, J]) * s2,
                            (eps[1:n, J] + eps[1:n, J + 1]) * s2, (eps[1:n, J] + eps[1:n, J - 1]) * s2]).T
    pos = P > 0
    star = (pos[1:n, J] & pos[2:, J] & pos[:n - 1, J] & pos[1:n, J + 1] & pos[1:n, J - 1]).T
    ja = (xi <= relax.XI_LIMIT) & star

    def L(Q):
        _, _, _, rq = mg.state(lv, Q)
        return reynolds.poiseuille(Q, eps, lv.h) - reynolds.wedge_squeeze(rq, lv.r1, lv.r2, lv.h, lv.ht)[1:-1, 1:-1]

    def entry(line, i, k):               # banded storage of solve_banded((3, 2), ...): ab[2 + row - col, col]
        row, col = line * ni + i, line * ni + k
        return ab[2 + row - col, col]

    worst, checked = {"gs": 0.0, "ja": 0.0}, {"gs": 0, "ja": 0}
    step = 1e-6
    for line, j in enumerate(J):
        if abs(lv.film.y[j]) > 0.3:              # the lines through the dent
            continue
        for i in range(3, ni - 3):
            ii = i + 1                           # grid index of line point i
            if not all(pos[ii + m, j] for m in range(-2, 3)):
                continue
            kinds = ja[line, i - 3:i + 3]
            if not (kinds.all() or not kinds.any()):
                continue
            kind = "ja" if kinds.all() else "gs"
            diag = abs(entry(line, i, i))
            for m in range(-3, 3):
                pattern = np.zeros_like(P)
                pattern[ii + m, j] = 1.0
                if kind == "ja":
                    for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                        pattern[ii + m + di, j + dj] -= 0.25
                fd = (L(P + step * pattern) - L(P - step * pattern))[ii - 1, j - 1] / (2.0 * step)
                worst[kind] = max(worst[kind], abs(entry(line, i, i + m) - fd) / diag)
            checked[kind] += 1
    assert checked["gs"] >= 10 and checked["ja"] >= 10, checked
    assert worst["gs"] < 1e-6 and worst["ja"] < 1e-6, worst
