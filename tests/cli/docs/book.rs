//! The shape of the documentation: a README read in five minutes that starts with the two
//! commands, and a book whose summary holds every page.

use std::path::Path;

use super::markdown;
use crate::common;

/// The README's longest allowed length, lines.
const README_LINES: usize = 250;

#[test]
fn the_readme_is_short_and_starts_with_the_two_commands() {
    let readme = markdown::read(Path::new("README.md"));
    let lines = readme.text.lines().count();
    assert!(
        lines <= README_LINES,
        "README.md has {lines} lines (at most {README_LINES})"
    );
    let first: Vec<&str> = readme
        .code_blocks
        .iter()
        .take(2)
        .map(|b| b.text.trim())
        .collect();
    assert_eq!(first, ["scripts/demo.sh", "scripts/test.sh"]);
    let ci = std::fs::read_to_string(common::root().join(".ci/run")).unwrap();
    assert!(
        ci.lines()
            .any(|l| l.trim_start().contains("scripts/test.sh")),
        ".ci/run calls the test command"
    );
}

#[test]
fn every_page_of_the_book_is_in_its_summary() {
    let summary = markdown::read(Path::new("docs/src/SUMMARY.md"));
    let listed: Vec<&str> = summary.links.iter().map(|l| l.target.as_str()).collect();
    let pages = common::files_in(&common::root().join("docs/src"));
    let mut missing = Vec::new();
    for page in &pages {
        let name = page.to_string_lossy();
        if name.ends_with(".md") && name != "SUMMARY.md" && !listed.contains(&name.as_ref()) {
            missing.push(name.into_owned());
        }
    }
    assert!(
        listed.len() >= 40,
        "only {} pages in the summary",
        listed.len()
    );
    assert!(
        missing.is_empty(),
        "pages the summary does not list: {missing:?}"
    );
}
