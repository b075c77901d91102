//! Which surfaces the exported scene carries in the light map and which in vertex colours
//! (Edström §5.3). A surface is one root of the face-cluster hierarchy (a connected
//! surface of one material), and it gets one representation, so no seam runs between a
//! Gouraud-shaded part and a textured part of it.
//!
//! Vertex lighting draws the input triangles, split where the light map is finer than
//! they are: a triangle whose longest side spans `n` texels becomes `n²` triangles, so
//! `n² − 1` are *introduced*. A surface not refined below its triangles (every side at
//! most one texel: curved, finely tessellated parts) introduces none and is best drawn
//! with its vertices; a wall of two triangles under a fine light map would introduce
//! thousands and is best textured. The heuristic: surfaces sorted by introduced triangles,
//! most first, turn to light maps until the introduced triangles left fall within the
//! budget. The scene file may fix a model's or a material's choice (`bake`,
//! `bake_materials`), and `--bake map|vertex` fixes every surface.
//!
//! The introduced triangles are the rendering overhead of the solution (Edström §7.6:
//! about 10 % on his car exterior, 35 % on its interior): what the exported mesh draws
//! beyond the model.

use crate::scene::file::Bake;

use super::scene::RadiosityScene;

/// The most parts one side of a triangle is split into for vertex lighting (a triangle
/// becomes at most `MAX_SPLITS²` triangles).
pub const MAX_SPLITS: u32 = 32;

/// The default budget of introduced triangles: this share of the model's triangles
/// (Edström's car exterior drew about 10 % more than its model).
pub const DEFAULT_BUDGET_SHARE: f64 = 0.10;

/// How the representation of each surface is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
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
    /// Per triangle: into how many parts each side is split when vertex-lit (1: not split).
    pub splits: Vec<u32>,
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

/// Into how many parts each side of triangle `t` is split for vertex lighting: its
/// longest side in texels of its chart, rounded up (1 to [`MAX_SPLITS`]).
pub fn splits(scene: &RadiosityScene, t: usize) -> u32 {
    let te = &scene.elements.triangles[t];
    let Some(chart) = scene.elements.charts.get(te.chart as usize) else {
        return 1;
    };
    let p = scene.casters.triangles[t].map(|i| scene.casters.positions[i as usize]);
    let longest = (p[1] - p[0])
        .length()
        .max((p[2] - p[1]).length())
        .max((p[0] - p[2]).length());
    let texels = (longest / chart.texel_m.max(1e-12)).ceil();
    texels.clamp(1.0, MAX_SPLITS as f64) as u32
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
    let splits: Vec<u32> = (0..count).map(|t| splits(scene, t)).collect();
    let has_elements = |t: u32| scene.elements.triangles[t as usize].chart != u32::MAX;
    let tree = &scene.planar_clusters().tree;
    struct Surface {
        triangles: Vec<u32>,
        introduced: u64,
        fixed: Option<Bake>,
    }
    let mut surfaces: Vec<Surface> = tree
        .roots
        .iter()
        .map(|&root| {
            let triangles: Vec<u32> = tree
                .triangles(root)
                .iter()
                .copied()
                .filter(|&t| has_elements(t))
                .collect();
            let introduced = triangles
                .iter()
                .map(|&t| (splits[t as usize] as u64).pow(2) - 1)
                .sum();
            let fixed = match choice {
                BakeChoice::Map => Some(Bake::Map),
                BakeChoice::Vertex => Some(Bake::Vertex),
                BakeChoice::Auto => material_bake
                    .get(tree.nodes[root as usize].material)
                    .copied()
                    .flatten(),
            };
            Surface {
                triangles,
                introduced,
                fixed,
            }
        })
        .filter(|s| !s.triangles.is_empty())
        .collect();
    let modelled: usize = surfaces.iter().map(|s| s.triangles.len()).sum();
    let budget = budget.unwrap_or((DEFAULT_BUDGET_SHARE * modelled as f64).round() as u64);
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
    let (mut surface_count, mut triangle_count) = ([0; 2], [0; 2]);
    for (s, &b) in surfaces.iter_mut().zip(&chosen) {
        let slot = usize::from(b == Bake::Vertex);
        surface_count[slot] += 1;
        triangle_count[slot] += s.triangles.len();
        for &t in &s.triangles {
            bake[t as usize] = Some(b);
        }
    }
    BakePlan {
        bake,
        splits,
        surfaces: surface_count,
        triangles: triangle_count,
        introduced,
        budget,
    }
}
