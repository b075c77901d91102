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
use crate::scene::{Mode, Palette, Tonemap};

/// goniolight's default false-colour scale (see [`Palette`]).
pub use crate::scene::palette::RAINBOW_STOPS as FALSE_COLOUR_STOPS;

pub use crate::scene::palette::linear_to_srgb;

/// The colour (linear RGB) of `t` in 0..1 on the default palette (the legend of
/// images that carry no palette, e.g. the profile's hours).
pub fn false_colour(t: f32) -> Vec3 {
    Palette::Rainbow.colour(t)
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
    /// The distribution of illuminance over the surface pixels (illuminance mode).
    pub lux: Option<LuxPercentiles>,
}

/// Illuminance over an image's surface pixels: what a designer can quote. The maximum
/// of a view is usually a surface touching a luminaire (a housing, a ceiling a few
/// centimetres above a lamp), so it is reported beside the 99th percentile, not alone.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct LuxPercentiles {
    /// Mean, lux.
    pub mean: f64,
    /// 5th percentile, lux.
    pub p5: f64,
    /// Median, lux.
    pub median: f64,
    /// 95th percentile, lux.
    pub p95: f64,
    /// 99th percentile, lux.
    pub p99: f64,
    /// Maximum, lux.
    pub max: f64,
}

impl LuxPercentiles {
    /// The percentiles of the lux channel (alpha) of `hdr` over surface pixels (alpha ≥
    /// 0; nearest rank); `None` when no pixel shows a surface.
    pub fn of_pixels(hdr: &[[f32; 4]]) -> Option<LuxPercentiles> {
        let mut lux: Vec<f64> = hdr
            .iter()
            .filter(|p| p[3] >= 0.0 && p[3].is_finite())
            .map(|p| p[3] as f64)
            .collect();
        if lux.is_empty() {
            return None;
        }
        lux.sort_by(f64::total_cmp);
        let at = |q: f64| lux[((q * lux.len() as f64).ceil() as usize).clamp(1, lux.len()) - 1];
        Some(LuxPercentiles {
            mean: lux.iter().sum::<f64>() / lux.len() as f64,
            p5: at(0.05),
            median: at(0.5),
            p95: at(0.95),
            p99: at(0.99),
            max: lux[lux.len() - 1],
        })
    }
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
            lux: None,
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
    /// The false-colour palette.
    #[serde(skip)]
    pub palette: Palette,
    /// Hard colour bands on the scale (0: continuous).
    pub steps: u32,
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
        ToneSettings::resolve_scale(
            mode,
            tonemap,
            exposure,
            lux_max,
            (Palette::default(), 0),
            stats,
        )
    }

    /// [`ToneSettings::resolve`] with a palette and a number of hard steps (0:
    /// continuous). The automatic top of the lux scale is the first multiple of a nice
    /// step (1, 2, 2.5, 5 × 10ⁿ; 4–8 of them) at or above the 95th percentile where the
    /// percentiles are known (else the maximum, at most 3 × the mean): the brightest
    /// 5 % show the top colour, labelled "≥", and a few pixels touching a luminaire do
    /// not squash the scale. With steps, one step is itself a nice value.
    pub fn resolve_scale(
        mode: Mode,
        tonemap: Tonemap,
        exposure: Option<f64>,
        lux_max: Option<f64>,
        (palette, steps): (Palette, u32),
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
        let top = match stats.lux {
            Some(p) => p.p95,
            None => stats.max_lux.min(3.0 * stats.mean_lux),
        };
        let lux_max = lux_max.unwrap_or_else(|| match steps {
            0 => nice_top(top),
            n => n as f64 * nice_ceil(top / n as f64),
        });
        ToneSettings {
            mode,
            tonemap,
            exposure_k,
            log_average: avg,
            key,
            white,
            lux_max,
            palette,
            steps,
        }
    }

    /// The false colour (linear RGB) of `lux` on this scale.
    pub fn lux_colour(&self, lux: f32) -> Vec3 {
        self.palette
            .stepped_colour(lux / self.lux_max as f32, self.steps)
    }

    /// The legend's labels: every step's boundary with steps, else 4–8 nice divisions
    /// of the scale (0/100/200/…), the top marked "≥".
    pub fn legend_labels(&self) -> Vec<f64> {
        scale_labels(self.lux_max, self.steps)
    }
}

/// The label values of a scale from 0 to `top` with `steps` hard bands (0: continuous,
/// labelled at 4–8 nice divisions).
pub fn scale_labels(top: f64, steps: u32) -> Vec<f64> {
    let divisions = if steps > 0 {
        steps
    } else {
        nice_divisions(top)
    };
    (0..=divisions)
        .map(|k| top * k as f64 / divisions as f64)
        .collect()
}

/// The smallest multiple of a nice step at or above `x`, with at most 8 steps (614 →
/// 700, 187 → 200, 3418 → 3500; 1 for x ≤ 0).
pub fn nice_top(x: f64) -> f64 {
    if !x.is_finite() || x <= 0.0 {
        return 1.0;
    }
    let mut step = nice_ceil(x / 8.0);
    let top = (x / step * (1.0 - 1e-12)).ceil() * step;
    if top / step < 4.0 {
        step = nice_ceil(x / 4.0);
        return (x / step * (1.0 - 1e-12)).ceil() * step;
    }
    top
}

/// How many equal divisions of 0..`top` make nice labels: 4 to 8 steps of 1, 2, 2.5 or 5
/// × 10ⁿ where one fits (`top` 250 → 5 of 50, 1000 → 5 of 200), else 4.
pub fn nice_divisions(top: f64) -> u32 {
    (4..=8)
        .rev()
        .find(|&n| {
            let step = top / n as f64;
            (nice_ceil(step) - step).abs() <= 1e-9 * top
        })
        .unwrap_or(4)
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
            (Mode::Illuminance, _) => self.lux_colour(hdr[3]),
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
    steps: u32,
    supersample: u32,
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
    centres: wgpu::RenderPipeline,
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
        ToneMapper {
            stats,
            tonemap: gpu.fullscreen_pipeline(
                "tonemap",
                &module,
                ("vs_fullscreen", "fs_tonemap"),
                LDR_FORMAT,
            ),
            centres: gpu.fullscreen_pipeline(
                "centre samples",
                &module,
                ("vs_fullscreen", "fs_centre"),
                super::targets::HDR_FORMAT,
            ),
        }
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
        let mut stops = [[0f32; 4]; crate::scene::palette::MAX_STOPS];
        let palette = tone.palette.stops();
        for (i, (t, c)) in palette.iter().enumerate() {
            stops[i] = [c.x, c.y, c.z, *t];
        }
        let params = ToneParamsGpu {
            key_scale: (tone.key / tone.log_average) as f32,
            tone_operator: match (tone.mode, tone.tonemap) {
                (Mode::Illuminance, _) => 2,
                (Mode::Shaded, Tonemap::Exposure) => 0,
                (Mode::Shaded, Tonemap::Reinhard) => 1,
            },
            stop_count: palette.len() as u32,
            steps: tone.steps,
            supersample: targets.supersample,
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
                (0, wgpu::BindingResource::TextureView(&targets.shade_view)),
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

    /// Records the copy of every pixel's centre sample from the supersampled target into
    /// the HDR target (nothing without supersampling: the scene was drawn there).
    pub fn record_centres(&self, gpu: &Gpu, enc: &mut wgpu::CommandEncoder, targets: &Targets) {
        if targets.supersample == 1 {
            return;
        }
        let params = ToneParamsGpu {
            supersample: targets.supersample,
            ..bytemuck::Zeroable::zeroed()
        };
        let buffer = gpu.uniform_buffer("centre params", &params);
        let bind = gpu.bind_group(
            "centre samples",
            &self.centres.get_bind_group_layout(0),
            &[
                (0, wgpu::BindingResource::TextureView(&targets.shade_view)),
                (1, buffer.as_entire_binding()),
            ],
        );
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("centre samples"),
            color_attachments: &[Some(crate::gpu::cleared_attachment(
                &targets.hdr_view,
                wgpu::Color::TRANSPARENT,
            ))],
            ..Default::default()
        });
        pass.set_pipeline(&self.centres);
        pass.set_bind_group(0, &bind, &[]);
        pass.draw(0..3, 0..1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_tops_and_divisions_make_round_labels() {
        assert_eq!(nice_top(614.0), 700.0);
        assert_eq!(nice_top(187.0), 200.0);
        assert_eq!(nice_top(3418.0), 3500.0);
        assert_eq!(nice_top(250.0), 250.0);
        assert_eq!(nice_top(0.0), 1.0);
        assert_eq!(
            scale_labels(700.0, 0),
            [0.0, 100.0, 200.0, 300.0, 400.0, 500.0, 600.0, 700.0]
        );
        assert_eq!(
            scale_labels(250.0, 0),
            [0.0, 50.0, 100.0, 150.0, 200.0, 250.0]
        );
        assert_eq!(scale_labels(200.0, 0)[1], 25.0);
        assert_eq!(scale_labels(300.0, 3), [0.0, 100.0, 200.0, 300.0]);
        // Every automatic top divides into nice steps.
        for k in 1..2000 {
            let top = nice_top(k as f64 * 1.37);
            let labels = scale_labels(top, 0);
            let step = labels[1];
            assert_eq!(nice_ceil(step), step, "{top}: {labels:?}");
            assert!(
                top >= k as f64 * 1.37 && (5..=9).contains(&labels.len()),
                "{top}"
            );
        }
    }

    #[test]
    fn lux_percentiles_use_surface_pixels_only() {
        let mut hdr: Vec<[f32; 4]> = (1..=100).map(|k| [0.0, 0.0, 0.0, k as f32]).collect();
        hdr.push([0.0, 0.0, 0.0, -1.0]);
        hdr.push([0.0, 0.0, 0.0, 1e6]);
        let p = LuxPercentiles::of_pixels(&hdr).unwrap();
        assert_eq!(
            (p.p5, p.median, p.p95, p.p99, p.max),
            (6.0, 51.0, 96.0, 100.0, 1e6)
        );
        assert!((p.mean - (5050.0 + 1e6) / 101.0).abs() < 1e-9);
        assert!(LuxPercentiles::of_pixels(&[[0.0, 0.0, 0.0, -1.0]]).is_none());
    }

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
            lux: None,
        };
        let t = ToneSettings::resolve(Mode::Shaded, Tonemap::Reinhard, None, None, &stats);
        assert!((t.key - 0.18).abs() < 1e-12);
        // Exposure: the log-average maps to 0.3.
        assert!((1.0 - (-t.exposure_k * 10.0).exp() - 0.3).abs() < 1e-12);
    }
}
