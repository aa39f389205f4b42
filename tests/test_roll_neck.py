"""Roll-neck beam flexibility (femcheck.analytic.roll_neck) against the closed forms of a Timoshenko cantilever.

Independent values: Euler-Bernoulli cantilever formulas (Roark, *Formulas for Stress and Strain*, Table 8.1 cases
1a/3a) plus the shear deflection V x/(k G A) (Timoshenko & Gere, *Mechanics of Materials*, sec. 9.11), and for a
stepped shaft the unit-load (Maxwell-Mohr) integrals done by hand. The element is exact at the nodes for nodal
loads, so the tolerances are round-off (1e-9 relative).
"""
import numpy as np
import pytest

from femcheck.analytic.roll_neck import ShaftSegment, cowper_circle, flexibility, neck_compliance, slice_map

E, NU = 210e9, 0.3
G = E / (2 * (1 + NU))
D = 0.09
I, A = np.pi * D**4 / 64, np.pi * D**2 / 4
KGA = cowper_circle(NU) * G * A


def test_cowper_coefficient_of_a_circle():
    # Cowper 1966 Table 1: solid circle k = 6(1+nu)/(7+6nu); nu = 0.3 -> 0.8864
    assert cowper_circle(0.3) == pytest.approx(7.8 / 8.8, rel=1e-12)


@pytest.mark.parametrize("clamp_side", [+1, -1])
def test_tip_force_and_moment_of_a_uniform_cantilever(clamp_side):
    L = 0.2
    z_clamp = clamp_side * L / 2
    tip = -z_clamp
    nodes = np.array([tip, 0.0])
    F = flexibility(nodes, [ShaftSegment(-L / 2, L / 2, D)], z_clamp, E, NU)
    t = 0                                          # tip node's DOFs 0..4
    # force P_x at the tip: w = P L^3/(3EI) + P L/(kGA); slope dw/dz at the tip = -clamp_side P L^2/(2EI)
    assert F[t + 0, t + 0] == pytest.approx(L**3 / (3 * E * I) + L / KGA, rel=1e-9)
    assert F[t + 1, t + 1] == pytest.approx(L**3 / (3 * E * I) + L / KGA, rel=1e-9)
    # theta_y = u_x' ; theta_x = -u_y'
    assert F[t + 4, t + 0] == pytest.approx(-clamp_side * L**2 / (2 * E * I), rel=1e-9)
    assert F[t + 3, t + 1] == pytest.approx(clamp_side * L**2 / (2 * E * I), rel=1e-9)
    # moment at the tip: rotation M L/(EI); axial force: P L/(EA)
    assert F[t + 4, t + 4] == pytest.approx(L / (E * I), rel=1e-9)
    assert F[t + 3, t + 3] == pytest.approx(L / (E * I), rel=1e-9)
    assert F[t + 2, t + 2] == pytest.approx(L / (E * A), rel=1e-9)
    # no coupling between the two bending planes, nor with the axial DOF
    assert abs(F[t + 0, t + 1]) < 1e-12 * F[t, t]
    assert abs(F[t + 2, t + 0]) < 1e-12 * F[t, t]
    # load at the tip, deflection at the mid node (x = L/2 from the clamp, a = L): x^2 (3a - x)/(6EI) + x/(kGA)
    x, a = L / 2, L
    assert F[5 + 0, 0] == pytest.approx(x**2 * (3 * a - x) / (6 * E * I) + x / KGA, rel=1e-9)
    assert np.allclose(F, F.T, rtol=0, atol=1e-12 * np.abs(F).max())


def test_stepped_shaft_by_the_unit_load_method():
    # neck (D) over 0 <= s <= L1 from the tip, body (D2) over L1 <= s <= L1 + L2, clamp at the far end;
    # tip deflection under a tip force: int_0^L s^2/(EI(s)) ds + int ds/(kGA(s))
    L1, L2, D2 = 0.25, 0.055, 0.21
    I2, A2 = np.pi * D2**4 / 64, np.pi * D2**2 / 4
    KGA2 = cowper_circle(NU) * G * A2
    segs = [ShaftSegment(-0.09, -0.09 + L1, D), ShaftSegment(-0.09 + L1, -0.09 + L1 + L2, D2)]
    F = flexibility(np.array([-0.09]), segs, -0.09 + L1 + L2, E, NU)
    Ltot = L1 + L2
    bending = L1**3 / (3 * E * I) + (Ltot**3 - L1**3) / (3 * E * I2)
    shear = L1 / KGA + L2 / KGA2
    assert F[0, 0] == pytest.approx(bending + shear, rel=1e-9)


def test_slice_compliance_is_symmetric_positive_and_maps_a_row_load_to_the_beam():
    psi = 2 * np.pi * np.arange(20) / 20
    xk = (np.arange(4) - 1.5) * 0.005
    row_z = np.array([-0.0675, -0.0225, 0.0225, 0.0675])
    signs = np.array([1, -1, 1, -1])
    alpha, R = np.deg2rad(15), 0.0625
    segs = [ShaftSegment(-0.09, 0.11, D), ShaftSegment(0.11, 0.165, 0.21)]
    C = neck_compliance(psi, xk, row_z, signs, alpha, R, segs, 0.165, E, NU)
    assert np.allclose(C, C.T, atol=1e-14 * np.abs(C).max())
    assert np.linalg.eigvalsh(C).min() > -1e-12 * np.abs(C).max()
    # a unit slice load on roller 0 (psi = 0) of row 1: the generalised force on its section is
    # -(cos a, 0, s sin a, 0, -s sin a R); its own approach change is g F g^T by the beam's closed forms
    Gl, nodes = slice_map(psi, xk, row_z, signs, alpha, R)
    m = 0                                               # row 0, roller 0, slice 0
    z = row_z[0] + xk[0]
    F = flexibility(np.array([z]), segs, 0.165, E, NU)
    g = np.array([np.cos(alpha), 0.0, np.sin(alpha), 0.0, -np.sin(alpha) * R])
    assert C[m, m] == pytest.approx(g @ F @ g, rel=1e-9)
    assert np.count_nonzero(Gl[m]) == 3                 # psi = 0: no y-plane terms
