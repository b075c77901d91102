"""The sun study from Python equals ``goniolight profile``, file for file and digit for
digit: the same options give the same ``study.json`` and ``hours.csv``."""

import csv
import json
import warnings

import numpy as np
import pytest

import goniolight

from test_goniolight import ROOT, cli, cli_with_stderr

BOX = ROOT / "assets" / "models" / "box.obj"
VIENNA = {"latitude": 48.21, "longitude": 16.37, "timezone": "Europe/Vienna"}
DATES = ["2026-03-21", "2026-06-21"]
# box.obj is 2 × 1 × 3 m from the origin: a window on its south face, one on its north face.
POINTS = """[[point]]
name = "south"
position = [1.0, 0.0, 1.5]
normal = [0, -1, 0]
[[point]]
name = "north"
position = [1.0, 1.0, 1.5]
normal = [0, 1, 0]
"""
# A garden north of the box, where its shadow falls.
AREAS = {"type": "FeatureCollection", "features": [{
    "type": "Feature", "properties": {"name": "garden"},
    "geometry": {"type": "Polygon",
                 "coordinates": [[[-2, 1.5], [4, 1.5], [4, 6], [-2, 6], [-2, 1.5]]]}}]}


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    d = tmp_path_factory.mktemp("inputs")
    (d / "points.toml").write_text(POINTS)
    (d / "areas.geojson").write_text(json.dumps(AREAS))
    return d


def command_study(out, inputs):
    cli("profile", str(BOX), "--up", "z", "--lat", "48.21", "--lon", "16.37",
        "--tz", "Europe/Vienna", "--dates", ",".join(DATES), "--from", "08:00",
        "--to", "16:00", "--step", "60", "--metric", "sun", "--resolution", "64",
        "--threshold", "2", "--areas", str(inputs / "areas.geojson"), "--facades",
        "--facade-cell", "0.25", "--points", str(inputs / "points.toml"), "--out", str(out))


def python_study(inputs, **extra):
    return goniolight.sun_study(
        BOX, VIENNA, DATES, start="08:00", end="16:00", step=60, up="z", metric="sun",
        resolution=64, threshold=2, areas=inputs / "areas.geojson", facades=True,
        facade_cell=0.25, points=inputs / "points.toml", **extra)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in r] for r in rows[1:]])


def test_study_and_hours_equal_the_commands(tmp_path, inputs):
    out = tmp_path / "cli"
    command_study(out, inputs)
    seen = []
    study = python_study(inputs, progress=lambda done, total: seen.append((done, total)))
    assert study.dates == DATES
    # One call per step of each date (9 hourly steps), counting up to the total.
    assert seen[-1] == (18, 18) and [d for d, _ in seen] == sorted(d for d, _ in seen)
    for k, date in enumerate(DATES):
        expected = json.loads((out / date / "study.json").read_text())
        assert study.studies[k] == expected
        # Both have facades, points and the garden: not an empty comparison.
        assert len(expected["facades"]) == 4 and len(expected["points"]) == 2
        assert expected["areas"][0]["name"] == "garden"
        header, rows = read_csv(out / date / "hours.csv")
        assert header == ["x", "y", "hours"]
        cells = study.cells(k)
        assert cells.shape == rows.shape and len(rows) > 1000
        # hours.csv prints four decimals.
        np.testing.assert_allclose(cells, rows, rtol=0, atol=0.5e-4 + 1e-9)
        hours = study.hours(k)
        assert hours.shape == (64, 64)
        np.testing.assert_array_equal(hours[~np.isnan(hours)], cells[:, 2])
        plan = study.plan(k)
        assert plan["resolution"] == 64
        cell = plan["extent_m"] / 64
        # Row 0, column 0's centre is the first cell of hours.csv when it sees a surface.
        if not np.isnan(hours[0, 0]):
            np.testing.assert_allclose(cells[0, :2], [plan["x"] + cell / 2, plan["y"] - cell / 2])
    # June's sun is up longer: more hours on the plan than in March.
    assert study.studies[1]["mean_h"] > study.studies[0]["mean_h"]


def test_written_files_equal_the_commands(tmp_path, inputs):
    out = tmp_path / "cli"
    command_study(out, inputs)
    mine = tmp_path / "python"
    python_study(inputs).write(mine)
    cli_files = sorted(p.relative_to(out) for p in out.rglob("*") if p.is_file())
    assert cli_files == sorted(p.relative_to(mine) for p in mine.rglob("*") if p.is_file())
    for name in ["dates.csv", "dates.json"] + [f"{d}/{f}" for d in DATES for f in (
            "study.json", "hours.csv", "hours.asc", "facades.csv", "points.csv",
            "profile.csv", "outlines.geojson")]:
        assert (mine / name).read_bytes() == (out / name).read_bytes(), name


def test_bad_options_name_the_option(inputs):
    def study(**kw):
        args = dict(start="08:00", end="16:00", step=60, up="z", resolution=32)
        args.update(kw)
        site = args.pop("site", VIENNA)
        return goniolight.sun_study(BOX, site, args.pop("dates", "2026-03-21"), **args)

    with pytest.raises(ValueError, match=r"threshold_h -1 must be hours"):
        study(threshold=-1)
    with pytest.raises(ValueError, match=r"facade_cell_m 0 must be at least 0\.01 m"):
        study(facades=True, facade_cell=0)
    with pytest.raises(ValueError, match=r'casters "nothing" matches no object'):
        study(casters=["nothing"])
    with pytest.raises(ValueError, match=r"site: latitude is missing"):
        study(site={"longitude": 16.37})
    with pytest.raises(ValueError, match=r"latitude 95"):
        study(site=(95, 16.37))
    with pytest.raises(ValueError, match=r'dates: "2026-13-01" is not a date'):
        study(dates="2026-13-01")
    with pytest.raises(ValueError, match=r"metric \"moon\": one of shadow, sun"):
        study(metric="moon")
    with pytest.raises(ValueError, match=r"resolution 8 is not in 16\.\."):
        study(resolution=8)
    with pytest.raises(ValueError, match=r"box\.objx"):
        goniolight.sun_study(str(BOX) + "x", VIENNA, "2026-03-21")


def test_a_wrong_up_axis_is_a_user_warning(tmp_path):
    model = ROOT / "assets" / "models" / "industrial_area.obj"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        s = goniolight.sun_study(model, VIENNA, "2026-03-21", start="10:00", end="14:00",
                                 step=120, resolution=32)
    said = [str(w.message) for w in caught if w.category is UserWarning]
    assert any("up axis" in m and "pass `up` z" in m for m in said), said
    assert s.warnings == said
    # The command says the same with its flag.
    _, err = cli_with_stderr("profile", str(model), "--lat", "48.21", "--lon", "16.37",
                             "--tz", "Europe/Vienna", "--date", "2026-03-21", "--from",
                             "10:00", "--to", "14:00", "--step", "120", "--resolution", "32",
                             "--out", str(tmp_path / "out"))
    assert "pass --up z" in err


def test_a_glb_model_gives_the_study_of_its_obj(tmp_path):
    """The same box as GLB (trimesh's conversion, Y up as glTF is) gives the same hours."""
    import trimesh  # noqa: E402  (installed by scripts/test-python.sh)
    mesh = trimesh.load(str(BOX), force="mesh", process=False, maintain_order=True)
    # The OBJ is Z up: turn it to glTF's Y up, (x, y, z) → (x, z, −y).
    mesh.vertices = mesh.vertices[:, [0, 2, 1]] * [1.0, 1.0, -1.0]
    glb = tmp_path / "box.glb"
    mesh.export(str(glb))
    args = dict(start="08:00", end="16:00", step=60, metric="sun", resolution=64)
    from_obj = goniolight.sun_study(BOX, VIENNA, DATES, up="z", **args)
    from_glb = goniolight.sun_study(glb, VIENNA, DATES, **args)
    for day in range(len(DATES)):
        assert from_obj.hours(day).max() > 0
        np.testing.assert_array_equal(from_glb.hours(day), from_obj.hours(day))
