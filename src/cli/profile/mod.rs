//! `goniolight profile`: sun studies of a model over a period — shadow profiles, hours of sun
//! or shadow, thresholds, several dates, facades and windows.

use std::path::PathBuf;

use anyhow::anyhow;
use chrono::{NaiveDate, NaiveTime};
use clap::Args;

mod bench;
mod model;
mod outputs;
mod surfaces;

pub use bench::run_bench;
pub use model::load_components;
use outputs::{write_dates_table, write_sun_path};
use surfaces::Surfaces;

use super::CliError;
use crate::gpu::Gpu;
use crate::io::limits::{bytes, MAX_OUTPUT_BYTES};
use crate::io::outputs::{OutputCheck, Staging};
use crate::scene::Camera;
use crate::scene::UpAxis;
use crate::shadow::SilhouetteMethod;
use crate::study::annotate::PlanLabels;
use crate::study::model::{recentre, up_axis_warning};
use crate::study::output::{write_study, StudyOutput};
use crate::study::profile::{
    compute_on, prepare, shared_extent, HoursMetric, Profile, ProfileSpec,
};
use crate::study::rasters::read_areas;
use crate::study::surfaces::parse_points;
use crate::study::view_hours::{compute as view_hours, default_camera, write_model_view};
use crate::sun::{Site, SunOptions, Zone};
use glam::DVec3;

/// Options of `profile`.
#[derive(Debug, Args)]
pub struct ProfileArgs {
    /// The model (OBJ), metres; the ground is its lowest point.
    pub model: PathBuf,
    /// Latitude, degrees north.
    #[arg(long, allow_hyphen_values = true)]
    pub lat: f64,
    /// Longitude, degrees east.
    #[arg(long, allow_hyphen_values = true)]
    pub lon: f64,
    /// The day, YYYY-MM-DD (or give --dates, --preset or --date-range).
    #[arg(long)]
    pub date: Option<NaiveDate>,
    /// Several days, comma-separated: one plan per date on one shared extent, and a table.
    #[arg(long, value_delimiter = ',', conflicts_with = "date")]
    pub dates: Vec<NaiveDate>,
    /// A named set of dates in --year.
    #[arg(long, value_enum, conflicts_with_all = ["date", "dates"])]
    pub preset: Option<DatePreset>,
    /// The year of --preset (default: this year).
    #[arg(long, requires = "preset")]
    pub year: Option<i32>,
    /// Dates from FIRST to LAST (inclusive) every --day-step days: FIRST..LAST.
    #[arg(long, value_parser = parse_range, conflicts_with_all = ["date", "dates", "preset"])]
    pub date_range: Option<(NaiveDate, NaiveDate)>,
    /// Days between the dates of --date-range.
    #[arg(long, default_value_t = 7, requires = "date_range")]
    pub day_step: u32,
    /// First step, local time HH:MM.
    #[arg(long, value_parser = parse_hhmm)]
    pub from: NaiveTime,
    /// Last step, local time HH:MM.
    #[arg(long, value_parser = parse_hhmm)]
    pub to: NaiveTime,
    /// Minutes between steps (at least 1).
    #[arg(long)]
    pub step: u32,
    /// Time zone: an IANA name (Europe/Vienna) or an offset (+02:00); without it the
    /// times are UTC (a warning says so).
    #[arg(long)]
    pub tz: Option<String>,
    /// Angle from the model's +Y axis clockwise (seen from above) to true north, degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub north_offset: f64,
    /// Side of the square plan, metres (default: enough for the lowest sun of every date,
    /// at most twenty times the model's height on each side).
    #[arg(long)]
    pub extent: Option<f64>,
    /// Pixels per side of the plan.
    #[arg(long, default_value_t = 1024)]
    pub resolution: u32,
    /// The model's up axis.
    #[arg(long, value_enum, default_value = "y")]
    pub up: UpAxis,
    /// Silhouette search.
    #[arg(long, value_enum, default_value = "hextree")]
    pub silhouettes: SilhouetteMethod,
    /// What hours.png and the rasters count: hours of direct sun or hours in shadow.
    #[arg(long, value_enum, default_value = "shadow")]
    pub metric: HoursMetric,
    /// Hours a ground cell needs to pass (e.g. 2 for BRE 209 on 21 March): pass.png and
    /// the passing fractions in study.json.
    #[arg(long, allow_hyphen_values = true)]
    pub threshold: Option<f64>,
    /// Analysis areas (GeoJSON Polygons/MultiPolygons in the model's plan coordinates,
    /// metres; `properties.name` names them): their passing fractions in study.json.
    #[arg(long, requires = "threshold")]
    pub areas: Option<PathBuf>,
    /// Only these objects cast shadows (OBJ `o`/`g` names, comma-separated, `*` matches
    /// any run of characters); the others still receive them (a new building's shadow on
    /// the existing ones).
    #[arg(long, value_delimiter = ',')]
    pub casters: Vec<String>,
    /// Also compute hours of sun on the model's facades (every vertical face, on cells of
    /// --facade-cell): facades.csv and one elevation image per facade.
    #[arg(long)]
    pub facades: bool,
    /// Side of a facade cell, metres.
    #[arg(long, default_value_t = 0.5, requires = "facades")]
    pub facade_cell: f64,
    /// Facades smaller than this are left out, m².
    #[arg(long, default_value_t = 1.0, requires = "facades")]
    pub min_facade_area: f64,
    /// Window points (TOML `[[point]]` tables: name, position [x, y, z] in the model's
    /// plan coordinates, normal): hours of direct sun and EN 17037's level in points.csv,
    /// and each point's sun-path diagram with its obstruction mask (sunpath-NAME.svg).
    #[arg(long)]
    pub points: Option<PathBuf>,
    /// The lowest sun counted on facades and at points, degrees (EN 17037 sets one for the
    /// site; default 0).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub min_elevation: f64,
    /// Also write one framed plan per step into DIR/steps/HHMM.png.
    #[arg(long)]
    pub step_images: bool,
    /// Also write the day's animation (one framed plan per step) as a GIF.
    #[arg(long)]
    pub gif: Option<PathBuf>,
    /// Also the model seen in 3D with every surface it shows (roofs, facades, ground)
    /// coloured by hours of the metric: model.png (framed, with a legend) and model.exr
    /// (hours per pixel), from the south-west 35° up unless --view-from is given.
    #[arg(long)]
    pub model_view: bool,
    /// --model-view's eye: X,Y,Z in the model file's plan coordinates and height, metres.
    #[arg(long, value_parser = parse_xyz, requires = "model_view", allow_hyphen_values = true)]
    pub view_from: Option<DVec3>,
    /// --model-view's target: X,Y,Z as --view-from (default: the model's centre).
    #[arg(long, value_parser = parse_xyz, requires = "view_from", allow_hyphen_values = true)]
    pub view_at: Option<DVec3>,
    /// --model-view's image size, pixels.
    #[arg(long, value_parser = parse_size, default_value = "1200x900", requires = "model_view")]
    pub view_size: (u32, u32),
    /// The output folder (one sub-folder per date when there are several).
    #[arg(long)]
    pub out: PathBuf,
    /// The most the study may write, GB (estimated from the resolution, dates and steps
    /// before the work; refused above it).
    #[arg(long, value_name = "GB", default_value_t = MAX_OUTPUT_BYTES as f64 / f64::from(1u32 << 30))]
    pub output_limit: f64,
}

/// The camera of `--model-view`: the user's eye and target (the model file's plan
/// coordinates, moved as the model was by `origin`), else the default view.
fn model_camera(
    a: &ProfileArgs,
    model: &crate::geometry::Mesh,
    origin: glam::DVec2,
) -> Result<Option<Camera>, CliError> {
    if !a.model_view {
        return Ok(None);
    }
    let shift = DVec3::new(origin.x, origin.y, 0.0);
    let camera = match a.view_from {
        Some(from) => {
            let (lo, hi) = model
                .bounds()
                .ok_or_else(|| CliError::input(anyhow!("the model has no triangles")))?;
            let at = a.view_at.map_or((lo + hi) * 0.5, |at| at - shift);
            if (from - shift).distance(at) < 1e-3 {
                return Err(CliError::input(anyhow!(
                    "--view-from and --view-at must be different points"
                )));
            }
            Camera::perspective(from - shift, at, 40.0)
        }
        None => default_camera(model, a.north_offset)
            .ok_or_else(|| CliError::input(anyhow!("the model has no triangles")))?,
    };
    Ok(Some(camera))
}

fn parse_xyz(s: &str) -> Result<DVec3, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|c| c.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{s:?}: {e} (expected X,Y,Z in metres)"))?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(DVec3::new(x, y, z)),
        _ => Err(format!("{s:?}: expected three finite numbers X,Y,Z")),
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("{s:?}: expected WIDTHxHEIGHT, e.g. 1200x900"))?;
    let px = |t: &str| {
        t.trim()
            .parse::<u32>()
            .map_err(|e| format!("{s:?}: {e} (expected WIDTHxHEIGHT)"))
    };
    let (w, h) = (px(w)?, px(h)?);
    let max = crate::scene::MAX_IMAGE_SIZE;
    if !(16..=max).contains(&w) || !(16..=max).contains(&h) {
        return Err(format!("{s:?}: each side must be 16 to {max} pixels"));
    }
    Ok((w, h))
}

/// Named sets of dates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DatePreset {
    /// 21 March, 21 June, 21 December (the dates BRE 209 and most sun studies use; on the
    /// southern hemisphere the same dates, whose meaning swaps).
    EquinoxSolstices,
    /// The 21st of every month.
    Monthly,
}

impl DatePreset {
    /// Its dates in `year`.
    pub fn dates(self, year: i32) -> Vec<NaiveDate> {
        let months: Vec<u32> = match self {
            DatePreset::EquinoxSolstices => vec![3, 6, 12],
            DatePreset::Monthly => (1..=12).collect(),
        };
        months
            .into_iter()
            .filter_map(|m| NaiveDate::from_ymd_opt(year, m, 21))
            .collect()
    }
}

fn parse_hhmm(s: &str) -> Result<NaiveTime, String> {
    NaiveTime::parse_from_str(s, "%H:%M").map_err(|_| format!("{s:?} is not a time HH:MM"))
}

fn parse_range(s: &str) -> Result<(NaiveDate, NaiveDate), String> {
    let (a, b) = s
        .split_once("..")
        .ok_or_else(|| format!("{s:?} is not FIRST..LAST (e.g. 2026-03-01..2026-03-31)"))?;
    let date = |t: &str| {
        NaiveDate::parse_from_str(t.trim(), "%Y-%m-%d")
            .map_err(|_| format!("{t:?} is not a date YYYY-MM-DD"))
    };
    let (a, b) = (date(a)?, date(b)?);
    if a > b {
        return Err(format!("{a} is after {b}"));
    }
    Ok((a, b))
}

/// The most dates one run takes (each date's profile stays in memory until all are done,
/// so an interrupted study writes nothing).
pub const MAX_DATES: usize = 60;

impl ProfileArgs {
    /// The study's dates, in order, without repeats.
    fn study_dates(&self) -> Result<Vec<NaiveDate>, CliError> {
        let mut dates = if let Some(d) = self.date {
            vec![d]
        } else if !self.dates.is_empty() {
            self.dates.clone()
        } else if let Some(p) = self.preset {
            let year = self
                .year
                .unwrap_or_else(|| chrono::Datelike::year(&chrono::Utc::now()));
            p.dates(year)
        } else if let Some((first, last)) = self.date_range {
            if self.day_step == 0 {
                return Err(CliError::input(anyhow!("--day-step must be at least 1")));
            }
            let mut v = Vec::new();
            let mut d = first;
            while d <= last {
                v.push(d);
                match d.checked_add_days(chrono::Days::new(u64::from(self.day_step))) {
                    Some(next) => d = next,
                    None => break,
                }
            }
            v
        } else {
            return Err(CliError::input(anyhow!(
                "give the day: --date, --dates, --preset or --date-range"
            )));
        };
        dates.sort();
        dates.dedup();
        if dates.len() > MAX_DATES {
            return Err(CliError::input(anyhow!(
                "{} dates; at most {MAX_DATES} per run (use a larger --day-step)",
                dates.len()
            )));
        }
        Ok(dates)
    }
}

impl ProfileArgs {
    /// The files the study reads: the model (and its MTL files), the points and areas.
    fn input_files(&self) -> Vec<PathBuf> {
        let mut files = crate::geometry::obj::material_libraries(&self.model);
        files.push(self.model.clone());
        files.extend(self.points.iter().cloned());
        files.extend(self.areas.iter().cloned());
        files
    }
}

/// Bytes per plan pixel over the files a date writes: measured 31 at 1024 px on a box
/// (hours.csv 23, hours.asc 7, the PNGs and hours.exr the rest), rounded up.
const BYTES_PER_PIXEL: u64 = 32;
/// Bytes per pixel of one step image (--step-images, --gif).
const BYTES_PER_STEP_PIXEL: u64 = 2;

/// An error when the study's files would exceed [`MAX_OUTPUT_BYTES`] (estimated from the
/// resolution, the dates and the steps before any is written).
fn check_budget(a: &ProfileArgs, dates: usize, steps: usize) -> Result<(), CliError> {
    let (dates, steps) = (dates as u64, steps as u64);
    let pixels = u64::from(a.resolution).pow(2);
    let per_step = u64::from(a.step_images) + u64::from(a.gif.is_some());
    let estimate =
        dates * pixels * BYTES_PER_PIXEL + steps * per_step * pixels * BYTES_PER_STEP_PIXEL;
    let limit = a.output_limit * f64::from(1u32 << 30);
    if !(a.output_limit.is_finite() && a.output_limit > 0.0) {
        return Err(CliError::input(anyhow!(
            "--output-limit {} must be a positive number of GB",
            a.output_limit
        )));
    }
    if estimate as f64 > limit {
        return Err(CliError::input(anyhow!(
            "--resolution {} over {dates} date(s) and {steps} step(s) would write about {} of files, more than --output-limit {} GB: lower --resolution, give fewer dates, or raise --output-limit",
            a.resolution,
            bytes(estimate),
            a.output_limit
        )));
    }
    Ok(())
}

/// A model's plan coordinates named for titles: "48.21° N, 16.37° E".
fn site_label(lat: f64, lon: f64) -> String {
    format!(
        "{:.4}° {}, {:.4}° {}",
        lat.abs(),
        if lat >= 0.0 { "N" } else { "S" },
        lon.abs(),
        if lon >= 0.0 { "E" } else { "W" }
    )
}

/// Runs `profile`.
pub fn run(a: ProfileArgs) -> Result<(), CliError> {
    let site = Site::new(a.lat, a.lon, 0.0)?;
    let zone = match &a.tz {
        Some(tz) => Zone::parse(tz)?,
        None => {
            eprintln!(
                "warning: no --tz: --from/--to and every time written are UTC (give --tz Europe/Vienna or +01:00 for local time)"
            );
            Zone::parse("UTC")?
        }
    };
    let tz_name = a.tz.clone().unwrap_or_else(|| "UTC".into());
    let dates = a.study_dates()?;
    let areas = match &a.areas {
        Some(p) => read_areas(p).map_err(CliError::input)?,
        None => Vec::new(),
    };
    if let Some(t) = a.threshold {
        if !(t.is_finite() && t >= 0.0) {
            return Err(CliError::input(anyhow!(
                "--threshold {t} must be a number of hours ≥ 0"
            )));
        }
    }
    let points = match &a.points {
        Some(p) => {
            let text = crate::io::read_text_limited(p, crate::io::MAX_TEXT_BYTES)
                .map_err(|e| CliError::input(anyhow!("{}: {e}", p.display())))?;
            parse_points(&text).map_err(|e| CliError::input(anyhow!("{}: {e}", p.display())))?
        }
        None => Vec::new(),
    };
    if a.facades && !(a.facade_cell.is_finite() && a.facade_cell >= 0.01) {
        return Err(CliError::input(anyhow!(
            "--facade-cell {} must be at least 0.01 m",
            a.facade_cell
        )));
    }
    let inputs = a.input_files();
    let mut outputs = OutputCheck::new();
    for f in &inputs {
        outputs.input(f);
    }
    if let Some(gif) = &a.gif {
        outputs.named_output(&format!("--gif {}", gif.display()), gif);
        super::check_folder_of(gif, "--gif")?;
    }
    outputs.check()?;
    if a.out.is_file() {
        return Err(CliError::input(anyhow!(
            "--out {}: is a file, not a folder",
            a.out.display()
        )));
    }
    let (mut model, non_casters) = load_components(&a.model, a.up, &a.casters)?;
    if let Some(w) = up_axis_warning(&model, a.up) {
        eprintln!("warning: {}: {w}", a.model.display());
    }
    let origin = recentre(&mut model);
    let specs: Vec<ProfileSpec> = dates
        .iter()
        .map(|&date| ProfileSpec {
            site,
            zone,
            date,
            from: a.from,
            to: a.to,
            step_minutes: a.step,
            sun: SunOptions {
                north_offset_deg: a.north_offset,
                ..Default::default()
            },
            extent_m: a.extent,
            resolution: a.resolution,
            silhouette: a.silhouettes,
            non_casters: non_casters.clone(),
            volume_ends: Default::default(),
        })
        .collect();
    // Check every period before starting the GPU; several dates share one extent.
    let mut steps = 0;
    for s in &specs {
        steps += s.local_times()?.len();
        s.suns()?;
    }
    check_budget(&a, specs.len(), steps)?;
    let camera = model_camera(&a, &model, origin)?;
    if camera.is_some() {
        steps *= 2;
    }
    let shared = match (a.extent, specs.len()) {
        (None, 2..) => Some(shared_extent(&model, &specs)?),
        (e, _) => e,
    };
    let gpu = Gpu::shared().map_err(CliError::failure)?;
    // Welded, with its edges (and the hextree on first use), once for every date and view.
    let geometry = prepare(&gpu, &model)?;
    let bar = indicatif::ProgressBar::new(steps as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} steps, {eta} left")
            .map_err(|e| CliError::failure(anyhow!(e)))?,
    );
    bar.set_message("shadow profile");
    // Ctrl-C stops between steps; nothing is written for an unfinished study.
    let cancel = super::interrupt_flag();
    eprintln!(
        "{}: {steps} steps on {} date(s) (Ctrl-C stops and writes nothing)",
        a.model.display(),
        dates.len()
    );
    let mut profiles = Vec::with_capacity(specs.len());
    let mut done_before = 0;
    for spec in &specs {
        let spec = ProfileSpec {
            extent_m: shared,
            ..spec.clone()
        };
        let t = std::time::Instant::now();
        let result = compute_on(
            &gpu,
            &geometry,
            &spec,
            |done, _| bar.set_position((done_before + done) as u64),
            &cancel,
        );
        let mut profile = match result {
            Ok(p) => p,
            Err(e) => {
                bar.finish_and_clear();
                return Err(e.into());
            }
        };
        done_before += spec.local_times()?.len();
        profile.origin = origin;
        let seconds = t.elapsed().as_secs_f64();
        let view = match &camera {
            Some(camera) => {
                let result = view_hours(
                    &gpu,
                    &geometry,
                    &spec,
                    camera,
                    a.view_size,
                    |done, _| bar.set_position((done_before + done) as u64),
                    &cancel,
                );
                done_before += spec.local_times()?.len();
                match result {
                    Ok(v) => Some(v),
                    Err(e) => {
                        bar.finish_and_clear();
                        return Err(e.into());
                    }
                }
            }
            None => None,
        };
        profiles.push((spec, profile, seconds, view));
    }
    bar.finish_and_clear();
    let mut staging = Staging::beside(&a.out, &inputs)
        .map_err(|e| CliError::input(anyhow!("--out {}: {e}", a.out.display())))?;
    let surfaces = Surfaces::new(&a, &model, origin, points, non_casters);
    let several = profiles.len() > 1;
    let mut summaries = Vec::new();
    for (spec, profile, seconds, view) in &profiles {
        report(&a, profile, *seconds);
        let dir = if several {
            staging.dir().join(spec.date.to_string())
        } else {
            staging.dir().to_path_buf()
        };
        let gif = match &a.gif {
            Some(g) if several => Some(dir.join(g.file_name().unwrap_or(g.as_os_str()))),
            Some(g) => Some(
                staging
                    .outside(g)
                    .map_err(|e| CliError::failure(anyhow!("--gif {}: {e}", g.display())))?,
            ),
            None => None,
        };
        let output = StudyOutput {
            metric: a.metric,
            threshold_h: a.threshold,
            areas: areas.clone(),
            labels: PlanLabels {
                title: site_label(a.lat, a.lon),
                subtitle: format!(
                    "{}, {}–{} {tz_name}, every {} min",
                    spec.date,
                    a.from.format("%H:%M"),
                    a.to.format("%H:%M"),
                    a.step
                ),
                north_offset_deg: a.north_offset,
            },
            step_images: a.step_images,
            surfaces: surfaces.for_profile(profile, a.north_offset),
            gif,
        };
        let summary = write_study(profile, &dir, &output).map_err(CliError::failure)?;
        write_sun_path(spec, profile, &dir, &output.labels, surfaces.masks())?;
        if let Some(v) = view {
            let view_labels = PlanLabels {
                title: format!(
                    "{} — hours of {} on the model",
                    site_label(a.lat, a.lon),
                    a.metric.name()
                ),
                subtitle: format!(
                    "{}; seen from {}",
                    output.labels.subtitle,
                    match a.view_from {
                        Some(f) => format!("({:.1}, {:.1}, {:.1}) m", f.x, f.y, f.z),
                        None => "the south-west, 35° above the horizon".into(),
                    }
                ),
                ..output.labels.clone()
            };
            write_model_view(v, a.metric, &view_labels, &dir).map_err(CliError::failure)?;
        }
        summaries.push((spec.date, summary));
    }
    if several {
        write_dates_table(staging.dir(), &summaries).map_err(CliError::failure)?;
    }
    // Complete or none: a Ctrl-C while writing leaves nothing.
    if cancel.load(std::sync::atomic::Ordering::SeqCst) {
        return Err(CliError::failure(anyhow!(
            "interrupted while writing the outputs: nothing written"
        )));
    }
    staging
        .commit()
        .map_err(|e| CliError::failure(anyhow!("--out {}: {e:#}", a.out.display())))?;
    for (date, s) in &summaries {
        if let Some(f) = s.pass_fraction {
            println!(
                "{date}: {:.1} % of the plan reaches {} h of {} ({} area(s){})",
                100.0 * f,
                s.threshold_h.unwrap_or(0.0),
                s.metric,
                s.areas.len(),
                s.areas
                    .iter()
                    .map(|r| format!(
                        ", {}: {}",
                        r.name,
                        r.pass_fraction
                            .map_or("outside the plan".into(), |f| format!("{:.1} %", 100.0 * f))
                    ))
                    .collect::<String>()
            );
        }
    }
    Ok(())
}

fn report(a: &ProfileArgs, profile: &Profile, seconds: f64) {
    let date = profile
        .steps
        .first()
        .map(|s| s.time.format("%Y-%m-%d: ").to_string())
        .unwrap_or_default();
    if !profile.skipped.is_empty() {
        let times: Vec<String> = profile
            .skipped
            .iter()
            .map(|t| t.format("%H:%M").to_string())
            .collect();
        eprintln!(
            "warning: {date}the sun is below the horizon at {} step(s), skipped: {}",
            times.len(),
            times.join(" ")
        );
    }
    let cut: Vec<String> = profile
        .steps
        .iter()
        .filter(|s| s.reaches_edge)
        .map(|s| s.time.format("%H:%M").to_string())
        .collect();
    if !cut.is_empty() {
        eprintln!(
            "warning: {date}the shadow reaches the edge of the {:.0} m plan at {} (its area is cut; use a larger --extent): {}",
            profile.extent_m,
            cut.len(),
            cut.join(" ")
        );
    }
    let n = profile.steps.len().max(1) as f64;
    println!(
        "{}: {date}{} steps, plan {:.1} m at {} px ({:.3} m/px), footprint {:.1} m²; {:.2} s ({:.1} ms/step: silhouettes {:.1} ms, shadow volumes {:.1} ms) → {}",
        a.model.display(),
        profile.steps.len(),
        profile.extent_m,
        profile.resolution,
        profile.extent_m / profile.resolution as f64,
        profile.footprint_area_m2(),
        seconds,
        1000.0 * seconds / n,
        1000.0 * profile.timing.silhouette_s / n,
        1000.0 * profile.timing.render_s / n,
        a.out.display()
    );
}
