"""groove-rolling in deep grooves: the applicability limit is the solved conformal contact's half-angle on the
groove (50 deg), not Hertz's estimate of it. A ball of radius 100.3 mm in a groove 1.002 times wider on a straight
rail (the scene's crown radius; a barrel of 9.9 mm rolling radius ends 25.7 deg from its apex, so only a body whose
crown reaches past 45 deg can carry such a contact) runs at a 45 deg half-angle; a load beyond the limit is one
line naming load.normal, exit 2. Numbers: docs/notes/groove-deep.md."""
import subprocess
import sys

import numpy as np
import pytest

import femcheck
from femcheck.analytic.hertz import elliptic_contact
from femcheck.errors import InputError
from femcheck.problems import groove_rolling as gr
from femcheck.scene import load_scene

BALL = {"geometry.rolling_radius": 0.1003, "geometry.ring_curvature": 0.0,
        "geometry.groove_radius": 0.1003 * 1.002}
LOAD_45 = 4.074e5          # N: solved half-angle 45.0 deg (frictionless check grid 21 x 41 and cect 41 x 81)
LIMIT = 6.270e5            # N: the largest load allowed, where the solved half-angle reaches 50 deg (measured)
FE_HALF_45 = 45.18         # deg: the fem model's level 11 x 21 at LOAD_45 (docs/notes/groove-deep.md)


def test_ball_in_a_deep_groove_runs_at_45_deg():
    # Hertz's estimate of this contact: b / r_g = 52.9 deg (> 30 deg, the former limit, and > 50 deg) and
    # b = 0.93 of the ball's radius (> 0.8): refused before, although the solved patch spans +-45 deg
    p = load_scene("groove-rolling", {**BALL, "load.normal": LOAD_45}).params
    rx, ry = gr.geometry(p).hertz_radii
    h = elliptic_contact(LOAD_45, rx, ry, gr._constants(p).contact_modulus)
    assert np.degrees(h.semi_axis_y / p["geometry.groove_radius"]) > 50.0
    res = femcheck.run("groove-rolling", {**BALL, "load.normal": LOAD_45}, models=["cect"])
    c = res.models["cect"]
    assert c.status == "ok" and c.stats["free_rolling_residual"] < 1e-7
    assert c.quantities["total_force"] == pytest.approx(LOAD_45, rel=1e-7)
    half = np.degrees(c.quantities["angle_span"]) / 2
    # independent value: the frictional FE reference of this scene (finite ball slice and rail segment, its own
    # compliances and contact solver), level 11 x 21 with numerics.fem_body_length = 2.2 b_H (the longest body the
    # FE meshes at this load; its next level does not fit on it): 45.18 deg. The developed half-space cect is
    # 0.4 % below it (41 x 81: 45.01 deg; the angle-corrected blanco 45.84 deg, +1.5 %); band 1 %
    assert half == pytest.approx(FE_HALF_45, rel=0.01)
    assert 44.0 < half < 46.0
    # the validation's solve (frictionless, 21 x 41 cells) is the same contact within 0.1 %
    assert np.degrees(gr._extent(p, LOAD_45).half_angle) == pytest.approx(half, rel=1e-3)


def test_load_beyond_the_solved_limit_is_refused_in_one_line():
    load_scene("groove-rolling", {**BALL, "load.normal": 0.995 * LIMIT})
    with pytest.raises(InputError) as err:
        load_scene("groove-rolling", {**BALL, "load.normal": 1.005 * LIMIT})
    msg = str(err.value)
    assert err.value.key == "load.normal" and "\n" not in msg
    assert "solved contact half-angle" in msg and "/ 50 deg" in msg
    allowed = float(msg.split("allowed: (0, ")[1].split("]")[0])
    assert allowed == pytest.approx(LIMIT, rel=2e-3)
    r = subprocess.run([sys.executable, "-m", "femcheck.cli", "run", "groove-rolling", "--models", "cect",
                        *[a for k, v in BALL.items() for a in ("--set", f"{k}={v!r}")],
                        "--set", f"load.normal={1.005 * LIMIT:.6g}"], capture_output=True, text=True)
    assert r.returncode == 2 and r.stderr.strip().count("\n") == 0, r.stderr
    assert r.stderr.startswith("load.normal") or "load.normal:" in r.stderr
    assert "allowed: (0, " in r.stderr and "Traceback" not in r.stderr
