//! `ldt plot`'s datasheet diagrams: the plane pairs overlaid in one polar (or cartesian)
//! chart scaled to the planes drawn, titled with name, flux and LOR, the legend beside
//! the chart; PNG and SVG the same drawing.

use crate::common;
use crate::svg_common as svg;

use std::path::Path;

use common::{luminaire, run_cli};
use goniolight::photometry::datasheet_plot::{plane_pair_curve, Diagram};
use goniolight::photometry::plot::nice_ceiling;
use goniolight::photometry::{Interp, Luminaire};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn the_scale_follows_the_planes_drawn() {
    // sample_01_isym3 peaks off the drawn planes (I_max 700 cd/klm at C15 γ60): the outer
    // ring follows C0–C180 and C90–C270, not the sphere's peak.
    let lum = Luminaire::load(&luminaire("eulumdat-plot/sample_01_isym3.ldt")).unwrap();
    let drawn = |planes: Vec<f64>| Diagram {
        lum: &lum,
        file_name: "x".into(),
        planes,
        interp: Interp::CatmullRom,
        lamp_flux_lm: None,
    };
    let mut peak = 0.0f64;
    for c in [0.0, 90.0, 180.0, 270.0] {
        for k in 0..=1800 {
            let g = k as f64 * 0.1;
            peak = peak.max(lum.distribution.sample(c, g, Interp::CatmullRom));
        }
    }
    let i_max = lum.summary().max_intensity;
    let scale = drawn(vec![0.0, 90.0]).scale();
    assert_eq!(scale, nice_ceiling(peak));
    assert!(
        scale < i_max && scale >= peak,
        "{scale} vs peak {peak}, I_max {i_max}"
    );
    // Adding the plane of the peak raises the scale above I_max.
    assert!(drawn(vec![0.0, 15.0]).scale() >= i_max);
}

#[test]
fn the_curve_is_the_plane_pair_in_polar_coordinates() {
    // An intensity of 2 at C0 and 1 at C180: right half radius 2, left half radius 1.
    let curve = plane_pair_curve(|c, _| if c < 90.0 { 2.0 } else { 1.0 }, 0.0, 45.0);
    assert_eq!(curve.len(), 10);
    let near =
        |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12;
    assert!(near(curve[0], [0.0, -2.0]), "γ 0 points down");
    assert!(near(curve[2], [2.0, 0.0]), "γ 90 of plane C0 to the right");
    assert!(
        near(curve[7], [-1.0, 0.0]),
        "γ 90 of plane C180 to the left"
    );
    assert!(near(curve[9], [0.0, -1.0]));
}

#[test]
fn svg_and_png_diagrams_carry_title_legend_and_the_same_curves() {
    let tmp = tempfile::tempdir().unwrap();
    let file = luminaire("eulumdat-luminance/sample_02.ldt");
    for kind in ["polar", "cartesian"] {
        let (svg_path, png_path) =
            common::plot_svg_and_png(&file, &["--kind", kind], tmp.path(), kind);
        let text = std::fs::read_to_string(&svg_path).unwrap();
        // Title: name, fluxes and LOR (sample_02: 2112 lm lamps, LOR 100.2 %).
        for needle in [
            "sample_02",
            "2112 lm lamps",
            "LOR 100.2 %",
            "C0–C180",
            "C90–C270",
        ] {
            assert!(text.contains(needle), "{kind}: {needle} missing");
        }
        // The legend stands beside the chart, right of every curve point.
        let legend_x = text
            .split("<text")
            .filter(|t| t.contains("C0–C180"))
            .filter_map(|t| {
                t.split("x=\"")
                    .nth(1)?
                    .split('"')
                    .next()?
                    .parse::<f64>()
                    .ok()
            })
            .next()
            .unwrap();
        let vector = svg::render(&svg_path);
        let raster = svg::load_png(&png_path);
        for rgb in [[200, 30, 30], [30, 80, 200]] {
            let (a, b) = (svg::pixels_of(&vector, rgb), svg::pixels_of(&raster, rgb));
            assert!(
                a.len() > 300 && b.len() > 300,
                "{kind} {rgb:?}: {} / {}",
                a.len(),
                b.len()
            );
            let curve_right = a.iter().filter(|p| p.1 > 90).map(|p| p.0).max().unwrap() as f64;
            assert!(
                legend_x > curve_right,
                "{kind}: legend at {legend_x}, curve to {curve_right}"
            );
            let bbox = |p: &[(u32, u32)]| {
                let xs = || p.iter().filter(|q| q.1 > 90).map(|q| q.0);
                [xs().min().unwrap(), xs().max().unwrap()]
            };
            let (ba, bb) = (bbox(&a), bbox(&b));
            assert!(
                ba[0].abs_diff(bb[0]) <= 4 && ba[1].abs_diff(bb[1]) <= 4,
                "{kind}: {ba:?} vs {bb:?}"
            );
        }
    }
    // More planes, more curves; planes out of range are refused.
    let out = tmp.path().join("three.svg");
    let (code, _, err) = run_cli(
        &[
            "ldt",
            "plot",
            s(&file),
            "--planes",
            "0,45,90",
            "--out",
            s(&out),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(&out).unwrap().contains("C45–C225"));
    let (code, _, err) = run_cli(
        &["ldt", "plot", s(&file), "--planes", "200", "--out", s(&out)],
        "",
    );
    assert_eq!(code, 2, "{err}");
}

#[test]
fn the_report_is_one_self_contained_page_with_the_same_numbers() {
    let tmp = tempfile::tempdir().unwrap();
    let file = luminaire("eulumdat-luminance/sample_06.ldt");
    let out = tmp.path().join("sheet.html");
    let (code, _, err) = run_cli(&["ldt", "report", s(&file), "--out", s(&out)], "");
    assert_eq!(code, 0, "{err}");
    let html = std::fs::read_to_string(&out).unwrap();
    assert!(html.starts_with("<!doctype html>") && html.ends_with("</html>"));
    // Nothing fetched from elsewhere.
    assert!(
        !html.contains("src=") && !html.contains("href="),
        "external resources"
    );
    // Both diagrams inline, each a valid SVG.
    let svgs: Vec<&str> = html
        .split("<svg")
        .skip(1)
        .map(|t| &t[..t.find("</svg>").unwrap()])
        .collect();
    assert_eq!(svgs.len(), 3);
    for (k, body) in svgs.iter().enumerate() {
        let path = tmp.path().join(format!("d{k}.svg"));
        std::fs::write(&path, format!("<svg{body}</svg>")).unwrap();
        let picture = svg::render(&path);
        // Polar and cartesian: the red C0–C180 curve; isocandela: its lowest (amber) line.
        let colour = if k < 2 { [200, 30, 30] } else { [240, 170, 40] };
        assert!(
            svg::pixels_of(&picture, colour).len() > 300,
            "diagram {k} has its curve"
        );
    }
    // The summary, UGR and luminance figures are the commands' own, for lamp set 1.
    assert!(
        html.contains("1983 lm from 1983 lm of lamps"),
        "lamp set 1 throughout"
    );
    let (_, ugr, _) = run_cli(&["ldt", "ugr", s(&file), "--json"], "");
    let ugr: serde_json::Value = serde_json::from_str(&ugr).unwrap();
    let row: Vec<String> = ugr["crosswise"][8]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| format!("<td>{:.1}</td>", v.as_f64().unwrap()))
        .collect();
    assert!(
        html.contains(&format!("<td>4H × 4H</td>{}", row.concat())),
        "4H×4H row"
    );
    let (_, lum, _) = run_cli(
        &["ldt", "luminance", s(&file), "--json", "--gamma-from", "45"],
        "",
    );
    let lum: serde_json::Value = serde_json::from_str(&lum).unwrap();
    let c90_g85 = lum["cd_m2"][6][8].as_f64().unwrap();
    assert!(
        html.contains(&format!("<td>{c90_g85:.0}</td>")),
        "{c90_g85}"
    );
    // An uplight's sheet says why it has no UGR table; other formats are refused.
    let up = luminaire("eulumdat-plot/sample_13_isym1.ldt");
    let (code, _, err) = run_cli(&["ldt", "report", s(&up), "--out", s(&out)], "");
    assert_eq!(code, 0, "{err}");
    let html = std::fs::read_to_string(&out).unwrap();
    assert!(html.contains("No UGR table:") && html.contains("indirect luminaire"));
    let (code, _, _) = run_cli(
        &[
            "ldt",
            "report",
            s(&file),
            "--out",
            s(&tmp.path().join("x.pdf")),
        ],
        "",
    );
    assert_eq!(code, 2);
}

#[test]
fn isocandela_lines_lie_where_the_distribution_has_their_level() {
    let lum = Luminaire::load(&luminaire("eulumdat-plot/sample_01_isym3.ldt")).unwrap();
    let diagram = Diagram {
        lum: &lum,
        file_name: "x".into(),
        planes: vec![0.0, 90.0],
        interp: Interp::CatmullRom,
        lamp_flux_lm: None,
    };
    let map = diagram.isocandela().unwrap();
    let peak = lum.summary().max_intensity;
    assert!(
        (5..=10).contains(&map.lines.len()),
        "{} levels",
        map.lines.len()
    );
    assert!(map.lines.iter().all(|l| l.level < peak));
    let mut points = 0;
    for line in &map.lines {
        for p in line.pieces.iter().flatten() {
            // Plan seen from above: x = γ cos C, y = γ sin C.
            let g = p[0].hypot(p[1]);
            let c = p[1].atan2(p[0]).to_degrees().rem_euclid(360.0);
            let i = lum.distribution.sample(c, g, Interp::CatmullRom);
            assert!(
                (i - line.level).abs() < 0.02 * peak,
                "level {} at C{c:.1} γ{g:.1}: {i}",
                line.level
            );
            points += 1;
        }
    }
    assert!(points > 1000, "{points} points");
    // The peak at C15 γ60 is inside the highest level's line: that line stays near it.
    let top = map.lines.last().unwrap();
    let (x, y) = (
        60f64 * 15f64.to_radians().cos(),
        60f64 * 15f64.to_radians().sin(),
    );
    let nearest = top
        .pieces
        .iter()
        .flatten()
        .map(|p| (p[0] - x).hypot(p[1] - y))
        .fold(f64::MAX, f64::min);
    assert!(nearest < 10.0, "highest line {nearest}° from the peak");
}

#[test]
fn the_isocandela_diagram_is_the_same_in_svg_and_png() {
    let tmp = tempfile::tempdir().unwrap();
    let file = luminaire("eulumdat-plot/sample_01_isym3.ldt");
    let (svg_path, png_path) =
        common::plot_svg_and_png(&file, &["--kind", "isocandela"], tmp.path(), "iso");
    let text = std::fs::read_to_string(&svg_path).unwrap();
    for needle in ["isocandela (cd/klm)", "C0 right, C90 up,", "C270", "700"] {
        assert!(text.contains(needle), "{needle} missing");
    }
    let (vector, raster) = (svg::render(&svg_path), svg::load_png(&png_path));
    // The lowest level's colour (light amber): the outer line, the same in both.
    let rgb = [240, 170, 40];
    let (a, b) = (svg::pixels_of(&vector, rgb), svg::pixels_of(&raster, rgb));
    assert!(a.len() > 300 && b.len() > 300, "{} / {}", a.len(), b.len());
    let chart = |p: &[(u32, u32)]| {
        let xs = || p.iter().filter(|q| q.0 < 820 && q.1 > 90).map(|q| q.0);
        [xs().min().unwrap(), xs().max().unwrap()]
    };
    let (ba, bb) = (chart(&a), chart(&b));
    assert!(
        ba[0].abs_diff(bb[0]) <= 4 && ba[1].abs_diff(bb[1]) <= 4,
        "{ba:?} vs {bb:?}"
    );
}

#[test]
fn the_svg_report_is_one_page_with_the_html_reports_content() {
    let tmp = tempfile::tempdir().unwrap();
    let file = luminaire("eulumdat-luminance/sample_06.ldt");
    let (svg_path, html_path) = (tmp.path().join("sheet.svg"), tmp.path().join("sheet.html"));
    for out in [&svg_path, &html_path] {
        let (code, _, err) = run_cli(&["ldt", "report", s(&file), "--out", s(out)], "");
        assert_eq!(code, 0, "{err}");
    }
    let text = std::fs::read_to_string(&svg_path).unwrap();
    let html = std::fs::read_to_string(&html_path).unwrap();
    // The same cells as the HTML sheet, each as an SVG text (a long summary value over
    // several lines, word by word).
    let cells: Vec<&str> = html
        .split("<td>")
        .skip(1)
        .map(|c| &c[..c.find("</td>").unwrap()])
        .collect();
    assert!(cells.len() > 19 * 11 + 9 * 25, "{} cells", cells.len());
    for cell in &cells {
        let whole = text.contains(&format!(">{cell}</text>"));
        let words = cell.split(' ').all(|w| text.contains(w));
        assert!(whole || (cell.contains(' ') && words), "{cell} missing");
    }
    for needle in [
        "UGR table (CIE 117/190)",
        "viewed endwise",
        "Luminance (cd/m²)",
    ] {
        assert!(text.contains(needle), "{needle} missing");
    }
    // It renders, with every diagram's curves: red (polar, cartesian) and amber (isocandela).
    let picture = svg::render(&svg_path);
    if let Some(dir) = std::env::var_os("GONIOLIGHT_KEEP_PICTURES") {
        svg::save_png(&picture, &std::path::Path::new(&dir).join("sheet.png"));
    }
    // At half size the lines are one pixel wide and blend with white: found by hue.
    let hue = |keep: fn([i32; 3]) -> bool| -> Vec<(u32, u32)> {
        let w = picture.width;
        (0..picture.rgb.len() as u32)
            .filter(|&i| keep(picture.rgb[i as usize].map(i32::from)))
            .map(|i| (i % w, i / w))
            .collect()
    };
    let red = hue(|[r, g, b]| r - g > 70 && (g - b).abs() < 25);
    let amber = hue(|[r, g, b]| r - b > 90 && g - b > 45 && r > g);
    assert!(
        red.len() > 300 && amber.len() > 300,
        "{} / {}",
        red.len(),
        amber.len()
    );
    // Polar at the right of the summary, cartesian below it at the left.
    assert!(red.iter().any(|p| p.0 > 600) && red.iter().any(|p| p.0 < 500));
    // The tables sit below the diagrams: the UGR heading's y is below every curve pixel.
    let heading_y: f64 = text
        .split("<text")
        .find(|t| t.contains("UGR table (CIE"))
        .and_then(|t| t.split("y=\"").nth(1)?.split('"').next()?.parse().ok())
        .unwrap();
    let lowest = red.iter().chain(&amber).map(|p| p.1).max().unwrap() as f64;
    assert!(
        heading_y > lowest,
        "UGR heading at {heading_y}, curves to {lowest}"
    );
}
