//! The image options shared by `render`, `demo` and `radiosity` (flags over the scene's
//! `[display]`), and an image rendered to its files with the line that reports it.

use std::path::Path;
use std::time::Instant;

use anyhow::anyhow;
use clap::Args;

use super::error::{flags_in, CliError};
use super::scene_input::warn_once;
use crate::gpu::Gpu;
use crate::photometry::Interp;
use crate::render::lightmap::LightMap;
use crate::render::output::{linear_image, write_image};
use crate::render::quality::RenderQuality;
use crate::render::scene_frame::{render_scene, SceneFrame};
use crate::render::{RenderSettings, RenderedFrame, Renderer, ShadowTechnique, VolumeTest};
use crate::scene::{DisplayEntry, Mode, Palette, Scene, Tonemap};
use crate::shadow::SilhouetteMethod;

/// Image options shared by `render` and `demo`.
#[derive(Debug, Args, Clone, Default)]
pub struct ImageOptions {
    /// Image width in pixels.
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels.
    #[arg(long)]
    pub height: Option<u32>,
    /// Interpolation of the light distributions.
    #[arg(long, value_enum)]
    pub interp: Option<Interp>,
    /// Shaded image or false-colour illuminance (lux).
    #[arg(long, value_enum)]
    pub mode: Option<Mode>,
    /// Tone-mapping operator.
    #[arg(long, value_enum)]
    pub tonemap: Option<Tonemap>,
    /// k of the exposure operator y = 1 − e^(−k·x), in 1/(cd/m²) (default: automatic).
    #[arg(long)]
    pub exposure: Option<f64>,
    /// Top of the false-colour scale in lux (default: a nice value at or above the
    /// image's 99th percentile).
    #[arg(long)]
    pub lux_max: Option<f64>,
    /// False-colour palette (viridis, cividis and inferno are perceptually uniform and
    /// readable with colour blindness).
    #[arg(long, value_enum)]
    pub palette: Option<Palette>,
    /// Hard colour bands on the false-colour scale, DIALux style (1–20; default smooth).
    #[arg(long)]
    pub steps: Option<u32>,
    /// Anti-aliasing: N × N samples per pixel for the displayed image (1, 3 or 5; the
    /// lux and luminance values are the pixel centres either way).
    #[arg(long, default_value_t = 3)]
    pub supersample: u32,
    /// Seconds since the start of the animation: effect lights (`spin_deg_per_s`) are
    /// drawn turned this far (default 0).
    #[arg(long)]
    pub time: Option<f64>,
    /// Shadows of the luminaires (default: the scene's `display.shadows`, else
    /// paraboloid maps, the sensible choice for point-like luminaires).
    #[arg(long, value_enum)]
    pub shadows: Option<ShadowTechnique>,
    /// Shadow volumes: z-pass, z-fail, or chosen per light by the near-clip-volume test.
    #[arg(long, value_enum, default_value = "auto")]
    pub volume_test: VolumeTest,
    /// Shadow volumes: how silhouettes are found.
    #[arg(long, value_enum, default_value = "hextree")]
    pub silhouettes: SilhouetteMethod,
    /// Paraboloid shadow-map side in texels, per hemisphere and luminaire (default 1024).
    #[arg(long)]
    pub shadow_map_size: Option<u32>,
    /// Debug view: draw the shadow volumes (translucent yellow) and silhouette edges
    /// (pink) over the image (shadow-volume mode).
    #[arg(long)]
    pub show_volumes: bool,
}

impl ImageOptions {
    /// The `[display]` settings these flags give (the overlay on the scene's).
    pub fn display(&self) -> DisplayEntry {
        DisplayEntry {
            mode: self.mode,
            tonemap: self.tonemap,
            exposure: self.exposure,
            interp: self.interp,
            width: self.width,
            height: self.height,
            lux_max: self.lux_max,
            palette: self.palette,
            steps: self.steps,
            shadows: self.shadows,
            ..Default::default()
        }
    }

    /// The scene's display settings with these options applied (checked by the one
    /// validator of `[display]`; a value out of range names its flag).
    pub fn settings(&self, scene: &Scene) -> Result<RenderSettings, CliError> {
        let display = scene.display.overlay(&self.display());
        display.check()?;
        let quality = RenderQuality {
            supersample: self.supersample,
            shadow_map_size: self.shadow_map_size,
        };
        let mut s = quality
            .apply(RenderSettings::from_display(&display))
            .map_err(|e| CliError::input(anyhow!(flags_in(&e.to_string()))))?;
        s.shadows.volume_test = self.volume_test;
        s.shadows.silhouette = self.silhouettes;
        s.shadows.show_volumes = self.show_volumes;
        s.shadows.show_silhouettes = self.show_volumes;
        Ok(s)
    }
}

/// Renders `scene` with `settings` (with a solved radiosity light map when given) and
/// writes the PNG (and EXR): the shared body of `render`, `demo` and `radiosity`. Returns
/// the frame and a one-line report for the caller to print.
pub fn render_to_files(
    gpu: &Gpu,
    renderer: &Renderer,
    scene: &Scene,
    light_map: Option<&LightMap>,
    settings: &RenderSettings,
    png: &Path,
    exr: Option<&Path>,
) -> Result<(RenderedFrame, String), CliError> {
    let mut settings = settings.clone();
    settings.read_hdr = exr.is_some();
    let started = Instant::now();
    let rendered = render_scene(gpu, renderer, scene, light_map, &settings)?;
    let what = rendered.light_summary();
    let SceneFrame {
        frame,
        settings,
        warnings,
    } = rendered;
    for w in &warnings {
        warn_once(&scene.path, w);
    }
    let ms = started.elapsed().as_millis();
    write_image(png, &frame.image).map_err(CliError::failure)?;
    if let Some(exr) = exr {
        let linear = linear_image(&frame, settings.width, settings.height)
            .ok_or_else(|| CliError::failure(anyhow!("no HDR values were read back")))?;
        write_image(exr, &linear).map_err(CliError::failure)?;
    }
    let report = format!(
        "{}: {} triangles, {} luminaires, {}×{} in {ms} ms; {what} → {}{}",
        scene.path.display(),
        scene.triangle_count(),
        scene.luminaires.len(),
        settings.width,
        settings.height,
        png.display(),
        exr.map(|e| format!(", {}", e.display()))
            .unwrap_or_default()
    );
    Ok((frame, report))
}
