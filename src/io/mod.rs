//! Small file helpers shared by the commands: atomic writes, the bundled data's folder and
//! the scene bundled in the binary.

pub mod bundled;
pub mod exact;
pub mod limits;
pub mod outputs;
mod write;

pub use write::{create_dir, write_atomic, WriteError};

use std::path::Path;

/// Text made safe inside HTML and SVG (elements and quoted attributes).
pub fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Text safe to print on a terminal: control characters (newlines, BEL, the ESC of
/// colour codes) shown escaped as `\n`, `\u{7}`, `\u{1b}` instead of acting.
pub fn printable(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// Words of `s` in lines of at most `width` characters (a longer word stands alone).
pub fn wrap_words(s: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in s.split_whitespace() {
        let last = lines.last_mut().expect("one line at least");
        if !last.is_empty() && last.chars().count() + 1 + word.chars().count() > width {
            lines.push(word.to_string());
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(word);
        }
    }
    lines
}

/// The folder holding the bundled data (`assets/`, `luminaires/`): `$GONIOLIGHT_DATA_DIR`
/// when set (packagers, tests), else the source checkout the binary was built from when it
/// is still there, else the working directory.
pub fn data_root() -> std::path::PathBuf {
    if let Some(dir) = std::env::var_os("GONIOLIGHT_DATA_DIR").filter(|d| !d.is_empty()) {
        return dir.into();
    }
    let built = Path::new(env!("CARGO_MANIFEST_DIR"));
    if built.join("assets").is_dir() && built.join("luminaires").is_dir() {
        built.to_path_buf()
    } else {
        std::path::PathBuf::from(".")
    }
}

/// True when a failed read is the input's fault (a missing, unreadable or unusable file,
/// a directory or a device given as a file), not the machine's.
pub fn is_bad_input(e: &std::io::Error) -> bool {
    matches!(
        e.kind(),
        std::io::ErrorKind::NotFound
            | std::io::ErrorKind::InvalidData
            | std::io::ErrorKind::IsADirectory
            | std::io::ErrorKind::PermissionDenied
    )
}

/// Largest luminaire file read: the biggest real ones are a few hundred kB; a 0.1°
/// grid over the whole sphere (the most `MAX_ANGLES` allows) is about 60 MB of text.
pub const MAX_LUMINAIRE_BYTES: u64 = 64 << 20;
/// Largest OBJ, MTL or scene file read (a 10-million-triangle OBJ is about 700 MB).
pub const MAX_MODEL_BYTES: u64 = 1 << 30;

/// Reads `path` whole, refusing devices (`/dev/zero` never ends) and anything longer
/// than `limit` bytes before it fills memory. Errors are `std::io::Error`s whose kind is
/// `InvalidData` for both refusals.
pub fn read_limited(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let invalid = |msg: String| std::io::Error::new(std::io::ErrorKind::InvalidData, msg);
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_char_device() || t.is_block_device() || t.is_socket() {
            return Err(invalid("a device, not a file".to_string()));
        }
    }
    if meta.is_dir() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::IsADirectory,
            "a directory, not a file",
        ));
    }
    if meta.len() > limit {
        return Err(invalid(format!(
            "{} bytes, more than the {limit} bytes goniolight reads from such a file",
            meta.len()
        )));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(invalid(format!(
            "longer than the {limit} bytes goniolight reads from such a file"
        )));
    }
    Ok(bytes)
}

/// Largest small text input read (a points file, GeoJSON areas, a jobs file).
pub const MAX_TEXT_BYTES: u64 = 64 << 20;

/// [`read_limited`] as UTF-8 text (invalid UTF-8 is `InvalidData`).
pub fn read_text_limited(path: &Path, limit: u64) -> std::io::Result<String> {
    String::from_utf8(read_limited(path, limit)?).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text: {e}"),
        )
    })
}

/// The process's peak resident memory, MB (Linux: `VmHWM` in `/proc/self/status`; `None`
/// elsewhere or when it cannot be read).
pub fn peak_memory_mb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024)
}

/// goniolight's folder of one XDG kind: `$own` when set, else `$xdg/goniolight`, else
/// `~/home_sub/goniolight` (`None` without any of these variables).
pub fn xdg_dir(own: &str, xdg: &str, home_sub: &str) -> Option<std::path::PathBuf> {
    let env = |k: &str| {
        std::env::var_os(k)
            .filter(|v| !v.is_empty())
            .map(std::path::PathBuf::from)
    };
    env(own)
        .or_else(|| env(xdg).map(|d| d.join("goniolight")))
        .or_else(|| env("HOME").map(|h| h.join(home_sub).join("goniolight")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_and_leaves_no_temp() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.txt");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"two");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        assert!(write_atomic(&dir.path().join("missing/x.txt"), b"x").is_err());
    }
}
