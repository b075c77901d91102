//! Render targets of one image size: depth, HDR (linear luminance + illuminance) and the
//! displayable sRGB image. With supersampling s (odd), the scene is drawn at s × s samples
//! per pixel into a larger HDR target; the numbers (HDR, statistics, EXR) are the centre
//! sample of each pixel — exactly the pixel-centre values of s = 1 — and the displayed
//! image averages the s × s tone-mapped samples (anti-aliased edges and textures).

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
    /// Samples per pixel side (1 or odd).
    pub supersample: u32,
    /// Depth and stencil (the stencil counts shadow volumes), at the render size.
    pub depth_view: wgpu::TextureView,
    /// The HDR target the scene is drawn into, at the render size (a view of `hdr` when
    /// `supersample` is 1).
    pub shade_view: wgpu::TextureView,
    /// HDR texture.
    pub hdr: wgpu::Texture,
    /// Its view.
    pub hdr_view: wgpu::TextureView,
    /// sRGB image.
    pub ldr: wgpu::Texture,
    /// Its view.
    pub ldr_view: wgpu::TextureView,
}

/// Bytes a supersampled pixel takes: depth-stencil and RGBA32F colour.
const SUPERSAMPLED_BYTES_PER_PIXEL: u64 = 24;
/// The most the supersampled targets may take, bytes.
const MAX_SUPERSAMPLED_BYTES: u64 = 1 << 30;

impl Targets {
    /// Creates targets of `width` × `height` without supersampling.
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Targets {
        Targets::with_supersample(gpu, width, height, 1)
    }

    /// The supersampling actually used for `width` × `height` when `wanted` is asked for:
    /// odd (an even factor has no centre sample), and 1 when the render size would pass
    /// the device's largest texture.
    pub fn supersample_for(gpu: &Gpu, width: u32, height: u32, wanted: u32) -> u32 {
        let mut s = wanted.max(1) | 1;
        let max = gpu.device.limits().max_texture_dimension_2d;
        if width.max(height).saturating_mul(s) > max {
            return 1;
        }
        // The supersampled depth and colour targets stay within a memory budget (a
        // software device runs out long before its largest texture).
        let pixels = |s: u32| u64::from(width * s) * u64::from(height * s);
        while s > 1 && pixels(s) * SUPERSAMPLED_BYTES_PER_PIXEL > MAX_SUPERSAMPLED_BYTES {
            s -= 2;
        }
        s
    }

    /// Creates targets of `width` × `height` drawn with `supersample` × `supersample`
    /// samples per pixel (see [`Targets::supersample_for`]).
    pub fn with_supersample(gpu: &Gpu, width: u32, height: u32, supersample: u32) -> Targets {
        let s = Targets::supersample_for(gpu, width, height, supersample);
        let make_sized = |label, format, usage, view_formats: &[wgpu::TextureFormat], k: u32| {
            gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: width * k,
                    height: height * k,
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
        let make = |label, format, usage, view_formats: &[wgpu::TextureFormat]| {
            make_sized(label, format, usage, view_formats, 1)
        };
        use wgpu::TextureUsages as U;
        let depth = make_sized(
            "depth",
            gpu.depth_stencil_format(),
            U::RENDER_ATTACHMENT,
            &[],
            s,
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
        let shade_view = if s == 1 {
            hdr.create_view(&Default::default())
        } else {
            make_sized(
                "supersampled hdr",
                HDR_FORMAT,
                U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
                &[],
                s,
            )
            .create_view(&Default::default())
        };
        Targets {
            width,
            height,
            supersample: s,
            shade_view,
            depth_view: depth.create_view(&Default::default()),
            hdr_view: hdr.create_view(&Default::default()),
            hdr,
            ldr_view: ldr.create_view(&Default::default()),
            ldr,
        }
    }
}

impl Targets {
    /// The size the scene is drawn at: (width, height) × supersample.
    pub fn render_size(&self) -> (u32, u32) {
        (
            self.width * self.supersample,
            self.height * self.supersample,
        )
    }
}
