//! `goniolight demo`: the main job on the bundled data.
//!
//! Renders the bundled furnished room (`assets/scenes/furnished_room.toml`) shaded and in
//! false-colour illuminance (PNG + EXR) with its interreflected light (a radiosity solution
//! run for `--indirect-time` seconds, shown through the light map; `--indirect none` for
//! the direct light alone), then runs the interpolation check on the bundled
//! raw lab measurement (`luminaires/eulumdat-analysis/sample_18.ldt`, 1° × 1°)
//! downsampled to the 15° × 5° grid of a typical manufacturer file, prints the table, and
//! writes the polar diagram and the check as JSON.

use std::path::PathBuf;

use clap::Args;

use super::error::CliError;
use super::image::{render_to_files, ImageOptions};
use crate::gpu::Gpu;
use crate::io::write_atomic;
use crate::photometry::polar_diagram::write_polar_diagram;
use crate::photometry::{check, check_text, Luminaire};
use crate::render::Renderer;
use crate::scene::{DisplayIndirect, Mode};

/// The bundled luminaire of the demo.
pub static DEMO_LUMINAIRE: &[u8] =
    include_bytes!("../../luminaires/eulumdat-analysis/sample_18.ldt");

/// Options of `demo`.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Where to write the outputs.
    #[arg(long, default_value = "out")]
    pub out_dir: PathBuf,
    /// The scene to render (default: the bundled furnished room).
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Image options (override the scene's `[display]`; the mode is set per image).
    #[command(flatten)]
    pub image: ImageOptions,
    /// Indirect light (default: radiosity, for --indirect-time seconds).
    #[command(flatten)]
    pub indirect: super::indirect::IndirectArgs,
}

/// The bundled furnished room (the checkout's, or the copy extracted from the binary).
pub fn default_scene() -> Result<PathBuf, CliError> {
    crate::io::bundled::default_scene().map_err(CliError::failure)
}

/// Renders the scene shaded and in false-colour illuminance.
fn render_both(args: &DemoArgs, staging: &crate::io::outputs::Staging) -> Result<(), CliError> {
    let dir = staging.dir();
    let scene_path = match &args.scene {
        Some(p) => p.clone(),
        None => default_scene()?,
    };
    let scene = super::scene_input::scene_at(
        super::scene_input::load_scene(&scene_path)?,
        args.image.time,
    )?;
    let gpu = Gpu::shared()?;
    println!("GPU: {}", gpu.describe());
    // One solution for both images.
    let choice = args.indirect.choice(&scene, DisplayIndirect::Radiosity);
    let mut base = args.image.settings(&scene)?;
    let map = super::indirect::light_map(
        &scene_path,
        &scene,
        &mut base,
        choice,
        args.indirect.indirect_time,
    )?;
    if let Some((_, what)) = &map {
        println!("{what}");
    }
    let renderer = Renderer::new(&gpu);
    for (mode, stem) in [
        (Mode::Shaded, "room-shaded"),
        (Mode::Illuminance, "room-illuminance"),
    ] {
        let mut opts = args.image.clone();
        opts.mode = Some(mode);
        let settings = crate::render::RenderSettings {
            shown_light: base.shown_light,
            ..opts.settings(&scene)?
        };
        let png = dir.join(format!("{stem}.png"));
        let exr = dir.join(format!("{stem}.exr"));
        let light_map = map.as_ref().map(|m| &m.0);
        let (_, report) = render_to_files(
            &gpu,
            &renderer,
            &scene,
            light_map,
            &settings,
            &png,
            Some(&exr),
        )?;
        println!("{}", staging.as_target(&report));
    }
    Ok(())
}

/// Runs the demo.
pub fn run(args: DemoArgs) -> Result<(), CliError> {
    let lum = Luminaire::from_bytes("luminaires/eulumdat-analysis/sample_18.ldt", DEMO_LUMINAIRE)?;
    if args.out_dir.is_file() {
        return Err(CliError::input(anyhow::anyhow!(
            "--out-dir {}: is a file, not a folder",
            args.out_dir.display()
        )));
    }
    // Complete or none: written beside the folder, moved in at the end.
    let inputs: Vec<PathBuf> = args.scene.iter().cloned().collect();
    let staging = crate::io::outputs::Staging::beside(&args.out_dir, &inputs)
        .map_err(|e| CliError::failure(anyhow::anyhow!("{}: {e}", args.out_dir.display())))?;
    render_both(&args, &staging)?;
    let dir = staging.dir();
    let s = lum.summary();
    println!(
        "sample_18.ldt: {} C planes × {} γ angles, integrated flux {:.1} lm (declared lamp flux {:.1} lm)",
        lum.distribution.grid().c_angles().len(),
        lum.distribution.grid().gamma_angles().len(),
        s.flux_lm,
        s.lamp_flux_lm
    );
    let (dc, dg) = (15.0, 5.0);
    let report = check::downsample(&lum.distribution, dc, dg)?;
    print!("{}", check_text::check_table(&report));
    let json = serde_json::to_string_pretty(&report).map_err(CliError::failure)?;
    write_atomic(&dir.join("check.json"), json.as_bytes()).map_err(CliError::failure)?;
    write_polar_diagram(
        &lum,
        "sample_18.ldt (lab measurement)",
        &dir.join("polar.png"),
        Some((dc, dg)),
    )?;
    staging
        .commit()
        .map_err(|e| CliError::failure(anyhow::anyhow!("{}: {e:#}", args.out_dir.display())))?;
    println!(
        "wrote {} and {}",
        args.out_dir.join("polar.png").display(),
        args.out_dir.join("check.json").display()
    );
    Ok(())
}
