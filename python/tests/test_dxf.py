"""``calc --dxf``: the plan as DXF, read back with ezdxf (an independent DXF library): the
value texts equal the CSV's values at their points, every isolux polyline lies on its value
(the grid's values interpolated at its vertices), and the luminaires are inserts of the
LUMINAIRE block at their positions."""

import csv

import numpy as np
import pytest

from test_goniolight import ROOT, cli

import ezdxf  # noqa: E402  (installed by scripts/test-python.sh)

SCENES = ROOT / "assets" / "scenes"
GRID = """
[[grid]]
name = "work plane"
corner = [0.5, 0.5]
size = [5.0, 3.0]
height = 0.8
spacing = 0.25
"""


def _scene(tmp_path):
    """The bundled box room (its files by absolute path) with a work plane."""
    text = (SCENES / "box_room.toml").read_text()
    text = text.replace('path = "box_room.obj"', f'path = "{SCENES / "box_room.obj"}"')
    text = text.replace('file = "../../', f'file = "{ROOT}/')
    path = tmp_path / "room.toml"
    path.write_text(text + GRID)
    return path


def _lattice(rows):
    xs = sorted({r[0] for r in rows})
    ys = sorted({r[1] for r in rows})
    grid = np.full((len(ys), len(xs)), np.nan)
    for x, y, v in rows:
        grid[ys.index(y), xs.index(x)] = v
    return np.asarray(xs), np.asarray(ys), grid


def _bilinear(xs, ys, grid, x, y):
    i = int(np.clip(np.searchsorted(xs, x) - 1, 0, len(xs) - 2))
    j = int(np.clip(np.searchsorted(ys, y) - 1, 0, len(ys) - 2))
    tx = (x - xs[i]) / (xs[i + 1] - xs[i])
    ty = (y - ys[j]) / (ys[j + 1] - ys[j])
    q = grid[j:j + 2, i:i + 2]
    return (q[0, 0] * (1 - tx) * (1 - ty) + q[0, 1] * tx * (1 - ty)
            + q[1, 0] * (1 - tx) * ty + q[1, 1] * tx * ty)


def test_calc_dxf_reads_back_with_ezdxf(tmp_path):
    out = tmp_path / "out"
    cli("calc", str(_scene(tmp_path)), "--dxf", "--out", str(out))
    with open(out / "work-plane.csv") as f:
        rows = [(float(r["x"]), float(r["y"]), float(r["lux"])) for r in csv.DictReader(f)]
    doc = ezdxf.readfile(out / "work-plane.dxf")
    assert doc.dxfversion == "AC1009"
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"OUTLINE", "ISOLUX", "ISOLUX_LABELS", "VALUES", "LUMINAIRES"} <= layers
    msp = doc.modelspace()
    # The value at every point, to 0.1 lx, centred on the point.
    texts = {(round(t.dxf.align_point.x, 4), round(t.dxf.align_point.y, 4)): float(t.dxf.text)
             for t in msp.query('TEXT[layer=="VALUES"]')}
    assert len(texts) == len(rows)
    for x, y, v in rows:
        assert texts[(round(x, 4), round(y, 4))] == pytest.approx(v, abs=0.051)
    # Each isolux polyline is where the values cross its level.
    xs, ys, grid = _lattice(rows)
    lines = msp.query('POLYLINE[layer=="ISOLUX"]')
    assert len(lines) > 0
    levels = set()
    for line in lines:
        level = dict(line.get_xdata("GONIOLIGHT"))[1040]
        levels.add(level)
        for p in line.points():
            if xs[0] <= p[0] <= xs[-1] and ys[0] <= p[1] <= ys[-1]:
                assert _bilinear(xs, ys, grid, p[0], p[1]) == pytest.approx(level, rel=0.02)
    assert all(min(v for *_, v in rows) < l <= max(v for *_, v in rows) for l in levels)
    labels = [t.dxf.text for t in msp.query('TEXT[layer=="ISOLUX_LABELS"]')]
    assert {float(t) for t in labels} == levels
    # The luminaires: inserts of the block at the scene's positions.
    inserts = msp.query('INSERT[layer=="LUMINAIRES"]')
    assert len(inserts) >= 1 and all(i.dxf.name == "LUMINAIRE" for i in inserts)
    assert "LUMINAIRE" in doc.blocks
    # The outline is closed.
    outline = msp.query('POLYLINE[layer=="OUTLINE"]')[0]
    assert outline.is_closed
