//! The sunlight and skylight tests of planning (BRE 209, 2022, and EN 17037:2018+A1:2021)
//! for a scene's `[[window]]`s and `[[open_space]]`s, before and after a development:
//!
//! - the **vertical sky component** at each window ([`vsc`]: CIE overcast sky, the
//!   model's obstruction), its 27 % test and the 0.8× test against the baseline;
//! - **annual and winter probable sunlight hours** at each window from a weather file
//!   ([`suns::ProbableSun`]: hours with direct normal irradiance above 120 W/m², the sun
//!   within 90° of the window's normal and unobstructed), per cent of the year's probable
//!   sunlight hours, the 25 % / 5 % tests, the 0.8× and 4-point tests against the baseline;
//! - **EN 17037 sunlight exposure**: hours of sun at each window on one day between
//!   1 February and 21 March, rated minimum (1.5 h), medium (3 h), high (4 h);
//! - **gardens and open spaces**: the share of each with at least 2 hours of sun on
//!   21 March, its 50 % test and the 0.8× test against the baseline.
//!
//! Every count casts rays through the model on the CPU ([`crate::shadow::sun_rays`]); the
//! verdicts are in [`verdicts`], the outputs in [`output`].

pub mod output;
pub mod plan;
pub mod report;
pub mod suns;
pub mod verdicts;
pub mod vsc;

use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};

use chrono::NaiveDate;
use glam::DVec3;
use rayon::prelude::*;

use crate::daylight::points::Obstructions;
use crate::geometry::Mesh;
use crate::scene::daylight::site_of;
use crate::scene::Scene;
use crate::shadow::bvh::TriangleBvh;
use crate::shadow::sun_rays::{surface_offset, Sun, SunRays};
use crate::shadow::IgnoredTriangles;
use crate::sun::SunOptions;
use crate::weather::Weather;
use suns::{day_suns, ProbableSun};

/// What the planning tests are run with.
#[derive(Debug, Clone)]
pub struct SunlightOptions {
    /// The weather file of the probable sunlight hours (none: APSH and WPSH are left out).
    pub weather: Option<Weather>,
    /// The day of the gardens' 2-hour test (BRE 209: 21 March).
    pub open_space_date: NaiveDate,
    /// The day of EN 17037's sunlight exposure (1 February … 21 March).
    pub en17037_date: NaiveDate,
    /// Minutes between the suns of a day.
    pub step_min: f64,
    /// EN 17037's minimum solar altitude for the site, degrees (suns lower do not count at
    /// windows).
    pub min_elevation_deg: f64,
}

/// Minutes between the suns of a day, by default.
pub const DEFAULT_STEP_MIN: f64 = 5.0;

/// What a front end asks for, as the command line's options (`None`: the default).
#[derive(Debug, Clone, Default)]
pub struct SunlightRequest<'a> {
    /// `--weather`: an EPW file.
    pub weather: Option<&'a std::path::Path>,
    /// `--date`: the gardens' day (default 21 March of `year`).
    pub date: Option<NaiveDate>,
    /// `--en17037-date` (default 21 March of `year`).
    pub en17037_date: Option<NaiveDate>,
    /// `--year` of the default days (default this year).
    pub year: Option<i32>,
    /// `--step`, minutes (default [`DEFAULT_STEP_MIN`]).
    pub step_min: Option<f64>,
    /// `--min-elevation`, degrees (default 0).
    pub min_elevation_deg: Option<f64>,
}

impl SunlightOptions {
    /// The options of `request` (the weather file read), and warnings; errors name the
    /// option (`weather`, `year`, `step`, `min_elevation`).
    pub fn from_request(
        request: &SunlightRequest,
    ) -> Result<(SunlightOptions, Vec<String>), PlanningError> {
        use chrono::Datelike;
        let year = request.year.unwrap_or_else(|| chrono::Utc::now().year());
        let march_21 = NaiveDate::from_ymd_opt(year, 3, 21)
            .ok_or_else(|| PlanningError::input("year", format!("{year} is not a year")))?;
        let en17037_date = request.en17037_date.unwrap_or(march_21);
        let mut warnings = Vec::new();
        let (m, d) = (en17037_date.month(), en17037_date.day());
        if !(m == 2 || (m == 3 && d <= 21)) {
            warnings.push(format!(
                "EN 17037 takes a day from 1 February to 21 March, not {en17037_date}"
            ));
        }
        let min_elevation_deg = request.min_elevation_deg.unwrap_or(0.0);
        if !(0.0..90.0).contains(&min_elevation_deg) {
            return Err(PlanningError::input(
                "min_elevation",
                format!("{min_elevation_deg}: give degrees from 0 to 90"),
            ));
        }
        let step_min = request.step_min.unwrap_or(DEFAULT_STEP_MIN);
        check_step(step_min)?;
        let weather = request
            .weather
            .map(crate::weather::read_epw)
            .transpose()
            .map_err(|e| PlanningError::input("weather", e.to_string()))?;
        let options = SunlightOptions {
            weather,
            open_space_date: request.date.unwrap_or(march_21),
            en17037_date,
            step_min,
            min_elevation_deg,
        };
        Ok((options, warnings))
    }
}

/// Why the planning tests could not run.
#[derive(Debug, Clone, PartialEq)]
pub enum PlanningError {
    /// The scene or an option does not give what the tests need: the key and what is
    /// wrong.
    Input {
        /// The scene-file key or option.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// Stopped by the cancel flag.
    Cancelled,
}

impl PlanningError {
    /// An input error at `key`.
    pub fn input(key: impl Into<String>, message: impl Into<String>) -> PlanningError {
        PlanningError::Input {
            key: key.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for PlanningError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlanningError::Input { key, message } => write!(f, "{key}: {message}"),
            PlanningError::Cancelled => write!(f, "cancelled"),
        }
    }
}

impl std::error::Error for PlanningError {}

/// One model's figures at a window.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowFigures {
    /// Vertical sky component, per cent.
    pub vsc: f64,
    /// Annual probable sunlight hours, per cent of the year's (with a weather file).
    pub apsh: Option<f64>,
    /// Winter (21 September – 21 March) probable sunlight hours, per cent of the year's.
    pub wpsh: Option<f64>,
    /// Hours of sun on EN 17037's day.
    pub en17037_hours: f64,
}

/// One model's figures over an open space.
#[derive(Debug, Clone, PartialEq)]
pub struct OpenSpaceFigures {
    /// Hours of sun on the day at each point.
    pub hours: Vec<f64>,
    /// The share of the points with at least 2 hours, 0 … 1.
    pub sunlit_fraction_2h: f64,
}

/// The hours of sun an open space needs on the day, at least.
pub const OPEN_SPACE_HOURS: f64 = 2.0;

/// One model's figures: per window, per open space.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelFigures {
    /// Per `[[window]]`.
    pub windows: Vec<WindowFigures>,
    /// Per `[[open_space]]`.
    pub open_spaces: Vec<OpenSpaceFigures>,
}

/// The planning tests of a scene: its figures, the baseline's, and what they were
/// computed with.
#[derive(Debug, Clone)]
pub struct SunlightAssessment {
    /// The proposed scene's figures.
    pub proposed: ModelFigures,
    /// The baseline's (existing situation's), with `--baseline`.
    pub baseline: Option<ModelFigures>,
    /// The year's probable sunlight hours at the site (with a weather file).
    pub probable_hours: Option<ProbableHours>,
    /// The suns per day counted (open spaces' day, EN 17037's day).
    pub day_sun_hours: (f64, f64),
    /// Options used.
    pub options: SunlightOptions,
    /// Warnings for the front ends.
    pub warnings: Vec<String>,
}

/// The year's probable sunlight hours: annual, winter, and hours missing in the file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbableHours {
    /// Hours of the year.
    pub annual: f64,
    /// Hours from 21 September to 21 March.
    pub winter: f64,
    /// Records without direct normal irradiance.
    pub missing: usize,
}

/// The suns every model is judged under.
struct SunSets {
    open_space: Vec<Sun>,
    en17037: Vec<Sun>,
    probable: Option<ProbableSun>,
}

/// A model's geometry with the acceleration structure its rays need.
struct Geometry {
    mesh: Mesh,
    bvh: TriangleBvh,
    eps: f64,
}

impl Geometry {
    fn of(scene: &Scene) -> Geometry {
        let mesh = scene.caster_mesh();
        let bvh = TriangleBvh::new(&mesh).with_cutouts(scene.caster_cutouts());
        let eps = surface_offset(&mesh);
        Geometry { mesh, bvh, eps }
    }

    /// Rays toward `suns` (those above `min_elevation_deg`), every triangle casting.
    fn rays<'a>(&'a self, suns: &'a [Sun], min_elevation_deg: f64) -> SunRays<'a> {
        static NONE: IgnoredTriangles = IgnoredTriangles(Vec::new());
        SunRays {
            bvh: &self.bvh,
            suns,
            min_elevation_deg,
            eps: self.eps,
            non_casters: &NONE,
        }
    }
}

/// Runs the planning tests on `scene`'s windows and open spaces, against `baseline`'s
/// model when given; `cancel` stops between stages.
pub fn assess(
    scene: &Scene,
    baseline: Option<&Scene>,
    options: &SunlightOptions,
    cancel: &AtomicBool,
) -> Result<SunlightAssessment, PlanningError> {
    let places = &scene.planning;
    if places.is_empty() {
        return Err(PlanningError::input(
            "window",
            "the scene has no [[window]] and no [[open_space]] to judge",
        ));
    }
    let entry = scene.site.as_ref().ok_or_else(|| {
        PlanningError::input(
            "site",
            "the sun's positions need a [site] (latitude, longitude, timezone)",
        )
    })?;
    let (site, zone) = site_of(entry).map_err(|(k, m)| PlanningError::input(k, m))?;
    let zone = zone.ok_or_else(|| {
        PlanningError::input(
            "site.timezone",
            "the days of the tests are local days: give the site's time zone",
        )
    })?;
    check_step(options.step_min)?;
    let sun_options = SunOptions {
        north_offset_deg: entry.north_offset_deg,
        ..SunOptions::default()
    };
    let mut warnings = Vec::new();
    let probable = match &options.weather {
        Some(w) => {
            warnings.extend(weather_warnings(w, entry.latitude, entry.longitude));
            Some(ProbableSun::of(w, &site, &sun_options)?)
        }
        None => None,
    };
    let suns = SunSets {
        open_space: day_suns(
            &site,
            &zone,
            options.open_space_date,
            options.step_min,
            &sun_options,
        )?,
        en17037: day_suns(
            &site,
            &zone,
            options.en17037_date,
            options.step_min,
            &sun_options,
        )?,
        probable,
    };
    let proposed = figures(scene, &Geometry::of(scene), &suns, options, cancel)?;
    let baseline = match baseline {
        Some(b) => Some(figures(scene, &Geometry::of(b), &suns, options, cancel)?),
        None => None,
    };
    let day_hours = |s: &[Sun]| s.iter().map(|s| s.weight_h).sum::<f64>();
    Ok(SunlightAssessment {
        proposed,
        baseline,
        probable_hours: suns.probable.as_ref().map(|p| ProbableHours {
            annual: p.annual_hours(),
            winter: p.winter.len() as f64,
            missing: p.missing_hours,
        }),
        day_sun_hours: (day_hours(&suns.open_space), day_hours(&suns.en17037)),
        options: options.clone(),
        warnings,
    })
}

/// Adds to `scene`'s windows those of the `profile --points` file at `path` (`[[point]]`
/// tables: name, position, normal); errors (key `points`) name the file and the point.
pub fn add_points_file(scene: &mut Scene, path: &std::path::Path) -> Result<(), PlanningError> {
    let text = crate::io::read_text_limited(path, crate::io::MAX_TEXT_BYTES)
        .map_err(|e| PlanningError::input("points", format!("{}: {e}", path.display())))?;
    scene
        .planning
        .add_points(&text)
        .map_err(|m| PlanningError::input("points", format!("{}: {m}", path.display())))
}

/// Adds to `scene`'s open spaces the analysis areas of the GeoJSON file at `path` (as the
/// sun study's `--areas`: Polygon and MultiPolygon features named by `properties.name`,
/// on the ground at z = 0), their points `spacing` m apart; errors (key `areas`) name the
/// file and the feature.
pub fn add_areas_file(
    scene: &mut Scene,
    path: &std::path::Path,
    spacing: f64,
) -> Result<(), PlanningError> {
    use crate::scene::planning::OpenSpace;
    let err = |m: String| PlanningError::input("areas", m);
    let areas = crate::geometry::areas::read_areas(path).map_err(|e| err(e.to_string()))?;
    for (k, area) in areas.iter().enumerate() {
        let space = OpenSpace::from_area(area, spacing).map_err(|m| {
            err(format!(
                "{}: features[{k}] ({:?}): {m}",
                path.display(),
                area.name
            ))
        })?;
        let name = area.name.trim().to_lowercase();
        let open_spaces = &mut scene.planning.open_spaces;
        if open_spaces
            .iter()
            .any(|o| o.entry.name.trim().to_lowercase() == name)
        {
            return Err(err(format!(
                "{}: features[{k}]: {:?} names an open space already; give each its own name",
                path.display(),
                area.name
            )));
        }
        open_spaces.push(space);
    }
    Ok(())
}

/// An error unless 0 < `step_min` ≤ 60.
fn check_step(step_min: f64) -> Result<(), PlanningError> {
    if step_min > 0.0 && step_min <= 60.0 {
        Ok(())
    } else {
        Err(PlanningError::input(
            "step",
            format!("{step_min} minutes: give 0 < step ≤ 60"),
        ))
    }
}

/// Warnings about a weather file far from the site.
fn weather_warnings(w: &Weather, latitude: f64, longitude: f64) -> Vec<String> {
    let d_lat = (w.location.latitude - latitude).abs();
    let d_lon = (w.location.longitude - longitude + 540.0).rem_euclid(360.0) - 180.0;
    if d_lat > 1.0 || d_lon.abs() > 1.0 {
        vec![format!(
            "the weather file {} was recorded at {:.2}° N, {:.2}° E, more than a degree from the site ({latitude:.2}° N, {longitude:.2}° E): its sunshine is another place's",
            w.path.display(),
            w.location.latitude,
            w.location.longitude
        )]
    } else {
        Vec::new()
    }
}

/// The figures of `scene`'s windows and open spaces in the model `geometry`.
fn figures(
    scene: &Scene,
    geometry: &Geometry,
    suns: &SunSets,
    options: &SunlightOptions,
    cancel: &AtomicBool,
) -> Result<ModelFigures, PlanningError> {
    let rays = |suns, min_elevation_deg| geometry.rays(suns, min_elevation_deg);
    let windows = &scene.planning.windows;
    let glazing = Vec::new();
    let obstructions = Obstructions {
        mesh: &geometry.mesh,
        bvh: &geometry.bvh,
        glazing: &glazing,
        eps: geometry.eps,
    };
    let vsc = vsc::vertical_sky_components(windows, &obstructions);
    stop_if(cancel)?;
    let per_cent = |hours: f64, of: f64| if of > 0.0 { 100.0 * hours / of } else { 0.0 };
    let windows = windows
        .iter()
        .zip(vsc)
        .map(|(w, vsc)| {
            let (apsh, wpsh) = match &suns.probable {
                Some(p) => {
                    let year = p.annual_hours();
                    (
                        Some(per_cent(
                            rays(&p.annual, 0.0).hours_at(w.position, w.normal),
                            year,
                        )),
                        Some(per_cent(
                            rays(&p.winter, 0.0).hours_at(w.position, w.normal),
                            year,
                        )),
                    )
                }
                None => (None, None),
            };
            WindowFigures {
                vsc,
                apsh,
                wpsh,
                en17037_hours: rays(&suns.en17037, options.min_elevation_deg)
                    .hours_at(w.position, w.normal),
            }
        })
        .collect();
    stop_if(cancel)?;
    let day = rays(&suns.open_space, 0.0);
    let open_spaces = scene
        .planning
        .open_spaces
        .iter()
        .map(|o| {
            let hours: Vec<f64> = o
                .grid
                .points
                .par_iter()
                .map(|&p| day.hours_at(p, DVec3::Z))
                .collect();
            let lit = hours
                .iter()
                .filter(|&&h| h >= OPEN_SPACE_HOURS - 1e-9)
                .count();
            OpenSpaceFigures {
                sunlit_fraction_2h: lit as f64 / hours.len() as f64,
                hours,
            }
        })
        .collect();
    stop_if(cancel)?;
    Ok(ModelFigures {
        windows,
        open_spaces,
    })
}

fn stop_if(cancel: &AtomicBool) -> Result<(), PlanningError> {
    if cancel.load(Ordering::Relaxed) {
        Err(PlanningError::Cancelled)
    } else {
        Ok(())
    }
}
