//! Outputs that never destroy inputs, complete or none.
//!
//! - [`OutputCheck`]: before any work, a command lists its inputs and outputs; an output
//!   that is one of the inputs (the same file, through links too), another output of the
//!   same run, or something other than a regular file (a FIFO, a device, a folder) is
//!   refused, naming both.
//! - [`Staging`]: a multi-file output is written into a hidden folder beside its target and
//!   moved into place at the end, each file checked again against the inputs; dropped
//!   without [`Staging::commit`] (an error, an interruption) it leaves nothing.
//! - [`remove_unfinished`]: the temporary files and folders of the writes in progress,
//!   removed by the Ctrl-C handler before the process ends at once.

use std::path::{Component, Path, PathBuf};
use std::sync::Mutex;

/// Why an output path is refused.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum OutputError {
    /// The output is one of the run's inputs.
    #[error("{output}: is the input {input}; writing it would destroy the input (choose another output path)")]
    IsInput {
        /// The output as given.
        output: String,
        /// The input it names.
        input: String,
    },
    /// Two outputs of one run are the same file.
    #[error(
        "{output}: is also {other}, another output of the same run (give each output its own path)"
    )]
    Twice {
        /// The output as given.
        output: String,
        /// The other output.
        other: String,
    },
    /// The output exists and is not a regular file.
    #[error("{output}: is {kind}, not a regular file: goniolight replaces only files it can write whole (use another path, or `-` for standard output where the option takes it)")]
    NotAFile {
        /// The output as given.
        output: String,
        /// What it is: "a FIFO", "a device", "a folder".
        kind: &'static str,
    },
}

/// The kind of a path that exists and is not a regular file (links followed).
fn special_kind(path: &Path) -> Option<&'static str> {
    let meta = std::fs::metadata(path).ok()?;
    let t = meta.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO");
        }
        if t.is_char_device() || t.is_block_device() {
            return Some("a device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    if t.is_dir() {
        return Some("a folder");
    }
    (!t.is_file()).then_some("not a regular file")
}

/// `path` made absolute and normalised without touching the disk for the part that does
/// not exist yet: the longest existing ancestor resolved (links followed), the rest
/// appended with `.` and `..` applied.
pub fn resolved(path: &Path) -> PathBuf {
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir()
            .unwrap_or_else(|_| PathBuf::from("/"))
            .join(path)
    };
    let mut lexical = PathBuf::new();
    for c in absolute.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                lexical.pop();
            }
            c => lexical.push(c),
        }
    }
    let mut rest = Vec::new();
    let mut head = lexical.as_path();
    loop {
        if let Ok(real) = head.canonicalize() {
            let mut out = real;
            out.extend(rest.iter().rev());
            return out;
        }
        match (head.parent(), head.file_name()) {
            (Some(parent), Some(name)) => {
                rest.push(name.to_os_string());
                head = parent;
            }
            _ => return lexical,
        }
    }
}

/// The file's identity on disk (device and inode), where it exists.
#[cfg(unix)]
fn identity(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    std::fs::metadata(path).ok().map(|m| (m.dev(), m.ino()))
}

#[cfg(not(unix))]
fn identity(_path: &Path) -> Option<(u64, u64)> {
    None
}

/// True when `a` and `b` are the same file: the same resolved path, or (hard links) the
/// same device and inode.
pub fn same_file(a: &Path, b: &Path) -> bool {
    if resolved(a) == resolved(b) {
        return true;
    }
    matches!((identity(a), identity(b)), (Some(x), Some(y)) if x == y)
}

/// A run's inputs and outputs, checked together before any work.
#[derive(Debug, Default, Clone)]
pub struct OutputCheck {
    inputs: Vec<PathBuf>,
    /// Each output and how messages name it (`--report out.html`).
    outputs: Vec<(String, PathBuf)>,
}

impl OutputCheck {
    /// An empty check.
    pub fn new() -> OutputCheck {
        OutputCheck::default()
    }

    /// Adds an input file (`-`, standard input, is no file and is left out).
    pub fn input(&mut self, path: impl AsRef<Path>) -> &mut OutputCheck {
        let path = path.as_ref();
        if path != Path::new("-") {
            self.inputs.push(path.to_path_buf());
        }
        self
    }

    /// Adds an output file (`-`, standard output, is no file and is left out).
    pub fn output(&mut self, path: impl AsRef<Path>) -> &mut OutputCheck {
        let path = path.as_ref();
        self.named_output(&path.display().to_string(), path)
    }

    /// Adds an output file that messages name as `name` (the option and its value:
    /// `--report out.html`, `job 2 stdout x.txt`).
    pub fn named_output(&mut self, name: &str, path: impl AsRef<Path>) -> &mut OutputCheck {
        let path = path.as_ref();
        if path != Path::new("-") {
            self.outputs.push((name.to_string(), path.to_path_buf()));
        }
        self
    }

    /// The inputs added so far.
    pub fn inputs(&self) -> &[PathBuf] {
        &self.inputs
    }

    /// The first conflict: an output that is an input, another output, or no regular file.
    pub fn check(&self) -> Result<(), OutputError> {
        for (k, (name, out)) in self.outputs.iter().enumerate() {
            if let Some(kind) = special_kind(out) {
                return Err(OutputError::NotAFile {
                    output: name.clone(),
                    kind,
                });
            }
            if let Some(input) = self.inputs.iter().find(|i| same_file(out, i)) {
                return Err(OutputError::IsInput {
                    output: name.clone(),
                    input: input.display().to_string(),
                });
            }
            if let Some((other, _)) = self.outputs[..k].iter().find(|(_, o)| same_file(out, o)) {
                return Err(OutputError::Twice {
                    output: name.clone(),
                    other: other.clone(),
                });
            }
        }
        Ok(())
    }
}

/// Temporary files and folders of writes in progress (removed on a forced exit).
static UNFINISHED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn register(path: &Path) {
    if let Ok(mut v) = UNFINISHED.lock() {
        v.push(path.to_path_buf());
    }
}

fn unregister(path: &Path) {
    if let Ok(mut v) = UNFINISHED.lock() {
        v.retain(|p| p != path);
    }
}

/// Removes every temporary file and folder of the writes in progress: for a handler that
/// ends the process at once (a second Ctrl-C), so that nothing half-written stays.
pub fn remove_unfinished() {
    let paths = match UNFINISHED.lock() {
        Ok(v) => v.clone(),
        Err(_) => return,
    };
    for p in paths {
        if p.is_dir() {
            let _ = std::fs::remove_dir_all(&p);
        } else {
            let _ = std::fs::remove_file(&p);
        }
    }
}

/// A temporary path `.NAME.tmpPID` beside `path`, registered for [`remove_unfinished`]
/// until [`finished`] is called with it.
pub(crate) fn temporary_beside(path: &Path, what: &str) -> std::io::Result<PathBuf> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file path"))?;
    let tmp = dir.join(format!(
        ".{}.{what}{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    register(&tmp);
    Ok(tmp)
}

/// Ends the registration of a temporary path (renamed into place or removed).
pub(crate) fn finished(tmp: &Path) {
    unregister(tmp);
}

/// A multi-file output written into a hidden folder beside `target` and moved into place
/// by [`Staging::commit`]; dropped without it, it removes what it wrote.
#[derive(Debug)]
pub struct Staging {
    target: PathBuf,
    root: PathBuf,
    inputs: Vec<PathBuf>,
    /// Files staged for places outside the target folder: (staged, target).
    outside: Vec<(PathBuf, PathBuf)>,
    committed: bool,
}

/// The staging sub-folder of files bound outside the target folder.
const OUTSIDE: &str = ".outside";

impl Staging {
    /// A staging folder for the output folder `target` (created at commit if missing);
    /// `inputs` are never replaced by the commit.
    pub fn beside(target: &Path, inputs: &[PathBuf]) -> std::io::Result<Staging> {
        let root = temporary_beside(&resolved(target), "partial")?;
        if let Err(e) = std::fs::create_dir_all(&root) {
            finished(&root);
            return Err(e);
        }
        Ok(Staging {
            target: target.to_path_buf(),
            root,
            inputs: inputs.to_vec(),
            outside: Vec::new(),
            committed: false,
        })
    }

    /// Where to write what goes into the target folder.
    pub fn dir(&self) -> &Path {
        &self.root
    }

    /// `text` (a message naming files written here) with the staging folder named as the
    /// target folder the files move into.
    pub fn as_target(&self, text: &str) -> String {
        text.replace(
            &self.root.display().to_string(),
            &self.target.display().to_string(),
        )
    }

    /// Where to write a file whose place is `target`, outside the target folder (moved
    /// there by the commit with the rest).
    pub fn outside(&mut self, target: &Path) -> std::io::Result<PathBuf> {
        let dir = self.root.join(OUTSIDE);
        std::fs::create_dir_all(&dir)?;
        let staged = dir.join(self.outside.len().to_string());
        self.outside.push((staged.clone(), target.to_path_buf()));
        Ok(staged)
    }

    /// The files written so far, relative to the folder, in order.
    fn files(&self) -> std::io::Result<Vec<PathBuf>> {
        let mut out = Vec::new();
        let mut stack = vec![self.root.clone()];
        while let Some(dir) = stack.pop() {
            for e in std::fs::read_dir(&dir)? {
                let p = e?.path();
                if p == self.root.join(OUTSIDE) {
                    continue;
                }
                if p.is_dir() {
                    stack.push(p);
                } else {
                    out.push(
                        p.strip_prefix(&self.root)
                            .expect("under root")
                            .to_path_buf(),
                    );
                }
            }
        }
        out.sort();
        Ok(out)
    }

    /// Moves every file written into the target folder, after checking that none would
    /// replace an input or something other than a regular file (then nothing is moved).
    /// Returns the files' final paths.
    pub fn commit(mut self) -> Result<Vec<PathBuf>, super::WriteError> {
        use super::WriteError;
        let files = self
            .files()
            .map_err(|e| WriteError::io("reading", &self.root, e))?;
        let mut check = OutputCheck::new();
        for i in &self.inputs {
            check.input(i);
        }
        for f in &files {
            check.output(self.target.join(f));
        }
        let outside: Vec<_> = self.outside.iter().filter(|(s, _)| s.exists()).collect();
        for (_, target) in &outside {
            check.output(target);
        }
        check.check()?;
        super::create_dir(&self.target)?;
        let mut moved = Vec::with_capacity(files.len());
        for f in &files {
            let to = self.target.join(f);
            if let Some(parent) = to.parent() {
                super::create_dir(parent)?;
            }
            std::fs::rename(self.root.join(f), &to)
                .map_err(|e| WriteError::io("moving", &to, e))?;
            moved.push(to);
        }
        for (staged, target) in outside {
            // Another file system: written whole beside the target, then renamed.
            if std::fs::rename(staged, target).is_err() {
                let bytes =
                    std::fs::read(staged).map_err(|e| WriteError::io("reading", staged, e))?;
                super::write_atomic(target, &bytes)?;
            }
            moved.push(target.clone());
        }
        self.committed = true;
        let _ = std::fs::remove_dir_all(&self.root);
        finished(&self.root);
        Ok(moved)
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.root);
            finished(&self.root);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_that_is_an_input_another_output_or_a_fifo_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("scene.toml");
        std::fs::write(&scene, "x").unwrap();
        let via_dots = dir.path().join("sub/../scene.toml");
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        let mut c = OutputCheck::new();
        c.input(&scene).output(&via_dots);
        assert!(matches!(c.check(), Err(OutputError::IsInput { .. })));
        #[cfg(unix)]
        {
            let link = dir.path().join("link.html");
            std::os::unix::fs::symlink(&scene, &link).unwrap();
            let hard = dir.path().join("hard.html");
            std::fs::hard_link(&scene, &hard).unwrap();
            for out in [&link, &hard] {
                let mut c = OutputCheck::new();
                c.input(&scene).output(out);
                assert!(
                    matches!(c.check(), Err(OutputError::IsInput { .. })),
                    "{out:?}"
                );
            }
            let fifo = dir.path().join("fifo");
            assert!(std::process::Command::new("mkfifo")
                .arg(&fifo)
                .status()
                .unwrap()
                .success());
            let mut c = OutputCheck::new();
            c.output(&fifo);
            assert_eq!(
                c.check(),
                Err(OutputError::NotAFile {
                    output: fifo.display().to_string(),
                    kind: "a FIFO"
                })
            );
            let mut c = OutputCheck::new();
            c.output("/dev/null");
            assert!(matches!(
                c.check(),
                Err(OutputError::NotAFile {
                    kind: "a device",
                    ..
                })
            ));
        }
        let mut c = OutputCheck::new();
        c.output(dir.path().join("a.png"))
            .output(dir.path().join("./a.png"));
        assert!(matches!(c.check(), Err(OutputError::Twice { .. })));
        let mut c = OutputCheck::new();
        c.input(&scene)
            .output(dir.path().join("new/a.png"))
            .output("-")
            .input("-");
        assert_eq!(c.check(), Ok(()));
    }

    #[test]
    fn staging_moves_everything_or_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out");
        let mut s = Staging::beside(&target, &[]).unwrap();
        std::fs::create_dir(s.dir().join("d")).unwrap();
        std::fs::write(s.dir().join("a.txt"), "a").unwrap();
        std::fs::write(s.dir().join("d/b.txt"), "b").unwrap();
        let gif = dir.path().join("a.gif");
        std::fs::write(s.outside(&gif).unwrap(), "g").unwrap();
        let moved = s.commit().unwrap();
        assert_eq!(moved.len(), 3);
        assert_eq!(
            std::fs::read_to_string(target.join("d/b.txt")).unwrap(),
            "b"
        );
        assert_eq!(std::fs::read_to_string(&gif).unwrap(), "g");
        std::fs::remove_file(&gif).unwrap();
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "no staging left"
        );

        let s = Staging::beside(&target, &[]).unwrap();
        std::fs::write(s.dir().join("c.txt"), "c").unwrap();
        drop(s);
        assert!(!target.join("c.txt").exists());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "dropped: nothing left"
        );

        // A file that would replace an input: nothing is moved.
        let input = target.join("a.txt");
        let s = Staging::beside(&target, std::slice::from_ref(&input)).unwrap();
        std::fs::write(s.dir().join("new.txt"), "n").unwrap();
        std::fs::write(s.dir().join("a.txt"), "x").unwrap();
        assert!(s.commit().is_err());
        assert_eq!(std::fs::read_to_string(&input).unwrap(), "a");
        assert!(!target.join("new.txt").exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_forced_exit_removes_the_writes_in_progress() {
        let dir = tempfile::tempdir().unwrap();
        let s = Staging::beside(&dir.path().join("out"), &[]).unwrap();
        std::fs::write(s.dir().join("half.csv"), "1,2").unwrap();
        let tmp = temporary_beside(&dir.path().join("x.png"), "tmp").unwrap();
        std::fs::write(&tmp, "partial").unwrap();
        remove_unfinished();
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        finished(&tmp);
        drop(s);
    }
}
