//! `goniolight illuminance`: the direct illuminance at points read from stdin.

use std::path::PathBuf;

use clap::Args;

use super::error::CliError;
use super::scene_input::{load_scene, scene_at, warn_shadow_fit};
use crate::gpu::Gpu;
use crate::lighting::read_points;
use crate::photometry::Interp;
use crate::render::illuminance::scene_illuminance;
use crate::render::ShadowTechnique;

/// Options of `illuminance`.
#[derive(Debug, Args)]
pub struct IlluminanceArgs {
    /// The scene file (TOML); its luminaires and its `[sky]` light the points.
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
    /// Seconds since the start of the animation (effect lights turned this far), or a
    /// local date and time at the scene's `[site]` (`2026-03-21T12:00`): the time of its
    /// `[sky]` (the sun's position).
    #[arg(long)]
    pub time: Option<String>,
    /// The sky, replacing the scene's `[sky] model`: `cie-overcast`, `cie-clear`, `cie:1`
    /// … `cie:15` or `uniform` (a scene without `[sky]` gets 10 000 lx of it, no sun).
    /// Daylight reaches the points through the model's openings and glazing.
    #[arg(long, value_name = "MODEL")]
    pub sky: Option<String>,
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
pub fn run(args: IlluminanceArgs) -> Result<(), CliError> {
    let seconds = args
        .time
        .as_deref()
        .and_then(|t| t.trim().parse::<f64>().ok());
    let sky_time = args.time.as_deref().filter(|_| seconds.is_none());
    let scene = scene_at(load_scene(&args.scene)?, seconds)?
        .with_sky(args.sky.as_deref(), sky_time)
        .map_err(|e| CliError::input(anyhow::anyhow!("--sky/--time: {e}")))?;
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
    // Every value was checked by the library (a wrong number is refused, −0 is 0).
    for (v, p) in lux.into_iter().zip(&points) {
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
