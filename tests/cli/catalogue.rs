//! `ldt` commands over many files at once: directories walked, one broken file reported
//! while the others go on (exit 2), the catalogue table and summary of `ldt check`, and the
//! residuals it writes.

use crate::common;
use crate::svg_common as svg;

use std::path::{Path, PathBuf};

use common::{luminaire, run_cli};
use serde_json::Value;

/// A folder with three good files (two EULUMDAT, one IES in a subfolder) and a broken one.
fn catalogue_with_a_broken_file(dir: &Path) -> Vec<PathBuf> {
    let sub = dir.join("sub");
    std::fs::create_dir_all(&sub).unwrap();
    let good = [
        (
            luminaire("eulumdat-plot/sample_01_isym3.ldt"),
            dir.join("a.ldt"),
        ),
        (
            luminaire("eulumdat-plot/sample_02_isym4.ldt"),
            dir.join("b.LDT"),
        ),
        (
            luminaire("photometric-viewer/ies95/round_opening.ies"),
            sub.join("c.ies"),
        ),
    ];
    for (from, to) in &good {
        std::fs::copy(from, to).unwrap();
    }
    std::fs::write(dir.join("broken.ldt"), "only a name line\n").unwrap();
    std::fs::write(dir.join("notes.txt"), "not a luminaire\n").unwrap();
    good.into_iter().map(|(_, to)| to).collect()
}

/// The fields of one CSV line (RFC 4180 quoting), read independently of the writer.
fn csv_fields(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                fields.last_mut().unwrap().push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(String::new()),
            (c, _) => fields.last_mut().unwrap().push(c),
        }
    }
    fields
}

fn json(text: &str) -> Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_broken_file_is_named_and_the_others_go_on() {
    let tmp = tempfile::tempdir().unwrap();
    let good = catalogue_with_a_broken_file(tmp.path());
    let dir = s(tmp.path());
    for args in [
        vec!["ldt", "info", dir, "--json"],
        vec!["ldt", "info", dir, "--csv"],
        vec!["ldt", "check", dir, "--json"],
    ] {
        let (code, out, err) = run_cli(&args, "");
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains("broken.ldt: line"), "{args:?}: {err}");
        assert!(err.contains("1 of 4 luminaire files failed"), "{err}");
        assert!(!err.contains("notes.txt"), "only .ldt/.ies are read: {err}");
        for g in &good {
            assert!(
                out.contains(s(g)),
                "{args:?}: {} missing in {out}",
                g.display()
            );
        }
    }
    // Conversion goes on past the broken file too; nothing is written for it.
    let out_dir = tmp.path().join("converted");
    let (code, _, err) = run_cli(
        &[
            "ldt",
            "convert",
            dir,
            "--to",
            "ies",
            "--out-dir",
            s(&out_dir),
        ],
        "",
    );
    assert_eq!(code, 2, "{err}");
    let mut written: Vec<String> = std::fs::read_dir(&out_dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    assert_eq!(written, ["a.ies", "b.ies", "c.ies"]);
}

#[test]
fn info_csv_is_one_row_per_file_with_the_json_figures() {
    let files = [
        luminaire("eulumdat-luminance/sample_01.ldt"),
        luminaire("eulumdat-luminance/sample_06.ldt"),
        luminaire("photometric-viewer/ies95/absolute_photometry.ies"),
    ];
    let mut args = vec!["ldt", "info", "--csv"];
    args.extend(files.iter().map(|f| s(f)));
    let (code, out, err) = run_cli(&args, "");
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 1 + files.len(), "{out}");
    let header = csv_fields(lines[0]);
    for key in [
        "path",
        "name",
        "format",
        "isym",
        "flux_lm",
        "lor_percent",
        "dff_percent",
        "i_max_cd_klm",
        "beam_c0_c180_deg",
        "field_c90_c270_deg",
        "efficacy_lm_w",
    ] {
        assert!(
            header.iter().any(|h| h == key),
            "{key} missing from {header:?}"
        );
    }
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    // The IES file's name holds commas: quoted, it stays one field.
    let ies = csv_fields(lines[3]);
    assert!(
        ies[col("name")].starts_with("Dummy IES file. Can be used"),
        "{ies:?}"
    );
    for (file, line) in files.iter().zip(&lines[1..]) {
        let row = csv_fields(line);
        assert_eq!(row.len(), header.len(), "{line}");
        assert_eq!(row[col("path")], s(file));
        let (_, one, _) = run_cli(&["ldt", "info", s(file), "--json"], "");
        let info = json(&one);
        let flux: f64 = row[col("flux_lm")].parse().unwrap();
        assert!(
            (flux - info["flux_lm"].as_f64().unwrap()).abs() <= 0.05,
            "{line}"
        );
        assert_eq!(
            row[col("isym")],
            info["symmetry"].as_u64().unwrap().to_string()
        );
        let watts: f64 = info["lamp_sets"]
            .as_array()
            .unwrap()
            .iter()
            .map(|l| l["watts"].as_f64().unwrap())
            .sum();
        let efficacy = row[col("efficacy_lm_w")].as_str();
        if watts > 0.0 {
            let e: f64 = efficacy.parse().unwrap();
            assert!((e - info["flux_lm"].as_f64().unwrap() / watts).abs() <= 0.05);
        } else {
            assert_eq!(efficacy, "", "no watts, no efficacy");
        }
    }
    // sample_01: 4828 lm lamps, 30.7 W (the file's own figures), DFF 89 %.
    let row = csv_fields(lines[1]);
    assert_eq!(row[col("watts")], "30.7");
    let e: f64 = row[col("efficacy_lm_w")].parse().unwrap();
    assert!((155.0..160.0).contains(&e), "{e}");
}

#[test]
fn catalogue_rows_equal_the_single_file_checks_and_the_summary_follows_from_them() {
    let files = [
        luminaire("eulumdat-plot/sample_01_isym3.ldt"),
        luminaire("eulumdat-plot/sample_07_isym4.ldt"),
        luminaire("eulumdat-plot/sample_13_isym1.ldt"),
    ];
    let mut args = vec!["ldt", "check", "--downsample", "30,10", "--json"];
    args.extend(files.iter().map(|f| s(f)));
    let (code, out, err) = run_cli(&args, "");
    assert_eq!(code, 0, "{err}");
    let all = json(&out);
    let rows = all["files"].as_array().unwrap();
    assert_eq!(rows.len(), files.len());
    for (file, row) in files.iter().zip(rows) {
        assert_eq!(row["path"], s(file));
        let (code, one, err) = run_cli(
            &["ldt", "check", s(file), "--downsample", "30,10", "--json"],
            "",
        );
        assert_eq!(code, 0, "{err}");
        assert_eq!(row["report"], json(&one), "{}", file.display());
    }
    // The summary recomputed from the rows: medians, worst values and wins.
    let summary = &all["summary"];
    assert_eq!(summary["files"], 3);
    let methods = ["nearest", "bilinear", "catmull_rom", "monotone"];
    let rms = |f: usize, m: &str| rows[f]["report"]["methods"][m]["rms"].as_f64().unwrap();
    for m in methods {
        let mut v: Vec<f64> = (0..3).map(|f| rms(f, m)).collect();
        v.sort_by(f64::total_cmp);
        let stats = &summary["metrics"]["rms"][m];
        assert_eq!(stats["median"].as_f64().unwrap(), v[1], "{m}");
        assert_eq!(stats["worst"].as_f64().unwrap(), v[2], "{m}");
        let wins = (0..3)
            .filter(|&f| methods.iter().all(|o| rms(f, m) <= rms(f, o)))
            .count();
        assert_eq!(stats["wins"].as_u64().unwrap() as usize, wins, "{m}");
    }
    let total_wins: u64 = methods
        .iter()
        .map(|m| summary["metrics"]["rms"][m]["wins"].as_u64().unwrap())
        .sum();
    assert!(total_wins >= 3, "every file has a winner");
    // The text table: one line per file, each metric's winner marked.
    let mut args = vec!["ldt", "check", "--downsample", "30,10"];
    args.extend(files.iter().map(|f| s(f)));
    let (code, table, _) = run_cli(&args, "");
    assert_eq!(code, 0);
    for file in &files {
        let name = file.file_name().unwrap().to_str().unwrap();
        let line = table.lines().find(|l| l.starts_with(name)).unwrap();
        assert!(line.matches('*').count() >= 4, "{line}");
    }
    assert!(table.contains("summary over 3 files"), "{table}");
}

#[test]
fn residuals_are_written_as_csv_chart_and_heat_map() {
    let tmp = tempfile::tempdir().unwrap();
    let file = luminaire("eulumdat-plot/sample_01_isym3.ldt");
    let dir = tmp.path().join("res");
    let (code, out, err) = run_cli(
        &["ldt", "check", s(&file), "--json", "--residuals", s(&dir)],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let report = json(&out);
    let csv = std::fs::read_to_string(dir.join("sample_01_isym3.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "c_deg,gamma_deg,measured_cd_klm,nearest,bilinear,catmull_rom,monotone"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len() as u64, report["held_out"].as_u64().unwrap());
    // The residuals give back each method's RMS and largest error.
    for (k, m) in ["nearest", "bilinear", "catmull_rom", "monotone"]
        .iter()
        .enumerate()
    {
        let sq: f64 = rows.iter().map(|r| r[3 + k] * r[3 + k]).sum();
        let rms = (sq / rows.len() as f64).sqrt();
        let want = report["methods"][m]["rms"].as_f64().unwrap();
        assert!(
            (rms - want).abs() <= 1e-9 * want.max(1.0),
            "{m}: {rms} vs {want}"
        );
        let max_abs = rows.iter().map(|r| r[3 + k].abs()).fold(0.0, f64::max);
        let want = report["methods"][m]["max_abs"].as_f64().unwrap();
        assert!((max_abs - want).abs() <= 1e-9 * want.max(1.0), "{m}");
    }
    // The measured column is the file's value at that angle (the same as sampling the
    // full file there, which every method reproduces at a measured angle).
    let probe: String = rows
        .iter()
        .take(20)
        .map(|r| format!("{} {}\n", r[0], r[1]))
        .collect();
    let (_, sampled, _) = run_cli(&["ldt", "sample", s(&file), "--interp", "bilinear"], &probe);
    for (r, v) in rows.iter().zip(sampled.lines()) {
        let v: f64 = v.parse().unwrap();
        assert!(
            (v - r[2]).abs() <= 1e-9 * r[2].abs().max(1.0),
            "{r:?} vs {v}"
        );
    }
    let png = image::open(dir.join("sample_01_isym3-heatmap.png")).unwrap();
    assert_eq!((png.width(), png.height()), (1400, 900));
    let svg = svg::render(&dir.join("sample_01_isym3-gamma.svg"));
    for (name, rgb) in [
        ("nearest", [150, 150, 150]),
        ("Catmull-Rom", [30, 90, 230]),
        ("monotone", [20, 160, 60]),
    ] {
        assert!(
            svg::pixels_of(&svg, rgb).len() > 200,
            "{name}'s curve not drawn"
        );
    }
}

#[test]
fn plot_and_convert_name_outputs_after_inputs() {
    let tmp = tempfile::tempdir().unwrap();
    let files = [
        luminaire("eulumdat-plot/sample_01_isym3.ldt"),
        luminaire("eulumdat-plot/sample_05_isym1.ldt"),
    ];
    // --out names one file: several inputs are refused before anything is written.
    let out = tmp.path().join("x.png");
    let (code, _, err) = run_cli(
        &["ldt", "plot", s(&files[0]), s(&files[1]), "--out", s(&out)],
        "",
    );
    assert_eq!(code, 2);
    assert!(err.contains("--out-dir"), "{err}");
    assert!(!out.exists());
    let plots = tmp.path().join("plots");
    let (code, _, err) = run_cli(
        &[
            "ldt",
            "plot",
            s(&files[0]),
            s(&files[1]),
            "--out-dir",
            s(&plots),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    for stem in ["sample_01_isym3", "sample_05_isym1"] {
        let img = image::open(plots.join(format!("{stem}.png"))).unwrap();
        assert!(img.width() > 100);
    }
    // Each converted file equals the single-file conversion, byte for byte.
    let conv = tmp.path().join("ies");
    let (code, _, err) = run_cli(
        &[
            "ldt",
            "convert",
            s(&files[0]),
            s(&files[1]),
            "--to",
            "ies",
            "--out-dir",
            s(&conv),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    for (file, stem) in files.iter().zip(["sample_01_isym3", "sample_05_isym1"]) {
        let one = tmp.path().join(format!("{stem}-one.ies"));
        let (code, _, _) = run_cli(&["ldt", "convert", s(file), "--out", s(&one)], "");
        assert_eq!(code, 0);
        assert_eq!(
            std::fs::read(conv.join(format!("{stem}.ies"))).unwrap(),
            std::fs::read(&one).unwrap()
        );
    }
    // Next to the input, a file already in the target format is left alone (exit 0).
    let beside = tmp.path().join("beside");
    std::fs::create_dir_all(&beside).unwrap();
    std::fs::copy(&files[0], beside.join("a.ldt")).unwrap();
    std::fs::copy(conv.join("sample_05_isym1.ies"), beside.join("b.ies")).unwrap();
    let before = std::fs::read(beside.join("b.ies")).unwrap();
    let (code, _, err) = run_cli(&["ldt", "convert", s(&beside), "--to", "ies"], "");
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("b.ies: already .ies"), "{err}");
    assert!(beside.join("a.ies").exists());
    assert_eq!(std::fs::read(beside.join("b.ies")).unwrap(), before);
    // Two inputs with one name would overwrite each other in one folder: the second fails.
    let (code, _, err) = run_cli(
        &[
            "ldt",
            "convert",
            s(&beside.join("a.ldt")),
            s(&beside.join("a.ies")),
            "--to",
            "ldt",
            "--out-dir",
            s(&tmp.path().join("twice")),
        ],
        "",
    );
    assert_eq!(code, 2);
    assert!(err.contains("would overwrite the one written for"), "{err}");
}

#[test]
fn sample_prints_one_column_per_file() {
    let files = [
        luminaire("eulumdat-plot/sample_01_isym3.ldt"),
        luminaire("eulumdat-plot/sample_05_isym1.ldt"),
    ];
    let angles = "0 0\n45 30\n200 65.5\n";
    let (code, out, err) = run_cli(&["ldt", "sample", s(&files[0]), s(&files[1])], angles);
    assert_eq!(code, 0, "{err}");
    let mut lines = out.lines();
    assert_eq!(
        lines.next().unwrap(),
        format!("# columns: {} {}", s(&files[0]), s(&files[1]))
    );
    let table: Vec<Vec<String>> = lines
        .map(|l| l.split(' ').map(str::to_string).collect())
        .collect();
    for (k, file) in files.iter().enumerate() {
        let (_, one, _) = run_cli(&["ldt", "sample", s(file)], angles);
        let column: Vec<String> = table.iter().map(|row| row[k].clone()).collect();
        assert_eq!(column, one.lines().collect::<Vec<_>>());
    }
}

#[test]
fn the_check_picture_in_svg_shows_the_png_curves() {
    let tmp = tempfile::tempdir().unwrap();
    let file = luminaire("eulumdat-plot/sample_01_isym3.ldt");
    let (svg_path, png_path) =
        common::plot_svg_and_png(&file, &["--downsample", "30,10"], tmp.path(), "p");
    let vector = svg::render(&svg_path);
    let raster = svg::load_png(&png_path);
    assert_eq!(vector.width, raster.width);
    // The measured marks (red) and the Catmull-Rom curve (blue) in the same places: the
    // bounding boxes of their pixels agree within a few pixels.
    for rgb in [[220, 30, 30], [30, 90, 230]] {
        let (a, b) = (svg::pixels_of(&vector, rgb), svg::pixels_of(&raster, rgb));
        assert!(
            a.len() > 100 && b.len() > 100,
            "{rgb:?}: {} vs {}",
            a.len(),
            b.len()
        );
        let bbox = |p: &[(u32, u32)]| {
            let xs = p.iter().map(|q| q.0);
            let ys = p.iter().map(|q| q.1);
            [
                xs.clone().min().unwrap(),
                xs.max().unwrap(),
                ys.clone().min().unwrap(),
                ys.max().unwrap(),
            ]
        };
        let (ba, bb) = (bbox(&a), bbox(&b));
        for k in 0..4 {
            assert!(ba[k].abs_diff(bb[k]) <= 4, "{rgb:?}: {ba:?} vs {bb:?}");
        }
    }
    // Directories into SVG by --format; an unknown extension is refused.
    let dir = tmp.path().join("svgs");
    let (code, _, err) = run_cli(
        &[
            "ldt",
            "plot",
            s(&file),
            "--out-dir",
            s(&dir),
            "--format",
            "svg",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    svg::render(&dir.join("sample_01_isym3.svg"));
    let (code, _, err) = run_cli(
        &[
            "ldt",
            "plot",
            s(&file),
            "--out",
            s(&tmp.path().join("p.pdf")),
        ],
        "",
    );
    assert_eq!(code, 2);
    assert!(err.contains(".png or .svg"), "{err}");
}
