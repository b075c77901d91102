//! The one Wavefront OBJ reader: tobj parses the file, for scenes (materials, normals,
//! texture coordinates) and for geometry alike. goniolight adds what tobj lacks:
//! - the file's own vertex numbering: tobj numbers the vertices of each object anew, so
//!   every `v` line is handed to tobj with its 0-based index in the vertex-colour slot
//!   (exact in f64), and for geometry an extra object lists every vertex as a point, so
//!   results can name OBJ vertices and unused vertices keep their place;
//! - line numbers in errors (tobj stops at the first bad line it reads);
//! - text that is not UTF-8 (Windows-1252, as many exporters write names) is decoded
//!   instead of refused; point elements (`p`) are dropped (they carry no surface).

use std::fmt::Write as _;
use std::io::{BufRead, Read};
use std::path::Path;

use glam::DVec3;

use super::{GeometryError, Mesh};

/// The name of the object that lists every vertex (geometry reading only).
const ALL_VERTICES: &str = "__goniolight_all_vertices__";

/// A parsed OBJ file.
#[derive(Debug)]
pub struct ObjFile {
    /// The objects, as tobj gives them (vertex colours hold file vertex indices).
    pub models: Vec<tobj::Model>,
    /// The materials of its `mtllib` files, or why they could not be read.
    pub materials: Result<Vec<tobj::Material>, MtlError>,
    /// Every vertex of the file in file order (filled for [`read_obj`] only).
    pub positions: Vec<DVec3>,
    /// True when the text was not UTF-8 and was decoded as Windows-1252.
    pub decoded_latin1: bool,
}

/// Why the materials of an OBJ could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MtlError {
    /// The `mtllib` file does not exist (common in exported models).
    Missing,
    /// The file exists but is unusable: the message names it and the line.
    Bad(String),
}

impl std::fmt::Display for MtlError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MtlError::Missing => write!(f, "the MTL file could not be opened"),
            MtlError::Bad(m) => write!(f, "{m}"),
        }
    }
}

impl ObjFile {
    /// The 0-based file index of vertex `local` of `model` (as tobj numbers it).
    pub fn file_index(model: &tobj::Model, local: u32) -> u32 {
        model.mesh.vertex_color[3 * local as usize] as u32
    }
}

/// How to read.
#[derive(Debug, Clone, Copy)]
pub struct ReadOptions {
    /// One index per vertex for positions, normals and texture coordinates together (for
    /// the GPU), or indices into the positions alone (for geometry).
    pub single_index: bool,
    /// Add the object listing every vertex, so `positions` holds all of them.
    pub all_vertices: bool,
}

/// Reads `path` with tobj; `mtllib` files are looked up next to it.
pub fn read(path: &Path, options: ReadOptions) -> Result<ObjFile, GeometryError> {
    let name = path.display().to_string();
    let bytes = read_file(path)?;
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    // tobj keeps only its own error kinds: the first detailed message is kept here.
    let detail = std::cell::RefCell::new(None);
    let mut file = parse(&name, &bytes, options, |mtl| {
        load_mtl(&dir.join(mtl)).map_err(|e| {
            let kind = match e {
                MtlError::Missing => tobj::LoadError::OpenFileFailed,
                MtlError::Bad(_) => tobj::LoadError::MaterialParseError,
            };
            detail.borrow_mut().get_or_insert(e);
            kind
        })
    })?;
    if let (Err(e), Some(d)) = (&mut file.materials, detail.into_inner()) {
        *e = d;
    }
    Ok(file)
}

fn read_file(path: &Path) -> Result<Vec<u8>, GeometryError> {
    crate::io::read_limited(path, crate::io::MAX_MODEL_BYTES).map_err(|source| GeometryError::Io {
        file: path.display().to_string(),
        source,
    })
}

/// What tobj's MTL reader returns on success: the materials and their index by name.
pub type MtlContent = <tobj::MTLLoadResult as IntoIterator>::Item;

/// Reads an MTL file (bounded, devices refused) and parses it with [`parse_mtl`].
fn load_mtl(path: &Path) -> Result<MtlContent, MtlError> {
    let bytes = crate::io::read_limited(path, crate::io::MAX_MODEL_BYTES).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            MtlError::Missing
        } else {
            MtlError::Bad(format!("{}: {e}", path.display()))
        }
    })?;
    parse_mtl(&path.display().to_string(), &bytes)
}

/// Parses MTL bytes into materials; `name` is used in messages. tobj panics on colour
/// lines with fewer than three numbers (`Kd 0.5`): such lines, and non-finite values of
/// the numeric keys, are refused here first, naming the line.
pub fn parse_mtl(name: &str, bytes: &[u8]) -> Result<MtlContent, MtlError> {
    let text = String::from_utf8_lossy(bytes);
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let numeric = matches!(
            key,
            "Ka" | "Kd" | "Ks" | "Ke" | "Kt" | "Tf" | "Ns" | "Ni" | "d" | "Tr"
        );
        if !numeric {
            continue;
        }
        let values: Vec<f32> = words.map_while(|w| w.parse::<f32>().ok()).collect();
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(MtlError::Bad(format!(
                "{name}: line {}: {key} value {v} is not a finite number",
                i + 1
            )));
        }
        let needed = if matches!(key, "Ns" | "Ni" | "d" | "Tr") {
            1
        } else {
            3
        };
        if values.len() < needed {
            return Err(MtlError::Bad(format!(
                "{name}: line {}: {key} needs {needed} number(s), found {}",
                i + 1,
                values.len()
            )));
        }
    }
    tobj::load_mtl_buf(&mut std::io::Cursor::new(bytes))
        .map_err(|e| MtlError::Bad(format!("{name}: {e}")))
}

/// Parses OBJ bytes; `name` is used in messages, `load_mtl` reads `mtllib` files.
pub fn parse(
    name: &str,
    bytes: &[u8],
    options: ReadOptions,
    load_mtl: impl Fn(&Path) -> tobj::MTLLoadResult,
) -> Result<ObjFile, GeometryError> {
    if bytes.starts_with(b"\xFF\xFE")
        || bytes.starts_with(b"\xFE\xFF")
        || bytes[..bytes.len().min(4096)].contains(&0)
    {
        return Err(GeometryError::Parse {
            file: name.to_string(),
            line: 1,
            message: "not OBJ text: the file is UTF-16 or binary (save it as UTF-8 or ASCII)"
                .to_string(),
        });
    }
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let (text, decoded_latin1) = match std::str::from_utf8(bytes) {
        Ok(t) => (std::borrow::Cow::Borrowed(t), false),
        Err(_) => (encoding_rs::WINDOWS_1252.decode(bytes).0, true),
    };
    let (tagged, file_lines, vertex_count) = tag_vertices(&text, options.all_vertices);
    let mut reader = LineCounter {
        inner: std::io::Cursor::new(tagged.as_bytes()),
        lines: 0,
    };
    let load = tobj::LoadOptions {
        triangulate: true,
        single_index: options.single_index,
        ignore_points: !options.all_vertices,
        ignore_lines: true,
    };
    let (models, materials) = tobj::load_obj_buf(&mut reader, &load, load_mtl).map_err(|e| {
        // Past the file's end means tobj was closing the file's last object.
        let at = reader.lines.clamp(1, file_lines.max(1));
        let message = e.to_string();
        if matches!(
            e,
            tobj::LoadError::FaceVertexOutOfBounds
                | tobj::LoadError::FaceTexCoordOutOfBounds
                | tobj::LoadError::FaceNormalOutOfBounds
                | tobj::LoadError::FaceColorOutOfBounds
        ) {
            // tobj checks faces when an object ends: name the object's last line.
            GeometryError::Parse {
                file: name.to_string(),
                line: at,
                message: format!("{message} (in the object that ends here)"),
            }
        } else {
            GeometryError::Parse {
                file: name.to_string(),
                line: at,
                message,
            }
        }
    })?;
    let mut file = ObjFile {
        models,
        materials: materials.map_err(|e| match e {
            tobj::LoadError::OpenFileFailed => MtlError::Missing,
            e => MtlError::Bad(e.to_string()),
        }),
        positions: Vec::new(),
        decoded_latin1,
    };
    if options.all_vertices {
        let k = file
            .models
            .iter()
            .position(|m| m.name == ALL_VERTICES)
            .filter(|_| vertex_count > 0);
        if let Some(k) = k {
            let all = file.models.remove(k);
            file.positions = all
                .mesh
                .positions
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0], p[1], p[2]))
                .collect();
        }
        if file.positions.len() != vertex_count {
            return Err(GeometryError::Invalid(format!(
                "{name}: read {} of its {vertex_count} vertices",
                file.positions.len()
            )));
        }
    }
    Ok(file)
}

/// The OBJ text with each `v` line as `v x y z INDEX 0 0` and `p` lines blanked (line
/// numbers unchanged), plus, with `all_vertices`, an object of one-vertex faces (points)
/// naming every vertex. Returns the text, the file's line count and its vertex count.
fn tag_vertices(text: &str, all_vertices: bool) -> (String, usize, usize) {
    let mut out = String::with_capacity(text.len() + text.len() / 4);
    let mut vertices = 0usize;
    let mut lines = 0usize;
    for line in text.lines() {
        lines += 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                out.push('v');
                for w in words.by_ref().take(3) {
                    out.push(' ');
                    out.push_str(w);
                }
                // A vertex index is exact in f64 far beyond any file's vertex count.
                let _ = writeln!(out, " {vertices} 0 0");
                vertices += 1;
            }
            Some("p") => out.push('\n'),
            _ => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    if all_vertices && vertices > 0 {
        let _ = writeln!(out, "o {ALL_VERTICES}");
        // tobj reads a one-vertex face as a point element.
        for i in 1..=vertices {
            let _ = writeln!(out, "f {i}");
        }
    }
    (out, lines, vertices)
}

/// Counts the lines a reader has handed out (tobj reads line by line).
struct LineCounter<R> {
    inner: R,
    lines: usize,
}

impl<R: BufRead> Read for LineCounter<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.lines += buf[..n].iter().filter(|&&b| b == b'\n').count();
        Ok(n)
    }
}

impl<R: BufRead> BufRead for LineCounter<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amt: usize) {
        if let Ok(buf) = self.inner.fill_buf() {
            let n = amt.min(buf.len());
            self.lines += buf[..n].iter().filter(|&&b| b == b'\n').count();
        }
        self.inner.consume(amt);
    }
}

/// Reads the positions and triangles of an OBJ with the file's own vertex numbering
/// (0-based); polygons are fan-triangulated; the model is taken as is (no up-axis
/// change). Materials are not read.
pub fn read_obj(path: &Path) -> Result<Mesh, GeometryError> {
    let name = path.display().to_string();
    let bytes = read_file(path)?;
    parse_obj(&name, &bytes)
}

/// Parses OBJ bytes into a [`Mesh`] with the file's vertex numbering; `name` is used in
/// messages.
pub fn parse_obj(name: &str, bytes: &[u8]) -> Result<Mesh, GeometryError> {
    parse_obj_objects(name, bytes).map(|(mesh, _)| mesh)
}

/// The objects of an OBJ (`o` and `g` names as tobj splits them): each triangle's object.
#[derive(Debug, Clone, Default)]
pub struct ObjObjects {
    /// The objects' names, in file order (unnamed ones as `unnamed N`).
    pub names: Vec<String>,
    /// Per triangle of the mesh, its index into `names`.
    pub of_triangle: Vec<u32>,
}

/// [`read_obj`] with each triangle's object.
pub fn read_obj_objects(path: &Path) -> Result<(Mesh, ObjObjects), GeometryError> {
    let name = path.display().to_string();
    let bytes = read_file(path)?;
    parse_obj_objects(&name, &bytes)
}

/// [`parse_obj`] with each triangle's object.
pub fn parse_obj_objects(name: &str, bytes: &[u8]) -> Result<(Mesh, ObjObjects), GeometryError> {
    let options = ReadOptions {
        single_index: false,
        all_vertices: true,
    };
    let file = parse(name, bytes, options, |_| Ok(Default::default()))?;
    let mut mesh = Mesh {
        positions: file.positions,
        triangles: Vec::new(),
    };
    let mut objects = ObjObjects::default();
    for m in &file.models {
        let id = objects.names.len() as u32;
        objects.names.push(if m.name.is_empty() {
            format!("unnamed {}", id + 1)
        } else {
            m.name.clone()
        });
        for t in m.mesh.indices.chunks_exact(3) {
            mesh.triangles
                .push([0, 1, 2].map(|k| ObjFile::file_index(m, t[k])));
            objects.of_triangle.push(id);
        }
    }
    Ok((mesh, objects))
}

/// OBJ text of a mesh (`v` and `f` lines, 1-based as OBJ wants).
pub fn to_obj_string(mesh: &Mesh, comment: &str) -> String {
    let mut out = String::new();
    for line in comment.lines() {
        out.push_str(&format!("# {line}\n"));
    }
    for p in &mesh.positions {
        out.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
    }
    for t in &mesh.triangles {
        out.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
    }
    out
}

/// The `mtllib` files an OBJ names (looked up beside it), from its first megabyte where
/// exporters write them; an unreadable file names none.
pub fn material_libraries(obj: &std::path::Path) -> Vec<std::path::PathBuf> {
    use std::io::{BufRead, Read};
    let Ok(file) = std::fs::File::open(obj) else {
        return Vec::new();
    };
    let dir = obj.parent().unwrap_or(std::path::Path::new(""));
    std::io::BufReader::new(file.take(1 << 20))
        .split(b'\n')
        .map_while(Result::ok)
        .filter_map(|line| {
            let line = String::from_utf8_lossy(&line).trim().to_string();
            line.strip_prefix("mtllib")
                .filter(|rest| rest.starts_with(char::is_whitespace))
                .map(|rest| dir.join(rest.trim()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_negative_indices_and_errors() {
        let m = parse_obj(
            "t.obj",
            b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2//2 3 4\nf -4 -3 -1\n",
        )
        .unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 1, 3]]);
        let e = parse_obj("t.obj", b"v 0 0 0\nv 1 0 x\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.obj: line 2"), "{e}");
        let e = parse_obj("t.obj", b"v 0 0 0\nf 1 2 3\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2") && e.contains("out of bounds"), "{e}");
    }

    #[test]
    fn file_numbering_survives_objects_and_unused_vertices() {
        // Object b uses vertices 5..7 first; vertex 4 (1-based) is used by nobody.
        let text = b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 9 9 9\no b\nv 0 0 1\nv 1 0 1\nv 0 1 1\n\
                     f 5 6 7\no a2\nf 1 2 3\np 4\n";
        let m = parse_obj("t.obj", text).unwrap();
        assert_eq!(m.positions.len(), 7);
        assert_eq!(m.positions[3], DVec3::splat(9.0));
        let mut t = m.triangles.clone();
        t.sort();
        assert_eq!(t, vec![[0, 1, 2], [4, 5, 6]]);
    }

    #[test]
    fn windows_1252_names_are_decoded() {
        let mut text = b"o Stra\xdfe\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
        let m = parse_obj("t.obj", &text).unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        text.extend_from_slice(b"f 1 2\n");
        let file = parse(
            "t.obj",
            &text[..text.len() - 6],
            ReadOptions {
                single_index: true,
                all_vertices: false,
            },
            |_| Ok(Default::default()),
        )
        .unwrap();
        assert!(file.decoded_latin1);
        assert_eq!(file.models[0].name, "Straße");
    }
}
