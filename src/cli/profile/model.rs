//! Reading a study's model: its objects, the casters among them, the up axis.

use std::path::Path;

use anyhow::anyhow;

use super::super::CliError;
use crate::geometry::obj::read_obj_objects;
use crate::geometry::Mesh;
use crate::scene::UpAxis;
use crate::shadow::IgnoredTriangles;

/// Reads an OBJ model, turns it to the world's +Z up and, when `casters` names objects
/// (`o`/`g` names, `*` matches any run of characters), puts their triangles first: the
/// rest receive shadows but cast none (returned as the triangles to leave out). Refused
/// when a pattern matches no object (the message lists the names).
pub fn load_components(
    path: &Path,
    up: UpAxis,
    casters: &[String],
) -> Result<(Mesh, IgnoredTriangles), CliError> {
    let (mut mesh, objects) = read_obj_objects(path)?;
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
                let mut names = objects.names.clone();
                names.truncate(30);
                return Err(CliError::input(anyhow!(
                    "--casters: {pattern:?} matches no object of {} (its objects: {}{})",
                    path.display(),
                    names.join(", "),
                    if objects.names.len() > 30 {
                        ", …"
                    } else {
                        ""
                    }
                )));
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
    if dropped > 0 {
        eprintln!(
            "warning: {}: {dropped} of its {total} triangles have no area and were dropped",
            path.display()
        );
    }
    let casting = model.triangles.len();
    model.triangles.extend(rest.triangles);
    model.validate(&path.display().to_string())?;
    if !casters.is_empty() {
        if casting == 0 {
            return Err(CliError::input(anyhow!(
                "--casters: the objects named have no triangles with area"
            )));
        }
        eprintln!(
            "{}: {casting} of {} triangles cast shadows (--casters)",
            path.display(),
            model.triangles.len()
        );
    }
    let non_casters = if casting < model.triangles.len() {
        IgnoredTriangles(std::iter::once(casting..model.triangles.len()).collect())
    } else {
        IgnoredTriangles::default()
    };
    Ok((model, non_casters))
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
