"""The Python package against the command line: the same numbers from both."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import goniolight

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "luminaires" / "eulumdat-analysis" / "sample_18.ldt"
SCENE = ROOT / "assets" / "scenes" / "box_room.toml"


def cli_with_stderr(*args, stdin=None):
    exe = os.environ.get("GONIOLIGHT_BIN") or str(ROOT / "target" / "debug" / "goniolight")
    assert os.path.exists(exe), f"goniolight binary not found at {exe}: build it or set GONIOLIGHT_BIN"
    done = subprocess.run([exe, *args], input=stdin, capture_output=True, text=True, check=True)
    return done.stdout, done.stderr


def cli(*args, stdin=None):
    return cli_with_stderr(*args, stdin=stdin)[0]


def test_info_equals_ldt_info_json():
    lum = goniolight.read(SAMPLE)
    expected = json.loads(cli("ldt", "info", str(SAMPLE), "--json"))
    assert lum.info == expected
    assert lum.intensities.shape == (len(expected["c_angles"]), len(expected["gamma_angles"]))
    np.testing.assert_array_equal(lum.intensities, np.asarray(expected["intensities"]))
    assert lum.info["flux_lm"] == pytest.approx(2445.4, rel=1e-3)


@pytest.mark.parametrize("interp", goniolight.INTERPOLATIONS)
def test_sampling_equals_ldt_sample(interp):
    lum = goniolight.read(SAMPLE)
    rng = np.random.default_rng(7)
    c = rng.uniform(-30.0, 390.0, 200)
    g = rng.uniform(0.0, 180.0, 200)
    text = "".join(f"{float(a)!r} {float(b)!r}\n" for a, b in zip(c, g))
    expected = np.asarray([float(v) for v in cli("ldt", "sample", str(SAMPLE), "--interp", interp, stdin=text).split()])
    got = lum.sample(c, g, interp=interp)
    assert got.shape == (200,)
    # The command prints Rust's shortest round-trip form: equal to the last bit.
    np.testing.assert_array_equal(got, expected)
    # Broadcasting keeps the shape; measured angles give the measured values.
    grid = lum.sample(lum.c_angles[:, None], lum.gamma_angles[None, :], interp=interp)
    np.testing.assert_allclose(grid, lum.intensities, rtol=0, atol=1e-9 * lum.intensities.max())


def test_check_equals_ldt_check_json():
    lum = goniolight.read(SAMPLE)
    expected = json.loads(cli("ldt", "check", str(SAMPLE), "--downsample", "15,5", "--json"))
    assert lum.check(downsample=(15, 5)) == expected


def test_write_round_trips(tmp_path):
    lum = goniolight.read(SAMPLE)
    for ext in ("ldt", "ies"):
        out = tmp_path / f"copy.{ext}"
        lum.write(out)
        back = goniolight.read(out)
        np.testing.assert_allclose(back.intensities, lum.intensities, rtol=1e-4, atol=1e-6)
    with pytest.raises(ValueError):
        lum.write(tmp_path / "copy.txt")


def test_tm33_files_read_write_and_equal_the_cli(tmp_path):
    shared = pathlib.Path(os.environ.get("GONIOLIGHT_SHARED", ROOT.parent / "shared"))
    grow = shared / "luminaires" / "tm33" / "grow_light.xml"
    lum = goniolight.read(grow)
    assert lum.info == json.loads(cli("ldt", "info", str(grow), "--json"))
    assert lum.info["format"] == "tm33"
    assert lum.info["tm33"]["spectral"]["ppf_umol_per_s"] > 0
    assert any("spectral distribution" in l for l in lum.losses("ldt"))
    for ext in ("xml", "json", "ldt"):
        out = tmp_path / f"grow.{ext}"
        lum.write(out)
        back = goniolight.read(out)
        np.testing.assert_allclose(back.intensities, lum.intensities, rtol=1e-9)
        assert back.info["flux_lm"] == pytest.approx(lum.info["flux_lm"], rel=1e-9)
    # What the command line writes is what Python writes.
    cli("ldt", "convert", str(SAMPLE), "--out", str(tmp_path / "cli.xml"))
    goniolight.read(SAMPLE).write(tmp_path / "py.xml")
    assert (tmp_path / "cli.xml").read_text() == (tmp_path / "py.xml").read_text()


def test_bad_files_name_the_file(tmp_path):
    bad = tmp_path / "bad.ldt"
    bad.write_text("not a luminaire\n")
    with pytest.raises(ValueError, match="bad.ldt"):
        goniolight.read(bad)


def test_sun_position_equals_sun_json():
    times = ["2026-03-21T09:00", "2026-06-21T12:30", "2026-12-21T15:45"]
    got = goniolight.sun_position(48.21, 16.37, times, tz="Europe/Vienna")
    for k, t in enumerate(times):
        expected = json.loads(cli("sun", "--lat", "48.21", "--lon", "16.37", "--time", t,
                                  "--tz", "Europe/Vienna", "--json"))
        assert got["utc"][k] == expected["utc"]
        for key in ("zenith_deg", "apparent_zenith_deg", "elevation_deg", "azimuth_deg", "delta_t_s"):
            assert got[key][k] == expected[key], key
        np.testing.assert_array_equal(got["direction"][k], expected["direction"])
    # numpy datetime64 (UTC) gives the same instant as the ISO string with an offset.
    a = goniolight.sun_position(48.21, 16.37, np.array(["2026-06-21T10:30:00"], dtype="datetime64[s]"))
    b = goniolight.sun_position(48.21, 16.37, "2026-06-21T10:30:00+00:00")
    assert a["azimuth_deg"][0] == b["azimuth_deg"][0]


def test_sun_position_names_the_bad_value_as_the_library_does():
    # Not the command's flags (--lat, --tz): the library's fields.
    with pytest.raises(ValueError, match=r"latitude 95 is outside \[-90, 90\]"):
        goniolight.sun_position(95.0, 0.0, "2026-06-21T12:00Z")
    with pytest.raises(ValueError, match=r'zone "Nowhere/City" is not a time zone'):
        goniolight.sun_position(40.0, 0.0, "2026-06-21T12:00", tz="Nowhere/City")
    with pytest.raises(ValueError, match="has no UTC offset"):
        goniolight.sun_position(40.0, 0.0, "2026-06-21T12:00")


def test_what_loading_worked_around_is_a_user_warning(tmp_path):
    # A model whose MTL file is missing loads with the default material: the command line
    # says so on stderr, Python as a UserWarning (and the numbers come all the same).
    (tmp_path / "floor.obj").write_text(
        "mtllib missing.mtl\nv 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nf 1 2 3\nf 1 3 4\n")
    scene = tmp_path / "scene.toml"
    scene.write_text(f'[[model]]\npath = "floor.obj"\nup = "z"\n\n[[luminaire]]\n'
                     f'file = {json.dumps(str(SAMPLE))}\nposition = [2.0, 2.0, 3.0]\n')
    with pytest.warns(UserWarning, match="its MTL file could not be opened"):
        lux = goniolight.illuminance(scene, np.array([[2.0, 2.0, 0.0, 0.0, 0.0, 1.0]]), cpu=True)
    assert lux[0] > 0.0
    _, err = cli_with_stderr("illuminance", str(scene), "--cpu", stdin="2 2 0 0 0 1\n")
    assert "warning: " in err and "its MTL file could not be opened" in err


def test_a_coarser_paraboloid_tessellation_is_a_user_warning():
    # A 300 m ground plane: its paraboloid casters at 0.25 m edges would exhaust the GPU's
    # buffers, so they are tessellated more coarsely (the library says so, naming its
    # option; the command names its flag).
    scene = ROOT.parent / "shared" / "fuzz-crashes" / "04-large-triangle-paraboloid" / "g300.toml"
    assert scene.exists(), f"the shared test data is missing: {scene}"
    with pytest.warns(UserWarning, match=r"casters tessellated to .*`shadows` volumes is exact"):
        lux = goniolight.illuminance(scene, np.array([[10.0, 10.0, 0.0, 0.0, 0.0, 1.0]]),
                                     shadows="paraboloid")
    assert lux[0] > 0.0
    _, err = cli_with_stderr("illuminance", str(scene), "--shadows", "paraboloid",
                             stdin="10 10 0 0 0 1\n")
    assert "--shadows volumes is exact" in err


def test_illuminance_equals_the_illuminance_command():
    xs = np.linspace(0.5, 3.5, 5)
    pts = np.array([[x, y, 0.8, 0.0, 0.0, 1.0] for x in xs for y in (1.0, 2.0)])
    text = "".join(" ".join(repr(float(v)) for v in p) + "\n" for p in pts)
    for cpu in (False, True):
        args = ["illuminance", str(SCENE)] + (["--cpu"] if cpu else [])
        expected = np.asarray([float(v) for v in cli(*args, stdin=text).split()])
        lux, device = goniolight.illuminance(SCENE, pts, cpu=cpu, return_device=True)
        assert device == ("cpu" if cpu else "gpu")
        # The command prints six decimals.
        np.testing.assert_allclose(lux, expected, rtol=0, atol=5e-7)
        assert (lux > 1.0).all()
    with pytest.raises(ValueError, match="N × 6"):
        goniolight.illuminance(SCENE, np.zeros((3, 5)))


def test_illuminance_with_daylight_equals_the_command():
    side_lit = SCENE.parent / "side_lit_room.toml"
    pts = np.array([[3.0, y, 0.85, 0.0, 0.0, 1.0] for y in (1.0, 2.0, 3.0)])
    text = "".join(" ".join(repr(float(v)) for v in p) + "\n" for p in pts)
    for extra, kwargs in [((), {}), (("--sky", "cie:12", "--time", "2026-06-21T13:00"),
                                     {"sky": "cie:12", "time": "2026-06-21T13:00"})]:
        args = ["illuminance", str(side_lit), "--cpu", *extra]
        expected = np.asarray([float(v) for v in cli(*args, stdin=text).split()])
        lux = goniolight.illuminance(side_lit, pts, cpu=True, **kwargs)
        np.testing.assert_allclose(lux, expected, rtol=0, atol=5e-7)
        # Daylight falls off away from the window.
        assert lux[0] > lux[1] > lux[2] > 10.0
    with pytest.raises(ValueError, match="cie:15"):
        goniolight.illuminance(side_lit, pts, cpu=True, sky="cie:16")


@pytest.mark.parametrize("shr", [0.25, 1.0])
def test_ugr_table_equals_ldt_ugr_json(shr):
    expected = json.loads(cli("ldt", "ugr", str(SAMPLE), "--json", "--shr", str(shr)))
    assert goniolight.ugr_table(SAMPLE, shr=shr) == expected
    assert goniolight.read(SAMPLE).ugr_table(shr=shr) == expected
    # A real table: crosswise values in the usual band, 19 rooms × 5 reflectances.
    assert len(expected["rooms"]) == 19
    values = [v for row in expected["crosswise"] for v in row if v is not None]
    assert values and all(10 < v < 35 for v in values)


def test_luminance_table_equals_ldt_luminance_json():
    for args, kwargs in [([], {}), (["--gamma-from", "45", "--interp", "catmull-rom"],
                                    {"gamma_from": 45, "interp": "catmull-rom"})]:
        expected = json.loads(cli("ldt", "luminance", str(SAMPLE), "--json", *args))
        got = goniolight.luminance_table(SAMPLE, **kwargs)
        assert set(got) == set(expected)
        assert got["c_angles"] == expected["c_angles"]
        assert got["gamma_angles"] == expected["gamma_angles"]
        assert got["flux_lm"] == expected["flux_lm"]
        np.testing.assert_array_equal(got["cd_m2"], np.asarray(expected["cd_m2"]))
    with pytest.raises(ValueError, match="gamma_from 47"):
        goniolight.luminance_table(SAMPLE, gamma_from=47)
    with pytest.raises(ValueError, match="lamp_set 0"):
        goniolight.ugr_table(SAMPLE, lamp_set=0)
    # The library's names of the arguments, not the command's flags (--shr, --lamp-set).
    with pytest.raises(ValueError, match="shr 9 is not a spacing-to-height ratio"):
        goniolight.ugr_table(SAMPLE, shr=9.0)
    with pytest.raises(ValueError, match="lamp_set 5 is not in the file"):
        goniolight.ugr_table(SAMPLE, lamp_set=5)
    with pytest.raises(ValueError, match="downsample 0,5 must be two positive steps"):
        goniolight.read(SAMPLE).check(downsample=(0.0, 5.0))


@pytest.mark.parametrize("ext", ["html", "svg"])
def test_datasheet_equals_ldt_report(tmp_path, ext):
    want = tmp_path / f"cli.{ext}"
    cli("ldt", "report", str(SAMPLE), "--out", str(want))
    got = tmp_path / f"py.{ext}"
    goniolight.datasheet(SAMPLE, got)
    assert got.read_bytes() == want.read_bytes()
    assert b"UGR" in got.read_bytes()
    with pytest.raises(ValueError, match="extension"):
        goniolight.datasheet(SAMPLE, tmp_path / "sheet.pdf")
