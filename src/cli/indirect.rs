//! `--indirect none|ambient|radiosity` of `render` and `demo`: the light surfaces send each
//! other, shown beside the luminaires' direct light — an ambient estimate from their first
//! bounce, or a radiosity solution run for a time budget — through the radiosity solver's
//! light map.

use std::path::Path;
use std::time::Instant;

use clap::Args;

use super::error::CliError;
use super::solving::solve;
use crate::radiosity::session::Options;
use crate::render::lightmap::LightMap;
use crate::render::RenderSettings;
use crate::scene::{DisplayIndirect, Scene};

/// The indirect-light options of `render` and `demo`.
#[derive(Debug, Clone, Args)]
pub struct IndirectArgs {
    /// Light shown besides the luminaires' direct light: none (direct only, exact per
    /// pixel), ambient (their first bounce spread evenly: an estimate) or radiosity (a
    /// solution run for --indirect-time); both at the light map's resolution (default:
    /// the scene's display.indirect, else none for render and radiosity for demo).
    #[arg(long, value_enum)]
    pub indirect: Option<DisplayIndirect>,
    /// With --indirect radiosity: seconds of shooting.
    #[arg(long, value_name = "S", default_value_t = 10.0, value_parser = super::args::seconds_arg)]
    pub indirect_time: f64,
}

impl IndirectArgs {
    /// What to show: the flag, else the scene's `display.indirect`, else `default`.
    pub fn choice(&self, scene: &Scene, default: DisplayIndirect) -> DisplayIndirect {
        self.indirect.or(scene.display.indirect).unwrap_or(default)
    }
}

/// The light map that shows `choice` for `scene` (`label`: its file, for messages), and
/// a line saying what it holds; `None` for [`DisplayIndirect::None`]. Sets
/// `settings.shown_light`.
pub fn light_map(
    label: &Path,
    scene: &Scene,
    settings: &mut RenderSettings,
    choice: DisplayIndirect,
    seconds: f64,
) -> Result<Option<(LightMap, String)>, CliError> {
    settings.shown_light = choice;
    let Some(options) = Options::shown_indirect(choice, seconds) else {
        return Ok(None);
    };
    let started = Instant::now();
    let solved = solve(label, scene, &options, settings, started)?;
    let what = solved.shown_summary(choice, started.elapsed().as_secs_f64());
    Ok(Some((solved.light_map(), what)))
}
