//! Indexed triangle meshes, OBJ geometry, vertex welding and edge adjacency.

pub mod adjacency;
pub mod areas;
pub mod generate;
pub mod gltf_file;
pub mod howell;
pub mod obj;
pub mod polygon;
pub mod simplify;
pub mod split;
pub mod weld;

use glam::DVec3;

pub use adjacency::{Adjacency, EdgeKind};

/// Problems with geometry input.
#[derive(Debug, thiserror::Error)]
pub enum GeometryError {
    /// The file could not be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A malformed line.
    #[error("{file}: line {line}: {message}")]
    Parse {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// Geometry that cannot be used (empty, all degenerate, non-finite).
    #[error("{0}")]
    Invalid(String),
}

/// Whether a triangle has an area: its cross product is finite and not negligible
/// against its edges (|n|² > 10⁻²⁴ · L⁴, L the longer of two edges), the one test every
/// reader and command uses to drop zero-area triangles.
pub fn has_area([p, q, r]: [glam::DVec3; 3]) -> bool {
    let n = (q - p).cross(r - p);
    let scale = (q - p).length_squared().max((r - p).length_squared());
    n.is_finite() && n.length_squared() > 1e-24 * scale * scale
}

/// The unit vector along `v`, or `None` when `v` has no direction (zero, or a component
/// that is not finite). Scaled by its largest component first, so vectors whose length
/// overflows (`[1e200, 3e199, 0]`) or underflows still give their direction.
pub fn unit(v: DVec3) -> Option<DVec3> {
    let scale = v.abs().max_element();
    if !(v.is_finite() && scale > 0.0) {
        return None;
    }
    Some((v / scale).normalize())
}

/// Reads a model file's triangles with each triangle's object: an OBJ ([`obj`]'s `o`/`g`
/// names, the file's vertex numbering) or a glTF ([`gltf_file`]'s node names, every node
/// transform applied, in the file's +Y-up frame).
pub fn read_model_objects(
    path: &std::path::Path,
) -> Result<(Mesh, obj::ObjObjects), GeometryError> {
    if gltf_file::is_gltf(path) {
        Ok(gltf_file::read(path)?.mesh_with_nodes())
    } else {
        obj::read_obj_objects(path)
    }
}

/// A triangle mesh: positions and counter-clockwise triangles (outward normals).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// Axis-aligned bounds of the positions used by triangles (`None` if there are none).
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut it = self
            .triangles
            .iter()
            .flatten()
            .map(|&i| self.positions[i as usize]);
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// The unnormalised normal (twice the area) of triangle `t`.
    pub fn face_normal(&self, t: usize) -> DVec3 {
        let [a, b, c] = self.triangles[t].map(|i| self.positions[i as usize]);
        (b - a).cross(c - a)
    }

    /// Drops triangles with repeated vertices or zero area; returns how many were dropped.
    pub fn remove_degenerate(&mut self) -> usize {
        let before = self.triangles.len();
        let pos = &self.positions;
        self.triangles.retain(|t| {
            let [a, b, c] = *t;
            if a == b || b == c || a == c {
                return false;
            }
            has_area(t.map(|i| pos[i as usize]))
        });
        before - self.triangles.len()
    }

    /// Checks the mesh is usable: some triangles, finite positions, valid indices.
    pub fn validate(&self, name: &str) -> Result<(), GeometryError> {
        if self.triangles.is_empty() {
            return Err(GeometryError::Invalid(format!(
                "{name}: the mesh has no triangles with an area ({} vertices; faces of zero area are dropped)",
                self.positions.len()
            )));
        }
        if let Some(i) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(GeometryError::Invalid(format!(
                "{name}: vertex {i} is not finite"
            )));
        }
        let n = self.positions.len() as u32;
        if self.triangles.iter().flatten().any(|&i| i >= n) {
            return Err(GeometryError::Invalid(format!(
                "{name}: vertex index out of range"
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_gives_the_direction_of_huge_and_tiny_vectors() {
        let small = unit(DVec3::new(1.0, 0.3, 0.0)).unwrap();
        for v in [
            DVec3::new(1e200, 3e199, 0.0),
            DVec3::new(1e-300, 3e-301, 0.0),
        ] {
            let u = unit(v).unwrap();
            assert!((u - small).length() < 1e-12, "{v} → {u}");
        }
        assert!((small.length() - 1.0).abs() < 1e-12);
        assert_eq!(unit(DVec3::ZERO), None);
        assert_eq!(unit(DVec3::new(f64::NAN, 0.0, 1.0)), None);
        assert_eq!(unit(DVec3::new(f64::INFINITY, 0.0, 1.0)), None);
    }
}
