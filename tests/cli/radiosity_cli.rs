//! `goniolight radiosity` end to end: the furnace through the command (points, light map,
//! rendering), the box room against Radiance's numbers (stored by
//! scripts/compare_radiance.py), the stop conditions and bad input.

use crate::common;
use crate::gpu_common;

use std::path::Path;

use common::{root, run_cli};

/// A closed 2 × 1.5 × 1 m box, faces inward, reflectance `rho`, exitance `e` (lm/m²).
fn write_furnace(dir: &Path, rho: f64, e: f64) -> std::path::PathBuf {
    let (x, y, z) = (2.0, 1.5, 1.0);
    let v = [
        (0., 0., 0.),
        (x, 0., 0.),
        (x, y, 0.),
        (0., y, 0.),
        (0., 0., z),
        (x, 0., z),
        (x, y, z),
        (0., y, z),
    ];
    let mut obj = String::from("mtllib furnace.mtl\nusemtl glow\n");
    for (a, b, c) in v {
        obj.push_str(&format!("v {a} {b} {c}\n"));
    }
    // Counter-clockwise seen from inside.
    for f in [
        [1, 2, 3, 4],
        [5, 8, 7, 6],
        [1, 5, 6, 2],
        [2, 6, 7, 3],
        [3, 7, 8, 4],
        [4, 8, 5, 1],
    ] {
        obj.push_str(&format!("f {} {} {} {}\n", f[0], f[1], f[2], f[3]));
    }
    std::fs::write(dir.join("furnace.obj"), obj).unwrap();
    std::fs::write(
        dir.join("furnace.mtl"),
        format!("newmtl glow\nKd {rho} {rho} {rho}\nKe {e} {e} {e}\n"),
    )
    .unwrap();
    let toml = "[[model]]\npath = \"furnace.obj\"\nup = \"z\"\n\n[camera]\nposition = [0.2, 0.2, 0.5]\nlook_at = [1.8, 1.3, 0.4]\nfov_deg = 80.0\n\n[display]\nmode = \"illuminance\"\nwidth = 96\nheight = 64\n";
    let path = dir.join("furnace.toml");
    std::fs::write(&path, toml).unwrap();
    path
}

fn read_exr(path: &Path) -> image::Rgb32FImage {
    image::open(path).unwrap().to_rgb32f()
}

#[test]
fn furnace_through_the_command_gives_e_over_one_minus_rho_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_furnace(dir.path(), 0.5, 100.0);
    let out = dir.path().join("out");
    // Points anywhere inside, facing anywhere, see B = E / (1 − ρ) = 200 lm/m² all round.
    let points = "1.0 0.75 0.0 0 0 1\n0.3 1.2 0.5 1 -1 0.3\n1.9 0.1 0.9 -0.2 0.3 -1\n";
    let (code, stdout, stderr) = run_cli(
        &[
            "radiosity",
            scene.to_str().unwrap(),
            "--points",
            "--converge",
            "0.999",
            "--texel-density",
            "8",
            "--out-dir",
            out.to_str().unwrap(),
        ],
        points,
    );
    assert_eq!(code, 0, "{stderr}");
    let lux: Vec<f64> = stdout.lines().map(|l| l.parse().unwrap()).collect();
    assert_eq!(lux.len(), 3);
    for v in &lux {
        assert!((v / 200.0 - 1.0).abs() < 0.01, "{lux:?}");
    }
    // The light map: radiosity 200 lm/m² and illuminance 200 lx on every used texel.
    let atlas = read_exr(&out.join("lightmap.exr"));
    let lux_map = read_exr(&out.join("lightmap_lux.exr"));
    let used: Vec<(f32, f32)> = atlas
        .pixels()
        .zip(lux_map.pixels())
        .filter(|(b, _)| b[0] > 0.0)
        .map(|(b, e)| (b[0], e[0]))
        .collect();
    assert!(used.len() > 500, "{}", used.len());
    for (b, e) in &used {
        assert!(
            (b / 200.0 - 1.0).abs() < 0.01 && (e / 200.0 - 1.0).abs() < 0.01,
            "{b} {e}"
        );
    }
    // The rendering shows the solution: 200 lx on every pixel (illuminance mode), and the
    // log ends converged.
    let render = read_exr(&out.join("render.exr"));
    for p in render.pixels() {
        assert!((p[0] / 200.0 - 1.0).abs() < 0.01, "{}", p[0]);
    }
    assert!(out.join("render.png").is_file());
    let csv = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("shot,seconds,shooter,unshot_lm,convergence")
    );
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    assert!(last[4].parse::<f64>().unwrap() >= 0.999, "{last:?}");
    assert!(stderr.contains("converged"), "{stderr}");
}

#[test]
fn stops_at_the_shot_limit_and_the_log_has_a_line_per_shot() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_furnace(dir.path(), 0.8, 50.0);
    let out = dir.path().join("out");
    let (code, _, stderr) = run_cli(
        &[
            "radiosity",
            scene.to_str().unwrap(),
            "--max-shots",
            "3",
            "--texel-density",
            "4",
            "--out-dir",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains("3 shots") && stderr.contains("shot limit"),
        "{stderr}"
    );
    // The preprocessing by stage (Edström's Table 7.1) and the peak memory.
    for stage in [
        "prepared in",
        "load ",
        "face clusters ",
        "elements and atlas ",
        "direct light ",
        "12 triangles",
        "peak memory ",
    ] {
        assert!(stderr.contains(stage), "{stage:?} in {stderr}");
    }
    let csv = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap_or(-1.0)).collect())
        .collect();
    assert_eq!(rows.len(), 4, "{csv}");
    // Convergence grows shot by shot from 0.
    assert_eq!(rows[0][4], 0.0);
    assert!(rows.windows(2).all(|w| w[1][4] > w[0][4]), "{csv}");
}

#[test]
fn stops_when_the_time_budget_is_spent() {
    let scene = root().join("assets/scenes/cornell_box.toml");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let (code, _, stderr) = run_cli(
        &[
            "radiosity",
            scene.to_str().unwrap(),
            "--converge",
            "1",
            "--texel-density",
            "6",
            "--time-limit",
            "0.05",
            "--out-dir",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("(time budget spent)"), "{stderr}");
    let csv = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    let seconds: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap().parse().unwrap())
        .collect();
    // Shooting stopped at the first check after the budget: only the last point is past it.
    let n = seconds.len();
    assert!(n >= 2 && seconds[n - 1] >= 0.05, "{csv}");
    assert!(seconds[..n - 1].iter().all(|&s| s < 0.05), "{csv}");
}

#[test]
fn box_room_agrees_with_radiance() {
    agrees_with_radiance("box_room");
}

/// Every lux on the luminous ceiling's work plane has come through its translucent panel
/// (Radiance `trans`, two-sided): none directly.
#[test]
fn luminous_ceiling_agrees_with_radiance() {
    agrees_with_radiance("luminous_ceiling");
}

/// The box room with its back wall a mirror (Radiance `mirror`, its virtual light
/// sources for the direct light).
#[test]
fn mirror_room_agrees_with_radiance() {
    agrees_with_radiance("mirror_room");
}

/// A room split by clear glass with the luminaire on one side (Radiance `trans`, all its
/// transmission specular): half the work plane is lit only through the glass.
#[test]
fn glass_partition_agrees_with_radiance() {
    agrees_with_radiance("glass_partition");
}

/// Radiance's work plane in scene `name` (scripts/compare_radiance.py --scene NAME:
/// rtrace -ab 0 and a converged run) is stored; goniolight must match direct within 1 %
/// at every point (within 0.01 lx where Radiance has none) and the total within 3 % mean
/// absolute difference (of Radiance averaged over the room's mirror images, where the
/// CSV has that column).
fn agrees_with_radiance(name: &str) {
    let csv =
        std::fs::read_to_string(root().join(format!("tests/data/radiance_{name}.csv"))).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    // Radiance's total averaged over the mirror images where the room has them (its
    // sampling noise), else as it came.
    let total_col = header
        .iter()
        .position(|h| *h == "radiance_total_averaged_lx")
        .unwrap_or_else(|| col("radiance_total_lx"));
    let direct_col = col("radiance_direct_lx");
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let points: String = rows
        .iter()
        .map(|r| format!("{} {} {} 0 0 1\n", r[0], r[1], r[2]))
        .collect();
    let scene = root().join(format!("assets/scenes/{name}.toml"));
    let scene = scene.to_str().unwrap();
    let lux = |args: &[&str]| -> Vec<f64> {
        let (code, stdout, stderr) = run_cli(args, &points);
        assert_eq!(code, 0, "{stderr}");
        stdout.lines().map(|l| l.parse().unwrap()).collect()
    };
    let direct = lux(&["illuminance", scene]);
    let total = lux(&["radiosity", scene, "--points", "--converge", "0.99"]);
    let mut worst_direct: f64 = 0.0;
    let (mut diff, mut sum) = (0.0, 0.0);
    for (k, r) in rows.iter().enumerate() {
        let off = if r[direct_col] > 0.0 {
            (direct[k] / r[direct_col] - 1.0).abs()
        } else {
            // Dark in Radiance: 0.01 lx counts as 1 %.
            direct[k].abs()
        };
        worst_direct = worst_direct.max(off);
        diff += (total[k] - r[total_col]).abs();
        sum += r[total_col];
    }
    let mad = diff / sum;
    eprintln!(
        "{name} vs Radiance: direct worst {:.3} %, total MAD {:.3} %",
        100.0 * worst_direct,
        100.0 * mad
    );
    assert!(worst_direct <= 0.01, "{worst_direct}");
    assert!(mad <= 0.03, "{mad}");
}

/// A translucent surface exports both its faces, single-sided, each with its own light;
/// opaque ones stay double-sided.
#[test]
fn translucent_surfaces_export_both_faces_single_sided() {
    let dir = tempfile::tempdir().unwrap();
    let scene = root().join("assets/scenes/luminous_ceiling.toml");
    let glb = dir.path().join("ceiling.glb");
    let out = dir.path().join("out");
    let (code, _, stderr) = run_cli(
        &[
            "radiosity",
            scene.to_str().unwrap(),
            "--max-shots",
            "5",
            "--out-dir",
            out.to_str().unwrap(),
            "--export",
            glb.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    let doc = gltf::Gltf::from_slice(&std::fs::read(&glb).unwrap()).unwrap();
    let mut normals_y = Vec::new();
    for prim in doc.meshes().next().unwrap().primitives() {
        let m = prim.material();
        let opal = m.name() == Some("opal");
        assert_eq!(m.double_sided(), !opal, "{:?}", m.name());
        if opal {
            let (_, normals) = prim
                .attributes()
                .find(|(s, _)| *s == gltf::Semantic::Normals)
                .unwrap();
            normals_y.extend(floats(&doc, normals, 3).iter().map(|n| n[1]));
        }
    }
    // glTF is Y-up: the room side faces −Y, the plenum side +Y, as many corners each.
    let down = normals_y.iter().filter(|&&y| y < -0.99).count();
    let up = normals_y.iter().filter(|&&y| y > 0.99).count();
    assert!(
        down > 0 && down == up && down + up == normals_y.len(),
        "{down} {up}"
    );
}

/// `--raster`: the command says which rasterizer drew the maps (`auto`: the render
/// pipeline on a software driver, compute on a GPU).
#[test]
fn the_command_says_which_rasterizer_drew_the_maps() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_furnace(dir.path(), 0.5, 100.0);
    let scene = scene.to_str().unwrap();
    let Some(gpu) = gpu_common::gpu() else { return };
    let software = gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu;
    let auto = if software {
        "(hardware raster)"
    } else {
        "(compute raster)"
    };
    for (raster, said) in [
        ("auto", auto),
        ("hardware", "(hardware raster)"),
        ("compute", "(compute raster)"),
    ] {
        let out = dir.path().join(raster);
        let (code, _, stderr) = run_cli(
            &[
                "radiosity",
                scene,
                "--max-shots",
                "2",
                "--texel-density",
                "4",
                "--raster",
                raster,
                "--out-dir",
                out.to_str().unwrap(),
            ],
            "",
        );
        assert_eq!(code, 0, "{stderr}");
        assert!(stderr.contains(said), "--raster {raster}: {stderr}");
    }
}

#[test]
fn bad_input_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_furnace(dir.path(), 0.5, 100.0);
    let scene = scene.to_str().unwrap();
    let out = dir.path().join("never");
    let o = out.to_str().unwrap();
    let under_a_file = format!("{scene}/models/room.glb");
    let cases: [(&[&str], &str, &str); 8] = [
        (
            &["radiosity", scene, "--export", "/", "--out-dir", o],
            "",
            "--export /: is a folder",
        ),
        (
            &[
                "radiosity",
                scene,
                "--export",
                &under_a_file,
                "--out-dir",
                o,
            ],
            "",
            "is a file, not a folder",
        ),
        (
            &["radiosity", scene, "--converge", "1.5", "--out-dir", o],
            "",
            "--converge",
        ),
        (
            &["radiosity", scene, "--texel-density", "0", "--out-dir", o],
            "",
            "--texel-density",
        ),
        (
            &["radiosity", scene, "--visibility", "cube", "--out-dir", o],
            "",
            "cube",
        ),
        (
            &["radiosity", scene, "--time-limit", "0", "--out-dir", o],
            "",
            "--time-limit",
        ),
        (
            &["radiosity", scene, "--points", "--out-dir", o],
            "1 2 3 0 0 1\n1 2 x 0 0 1\n",
            "line 2",
        ),
        (
            &["radiosity", "missing.toml", "--out-dir", o],
            "",
            "missing.toml",
        ),
    ];
    for (args, stdin, says) in cases {
        let (code, _, stderr) = run_cli(args, stdin);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
}

#[test]
fn bench_radiosity_json_has_the_contract_keys() {
    let (code, stdout, stderr) = run_cli(
        &[
            "bench",
            "radiosity",
            "--elements",
            "3000",
            "--level",
            "2",
            "--ambient",
            "display,overshoot",
            "--json",
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    let names: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| {
            (
                r["visibility"].as_str().unwrap(),
                r["ambient"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        names,
        [
            ("hemicube", "display"),
            ("stereographic", "display"),
            ("hemicube", "overshoot"),
            ("stereographic", "overshoot")
        ]
    );
    // Ambient overshooting (Wallner §4.3.5: 10–40 % less time) reaches 99 % in fewer
    // shots with either map.
    let shots_99 = |r: &serde_json::Value| r["shots_99"].as_u64().unwrap();
    for k in 0..2 {
        assert!(
            shots_99(&rows[k + 2]) < shots_99(&rows[k]),
            "{} vs {}",
            rows[k + 2],
            rows[k]
        );
    }
    for r in rows {
        let elements = r["elements"].as_u64().unwrap();
        assert!((2500..4000).contains(&elements), "{r}");
        let (s90, s99) = (
            r["seconds_90"].as_f64().unwrap(),
            r["seconds_99"].as_f64().unwrap(),
        );
        let (n90, n99) = (
            r["shots_90"].as_u64().unwrap(),
            r["shots_99"].as_u64().unwrap(),
        );
        assert!(0.0 < s90 && s90 <= s99 && 0 < n90 && n90 < n99, "{r}");
        assert!(r["ms_per_shot"].as_f64().unwrap() > 0.0);
        assert_eq!(r["map_size"], 256);
        // The GPU's own clock (lavapipe has timestamp queries): both passes took time,
        // batches were timed, and the passes fit in the run.
        let gpu = &r["gpu_pass_seconds"];
        let (maps, receive) = (
            gpu["maps"].as_f64().unwrap(),
            gpu["receive"].as_f64().unwrap(),
        );
        assert!(maps > 0.0 && receive > 0.0, "{r}");
        assert!(
            maps + receive < 1.1 * r["seconds"].as_f64().unwrap() + 0.05,
            "{r}"
        );
        assert!(gpu["batches"].as_u64().unwrap() >= 1, "{r}");
        let receivers = r["receivers_per_map"].as_f64().unwrap();
        assert!(receivers > 0.0 && receivers <= elements as f64, "{r}");
    }
}

#[test]
fn bench_radiosity_compares_flat_and_cluster_shooters_side_by_side() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/cad_room.toml");
    let (code, stdout, stderr) = run_cli(
        &[
            "bench",
            "radiosity",
            "--scene",
            scene,
            "--texel-density",
            "5",
            "--visibility",
            "hemicube",
            "--hierarchy",
            "none,clusters",
            "--max-shots",
            "60",
            "--json",
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    let pairs: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| {
            (
                r["visibility"].as_str().unwrap(),
                r["hierarchy"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(pairs, [("hemicube", "none"), ("hemicube", "clusters")]);
    // The CAD-like room: 2 600 strips; every strip shoots without a hierarchy, a few
    // dozen flat faces with one — and 60 cluster shots get further than 60 strip shots.
    assert_eq!(rows[0]["triangles"], 2600);
    assert_eq!(rows[0]["shooters"], 2600);
    let clusters = rows[1]["shooters"].as_u64().unwrap();
    assert!((6..=60).contains(&clusters), "{clusters} shooters");
    let reached = |r: &serde_json::Value| r["convergence"].as_f64().unwrap();
    assert!(reached(&rows[1]) > reached(&rows[0]) + 0.2, "{rows:?}");
    assert!(rows[1]["shooters_seconds"].as_f64().unwrap() >= 0.0);
    // Each hierarchy lays its own charts at the density asked: the strips' shared edges
    // cost elements only without charts.
    for r in rows {
        assert_eq!(r["texel_density"].as_f64(), Some(5.0), "{r}");
    }
    let elements = |r: &serde_json::Value| r["elements"].as_u64().unwrap();
    assert!(2 * elements(&rows[1]) < elements(&rows[0]), "{rows:?}");
}

/// Reads `child`'s stderr until it says `marker`, then sends it SIGINT 0.3 s later:
/// the stderr before and after.
fn interrupt_after(child: &mut std::process::Child, marker: &str) -> (String, String) {
    use std::io::{BufRead, BufReader, Read};
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut text = String::new();
    while !text.contains(marker) {
        let mut line = String::new();
        assert!(
            stderr.read_line(&mut line).unwrap() > 0,
            "ended early: {text}"
        );
        text.push_str(&line);
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    unsafe { libc::kill(child.id() as i32, libc::SIGINT) };
    let mut rest = String::new();
    stderr.read_to_string(&mut rest).unwrap();
    (text, rest)
}

#[test]
fn ctrl_c_stops_the_gather_at_points_and_prints_nothing() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let scene = root().join("assets/scenes/box_room.toml");
    let mut child = Command::new(env!("CARGO_BIN_EXE_goniolight"))
        .args(["radiosity", scene.to_str().unwrap(), "--max-shots", "2"])
        .arg("--points")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A million points over the work plane: minutes of gathering.
    let mut points = String::new();
    for k in 0..1_000_000 {
        let (x, y) = (
            0.5 + (k % 500) as f64 * 0.01,
            0.5 + (k / 500) as f64 * 0.0015,
        );
        points.push_str(&format!("{x} {y} 0.8 0 0 1\n"));
    }
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(points.as_bytes()).unwrap();
    drop(stdin);
    let started = std::time::Instant::now();
    let (text, rest) = interrupt_after(&mut child, "gathering at 1000000 points");
    let mut stdout = String::new();
    std::io::Read::read_to_string(&mut child.stdout.take().unwrap(), &mut stdout).unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(1), "{text}{rest}");
    assert!(rest.contains("interrupted while gathering"), "{rest}");
    assert!(stdout.is_empty(), "printed {} bytes", stdout.len());
    // It stopped within a point's work per thread, not after the remaining minutes.
    assert!(started.elapsed().as_secs_f64() < 20.0);
}

#[test]
fn ctrl_c_while_preparing_stops_and_writes_nothing() {
    use std::process::{Command, Stdio};
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    // The CAD-like room at 40 texels/m: seconds of clustering, charts and direct light.
    let scene = root().join("assets/scenes/cad_room.toml");
    let mut child = Command::new(env!("CARGO_BIN_EXE_goniolight"))
        .args([
            "radiosity",
            scene.to_str().unwrap(),
            "--texel-density",
            "40",
        ])
        .arg("--out-dir")
        .arg(&out)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let (text, rest) = interrupt_after(&mut child, "preparing");
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(1), "{text}{rest}");
    assert!(rest.contains("interrupted while preparing ("), "{rest}");
    assert!(!rest.contains("shooting"), "it went on to shoot: {rest}");
    assert!(!out.exists(), "wrote {}", out.display());
}

#[test]
fn ctrl_c_stops_the_solver_and_writes_the_solution_so_far() {
    use std::process::{Command, Stdio};
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let scene = root().join("assets/scenes/cornell_box.toml");
    // Every texel a shooting patch of its triangle: far longer than the 300 ms before the
    // interrupt, also on a real GPU (with face clusters an H200 converged in 0.29 s).
    let mut child = Command::new(env!("CARGO_BIN_EXE_goniolight"))
        .args(["radiosity", scene.to_str().unwrap(), "--converge", "1"])
        .args([
            "--hierarchy",
            "none",
            "--texel-density",
            "20",
            "--level",
            "0",
        ])
        .arg("--out-dir")
        .arg(&out)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Once it says it is shooting (the handler is in place).
    let (text, rest) = interrupt_after(&mut child, "shooting");
    let status = child.wait().unwrap();
    assert!(status.success(), "{status:?}: {text}{rest}");
    assert!(
        rest.contains("(interrupted)") && rest.contains("stopped early"),
        "{rest}"
    );
    let csv = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    let last: f64 = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .nth(4)
        .unwrap()
        .parse()
        .unwrap();
    assert!(last < 1.0, "{csv}");
    assert!(out.join("render.png").is_file() && out.join("lightmap.exr").is_file());
}

/// Reads a float accessor of a GLB: `width` floats per item.
fn floats(doc: &gltf::Gltf, accessor: gltf::Accessor, width: usize) -> Vec<Vec<f32>> {
    let blob = doc.blob.as_ref().unwrap();
    let view = accessor.view().unwrap();
    assert_eq!(accessor.data_type(), gltf::accessor::DataType::F32);
    let at = view.offset() + accessor.offset();
    (0..accessor.count())
        .map(|i| {
            (0..width)
                .map(|k| {
                    let o = at + 4 * (i * width + k);
                    f32::from_le_bytes(blob[o..o + 4].try_into().unwrap())
                })
                .collect()
        })
        .collect()
}

/// What an export of the box room holds, as read back by the `gltf` crate.
struct Exported {
    /// Triangles exported.
    triangles: usize,
    /// Light-mapped and vertex-lit triangles.
    by_bake: [usize; 2],
    /// Their summed area, m².
    area: f64,
    /// The longest side of any vertex-lit triangle, m.
    longest_vertex_side: f32,
    /// What the command printed.
    stderr: String,
}

/// Runs `radiosity --export` on the box room with `extra` flags and checks the file: a
/// glTF binary, Y-up, wound like the model, whose baked values at every corner are the
/// solver's light map under that corner (`lightmap.exr`, `lightmap_lux.exr` of the same
/// run); vertex-lit primitives carry colours that are those values over the stated white
/// point, light-mapped ones carry the light map as their base colour texture (bilinear,
/// clamped) and no colours. The export's folder is made where it is missing.
fn export_box_room(extra: &[&str]) -> Exported {
    let dir = tempfile::tempdir().unwrap();
    let scene = root().join("assets/scenes/box_room.toml");
    // The export's folder does not exist yet: the command makes it, as it does --out-dir.
    let (out, glb) = (dir.path().join("out"), dir.path().join("models/room.glb"));
    let mut args = vec![
        "radiosity",
        scene.to_str().unwrap(),
        "--max-shots",
        "30",
        "--out-dir",
        out.to_str().unwrap(),
        "--export",
        glb.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let (code, _, stderr) = run_cli(&args, "");
    assert_eq!(code, 0, "{stderr}");
    let doc = gltf::Gltf::from_slice(&std::fs::read(&glb).unwrap()).expect("a valid glTF binary");
    let extras: serde_json::Value =
        serde_json::from_str(doc.document.as_json().asset.extras.as_ref().unwrap().get()).unwrap();
    let white = extras["white_lm_per_m2"].as_f64().unwrap();
    assert!(white > 1.0, "{extras}");
    let mut names: Vec<_> = doc
        .materials()
        .map(|m| m.name().unwrap().to_string())
        .collect();
    names.dedup();
    assert_eq!(names, ["floor", "wall", "ceiling"]);
    assert!(doc.materials().all(|m| m.unlit()));
    let (map, lux) = (
        read_exr(&out.join("lightmap.exr")),
        read_exr(&out.join("lightmap_lux.exr")),
    );
    let (w, h) = (map.width() as f32, map.height() as f32);
    let mut found = Exported {
        triangles: 0,
        by_bake: [0; 2],
        area: 0.0,
        longest_vertex_side: 0.0,
        stderr,
    };
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for prim in doc.meshes().next().unwrap().primitives() {
        let attribute = |name: &str| {
            prim.attributes()
                .find(|(s, _)| s.to_string() == name)
                .map(|a| a.1)
        };
        let get = |name: &str, width| floats(&doc, attribute(name).unwrap(), width);
        let texture = prim
            .material()
            .pbr_metallic_roughness()
            .base_color_texture();
        let vertex_lit = texture.is_none();
        assert_eq!(
            attribute("COLOR_0").is_some(),
            vertex_lit,
            "colours xor light map"
        );
        if let Some(info) = texture {
            assert_eq!(info.texture().name(), Some("lightmap"));
            assert_eq!(info.tex_coord(), 0);
            let sampler = info.texture().sampler();
            assert_eq!(sampler.mag_filter(), Some(gltf::texture::MagFilter::Linear));
            assert_eq!(sampler.min_filter(), Some(gltf::texture::MinFilter::Linear));
            assert_eq!(sampler.wrap_s(), gltf::texture::WrappingMode::ClampToEdge);
        }
        let (pos, nrm) = (get("POSITION", 3), get("NORMAL", 3));
        let (uv, rad, ill) = (
            get("TEXCOORD_0", 2),
            get("_RADIOSITY", 3),
            get("_ILLUMINANCE", 1),
        );
        let colours = vertex_lit.then(|| get("COLOR_0", 3));
        for t in 0..pos.len() / 3 {
            let p: Vec<glam::Vec3> = (0..3)
                .map(|k| glam::Vec3::from_slice(&pos[3 * t + k]))
                .collect();
            let n = (p[1] - p[0]).cross(p[2] - p[0]);
            found.area += 0.5 * n.length() as f64;
            assert!(
                (n.normalize() - glam::Vec3::from_slice(&nrm[3 * t])).length() < 1e-4,
                "winding"
            );
            if vertex_lit {
                let side = (0..3).map(|k| (p[(k + 1) % 3] - p[k]).length());
                found.longest_vertex_side = side.fold(found.longest_vertex_side, f32::max);
            }
            let centre: glam::Vec2 = (0..3)
                .map(|k| glam::Vec2::from_slice(&uv[3 * t + k]))
                .sum::<glam::Vec2>()
                / 3.0;
            for k in 3 * t..3 * t + 3 {
                // The texel under the corner nudged a thousandth of the way to the
                // centroid, in texels (in f64, as the exporter reads it).
                let size = glam::DVec2::new(w as f64, h as f64);
                let c = glam::Vec2::from_slice(&uv[k]).as_dvec2() * size;
                let q = c + (centre.as_dvec2() * size - c) * 1e-3;
                let texel = map.get_pixel(q.x as u32, q.y as u32).0;
                assert_eq!(rad[k], texel, "radiosity at corner {k}");
                assert_eq!(ill[k][0], lux.get_pixel(q.x as u32, q.y as u32).0[0]);
                if let Some(col) = &colours {
                    for c in 0..3 {
                        let expected = (rad[k][c] as f64 / white).clamp(0.0, 1.0) as f32;
                        assert!((col[k][c] - expected).abs() < 1e-6);
                    }
                }
                for a in 0..3 {
                    lo[a] = lo[a].min(pos[k][a]);
                    hi[a] = hi[a].max(pos[k][a]);
                }
            }
            found.triangles += 1;
            found.by_bake[usize::from(vertex_lit)] += 1;
        }
    }
    // The room's bounds (Z up) seen Y up: x, height, −y.
    let room = goniolight::scene::Scene::load(&scene).unwrap().bounds();
    let expect_lo = [room.0.x, room.0.z, -room.1.y].map(|v| v as f32);
    let expect_hi = [room.1.x, room.1.z, -room.0.y].map(|v| v as f32);
    for a in 0..3 {
        assert!((lo[a] - expect_lo[a]).abs() < 1e-4 && (hi[a] - expect_hi[a]).abs() < 1e-4);
    }
    found
}

/// The number after `before` in `text`.
fn number_after(text: &str, before: &str) -> u64 {
    let at = text
        .find(before)
        .unwrap_or_else(|| panic!("{before:?} in {text}"));
    text[at + before.len()..]
        .split(|c: char| !c.is_ascii_digit())
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

/// The box room's surfaces (floor, walls, ceiling: 12 triangles of 6 × 4 × 3 m) are far
/// coarser than its light map: vertex lighting would add thousands of triangles, so the
/// default export light-maps every one and draws the model's own 12 triangles.
#[test]
fn export_light_maps_the_box_rooms_large_surfaces() {
    let e = export_box_room(&[]);
    assert_eq!((e.triangles, e.by_bake), (12, [12, 0]), "{}", e.stderr);
    assert!((e.area - 108.0).abs() < 1e-3, "{}", e.area);
    assert!(
        e.stderr
            .contains("3 surfaces (12 triangles) light-mapped, 0 (0 triangles) vertex-lit")
            && e.stderr.contains("+0.0 % triangles over the model"),
        "{}",
        e.stderr
    );
}

/// `--bake vertex`: every triangle refined (Edström's patch refinement) into patches no
/// longer than a texel (the box room's 0.1 m at 10 texels per metre) or a 32nd of the
/// triangle's longest side (7.2 m on the floor), the same area, as many triangles as the
/// command says it introduced, colours at every corner.
#[test]
fn export_bake_vertex_refines_triangles_to_the_light_maps_texels() {
    let e = export_box_room(&["--bake", "vertex", "--texel-density", "10"]);
    let introduced = number_after(&e.stderr, "vertex-lit with ");
    assert_eq!(e.triangles as u64, 12 + introduced, "{}", e.stderr);
    assert_eq!(e.by_bake[0], 0);
    assert!((e.area - 108.0).abs() < 1e-3, "{}", e.area);
    // A patch is at most 7.21 / 32 m long, so no side of its triangles exceeds its
    // rectangle's diagonal.
    let size = 52f64.sqrt() / 32.0;
    assert!(
        e.longest_vertex_side <= (2f64.sqrt() * size) as f32 + 1e-4,
        "{}",
        e.longest_vertex_side
    );
    // Each patch fits in a square of its triangle's size: 2 752 patches at least (floor
    // and ceiling 2 × 24 m² at 7.21 / 32 m, walls 2 × 18 m² at 6.71 / 32 m and 2 × 12 m²
    // at 5 / 32 m). These right triangles are well shaped: regular refinement (32 parts
    // per side, 12 · (32² − 1) introduced) is the cheaper refinement for each.
    let fewest: f64 = [(48.0, 52f64), (36.0, 45.0), (24.0, 25.0)]
        .iter()
        .map(|&(area, diagonal2)| area / (diagonal2 / 1024.0))
        .sum();
    assert!(
        introduced as f64 >= fewest - 12.0 && introduced <= 12 * 1023,
        "{introduced} (at least {fewest})"
    );
}

/// `--export` writes the luminaires as `EXT_lights_ies` lights (with `KHR_lights_punctual`
/// fallbacks): the exported file read back as a model gives the same direct lux at points
/// as the scene it came from, for an aimed, rolled, dimmed and tinted luminaire without
/// symmetry and a plain one.
#[test]
fn exported_luminaires_come_back_with_the_same_direct_lux() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = root().join("assets/scenes");
    let text = format!(
        "[[model]]\npath = {:?}\nup = \"z\"\n\n\
         [[luminaire]]\nfile = {:?}\nposition = [3.0, 2.0, 2.95]\n\n\
         [[luminaire]]\nfile = {:?}\nposition = [1.5, 1.0, 2.5]\naim = [0.3, 0.2, -1.0]\nroll = 25.0\nmultiplier = 0.7\ncolor = [1.0, 0.6, 0.3]\n",
        scenes.join("box_room.obj"),
        root().join("luminaires/eulumdat-plot/sample_06_isym1.ldt"),
        root().join("luminaires/effects/disco.ldt"),
    );
    let scene = dir.path().join("room.toml");
    std::fs::write(&scene, text).unwrap();
    let glb = dir.path().join("room.glb");
    let args = [
        "radiosity",
        scene.to_str().unwrap(),
        "--max-shots",
        "2",
        "--out-dir",
    ];
    let out = dir.path().join("out");
    let (code, _, stderr) = run_cli(
        &[
            &args[..],
            &[out.to_str().unwrap(), "--export", glb.to_str().unwrap()],
        ]
        .concat(),
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    let back = dir.path().join("back.toml");
    std::fs::write(&back, format!("[[model]]\npath = {glb:?}\n")).unwrap();
    let loaded = goniolight::scene::Scene::load(&back).unwrap();
    assert_eq!(
        loaded.luminaires.len(),
        2,
        "the KHR fallbacks are not placed twice"
    );
    let points: String = (0..24)
        .map(|k| {
            let (x, y) = (0.3 + 0.23 * k as f64, 0.2 + 0.15 * ((k * 7) % 24) as f64);
            format!("{x} {y} 0.8 0 0 1\n{x} {y} 1.2 1 0 0\n")
        })
        .collect();
    let lux = |s: &Path| -> Vec<f64> {
        let (code, out, err) = run_cli(
            &["illuminance", s.to_str().unwrap(), "--shadows", "none"],
            &points,
        );
        assert_eq!(code, 0, "{err}");
        out.lines().map(|l| l.trim().parse().unwrap()).collect()
    };
    let (before, after) = (lux(&scene), lux(&back));
    assert_eq!(before.len(), 48);
    for (k, (a, b)) in before.iter().zip(&after).enumerate() {
        assert!(
            (a - b).abs() <= 1e-3 * a.max(1.0),
            "point {k}: {a} lx before, {b} lx after"
        );
    }
}
