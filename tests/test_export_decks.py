"""Every FE scene's exported deck: the Abaqus deck passes the keyword-format check, the CalculiX deck loads in
ccx (read, structure set up, the contact pair found in the first Newton iteration), and the small 2D decks solve
to the end with the scene's load carried.

Sizes and times measured at level 0 (CalculiX 2.20, one thread; deformable DOFs; ccx CPU to the first contact
evaluation / full solve): hertz-point C3D4 19.7k DOFs 1.3 s / 21 s; hertz-line CPE3 460, full 0.1 s; roller
C3D4 43.6k 2.3 s / 27 s; srb-normal C3D4 127k 4.4 s / > 15 min (the conformal 40:1 contact set chatters: 160
Newton iterations and step 1 at 37 %), C3D10 884k; layer-point C3D4 5.8k, full 2.8 s; layer-line CPE3 818, full
0.2 s; layer-rigid CPE3 270, full 0.06 s; cattaneo-2d CPE3 1650, full 1.1 s, CPE6 6.2k, full 32 s;
crb-rigid-rings CPE3 21.3k, full 3.1 s; crb-elastic-rings / crb-housing-arc CPE3 20.0k, load and find their
contacts but fail in the push step (too many cutbacks, 82 Newton iterations, 17 s).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from femcheck.analytic import hertz, thin_layer
from femcheck.errors import InputError
from femcheck.export import frd as frd_reader
from femcheck.export import inp, run
from femcheck.export.write import export
from femcheck.runner import resolve_scene

needs_ccx = pytest.mark.skipif(run.ccx() is None, reason=run.MISSING + ": decks are written and format-checked "
                                                                     "but not loaded")

# scene -> (element at order 1, load on the modelled part from the scene TOML (N or N/m), its dof)
SCENES = {
    "hertz-point": ("C3D4", 1000.0 / 4, 3),
    "hertz-elliptic": ("C3D4", None, 3),
    "hertz-line": ("CPE3", 1.0e6 / 2, 2),
    "roller-finite": ("C3D4", 3683.6 / 4, 3),
    "roller-crowned": ("C3D4", 3683.6 / 4, 3),
    "srb-normal": ("C3D4", 5500.0 / 2, 3),
    "layer-point": ("C3D4", 100.0 / 4, 3),
    "layer-line": ("CPE3", 1.0e5 / 2, 2),
    "layer-rigid": ("CPE3", 1.0e5 / 2, 2),
    "cattaneo-2d": ("CPE3", 1.0e6, 2),
    # bearing sections: F_r / l = 8900 N / 9.6 mm on the shaft, along +x (dof 1), pushed
    "crb-rigid-rings": ("CPE3", -8900.0 / 9.6e-3, 1),
    "crb-elastic-rings": ("CPE3", -8900.0 / 9.6e-3, 1),
    "crb-housing-arc": ("CPE3", -8900.0 / 9.6e-3, 1),
}
SLOW_START = {"srb-normal"}          # 42k-node meshes: several seconds to read


def _last_loads(cards) -> dict[tuple[int, int], float]:
    """{(node, dof): value} of the *CLOAD cards (later cards override earlier ones)."""
    out = {}
    for c in cards:
        if c.keyword == "CLOAD":
            for r in c.data:
                out[(int(r[0]), int(r[1]))] = float(r[2])
    return out


@pytest.fixture(scope="module")
def decks(tmp_path_factory):
    out = tmp_path_factory.mktemp("decks")
    return {name: Path(export(resolve_scene(name), "calculix", 0, 1, out / name)["deck"]) for name in SCENES}


@pytest.mark.parametrize("name", sorted(SCENES))
def test_deck_carries_the_scene_load(decks, name):
    element, load, dof = SCENES[name]
    cards = inp.parse(decks[name].read_text())
    assert inp.check(decks[name].read_text()) == []
    types = set(inp.element_types(cards).values())
    assert element in types
    loads = _last_loads(cards)
    assert loads, "no *CLOAD"
    total = -sum(v for (n, d), v in loads.items() if d == dof)
    if load is not None:
        # the scene TOML's load on the modelled part (quarter, half or full model); 12 significant digits
        per_contact = total / (2 if name == "srb-normal" else 1)
        assert per_contact == pytest.approx(load, rel=1e-11)


@needs_ccx
@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW_START else n
                                  for n in sorted(SCENES)])
def test_calculix_loads_the_deck_and_finds_the_contact(decks, name):
    r = run.run(decks[name], timeout=120, stop_at_contact=True)
    assert r.errors == [] and r.stopped, r.tail
    # step 1 pushes the indenter into the block: the first Newton iteration has contact elements (the push
    # overlaps at least the node under the indenter's tip; 1 on hertz-point at a/16, 33 to 178 elsewhere)
    assert r.springs[0] >= 1


@needs_ccx
@pytest.mark.parametrize("name", ["hertz-line", "layer-line", "layer-rigid", "cattaneo-2d", "crb-rigid-rings",
                                  pytest.param("layer-point", marks=pytest.mark.slow)])
def test_calculix_loads_the_quadratic_deck(tmp_path, name):
    """The quadratic decks (CPE6, C3D10) load too; measured at level 0: 31-422 contact springs in the first
    iteration, under 3 s of ccx each (hertz-point C3D10 143k DOFs 35 s and roller-finite C3D10 319k DOFs 61 s
    were checked once by hand, srb-normal C3D10 884k DOFs not)."""
    deck = Path(export(resolve_scene(name), "calculix", 0, 2, tmp_path)["deck"])
    r = run.run(deck, timeout=120, stop_at_contact=True)
    assert r.errors == [] and r.stopped, r.tail
    assert r.springs[0] >= 1


@needs_ccx
@pytest.mark.parametrize("name", ["hertz-line", "layer-line", "layer-rigid", "cattaneo-2d"])
def test_small_decks_solve_and_carry_the_load(decks, name):
    r = run.run(decks[name], timeout=120)
    assert r.finished, r.tail
    dat = frd_reader.read_dat(decks[name].with_suffix(".dat"))
    _, load, dof = SCENES[name]
    reaction = dat[("total force", "NBOTTOM")][0, dof]
    # load control: the clamped bottom carries the load on the modelled part (.dat: 7 significant digits)
    assert reaction == pytest.approx(load, rel=1e-6)


@needs_ccx
def test_cattaneo_deck_carries_the_tangential_load_and_the_hertz_peak(decks):
    """cattaneo-2d CPE3, level 0 (h = a/10): after step 3 the clamped bottom carries W' = 1 MN/m and Q' = 150 kN/m
    (the scene TOML; .dat 7 digits), and -S22 on the block's top peaks at Hertz's p0 = 1.916 GPa within 1 % (the
    CPE3 band of tests/test_export.py: +0.38 % measured on hertz-line at a/10; +0.4 % here)."""
    from femcheck.export.pressure import read

    deck = decks["cattaneo-2d"]
    if not deck.with_suffix(".frd").exists():
        assert run.run(deck, timeout=120).finished
    dat = frd_reader.read_dat(deck.with_suffix(".dat"))
    rf = dat[("total force", "NBOTTOM")][0]
    assert rf[2] == pytest.approx(1.0e6, rel=1e-6)
    assert -rf[1] == pytest.approx(1.5e5, rel=1e-6)
    h = hertz.line_contact(1.0e6, 0.010, 210e9 / (1 - 0.09) / 2)
    assert read(deck)["p_max"] == pytest.approx(h.p_max, rel=0.01)


@needs_ccx
@pytest.mark.parametrize("name", ["layer-line", "layer-rigid"])
def test_layered_line_agrees_with_femcheck_fe_within_both_estimates(tmp_path, name):
    """Two FE codes on the same mesh family (level 0, CPE6 against femcheck's stored P2 reference): p_max agrees
    within femcheck's error estimate plus twice CalculiX's fitted standard error (measured -0.031 % against 0.065 %
    + 0.08 % on layer-line, +0.009 % against 0.014 % + 0.03 % on layer-rigid)."""
    from femcheck.export.pressure import read
    from femcheck.runner import run as run_scene

    ref = run_scene(name, models=["fem"]).models["fem"]
    estimate = ref.stats["certificates"]["p_max"]["error_estimate"]
    deck = Path(export(resolve_scene(name), "calculix", 0, 2, tmp_path)["deck"])
    assert run.run(deck, timeout=120).finished
    r = read(deck)
    tol = estimate + 2.0 * r["p_max_std"] / r["p_max"]
    assert r["p_max"] == pytest.approx(ref.quantities["p_max"], rel=tol)


@needs_ccx
@pytest.mark.slow
def test_roller_finite_agrees_with_femcheck_fe_within_both_estimates(decks):
    """roller-finite, C3D4 at level 0 (a_H/4, 43.6k DOFs, ccx 27 s): CPRESS through femcheck's centre estimator
    (femcheck.fem.roller_contact.centre_quantities' window) against femcheck's stored P1 reference: measured
    p_centre +0.19 % (CalculiX's fitted std 1.4 %, femcheck's estimate 1.2 %), half-width +0.08 %; on the same
    level femcheck's P1 gave 1.2257 GPa / 133.64 um, CalculiX 1.2311 GPa / 133.79 um."""
    from femcheck.export.pressure import read_roller
    from femcheck.runner import run as run_scene

    ref = run_scene("roller-finite", models=["fem"]).models["fem"]
    deck = decks["roller-finite"]
    assert run.run(deck, timeout=300, threads=2).finished            # 2 CPUs: the slowest deck here
    q = read_roller(deck, ref.stats["hertz_half_width"], 0.0127)
    cert = ref.stats["certificates"]
    tol = cert["p_centre"]["error_estimate"] + 2.0 * q["p_centre_std"] / q["p_centre"]
    assert q["p_centre"] == pytest.approx(ref.quantities["p_centre"], rel=tol)
    tol = cert["half_width"]["error_estimate"] + 2.0 * q["half_width_std"] / q["half_width"]
    assert q["half_width"] == pytest.approx(ref.quantities["half_width"], rel=tol)
    assert q["total_force"] == pytest.approx(3683.6, rel=1e-4)


@needs_ccx
def test_rigid_ring_bearing_section_against_rigid_ring_theory(decks):
    """crb-rigid-rings: with rigid rings and the exact 2D roller law, rigid-ring theory is exact for the shaft's
    displacement (the scene's description); CalculiX CPE3 at level 0 (h = b/5.7) measured -1.7 % of it (31.33 um),
    so 3 %. The housing carries F' = 927 kN/m (.dat: 7 digits; the rollers' tangential constraints take 8e-5)."""
    from femcheck.export.scenes import build
    from femcheck.runner import resolve_scene as scene

    deck = decks["crb-rigid-rings"]
    assert run.run(deck, timeout=120).finished
    info = build(scene("crb-rigid-rings"), 0, 1).info
    dat = frd_reader.read_dat(deck.with_suffix(".dat"))
    shaft = info["initial_shift"] + dat[("displacements", "NREF")][0, 1]
    assert shaft == pytest.approx(info["rigid_ring"]["displacement"][0], rel=0.03)
    assert -dat[("total force", "NHOUSING")][0, 1] == pytest.approx(8900.0 / 9.6e-3, rel=1e-3)


@needs_ccx
def test_layer_rigid_peak_against_the_thin_layer_closed_form(decks):
    """layer-rigid (h/a = 0.09): Johnson's compressible thin-layer p0 within the scene's 5 % band for h/a <= 0.1
    (the scene's description); CalculiX CPE3 at level 0 (h = a/20) measured 3.41 GPa."""
    deck = decks["layer-rigid"]
    if not deck.with_suffix(".frd").exists():
        assert run.run(deck, timeout=120).finished
    from femcheck.export.pressure import read
    p = read(deck)["p_max"]
    closed = thin_layer.compressible(210e9, 0.3, 2e-6, 0.010, 1.0e5, "line")
    assert p == pytest.approx(closed.p_max, rel=0.05)
    # and far from the uncoated Hertz peak on steel (0.95 GPa): the layer is what the deck models
    assert p > 2.0 * hertz.line_contact(1.0e5, 0.010, 210e9 / (1 - 0.09)).p_max


@pytest.mark.parametrize("name", ["roller-crowned", "srb-normal", "layer-point", "layer-line", "cattaneo-2d"])
def test_abaqus_decks_of_the_other_kinds_pass_the_format_check(tmp_path, name):
    path = Path(export(resolve_scene(name), "abaqus", 0, 2, tmp_path)["deck"])
    text = path.read_text()
    assert inp.check(text) == []
    cards = inp.parse(text)
    rigid = [c for c in cards if c.keyword == "RIGID BODY"]
    assert all("ROT NODE" not in c.params for c in rigid)
    # a deformable face made rigid is a TIE NSET in Abaqus (srb-normal's rollers, cattaneo's cylinder flat)
    assert any("TIE NSET" in c.params for c in rigid) == (name in ("srb-normal", "cattaneo-2d"))
    friction = [c for c in cards if c.keyword == "FRICTION"]
    if name == "cattaneo-2d":
        # Abaqus' *FRICTION data line: mu alone (its second field would be a slip rate); mu = 0.3 (the TOML)
        assert len(friction) == 1 and [float(v) for v in friction[0].data[0]] == [0.3]
    else:
        assert friction == []
    assert set(inp.element_types(cards).values()) & {"C3D10", "CPE6"}


def test_quadratic_srb_contact_faces_lie_on_the_barrel(tmp_path):
    """The C3D10 deck's contact-face mid-side nodes are on the exact barrel surface (distance from the roller
    axis r - (R - sqrt(R^2 - y^2))) to rounding (12 digits of 10 mm: 1e-14 m), where straight mid-side nodes
    would sit h^2/(8 r) ~ 7e-11 m inside it at h = 74 um."""
    path = Path(export(resolve_scene("srb-normal"), "calculix", 0, 2, tmp_path)["deck"])
    cards = inp.parse(path.read_text())
    nodes = next(c for c in cards if c.keyword == "NODE")
    xyz = np.array([[float(v) for v in r[1:4]] for r in nodes.data])
    top = inp.node_sets(cards)["NTOP_I"] - 1
    x, y, z = xyz[top].T
    r, R = 0.5 * 0.0198, 0.1003
    miss = np.hypot(x, z - r) - (r - (R - np.sqrt(R * R - y * y)))
    assert np.abs(miss).max() < 1e-12


@pytest.mark.parametrize("scene, field", [("carter-2d", "kinematics.xi"), ("ehl-smooth", "SCENE")])
def test_scenes_that_cannot_be_exported_are_refused_naming_the_field(tmp_path, scene, field):
    with pytest.raises(InputError) as e:
        export(resolve_scene(scene), "calculix", 0, 1, tmp_path)
    assert e.value.key == field and len(str(e.value).splitlines()) == 1
    assert not any(tmp_path.iterdir())
