//! The model of a sun study: moved near the origin when its coordinates are far off (a
//! national grid), and checked for a wrong up axis.

use crate::geometry::Mesh;
use crate::scene::UpAxis;

/// Moves `mesh` so its plan centre (rounded to a metre) is at the origin and returns that
/// centre: 32-bit floats on the GPU resolve only centimetres at national-grid coordinates
/// (85 000, 447 000 m), so every study works near the origin and writes the file's own
/// coordinates back.
pub fn recentre(mesh: &mut Mesh) -> glam::DVec2 {
    let Some((lo, hi)) = mesh.bounds() else {
        return glam::DVec2::ZERO;
    };
    let c = ((lo + hi) / 2.0).truncate().round();
    for p in &mut mesh.positions {
        p.x -= c.x;
        p.y -= c.y;
    }
    c
}

/// A warning when the model looks as if its up axis were another than `up` (a heuristic):
/// half as much again of its area faces the other reading's up direction as faces this
/// one's, and it stands at least three quarters as tall as it is deep along the other
/// reading's up (a site read with the wrong axis lies on its side: its terrain and roofs
/// face sideways and its plan depth becomes its height). A lone tower without a ground is
/// ambiguous and may be warned about; a block of towers or a site is not.
pub fn up_axis_warning(mesh: &Mesh, up: UpAxis) -> Option<String> {
    use glam::DVec3;
    // The other reading's up, in this reading's world frame.
    let (other, other_flag) = match up {
        UpAxis::Y => (DVec3::NEG_Y, "z"),
        UpAxis::Z => (DVec3::Y, "y"),
    };
    let (lo, hi) = mesh.bounds()?;
    let size = hi - lo;
    let (mut up_area, mut other_area) = (0.0, 0.0);
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let n = (b - a).cross(c - a);
        let area = n.length() / 2.0;
        let n = n.normalize_or_zero();
        if n.z > 0.9 {
            up_area += area;
        }
        if n.dot(other) > 0.9 {
            other_area += area;
        }
    }
    let other_extent = size.y;
    (other_area > 1.5 * up_area && size.z > 0.75 * other_extent).then(|| {
        format!(
            "the model looks as if its up axis were not {}: more of its area faces the other axis ({:.0} m² against {:.0} m² facing up) and it stands {:.1} m tall on a {:.1} m deep plan; if the file is {}-up, pass --up {other_flag}",
            match up {
                UpAxis::Y => "y",
                UpAxis::Z => "z",
            },
            other_area,
            up_area,
            size.z,
            other_extent,
            other_flag.to_uppercase()
        )
    })
}
