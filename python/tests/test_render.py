"""Python's render draws what ``goniolight render`` draws: the same pixels, the same
statistics; its HDR arrays hold the luminance and the lux of each pixel."""

import re
import struct
import zlib

import numpy as np
import pytest

import goniolight

from test_goniolight import ROOT, cli

BOX = ROOT / "assets" / "scenes" / "box_room.toml"


def read_png(path):
    """The pixels of an 8-bit RGBA, non-interlaced PNG (what the command writes)."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat, header = 8, b"", None
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert (depth, colour, interlace) == (8, 6, 0), header
    raw, stride = zlib.decompress(idat), width * 4
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 4] if i >= 4 else 0
            b = previous[i]
            c = previous[i - 4] if i >= 4 else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, 4)


@pytest.mark.parametrize("mode", ["illuminance", "shaded"])
def test_the_image_equals_the_commands(tmp_path, mode):
    png = tmp_path / "box.png"
    said = cli("render", str(BOX), "--out", str(png), "--width", "64", "--height", "48",
               "--supersample", "1", "--mode", mode)
    r = goniolight.render(BOX, width=64, height=48, mode=mode, supersample=1)
    expected = read_png(png)
    assert r.image.shape == expected.shape
    np.testing.assert_array_equal(r.image, expected)
    stats = r.stats
    if mode == "illuminance":
        # The command prints the mean and the percentiles to the lux.
        m = re.search(r"mean (\d+) lx, median (\d+), 5 % (\d+), 95 % (\d+)", said)
        assert m, said
        printed = [int(v) for v in m.groups()]
        mine = [stats["lux"][k] for k in ("mean", "median", "p5", "p95")]
        assert [round(v) for v in mine] == printed
        # The per-pixel lux agrees with its statistics.
        lux = r.lux[~np.isnan(r.lux)]
        assert lux.size > 64 * 48 / 2
        assert abs(float(lux.mean()) - stats["lux"]["mean"]) < 1e-3 * stats["lux"]["mean"]
    else:
        m = re.search(r"max (\d+) cd/m²", said)
        assert m and round(stats["max_luminance"]) == int(m.group(1)), said
        assert r.rgb.shape == (48, 64, 3) and float(r.rgb.max()) > 0.0


def test_a_solution_adds_its_interreflected_light():
    direct = goniolight.render(BOX, width=48, height=36, mode="illuminance", supersample=1)
    sol = goniolight.radiosity(BOX, converge=0.9, texel_density=4)
    both = goniolight.render(BOX, width=48, height=36, mode="illuminance", supersample=1,
                             solution=sol)
    seen = ~np.isnan(direct.lux)
    np.testing.assert_array_equal(seen, ~np.isnan(both.lux))
    # The surfaces gain the light that the walls and floor send each other (the solved
    # image reads the direct light from the light map, at its texels: a few pixels at
    # shadow edges differ either way).
    gained = both.lux[seen] >= direct.lux[seen]
    assert gained.mean() > 0.95, gained.mean()
    assert both.stats["lux"]["mean"] > 1.05 * direct.stats["lux"]["mean"]


def test_bad_values_name_the_display_key(tmp_path):
    with pytest.raises(ValueError, match=r"display\.width 0 is not in 1\.\."):
        goniolight.render(BOX, width=0)
    with pytest.raises(ValueError, match=r"display\.lux_max -5 must be a positive number"):
        goniolight.render(BOX, lux_max=-5)
    with pytest.raises(ValueError, match=r"`supersample` 2 must be 1, 3 or 5"):
        goniolight.render(BOX, supersample=2)
    r = goniolight.render(BOX, width=32, height=24, supersample=1)
    r.save(tmp_path / "a.png", tmp_path / "a.exr")
    np.testing.assert_array_equal(read_png(tmp_path / "a.png"), r.image)
    assert (tmp_path / "a.exr").stat().st_size > 32 * 24
