//! A scene uploaded to the GPU: one vertex and index buffer, a bind group per material,
//! the luminaires (a storage buffer) and their light distribution textures (one array).

use std::sync::{Arc, Mutex, OnceLock};

use glam::Vec2;
use wgpu::util::DeviceExt;

use super::layouts::Layouts;
use super::lightmap::{self, LightMap};
use super::mipmaps::{mip_chain, TexelKind};
use super::paraboloid::{ParaboloidCasters, ShadowLight};
use super::volumes::VolumeGeometry;
use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::photometry::LdtTexture;
use crate::render::ldt::table::LdtTables;
use crate::render::ldt::LdtAtlas;
use crate::scene::{Material, PlacedLuminaire, Scene};

/// A vertex as the shaders read it.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// World position, metres.
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Texture coordinates.
    pub uv: [f32; 2],
    /// Tangent (xyz) and handedness (w) for normal mapping.
    pub tangent: [f32; 4],
    /// Light-map atlas coordinates (0..1; unused without a light map).
    pub lightmap_uv: [f32; 2],
}

impl Vertex {
    /// The vertex buffer layout.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4, 4 => Float32x2],
    };
}

/// A luminaire as the shaders read it (`Light` in `shaders/lighting.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LightGpu {
    /// Photometric centre; w: the LDT layer.
    pub position: [f32; 4],
    /// Luminaire X (C0) axis in the world.
    pub axis_x: [f32; 4],
    /// Luminaire Y (C90) axis.
    pub axis_y: [f32; 4],
    /// Luminaire Z (up) axis.
    pub axis_z: [f32; 4],
    /// Colour (luminance 1); w: candela per texel unit.
    pub color: [f32; 4],
}

impl LightGpu {
    /// The GPU record of `l`, whose distribution is layer `layer` of the atlas and whose
    /// sector colours (if any) start at `first_sector` of the sector buffer.
    pub fn new(l: &PlacedLuminaire, layer: u32, first_sector: u32) -> LightGpu {
        let axis = |v: glam::DVec3, w: f32| [v.x as f32, v.y as f32, v.z as f32, w];
        let p = l.position.as_vec3();
        let c = l.color.as_vec3();
        LightGpu {
            position: [p.x, p.y, p.z, layer as f32],
            axis_x: axis(l.rotation.x_axis, l.sector_colors.len() as f32),
            axis_y: axis(l.rotation.y_axis, first_sector as f32),
            axis_z: axis(l.rotation.z_axis, 0.0),
            color: [c.x, c.y, c.z, l.candela_scale() as f32],
        }
    }
}

/// The luminaires' distinct distributions (one atlas layer per file) and their records.
pub struct GpuLights {
    /// `array<Light>` (at least one element, so it can be bound).
    pub buffer: wgpu::Buffer,
    /// The effect lights' sector colours (`sector_colors`, at least one element).
    pub sectors: wgpu::Buffer,
    /// Number of lights.
    pub count: u32,
    /// The distributions.
    pub atlas: LdtAtlas,
    /// Their Catmull-Rom tables (the `CatmullRomTable` light model), drawn on first use:
    /// uploads (every animation frame of the viewer) pay nothing for them otherwise.
    tables: std::sync::OnceLock<LdtTables>,
    /// Their Catmull-Rom cube maps (the `CatmullRomCube` light model), made on first use
    /// from `textures`.
    cubes: std::sync::OnceLock<LdtTables>,
    /// The distributions of the atlas's layers, in order (for the cube maps).
    textures: Vec<LdtTexture>,
    /// The one-texel stand-in bound for every other light model.
    no_tables: LdtTables,
}

impl GpuLights {
    /// Uploads `luminaires`; luminaires with the same distribution share a layer.
    pub fn new(gpu: &Gpu, luminaires: &[PlacedLuminaire]) -> GpuLights {
        let mut textures: Vec<&LdtTexture> = Vec::new();
        let mut records = Vec::with_capacity(luminaires.len());
        let mut sectors: Vec<[f32; 4]> = Vec::new();
        for l in luminaires {
            let t = &l.texture;
            let same = |o: &&LdtTexture| {
                (o.c_count, o.gamma_count) == (t.c_count, t.gamma_count)
                    && (o.gamma_start_deg, o.gamma_step_deg)
                        == (t.gamma_start_deg, t.gamma_step_deg)
                    && o.data == t.data
            };
            let layer = match textures.iter().position(same) {
                Some(k) => k,
                None => {
                    textures.push(t);
                    textures.len() - 1
                }
            };
            records.push(LightGpu::new(l, layer as u32, sectors.len() as u32));
            sectors.extend(l.sector_colors.iter().map(|c| {
                let c = c.as_vec3();
                [c.x, c.y, c.z, 1.0]
            }));
        }
        let atlas = if textures.is_empty() {
            LdtAtlas::empty(gpu)
        } else {
            LdtAtlas::new(gpu, &textures)
        };
        let count = records.len() as u32;
        if records.is_empty() {
            records.push(bytemuck::Zeroable::zeroed());
        }
        let buffer = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("lights"),
                contents: bytemuck::cast_slice(&records),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            });
        if sectors.is_empty() {
            sectors.push([1.0; 4]);
        }
        let sectors = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sector colours"),
                contents: bytemuck::cast_slice(&sectors),
                usage: wgpu::BufferUsages::STORAGE,
            });
        GpuLights {
            buffer,
            sectors,
            count,
            tables: std::sync::OnceLock::new(),
            cubes: std::sync::OnceLock::new(),
            textures: textures.into_iter().cloned().collect(),
            no_tables: LdtTables::empty(gpu),
            atlas,
        }
    }
}

impl GpuLights {
    /// The Catmull-Rom tables or cube maps `model` reads: made (once) for
    /// `CatmullRomTable` and `CatmullRomCube`, the empty stand-in otherwise.
    pub fn tables(&self, gpu: &Gpu, model: super::LightModel) -> &LdtTables {
        match model {
            super::LightModel::CatmullRomTable => {
                self.tables.get_or_init(|| LdtTables::new(gpu, &self.atlas))
            }
            super::LightModel::CatmullRomCube => self
                .cubes
                .get_or_init(|| LdtTables::cubes(gpu, &self.textures)),
            _ => &self.no_tables,
        }
    }
}

/// One draw call: a range of the index buffer with one material.
#[derive(Debug, Clone, Copy)]
pub struct Draw {
    /// First index.
    pub first_index: u32,
    /// Number of indices.
    pub index_count: u32,
    /// Material index.
    pub material: usize,
}

/// Material parameters (`MaterialParams` in `shaders/scene.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MaterialGpu {
    diffuse: [f32; 4],
    specular: [f32; 4],
    flags: [u32; 4],
    texture_mean: [f32; 4],
    transmittance: [f32; 4],
}

/// The uploaded scene.
pub struct GpuScene {
    /// Vertices of every mesh.
    pub vertices: wgpu::Buffer,
    /// Indices of every mesh.
    pub indices: wgpu::Buffer,
    /// Draw calls, grouped by material.
    pub draws: Vec<Draw>,
    /// One bind group per material (group 1).
    pub materials: Vec<wgpu::BindGroup>,
    /// Per material, whether its diffuse map's alpha cuts holes (drawn by the pipelines
    /// that test them; the others keep early depth tests).
    pub masked: Vec<bool>,
    /// The luminaires.
    pub lights: GpuLights,
    /// Number of triangles.
    pub triangle_count: usize,
    /// Every triangle as one mesh: the shadow casters.
    pub casters: Mesh,
    /// The holes of its alpha-masked triangles.
    pub cutouts: Option<Arc<crate::shadow::Cutouts>>,
    /// The object of each caster triangle ([`Scene::caster_objects`]).
    caster_objects: Vec<u32>,
    /// The luminaires as shadow-casting lights, in the order of `lights`.
    pub shadow_lights: Vec<ShadowLight>,
    /// The radiosity light map (a 1 × 1 black texture when there is none).
    pub light_map: wgpu::TextureView,
    /// Whether a solved light map is shown instead of the direct diffuse light.
    pub has_light_map: bool,
    volume_geometry: OnceLock<Option<VolumeGeometry>>,
    paraboloid_casters: Mutex<Option<(f64, Arc<ParaboloidCasters>)>>,
}

impl GpuScene {
    /// Uploads `scene`.
    pub fn new(gpu: &Gpu, layouts: &Layouts, scene: &Scene) -> GpuScene {
        GpuScene::with_light_map(gpu, layouts, scene, None)
    }

    /// Uploads `scene` with a solved radiosity light map: its triangles then get their
    /// own vertices (each has its own place in the atlas).
    pub fn with_light_map(
        gpu: &Gpu,
        layouts: &Layouts,
        scene: &Scene,
        light_map: Option<&LightMap>,
    ) -> GpuScene {
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        // First triangle of each mesh in scene order (the light map's numbering).
        let first_triangle: Vec<usize> = scene
            .meshes
            .iter()
            .scan(0, |next, m| {
                let first = *next;
                *next += m.indices.len() / 3;
                Some(first)
            })
            .collect();
        let mut order: Vec<usize> = (0..scene.meshes.len()).collect();
        order.sort_by_key(|&i| scene.meshes[i].material);
        let mut draws: Vec<Draw> = Vec::new();
        for i in order {
            let m = &scene.meshes[i];
            let tangents = m.tangents();
            let vertex = |k: usize, lightmap_uv: Vec2| Vertex {
                position: m.positions[k].to_array(),
                normal: m.normals[k].to_array(),
                uv: m.uvs[k].to_array(),
                tangent: tangents[k],
                lightmap_uv: lightmap_uv.to_array(),
            };
            let first_index = indices.len() as u32;
            match light_map {
                None => {
                    let base = vertices.len() as u32;
                    vertices.extend((0..m.positions.len()).map(|k| vertex(k, Vec2::ZERO)));
                    indices.extend(m.indices.iter().map(|k| k + base));
                }
                Some(map) => {
                    for (t, corners) in m.indices.chunks_exact(3).enumerate() {
                        let uv = map
                            .triangle_uv
                            .get(first_triangle[i] + t)
                            .copied()
                            .unwrap_or([Vec2::ZERO; 3]);
                        for c in 0..3 {
                            indices.push(vertices.len() as u32);
                            vertices.push(vertex(corners[c] as usize, uv[c]));
                        }
                    }
                }
            }
            let index_count = indices.len() as u32 - first_index;
            match draws.last_mut() {
                Some(d)
                    if d.material == m.material && d.first_index + d.index_count == first_index =>
                {
                    d.index_count += index_count
                }
                _ => draws.push(Draw {
                    first_index,
                    index_count,
                    material: m.material,
                }),
            }
        }
        if vertices.is_empty() {
            vertices.push(bytemuck::Zeroable::zeroed());
            indices.extend([0, 0, 0]);
        }
        let dev = &gpu.device;
        let vertex_buffer = dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("vertices"),
            contents: bytemuck::cast_slice(&vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let index_buffer = dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("indices"),
            contents: bytemuck::cast_slice(&indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        let materials = scene
            .materials
            .iter()
            .map(|m| material_bind_group(gpu, layouts, m))
            .collect();
        GpuScene {
            vertices: vertex_buffer,
            indices: index_buffer,
            draws,
            materials,
            masked: scene
                .materials
                .iter()
                .map(|m| m.alpha_mask.is_some())
                .collect(),
            lights: GpuLights::new(gpu, &scene.luminaires),
            triangle_count: scene.triangle_count(),
            casters: scene.caster_mesh(),
            cutouts: scene.caster_cutouts(),
            caster_objects: scene.caster_objects(),
            shadow_lights: scene
                .luminaires
                .iter()
                .map(|l| ShadowLight {
                    position: l.position,
                    rotation: l.rotation,
                    hemisphere: l.texture.hemisphere,
                    ignored: scene.ignored_by(l),
                })
                .collect(),
            light_map: lightmap::upload(gpu, light_map),
            has_light_map: light_map.is_some(),
            volume_geometry: OnceLock::new(),
            paraboloid_casters: Mutex::new(None),
        }
    }

    /// Shows `map` instead of the light map uploaded with the scene, which must have the
    /// same layout ([`LightMap::same_layout`]: the vertices keep their atlas places).
    pub fn set_light_map(&mut self, gpu: &Gpu, map: &LightMap) {
        self.light_map = lightmap::upload(gpu, Some(map));
        self.has_light_map = true;
    }

    /// The casters prepared for shadow volumes (built on first use; `None` when the
    /// scene has no usable triangle).
    pub fn volume_geometry(&self, gpu: &Gpu) -> Option<&VolumeGeometry> {
        self.volume_geometry
            .get_or_init(|| VolumeGeometry::new(gpu, &self.casters, "scene").ok())
            .as_ref()
    }

    /// The volume geometry if [`GpuScene::volume_geometry`] has built it.
    pub fn volume_geometry_if_built(&self) -> Option<&VolumeGeometry> {
        self.volume_geometry.get().and_then(|g| g.as_ref())
    }

    /// The casters tessellated to `max_edge` metres for paraboloid maps (cached).
    pub fn paraboloid_casters(&self, gpu: &Gpu, max_edge: f64) -> Arc<ParaboloidCasters> {
        let mut cache = self
            .paraboloid_casters
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        match &*cache {
            Some((edge, casters)) if *edge == max_edge => casters.clone(),
            _ => {
                let cutouts = self.cutouts.as_deref();
                let merged =
                    super::paraboloid::merged_casters(&self.casters, &self.caster_objects, cutouts);
                let casters = Arc::new(ParaboloidCasters::new(
                    gpu,
                    &merged,
                    &self.casters,
                    cutouts,
                    max_edge,
                ));
                *cache = Some((max_edge, casters.clone()));
                casters
            }
        }
    }

    /// The distance stored as depth 1 in the paraboloid maps: the farthest caster
    /// vertex from any luminaire, with a margin.
    pub fn shadow_far(&self) -> f32 {
        let far = self
            .shadow_lights
            .iter()
            .flat_map(|l| {
                self.casters
                    .positions
                    .iter()
                    .map(move |p| p.distance(l.position))
            })
            .fold(1.0f64, f64::max);
        (far * 1.05) as f32
    }

    /// Records the draw calls (bind group 1 and the buffers are set here), each material
    /// with `pipelines[0]`, or `pipelines[1]` where it is alpha-masked.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, pipelines: [&wgpu::RenderPipeline; 2]) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        let mut bound = None;
        for d in &self.draws {
            let masked = self.masked.get(d.material).copied().unwrap_or(false);
            if bound != Some(masked) {
                pass.set_pipeline(pipelines[usize::from(masked)]);
                bound = Some(masked);
            }
            pass.set_bind_group(1, &self.materials[d.material], &[]);
            pass.draw_indexed(d.first_index..d.first_index + d.index_count, 0, 0..1);
        }
    }
}

/// Uploads a material texture with its full mip chain (see [`super::mipmaps`]).
fn upload_rgba(
    gpu: &Gpu,
    img: &image::RgbaImage,
    format: wgpu::TextureFormat,
) -> wgpu::TextureView {
    let kind = if format.is_srgb() {
        TexelKind::SrgbColour
    } else {
        TexelKind::Normal
    };
    let chain = mip_chain(img, kind);
    let data: Vec<u8> = chain
        .iter()
        .flat_map(|l| l.as_raw().iter().copied())
        .collect();
    let texture = gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("material texture"),
            size: wgpu::Extent3d {
                width: img.width(),
                height: img.height(),
                depth_or_array_layers: 1,
            },
            mip_level_count: chain.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    texture.create_view(&Default::default())
}

fn material_bind_group(gpu: &Gpu, layouts: &Layouts, m: &Material) -> wgpu::BindGroup {
    let one_pixel = |rgba: [u8; 4]| image::RgbaImage::from_pixel(1, 1, image::Rgba(rgba));
    let diffuse = match &m.diffuse_map {
        Some(img) => upload_rgba(gpu, img, wgpu::TextureFormat::Rgba8UnormSrgb),
        None => upload_rgba(
            gpu,
            &one_pixel([255; 4]),
            wgpu::TextureFormat::Rgba8UnormSrgb,
        ),
    };
    let normal = match &m.normal_map {
        Some(img) => upload_rgba(gpu, img, wgpu::TextureFormat::Rgba8Unorm),
        None => upload_rgba(
            gpu,
            &one_pixel([128, 128, 255, 255]),
            wgpu::TextureFormat::Rgba8Unorm,
        ),
    };
    let params = MaterialGpu {
        diffuse: [
            m.diffuse.x,
            m.diffuse.y,
            m.diffuse.z,
            m.diffuse_map.is_some() as u32 as f32,
        ],
        specular: [m.specular.x, m.specular.y, m.specular.z, m.shininess],
        flags: [
            m.normal_map.is_some() as u32,
            m.alpha_mask.is_some() as u32,
            0,
            0,
        ],
        texture_mean: m.texture_mean().extend(1.0).to_array(),
        transmittance: m.diffuse_transmittance.extend(0.0).to_array(),
    };
    let buffer = gpu.uniform_buffer("material", &params);
    gpu.bind_group(
        &m.name,
        &layouts.material,
        &[
            (0, buffer.as_entire_binding()),
            (1, wgpu::BindingResource::TextureView(&diffuse)),
            (2, wgpu::BindingResource::TextureView(&normal)),
            (3, wgpu::BindingResource::Sampler(&layouts.material_sampler)),
        ],
    )
}
