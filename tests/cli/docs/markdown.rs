//! The Markdown files of the repository's documentation and the parts of them the tests
//! read: fenced code blocks and links.

use std::path::{Path, PathBuf};

use pulldown_cmark::{CodeBlockKind, Event, Options, Parser, Tag, TagEnd};

use crate::common;

/// README.md, ARCHITECTURE.md, CHANGELOG.md and every page under `docs/src/`, as paths
/// relative to the repository root, sorted.
pub fn documentation_files() -> Vec<PathBuf> {
    let root = common::root();
    let mut files: Vec<PathBuf> = ["README.md", "ARCHITECTURE.md", "CHANGELOG.md"]
        .iter()
        .map(PathBuf::from)
        .collect();
    for page in common::files_in(&root.join("docs/src")) {
        if page.extension().is_some_and(|e| e == "md") {
            files.push(Path::new("docs/src").join(page));
        }
    }
    files
}

/// Runs `check` on every documentation page; it returns how many things it checked there
/// and what is wrong ("LINE: why", prefixed here with the file). Fails with every problem
/// found, or when fewer than `at_least` things were checked in all (the check would then
/// not be reading the pages).
pub fn check_every_page(
    what: &str,
    at_least: usize,
    mut check: impl FnMut(&Path, &Page) -> (usize, Vec<String>),
) {
    let mut checked = 0;
    let mut problems = Vec::new();
    for file in documentation_files() {
        let (n, found) = check(&file, &read(&file));
        checked += n;
        problems.extend(found.into_iter().map(|p| format!("{}:{p}", file.display())));
    }
    assert!(checked >= at_least, "only {checked} {what} found");
    assert!(
        problems.is_empty(),
        "{what} that fail:\n{}",
        problems.join("\n")
    );
}

/// One fenced code block: its info string (`sh`, `console`, …), its text and the line of
/// its opening fence.
pub struct CodeBlock {
    pub info: String,
    pub text: String,
    pub line: usize,
}

/// One link or image: its target as written and its line.
pub struct Link {
    pub target: String,
    pub line: usize,
}

/// What the tests read of one Markdown file.
pub struct Page {
    pub text: String,
    pub code_blocks: Vec<CodeBlock>,
    pub links: Vec<Link>,
    /// Inline code spans outside headings, with their lines.
    pub inline_code: Vec<(usize, String)>,
    /// The anchors of its headings, as GitHub and mdBook make them.
    pub anchors: Vec<String>,
}

/// Reads and parses `rel` (relative to the repository root).
pub fn read(rel: &Path) -> Page {
    let text = std::fs::read_to_string(common::root().join(rel))
        .unwrap_or_else(|e| panic!("{}: {e}", rel.display()));
    let line_of = |offset: usize| text[..offset].matches('\n').count() + 1;
    let mut page = Page {
        text: String::new(),
        code_blocks: Vec::new(),
        links: Vec::new(),
        inline_code: Vec::new(),
        anchors: Vec::new(),
    };
    let mut block: Option<CodeBlock> = None;
    let mut heading: Option<String> = None;
    for (event, range) in Parser::new_ext(&text, Options::ENABLE_TABLES).into_offset_iter() {
        match event {
            Event::Start(Tag::CodeBlock(CodeBlockKind::Fenced(info))) => {
                block = Some(CodeBlock {
                    info: info.split_whitespace().next().unwrap_or("").to_string(),
                    text: String::new(),
                    line: line_of(range.start),
                })
            }
            Event::End(TagEnd::CodeBlock) => page.code_blocks.extend(block.take()),
            Event::Text(t) if block.is_some() => block.as_mut().unwrap().text.push_str(&t),
            Event::Start(Tag::Link { dest_url, .. })
            | Event::Start(Tag::Image { dest_url, .. }) => page.links.push(Link {
                target: dest_url.to_string(),
                line: line_of(range.start),
            }),
            Event::Start(Tag::Heading { .. }) => heading = Some(String::new()),
            Event::End(TagEnd::Heading(_)) => {
                let base = anchor(&heading.take().unwrap_or_default());
                // A repeated heading gets -1, -2, … as on GitHub.
                let mut name = base.clone();
                let mut n = 0;
                while page.anchors.contains(&name) {
                    n += 1;
                    name = format!("{base}-{n}");
                }
                page.anchors.push(name);
            }
            Event::Text(t) | Event::Code(t) if heading.is_some() => {
                heading.as_mut().unwrap().push_str(&t)
            }
            Event::Code(t) => page.inline_code.push((line_of(range.start), t.to_string())),
            _ => {}
        }
    }
    page.text = text;
    page
}

/// A heading's anchor: lower case, punctuation other than `-` and `_` dropped, spaces as
/// `-` (GitHub's rule, which mdBook follows).
pub fn anchor(title: &str) -> String {
    title
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

#[test]
fn anchors_follow_githubs_rule() {
    assert_eq!(
        anchor("Live in the viewer: luminaires moved without a restart"),
        "live-in-the-viewer-luminaires-moved-without-a-restart"
    );
    assert_eq!(anchor("CPU ray casts (BVH)"), "cpu-ray-casts-bvh");
    assert_eq!(
        anchor("Lighting calculations (calc)"),
        "lighting-calculations-calc"
    );
}
