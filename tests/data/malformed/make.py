#!/usr/bin/env python3
"""Regenerates the malformed luminaire files used by tests/cli/malformed.rs.

Each case starts from a valid file and breaks one thing. EXPECTED.txt lists
`file<TAB>line<TAB>substring of the message` for the test to assert."""
import pathlib

here = pathlib.Path(__file__).parent
root = here.parents[2]
ldt = (root / "luminaires/photometric-viewer/ldt/relative.ldt").read_text().splitlines()
ies = (root / "luminaires/photometric-viewer/ies95/relative_photometry.ies").read_text().splitlines()
expected = []


def case(name, lines, line, text, crlf=False):
    body = ("\r\n" if crlf else "\n").join(lines) + "\n" if lines else ""
    (here / name).write_text(body, encoding="utf-8")
    expected.append(f"{name}\t{line}\t{text}")


def with_line(src, n, value):
    out = list(src)
    out[n - 1] = value
    return out


# relative.ldt: Isym 1, Mc 1, Ng 37; data from line 33 (direct ratios),
# C angle line 43, γ angles 44-80, intensities 81-117.
case("truncated.ldt", ldt[:60], 61, "unexpected end of file")
case("text_in_intensity.ldt", with_line(ldt, 90, "abc"), 90, "found \"abc\"")
case("isym_7.ldt", with_line(ldt, 3, "7"), 3, "Isym")
case("mc_zero.ldt", with_line(ldt, 4, "0"), 4, "Mc")
case("ng_zero.ldt", with_line(ldt, 6, "0"), 6, "Ng")
case("extra_intensities.ldt", ldt + ["12.5", "13.5"], 118, "more data")
case("isym2_odd_mc.ldt", with_line(ldt, 3, "2"), 4, "cannot be split")
case("absurd_mc.ldt", with_line(ldt, 4, "99999"), 4, "Mc")
case("nan_intensity.ldt", with_line(ldt, 95, "NaN"), 95, "found \"NaN\"")
case("negative_intensity.ldt", with_line(ldt, 100, "-5.0"), 100, "negative intensity")
case("gamma_not_increasing.ldt", with_line(ldt, 50, "1.0"), 50, "must increase")
case("c_angle_360.ldt", with_line(ldt, 43, "360"), 43, "outside")
case("mc_text.ldt", with_line(ldt, 4, "twelve"), 4, "found \"twelve\"")
case("zero_lamp_sets.ldt", with_line(ldt, 26, "0"), 26, "lamp sets")
case("empty.ldt", [], 1, "unexpected end of file")
case("ng_fraction.ldt", with_line(ldt, 6, "37.5"), 6, "whole number")
case("negative_lamp_flux.ldt", with_line(ldt, 29, "-500"), 29, "negative")
case("gamma_over_180.ldt", with_line(ldt, 80, "190"), 80, "outside")
case("infinite_intensity.ldt", with_line(ldt, 85, "inf"), 85, "found \"inf\"")
case("too_few_intensities_crlf.ldt", ldt[:110], 111, "found 30", crlf=True)
sym4 = with_line(with_line(ldt, 3, "4"), 4, "4")
sym4 = sym4[:43] + ["10", "20", "30"] + sym4[43:]
case("isym4_angles_do_not_fold.ldt", sym4, 43, "no stored mirror plane")

# relative_photometry.ies: TILT at line 13, numbers from line 14.
tilt = next(i for i, l in enumerate(ies) if l.startswith("TILT")) + 1
case("no_tilt.ies", [l for l in ies if not l.startswith("TILT")], len(ies), "no TILT= line")
case("tilt_include_truncated.ies", ies[: tilt - 1] + ["TILT=INCLUDE", "1", "5", "0 10 20"], tilt + 4, "unexpected end of file")
first = ies[tilt].split()
# Type A/B angles run from -90 to 90: a vertical angle of 120 cannot be one.
type_a = with_line(ies, tilt + 1, " ".join(first[:5] + ["3"] + first[6:]))
type_a = with_line(type_a, tilt + 4, type_a[tilt + 3].replace("90.0", "120.0"))
case("type_a_vertical_120.ies", type_a, tilt + 4, "vertical angle 120 outside")
case("units_3.ies", with_line(ies, tilt + 1, " ".join(first[:6] + ["3"] + first[7:])), tilt + 1, "between 1 and 2")
last = ies[-1].split()
case("negative_candela.ies", ies[:-1] + [" ".join(last[:-1] + ["-3"])], len(ies), "negative candela")
case("too_few_candela.ies", ies[:-1], len(ies), "unexpected end of file")
case("tilt_empty.ies", with_line(ies, tilt, "TILT="), tilt, "TILT= has no value")
# Horizontal angles 0..45 (two planes) are not a Type C symmetry.
hz_line = next(i for i, l in enumerate(ies) if i > tilt + 1 and l.strip() == "0.0") + 1
bad_h = list(ies)
bad_h[tilt] = " ".join(first[:4] + ["2"] + first[5:])
bad_h[hz_line - 1] = "0.0 45.0"
bad_h = bad_h + [ies[-2], ies[-1]]
case("horizontal_0_45.ies", bad_h, hz_line, "unsupported horizontal angle range")

(here / "EXPECTED.txt").write_text("\n".join(expected) + "\n")
print(f"{len(expected)} cases")
