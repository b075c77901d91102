//! `bench profile`: one sun-path shadow profile of a generated building (and, when asked,
//! of the real models), with brute-force and hextree silhouettes, and with the volumes
//! ending at the ground or all of one length, side by side.

use std::sync::atomic::AtomicBool;

use chrono::{NaiveDate, NaiveTime};
use serde::Serialize;

use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::shadow::SilhouetteMethod;
use crate::study::shadow_profile::{compute, ProfileError, ProfileSpec, VolumeEnds};
use crate::sun::{Site, SunOptions, Zone};

/// One silhouette method's timing on one model.
#[derive(Debug, Clone, Serialize)]
pub struct ProfileBenchRow {
    /// The model.
    pub model: String,
    /// "brute force" or "hextree".
    pub method: &'static str,
    /// Where the volumes end: "ground" (the default) or "one length" (the first release).
    pub volume_ends: &'static str,
    /// Triangles of the building.
    pub triangles: usize,
    /// Profile steps (sun positions).
    pub steps: usize,
    /// Side of the plan, pixels.
    pub resolution: u32,
    /// Whole profile, seconds.
    pub total_s: f64,
    /// Per step, milliseconds.
    pub per_step_ms: f64,
    /// Silhouette search per step, milliseconds.
    pub silhouette_ms_per_step: f64,
    /// Volume passes and read-back per step, milliseconds.
    pub render_ms_per_step: f64,
}

/// The generated benchmark building: 25 × 25 bays, `floors` storeys.
pub fn generated_building(floors: u32) -> (String, Mesh) {
    (
        format!("generated building, {floors} storeys"),
        crate::geometry::generate::building(25, 25, floors),
    )
}

/// Profiles each of `models` (world frame, metres, +Z up, near the origin) in Vienna on
/// the 2026 equinox, 08:00–16:00 every `step` minutes: a warm-up run (pipelines, hextree
/// build), then each method.
pub fn run(
    gpu: &Gpu,
    models: &[(String, Mesh)],
    resolution: u32,
    step: u32,
) -> Result<Vec<ProfileBenchRow>, ProfileError> {
    let mut rows = Vec::new();
    for (name, model) in models {
        rows.extend(run_model(gpu, name, model, resolution, step)?);
    }
    Ok(rows)
}

fn run_model(
    gpu: &Gpu,
    name: &str,
    model: &Mesh,
    resolution: u32,
    step: u32,
) -> Result<Vec<ProfileBenchRow>, ProfileError> {
    let hm = |h| NaiveTime::from_hms_opt(h, 0, 0).unwrap_or_default();
    let input = |e: crate::sun::SunError| ProfileError::Input(e.to_string());
    let mut spec = ProfileSpec {
        site: Site::new(48.21, 16.37, 0.0).map_err(input)?,
        zone: Zone::parse("Europe/Vienna").map_err(input)?,
        date: NaiveDate::from_ymd_opt(2026, 3, 21).unwrap_or_default(),
        from: hm(8),
        to: hm(16),
        step_minutes: step,
        sun: SunOptions::default(),
        extent_m: None,
        resolution,
        silhouette: SilhouetteMethod::Brute,
        non_casters: Default::default(),
        volume_ends: Default::default(),
    };
    let cancel = AtomicBool::new(false);
    let mut rows = Vec::new();
    for (label, method, ends) in [
        ("warm-up", SilhouetteMethod::Hextree, VolumeEnds::Ground),
        ("brute force", SilhouetteMethod::Brute, VolumeEnds::Ground),
        ("hextree", SilhouetteMethod::Hextree, VolumeEnds::Ground),
        ("hextree", SilhouetteMethod::Hextree, VolumeEnds::OneLength),
    ] {
        spec.silhouette = method;
        spec.volume_ends = ends;
        let t = std::time::Instant::now();
        let p = compute(gpu, model, &spec, |_, _| {}, &cancel)?;
        let total_s = t.elapsed().as_secs_f64();
        let n = p.steps.len().max(1) as f64;
        if label != "warm-up" {
            rows.push(ProfileBenchRow {
                model: name.to_string(),
                method: label,
                volume_ends: match ends {
                    VolumeEnds::Ground => "ground",
                    VolumeEnds::OneLength => "one length",
                },
                triangles: model.triangles.len(),
                steps: p.steps.len(),
                resolution,
                total_s,
                per_step_ms: 1000.0 * total_s / n,
                silhouette_ms_per_step: 1000.0 * p.timing.silhouette_s / n,
                render_ms_per_step: 1000.0 * p.timing.render_s / n,
            });
        }
    }
    Ok(rows)
}

/// The report of `bench profile`: each model's rows, then per model the hextree's and the
/// ground-ended volumes' speed-ups.
pub fn report(rows: &[ProfileBenchRow], resolution: u32) -> super::report::BenchReport {
    use super::report::{BenchReport, Table};
    let mut r = BenchReport::new(serde_json::json!({ "rows": rows }));
    r.line(format!(
        "shadow profile: {} steps, {resolution}² plan",
        rows.first().map_or(0, |r| r.steps)
    ));
    let mut t = Table::new(&[
        "model",
        "triangles",
        "silhouettes",
        "volumes end",
        "total s",
        "ms/step",
        "silhouette ms/step",
        "volumes + read-back ms/step",
    ])
    .numbers_from(4);
    for row in rows {
        t.row(vec![
            row.model.clone(),
            row.triangles.to_string(),
            row.method.to_string(),
            row.volume_ends.to_string(),
            format!("{:.2}", row.total_s),
            format!("{:.1}", row.per_step_ms),
            format!("{:.2}", row.silhouette_ms_per_step),
            format!("{:.1}", row.render_ms_per_step),
        ]);
    }
    r.table(t);
    for model in rows.chunks(3) {
        if let [brute, hex, one_length] = model {
            r.line(format!(
                "{}: hextree / brute force: total {:.2}×, silhouettes {:.2}× faster; volumes to the ground / of one length: volumes {:.2}× faster",
                brute.model,
                brute.total_s / hex.total_s,
                brute.silhouette_ms_per_step / hex.silhouette_ms_per_step.max(1e-12),
                one_length.render_ms_per_step / hex.render_ms_per_step.max(1e-12)
            ));
        }
    }
    r
}
