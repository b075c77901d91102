//! The normals elements receive with (Wallner §2.3.3): the mesh's interpolated vertex
//! normals, perturbed by the material's normal map, instead of the flat normal of the
//! element's chart. A curved mesh then no longer shows its facets in the solution, and a
//! normal-mapped wall receives as its relief does.
//!
//! An element's receiving normal is the **mean** of the shading normals over its texel
//! (a grid of samples where a normal map varies it, the texel's centre otherwise). The
//! mean is not normalised: diffuse light is linear in the normal, so a receiver whose
//! relief tilts this way and that takes the mean of what each tilt takes, and the relief
//! shortens the mean (the renderer's normal-map mipmaps do the same,
//! [`crate::render::mipmaps`]). Normal maps are read at the mip level whose texels match the
//! samples' spacing.
//!
//! Light never arrives through a surface's back: a receiver takes light only from
//! sources in front of its geometric plane, whatever its shading normal says
//! ([`receiving`]). Shooting keeps the geometric normal (a patch emits into its
//! geometric hemisphere).

use std::collections::HashMap;

use glam::{DVec2, DVec3, Vec3};

use super::elements::{Chart, Elements};
use crate::render::mipmaps::{mip_chain, TexelKind};
use crate::scene::{Scene, SceneMesh};

/// Samples per side of a texel where a normal map varies the normal.
const NORMAL_MAP_SAMPLES: u32 = 4;

/// How far (length of the difference) a receiving normal may be from the chart's normal
/// and still count as it: flat meshes keep exactly the flat solution.
const SAME_NORMAL: f64 = 1e-6;

/// The receiving normal of every element of `elements` (built from `scene`'s triangles,
/// meshes in order), or an empty list when every one is its chart's normal (flat meshes
/// without normal maps: nothing to compute or store).
pub fn receiving_normals(scene: &Scene, elements: &Elements) -> Vec<DVec3> {
    let sources = TriangleSources::new(scene);
    let shaded: Vec<bool> = elements
        .charts
        .iter()
        .map(|c| c.triangles.iter().any(|&t| sources.shaded(t as usize)))
        .collect();
    if !shaded.contains(&true) {
        return Vec::new();
    }
    let mut maps: HashMap<usize, NormalMap> = HashMap::new();
    let mut out = vec![DVec3::ZERO; elements.len()];
    for (c, chart) in elements.charts.iter().enumerate() {
        let range = chart.first as usize..(chart.first + chart.count) as usize;
        if !shaded[c] {
            out[range].fill(chart.normal);
            continue;
        }
        let map = scene.materials[chart.material]
            .normal_map
            .as_ref()
            .map(|img| {
                &*maps
                    .entry(chart.material)
                    .or_insert_with(|| NormalMap::new(img))
            });
        let locator = ChartLocator::new(elements, chart);
        for e in range {
            let n = chart_element_normal(&sources, elements, chart, &locator, map, e);
            out[e] = if (n - chart.normal).length() < SAME_NORMAL {
                chart.normal
            } else {
                n
            };
        }
    }
    out
}

/// The form factor a receiver with geometric normal `geometric` and receiving normal
/// `shading` takes from a source `to_source` away (any length), where `form_factor(n)`
/// is the form factor for a receiver with unit normal `n`: with the shading normal's
/// direction, times its length, and zero when the source is behind the geometric plane.
pub fn receiving(
    geometric: DVec3,
    shading: DVec3,
    to_source: DVec3,
    form_factor: impl Fn(DVec3) -> f64,
) -> f64 {
    match own_direction(geometric, shading) {
        None if shading == geometric => form_factor(geometric),
        Some((direction, length)) if geometric.dot(to_source) > 0.0 => {
            form_factor(direction) * length
        }
        _ => 0.0,
    }
}

/// The unit direction and the length of receiving normal `shading` when it is not the
/// geometric normal (`None` when it is, or when it has no length).
pub fn own_direction(geometric: DVec3, shading: DVec3) -> Option<(DVec3, f64)> {
    let length = shading.length();
    (shading != geometric && length > 0.0).then(|| (shading / length, length))
}

/// Element `e`'s mean shading normal.
fn chart_element_normal(
    sources: &TriangleSources,
    elements: &Elements,
    chart: &Chart,
    locator: &ChartLocator,
    map: Option<&NormalMap>,
    e: usize,
) -> DVec3 {
    let (lo, side) = elements.atlas_square(e);
    let per_texel = if map.is_some() { NORMAL_MAP_SAMPLES } else { 1 };
    let n = per_texel * side as u32;
    let step = side / n as f64;
    let mut sum = DVec3::ZERO;
    let mut count = 0;
    for j in 0..n {
        for i in 0..n {
            let p = lo + DVec2::new(i as f64 + 0.5, j as f64 + 0.5) * step;
            if let Some((t, b)) = locator.inside(elements, p) {
                sum += sources.normal_at(t, b, chart, map, step);
                count += 1;
            }
        }
    }
    if count == 0 {
        // A texel only an edge of the chart crosses: the nearest triangle's nearest point.
        let (t, b) = locator.nearest(elements, lo + DVec2::splat(0.5 * side));
        return sources.normal_at(t, b, chart, map, 1.0);
    }
    sum / count as f64
}

/// Where each of the scene's triangles comes from (meshes in order, as the elements'
/// input triangles).
struct TriangleSources<'a> {
    scene: &'a Scene,
    /// Per triangle: its mesh and its first index in the mesh's index list.
    origin: Vec<(u32, u32)>,
    /// Per mesh with a normal map: its vertex tangents.
    tangents: HashMap<usize, Vec<[f32; 4]>>,
}

impl<'a> TriangleSources<'a> {
    fn new(scene: &'a Scene) -> TriangleSources<'a> {
        let mut origin = Vec::with_capacity(scene.triangle_count());
        let mut tangents = HashMap::new();
        for (k, m) in scene.meshes.iter().enumerate() {
            origin.extend((0..m.indices.len() as u32 / 3).map(|t| (k as u32, 3 * t)));
            if scene.materials[m.material].normal_map.is_some() {
                tangents.insert(k, m.tangents());
            }
        }
        TriangleSources {
            scene,
            origin,
            tangents,
        }
    }

    fn mesh(&self, t: usize) -> (&SceneMesh, [usize; 3]) {
        let (m, first) = self.origin[t];
        let mesh = &self.scene.meshes[m as usize];
        let i = first as usize;
        let corners = [0, 1, 2].map(|k| mesh.indices[i + k] as usize);
        (mesh, corners)
    }

    /// Whether triangle `t` receives with other normals than its plane's: its material
    /// has a normal map, or its vertex normals differ from each other. Three equal
    /// normals are a flat-shaded triangle's face normal (made from its corners in single
    /// precision, it can miss a sliver's by 2e-2): it receives with its chart's.
    fn shaded(&self, t: usize) -> bool {
        let (mesh, c) = self.mesh(t);
        if self.scene.materials[mesh.material].normal_map.is_some() {
            return true;
        }
        let n = c.map(|k| mesh.normals[k].as_dvec3().normalize_or_zero());
        (n[1] - n[0]).length() > 1e-6 || (n[2] - n[0]).length() > 1e-6
    }

    /// The shading normal at barycentric `b` of triangle `t` in `chart` (mean over a
    /// sample `spacing` texels of the chart wide where `map` perturbs it).
    fn normal_at(
        &self,
        t: usize,
        b: [f64; 3],
        chart: &Chart,
        map: Option<&NormalMap>,
        spacing: f64,
    ) -> DVec3 {
        let (mesh, c) = self.mesh(t);
        let interpolated: DVec3 = (0..3)
            .map(|k| mesh.normals[c[k]].as_dvec3() * b[k])
            .sum::<DVec3>()
            .normalize_or_zero();
        // Normals the file gives against the face's winding are not the surface's front.
        let normal = if interpolated.dot(chart.normal) > 0.0 {
            interpolated
        } else {
            chart.normal
        };
        let (Some(map), Some(tangents)) = (map, self.tangents.get(&(self.origin[t].0 as usize)))
        else {
            return normal;
        };
        let uv: DVec2 = (0..3).map(|k| mesh.uvs[c[k]].as_dvec2() * b[k]).sum();
        let tangent: DVec3 = (0..3)
            .map(|k| Vec3::from_slice(&tangents[c[k]][..3]).as_dvec3() * b[k])
            .sum();
        let handedness = tangents[c[0]][3] as f64;
        let tangent = (tangent - normal * normal.dot(tangent)).normalize_or_zero();
        let tangent = if tangent == DVec3::ZERO {
            normal.any_orthonormal_vector()
        } else {
            tangent
        };
        let bitangent = normal.cross(tangent) * handedness;
        // Texels of the map per metre of the surface, from the triangle's two mappings.
        let [pa, pb, pc] = c.map(|k| mesh.positions[k].as_dvec3());
        let world = (pb - pa).cross(pc - pa).length();
        let [ua, ub, uc] = c.map(|k| mesh.uvs[k].as_dvec2() * map.size());
        let texels = (ub - ua).perp_dot(uc - ua).abs();
        let per_metre = if world > 0.0 {
            (texels / world).sqrt()
        } else {
            0.0
        };
        let (m, length) = map.sample(uv, spacing * chart.texel_m * per_metre);
        let perturbed = tangent * m.x + bitangent * m.y + normal * m.z;
        perturbed.normalize_or_zero() * length
    }
}

/// Finds the triangle of a chart under a point of the atlas.
struct ChartLocator<'a> {
    triangles: &'a [u32],
    /// Per atlas texel, the chart's triangles whose bounding boxes touch it (none for a
    /// chart of a few triangles: all are tried).
    bins: HashMap<(u32, u32), Vec<u32>>,
}

impl<'a> ChartLocator<'a> {
    /// Charts of at most this many triangles are searched whole.
    const SMALL: usize = 8;

    fn new(elements: &Elements, chart: &'a Chart) -> ChartLocator<'a> {
        let mut bins: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
        if chart.triangles.len() > Self::SMALL {
            for &t in &chart.triangles {
                let uv = elements.triangles[t as usize].atlas_uv;
                let lo = uv[0].min(uv[1]).min(uv[2]).floor().max(DVec2::ZERO);
                let hi = uv[0].max(uv[1]).max(uv[2]).floor().max(DVec2::ZERO);
                for y in lo.y as u32..=hi.y as u32 {
                    for x in lo.x as u32..=hi.x as u32 {
                        bins.entry((x, y)).or_default().push(t);
                    }
                }
            }
        }
        ChartLocator {
            triangles: &chart.triangles,
            bins,
        }
    }

    fn candidates(&self, p: DVec2) -> &[u32] {
        if self.bins.is_empty() {
            return self.triangles;
        }
        let key = (p.x.max(0.0) as u32, p.y.max(0.0) as u32);
        self.bins.get(&key).map_or(&[], Vec::as_slice)
    }

    /// The triangle holding atlas point `p` and its barycentric coordinates there.
    fn inside(&self, elements: &Elements, p: DVec2) -> Option<(usize, [f64; 3])> {
        self.candidates(p).iter().find_map(|&t| {
            let b = barycentric(elements.triangles[t as usize].atlas_uv, p)?;
            (b.iter().all(|&x| x >= -1e-9)).then_some((t as usize, b))
        })
    }

    /// The triangle nearest atlas point `p` (the least outside it) and the barycentric
    /// coordinates of its point nearest `p` (clamped into it).
    fn nearest(&self, elements: &Elements, p: DVec2) -> (usize, [f64; 3]) {
        let mut candidates = self.candidates(p);
        if candidates.is_empty() {
            candidates = self.triangles;
        }
        let mut best = (candidates[0] as usize, [1.0 / 3.0; 3], f64::NEG_INFINITY);
        for &t in candidates {
            if let Some(b) = barycentric(elements.triangles[t as usize].atlas_uv, p) {
                let worst = b[0].min(b[1]).min(b[2]);
                if worst > best.2 {
                    let clamped = b.map(|x| x.max(0.0));
                    let sum: f64 = clamped.iter().sum();
                    best = (t as usize, clamped.map(|x| x / sum), worst);
                }
            }
        }
        (best.0, best.1)
    }
}

/// Barycentric coordinates of `p` in triangle `c` (`None` when it has no area).
fn barycentric(c: [DVec2; 3], p: DVec2) -> Option<[f64; 3]> {
    let (v0, v1) = (c[1] - c[0], c[2] - c[0]);
    let det = v0.perp_dot(v1);
    if det.abs() < 1e-12 {
        return None;
    }
    let d = p - c[0];
    let (u, v) = (d.perp_dot(v1) / det, v0.perp_dot(d) / det);
    Some([1.0 - u - v, u, v])
}

/// A tangent-space normal map with its mip chain (rgb: the mean direction; alpha: the
/// mean's length, [`mip_chain`]).
struct NormalMap {
    levels: Vec<image::RgbaImage>,
}

impl NormalMap {
    fn new(img: &image::RgbaImage) -> NormalMap {
        NormalMap {
            levels: mip_chain(img, TexelKind::Normal),
        }
    }

    /// Level 0's size in texels.
    fn size(&self) -> DVec2 {
        let l = &self.levels[0];
        DVec2::new(l.width() as f64, l.height() as f64)
    }

    /// The tangent-space direction at `uv` (repeating; row 0 at v = 0, as the renderer
    /// samples) and the mean's length, bilinear on the level whose texels are about
    /// `footprint` level-0 texels wide.
    fn sample(&self, uv: DVec2, footprint: f64) -> (DVec3, f64) {
        let level = if footprint > 1.0 {
            (footprint.log2().floor() as usize).min(self.levels.len() - 1)
        } else {
            0
        };
        let img = &self.levels[level];
        let (w, h) = (img.width() as i64, img.height() as i64);
        let x = uv.x * w as f64 - 0.5;
        let y = uv.y * h as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let mut sum = [0.0f64; 4];
        for (dy, wy) in [(0, 1.0 - fy), (1, fy)] {
            for (dx, wx) in [(0, 1.0 - fx), (1, fx)] {
                let px = (x0 as i64 + dx).rem_euclid(w) as u32;
                let py = (y0 as i64 + dy).rem_euclid(h) as u32;
                let texel = img.get_pixel(px, py).0;
                for (s, &v) in sum.iter_mut().zip(&texel) {
                    *s += wx * wy * v as f64 / 255.0;
                }
            }
        }
        let direction = DVec3::new(sum[0], sum[1], sum[2]) * 2.0 - DVec3::ONE;
        (direction, sum[3])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_source_behind_the_geometric_plane_gives_nothing_whatever_the_shading_normal() {
        let geometric = DVec3::Z;
        let shading = DVec3::new(0.6, 0.0, 0.8) * 0.5;
        let cosine = |n: DVec3| n.dot(DVec3::new(1.0, 0.0, -0.1).normalize()).max(0.0);
        assert_eq!(
            receiving(geometric, shading, DVec3::new(1.0, 0.0, -0.1), cosine),
            0.0
        );
        // In front: the unit direction's form factor times the mean's length.
        let to = DVec3::new(1.0, 0.0, 1.0);
        let f = receiving(geometric, shading, to, |n| n.dot(to.normalize()));
        assert!((f - 0.5 * (0.6 + 0.8) / 2f64.sqrt()).abs() < 1e-12);
        // The chart's own normal: the form factor as it is.
        assert_eq!(receiving(geometric, geometric, -to, |_| 0.25), 0.25);
    }

    #[test]
    fn a_flat_normal_map_texel_is_the_surface_normal_and_a_level_keeps_the_mean_length() {
        // Left half tilted +x by 45°, right half −x: level 0 gives each, level 1 their mean.
        let tilt = |s: f64| {
            let n = DVec3::new(s, 0.0, 1.0).normalize();
            let c = (n * 0.5 + DVec3::splat(0.5)) * 255.0;
            image::Rgba([c.x.round() as u8, c.y.round() as u8, c.z.round() as u8, 255])
        };
        let img = image::RgbaImage::from_fn(2, 2, |x, _| tilt(if x == 0 { 1.0 } else { -1.0 }));
        let map = NormalMap::new(&img);
        let (left, len) = map.sample(DVec2::new(0.25, 0.25), 1.0);
        assert!((left.normalize() - DVec3::new(1.0, 0.0, 1.0).normalize()).length() < 0.01);
        assert!((len - 1.0).abs() < 1e-12);
        let (mean, len) = map.sample(DVec2::new(0.5, 0.5), 2.0);
        // The mean of two unit normals 90° apart is 1/√2 long, straight up.
        assert!(mean.normalize().dot(DVec3::Z) > 0.999, "{mean}");
        assert!((len - 0.5f64.sqrt()).abs() < 0.01, "{len}");
    }
}
