"""Papadopoulos' shear-stress amplitude T_sigma and the von Mises history measure
(:mod:`femcheck.analytic.multiaxial`) against closed forms (Papadopoulos et al., Int. J. Fatigue 19 (1997)
219-235: T_sigma = tau_a in fully reversed torsion, sigma_a/sqrt(3) in fully reversed tension)."""
import numpy as np
import pytest

from femcheck.analytic import multiaxial as mx

T = np.linspace(0.0, 2.0 * np.pi, 3601)          # 0.1 degree steps: sampled extremes within 1 - cos(0.05 deg)
EXACT = mx.line_rule(3, 5, 3)                     # exact for degree-4 integrands (proportional histories)


def _history(amp: np.ndarray, phase: np.ndarray | None = None, mean: np.ndarray | None = None) -> np.ndarray:
    """sigma(t) = mean + amp sin t (+ phase cos t), components (sx, sy, sz, txy, txz, tyz), shape (T, 6)."""
    h = np.sin(T)[:, None] * amp[None, :]
    if phase is not None:
        h = h + np.cos(T)[:, None] * phase[None, :]
    return h + (0.0 if mean is None else mean[None, :])


def _j2(c: np.ndarray) -> float:
    sx, sy, sz, txy, txz, tyz = c
    return ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) / 6.0 + txy**2 + txz**2 + tyz**2


@pytest.mark.parametrize("rule", [EXACT, mx.line_rule()], ids=["exact-3x5x3", "default-8x16x8"])
def test_fully_reversed_tension_and_torsion(rule):
    """Tension sigma_a: T_sigma = sigma_a/sqrt(3), sigma_VM max = sigma_a; torsion tau_a: T_sigma = tau_a,
    sigma_VM max = sqrt(3) tau_a (the normalisation 5/(8 pi^2) of the paper). Both rules are exact for these
    degree-4 integrands: 1e-12."""
    sa, ta = 300e6, 200e6
    tension = _history(np.array([sa, 0, 0, 0, 0, 0]))
    torsion = _history(np.array([0, 0, 0, 0, ta, 0]))
    assert mx.papadopoulos_amplitude(tension, rule) == pytest.approx(sa / np.sqrt(3.0), rel=1e-12)
    assert mx.papadopoulos_amplitude(torsion, rule) == pytest.approx(ta, rel=1e-12)
    assert mx.von_mises_max(tension) == pytest.approx(sa, rel=1e-12)
    assert mx.von_mises_max(torsion) == pytest.approx(np.sqrt(3.0) * ta, rel=1e-12)


def test_proportional_history_is_the_von_mises_amplitude_over_sqrt3():
    """For sigma(t) = S sin t with any S: T_a(n, m) = |n.S.m| and T_sigma = sqrt(J2(S)) (the average of
    (n.S.m)^2 over the orthonormal pairs is J2/5); the hydrostatic part of S does not count. 1e-12 (exact rule)."""
    rng = np.random.default_rng(4)
    for _ in range(5):
        S = rng.normal(size=6) * 1e8
        assert mx.papadopoulos_amplitude(_history(S), EXACT) == pytest.approx(np.sqrt(_j2(S)), rel=1e-12)
        assert mx.von_mises_max(_history(S)) == pytest.approx(np.sqrt(3.0 * _j2(S)), rel=1e-12)


def test_static_stress_and_mean_stress():
    """A constant stress has no amplitude; a constant stress added to a cycle changes neither T_sigma nor T_a
    (only the hydrostatic term sees it: sigma_H,max = max tr/3)."""
    rng = np.random.default_rng(5)
    mean = rng.normal(size=6) * 1e8
    static = np.repeat(mean[None, :], 50, axis=0)
    assert mx.papadopoulos_amplitude(static) == pytest.approx(0.0, abs=1e-6)
    amp, ph = rng.normal(size=6) * 1e8, rng.normal(size=6) * 1e8
    a0 = mx.papadopoulos_amplitude(_history(amp, ph))
    assert mx.papadopoulos_amplitude(_history(amp, ph, mean)) == pytest.approx(a0, rel=1e-12)
    h = _history(amp, ph, mean)
    assert mx.hydrostatic_max(h) == pytest.approx(((h[:, 0] + h[:, 1] + h[:, 2]) / 3).max(), rel=1e-15)
    assert mx.papadopoulos_criterion(h, 0.5) == pytest.approx(a0 + 0.5 * mx.hydrostatic_max(h), rel=1e-12)


def test_out_of_phase_tension_torsion():
    """sigma_x = sigma_a sin t, tau_xz = tau_a cos t (90 degrees out of phase): on every line
    tau = A sin t + B cos t, T_a = sqrt(A^2 + B^2), so T_sigma = sqrt(J2(A) + J2(B)) = sqrt(sigma_a^2/3 + tau_a^2)
    whatever the phase (Papadopoulos' criterion is phase-insensitive for synchronous sinusoids). With
    tau_a = sigma_a/sqrt(3) the von Mises stress is constant, sigma_a, while T_sigma = sqrt(2/3) sigma_a: the
    rotating loading counts more. T_a is not a polynomial here; measured errors -1.2e-7 (default rule and
    16 x 32 x 16, the time sampling's 1 - cos(0.05 deg) = 3.8e-7 bounding it); tolerance 1e-6."""
    sa = 300e6
    h = _history(np.array([sa, 0, 0, 0, 0, 0]), np.array([0, 0, 0, 0, sa / np.sqrt(3), 0]))
    ref = np.sqrt(2.0 / 3.0) * sa
    assert mx.papadopoulos_amplitude(h) == pytest.approx(ref, rel=1e-6)
    assert mx.papadopoulos_amplitude(h, mx.line_rule(16, 32, 16)) == pytest.approx(ref, rel=1e-6)
    assert mx.von_mises_max(h) == pytest.approx(sa, rel=1e-12)
    assert np.ptp(mx.von_mises(h)) == pytest.approx(0.0, abs=1e-6 * sa)


def test_rotation_invariance_and_tensor_form():
    """A rotated history sigma' = R sigma R^T (given as (T, 3, 3)) has the same T_sigma, to the rule's accuracy
    (measured 3.6e-5 with the 16 x 32 x 16 rule, 4.5e-4 with the default 8 x 16 x 8, -3.1e-6 with 32 x 64 x 32;
    tolerance 2e-4 on the 16 x 32 x 16 rule), and the same von Mises measure
    exactly. Non-proportional history: two random amplitude tensors in quadrature plus a third at twice the
    frequency."""
    rng = np.random.default_rng(6)
    a, b, c = (rng.normal(size=6) * 1e8 for _ in range(3))
    h6 = _history(a, b) + np.sin(2 * T)[:, None] * c[None, :]
    i, j = np.array([0, 1, 2, 0, 0, 1]), np.array([0, 1, 2, 1, 2, 2])
    h33 = np.zeros((T.size, 3, 3))
    h33[:, i, j] = h6
    h33[:, j, i] = h6
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    rot = np.einsum("ab,tbc,dc->tad", q, h33, q)
    rule = mx.line_rule(16, 32, 16)
    v0 = mx.papadopoulos_amplitude(h6, rule)
    assert mx.papadopoulos_amplitude(h33, rule) == pytest.approx(v0, rel=1e-12)
    assert mx.papadopoulos_amplitude(rot, rule) == pytest.approx(v0, rel=2e-4)
    assert mx.von_mises_max(rot) == pytest.approx(mx.von_mises_max(h6), rel=1e-12)


def test_points_axis_and_chunks():
    """A (T, 6, P) history gives P values, the same as one point at a time, whatever the chunk size."""
    rng = np.random.default_rng(7)
    h = rng.normal(size=(40, 6, 7)) * 1e8
    one = [mx.papadopoulos_amplitude(h[:, :, p]) for p in range(7)]
    assert mx.papadopoulos_amplitude(h, chunk=3) == pytest.approx(one, rel=1e-13)
    assert mx.von_mises_max(h).shape == (7,)


def test_pulsating_tension_range_and_from_zero():
    """Pulsating tension 0 -> sigma_max: Papadopoulos' T_a is half the range, T_sigma = sigma_max / (2 sqrt 3);
    measured from the unloaded state ("zero" variant) it is sigma_max / sqrt 3; fully reversed, both coincide.
    Exact rule: 1e-12."""
    smax = 400e6
    h = np.zeros((T.size, 6))
    h[:, 0] = 0.5 * smax * (1.0 - np.cos(T))
    assert mx.papadopoulos_amplitude(h, EXACT) == pytest.approx(smax / (2 * np.sqrt(3.0)), rel=1e-12)
    assert mx.papadopoulos_amplitude(h, EXACT, about="zero") == pytest.approx(smax / np.sqrt(3.0), rel=1e-12)
    rev = _history(np.array([smax, 0, 0, 0, 0, 0]))
    assert mx.papadopoulos_amplitude(rev, EXACT, about="zero") == pytest.approx(smax / np.sqrt(3.0), rel=1e-12)


def test_critical_plane_form():
    """Papadopoulos 1995 (hard metals): max over planes of sqrt((1/pi) int T_a^2 dchi). Fully reversed tension
    sigma_a: sigma_a / 2 (planes at 45 degrees; measured error -8e-8 with the default rule), torsion tau_a:
    tau_a (plane normal along x or z, which the Gauss normals miss by a fraction of their spacing: measured -5.6e-5
    with 16 x 32 x 16). Tolerances 1e-6 and 1e-4, and a discrete max is never above the exact one."""
    sa, ta = 300e6, 200e6
    tension = _history(np.array([sa, 0, 0, 0, 0, 0]))
    torsion = _history(np.array([0, 0, 0, 0, ta, 0]))
    v = mx.papadopoulos_critical_plane(tension)
    assert v == pytest.approx(sa / 2, rel=1e-6) and v <= sa / 2 * (1 + 1e-12)
    v = mx.papadopoulos_critical_plane(torsion, mx.line_rule(16, 32, 16))
    assert v == pytest.approx(ta, rel=1e-4) and v <= ta * (1 + 1e-12)
