//! The solved scene as glTF 2.0 binary (`radiosity --export scene.glb`), for Blender,
//! three.js and any glTF viewer: every triangle with an area, grouped by material and
//! representation, with the solution baked in. Each surface is light-mapped or
//! vertex-lit as [`super::bake`] chose (Edström §5.3); materials are unlit
//! (`KHR_materials_unlit`), so viewers show the light as it is.
//!
//! - Light-mapped primitives: the model's triangles; the material's base colour texture
//!   is the light map (the image `lightmap`, PNG, sRGB, over `TEXCOORD_0`, bilinear,
//!   clamped, no mipmaps: the atlas's gutters keep charts apart).
//! - Vertex-lit primitives: the model's triangles, refined where the light map is finer
//!   (Edström's patch refinement, [`super::refine`]); `COLOR_0` is the radiosity at each corner as a linear colour,
//!   over the white point (the 99th percentile of the element radiosity's luminance by
//!   area, given in the asset's `extras` as `white_lm_per_m2`), clamped to 1.
//! - Every primitive: `_RADIOSITY` (lm/m², RGB) and `_ILLUMINANCE` (lux) at each corner,
//!   the exact values of the element that covers it (the light-map texel under the corner,
//!   nudged into its triangle), and `TEXCOORD_0`, the corner's place in the atlas.
//!
//! - The luminaires: `EXT_lights_ies` lights with their profiles and `KHR_lights_punctual`
//!   fallbacks ([`lights`]).
//!
//! goniolight's frame is metres with +Z up; glTF's is +Y up: (x, y, z) → (x, z, −y).

use std::borrow::Cow;
use std::collections::BTreeMap;

use glam::{DVec2, DVec3, Vec2};
use gltf::json;
use json::validation::Checked::Valid;
use json::validation::USize64;

mod lights;

use super::bake::BakePlan;
use super::scene::RadiosityScene;
use crate::render::lightmap::LightMap;
use crate::scene::file::Bake;

/// Why the solved scene could not be exported as glTF.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The binary chunk would pass the 4 GB that a GLB's 32-bit length holds.
    #[error("the solved scene needs {mb} MB, more than a glTF binary holds (4 GB)")]
    TooLarge {
        /// The size it needs, MB.
        mb: usize,
    },
    /// The glTF JSON or binary container could not be written.
    #[error("encoding the glTF: {0}")]
    Gltf(String),
    /// The light map could not be encoded as PNG.
    #[error("encoding the light map: {0}")]
    LightMap(String),
}

/// One corner's baked values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BakedCorner {
    /// Position, metres, glTF frame (+Y up).
    pub position: [f32; 3],
    /// Unit face normal, glTF frame.
    pub normal: [f32; 3],
    /// Radiosity, lm/m² (RGB).
    pub radiosity: [f32; 3],
    /// Illuminance received, lux.
    pub illuminance: f32,
    /// Light-map coordinates (0..1 from the atlas's top-left corner).
    pub lightmap_uv: [f32; 2],
}

/// The exported triangles: three corners each, with a material and a representation.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Baked {
    /// Three per triangle.
    pub corners: Vec<BakedCorner>,
    /// Per triangle, its material.
    pub material: Vec<usize>,
    /// Per triangle, how it carries its light.
    pub bake: Vec<Bake>,
}

/// Z-up metres to glTF's Y-up.
fn to_gltf(p: DVec3) -> [f32; 3] {
    [p.x as f32, p.z as f32, -p.y as f32]
}

/// The light-map texel value under atlas point `uv` (0..1), nudged toward `inside` (the
/// triangle's centroid in the atlas) so a corner on a texel edge reads its own triangle.
fn texel_at(map: &LightMap, uv: Vec2, inside: Vec2) -> [f32; 4] {
    let size = DVec2::new(map.width as f64, map.height as f64);
    let p = uv.as_dvec2() * size;
    let q = p + (inside.as_dvec2() * size - p) * 1e-3;
    let x = (q.x.floor().max(0.0) as u32).min(map.width - 1);
    let y = (q.y.floor().max(0.0) as u32).min(map.height - 1);
    map.texels[(y * map.width + x) as usize]
}

/// The exported triangles of every triangle with elements, in the scene's triangle
/// order: light-mapped ones as they are, vertex-lit ones as the parts `plan` refined them
/// into.
pub fn bake(scene: &RadiosityScene, map: &LightMap, plan: &BakePlan) -> Baked {
    let mesh = &scene.casters;
    let whole = [[DVec3::X, DVec3::Y, DVec3::Z]];
    let mut out = Baked::default();
    for (t, te) in scene.elements.triangles.iter().enumerate() {
        let Some(bake) = plan.bake[t] else {
            continue;
        };
        let parts: &[[DVec3; 3]] = match bake {
            Bake::Map => &whole,
            Bake::Vertex => &plan.parts[t],
        };
        let corners = mesh.triangles[t].map(|i| mesh.positions[i as usize]);
        let uv = map.triangle_uv[t];
        let normal = to_gltf(te.normal);
        for part in parts {
            let points = part.map(|w| corners[0] * w.x + corners[1] * w.y + corners[2] * w.z);
            let uvs = part.map(|w| {
                let w = w.as_vec3();
                uv[0] * w.x + uv[1] * w.y + uv[2] * w.z
            });
            let centre = (uvs[0] + uvs[1] + uvs[2]) / 3.0;
            for k in 0..3 {
                let v = texel_at(map, uvs[k], centre);
                out.corners.push(BakedCorner {
                    position: to_gltf(points[k]),
                    normal,
                    radiosity: [v[0], v[1], v[2]],
                    illuminance: v[3],
                    lightmap_uv: uvs[k].to_array(),
                });
            }
            out.material.push(te.material);
            out.bake.push(bake);
        }
    }
    out
}

/// The white point: the 99th percentile of the elements' radiosity luminance, weighted by
/// area (1 lm/m² when everything is dark).
pub fn white_point(scene: &RadiosityScene, map: &LightMap) -> f64 {
    let el = &scene.elements;
    let mut values: Vec<(f64, f64)> = el
        .texel
        .iter()
        .zip(&el.area)
        .map(|(&[x, y], &a)| {
            let t = map.texels[(y * map.width + x) as usize];
            (
                0.2126 * t[0] as f64 + 0.7152 * t[1] as f64 + 0.0722 * t[2] as f64,
                a,
            )
        })
        .collect();
    values.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = values.iter().map(|v| v.1).sum();
    let mut acc = 0.0;
    for (l, a) in &values {
        acc += a;
        if acc >= 0.99 * total {
            return l.max(1e-9);
        }
    }
    1.0
}

/// The display colour of `radiosity` for white point `white`: linear, clamped to 0..1.
pub fn colour(radiosity: [f32; 3], white: f64) -> [f32; 3] {
    radiosity.map(|c| (c as f64 / white).clamp(0.0, 1.0) as f32)
}

/// Accumulates the binary chunk and the JSON objects that point into it.
struct GlbBuilder {
    root: json::Root,
    bin: Vec<u8>,
    buffer: json::Index<json::Buffer>,
}

impl GlbBuilder {
    fn new() -> GlbBuilder {
        let mut root = json::Root::default();
        let buffer = root.push(json::Buffer {
            byte_length: USize64(0),
            extensions: None,
            extras: None,
            name: None,
            uri: None,
        });
        GlbBuilder {
            root,
            bin: Vec::new(),
            buffer,
        }
    }

    /// Appends `bytes` (4-byte aligned) as a buffer view.
    fn view(
        &mut self,
        bytes: &[u8],
        target: Option<json::buffer::Target>,
    ) -> json::Index<json::buffer::View> {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.root.push(json::buffer::View {
            buffer: self.buffer,
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            extensions: None,
            extras: None,
            name: None,
            target: target.map(Valid),
        })
    }

    /// A float accessor over `values` (`width` floats per item), with bounds for positions.
    fn accessor(
        &mut self,
        values: &[f32],
        width: usize,
        bounds: bool,
    ) -> json::Index<json::Accessor> {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, Some(json::buffer::Target::ArrayBuffer));
        let type_ = match width {
            1 => json::accessor::Type::Scalar,
            2 => json::accessor::Type::Vec2,
            _ => json::accessor::Type::Vec3,
        };
        let (min, max) = if bounds {
            let fold = |f: fn(f32, f32) -> f32, start: f32| {
                let mut m = vec![start; width];
                for item in values.chunks_exact(width) {
                    for (a, &b) in m.iter_mut().zip(item) {
                        *a = f(*a, b);
                    }
                }
                json::Value::from(m)
            };
            (
                Some(fold(f32::min, f32::MAX)),
                Some(fold(f32::max, f32::MIN)),
            )
        } else {
            (None, None)
        };
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(values.len() / width),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::F32,
            )),
            extensions: None,
            extras: None,
            type_: Valid(type_),
            min,
            max,
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    fn finish(mut self) -> Result<Vec<u8>, ExportError> {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        // A GLB states its length in 32 bits.
        if self.bin.len() > (u32::MAX as usize) - (64 << 20) {
            return Err(ExportError::TooLarge {
                mb: self.bin.len() >> 20,
            });
        }
        self.root.buffers[0].byte_length = USize64::from(self.bin.len());
        let json =
            json::serialize::to_vec(&self.root).map_err(|e| ExportError::Gltf(e.to_string()))?;
        let glb = gltf::binary::Glb {
            header: gltf::binary::Header {
                magic: *b"glTF",
                version: 2,
                length: 0, // written by to_vec
            },
            json: Cow::Owned(json),
            bin: Some(Cow::Owned(self.bin)),
        };
        glb.to_vec().map_err(|e| ExportError::Gltf(e.to_string()))
    }
}

/// The solved scene as a glTF binary: one primitive per material (named as in the MTL)
/// and representation, as `plan` chose; the light map as the image `lightmap`.
pub fn glb(
    scene: &RadiosityScene,
    map: &LightMap,
    plan: &BakePlan,
    material_names: &[String],
    luminaires: &[crate::scene::PlacedLuminaire],
) -> Result<Vec<u8>, ExportError> {
    let baked = bake(scene, map, plan);
    let white = white_point(scene, map);
    let mut b = GlbBuilder::new();
    let texture = lightmap_texture(&mut b, map, white)?;
    let mut groups: Vec<(usize, Bake)> = baked
        .material
        .iter()
        .copied()
        .zip(baked.bake.iter().copied())
        .collect();
    groups.sort_by_key(|&(m, bake)| (m, bake == Bake::Vertex));
    groups.dedup();
    let mut primitives = Vec::new();
    for (m, bake) in groups {
        let mine: Vec<&BakedCorner> = baked
            .corners
            .chunks_exact(3)
            .zip(baked.material.iter().zip(&baked.bake))
            .filter(|(_, (&tm, &tb))| tm == m && tb == bake)
            .flat_map(|(c, _)| c)
            .collect();
        let flat = |f: &dyn Fn(&BakedCorner) -> Vec<f32>| -> Vec<f32> {
            mine.iter().flat_map(|c| f(c)).collect()
        };
        let mut attributes = BTreeMap::new();
        let mut add =
            |semantic: json::mesh::Semantic, values: Vec<f32>, width: usize, bounds: bool| {
                let a = b.accessor(&values, width, bounds);
                attributes.insert(Valid(semantic), a);
            };
        use json::mesh::Semantic;
        add(Semantic::Positions, flat(&|c| c.position.to_vec()), 3, true);
        add(Semantic::Normals, flat(&|c| c.normal.to_vec()), 3, false);
        if bake == Bake::Vertex {
            add(
                Semantic::Colors(0),
                flat(&|c| colour(c.radiosity, white).to_vec()),
                3,
                false,
            );
        }
        add(
            Semantic::TexCoords(0),
            flat(&|c| c.lightmap_uv.to_vec()),
            2,
            false,
        );
        add(
            Semantic::Extras("RADIOSITY".into()),
            flat(&|c| c.radiosity.to_vec()),
            3,
            false,
        );
        add(
            Semantic::Extras("ILLUMINANCE".into()),
            flat(&|c| vec![c.illuminance]),
            1,
            false,
        );
        let base_color_texture = (bake == Bake::Map).then_some(json::texture::Info {
            index: texture,
            tex_coord: 0,
            extensions: None,
            extras: None,
        });
        let material = b.root.push(json::Material {
            name: Some(
                material_names
                    .get(m)
                    .cloned()
                    .unwrap_or_else(|| format!("material {m}")),
            ),
            // Seen from behind, a surface shows its front's light; a translucent one has
            // a back face of its own with the back's light (radiosity/transmission.rs).
            double_sided: scene.transmittance.get(m).is_none_or(|t| *t == DVec3::ZERO),
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_texture,
                ..Default::default()
            },
            extensions: Some(json::extensions::material::Material {
                unlit: Some(json::extensions::material::Unlit {}),
                ..Default::default()
            }),
            extras: Some(
                serde_json::value::to_raw_value(&serde_json::json!({
                    "bake": match bake { Bake::Map => "map", Bake::Vertex => "vertex" },
                }))
                .map_err(|e| ExportError::Gltf(e.to_string()))?,
            ),
            ..Default::default()
        });
        primitives.push(json::mesh::Primitive {
            attributes,
            extensions: None,
            extras: None,
            indices: None,
            material: Some(material),
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        });
    }
    let mesh = b.root.push(json::Mesh {
        extensions: None,
        extras: None,
        name: Some("radiosity".into()),
        primitives,
        weights: None,
    });
    let light_nodes = lights::add(&mut b, luminaires);
    let node = b.root.push(json::Node {
        mesh: Some(mesh),
        name: Some("scene".into()),
        ..Default::default()
    });
    let scene_index = b.root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some("radiosity solution".into()),
        nodes: [vec![node], light_nodes].concat(),
    });
    b.root.scene = Some(scene_index);
    b.root
        .extensions_used
        .insert(0, "KHR_materials_unlit".into());
    b.root.asset.generator = Some(format!("goniolight {}", env!("CARGO_PKG_VERSION")));
    b.root.asset.extras = Some(
        serde_json::value::to_raw_value(&serde_json::json!({
            "white_lm_per_m2": white,
            "units": "metres, +Y up; _RADIOSITY lm/m², _ILLUMINANCE lux",
            "introduced_triangles": plan.introduced,
        }))
        .map_err(|e| ExportError::Gltf(e.to_string()))?,
    );
    b.finish()
}

/// The light map as the texture `lightmap`: an embedded sRGB PNG at white point `white`,
/// sampled bilinearly without mipmaps and clamped at the atlas's edges.
fn lightmap_texture(
    b: &mut GlbBuilder,
    map: &LightMap,
    white: f64,
) -> Result<json::Index<json::Texture>, ExportError> {
    let png = lightmap_png(map, white)?;
    let image_view = b.view(&png, None);
    let image = b.root.push(json::Image {
        buffer_view: Some(image_view),
        mime_type: Some(json::image::MimeType("image/png".into())),
        name: Some("lightmap".into()),
        uri: None,
        extensions: None,
        extras: None,
    });
    use json::texture::{MagFilter, MinFilter, WrappingMode};
    let sampler = b.root.push(json::texture::Sampler {
        mag_filter: Some(Valid(MagFilter::Linear)),
        min_filter: Some(Valid(MinFilter::Linear)),
        name: None,
        wrap_s: Valid(WrappingMode::ClampToEdge),
        wrap_t: Valid(WrappingMode::ClampToEdge),
        extensions: None,
        extras: None,
    });
    Ok(b.root.push(json::Texture {
        name: Some("lightmap".into()),
        sampler: Some(sampler),
        source: image,
        extensions: None,
        extras: None,
    }))
}

/// The light map as an sRGB PNG at white point `white`.
fn lightmap_png(map: &LightMap, white: f64) -> Result<Vec<u8>, ExportError> {
    let srgb = |c: f32| {
        let l = (c as f64 / white).clamp(0.0, 1.0);
        let s = if l <= 0.003_130_8 {
            12.92 * l
        } else {
            1.055 * l.powf(1.0 / 2.4) - 0.055
        };
        (s * 255.0).round() as u8
    };
    let pixels: Vec<u8> = map
        .texels
        .iter()
        .flat_map(|t| [srgb(t[0]), srgb(t[1]), srgb(t[2])])
        .collect();
    let img = image::RgbImage::from_raw(map.width, map.height, pixels)
        .expect("a light map holds width × height texels");
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| ExportError::LightMap(e.to_string()))?;
    Ok(out.into_inner())
}
