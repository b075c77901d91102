//! The files of a sun study: `profile.png` (every step's shadow overlaid, coloured by
//! time, with the building and a legend), `hours.png` (hours of sun or of shadow per cell
//! on a colour scale with a legend), `profile.csv` (one row per step), the numeric rasters
//! and outlines ([`super::rasters`], [`super::outlines`]), `study.json`, with a threshold
//! `pass.png`, and optional per-step plans and a GIF of the day. Every plan is framed by
//! [`super::annotate`]. Each file is written through a temporary file.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde_json::json;

pub use super::colours::{hours_colour, time_colour};

use super::annotate::{annotate, PlanLabels};
use super::outlines::{outlines_geojson, outlines_svg};
use super::rasters::{ascii_grid, hours_csv, hours_exr, pass_fraction, surface_mean, AnalysisArea};
use super::shadow_profile::{
    HoursMetric, Profile, ProfileStep, SURFACE_GROUND, SURFACE_MODEL, SURFACE_NONE,
};
use super::surface_output::{write_surfaces, FacadeSummary, PointResult, SurfaceResults};
use crate::io::{create_dir, write_atomic, WriteError};
use crate::render::legend::with_legend_panel;
use crate::render::output::write_image;

const BACKGROUND: [u8; 3] = [255, 255, 255];
const GROUND: [u8; 3] = [246, 246, 243];
const BUILDING: [u8; 3] = [128, 128, 132];
const BUILDING_SHADED: [u8; 3] = [88, 88, 94];
const OUTLINE: [u8; 3] = [20, 20, 20];

/// The top of the hours scale: the whole period's length.
pub fn hours_scale(profile: &Profile) -> f32 {
    (profile.period_h as f32).max(1e-3)
}

fn blend(a: [u8; 3], b: [u8; 3], alpha: f32) -> [u8; 3] {
    [0, 1, 2].map(|i| (a[i] as f32 * (1.0 - alpha) + b[i] as f32 * alpha).round() as u8)
}

fn to_image(n: u32, rgb: &[[u8; 3]]) -> image::RgbaImage {
    image::RgbaImage::from_fn(n, n, |x, y| {
        let [r, g, b] = rgb[(y * n + x) as usize];
        image::Rgba([r, g, b, 255])
    })
}

/// Pixels of `inside` with a 4-neighbour outside it (or on the image border) in a
/// `w` × `h` image.
fn boundary((w, h): (u32, u32), inside: impl Fn(usize) -> bool) -> Vec<bool> {
    let (w, h) = (w as usize, h as usize);
    (0..w * h)
        .map(|k| {
            if !inside(k) {
                return false;
            }
            let (x, y) = (k % w, k / w);
            let out = |dx: i64, dy: i64| {
                let (xx, yy) = (x as i64 + dx, y as i64 + dy);
                xx < 0
                    || yy < 0
                    || xx >= w as i64
                    || yy >= h as i64
                    || !inside(yy as usize * w + xx as usize)
            };
            out(-1, 0) || out(1, 0) || out(0, -1) || out(0, 1)
        })
        .collect()
}

/// The base plan: ground, background and the building (its roof darker where a step
/// shadows it, when `step` is given) with its outline.
fn base_plan(profile: &Profile, step: Option<&ProfileStep>) -> Vec<[u8; 3]> {
    let footprint = boundary((profile.resolution, profile.resolution), |k| {
        profile.surface[k] == SURFACE_MODEL
    });
    profile
        .surface
        .iter()
        .enumerate()
        .map(|(k, &s)| match s {
            SURFACE_NONE => BACKGROUND,
            SURFACE_GROUND => GROUND,
            _ if footprint[k] => OUTLINE,
            _ if step.is_some_and(|st| st.in_shadow(k)) => BUILDING_SHADED,
            _ => BUILDING,
        })
        .collect()
}

fn hhmm(step: &ProfileStep) -> String {
    step.time.format("%H:%M").to_string()
}

/// `profile.png`: every step's ground shadow as a light wash and an outline in its time
/// colour, the building on top, a time legend.
pub fn profile_image(profile: &Profile) -> image::RgbaImage {
    let n = profile.resolution;
    let mut rgb = base_plan(profile, None);
    let count = profile.steps.len();
    let t_of = |k: usize| {
        if count > 1 {
            k as f32 / (count - 1) as f32
        } else {
            0.5
        }
    };
    let ground_shadow =
        |s: &ProfileStep, k: usize| s.in_shadow(k) && profile.surface[k] == SURFACE_GROUND;
    for (i, s) in profile.steps.iter().enumerate() {
        let c = time_colour(t_of(i));
        for (k, px) in rgb.iter_mut().enumerate() {
            if ground_shadow(s, k) {
                *px = blend(*px, c, 0.08);
            }
        }
    }
    for (i, s) in profile.steps.iter().enumerate() {
        let c = time_colour(t_of(i));
        let edge = boundary((n, n), |k| {
            s.in_shadow(k) || profile.surface[k] == SURFACE_MODEL
        });
        for (k, px) in rgb.iter_mut().enumerate() {
            if edge[k] && profile.surface[k] == SURFACE_GROUND {
                *px = c;
            }
        }
    }
    with_legend_panel(
        &to_image(n, &rgb),
        "time",
        &time_labels(profile),
        time_colour,
    )
}

fn time_labels(profile: &Profile) -> Vec<String> {
    let steps = &profile.steps;
    match steps.len() {
        0 => Vec::new(),
        1 => vec![hhmm(&steps[0])],
        len => (0..=4)
            .map(|q| hhmm(&steps[(q * (len - 1) + 2) / 4]))
            .collect(),
    }
}

/// `hours.png`: hours of `metric` per cell (the roof's too), the building outlined.
pub fn hours_image(profile: &Profile, metric: HoursMetric) -> image::RgbaImage {
    let n = profile.resolution;
    let hours = profile.hours(metric);
    let scale = hours_scale(profile);
    let footprint = boundary((n, n), |k| profile.surface[k] == SURFACE_MODEL);
    let rgb: Vec<[u8; 3]> = (0..(n * n) as usize)
        .map(|k| match profile.surface[k] {
            SURFACE_NONE => BACKGROUND,
            _ if footprint[k] => OUTLINE,
            _ => hours_colour(hours[k], scale),
        })
        .collect();
    with_hours_legend(&to_image(n, &rgb), metric, scale)
}

/// `image` with the legend of hours of `metric` from 0 to `scale` beside it.
pub(super) fn with_hours_legend(
    image: &image::RgbaImage,
    metric: HoursMetric,
    scale: f32,
) -> image::RgbaImage {
    let labels: Vec<String> = (0..=4)
        .map(|q| format!("{:.1} h", scale * q as f32 / 4.0))
        .collect();
    let title = match metric {
        HoursMetric::Sun => "sun",
        HoursMetric::Shadow => "in shadow",
    };
    with_legend_panel(image, title, &labels, |t| hours_colour(t, 1.0))
}

const PASS: [u8; 3] = [90, 180, 90];
const FAIL: [u8; 3] = [215, 80, 70];

/// `pass.png`: cells whose hours reach `threshold_h` green, the others red (ground, and
/// roofs inside their outline); the analysis areas outlined in blue.
pub fn pass_image(
    profile: &Profile,
    hours: &[f32],
    threshold_h: f64,
    areas: &[AnalysisArea],
) -> image::RgbaImage {
    let n = profile.resolution;
    let mut rgb = base_plan(profile, None);
    for (k, px) in rgb.iter_mut().enumerate() {
        if profile.surface[k] == SURFACE_GROUND
            || (profile.surface[k] == SURFACE_MODEL && *px != OUTLINE)
        {
            *px = if hours[k] as f64 >= threshold_h - 1e-4 {
                PASS
            } else {
                FAIL
            };
        }
    }
    for area in areas {
        let inside: Vec<bool> = (0..(n * n) as usize)
            .map(|k| {
                let (px, py) = (k as u32 % n, k as u32 / n);
                area.contains(profile.pixel_center(px, py) + profile.origin)
            })
            .collect();
        for (k, edge) in boundary((n, n), |k| inside[k]).into_iter().enumerate() {
            if edge {
                rgb[k] = [20, 60, 200];
            }
        }
    }
    let labels = vec![format!("< {threshold_h} h"), format!("≥ {threshold_h} h")];
    with_legend_panel(&to_image(n, &rgb), "hours", &labels, |t| {
        if t < 0.5 {
            FAIL
        } else {
            PASS
        }
    })
}

/// One step's plan: its shadow in grey on the ground (no legend: the frame says the time).
pub fn step_image(profile: &Profile, step: &ProfileStep) -> image::RgbaImage {
    let mut rgb = base_plan(profile, Some(step));
    for (k, px) in rgb.iter_mut().enumerate() {
        if profile.surface[k] == SURFACE_GROUND && step.in_shadow(k) {
            *px = [150, 150, 160];
        }
    }
    to_image(profile.resolution, &rgb)
}

/// `profile.csv`.
pub fn profile_csv(profile: &Profile) -> String {
    let mut out = String::from(
        "time,azimuth_deg,elevation_deg,shadow_area_m2,shadow_area_with_footprint_m2,reaches_edge,weight_h\n",
    );
    for s in &profile.steps {
        let _ = writeln!(
            out,
            "{},{:.4},{:.4},{:.3},{:.3},{},{:.6}",
            s.time.to_rfc3339_opts(chrono::SecondsFormat::Secs, true),
            s.azimuth_deg,
            s.elevation_deg,
            s.shadow_area_m2,
            s.shadow_area_with_footprint_m2,
            s.reaches_edge,
            s.weight_h
        );
    }
    out
}

/// What a study writes besides the plans every profile has.
#[derive(Debug, Clone, Default)]
pub struct StudyOutput {
    /// What the hours count.
    pub metric: HoursMetric,
    /// Hours a ground cell needs to pass (`pass.png`, the passing fractions).
    pub threshold_h: Option<f64>,
    /// Areas whose passing fraction is reported.
    pub areas: Vec<AnalysisArea>,
    /// The frame's title (what and where) and subtitle (date, period, zone).
    pub labels: PlanLabels,
    /// Also write one plan per step into `steps/HHMM.png`.
    pub step_images: bool,
    /// Also write the day's animation (one frame per step) to this GIF.
    pub gif: Option<PathBuf>,
    /// Sun hours on the model's facades and at window points, when asked for.
    pub surfaces: Option<SurfaceResults>,
}

/// The numbers of one study (one date), as `study.json` holds them.
#[derive(Debug, Clone, serde::Serialize)]
pub struct StudySummary {
    /// The day (YYYY-MM-DD).
    pub date: String,
    /// `"sun"` or `"shadow"`.
    pub metric: &'static str,
    /// The threshold, hours.
    pub threshold_h: Option<f64>,
    /// `to` − `from`, hours.
    pub period_h: f64,
    /// The part of the period with the sun up, hours.
    pub sun_up_h: f64,
    /// The fraction of the plan's cells that pass (every cell that sees the ground or the
    /// model from above).
    pub pass_fraction: Option<f64>,
    /// Each analysis area's passing fraction.
    pub areas: Vec<AreaResult>,
    /// The mean hours over the plan's cells that see a surface from above.
    pub mean_h: f64,
    /// The plan's side, metres, and its cell size.
    pub extent_m: f64,
    /// The side of a cell, metres.
    pub cell_m: f64,
    /// The facades' hours (with `--facades`).
    pub facades: Vec<FacadeSummary>,
    /// The window points' hours and EN 17037 levels (with `--points`).
    pub points: Vec<PointResult>,
}

/// One analysis area's result.
#[derive(Debug, Clone, serde::Serialize)]
pub struct AreaResult {
    /// Its name.
    pub name: String,
    /// The fraction of its ground cells that pass (`None` when none lies in the plan).
    pub pass_fraction: Option<f64>,
}

/// The summary of `profile` under `out`'s metric, threshold and areas.
pub fn summary(profile: &Profile, out: &StudyOutput) -> StudySummary {
    summary_of(profile, out, &profile.hours(out.metric))
}

/// [`summary`] from the hours already counted under `out`'s metric.
fn summary_of(profile: &Profile, out: &StudyOutput, hours: &[f32]) -> StudySummary {
    let fraction = |area| {
        out.threshold_h
            .and_then(|t| pass_fraction(profile, hours, t, area))
    };
    StudySummary {
        date: profile
            .steps
            .first()
            .map(|s| s.time.date_naive().to_string())
            .unwrap_or_default(),
        metric: out.metric.name(),
        threshold_h: out.threshold_h,
        period_h: profile.period_h,
        sun_up_h: profile.sun_up_h,
        pass_fraction: fraction(None),
        areas: out
            .areas
            .iter()
            .map(|a| AreaResult {
                name: a.name.clone(),
                pass_fraction: fraction(Some(a)),
            })
            .collect(),
        mean_h: surface_mean(profile, hours),
        extent_m: profile.extent_m,
        cell_m: profile.extent_m / profile.resolution as f64,
        facades: Vec::new(),
        points: Vec::new(),
    }
}

fn step_labels(step: &ProfileStep, labels: &PlanLabels) -> PlanLabels {
    PlanLabels {
        title: format!("Shadows — {}", labels.title),
        subtitle: format!(
            "{} — sun azimuth {:.1}°, elevation {:.1}°",
            step.time.format("%Y-%m-%d %H:%M (UTC%:z)"),
            step.azimuth_deg,
            step.elevation_deg
        ),
        north_offset_deg: labels.north_offset_deg,
    }
}

/// One step's framed plan (the step images and the GIF's frames).
pub fn step_frame(profile: &Profile, step: &ProfileStep, labels: &PlanLabels) -> image::RgbaImage {
    annotate(
        profile,
        &step_image(profile, step),
        &step_labels(step, labels),
    )
}

/// Writes the study of `profile` into `dir` (created if missing): `profile.png`,
/// `hours.png`, `profile.csv`, `hours.asc`, `hours.csv`, `hours.exr`,
/// `outlines.geojson`, `outlines.svg`, `study.json`; with a threshold `pass.png`; with
/// `step_images` `steps/HHMM.png`; with `gif` the animation. Returns the summary.
pub fn write_study(
    profile: &Profile,
    dir: &Path,
    out: &StudyOutput,
) -> Result<StudySummary, WriteError> {
    create_dir(dir)?;
    let labels = &out.labels;
    let framed = |body: &image::RgbaImage, what: &str| {
        let mut l = labels.clone();
        l.title = format!("{what} — {}", labels.title);
        annotate(profile, body, &l)
    };
    write_image(
        &dir.join("profile.png"),
        &framed(&profile_image(profile), "Shadow profile"),
    )?;
    let what = match out.metric {
        HoursMetric::Sun => "Hours of sun",
        HoursMetric::Shadow => "Hours in shadow",
    };
    write_image(
        &dir.join("hours.png"),
        &framed(&hours_image(profile, out.metric), what),
    )?;
    write_atomic(&dir.join("profile.csv"), profile_csv(profile).as_bytes())?;
    let hours = profile.hours(out.metric);
    write_atomic(
        &dir.join("hours.asc"),
        ascii_grid(profile, &hours).as_bytes(),
    )?;
    write_atomic(
        &dir.join("hours.csv"),
        hours_csv(profile, &hours).as_bytes(),
    )?;
    write_image(&dir.join("hours.exr"), &hours_exr(profile, &hours))?;
    let geojson = dir.join("outlines.geojson");
    let text = outlines_geojson(profile).map_err(|e| WriteError::encode(&geojson, e))?;
    write_atomic(&geojson, text.as_bytes())?;
    let svg = outlines_svg(
        profile,
        &format!("Shadow outlines — {}, {}", labels.title, labels.subtitle),
        labels.north_offset_deg,
    )
    .map_err(|e| WriteError::encode(&dir.join("outlines.svg"), e))?;
    write_atomic(&dir.join("outlines.svg"), svg.as_bytes())?;
    if let Some(t) = out.threshold_h {
        write_image(
            &dir.join("pass.png"),
            &framed(
                &pass_image(profile, &hours, t, &out.areas),
                &format!("{what} ≥ {t} h"),
            ),
        )?;
    }
    let mut summary = summary_of(profile, out, &hours);
    if let Some(results) = &out.surfaces {
        (summary.facades, summary.points) = write_surfaces(
            dir,
            results,
            labels,
            profile.origin,
            profile.ground_z,
            hours_scale(profile),
        )?;
    }
    let study_json = dir.join("study.json");
    let text = serde_json::to_string_pretty(&json!(summary))
        .map_err(|e| WriteError::encode(&study_json, e))?;
    write_atomic(&study_json, text.as_bytes())?;
    if out.step_images {
        let steps = dir.join("steps");
        create_dir(&steps)?;
        for s in &profile.steps {
            let name = format!("{}.png", s.time.format("%H%M"));
            write_image(&steps.join(name), &step_frame(profile, s, labels))?;
        }
    }
    if let Some(path) = &out.gif {
        write_gif(profile, labels, path)?;
    }
    Ok(summary)
}

/// The day's animation: one framed plan per step, half a second each, looping; frames
/// wider than 720 pixels are scaled down.
pub fn write_gif(profile: &Profile, labels: &PlanLabels, path: &Path) -> Result<(), WriteError> {
    use image::codecs::gif::{GifEncoder, Repeat};
    let mut bytes = Vec::new();
    {
        let mut encoder = GifEncoder::new_with_speed(&mut bytes, 20);
        encoder
            .set_repeat(Repeat::Infinite)
            .map_err(|e| WriteError::encode(path, e))?;
        for s in &profile.steps {
            let mut frame = step_frame(profile, s, labels);
            if frame.width() > 720 {
                let h = frame.height() * 720 / frame.width();
                frame =
                    image::imageops::resize(&frame, 720, h, image::imageops::FilterType::Triangle);
            }
            encoder
                .encode_frame(image::Frame::from_parts(
                    frame,
                    0,
                    0,
                    image::Delay::from_numer_denom_ms(500, 1),
                ))
                .map_err(|e| WriteError::encode(path, e))?;
        }
    }
    write_atomic(path, &bytes)
}
