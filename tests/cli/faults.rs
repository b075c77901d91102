//! Faults and interruptions: outputs on a read-only or full file system, a file where a
//! folder should be, Ctrl-C in the middle of long commands, and commands side by side.
//! Whatever happens, an output is complete or absent (never truncated, no temporary
//! files left), and the exit is clean with a message naming the path.
//!
//! Read-only and full file systems are tiny tmpfs mounts in a private mount namespace
//! (`unshare --user --map-root-user --mount`, no privileges needed); the outputs are copied
//! out before the namespace ends.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_goniolight")
}

fn root_path(rel: &str) -> String {
    common::root().join(rel).to_str().unwrap().to_string()
}

/// Runs `goniolight args…` (where `{DIR}` stands for the mount point) with a tmpfs
/// mounted with `options` at a private mount point; afterwards copies what the command
/// left there into `copy`. Returns (exit code, stderr).
fn on_tmpfs(options: &str, args: &[String], copy: &Path) -> (i32, String) {
    let mnt = tempfile::tempdir().unwrap();
    let m = mnt.path().to_str().unwrap();
    let args: Vec<String> = args.iter().map(|a| a.replace("{DIR}", m)).collect();
    let script = format!(
        "mount -t tmpfs -o {options} none {m} || exit 97; \"$@\"; rc=$?; cp -a {m}/. {} ; exit $rc",
        copy.display()
    );
    let out = Command::new("unshare")
        .args([
            "--user",
            "--map-root-user",
            "--mount",
            "sh",
            "-c",
            &script,
            "sh",
            bin(),
        ])
        .args(&args)
        .output()
        .expect("unshare (util-linux) runs");
    let code = out.status.code().unwrap_or(-1);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_ne!(
        code, 97,
        "could not mount a tmpfs in a user namespace: {err}"
    );
    (code, err)
}

/// A file is complete when it decodes (images) or parses (CSV, JSON, luminaires) whole.
fn assert_complete(path: &Path) {
    let name = path.display().to_string();
    let file = path.file_name().unwrap().to_string_lossy();
    assert!(!file.contains(".tmp"), "temporary file left: {name}");
    match path.extension().and_then(|e| e.to_str()) {
        Some("png") | Some("exr") => {
            image::open(path).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        Some("csv") => {
            let text = std::fs::read_to_string(path).unwrap();
            assert!(text.ends_with('\n'), "{name}: truncated");
            let cols = text.lines().next().unwrap().split(',').count();
            assert!(
                text.lines().all(|l| l.split(',').count() == cols),
                "{name}: ragged"
            );
        }
        Some("json") => {
            serde_json::from_slice::<serde_json::Value>(&std::fs::read(path).unwrap())
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        Some("ldt") | Some("ies") => {
            goniolight::photometry::Luminaire::load(path).unwrap_or_else(|e| panic!("{e}"));
        }
        _ => {}
    }
}

/// The commands that write files, each writing into `{DIR}`.
fn writers() -> Vec<(&'static str, Vec<String>)> {
    let s = |v: &[&str]| v.iter().map(|a| a.to_string()).collect::<Vec<_>>();
    let big = root_path("luminaires/eulumdat-analysis/sample_18.ldt");
    let lum = root_path("luminaires/eulumdat-plot/sample_06_isym1.ldt");
    let room = root_path("assets/scenes/box_room.toml");
    let model = root_path("assets/models/building.obj");
    vec![
        (
            "convert",
            s(&["ldt", "convert", &big, "--out", "{DIR}/x.ies"]),
        ),
        ("plot", s(&["ldt", "plot", &lum, "--out", "{DIR}/x.png"])),
        (
            "render",
            s(&[
                "render",
                &room,
                "--out",
                "{DIR}/x.png",
                "--width",
                "160",
                "--height",
                "120",
            ]),
        ),
        (
            "profile",
            common::profile_args(
                &model,
                "08:00",
                "16:00",
                "120",
                &["--resolution", "128", "--out", "{DIR}/p"],
            ),
        ),
    ]
}

/// Each writer on a tmpfs mounted with `options`: a clean failure that `says` why and
/// names the path, and only complete files left (none at all for single-file outputs).
fn writers_fail_cleanly_on(options: &str, says: &str) {
    for (what, args) in writers() {
        let copy = tempfile::tempdir().unwrap();
        let (code, err) = on_tmpfs(options, &args, copy.path());
        assert!(matches!(code, 1 | 2), "{what}: exit {code}: {err}");
        assert!(err.contains(says), "{what}: {err}");
        assert!(
            err.contains("/x.") || err.contains("/p"),
            "{what} names the path: {err}"
        );
        assert!(!err.contains("panicked"), "{what}: {err}");
        let left = common::files_in(copy.path());
        for f in &left {
            assert_complete(&copy.path().join(f));
        }
        if what != "profile" {
            assert!(left.is_empty(), "{what}: {left:?}");
        }
    }
}

#[test]
fn a_read_only_output_gives_exit_1_naming_the_path_and_no_files() {
    writers_fail_cleanly_on("ro", "Read-only file system");
}

#[test]
fn a_full_disk_leaves_no_partial_file() {
    // 4 kB: the smallest tmpfs; every output here is larger.
    writers_fail_cleanly_on("size=4k", "No space left on device");
}

#[test]
fn a_file_where_a_folder_should_be_is_named() {
    for (what, args) in writers() {
        let dir = tempfile::tempdir().unwrap();
        let blocker = dir.path().join("f");
        std::fs::write(&blocker, b"keep").unwrap();
        let d = blocker.to_str().unwrap();
        let args: Vec<String> = args.iter().map(|a| a.replace("{DIR}", d)).collect();
        let out = Command::new(bin()).args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        let code = out.status.code().unwrap_or(-1);
        assert!(matches!(code, 1 | 2), "{what}: exit {code}: {err}");
        assert!(err.contains(d), "{what} names the path: {err}");
        assert!(!err.contains("panicked"), "{what}: {err}");
        assert_eq!(std::fs::read(&blocker).unwrap(), b"keep");
        assert_eq!(
            common::files_in(dir.path()),
            vec![PathBuf::from("f")],
            "{what}"
        );
    }
}

/// Starts `args`, waits until stderr shows `ready`, then `after`, sends SIGINT and waits:
/// (exit code or −signal, stderr).
fn interrupt(args: &[String], ready: &str, after: Duration) -> (i32, String) {
    use std::io::Read;
    let mut child = Command::new(bin())
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut err_pipe = child.stderr.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel::<String>();
    let reader = std::thread::spawn(move || {
        let mut all = String::new();
        let mut buf = [0u8; 4096];
        while let Ok(n) = err_pipe.read(&mut buf) {
            if n == 0 {
                break;
            }
            all.push_str(&String::from_utf8_lossy(&buf[..n]));
            let _ = tx.send(all.clone());
        }
        all
    });
    let started = Instant::now();
    // An empty `ready` waits for nothing but `after`.
    while !ready.is_empty() && started.elapsed() < Duration::from_secs(300) {
        if let Ok(seen) = rx.recv_timeout(Duration::from_millis(100)) {
            if seen.contains(ready) {
                break;
            }
        }
        if child.try_wait().unwrap().is_some() {
            break;
        }
    }
    std::thread::sleep(after);
    // SAFETY: sending a signal to our own child process.
    unsafe {
        libc::kill(child.id() as i32, libc::SIGINT);
    }
    let status = child.wait().unwrap();
    let err = reader.join().unwrap();
    use std::os::unix::process::ExitStatusExt;
    let code = status
        .code()
        .unwrap_or_else(|| -status.signal().unwrap_or(0));
    (code, err)
}

#[test]
fn ctrl_c_stops_radiosity_with_a_complete_solution() {
    let out = tempfile::tempdir().unwrap();
    let args: Vec<String> = [
        "radiosity",
        &root_path("assets/scenes/cornell_box.toml"),
        "--out-dir",
        out.path().to_str().unwrap(),
        "--max-shots",
        "100000",
        "--converge",
        "0.9999",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let (code, err) = interrupt(&args, "shooting", Duration::from_secs(2));
    assert_eq!(code, 0, "writes the solution so far: {err}");
    assert!(err.contains("interrupted"), "{err}");
    let written = common::files_in(out.path());
    assert!(!written.is_empty(), "{err}");
    for f in written {
        assert_complete(&out.path().join(f));
    }
}

#[test]
fn ctrl_c_stops_profile_writing_nothing() {
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("p");
    let model = root_path("assets/models/industrial_area.obj");
    let args = common::profile_args(
        &model,
        "05:00",
        "20:00",
        "1",
        &["--resolution", "2048", "--out", dir.to_str().unwrap()],
    );
    // 900 steps at 2048 px take far longer than the second before Ctrl-C.
    let (code, err) = interrupt(&args, "Ctrl-C stops", Duration::from_secs(1));
    assert_eq!(code, 1, "a clean exit: {err}");
    assert!(err.contains("interrupted"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        common::files_in(out.path()).is_empty(),
        "{:?}",
        common::files_in(out.path())
    );
}

#[test]
fn eight_commands_side_by_side_give_what_they_give_alone() {
    let lum = root_path("luminaires/eulumdat-plot/sample_06_isym1.ldt");
    let room = root_path("assets/scenes/box_room.toml");
    let model = root_path("assets/models/building.obj");
    let jobs: Vec<(Vec<String>, &str)> = vec![
        (
            vec!["ldt".into(), "info".into(), lum.clone(), "--json".into()],
            "",
        ),
        (
            vec!["ldt".into(), "check".into(), lum.clone(), "--json".into()],
            "",
        ),
        (
            vec!["illuminance".into(), room.clone()],
            "1 1 0.8 0 0 1\n3 2 0 0 0 1\n",
        ),
        (
            vec!["illuminance".into(), room.clone(), "--cpu".into()],
            "1 1 0.8 0 0 1\n",
        ),
        (
            vec![
                "silhouette".into(),
                model.clone(),
                "--light".into(),
                "1,2,30,1".into(),
                "--json".into(),
            ],
            "",
        ),
        (
            vec![
                "sun".into(),
                "--lat".into(),
                "48.2".into(),
                "--lon".into(),
                "16.4".into(),
                "--time".into(),
                "2026-06-21T12:00:00Z".into(),
                "--json".into(),
            ],
            "",
        ),
        (
            vec!["ldt".into(), "sample".into(), lum.clone()],
            "0 0\n90 45\n",
        ),
        (
            vec![
                "illuminance".into(),
                room.clone(),
                "--shadows".into(),
                "volumes".into(),
            ],
            "1 1 0.8 0 0 1\n",
        ),
    ];
    let run = |args: &[String], stdin: &str| -> (i32, String) {
        let (code, out, err) =
            common::run_cli(&args.iter().map(String::as_str).collect::<Vec<_>>(), stdin);
        assert_eq!(code, 0, "{args:?}: {err}");
        (code, out)
    };
    let alone: Vec<(i32, String)> = jobs.iter().map(|(a, i)| run(a, i)).collect();
    let together: Vec<(i32, String)> = std::thread::scope(|s| {
        let handles: Vec<_> = jobs
            .iter()
            .map(|(a, i)| s.spawn(move || run(a, i)))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(alone, together);
}
