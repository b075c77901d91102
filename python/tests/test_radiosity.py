"""The radiosity solution from Python equals the command line's, option for option."""

import json
import math

import numpy as np
import pytest

import goniolight
from goniolight import _native

from test_goniolight import ROOT, cli

BOX_CALC = ROOT / "assets" / "scenes" / "box_room_calc.toml"
FURNISHED = ROOT / "assets" / "scenes" / "furnished_room.toml"
# Lit by its [sky] alone: the daylight through its window, interreflected.
SIDE_LIT = ROOT / "assets" / "scenes" / "side_lit_room.toml"
# Coarse and not fully converged: the same work on both sides, and quick on lavapipe.
FLAGS = {"converge": 0.9, "texel_density": 4.0}


def grid_points(z=0.8, n=4, extent=(0.5, 3.5)):
    xs = np.linspace(*extent, n)
    return np.array([[x, y, z, 0.0, 0.0, 1.0] for x in xs for y in xs])


def command_lux(scene, pts, **flags):
    args = ["radiosity", str(scene), "--points"]
    for k, v in flags.items():
        args += ["--" + k.replace("_", "-"), str(v)]
    text = "".join(" ".join(repr(float(v)) for v in p) + "\n" for p in pts)
    return np.asarray([float(v) for v in cli(*args, stdin=text).split()])


@pytest.mark.parametrize("scene", [BOX_CALC, FURNISHED, SIDE_LIT],
                         ids=["box_room_calc", "furnished_room", "side_lit_room"])
def test_lux_at_points_equals_radiosity_points(scene):
    pts = grid_points()
    expected = command_lux(scene, pts, **FLAGS)
    sol = goniolight.radiosity(scene, **FLAGS)
    assert sol.stop_reason == "converged"
    assert sol.convergence >= 0.9
    lux = sol.lux(pts)
    # The command prints six decimals; both solve on the same GPU in the same order.
    np.testing.assert_allclose(lux, expected, rtol=1e-4, atol=5e-6)
    assert (lux > 0).all()
    # The interreflected part is a real share of it, below the total.
    inter = sol.interreflected_lux(pts)
    assert (inter > 0).all() and (inter < lux).all()


def test_every_keyword_defaults_to_the_commands_default():
    import inspect

    defaults = json.loads(_native.radiosity_defaults_json())
    params = inspect.signature(goniolight.radiosity).parameters
    for name, value in defaults.items():
        if name == "importance_time_limit":  # the viewer's; the command has no flag
            continue
        given = params[name].default
        if isinstance(value, list):
            given = list(given)
        assert given == value, f"{name}: {given!r} vs the library's {value!r}"


def test_a_bad_option_names_its_field():
    with pytest.raises(ValueError, match=r"map_size 8 is not in 16\.\.=4096"):
        goniolight.radiosity(BOX_CALC, map_size=8)
    with pytest.raises(ValueError, match="unknown variant"):
        goniolight.radiosity(BOX_CALC, visibility="cubemap")


def test_progress_shot_limit_log_and_export(tmp_path):
    seen = []
    sol = goniolight.radiosity(BOX_CALC, max_shots=5, texel_density=4.0,
                               progress=lambda shot, c: seen.append((shot, c)))
    assert sol.stop_reason == "shot limit reached"
    assert [s for s, _ in seen] == list(range(6))
    conv = [c for _, c in seen]
    assert conv == sorted(conv) and conv[0] == 0.0 and conv[-1] > 0.0
    log = sol.log
    np.testing.assert_array_equal(log["shot"], np.arange(6))
    assert math.isclose(log["convergence"][-1], sol.convergence, rel_tol=1e-6)
    glb = tmp_path / "box.glb"
    sol.export(glb)
    assert glb.read_bytes()[:4] == b"glTF"


def test_a_raising_progress_callable_stops_the_solve():
    def fail(shot, c):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        goniolight.radiosity(BOX_CALC, texel_density=4.0, progress=fail)


def calc_command(scene, out, *flags):
    cli("calc", str(scene), "--out", str(out), *flags)
    return json.loads((out / "calc.json").read_text())


def csv_values(path):
    rows = path.read_text().splitlines()[1:]
    return np.asarray([float(r.split(",")[3]) for r in rows])


COARSE = {"converge": 0.9, "texel_density": 4.0}
COARSE_FLAGS = ["--converge", "0.9", "--texel-density", "4"]


@pytest.mark.parametrize("flags,kwargs", [
    ([], {}),
    (["--maintenance-factor", "0.8", "--interp", "bilinear", "--shadows", "paraboloid"],
     {"maintenance_factor": 0.8, "interp": "bilinear", "shadows": "paraboloid"}),
], ids=["scene-defaults", "mf-bilinear-paraboloid"])
def test_calc_equals_the_calc_command(tmp_path, flags, kwargs):
    # The scene asks for the interreflected light (UGR at its observers needs it).
    expected = calc_command(BOX_CALC, tmp_path, *flags, *COARSE_FLAGS)
    got = goniolight.calc(BOX_CALC, solver=COARSE, **kwargs)
    values = [g.pop("values") for g in got["grids"]]
    got["scene"] = expected["scene"]  # named as each was given the path
    # The same solve on the same GPU: equal to the last digit.
    assert got == expected
    assert expected["indirect"] == "radiosity" and expected["observers"][0]["ugr"] > 0
    for grid, v in zip(expected["grids"], values):
        np.testing.assert_allclose(v, csv_values(tmp_path / grid["csv"]), rtol=0, atol=5e-7)
        assert v.size == grid["points"] and v.min() == grid["emin"]


def test_calc_judges_en12464_areas_as_the_command(tmp_path):
    scene = ROOT / "assets" / "scenes" / "box_room_en12464.toml"
    expected = calc_command(scene, tmp_path, *COARSE_FLAGS)
    got = goniolight.calc(scene, solver=COARSE)
    for g in got["grids"]:
        g.pop("values")
    got["scene"] = expected["scene"]
    assert got == expected
    # The desk: Em, U0, UGR, Ra and its surrounding's and background's Em and U0; the
    # room: its activity area's Em and U0, four walls' and the ceiling's.
    verdicts = got["requirements"]
    assert len(verdicts) == 8 + 2 + 2 * 5
    desk = {(r["part"], r["quantity"]): r for r in verdicts if r["area"] == "desk"}
    assert desk[("background", "Em")]["required"] == pytest.approx(200 / 3)
    assert desk[("task", "UGR")]["achieved"] == got["observers"][0]["ugr"]
    assert desk[("task", "Ra")]["pass"] is None
    walls = [r for r in verdicts if r["part"] == "wall"]
    assert [r["grid"] for r in walls[::2]] == [f"office wall {k}" for k in (1, 2, 3, 4)]
    assert got["method"]["standards"][0].startswith("EN 12464-1:2021")


def test_calc_emergency_equals_the_command(tmp_path):
    scene = ROOT / "assets" / "scenes" / "box_room_en12464.toml"
    expected = calc_command(scene, tmp_path, "--emergency")
    got = goniolight.calc(scene, emergency=True)
    for g in got["grids"]:
        g.pop("values")
    got["scene"] = expected["scene"]
    assert got == expected
    assert got["method"]["emergency"] is True
    assert got["method"]["standards"] == ["EN 1838:2013"]
    assert {r["area"] for r in got["requirements"]} == {"escape route", "extinguisher", "L1", "L2"}
    with pytest.raises(ValueError, match="direct light only"):
        goniolight.calc(scene, emergency=True, indirect="radiosity")


def test_calc_with_radiosity_equals_the_command_and_names_bad_options(tmp_path):
    expected = calc_command(BOX_CALC, tmp_path, "--indirect", "radiosity",
                            "--converge", "0.9", "--texel-density", "4")
    got = goniolight.calc(BOX_CALC, indirect="radiosity",
                          solver={"converge": 0.9, "texel_density": 4.0})
    assert got["indirect"] == "radiosity" and got["convergence"] >= 0.9
    for g, e in zip(got["grids"], expected["grids"]):
        for key in ("em", "emin", "emax", "u0", "g2"):
            assert math.isclose(g[key], e[key], rel_tol=1e-4), (g["name"], key)
        np.testing.assert_allclose(g["values"], csv_values(tmp_path / e["csv"]), rtol=1e-4)
    with pytest.raises(ValueError, match="cpu computes the direct light only"):
        goniolight.calc(BOX_CALC, cpu=True)
    with pytest.raises(ValueError, match="maintenance_factor 1.5"):
        goniolight.calc(BOX_CALC, maintenance_factor=1.5)
    with pytest.raises(ValueError, match="drive importance"):
        goniolight.calc(BOX_CALC, indirect="radiosity", solver={"drive": "importance"})
