//! The solver's flags, shared by `radiosity`, `calc --indirect radiosity` and the
//! benchmarks: each a field of the library's `radiosity::session::Options`.

use anyhow::anyhow;
use clap::Args;

use super::error::CliError;
use crate::radiosity::gpu::{Raster, Visibility};
use crate::radiosity::links::DEFAULT_LINK_ERROR;
use crate::radiosity::session::Options;
use crate::radiosity::shooters::{Hierarchy, DEFAULT_CELL_POWER};
use crate::radiosity::view::Drive;
use crate::radiosity::{Ambient, FormFactorKind};

/// The solver's options, shared by `radiosity` and `calc --indirect radiosity`.
#[derive(Debug, Clone, Args)]
pub struct SolverArgs {
    /// Stop when this fraction of the initial unshot power has been shot (0..1).
    #[arg(long, default_value_t = 0.99)]
    pub converge: f64,
    /// Stop after this many shots.
    #[arg(long)]
    pub max_shots: Option<usize>,
    /// Stop after this many seconds of shooting.
    #[arg(long, value_parser = super::args::seconds_arg)]
    pub time_limit: Option<f64>,
    /// Elements (light-map texels) per metre.
    #[arg(long, default_value_t = 10.0)]
    pub texel_density: f64,
    /// Shooting patches are 2^LEVEL × 2^LEVEL texels (substructuring; 0: every texel).
    #[arg(long, default_value_t = 2)]
    pub level: u32,
    /// Adaptive subdivision (Wallner §2.4): split elements of 1 / --texel-density up to
    /// LEVELS times (each halving their side) where a luminaire's shadow or beam edge
    /// crosses them; the light map's texels are the finest elements. 0: uniform elements.
    #[arg(long, value_name = "LEVELS", default_value_t = 0)]
    pub adaptive: u32,
    /// With --adaptive: split a block only where the share of its points a luminaire
    /// lights lies in LOWER,UPPER (Wallner's b_l, b_u; none and all never split).
    #[arg(
        long,
        value_name = "LOWER,UPPER",
        value_delimiter = ',',
        default_values_t = [0.0, 1.0]
    )]
    pub adaptive_share: Vec<f64>,
    /// Visibility maps of the shooting patches.
    #[arg(long, value_enum, default_value = "hemicube")]
    pub visibility: Visibility,
    /// Side of a hemicube face or of the stereographic map, texels.
    #[arg(long, default_value_t = 256)]
    pub map_size: u32,
    /// How the visibility maps are drawn: by the GPU's render pipeline (`hardware`), or
    /// by compute shaders on all of its units (`compute`: a data-centre GPU has only a
    /// few units that do graphics); `auto` takes compute on a GPU and the render
    /// pipeline on a software driver (lavapipe) or with alpha-masked casters.
    #[arg(long, value_enum, default_value = "auto")]
    pub raster: Raster,
    /// Who shoots: every triangle from its own patches (`none`, the flat solver), or the
    /// flat face clusters of Edström's hierarchy as a whole (`clusters`): a surface drawn
    /// as thousands of triangles is one shooter.
    #[arg(long, value_enum, default_value = "clusters")]
    pub hierarchy: Hierarchy,
    /// With `--hierarchy clusters`: the largest share of the initial unshot power one
    /// shooting cell may carry; smaller is finer and slower (the oracle that sizes a
    /// cluster's shooting cells from its power).
    #[arg(long, default_value_t = DEFAULT_CELL_POWER)]
    pub cell_power: f64,
    /// With `--hierarchy clusters`: the irradiance error a receiver accepts from taking a
    /// coarse cell's light as one source, as a share of the mean initial exitance (the
    /// links' oracle: far receivers take a cluster's light from a few coarse cells, near
    /// ones from the fine cells); 0 links every receiver to the finest cells.
    #[arg(long, default_value_t = DEFAULT_LINK_ERROR)]
    pub link_error: f64,
    /// Form factor from a patch to an element.
    #[arg(long, value_enum, default_value = "polygon")]
    pub form_factor: FormFactorKind,
    /// Ambient term: for display only, also for overshooting, or none.
    #[arg(long, value_enum, default_value = "display")]
    pub ambient: Ambient,
    /// What chooses the work, from the scene's camera (Bozalina 2011): `global` shoots
    /// the most unshot power to every element; `importance` weighs each shooter by the
    /// importance the camera sends through the scene (what the view will see of its
    /// light); `perspective` also limits the receivers to the view's frustum plus
    /// --fov-margin, widened as the view's light settles (what waited is caught up).
    /// With importance and perspective, convergence and the displayed ambient term are
    /// the view's.
    #[arg(long, value_enum, default_value = "global")]
    pub drive: Drive,
    /// With --drive perspective: degrees added to the camera's half field of view for
    /// the first area of interest (each later stage adds 30°).
    #[arg(long, value_name = "DEG", default_value_t = 10.0)]
    pub fov_margin: f64,
}

impl SolverArgs {
    /// The library's options these flags give (`adaptive_share` must hold two values:
    /// [`SolverArgs::check`]).
    pub fn options(&self) -> Options {
        let share = match self.adaptive_share[..] {
            [lower, upper] => [lower, upper],
            _ => [f64::NAN; 2],
        };
        Options {
            converge: self.converge,
            max_shots: self.max_shots,
            time_limit: self.time_limit,
            texel_density: self.texel_density,
            level: self.level,
            adaptive: self.adaptive,
            adaptive_share: share,
            visibility: self.visibility,
            map_size: self.map_size,
            raster: self.raster,
            hierarchy: self.hierarchy,
            cell_power: self.cell_power,
            link_error: self.link_error,
            form_factor: self.form_factor,
            ambient: self.ambient,
            drive: self.drive,
            fov_margin: self.fov_margin,
            importance_time_limit: None,
        }
    }

    /// The options, or an error naming the flag whose value is out of range.
    pub fn check(&self) -> Result<Options, CliError> {
        if self.adaptive_share.len() != 2 {
            let given: Vec<String> = self.adaptive_share.iter().map(f64::to_string).collect();
            return Err(CliError::input(anyhow!(
                "--adaptive-share {}: give LOWER,UPPER with 0 ≤ LOWER ≤ UPPER ≤ 1",
                given.join(",")
            )));
        }
        let options = self.options();
        options.validate()?;
        Ok(options)
    }
}

#[cfg(test)]
mod tests {
    use clap::{Args, FromArgMatches};

    use super::SolverArgs;
    use crate::radiosity::session::Options;

    fn parsed(args: &[&str]) -> SolverArgs {
        let command = SolverArgs::augment_args(clap::Command::new("radiosity"));
        let matches = command
            .try_get_matches_from(std::iter::once("radiosity").chain(args.iter().copied()))
            .unwrap();
        SolverArgs::from_arg_matches(&matches).unwrap()
    }

    #[test]
    fn the_flags_defaults_are_the_librarys() {
        assert_eq!(parsed(&[]).options(), Options::default());
    }

    #[test]
    fn a_value_out_of_range_names_its_flag() {
        let e = parsed(&["--map-size", "8"]).check().unwrap_err();
        assert_eq!(e.message(), "--map-size 8 is not in 16..=4096");
        let e = parsed(&["--adaptive-share", "0.5"]).check().unwrap_err();
        assert!(e
            .message()
            .starts_with("--adaptive-share 0.5: give LOWER,UPPER"));
    }
}
