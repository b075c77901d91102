//! Scenes: the TOML scene file, OBJ/MTL models (tobj) with their textures (image),
//! luminaires placed in the world, and the camera. See [`mod@file`] for the format.
//!
//! Frames: the world is right-handed with +Z up (metres). A luminaire's own frame has
//! γ = 0 along −Z and C0 along +X; [`PlacedLuminaire::rotation`] maps it to the world.

pub mod alpha;
pub mod area;
pub mod back_faces;
pub mod bump;
pub mod camera;
pub mod daylight;
pub mod display;
pub mod emergency;
pub mod file;
pub mod gltf_model;
pub mod grid;
pub mod materials;
pub mod model;
pub mod observer;
pub mod palette;
pub mod placement;
pub mod planning;
pub mod requirement;
pub mod save;

use std::path::{Path, PathBuf};

use glam::DVec3;

pub use camera::{Camera, Projection};
pub use file::{DisplayEntry, DisplayIndirect, Mode, SceneFile, Tonemap, UpAxis, MAX_IMAGE_SIZE};
pub use model::{Material, SceneMesh};
pub use observer::Observer;
pub use palette::Palette;
pub use placement::{Housing, PlacedLuminaire};

/// A problem with a scene: the file, the key (`luminaire[2].position`, `model[0].path`, or
/// `line 7` for syntax errors) and what is wrong.
#[derive(Debug, thiserror::Error)]
#[error("{file}: {key}: {message}")]
pub struct SceneError {
    /// The scene file (or the model/texture file the key points to).
    pub file: String,
    /// Where in it.
    pub key: String,
    /// What is wrong.
    pub message: String,
}

impl SceneError {
    /// An error at `key` of `file`.
    pub fn new(file: &Path, key: impl Into<String>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: file.display().to_string(),
            key: key.into(),
            message: message.into(),
        }
    }
}

/// A loaded scene, in world coordinates.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The scene file (empty for scenes built in code).
    pub path: PathBuf,
    /// Triangle meshes, one per OBJ object, with a material each.
    pub meshes: Vec<SceneMesh>,
    /// Materials; index 0 is the default (matte grey) for faces without one.
    pub materials: Vec<Material>,
    /// Light sources.
    pub luminaires: Vec<PlacedLuminaire>,
    /// The view.
    pub camera: Camera,
    /// Display settings as written in the file.
    pub display: DisplayEntry,
    /// The `[[model]]` entries, their paths resolved against the scene file's folder
    /// (what [`Scene::save`] writes back).
    pub models: Vec<file::ModelEntry>,
    /// Calculation surfaces, with their points (virtual: no geometry): the `[[grid]]`s,
    /// then the grids of the `[[area]]`s.
    pub grids: Vec<grid::CalcGrid>,
    /// EN 12464-1 areas with their requirements (`[[area]]`); their grids are in `grids`.
    pub areas: Vec<area::Area>,
    /// EN 1838 emergency areas (`[[emergency]]`), resolved; their grids are computed in
    /// the scene's emergency mode only ([`Scene::in_emergency`]).
    pub emergency: Vec<emergency::EmergencyPlan>,
    /// `[calc]` settings.
    pub calc: grid::CalcSettings,
    /// Observers rated for glare (`[[observer]]`).
    pub observers: Vec<Observer>,
    /// The sky and sun of `[site]` and `[sky]`, if the scene has daylight.
    pub daylight: Option<daylight::SceneDaylight>,
    /// `[site]`: where the building is (the sun's positions, the plans' north).
    pub site: Option<daylight::SiteEntry>,
    /// The planning tests' `[[window]]`s and `[[open_space]]`s.
    pub planning: planning::PlanningPlaces,
    /// The `[[material]]` overrides as written (already applied to `materials`).
    pub material_overrides: Vec<file::MaterialEntry>,
    /// What loading worked around rather than refused (a model's missing MTL file, its
    /// triangles without area, a transmittance capped at what a material does not
    /// reflect): the front ends show them (the command line on stderr, Python as
    /// `UserWarning`s).
    pub warnings: Vec<String>,
}

/// Resolves the `[[table]]` entries (`what`: the table's name in keys and messages) one by
/// one with `resolve(entry, index)`; their names (`name_of`) must differ, ignoring case and
/// surrounding blanks, since each names an output.
fn resolve_named<E, T>(
    path: &Path,
    entries: &[E],
    what: &str,
    name_of: impl Fn(&E) -> &str,
    resolve: impl Fn(&E, usize) -> Result<T, SceneError>,
) -> Result<Vec<T>, SceneError> {
    let mut seen = std::collections::HashSet::new();
    entries
        .iter()
        .enumerate()
        .map(|(i, e)| {
            if !seen.insert(name_of(e).trim().to_lowercase()) {
                return Err(SceneError::new(
                    path,
                    format!("{what}[{i}].name"),
                    format!(
                        "{:?} names an earlier {what} too; give each {what} its own name",
                        name_of(e)
                    ),
                ));
            }
            resolve(e, i)
        })
        .collect()
}

/// The `[[grid]]` entries with their points; names must differ (each names a CSV file).
fn resolve_grids(
    path: &Path,
    entries: &[grid::GridEntry],
) -> Result<Vec<grid::CalcGrid>, SceneError> {
    resolve_named(
        path,
        entries,
        "grid",
        |e| &e.name,
        |e, i| {
            e.resolve()
                .map_err(|(key, msg)| SceneError::new(path, format!("grid[{i}].{key}"), msg))
        },
    )
}

/// The `[[window]]` and `[[open_space]]` entries; names must differ within each (each
/// names a row of the planning tests).
fn resolve_planning(
    path: &Path,
    windows: &[planning::WindowEntry],
    open_spaces: &[planning::OpenSpaceEntry],
) -> Result<planning::PlanningPlaces, SceneError> {
    let windows = resolve_named(
        path,
        windows,
        "window",
        |e| &e.name,
        |e, i| {
            e.resolve()
                .map_err(|(key, msg)| SceneError::new(path, format!("window[{i}].{key}"), msg))
        },
    )?;
    let open_spaces = resolve_named(
        path,
        open_spaces,
        "open_space",
        |e| &e.name,
        |e, i| {
            e.resolve()
                .map_err(|(key, msg)| SceneError::new(path, format!("open_space[{i}].{key}"), msg))
        },
    )?;
    Ok(planning::PlanningPlaces {
        windows,
        open_spaces,
    })
}

/// The `[[area]]` entries: each area's grids appended to `grids` (names must differ
/// from every grid's), its requirements; a background that the surrounding leaves no
/// room for is left out with a warning.
fn resolve_areas(
    path: &Path,
    entries: &[area::AreaEntry],
    models: &area::ModelExtent,
    grids: &mut Vec<grid::CalcGrid>,
    warnings: &mut Vec<String>,
) -> Result<Vec<area::Area>, SceneError> {
    let resolved = resolve_named(
        path,
        entries,
        "area",
        |e| &e.name,
        |e, i| {
            e.resolve(models)
                .map_err(|(key, msg)| SceneError::new(path, format!("area[{i}].{key}"), msg))
        },
    )?;
    let mut names: std::collections::HashSet<String> = grids
        .iter()
        .map(|g| g.entry.name.trim().to_lowercase())
        .collect();
    let mut areas = Vec::with_capacity(entries.len());
    for (i, (entry, plan)) in entries.iter().zip(resolved).enumerate() {
        let area::AreaPlan {
            outline,
            grids: parts,
            mut requirements,
        } = plan;
        let mut indices = Vec::new();
        for (part, g) in parts {
            if !names.insert(g.name.trim().to_lowercase()) {
                return Err(SceneError::new(
                    path,
                    format!("area[{i}].name"),
                    format!(
                        "its grid {:?} has the name of another grid; rename the area",
                        g.name
                    ),
                ));
            }
            match g.resolve() {
                Ok(resolved) => {
                    indices.push((part, grids.len()));
                    grids.push(resolved);
                }
                Err((key, _)) if part == area::AreaPart::Background && key == "border" => {
                    requirements.retain(|r| r.part != part);
                    warnings.push(format!(
                        "area {:?}: its immediate surrounding leaves no background in the room",
                        entry.name
                    ));
                }
                Err((key, msg)) => {
                    return Err(SceneError::new(
                        path,
                        format!("area[{i}] ({}).{key}", g.name),
                        msg,
                    ))
                }
            }
        }
        areas.push(area::Area {
            entry: entry.clone(),
            standard: area::Standard::En12464,
            outline,
            grids: indices,
            requirements,
        });
    }
    Ok(areas)
}

/// An area's UGR limit needs observers, and the observers it names must exist.
fn check_area_observers(
    path: &Path,
    areas: &[area::Area],
    observers: &[Observer],
) -> Result<(), SceneError> {
    for (i, a) in areas.iter().enumerate() {
        if a.entry.ugr_l.is_some() && observers.is_empty() {
            return Err(SceneError::new(
                path,
                format!("area[{i}].ugr_l"),
                "UGR is rated at an eye: add an [[observer]] looking across the area",
            ));
        }
        for name in a.entry.observers.iter().flatten() {
            if !observers.iter().any(|o| o.entry.name.trim() == name.trim()) {
                return Err(SceneError::new(
                    path,
                    format!("area[{i}].observers"),
                    format!("{name:?} names no [[observer]]"),
                ));
            }
        }
    }
    Ok(())
}

/// The models' extent in plan (a rectangle) and their top, if there are models.
fn model_extent(meshes: &[SceneMesh]) -> area::ModelExtent {
    let (lo, hi) = meshes.iter().flat_map(|m| m.positions.iter()).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p.as_dvec3()), hi.max(p.as_dvec3())),
    );
    if !(lo.x < hi.x && lo.y < hi.y) {
        return area::ModelExtent::default();
    }
    area::ModelExtent {
        outline: Some(crate::geometry::polygon::rectangle(
            [lo.x, lo.y],
            [hi.x - lo.x, hi.y - lo.y],
        )),
        top: Some(hi.z),
    }
}

/// The `[[observer]]` entries, resolved; names must differ (each names a row of the
/// report).
fn resolve_observers(
    path: &Path,
    entries: &[observer::ObserverEntry],
) -> Result<Vec<Observer>, SceneError> {
    resolve_named(
        path,
        entries,
        "observer",
        |e| &e.name,
        |e, i| e.resolve(path, i),
    )
}

/// Most luminaires one scene may hold (a stadium has a few hundred; the limit keeps a
/// mistaken file from taking the machine).
pub const MAX_LUMINAIRES: usize = 10_000;

impl Scene {
    /// The files the scene was read from: the scene file, its models (with the MTL files
    /// beside them that they name) and its luminaires — what no output may replace.
    pub fn input_files(&self) -> Vec<PathBuf> {
        let mut files = Vec::new();
        if !self.path.as_os_str().is_empty() {
            files.push(self.path.clone());
        }
        for m in &self.models {
            let obj = PathBuf::from(&m.path);
            files.extend(crate::geometry::obj::material_libraries(&obj));
            files.push(obj);
        }
        files.extend(self.luminaires.iter().map(|l| l.file.clone()));
        files.sort();
        files.dedup();
        files
    }

    /// Reads a scene file and everything it refers to.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let bytes = crate::io::read_limited(path, crate::io::MAX_MODEL_BYTES)
            .map_err(|e| SceneError::new(path, "file", e.to_string()))?;
        let text = String::from_utf8(bytes)
            .map_err(|e| SceneError::new(path, "file", format!("not UTF-8 text: {e}")))?;
        Scene::from_toml(path, &text)
    }

    /// Parses scene text; relative paths are resolved against `path`'s folder.
    pub fn from_toml(path: &Path, text: &str) -> Result<Scene, SceneError> {
        let parsed: SceneFile = toml::from_str(text).map_err(|e| toml_error(path, text, &e))?;
        Scene::from_file(path, parsed)
    }

    /// A scene from a JSON value with the scene file's keys (`{"model": [{"path": …}],
    /// "luminaire": [...]}`: what Python's `Scene.from_dict` passes); relative paths are
    /// resolved against `path`'s folder, which names the scene in messages.
    pub fn from_json(path: &Path, value: serde_json::Value) -> Result<Scene, SceneError> {
        let parsed: SceneFile = serde_json::from_value(value)
            .map_err(|e| SceneError::new(path, "scene", e.to_string()))?;
        Scene::from_file(path, parsed)
    }

    /// The scene a parsed scene file describes (`path`: where it is, for relative paths).
    fn from_file(path: &Path, parsed: SceneFile) -> Result<Scene, SceneError> {
        let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
        let mut materials = vec![Material::default()];
        let (mut meshes, mut warnings) = (Vec::new(), Vec::new());
        let mut model_lights = Vec::new();
        for (i, entry) in parsed.model.iter().enumerate() {
            let key = format!("model[{i}]");
            let file = model::checked_entry(path, &key, &dir, entry)?;
            let sinks = (&mut materials, &mut warnings);
            if crate::geometry::gltf_file::is_gltf(&file) {
                let content = gltf_model::load(path, &key, &file, entry, sinks)?;
                meshes.extend(content.meshes);
                model_lights.extend(content.lights);
            } else {
                meshes.extend(model::load_obj(path, &key, &file, entry, sinks)?);
            }
        }
        materials::apply(&parsed.material, &mut materials)
            .map_err(|(key, message)| SceneError::new(path, key, message))?;
        if parsed.luminaire.len() + model_lights.len() > MAX_LUMINAIRES {
            return Err(SceneError::new(
                path,
                "luminaire",
                format!(
                    "{} luminaires (the models' lights counted); goniolight places at most {MAX_LUMINAIRES} in one scene",
                    parsed.luminaire.len() + model_lights.len()
                ),
            ));
        }
        let mut loaded = std::collections::HashMap::new();
        let luminaires = parsed
            .luminaire
            .iter()
            .enumerate()
            .map(|(i, entry)| {
                PlacedLuminaire::from_entry(
                    path,
                    &format!("luminaire[{i}]"),
                    &dir,
                    entry,
                    &mut loaded,
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut luminaires = luminaires;
        luminaires.extend(model_lights);
        for (i, l) in luminaires.iter_mut().enumerate() {
            if let Some(h) = &mut l.housing {
                h.meshes = find_housing(
                    path,
                    &format!("luminaire[{i}].housing"),
                    &meshes,
                    &h.name,
                    l.position,
                )?;
            }
        }
        let bounds = bounds_of(&meshes, &luminaires);
        let camera = match &parsed.camera {
            Some(entry) => Camera::from_entry(path, entry, bounds)?,
            None => Camera::framing(bounds, &luminaires),
        };
        check_display(path, &parsed.display)?;
        let mut grids = resolve_grids(path, &parsed.grid)?;
        let extent = model_extent(&meshes);
        let areas = resolve_areas(path, &parsed.area, &extent, &mut grids, &mut warnings)?;
        let calc = parsed.calc.unwrap_or_default();
        grid::CalcSettings::check(calc.maintenance_factor)
            .map_err(|m| SceneError::new(path, "calc.maintenance_factor", m))?;
        let observers = resolve_observers(path, &parsed.observer)?;
        let emergency = resolve_named(
            path,
            &parsed.emergency,
            "emergency",
            |e| &e.name,
            |e, i| {
                e.resolve().map_err(|(key, msg)| {
                    SceneError::new(path, format!("emergency[{i}].{key}"), msg)
                })
            },
        )?;
        check_area_observers(path, &areas, &observers)?;
        let daylight = daylight::resolve(path, parsed.site.as_ref(), parsed.sky.as_ref())?;
        let planning = resolve_planning(path, &parsed.window, &parsed.open_space)?;
        Ok(Scene {
            path: path.to_path_buf(),
            meshes,
            materials,
            luminaires,
            camera,
            display: parsed.display,
            models: parsed
                .model
                .iter()
                .map(|m| file::ModelEntry {
                    path: dir.join(&m.path).to_string_lossy().into_owned(),
                    ..m.clone()
                })
                .collect(),
            grids,
            areas,
            emergency,
            calc,
            observers,
            daylight,
            site: parsed.site,
            planning,
            material_overrides: parsed.material,
            warnings,
        })
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.indices.len() / 3).sum()
    }

    /// The area of all its triangles, m² (one side each).
    pub fn surface_area(&self) -> f64 {
        self.meshes
            .iter()
            .flat_map(|m| {
                m.indices.chunks_exact(3).map(|t| {
                    let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.positions[i as usize].as_dvec3());
                    (b - a).cross(c - a).length() / 2.0
                })
            })
            .sum()
    }

    /// A scene made in code (tests, benchmarks): `meshes` with `materials` under
    /// `luminaires`, seen by `camera`, with the default display and no models, grids,
    /// observers or material overrides. `name` stands for the file in messages.
    pub fn in_code(
        name: &str,
        meshes: Vec<SceneMesh>,
        materials: Vec<Material>,
        luminaires: Vec<PlacedLuminaire>,
        camera: Camera,
    ) -> Scene {
        Scene {
            path: PathBuf::from(name),
            meshes,
            materials,
            luminaires,
            camera,
            display: DisplayEntry::default(),
            models: Vec::new(),
            grids: Vec::new(),
            calc: Default::default(),
            areas: Vec::new(),
            emergency: Vec::new(),
            observers: Vec::new(),
            daylight: None,
            site: None,
            planning: Default::default(),
            material_overrides: Vec::new(),
            warnings: Vec::new(),
        }
    }

    /// Every triangle of the scene as one mesh: what casts shadows.
    pub fn caster_mesh(&self) -> crate::geometry::Mesh {
        let mut mesh = crate::geometry::Mesh::default();
        for m in &self.meshes {
            let base = mesh.positions.len() as u32;
            mesh.positions
                .extend(m.positions.iter().map(|p| p.as_dvec3()));
            mesh.triangles.extend(
                m.indices
                    .chunks_exact(3)
                    .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
            );
        }
        mesh
    }

    /// The object (index into [`Scene::meshes`]) of each triangle of
    /// [`Scene::caster_mesh`], in its order.
    pub fn caster_objects(&self) -> Vec<u32> {
        self.meshes
            .iter()
            .enumerate()
            .flat_map(|(k, m)| std::iter::repeat_n(k as u32, m.indices.len() / 3))
            .collect()
    }

    /// The first mirror or clear glass among the materials its meshes use, if any
    /// ([`Material::is_specular`]).
    pub fn specular_material(&self) -> Option<&Material> {
        self.meshes
            .iter()
            .map(|m| &self.materials[m.material])
            .find(|m| m.is_specular())
    }

    /// The material of each triangle of [`Scene::caster_mesh`], in its order.
    pub fn caster_materials(&self) -> Vec<usize> {
        self.meshes
            .iter()
            .flat_map(|m| std::iter::repeat_n(m.material, m.indices.len() / 3))
            .collect()
    }

    /// The holes of [`Scene::caster_mesh`]'s alpha-masked triangles, in its order; `None`
    /// when no material has an alpha mask.
    pub fn caster_cutouts(&self) -> Option<std::sync::Arc<crate::shadow::Cutouts>> {
        let masked: Vec<_> = self
            .materials
            .iter()
            .map(|m| m.alpha_mask.clone())
            .collect();
        if masked.iter().all(Option::is_none) {
            return None;
        }
        let masks: Vec<_> = masked.iter().flatten().cloned().collect();
        let mut slot = Vec::with_capacity(masked.len());
        let mut next = 0u32;
        for m in &masked {
            slot.push(m.as_ref().map(|_| {
                next += 1;
                next - 1
            }));
        }
        let mut triangles = Vec::with_capacity(self.triangle_count());
        for m in &self.meshes {
            let mask = slot.get(m.material).copied().flatten();
            triangles.extend(m.indices.chunks_exact(3).map(|t| {
                mask.map(|k| {
                    (
                        k,
                        [0, 1, 2].map(|c| m.uvs.get(t[c] as usize).copied().unwrap_or_default()),
                    )
                })
            }));
        }
        Some(std::sync::Arc::new(crate::shadow::Cutouts::new(
            triangles, masks,
        )))
    }

    /// The triangles of [`Scene::caster_mesh`] that luminaire `l` ignores: its housing.
    /// Nothing when the luminaire has been moved away from it (the viewer moves
    /// luminaires, not model objects): then the object is other geometry.
    pub fn ignored_by(&self, l: &PlacedLuminaire) -> crate::shadow::IgnoredTriangles {
        let Some(h) = self.housing_in_reach(l) else {
            return Default::default();
        };
        let mut first = Vec::with_capacity(self.meshes.len() + 1);
        let mut at = 0;
        for m in &self.meshes {
            first.push(at);
            at += m.indices.len() / 3;
        }
        first.push(at);
        crate::shadow::IgnoredTriangles(
            h.meshes
                .iter()
                .filter(|&&m| m < self.meshes.len())
                .map(|&m| first[m]..first[m + 1])
                .collect(),
        )
    }

    /// The luminaire's housing if every one of its objects still comes within
    /// [`file::HOUSING_REACH_M`] of its photometric centre.
    pub fn housing_in_reach<'a>(&self, l: &'a PlacedLuminaire) -> Option<&'a Housing> {
        let h = l.housing.as_ref()?;
        let near = |&m: &usize| {
            self.meshes.get(m).is_some_and(|mesh| {
                gap_to(std::slice::from_ref(mesh), l.position) <= file::HOUSING_REACH_M
            })
        };
        (!h.meshes.is_empty() && h.meshes.iter().all(near)).then_some(h)
    }

    /// [`Scene::ignored_by`] for every luminaire, in order.
    pub fn ignored_per_luminaire(&self) -> Vec<crate::shadow::IgnoredTriangles> {
        self.luminaires.iter().map(|l| self.ignored_by(l)).collect()
    }

    /// The scene `t_s` seconds on: effect lights turned by their spin.
    pub fn at_time(&self, t_s: f64) -> Scene {
        Scene {
            luminaires: self.luminaires.iter().map(|l| l.at_time(t_s)).collect(),
            ..self.clone()
        }
    }

    /// Whether any luminaire moves with time.
    pub fn is_animated(&self) -> bool {
        self.luminaires.iter().any(|l| l.spin_deg_per_s != 0.0)
    }

    /// Bounds of the geometry and the luminaires.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        bounds_of(&self.meshes, &self.luminaires)
    }
}

/// The meshes named `name` whose bounds come within [`file::HOUSING_REACH_M`] of
/// `position` (a luminaire's housing); an error naming `key` when there is none.
fn find_housing(
    path: &Path,
    key: &str,
    meshes: &[SceneMesh],
    name: &str,
    position: DVec3,
) -> Result<Vec<usize>, SceneError> {
    let reach = file::HOUSING_REACH_M;
    let mut nearest = f64::INFINITY;
    let mut found = Vec::new();
    for (k, m) in meshes.iter().enumerate().filter(|(_, m)| m.name == name) {
        let gap = gap_to(std::slice::from_ref(m), position);
        nearest = nearest.min(gap);
        if gap <= reach {
            found.push(k);
        }
    }
    if found.is_empty() {
        let message = if nearest.is_finite() {
            format!(
                "the nearest object named {name:?} is {nearest:.3} m from the luminaire; a housing must come within {reach} m of its photometric centre"
            )
        } else {
            format!("no model object is named {name:?}")
        };
        return Err(SceneError::new(path, key, message));
    }
    Ok(found)
}

/// Distance from `p` to the bounding box of `meshes` (0 inside).
fn gap_to(meshes: &[SceneMesh], p: DVec3) -> f64 {
    let (lo, hi) = bounds_of(meshes, &[]);
    (lo - p).max(p - hi).max(DVec3::ZERO).length()
}

fn bounds_of(meshes: &[SceneMesh], luminaires: &[PlacedLuminaire]) -> (DVec3, DVec3) {
    let points = meshes
        .iter()
        .flat_map(|m| m.positions.iter().map(|p| p.as_dvec3()))
        .chain(luminaires.iter().map(|l| l.position));
    let (lo, hi) = points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    if lo.x > hi.x {
        (DVec3::ZERO, DVec3::ZERO)
    } else {
        (lo, hi)
    }
}

fn check_display(path: &Path, d: &DisplayEntry) -> Result<(), SceneError> {
    d.check()
        .map_err(|e| SceneError::new(path, e.field, format!("{} {}", e.value, e.problem)))
}

/// `v` as a vector if every component is finite.
pub(crate) fn finite_vec(path: &Path, key: &str, v: [f64; 3]) -> Result<DVec3, SceneError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(DVec3::from_array(v))
    } else {
        Err(SceneError::new(
            path,
            key,
            format!("{v:?} has a component that is not a finite number"),
        ))
    }
}

/// A TOML error with its line and, where the line has one, the key it is about.
fn toml_error(path: &Path, text: &str, e: &toml::de::Error) -> SceneError {
    let message = e.message().trim().to_string();
    let Some(span) = e.span() else {
        return SceneError::new(path, "toml", message);
    };
    let line_no = text[..span.start.min(text.len())].matches('\n').count() + 1;
    let line = text.lines().nth(line_no - 1).unwrap_or("");
    let table = text
        .lines()
        .take(line_no)
        .filter_map(|l| {
            let t = l.trim();
            t.starts_with('[')
                .then(|| t.trim_matches(['[', ']']).to_string())
        })
        .last();
    let missing = message
        .strip_prefix("missing field `")
        .and_then(|m| m.split('`').next());
    if let Some(field) = missing {
        // The span is the table that lacks the field.
        let header = line.trim();
        // A field missing from the top level has an empty span at the file's start.
        let top_level = span.is_empty() && span.start == 0;
        let key = if header.starts_with('[') && !top_level {
            format!("{}.{field}", header.trim_matches(['[', ']']))
        } else {
            field.to_string()
        };
        return SceneError::new(path, key, message);
    }
    let key = match line.split_once('=') {
        Some((k, _)) if !line.trim_start().starts_with('[') => {
            let k = k.trim();
            match &table {
                Some(t) => format!("line {line_no}: {t}.{k}"),
                None => format!("line {line_no}: {k}"),
            }
        }
        _ => format!("line {line_no}"),
    };
    SceneError::new(path, key, message)
}
