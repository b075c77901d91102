//! Mutation fuzzing of every reader on stable Rust, time-boxed: luminaire files (LDT, IES,
//! TM-33 / ATLA XML and JSON), OBJ meshes, MTL materials, scene TOML, EPW weather files and the point and angle lists read from
//! stdin. Seeds are the real
//! files (bundled luminaires, the wild corpus in `../shared`, the bundled scenes); each
//! case applies a few structure-aware mutations (extreme numbers in place of numbers,
//! lines deleted, duplicated or swapped, truncation, byte flips, splices).
//!
//! Every case must end without a panic, and what is accepted must be usable: finite,
//! non-negative intensities and flux, files the writers produce read back with the same
//! table, mesh indices inside the mesh. A failing input is written to
//! `target/fuzz-found/`; once fixed, keep it in `tests/data/fuzz-found/` (`.lum` for
//! luminaires), where it becomes a seed that must pass.
//!
//! `GONIOLIGHT_FUZZ_SECONDS` sets the budget of each target (default 10, as in the gate;
//! `scripts/fuzz.sh` runs them for 10 minutes each, for nightly use) and
//! `GONIOLIGHT_FUZZ_SEED` the first seed (default: fixed, so a run repeats).

use crate::common;

use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use goniolight::geometry::obj::{parse_mtl, parse_obj};
use goniolight::lighting::{read_angles, read_points};
use goniolight::photometry::convert::{convert, OutputFormat};
use goniolight::photometry::ies::write_ies;
use goniolight::photometry::{Interp, Luminaire};
use goniolight::scene::Scene;

/// xorshift64*: enough randomness to pick mutations, and reproducible from a seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Numbers that broke or nearly broke goniolight before: overflow, underflow, signs,
/// counts beyond every limit, things that are not numbers.
const EXTREMES: &[&str] = &[
    "1e308",
    "-1e308",
    "1e-320",
    "4.9e-324",
    "-1",
    "0",
    "-0",
    "1e9",
    "3601",
    "99999999999",
    "NaN",
    "inf",
    "",
    "0,5",
    "1e-7",
    "360",
    "180",
    "-90",
    "2",
    "3",
];

fn mutate(rng: &mut Rng, seed: &[u8], others: &[Vec<u8>]) -> Vec<u8> {
    let mut b = seed.to_vec();
    for _ in 0..1 + rng.below(4) {
        if b.is_empty() {
            b.extend_from_slice(b"1\n");
        }
        match rng.below(8) {
            0 | 1 => {
                // A number replaced by an extreme.
                let at = rng.below(b.len());
                if let Some(start) = (0..=at).rev().find(|&i| b[i].is_ascii_digit()) {
                    let mut lo = start;
                    while lo > 0 && !b[lo - 1].is_ascii_whitespace() {
                        lo -= 1;
                    }
                    let mut hi = start;
                    while hi < b.len() && !b[hi].is_ascii_whitespace() {
                        hi += 1;
                    }
                    let x = EXTREMES[rng.below(EXTREMES.len())].as_bytes();
                    b.splice(lo..hi, x.iter().copied());
                }
            }
            2 | 3 => {
                // A line deleted, duplicated or moved.
                let mut lines: Vec<Vec<u8>> =
                    b.split(|&c| c == b'\n').map(<[u8]>::to_vec).collect();
                let i = rng.below(lines.len());
                match rng.below(3) {
                    0 => {
                        lines.remove(i);
                    }
                    1 => {
                        let l = lines[i].clone();
                        for _ in 0..1 + rng.below(3) {
                            lines.insert(i, l.clone());
                        }
                    }
                    _ => {
                        let j = rng.below(lines.len());
                        lines.swap(i, j);
                    }
                }
                b = lines.join(&b'\n');
            }
            4 => {
                let at = rng.below(b.len());
                b.truncate(at);
            }
            5 => {
                let at = rng.below(b.len());
                b[at] = b"0123456789.-+eE ,\n\r\t#[]=\"\x00\xff\xe4"[rng.below(27)];
            }
            6 => {
                let at = rng.below(b.len() + 1);
                let x = EXTREMES[rng.below(EXTREMES.len())].as_bytes();
                let sep: &[u8] = if rng.below(2) == 0 { b"\n" } else { b" " };
                b.splice(at..at, sep.iter().chain(x).copied());
            }
            _ => {
                // The tail of another seed spliced on.
                let other = &others[rng.below(others.len())];
                let at = rng.below(b.len());
                let from = rng.below(other.len());
                b.truncate(at);
                b.extend_from_slice(&other[from..]);
            }
        }
    }
    b
}

fn budget() -> Duration {
    let s = std::env::var("GONIOLIGHT_FUZZ_SECONDS")
        .ok()
        .and_then(|v| v.parse::<f64>().ok())
        .unwrap_or(10.0);
    Duration::from_secs_f64(s)
}

fn first_seed(target: &str) -> u64 {
    let base = std::env::var("GONIOLIGHT_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse::<u64>().ok())
        .unwrap_or(0x9E37_79B9_7F4A_7C15);
    target
        .bytes()
        .fold(base, |h, c| (h ^ c as u64).wrapping_mul(0x100_0000_01B3))
        | 1
}

/// Runs `check` on mutations of `seeds` for the budget; saves and reports failures.
fn fuzz(target: &str, ext: &str, seeds: &[Vec<u8>], check: impl Fn(&[u8]) -> Result<(), String>) {
    assert!(!seeds.is_empty(), "{target}: no seeds");
    let mut rng = Rng(first_seed(target));
    let started = Instant::now();
    let (mut cases, mut accepted) = (0usize, 0usize);
    let mut failures = Vec::new();
    let found = common::root().join("target/fuzz-found");
    // Seeds first (they must pass as they are), then mutations until the budget is spent.
    while cases < seeds.len() || started.elapsed() < budget() {
        let input = if cases < seeds.len() {
            seeds[cases].clone()
        } else {
            let k = rng.below(seeds.len());
            mutate(&mut rng, &seeds[k], seeds)
        };
        cases += 1;
        let t0 = Instant::now();
        let outcome = std::panic::catch_unwind(AssertUnwindSafe(|| check(&input)));
        let slow = t0.elapsed() > Duration::from_secs(10);
        let problem = match outcome {
            Ok(Ok(())) if !slow => {
                accepted += 1;
                continue;
            }
            Ok(Ok(())) => format!("took {:?}", t0.elapsed()),
            Ok(Err(e)) => e,
            Err(_) => "panicked".to_string(),
        };
        let _ = std::fs::create_dir_all(&found);
        let file = found.join(format!("{target}-{cases}.{ext}"));
        let _ = std::fs::write(&file, &input);
        failures.push(format!("{}: {problem}", file.display()));
        if failures.len() >= 10 {
            break;
        }
    }
    eprintln!(
        "fuzz {target}: {cases} cases in {:.1} s ({accepted} ended well), {} failures",
        started.elapsed().as_secs_f64(),
        failures.len()
    );
    assert!(failures.is_empty(), "{target}:\n{}", failures.join("\n"));
}

fn read_all(files: impl IntoIterator<Item = PathBuf>) -> Vec<Vec<u8>> {
    files
        .into_iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect()
}

fn files_under(dir: &Path, exts: &[&str], out: &mut Vec<PathBuf>) {
    out.extend(common::files_with(dir, exts));
}

/// What an accepted luminaire must be: usable numbers, and both writers' output read back
/// with the same table.
fn luminaire_is_usable(name: &str, bytes: &[u8]) -> Result<(), String> {
    let Ok(lum) = Luminaire::from_bytes(name, bytes) else {
        return Ok(());
    };
    let d = &lum.distribution;
    if d.grid().values().iter().any(|v| !v.is_finite() || *v < 0.0) {
        return Err("accepted a non-finite or negative intensity".into());
    }
    let (lamp, flux) = (d.lamp_flux_lm(), d.flux_lm());
    if !(lamp.is_finite() && lamp > 0.0 && flux.is_finite() && flux >= 0.0) {
        return Err(format!("accepted lamp flux {lamp}, flux {flux}"));
    }
    let _ = lum.summary();
    let peak = d.max_intensity().0 * lamp / 1000.0;
    let tm33 = |to| convert(&lum, to, false).map(|c| c.text).unwrap_or_default();
    for (ext, text) in [
        ("ldt", lum.data.to_ldt_string()),
        ("ies", write_ies(&lum.data, lum.source_label())),
        ("xml", tm33(OutputFormat::Tm33)),
        ("json", tm33(OutputFormat::Atla)),
    ] {
        let back = Luminaire::from_bytes(&format!("w.{ext}"), text.as_bytes())
            .map_err(|e| format!("its {ext} is refused: {e}"))?;
        let b = &back.distribution;
        for (ci, &c) in d.grid().c_angles().iter().enumerate() {
            for (gi, &g) in d.grid().gamma_angles().iter().enumerate() {
                let want = d.grid().value(ci, gi) * lamp / 1000.0;
                let got = b.candela(c, g, Interp::Nearest, 1.0);
                if (got - want).abs() > 1e-9 * peak {
                    return Err(format!("{ext} round trip: C{c} γ{g} {want} → {got} cd"));
                }
            }
        }
    }
    Ok(())
}

#[test]
fn fuzz_luminaire_readers_and_writers() {
    let mut files = Vec::new();
    files_under(
        &common::root().join("luminaires"),
        &["ldt", "ies"],
        &mut files,
    );
    files_under(
        &common::shared_dir().join("luminaires/wild"),
        &["ldt", "ies"],
        &mut files,
    );
    // The largest tables make slow cases; the small ones reach every branch.
    files.retain(|p| std::fs::metadata(p).unwrap().len() < 60_000);
    let seeds = read_all(files);
    fuzz("luminaire", "txt", &seeds, |bytes| {
        // The same bytes through both readers (the extension is only a hint).
        luminaire_is_usable("f.ldt", bytes)?;
        luminaire_is_usable("f.ies", bytes)
    });
}

#[test]
fn fuzz_tm33_reader() {
    let mut files = Vec::new();
    files_under(
        &common::shared_dir().join("luminaires/tm33"),
        &["xml", "json"],
        &mut files,
    );
    let seeds = read_all(files);
    for seed in &seeds {
        // The seeds themselves read: mutations start from valid files.
        Luminaire::from_bytes("seed.xml", seed).unwrap();
    }
    fuzz("tm33", "xml", &seeds, |bytes| {
        luminaire_is_usable("f.xml", bytes)?;
        luminaire_is_usable("f.json", bytes)
    });
}

#[test]
fn fuzz_obj_reader() {
    let mut files = Vec::new();
    files_under(&common::root().join("assets"), &["obj"], &mut files);
    files.retain(|p| std::fs::metadata(p).unwrap().len() < 300_000);
    let seeds = read_all(files);
    fuzz("obj", "obj", &seeds, |bytes| {
        let Ok(mut mesh) = parse_obj("f.obj", bytes) else {
            return Ok(());
        };
        let n = mesh.positions.len();
        if mesh.triangles.iter().flatten().any(|&i| i as usize >= n) {
            return Err(format!("a triangle indexes past the {n} vertices"));
        }
        mesh.remove_degenerate();
        let _ = mesh.validate("f.obj");
        Ok(())
    });
}

#[test]
fn fuzz_gltf_reader() {
    use crate::gltf_models::{document, FLOOR, FLOOR_TRIANGLES};
    use goniolight::geometry::gltf_file::parse;
    use serde_json::json;
    let cornell = common::shared_dir().join("models/gltf/CornellBox/CornellBox.glb");
    let lights = json!({"KHR_lights_punctual": {"lights": [
        {"type": "spot", "intensity": 50.0, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}
    ]}});
    let nodes = json!([{"translation": [0.0, 2.0, 0.0], "rotation": [0.0, 0.0, 0.0, 1.0],
                        "children": [], "extensions": {"KHR_lights_punctual": {"light": 0}}}]);
    let text = document(&FLOOR, &FLOOR_TRIANGLES, nodes, lights).to_string();
    let seeds = vec![std::fs::read(cornell).unwrap(), text.into_bytes()];
    let no_files = |uri: &str| -> Result<Vec<u8>, String> { Err(format!("{uri}: no files here")) };
    for seed in &seeds {
        // The seeds themselves read: mutations start from valid files.
        assert!(parse("seed", seed, &no_files).is_ok());
    }
    fuzz("gltf", "gltf", &seeds, |bytes| {
        let Ok(model) = parse("f.gltf", bytes, &no_files) else {
            return Ok(());
        };
        for p in &model.primitives {
            let n = p.positions.len();
            if p.triangles.iter().flatten().any(|&i| i as usize >= n) {
                return Err(format!("a triangle indexes past the {n} vertices"));
            }
            if p.positions.iter().any(|v| !v.is_finite()) {
                return Err("a position is not finite".into());
            }
        }
        for l in &model.lights {
            if !(l.position.is_finite() && l.frame.is_finite()) {
                return Err(format!("light {:?} is not finite", l.node));
            }
        }
        Ok(())
    });
}

#[test]
fn fuzz_scene_files() {
    let dir = common::root().join("assets/scenes");
    let mut files = Vec::new();
    files_under(&dir, &["toml"], &mut files);
    let seeds = read_all(files);
    // Scenes resolve their files against the bundled scenes' folder.
    let path = dir.join("fuzzed.toml");
    fuzz("scene", "toml", &seeds, |bytes| {
        let text = String::from_utf8_lossy(bytes);
        let Ok(scene) = Scene::from_toml(&path, &text) else {
            return Ok(());
        };
        for l in &scene.luminaires {
            if !l.position.is_finite() {
                return Err("accepted a non-finite luminaire position".into());
            }
        }
        for g in &scene.grids {
            if g.points.is_empty() || g.points.iter().any(|p| !p.is_finite()) {
                return Err(format!(
                    "accepted grid {:?} without usable points",
                    g.entry.name
                ));
            }
        }
        Ok(())
    });
}

#[test]
fn fuzz_point_lists() {
    let seeds = vec![
        b"1 1 0.8 0 0 1\n2 3 0 0 0 1\n".to_vec(),
        b"# x y z nx ny nz\n0.5,0.5,0.8,0,0,1\n\n1 2 3 0 1 0\n".to_vec(),
        b"3 2 0.8 0 0 1 extra\n".to_vec(),
    ];
    fuzz("points", "txt", &seeds, |bytes| {
        let Ok(points) = read_points(std::io::Cursor::new(bytes), "<stdin>") else {
            return Ok(());
        };
        for p in &points {
            let ok = p.position.is_finite() && p.normal.is_finite() && p.normal.length() > 0.5;
            if !ok {
                return Err(format!("accepted point {p:?}"));
            }
        }
        Ok(())
    });
}

#[test]
fn fuzz_mtl_reader() {
    let mut files = Vec::new();
    files_under(&common::root().join("assets"), &["mtl"], &mut files);
    let seeds = read_all(files);
    fuzz("mtl", "mtl", &seeds, |bytes| {
        let Ok((materials, _)) = parse_mtl("f.mtl", bytes) else {
            return Ok(());
        };
        for m in &materials {
            if m.diffuse.is_some_and(|d| d.iter().any(|x| !x.is_finite())) {
                return Err(format!(
                    "accepted material {:?} with a non-finite colour",
                    m.name
                ));
            }
        }
        Ok(())
    });
}

#[test]
fn fuzz_angle_lists() {
    let seeds = vec![
        b"0 0\n90 45\n".to_vec(),
        b"# C gamma\n370,12.5\n\n-15 180\n".to_vec(),
    ];
    fuzz("angles", "txt", &seeds, |bytes| {
        let Ok(angles) = read_angles(std::io::Cursor::new(bytes), "<stdin>") else {
            return Ok(());
        };
        for &(c, g) in &angles {
            if !c.is_finite() || !(0.0..=180.0).contains(&g) {
                return Err(format!("accepted C {c}, γ {g}"));
            }
        }
        Ok(())
    });
}

/// The scene's tables that name outputs and glare: `[[grid]]`, `[[area]]`, `[[emergency]]`
/// (and a luminaire's emergency output), `[[observer]]`,
/// `[[material]]` (seeds: the bundled calculation scene with each table added). What is
/// accepted must be computable: grids of finite points within the per-grid cap (the
/// areas' too), areas with finite limits and outlines, observers
/// with a finite eye and a unit line of sight, materials that send back at most what they
/// receive, no name twice.
#[test]
fn fuzz_scene_tables() {
    let dir = common::root().join("assets/scenes");
    let base = std::fs::read_to_string(dir.join("box_room_calc.toml")).unwrap();
    let tables = [
        "[[material]]\nname = \"wall\"\ndiffuse_reflectance = [0.5, 0.5, 0.5]\n",
        "[[material]]\nname = \"floor\"\ndiffuse_reflectance = [0.2, 0.2, 0.2]\ndiffuse_transmittance = [0.1, 0.1, 0.1]\n",
        "[[observer]]\nname = \"door\"\nposition = [0.5, 0.5, 1.6]\ndirection = [1.0, 0.3, 0.0]\n",
        "[[grid]]\nname = \"outline\"\noutline = [[0.5, 0.5], [3.0, 0.5], [2.0, 3.0]]\nheight = 0.8\nspacing = 0.25\n",
        "[[grid]]\nname = \"wall\"\nkind = \"vertical\"\ncorner = [0.0, 0.0]\nsize = [3.0, 2.0]\nnormal = [0.0, 1.0, 0.0]\n",
        "[[area]]\nname = \"desk\"\ncorner = [1.0, 1.0]\nsize = [1.6, 0.8]\nheight = 0.75\nem = 500\nu0 = 0.6\nra = 80\n",
        "[[area]]\nname = \"hall\"\nkind = \"area\"\noutline = [[0.5, 0.5], [3.0, 0.5], [2.0, 3.0]]\nem = 100\nez = 50\nugr_l = 22\n",
        "[[emergency]]\nname = \"route\"\nkind = \"route\"\nline = [[0, 1], [3, 1], [5, 3]]\nwidth = 1.5\n\n[[emergency]]\nname = \"x\"\nkind = \"point\"\nposition = [0.1, 2, 1.2]\nnormal = [1, 0, 0]\n\n[[luminaire]]\nfile = \"../../luminaires/eulumdat-plot/sample_06_isym1.ldt\"\nposition = [2, 2, 2.9]\nemergency_flux_lm = 250\n",
        "[[emergency]]\nname = \"hall\"\nkind = \"open-area\"\ncorner = [0, 0]\nsize = [6, 4]\n\n[[emergency]]\nname = \"saw\"\nkind = \"high-risk\"\noutline = [[1, 1], [2, 1], [2, 2]]\nem = 300\n",
        "[[area]]\nname = \"bench\"\noutline = [[1, 1], [2, 1], [2, 2]]\nroom = [[0, 0], [6, 0], [6, 2], [3, 2], [3, 4], [0, 4]]\nem = 300\nsurrounding_width = 1\nbackground_width = 4\n",
    ];
    let mut seeds = vec![base.clone().into_bytes()];
    seeds.extend(tables.iter().map(|t| format!("{base}\n{t}").into_bytes()));
    let path = dir.join("fuzzed.toml");
    fuzz("scene-tables", "toml", &seeds, |bytes| {
        let text = String::from_utf8_lossy(bytes);
        let Ok(scene) = Scene::from_toml(&path, &text) else {
            return Ok(());
        };
        let mut names = std::collections::HashSet::new();
        for g in &scene.grids {
            if g.points.is_empty()
                || g.points.len() > goniolight::scene::grid::MAX_POINTS
                || g.points.iter().any(|p| !p.is_finite())
            {
                return Err(format!(
                    "accepted grid {:?} without usable points",
                    g.entry.name
                ));
            }
            if !names.insert(g.entry.name.trim().to_lowercase()) {
                return Err(format!("accepted grid {:?} twice", g.entry.name));
            }
        }
        for a in &scene.areas {
            if a.grids.iter().any(|(_, k)| *k >= scene.grids.len())
                || a.requirements.iter().any(|r| !r.required.is_finite())
                || a.outline.iter().flatten().any(|v| !v.is_finite())
            {
                return Err(format!(
                    "accepted area {:?} with unusable grids or limits",
                    a.entry.name
                ));
            }
        }
        if let Ok(emergency) = scene.in_emergency() {
            let usable = emergency
                .grids
                .iter()
                .all(|g| !g.points.is_empty() && g.points.iter().all(|p| p.is_finite()))
                && emergency.areas.iter().all(|a| {
                    a.requirements.iter().all(|r| r.required.is_finite())
                        && a.grids.iter().all(|(_, k)| *k < emergency.grids.len())
                })
                && emergency
                    .luminaires
                    .iter()
                    .all(|l| l.multiplier.is_finite() && l.multiplier > 0.0);
            if !usable {
                return Err(
                    "accepted an emergency scene with unusable grids, limits or outputs".into(),
                );
            }
        }
        for o in &scene.observers {
            if !o.eye.is_finite() || (o.forward.length() - 1.0).abs() > 1e-9 {
                return Err(format!(
                    "accepted observer {:?}: eye {}, forward {}",
                    o.entry.name, o.eye, o.forward
                ));
            }
        }
        for m in &scene.materials {
            let sent = m.diffuse_reflectance()
                + m.diffuse_transmittance
                + m.specular_reflectance
                + m.specular_transmittance;
            if !sent.is_finite() || sent.max_element() > 1.0 + 1e-5 {
                return Err(format!(
                    "accepted material {:?} sending back {sent}",
                    m.name
                ));
            }
        }
        let mut overridden = std::collections::HashSet::new();
        for m in &scene.material_overrides {
            if !overridden.insert(m.name.as_str()) {
                return Err(format!("accepted [[material]] {:?} twice", m.name));
            }
        }
        Ok(())
    });
}

/// `batch`'s jobs files (seeds: the reproducers' and a full one): no panic, and an
/// accepted file has jobs.
#[test]
fn fuzz_jobs_files() {
    let mut files = Vec::new();
    files_under(
        &common::shared_dir().join("fuzz-crashes/outputs-and-limits"),
        &["toml"],
        &mut files,
    );
    let mut seeds: Vec<Vec<u8>> = read_all(files)
        .into_iter()
        .filter(|b| String::from_utf8_lossy(b).contains("[[job]]"))
        .collect();
    seeds.push(
        b"[[job]]\nname = \"a\"\nargs = [\"sun\", \"--lat\", \"48.2\", \"--lon\", \"16.4\", \"--time\", \"2026-03-21T12:00:00+01:00\"]\nstdout = \"out/a.txt\"\n\n[[job]]\nargs = [\"illuminance\", \"s.toml\"]\nstdin = \"p.txt\"\n".to_vec(),
    );
    let path = Path::new("jobs.toml");
    fuzz("jobs", "toml", &seeds, |bytes| {
        let text = String::from_utf8_lossy(bytes);
        match goniolight::cli::count_jobs(path, &text) {
            Ok(0) => Err("accepted a jobs file without jobs".into()),
            Ok(_) => Ok(()),
            Err(e) if e.message().contains("jobs.toml") => Ok(()),
            Err(e) => Err(format!(
                "an error that does not name the file: {}",
                e.message()
            )),
        }
    });
}

#[test]
fn fuzz_epw_reader() {
    use goniolight::planning::suns::ProbableSun;
    use goniolight::sun::{Site, SunOptions};
    use goniolight::weather::epw::{parse_epw, BUNDLED_EPW};
    let full = std::fs::read_to_string(common::root().join(BUNDLED_EPW)).unwrap();
    // The header and the first two days, and the header and a summer noon: mutations of
    // a whole year would spend the budget on copying.
    let lines: Vec<&str> = full.lines().collect();
    let seeds = vec![
        lines[..56].join("\n").into_bytes(),
        [&lines[..8], &lines[4200..4204]]
            .concat()
            .join("\n")
            .into_bytes(),
    ];
    let site = Site::new(41.98, -87.92, 0.0).unwrap();
    fuzz("epw", "epw", &seeds, |bytes| {
        let text = String::from_utf8_lossy(bytes);
        let Ok(weather) = parse_epw(Path::new("f.epw"), &text) else {
            return Ok(());
        };
        let l = &weather.location;
        if !(l.latitude.abs() <= 90.0 && l.longitude.abs() <= 180.0 && l.time_zone_h.abs() <= 14.0)
        {
            return Err(format!("accepted location {l:?}"));
        }
        for h in &weather.hours {
            let fields = [
                h.global_horizontal_w,
                h.direct_normal_w,
                h.diffuse_horizontal_w,
                h.global_horizontal_lux,
                h.direct_normal_lux,
                h.diffuse_horizontal_lux,
            ];
            if fields
                .iter()
                .flatten()
                .any(|v| !(v.is_finite() && *v >= 0.0))
                || !(1..=24).contains(&h.hour)
            {
                return Err(format!("accepted hour {h:?}"));
            }
            let _ = h.utc_midpoint(l.time_zone_h);
        }
        // What is accepted goes on to the sun's positions without a panic.
        let _ = ProbableSun::of(&weather, &site, &SunOptions::default());
        Ok(())
    });
}
