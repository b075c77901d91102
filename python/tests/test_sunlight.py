"""The planning tests from Python equal ``goniolight sunlight``, digit for digit: the same
options give the same ``sunlight.json`` and open-space hours; bad keywords raise
ValueError naming them."""

import csv
import datetime
import json

import numpy as np
import pytest

import goniolight

from test_goniolight import ROOT, cli

SCENES = ROOT / "assets" / "scenes"
SITE = SCENES / "sunlight_site.toml"
EXISTING = SCENES / "sunlight_site_existing.toml"
EPW = ROOT / "assets" / "weather" / "USA_IL_Chicago.OHare.Intl.AP.725300_TMY3.epw"


def test_sunlight_equals_the_command(tmp_path):
    out = tmp_path / "out"
    points = tmp_path / "windows.toml"
    points.write_text('[[point]]\nname = "gable"\nposition = [0.0, 5.0, 4.5]\nnormal = [-1, 0, 0]\n')
    cli("sunlight", str(SITE), "--baseline", str(EXISTING), "--weather", str(EPW),
        "--year", "2026", "--step", "10", "--points", str(points), "--out", str(out))
    expected = json.loads((out / "sunlight.json").read_text())
    doc = goniolight.sunlight(SITE, baseline=goniolight.Scene.load(EXISTING), weather=EPW,
                              year=2026, step=10, date=datetime.date(2026, 3, 21),
                              points=points)
    hours = [a.pop("hours") for a in doc["areas"]]
    assert doc == expected
    with open(out / "open-space-front-gardens.csv") as f:
        rows = list(csv.DictReader(f))
    np.testing.assert_allclose(hours[0], [float(r["hours"]) for r in rows], atol=5e-4)
    assert [w["pass"]["vsc"] for w in doc["windows"]] == [False] * 4 + [True, True]
    assert doc["windows"][-1]["name"] == "gable"


@pytest.mark.parametrize("kwargs, needle", [
    ({"step": 0}, "step"),
    ({"min_elevation": 95}, "min_elevation"),
    ({"date": "21 March"}, "date"),
    ({"weather": ROOT / "assets" / "scenes" / "box_room.toml"}, "LOCATION"),
])
def test_sunlight_refuses_bad_keywords(kwargs, needle):
    with pytest.raises(ValueError, match=needle):
        goniolight.sunlight(SITE, year=2026, **kwargs)
