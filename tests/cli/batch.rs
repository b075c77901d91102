//! `goniolight batch`: jobs in one process, shards that together equal one run, the
//! summary, failures reported per job, bad jobs files refused.

use crate::common;

use std::collections::BTreeMap;
use std::path::Path;

use common::{luminaire, root, run_cli};

/// Every file under `dir` (relative path → bytes), summaries left out.
fn tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    common::files_in(dir)
        .into_iter()
        .filter(|p| {
            !p.to_string_lossy().contains("summary") && p.extension().is_none_or(|e| e != "toml")
        })
        .map(|p| {
            (
                p.display().to_string(),
                std::fs::read(dir.join(&p)).unwrap(),
            )
        })
        .collect()
}

/// A jobs file with five jobs of four kinds (two on the GPU), written into `dir`.
fn write_jobs(dir: &Path) -> std::path::PathBuf {
    let ldt = luminaire("eulumdat-analysis/sample_18.ldt");
    let scene = root().join("assets/scenes/box_room.toml");
    std::fs::create_dir_all(dir.join("in")).unwrap();
    std::fs::create_dir_all(dir.join("out")).unwrap();
    std::fs::write(
        dir.join("in/points.txt"),
        "1 1 0.8 0 0 1\n2 1.5 0.8 0 0 1\n",
    )
    .unwrap();
    let jobs = format!(
        r#"
[[job]]
name = "info"
args = ["ldt", "info", "{ldt}", "--json"]
stdout = "out/info.json"

[[job]]
name = "convert"
args = ["ldt", "convert", "{ldt}", "--out", "out/sample.ies"]

[[job]]
name = "sun"
args = ["sun", "--lat", "48.21", "--lon", "16.37", "--time", "2026-03-21T12:00", "--tz", "Europe/Vienna", "--json"]
stdout = "out/sun.json"

[[job]]
name = "lux"
args = ["illuminance", "{scene}"]
stdin = "in/points.txt"
stdout = "out/lux.txt"

[[job]]
name = "render"
args = ["render", "{scene}", "--out", "out/room.png", "--width", "64", "--height", "48"]
"#,
        ldt = ldt.display(),
        scene = scene.display()
    );
    let path = dir.join("jobs.toml");
    std::fs::write(&path, jobs).unwrap();
    path
}

#[test]
fn two_shards_write_exactly_what_one_run_writes() {
    let whole = tempfile::tempdir().unwrap();
    let jobs = write_jobs(whole.path());
    let (code, stdout, stderr) = run_cli(&["batch", jobs.to_str().unwrap()], "");
    assert_eq!(code, 0, "{stderr}");
    let summary: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(summary["ran"], 5);
    assert_eq!(summary["failed"], 0);
    assert_eq!(summary["shard"], serde_json::json!([1, 1]));

    let sharded = tempfile::tempdir().unwrap();
    let jobs = write_jobs(sharded.path());
    let mut ran = Vec::new();
    for k in ["1/2", "2/2"] {
        let out = sharded.path().join(format!("summary-{}.json", &k[..1]));
        let (code, stdout, stderr) = run_cli(
            &[
                "batch",
                jobs.to_str().unwrap(),
                "--shard",
                k,
                "--summary",
                out.to_str().unwrap(),
            ],
            "",
        );
        assert_eq!(code, 0, "{stderr}");
        assert!(stdout.is_empty(), "the summary went to the file: {stdout}");
        let s: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
        for j in s["jobs"].as_array().unwrap() {
            ran.push(j["index"].as_u64().unwrap());
        }
    }
    ran.sort();
    assert_eq!(
        ran,
        [0, 1, 2, 3, 4],
        "every job ran exactly once over the shards"
    );

    let a = tree(whole.path());
    let b = tree(sharded.path());
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    for (k, v) in &a {
        assert!(v == &b[k], "{k} differs between one run and two shards");
    }
    // The captured outputs are the commands' own.
    let info: serde_json::Value =
        serde_json::from_slice(&a["out/info.json"]).expect("info is JSON");
    assert!((info["flux_lm"].as_f64().unwrap() - 2445.4).abs() < 1.0);
    let lux: Vec<f64> = String::from_utf8_lossy(&a["out/lux.txt"])
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    let (code, alone, _) = run_cli(
        &[
            "illuminance",
            root().join("assets/scenes/box_room.toml").to_str().unwrap(),
        ],
        "1 1 0.8 0 0 1\n2 1.5 0.8 0 0 1\n",
    );
    assert_eq!(code, 0);
    let alone: Vec<f64> = alone
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(lux, alone, "a job's output equals the command run alone");
    assert!(a.contains_key("out/room.png") && a.contains_key("out/sample.ies"));
}

#[test]
fn failed_jobs_are_reported_and_the_others_run() {
    let dir = tempfile::tempdir().unwrap();
    let jobs = dir.path().join("jobs.toml");
    std::fs::write(
        &jobs,
        r#"
[[job]]
args = ["ldt", "info", "missing.ldt"]
[[job]]
args = ["sun", "--lat", "48", "--lon", "16", "--time", "2026-03-21T12:00:00Z", "--json"]
stdout = "sun.json"
[[job]]
args = ["render", "--no-such-flag"]
[[job]]
args = ["ldt", "info", "missing.ldt"]
stdout = "never.json"
"#,
    )
    .unwrap();
    let (code, stdout, _) = run_cli(&["batch", jobs.to_str().unwrap()], "");
    assert_eq!(code, 1);
    let s: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let codes: Vec<u64> = s["jobs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["exit_code"].as_u64().unwrap())
        .collect();
    assert_eq!(codes, [2, 0, 2, 2]);
    assert_eq!(s["failed"], 3);
    assert!(s["jobs"][0]["error"]
        .as_str()
        .unwrap()
        .contains("missing.ldt"));
    assert!(s["jobs"][2]["error"]
        .as_str()
        .unwrap()
        .contains("--no-such-flag"));
    assert!(dir.path().join("sun.json").is_file());
    // A failed job leaves no output file, not even a temporary one.
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        names
            .iter()
            .all(|n| n != "never.json" && !n.contains(".tmp")),
        "{names:?}"
    );
    // --fail-fast stops at the first failure.
    let (code, stdout, _) = run_cli(&["batch", jobs.to_str().unwrap(), "--fail-fast"], "");
    assert_eq!(code, 1);
    let s: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(s["ran"], 1);
}

#[test]
fn bad_jobs_files_and_shards_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let jobs = dir.path().join("jobs.toml");
    std::fs::write(&jobs, "[[job]]\nargs = [\"batch\", \"x.toml\"]\n").unwrap();
    let (code, _, stderr) = run_cli(&["batch", jobs.to_str().unwrap()], "");
    assert_eq!(code, 2);
    assert!(
        stderr.contains("jobs.toml") && stderr.contains("job[0].args"),
        "{stderr}"
    );
    std::fs::write(&jobs, "[[job]]\nargs = [\"sun\"]\n").unwrap();
    let (code, _, stderr) = run_cli(&["batch", jobs.to_str().unwrap(), "--shard", "3/2"], "");
    assert_eq!(code, 2);
    assert!(stderr.contains("--shard"), "{stderr}");
    let (code, _, stderr) = run_cli(
        &["batch", dir.path().join("none.toml").to_str().unwrap()],
        "",
    );
    assert_eq!(code, 2);
    assert!(stderr.contains("none.toml"), "{stderr}");
}
