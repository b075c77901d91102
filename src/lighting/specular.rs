//! Mirrors and clear glass (Wallner §4.3.2–4.3.3; Rushmeier and Torrance 1990; Sillion
//! and Puech 1989): specular transfer by virtual shooters.
//!
//! A planar mirror is a window onto a mirrored world: light a shooter at `p` sends onto
//! the mirror and on to a receiver `x` travels as far as from `p`'s mirror image `p′`
//! straight to `x`, through the mirror's outline, attenuated by its reflectance ρ_s. So
//! the receiver takes the form factor of the shooter's mirror image times ρ_s, when the
//! straight line from `p′` to `x` crosses the mirror at a point `m` inside its outline
//! (the window test), nothing blocks `m`→`x` (the second leg) and nothing blocks `p`→`m`
//! (the first leg, which a GPU checks in the real shooter's map). Clear glass is the same
//! window without the mirroring: the shooter stays where it is and τ_s attenuates
//! (refraction neglected, as for a thin pane). Paths through several windows (a mirror
//! seen in a mirror, a mirror behind glass) form the reflection tree: a window's image
//! shoots again through every window beyond it, to a depth limit and while the product
//! of the coefficients is worth it.
//!
//! The coefficients are constant (no Fresnel term), as Wallner's. A specular surface's
//! diffuse part, if any, is handled as any other surface's; the mirror or pane itself
//! blocks every straight path (it is opaque except through its windows).
//!
//! Windows group a material's specular triangles by plane (Wallner: one virtual shooter
//! per mirror plane). A reflecting window reflects on the side its triangles face, or on
//! both sides when the material also transmits (a pane of glass reflects on both sides).

use glam::DVec3;

use super::SurfacePoint;
use crate::geometry::Mesh;
use crate::photometry::Interp;
use crate::scene::{Material, PlacedLuminaire, Scene};
use crate::shadow::{IgnoredTriangles, TriangleBvh};

/// Paths through more windows than this are not followed.
pub const DEFAULT_DEPTH: u32 = 4;
/// Paths whose coefficients multiply to less than this (in every channel) are not followed.
pub const DEFAULT_MIN_WEIGHT: f64 = 1e-3;

/// How a window passes light on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Passage {
    /// A mirror: light leaves on the side it arrived from, mirrored.
    Reflect,
    /// Clear glass: light goes on undeviated to the other side.
    Transmit,
}

/// One material's specular triangles in one plane, passing light one way: a node kind
/// of the reflection tree.
#[derive(Debug, Clone)]
pub struct SpecularWindow {
    /// Reflection or transmission.
    pub passage: Passage,
    /// The plane's unit normal; a reflecting window reflects what arrives on this side.
    pub normal: DVec3,
    /// The plane: `normal · x = offset`.
    pub offset: f64,
    /// Its triangles, as indices into the scene's caster mesh.
    pub triangles: Vec<usize>,
    /// Their corners.
    pub corners: Vec<[DVec3; 3]>,
    /// ρ_s or τ_s (linear RGB).
    pub coefficient: DVec3,
}

impl SpecularWindow {
    /// Signed distance of `p` from the plane (positive on the normal's side).
    pub fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }

    /// Where a source at `p` appears from beyond the window: its mirror image for a
    /// mirror, `p` itself for glass.
    pub fn image(&self, p: DVec3) -> DVec3 {
        match self.passage {
            Passage::Reflect => p - 2.0 * self.distance(p) * self.normal,
            Passage::Transmit => p,
        }
    }

    /// A direction seen through the window (mirrored for a mirror).
    pub fn image_direction(&self, d: DVec3) -> DVec3 {
        match self.passage {
            Passage::Reflect => d - 2.0 * d.dot(self.normal) * self.normal,
            Passage::Transmit => d,
        }
    }

    /// Whether `p`, a point of the plane, lies within the window's outline.
    pub fn contains(&self, p: DVec3) -> bool {
        self.corners.iter().any(|&t| {
            let [a, b, c] = crate::shadow::cutout::barycentric(t, p);
            a >= -1e-9 && b >= -1e-9 && c >= -1e-9
        })
    }

    fn ignored(&self) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
        self.triangles.iter().map(|&k| k..k + 1)
    }
}

/// A path of the reflection tree: the windows light passes, in order from the source,
/// and the source's image after each.
#[derive(Debug, Clone, PartialEq)]
pub struct SpecularPath {
    /// Indices into [`SpecularSurfaces::windows`].
    pub windows: Vec<usize>,
    /// The source's image after each window (the last is the virtual shooter).
    pub images: Vec<DVec3>,
    /// The product of the windows' coefficients.
    pub weight: DVec3,
}

impl SpecularPath {
    /// The virtual shooter: where the light appears to come from at the end.
    pub fn virtual_source(&self) -> DVec3 {
        *self.images.last().expect("a path passes a window")
    }
}

/// The scene's specular windows and how far paths through them are followed.
#[derive(Debug, Clone, Default)]
pub struct SpecularSurfaces {
    /// The windows.
    pub windows: Vec<SpecularWindow>,
    /// Most windows on one path.
    pub max_depth: u32,
    /// Least product of coefficients (largest channel) a path must keep.
    pub min_weight: f64,
}

impl SpecularSurfaces {
    /// The windows of `casters`' specular triangles (`material_of[k]` indexes `materials`),
    /// followed to [`DEFAULT_DEPTH`] windows.
    pub fn new(casters: &Mesh, material_of: &[usize], materials: &[Material]) -> SpecularSurfaces {
        let mut windows: Vec<(usize, SpecularWindow)> = Vec::new();
        for (k, t) in casters.triangles.iter().enumerate() {
            let Some(m) = material_of
                .get(k)
                .and_then(|&m| materials.get(m).map(|x| (m, x)))
            else {
                continue;
            };
            let (material, mat) = m;
            if !mat.is_specular() {
                continue;
            }
            let corners = t.map(|i| casters.positions[i as usize]);
            let cross = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            if cross.length() <= 1e-300 {
                continue;
            }
            let normal = cross.normalize();
            let both_sides = mat.specular_transmittance.max_element() > 0.0;
            let mut kinds = Vec::new();
            if mat.specular_reflectance.max_element() > 0.0 {
                let r = mat.specular_reflectance.as_dvec3();
                kinds.push((Passage::Reflect, normal, r));
                if both_sides {
                    kinds.push((Passage::Reflect, -normal, r));
                }
            }
            if both_sides {
                let t = mat.specular_transmittance.as_dvec3();
                kinds.push((Passage::Transmit, normal, t));
            }
            for (passage, n, coefficient) in kinds {
                let offset = n.dot(corners[0]);
                let scale = 1e-6 * (1.0 + offset.abs());
                let same = windows.iter_mut().find(|(wm, w)| {
                    *wm == material
                        && w.passage == passage
                        && w.normal.dot(n) > 1.0 - 1e-9
                        && (w.offset - offset).abs() <= scale
                });
                match same {
                    Some((_, w)) => {
                        w.triangles.push(k);
                        w.corners.push(corners);
                    }
                    None => windows.push((
                        material,
                        SpecularWindow {
                            passage,
                            normal: n,
                            offset,
                            triangles: vec![k],
                            corners: vec![corners],
                            coefficient,
                        },
                    )),
                }
            }
        }
        SpecularSurfaces {
            windows: windows.into_iter().map(|(_, w)| w).collect(),
            max_depth: DEFAULT_DEPTH,
            min_weight: DEFAULT_MIN_WEIGHT,
        }
    }

    /// Whether the scene has no specular surface.
    pub fn is_empty(&self) -> bool {
        self.windows.is_empty()
    }

    /// Point `q` as seen through `path`'s windows (imaged by each in turn).
    pub fn image_through(&self, path: &SpecularPath, q: DVec3) -> DVec3 {
        path.windows
            .iter()
            .fold(q, |q, &w| self.windows[w].image(q))
    }

    /// Direction `d` as seen through `path`'s windows.
    pub fn image_direction_through(&self, path: &SpecularPath, d: DVec3) -> DVec3 {
        path.windows
            .iter()
            .fold(d, |d, &w| self.windows[w].image_direction(d))
    }

    /// A surface's images for a receiver: per path of the reflection tree of a polygon
    /// facing `normal` seen from `centroid`, the path, the imaged polygon and the imaged
    /// normal.
    pub fn images(
        &self,
        polygon: &[DVec3],
        centroid: DVec3,
        normal: DVec3,
    ) -> Vec<(SpecularPath, Vec<DVec3>, DVec3)> {
        self.paths(centroid, Some(normal))
            .into_iter()
            .map(|path| {
                let imaged = polygon
                    .iter()
                    .map(|&q| self.image_through(&path, q))
                    .collect();
                let n = self.image_direction_through(&path, normal);
                (path, imaged, n)
            })
            .collect()
    }

    /// The reflection tree of a source at `source` (facing `facing`, a unit normal, when
    /// it is a surface; `None` for a point source shining every way): every path whose
    /// windows could pass its light on, one after the other.
    pub fn paths(&self, source: DVec3, facing: Option<DVec3>) -> Vec<SpecularPath> {
        let mut out = Vec::new();
        let root = SpecularPath {
            windows: Vec::new(),
            images: Vec::new(),
            weight: DVec3::ONE,
        };
        self.grow(&root, source, facing, &mut out);
        out
    }

    fn grow(
        &self,
        path: &SpecularPath,
        source: DVec3,
        facing: Option<DVec3>,
        out: &mut Vec<SpecularPath>,
    ) {
        if path.windows.len() >= self.max_depth as usize {
            return;
        }
        let at = path.images.last().copied().unwrap_or(source);
        let last = path.windows.last().map(|&w| &self.windows[w]);
        for (k, w) in self.windows.iter().enumerate() {
            let d = w.distance(at);
            let faces = match w.passage {
                Passage::Reflect => d > 1e-9,
                Passage::Transmit => d.abs() > 1e-9,
            };
            // Some of it in front of the source, and beyond the last window (on the side
            // its light leaves to: away from the image).
            let corners = || w.corners.iter().flatten();
            let in_front = match (facing, last) {
                (Some(n), None) => corners().any(|&c| n.dot(c - source) > 1e-9),
                (_, Some(l)) => {
                    let side = -l.distance(at).signum();
                    corners().any(|&c| side * l.distance(c) > 1e-9)
                }
                (None, None) => true,
            };
            let weight = path.weight * w.coefficient;
            if !faces || !in_front || weight.max_element() < self.min_weight {
                continue;
            }
            if path.windows.last() == Some(&k) {
                continue;
            }
            let mut next = path.clone();
            next.windows.push(k);
            next.images.push(w.image(at));
            next.weight = weight;
            self.grow(&next, source, facing, out);
            out.push(next);
        }
    }

    /// Whether light from `source` reaches `x` along `path`, every leg clear in `bvh`
    /// (over the caster mesh; `ignored` are the source's own triangles, `eps` how far
    /// rays start off surfaces): the point where it meets the first window, from which
    /// the source's own direction follows.
    pub fn trace(
        &self,
        bvh: &TriangleBvh,
        source: DVec3,
        path: &SpecularPath,
        x: DVec3,
        eps: f64,
        ignored: &IgnoredTriangles,
    ) -> Option<DVec3> {
        let mut y = x;
        let mut beyond: Option<&SpecularWindow> = None;
        for (i, &w) in path.windows.iter().enumerate().rev() {
            let win = &self.windows[w];
            let v = path.images[i];
            let (dv, dy) = (win.distance(v), win.distance(y));
            if dv * dy >= 0.0 || (win.passage == Passage::Reflect && dy <= 0.0) {
                return None;
            }
            let m = v + (y - v) * (dv / (dv - dy));
            if !win.contains(m) {
                return None;
            }
            let skip = IgnoredTriangles(win.ignored().chain(beyond_ranges(beyond)).collect());
            if segment_blocked(bvh, m, y, eps, &skip) {
                return None;
            }
            y = m;
            beyond = Some(win);
        }
        let mut skip = ignored.clone();
        skip.0.extend(beyond_ranges(beyond));
        (!segment_blocked(bvh, source, y, eps, &skip)).then_some(y)
    }
}

/// The luminaires' direct light by way of mirrors and clear glass, ray-cast: each path of
/// a luminaire's reflection tree is a virtual luminaire that sends what the real one
/// sends toward the path's first window, times the windows' coefficients, over the
/// unfolded distance. The GPU's first shot and the renderer's illuminance probe draw only
/// the straight light; this is added to theirs.
#[derive(Debug, Clone)]
pub struct SpecularLight<'a> {
    surfaces: &'a SpecularSurfaces,
    bvh: &'a TriangleBvh,
    luminaires: &'a [PlacedLuminaire],
    ignored: &'a [IgnoredTriangles],
    eps: f64,
    /// Per luminaire, its reflection tree.
    paths: Vec<Vec<SpecularPath>>,
}

impl<'a> SpecularLight<'a> {
    /// The light of `luminaires` through `surfaces`' windows, the legs' rays cast in `bvh`
    /// (over the caster mesh; `ignored[k]` are luminaire `k`'s housing, `eps` how far
    /// rays start off surfaces).
    pub fn new(
        surfaces: &'a SpecularSurfaces,
        bvh: &'a TriangleBvh,
        luminaires: &'a [PlacedLuminaire],
        ignored: &'a [IgnoredTriangles],
        eps: f64,
    ) -> SpecularLight<'a> {
        let paths = luminaires
            .iter()
            .map(|l| surfaces.paths(l.position, None))
            .collect();
        SpecularLight {
            surfaces,
            bvh,
            luminaires,
            ignored,
            eps,
            paths,
        }
    }

    /// Whether no light comes this way (no windows).
    pub fn is_empty(&self) -> bool {
        self.surfaces.is_empty()
    }

    /// The illuminance (RGB lux) at `p` on a surface with unit normal `n`.
    pub fn at(&self, p: DVec3, n: DVec3, interp: Interp) -> DVec3 {
        let none = IgnoredTriangles::default();
        let q = p + n * self.eps;
        let mut sum = DVec3::ZERO;
        for (k, (l, paths)) in self.luminaires.iter().zip(&self.paths).enumerate() {
            let ignored = self.ignored.get(k).unwrap_or(&none);
            for path in paths {
                let to = path.virtual_source() - p;
                let d2 = to.length_squared();
                if d2 <= 0.0 || n.dot(to) <= 0.0 {
                    continue;
                }
                let cos = n.dot(to) / d2.sqrt();
                let traced = self
                    .surfaces
                    .trace(self.bvh, l.position, path, q, self.eps, ignored);
                let Some(m) = traced else {
                    continue;
                };
                let out = (m - l.position).normalize_or_zero();
                let intensity = l.intensity_toward(out, interp);
                sum += path.weight * l.color_toward(out) * intensity * cos / d2;
            }
        }
        sum
    }

    /// Adds [`SpecularLight::at`] to `rgb` (one per point, RGB lux) at every point, on
    /// the CPU's threads; nothing without windows.
    pub fn add_at_points(&self, points: &[SurfacePoint], rgb: &mut [DVec3], interp: Interp) {
        use rayon::prelude::*;
        if self.is_empty() {
            return;
        }
        rgb.par_iter_mut().zip(points).for_each(|(v, p)| {
            *v += self.at(p.position, p.normal.normalize_or_zero(), interp);
        });
    }

    /// [`SpecularLight::add_at_points`] for illuminance (lux, luminance).
    pub fn add_lux_at_points(&self, points: &[SurfacePoint], lux: &mut [f64], interp: Interp) {
        use rayon::prelude::*;
        if self.is_empty() {
            return;
        }
        lux.par_iter_mut().zip(points).for_each(|(v, p)| {
            let rgb = self.at(p.position, p.normal.normalize_or_zero(), interp);
            *v += rgb.dot(crate::scene::placement::LUMINANCE_WEIGHTS);
        });
    }
}

/// What [`SpecularLight`] needs of a [`Scene`], built from it: its windows, the ray-cast
/// hierarchy over its casters and its luminaires' housings.
#[derive(Debug, Clone)]
pub struct SceneWindows {
    surfaces: SpecularSurfaces,
    bvh: TriangleBvh,
    ignored: Vec<IgnoredTriangles>,
    eps: f64,
}

impl SceneWindows {
    /// `None` when `scene` has no mirror or clear glass.
    pub fn new(scene: &Scene) -> Option<SceneWindows> {
        if !scene.materials.iter().any(Material::is_specular) {
            return None;
        }
        let casters = scene.caster_mesh();
        let surfaces = SpecularSurfaces::new(&casters, &scene.caster_materials(), &scene.materials);
        Some(SceneWindows {
            surfaces,
            bvh: TriangleBvh::new(&casters).with_cutouts(scene.caster_cutouts()),
            ignored: scene.ignored_per_luminaire(),
            eps: crate::shadow::raycast::self_hit_epsilon(&casters),
        })
    }

    /// The light of `luminaires` (the scene's) through the windows.
    pub fn light<'a>(&'a self, luminaires: &'a [PlacedLuminaire]) -> SpecularLight<'a> {
        SpecularLight::new(
            &self.surfaces,
            &self.bvh,
            luminaires,
            &self.ignored,
            self.eps,
        )
    }
}

fn beyond_ranges(w: Option<&SpecularWindow>) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
    w.into_iter().flat_map(SpecularWindow::ignored)
}

/// Whether a triangle not in `ignored` crosses the segment `a`–`b` (short of `eps` at
/// either end).
fn segment_blocked(
    bvh: &TriangleBvh,
    a: DVec3,
    b: DVec3,
    eps: f64,
    ignored: &IgnoredTriangles,
) -> bool {
    let d = b - a;
    let len = d.length();
    if len <= 2.0 * eps {
        return false;
    }
    bvh.blocked(a, d / len, eps, len - eps, ignored)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn quad(z: f64, flip: bool) -> Vec<[DVec3; 3]> {
        let (a, b, c, d) = (
            DVec3::new(0.0, 0.0, z),
            DVec3::new(1.0, 0.0, z),
            DVec3::new(1.0, 1.0, z),
            DVec3::new(0.0, 1.0, z),
        );
        if flip {
            vec![[a, c, b], [a, d, c]]
        } else {
            vec![[a, b, c], [a, c, d]]
        }
    }

    fn surfaces(triangles: &[[DVec3; 3]], material: Material) -> (Mesh, SpecularSurfaces) {
        let mut mesh = Mesh::default();
        for t in triangles {
            let base = mesh.positions.len() as u32;
            mesh.positions.extend(t);
            mesh.triangles.push([base, base + 1, base + 2]);
        }
        let materials = vec![Material::default(), material];
        let s = SpecularSurfaces::new(&mesh, &vec![1; triangles.len()], &materials);
        (mesh, s)
    }

    fn mirror(r: f32) -> Material {
        Material {
            diffuse: Vec3::ZERO,
            specular_reflectance: Vec3::splat(r),
            ..Material::default()
        }
    }

    #[test]
    fn a_mirror_is_one_window_and_images_the_source() {
        let (_, s) = surfaces(&quad(0.0, false), mirror(0.9));
        assert_eq!(s.windows.len(), 1, "two coplanar triangles: one window");
        let w = &s.windows[0];
        assert_eq!(w.triangles, vec![0, 1]);
        let p = DVec3::new(0.3, 0.4, 2.0);
        assert!((w.image(p) - DVec3::new(0.3, 0.4, -2.0)).length() < 1e-12);
        assert!(w.contains(DVec3::new(0.9, 0.1, 0.0)) && !w.contains(DVec3::new(1.1, 0.5, 0.0)));
        let paths = s.paths(p, None);
        assert_eq!(paths.len(), 1);
        assert!((paths[0].weight - DVec3::splat(0.9)).abs().max_element() < 1e-6);
        // Behind the mirror, nothing is reflected.
        assert!(s.paths(DVec3::new(0.3, 0.4, -2.0), None).is_empty());
    }

    #[test]
    fn two_facing_mirrors_form_a_tree_to_the_depth_limit() {
        let mut t = quad(0.0, false);
        t.extend(quad(1.0, true));
        let (_, s) = surfaces(&t, mirror(0.9));
        assert_eq!(s.windows.len(), 2);
        let paths = s.paths(DVec3::new(0.5, 0.5, 0.5), None);
        // Alternating windows only: two chains of DEFAULT_DEPTH.
        assert_eq!(paths.len(), 2 * DEFAULT_DEPTH as usize);
        // The image after floor then ceiling: z = 0.5 → −0.5 → 2.5.
        let two = paths
            .iter()
            .find(|p| p.windows == vec![0, 1])
            .expect("floor then ceiling");
        assert!((two.virtual_source().z - 2.5).abs() < 1e-12);
        assert!((two.weight.x - 0.81).abs() < 1e-6);
    }

    #[test]
    fn a_pane_transmits_both_ways_and_reflects_on_both_sides() {
        let glass = Material {
            diffuse: Vec3::ZERO,
            specular_reflectance: Vec3::splat(0.08),
            specular_transmittance: Vec3::splat(0.9),
            ..Material::default()
        };
        let (mesh, s) = surfaces(&quad(0.0, false), glass);
        assert_eq!(s.windows.len(), 3, "reflect up, reflect down, transmit");
        let bvh = TriangleBvh::new(&mesh);
        let none = IgnoredTriangles::default();
        let (above, below) = (DVec3::new(0.5, 0.5, 1.0), DVec3::new(0.2, 0.6, -1.0));
        for source in [above, below] {
            let paths = s.paths(source, None);
            assert_eq!(paths.len(), 2, "one reflection, one transmission");
            let through = paths
                .iter()
                .find(|p| s.windows[p.windows[0]].passage == Passage::Transmit)
                .unwrap();
            let target = if source == above { below } else { above };
            let m = s.trace(&bvh, source, through, target, 1e-9, &none).unwrap();
            assert!(m.z.abs() < 1e-12, "meets the pane at {m}");
            // Not to a point on the source's own side.
            assert!(s
                .trace(&bvh, source, through, source + DVec3::X * 0.1, 1e-9, &none)
                .is_none());
        }
    }

    #[test]
    fn legs_blocked_on_either_side_stop_the_light() {
        // A mirror floor and a small blocker hanging at z = 0.5 over its middle.
        let mut t = quad(0.0, false);
        let blocker = [
            DVec3::new(0.4, 0.4, 0.5),
            DVec3::new(0.6, 0.4, 0.5),
            DVec3::new(0.5, 0.6, 0.5),
        ];
        t.push(blocker);
        let mut mesh = Mesh::default();
        for t in &t {
            let base = mesh.positions.len() as u32;
            mesh.positions.extend(t);
            mesh.triangles.push([base, base + 1, base + 2]);
        }
        let materials = vec![Material::default(), mirror(0.9)];
        let s = SpecularSurfaces::new(&mesh, &[1, 1, 0], &materials);
        let bvh = TriangleBvh::new(&mesh);
        let none = IgnoredTriangles::default();
        let path = &s.paths(DVec3::new(0.5, 0.5, 1.0), None)[0];
        // Straight down and back up through the blocker: the first leg is blocked.
        let source = DVec3::new(0.5, 0.5, 1.0);
        assert!(s
            .trace(&bvh, source, path, DVec3::new(0.5, 0.5, 0.9), 1e-9, &none)
            .is_none());
        // Source beside the blocker, receiver above it: the second leg is blocked.
        let source = DVec3::new(0.1, 0.5, 0.8);
        let seen = DVec3::new(0.9, 0.5, 0.8);
        assert!(s.trace(&bvh, source, path, seen, 1e-9, &none).is_some());
        let source = DVec3::new(0.5, 0.5, 0.3);
        assert!(s
            .trace(&bvh, source, path, DVec3::new(0.5, 0.5, 0.9), 1e-9, &none)
            .is_none());
        // Outside the mirror's outline: no reflection.
        let far = DVec3::new(3.0, 0.5, 0.8);
        assert!(s
            .trace(&bvh, DVec3::new(0.1, 0.5, 0.8), path, far, 1e-9, &none)
            .is_none());
    }
}
