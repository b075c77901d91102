//! Checked-in files that the code generates: compared with what it generates now, or
//! written when `GONIOLIGHT_BLESS` is set (scripts/gen-docs.sh).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::common;

/// Fails unless the files `want` (paths relative to the repository root) are checked in
/// as generated and the folders `owned` hold nothing else; with `GONIOLIGHT_BLESS` set,
/// writes them first (emptying `owned`).
pub fn compare_or_bless(want: &BTreeMap<PathBuf, Vec<u8>>, owned: &[&str]) {
    let root = common::root();
    if std::env::var_os("GONIOLIGHT_BLESS").is_some() {
        for dir in owned {
            let _ = std::fs::remove_dir_all(root.join(dir));
            std::fs::create_dir_all(root.join(dir)).unwrap();
        }
        for (path, bytes) in want {
            std::fs::write(root.join(path), bytes).unwrap();
        }
    }
    let mut stale = Vec::new();
    for dir in owned {
        for rel in common::files_in(&root.join(dir)) {
            let path = Path::new(dir).join(rel);
            if !want.contains_key(&path) {
                stale.push(path);
            }
        }
    }
    let differ: Vec<_> = want
        .iter()
        .filter(|(p, bytes)| std::fs::read(root.join(p)).ok().as_ref() != Some(*bytes))
        .map(|(p, _)| p)
        .collect();
    assert!(
        stale.is_empty() && differ.is_empty(),
        "generated documentation is out of date (run scripts/gen-docs.sh):\n\
         differ or missing: {differ:?}\nstale: {stale:?}"
    );
}
