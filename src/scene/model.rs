//! OBJ models with MTL materials (via tobj) and their textures (via image), converted to
//! the world frame (+Z up) with the model's transform applied.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DMat3, DMat4, DVec3, Vec2, Vec3};

use super::file::{ModelEntry, Scale, UpAxis};
use super::{finite_vec, SceneError};
use crate::geometry::obj::{self as obj_file, MtlError, ObjFile, ReadOptions};

/// A surface material (MTL subset).
#[derive(Debug, Clone)]
pub struct Material {
    /// Its name in the MTL file.
    pub name: String,
    /// `Kd`: diffuse reflectance (linear RGB).
    pub diffuse: Vec3,
    /// `Ks`: specular reflectance.
    pub specular: Vec3,
    /// `Ns`: Blinn-Phong exponent.
    pub shininess: f32,
    /// `Ke`: luminous exitance, lm/m² (for the radiosity solver).
    pub emission: Vec3,
    /// `map_Kd`: diffuse colour texture (sRGB), multiplied with `Kd`; its alpha (with
    /// MTL `map_d` folded in) cuts holes ([`super::alpha`]). Set it with
    /// [`Material::set_diffuse_map`], which keeps [`Material::alpha_mask`] in step.
    pub diffuse_map: Option<Arc<image::RgbaImage>>,
    /// The holes of `diffuse_map`'s alpha, `None` where it has none.
    pub alpha_mask: Option<Arc<super::alpha::AlphaMask>>,
    /// `map_Bump` / `bump` / `norm`: tangent-space normal map.
    pub normal_map: Option<Arc<image::RgbaImage>>,
    /// How radiosity export bakes its surfaces, as the scene file says (`None`: chosen
    /// per surface).
    pub bake: Option<super::file::Bake>,
    /// Diffuse transmittance (linear RGB): the share of the light arriving on one side
    /// that the other side emits diffusely (MTL `d`/`Tr` with `Tf`, or `[[material]]`;
    /// [`super::materials`]).
    pub diffuse_transmittance: Vec3,
    /// Specular reflectance (linear RGB): a mirror, reflecting on the side its normal
    /// faces, or on both sides of clear glass (`[[material]]` `specular_reflectance`;
    /// [`crate::lighting::specular`]).
    pub specular_reflectance: Vec3,
    /// Specular transmittance (linear RGB): clear glass, light passing undeviated
    /// (`[[material]]` `specular_transmittance`).
    pub specular_transmittance: Vec3,
}

impl Default for Material {
    fn default() -> Material {
        Material {
            name: "default".into(),
            diffuse: Vec3::splat(0.6),
            specular: Vec3::ZERO,
            shininess: 1.0,
            emission: Vec3::ZERO,
            diffuse_map: None,
            alpha_mask: None,
            normal_map: None,
            bake: None,
            diffuse_transmittance: Vec3::ZERO,
            specular_reflectance: Vec3::ZERO,
            specular_transmittance: Vec3::ZERO,
        }
    }
}

/// The largest luminous exitance a material may emit (`Ke`), lm/m²: about twice the
/// sun's surface (π × 1.6·10⁹ cd/m²); larger values are mistakes whose solution overflows.
pub const MAX_EXITANCE_LM_M2: f64 = 1e10;

impl Material {
    /// Sets the diffuse texture and the alpha mask of its holes.
    pub fn set_diffuse_map(&mut self, img: Option<Arc<image::RgbaImage>>) {
        self.alpha_mask = img
            .as_deref()
            .and_then(super::alpha::AlphaMask::from_alpha)
            .map(Arc::new);
        self.diffuse_map = img;
    }

    /// The mean colour of the diffuse texture's solid texels in linear light (sRGB
    /// decoded; holes left out), white without one.
    pub fn texture_mean(&self) -> Vec3 {
        let Some(img) = &self.diffuse_map else {
            return Vec3::ONE;
        };
        let linear: Vec<f64> = (0..=255u8)
            .map(|c| super::palette::srgb_to_linear(c) as f64)
            .collect();
        let masked = self.alpha_mask.is_some();
        let mut sum = [0.0f64; 3];
        let mut count = 0.0f64;
        for p in img.pixels() {
            if masked && p.0[3] < super::alpha::ALPHA_CUTOFF {
                continue;
            }
            count += 1.0;
            for (s, &c) in sum.iter_mut().zip(&p.0[..3]) {
                *s += linear[c as usize];
            }
        }
        Vec3::from_array(sum.map(|s| (s / count.max(1.0)) as f32))
    }

    /// The diffuse reflectance radiosity uses: `Kd` times the diffuse texture's mean
    /// colour (Wallner §2.3.3), so a textured wall bleeds its own colour.
    pub fn diffuse_reflectance(&self) -> Vec3 {
        self.diffuse * self.texture_mean()
    }

    /// Whether it reflects or transmits specularly (a mirror or clear glass).
    pub fn is_specular(&self) -> bool {
        self.specular_reflectance.max_element() > 0.0
            || self.specular_transmittance.max_element() > 0.0
    }
}

/// A triangle mesh in world coordinates with one material.
#[derive(Debug, Clone, Default)]
pub struct SceneMesh {
    /// Object name from the OBJ file.
    pub name: String,
    /// Vertex positions, metres.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals.
    pub normals: Vec<Vec3>,
    /// Texture coordinates (zero when the OBJ has none).
    pub uvs: Vec<Vec2>,
    /// Triangles, three indices each, counter-clockwise seen from the front.
    pub indices: Vec<u32>,
    /// Index into the scene's materials.
    pub material: usize,
}

impl SceneMesh {
    /// Builds a mesh with flat normals from world-space triangles (for scenes made in code).
    pub fn from_triangles(name: &str, triangles: &[[Vec3; 3]], material: usize) -> SceneMesh {
        let mut m = SceneMesh {
            name: name.into(),
            material,
            ..Default::default()
        };
        for t in triangles {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
            for p in t {
                m.indices.push(m.positions.len() as u32);
                m.positions.push(*p);
                m.normals.push(n);
                m.uvs.push(Vec2::ZERO);
            }
        }
        m
    }

    /// Per-vertex tangents from the texture coordinates (w = handedness); any unit vector
    /// across the normal where the mapping is degenerate.
    pub fn tangents(&self) -> Vec<[f32; 4]> {
        let m = self;
        let n = m.positions.len();
        let mut tan = vec![Vec3::ZERO; n];
        let mut bit = vec![Vec3::ZERO; n];
        for t in m.indices.chunks_exact(3) {
            let [a, b, c] = [t[0] as usize, t[1] as usize, t[2] as usize];
            let (e1, e2) = (
                m.positions[b] - m.positions[a],
                m.positions[c] - m.positions[a],
            );
            let (d1, d2): (Vec2, Vec2) = (m.uvs[b] - m.uvs[a], m.uvs[c] - m.uvs[a]);
            let det = d1.x * d2.y - d2.x * d1.y;
            if det.abs() < 1e-12 {
                continue;
            }
            let r = 1.0 / det;
            let t_dir = (e1 * d2.y - e2 * d1.y) * r;
            let b_dir = (e2 * d1.x - e1 * d2.x) * r;
            for i in [a, b, c] {
                tan[i] += t_dir;
                bit[i] += b_dir;
            }
        }
        (0..n)
            .map(|i| {
                let nrm = m.normals[i];
                let mut t = (tan[i] - nrm * nrm.dot(tan[i])).normalize_or_zero();
                if t == Vec3::ZERO {
                    t = nrm.any_orthonormal_vector();
                }
                let w = if nrm.cross(t).dot(bit[i]) < 0.0 {
                    -1.0
                } else {
                    1.0
                };
                [t.x, t.y, t.z, w]
            })
            .collect()
    }
}

/// The model's matrix: OBJ frame → world (up-axis change, scale, rotation, translation).
pub fn model_matrix(entry: &ModelEntry) -> DMat4 {
    let up = match entry.up {
        UpAxis::Y => DMat4::from_rotation_x(std::f64::consts::FRAC_PI_2),
        UpAxis::Z => DMat4::IDENTITY,
    };
    let scale = match entry.scale {
        None => DVec3::ONE,
        Some(Scale::Uniform(s)) => DVec3::splat(s),
        Some(Scale::PerAxis(s)) => DVec3::from_array(s),
    };
    let rotation = euler_xyz_deg(entry.rotation_deg.unwrap_or([0.0; 3]));
    let translation = DVec3::from_array(entry.translation.unwrap_or([0.0; 3]));
    DMat4::from_translation(translation)
        * DMat4::from_mat3(rotation)
        * DMat4::from_scale(scale)
        * up
}

/// Rotation about world X, then Y, then Z (degrees).
pub fn euler_xyz_deg(deg: [f64; 3]) -> DMat3 {
    DMat3::from_rotation_z(deg[2].to_radians())
        * DMat3::from_rotation_y(deg[1].to_radians())
        * DMat3::from_rotation_x(deg[0].to_radians())
}

/// Checks `entry`'s transform and that its file exists; returns the file.
pub(super) fn checked_entry(
    scene: &Path,
    key: &str,
    dir: &Path,
    entry: &ModelEntry,
) -> Result<PathBuf, SceneError> {
    let path_key = format!("{key}.path");
    for (k, v) in [
        ("translation", entry.translation),
        ("rotation_deg", entry.rotation_deg),
    ] {
        if let Some(v) = v {
            finite_vec(scene, &format!("{key}.{k}"), v)?;
        }
    }
    let scale = match entry.scale {
        None => [1.0; 3],
        Some(Scale::Uniform(s)) => [s; 3],
        Some(Scale::PerAxis(s)) => s,
    };
    if scale.iter().any(|s| !s.is_finite() || *s == 0.0) {
        return Err(SceneError::new(
            scene,
            format!("{key}.scale"),
            format!("{scale:?}: every factor must be finite and non-zero"),
        ));
    }
    let obj = dir.join(&entry.path);
    if !obj.is_file() {
        return Err(SceneError::new(
            scene,
            path_key,
            format!("cannot read model {}: no such file", obj.display()),
        ));
    }
    Ok(obj)
}

/// Loads the OBJ `obj` of `entry` (checked by [`checked_entry`]); its materials are
/// appended to `materials`, and what the loading worked around (a missing MTL file,
/// triangles without area, a capped transmittance) to `warnings`.
pub(super) fn load_obj(
    scene: &Path,
    key: &str,
    obj: &Path,
    entry: &ModelEntry,
    (materials, warnings): (&mut Vec<Material>, &mut Vec<String>),
) -> Result<Vec<SceneMesh>, SceneError> {
    let path_key = format!("{key}.path");
    if entry.light_files.keys().next().is_some() || !entry.import_lights {
        return Err(SceneError::new(
            scene,
            format!("{key}.light_files"),
            "only glTF models have lights: light_files and import_lights are for .gltf and .glb files",
        ));
    }
    let options = ReadOptions {
        single_index: true,
        all_vertices: false,
    };
    let ObjFile {
        models,
        materials: mtl,
        ..
    } = obj_file::read(obj, options)
        .map_err(|e| SceneError::new(scene, &path_key, e.to_string()))?;
    let obj_dir = obj.parent().unwrap_or(Path::new("")).to_path_buf();
    let first_material = materials.len();
    let mut textures = TextureCache::new(&obj_dir);
    match mtl {
        Ok(list) => {
            for m in &list {
                materials.push(textures.material(m).map_err(|message| {
                    SceneError::new(
                        scene,
                        &path_key,
                        format!("material {:?}: {message}", m.name),
                    )
                })?);
            }
        }
        // A missing MTL is common in exported files: warn and use the default material.
        Err(MtlError::Missing) => warnings.push(format!(
            "{}: its MTL file could not be opened; using the default material",
            obj.display()
        )),
        Err(e) => {
            return Err(SceneError::new(
                scene,
                &path_key,
                format!("{}: MTL: {e}", obj.display()),
            ))
        }
    }
    warnings.append(&mut textures.warnings);
    let mtl_end = materials.len();
    let fallback = bake_overrides(scene, key, entry, first_material, materials)?;
    let matrix = model_matrix(entry);
    let normal_matrix = DMat3::from_mat4(matrix).inverse().transpose();
    let mut meshes = Vec::new();
    let (mut dropped, mut total) = (0usize, 0usize);
    for m in models {
        total += m.mesh.indices.len() / 3;
        let range = (first_material, mtl_end, fallback);
        let (mesh, zero_area) = convert(&m, matrix, normal_matrix, range).map_err(|message| {
            SceneError::new(
                scene,
                &path_key,
                format!("{}: object {:?}: {message}", obj.display(), m.name),
            )
        })?;
        dropped += zero_area;
        if !mesh.indices.is_empty() {
            meshes.push(mesh);
        }
    }
    if dropped > 0 {
        warnings.push(format!(
            "{}: {key} ({}): {dropped} of its {total} triangles have no area and were dropped",
            scene.display(),
            obj.display()
        ));
    }
    if meshes.is_empty() {
        return Err(SceneError::new(
            scene,
            path_key,
            format!("{}: no triangles with a non-zero area", obj.display()),
        ));
    }
    Ok(meshes)
}

/// Sets `bake` on the materials `entry` appended (from `first`): `bake_materials` by
/// name, else `bake`. Returns the material for faces without one: the default, or a copy
/// of it carrying `bake`.
pub(super) fn bake_overrides(
    scene: &Path,
    key: &str,
    entry: &ModelEntry,
    first: usize,
    materials: &mut Vec<Material>,
) -> Result<usize, SceneError> {
    for name in entry.bake_materials.keys() {
        if !materials[first..].iter().any(|m| &m.name == name) {
            let known: Vec<&str> = materials[first..].iter().map(|m| m.name.as_str()).collect();
            return Err(SceneError::new(
                scene,
                format!("{key}.bake_materials.{name}"),
                format!("the model has no material {name:?} (its materials: {known:?})"),
            ));
        }
    }
    for m in &mut materials[first..] {
        m.bake = entry.bake_materials.get(&m.name).copied().or(entry.bake);
    }
    Ok(match entry.bake {
        None => 0,
        Some(bake) => {
            materials.push(Material {
                bake: Some(bake),
                ..Material::default()
            });
            materials.len() - 1
        }
    })
}

/// One tobj model to a world-space mesh, dropping zero-area triangles (returned: how
/// many); flat normals where the OBJ has none. `materials` is the model's range of the
/// scene's materials (first, end) and the material of faces without one.
fn convert(
    m: &tobj::Model,
    matrix: DMat4,
    normal_matrix: DMat3,
    materials: (usize, usize, usize),
) -> Result<(SceneMesh, usize), String> {
    let (first_material, material_count, fallback) = materials;
    let src = &m.mesh;
    let point = |i: usize| {
        let p = DVec3::new(
            src.positions[3 * i],
            src.positions[3 * i + 1],
            src.positions[3 * i + 2],
        );
        matrix.transform_point3(p)
    };
    if src.positions.iter().any(|v| !v.is_finite()) {
        return Err("a vertex position is not a finite number".into());
    }
    let has_normals = src.normals.len() == src.positions.len();
    let has_uvs = src.texcoords.len() / 2 == src.positions.len() / 3;
    let material = match src.material_id {
        Some(id) if first_material + id < material_count => first_material + id,
        _ => fallback,
    };
    let mut out = SceneMesh {
        name: m.name.clone(),
        material,
        ..Default::default()
    };
    let mut remap: HashMap<u32, u32> = HashMap::new();
    let mut dropped = 0;
    for tri in src.indices.chunks_exact(3) {
        let p = [0, 1, 2].map(|k| point(tri[k] as usize));
        if !crate::geometry::has_area(p) {
            dropped += 1;
            continue;
        }
        let face = (p[1] - p[0]).cross(p[2] - p[0]);
        let face_n = face.normalize().as_vec3();
        for (k, &vi) in tri.iter().enumerate() {
            let i = vi as usize;
            let normal = if has_normals {
                let n = DVec3::new(
                    src.normals[3 * i],
                    src.normals[3 * i + 1],
                    src.normals[3 * i + 2],
                );
                let n = (normal_matrix * n).normalize_or_zero().as_vec3();
                if n == Vec3::ZERO {
                    face_n
                } else {
                    n
                }
            } else {
                face_n
            };
            let uv = if has_uvs {
                Vec2::new(src.texcoords[2 * i] as f32, src.texcoords[2 * i + 1] as f32)
            } else {
                Vec2::ZERO
            };
            // Shared vertices only when the file gives normals; flat faces otherwise.
            let index = if has_normals {
                *remap.entry(vi).or_insert_with(|| {
                    out.positions.push(p[k].as_vec3());
                    out.normals.push(normal);
                    out.uvs.push(uv);
                    out.positions.len() as u32 - 1
                })
            } else {
                out.positions.push(p[k].as_vec3());
                out.normals.push(normal);
                out.uvs.push(uv);
                out.positions.len() as u32 - 1
            };
            out.indices.push(index);
        }
    }
    Ok((out, dropped))
}

/// An MTL material's diffuse transmittance ([`mtl_transmittance`]).
fn transmittance(m: &tobj::Material) -> Result<Vec3, String> {
    let number = |key: &str| -> Result<Option<f64>, String> {
        m.unknown_param
            .get(key)
            .map(|v| {
                v.trim()
                    .parse::<f64>()
                    .map_err(|_| format!("{key} {v:?} is not a number"))
            })
            .transpose()
    };
    let tf = match m.unknown_param.get("Tf") {
        None => None,
        Some(v) => {
            let values: Vec<f32> = v
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()
                .map_err(|_| format!("Tf {v:?} is not three numbers"))?;
            match values[..] {
                [g] => Some(Vec3::splat(g)),
                [r, g, b] => Some(Vec3::new(r, g, b)),
                _ => return Err(format!("Tf {v:?} is not three numbers")),
            }
        }
    };
    let dissolve = m.dissolve;
    let t = mtl_transmittance(dissolve, number("Tr")?, tf, m.illumination_model);
    if !t.is_finite() {
        return Err(format!("Tf/d/Tr give a transmittance {t}"));
    }
    Ok(t)
}

/// The diffuse transmittance an MTL material states: `(1 − d) × Tf` (`Tr` = 1 − `d` when
/// `d` is absent; `Tf` white when absent) for the illumination models without
/// refraction; nothing for `illum` 4, 6, 7 and 9 (glass: specular transmission, which
/// the scene file's `specular_transmittance` sets) and for opaque materials (`d` 1, the
/// usual `Tf 1 1 1` alone).
pub fn mtl_transmittance(
    dissolve: Option<f64>,
    tr: Option<f64>,
    tf: Option<Vec3>,
    illum: Option<u8>,
) -> Vec3 {
    if matches!(illum, Some(4 | 6 | 7 | 9)) {
        return Vec3::ZERO;
    }
    let opacity = dissolve.or(tr.map(|t| 1.0 - t)).unwrap_or(1.0);
    let clear = (1.0 - opacity).clamp(0.0, 1.0) as f32;
    (tf.unwrap_or(Vec3::ONE).clamp(Vec3::ZERO, Vec3::ONE)) * clear
}

/// Loads each texture once per model.
struct TextureCache {
    dir: PathBuf,
    loaded: HashMap<String, Arc<image::RgbaImage>>,
    /// What reading the materials worked around.
    warnings: Vec<String>,
}

impl TextureCache {
    fn new(dir: &Path) -> TextureCache {
        TextureCache {
            dir: dir.to_path_buf(),
            loaded: HashMap::new(),
            warnings: Vec::new(),
        }
    }

    fn texture(&mut self, name: &str) -> Result<Arc<image::RgbaImage>, String> {
        // MTL map statements may carry options ("-bm 1 file.png"): the file is last.
        let file = name.split_whitespace().last().unwrap_or(name).to_string();
        if let Some(t) = self.loaded.get(&file) {
            return Ok(t.clone());
        }
        let path = self.dir.join(&file);
        let img = image::open(&path)
            .map_err(|e| format!("texture {}: {e}", path.display()))?
            .to_rgba8();
        let img = Arc::new(img);
        self.loaded.insert(file, img.clone());
        Ok(img)
    }

    fn material(&mut self, m: &tobj::Material) -> Result<Material, String> {
        let v3 = |v: Option<[f64; 3]>, d: f32| {
            v.map(|a| Vec3::from_array(a.map(|x| x as f32)))
                .unwrap_or(Vec3::splat(d))
        };
        let diffuse = v3(m.diffuse, 0.6);
        let specular = v3(m.specular, 0.0);
        let emission = v3(m.emissive, 0.0);
        for (key, v) in [("Kd", diffuse), ("Ks", specular), ("Ke", emission)] {
            if !v.is_finite() || v.min_element() < 0.0 {
                return Err(format!("{key} {v} must be finite and non-negative"));
            }
        }
        if diffuse.max_element() > 1.0 {
            return Err(format!("Kd {diffuse} is a reflectance and cannot exceed 1"));
        }
        if f64::from(emission.max_element()) > MAX_EXITANCE_LM_M2 {
            return Err(format!(
                "Ke {emission} lm/m² is brighter than the sun's surface (at most {MAX_EXITANCE_LM_M2:e})"
            ));
        }
        let shininess = m.shininess.unwrap_or(1.0).max(0.0) as f32;
        let mut diffuse_map = m
            .diffuse_texture
            .as_deref()
            .map(|t| self.texture(t))
            .transpose()?;
        // `map_d` cuts holes: it becomes the diffuse texture's alpha.
        if let Some(map_d) = m.dissolve_texture.as_deref() {
            let mask = self.texture(map_d)?;
            let combined = super::alpha::with_dissolve_map(diffuse_map.as_deref(), &mask);
            diffuse_map = Some(Arc::new(combined));
        }
        // `norm` is a normal map; `bump` / `map_Bump` a height map when it is grey
        // (converted), a normal map otherwise.
        let normal_map = match (m.unknown_param.get("norm"), m.normal_texture.as_deref()) {
            (Some(norm), _) => Some(self.texture(norm)?),
            (None, Some(bump)) => {
                let img = self.texture(bump)?;
                Some(if super::bump::is_height_map(&img) {
                    let scale = super::bump::bump_multiplier(bump);
                    Arc::new(super::bump::height_to_normal(&img, scale))
                } else {
                    img
                })
            }
            (None, None) => None,
        };
        let mut material = Material {
            name: m.name.clone(),
            diffuse,
            specular,
            shininess,
            emission,
            diffuse_map: None,
            alpha_mask: None,
            normal_map,
            bake: None,
            diffuse_transmittance: transmittance(m)?,
            specular_reflectance: Vec3::ZERO,
            specular_transmittance: Vec3::ZERO,
        };
        material.set_diffuse_map(diffuse_map);
        // Exporters often keep Kd white on a see-through material: what it transmits is
        // capped at what it does not reflect.
        let room = (Vec3::ONE - material.diffuse_reflectance()).max(Vec3::ZERO);
        if material.diffuse_transmittance.cmpgt(room).any() {
            self.warnings.push(format!(
                "material {:?}: reflectance {} plus transmittance {} exceeds 1; the \
                 transmittance is capped at {room}",
                m.name,
                material.diffuse_reflectance(),
                material.diffuse_transmittance
            ));
            material.diffuse_transmittance = material.diffuse_transmittance.min(room);
        }
        Ok(material)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mtl_statements_map_to_a_transmittance() {
        let t = mtl_transmittance(Some(0.8), None, Some(Vec3::splat(0.8)), Some(2));
        assert!((t - Vec3::splat(0.16)).abs().max_element() < 1e-6);
        assert_eq!(
            mtl_transmittance(Some(1.0), None, Some(Vec3::ONE), Some(2)),
            Vec3::ZERO
        );
        assert_eq!(
            mtl_transmittance(None, None, Some(Vec3::ONE), None),
            Vec3::ZERO
        );
        let tr = mtl_transmittance(None, Some(0.3), None, Some(2));
        assert!((tr - Vec3::splat(0.3)).abs().max_element() < 1e-6);
        assert_eq!(
            mtl_transmittance(Some(0.2), None, None, Some(6)),
            Vec3::ZERO
        );
    }
}
