//! Wavefront OBJ geometry (`v` and `f` lines) with the file's own vertex numbering, so
//! results can name OBJ vertices (0-based). Materials and texture coordinates are the
//! scene loader's business.

use std::path::Path;

use glam::DVec3;

use super::{GeometryError, Mesh};

/// Reads positions and faces; polygons are fan-triangulated; the model is taken as is
/// (no up-axis change).
pub fn read_obj(path: &Path) -> Result<Mesh, GeometryError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| GeometryError::Io {
        file: name.clone(),
        source,
    })?;
    parse_obj(&name, &String::from_utf8_lossy(&bytes))
}

/// Parses OBJ text; `name` is used in messages.
pub fn parse_obj(name: &str, text: &str) -> Result<Mesh, GeometryError> {
    let err = |line: usize, message: String| GeometryError::Parse {
        file: name.to_string(),
        line,
        message,
    };
    let mut mesh = Mesh::default();
    let mut faces: Vec<(usize, Vec<i64>)> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let mut parts = raw.split_whitespace();
        match parts.next() {
            Some("v") => {
                let mut c = [0.0; 3];
                for (k, slot) in c.iter_mut().enumerate() {
                    let tok = parts.next().ok_or_else(|| {
                        err(line, format!("vertex needs 3 coordinates, found {k}"))
                    })?;
                    *slot = tok
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| err(line, format!("bad vertex coordinate {tok:?}")))?;
                }
                mesh.positions.push(DVec3::from_array(c));
            }
            Some("f") => {
                let idx = parts
                    .map(|tok| {
                        tok.split('/')
                            .next()
                            .and_then(|s| s.parse::<i64>().ok())
                            .filter(|&v| v != 0)
                            .ok_or_else(|| err(line, format!("bad face index {tok:?}")))
                    })
                    .collect::<Result<Vec<i64>, _>>()?;
                if idx.len() < 3 {
                    return Err(err(
                        line,
                        format!("a face needs 3 vertices, found {}", idx.len()),
                    ));
                }
                faces.push((line, idx));
            }
            _ => {}
        }
    }
    let n = mesh.positions.len() as i64;
    for (line, idx) in faces {
        // Negative indices count back from the vertices defined so far; we resolve them
        // against all vertices, which equals that for files that define before use.
        let resolve = |v: i64| -> Result<u32, GeometryError> {
            let k = if v > 0 { v - 1 } else { n + v };
            if (0..n).contains(&k) {
                Ok(k as u32)
            } else {
                Err(err(
                    line,
                    format!("face index {v} outside the {n} vertices"),
                ))
            }
        };
        let vs = idx
            .into_iter()
            .map(resolve)
            .collect::<Result<Vec<u32>, _>>()?;
        for k in 1..vs.len() - 1 {
            mesh.triangles.push([vs[0], vs[k], vs[k + 1]]);
        }
    }
    Ok(mesh)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_negative_indices_and_errors() {
        let m = parse_obj(
            "t.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2//2 3 4\nf -4 -3 -1\n",
        )
        .unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 1, 3]]);
        let e = parse_obj("t.obj", "v 0 0 0\nv 1 0 x\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.obj: line 2"), "{e}");
        let e = parse_obj("t.obj", "v 0 0 0\nf 1 2 3\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2") && e.contains("outside"), "{e}");
        let e = parse_obj("t.obj", "v 0 0 0\nf 1 1\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("needs 3"), "{e}");
    }
}
