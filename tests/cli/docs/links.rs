//! Every relative link and image of the documentation resolves: the file exists inside the
//! repository and the heading an anchor names is there.

use std::path::{Component, Path, PathBuf};

use super::markdown;
use crate::common;

/// `path` with `.` and `..` taken out, or `None` when it climbs above its start.
fn normalised(path: &Path) -> Option<PathBuf> {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    return None;
                }
            }
            other => out.push(other),
        }
    }
    Some(out)
}

/// What is wrong with `target` written in `page` (relative to the root), if anything.
fn broken(page: &Path, anchors: &[String], target: &str) -> Option<String> {
    if target.contains("://") || target.starts_with("mailto:") {
        return None;
    }
    let (path, fragment) = target.split_once('#').unwrap_or((target, ""));
    let (file, anchors_there) = if path.is_empty() {
        (page.to_path_buf(), anchors.to_vec())
    } else {
        let Some(file) = normalised(&page.parent().unwrap().join(path)) else {
            return Some("leaves the repository".into());
        };
        let on_disk = common::root().join(&file);
        if !on_disk.exists() {
            return Some(format!("{} does not exist", file.display()));
        }
        let is_markdown = file.extension().is_some_and(|e| e == "md");
        if fragment.is_empty() || !is_markdown {
            return None;
        }
        (file.clone(), markdown::read(&file).anchors)
    };
    (!fragment.is_empty() && !anchors_there.iter().any(|a| a == fragment))
        .then(|| format!("{} has no heading #{fragment}", file.display()))
}

#[test]
fn every_relative_link_and_image_resolves() {
    markdown::check_every_page("links", 100, |file, page| {
        let problems = page
            .links
            .iter()
            .filter_map(|link| {
                let why = broken(file, &page.anchors, &link.target)?;
                Some(format!("{}: ({}) {why}", link.line, link.target))
            })
            .collect();
        (page.links.len(), problems)
    });
}

#[test]
fn a_broken_link_is_found() {
    let page = Path::new("docs/src/guide/calc.md");
    assert!(broken(page, &[], "../images/calc-work-plane.png").is_none());
    assert!(broken(page, &[], "../images/no-such.png").is_some());
    assert!(broken(page, &[], "../../../../outside.md").is_some());
    assert!(broken(page, &["here".into()], "#here").is_none());
    assert!(broken(page, &["here".into()], "#there").is_some());
    assert!(broken(page, &[], "radiosity.md#no-such-heading").is_some());
    assert!(broken(page, &[], "radiosity.md#radiosity").is_none());
    assert!(broken(page, &[], "https://example.com/x.md#y").is_none());
}
