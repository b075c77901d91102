//! `goniolight bench adaptive`: Wallner's Table 2.1 — uniform against adaptive elements,
//! with and without normal maps: triangles, elements, the preprocessing (elements and
//! atlas, the subdivision inside it), the solve to a convergence and its shots, side by
//! side in one run.

use std::sync::atomic::AtomicBool;

use crate::gpu::Gpu;
use crate::photometry::Interp;
use crate::radiosity::session::{Options, Prepared, Setup};
use crate::radiosity::shooters::Hierarchy;
use crate::radiosity::solve::StopAt;
use crate::scene::Scene;

/// One measured meshing.
#[derive(Debug, Clone, serde::Serialize)]
pub struct AdaptiveBenchRow {
    /// "uniform" or "adaptive".
    pub meshing: String,
    /// Whether the materials' normal maps were used.
    pub normal_maps: bool,
    /// Elements per metre where unsplit.
    pub texel_density: f64,
    /// Subdivision levels (0: uniform).
    pub levels: u32,
    /// Triangles (n_t).
    pub triangles: usize,
    /// Elements (n_e).
    pub elements: usize,
    /// Light-map texels covered by elements.
    pub texels: u64,
    /// Seconds to lay the elements and the atlas, the subdivision's tests included.
    pub elements_seconds: f64,
    /// CPU seconds of the subdivision's tests (summed over threads).
    pub subdivision_seconds: f64,
    /// Seconds for the receiving normals (normal maps, vertex normals).
    pub normals_seconds: f64,
    /// Seconds for the luminaires' direct light (on the GPU; their GPU scene built for
    /// it included).
    pub direct_seconds: f64,
    /// Seconds of shooting to the convergence asked for (or the limits).
    pub solve_seconds: f64,
    /// Shots (Wallner's iterations: a shooter's patches each).
    pub shots: usize,
    /// Convergence reached.
    pub convergence: f64,
}

/// One meshing to measure: texel density and subdivision levels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Meshing {
    /// Elements per metre where unsplit.
    pub texel_density: f64,
    /// Subdivision levels (0: uniform).
    pub levels: u32,
}

/// Solves `scene` once per meshing, with and without its normal maps when it has any,
/// to `stop`.
pub fn run(
    gpu: &Gpu,
    scene: &Scene,
    meshings: &[Meshing],
    level: u32,
    stop: &StopAt,
    mut progress: impl FnMut(&str),
) -> Result<Vec<AdaptiveBenchRow>, super::BenchError> {
    // With normal maps, the scene without them first (one copy, only then).
    let with_maps = scene.materials.iter().any(|m| m.normal_map.is_some());
    let flat = with_maps.then(|| {
        let mut flat = scene.clone();
        for m in &mut flat.materials {
            m.normal_map = None;
        }
        flat
    });
    let variants: Vec<(&Scene, bool)> = match &flat {
        Some(flat) => vec![(flat, false), (scene, true)],
        None => vec![(scene, false)],
    };
    let mut shadows = crate::render::ShadowSettings::default();
    let cancel = AtomicBool::new(false);
    let mut rows = Vec::new();
    for (variant, normal_maps) in variants {
        for m in meshings {
            progress(&format!(
                "{} at {} /m{}",
                if m.levels == 0 { "uniform" } else { "adaptive" },
                m.texel_density,
                if normal_maps { ", normal maps" } else { "" }
            ));
            let options = Options {
                converge: stop.converge,
                max_shots: stop.max_shots,
                time_limit: stop.time_budget.map(|d| d.as_secs_f64()),
                texel_density: m.texel_density,
                level,
                adaptive: m.levels,
                hierarchy: Hierarchy::Clusters,
                ..Options::default()
            };
            let setup = Setup {
                scene: variant,
                options: &options,
                interp: Interp::CatmullRom,
                shadows: &mut shadows,
                view: None,
            };
            let prepared = Prepared::new(gpu, setup, &cancel, &mut |_| {})?;
            let mut session = prepared.session(&mut |_| {})?;
            session.solve(&cancel, &mut |_| {})?;
            let rscene = prepared.scene();
            let log = session.log();
            let el = &rscene.elements;
            rows.push(AdaptiveBenchRow {
                meshing: if m.levels == 0 { "uniform" } else { "adaptive" }.into(),
                normal_maps,
                texel_density: m.texel_density,
                levels: m.levels,
                triangles: el.triangles.len(),
                elements: el.len(),
                texels: el.span.iter().map(|&s| u64::from(s) * u64::from(s)).sum(),
                elements_seconds: prepared.times.elements - rscene.receiving_seconds,
                subdivision_seconds: rscene.subdivision_seconds,
                normals_seconds: rscene.receiving_seconds,
                direct_seconds: prepared.times.direct_light,
                solve_seconds: log.last().map_or(0.0, |p| p.seconds),
                shots: session.solver().stats.shots,
                convergence: log.last().map_or(0.0, |p| p.convergence),
            });
        }
    }
    Ok(rows)
}

/// The report of `bench adaptive` on the scene at `scene` solved to `converge`.
pub fn report(
    rows: &[AdaptiveBenchRow],
    scene: &std::path::Path,
    converge: f64,
) -> super::report::BenchReport {
    use super::report::{BenchReport, Table};
    let mut r = BenchReport::new(serde_json::json!({ "scene": scene, "rows": rows }));
    r.line(format!(
        "Uniform vs adaptive elements (Wallner Table 2.1), {}, to {:.0} %",
        scene.display(),
        100.0 * converge
    ));
    let mut t = Table::new(&[
        "meshing",
        "normal maps",
        "elements /m",
        "n_t",
        "n_e",
        "texels",
        "elements s (subdivision incl.)",
        "subdivision CPU s",
        "normals s",
        "direct s",
        "solve s",
        "shots",
        "reached",
    ]);
    for row in rows {
        let levels = match row.levels {
            0 => String::new(),
            1 => " (1 level)".into(),
            n => format!(" ({n} levels)"),
        };
        t.row(vec![
            format!("{}{levels}", row.meshing),
            if row.normal_maps { "yes" } else { "no" }.into(),
            row.texel_density.to_string(),
            row.triangles.to_string(),
            row.elements.to_string(),
            row.texels.to_string(),
            format!("{:.2}", row.elements_seconds),
            format!("{:.2}", row.subdivision_seconds),
            format!("{:.2}", row.normals_seconds),
            format!("{:.2}", row.direct_seconds),
            format!("{:.2}", row.solve_seconds),
            row.shots.to_string(),
            format!("{:.1} %", 100.0 * row.convergence),
        ]);
    }
    r.table(t);
    r
}
