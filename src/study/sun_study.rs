//! A whole sun study as one call: the model read and checked, every date's shadow profile
//! (and the model seen in 3D) computed on the GPU with progress and cancellation, the
//! facades' and window points' hours, and the files written. `goniolight profile` and
//! Python's `sun_study` both run it; errors name [`SunStudyOptions`]' fields.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use chrono::{NaiveDate, NaiveTime};
use glam::{DVec2, DVec3};

use super::annotate::PlanLabels;
use super::model::{load_components, recentre, up_axis_warning, StudyModel};
use super::output::{summary, write_study, StudyOutput, StudySummary};
use super::rasters::{surface_cells, AnalysisArea};
use super::shadow_profile::{
    compute_on, prepare, shared_extent, HoursMetric, Profile, ProfileSpec,
};
use super::study_files::{write_dates_table, write_sun_path};
use super::surface_output::{surface_summaries, SurfaceResults};
use super::surface_set::{FacadeOptions, SurfaceSet, SurfaceSetup};
use super::surfaces::{check_points, Facade, WindowPoint};
use super::view_hours::{compute as view_hours, default_camera, write_model_view, ViewHours};
use super::ProfileError;
use crate::gpu::Gpu;
use crate::scene::{Camera, UpAxis};
use crate::shadow::SilhouetteMethod;
use crate::sun::{Site, SunOptions, Zone};

/// The most dates one study takes (each date's profile stays in memory until all are done,
/// so an interrupted study writes nothing).
pub const MAX_DATES: usize = 60;

/// Bytes per plan pixel over the files a date writes: measured 31 at 1024 px on a box
/// (hours.csv 23, hours.asc 7, the PNGs and hours.exr the rest), rounded up.
const BYTES_PER_PIXEL: u64 = 32;
/// Bytes per pixel of one step image (step images, the GIF).
const BYTES_PER_STEP_PIXEL: u64 = 2;

/// The model seen in 3D with every surface coloured by hours (`model.png`, `model.exr`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelView {
    /// The eye, in the model file's plan coordinates and height, metres (default: from the
    /// south-west, 35° up).
    pub from: Option<DVec3>,
    /// The target, as `from` (default: the model's centre).
    pub at: Option<DVec3>,
    /// Width and height, pixels.
    pub size: (u32, u32),
}

impl Default for ModelView {
    /// The default view at 1200 × 900 pixels.
    fn default() -> Self {
        ModelView {
            from: None,
            at: None,
            size: (1200, 900),
        }
    }
}

/// Every option of a sun study, named as fields (`goniolight profile`'s flags).
#[derive(Debug, Clone)]
pub struct SunStudyOptions {
    /// The model (OBJ), metres; the ground is its lowest point.
    pub model: PathBuf,
    /// The model file's up axis.
    pub up: UpAxis,
    /// Only these objects cast shadows (`o`/`g` names, `*` matches any run of characters);
    /// empty: all of them.
    pub casters: Vec<String>,
    /// Latitude, degrees north.
    pub latitude: f64,
    /// Longitude, degrees east.
    pub longitude: f64,
    /// The time zone (an IANA name or an offset such as `+01:00`); `None`: UTC.
    pub zone: Option<String>,
    /// The days (sorted and without repeats by [`SunStudy::prepare`]).
    pub dates: Vec<NaiveDate>,
    /// First step, local time.
    pub from: NaiveTime,
    /// Last step, local time.
    pub to: NaiveTime,
    /// Minutes between steps.
    pub step_minutes: u32,
    /// The model's +Y from true north, clockwise seen from above, degrees.
    pub north_offset_deg: f64,
    /// Side of the square plan, metres (`None`: enough for the lowest sun of every date).
    pub extent_m: Option<f64>,
    /// Pixels per side of the plan.
    pub resolution: u32,
    /// Silhouette search.
    pub silhouettes: SilhouetteMethod,
    /// What the hours count.
    pub metric: HoursMetric,
    /// Hours a ground cell needs to pass.
    pub threshold_h: Option<f64>,
    /// Areas whose passing fraction is reported (with a threshold).
    pub areas: Vec<AnalysisArea>,
    /// Hours of sun on the facades, when given.
    pub facades: Option<FacadeOptions>,
    /// Window points: hours of direct sun, EN 17037's level, their sun-path diagrams.
    pub points: Vec<WindowPoint>,
    /// The lowest sun counted on facades and at points, degrees.
    pub min_elevation_deg: f64,
    /// The model seen in 3D coloured by hours, when given.
    pub model_view: Option<ModelView>,
}

impl SunStudyOptions {
    /// A study of `model` at a site over `dates` from `from` to `to` every `step_minutes`,
    /// with every other option at `goniolight profile`'s default.
    pub fn new(
        model: PathBuf,
        (latitude, longitude): (f64, f64),
        dates: Vec<NaiveDate>,
        (from, to): (NaiveTime, NaiveTime),
        step_minutes: u32,
    ) -> Self {
        SunStudyOptions {
            model,
            up: UpAxis::Y,
            casters: Vec::new(),
            latitude,
            longitude,
            zone: None,
            dates,
            from,
            to,
            step_minutes,
            north_offset_deg: 0.0,
            extent_m: None,
            resolution: 1024,
            silhouettes: SilhouetteMethod::Hextree,
            metric: HoursMetric::Shadow,
            threshold_h: None,
            areas: Vec::new(),
            facades: None,
            points: Vec::new(),
            min_elevation_deg: 0.0,
            model_view: None,
        }
    }

    /// The files the study reads: the model and its MTL files.
    pub fn input_files(&self) -> Vec<PathBuf> {
        let mut files = crate::geometry::obj::material_libraries(&self.model);
        files.push(self.model.clone());
        files
    }

    /// An error naming the first field out of range.
    fn check(&self) -> Result<(), ProfileError> {
        let invalid = ProfileError::invalid;
        if self.dates.is_empty() {
            return Err(invalid("dates", "is empty: give at least one day".into()));
        }
        if self.dates.len() > MAX_DATES {
            return Err(invalid(
                "dates",
                format!(
                    "has {} days; at most {MAX_DATES} per study",
                    self.dates.len()
                ),
            ));
        }
        if let Some(t) = self.threshold_h {
            if !(t.is_finite() && t >= 0.0) {
                return Err(invalid("threshold_h", format!("{t} must be hours ≥ 0")));
            }
        }
        if let Some(f) = self.facades {
            if !(f.cell_m.is_finite() && f.cell_m >= 0.01) {
                return Err(invalid(
                    "facade_cell_m",
                    format!("{} must be at least 0.01 m", f.cell_m),
                ));
            }
            if !(f.min_area_m2.is_finite() && f.min_area_m2 >= 0.0) {
                return Err(invalid(
                    "min_facade_area_m2",
                    format!("{} must be m² ≥ 0", f.min_area_m2),
                ));
            }
        }
        if !self.points.is_empty() {
            check_points(&self.points).map_err(|e| invalid("points", e))?;
        }
        for (field, v) in [
            ("north_offset_deg", self.north_offset_deg),
            ("min_elevation_deg", self.min_elevation_deg),
        ] {
            if !v.is_finite() {
                return Err(invalid(field, format!("{v} is not a number")));
            }
        }
        Ok(())
    }

    /// The title of the study's plans: "48.2100° N, 16.3700° E".
    fn site_label(&self) -> String {
        let (lat, lon) = (self.latitude, self.longitude);
        format!(
            "{:.4}° {}, {:.4}° {}",
            lat.abs(),
            if lat >= 0.0 { "N" } else { "S" },
            lon.abs(),
            if lon >= 0.0 { "E" } else { "W" }
        )
    }
}

/// A sun study with its model read and every date checked, ready to compute.
pub struct SunStudy {
    options: SunStudyOptions,
    model: StudyModel,
    origin: DVec2,
    specs: Vec<ProfileSpec>,
    camera: Option<Camera>,
    surfaces: SurfaceSet,
    warnings: Vec<String>,
}

/// One date of a computed study.
#[derive(Debug, Clone)]
pub struct StudyDay {
    /// The date's period, site and plan.
    pub spec: ProfileSpec,
    /// The shadow of every step on the plan.
    pub profile: Profile,
    /// Seconds the profile took.
    pub seconds: f64,
    /// The model seen in 3D, when asked for.
    pub view: Option<ViewHours>,
    /// The hours on the facades and at the window points, when asked for.
    pub surfaces: Option<SurfaceResults>,
}

/// Where the day's animation goes.
#[derive(Debug, Clone)]
pub enum GifPlace {
    /// Into each date's folder under this file name.
    EachDate(std::ffi::OsString),
    /// To this path (one date).
    At(PathBuf),
}

/// What a study writes besides the plans, rasters, tables and diagrams it always writes.
#[derive(Debug, Clone, Default)]
pub struct StudyFiles {
    /// One framed plan per step (`steps/HHMM.png`).
    pub step_images: bool,
    /// The day's animation.
    pub gif: Option<GifPlace>,
}

impl SunStudy {
    /// Reads the model, checks every option and every date's period and suns, and finds the
    /// facades and the window points' obstruction masks; no GPU work yet.
    pub fn prepare(mut options: SunStudyOptions) -> Result<SunStudy, ProfileError> {
        options.dates.sort();
        options.dates.dedup();
        options.check()?;
        let site = Site::new(options.latitude, options.longitude, 0.0)?;
        let zone = Zone::parse(options.zone.as_deref().unwrap_or("UTC"))?;
        let mut model = load_components(&options.model, options.up, &options.casters)?;
        let mut warnings = std::mem::take(&mut model.warnings);
        warnings.extend(up_axis_warning(&model.mesh, options.up));
        let origin = recentre(&mut model.mesh);
        let mut specs: Vec<ProfileSpec> = options
            .dates
            .iter()
            .map(|&date| ProfileSpec {
                site,
                zone,
                date,
                from: options.from,
                to: options.to,
                step_minutes: options.step_minutes,
                sun: SunOptions {
                    north_offset_deg: options.north_offset_deg,
                    ..Default::default()
                },
                extent_m: options.extent_m,
                resolution: options.resolution,
                silhouette: options.silhouettes,
                non_casters: model.non_casters.clone(),
                volume_ends: Default::default(),
            })
            .collect();
        // Every period is checked before the GPU starts; several dates share one extent.
        for s in &specs {
            s.local_times()?;
            s.suns()?;
        }
        if options.extent_m.is_none() && specs.len() > 1 {
            let shared = shared_extent(&model.mesh, &specs)?;
            for s in &mut specs {
                s.extent_m = Some(shared);
            }
        }
        let camera = model_camera(&options, &model.mesh, origin)?;
        let surfaces = SurfaceSet::new(
            &model.mesh,
            SurfaceSetup {
                facades: options.facades,
                points: &options.points,
                origin,
                non_casters: &model.non_casters,
                north_offset_deg: options.north_offset_deg,
                min_elevation_deg: options.min_elevation_deg,
            },
        );
        Ok(SunStudy {
            options,
            model,
            origin,
            specs,
            camera,
            surfaces,
            warnings,
        })
    }

    /// The options (dates sorted, without repeats).
    pub fn options(&self) -> &SunStudyOptions {
        &self.options
    }

    /// The model as studied (recentred; casters first).
    pub fn model(&self) -> &StudyModel {
        &self.model
    }

    /// What the caller should be told about the model (the file's name left out; field
    /// names in backquotes, as `` `up` ``).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The facades found (with facade options).
    pub fn facades(&self) -> &[Facade] {
        self.surfaces.facades()
    }

    /// Steps of every date's plan.
    pub fn plan_steps(&self) -> usize {
        self.specs
            .iter()
            .map(|s| s.local_times().map_or(0, |t| t.len()))
            .sum()
    }

    /// The units of [`SunStudy::compute`]'s progress: each date's steps, twice with a model
    /// view.
    pub fn progress_steps(&self) -> usize {
        self.plan_steps() * if self.camera.is_some() { 2 } else { 1 }
    }

    /// About how many bytes [`SunStudy::write`] writes with `files` (from the resolution,
    /// the dates and the steps).
    pub fn estimated_output_bytes(&self, files: &StudyFiles) -> u64 {
        let pixels = u64::from(self.options.resolution).pow(2);
        let per_step = u64::from(files.step_images) + u64::from(files.gif.is_some());
        self.specs.len() as u64 * pixels * BYTES_PER_PIXEL
            + self.plan_steps() as u64 * per_step * pixels * BYTES_PER_STEP_PIXEL
    }

    /// Every date's profile (and model view, facade and point hours) on `gpu`, calling
    /// `progress(done, total)` after each step; stops with [`ProfileError::Cancelled`] when
    /// `cancel` is set.
    pub fn compute(
        &self,
        gpu: &Gpu,
        mut progress: impl FnMut(usize, usize),
        cancel: &AtomicBool,
    ) -> Result<Vec<StudyDay>, ProfileError> {
        let total = self.progress_steps();
        // Welded, with its edges (and the hextree on first use), once for every date and view.
        let geometry = prepare(gpu, &self.model.mesh)?;
        let mut days = Vec::with_capacity(self.specs.len());
        let mut done_before = 0;
        for spec in &self.specs {
            let t = std::time::Instant::now();
            let mut profile = compute_on(
                gpu,
                &geometry,
                spec,
                |done, _| progress(done_before + done, total),
                cancel,
            )?;
            done_before += spec.local_times()?.len();
            profile.origin = self.origin;
            let seconds = t.elapsed().as_secs_f64();
            let view = match &self.camera {
                Some(camera) => {
                    let size = self.options.model_view.unwrap_or_default().size;
                    let report = |done, _| progress(done_before + done, total);
                    let v = view_hours(gpu, &geometry, spec, camera, size, report, cancel)?;
                    done_before += spec.local_times()?.len();
                    Some(v)
                }
                None => None,
            };
            let surfaces = self.surfaces.for_profile(&profile);
            days.push(StudyDay {
                spec: spec.clone(),
                profile,
                seconds,
                view,
                surfaces,
            });
        }
        Ok(days)
    }

    /// What the output of `day` holds: its metric, threshold, areas, labels and surfaces.
    fn output(&self, day: &StudyDay, step_images: bool, gif: Option<PathBuf>) -> StudyOutput {
        let o = &self.options;
        StudyOutput {
            metric: o.metric,
            threshold_h: o.threshold_h,
            areas: o.areas.clone(),
            labels: PlanLabels {
                title: o.site_label(),
                subtitle: format!(
                    "{}, {}–{} {}, every {} min",
                    day.spec.date,
                    o.from.format("%H:%M"),
                    o.to.format("%H:%M"),
                    o.zone.as_deref().unwrap_or("UTC"),
                    o.step_minutes
                ),
                north_offset_deg: o.north_offset_deg,
            },
            step_images,
            surfaces: day.surfaces.clone(),
            gif,
        }
    }

    /// The numbers of `day` as `study.json` holds them (facades and points included).
    pub fn summary(&self, day: &StudyDay) -> StudySummary {
        let out = self.output(day, false, None);
        let mut s = summary(&day.profile, &out);
        if let Some(results) = &day.surfaces {
            (s.facades, s.points) = surface_summaries(results, self.options.north_offset_deg);
        }
        s
    }

    /// Writes the study of `days` into `dir` (one folder per date when there are several,
    /// with `dates.csv` and `dates.json`): each date's plans, rasters, tables, `study.json`,
    /// sun-path diagrams and model view. Returns each date's summary.
    pub fn write(
        &self,
        days: &[StudyDay],
        dir: &Path,
        files: &StudyFiles,
    ) -> Result<Vec<StudySummary>, ProfileError> {
        let several = days.len() > 1;
        let mut summaries = Vec::with_capacity(days.len());
        for day in days {
            let day_dir = if several {
                dir.join(day.spec.date.to_string())
            } else {
                dir.to_path_buf()
            };
            let gif = match &files.gif {
                Some(GifPlace::EachDate(name)) => Some(day_dir.join(name)),
                Some(GifPlace::At(path)) => Some(path.clone()),
                None => None,
            };
            let output = self.output(day, files.step_images, gif);
            let summary =
                write_study(&day.profile, &day_dir, &output).map_err(ProfileError::Output)?;
            write_sun_path(
                &day.spec,
                &day.profile,
                &day_dir,
                &output.labels,
                self.surfaces.masks(),
            )
            .map_err(ProfileError::Output)?;
            if let Some(v) = &day.view {
                let labels = self.view_labels(&output.labels);
                write_model_view(v, self.options.metric, &labels, &day_dir)
                    .map_err(ProfileError::Output)?;
            }
            summaries.push(summary);
        }
        if several {
            let dated: Vec<_> = days
                .iter()
                .map(|d| d.spec.date)
                .zip(summaries.iter().cloned())
                .collect();
            write_dates_table(dir, &dated).map_err(ProfileError::Output)?;
        }
        Ok(summaries)
    }

    /// The model view's title and subtitle (where it is seen from).
    fn view_labels(&self, plan: &PlanLabels) -> PlanLabels {
        let o = &self.options;
        let from = o.model_view.and_then(|v| v.from);
        PlanLabels {
            title: format!(
                "{} — hours of {} on the model",
                o.site_label(),
                o.metric.name()
            ),
            subtitle: format!(
                "{}; seen from {}",
                plan.subtitle,
                match from {
                    Some(f) => format!("({:.1}, {:.1}, {:.1}) m", f.x, f.y, f.z),
                    None => "the south-west, 35° above the horizon".into(),
                }
            ),
            ..plan.clone()
        }
    }
}

impl StudyDay {
    /// The day's warnings: steps skipped with the sun below the horizon, shadows cut by
    /// the plan's edge (field names in backquotes).
    pub fn warnings(&self) -> Vec<String> {
        let date = self.spec.date;
        let hhmm = |t: &chrono::DateTime<chrono::FixedOffset>| t.format("%H:%M").to_string();
        let mut out = Vec::new();
        let p = &self.profile;
        if !p.skipped.is_empty() {
            let times: Vec<String> = p.skipped.iter().map(hhmm).collect();
            out.push(format!(
                "{date}: the sun is below the horizon at {} step(s), skipped: {}",
                times.len(),
                times.join(" ")
            ));
        }
        let cut: Vec<String> = p
            .steps
            .iter()
            .filter(|s| s.reaches_edge)
            .map(|s| hhmm(&s.time))
            .collect();
        if !cut.is_empty() {
            out.push(format!(
                "{date}: the shadow reaches the edge of the {:.0} m plan at {} (its area is cut; use a larger `extent_m`): {}",
                p.extent_m,
                cut.len(),
                cut.join(" ")
            ));
        }
        out
    }

    /// One line on the day's work: "2026-03-21: 9 steps, plan 40.0 m at 1024 px (…); 0.52 s
    /// (…ms/step: …)".
    pub fn describe(&self) -> String {
        let p = &self.profile;
        let n = p.steps.len().max(1) as f64;
        format!(
            "{}: {} steps, plan {:.1} m at {} px ({:.3} m/px), footprint {:.1} m²; {:.2} s ({:.1} ms/step: silhouettes {:.1} ms, shadow volumes {:.1} ms)",
            self.spec.date,
            p.steps.len(),
            p.extent_m,
            p.resolution,
            p.extent_m / p.resolution as f64,
            p.footprint_area_m2(),
            self.seconds,
            1000.0 * self.seconds / n,
            1000.0 * p.timing.silhouette_s / n,
            1000.0 * p.timing.render_s / n,
        )
    }

    /// The rows of `hours.csv` under `metric`: x, y (the model file's plan coordinates,
    /// metres) and hours at every cell that sees ground or model.
    pub fn hours_cells(&self, metric: HoursMetric) -> Vec<[f64; 3]> {
        let hours = self.profile.hours(metric);
        surface_cells(&self.profile)
            .map(|(k, c)| [c.x, c.y, f64::from(hours[k])])
            .collect()
    }
}

impl StudySummary {
    /// "42.0 % of the plan reaches 2 h of sun (1 area(s), garden: 61.5 %)" when the study
    /// has a threshold.
    pub fn pass_line(&self) -> Option<String> {
        let f = self.pass_fraction?;
        let areas: String = self
            .areas
            .iter()
            .map(|r| {
                let share = r
                    .pass_fraction
                    .map_or("outside the plan".into(), |f| format!("{:.1} %", 100.0 * f));
                format!(", {}: {share}", r.name)
            })
            .collect();
        Some(format!(
            "{:.1} % of the plan reaches {} h of {} ({} area(s){areas})",
            100.0 * f,
            self.threshold_h.unwrap_or(0.0),
            self.metric,
            self.areas.len(),
        ))
    }
}

/// The camera of the model view: the eye and target given (the model file's plan
/// coordinates, moved as the model was by `origin`), else the default view.
fn model_camera(
    o: &SunStudyOptions,
    model: &crate::geometry::Mesh,
    origin: DVec2,
) -> Result<Option<Camera>, ProfileError> {
    let Some(view) = o.model_view else {
        return Ok(None);
    };
    let empty = || ProfileError::Input("the model has no triangles".into());
    let shift = DVec3::new(origin.x, origin.y, 0.0);
    let camera = match view.from {
        Some(from) => {
            let (lo, hi) = model.bounds().ok_or_else(empty)?;
            let at = view.at.map_or((lo + hi) * 0.5, |at| at - shift);
            if (from - shift).distance(at) < 1e-3 {
                return Err(ProfileError::invalid(
                    "view_from",
                    "and `view_at` must be different points".into(),
                ));
            }
            Camera::perspective(from - shift, at, 40.0)
        }
        None => default_camera(model, o.north_offset_deg).ok_or_else(empty)?,
    };
    Ok(Some(camera))
}
