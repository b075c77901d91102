//! `goniolight profile`: sun-path shadow profiles of a model over a period.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use chrono::{NaiveDate, NaiveTime};
use clap::Args;

use super::CliError;
use crate::geometry::obj::read_obj_objects;
use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::io::write_atomic;
use crate::scene::UpAxis;
use crate::shadow::bvh::TriangleBvh;
use crate::shadow::IgnoredTriangles;
use crate::shadow::SilhouetteMethod;
use crate::study::annotate::PlanLabels;
use crate::study::model::{recentre, up_axis_warning};
use crate::study::output::{write_study, StudyOutput};
use crate::study::profile::{compute, shared_extent, HoursMetric, Profile, ProfileSpec};
use crate::study::rasters::read_areas;
use crate::study::sunpath::SunPathDiagram;
use crate::study::surface_output::SurfaceResults;
use crate::study::surfaces::{
    facade_hours, find_facades, parse_points, surface_offset, Facade, Sun, SunRays, WindowPoint,
};
use crate::sun::direction_from_angles;
use crate::sun::{Site, SunOptions, Zone};

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
    /// plan coordinates, normal): hours of direct sun and EN 17037's level in points.csv.
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
    /// The output folder (one sub-folder per date when there are several).
    #[arg(long)]
    pub out: PathBuf,
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
                d += chrono::Duration::days(self.day_step as i64);
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

/// Reads an OBJ model, turns it to the world's +Z up and, when `casters` names objects
/// (`o`/`g` names, `*` matches any run of characters), puts their triangles first: the
/// rest receive shadows but cast none (returned as the triangles to leave out). Refused
/// when a pattern matches no object (the message lists the names).
pub fn load_components(
    path: &Path,
    up: UpAxis,
    casters: &[String],
) -> Result<(Mesh, IgnoredTriangles), CliError> {
    let (mut mesh, objects) = read_obj_objects(path)?;
    if up == UpAxis::Y {
        for p in &mut mesh.positions {
            *p = glam::DVec3::new(p.x, -p.z, p.y);
        }
    }
    let casts: Vec<bool> = if casters.is_empty() {
        vec![true; objects.names.len()]
    } else {
        for pattern in casters {
            if !objects.names.iter().any(|n| wildcard_match(pattern, n)) {
                let mut names = objects.names.clone();
                names.truncate(30);
                return Err(CliError::input(anyhow!(
                    "--casters: {pattern:?} matches no object of {} (its objects: {}{})",
                    path.display(),
                    names.join(", "),
                    if objects.names.len() > 30 {
                        ", …"
                    } else {
                        ""
                    }
                )));
            }
        }
        objects
            .names
            .iter()
            .map(|n| casters.iter().any(|p| wildcard_match(p, n)))
            .collect()
    };
    let total = mesh.triangles.len();
    // Casters first, then the rest; each part loses its degenerate triangles.
    let part = |cast: bool| {
        let mut m = Mesh {
            positions: mesh.positions.clone(),
            triangles: mesh
                .triangles
                .iter()
                .zip(&objects.of_triangle)
                .filter(|(_, &o)| casts[o as usize] == cast)
                .map(|(t, _)| *t)
                .collect(),
        };
        let dropped = m.remove_degenerate();
        (m, dropped)
    };
    let ((mut model, dropped_casting), (rest, dropped_rest)) = (part(true), part(false));
    let dropped = dropped_casting + dropped_rest;
    if dropped > 0 {
        eprintln!(
            "warning: {}: {dropped} of its {total} triangles have no area and were dropped",
            path.display()
        );
    }
    let casting = model.triangles.len();
    model.triangles.extend(rest.triangles);
    model.validate(&path.display().to_string())?;
    if !casters.is_empty() {
        if casting == 0 {
            return Err(CliError::input(anyhow!(
                "--casters: the objects named have no triangles with area"
            )));
        }
        eprintln!(
            "{}: {casting} of {} triangles cast shadows (--casters)",
            path.display(),
            model.triangles.len()
        );
    }
    let non_casters = if casting < model.triangles.len() {
        IgnoredTriangles(std::iter::once(casting..model.triangles.len()).collect())
    } else {
        IgnoredTriangles::default()
    };
    Ok((model, non_casters))
}

/// Whether `name` matches `pattern`, where `*` stands for any run of characters.
pub fn wildcard_match(pattern: &str, name: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    if parts.len() == 1 {
        return pattern == name;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !name.starts_with(first) || name.len() < first.len() + last.len() || !name.ends_with(last) {
        return false;
    }
    let mut rest = &name[first.len()..name.len() - last.len()];
    for middle in &parts[1..parts.len() - 1] {
        match rest.find(middle) {
            Some(k) => rest = &rest[k + middle.len()..],
            None => return false,
        }
    }
    true
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
            let text = std::fs::read_to_string(p)
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
        })
        .collect();
    // Check every period before starting the GPU; several dates share one extent.
    let mut steps = 0;
    for s in &specs {
        steps += s.local_times()?.len();
        s.suns()?;
    }
    let shared = match (a.extent, specs.len()) {
        (None, 2..) => Some(shared_extent(&model, &specs)?),
        (e, _) => e,
    };
    let gpu = Gpu::shared().map_err(CliError::failure)?;
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
        let result = compute(
            &gpu,
            &model,
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
        profiles.push((spec, profile, t.elapsed().as_secs_f64()));
    }
    bar.finish_and_clear();
    let surfaces = Surfaces::new(&a, &model, origin, points, non_casters);
    let several = profiles.len() > 1;
    let mut summaries = Vec::new();
    for (spec, profile, seconds) in &profiles {
        report(&a, profile, *seconds);
        let dir = if several {
            a.out.join(spec.date.to_string())
        } else {
            a.out.clone()
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
            gif: a.gif.as_ref().map(|g| {
                if several {
                    dir.join(g.file_name().unwrap_or(g.as_os_str()))
                } else {
                    g.clone()
                }
            }),
        };
        let summary = write_study(profile, &dir, &output).map_err(CliError::failure)?;
        write_sun_path(spec, profile, &dir, &output.labels)?;
        summaries.push((spec.date, summary));
    }
    if several {
        write_dates_table(&a.out, &summaries).map_err(CliError::failure)?;
    }
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

/// The model's facades and the window points, set up once for every date.
struct Surfaces {
    bvh: Option<TriangleBvh>,
    facades: Vec<Facade>,
    points: Vec<WindowPoint>,
    origin: glam::DVec2,
    min_elevation_deg: f64,
    eps: f64,
    non_casters: IgnoredTriangles,
}

impl Surfaces {
    fn new(
        a: &ProfileArgs,
        model: &Mesh,
        origin: glam::DVec2,
        points: Vec<WindowPoint>,
        non_casters: IgnoredTriangles,
    ) -> Self {
        let wanted = a.facades || !points.is_empty();
        let facades = if a.facades {
            find_facades(model, a.facade_cell, a.min_facade_area)
        } else {
            Vec::new()
        };
        if a.facades {
            eprintln!(
                "{}: {} facade(s) of at least {} m², {} cells",
                a.model.display(),
                facades.len(),
                a.min_facade_area,
                facades
                    .iter()
                    .map(|f| f.hours.iter().flatten().count())
                    .sum::<usize>()
            );
        }
        Surfaces {
            bvh: wanted.then(|| TriangleBvh::new(model)),
            facades,
            points,
            origin,
            min_elevation_deg: a.min_elevation,
            eps: surface_offset(model),
            non_casters,
        }
    }

    /// The hours on the facades and at the points under `profile`'s suns.
    fn for_profile(&self, profile: &Profile, north_offset_deg: f64) -> Option<SurfaceResults> {
        let bvh = self.bvh.as_ref()?;
        let suns: Vec<Sun> = profile
            .steps
            .iter()
            .map(|s| Sun {
                direction: direction_from_angles(s.azimuth_deg, s.elevation_deg, north_offset_deg),
                elevation_deg: s.elevation_deg,
                weight_h: s.weight_h,
            })
            .collect();
        let mut facades = self.facades.clone();
        let rays = SunRays {
            bvh,
            suns: &suns,
            min_elevation_deg: self.min_elevation_deg,
            eps: self.eps,
            non_casters: &self.non_casters,
        };
        facade_hours(&rays, &mut facades);
        let points = self
            .points
            .iter()
            .map(|p| {
                let [x, y, z] = p.position;
                let world = glam::DVec3::new(x - self.origin.x, y - self.origin.y, z);
                let normal = glam::DVec3::from_array(p.normal).normalize();
                let hours = rays.hours_at(world, normal);
                (p.clone(), hours)
            })
            .collect();
        Some(SurfaceResults {
            facades,
            points,
            min_elevation_deg: self.min_elevation_deg,
        })
    }
}

/// The sun-path diagram of the study's site with this date's steps marked.
fn write_sun_path(
    spec: &ProfileSpec,
    profile: &Profile,
    dir: &Path,
    labels: &PlanLabels,
) -> Result<(), CliError> {
    let suns: Vec<_> = profile
        .steps
        .iter()
        .map(|s| (s.time, s.azimuth_deg, s.elevation_deg))
        .collect();
    let diagram = SunPathDiagram {
        site: spec.site,
        zone: spec.zone,
        year: chrono::Datelike::year(&spec.date),
        sun: spec.sun,
        title: format!("Sun path — {}", labels.title),
        marked: suns,
    };
    let svg = diagram.svg().map_err(|e| CliError::failure(anyhow!(e)))?;
    write_atomic(&dir.join("sunpath.svg"), svg.as_bytes()).map_err(CliError::failure)
}

/// `dates.csv` and `dates.json` beside the per-date folders: one row per date.
fn write_dates_table(
    dir: &Path,
    summaries: &[(NaiveDate, crate::study::output::StudySummary)],
) -> anyhow::Result<()> {
    use std::fmt::Write as _;
    let mut csv = String::from("date,metric,period_h,sun_up_h,mean_h,threshold_h,pass_fraction\n");
    for (date, s) in summaries {
        let _ = writeln!(
            csv,
            "{date},{},{:.4},{:.4},{:.4},{},{}",
            s.metric,
            s.period_h,
            s.sun_up_h,
            s.mean_h,
            s.threshold_h.map_or(String::new(), |t| t.to_string()),
            s.pass_fraction.map_or(String::new(), |f| format!("{f:.6}"))
        );
    }
    write_atomic(&dir.join("dates.csv"), csv.as_bytes())?;
    let json: Vec<_> = summaries
        .iter()
        .map(|(d, s)| serde_json::json!({ "date": d.to_string(), "study": s }))
        .collect();
    write_atomic(
        &dir.join("dates.json"),
        serde_json::to_string_pretty(&json)?.as_bytes(),
    )
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

/// Runs `bench profile`: the same profile with brute-force and hextree silhouettes, on
/// the generated building and, with `shared`, on the real models.
pub fn run_bench(
    as_json: bool,
    resolution: u32,
    step: u32,
    floors: u32,
    shared: Option<PathBuf>,
) -> Result<(), CliError> {
    if !(1..=40).contains(&floors) {
        return Err(CliError::input(anyhow!(
            "--floors {floors} is not in 1..=40"
        )));
    }
    let mut models = vec![crate::bench::profile::generated_building(floors)];
    if let Some(dir) = shared {
        for (name, rel) in [
            ("Delft city block", "models/delft_3dfier/testarea.obj"),
            ("high-rise block", "models/openfoam_buildings/buildings.obj"),
        ] {
            let (mut mesh, _) = load_components(&dir.join(rel), UpAxis::Z, &[])?;
            recentre(&mut mesh);
            models.push((name.to_string(), mesh));
        }
    }
    let gpu = Gpu::shared().map_err(CliError::failure)?;
    eprintln!("GPU: {}", gpu.describe());
    let rows = crate::bench::profile::run(&gpu, &models, resolution, step)?;
    if as_json {
        println!("{}", serde_json::json!({ "rows": rows }));
        return Ok(());
    }
    println!(
        "shadow profile: {} steps, {resolution}² plan",
        rows.first().map_or(0, |r| r.steps)
    );
    println!(
        "| model | triangles | silhouettes | total s | ms/step | silhouette ms/step | volumes + read-back ms/step |"
    );
    println!("|---|---:|---|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {} | {} | {:.2} | {:.1} | {:.2} | {:.1} |",
            r.model,
            r.triangles,
            r.method,
            r.total_s,
            r.per_step_ms,
            r.silhouette_ms_per_step,
            r.render_ms_per_step
        );
    }
    for pair in rows.chunks(2) {
        if let [brute, hex] = pair {
            println!(
                "{}: hextree / brute force: total {:.2}×, silhouettes {:.2}× faster",
                brute.model,
                brute.total_s / hex.total_s,
                brute.silhouette_ms_per_step / hex.silhouette_ms_per_step.max(1e-12)
            );
        }
    }
    Ok(())
}
