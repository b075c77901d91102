//! Tone mapping and false colour: the statistics pass (GPU, per tile), the automatic
//! settings derived from it (CPU), and the full-screen pass that writes the sRGB image.
//!
//! - Exposure: y = 1 − e^(−k·x) per channel; automatic k puts the log-average luminance
//!   at 0.3 on the display.
//! - Reinhard's global operator (Reinhard et al. 2002) with the automatic key of Reinhard
//!   2002 ("Parameter estimation for photographic tone reproduction"):
//!   a = 0.18 · 4^((2 log₂ L̄ − log₂ L_min − log₂ L_max) / (log₂ L_max − log₂ L_min)) and
//!   L_white = 1.5 · 2^(log₂ L_max − log₂ L_min − 5).
//! - False colour: lux on a colour scale from 0 to `lux_max`.

use glam::Vec3;

use super::targets::{Targets, LDR_FORMAT};
use crate::gpu::{shaders, Gpu, GpuError};
use crate::scene::{Mode, Tonemap};

/// The false-colour scale: (position 0..1, sRGB colour).
pub const FALSE_COLOUR_STOPS: [(f32, [u8; 3]); 8] = [
    (0.0, [20, 10, 70]),
    (0.14, [30, 60, 200]),
    (0.29, [20, 160, 230]),
    (0.43, [40, 190, 90]),
    (0.57, [225, 225, 40]),
    (0.71, [250, 150, 20]),
    (0.86, [225, 30, 20]),
    (1.0, [255, 170, 230]),
];

fn srgb_to_linear(c: u8) -> f32 {
    let v = c as f32 / 255.0;
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear → 8-bit sRGB.
pub fn linear_to_srgb(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 {
        v * 12.92
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// The false colour (linear RGB) of `t` in 0..1: the CPU twin of `false_colour` in
/// `shaders/tonemap.wgsl` (the legend uses it).
pub fn false_colour(t: f32) -> Vec3 {
    let x = t.clamp(0.0, 1.0);
    let lin = |c: [u8; 3]| {
        Vec3::new(
            srgb_to_linear(c[0]),
            srgb_to_linear(c[1]),
            srgb_to_linear(c[2]),
        )
    };
    let mut c = lin(FALSE_COLOUR_STOPS[0].1);
    for w in FALSE_COLOUR_STOPS.windows(2) {
        let ((a, ca), (b, cb)) = (w[0], w[1]);
        if x >= a && x <= b {
            c = lin(ca).lerp(lin(cb), (x - a) / (b - a).max(1e-6));
        }
    }
    c
}

/// Image statistics over pixels that show a surface.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct ImageStats {
    /// Surface pixels.
    pub pixels: u64,
    /// Log-average luminance, cd/m².
    pub log_average_luminance: f64,
    /// Smallest non-zero luminance.
    pub min_luminance: f64,
    /// Largest luminance.
    pub max_luminance: f64,
    /// Largest illuminance, lux.
    pub max_lux: f64,
    /// Mean illuminance, lux.
    pub mean_lux: f64,
}

impl ImageStats {
    /// Sums the per-tile records of the statistics pass.
    pub fn from_tiles(tiles: &[f32]) -> ImageStats {
        let (mut sum_log, mut count, mut min, mut max, mut max_lux, mut sum_lux) =
            (0.0f64, 0.0f64, f64::INFINITY, 0.0f64, 0.0f64, 0.0f64);
        for t in tiles.chunks_exact(8) {
            sum_log += t[0] as f64;
            count += t[1] as f64;
            if t[1] > 0.0 {
                min = min.min(t[2] as f64);
                max = max.max(t[3] as f64);
            }
            max_lux = max_lux.max(t[4] as f64);
            sum_lux += t[5] as f64;
        }
        if count == 0.0 {
            return ImageStats::default();
        }
        ImageStats {
            pixels: count as u64,
            log_average_luminance: (sum_log / count).exp(),
            min_luminance: if min.is_finite() && min < 1e30 {
                min
            } else {
                0.0
            },
            max_luminance: max,
            max_lux,
            mean_lux: sum_lux / count,
        }
    }
}

/// What the tone-mapping pass does, resolved from the settings and the statistics.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ToneSettings {
    /// Shaded or false colour.
    #[serde(skip)]
    pub mode: Mode,
    /// The operator in shaded mode.
    #[serde(skip)]
    pub tonemap: Tonemap,
    /// k of the exposure operator, 1/(cd/m²).
    pub exposure_k: f64,
    /// Log-average luminance of the image, cd/m².
    pub log_average: f64,
    /// Reinhard key a.
    pub key: f64,
    /// Reinhard L_white (in scaled units).
    pub white: f64,
    /// Top of the false-colour scale, lux.
    pub lux_max: f64,
}

impl ToneSettings {
    /// Resolves automatic values from `stats`; `exposure` and `lux_max` override them.
    pub fn resolve(
        mode: Mode,
        tonemap: Tonemap,
        exposure: Option<f64>,
        lux_max: Option<f64>,
        stats: &ImageStats,
    ) -> ToneSettings {
        let avg = stats.log_average_luminance.max(1e-6);
        let exposure_k = exposure.unwrap_or(-(1.0f64 - 0.3).ln() / avg);
        let (lmin, lmax) = (
            stats.min_luminance.max(1e-4).log2(),
            stats.max_luminance.max(2e-4).log2(),
        );
        let range = (lmax - lmin).max(1e-3);
        let key = 0.18 * 4f64.powf((2.0 * avg.log2() - lmin - lmax) / range);
        let white = (1.5 * 2f64.powf(range - 5.0)).max(1.0);
        let lux_max = lux_max.unwrap_or_else(|| nice_ceil(stats.max_lux.min(3.0 * stats.mean_lux)));
        ToneSettings {
            mode,
            tonemap,
            exposure_k,
            log_average: avg,
            key,
            white,
            lux_max,
        }
    }
}

impl ToneSettings {
    /// The display colour (linear RGB, 0..1) of one HDR pixel: the CPU reference of
    /// `fs_tonemap` in `shaders/tonemap.wgsl`.
    pub fn map_pixel(&self, hdr: [f32; 4], background: Vec3) -> Vec3 {
        if hdr[3] < 0.0 {
            return background;
        }
        let rgb = Vec3::new(hdr[0], hdr[1], hdr[2]);
        match (self.mode, self.tonemap) {
            (Mode::Illuminance, _) => false_colour(hdr[3] / self.lux_max as f32),
            (Mode::Shaded, Tonemap::Exposure) => {
                Vec3::ONE - (-(self.exposure_k as f32) * rgb).exp()
            }
            (Mode::Shaded, Tonemap::Reinhard) => {
                let lw = rgb.dot(Vec3::new(0.2126, 0.7152, 0.0722));
                if lw <= 0.0 {
                    return Vec3::ZERO;
                }
                let l = (self.key / self.log_average) as f32 * lw;
                let white2 = (self.white * self.white) as f32;
                let ld = l * (1.0 + l / white2) / (1.0 + l);
                (rgb * (ld / lw)).min(Vec3::ONE)
            }
        }
    }
}

/// The smallest of 1, 2, 2.5, 5 × 10ⁿ that is ≥ `x` (1 for x ≤ 0).
pub fn nice_ceil(x: f64) -> f64 {
    if !x.is_finite() || x <= 0.0 {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|v| *v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// `ToneParams` in `shaders/tonemap.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ToneParamsGpu {
    tone_operator: u32,
    stop_count: u32,
    pad: [u32; 2],
    k: f32,
    key_scale: f32,
    inv_white2: f32,
    lux_max: f32,
    background: [f32; 4],
    stops: [[f32; 4]; 16],
}

/// The statistics and tone-mapping pipelines.
pub struct ToneMapper {
    stats: wgpu::ComputePipeline,
    tonemap: wgpu::RenderPipeline,
}

const TILE: u32 = 16;

impl ToneMapper {
    /// Compiles the pipelines.
    pub fn new(gpu: &Gpu) -> ToneMapper {
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("tonemap"),
                source: wgpu::ShaderSource::Wgsl(shaders::TONEMAP.into()),
            });
        let stats = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("image statistics"),
                layout: None,
                module: &module,
                entry_point: Some("stats"),
                compilation_options: Default::default(),
                cache: None,
            });
        let tonemap = gpu
            .device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("tonemap"),
                layout: None,
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_fullscreen"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_tonemap"),
                    compilation_options: Default::default(),
                    targets: &[Some(LDR_FORMAT.into())],
                }),
                multiview_mask: None,
                cache: None,
            });
        ToneMapper { stats, tonemap }
    }

    /// Statistics of the HDR target (runs on the GPU, reads back one record per tile).
    pub fn statistics(&self, gpu: &Gpu, targets: &Targets) -> Result<ImageStats, GpuError> {
        let (tx, ty) = (targets.width.div_ceil(TILE), targets.height.div_ceil(TILE));
        let tiles = gpu.output_buffer("statistics tiles", (tx * ty * 32) as u64);
        let bind = gpu.bind_group(
            "statistics",
            &self.stats.get_bind_group_layout(0),
            &[
                (0, wgpu::BindingResource::TextureView(&targets.hdr_view)),
                (2, tiles.as_entire_binding()),
            ],
        );
        let tiles = gpu.dispatch_and_read(&self.stats, &bind, [tx, ty, 1], &tiles)?;
        Ok(ImageStats::from_tiles(&tiles))
    }

    /// Records the tone-mapping pass from the HDR target into the sRGB image.
    pub fn record(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        targets: &Targets,
        tone: &ToneSettings,
        background: Vec3,
    ) {
        let mut stops = [[0f32; 4]; 16];
        for (i, (t, _)) in FALSE_COLOUR_STOPS.iter().enumerate() {
            let c = false_colour(*t);
            stops[i] = [c.x, c.y, c.z, *t];
        }
        let params = ToneParamsGpu {
            key_scale: (tone.key / tone.log_average) as f32,
            tone_operator: match (tone.mode, tone.tonemap) {
                (Mode::Illuminance, _) => 2,
                (Mode::Shaded, Tonemap::Exposure) => 0,
                (Mode::Shaded, Tonemap::Reinhard) => 1,
            },
            stop_count: FALSE_COLOUR_STOPS.len() as u32,
            pad: [0; 2],
            k: tone.exposure_k as f32,
            inv_white2: (1.0 / (tone.white * tone.white)) as f32,
            lux_max: tone.lux_max as f32,
            background: [background.x, background.y, background.z, 1.0],
            stops,
        };
        let buffer = gpu.uniform_buffer("tone params", &params);
        let bind = gpu.bind_group(
            "tonemap",
            &self.tonemap.get_bind_group_layout(0),
            &[
                (0, wgpu::BindingResource::TextureView(&targets.hdr_view)),
                (1, buffer.as_entire_binding()),
            ],
        );
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("tonemap"),
            color_attachments: &[Some(crate::gpu::cleared_attachment(
                &targets.ldr_view,
                wgpu::Color::BLACK,
            ))],
            ..Default::default()
        });
        pass.set_pipeline(&self.tonemap);
        pass.set_bind_group(0, &bind, &[]);
        pass.draw(0..3, 0..1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_ceil_rounds_up_to_1_2_2_5_5() {
        assert_eq!(nice_ceil(0.0), 1.0);
        assert_eq!(nice_ceil(1.0), 1.0);
        assert_eq!(nice_ceil(1.3), 2.0);
        assert_eq!(nice_ceil(2.2), 2.5);
        assert_eq!(nice_ceil(430.0), 500.0);
        assert_eq!(nice_ceil(501.0), 1000.0);
    }

    #[test]
    fn false_colour_hits_its_stops_and_srgb_round_trips() {
        for (t, c) in FALSE_COLOUR_STOPS {
            let v = false_colour(t);
            assert_eq!(
                [
                    linear_to_srgb(v.x),
                    linear_to_srgb(v.y),
                    linear_to_srgb(v.z)
                ],
                c
            );
        }
        assert_eq!(false_colour(-1.0), false_colour(0.0));
        assert_eq!(false_colour(7.0), false_colour(1.0));
    }

    #[test]
    fn automatic_key_is_0_18_for_a_symmetric_range() {
        // log-average in the middle of the range (in log₂) gives the base key 0.18.
        let stats = ImageStats {
            pixels: 10,
            log_average_luminance: 10.0,
            min_luminance: 1.0,
            max_luminance: 100.0,
            max_lux: 0.0,
            mean_lux: 0.0,
        };
        let t = ToneSettings::resolve(Mode::Shaded, Tonemap::Reinhard, None, None, &stats);
        assert!((t.key - 0.18).abs() < 1e-12);
        // Exposure: the log-average maps to 0.3.
        assert!((1.0 - (-t.exposure_k * 10.0).exp() - 0.3).abs() < 1e-12);
    }
}
