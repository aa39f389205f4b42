"""Fatigue life closed forms (seed 004 ch. 4, spec ehl-life part B): risk integral and its quadrature, the Weibull
law with the corrected sign of eq 4.7, the weakest link (eq 4.9), the dented-track life ratio (eq 4.10 and its
closed form), the Lundberg-Palmgren load-life exponents, and McEwen's line-contact history."""
import numpy as np
import pytest
from scipy import special

from femcheck.analytic import life
from femcheck.analytic.hertz import LineContact
from femcheck.analytic.stress import line_contact_field
from femcheck.errors import InputError


def _history(rng):
    return 1e9 * rng.random((6, 7, 5)), rng.random(6)[:, None, None] * rng.random(7)[None, :, None] * np.ones(5)


def test_risk_integral_scales_as_lambda_to_the_c_without_fatigue_limit():
    rng = np.random.default_rng(1)
    T, w = _history(rng)
    for c in (6.3, 8.0, 31 / 3):
        k = life.LifeConstants(c=c)
        lam = 1.37
        assert life.risk_integral(lam * T, w, k) == pytest.approx(lam**c * life.risk_integral(T, w, k), rel=1e-12)
    # with a fatigue limit it does not (the limit does not scale): the check above is not automatic
    k = life.LifeConstants(c=8.0, fatigue_limit=3e8)
    assert life.risk_integral(1.37 * T, w, k) > 1.37**8 * life.risk_integral(T, w, k) * 1.05


def test_risk_integral_of_a_uniform_block_is_closed_form():
    # T uniform over a box: I = (T - T_inf)^c V exactly, and the depth weight integrates z^-h
    z, wz = life.depth_planes(1e-3, 48)
    T = np.full(z.size, 1.5e9)
    k = life.LifeConstants(c=8.0, fatigue_limit=0.5e9)
    assert life.risk_integral(T, wz * 2e-3, k) == pytest.approx(1e9**8 * 1e-3 * 2e-3, rel=1e-12)
    kh = life.LifeConstants(c=8.0, h=0.5)
    b = 1e-3    # floor 0.05 b = 5e-5 m: int_0^1e-3 max(z, 5e-5)^-0.5 dz = 5e-5^0.5 + 2 (1e-3^0.5 - 5e-5^0.5)
    exact = 1.5e9**8 * (5e-5**0.5 + 2 * (1e-3**0.5 - 5e-5**0.5))
    got = life.risk_integral(T, wz, kh, life.depth_weight(z, 0.5, b))
    assert got == pytest.approx(exact, rel=2e-3)


def test_depth_quadrature_is_second_order_and_exact_for_the_window():
    z0, s = 0.48, 0.16          # a Hertz-like peak of T^c at z0
    exact = 0.5 * s * np.sqrt(np.pi) * (special.erf((2.0 - z0) / s) + special.erf(z0 / s))
    errs = []
    for n in (12, 24, 48):
        z, w = life.depth_planes(2.0, n)
        assert w.sum() == pytest.approx(2.0, rel=1e-14)
        assert z[-1] == pytest.approx(2.0) and z[0] == pytest.approx(2.0 / n**2)
        errs.append(abs(np.sum(w * np.exp(-((z - z0) / s) ** 2)) - exact) / exact)
    assert errs[-1] < 1e-5
    order = np.log2(errs[0] / errs[1])
    assert order > 1.8, order


def test_window_weights_give_the_exact_window_length():
    x = (np.arange(41) - 20) * 0.1
    for half in (0.5, 0.73, 1.96):
        w = life.window_weights(x, 0.1, half)
        assert w.sum() == pytest.approx(2 * half, rel=1e-12)
        inside, outside = np.abs(x) + 0.05 <= half + 1e-12, np.abs(x) - 0.05 >= half - 1e-12
        assert np.allclose(w[inside], 0.1, rtol=1e-12) and np.all(w[outside] == 0.0)


def test_infinite_life_above_the_fatigue_limit_is_inf_not_nan():
    T = np.array([1.0e9, 1.8e9, 1.2e9])
    k = life.LifeConstants(c=8.0, fatigue_limit=1.8e9)
    risk = life.risk_integral(T, np.ones(3), k)
    assert risk == 0.0
    assert life.relative_life(risk, k) == np.inf
    assert life.risk_ratio(0.0, 0.0) == 1.0 and life.risk_ratio(2.0, 0.0) == np.inf
    assert life.dented_life_ratio(np.inf, 0.5, 10 / 9) == 0.0     # smooth track never fails, dented one does
    assert life.weakest_link_life([np.inf, np.inf], 10 / 9) == np.inf


def test_relative_life_definition():
    k = life.LifeConstants(c=8.0, e=10 / 9)
    # R = (1 GPa)^c (1 mm)^2 is the reference: life 1; doubling the risk divides the life by 2^(1/e)
    ref = 1e9**8 * 1e-6
    assert life.relative_life(ref, k) == pytest.approx(1.0, rel=1e-12)
    assert life.relative_life(2 * ref, k) == pytest.approx(2 ** (-0.9), rel=1e-12)


def test_weibull_survival_has_the_corrected_sign():
    # eq 4.7 as printed, F = 1 - exp(-ln(1 - theta)(L/L_theta)^e), gives survival > 1; corrected: F(L_theta) = theta
    for theta in (0.1, 0.5):
        assert life.failure_probability(2.0, 2.0, 10 / 9, theta) == pytest.approx(theta, rel=1e-12)
        s = life.survival(np.linspace(0.0, 10.0, 11), 2.0, 10 / 9, theta)
        assert np.all((s <= 1.0) & (s > 0.0)) and np.all(np.diff(s) < 0)


def test_weakest_link_equals_the_product_of_survival_probabilities():
    rng = np.random.default_rng(7)
    e, theta = 9 / 8, 0.1
    lives = 10 ** rng.uniform(-1, 2, 50)
    combined = life.weakest_link_life(lives, e)
    for L in (0.01, 0.3, 1.0, 7.0):
        product = np.prod([life.survival(L, Li, e, theta) for Li in lives])
        assert abs(product - life.survival(L, combined, e, theta)) <= 1e-12
    # the combination is dominated by the weakest element and never exceeds it
    assert combined < lives.min()
    assert life.weakest_link_life([3.0], e) == pytest.approx(3.0, rel=1e-15)


def test_eq_4_10_and_the_closed_form_for_an_indent_fraction():
    # a track of N equal windows, N_d of them dented: eq 4.10 with the per-window risks = the closed form
    I_S, I_D, e = 2.3, 7.9, 10 / 9
    for N, Nd in ((10, 1), (10, 4), (7, 7)):
        risks = [I_D] * Nd + [I_S] * (N - Nd)
        eq410 = life.life_ratio_from_risks([I_S] * N, risks, e)
        assert life.dented_life_ratio(I_D / I_S, Nd / N, e) == pytest.approx(eq410, rel=1e-12)
    assert life.dented_life_ratio(I_D / I_S, 1.0, e) == pytest.approx((I_S / I_D) ** (1 / e), rel=1e-12)
    assert life.dented_life_ratio(1.0, 0.3, e) == 1.0        # a smooth "indent": exactly 1
    assert life.dented_life_ratio(5.0, 0.0, e) == 1.0        # no indent on the track


def test_lundberg_palmgren_exponents():
    assert life.load_life_exponent(**life.LP_POINT, contact="point") == pytest.approx(3.0, rel=1e-14)
    assert life.load_life_exponent(**life.LP_LINE, contact="line") == pytest.approx(4.0, rel=1e-14)
    assert life.load_life_exponent(8.0, 0.0, 10 / 9, "point") == pytest.approx(3.0, rel=1e-14)
    assert life.load_life_exponent(8.0, 0.0, 9 / 8, "line") == pytest.approx(4.0, rel=1e-14)
    assert life.local_exponents([1.0, 2.0], [1.0, 0.125]) == pytest.approx([3.0])


def test_mcewen_history_maximum_is_the_line_contact_von_mises_maximum():
    # spec B.1: line contact, nu = 0.3: T_Smax = 0.557 p_H at z = 0.70 a (McEwen field maximum by Nelder-Mead)
    h = LineContact(load=1e6, radius=0.01, modulus=115e9, half_width=1.0, p_max=1.0)
    ref = line_contact_field(h, 0.3).maxima
    z = np.linspace(0.6, 0.8, 201)
    T = life.mcewen_history(1.0, 1.0, 0.3, z)
    k = np.argmax(T)
    assert T[k] == pytest.approx(ref["von_mises_max"], rel=2e-6)
    assert z[k] == pytest.approx(ref["von_mises_max_depth"], abs=2e-3)
    assert T[k] == pytest.approx(0.557, abs=1e-3) and z[k] == pytest.approx(0.70, abs=0.01)


def test_bad_constants_are_one_clear_input_error():
    for kw, key in (({"e": 0.0}, "life.e"), ({"e": -1.0}, "life.e"), ({"fatigue_limit": -1.0}, "life.fatigue_limit"),
                    ({"c": 0.5}, "life.c"), ({"h": -0.1}, "life.h")):
        with pytest.raises(InputError) as err:
            life.LifeConstants(**kw)
        assert err.value.key == key and "allowed" in str(err.value)
