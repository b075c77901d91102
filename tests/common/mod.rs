//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A bundled luminaire file by its path under `luminaires/`.
pub fn luminaire(rel: &str) -> PathBuf {
    root().join("luminaires").join(rel)
}

/// Every file under `dir`, recursively, as paths relative to `dir`, sorted.
pub fn files_in(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push(p.strip_prefix(dir).unwrap().to_path_buf());
            }
        }
    }
    out.sort();
    out
}

/// Every file under `dir` whose extension is one of `exts` (any case), as full paths.
pub fn files_with(dir: &Path, exts: &[&str]) -> Vec<PathBuf> {
    files_in(dir)
        .into_iter()
        .filter(|p| {
            p.extension()
                .is_some_and(|x| exts.iter().any(|e| x.eq_ignore_ascii_case(e)))
        })
        .map(|p| dir.join(p))
        .collect()
}

/// Every bundled `.ldt` and `.ies` file.
pub fn all_luminaire_files() -> Vec<PathBuf> {
    let out = files_with(&root().join("luminaires"), &["ldt", "ies"]);
    assert!(
        out.len() >= 60,
        "expected the bundled luminaires, found {}",
        out.len()
    );
    out
}

/// An independent, minimal EULUMDAT reader used as the oracle for the expansion tests:
/// it returns (Isym, C angles, γ angles, stored planes in file order).
pub fn raw_ldt(path: &Path) -> (u8, Vec<f64>, Vec<f64>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().map(|l| l.trim()).collect();
    let num = |s: &str| s.replace(',', ".").parse::<f64>().unwrap();
    let isym = num(lines[2]) as u8;
    let mc = num(lines[3]) as usize;
    let ng = num(lines[5]) as usize;
    let sets = num(lines[25]) as usize;
    let data: Vec<f64> = lines[26 + 6 * sets..]
        .iter()
        .flat_map(|l| l.split_whitespace())
        .map(num)
        .collect();
    let c = data[10..10 + mc].to_vec();
    let g = data[10 + mc..10 + mc + ng].to_vec();
    let values = &data[10 + mc + ng..];
    let planes = values.chunks(ng).map(|c| c.to_vec()).collect();
    (isym, c, g, planes)
}

/// Runs the built binary with `args` and `stdin`; returns (exit code, stdout, stderr).
pub fn run_cli(args: &[&str], stdin: &str) -> (i32, String, String) {
    run_cli_without(args, stdin, &[])
}

/// [`run_cli`] with the environment variables `unset` removed.
pub fn run_cli_without(args: &[&str], stdin: &str, unset: &[&str]) -> (i32, String, String) {
    run_cli_env(args, stdin, &[], unset)
}

/// [`run_cli`] with the environment variables `set` set and `unset` removed.
pub fn run_cli_env(
    args: &[&str],
    stdin: &str,
    set: &[(&str, &str)],
    unset: &[&str],
) -> (i32, String, String) {
    use std::process::{Command, Stdio};
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_goniolight"));
    cmd.args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    for v in unset {
        cmd.env_remove(v);
    }
    cmd.envs(set.iter().copied());
    let mut child = cmd.spawn().unwrap();
    feed(&mut child, stdin, args);
    let out = child.wait_with_output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The arguments of `goniolight profile MODEL` for Vienna on 2026-06-21 from `from` to
/// `to` every `step` minutes, then `extra`.
pub fn profile_args(model: &str, from: &str, to: &str, step: &str, extra: &[&str]) -> Vec<String> {
    [
        "profile",
        model,
        "--lat",
        "48.2",
        "--lon",
        "16.4",
        "--date",
        "2026-06-21",
        "--from",
        from,
        "--to",
        to,
        "--step",
        step,
    ]
    .iter()
    .chain(extra)
    .map(|s| s.to_string())
    .collect()
}

/// The shared test data (`../shared` beside the repository, or `$GONIOLIGHT_SHARED`):
/// real luminaires, real models and fuzzing reproducers, read in place. Missing data
/// fails the test with a message rather than skipping it.
pub fn shared_dir() -> PathBuf {
    let dir = std::env::var_os("GONIOLIGHT_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("../shared"));
    assert!(
        dir.join("luminaires/wild").is_dir(),
        "shared test data not found at {} (set GONIOLIGHT_SHARED to its folder)",
        dir.display()
    );
    dir
}

/// Writes `stdin` to the started command `child` (run with `args`) and closes its input.
/// A command that refuses its flags exits before it reads its input; the pipe is then
/// closed under the write, which is not the test's failure (its exit code is checked):
/// any other error is.
fn feed(child: &mut std::process::Child, stdin: &str, args: &[&str]) {
    use std::io::Write;
    if let Err(e) = child.stdin.take().unwrap().write_all(stdin.as_bytes()) {
        assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{args:?}: {e}");
    }
}

/// Runs the CLI in `dir` with `stdin`, killing it after `limit`: (exit code, stdout,
/// stderr, timed out). A signal gives code −1.
pub fn run_cli_in(
    dir: &Path,
    args: &[&str],
    stdin: &str,
    limit: std::time::Duration,
) -> (i32, String, String, bool) {
    use std::io::Read;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_goniolight"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    feed(&mut child, stdin, args);
    let mut out_pipe = child.stdout.take().unwrap();
    let mut err_pipe = child.stderr.take().unwrap();
    let out_reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = out_pipe.read_to_end(&mut s);
        s
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = err_pipe.read_to_end(&mut s);
        s
    });
    let started = std::time::Instant::now();
    let mut timed_out = false;
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > limit {
            timed_out = true;
            let _ = child.kill();
            break child.wait().unwrap();
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    let text = |b: Vec<u8>| String::from_utf8_lossy(&b).into_owned();
    (
        status.code().unwrap_or(-1),
        text(out_reader.join().unwrap()),
        text(err_reader.join().unwrap()),
        timed_out,
    )
}

/// Writes `dir/NAME.toml`: the bundled box room with one luminaire `file` (under
/// `luminaires/`) and `rest` (its placement keys, then further tables such as
/// `[camera]`) appended; returns its path.
pub fn box_room_scene(dir: &Path, name: &str, file: &str, rest: &str) -> PathBuf {
    let scene = dir.join(format!("{name}.toml"));
    std::fs::write(
        &scene,
        format!(
            "[[model]]\npath = {:?}\nup = \"z\"\n[[luminaire]]\nfile = {:?}\n{rest}",
            root()
                .join("assets/scenes/box_room.obj")
                .display()
                .to_string(),
            luminaire(file).display().to_string()
        ),
    )
    .unwrap();
    scene
}

/// `ldt plot FILE ARGS… --out` into `dir` twice, as `NAME.svg` and `NAME.png`; both must
/// succeed. Returns (svg, png).
pub fn plot_svg_and_png(file: &Path, args: &[&str], dir: &Path, name: &str) -> (PathBuf, PathBuf) {
    let (svg, png) = (
        dir.join(format!("{name}.svg")),
        dir.join(format!("{name}.png")),
    );
    for out in [&svg, &png] {
        let mut all = vec!["ldt", "plot", file.to_str().unwrap()];
        all.extend(args);
        all.extend(["--out", out.to_str().unwrap()]);
        let (code, _, err) = run_cli(&all, "");
        assert_eq!(code, 0, "{err}");
    }
    (svg, png)
}

/// The rows of a grid CSV written by `calc` (`x,y,z,lux`, header checked).
pub fn calc_csv_rows(path: &Path) -> Vec<[f64; 4]> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,z,lux"), "{}", path.display());
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3]]
        })
        .collect()
}

/// Writes a unit quad (`quad.obj`, corners and texture coordinates 0..1, then `faces`:
/// its `usemtl` and `f` lines), its `quad.mtl` (`mtl`) and a scene file into `dir`, and
/// loads the scene. The textures the MTL names must be in `dir` before.
pub fn load_quad_scene(dir: &Path, faces: &str, mtl: &str) -> goniolight::scene::Scene {
    std::fs::write(
        dir.join("quad.obj"),
        format!(
            "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n{faces}"
        ),
    )
    .unwrap();
    std::fs::write(dir.join("quad.mtl"), mtl).unwrap();
    let p = dir.join("s.toml");
    std::fs::write(
        &p,
        "[[model]]\npath = \"quad.obj\"\nup = \"z\"\n[camera]\nposition = [0.5, -1, 2]\nlook_at = [0.5, 0.5, 0]\n",
    )
    .unwrap();
    goniolight::scene::Scene::load(&p).unwrap()
}
