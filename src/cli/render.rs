//! `goniolight render` and `goniolight illuminance`: a scene to images, and the direct
//! illuminance at points read from stdin.

use crate::render::scene_frame::{render_scene, SceneFrame};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::anyhow;
use clap::Args;

use super::error::{flags_in, CliError};
use crate::gpu::Gpu;
use crate::lighting::read_points;
use crate::photometry::Interp;
use crate::render::illuminance::scene_illuminance;
use crate::render::legend::format_lux;
use crate::render::lightmap::LightMap;
use crate::render::output::{linear_image, write_image};
use crate::render::{
    RenderSettings, RenderedFrame, Renderer, ShadowTechnique, VolumeTest, MAX_IMAGE_SIZE,
};
use crate::scene::{DisplayEntry, DisplayIndirect, Mode, Palette, Scene, Tonemap};
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

/// The scene file at `path`, what its loading worked around printed as warnings on stderr.
pub fn load_scene(path: &std::path::Path) -> Result<Scene, CliError> {
    let scene = Scene::load(path)?;
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    Ok(scene)
}

/// `scene` at `--time` seconds (effect lights turned); an error when it is not finite.
pub fn scene_at(scene: Scene, time: Option<f64>) -> Result<Scene, CliError> {
    match time {
        None => Ok(scene),
        Some(t) if t.is_finite() => Ok(scene.at_time(t)),
        Some(t) => Err(CliError::input(anyhow!(
            "--time {t} is not a finite number"
        ))),
    }
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
        let mut s = RenderSettings::from_display(&display);
        if let Some(size) = self.shadow_map_size {
            if !(16..=MAX_IMAGE_SIZE).contains(&size) {
                return Err(CliError::input(anyhow!(
                    "--shadow-map-size {size} is not in 16..={MAX_IMAGE_SIZE}"
                )));
            }
            s.shadows.map_size = size;
        }
        if ![1, 3, 5].contains(&self.supersample) {
            return Err(CliError::input(anyhow!(
                "--supersample {} must be 1, 3 or 5 (an odd count has a sample at the pixel centre)",
                self.supersample
            )));
        }
        s.supersample = self.supersample;
        s.shadows.volume_test = self.volume_test;
        s.shadows.silhouette = self.silhouettes;
        s.shadows.show_volumes = self.show_volumes;
        s.shadows.show_silhouettes = self.show_volumes;
        Ok(s)
    }
}

/// The illuminance line of a report: percentiles over the surface pixels, the maximum
/// beside the 99th percentile (it is usually a surface touching a luminaire), the scale.
fn lux_report(frame: &RenderedFrame, light: DisplayIndirect) -> String {
    let scale = format!("scale 0–{} lx", format_lux(frame.tone.lux_max));
    match frame.stats.lux {
        Some(p) => {
            let note = if p.max > 5.0 * p.p99 {
                " (a few pixels next to a luminaire: quote the percentiles)"
            } else {
                ""
            };
            format!(
                "illuminance ({}) over the surfaces in view: mean {:.0} lx, median {:.0}, 5 % {:.0}, 95 % {:.0}, 99 % {:.0}, max {:.0}{note}; {scale}",
                light.describe(),
                p.mean,
                p.median,
                p.p5,
                p.p95,
                p.p99,
                p.max
            )
        }
        None => format!("no surface in view; {scale}"),
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
    let SceneFrame {
        frame,
        settings,
        warnings,
    } = render_scene(gpu, renderer, scene, light_map, &settings)?;
    for w in &warnings {
        warn_once(&scene.path, w);
    }
    let ms = started.elapsed().as_secs_f64() * 1e3;
    write_image(png, &frame.image).map_err(CliError::failure)?;
    if let Some(exr) = exr {
        let linear = linear_image(&frame, settings.width, settings.height)
            .ok_or_else(|| CliError::failure(anyhow!("no HDR values were read back")))?;
        write_image(exr, &linear).map_err(CliError::failure)?;
    }
    let what = match settings.mode {
        Mode::Shaded => format!(
            "log-average luminance {:.1} cd/m², max {:.0} cd/m²",
            frame.stats.log_average_luminance, frame.stats.max_luminance
        ),
        Mode::Illuminance => lux_report(&frame, settings.shown_light),
    };
    let report = format!(
        "{}: {} triangles, {} luminaires, {}×{} in {ms:.0} ms; {what} → {}{}",
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

/// Options of `illuminance`.
#[derive(Debug, Args)]
pub struct IlluminanceArgs {
    /// The scene file (TOML); its luminaires are used.
    pub scene: PathBuf,
    /// Compute on the CPU (the reference) instead of with the renderer's WGSL code.
    #[arg(long)]
    pub cpu: bool,
    /// Interpolation of the light distributions.
    #[arg(long, value_enum, default_value = "catmull-rom")]
    pub interp: Interp,
    /// Shadows cast by the scene's geometry (default: the scene's `display.shadows`, else
    /// paraboloid). For points, `volumes` means exact hard shadows (a ray cast from each
    /// point toward each luminaire); `--cpu` always ray casts unless `none`.
    #[arg(long, value_enum)]
    pub shadows: Option<ShadowTechnique>,
    /// Seconds since the start of the animation (effect lights turned this far).
    #[arg(long)]
    pub time: Option<f64>,
    /// Output: one lux value per line (`plain`), or each point with its value as CSV
    /// (`x,y,z,nx,ny,nz,lux` with a header) or JSON (`[{"position", "normal", "lux"}]`).
    #[arg(long, value_enum, default_value = "plain")]
    pub format: PointsFormat,
}

/// How `illuminance` prints its values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PointsFormat {
    /// One value per line.
    Plain,
    /// The points with their values, CSV.
    Csv,
    /// The points with their values, JSON.
    Json,
}

/// Runs `illuminance`.
pub fn run_illuminance(args: IlluminanceArgs) -> Result<(), CliError> {
    let scene = scene_at(load_scene(&args.scene)?, args.time)?;
    let points = read_points(std::io::stdin().lock(), "stdin")?;
    let technique = args.shadows.or(scene.display.shadows).unwrap_or_default();
    let gpu = if args.cpu { None } else { Some(Gpu::shared()?) };
    let mut shadows = crate::render::ShadowSettings::with(technique);
    let lux = scene_illuminance(gpu.as_ref(), &scene, &points, args.interp, &mut shadows)?;
    warn_shadow_fit(&scene, &shadows);
    let mut out = String::with_capacity(lux.len() * 12);
    let mut json = Vec::new();
    if args.format == PointsFormat::Csv {
        out.push_str("x,y,z,nx,ny,nz,lux\n");
    }
    for (i, (v, p)) in lux.into_iter().zip(&points).enumerate() {
        // A wrong number is refused, never printed (−0 and rounding below 0 print as 0).
        if !v.is_finite() || v < -1e-6 {
            return Err(CliError::failure(anyhow::anyhow!(
                "point {}: the computed illuminance {v} lx is not a usable number",
                i + 1
            )));
        }
        let v = if v > 0.0 { v } else { 0.0 };
        let (x, n) = (p.position, p.normal);
        match args.format {
            PointsFormat::Plain => out.push_str(&format!("{v:.6}\n")),
            PointsFormat::Csv => out.push_str(&format!(
                "{},{},{},{},{},{},{v:.6}\n",
                x.x, x.y, x.z, n.x, n.y, n.z
            )),
            PointsFormat::Json => json.push(serde_json::json!({
                "position": x.to_array(),
                "normal": n.to_array(),
                "lux": v,
            })),
        }
    }
    if args.format == PointsFormat::Json {
        out = serde_json::to_string_pretty(&json).map_err(CliError::failure)? + "\n";
    }
    print!("{out}");
    Ok(())
}

/// What stencil shadow volumes cannot show, said once with the choice that shows it: they
/// start at a surface turned from the light, so a translucent surface lit from behind
/// stays dark in a direct render (a solved light map holds the transmitted light either
/// way); and they are built from whole triangles, so alpha-masked holes cast shadows.
/// Prints what the GPU's check changed in `shadows` (a coarser paraboloid tessellation).
pub(super) fn warn_shadow_fit(scene: &Scene, shadows: &crate::render::ShadowSettings) {
    if let Some(w) = shadows.warning() {
        warn_once(&scene.path, &w);
    }
}

/// Prints the library's warning `text` about `file` (options as flags) unless this process
/// printed it already (a solve and the render or calculation after it meet the same
/// limits).
pub(super) fn warn_once(file: &Path, text: &str) {
    use std::collections::HashSet;
    use std::sync::{Mutex, OnceLock};
    static SAID: OnceLock<Mutex<HashSet<String>>> = OnceLock::new();
    let line = format!("warning: {}: {}", file.display(), flags_in(text));
    let said = SAID.get_or_init(Default::default);
    if said.lock().map_or(true, |mut s| s.insert(line.clone())) {
        eprintln!("{line}");
    }
}
