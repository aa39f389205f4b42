"""Four-row tapered bearing in an elastic chock on a flexible roll (femcheck.bem.mill_chock; spec bearing-load P3).

Independent values: the rigid-ring ISO/TS 16281 equilibrium (stiff bodies), the mirror symmetry of a bearing whose
rows alternate (row r at z with sign s is the mirror of the row at -z with -s: shares must mirror when the chock
is supported in the middle and the roll is stiff), the patch load's resultant (the contact normal of each row),
static equilibrium, and the beam's closed form through femcheck.analytic.roll_neck (tested there).
"""
import numpy as np
import pytest

from femcheck.analytic.roll_neck import ShaftSegment
from femcheck.bem import mill_chock as mc
from femcheck.fem import ring3d_compliance as rc
from femcheck.materials import Elastic

STEEL = Elastic(210e9, 0.3)
ALPHA = np.deg2rad(15.0)
# seed 003's bearing as reconstructed in spec bearing-load 2.4 (coarse: 4 slices per roller)
BEARING = mc.MillBearing(20, (-0.0675, -0.0225, 0.0225, 0.0675), (1, -1, 1, -1), ALPHA, 0.0625, 0.0266, 0.0176, 4,
                         0.0713, 0.0537, 0.045, 0.18)
LOAD = 73.8e3


def chock(zc=0.0, length=0.06, steel=STEEL):
    return mc.Chock(0.12, (zc - length / 2, zc + length / 2), np.pi / 20 * 3, steel)


def neck(steel=STEEL):
    return mc.RollNeck((ShaftSegment(-0.09, 0.11, 0.09), ShaftSegment(0.11, 0.165, 0.21)), 0.165, steel)


@pytest.fixture(scope="module")
def parts():
    cc = mc.chock_compliance(BEARING, chock())
    ci = mc.cone_compliance(BEARING, STEEL)
    cn = mc.roll_compliance(BEARING, neck())
    return cc, ci, cn


def test_patch_loads_act_along_each_rows_contact_normal():
    # the resultant of b_ijk is the contact normal n_i = cos(a) e_r + s_i sin(a) e_z, up to the facets being
    # chords: the patch's two facets of angle a_c have the area of the arc times sin(a_c/2)/(a_c/2) (axial part,
    # exact), and e_r turns over the patch (radial part: a further sin(a_c)/a_c, to 7e-9 on these chords)
    spec = mc._spec(BEARING, BEARING.outer_race, 0.12, mc.Mesh3D(), 2)
    fe = rc.RingFE(spec, STEEL, "housing", np.pi, contact_angle=ALPHA, row_signs=BEARING.signs)
    system = rc.ring_system(fe)
    B = system.B
    fx, fy, fz = (B[c::3].sum(axis=0) for c in range(3))
    ns, Z = BEARING.slices, BEARING.rollers
    for i, s in enumerate(BEARING.signs):
        for j in (0, 5):
            col = (i * Z + j) * ns + 1
            psi = BEARING.psi[j]
            radial = fx[col] * np.cos(psi) + fy[col] * np.sin(psi)
            across = -fx[col] * np.sin(psi) + fy[col] * np.cos(psi)
            a_c = mc.Mesh3D().patch_half_angle
            assert fz[col] / (s * np.sin(ALPHA)) == pytest.approx(np.sin(a_c / 2) / (a_c / 2), rel=1e-9)
            assert radial / np.cos(ALPHA) / (np.sin(a_c / 2) / (a_c / 2)) == pytest.approx(np.sin(a_c) / a_c,
                                                                                          abs=1e-7)
            assert abs(across) < 1e-9


def test_stiff_bodies_recover_the_rigid_rows(parts):
    cc, ci, cn = parts
    rigid = mc.solve(BEARING, None, LOAD)
    stiff = mc.solve(BEARING, (cc.C + ci.C + cn) / 1e4, LOAD)      # E x 1e4 everywhere: compliance / 1e4
    assert np.allclose(rigid.row_shares, 25.0, atol=1e-6)          # no tilt, F_a = 0: alternate rows alike
    assert np.abs(stiff.row_shares - rigid.row_shares).max() < 0.05   # percentage points (elastic ones move ~10)
    assert stiff.row_radial.sum() == pytest.approx(LOAD, rel=1e-9)


def test_rigid_rows_on_a_seat_follow_the_lever_rule():
    """Rigid bodies, the chock on a spherical seat at z_e: the rows carry no moment about it, so sum_r F_r z_r =
    z_e F_r (lever rule); a seat towards the mill roll (+z) loads rows 3, 4 more than rows 1, 2."""
    for z_e in (0.0, 0.0254, -0.03):
        sol = mc.solve(BEARING, None, LOAD, seat=z_e)
        z_rows = np.array(BEARING.row_z)
        # axial components of tapered rows add a moment s sin(a) q R about the axis' normal: the lever rule holds
        # for the whole contact force; check it on the rows' radial forces with that part added
        q = sol.slice_loads
        ca, sa = np.cos(ALPHA), np.sin(ALPHA)
        cp = np.cos(BEARING.psi)
        z_sl = z_rows[:, None] + BEARING.x[None, :]
        moment = (ca * (q * cp[None, :, None] * z_sl[:, None, :]).sum()
                  - sa * BEARING.pitch_radius * (q.sum(axis=2) * cp[None, :] * np.array(BEARING.signs)[:, None]).sum())
        assert moment == pytest.approx(z_e * LOAD, abs=1e-9 * LOAD * 0.1)
    mill = mc.solve(BEARING, None, LOAD, seat=0.0254).row_shares
    assert mill[2] + mill[3] > 60.0 > mill[0] + mill[1]


def test_centred_support_and_stiff_roll_share_mirror_symmetrically(parts):
    cc, ci, _ = parts
    sol = mc.solve(BEARING, cc.C + ci.C, LOAD)
    sh = sol.row_shares
    assert sh[0] == pytest.approx(sh[3], abs=1e-6)
    assert sh[1] == pytest.approx(sh[2], abs=1e-6)
    # the middle rows sit on the support: the chock is stiffest there
    assert sh[1] > sh[0] + 1.0


def test_flexible_roll_shifts_load_towards_its_body_and_equilibrium_holds(parts):
    cc, ci, cn = parts
    stiff_roll = mc.solve(BEARING, cc.C + ci.C, LOAD, axial_load=2000.0)
    sol = mc.solve(BEARING, cc.C + ci.C + cn, LOAD, axial_load=2000.0)
    # the neck bends most at its free (operating-side) end: rows 3, 4 (mill side) take more, rows 1, 2 less
    assert sol.row_shares[3] > stiff_roll.row_shares[3] + 1.0
    assert sol.row_shares[0] < stiff_roll.row_shares[0] - 1.0
    q = sol.slice_loads
    ca, sa = np.cos(ALPHA), np.sin(ALPHA)
    fx = ca * (q.sum(axis=2) * np.cos(BEARING.psi)).sum()
    fa = sa * (q.sum(axis=(1, 2)) * np.array(BEARING.signs)).sum()
    assert fx == pytest.approx(LOAD, rel=1e-9)
    assert fa == pytest.approx(2000.0, rel=1e-7)
    assert sol.iterations < 30


def test_support_moved_towards_the_mill_roll_loads_the_mill_side_rows(parts):
    cc_mill = mc.chock_compliance(BEARING, chock(0.045))
    mid = mc.solve(BEARING, parts[0].C, LOAD)
    mill = mc.solve(BEARING, cc_mill.C, LOAD)
    assert mill.row_shares[2] + mill.row_shares[3] > mid.row_shares[2] + mid.row_shares[3] + 2.0


# --- the scene model (trb-mill-4row, flexible_chock) ----------------------------------------------------------------

def test_scene_reproduces_the_measured_row_ordering_that_rigid_rings_miss():
    """seed 003 Table 3: row 3 carries more than row 4 (40.79 vs 32.67 %, measured). With the same load line and
    axial load, rigid rings give row 4 above row 3; the elastic chock and roll turn it round (spec bearing-load
    2.3: 'that needs the chock/neck elasticity')."""
    import femcheck
    from grading import assert_fully_graded

    res = femcheck.run("trb-mill-4row")
    assert_fully_graded(res, "trb-mill-4row")
    flex, rigid = res.models["flexible_chock"].quantities, res.models["rigid_ring"].quantities
    assert sum(flex[f"row_share_{r}"] for r in range(1, 5)) == pytest.approx(100.0, abs=1e-9)
    assert flex["total_force"] == pytest.approx(73.8e3, rel=1e-9)
    assert rigid["row_share_3"] < rigid["row_share_4"]
    assert flex["row_share_3"] > flex["row_share_4"] + 3.0
    # the rows the paper's model gets within 10 % (seed 003's claim), this model does too: rows 2-4
    meas = load_measured()
    for r in (2, 3, 4):
        assert abs(flex[f"row_share_{r}"] - meas[r - 1]) / meas[r - 1] < 0.10


def load_measured():
    from femcheck.scene import load_scene
    return load_scene("trb-mill-4row")["paper.row_shares_measured"]


@pytest.mark.parametrize("setting, key", [
    ("chock.outer_radius=0.05", "chock.outer_radius"),
    ("load.offset=0.08", "load.offset"),
    ("roll.neck_length=0.05", "roll.neck_length"),
    ("chock.seat=hinge", "chock.seat"),
])
def test_flexible_chock_bad_input_is_one_line_exit_2(setting, key):
    import subprocess
    import sys
    r = subprocess.run([sys.executable, "-m", "femcheck.cli", "run", "trb-mill-4row", "--models",
                        "flexible_chock", "--set", setting], capture_output=True, text=True)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and key in r.stderr and "allowed" in r.stderr
