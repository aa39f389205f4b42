"""The stored 2D FE references of the line_tangential kind (femcheck.fem.friction_line): the exact 2D theory
(femcheck.cect.line, Panagiotopoulos' process) against them on dissimilar bodies, where neither Carter nor 2D
Cattaneo applies, and proof that each stored reference is what the current code computes.

Tests never re-solve a fine FE level (minutes on a loaded machine: these were the suite's slowest tests). The FE
numbers are read from references/ under the current code key; their currency is proved by re-solving the coarsest
mesh level alone (about a second, femcheck.reference_check): on the inputs recorded with the reference to 1e-6,
and on this machine's own meshes to twice the reference's level-0 error. A missing or stale reference fails with
the command that regenerates it (`femcheck run SCENE --set ... --models fem --rebuild --references DIR`).

The dissimilar pairs are stored as overrides of carter-2d / cattaneo-2d (as srb-rolling's mu = 0.3 case), not as
scenes of their own: the agreement is graded with the FE's own error estimate of each case plus 1 %, and the
steel-on-aluminium creep force is uncertified on either mesh sequence (a near cancellation), so a scene graded by
a fixed band would only ever report "reference uncertified". A user's `femcheck run carter-2d --set
materials.cylinder.rigid=true` finds the stored reference by its key.
"""
import pytest

import femcheck
from femcheck import reference_check, references
from femcheck.runner import model_key
from femcheck.scene import load_scene

RIGID_ON_STEEL = {"materials.cylinder.rigid": True}
STEEL_ON_ALUMINIUM = {"materials.block.E": 70e9, "materials.block.nu": 0.33}
FINER = {"numerics.fem_h_contact": 0.05}     # meshes 0.05, 0.025, 0.0125 a (default 0.1 ... 0.025 a)

# (scene, overrides the reference was solved with); solve times of the whole reference measured under the CPU lock
STORED = [
    pytest.param("carter-2d", None, id="carter-2d"),                                              # 9 s
    pytest.param("cattaneo-2d", None, id="cattaneo-2d"),                                          # 9 s
    pytest.param("carter-2d", RIGID_ON_STEEL, id="carter-2d-rigid-cylinder"),                     # 20-140 s
    pytest.param("cattaneo-2d", RIGID_ON_STEEL, id="cattaneo-2d-rigid-cylinder"),                 # 22 s
    pytest.param("carter-2d", STEEL_ON_ALUMINIUM, id="carter-2d-aluminium-block"),                # 19 s
    pytest.param("cattaneo-2d", STEEL_ON_ALUMINIUM, id="cattaneo-2d-aluminium-block"),            # 18 s
    pytest.param("carter-2d", {**STEEL_ON_ALUMINIUM, **FINER}, id="carter-2d-aluminium-block-finer"),   # 51 s
]


def _missing(c) -> str:
    return (f"references/ has no {c.scene} {c.model} entry for the current code (key {c.key[:16]}); regenerate it "
            f"with `{c.command}`")


def stored_fem(scene: str, over: dict):
    """The stored FE reference of ``scene`` under ``over`` for the current code key; fails (never re-solves)
    when there is none."""
    sc = load_scene(scene, over)
    ref = references.load(sc.kind, "fem", model_key(sc, "fem"))
    if ref is None:
        sets = "".join(f" --set {k}={v}" for k, v in over.items())
        pytest.fail(f"references/ has no {scene} fem entry for {over} and the current code; regenerate it with "
                    f"`femcheck run {scene}{sets} --models fem --rebuild --references {references.reference_dir()}`")
    return ref


@pytest.mark.parametrize("scene, params", STORED)
def test_stored_reference_reproduces_its_coarsest_level(scene, params):
    # level 0 on the recorded meshes, to 1e-6: the friction quantities (creep force or shift, adhesion or stick
    # zone) and the normal ones (p_max, half-width, load) with the mesh counts
    c = reference_check.check(scene, "fem", params=params)
    assert c.stored is not None, _missing(c)
    assert c.fresh.status == "ok", c.fresh.error
    compared = {q for _, q, *_ in c.compared}
    friction = {"creep_force_x", "adhesion_length"} if scene == "carter-2d" else {"shift", "stick_half_width"}
    assert friction | {"p_max", "half_width", "n_dofs"} <= compared, compared
    assert not c.mismatches, f"{scene} {params}: the stored reference is stale:\n  " + "\n  ".join(c.mismatches)
    certs = c.stored.stats["certificates"]
    assert certs and all({"value", "certified", "error_estimate", "note"} <= set(v) for v in certs.values())
    # a whole reference: three mesh levels and three blocks (the coarse re-solve has one of each)
    assert len(c.stored.stats["levels"]) == 3 and len(c.stored.stats["blocks"]) == 3


@pytest.mark.parametrize("scene, params", STORED)
def test_stored_reference_reproduces_on_this_machines_meshes(scene, params):
    c = reference_check.check(scene, "fem", params=params, replayed=False)
    assert c.stored is not None, _missing(c)
    assert c.fresh.status == "ok", c.fresh.error
    assert len(c.compared) >= 4
    assert not c.mismatches, (f"{scene} {params}: fresh meshes give level-0 numbers beyond twice the reference's "
                              f"own level-0 error:\n  " + "\n  ".join(c.mismatches + c.notes))


@pytest.mark.slow           # the exact model on three grids with the coupling iterations: about 2 s
@pytest.mark.parametrize("scene", ["carter-2d", "cattaneo-2d"])
@pytest.mark.parametrize("pair", ["rigid cylinder on steel", "steel on aluminium"])
def test_dissimilar_exact_theory_and_fe_agree(scene, pair):
    # The 2D exact theory (Panagiotopoulos' process, half-planes) and the stored 2D FE reference (two mirrored
    # half-plane blocks, full coupling, block extrapolation) on the scenes with dissimilar bodies.
    # Measured (exact vs FE): rigid/steel creep force -48.39 vs -48.26 kN/m (-0.3 %), shift 1.886e-8 vs
    # 1.910e-8 m (+1.3 %, FE estimate 8.9 %); steel/Al shift 2.206e-7 vs 2.220e-7 m (+0.6 %), creep force -63.55
    # vs -64.99 kN/m (+2.3 %, FE estimate 2.0 %, uncertified: a near-cancellation, kappa p0 = -1.09 xi, where
    # 0.05 % of p0 in the pressure change moves the force by 1 %). Tolerance: the FE's error estimate plus 1 %.
    # Before the finite-block extrapolation the FE gave -82.3 kN/m for the rigid cylinder. The coupling's sign
    # flipped in the exact model fails both creep forces (-297 and -238 kN/m); the shifts do not see it (a flip
    # of kappa mirrors the pressure tilt, |shift| is unchanged).
    over = RIGID_ON_STEEL if pair.startswith("rigid") else STEEL_ON_ALUMINIUM
    fe = stored_fem(scene, over)
    ex = femcheck.run(scene, over, models=["exact"]).models["exact"]
    assert ex.status == "ok" and ex.stats["process"] == "Panagiotopoulos"
    q = "creep_force_x" if scene == "carter-2d" else "shift"
    err = fe.stats["certificates"][q]["error_estimate"]
    assert fe.quantities[q] == pytest.approx(ex.quantities[q], rel=err + 0.01)


@pytest.mark.slow
def test_steel_on_aluminium_creep_force_with_finer_fe_meshes():
    # Exact and FE within 2 % on the dissimilar creep force. At carter-2d's xi = 0.005 the steel-on-aluminium
    # creep force is a near cancellation (kappa p0 = -1.09 xi): the default FE meshes (0.1 to 0.025 a) give
    # +2.3 %; with meshes 0.05 to 0.0125 a the FE is within 0.54 % of the exact theory (its levels are still not in
    # the asymptotic range, so the FE value stays uncertified).
    fe = stored_fem("carter-2d", {**STEEL_ON_ALUMINIUM, **FINER})
    assert [round(lv["h_over_a"], 6) for lv in fe.stats["levels"]] == [0.05, 0.025, 0.0125]
    ex = femcheck.run("carter-2d", STEEL_ON_ALUMINIUM, models=["exact"]).models["exact"]
    assert fe.quantities["creep_force_x"] == pytest.approx(ex.quantities["creep_force_x"], rel=0.02)
