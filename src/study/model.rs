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
            "the model looks as if its up axis were not {}: more of its area faces the other axis ({:.0} m² against {:.0} m² facing up) and it stands {:.1} m tall on a {:.1} m deep plan; if the file is {}-up, pass `up` {other_flag}",
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

/// A study's model read from its file: +Z up, the casting triangles first.
#[derive(Debug, Clone)]
pub struct StudyModel {
    /// The triangles, in the world frame (metres, +Z up), casters first.
    pub mesh: Mesh,
    /// The triangles that receive shadows but cast none (those after the casters).
    pub non_casters: crate::shadow::IgnoredTriangles,
    /// How many triangles cast shadows.
    pub casting: usize,
    /// What the caller should be told (dropped triangles), without the file's name.
    pub warnings: Vec<String>,
}

/// Reads an OBJ or glTF model, turns it to the world's +Z up and, when `casters` names objects
/// (`o`/`g` names, `*` matches any run of characters), puts their triangles first: the
/// rest receive shadows but cast none. Refused (field `casters`) when a pattern matches no
/// object (the message lists the names) or the objects named have no triangle with area.
pub fn load_components(
    path: &std::path::Path,
    up: UpAxis,
    casters: &[String],
) -> Result<StudyModel, super::ProfileError> {
    use super::ProfileError;
    let (mut mesh, objects) = crate::geometry::read_model_objects(path)?;
    if up == UpAxis::Y {
        for p in &mut mesh.positions {
            *p = glam::DVec3::new(p.x, -p.z, p.y);
        }
    }
    let casts: Vec<bool> = if casters.is_empty() {
        vec![true; objects.names.len()]
    } else {
        for pattern in casters {
            if !objects.names.iter().any(|n| wildcard_match(pattern, n)) {
                let names = objects.names.iter().take(30).cloned().collect::<Vec<_>>();
                let more = if objects.names.len() > 30 {
                    ", …"
                } else {
                    ""
                };
                return Err(ProfileError::invalid(
                    "casters",
                    format!(
                        "{pattern:?} matches no object of {} (its objects: {}{more})",
                        path.display(),
                        names.join(", ")
                    ),
                ));
            }
        }
        objects
            .names
            .iter()
            .map(|n| casters.iter().any(|p| wildcard_match(p, n)))
            .collect()
    };
    let total = mesh.triangles.len();
    // Casters first, then the rest; each part loses its degenerate triangles.
    let part = |cast: bool| {
        let mut m = Mesh {
            positions: mesh.positions.clone(),
            triangles: mesh
                .triangles
                .iter()
                .zip(&objects.of_triangle)
                .filter(|(_, &o)| casts[o as usize] == cast)
                .map(|(t, _)| *t)
                .collect(),
        };
        let dropped = m.remove_degenerate();
        (m, dropped)
    };
    let ((mut model, dropped_casting), (rest, dropped_rest)) = (part(true), part(false));
    let dropped = dropped_casting + dropped_rest;
    let mut warnings = Vec::new();
    if dropped > 0 {
        warnings.push(format!(
            "{dropped} of its {total} triangles have no area and were dropped"
        ));
    }
    let casting = model.triangles.len();
    model.triangles.extend(rest.triangles);
    model.validate(&path.display().to_string())?;
    if !casters.is_empty() && casting == 0 {
        return Err(ProfileError::invalid(
            "casters",
            "names only objects without triangles of any area".into(),
        ));
    }
    let non_casters = if casting < model.triangles.len() {
        crate::shadow::IgnoredTriangles(std::iter::once(casting..model.triangles.len()).collect())
    } else {
        crate::shadow::IgnoredTriangles::default()
    };
    Ok(StudyModel {
        mesh: model,
        non_casters,
        casting,
        warnings,
    })
}

/// Whether `name` matches `pattern`, where `*` stands for any run of characters.
pub fn wildcard_match(pattern: &str, name: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    if parts.len() == 1 {
        return pattern == name;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !name.starts_with(first) || name.len() < first.len() + last.len() || !name.ends_with(last) {
        return false;
    }
    let mut rest = &name[first.len()..name.len() - last.len()];
    for middle in &parts[1..parts.len() - 1] {
        match rest.find(middle) {
            Some(k) => rest = &rest[k + middle.len()..],
            None => return false,
        }
    }
    true
}
