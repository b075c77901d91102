//! What a solve tells a person, as lines of text: the preparation (stages' times,
//! triangles, peak memory), the set-up before shooting, the result after it, adaptive
//! subdivision and the export's bake. The command prints them with the scene's name in
//! front; the figures are worked out here, never by a front end.

use super::{Prepared, Session, Solution};
use crate::radiosity::bake::BakePlan;
use crate::radiosity::elements::Elements;
use crate::radiosity::shooters::Hierarchy;
use crate::radiosity::solve::StopReason;
use crate::render::lightmap::LightMap;
use crate::scene::DisplayIndirect;

/// `, peak memory N MB` (with `separator` in front), or nothing where the system does not
/// say.
fn peak_memory(separator: &str) -> String {
    crate::io::peak_memory_mb().map_or(String::new(), |mb| {
        format!("{separator}peak memory {mb} MB")
    })
}

impl Prepared {
    /// Adaptive subdivision's result (when asked for): elements by size and the CPU time
    /// of the splits.
    pub fn adaptive_line(&self) -> Option<String> {
        let rscene = self.scene();
        (self.options().adaptive > 0).then(|| {
            format!(
                "{} (the splits decided in {:.2} s of CPU)",
                adaptive_summary(&rscene.elements),
                rscene.subdivision_seconds
            )
        })
    }

    /// The preparation's line: its stages' times — `load_s` to load the scene,
    /// `prepared_s` from the command's start to the end of the preparation — the
    /// triangles and the peak memory.
    pub fn summary(&self, load_s: f64, prepared_s: f64) -> String {
        let rscene = self.scene();
        format!(
            "prepared in {prepared_s:.2} s — load {load_s:.2} s, {}elements and atlas {:.2} s, {}luminaires' direct light {:.2} s; {} triangles{}",
            match self.options().hierarchy {
                Hierarchy::None => String::new(),
                Hierarchy::Clusters => format!("face clusters {:.2} s, ", rscene.clustering_seconds),
            },
            self.times.elements - rscene.clustering_seconds - rscene.receiving_seconds,
            if rscene.receiving_normals.is_empty() {
                String::new()
            } else {
                format!("receiving normals {:.2} s, ", rscene.receiving_seconds)
            },
            self.times.direct_light,
            self.triangle_count(),
            peak_memory(", "),
        )
    }
}

impl Session<'_> {
    /// The lines before shooting: what a view-driven solve's camera sees, then elements,
    /// charts, patches, atlas, shooters and the visibility maps.
    pub fn shooting_summary(&self) -> Vec<String> {
        let rscene = self.prepared().scene();
        let solver = self.solver();
        let mut lines = Vec::new();
        if let Some(d) = self.driven() {
            lines.push(format!(
                "the camera sees {} of {} elements; importance solved in {:.2} s",
                d.view.iter().filter(|&&w| w > 0.0).count(),
                rscene.elements.len(),
                d.importance_seconds
            ));
        }
        lines.push(format!(
            "{} elements in {} charts, {} patches, atlas {}×{}; {} shooters{}; visibility maps draw {} triangles ({} raster); shooting (Ctrl-C stops and writes the solution so far)",
            rscene.elements.len(),
            rscene.elements.charts.len(),
            rscene.elements.patches.len(),
            rscene.elements.atlas_width,
            rscene.elements.atlas_height,
            solver.shooters().len(),
            match self.prepared().options().hierarchy {
                Hierarchy::None => " (one per triangle: `hierarchy` none)".to_string(),
                Hierarchy::Clusters => {
                    let tree = &rscene.planar_clusters().tree;
                    format!(" of {} face clusters", tree.nodes.len() - tree.order.len())
                }
            },
            solver.visibility_triangles(),
            solver.raster().name(),
        ));
        lines
    }

    /// How far along a progress bar of `steps` a solve at `convergence` (0 … 1) is: the
    /// bar's position, clamped to the bar.
    pub fn progress_position(convergence: f64, steps: u64) -> u64 {
        (convergence.clamp(0.0, 1.0) * steps as f64) as u64
    }

    /// The progress line of the shooting: `12.34 % converged, 56 shots`.
    pub fn progress_line(convergence: f64, shots: usize) -> String {
        format!("{:.2} % converged, {shots} shots", 100.0 * convergence)
    }

    /// The lines after shooting (`prepared_s`: the preparation's seconds): the area of
    /// interest's stage (perspective-driven), then shots, convergence, why it stopped, the
    /// maps drawn and skipped, the receivers' share and the peak memory.
    pub fn solved_summary(&self, prepared_s: f64) -> Vec<String> {
        let solver = self.solver();
        let mut lines = Vec::new();
        if let Some((stage, stages)) = solver.area_stage() {
            lines.push(format!(
                "area of interest at stage {} of {stages}; {} charts hold their light back, {} wait, {} shots kept for them",
                stage + 1,
                solver.holding_charts(),
                solver.waiting_charts(),
                solver.missed_shots(),
            ));
        }
        let last = self.log().last().copied();
        let drawn = solver.stats.drawn + solver.stats.virtual_drawn;
        lines.push(format!(
            "{} shots, {:.2} % converged ({}) in {:.2} s (+{prepared_s:.2} s to prepare); {drawn} visibility maps drawn{}, {} cells skipped (no receiver takes light from them); receivers culled to {:.0} % of the elements per map{}",
            solver.stats.shots,
            100.0 * last.map_or(1.0, |p| p.convergence),
            self.stopped().unwrap_or(StopReason::Cancelled),
            last.map_or(0.0, |p| p.seconds),
            match solver.stats.virtual_drawn {
                0 => String::new(),
                n => format!(" ({n} of them cells' images through mirrors and glass)"),
            },
            solver.stats.skipped,
            100.0 * solver.receiver_share(),
            peak_memory("; "),
        ));
        lines
    }
}

impl Solution {
    /// What a light map solved to show `choice` holds, solved in `seconds`: the ambient
    /// estimate, or the radiosity solution's convergence and why it stopped.
    pub fn shown_summary(&self, choice: DisplayIndirect, seconds: f64) -> String {
        match choice {
            DisplayIndirect::Ambient => format!(
                "indirect light: ambient estimate from the luminaires' first bounce ({seconds:.1} s)"
            ),
            _ => format!(
                "indirect light: radiosity, {:.1} % converged ({}) in {seconds:.1} s, the ambient term for the rest",
                100.0 * self.convergence(),
                self.stop(),
            ),
        }
    }
}

/// What adaptive subdivision made: elements by size against one per texel.
pub fn adaptive_summary(el: &Elements) -> String {
    let (by_side, texels) = el.sizes();
    let sizes: Vec<String> = by_side
        .iter()
        .enumerate()
        .rev()
        .map(|(k, n)| format!("{n} of {0}×{0}", 1u32 << k))
        .collect();
    format!(
        "adaptive subdivision: {} elements ({} texels), split at the luminaires' shadow and beam edges: {}",
        el.len(),
        texels,
        sizes.join(", ")
    )
}

/// What the export's representation costs (Edström §5.3, §7.6): surfaces and triangles
/// light-mapped and vertex-lit, the triangles introduced against the budget, the light
/// map's size.
pub fn bake_summary(plan: &BakePlan, map: &LightMap) -> String {
    format!(
        "bake: {} surfaces ({} triangles) light-mapped, {} ({} triangles) vertex-lit with {} triangles introduced (budget {}): the exported mesh draws {:+.1} % triangles over the model; light map {}×{} texels",
        plan.surfaces[0],
        plan.triangles[0],
        plan.surfaces[1],
        plan.triangles[1],
        plan.introduced,
        plan.budget,
        100.0 * plan.overhead(),
        map.width,
        map.height,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_progress_line_gives_percent_and_shots() {
        assert_eq!(
            Session::progress_line(0.123456, 42),
            "12.35 % converged, 42 shots"
        );
    }
}
