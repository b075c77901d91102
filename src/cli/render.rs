//! `goniolight render`: one image of a scene, with the indirect light asked for
//! ([`super::indirect`]); the image options are [`super::image`]'s.

use clap::Args;
use std::path::{Path, PathBuf};

use anyhow::anyhow;

use super::error::CliError;
use super::image::{render_to_files, ImageOptions};
use super::indirect::{light_map, IndirectArgs};
use super::scene_input::{load_scene, scene_at};
use crate::gpu::Gpu;
use crate::render::Renderer;
use crate::scene::DisplayIndirect;

/// Options of `render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// The image to write (PNG).
    #[arg(long)]
    pub out: PathBuf,
    /// Also write linear values as OpenEXR (cd/m² when shaded, lux in illuminance mode).
    #[arg(long)]
    pub exr: Option<PathBuf>,
    /// Image options (override the scene's `[display]`).
    #[command(flatten)]
    pub image: ImageOptions,
    /// Indirect light.
    #[command(flatten)]
    pub indirect: IndirectArgs,
}

fn check_extension(path: &Path, ext: &str, flag: &str) -> Result<(), CliError> {
    let ok = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext));
    if ok {
        Ok(())
    } else {
        Err(CliError::input(anyhow!(
            "{flag} {}: the file name must end in .{ext}",
            path.display()
        )))
    }
}

/// Runs `render`.
pub fn run(args: RenderArgs) -> Result<(), CliError> {
    check_extension(&args.out, "png", "--out")?;
    if let Some(e) = &args.exr {
        check_extension(e, "exr", "--exr")?;
    }
    let scene = scene_at(load_scene(&args.scene)?, args.image.time)?;
    let mut outputs = crate::io::outputs::OutputCheck::new();
    for f in scene.input_files() {
        outputs.input(f);
    }
    outputs.named_output(&format!("--out {}", args.out.display()), &args.out);
    if let Some(e) = &args.exr {
        outputs.named_output(&format!("--exr {}", e.display()), e);
    }
    outputs.check()?;
    let mut settings = args.image.settings(&scene)?;
    if scene.daylight.is_some() {
        if settings.mode == crate::scene::Mode::Illuminance {
            return Err(CliError::input(anyhow!(
                "{}: render does not draw daylight yet, so its lux would leave out the scene's [sky]; `goniolight illuminance` and `goniolight radiosity --points` give daylight at points (or remove [sky])",
                args.scene.display()
            )));
        }
        eprintln!(
            "warning: render does not draw the scene's [sky] yet (the luminaires alone are shown)"
        );
    }
    let choice = args.indirect.choice(&scene, DisplayIndirect::None);
    let map = light_map(
        &args.scene,
        &scene,
        &mut settings,
        choice,
        args.indirect.indirect_time,
    )?;
    let gpu = Gpu::shared()?;
    let renderer = Renderer::new(&gpu);
    let (_, report) = render_to_files(
        &gpu,
        &renderer,
        &scene,
        map.as_ref().map(|m| &m.0),
        &settings,
        &args.out,
        args.exr.as_deref(),
    )?;
    println!("{report}");
    if let Some((_, what)) = &map {
        println!("{what}");
    }
    Ok(())
}
