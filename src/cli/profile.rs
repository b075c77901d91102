//! `goniolight profile`: sun-path shadow profiles of a model over a period.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use chrono::{NaiveDate, NaiveTime};
use clap::Args;

use super::CliError;
use crate::geometry::obj::read_obj;
use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::scene::UpAxis;
use crate::shadow::SilhouetteMethod;
use crate::study::output::write_profile;
use crate::study::profile::{compute, Profile, ProfileSpec};
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
    /// The day, YYYY-MM-DD.
    #[arg(long)]
    pub date: NaiveDate,
    /// First step, local time HH:MM.
    #[arg(long, value_parser = parse_hhmm)]
    pub from: NaiveTime,
    /// Last step, local time HH:MM.
    #[arg(long, value_parser = parse_hhmm)]
    pub to: NaiveTime,
    /// Minutes between steps (at least 1).
    #[arg(long)]
    pub step: u32,
    /// Time zone: an IANA name (Europe/Vienna) or an offset (+02:00); default UTC.
    #[arg(long, default_value = "UTC")]
    pub tz: String,
    /// Angle from the model's +Y axis clockwise (seen from above) to true north, degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub north_offset: f64,
    /// Side of the square plan, metres (default: enough for the lowest sun, at most
    /// twenty times the model's height on each side).
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
    /// Also write one plan per step into DIR/steps/HHMM.png.
    #[arg(long)]
    pub step_images: bool,
    /// The output folder (profile.png, hours.png, profile.csv).
    #[arg(long)]
    pub out: PathBuf,
}

fn parse_hhmm(s: &str) -> Result<NaiveTime, String> {
    NaiveTime::parse_from_str(s, "%H:%M").map_err(|_| format!("{s:?} is not a time HH:MM"))
}

/// Reads an OBJ model and turns it to the world's +Z up.
pub fn load_model(path: &Path, up: UpAxis) -> Result<Mesh, CliError> {
    let mut mesh = read_obj(path)?;
    if up == UpAxis::Y {
        for p in &mut mesh.positions {
            *p = glam::DVec3::new(p.x, -p.z, p.y);
        }
    }
    let total = mesh.triangles.len();
    let dropped = mesh.remove_degenerate();
    if dropped > 0 {
        eprintln!(
            "warning: {}: {dropped} of its {total} triangles have no area and were dropped",
            path.display()
        );
    }
    mesh.validate(&path.display().to_string())?;
    Ok(mesh)
}

/// Runs `profile`.
pub fn run(a: ProfileArgs) -> Result<(), CliError> {
    let site = Site::new(a.lat, a.lon, 0.0)?;
    let zone = Zone::parse(&a.tz)?;
    let model = load_model(&a.model, a.up)?;
    let spec = ProfileSpec {
        site,
        zone,
        date: a.date,
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
    };
    // Check the period before starting the GPU.
    let steps = spec.local_times()?.len();
    let gpu = Gpu::shared().map_err(CliError::failure)?;
    let bar = indicatif::ProgressBar::new(steps as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} steps, {eta} left")
            .map_err(|e| CliError::failure(anyhow!(e)))?,
    );
    bar.set_message("shadow profile");
    // Ctrl-C stops between steps; nothing is written for an unfinished profile.
    let cancel = super::interrupt_flag();
    eprintln!(
        "{}: {steps} steps (Ctrl-C stops and writes nothing)",
        a.model.display()
    );
    let t = std::time::Instant::now();
    let profile = compute(
        &gpu,
        &model,
        &spec,
        |done, _| bar.set_position(done as u64),
        &cancel,
    );
    bar.finish_and_clear();
    let profile = profile?;
    report(&a, &profile, t.elapsed().as_secs_f64());
    write_profile(&profile, &a.out, a.step_images).map_err(CliError::failure)?;
    Ok(())
}

fn report(a: &ProfileArgs, profile: &Profile, seconds: f64) {
    if !profile.skipped.is_empty() {
        let times: Vec<String> = profile
            .skipped
            .iter()
            .map(|t| t.format("%H:%M").to_string())
            .collect();
        eprintln!(
            "warning: the sun is below the horizon at {} step(s), skipped: {}",
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
            "warning: the shadow reaches the edge of the {:.0} m plan at {} (its area is cut; use a larger --extent): {}",
            profile.extent_m,
            cut.len(),
            cut.join(" ")
        );
    }
    let n = profile.steps.len().max(1) as f64;
    println!(
        "{}: {} steps, plan {:.1} m at {} px ({:.3} m/px), footprint {:.1} m²; {:.2} s ({:.1} ms/step: silhouettes {:.1} ms, shadow volumes {:.1} ms) → {}",
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

/// Runs `bench profile`: the same profile with brute-force and hextree silhouettes.
pub fn run_bench(as_json: bool, resolution: u32, step: u32, floors: u32) -> Result<(), CliError> {
    if !(1..=40).contains(&floors) {
        return Err(CliError::input(anyhow!(
            "--floors {floors} is not in 1..=40"
        )));
    }
    let gpu = Gpu::shared().map_err(CliError::failure)?;
    eprintln!("GPU: {}", gpu.describe());
    let rows = crate::bench::profile::run(&gpu, resolution, step, floors)?;
    if as_json {
        println!("{}", serde_json::json!({ "rows": rows }));
        return Ok(());
    }
    println!(
        "shadow profile: {} triangles, {} steps, {resolution}² plan",
        rows.first().map_or(0, |r| r.triangles),
        rows.first().map_or(0, |r| r.steps)
    );
    println!(
        "| silhouettes | total s | ms/step | silhouette ms/step | volumes + read-back ms/step |"
    );
    println!("|---|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {:.2} | {:.1} | {:.2} | {:.1} |",
            r.method, r.total_s, r.per_step_ms, r.silhouette_ms_per_step, r.render_ms_per_step
        );
    }
    if let [brute, hex] = rows.as_slice() {
        println!(
            "hextree / brute force: total {:.2}×, silhouettes {:.2}× faster",
            brute.total_s / hex.total_s,
            brute.silhouette_ms_per_step / hex.silhouette_ms_per_step.max(1e-12)
        );
    }
    Ok(())
}
