//! Mirrors and clear glass on the GPU ([`crate::radiosity::specular`]; Wallner §4.3.2):
//! every drawn cell's reflection tree becomes virtual cells, drawn and received in the
//! same batch as the cell.
//!
//! A virtual cell is the cell imaged through its path's windows (centroid, polygon and
//! normal; a fresh frame around the imaged normal), with its own visibility map drawn
//! from the image with the last window's plane as clip plane: what lies behind the mirror
//! or pane is not seen through it. A receiver takes its light when its own map sees it,
//! the straight line from the image meets the window inside its outline, and the cell it
//! images (its parent: the real cell or a shallower virtual one) sees that point in its
//! map — the first leg, checked in the real cell's map (`through_windows` in
//! `shaders/radiosity.wgsl`). Its power is the cell's times the path's coefficients.

use glam::{DVec3, DVec4};

use crate::radiosity::shooters::PlannedPatch;
use crate::radiosity::specular::{Passage, SpecularSurfaces};

/// One virtual cell of a drawn cell.
#[derive(Debug, Clone)]
pub struct VirtualCell {
    /// The cell imaged through the path's windows (a top cell of its own).
    pub planned: PlannedPatch,
    /// The product of the windows' coefficients.
    pub tint: DVec3,
    /// The last window's plane, oriented to where the light goes (`xyz · p + w > 0`).
    pub plane: DVec4,
    /// The last window (an index into [`SpecularSurfaces::windows`]).
    pub window: usize,
    /// The cell it images: 0 the real cell, `j` its `j − 1`-th virtual cell.
    pub parent: usize,
}

/// The virtual cells of `cell` (parents before children).
pub fn virtual_cells(specular: &SpecularSurfaces, cell: &PlannedPatch) -> Vec<VirtualCell> {
    let mut images = specular.images(&cell.polygon, cell.centroid, cell.normal);
    images.sort_by_key(|(path, _, _)| path.windows.len());
    let index_of = |windows: &[usize]| images.iter().position(|(p, _, _)| p.windows == windows);
    images
        .iter()
        .map(|(path, polygon, normal)| {
            let depth = path.windows.len();
            let parent = match depth {
                1 => 0,
                _ => index_of(&path.windows[..depth - 1]).map_or(0, |k| k + 1),
            };
            let last = path.windows[depth - 1];
            let w = &specular.windows[last];
            // The side the light leaves to: a mirror's front; beyond glass, away from the
            // image that shines through it.
            let side = match w.passage {
                Passage::Reflect => 1.0,
                Passage::Transmit => -w.distance(path.virtual_source()).signum(),
            };
            let mut planned = cell.clone();
            planned.polygon.clone_from(polygon);
            planned.centroid = path.virtual_source();
            planned.normal = normal.normalize();
            planned.parent = u32::MAX;
            planned.pieces = [0, 0];
            VirtualCell {
                planned,
                tint: path.weight,
                plane: (w.normal * side).extend(-w.offset * side),
                window: last,
                parent,
            }
        })
        .collect()
}

/// The windows' triangles for the GPU (three corners each) and each window's (first
/// triangle, count).
pub fn window_corners(specular: &SpecularSurfaces) -> (Vec<[f32; 4]>, Vec<[u32; 2]>) {
    let mut corners = Vec::new();
    let mut ranges = Vec::new();
    for w in &specular.windows {
        ranges.push([(corners.len() / 3) as u32, w.corners.len() as u32]);
        for t in &w.corners {
            corners.extend(t.map(|c| c.as_vec3().extend(1.0).to_array()));
        }
    }
    if corners.is_empty() {
        corners = vec![[0.0; 4]; 3];
    }
    (corners, ranges)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Mesh;
    use crate::scene::Material;
    use glam::Vec3;

    #[test]
    fn a_cell_facing_two_mirrors_gets_their_images_and_the_image_of_an_image() {
        // A mirror floor (z = 0, facing up) and a mirror wall (x = 1, facing −x).
        let mut mesh = Mesh::default();
        let quads = [
            [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            [
                [1.0, 0.0, 0.0],
                [1.0, 0.0, 1.0],
                [1.0, 1.0, 1.0],
                [1.0, 1.0, 0.0],
            ],
        ];
        for q in quads {
            let base = mesh.positions.len() as u32;
            mesh.positions.extend(q.map(DVec3::from_array));
            mesh.triangles.push([base, base + 1, base + 2]);
            mesh.triangles.push([base, base + 2, base + 3]);
        }
        let mirror = Material {
            specular_reflectance: Vec3::splat(0.5),
            diffuse: Vec3::ZERO,
            ..Material::default()
        };
        let s = SpecularSurfaces::new(&mesh, &[1; 4], &[Material::default(), mirror]);
        assert_eq!(s.windows.len(), 2);
        // A cell on the wall x = 0, facing +x, at (0, 0.5, 0.5).
        let cell = PlannedPatch {
            first: 0,
            count: 1,
            polygon: vec![
                DVec3::new(0.0, 0.4, 0.4),
                DVec3::new(0.0, 0.6, 0.4),
                DVec3::new(0.0, 0.6, 0.6),
                DVec3::new(0.0, 0.4, 0.6),
            ],
            centroid: DVec3::new(0.0, 0.5, 0.5),
            normal: DVec3::X,
            area: 0.04,
            element_area: 0.04,
            level: 0,
            parent: u32::MAX,
            radius: 0.15,
            pieces: [3, 4],
            merged: false,
        };
        let cells = virtual_cells(&s, &cell);
        // Floor, wall, floor then wall, wall then floor (a corner reflector).
        assert_eq!(cells.len(), 4);
        let first: Vec<_> = cells.iter().filter(|c| c.parent == 0).collect();
        assert_eq!(first.len(), 2);
        for c in &cells {
            assert_eq!(c.planned.pieces, [0, 0], "every element receives an image");
            if c.parent > 0 {
                // An image of an image: parent listed before it, the weight squared.
                assert!(c.parent - 1 < cells.iter().position(|x| std::ptr::eq(x, c)).unwrap());
                assert!((c.tint.x - 0.25).abs() < 1e-6);
                // Both mirrors: (0, 0.5, 0.5) → (2, 0.5, −0.5), facing −x.
                assert!((c.planned.centroid - DVec3::new(2.0, 0.5, -0.5)).length() < 1e-9);
                assert!((c.planned.normal + DVec3::X).length() < 1e-9);
            }
        }
        // The wall's image faces −x behind it; its plane keeps the room side (x < 1).
        let wall = cells
            .iter()
            .find(|c| c.parent == 0 && c.window == 1)
            .unwrap();
        assert!((wall.planned.centroid - DVec3::new(2.0, 0.5, 0.5)).length() < 1e-9);
        let keeps = |p: DVec3| wall.plane.truncate().dot(p) + wall.plane.w > 0.0;
        assert!(keeps(DVec3::new(0.5, 0.5, 0.5)) && !keeps(DVec3::new(1.5, 0.5, 0.5)));
        let (corners, ranges) = window_corners(&s);
        assert_eq!((corners.len(), ranges), (12, vec![[0, 2], [2, 2]]));
    }
}
