//! `goniolight profile`: sun studies of a model over a period — shadow profiles, hours of sun
//! or shadow, thresholds, several dates, facades and windows.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use chrono::{NaiveDate, NaiveTime};
use clap::Args;
use glam::DVec3;

use super::error::flags_in;
use super::error::CliError;
use crate::gpu::Gpu;
use crate::io::limits::{bytes, MAX_OUTPUT_BYTES};
use crate::io::outputs::{OutputCheck, Staging};
use crate::scene::UpAxis;
use crate::shadow::SilhouetteMethod;
use crate::study::rasters::{read_areas, AnalysisArea};
use crate::study::shadow_profile::HoursMetric;
use crate::study::sun_study::{GifPlace, ModelView, StudyFiles, MAX_DATES};
use crate::study::surface_set::FacadeOptions;
use crate::study::surfaces::{parse_points, WindowPoint};
use crate::study::{SunStudy, SunStudyOptions};

/// Options of `profile`.
#[derive(Debug, Args)]
pub struct ProfileArgs {
    /// The model (OBJ or glTF: .gltf, .glb), metres; the ground is its lowest point.
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
    /// Only these objects cast shadows (OBJ `o`/`g` names or glTF node names, comma-separated, `*` matches
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
    /// The library's options from the flags, with the dates, areas and points read.
    fn options(
        &self,
        dates: Vec<NaiveDate>,
        areas: Vec<AnalysisArea>,
        points: Vec<WindowPoint>,
    ) -> SunStudyOptions {
        SunStudyOptions {
            up: self.up,
            casters: self.casters.clone(),
            zone: self.tz.clone(),
            north_offset_deg: self.north_offset,
            extent_m: self.extent,
            resolution: self.resolution,
            silhouettes: self.silhouettes,
            metric: self.metric,
            threshold_h: self.threshold,
            areas,
            facades: self.facades.then_some(FacadeOptions {
                cell_m: self.facade_cell,
                min_area_m2: self.min_facade_area,
            }),
            points,
            min_elevation_deg: self.min_elevation,
            model_view: self.model_view.then_some(ModelView {
                from: self.view_from,
                at: self.view_at,
                size: self.view_size,
            }),
            ..SunStudyOptions::new(
                self.model.clone(),
                (self.lat, self.lon),
                dates,
                (self.from, self.to),
                self.step,
            )
        }
    }
}

/// An error when the study's files would exceed `--output-limit` (estimated from the
/// resolution, the dates and the steps before any is written).
fn check_budget(a: &ProfileArgs, study: &SunStudy, files: &StudyFiles) -> Result<(), CliError> {
    if !(a.output_limit.is_finite() && a.output_limit > 0.0) {
        return Err(CliError::input(anyhow!(
            "--output-limit {} must be a positive number of GB",
            a.output_limit
        )));
    }
    let estimate = study.estimated_output_bytes(files);
    if estimate as f64 > a.output_limit * f64::from(1u32 << 30) {
        return Err(CliError::input(anyhow!(
            "--resolution {} over {} date(s) and {} step(s) would write about {} of files, more than --output-limit {} GB: lower --resolution, give fewer dates, or raise --output-limit",
            a.resolution,
            study.options().dates.len(),
            study.plan_steps(),
            bytes(estimate),
            a.output_limit
        )));
    }
    Ok(())
}

/// Reads the `--points` file.
fn read_points(path: &Path) -> Result<Vec<WindowPoint>, CliError> {
    let text = crate::io::read_text_limited(path, crate::io::MAX_TEXT_BYTES)
        .map_err(|e| CliError::input(anyhow!("{}: {e}", path.display())))?;
    parse_points(&text).map_err(|e| CliError::input(anyhow!("{}: {e}", path.display())))
}

/// Runs `profile`.
pub fn run(a: ProfileArgs) -> Result<(), CliError> {
    if a.tz.is_none() {
        eprintln!(
            "warning: no --tz: --from/--to and every time written are UTC (give --tz Europe/Vienna or +01:00 for local time)"
        );
    }
    let dates = a.study_dates()?;
    let areas = match &a.areas {
        Some(p) => read_areas(p).map_err(CliError::input)?,
        None => Vec::new(),
    };
    let points = match &a.points {
        Some(p) => read_points(p)?,
        None => Vec::new(),
    };
    let options = a.options(dates, areas, points);
    let mut inputs = options.input_files();
    inputs.extend(a.points.iter().cloned());
    inputs.extend(a.areas.iter().cloned());
    let mut outputs = OutputCheck::new();
    for f in &inputs {
        outputs.input(f);
    }
    if let Some(gif) = &a.gif {
        outputs.named_output(&format!("--gif {}", gif.display()), gif);
        super::args::check_folder_of(gif, "--gif")?;
    }
    outputs.check()?;
    if a.out.is_file() {
        return Err(CliError::input(anyhow!(
            "--out {}: is a file, not a folder",
            a.out.display()
        )));
    }
    let study = SunStudy::prepare(options)?;
    let name = a.model.display();
    for w in study.warnings() {
        eprintln!("warning: {name}: {}", flags_in(w));
    }
    let model = study.model();
    if !a.casters.is_empty() {
        let total = model.mesh.triangles.len();
        eprintln!(
            "{name}: {} of {total} triangles cast shadows (--casters)",
            model.casting
        );
    }
    if a.facades {
        let facades = study.facades();
        let cells: usize = facades
            .iter()
            .map(|f| f.hours.iter().flatten().count())
            .sum();
        eprintln!(
            "{name}: {} facade(s) of at least {} m², {cells} cells",
            facades.len(),
            a.min_facade_area
        );
    }
    let mut files = StudyFiles {
        step_images: a.step_images,
        gif: a.gif.as_ref().map(|g| GifPlace::At(g.clone())),
    };
    check_budget(&a, &study, &files)?;
    let gpu = Gpu::shared().map_err(CliError::failure)?;
    let steps = study.progress_steps();
    let bar = indicatif::ProgressBar::new(steps as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} steps, {eta} left")
            .map_err(CliError::failure)?,
    );
    bar.set_message("shadow profile");
    // Ctrl-C stops between steps; nothing is written for an unfinished study.
    let cancel = super::interrupt::interrupt_flag();
    eprintln!(
        "{name}: {steps} steps on {} date(s) (Ctrl-C stops and writes nothing)",
        study.options().dates.len()
    );
    let days = study.compute(&gpu, |done, _| bar.set_position(done as u64), &cancel);
    bar.finish_and_clear();
    let days = days?;
    for day in &days {
        for w in day.warnings() {
            eprintln!("warning: {}", flags_in(&w));
        }
        println!("{name}: {} → {}", day.describe(), a.out.display());
    }
    let mut staging = Staging::beside(&a.out, &inputs)
        .map_err(|e| CliError::input(anyhow!("--out {}: {e}", a.out.display())))?;
    files.gif = match &a.gif {
        Some(g) if days.len() > 1 => Some(GifPlace::EachDate(
            g.file_name().unwrap_or(g.as_os_str()).to_owned(),
        )),
        Some(g) => Some(GifPlace::At(staging.outside(g).map_err(|e| {
            CliError::failure(anyhow!("--gif {}: {e}", g.display()))
        })?)),
        None => None,
    };
    let summaries = study
        .write(&days, staging.dir(), &files)
        .map_err(CliError::failure)?;
    // Complete or none: a Ctrl-C while writing leaves nothing.
    if cancel.load(std::sync::atomic::Ordering::SeqCst) {
        return Err(CliError::failure(anyhow!(
            "interrupted while writing the outputs: nothing written"
        )));
    }
    staging
        .commit()
        .map_err(|e| CliError::failure(anyhow!("--out {}: {e:#}", a.out.display())))?;
    for (day, s) in days.iter().zip(&summaries) {
        if let Some(line) = s.pass_line() {
            println!("{}: {line}", day.spec.date);
        }
    }
    Ok(())
}
