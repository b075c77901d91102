//! What the solver works on: the scene's triangles as elements, their materials'
//! reflectance (`Kd`) and luminous exitance (`Ke`, lm/m²), and the luminaires.

use std::sync::Arc;

use glam::DVec3;

use super::clusters::PlanarClusters;
use super::elements::{
    ElementError, Elements, InputTriangle, NeverSplit, SplitTest, Subdivision, MAX_ATLAS,
    MAX_SENT_BACK, MAX_SUBDIVISION,
};
use super::shadow_edges::LuminaireShadowEdges;
use super::specular::SpecularSurfaces;
use super::Hierarchy;
use crate::daylight::glazing::Glazing;
use crate::daylight::points::{daylight_at_points, scene_glazing, DaylightAtPoint, Obstructions};
use crate::daylight::sky::Sky;
use crate::geometry::Mesh;
use crate::lighting::SurfacePoint;
use crate::scene::{PlacedLuminaire, Scene};
use crate::shadow::{Cutouts, IgnoredTriangles, TriangleBvh};

/// A scene prepared for radiosity.
#[derive(Debug, Clone)]
pub struct RadiosityScene {
    /// The elements and patches.
    pub elements: Elements,
    /// Diffuse reflectance per material (RGB, 0..1): `Kd` times the mean colour of its
    /// diffuse texture ([`crate::scene::Material::diffuse_reflectance`]).
    pub reflectance: Vec<DVec3>,
    /// Diffuse transmittance per material (RGB, 0..1; [`super::transmission`]).
    pub transmittance: Vec<DVec3>,
    /// Luminous exitance per material, lm/m² (RGB).
    pub emission: Vec<DVec3>,
    /// The luminaires.
    pub luminaires: Vec<PlacedLuminaire>,
    /// Per element, the normal it receives with ([`super::shading`]); empty when every
    /// element receives with its chart's normal.
    pub receiving_normals: Vec<DVec3>,
    /// Seconds spent on [`Self::receiving_normals`].
    pub receiving_seconds: f64,
    /// Every triangle as one mesh (occluders for the CPU's visibility rays).
    pub casters: Mesh,
    /// The ray-cast hierarchy over `casters`, built on first use.
    caster_bvh: std::sync::OnceLock<TriangleBvh>,
    /// The holes of `casters`' alpha-masked triangles.
    pub cutouts: Option<Arc<Cutouts>>,
    /// `casters` with CAD fans merged back, and its ray-cast hierarchy, built on first use.
    visibility: std::sync::OnceLock<VisibilityParts>,
    /// Seconds spent building the face clusters for the charts (0 without them).
    pub clustering_seconds: f64,
    /// CPU seconds (summed over threads) spent deciding adaptive subdivision's splits
    /// (0 without it).
    pub subdivision_seconds: f64,
    /// The planar face clusters of `casters`, built on first use.
    planar: std::sync::OnceLock<PlanarClusters>,
    /// Per luminaire, the caster triangles of its housing (they never shadow its light).
    pub ignored: Vec<IgnoredTriangles>,
    /// How far rays between surfaces start off them, metres
    /// ([`crate::shadow::raycast::self_hit_epsilon`] of `casters`).
    pub self_hit_epsilon: f64,
    /// The mirrors and clear glass ([`super::specular`]); only the CPU reference
    /// solver transfers light through them so far.
    pub specular: SpecularSurfaces,
    /// Total surface area, m².
    pub total_area: f64,
    /// The area-weighted mean of what a surface sends back out, reflectance plus
    /// transmittance (luminance), for the ambient term.
    pub mean_reflectance: f64,
    /// The scene's sky and the glazing of each of [`Self::casters`]' triangles, if the
    /// scene has daylight ([`crate::daylight`]).
    pub daylight: Option<(Sky, Vec<Option<Glazing>>)>,
}

/// The sky of `scene` and the glazing of its caster triangles, if it has daylight.
fn daylight_of(scene: &Scene) -> Option<(Sky, Vec<Option<Glazing>>)> {
    let d = scene.daylight.as_ref()?;
    Some((d.sky.clone(), scene_glazing(scene)))
}

/// The visibility mesh, its hierarchy, how many of its triangles are solid (they come
/// first) and the holes of the rest.
#[derive(Debug, Clone)]
struct VisibilityParts {
    mesh: Mesh,
    bvh: TriangleBvh,
    solid: usize,
    cutouts: Option<Arc<Cutouts>>,
}

impl RadiosityScene {
    /// Splits `scene` into elements of `1 / texel_density` metres with shooting patches of
    /// 2^`level` texels, every triangle its own chart.
    pub fn new(scene: &Scene, texel_density: f64, level: u32) -> Result<Self, ElementError> {
        Self::with_hierarchy(scene, texel_density, level, Hierarchy::None)
    }

    /// [`RadiosityScene::new`] with charts as `hierarchy` asks: with
    /// [`Hierarchy::Clusters`] each planar face cluster is one chart.
    pub fn with_hierarchy(
        scene: &Scene,
        texel_density: f64,
        level: u32,
        hierarchy: Hierarchy,
    ) -> Result<Self, ElementError> {
        Self::with_subdivision(scene, texel_density, level, hierarchy, Subdivision::NONE)
    }

    /// [`RadiosityScene::with_hierarchy`] with adaptive subdivision: elements of
    /// `1 / texel_density` metres are split (2^`subdivision.levels` times at most, the
    /// light map's texels being the finest elements) where a luminaire's shadow or beam
    /// edge crosses them ([`super::shadow_edges`]).
    pub fn with_subdivision(
        scene: &Scene,
        texel_density: f64,
        level: u32,
        hierarchy: Hierarchy,
        subdivision: Subdivision,
    ) -> Result<Self, ElementError> {
        if subdivision.levels > MAX_SUBDIVISION {
            return Err(ElementError::Subdivision(subdivision.levels));
        }
        check_absorbing(scene)?;
        // Translucent surfaces get back faces of their own (appended after the scene's).
        let twinned = super::transmission::with_back_faces(scene);
        let scene = &*twinned;
        let texel_m = 1.0 / texel_density / f64::from(subdivision.block());
        let mut triangles = Vec::with_capacity(scene.triangle_count());
        for m in &scene.meshes {
            for t in m.indices.chunks_exact(3) {
                triangles.push(InputTriangle {
                    corners: [0, 1, 2].map(|k| m.positions[t[k] as usize].as_dvec3()),
                    material: m.material,
                    texel_m,
                });
            }
        }
        let casters = scene.caster_mesh();
        let self_hit_epsilon = crate::shadow::raycast::self_hit_epsilon(&casters);
        let ignored = scene.ignored_per_luminaire();
        let cutouts = scene.caster_cutouts();
        let caster_bvh = std::sync::OnceLock::new();
        let edges = (subdivision.levels > 0).then(|| LuminaireShadowEdges {
            luminaires: &scene.luminaires,
            bvh: caster_bvh
                .get_or_init(|| TriangleBvh::new(&casters).with_cutouts(cutouts.clone())),
            ignored: &ignored,
            eps: self_hit_epsilon,
            subdivision,
            nanos: Default::default(),
        });
        let split: &dyn SplitTest = match &edges {
            Some(edges) => edges,
            None => &NeverSplit,
        };
        let planar = std::sync::OnceLock::new();
        let clustering = std::time::Instant::now();
        let mut clustering_seconds = 0.0;
        let elements = match hierarchy {
            Hierarchy::None => {
                let ids: Vec<u32> = (0..triangles.len() as u32).collect();
                Elements::build_subdivided(&triangles, &ids, level, subdivision, split)?
            }
            Hierarchy::Clusters => {
                if !(texel_m.is_finite() && texel_m > 0.0) {
                    return Err(ElementError::TexelSize(texel_m));
                }
                // The elements cover the area: refuse what cannot fit before clustering.
                let area: f64 = triangles
                    .iter()
                    .map(|t| {
                        let [a, b, c] = t.corners;
                        0.5 * (b - a).cross(c - a).length()
                    })
                    .sum();
                let texels = area / (texel_m * texel_m);
                if texels > (MAX_ATLAS as f64).powi(2) {
                    return Err(ElementError::TooLarge(texels.min(u64::MAX as f64) as u64));
                }
                let materials: Vec<usize> = triangles.iter().map(|t| t.material).collect();
                let clusters =
                    PlanarClusters::new(&casters, &materials, &vec![texel_m; triangles.len()]);
                clustering_seconds = clustering.elapsed().as_secs_f64();
                let elements = Elements::build_subdivided(
                    &triangles,
                    &clusters.cluster_of_triangle(),
                    level,
                    subdivision,
                    split,
                )?;
                let _ = planar.set(clusters);
                elements
            }
        };
        let subdivision_seconds = edges.as_ref().map_or(0.0, LuminaireShadowEdges::seconds);
        let specular = SpecularSurfaces::new(&casters, &scene.caster_materials(), &scene.materials);
        // What specular surfaces send on counts in the ambient term's mean reflectance.
        let specular_share: Vec<f64> = scene
            .materials
            .iter()
            .map(|m| luminance((m.specular_reflectance + m.specular_transmittance).as_dvec3()))
            .collect();
        let source = scene;
        let mut scene = RadiosityScene {
            elements,
            reflectance: scene
                .materials
                .iter()
                .map(|m| {
                    m.diffuse_reflectance()
                        .as_dvec3()
                        .clamp(DVec3::ZERO, DVec3::splat(0.999))
                })
                .collect(),
            transmittance: scene
                .materials
                .iter()
                .map(|m| {
                    m.diffuse_transmittance
                        .as_dvec3()
                        .clamp(DVec3::ZERO, DVec3::ONE)
                })
                .collect(),
            emission: scene
                .materials
                .iter()
                .map(|m| m.emission.as_dvec3().max(DVec3::ZERO))
                .collect(),
            luminaires: scene.luminaires.clone(),
            receiving_normals: Vec::new(),
            receiving_seconds: 0.0,
            casters,
            caster_bvh,
            cutouts,
            visibility: std::sync::OnceLock::new(),
            planar,
            clustering_seconds,
            subdivision_seconds,
            ignored,
            self_hit_epsilon,
            specular,
            total_area: 0.0,
            mean_reflectance: 0.0,
            daylight: daylight_of(source),
        };
        if let Some(cutouts) = &scene.cutouts {
            super::coverage::apply(&mut scene.elements, cutouts);
        }
        let shading = std::time::Instant::now();
        scene.receiving_normals = super::shading::receiving_normals(source, &scene.elements);
        scene.receiving_seconds = shading.elapsed().as_secs_f64();
        let e = &scene.elements;
        scene.total_area = e.area.iter().sum();
        let reflected: f64 = (0..e.len())
            .map(|k| {
                let share = specular_share[scene.element_material(k)];
                (luminance(scene.element_reemittance(k)) + share) * e.area[k]
            })
            .sum();
        scene.mean_reflectance = (reflected / scene.total_area.max(1e-300)).min(0.999);
        Ok(scene)
    }

    /// The direct daylight (sky, ground and sun through the openings and glazing) at
    /// `points`, each point's hemisphere in `cells`
    /// ([`crate::daylight::points::daylight_at_points`]); `None` without a sky.
    pub fn daylight_at(
        &self,
        points: &[SurfacePoint],
        cells: (usize, usize),
    ) -> Option<Vec<DaylightAtPoint>> {
        let (sky, glazing) = self.daylight.as_ref()?;
        let obstructions = Obstructions {
            mesh: &self.casters,
            bvh: self.caster_bvh(),
            glazing,
            eps: self.self_hit_epsilon,
        };
        Some(daylight_at_points(sky, Some(&obstructions), points, cells))
    }

    /// The luminaires' light through the mirrors and clear glass ([`super::specular`]).
    pub fn specular_light(&self) -> super::specular::SpecularLight<'_> {
        super::specular::SpecularLight::new(
            &self.specular,
            self.caster_bvh(),
            &self.luminaires,
            &self.ignored,
            self.self_hit_epsilon,
        )
    }

    /// The ray-cast hierarchy over [`Self::casters`] (built on the first call), with
    /// their holes.
    pub fn caster_bvh(&self) -> &TriangleBvh {
        self.caster_bvh
            .get_or_init(|| TriangleBvh::new(&self.casters).with_cutouts(self.cutouts.clone()))
    }

    /// What blocks light between surfaces: [`Self::casters`] with CAD fans merged back
    /// into the triangles they fill ([`crate::geometry::simplify::merge_strips`]: the same
    /// points, far fewer and better-shaped triangles), then the alpha-masked triangles
    /// as they are (after [`Self::visibility_solid_count`] triangles), built on the first
    /// call. The GPU's visibility maps draw it; rays between surfaces are cast against it.
    /// Its triangles are not the casters' (a luminaire's ignored housing needs
    /// [`Self::caster_bvh`]).
    pub fn visibility_mesh(&self) -> &Mesh {
        &self.visibility_parts().mesh
    }

    /// The ray-cast hierarchy over [`Self::visibility_mesh`], with its holes.
    pub fn visibility_bvh(&self) -> &TriangleBvh {
        &self.visibility_parts().bvh
    }

    /// How many of [`Self::visibility_mesh`]'s triangles come first and are solid; the
    /// rest have holes ([`Self::visibility_cutouts`]).
    pub fn visibility_solid_count(&self) -> usize {
        self.visibility_parts().solid
    }

    /// Whether some of [`Self::visibility_mesh`]'s triangles have holes.
    pub fn has_masked_casters(&self) -> bool {
        self.visibility_solid_count() < self.visibility_mesh().triangles.len()
    }

    /// The holes of [`Self::visibility_mesh`]'s alpha-masked triangles.
    pub fn visibility_cutouts(&self) -> Option<&Arc<Cutouts>> {
        self.visibility_parts().cutouts.as_ref()
    }

    fn visibility_parts(&self) -> &VisibilityParts {
        self.visibility.get_or_init(|| {
            let size = self
                .casters
                .bounds()
                .map_or(1.0, |(lo, hi)| (hi - lo).length());
            let cut = self.cutouts.as_deref();
            let masked: Vec<usize> = (0..self.casters.triangles.len())
                .filter(|&k| cut.is_some_and(|c| c.mask_of(k).is_some()))
                .collect();
            // Without masks the casters are merged as they are (no copy).
            let solid_part = if masked.is_empty() {
                std::borrow::Cow::Borrowed(&self.casters)
            } else {
                let is_masked = |k: usize| masked.binary_search(&k).is_ok();
                std::borrow::Cow::Owned(Mesh {
                    positions: self.casters.positions.clone(),
                    triangles: (0..self.casters.triangles.len())
                        .filter(|&k| !is_masked(k))
                        .map(|k| self.casters.triangles[k])
                        .collect(),
                })
            };
            let mut mesh = crate::geometry::simplify::merge_strips(&solid_part, 1e-6 * size);
            let solid = mesh.triangles.len();
            for &k in &masked {
                let base = mesh.positions.len() as u32;
                let corners = self.casters.triangles[k].map(|i| self.casters.positions[i as usize]);
                mesh.positions.extend(corners);
                mesh.triangles.push([base, base + 1, base + 2]);
            }
            let cutouts = cut.filter(|_| !masked.is_empty()).map(|c| {
                let source = (0..solid)
                    .map(|_| None)
                    .chain(masked.iter().map(|&k| Some(k)));
                Arc::new(c.remapped(source))
            });
            let bvh = TriangleBvh::new(&mesh).with_cutouts(cutouts.clone());
            VisibilityParts {
                mesh,
                bvh,
                solid,
                cutouts,
            }
        })
    }

    /// The planar face clusters of [`Self::casters`] (built on the first call unless the
    /// charts came from them).
    pub fn planar_clusters(&self) -> &PlanarClusters {
        self.planar.get_or_init(|| {
            let el = &self.elements;
            let materials: Vec<usize> = el.triangles.iter().map(|t| t.material).collect();
            let texel: Vec<f64> = el
                .triangles
                .iter()
                .map(|t| el.charts.get(t.chart as usize).map_or(0.0, |c| c.texel_m))
                .collect();
            PlanarClusters::new(&self.casters, &materials, &texel)
        })
    }

    /// The connected surfaces of one material (each a root of the face-cluster hierarchy),
    /// each's triangles ascending: from the hierarchy when it is built, else from the mesh's
    /// dual graph alone (`--hierarchy none` needs no clustering for them).
    pub fn surfaces(&self) -> Vec<Vec<u32>> {
        match self.planar.get() {
            Some(planar) => planar.tree.root_surfaces(),
            None => {
                let materials: Vec<usize> =
                    self.elements.triangles.iter().map(|t| t.material).collect();
                super::clusters::connected_surfaces(&self.casters, &materials)
            }
        }
    }

    /// The normal element `e` receives with: its chart's, or where the mesh is curved or
    /// normal-mapped the mean of its shading normals ([`super::shading`]).
    pub fn element_receiving_normal(&self, e: usize) -> DVec3 {
        self.receiving_normals
            .get(e)
            .copied()
            .unwrap_or_else(|| self.elements.normal(e))
    }

    /// The form factor element `e` at `p` takes from a source `to_source` away, where
    /// `form_factor(n)` gives it for a receiver with unit normal `n`
    /// ([`super::shading::receiving`]).
    pub fn element_receives(
        &self,
        e: usize,
        to_source: DVec3,
        form_factor: impl Fn(DVec3) -> f64,
    ) -> f64 {
        super::shading::receiving(
            self.elements.normal(e),
            self.element_receiving_normal(e),
            to_source,
            form_factor,
        )
    }

    /// Reflectance of element `e`.
    pub fn element_reflectance(&self, e: usize) -> DVec3 {
        self.reflectance[self.element_material(e)]
    }

    /// Diffuse transmittance of element `e`: the share of what arrives on its back that
    /// it emits ([`super::transmission`]; zero for an opaque surface).
    pub fn element_transmittance(&self, e: usize) -> DVec3 {
        self.transmittance[self.element_material(e)]
    }

    /// What element `e` sends back out of what arrives on both its sides: reflectance
    /// plus transmittance (light arriving everywhere, as the ambient term's does).
    pub fn element_reemittance(&self, e: usize) -> DVec3 {
        self.element_reflectance(e) + self.element_transmittance(e)
    }

    /// Exitance of element `e`, lm/m².
    pub fn element_emission(&self, e: usize) -> DVec3 {
        self.emission[self.element_material(e)]
    }

    fn element_material(&self, e: usize) -> usize {
        self.elements.charts[self.elements.chart[e] as usize].material
    }
}

/// Rec. 709 luminance of an RGB value.
pub fn luminance(c: DVec3) -> f64 {
    c.dot(crate::scene::placement::LUMINANCE_WEIGHTS)
}

/// An error when no surface of the scene absorbs (reflectance plus transmittance above
/// [`MAX_SENT_BACK`] in some channel on every triangle): in a closed room its light
/// never ends, and the solver would shoot forever. One lossless surface among absorbing
/// ones (an ideal mirror or pane) converges and is accepted.
fn check_absorbing(scene: &Scene) -> Result<(), ElementError> {
    let mut lossless = None;
    for m in scene.meshes.iter().filter(|m| !m.indices.is_empty()) {
        let Some(mat) = scene.materials.get(m.material) else {
            continue;
        };
        let sum = (mat.diffuse_reflectance()
            + mat.diffuse_transmittance
            + mat.specular_reflectance
            + mat.specular_transmittance)
            .max_element();
        if sum <= MAX_SENT_BACK {
            return Ok(());
        }
        lossless.get_or_insert((mat.name.clone(), sum));
    }
    match lossless {
        Some((name, sum)) => Err(ElementError::Lossless { name, sum }),
        None => Ok(()),
    }
}
