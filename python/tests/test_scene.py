"""``goniolight.Scene``: a scene loaded once or built from a dict gives what its file gives."""

import tomllib

import numpy as np
import pytest

import goniolight
from test_goniolight import ROOT

BOX = ROOT / "assets" / "scenes" / "box_room.toml"
BOX_CALC = ROOT / "assets" / "scenes" / "box_room_calc.toml"
POINTS = np.array([[1.0, 1.0, 0.8, 0, 0, 1], [3.0, 2.0, 0.0, 0, 0, 1], [0.0, 2.0, 1.5, 1, 0, 0]])


def from_its_dict(path):
    """The scene of ``path`` built from the dict ``tomllib`` reads from it."""
    return goniolight.Scene.from_dict(tomllib.loads(path.read_text()), base=path.parent,
                                      name=path.name)


COARSE = {"converge": 0.9, "texel_density": 4.0}


def test_a_scene_from_the_dict_of_its_file_calculates_as_the_file():
    # The scene's observers need the interreflected light: the same solve on the same GPU.
    expected = goniolight.calc(BOX_CALC, solver=COARSE)
    scene = from_its_dict(BOX_CALC)
    assert scene.path == str(BOX_CALC) and len(scene.grids) == len(expected["grids"])
    got = goniolight.calc(scene, solver=COARSE)
    got_values = [g.pop("values") for g in got["grids"]]
    want_values = [g.pop("values") for g in expected["grids"]]
    assert got == expected
    for a, b in zip(got_values, want_values):
        np.testing.assert_array_equal(a, b)
    assert expected["grids"][0]["emin"] > 0 and expected["observers"][0]["ugr"] > 0


def test_a_loaded_scene_lights_points_and_renders_as_its_file():
    scene = goniolight.Scene.load(BOX)
    assert scene.luminaires == 1 and scene.triangles > 0 and scene.warnings == []
    np.testing.assert_array_equal(goniolight.illuminance(scene, POINTS, cpu=True),
                                  goniolight.illuminance(BOX, POINTS, cpu=True))
    np.testing.assert_array_equal(goniolight.render(scene, width=64, height=48).image,
                                  goniolight.render(BOX, width=64, height=48).image)


def test_a_dict_with_moved_luminaire_changes_the_light_as_expected():
    # Raising the luminaire by d lowers the direct lux under it by (h / (h + d))² for a
    # point straight below (the same intensity straight down).
    d = tomllib.loads(BOX.read_text())
    below = np.array([[d["luminaire"][0]["position"][0], d["luminaire"][0]["position"][1],
                       0.0, 0, 0, 1]])
    near = goniolight.illuminance(from_its_dict(BOX), below, cpu=True, shadows="none")[0]
    h = d["luminaire"][0]["position"][2]
    d["luminaire"][0]["position"][2] = h + 1.0
    far = goniolight.illuminance(goniolight.Scene.from_dict(d, base=BOX.parent), below,
                                 cpu=True, shadows="none")[0]
    assert far == pytest.approx(near * (h / (h + 1.0)) ** 2, rel=1e-9)


def test_a_bad_dict_names_the_key_and_a_missing_file_names_the_file():
    with pytest.raises(ValueError, match="modle"):
        goniolight.Scene.from_dict({"modle": [{"path": "box_room.obj"}]}, base=BOX.parent)
    with pytest.raises(ValueError, match="no_such.toml"):
        goniolight.Scene.load(BOX.parent / "no_such.toml")


def test_refusals_name_the_keyword_not_the_commands_flag():
    # The scene has observers: UGR needs the interreflected light.
    with pytest.raises(ValueError) as e:
        goniolight.calc(BOX_CALC, cpu=True, indirect="none")
    assert "`indirect` radiosity" in str(e.value) and "--" not in str(e.value)
