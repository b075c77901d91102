//! The commands the README and the book show: every `goniolight …` line of a shell or
//! console block is a valid command line (it parses with the clap definitions), and every
//! `$ goniolight …` line of a `console` block runs on the bundled data with exit 0 and
//! prints the output shown below it.

use std::path::Path;
use std::time::Duration;

use clap::Parser;

use super::markdown::{self, CodeBlock};
use crate::common;

/// The info strings of the blocks whose `goniolight` lines are commands.
const SHELL: [&str; 5] = ["sh", "bash", "shell", "console", "text"];

/// The command lines of a block: `\` continuations joined, a `$ ` prompt taken off,
/// comments and redirections cut off; with the line of the block they start on.
fn command_lines(block: &CodeBlock) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut pending = String::new();
    let mut start = 0;
    for (i, raw) in block.text.lines().enumerate() {
        let line = raw.trim_end();
        if pending.is_empty() {
            start = block.line + 1 + i;
        }
        let (body, continues) = match line.strip_suffix('\\') {
            Some(body) => (body, true),
            None => (line, false),
        };
        pending.push_str(body);
        pending.push(' ');
        if !continues {
            let text = pending.trim().trim_start_matches("$ ").to_string();
            pending.clear();
            out.push((start, text));
        }
    }
    out
}

/// The words of a `goniolight …` command line, or `None` for any other line.
fn goniolight_words(line: &str) -> Option<Vec<String>> {
    let line = line
        .split(" # ")
        .next()
        .unwrap()
        .split("  #")
        .next()
        .unwrap();
    let line = line.split(['<', '>', '|']).next().unwrap();
    let words = shlex::split(line)?;
    // `cargo run [--release] -- ARGS` runs goniolight with ARGS (not `--example`s).
    if words.starts_with(&["cargo".into(), "run".into()]) && !words.contains(&"--example".into()) {
        let args = words
            .iter()
            .position(|w| w == "--")
            .map_or(&[][..], |i| &words[i + 1..]);
        return Some(
            std::iter::once("goniolight".to_string())
                .chain(args.iter().cloned())
                .collect(),
        );
    }
    (words.first().map(String::as_str) == Some("goniolight")).then_some(words)
}

/// Why `words` is not a command line of goniolight, if it is not. A `mention` (an
/// inline span such as `goniolight calc` in a sentence) may leave out required arguments;
/// its command, flags and values must still exist.
fn rejected(words: &[String], mention: bool) -> Option<String> {
    use clap::error::ErrorKind;
    match goniolight::cli::Cli::try_parse_from(words) {
        Ok(_) => None,
        Err(e) if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) => None,
        Err(e)
            if mention
                && matches!(
                    e.kind(),
                    ErrorKind::MissingRequiredArgument
                        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
                ) =>
        {
            None
        }
        Err(e) => Some(e.to_string().lines().next().unwrap_or("").to_string()),
    }
}

/// Whether an inline code span is a synopsis (`[--flag N]`, `a|b`, `FILE…`) rather than a
/// command line to type.
fn is_synopsis(text: &str) -> bool {
    text.contains(['[', '|', '…']) || text.contains("...")
}

#[test]
fn every_command_shown_is_a_valid_command_line() {
    let mut problems = Vec::new();
    let mut checked = 0;
    for file in markdown::documentation_files() {
        let page = markdown::read(&file);
        let in_blocks = page
            .code_blocks
            .iter()
            .filter(|b| SHELL.contains(&b.info.as_str()))
            .flat_map(command_lines)
            .map(|(line, text)| (line, text, false));
        let inline = page
            .inline_code
            .iter()
            .filter(|(_, text)| !is_synopsis(text))
            .map(|(line, text)| (*line, text.clone(), true));
        for (line, text, mention) in in_blocks.chain(inline) {
            let Some(words) = goniolight_words(&text) else {
                continue;
            };
            checked += 1;
            if let Some(why) = rejected(&words, mention) {
                problems.push(format!("{}:{line}: {text}\n    {why}", file.display()));
            }
        }
    }
    assert!(checked > 30, "only {checked} command lines found");
    assert!(
        problems.is_empty(),
        "commands that do not parse:\n{}",
        problems.join("\n")
    );
}

#[test]
fn a_wrong_command_line_is_rejected() {
    let words = |s: &str| goniolight_words(s).unwrap();
    assert!(rejected(&words("goniolight ldt info x.ldt --json"), false).is_none());
    assert!(rejected(&words("goniolight ldt info x.ldt --jsn"), false).is_some());
    let wrong_value = words("goniolight calc s.toml --out o --indirect sometimes");
    assert!(rejected(&wrong_value, false).is_some());
    assert!(rejected(&wrong_value, true).is_some());
    assert!(rejected(
        &words("goniolight radiosity s.toml --points < points.txt"),
        false
    )
    .is_none());
    // A mention may leave out what is required, not misspell a command.
    assert!(rejected(&words("goniolight calc"), false).is_some());
    assert!(rejected(&words("goniolight calc"), true).is_none());
    assert!(rejected(&words("goniolight calk"), true).is_some());
    assert!(goniolight_words("cargo build").is_none());
    assert_eq!(
        goniolight_words("cargo run --release -- view --up z").unwrap(),
        ["goniolight", "view", "--up", "z"]
    );
    assert!(goniolight_words("cargo run --release --example make_scenes x").is_none());
}

/// A folder to run examples in: the bundled data linked in, outputs written inside.
fn example_folder() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for name in ["assets", "luminaires"] {
        std::os::unix::fs::symlink(common::root().join(name), dir.path().join(name)).unwrap();
    }
    dir
}

/// Runs the console examples of `file`: `$` lines, each followed by lines it must print.
fn run_console_examples(file: &Path, dir: &Path) -> (usize, Vec<String>) {
    let mut problems = Vec::new();
    let mut ran = 0;
    for block in markdown::read(file).code_blocks {
        if block.info != "console" {
            continue;
        }
        let mut last: Option<(usize, String, String)> = None;
        for (line, text) in command_lines(&block) {
            let is_command = block
                .text
                .lines()
                .nth(line - block.line - 1)
                .is_some_and(|l| l.starts_with("$ "));
            if !is_command {
                // Output shown under a command: the command printed it.
                if let Some((at, cmd, out)) = &last {
                    if !text.is_empty() && !out.contains(text.trim()) {
                        problems.push(format!(
                            "{}:{at}: {cmd}\n    did not print {:?}",
                            file.display(),
                            text.trim()
                        ));
                    }
                }
                continue;
            }
            let Some(words) = goniolight_words(&text) else {
                problems.push(format!(
                    "{}:{line}: only goniolight commands run in a console block: {text}",
                    file.display()
                ));
                continue;
            };
            let args: Vec<&str> = words[1..].iter().map(String::as_str).collect();
            ran += 1;
            let (code, out, err, timed_out) =
                common::run_cli_in(dir, &args, "", Duration::from_secs(300));
            if code != 0 || timed_out {
                problems.push(format!(
                    "{}:{line}: {text}\n    exit {code}{}: {}",
                    file.display(),
                    if timed_out { " (timed out)" } else { "" },
                    err.lines().last().unwrap_or("")
                ));
            }
            last = Some((line, text, out));
        }
    }
    (ran, problems)
}

#[test]
fn every_console_example_runs_as_shown() {
    let dir = example_folder();
    let mut ran = 0;
    let mut problems = Vec::new();
    for file in markdown::documentation_files() {
        let (n, p) = run_console_examples(&file, dir.path());
        ran += n;
        problems.extend(p);
    }
    assert!(ran >= 6, "only {ran} console examples ran");
    assert!(
        problems.is_empty(),
        "examples that fail:\n{}",
        problems.join("\n")
    );
}

/// Why a `toml` block of the documentation is not a valid file of its kind (scene file,
/// batch jobs file, sun-study points file), if it is not.
fn toml_rejected(text: &str) -> Option<String> {
    let first_table = text
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with('['))
        .unwrap_or("");
    let result = match first_table {
        "[[job]]" => goniolight::cli::count_jobs(Path::new("jobs.toml"), text)
            .map(|_| ())
            .map_err(|e| format!("{e:?}")),
        "[[point]]" => goniolight::study::surfaces::parse_points(text).map(|_| ()),
        _ => toml::from_str::<goniolight::scene::file::SceneFile>(text)
            .map(|_| ())
            .map_err(|e| e.to_string()),
    };
    result.err()
}

#[test]
fn every_toml_example_is_a_valid_file() {
    let mut problems = Vec::new();
    let mut checked = 0;
    for file in markdown::documentation_files() {
        for block in markdown::read(&file).code_blocks {
            if block.info != "toml" {
                continue;
            }
            checked += 1;
            if let Some(why) = toml_rejected(&block.text) {
                problems.push(format!("{}:{}: {why}", file.display(), block.line));
            }
        }
    }
    assert!(checked >= 5, "only {checked} toml blocks found");
    assert!(
        problems.is_empty(),
        "toml examples that do not read:\n{}",
        problems.join("\n")
    );
}

#[test]
fn a_wrong_toml_example_is_rejected() {
    assert!(toml_rejected("[[luminaire]]\nfile = \"a.ldt\"\nposition = [0, 0, 3]\n").is_none());
    assert!(toml_rejected("[[luminaire]]\nfile = \"a.ldt\"\nposition = [0, 0]\n").is_some());
    assert!(toml_rejected("[display]\nmode = \"shady\"\n").is_some());
    assert!(toml_rejected("[[job]]\nargs = [\"ldt\", \"info\", \"x.ldt\"]\n").is_none());
    assert!(toml_rejected("[[job]]\nargz = []\n").is_some());
}

#[test]
fn a_wrong_console_example_fails() {
    let dir = example_folder();
    let page = dir.path().join("page.md");
    let info = "$ goniolight ldt info luminaires/eulumdat-analysis/sample_18.ldt";
    let write = |body: &str| std::fs::write(&page, format!("# t\n\n```console\n{body}\n```\n"));
    write(&format!("{info}\n  CIE flux code  55 85 98 100 100")).unwrap();
    assert_eq!(run_console_examples(&page, dir.path()), (1, vec![]));
    for wrong in [
        format!("{info}\n  CIE flux code  99 99 99 100 100"),
        "$ goniolight ldt info luminaires/none.ldt".to_string(),
        "$ ls".to_string(),
    ] {
        write(&wrong).unwrap();
        let (_, problems) = run_console_examples(&page, dir.path());
        assert_eq!(problems.len(), 1, "{wrong}: {problems:?}");
    }
}
