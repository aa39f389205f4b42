"""Scene loading, --set overrides and the refusal of bad input (one line naming key and range)."""
import pytest
from hypothesis import given
from hypothesis import strategies as st

from femcheck.errors import InputError
from femcheck.scene import load_scene, parse_overrides


def test_builtin_scene_loads_with_defaults():
    s = load_scene("hertz-line")
    assert s.kind == "line_contact" and "quick" in s.tags
    assert s["geometry.radius"] == 0.01 and s["numerics.fem_order"] == 2
    assert s.material("cylinder").E == 210e9


def test_overrides_are_typed():
    s = load_scene("hertz-line", parse_overrides(["load.per_length=2.5e6", "materials.cylinder.rigid=true",
                                                  "numerics.fem_levels=4", "models.run=analytic,bem"]))
    assert s["load.per_length"] == 2.5e6
    assert s["materials.cylinder.rigid"] is True
    assert s["numerics.fem_levels"] == 4
    assert s["models.run"] == ["analytic", "bem"]


@pytest.mark.parametrize("key,value,fragment", [
    ("nope.key", "1", "unknown key"),
    ("materials.block.E", "0", "(0, inf) Pa"),
    ("materials.block.E", "-2e9", "(0, inf) Pa"),
    ("materials.cylinder.nu", "0.5", "(-1, 0.5)"),
    ("materials.block.nu", "-1", "(-1, 0.5)"),
    ("load.per_length", "0", "(0, inf) N/m"),
    ("load.per_length", "-5", "(0, inf) N/m"),
    ("geometry.radius", "0", "(0, inf) m"),
    ("geometry.radius", "abc", "(0, inf) m"),
    ("numerics.fem_levels", "2.5", "[1, 6]"),
    ("numerics.fem_method", "magic", "active_set, penalty"),
    ("materials.cylinder.rigid", "maybe", "true or false"),
    ("numerics.fem_block_width", "10", "[40, 1000]"),
    ("load.per_length", "1e12", "a/R"),            # a contact too large for half-space theory
])
def test_bad_input_names_key_and_range(key, value, fragment):
    with pytest.raises(InputError) as err:
        load_scene("hertz-line", {key: value})
    msg = str(err.value)
    assert msg.startswith(key) and fragment in msg and "\n" not in msg


def test_oversized_contact_message_gives_admissible_load():
    with pytest.raises(InputError, match=r"allowed \(0, 9\.06\d*e\+06\] N/m"):
        load_scene("hertz-line", {"load.per_length": "2e7"})


@given(st.floats(-0.999, 0.4999))
def test_any_admissible_poisson_ratio_is_accepted(nu):
    assert load_scene("hertz-line", {"materials.block.nu": nu})["materials.block.nu"] == nu


@given(st.one_of(st.floats(max_value=-1.0), st.floats(min_value=0.5)))
def test_inadmissible_poisson_ratio_is_refused(nu):
    with pytest.raises(InputError, match="materials.block.nu"):
        load_scene("hertz-line", {"materials.block.nu": nu})


def test_malformed_set_and_unknown_scene():
    with pytest.raises(InputError, match="KEY=VALUE"):
        parse_overrides(["load.per_length"])
    with pytest.raises(InputError, match="neither a built-in scene"):
        load_scene("no-such-scene")


def test_scene_file_from_path(tmp_path):
    f = tmp_path / "soft.toml"
    f.write_text('kind = "line_contact"\n[geometry]\nradius = 0.005\n[materials.cylinder]\nrigid = true\n'
                 '[materials.block]\nE = 2e9\nnu = 0.45\n[load]\nper_length = 1e3\n')
    s = load_scene(f)
    assert s.name == "soft" and s.material("cylinder").rigid
