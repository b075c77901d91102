//! The command-line reference under `docs/src/reference/cli/` (a Markdown page per command)
//! and the man pages under `docs/man/`, generated from the clap definitions; a test fails
//! when a checked-in page differs from what the code generates, and another when `--help`
//! lists a command or flag that the reference lacks.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::{Arg, ArgAction, Command, CommandFactory};

use super::generated;
use crate::common;

/// Where the Markdown pages live, relative to the repository root.
const PAGES: &str = "docs/src/reference/cli";
/// Where the man pages live.
const MAN: &str = "docs/man";
/// The first line of every generated Markdown page after its title.
const GENERATED: &str = "<!-- Generated from the clap definitions in src/cli/ by \
`scripts/gen-docs.sh`; edit the doc comments there, not this page. -->";

/// The command line as the binary builds it, with bin names and `help` propagated.
fn command() -> Command {
    let mut cmd = goniolight::cli::Cli::command();
    cmd.build();
    cmd
}

/// Every visible command below the root with its path of names (`["ldt", "info"]`), in
/// the order `--help` lists them, depth first.
fn commands(cmd: &Command, path: &[String], out: &mut Vec<(Vec<String>, Command)>) {
    for sub in cmd.get_subcommands() {
        if sub.is_hide_set() || sub.get_name() == "help" {
            continue;
        }
        let mut here = path.to_vec();
        here.push(sub.get_name().to_string());
        out.push((here.clone(), sub.clone()));
        commands(sub, &here, out);
    }
}

/// An argument as the reference names it: `<FILES>...`, `-o`, `--out <DIR>`.
fn signature(arg: &Arg) -> String {
    let names: Vec<String> = arg
        .get_value_names()
        .map(|v| v.iter().map(|n| format!("<{n}>")).collect())
        .unwrap_or_else(|| vec![format!("<{}>", arg.get_id().as_str().to_uppercase())]);
    let many = matches!(arg.get_action(), ArgAction::Append)
        || arg.get_num_args().is_some_and(|n| n.max_values() > 1);
    let value = format!("{}{}", names.join(" "), if many { "..." } else { "" });
    if arg.is_positional() {
        return format!("`{value}`");
    }
    let mut flags = Vec::new();
    if let Some(s) = arg.get_short() {
        flags.push(format!("-{s}"));
    }
    if let Some(l) = arg.get_long() {
        flags.push(format!("--{l}"));
    }
    let flags = flags.join(", ");
    if arg.get_action().takes_values() {
        format!("`{flags} {value}`")
    } else {
        format!("`{flags}`")
    }
}

/// The help of `arg` as one list item: signature, text, possible values, default.
fn entry(arg: &Arg) -> String {
    let help = arg
        .get_long_help()
        .or(arg.get_help())
        .map(|h| h.to_string())
        .unwrap_or_default();
    let mut text = format!("- {}", signature(arg));
    if arg.is_required_set() && !arg.is_positional() {
        text.push_str(" (required)");
    }
    let mut lines = help.trim().lines();
    if let Some(first) = lines.next() {
        write!(text, ": {first}").unwrap();
    }
    for line in lines {
        text.push('\n');
        if !line.trim().is_empty() {
            write!(text, "  {line}").unwrap();
        }
    }
    let values: Vec<String> = arg
        .get_possible_values()
        .iter()
        .filter(|v| !v.is_hide_set())
        .map(|v| format!("`{}`", v.get_name()))
        .collect();
    if !values.is_empty() && arg.get_action().takes_values() {
        write!(text, "\n\n  Values: {}.", values.join(", ")).unwrap();
    }
    let defaults: Vec<String> = arg
        .get_default_values()
        .iter()
        .map(|v| format!("`{}`", v.to_string_lossy()))
        .collect();
    if !defaults.is_empty() && !arg.is_hide_default_value_set() && arg.get_action().takes_values() {
        write!(text, "\n\n  Default: {}.", defaults.join(", ")).unwrap();
    }
    text.push('\n');
    text
}

/// The file name of a command's page (without extension): `ldt-info`.
fn page_name(path: &[String]) -> String {
    path.join("-")
}

/// The Markdown page of one command.
fn page(path: &[String], cmd: &mut Command) -> String {
    let mut out = format!("# goniolight {}\n\n{GENERATED}\n\n", path.join(" "));
    if let Some(about) = cmd.get_long_about().or(cmd.get_about()) {
        writeln!(out, "{}\n", about.to_string().trim()).unwrap();
    }
    writeln!(
        out,
        "```text\n{}\n```\n",
        cmd.render_usage().to_string().trim()
    )
    .unwrap();
    let subs: Vec<(String, String)> = cmd
        .get_subcommands()
        .filter(|s| !s.is_hide_set() && s.get_name() != "help")
        .map(|s| {
            let mut sub_path = path.to_vec();
            sub_path.push(s.get_name().to_string());
            let about = s.get_about().map(|a| a.to_string()).unwrap_or_default();
            (
                format!("[`{}`]({}.md)", s.get_name(), page_name(&sub_path)),
                about,
            )
        })
        .collect();
    if !subs.is_empty() {
        out.push_str("## Commands\n\n");
        for (link, about) in subs {
            writeln!(out, "- {link}: {}", about.trim()).unwrap();
        }
        out.push('\n');
    }
    let visible = |a: &&Arg| !a.is_hide_set() && !matches!(a.get_id().as_str(), "help" | "version");
    let positionals: Vec<&Arg> = cmd.get_positionals().filter(visible).collect();
    if !positionals.is_empty() {
        out.push_str("## Arguments\n\n");
        for arg in positionals {
            out.push_str(&entry(arg));
        }
        out.push('\n');
    }
    // Options and flags in the order the code defines them (as --help lists them).
    let options: Vec<&Arg> = cmd
        .get_arguments()
        .filter(|a| !a.is_positional())
        .filter(visible)
        .collect();
    if !options.is_empty() {
        out.push_str("## Options\n\n");
        for arg in options {
            out.push_str(&entry(arg));
        }
        out.push('\n');
    }
    out.push_str("Every command also takes `-h`/`--help`.\n");
    out
}

/// The index page: every command with its one-line description.
fn index(root: &Command, all: &[(Vec<String>, Command)]) -> String {
    let mut out = format!("# Command line\n\n{GENERATED}\n\n");
    if let Some(about) = root.get_about() {
        writeln!(out, "{}\n", about.to_string().trim()).unwrap();
    }
    out.push_str(
        "Exit codes: 0 success, 2 bad input or usage (the message names the file and line, or \
         the flag), 1 any other failure. `-V`, `--version` prints the version; every command takes \
         `-h`, `--help`. The same pages as man pages: `docs/man/`.\n\n",
    );
    for (path, cmd) in all {
        let about = cmd.get_about().map(|a| a.to_string()).unwrap_or_default();
        let indent = "  ".repeat(path.len() - 1);
        writeln!(
            out,
            "{indent}- [`goniolight {}`]({}.md): {}",
            path.join(" "),
            page_name(path),
            about.trim()
        )
        .unwrap();
    }
    out
}

/// Every generated file: path relative to the repository root → contents.
fn generated() -> BTreeMap<PathBuf, Vec<u8>> {
    let root = command();
    let mut all = Vec::new();
    commands(&root, &[], &mut all);
    let mut files = BTreeMap::new();
    files.insert(
        Path::new(PAGES).join("index.md"),
        index(&root, &all).into_bytes(),
    );
    let mut man = Vec::new();
    clap_mangen::Man::new(root.clone())
        .render(&mut man)
        .unwrap();
    files.insert(Path::new(MAN).join("goniolight.1"), man);
    for (path, cmd) in &all {
        let mut cmd = cmd.clone();
        files.insert(
            Path::new(PAGES).join(format!("{}.md", page_name(path))),
            page(path, &mut cmd).into_bytes(),
        );
        let name = format!("goniolight-{}", page_name(path));
        let mut man = Vec::new();
        // clap takes a name that lives as long as the program (no `string` feature).
        let leaked: &'static str = Box::leak(name.clone().into_boxed_str());
        clap_mangen::Man::new(cmd.name(leaked))
            .render(&mut man)
            .unwrap();
        files.insert(Path::new(MAN).join(format!("{name}.1")), man);
    }
    files
}

#[test]
fn the_command_line_reference_is_what_the_code_generates() {
    generated::compare_or_bless(&generated(), &[PAGES, MAN]);
}

/// The commands and `--flags` that `goniolight PATH --help` lists.
fn help_lists(path: &[String]) -> (Vec<String>, Vec<String>) {
    let mut args: Vec<&str> = path.iter().map(String::as_str).collect();
    args.push("--help");
    let (code, out, err) = common::run_cli(&args, "");
    assert_eq!(code, 0, "{args:?}: {err}");
    let mut subcommands = Vec::new();
    let mut flags = Vec::new();
    let mut section = "";
    for line in out.lines() {
        if !line.starts_with(' ') && line.ends_with(':') {
            section = line;
            continue;
        }
        let word = line.split_whitespace().next().unwrap_or("");
        match section {
            "Commands:" if line.starts_with("  ") && word != "help" && !word.is_empty() => {
                subcommands.push(word.to_string())
            }
            "Options:" => {
                for token in line.split(|c: char| c.is_whitespace() || c == ',') {
                    let is_flag = token.len() > 2
                        && token.starts_with("--")
                        && token[2..]
                            .chars()
                            .all(|c| c.is_ascii_alphanumeric() || c == '-');
                    if is_flag && line.trim_start().starts_with('-') && token != "--help" {
                        flags.push(token.to_string());
                    }
                }
            }
            _ => {}
        }
    }
    (subcommands, flags)
}

#[test]
fn every_command_and_flag_that_help_lists_has_an_entry() {
    let root = common::root();
    let page_of = |path: &[String]| {
        let file = if path.is_empty() {
            "index".to_string()
        } else {
            page_name(path)
        };
        std::fs::read_to_string(root.join(PAGES).join(format!("{file}.md")))
            .unwrap_or_else(|e| panic!("no reference page for goniolight {path:?}: {e}"))
    };
    let mut queue = vec![Vec::<String>::new()];
    let (mut pages, mut flags) = (0, 0);
    let mut missing = Vec::new();
    while let Some(path) = queue.pop() {
        let page = page_of(&path);
        pages += 1;
        let (subcommands, listed_flags) = help_lists(&path);
        for sub in subcommands {
            let mut next = path.clone();
            next.push(sub);
            queue.push(next);
        }
        for flag in listed_flags {
            flags += 1;
            if !page.contains(&format!("`{flag}")) && !page.contains(&format!(", {flag}")) {
                missing.push(format!("goniolight {} {flag}", path.join(" ")));
            }
        }
    }
    assert!(
        pages > 20 && flags > 150,
        "{pages} pages, {flags} flags: is --help parsed?"
    );
    assert!(
        missing.is_empty(),
        "not in the reference:\n{}",
        missing.join("\n")
    );
}
