//! The files of a shadow profile: `profile.png` (every step's shadow overlaid, coloured
//! by time, with the building and a legend), `hours.png` (hours in shadow per ground cell
//! on a colour scale with a legend), `profile.csv` (one row per step) and optional
//! per-step plans. Each is written through a temporary file.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Context;

use super::profile::{Profile, ProfileStep, SURFACE_GROUND, SURFACE_MODEL, SURFACE_NONE};
use crate::io::write_atomic;
use crate::render::legend::with_legend_panel;
use crate::render::output::write_image;
use crate::render::tonemap::{false_colour, linear_to_srgb};

const BACKGROUND: [u8; 3] = [255, 255, 255];
const GROUND: [u8; 3] = [246, 246, 243];
const BUILDING: [u8; 3] = [128, 128, 132];
const BUILDING_SHADED: [u8; 3] = [88, 88, 94];
const OUTLINE: [u8; 3] = [20, 20, 20];

/// The colour of time `t` in 0..1 (early = blue, noon = green, late = red).
pub fn time_colour(t: f32) -> [u8; 3] {
    let hue = 240.0 * (1.0 - t.clamp(0.0, 1.0));
    let c = hue / 60.0;
    let x = 1.0 - (c % 2.0 - 1.0).abs();
    let (r, g, b) = match c as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        _ => (x, 0.0, 1.0),
    };
    [r, g, b].map(|v: f32| (v * 220.0) as u8)
}

/// The colour of `hours` in shadow on a scale whose top is `scale_hours`.
pub fn hours_colour(hours: f32, scale_hours: f32) -> [u8; 3] {
    let c = false_colour(hours / scale_hours.max(1e-6));
    [
        linear_to_srgb(c.x),
        linear_to_srgb(c.y),
        linear_to_srgb(c.z),
    ]
}

/// The top of the hours scale: the whole period's length.
pub fn hours_scale(profile: &Profile) -> f32 {
    ((profile.steps.len() + profile.skipped.len()) as f32 * profile.step_minutes as f32 / 60.0)
        .max(1e-3)
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

/// Pixels of `inside` with a 4-neighbour outside it (or on the image border).
fn boundary(n: u32, inside: impl Fn(usize) -> bool) -> Vec<bool> {
    let n = n as usize;
    (0..n * n)
        .map(|k| {
            if !inside(k) {
                return false;
            }
            let (x, y) = (k % n, k / n);
            let out = |dx: i64, dy: i64| {
                let (xx, yy) = (x as i64 + dx, y as i64 + dy);
                xx < 0
                    || yy < 0
                    || xx >= n as i64
                    || yy >= n as i64
                    || !inside(yy as usize * n + xx as usize)
            };
            out(-1, 0) || out(1, 0) || out(0, -1) || out(0, 1)
        })
        .collect()
}

/// The base plan: ground, background and the building (its roof darker where a step
/// shadows it, when `step` is given) with its outline.
fn base_plan(profile: &Profile, step: Option<&ProfileStep>) -> Vec<[u8; 3]> {
    let footprint = boundary(profile.resolution, |k| profile.surface[k] == SURFACE_MODEL);
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
        let edge = boundary(n, |k| s.in_shadow(k) || profile.surface[k] == SURFACE_MODEL);
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

/// `hours.png`: hours in shadow per cell (the roof's too), the building outlined.
pub fn hours_image(profile: &Profile) -> image::RgbaImage {
    let n = profile.resolution;
    let hours = profile.hours_in_shadow();
    let scale = hours_scale(profile);
    let footprint = boundary(n, |k| profile.surface[k] == SURFACE_MODEL);
    let rgb: Vec<[u8; 3]> = (0..(n * n) as usize)
        .map(|k| match profile.surface[k] {
            SURFACE_NONE => BACKGROUND,
            _ if footprint[k] => OUTLINE,
            _ => hours_colour(hours[k], scale),
        })
        .collect();
    let labels: Vec<String> = (0..=4)
        .map(|q| format!("{:.1} h", scale * q as f32 / 4.0))
        .collect();
    with_legend_panel(&to_image(n, &rgb), "in shadow", &labels, |t| {
        hours_colour(t, 1.0)
    })
}

/// One step's plan: its shadow in grey on the ground.
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
        "time,azimuth_deg,elevation_deg,shadow_area_m2,shadow_area_with_footprint_m2,reaches_edge\n",
    );
    for s in &profile.steps {
        let _ = writeln!(
            out,
            "{},{:.4},{:.4},{:.3},{:.3},{}",
            s.time.to_rfc3339_opts(chrono::SecondsFormat::Secs, true),
            s.azimuth_deg,
            s.elevation_deg,
            s.shadow_area_m2,
            s.shadow_area_with_footprint_m2,
            s.reaches_edge
        );
    }
    out
}

/// Writes `profile.png`, `hours.png`, `profile.csv` and, with `step_images`,
/// `steps/HHMM.png` into `dir` (created if missing).
pub fn write_profile(profile: &Profile, dir: &Path, step_images: bool) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    write_image(&dir.join("profile.png"), &profile_image(profile))?;
    write_image(&dir.join("hours.png"), &hours_image(profile))?;
    write_atomic(&dir.join("profile.csv"), profile_csv(profile).as_bytes())?;
    if step_images {
        let steps = dir.join("steps");
        std::fs::create_dir_all(&steps).with_context(|| format!("creating {}", steps.display()))?;
        for s in &profile.steps {
            let name = format!("{}.png", s.time.format("%H%M"));
            write_image(&steps.join(name), &step_image(profile, s))?;
        }
    }
    Ok(())
}
