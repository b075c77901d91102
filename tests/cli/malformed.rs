//! Crafted malformed files: each gives exit code 2, a message naming the file and the
//! line, no panic and no output (tests/data/malformed/make.py makes them).

use crate::common;

use common::{root, run_cli};

#[test]
fn every_malformed_file_is_rejected_with_file_and_line() {
    let dir = root().join("tests/data/malformed");
    let expected = std::fs::read_to_string(dir.join("EXPECTED.txt")).unwrap();
    let mut n = 0;
    for row in expected.lines().filter(|l| !l.is_empty()) {
        let mut parts = row.split('\t');
        let (file, line, text) = (
            parts.next().unwrap(),
            parts.next().unwrap(),
            parts.next().unwrap(),
        );
        let path = dir.join(file);
        let path_s = path.to_str().unwrap();
        for args in [
            vec!["ldt", "info", path_s, "--json"],
            vec!["ldt", "check", path_s],
        ] {
            let (code, out, err) = run_cli(&args, "");
            assert_eq!(code, 2, "{file}: exit code, stderr: {err}");
            assert!(out.is_empty(), "{file}: no partial output, got {out}");
            assert!(!err.contains("panicked"), "{file}: {err}");
            assert!(err.contains(file), "{file}: message names the file: {err}");
            assert!(
                err.contains(&format!("line {line}:")),
                "{file}: line {line}: {err}"
            );
            assert!(err.contains(text), "{file}: {text:?} in {err}");
        }
        n += 1;
    }
    assert!(n >= 20, "at least 20 malformed cases, found {n}");
}

#[test]
fn missing_file_and_bad_flags_exit_2() {
    let (code, out, err) = run_cli(&["ldt", "info", "no/such/file.ldt"], "");
    assert_eq!(code, 2);
    assert!(out.is_empty() && err.contains("no/such/file.ldt"), "{err}");
    let (code, _, _) = run_cli(&["ldt", "info"], "");
    assert_eq!(code, 2);
    let (code, _, _) = run_cli(&["ldt", "sample", "x.ldt", "--interp", "cubic"], "");
    assert_eq!(code, 2);
    let f = common::luminaire("eulumdat-plot/sample_02_isym4.ldt");
    let (code, _, err) = run_cli(
        &["ldt", "check", f.to_str().unwrap(), "--downsample", "0,5"],
        "",
    );
    assert_eq!(code, 2, "{err}");
    // The flag's parser refuses it (the library's own check answers Python: pytest).
    assert!(err.contains("expected a positive number"), "{err}");
    let (code, _, err) = run_cli(
        &["ldt", "check", f.to_str().unwrap(), "--downsample", "15,5"],
        "",
    );
    assert_eq!(
        code, 2,
        "a 15° × 5° file has nothing to hide at 15° × 5°: {err}"
    );
    assert!(err.contains("no measured value is hidden"), "{err}");
}

#[test]
fn sample_rejects_bad_stdin_without_partial_output() {
    let f = common::luminaire("eulumdat-plot/sample_02_isym4.ldt");
    let (code, out, err) = run_cli(&["ldt", "sample", f.to_str().unwrap()], "0 10\n0 abc\n");
    assert_eq!(code, 2);
    assert!(out.is_empty(), "{out}");
    assert!(err.contains("<stdin>: line 2"), "{err}");
    let (code, out, _) = run_cli(&["ldt", "sample", f.to_str().unwrap()], "0 190\n");
    assert_eq!(code, 2);
    assert!(out.is_empty());
}

#[test]
fn a_command_that_refuses_its_flags_before_reading_its_input_still_reports_exit_2() {
    // More input than a pipe holds: the command exits without reading it, so the write
    // meets a closed pipe every time (the race that once failed a CI run).
    let f = common::luminaire("eulumdat-plot/sample_02_isym4.ldt");
    let input = "0 10\n".repeat(1 << 16);
    let (code, out, err) = run_cli(
        &["ldt", "sample", f.to_str().unwrap(), "--no-such-flag"],
        &input,
    );
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty(), "{out}");
    assert!(err.contains("--no-such-flag"), "{err}");
}
