//! The Catmull-Rom tables of an LDT atlas (`shaders/ldt_table.wgsl`), drawn once on the
//! GPU: per layer one row per γ knot of the stored grid (plus the two knots Catmull-Rom
//! reads beyond either end) and one column per 0.125° of C, holding the Catmull-Rom
//! interpolation across the C planes at that knot, as 16-bit floats. Catmull-Rom is a
//! tensor product, so the renderer's `CatmullRomTable` light model — the γ spline over
//! four table rows, linear across two columns, two texel gathers instead of 16 loads and
//! the 2D spline — is the per-pixel spline up to the linear step in C and the 16-bit
//! rounding: within 1e-3 · I_max (checked by `tests/gpu/gpu_ldt.rs` for every bundled file,
//! with [`table_value`] as the CPU twin of the lookup).

use super::LdtAtlas;
use crate::gpu::{shaders, Gpu};
use crate::photometry::{Interp, LdtTexture};

/// Columns: C from 0° in 0.125° steps (wrapping at 360°).
pub const TABLE_COLUMNS: u32 = 2880;
/// Rows besides the stored γ knots: two padding knots beyond either end.
pub const TABLE_PADDING_ROWS: u32 = 4;
/// Texel format (filterable on every backend).
pub const TABLE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;

/// The tables of every layer of an atlas, with their filtering sampler; or, for the
/// `CatmullRomCube` light model, the cube maps of [`super::cube`] (the other half
/// is then a one-texel stand-in: WGSL needs every binding filled).
pub struct LdtTables {
    /// A `D2Array` view, one layer per atlas layer.
    pub view: wgpu::TextureView,
    /// A `CubeArray` view, one cube per atlas layer.
    pub cube: wgpu::TextureView,
    /// Bilinear, C repeating, γ clamped.
    pub sampler: wgpu::Sampler,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct TableParams {
    layer: u32,
    columns: u32,
    pad: [u32; 2],
}

impl LdtTables {
    /// A one-texel table bound where no light uses the tables (WGSL needs every
    /// binding filled); nothing is drawn.
    pub fn empty(gpu: &Gpu) -> LdtTables {
        LdtTables::with_texture(gpu, &LdtTables::one_texel(gpu), None)
    }

    /// The cube maps of `textures` (one per atlas layer, in order), with a one-texel table.
    pub fn cubes(gpu: &Gpu, textures: &[LdtTexture]) -> LdtTables {
        let cube = super::cube::cube_array(gpu, textures, super::cube::CUBE_SIZE);
        LdtTables::with_texture(gpu, &LdtTables::one_texel(gpu), Some(cube))
    }

    fn one_texel(gpu: &Gpu) -> wgpu::Texture {
        gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("no catmull-rom tables"),
            size: wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: TABLE_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
    }

    /// The table `texture` and the cube maps `cube` (a one-texel stand-in when `None`).
    fn with_texture(
        gpu: &Gpu,
        texture: &wgpu::Texture,
        cube: Option<wgpu::TextureView>,
    ) -> LdtTables {
        let cube = cube.unwrap_or_else(|| super::cube::cube_array(gpu, &[], 1));
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("catmull-rom tables"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        LdtTables {
            view: texture.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2Array),
                ..Default::default()
            }),
            cube,
            sampler,
        }
    }

    /// Draws the tables of every layer of `atlas` (one layer of zeros when it has none).
    pub fn new(gpu: &Gpu, atlas: &LdtAtlas) -> LdtTables {
        let layers = atlas.layers.max(1) as u32;
        // The atlas is as wide as its longest γ row.
        let rows = atlas.texture.width() + TABLE_PADDING_ROWS;
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("catmull-rom tables"),
            size: wgpu::Extent3d {
                width: TABLE_COLUMNS,
                height: rows,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: TABLE_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("ldt table"),
                source: wgpu::ShaderSource::Wgsl(shaders::ldt_table().into()),
            });
        let pipeline =
            gpu.fullscreen_pipeline("ldt table", &module, ("vs_table", "fs_table"), TABLE_FORMAT);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        for layer in 0..layers {
            let view = crate::gpu::layer_view(&texture, layer);
            let params = gpu.uniform_buffer(
                "ldt table params",
                &TableParams {
                    layer,
                    columns: TABLE_COLUMNS,
                    pad: [0; 2],
                },
            );
            let bind = gpu.bind_group(
                "ldt table",
                &pipeline.get_bind_group_layout(0),
                &[
                    (0, wgpu::BindingResource::TextureView(&atlas.view)),
                    (1, atlas.info.as_entire_binding()),
                    (2, params.as_entire_binding()),
                ],
            );
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("ldt table"),
                color_attachments: &[Some(crate::gpu::cleared_attachment(
                    &view,
                    wgpu::Color::TRANSPARENT,
                ))],
                ..Default::default()
            });
            if (layer as usize) < atlas.layers {
                pass.set_pipeline(&pipeline);
                pass.set_bind_group(0, &bind, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        gpu.queue.submit([enc.finish()]);
        LdtTables::with_texture(gpu, &texture, None)
    }
}

/// The CPU twin of a table lookup (`ldt_table_lookup` in `shaders/lighting.wgsl`): the
/// exact Catmull-Rom values of `t` at the two table columns of C around (C, γ),
/// interpolated linearly (the γ part of the lookup is the spline itself).
pub fn table_value(t: &LdtTexture, c_deg: f64, gamma_deg: f64) -> f64 {
    let step = 360.0 / TABLE_COLUMNS as f64;
    let x = c_deg.rem_euclid(360.0) / step;
    let (i, f) = (x.floor(), x - x.floor());
    let at = |col: f64| {
        t.sample(
            (col * step).rem_euclid(360.0),
            gamma_deg,
            Interp::CatmullRom,
        )
    };
    at(i) * (1.0 - f) + at(i + 1.0) * f
}
