//! Which surfaces the exported scene carries in the light map and which in vertex colours
//! (Edström §5.3). A surface is one root of the face-cluster hierarchy (a connected
//! surface of one material), and it gets one representation, so no seam runs between a
//! Gouraud-shaded part and a textured part of it.
//!
//! Vertex lighting draws the input triangles, refined where the light map is finer than
//! they are: Edström's patch refinement ([`super::refine`]) splits each triangle into
//! patches no longer than a texel (well shaped even where the triangle is a sliver,
//! conforming across the surface's shared edges); the triangles beyond the model's are
//! *introduced*. A surface not refined below its triangles (curved, finely tessellated
//! parts) introduces none and is best drawn with its vertices; a wall of two triangles
//! under a fine light map would introduce thousands and is best textured. The heuristic: surfaces sorted by introduced triangles,
//! most first, turn to light maps until the introduced triangles left fall within the
//! budget. The scene file may fix a model's or a material's choice (`bake`,
//! `bake_materials`), and `--bake map|vertex` fixes every surface.
//!
//! The introduced triangles are the rendering overhead of the solution (Edström §7.6:
//! about 10 % on his car exterior, 35 % on its interior): what the exported mesh draws
//! beyond the model.

use glam::DVec3;
use rayon::prelude::*;

use crate::scene::file::Bake;

use super::refine::refine_surface;
use super::scene::RadiosityScene;

/// The most parts the longest side of a triangle is cut into for vertex lighting: its
/// patches are at least `1 / MAX_SPLITS` of it long, so a triangle becomes at most about
/// `MAX_SPLITS²` patches.
pub const MAX_SPLITS: u32 = 32;

/// The default budget of introduced triangles: this share of the model's triangles
/// (Edström's car exterior drew about 10 % more than its model).
pub const DEFAULT_BUDGET_SHARE: f64 = 0.10;

/// How the representation of each surface is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum BakeChoice {
    /// Per surface: the scene file's choice, else the introduced-triangles heuristic.
    #[default]
    Auto,
    /// Every surface in the light map.
    Map,
    /// Every surface in vertex colours.
    Vertex,
}

/// The representation of every triangle and what it costs.
#[derive(Debug, Clone, PartialEq)]
pub struct BakePlan {
    /// Per triangle of the scene's casters: its representation (`None`: it has no
    /// elements and is not exported).
    pub bake: Vec<Option<Bake>>,
    /// Per triangle: the triangles it is drawn as when vertex-lit, each as three corners in
    /// barycentric weights over the triangle's corners (one part, the triangle itself,
    /// where it is not refined); empty when it is light-mapped or not exported.
    pub parts: Vec<Vec<[DVec3; 3]>>,
    /// Surfaces light-mapped and vertex-lit.
    pub surfaces: [usize; 2],
    /// Triangles of the model light-mapped and vertex-lit.
    pub triangles: [usize; 2],
    /// Triangles the vertex-lit surfaces add to the model.
    pub introduced: u64,
    /// The budget the heuristic kept `introduced` within, where the choice let it.
    pub budget: u64,
}

impl BakePlan {
    /// Introduced triangles per triangle of the model: the rendering overhead.
    pub fn overhead(&self) -> f64 {
        self.introduced as f64 / (self.triangles[0] + self.triangles[1]).max(1) as f64
    }
}

/// How long the patches of triangle `t` may be for vertex lighting, metres: a texel of
/// its chart, or a [`MAX_SPLITS`]th of its longest side where that is longer.
pub fn patch_size(scene: &RadiosityScene, t: usize) -> f64 {
    let te = &scene.elements.triangles[t];
    let p = scene.casters.triangles[t].map(|i| scene.casters.positions[i as usize]);
    let longest = (p[1] - p[0])
        .length()
        .max((p[2] - p[1]).length())
        .max((p[0] - p[2]).length());
    let texel = scene
        .elements
        .charts
        .get(te.chart as usize)
        .map_or(longest, |chart| chart.texel_m);
    texel.max(longest / f64::from(MAX_SPLITS))
}

/// The fewest triangles vertex lighting can introduce on `triangles`: each patch fits a
/// square of its triangle's [`patch_size`], so a triangle draws at least its area over
/// that square.
pub fn introduced_at_least(scene: &RadiosityScene, triangles: &[u32]) -> u64 {
    triangles
        .iter()
        .map(|&t| {
            let size = patch_size(scene, t as usize);
            let p =
                scene.casters.triangles[t as usize].map(|i| scene.casters.positions[i as usize]);
            let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
            ((area / (size * size)) * (1.0 - 1e-9)).ceil().max(1.0) as u64 - 1
        })
        .sum()
}

/// Chooses each surface's representation. `material_bake` is the scene file's choice per
/// material; `budget` the introduced triangles allowed (default: [`DEFAULT_BUDGET_SHARE`]
/// of the triangles with elements).
pub fn plan(
    scene: &RadiosityScene,
    material_bake: &[Option<Bake>],
    choice: BakeChoice,
    budget: Option<u64>,
) -> BakePlan {
    let count = scene.elements.triangles.len();
    let has_elements = |t: u32| scene.elements.triangles[t as usize].chart != u32::MAX;
    struct Surface {
        triangles: Vec<u32>,
        parts: Vec<Vec<[DVec3; 3]>>,
        introduced: u64,
        fixed: Option<Bake>,
    }
    let mut surfaces: Vec<Surface> = scene
        .surfaces()
        .into_iter()
        .map(|surface| {
            let material = scene.elements.triangles[surface[0] as usize].material;
            let fixed = match choice {
                BakeChoice::Map => Some(Bake::Map),
                BakeChoice::Vertex => Some(Bake::Vertex),
                BakeChoice::Auto => material_bake.get(material).copied().flatten(),
            };
            Surface {
                triangles: surface.into_iter().filter(|&t| has_elements(t)).collect(),
                parts: Vec::new(),
                introduced: 0,
                fixed,
            }
        })
        .filter(|s| !s.triangles.is_empty())
        .collect();
    let modelled: usize = surfaces.iter().map(|s| s.triangles.len()).sum();
    let budget = budget.unwrap_or((DEFAULT_BUDGET_SHARE * modelled as f64).round() as u64);
    // Refined where the surface may be vertex-lit. A free surface that must introduce
    // more than the whole budget is light-mapped whatever the rest do (the heuristic turns
    // it before any smaller one), so its lower bound suffices.
    surfaces.par_iter_mut().for_each(|s| {
        let bound = if s.fixed.is_none() {
            introduced_at_least(scene, &s.triangles)
        } else {
            0
        };
        match s.fixed {
            Some(Bake::Map) => {}
            None if bound > budget => s.introduced = bound,
            _ => {
                s.parts = refine_surface(&scene.casters, &s.triangles, |t| {
                    patch_size(scene, t as usize)
                });
                let drawn: usize = s.parts.iter().map(Vec::len).sum();
                s.introduced = (drawn - s.triangles.len()) as u64;
            }
        }
    });
    let mut chosen: Vec<Bake> = surfaces
        .iter()
        .map(|s| s.fixed.unwrap_or(Bake::Vertex))
        .collect();
    let mut introduced: u64 = surfaces
        .iter()
        .zip(&chosen)
        .filter(|(_, &b)| b == Bake::Vertex)
        .map(|(s, _)| s.introduced)
        .sum();
    let mut free: Vec<usize> = (0..surfaces.len())
        .filter(|&k| surfaces[k].fixed.is_none())
        .collect();
    free.sort_by(|&a, &b| surfaces[b].introduced.cmp(&surfaces[a].introduced));
    for k in free {
        if introduced <= budget || surfaces[k].introduced == 0 {
            break;
        }
        chosen[k] = Bake::Map;
        introduced -= surfaces[k].introduced;
    }
    let mut bake = vec![None; count];
    let mut parts = vec![Vec::new(); count];
    let (mut surface_count, mut triangle_count) = ([0; 2], [0; 2]);
    for (s, &b) in surfaces.iter_mut().zip(&chosen) {
        let slot = usize::from(b == Bake::Vertex);
        surface_count[slot] += 1;
        triangle_count[slot] += s.triangles.len();
        for &t in &s.triangles {
            bake[t as usize] = Some(b);
        }
        if b == Bake::Vertex {
            // A vertex-lit surface was refined: its parts, triangle by triangle.
            for (&t, p) in s.triangles.iter().zip(std::mem::take(&mut s.parts)) {
                parts[t as usize] = p;
            }
        }
    }
    BakePlan {
        bake,
        parts,
        surfaces: surface_count,
        triangles: triangle_count,
        introduced,
        budget,
    }
}
