//! Render targets of one image size: depth, HDR (linear luminance + illuminance) and the
//! displayable sRGB image.

use crate::gpu::Gpu;

/// HDR target: rgb = luminance (cd/m²), a = direct illuminance (lux), −1 where no surface.
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The displayable image.
pub const LDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// The targets.
pub struct Targets {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Depth and stencil (the stencil counts shadow volumes).
    pub depth_view: wgpu::TextureView,
    /// HDR texture.
    pub hdr: wgpu::Texture,
    /// Its view.
    pub hdr_view: wgpu::TextureView,
    /// sRGB image.
    pub ldr: wgpu::Texture,
    /// Its view.
    pub ldr_view: wgpu::TextureView,
}

impl Targets {
    /// Creates targets of `width` × `height`.
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Targets {
        let make = |label, format, usage, view_formats: &[wgpu::TextureFormat]| {
            gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats,
            })
        };
        use wgpu::TextureUsages as U;
        let depth = make(
            "depth",
            gpu.depth_stencil_format(),
            U::RENDER_ATTACHMENT,
            &[],
        );
        let hdr = make(
            "hdr",
            HDR_FORMAT,
            U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC,
            &[],
        );
        // Sampled too: the viewer shows its sRGB-encoded bytes as they are (egui's
        // textures are gamma-encoded `Rgba8Unorm`).
        let ldr = make(
            "ldr",
            LDR_FORMAT,
            U::RENDER_ATTACHMENT | U::COPY_SRC | U::TEXTURE_BINDING,
            &[wgpu::TextureFormat::Rgba8Unorm],
        );
        Targets {
            width,
            height,
            depth_view: depth.create_view(&Default::default()),
            hdr_view: hdr.create_view(&Default::default()),
            hdr,
            ldr_view: ldr.create_view(&Default::default()),
            ldr,
        }
    }
}
