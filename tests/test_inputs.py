"""Inputs a user cannot get silently wrong: a quoted number in a scene file, a path that does not exist, a
built-in scene's description after --set, and an unknown suite refused without building every scene."""
import pytest

from femcheck import cli, scene
from femcheck.errors import InputError


def test_a_quoted_number_in_a_scene_file_is_refused(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text('name = "s"\nkind = "line_contact"\n[geometry]\nradius = "0.01"\n[load]\nper_length = 1e6\n')
    with pytest.raises(InputError) as err:
        scene.load_scene(path)
    assert err.value.key == "geometry.radius" and "is a string in s.toml" in str(err.value)
    # --set values are text by nature and are converted
    assert scene.load_scene("hertz-line", {"geometry.radius": "0.02"})["geometry.radius"] == 0.02


def test_a_missing_path_says_no_such_file(tmp_path):
    with pytest.raises(InputError, match="no such file"):
        scene.load_scene(tmp_path / "nothing.toml")
    with pytest.raises(InputError, match="neither a built-in scene"):
        scene.load_scene("hertz-lin")


def test_a_modified_scene_says_so_before_its_description():
    sc = scene.load_scene("hertz-line", {"load.per_length": "2e6", "models.run": "analytic"})
    assert sc.description.startswith("Modified by load.per_length = 2e6: ")
    assert "models.run" not in sc.description.partition("\n")[0]
    again = sc.with_overrides({"geometry.radius": 0.02})
    assert again.description.count("Modified by") == 1
    assert scene.load_scene("hertz-line").description == scene.load_scene("hertz-line", {}).description


def test_an_unknown_suite_is_refused_without_building_a_scene(monkeypatch):
    def forbidden(*a, **k):
        raise AssertionError("a scene was built to refuse an unknown suite")
    monkeypatch.setattr(scene, "load_scene", forbidden)
    with pytest.raises(InputError, match="no scene is tagged 'nosuch'"):
        cli.suite("nosuch", None, False)
