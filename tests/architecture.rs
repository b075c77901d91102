//! The house's rules, checked on the source itself:
//! - no import cycle between the library's files (every `use crate::…`, `use super::…`,
//!   child-module path and inline `crate::…` path counts as an arrow to the file that
//!   defines the module it names, except a child naming its own ancestors);
//! - the library without default features pulls in no GPU or GUI crate;
//! - the command line, the viewer and the Python package solve radiosity only through
//!   `radiosity::session` (no second shooting loop);
//! - `gpu/` (the device layer) imports no other library module;
//! - one module style (`name/mod.rs`, never `name.rs` beside `name/`).

mod common;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

mod imports {
    use super::*;

    /// A module path (`["render", "shadows"]`) for each `.rs` file under `src`.
    pub fn module_files(src: &Path) -> BTreeMap<Vec<String>, PathBuf> {
        let mut out = BTreeMap::new();
        for path in super::rust_files(src) {
            let rel = path.strip_prefix(src).expect("under src");
            let mut parts: Vec<String> = rel
                .iter()
                .map(|p| p.to_string_lossy().trim_end_matches(".rs").to_string())
                .collect();
            match parts.last().map(String::as_str) {
                Some("main") if parts.len() == 1 => continue,
                Some("lib") if parts.len() == 1 => parts.clear(),
                Some("mod") => {
                    parts.pop();
                }
                _ => {}
            }
            out.insert(parts, path);
        }
        out
    }

    /// Source without comments, string and char literals, and without inline
    /// `#[cfg(test)]` modules (tests may reach anywhere).
    pub fn code_only(text: &str) -> String {
        let b = text.as_bytes();
        let mut out = String::with_capacity(text.len());
        let mut i = 0;
        while i < b.len() {
            if b[i..].starts_with(b"//") {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            } else if b[i..].starts_with(b"/*") {
                let mut depth = 0;
                while i < b.len() {
                    if b[i..].starts_with(b"/*") {
                        depth += 1;
                        i += 2;
                    } else if b[i..].starts_with(b"*/") {
                        depth -= 1;
                        i += 2;
                        if depth == 0 {
                            break;
                        }
                    } else {
                        i += 1;
                    }
                }
            } else if b[i] == b'"'
                || (b[i] == b'r'
                    && b.get(i + 1).is_some_and(|c| *c == b'"' || *c == b'#')
                    && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_')))
            {
                // Plain or raw string literal.
                let mut hashes = 0;
                if b[i] == b'r' {
                    i += 1;
                    while b.get(i) == Some(&b'#') {
                        hashes += 1;
                        i += 1;
                    }
                    i += 1;
                    loop {
                        if i >= b.len() {
                            break;
                        }
                        if b[i] == b'"'
                            && b[i + 1..]
                                .iter()
                                .take(hashes)
                                .filter(|c| **c == b'#')
                                .count()
                                == hashes
                        {
                            i += 1 + hashes;
                            break;
                        }
                        i += 1;
                    }
                } else {
                    i += 1;
                    while i < b.len() && b[i] != b'"' {
                        if b[i] == b'\\' {
                            i += 1;
                        }
                        i += 1;
                    }
                    i += 1;
                }
                out.push_str("\"\"");
            } else if b[i] == b'\''
                && (b.get(i + 2) == Some(&b'\'') || b.get(i + 1) == Some(&b'\\'))
            {
                // A char literal ('a' or '\n'); lifetimes ('a) are left alone.
                i += 1;
                while i < b.len() && b[i] != b'\'' {
                    if b[i] == b'\\' {
                        i += 1;
                    }
                    i += 1;
                }
                i += 1;
                out.push_str("' '");
            } else {
                let c = text[i..].chars().next().expect("char");
                out.push(c);
                i += c.len_utf8();
            }
        }
        match out.find("#[cfg(test)]\nmod ") {
            Some(k) => out[..k].to_string(),
            None => out,
        }
    }

    /// Expands a `use` tree (`a::{b, c::{d as e}, f::*}`) into its paths.
    pub fn use_paths(tree: &str) -> Vec<Vec<String>> {
        fn expand(prefix: &[String], tree: &str, out: &mut Vec<Vec<String>>) {
            let tree = tree.trim();
            if tree.is_empty() {
                return;
            }
            // Split the top level at the first `{`.
            if let Some(open) = tree.find('{') {
                let head: Vec<String> = split_path(&tree[..open]);
                let close = tree.rfind('}').unwrap_or(tree.len());
                let inner = &tree[open + 1..close];
                let mut base = prefix.to_vec();
                base.extend(head);
                let mut depth = 0;
                let mut start = 0;
                for (k, c) in inner.char_indices() {
                    match c {
                        '{' => depth += 1,
                        '}' => depth -= 1,
                        ',' if depth == 0 => {
                            expand(&base, &inner[start..k], out);
                            start = k + 1;
                        }
                        _ => {}
                    }
                }
                expand(&base, &inner[start..], out);
            } else {
                let name = tree.split(" as ").next().unwrap_or(tree);
                let mut path = prefix.to_vec();
                path.extend(split_path(name));
                if path.last().is_some_and(|s| s == "self" || s == "*") {
                    path.pop();
                }
                out.push(path);
            }
        }
        fn split_path(s: &str) -> Vec<String> {
            s.split("::")
                .map(|p| p.trim().to_string())
                .filter(|p| !p.is_empty())
                .collect()
        }
        let mut out = Vec::new();
        expand(&[], tree, &mut out);
        out
    }

    /// Every path the code names: `use` trees and inline `crate::`/`super::`/`self::` paths.
    pub fn named_paths(code: &str) -> Vec<Vec<String>> {
        let mut out = Vec::new();
        let mut rest = String::new();
        let mut i = 0;
        let bytes = code.as_bytes();
        while i < code.len() {
            let at_word = i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
            if at_word && code[i..].starts_with("use ") {
                let end = code[i..].find(';').map_or(code.len(), |k| i + k);
                out.extend(use_paths(&code[i + 4..end]));
                i = end + 1;
                continue;
            }
            let c = code[i..].chars().next().expect("char");
            rest.push(c);
            i += c.len_utf8();
        }
        for start in ["crate::", "super::", "self::"] {
            let mut from = 0;
            while let Some(k) = rest[from..].find(start) {
                let at = from + k;
                from = at + start.len();
                let before = rest[..at].chars().last();
                if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                    continue;
                }
                let path: Vec<String> = rest[at..]
                    .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                    .next()
                    .unwrap_or("")
                    .split("::")
                    .filter(|s| !s.is_empty())
                    .map(str::to_string)
                    .collect();
                out.push(path);
            }
        }
        out
    }

    /// The arrows between files: `from → to` when `from` names a module `to` defines.
    pub fn arrows(src: &Path) -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
        let modules = module_files(src);
        let mut graph: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
        for (module, file) in &modules {
            let text = std::fs::read_to_string(file).expect("read source");
            let targets = graph.entry(file.clone()).or_default();
            for path in named_paths(&code_only(&text)) {
                let Some(first) = path.first() else { continue };
                let (mut base, skip) = match first.as_str() {
                    "crate" => (Vec::new(), 1),
                    "self" => (module.clone(), 1),
                    "super" => {
                        let supers = path.iter().take_while(|s| *s == "super").count();
                        let keep = module.len().saturating_sub(supers);
                        (module[..keep].to_vec(), supers)
                    }
                    name => {
                        // A child module named without `self::` (2018 uniform paths).
                        let mut child = module.clone();
                        child.push(name.to_string());
                        if !modules.contains_key(&child) {
                            continue;
                        }
                        (module.clone(), 0)
                    }
                };
                for seg in &path[skip..] {
                    let mut next = base.clone();
                    next.push(seg.clone());
                    if modules.contains_key(&next) {
                        base = next;
                    } else {
                        break;
                    }
                }
                // A file reaching into its own ancestors (`use super::Error` in a child of
                // the module that declares it) is containment, not an arrow: the folder is
                // one module. Arrows from a parent into its children count.
                if module.starts_with(&base) {
                    continue;
                }
                if let Some(target) = modules.get(&base) {
                    if target != file {
                        targets.insert(target.clone());
                    }
                }
            }
        }
        graph
    }

    /// The strongly connected components with more than one file (Tarjan).
    pub fn cycles(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<Vec<PathBuf>> {
        struct State<'a> {
            graph: &'a BTreeMap<PathBuf, BTreeSet<PathBuf>>,
            index: BTreeMap<&'a PathBuf, usize>,
            low: BTreeMap<&'a PathBuf, usize>,
            stack: Vec<&'a PathBuf>,
            on_stack: BTreeSet<&'a PathBuf>,
            next: usize,
            out: Vec<Vec<PathBuf>>,
        }
        fn visit<'a>(s: &mut State<'a>, v: &'a PathBuf) {
            s.index.insert(v, s.next);
            s.low.insert(v, s.next);
            s.next += 1;
            s.stack.push(v);
            s.on_stack.insert(v);
            let graph = s.graph;
            for w in graph.get(v).into_iter().flatten() {
                let Some((w, _)) = graph.get_key_value(w) else {
                    continue;
                };
                if !s.index.contains_key(w) {
                    visit(s, w);
                    let lw = s.low[w];
                    let lv = s.low.get_mut(v).expect("low");
                    *lv = (*lv).min(lw);
                } else if s.on_stack.contains(w) {
                    let iw = s.index[w];
                    let lv = s.low.get_mut(v).expect("low");
                    *lv = (*lv).min(iw);
                }
            }
            if s.low[v] == s.index[v] {
                let mut scc = Vec::new();
                while let Some(w) = s.stack.pop() {
                    s.on_stack.remove(w);
                    scc.push(w.clone());
                    if w == v {
                        break;
                    }
                }
                if scc.len() > 1 {
                    scc.sort();
                    s.out.push(scc);
                }
            }
        }
        let mut s = State {
            graph,
            index: BTreeMap::new(),
            low: BTreeMap::new(),
            stack: Vec::new(),
            on_stack: BTreeSet::new(),
            next: 0,
            out: Vec::new(),
        };
        for v in graph.keys() {
            if !s.index.contains_key(v) {
                visit(&mut s, v);
            }
        }
        s.out
    }
}

fn describe(cycles: &[Vec<PathBuf>], graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> String {
    let mut msg = String::new();
    for c in cycles {
        msg.push_str("cycle:\n");
        for a in c {
            for b in &graph[a] {
                if c.contains(b) {
                    msg.push_str(&format!("  {} -> {}\n", a.display(), b.display()));
                }
            }
        }
    }
    msg
}

#[test]
fn the_library_has_no_import_cycles() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let graph = imports::arrows(&src);
    // The check sees the real arrows (a broken parser would find none and pass).
    let arrows: usize = graph.values().map(BTreeSet::len).sum();
    assert!(
        arrows > 150,
        "only {arrows} arrows found: the import parser is broken"
    );
    let render = src.join("render/mod.rs");
    assert!(graph[&src.join("cli/render.rs")].contains(&render));
    let cycles = imports::cycles(&graph);
    assert!(cycles.is_empty(), "{}", describe(&cycles, &graph));
}

#[test]
fn a_planted_cycle_is_found() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path();
    let write = |p: &str, t: &str| {
        let path = src.join(p);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, t).unwrap();
    };
    write("lib.rs", "pub mod a;\npub mod b;\npub mod c;\n");
    write(
        "a/mod.rs",
        "mod inner;\nuse inner::X;\n// use crate::c; (a comment)\n",
    );
    write(
        "a/inner.rs",
        "use crate::b::{self, Y as Z};\nuse super::helper;\npub struct X;\n",
    );
    write(
        "b.rs",
        "pub fn f() { let _ = crate::a::helper(); }\npub struct Y;\n",
    );
    write(
        "c.rs",
        "const S: &str = \"crate::a\";\n#[cfg(test)]\nmod tests { use crate::a; }\n",
    );
    let graph = imports::arrows(src);
    let cycles = imports::cycles(&graph);
    assert_eq!(cycles.len(), 1, "{}", describe(&cycles, &graph));
    let names: Vec<String> = cycles[0]
        .iter()
        .map(|p| p.strip_prefix(src).unwrap().display().to_string())
        .collect();
    assert_eq!(names, ["a/inner.rs", "a/mod.rs", "b.rs"]);
    // Strings, comments and test modules are not arrows.
    assert!(graph[&src.join("c.rs")].is_empty());
    assert!(!graph[&src.join("a/mod.rs")].contains(&src.join("c.rs")));
    // A child naming its parent is containment; the parent naming the child is an arrow.
    assert!(!graph[&src.join("a/inner.rs")].contains(&src.join("a/mod.rs")));
    assert!(graph[&src.join("a/mod.rs")].contains(&src.join("a/inner.rs")));
}

#[test]
fn use_trees_expand_to_every_path() {
    let paths = imports::use_paths("crate::a::{b, c::{d as e, self}, f::*}");
    let joined: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        joined,
        [
            "crate::a::b",
            "crate::a::c::d",
            "crate::a::c",
            "crate::a::f"
        ]
    );
}

#[test]
fn the_library_without_default_features_has_no_gpu_or_gui_crates() {
    let out = std::process::Command::new(env!("CARGO"))
        .args([
            "tree",
            "--offline",
            "--no-default-features",
            "-e",
            "normal",
            "--prefix",
            "none",
            "-p",
            "goniolight",
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run cargo tree");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let tree = String::from_utf8_lossy(&out.stdout);
    let crates: BTreeSet<&str> = tree
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert!(
        crates.contains("goniolight") && crates.contains("glam"),
        "{tree}"
    );
    for gui in [
        "wgpu",
        "egui",
        "winit",
        "rfd",
        "egui-wgpu",
        "naga",
        "clap",
        "indicatif",
    ] {
        assert!(
            !crates.contains(gui),
            "{gui} is in the library's tree without default features"
        );
    }
}

/// proptest reads a test module's failure seeds from a folder beside the nearest folder
/// with a `main.rs` or `lib.rs`: for `tests/AREA/NAME.rs` that is
/// `tests/proptest-regressions/NAME.txt`. A seed file anywhere else (such as
/// `NAME.proptest-regressions` beside its module) is never read, and its cases never run.
#[test]
fn proptest_seed_files_sit_where_proptest_reads_them() {
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let stray: Vec<_> = common::files_in(&tests)
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e == "proptest-regressions"))
        .collect();
    assert!(
        stray.is_empty(),
        "seed files proptest never reads: {stray:?}"
    );
    let seeds = tests.join("proptest-regressions");
    let mut modules = 0;
    for seed in common::files_in(&seeds) {
        let name = seed.file_stem().unwrap().to_str().unwrap();
        let module: Vec<_> = ["cpu", "gpu", "cli", "viewer"]
            .iter()
            .map(|area| tests.join(area).join(format!("{name}.rs")))
            .filter(|p| p.is_file())
            .collect();
        assert_eq!(
            module.len(),
            1,
            "{seed:?} belongs to one test module: {module:?}"
        );
        let text = std::fs::read_to_string(&module[0]).unwrap();
        assert!(
            text.contains("proptest!"),
            "{:?} has no property test",
            module[0]
        );
        modules += 1;
    }
    assert!(
        modules >= 3,
        "the interpolation, BVH and silhouette seeds are kept"
    );
}

/// What only `radiosity::session` (and the solver's own modules) may name: the solver,
/// its start, the view's importance, the elements' construction, the gather, the loop's
/// steps.
const SOLVER_INTERNALS: [&str; 9] = [
    "GpuSolver",
    "InitialState",
    "LuminaireLight",
    "ViewDriven",
    "RadiosityScene::",
    "gather::",
    "select_next",
    "shoot_until",
    "solve_to_scale",
];

/// The solver internals that `text` names outside comments, with their line numbers.
fn solver_internals_named(text: &str) -> Vec<(usize, &'static str)> {
    let mut found = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        for name in SOLVER_INTERNALS {
            if code.contains(name) {
                found.push((i + 1, name));
            }
        }
    }
    found
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).expect("read dir") {
            let path = entry.expect("dir entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().and_then(|e| e.to_str()) == Some("rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

#[test]
fn the_front_ends_solve_radiosity_only_through_the_session() {
    let root = common::root();
    let mut files = rust_files(&root.join("src/cli"));
    files.extend(rust_files(&root.join("src/viewer")));
    files.extend(rust_files(&root.join("python/src")));
    assert!(files.len() > 20, "{} files", files.len());
    let mut offences = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).expect("read source");
        for (line, name) in solver_internals_named(&text) {
            offences.push(format!("{}:{line}: {name}", f.display()));
        }
    }
    assert!(
        offences.is_empty(),
        "front ends reach into the radiosity solver (use radiosity::session):\n{}",
        offences.join("\n")
    );
}

#[test]
fn a_planted_shooting_loop_is_found() {
    let planted = "let s = solver.select_next()?; // pick\n// solver.shoot_until(t)\nsolver.shoot_until(t, &over)?;\n";
    assert_eq!(
        solver_internals_named(planted),
        vec![(1, "select_next"), (3, "shoot_until")]
    );
}

/// The numbers (from 1) of the lines of `text` whose code, before any `//` comment, holds
/// one of `needles`.
fn lines_whose_code_holds(text: &str, needles: &[&str]) -> Vec<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, line)| {
            let code = line.split("//").next().unwrap_or("");
            needles.iter().any(|n| code.contains(n))
        })
        .map(|(i, _)| i + 1)
        .collect()
}

/// The printing macros `text` calls outside comments, with their line numbers.
fn prints_in(text: &str) -> Vec<usize> {
    lines_whose_code_holds(text, &["println!", "eprintln!", "print!(", "eprint!("])
}

/// The library's files outside the front ends (`cli/`, `viewer/`, the binary) with their
/// paths from the repository root (`src/render/mod.rs`) and the `(line → offence)` lines
/// `find` reports in each, as `path:line`.
fn library_offences(find: fn(&str) -> Vec<usize>, skip: &[&str]) -> Vec<String> {
    let root = common::root();
    let mut offences = Vec::new();
    for f in rust_files(&root.join("src")) {
        let rel = f
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let front_end = ["src/cli/", "src/viewer/", "src/main.rs"]
            .iter()
            .any(|p| rel.starts_with(p));
        if front_end || skip.contains(&rel.as_str()) {
            continue;
        }
        let text = std::fs::read_to_string(&f).expect("read source");
        for line in find(&text) {
            offences.push(format!("{rel}:{line}"));
        }
    }
    offences
}

/// Library files that still print, each with why (docs/src/design/library.md): none may
/// join without a line here.
const STILL_PRINTING: [&str; 0] = [];

/// The library says nothing on a terminal: what it worked around goes back to the caller
/// (`Scene::warnings`), and the front ends (`cli/`, `viewer/`, the binary, Python) show it.
#[test]
fn the_library_prints_nothing_the_front_ends_show_its_warnings() {
    let offences = library_offences(prints_in, &STILL_PRINTING);
    assert!(
        offences.is_empty(),
        "the library prints (return the message to the caller):\n{}",
        offences.join("\n")
    );
}

#[test]
fn a_planted_print_is_found() {
    let planted = "let a = 1; // eprintln!(\"no\")\neprintln!(\"warning: {a}\");\n";
    assert_eq!(prints_in(planted), vec![2]);
}

/// Lines of `text` that lay out a Markdown table by hand (a `|---` rule or a
/// `println!("| …`): the library's `bench::report::Table` lays them out.
fn hand_made_tables_in(text: &str) -> Vec<usize> {
    lines_whose_code_holds(text, &["\"|---", "println!(\"|"])
}

#[test]
fn the_commands_print_no_tables_by_hand() {
    let root = common::root();
    let offences: Vec<String> = rust_files(&root.join("src/cli"))
        .iter()
        .flat_map(|f| {
            let text = std::fs::read_to_string(f).expect("read source");
            let rel = f.strip_prefix(&root).unwrap().display().to_string();
            hand_made_tables_in(&text)
                .into_iter()
                .map(move |line| format!("{rel}:{line}"))
        })
        .collect();
    assert!(
        offences.is_empty(),
        "cli/ lays out tables (build a bench::report::BenchReport in the library):\n{}",
        offences.join("\n")
    );
}

#[test]
fn a_planted_hand_made_table_is_found() {
    let planted =
        "let t = 1;\nprintln!(\"| a | b |\");\nlet r = \"|---|---|\";\n// println!(\"| no\")\n";
    assert_eq!(hand_made_tables_in(planted), vec![2, 3]);
}

/// The library modules outside `gpu/` that files under `gpu/` import, as `file → module`.
fn gpu_layer_imports(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>, src: &Path) -> Vec<String> {
    let gpu = src.join("gpu");
    let mut out = Vec::new();
    for (from, targets) in graph {
        if !from.starts_with(&gpu) {
            continue;
        }
        for to in targets.iter().filter(|t| !t.starts_with(&gpu)) {
            let rel = |p: &Path| p.strip_prefix(src).unwrap_or(p).display().to_string();
            out.push(format!("{} → {}", rel(from), rel(to)));
        }
    }
    out
}

/// `gpu/` is the device layer (context, WGSL sources, read-back): it knows no photometry,
/// scene or renderer; what is uploaded lives with whoever uploads it (`render::ldt`).
#[test]
fn the_device_layer_imports_no_other_library_module() {
    let src = common::root().join("src");
    let graph = imports::arrows(&src);
    assert!(graph.keys().any(|f| f.starts_with(src.join("gpu"))));
    let offences = gpu_layer_imports(&graph, &src);
    assert!(
        offences.is_empty(),
        "gpu/ imports library modules (move the code to its user):\n{}",
        offences.join("\n")
    );
}

#[test]
fn a_planted_device_layer_import_is_found() {
    let src = Path::new("/s");
    let graph = BTreeMap::from([
        (
            src.join("gpu/mod.rs"),
            BTreeSet::from([src.join("gpu/shaders.rs")]),
        ),
        (
            src.join("gpu/ldt.rs"),
            BTreeSet::from([src.join("photometry/mod.rs")]),
        ),
    ]);
    assert_eq!(
        gpu_layer_imports(&graph, src),
        vec!["gpu/ldt.rs → photometry/mod.rs"]
    );
}

/// Files `name.rs` that sit beside a folder `name/` (the other module style).
fn modules_in_both_styles(files: &[PathBuf]) -> Vec<PathBuf> {
    let dirs: BTreeSet<PathBuf> = files
        .iter()
        .filter_map(|f| f.parent().map(Path::to_path_buf))
        .collect();
    files
        .iter()
        .filter(|f| dirs.contains(&f.with_extension("")))
        .cloned()
        .collect()
}

/// One module style: a module with children is `name/mod.rs`, never `name.rs` beside
/// `name/`.
#[test]
fn every_module_with_children_is_a_folder_with_mod_rs() {
    let root = common::root();
    let mut files = rust_files(&root.join("src"));
    files.extend(rust_files(&root.join("python/src")));
    let both = modules_in_both_styles(&files);
    assert!(
        both.is_empty(),
        "modules written as name.rs beside name/ (move to name/mod.rs): {both:?}"
    );
}

#[test]
fn a_planted_second_module_style_is_found() {
    let files = [
        "/s/a.rs",
        "/s/a/b.rs",
        "/s/c/mod.rs",
        "/s/c/d.rs",
        "/s/e.rs",
    ]
    .map(PathBuf::from);
    assert_eq!(
        modules_in_both_styles(&files),
        vec![PathBuf::from("/s/a.rs")]
    );
}

/// Lines of `text` (before its `#[cfg(test)]` module) whose code, outside comments, holds a
/// string naming a command-line flag (`--name`).
fn flags_named_in(text: &str) -> Vec<usize> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("#[cfg(test)]") {
            break;
        }
        let code = line.trim_start();
        if code.starts_with("//") {
            continue;
        }
        let bytes = code.as_bytes();
        let named = (0..bytes.len().saturating_sub(2)).any(|k| {
            bytes[k] == b'-'
                && bytes[k + 1] == b'-'
                && bytes[k + 2].is_ascii_lowercase()
                && (k == 0 || !bytes[k - 1].is_ascii_alphanumeric())
        });
        if named && (code.contains('"') || code.ends_with('\\') || !code.contains("//")) {
            out.push(i + 1);
        }
    }
    out
}

/// Errors and warnings of the library name its fields (`` `indirect` ``, `display.width`),
/// never a flag of the command line: the viewer and Python show them too, and the command
/// turns fields into flags in one place (`cli/error.rs`).
#[test]
fn the_library_names_fields_not_the_commands_flags() {
    let offences = library_offences(flags_named_in, &[]);
    assert!(
        offences.is_empty(),
        "library strings name command-line flags (quote the field in backquotes):\n{}",
        offences.join("\n")
    );
}

#[test]
fn a_planted_flag_in_a_library_string_is_found() {
    let planted = "/// `--lat` in a comment\nlet a = x--y;\nErr(\"use --indirect radiosity\")\n    \"or a smaller --map-size)\",\n#[cfg(test)]\n\"--in-tests\"\n";
    assert_eq!(flags_named_in(planted), vec![3, 4]);
}

/// Lines of `text` whose code, outside comments, uses `anyhow` (a type, a macro or an
/// import).
fn anyhow_uses_in(text: &str) -> Vec<usize> {
    lines_whose_code_holds(text, &["anyhow::", "anyhow!", "use anyhow"])
}

/// The library's errors are types a caller can match (`thiserror` enums naming the file or
/// the field): `anyhow` belongs to the front ends, which only add context and print. The
/// manifest backs this up: `anyhow` is a dependency of the `cli` and `viewer` features only.
#[test]
fn the_library_returns_typed_errors_not_anyhow() {
    let offences = library_offences(anyhow_uses_in, &[]);
    assert!(
        offences.is_empty(),
        "the library uses anyhow (return a thiserror type naming the file or field):\n{}",
        offences.join("\n")
    );
    let manifest = std::fs::read_to_string(common::root().join("Cargo.toml")).unwrap();
    let line = manifest
        .lines()
        .find(|l| l.starts_with("anyhow ="))
        .expect("anyhow in [dependencies]");
    assert!(
        line.contains("optional = true"),
        "anyhow must stay optional (the cli and viewer features'): {line}"
    );
}

#[test]
fn a_planted_anyhow_use_is_found() {
    let planted = "// anyhow::Result in a comment\nuse anyhow::Context;\nfn f() -> anyhow::Result<()> {\n    Err(anyhow!(\"no\"))\n}\n";
    assert_eq!(anyhow_uses_in(planted), vec![2, 3, 4]);
}

/// The longest a function of the library may grow, in lines from its `fn` to its closing
/// brace (the issue that split the long ones set it; a longer one is split while touched).
const MAX_FUNCTION_LINES: usize = 150;

/// Functions of `text` (with bodies) longer than `max` lines: `(line of fn, name, lines)`.
/// A function ends at the first line after its signature that is its indentation and `}`
/// (rustfmt's layout).
fn long_functions(text: &str, max: usize) -> Vec<(usize, String, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let code = line.trim_start();
        let indent = &line[..line.len() - code.len()];
        let after_qualifiers = code
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub(super) ")
            .trim_start_matches("pub ")
            .trim_start_matches("const ")
            .trim_start_matches("unsafe ");
        let Some(rest) = after_qualifiers.strip_prefix("fn ") else {
            continue;
        };
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        // The signature ends at the first line with `{` (a body) or `;` (none).
        let Some(open) =
            (i..lines.len()).find(|&k| lines[k].contains('{') || lines[k].ends_with(';'))
        else {
            continue;
        };
        if !lines[open].contains('{') || lines[open].trim_end().ends_with('}') {
            continue;
        }
        let close = format!("{indent}}}");
        if let Some(end) = (open + 1..lines.len()).find(|&k| lines[k] == close) {
            let n = end - i + 1;
            if n > max {
                out.push((i + 1, name, n));
            }
        }
    }
    out
}

/// No function of the crate (library and front ends) is longer than
/// [`MAX_FUNCTION_LINES`]: long ones were split into steps that each have a name.
#[test]
fn no_function_is_longer_than_the_limit() {
    let root = common::root();
    let mut offences = Vec::new();
    for f in rust_files(&root.join("src")) {
        let text = std::fs::read_to_string(&f).unwrap();
        for (line, name, n) in long_functions(&text, MAX_FUNCTION_LINES) {
            let rel = f.strip_prefix(&root).unwrap().display().to_string();
            offences.push(format!("{rel}:{line} fn {name}: {n} lines"));
        }
    }
    assert!(
        offences.is_empty(),
        "functions over {MAX_FUNCTION_LINES} lines (split them into named steps):\n{}",
        offences.join("\n")
    );
}

#[test]
fn a_planted_long_function_is_found() {
    let body = "    let x = 1;\n".repeat(5);
    let planted = format!(
        "fn short() {{}}\n\npub(super) fn long(\n    a: u32,\n) -> u32 {{\n{body}    a\n}}\n\nfn decl();\n    fn inner() {{\n{body}    }}\n"
    );
    assert_eq!(
        long_functions(&planted, 6),
        vec![(3, "long".to_string(), 10), (15, "inner".to_string(), 7)]
    );
    assert!(long_functions(&planted, 10).is_empty());
}

/// The viewer's files that hold its state and background work, which draw nothing: the
/// panels (`panels.rs`, `luminaires.rs`, `work.rs`, `viewport_ui.rs`, …) draw them.
const VIEWER_STATE_FILES: [&str; 7] = [
    "app.rs",
    "background.rs",
    "camera.rs",
    "files.rs",
    "jobs.rs",
    "live_radiosity.rs",
    "sun.rs",
];

/// Lines of `text` that draw egui widgets (take an `egui::Ui`), outside comments.
fn egui_drawing_in(text: &str) -> Vec<usize> {
    lines_whose_code_holds(text, &["egui::Ui", "ui: &mut Ui"])
}

/// `ViewerApp`'s state is apart from its egui panels: the state files take no `egui::Ui`.
#[test]
fn the_viewers_state_draws_no_panel() {
    let dir = common::root().join("src/viewer");
    let mut offences = Vec::new();
    for name in VIEWER_STATE_FILES {
        let text = std::fs::read_to_string(dir.join(name)).expect("a viewer state file");
        for line in egui_drawing_in(&text) {
            offences.push(format!("src/viewer/{name}:{line}"));
        }
    }
    assert!(
        offences.is_empty(),
        "the viewer's state files draw egui widgets (move the drawing to a panel file):\n{}",
        offences.join("\n")
    );
}

#[test]
fn a_planted_panel_in_the_state_is_found() {
    let planted =
        "// fn panel(ui: &mut egui::Ui)\npub fn panel(&mut self, ui: &mut egui::Ui) {\n}\n";
    assert_eq!(egui_drawing_in(planted), vec![2]);
}

/// The files of `src/cli/` that several commands share; every other file there is a
/// command (or `mod.rs`, which dispatches to them).
const CLI_HELPERS: [&str; 8] = [
    "args",
    "error",
    "image",
    "indirect",
    "interrupt",
    "scene_input",
    "solver_args",
    "solving",
];

/// The sibling modules of `src/cli/` that `text` (a file directly in `src/cli/`) names
/// through `super::`.
fn cli_siblings_named(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(at) = rest.find("super::") {
            rest = &rest[at + "super::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() && name != "super" {
                out.insert(name);
            }
        }
    }
    out
}

/// The offences of one command file: the other commands it names (`bench` may name its
/// own subcommands' files, `bench_*`).
fn commands_named_by(file: &str, text: &str, commands: &BTreeSet<String>) -> Vec<String> {
    cli_siblings_named(text)
        .into_iter()
        .filter(|m| commands.contains(m) && m != file)
        .filter(|m| !(file == "bench" && m.starts_with("bench_")))
        .collect()
}

/// The commands of `cli/` are one flat floor: a command reaches another command's code
/// never, only the shared helpers ([`CLI_HELPERS`]) and the library.
#[test]
fn no_command_reaches_into_another() {
    let dir = common::root().join("src/cli");
    let mut files = BTreeMap::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let text = if path.is_dir() {
            std::fs::read_to_string(path.join("mod.rs")).unwrap()
        } else {
            std::fs::read_to_string(&path).unwrap()
        };
        files.insert(name, text);
    }
    let commands: BTreeSet<String> = files
        .keys()
        .filter(|n| *n != "mod" && !CLI_HELPERS.contains(&n.as_str()))
        .cloned()
        .collect();
    let mut offences = Vec::new();
    for (name, text) in &files {
        if name == "mod" {
            continue;
        }
        for other in commands_named_by(name, text, &commands) {
            offences.push(format!("src/cli/{name}: uses the command {other}"));
        }
    }
    for helper in CLI_HELPERS {
        assert!(
            files.contains_key(helper),
            "{helper} is no longer in src/cli/"
        );
    }
    assert!(
        offences.is_empty(),
        "commands reach into other commands (move what they share into a helper or the library):\n{}",
        offences.join("\n")
    );
}

#[test]
fn a_planted_command_reaching_into_another_is_found() {
    let commands: BTreeSet<String> = ["demo", "ldt", "bench", "bench_profile", "render"]
        .map(String::from)
        .into();
    let planted = "use super::error::CliError;\nuse super::ldt::{write_plot};\n// super::render in a comment\nlet x = super::bench_profile::run();\n";
    assert_eq!(
        commands_named_by("demo", planted, &commands),
        vec!["bench_profile".to_string(), "ldt".to_string()]
    );
    assert!(commands_named_by("bench", "super::bench_profile::run()", &commands).is_empty());
}

/// Words that name a quantity of light or time in the commands' code.
const LIGHT_AND_TIME: [&str; 6] = ["lux", "luminance", "cd_m2", "seconds", "secs", "millis"];

/// `code` with the contents of its string literals blanked (a `-` in `"room-illuminance"`
/// is no subtraction).
fn without_strings(code: &str) -> String {
    let mut out = String::with_capacity(code.len());
    let (mut inside, mut escaped) = (false, false);
    for c in code.chars() {
        if inside {
            if escaped {
                escaped = false;
            } else if c == '\\' {
                escaped = true;
            } else if c == '"' {
                inside = false;
                out.push(c);
            }
            continue;
        }
        if c == '"' {
            inside = true;
        }
        out.push(c);
    }
    out
}

/// Lines of `text` where a word naming light or time ([`LIGHT_AND_TIME`]) is an operand of
/// `+ - * /` (the operator right before the word, or right after it and any call's
/// parentheses), outside comments and strings.
fn arithmetic_on_light_or_time(text: &str) -> Vec<usize> {
    let is_word = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '.';
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let code = without_strings(line.split("//").next().unwrap_or(""));
        let chars: Vec<char> = code.chars().collect();
        let mut k = 0;
        let mut hit = false;
        while k < chars.len() {
            if !is_word(chars[k]) {
                k += 1;
                continue;
            }
            let start = k;
            while k < chars.len() && (is_word(chars[k]) || chars[k] == '(' || chars[k] == ')') {
                k += 1;
            }
            let token: String = chars[start..k].iter().collect();
            if !LIGHT_AND_TIME.iter().any(|w| token.contains(w)) || token.ends_with(".len()") {
                continue;
            }
            let before = chars[..start].iter().rev().find(|c| !c.is_whitespace());
            let after = chars[k..].iter().find(|c| !c.is_whitespace());
            let arithmetic = |c: Option<&char>| c.is_some_and(|c| "+-*/".contains(*c));
            let arrow = chars[k..]
                .iter()
                .collect::<String>()
                .trim_start()
                .starts_with("->");
            if arithmetic(before) || (arithmetic(after) && !arrow) {
                hit = true;
            }
        }
        if hit {
            out.push(i + 1);
        }
    }
    out
}

/// The commands do no arithmetic on lux, luminance or time: a summary or a converted value
/// is a library function (`radiosity::session::describe`, `photometry::check_text`, …).
#[test]
fn the_commands_do_no_arithmetic_on_light_or_time() {
    let root = common::root();
    let mut offences = Vec::new();
    for f in rust_files(&root.join("src/cli")) {
        let text = std::fs::read_to_string(&f).unwrap();
        for line in arithmetic_on_light_or_time(&text) {
            let rel = f.strip_prefix(&root).unwrap().display().to_string();
            offences.push(format!("{rel}:{line}"));
        }
    }
    assert!(
        offences.is_empty(),
        "the commands compute with light or time (make it a library function):\n{}",
        offences.join("\n")
    );
}

#[test]
fn planted_arithmetic_on_light_or_time_is_found() {
    let planted = "let ms = t.elapsed().as_secs_f64() * 1e3;\n\
        let total = direct_lux + reflected;\n\
        let half = 0.5 * self.luminance;\n\
        let name = \"room-illuminance\"; // lux - 1\n\
        let n = lux.len() * 12;\n\
        fn lux(x: f64) -> f64 {\n\
        let ms = t.elapsed().as_millis();\n";
    assert_eq!(arithmetic_on_light_or_time(planted), vec![1, 2, 3]);
}
