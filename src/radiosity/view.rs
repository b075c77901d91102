//! View-driven radiosity (Bozalina 2011 §4–5; Smits, Arvo and Salesin 1992): importance
//! emitted by the camera and carried through the scene like light, shooters chosen by
//! unshot power × importance, and receivers limited to an area of interest around the
//! view that widens as the view's light settles.
//!
//! Importance, derived for progressive shooting: the view measures Σᵢ Vᵢ Bᵢ, with Vᵢ the
//! share of the image element i covers (`vᵢ Aᵢ`, [`view_weights`]). Unshot radiosity ΔBⱼ
//! raises it, once shot and carried on, by ΔBⱼ Aⱼ Hⱼ, where Hⱼ = Σᵢ Fⱼᵢ uᵢ is the
//! irradiance j receives from the field u = ρ (v + H): a radiosity solution whose emission
//! is ρᵢ vᵢ. So the importance is solved by the radiosity solver itself (same visibility
//! maps, [`importance`]), read back as each element's received "illuminance", and a
//! shooter's weight is its elements' mean H ([`shooter_weights`]).

use glam::DVec3;
use rayon::prelude::*;

use super::gpu::{GpuSettings, GpuSolver};
use super::initial::InitialState;
use super::scene::{luminance, RadiosityScene};
use super::shooters::Shooters;
use super::solve::StopAt;
use super::{Ambient, SolverSettings};
use crate::gpu::GpuError;
use crate::scene::camera::{Camera, Projection};
use crate::shadow::IgnoredTriangles;

/// What drives the choice of shooters and receivers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Drive {
    /// Progressive refinement: the shooter with the most unshot power; every element
    /// receives (view-independent).
    #[default]
    Global,
    /// The shooter with the most unshot power × importance from the camera.
    Importance,
    /// Importance-driven shooters, and receivers limited to the area of interest (the
    /// view's frustum plus a margin, widened as the view's light settles); a receiver
    /// outside it holds back what it receives (one hidden from the eye that the view's
    /// importance does not reach: waits until the view is 99 % converged, and the shots it
    /// missed are shot at it) until it joins.
    Perspective,
}

impl Drive {
    /// The name as the command line spells it.
    pub fn name(self) -> &'static str {
        match self {
            Drive::Global => "global",
            Drive::Importance => "importance",
            Drive::Perspective => "perspective",
        }
    }
}

/// A share of the shooters' weights every shooter keeps: one no camera ray and no
/// importance reaches is still shot in the end, so the solution converges everywhere.
pub const WEIGHT_FLOOR: f64 = 1e-3;
/// How far the importance solve runs (its own convergence): it only ranks shooters.
/// Half is enough to rank them (at 80 % the eight-room benchmark spent 28–31 s of the
/// driven solves' 33–47 s on importance; at 50 %, 21 s, and the drives reach 5 % in view
/// as soon or sooner).
pub const IMPORTANCE_CONVERGE: f64 = 0.5;
/// The importance solve's cells carry up to this share of its initial power: a surface
/// the camera sees shoots its importance from a few cells. Cells of 4 × the light solve's
/// share (0.4 %) and of 25 % ranked the shooters alike (two furnished rooms, 21–23 shots
/// to 5 % in view either way; 25 %: 10 maps instead of 530), but at 25 % the cells lose
/// importance on its way, and the view's ambient term ([`view_ambient`]), which needs
/// H's magnitude, came out at half the missing light (furnished room after the first
/// shot: 22.6 against the light cells' 42.8; the image as shown within 5 % after
/// 6.6–6.8 s, global 4.5 s). At 5 % it is 41.8 and the image as shown is within 5 %
/// after 2.8 s, for 0.14 s of importance solve instead of 0.05 s (lavapipe;
/// docs/src/measurements/radiosity-view.md: "Why the driven drives' image as shown
/// lagged").
pub const IMPORTANCE_CELL_POWER: f64 = 0.05;
/// The importance solve's visibility maps have this many times fewer texels per side
/// (Bozalina keeps importance at half the radiosity's resolution).
pub const IMPORTANCE_MAP_DIVISOR: u32 = 4;
/// How much wider each stage of the area of interest is, degrees of half-angle.
pub const STAGE_STEP_DEG: f64 = 30.0;
/// A chart the eye does not see joins the area of interest with its widest cone (and holds
/// its light until then) when its mean importance is at least this share of the seen
/// charts': light it sends on reaches the view. The others wait for the last stage. In
/// the furnished room 112 of the 169 charts the eye does not see pass (the rest are
/// below 10⁻², 23 have none); in two such rooms side by side, none of the second room's.
pub const IMPORTANCE_REACHED: f64 = 1e-2;

/// The least share of a piece's unshot power the cells' oracle sizes its cells by, with a
/// view driving ([`cell_weights`]): cells at most 4 × the side global progressive
/// refinement gives them. The open office seen at a desk draws the same maps with 1/256
/// (its far walls and floor are one cell a piece either way).
pub const CELL_WEIGHT_FLOOR: f64 = 1.0 / 16.0;
/// The least share of the link error a receiver takes ([`receiver_weights`]): its reaches
/// at least an eighth of what they are for what the eye sees. The open office seen at a
/// desk draws 529 maps to 5 % in view with 1/16, 456 with 1/64, 453 with 1/256 and 450
/// with 1/1024 (its first shooters' cells are then sized by what the eye sees), so a lower
/// floor would only add error where the view needs little.
pub const RECEIVER_WEIGHT_FLOOR: f64 = 1.0 / 64.0;

/// The camera as the solver sees it: a perspective view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewPoint {
    /// Eye, metres.
    pub eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    /// tan of the half field of view, across and up.
    tan_half: (f64, f64),
}

impl ViewPoint {
    /// The view of `camera` with an image `aspect` (width / height) wide; `None` for an
    /// orthographic camera (it has no eye to drive from).
    pub fn new(camera: &Camera, aspect: f64) -> Option<ViewPoint> {
        let Projection::Perspective { fov_deg } = camera.projection else {
            return None;
        };
        let forward = (camera.look_at - camera.position).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let tan_y = (0.5 * fov_deg.to_radians()).tan();
        Some(ViewPoint {
            eye: camera.position,
            forward,
            right,
            up,
            tan_half: (tan_y * aspect, tan_y),
        })
    }

    /// The half-angle of the cone around the view direction that holds the image (to
    /// its corners), degrees.
    pub fn half_diagonal_deg(&self) -> f64 {
        self.tan_half.0.hypot(self.tan_half.1).atan().to_degrees()
    }

    /// Where `p` appears: (x, y) on the image plane at distance 1 (in the image when both
    /// are within `tan_half`), and its depth along the view; `None` behind the eye.
    fn image(&self, p: DVec3) -> Option<(f64, f64, f64)> {
        let d = p - self.eye;
        let z = d.dot(self.forward);
        (z > 0.0).then(|| (d.dot(self.right) / z, d.dot(self.up) / z, z))
    }

    /// Whether the eye sees the front of a surface at `p` facing `n`: nothing of `scene`
    /// in between.
    fn sees(&self, scene: &RadiosityScene, p: DVec3, n: DVec3, eps: f64) -> bool {
        let to_eye = self.eye - p;
        let distance = to_eye.length();
        if distance <= 0.0 || n.dot(to_eye) <= 0.0 {
            return false;
        }
        if distance <= 2.0 * eps {
            return true;
        }
        let dir = to_eye / distance;
        let none = IgnoredTriangles::default();
        !scene
            .visibility_bvh()
            .blocked(p + n * eps, dir, 0.0, distance - eps, &none)
    }
}

/// The offset from a surface a ray to the eye starts at, metres.
fn ray_offset(scene: &RadiosityScene) -> f64 {
    1e-5 * scene
        .casters
        .bounds()
        .map_or(1.0, |(lo, hi)| (hi - lo).length())
}

/// Per element, the share of the image it covers per m² of its area (up to a constant):
/// cos θ / (d² cos³ α) — the solid angle it subtends at the eye per area, times the
/// pixels per steradian at its angle α from the view direction — where the eye sees its
/// centre inside the image; 0 elsewhere.
pub fn view_weights(scene: &RadiosityScene, view: &ViewPoint) -> Vec<f64> {
    let el = &scene.elements;
    let eps = ray_offset(scene);
    (0..el.len())
        .into_par_iter()
        .map(|e| {
            let p = el.position[e];
            let n = el.normal(e);
            let Some((x, y, z)) = view.image(p) else {
                return 0.0;
            };
            if x.abs() > view.tan_half.0
                || y.abs() > view.tan_half.1
                || !view.sees(scene, p, n, eps)
            {
                return 0.0;
            }
            let to_eye = view.eye - p;
            let d2 = to_eye.length_squared();
            let cos_surface = n.dot(to_eye) / d2.sqrt();
            let cos_axis = z / d2.sqrt();
            cos_surface / (d2 * cos_axis.powi(3))
        })
        .collect()
}

/// Per chart, the largest cosine between the view direction and the direction to one of
/// its elements that the eye sees, among those within `widest_deg` of the view direction
/// (`None`: none). Elements are tried nearest the axis first, so a chart in view costs one
/// ray and one that is hidden a ray per element within the cone, once for every stage.
fn charts_seen_cosine(
    scene: &RadiosityScene,
    view: &ViewPoint,
    widest_deg: f64,
) -> Vec<Option<f64>> {
    let el = &scene.elements;
    let cos_widest = widest_deg.to_radians().cos();
    let eps = ray_offset(scene);
    el.charts
        .par_iter()
        .map(|c| {
            let mut near: Vec<(f64, usize)> = (c.first..c.first + c.count)
                .map(|e| {
                    let d = (el.position[e as usize] - view.eye).normalize_or_zero();
                    (d.dot(view.forward), e as usize)
                })
                .filter(|&(cos, _)| cos >= cos_widest)
                .collect();
            near.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
            near.into_iter()
                .find(|&(_, e)| view.sees(scene, el.position[e], el.normal(e), eps))
                .map(|(cos, _)| cos)
        })
        .collect()
}

/// The stages of the area of interest, narrowest first: the charts the eye sees within the
/// image's cone widened by `margin_deg`, then by [`STAGE_STEP_DEG`] more each, and last
/// every chart.
pub fn area_stages(scene: &RadiosityScene, view: &ViewPoint, margin_deg: f64) -> Vec<Vec<bool>> {
    let mut angles = Vec::new();
    let mut angle = view.half_diagonal_deg() + margin_deg.max(0.0);
    while angle < 180.0 {
        angles.push(angle);
        angle += STAGE_STEP_DEG;
    }
    let seen = match angles.last() {
        Some(&widest) => charts_seen_cosine(scene, view, widest),
        None => Vec::new(),
    };
    let mut stages: Vec<Vec<bool>> = angles
        .iter()
        .map(|a| {
            let cos_limit = a.to_radians().cos();
            seen.iter()
                .map(|c| c.is_some_and(|c| c >= cos_limit))
                .collect()
        })
        .collect();
    stages.push(vec![true; scene.elements.charts.len()]);
    stages.dedup();
    stages
}

/// `stages` ([`area_stages`]) with the charts `reached` by the importance in its widest
/// cone (the stage before the last; with only the last, nothing changes).
pub fn with_charts_reached(mut stages: Vec<Vec<bool>>, reached: &[bool]) -> Vec<Vec<bool>> {
    if stages.len() >= 2 {
        let widest = stages.len() - 2;
        for (k, r) in stages[widest].iter_mut().enumerate() {
            *r |= reached[k];
        }
        stages.dedup();
    }
    stages
}

/// The importance H per element (see the module's notes): a radiosity solution of the
/// scene without luminaires whose emission is reflectance × `view` weight, solved on the
/// GPU to [`IMPORTANCE_CONVERGE`] (or `time_budget`), read back as each element's received
/// irradiance (luminance) and divided by the convergence c it reached; and the seconds
/// its solver took to set up (a sibling of the scene's `light` solver:
/// [`GpuSolver::sibling`]).
///
/// Why 1 / c: with a mean reflectance ρ, all the importance ever shot is U₀ / (1 − ρ) and
/// what the unshot (1 − c) U₀ will still shoot is (1 − c) U₀ / (1 − ρ), so what has been
/// shot, and received, is the share c of the whole. Scaling by 1 / c estimates the
/// converged H where the received H lies — within the rooms the importance reached, unlike
/// an ambient term spread over the scene — and leaves the shooters' ranking unchanged.
/// The view's ambient term ([`view_ambient`]) needs the whole H: with H at half its
/// value it showed half the missing light (the CAD office seen at a desk, lavapipe: the
/// image as shown within 5 % after 14.3 s importance-driven, 4.8 s with the scaling;
/// global, 3.9–4.8 s).
pub fn importance(
    light: &GpuSolver,
    settings: SolverSettings,
    gpu_settings: GpuSettings,
    view: &[f64],
    time_budget: Option<std::time::Duration>,
) -> Result<(Vec<f64>, f64), GpuError> {
    let scene = light.scene();
    let radiosity = (0..scene.elements.len())
        .map(|e| scene.element_reflectance(e) * view[e])
        .collect();
    let initial = InitialState {
        radiosity,
        illuminance: vec![0.0; scene.elements.len()],
    };
    let settings = SolverSettings {
        ambient: Ambient::None,
        ..settings
    };
    let gpu_settings = GpuSettings {
        cell_power: IMPORTANCE_CELL_POWER.max(gpu_settings.cell_power),
        map_size: (gpu_settings.map_size / IMPORTANCE_MAP_DIVISOR).max(32),
        ..gpu_settings
    };
    let started = std::time::Instant::now();
    let mut solver = light.sibling(&initial, settings, gpu_settings);
    let setup_seconds = started.elapsed().as_secs_f64();
    let stop = StopAt {
        converge: IMPORTANCE_CONVERGE,
        max_shots: None,
        time_budget,
    };
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let (_, log) = solver.solve(&stop, &cancel, |_| {})?;
    let converged = log.last().map_or(1.0, |p| p.convergence);
    let scale = if converged > 0.0 {
        1.0 / converged
    } else {
        1.0
    };
    let received = solver.radiosity_and_illuminance()?.1;
    Ok((
        received.into_iter().map(|h| h * scale).collect(),
        setup_seconds,
    ))
}

/// The area-weighted mean of `values` (one per element of `scene`) over `elements`; 0
/// where they have no area.
fn area_mean(scene: &RadiosityScene, values: &[f64], elements: impl Iterator<Item = usize>) -> f64 {
    let area = &scene.elements.area;
    let (sum, total) = elements.fold((0.0, 0.0), |(s, a), e| {
        (s + values[e] * area[e], a + area[e])
    });
    if total > 0.0 {
        sum / total
    } else {
        0.0
    }
}

/// Per shooter, its weight in the selection: its elements' area-weighted mean
/// importance, plus [`WEIGHT_FLOOR`] × the scene's.
pub fn shooter_weights(
    scene: &RadiosityScene,
    shooters: &Shooters,
    importance: &[f64],
) -> Vec<f64> {
    let el = &scene.elements;
    let means: Vec<f64> = (0..shooters.len())
        .map(|k| {
            let elements = shooters.elements_of(k).iter().map(|&e| e as usize);
            area_mean(scene, importance, elements)
        })
        .collect();
    let total: f64 = (0..el.len()).map(|e| importance[e] * el.area[e]).sum();
    let floor = WEIGHT_FLOOR * total / scene.total_area.max(1e-300);
    means.into_iter().map(|m| m + floor).collect()
}

/// Per piece of `shooters`, the share of its unshot power its cells are sized by
/// (importance-weighted refinement, after Smits, Arvo and Salesin 1992, who refine links
/// by power × importance): the piece's area-weighted mean importance over that of the
/// elements the view shows (`view` > 0), between [`CELL_WEIGHT_FLOOR`] and 1. A cell's
/// error in the image is about its power times its importance, so a piece as important
/// as what the eye sees keeps the cells global progressive refinement gives it, and one
/// whose light matters less to the view shoots from cells that carry more power each
/// (at most 1 / [`CELL_WEIGHT_FLOOR`] times as much: twice the side per factor 4). All 1
/// when the view shows nothing the importance reaches.
pub fn cell_weights(
    scene: &RadiosityScene,
    shooters: &Shooters,
    importance: &[f64],
    view: &[f64],
) -> Vec<f64> {
    let seen = area_mean(
        scene,
        importance,
        (0..view.len()).filter(|&e| view[e] > 0.0),
    );
    (0..shooters.pieces.len())
        .map(|p| {
            let elements = shooters.piece_elements(p).iter().map(|&e| e as usize);
            let mean = area_mean(scene, importance, elements);
            if seen > 0.0 {
                (mean / seen).clamp(CELL_WEIGHT_FLOOR, 1.0)
            } else {
                1.0
            }
        })
        .collect()
}

/// Per element, its share of the link error (importance-driven links on the receiving
/// side, after Smits, Arvo and Salesin 1992): an irradiance error ΔE on element i changes
/// the view by ΔE ρᵢ (vᵢ + Hᵢ) per m² — directly where the eye sees it, through the
/// light it sends on elsewhere — so a receiver whose ρ (v + H) is a share w of that of
/// the elements the view shows (area-weighted mean) accepts 1 / w times the link error:
/// w between [`RECEIVER_WEIGHT_FLOOR`] and 1 (ρ: reflectance plus transmittance, by
/// luminance). All 1 when the view shows nothing the importance reaches.
pub fn receiver_weights(scene: &RadiosityScene, importance: &[f64], view: &[f64]) -> Vec<f64> {
    let worth: Vec<f64> = (0..view.len())
        .map(|e| luminance(scene.element_reemittance(e)) * (view[e] + importance[e]))
        .collect();
    let seen = area_mean(scene, &worth, (0..view.len()).filter(|&e| view[e] > 0.0));
    worth
        .iter()
        .map(|&w| {
            if seen > 0.0 {
                (w / seen).clamp(RECEIVER_WEIGHT_FLOOR, 1.0)
            } else {
                1.0
            }
        })
        .collect()
}

/// The ambient term as the view sees it: the unshot power's expected gain in the view,
/// Σⱼ ΔBⱼ Aⱼ Hⱼ, spread evenly over what the view shows (Σᵢ vᵢ Aᵢ ρᵢ), so that the
/// image's mean is right where the global term ([`super::solve::ambient_term`]) spreads
/// the unshot power over the whole scene. Zero when the view shows nothing. `unshot` is
/// all the light still to come: with perspective-driven radiosity, what the charts that
/// hold have received as well ([`GpuSolver::unshot_to_come`]).
pub fn view_ambient(
    scene: &RadiosityScene,
    unshot: &[DVec3],
    importance: &[f64],
    view: &[f64],
) -> DVec3 {
    let el = &scene.elements;
    let gain: DVec3 = (0..el.len())
        .map(|e| unshot[e] * el.area[e] * importance[e])
        .sum();
    let shown: f64 = (0..el.len())
        .map(|e| view[e] * el.area[e] * luminance(scene.element_reflectance(e)))
        .sum();
    if shown > 0.0 {
        gain / shown
    } else {
        DVec3::ZERO
    }
}

/// A solution as displayed ([`super::solve::displayed`]), with the view's ambient term
/// ([`ViewDriven::ambient`]) where a view drives it and the ambient term is shown.
pub fn displayed(
    scene: &RadiosityScene,
    radiosity: &[DVec3],
    illuminance: &[f64],
    unshot: &[DVec3],
    ambient: Ambient,
    driven: Option<&ViewDriven>,
) -> (Vec<DVec3>, Vec<f64>) {
    match driven {
        Some(d) if ambient != Ambient::None => {
            super::solve::with_ambient(scene, radiosity, illuminance, d.ambient(scene, unshot))
        }
        _ => super::solve::displayed(scene, radiosity, illuminance, unshot, ambient),
    }
}

/// What a view-driven solution keeps: the view's weights and the importance.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewDriven {
    /// Per element, [`view_weights`].
    pub view: Vec<f64>,
    /// Per element, the importance H ([`importance`]).
    pub importance: Vec<f64>,
    /// Seconds the importance solve took …
    pub importance_seconds: f64,
    /// … of which setting up its solver (its buffers; the shooters, element records,
    /// visibility mesh and receivers' boxes are the light solver's: [`GpuSolver::sibling`]).
    pub importance_setup_seconds: f64,
}

impl ViewDriven {
    /// Solves the importance of the view whose [`view_weights`] are `view` (an importance
    /// solve of at most `time_budget`) for the scene of the `light` solver it will drive.
    pub fn new(
        light: &GpuSolver,
        settings: SolverSettings,
        gpu_settings: GpuSettings,
        view: Vec<f64>,
        time_budget: Option<std::time::Duration>,
    ) -> Result<ViewDriven, GpuError> {
        let started = std::time::Instant::now();
        let (importance, importance_setup_seconds) =
            importance(light, settings, gpu_settings, &view, time_budget)?;
        Ok(ViewDriven {
            view,
            importance,
            importance_seconds: started.elapsed().as_secs_f64(),
            importance_setup_seconds,
        })
    }

    /// Sets `solver` to be driven by this view: the shooters weighed by importance, their
    /// cells sized by the importance-weighted power ([`cell_weights`]), each receiver's
    /// link error by its importance ([`receiver_weights`]), and
    /// for [`Drive::Perspective`] the receivers limited to the area of interest seen from
    /// `point` ([`area_stages`] with `margin_deg`). [`Drive::Global`] changes nothing.
    pub fn drive(
        &self,
        solver: &mut GpuSolver,
        drive: Drive,
        point: &ViewPoint,
        margin_deg: f64,
    ) -> Result<(), GpuError> {
        if drive == Drive::Global {
            return Ok(());
        }
        let weights = shooter_weights(solver.scene(), solver.shooters(), &self.importance);
        solver.set_shooter_weights(&weights);
        let cells = cell_weights(
            solver.scene(),
            solver.shooters(),
            &self.importance,
            &self.view,
        );
        solver.set_cell_weights(cells);
        let receivers = receiver_weights(solver.scene(), &self.importance, &self.view);
        solver.set_receiver_weights(&receivers);
        if drive == Drive::Perspective {
            let stages = area_stages(solver.scene(), point, margin_deg);
            let reached = self.charts_reached(solver.scene(), &stages);
            solver.set_area_of_interest(with_charts_reached(stages, &reached))?;
        }
        Ok(())
    }

    /// Per chart, whether the importance reaches it: its area-weighted mean importance is
    /// at least [`IMPORTANCE_REACHED`] × that of the charts the eye sees (those a stage
    /// before the last of `stages` has).
    pub fn charts_reached(&self, scene: &RadiosityScene, stages: &[Vec<bool>]) -> Vec<bool> {
        let el = &scene.elements;
        let mean: Vec<f64> = el
            .charts
            .iter()
            .map(|c| {
                let range = c.first as usize..(c.first + c.count) as usize;
                area_mean(scene, &self.importance, range)
            })
            .collect();
        let cones = &stages[..stages.len().saturating_sub(1)];
        let (sum, area) = (0..mean.len())
            .filter(|&k| cones.iter().any(|s| s[k]))
            .fold((0.0, 0.0), |(s, a), k| {
                (s + mean[k] * el.charts[k].area, a + el.charts[k].area)
            });
        let limit = IMPORTANCE_REACHED * sum / area.max(1e-300);
        mean.iter().map(|&m| m > 0.0 && m >= limit).collect()
    }

    /// [`view_ambient`] of `unshot`.
    pub fn ambient(&self, scene: &RadiosityScene, unshot: &[DVec3]) -> DVec3 {
        view_ambient(scene, unshot, &self.importance, &self.view)
    }
}
