//! The files an `ldt` command works on — files as named, directories walked for `.ldt` and
//! `.ies` files and TM-33 / ATLA `.xml` / `.json` documents (sorted by path) — and the bookkeeping of a catalogue run: a failed file is
//! reported on standard error and the others go on; the command exits 2 at the end.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use anyhow::anyhow;

use super::CliError;

/// The luminaire files named on the command line.
pub(super) struct Inputs {
    /// Every file to work on, in command-line order (each directory's files sorted).
    pub files: Vec<PathBuf>,
    /// True when the command line named exactly one file (not a directory): the command
    /// keeps its single-file output (and its error is the command's error).
    pub single: bool,
    failures: Failures,
}

impl Inputs {
    /// Expands `named` (files and directories). A directory without luminaire files, or
    /// one that cannot be read, is reported and counted as a failure.
    pub fn expand(named: &[PathBuf]) -> Inputs {
        let mut files = Vec::new();
        let mut failures = Failures::default();
        for path in named {
            if !path.is_dir() {
                files.push(path.clone());
                continue;
            }
            match walk(path) {
                Ok(found) if found.is_empty() => failures.report(CliError::input(anyhow!(
                    "{}: no .ldt, .ies or TM-33 file in this directory",
                    path.display()
                ))),
                Ok(found) => files.extend(found),
                Err(e) => failures.report(e),
            }
        }
        failures.total = files.len() + failures.count;
        Inputs {
            single: named.len() == 1 && files.len() == 1 && !named[0].is_dir(),
            files,
            failures,
        }
    }

    /// Reports a file's failure on standard error; the run goes on.
    pub fn fail(&mut self, error: CliError) {
        self.failures.report(error);
    }

    /// Runs `job` on every file, reporting failures and keeping the results of the others.
    /// For a single named file its failure is the command's error, returned as it is.
    pub fn each<T>(
        &mut self,
        mut job: impl FnMut(&Path) -> Result<T, CliError>,
    ) -> Result<Vec<(PathBuf, T)>, CliError> {
        let mut done = Vec::new();
        for file in self.files.clone() {
            match job(&file) {
                Ok(v) => done.push((file, v)),
                Err(e) if self.single => return Err(e),
                Err(e) => self.fail(e),
            }
        }
        Ok(done)
    }

    /// The messages of the failures so far.
    pub fn errors(&self) -> &[String] {
        &self.failures.messages
    }

    /// The command's result: an error (exit 2) naming how many files failed, if any did.
    pub fn finish(self) -> Result<(), CliError> {
        let Failures { count, total, .. } = self.failures;
        if count == 0 {
            return Ok(());
        }
        Err(CliError::input(anyhow!(
            "{count} of {total} luminaire files failed (each is named above); the others' results were written"
        )))
    }
}

#[derive(Default)]
struct Failures {
    count: usize,
    total: usize,
    messages: Vec<String>,
}

impl Failures {
    fn report(&mut self, error: CliError) {
        let message = error.message();
        eprintln!("error: {message}");
        self.messages.push(message);
        self.count += 1;
    }
}

/// The `.ldt` and `.ies` files under `dir` (any depth, any letter case), and the `.xml` and
/// `.json` files among them that are TM-33 or ATLA documents, sorted.
fn walk(dir: &Path) -> Result<Vec<PathBuf>, CliError> {
    let mut found = Vec::new();
    for entry in walkdir::WalkDir::new(dir).sort_by_file_name() {
        let entry = entry.map_err(|e| CliError::input(anyhow!("{}: {e}", dir.display())))?;
        if entry.file_type().is_file()
            && (is_luminaire(entry.path()) || is_tm33_document(entry.path()))
        {
            found.push(entry.into_path());
        }
    }
    Ok(found)
}

/// True for a `.ldt` or `.ies` name (any letter case).
pub(super) fn is_luminaire(path: &Path) -> bool {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .is_some_and(|e| e == "ldt" || e == "ies")
}

/// True for a `.xml` or `.json` file whose beginning names a TM-33 or ATLA document.
fn is_tm33_document(path: &Path) -> bool {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if !matches!(ext.as_deref(), Some("xml" | "json")) {
        return false;
    }
    let mut head = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| std::io::Read::read_to_end(&mut std::io::Read::take(f, 4096), &mut head))
        .is_ok_and(|_| crate::photometry::tm33::names_itself(&head))
}

/// Output names in one folder for many inputs: `stem.ext`, refusing a second input whose
/// output would overwrite the first's (two `a.ldt` in different folders).
#[derive(Default)]
pub(super) struct OutputNames {
    taken: HashMap<PathBuf, PathBuf>,
}

impl OutputNames {
    /// The output for `input` in `dir` (or next to the input without one), with `ext`.
    pub fn claim(
        &mut self,
        input: &Path,
        dir: Option<&Path>,
        ext: &str,
    ) -> Result<PathBuf, CliError> {
        let stem = input.file_stem().unwrap_or_default().to_string_lossy();
        let folder = dir.map_or_else(
            || input.parent().unwrap_or(Path::new("")).to_path_buf(),
            Path::to_path_buf,
        );
        let out = folder.join(format!("{stem}.{ext}"));
        if let Some(first) = self.taken.get(&out) {
            return Err(CliError::input(anyhow!(
                "{}: its output {} would overwrite the one written for {}; give it a run of its own with --out",
                input.display(),
                out.display(),
                first.display()
            )));
        }
        self.taken.insert(out.clone(), input.to_path_buf());
        Ok(out)
    }
}
