//! Shadow-volume geometry: silhouette quads extruded to infinity (w = 0), front and back
//! caps for point lights (front cap only for lights at infinity, whose extrusions meet in
//! one point), consistent outward winding; and the infinite projection.

use glam::{DMat4, DVec4};

use super::silhouette::{Silhouette, SilhouetteMesh};
use super::Light;

/// A shadow volume in homogeneous coordinates, counter-clockwise seen from outside.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowVolume {
    /// Mesh vertices (w = 1) followed by their extrusions to infinity (w = 0).
    pub vertices: Vec<DVec4>,
    /// Triangles.
    pub triangles: Vec<[u32; 3]>,
}

impl ShadowVolume {
    /// Builds the volume of `mesh`'s lit faces for `light`, from `silhouette` (computed
    /// for the same light by either method).
    pub fn build(mesh: &SilhouetteMesh, light: &Light, silhouette: &Silhouette) -> ShadowVolume {
        let m = mesh.mesh();
        let l = light.0;
        let mut vertices: Vec<DVec4> = m.positions.iter().map(|p| p.extend(1.0)).collect();
        let directional = light.is_directional();
        if directional {
            // Every extrusion of a light at infinity is the same point: away from it.
            vertices.push((-l.truncate()).extend(0.0));
        } else {
            vertices.extend(m.positions.iter().map(|p| (*p - l.truncate()).extend(0.0)));
        }
        ShadowVolume {
            vertices,
            triangles: volume_triangles(mesh, light, silhouette, directional),
        }
    }

    /// Whether every directed edge is matched by its reverse exactly once: the volume is
    /// closed and consistently wound.
    pub fn is_closed(&self) -> bool {
        let mut directed: Vec<(u32, u32)> = self
            .triangles
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .collect();
        let mut reversed: Vec<(u32, u32)> = directed.iter().map(|&(a, b)| (b, a)).collect();
        directed.sort_unstable();
        reversed.sort_unstable();
        directed == reversed
    }
}

/// The triangles of the shadow volume of `mesh`'s lit faces for `light`: the lit faces
/// (front cap; an open surface's faces turned from the light reversed,
/// [`SilhouetteMesh::cap_faces`]), their extrusions (back cap, point lights only) and a
/// side for every silhouette edge. Vertex `v < n` is mesh vertex `v`; its extrusion to infinity is
/// `n + v`, or `n` for every vertex when `shared_apex` (a light at infinity, whose
/// extrusions are one point). The GPU keeps `n + v` for both and extrudes in the vertex
/// shader, where the extrusions of a light at infinity coincide by themselves.
pub fn volume_triangles(
    mesh: &SilhouetteMesh,
    light: &Light,
    silhouette: &Silhouette,
    shared_apex: bool,
) -> Vec<[u32; 3]> {
    let m = mesh.mesh();
    let n = m.positions.len() as u32;
    let directional = light.is_directional();
    let far = |v: u32| if shared_apex { n } else { n + v };
    let mut triangles = Vec::new();
    for t in mesh.cap_faces(light) {
        triangles.push(t);
        if !directional {
            let [a, b, c] = t;
            triangles.push([far(a), far(c), far(b)]);
        }
    }
    for &[u, v] in &silhouette.edges {
        // The lit face runs u→v; the side runs v→u, then out to infinity.
        triangles.push([v, u, far(u)]);
        // For a light at infinity this half is degenerate (both ends are one point) unless
        // the GPU extrudes by a finite length, which needs it.
        if !shared_apex {
            triangles.push([v, far(u), far(v)]);
        }
    }
    triangles
}

/// Perspective projection with the far plane at infinity, for depth in [0, 1] (wgpu),
/// right-handed: the limit of the usual matrix as far → ∞ (the depth-[0, 1] form of
/// Wallner Eq. 1.3). Points at infinity (w = 0) in front of the camera land at depth 1.
///
/// ```text
/// | f/aspect  0   0   0  |
/// |    0      f   0   0  |      f = 1 / tan(fov_y / 2)
/// |    0      0  -1  -near |
/// |    0      0  -1   0  |
/// ```
pub fn infinite_perspective(fov_y_rad: f64, aspect: f64, near: f64) -> DMat4 {
    DMat4::perspective_infinite_rh(fov_y_rad, aspect, near)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn infinite_projection_maps_near_to_0_and_infinity_to_1() {
        let p = infinite_perspective(60f64.to_radians(), 16.0 / 9.0, 0.1);
        let near = p * DVec4::new(0.0, 0.0, -0.1, 1.0);
        assert!((near.z / near.w).abs() < 1e-12);
        let inf = p * DVec3::new(0.3, -0.2, -1.0).normalize().extend(0.0);
        assert!((inf.z / inf.w - 1.0).abs() < 1e-12);
        let mid = p * DVec4::new(0.0, 0.0, -1000.0, 1.0);
        assert!(mid.z / mid.w < 1.0 && mid.z / mid.w > 0.99);
    }
}
