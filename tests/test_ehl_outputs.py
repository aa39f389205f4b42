"""The additional-pressure amplitudes of :mod:`femcheck.ehl.outputs` on fields whose shoulders are known: the
amplitude is read on the indent's shoulder (first positive maximum outwards from the hole), not on a steeper
feature farther out such as the outlet spike that an indent as large as the contact shifts (seed 004 neglects
the outlet spike, §3.3.1)."""
import numpy as np
import pytest

from femcheck.ehl import outputs

N = 129
X0, X1 = -2.5, 1.5


def field(A=0.1, front_gain=0.2, spike=0.3, xd=0.0):
    """Hole (-0.35, with ripples like the plateau of an EHL hole: a negative local maximum at r = 0.15 and a small
    positive one at r = 0.4, inside the hole's edge Phi/2), a shoulder ring at r = 0.6 of height A (1 + front_gain cos theta) around (xd, 0), and a one-cell-wide ridge of
    height ``spike`` on the outlet side of the contact, 0.8 from the contact centre."""
    x = np.linspace(X0, X1, N)
    y = np.linspace(-2.0, 2.0, N)
    h = x[1] - x[0]
    X, Y = np.meshgrid(x, y, indexing="ij")
    r, th = np.hypot(X - xd, Y), np.arctan2(Y, X - xd)
    dP = -0.35 * np.exp(-(r / 0.2) ** 2) + A * (1 + front_gain * np.cos(th)) * np.exp(-((r - 0.6) / 0.1) ** 2)
    dP += 0.1 * np.exp(-((r - 0.15) / 0.04) ** 2) + 0.02 * np.exp(-((r - 0.4) / 0.03) ** 2)
    R = np.hypot(X, Y)
    dP += spike * ((np.abs(R - 0.8) < 0.5 * h) & (X > 0.3 * R))
    return x, y, dP


def test_amplitudes_are_read_on_the_shoulders_not_on_the_outlet_ridge():
    A, g = 0.1, 0.2
    x, y, dP = field(A, g)
    a = outputs.additional_pressure(x, y, dP, 0.0, 0.0, 1.0)
    # the ring peaks at r = 0.6 (the hole adds < 1e-4 there): front A (1 + g) on the axis; rear and sides at
    # their sector edges (135 and 45 degrees): A (1 - g cos 45), A (1 + g cos 45)
    assert a["front"] == pytest.approx(A * (1 + g), rel=0.02)
    assert a["rear"] == pytest.approx(A * (1 - g / np.sqrt(2)), rel=0.02)
    assert a["lateral"] == pytest.approx(A * (1 + g / np.sqrt(2)), rel=0.02)
    assert a["amplitude"] == a["front"]
    assert a["centre"] == pytest.approx(-0.35, abs=1e-3) and dP[np.hypot(*np.meshgrid(x, y, indexing="ij")) < 0.3].max() < 0
    j0, i = N // 2, np.searchsorted(x, 0.4)
    assert dP[i, j0] > max(dP[i - 1, j0], dP[i + 1, j0], 0.0)           # the positive ripple in the hole
    # the ridge is the largest dP in the disc, but it is not a shoulder
    assert a["disc_max"] == pytest.approx(0.3 + A * (1 + g) * np.exp(-((0.8 - 0.6) / 0.1) ** 2), rel=0.05)


def test_axisymmetric_shoulder_equals_the_maximum():
    """Without an outer feature (the dry, axisymmetric case) the amplitude is the maximum of dP, as the dry model's."""
    x, y, dP = field(0.15, 0.0, 0.0, xd=-0.3)
    a = outputs.additional_pressure(x, y, dP, -0.3, 0.0, 1.0)
    for k in ("front", "rear", "lateral", "amplitude"):
        assert a[k] == pytest.approx(dP.max(), rel=5e-3)
    assert a["disc_max"] == pytest.approx(dP.max(), rel=1e-12)


def test_ray_without_a_shoulder_gives_nan_not_the_edge_value():
    """dP that only rises outwards (no shoulder within 1.5 Phi) has no amplitude."""
    x = np.linspace(X0, X1, N)
    y = np.linspace(-2.0, 2.0, N)
    X, Y = np.meshgrid(x, y, indexing="ij")
    dP = np.hypot(X, Y) ** 2 - 0.1
    a = outputs.additional_pressure(x, y, dP, 0.0, 0.0, 0.5)
    assert np.isnan(a["amplitude"]) and np.isnan(a["front"])
    assert a["disc_max"] == pytest.approx(0.75**2 - 0.1, abs=0.05)


def test_negative_ripples_beyond_the_hole_edge_are_not_shoulders():
    """A rippled negative flank between the hole edge (Phi/2) and the shoulder: its local maxima are negative and
    do not count; the shoulder ring (r = 0.75, the largest dP) does."""
    A = 0.08
    x = np.linspace(X0, X1, N)
    y = np.linspace(-2.0, 2.0, N)
    X, Y = np.meshgrid(x, y, indexing="ij")
    r = np.hypot(X, Y)
    dP = A * np.exp(-((r - 0.75) / 0.08) ** 2) - 0.1 * np.exp(-((r / 0.55) ** 4)) * (1 + 0.2 * np.sin(60 * r))
    a = outputs.additional_pressure(x, y, dP, 0.0, 0.0, 1.0)
    assert dP[r < 0.6].max() < 0 and 0.07 < dP.max() < A
    for k in ("front", "rear", "lateral"):
        assert a[k] == pytest.approx(dP.max(), rel=0.02)
