//! The commands the README and the book show: every `goniolight …` line of a shell or
//! console block is a valid command line (it parses with the clap definitions), and every
//! `$ goniolight …` line of a `console` block runs on the bundled data with exit 0 and
//! prints the output shown below it.

use std::path::Path;
use std::time::Duration;

use clap::Parser;

use super::markdown::{self, CodeBlock, Page};
use crate::common;

/// The info strings of the blocks whose `goniolight` lines are commands.
const SHELL: [&str; 5] = ["sh", "bash", "shell", "console", "text"];

/// One line of a block with its `\` continuations joined.
struct CommandLine {
    /// The line of the file it starts on.
    line: usize,
    /// Its text, the `$ ` prompt taken off.
    text: String,
    /// Whether it had the prompt (a command to run, not output shown under one).
    prompted: bool,
}

/// The lines of a block: `\` continuations joined, a `$ ` prompt taken off.
fn command_lines(block: &CodeBlock) -> Vec<CommandLine> {
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
            let joined = pending.trim();
            out.push(CommandLine {
                line: start,
                text: joined.strip_prefix("$ ").unwrap_or(joined).to_string(),
                prompted: joined.starts_with("$ "),
            });
            pending.clear();
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
    markdown::check_every_page("command lines", 30, |_, page| {
        let in_blocks = page
            .code_blocks
            .iter()
            .filter(|b| SHELL.contains(&b.info.as_str()))
            .flat_map(command_lines)
            .map(|c| (c.line, c.text, false));
        let inline = page
            .inline_code
            .iter()
            .filter(|(_, text)| !is_synopsis(text))
            .map(|(line, text)| (*line, text.clone(), true));
        let mut checked = 0;
        let mut problems = Vec::new();
        for (line, text, mention) in in_blocks.chain(inline) {
            let Some(words) = goniolight_words(&text) else {
                continue;
            };
            checked += 1;
            if let Some(why) = rejected(&words, mention) {
                problems.push(format!("{line}: {text}\n    {why}"));
            }
        }
        (checked, problems)
    });
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

/// Runs the console examples of a page in `dir`: `$` lines, each followed by lines it must
/// print. Returns how many ran and what failed ("LINE: why").
fn run_console_examples(page: &Page, dir: &Path) -> (usize, Vec<String>) {
    let mut problems = Vec::new();
    let mut ran = 0;
    for block in &page.code_blocks {
        if block.info != "console" {
            continue;
        }
        let mut last: Option<(usize, String, String)> = None;
        for CommandLine {
            line,
            text,
            prompted,
        } in command_lines(block)
        {
            if !prompted {
                // Output shown under a command: the command printed it.
                if let Some((at, cmd, out)) = &last {
                    if !text.is_empty() && !out.contains(text.trim()) {
                        problems.push(format!("{at}: {cmd}\n    did not print {:?}", text.trim()));
                    }
                }
                continue;
            }
            let Some(words) = goniolight_words(&text) else {
                problems.push(format!(
                    "{line}: only goniolight commands run in a console block: {text}"
                ));
                continue;
            };
            let args: Vec<&str> = words[1..].iter().map(String::as_str).collect();
            ran += 1;
            let (code, out, err, timed_out) =
                common::run_cli_in(dir, &args, "", Duration::from_secs(300));
            if code != 0 || timed_out {
                problems.push(format!(
                    "{line}: {text}\n    exit {code}{}: {}",
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
    markdown::check_every_page("console examples", 6, |_, page| {
        run_console_examples(page, dir.path())
    });
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
    markdown::check_every_page("toml examples", 5, |_, page| {
        let blocks: Vec<_> = page
            .code_blocks
            .iter()
            .filter(|b| b.info == "toml")
            .collect();
        let problems = blocks
            .iter()
            .filter_map(|b| Some(format!("{}: {}", b.line, toml_rejected(&b.text)?)))
            .collect();
        (blocks.len(), problems)
    });
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
    // A page as the documentation holds it (read back from a file, as the pages are).
    let page_with = |body: &str| {
        std::fs::write(&page, format!("# t\n\n```console\n{body}\n```\n")).unwrap();
        markdown::read(&page)
    };
    let right = page_with(&format!("{info}\n  CIE flux code  55 85 98 100 100"));
    assert_eq!(run_console_examples(&right, dir.path()), (1, vec![]));
    for wrong in [
        format!("{info}\n  CIE flux code  99 99 99 100 100"),
        "$ goniolight ldt info luminaires/none.ldt".to_string(),
        "$ ls".to_string(),
    ] {
        let (_, problems) = run_console_examples(&page_with(&wrong), dir.path());
        assert_eq!(problems.len(), 1, "{wrong}: {problems:?}");
    }
}
