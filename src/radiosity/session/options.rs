//! Every option of a radiosity solve in one validated value, with the command line's
//! defaults; its fields are named as the command's flags are (`map_size` is
//! `--map-size`), so a front end maps an [`OptionError`] to its own spelling in one place.

use std::time::Duration;

use super::super::elements::Subdivision;
use super::super::gpu::{GpuSettings, Raster, Visibility};
use super::super::links::DEFAULT_LINK_ERROR;
use super::super::shooters::{Hierarchy, DEFAULT_CELL_POWER};
use super::super::solve::StopAt;
use super::super::view::Drive;
use super::super::{Ambient, FormFactorKind, SolverSettings};
use crate::photometry::Interp;
use crate::scene::DisplayIndirect;

/// The options of a radiosity solve: what is solved (elements, shooters, form factors),
/// how the visibility maps are drawn, what drives the work and when it stops.
///
/// [`Options::default`] gives the command line's defaults (`goniolight radiosity` with
/// no flag).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Options {
    /// Stop when this fraction of the initial unshot power has been shot (0..=1; 0
    /// shoots nothing: the luminaires' first bounce and the ambient term).
    pub converge: f64,
    /// Stop after this many shots.
    pub max_shots: Option<usize>,
    /// Stop after this many seconds of shooting (the importance solve of a view-driven
    /// solution included).
    pub time_limit: Option<f64>,
    /// Elements (light-map texels) per metre.
    pub texel_density: f64,
    /// Shooting patches are 2^level × 2^level texels (0..=6).
    pub level: u32,
    /// Adaptive subdivision: elements split up to this many times (0..=4) where a
    /// luminaire's shadow or beam edge crosses them; 0: uniform elements.
    pub adaptive: u32,
    /// With `adaptive`: a block splits only where the share of its points a luminaire
    /// lights lies in (lower, upper).
    pub adaptive_share: [f64; 2],
    /// Visibility maps of the shooting patches.
    pub visibility: Visibility,
    /// Side of a hemicube face or of the stereographic map, texels (16..=4096).
    pub map_size: u32,
    /// How the visibility maps are drawn.
    pub raster: Raster,
    /// Who shoots: every triangle, or the flat face clusters as a whole.
    pub hierarchy: Hierarchy,
    /// With clusters: the largest share of the initial unshot power one shooting cell may
    /// carry, in (0, 1].
    pub cell_power: f64,
    /// With clusters: the irradiance error a receiver accepts from a coarse cell, as a
    /// share of the mean initial exitance, in [0, 1].
    pub link_error: f64,
    /// Form factor from a patch to an element.
    pub form_factor: FormFactorKind,
    /// Ambient term: for display only, also for overshooting, or none.
    pub ambient: Ambient,
    /// What chooses the work: the whole scene, or the camera's view.
    pub drive: Drive,
    /// With the perspective drive: degrees added to the camera's half field of view for
    /// the first area of interest (0..=180).
    pub fov_margin: f64,
    /// The longest a view-driven solution's importance solve may take, seconds (`None`:
    /// a quarter of `time_limit`, else no limit).
    pub importance_time_limit: Option<f64>,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            converge: 0.99,
            max_shots: None,
            time_limit: None,
            texel_density: 10.0,
            level: 2,
            adaptive: 0,
            adaptive_share: [0.0, 1.0],
            visibility: Visibility::Hemicube,
            map_size: 256,
            raster: Raster::Auto,
            hierarchy: Hierarchy::Clusters,
            cell_power: DEFAULT_CELL_POWER,
            link_error: DEFAULT_LINK_ERROR,
            form_factor: FormFactorKind::Polygon,
            ambient: Ambient::Display,
            drive: Drive::Global,
            fov_margin: 10.0,
            importance_time_limit: None,
        }
    }
}

/// An option out of its range: the field, the value given and what it must be.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field} {value} {problem}")]
pub struct OptionError {
    /// The field of [`Options`] (the command line's flag with `_` for `-`).
    pub field: &'static str,
    /// The value given, as written.
    pub value: String,
    /// What is wrong with it ("is not in 0..=1").
    pub problem: String,
}

impl OptionError {
    fn new(field: &'static str, value: impl ToString, problem: impl Into<String>) -> Self {
        OptionError {
            field,
            value: value.to_string(),
            problem: problem.into(),
        }
    }
}

/// `Err` naming `field` unless `ok`.
fn require(
    ok: bool,
    field: &'static str,
    value: impl ToString,
    problem: &str,
) -> Result<(), OptionError> {
    if ok {
        Ok(())
    } else {
        Err(OptionError::new(field, value, problem))
    }
}

fn positive_seconds(field: &'static str, t: Option<f64>) -> Result<(), OptionError> {
    match t {
        Some(t) => crate::io::limits::duration(t)
            .map(|_| ())
            .map_err(|_| OptionError::new(field, t, "must be a positive number of seconds")),
        None => Ok(()),
    }
}

impl Options {
    /// An error naming the first field out of its range.
    pub fn validate(&self) -> Result<(), OptionError> {
        let unit = |v: f64| v.is_finite() && (0.0..=1.0).contains(&v);
        require(
            unit(self.converge),
            "converge",
            self.converge,
            "is not in 0..=1",
        )?;
        require(
            self.texel_density.is_finite() && self.texel_density > 0.0,
            "texel_density",
            self.texel_density,
            "must be a positive number of texels per metre",
        )?;
        require(self.level <= 6, "level", self.level, "is not in 0..=6")?;
        require(
            self.adaptive <= 4,
            "adaptive",
            self.adaptive,
            "is not in 0..=4",
        )?;
        let [lower, upper] = self.adaptive_share;
        require(
            unit(lower) && unit(upper) && lower <= upper,
            "adaptive_share",
            format!("{lower},{upper}"),
            "must be LOWER,UPPER with 0 ≤ LOWER ≤ UPPER ≤ 1",
        )?;
        require(
            self.cell_power.is_finite() && self.cell_power > 0.0 && self.cell_power <= 1.0,
            "cell_power",
            self.cell_power,
            "is not in (0, 1]",
        )?;
        require(
            unit(self.link_error),
            "link_error",
            self.link_error,
            "is not in [0, 1]",
        )?;
        require(
            (16..=4096).contains(&self.map_size),
            "map_size",
            self.map_size,
            "is not in 16..=4096",
        )?;
        require(
            self.fov_margin.is_finite() && (0.0..=180.0).contains(&self.fov_margin),
            "fov_margin",
            self.fov_margin,
            "is not in 0..=180 degrees",
        )?;
        positive_seconds("time_limit", self.time_limit)?;
        positive_seconds("importance_time_limit", self.importance_time_limit)
    }

    /// Why `raster` cannot draw a scene with or without alpha-masked casters, if it
    /// cannot.
    pub fn check_raster(&self, masked: bool) -> Result<(), OptionError> {
        match self.raster.refusal(masked) {
            Some(why) => Err(OptionError::new("raster", self.raster.name(), why)),
            None => Ok(()),
        }
    }

    /// When the shooting stops.
    pub fn stop(&self) -> StopAt {
        StopAt {
            converge: self.converge,
            max_shots: self.max_shots,
            time_budget: self
                .time_limit
                .and_then(|t| Duration::try_from_secs_f64(t).ok()),
        }
    }

    /// The adaptive subdivision asked for.
    pub fn subdivision(&self) -> Subdivision {
        Subdivision {
            levels: self.adaptive,
            lower: self.adaptive_share[0],
            upper: self.adaptive_share[1],
        }
    }

    /// The GPU solver's options.
    pub fn gpu_settings(&self) -> GpuSettings {
        GpuSettings {
            visibility: self.visibility,
            map_size: self.map_size,
            hierarchy: self.hierarchy,
            cell_power: self.cell_power,
            link_error: self.link_error,
            raster: self.raster,
            ..GpuSettings::default()
        }
    }

    /// The options the GPU solver shares with the CPU reference, the luminaires'
    /// distributions interpolated by `interp`.
    pub fn solver_settings(&self, interp: Interp) -> SolverSettings {
        SolverSettings {
            form_factor: self.form_factor,
            ambient: self.ambient,
            interp,
        }
    }

    /// The options of the indirect light that `render`, `demo` and the viewer show
    /// beside the luminaires' direct light: none, the luminaires' first bounce with the
    /// ambient term (no shot), or a solution of `seconds` of shooting.
    pub fn shown_indirect(choice: DisplayIndirect, seconds: f64) -> Option<Options> {
        let defaults = Options::default();
        match choice {
            DisplayIndirect::None => None,
            DisplayIndirect::Ambient => Some(Options {
                max_shots: Some(0),
                ..defaults
            }),
            DisplayIndirect::Radiosity => Some(Options {
                time_limit: Some(seconds),
                ..defaults
            }),
        }
    }

    /// How long the importance solve of a view-driven solution may take.
    pub fn importance_budget(&self) -> Option<Duration> {
        match (self.importance_time_limit, self.time_limit) {
            (Some(t), _) => Duration::try_from_secs_f64(t).ok(),
            (None, Some(t)) => Duration::try_from_secs_f64(t / 4.0).ok(),
            (None, None) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Options;

    #[test]
    fn the_defaults_are_valid() {
        Options::default().validate().unwrap();
    }

    #[test]
    fn each_range_names_its_field() {
        type Spoil = fn(&mut Options);
        let cases: [(&str, Spoil); 10] = [
            ("converge", |o| o.converge = 1.5),
            ("texel_density", |o| o.texel_density = 0.0),
            ("level", |o| o.level = 7),
            ("adaptive", |o| o.adaptive = 5),
            ("adaptive_share", |o| o.adaptive_share = [0.8, 0.2]),
            ("cell_power", |o| o.cell_power = 0.0),
            ("link_error", |o| o.link_error = f64::NAN),
            ("map_size", |o| o.map_size = 8),
            ("fov_margin", |o| o.fov_margin = 200.0),
            ("time_limit", |o| o.time_limit = Some(-1.0)),
        ];
        for (field, spoil) in cases {
            let mut o = Options::default();
            spoil(&mut o);
            let e = o.validate().unwrap_err();
            assert_eq!(e.field, field, "{e}");
            assert!(e.to_string().starts_with(field), "{e}");
        }
    }

    #[test]
    fn options_read_from_json_with_defaults_for_what_is_left_out() {
        let o: Options =
            serde_json::from_str(r#"{"map_size": 64, "visibility": "stereographic"}"#).unwrap();
        assert_eq!(o.map_size, 64);
        assert_eq!(o.visibility, super::Visibility::Stereographic);
        assert_eq!(o.converge, Options::default().converge);
        let e = serde_json::from_str::<Options>(r#"{"map_sise": 64}"#).unwrap_err();
        assert!(e.to_string().contains("map_sise"), "{e}");
    }

    #[test]
    fn the_shown_indirect_light_shoots_nothing_or_for_its_time() {
        use crate::scene::DisplayIndirect;
        assert_eq!(Options::shown_indirect(DisplayIndirect::None, 5.0), None);
        let ambient = Options::shown_indirect(DisplayIndirect::Ambient, 5.0).unwrap();
        assert_eq!((ambient.max_shots, ambient.time_limit), (Some(0), None));
        let solved = Options::shown_indirect(DisplayIndirect::Radiosity, 5.0).unwrap();
        assert_eq!((solved.max_shots, solved.time_limit), (None, Some(5.0)));
    }

    #[test]
    fn the_importance_gets_a_quarter_of_the_time_limit_unless_given_its_own() {
        let mut o = Options {
            time_limit: Some(8.0),
            ..Options::default()
        };
        assert_eq!(o.importance_budget().unwrap().as_secs_f64(), 2.0);
        o.importance_time_limit = Some(0.5);
        assert_eq!(o.importance_budget().unwrap().as_secs_f64(), 0.5);
        assert_eq!(Options::default().importance_budget(), None);
    }
}
