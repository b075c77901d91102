//! A scene's calculation, whichever front end asks (`goniolight calc`, Python's
//! `goniolight.calc`): the checks before any work ([`Request::new`]), the luminaires'
//! direct light at every grid point ([`Request::direct`]), the interreflected light of a
//! radiosity solution where asked ([`Request::gather_points`], then the front end's
//! solve and gather), and the maintained values, their statistics and the observers' UGR
//! ([`Request::finish`]); [`compute`] runs them in a row. The result writes its own
//! `calc.json`, CSVs and plans ([`Calculation`]).

use std::sync::atomic::{AtomicBool, Ordering};

use serde_json::json;

use super::daylight::DaylightGrids;
use super::directions::{combine, surface_points};
use super::glare::{background_point, check_outside, observer_glare, ObserverGlare};
use super::plan::Plan;
use super::requirements::{judge, Verdict};
use super::{grid_stats, CalcGrid, CalcSettings, GridStats};
use crate::gpu::{Gpu, GpuError};
use crate::io::limits::MAX_TOTAL_POINTS;
use crate::lighting::{usable_lux, SurfacePoint, UnusableLux};
use crate::photometry::Interp;
use crate::radiosity::session::{self, Event, SessionError};
use crate::radiosity::view::Drive;
use crate::render::illuminance::{scene_illuminance, IlluminanceError};
use crate::render::ShadowTechnique;
use crate::scene::grid::Indirect;
use crate::scene::{Palette, Scene};

/// What a calculation is asked to do (the options of `goniolight calc`, with its
/// defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct CalcOptions {
    /// The values reported are the computed ones times this, in (0, 1] (`None`: the
    /// scene's `calc.maintenance_factor`).
    pub maintenance_factor: Option<f64>,
    /// Compute the direct light on the CPU (the reference) instead of the GPU.
    pub cpu: bool,
    /// Interpolation of the light distributions.
    pub interp: Interp,
    /// Shadows cast by the scene's geometry.
    pub shadows: ShadowTechnique,
    /// Direct light only, or total light through the radiosity solver (`None`: the
    /// scene's `calc.indirect`, else none).
    pub indirect: Option<Indirect>,
    /// The most points over all grids together.
    pub max_points: usize,
    /// The radiosity solver's options (with the radiosity indirect light).
    pub radiosity: session::Options,
}

impl Default for CalcOptions {
    fn default() -> CalcOptions {
        CalcOptions {
            maintenance_factor: None,
            cpu: false,
            interp: Interp::CatmullRom,
            shadows: ShadowTechnique::Volumes,
            indirect: None,
            max_points: MAX_TOTAL_POINTS,
            radiosity: session::Options::default(),
        }
    }
}

/// Why a calculation failed.
#[derive(Debug, thiserror::Error)]
pub enum CalcError {
    /// An option out of range or in conflict with another (the field named as in
    /// [`CalcOptions`]; `radiosity.…` for the solver's).
    #[error("{field} {message}")]
    Option {
        /// The field of [`CalcOptions`].
        field: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The scene cannot be calculated as it is (no grid, two grids writing one file, an
    /// observer inside a luminaire, …).
    #[error("{0}")]
    Scene(String),
    /// A computed value is not a usable number: a bug, refused rather than reported.
    #[error(
        "grid {grid:?}, point {point}: the computed illuminance {value} lx is not a usable number"
    )]
    Unusable {
        /// The grid's name.
        grid: String,
        /// The point, counted from 1.
        point: usize,
        /// The value.
        value: f64,
    },
    /// The GPU failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The radiosity solution failed (or its preparation was cancelled).
    #[error(transparent)]
    Radiosity(#[from] SessionError),
    /// Cancelled before the values were complete.
    #[error("interrupted: nothing written")]
    Cancelled,
}

impl CalcError {
    /// Whether the input (options, scene) is to blame rather than the machine.
    pub fn is_bad_input(&self) -> bool {
        match self {
            CalcError::Option { .. } | CalcError::Scene(_) => true,
            CalcError::Radiosity(e) => e.is_bad_input(),
            CalcError::Gpu(e) => matches!(e, GpuError::Limit(_)),
            CalcError::Unusable { .. } | CalcError::Cancelled => false,
        }
    }
}

/// The file name of a grid's CSV: its name with anything but letters, digits, `-` and `_`
/// replaced by `-`.
pub fn csv_name(grid_name: &str) -> String {
    let stem: String = grid_name
        .trim()
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '-'
            }
        })
        .collect();
    format!("{stem}.csv")
}

/// The file of a grid's daylight-factor plan beside its CSV `csv` (`desk.csv` →
/// `desk-df.png`).
pub fn df_plan_name(csv: &str, extension: &str) -> String {
    format!("{}-df.{extension}", csv.trim_end_matches(".csv"))
}

/// How grid points are placed.
pub const GRID_RULE: &str = "points at the centres of equal cells; spacing as given, or EN 12464-1's p = 0.2 · 5^log10(d) over the grid's longer side d";

/// A calculation checked and ready to run.
pub struct Request<'s> {
    scene: &'s Scene,
    /// What lights the request when it is not the scene as it is: the luminaires alone
    /// (a scene with a sky), or the sky alone ([`Request::daylight`]).
    lighting: Option<Scene>,
    options: &'s CalcOptions,
    /// The maintenance factor applied.
    pub maintenance_factor: f64,
    /// The light computed.
    pub indirect: Indirect,
    grid_points: Vec<Vec<SurfacePoint>>,
}

impl<'s> Request<'s> {
    /// Checks `options` against `scene` before any work: a scene with something to
    /// compute, the maintenance factor, the light asked for (UGR needs the
    /// interreflected light; the CPU computes direct light only; a grid's lux must not
    /// depend on a view), grid files that do not collide, the point budget, observers
    /// outside every luminaire.
    pub fn new(scene: &'s Scene, options: &'s CalcOptions) -> Result<Request<'s>, CalcError> {
        let label = scene.path.display();
        if scene.grids.is_empty() && scene.observers.is_empty() {
            return Err(CalcError::Scene(format!(
                "{label}: no [[grid]] or [[observer]] to compute; add a calculation surface (docs/src/guide/calc.md)"
            )));
        }
        let mf = CalcSettings::check(
            options
                .maintenance_factor
                .unwrap_or(scene.calc.maintenance_factor),
        )
        .map_err(|message| CalcError::Option {
            field: "maintenance_factor",
            message,
        })?;
        let indirect = options
            .indirect
            .or(scene.calc.indirect)
            .unwrap_or(Indirect::None);
        if !scene.observers.is_empty() && indirect == Indirect::None {
            return Err(CalcError::Scene(format!(
                "{label}: UGR at the [[observer]]s needs the background luminance, which is the interreflected light at the eye: use `indirect` radiosity (or set calc.indirect = \"radiosity\" in the scene)"
            )));
        }
        if indirect == Indirect::Radiosity {
            if options.cpu {
                return Err(CalcError::Option {
                    field: "cpu",
                    message: "computes the direct light only: the radiosity solver runs on the GPU (leave out `cpu`, or use `indirect` none)".into(),
                });
            }
            options.radiosity.validate().map_err(SessionError::from)?;
            if options.radiosity.drive != Drive::Global {
                // A grid's lux must not depend on where the camera looks.
                return Err(CalcError::Option {
                    field: "drive",
                    message: format!("{}: calc's interreflected light is solved for the whole scene (`drive` global); view-driven solutions are for `radiosity` and the viewer", options.radiosity.drive.name()),
                });
            }
        }
        let mut names = std::collections::HashSet::new();
        for g in &scene.grids {
            if !names.insert(csv_name(&g.entry.name)) {
                return Err(CalcError::Scene(format!(
                    "{label}: grid {:?} would write the same CSV file as another grid ({}); rename one",
                    g.entry.name,
                    csv_name(&g.entry.name)
                )));
            }
        }
        let total: usize = scene.grids.iter().map(|g| g.points.len()).sum();
        if total > options.max_points {
            return Err(CalcError::Scene(format!(
                "{label}: the grids hold {total} points together, more than `max_points` {} (each point costs memory and about 100 bytes of files): use a larger spacing, split the grids over several runs, or raise `max_points`",
                options.max_points
            )));
        }
        for o in &scene.observers {
            for l in &scene.luminaires {
                check_outside(o, l).map_err(|e| {
                    CalcError::Scene(format!("{label}: observer {:?}: {e}", o.entry.name))
                })?;
            }
        }
        Ok(Request {
            scene,
            lighting: scene.daylight.is_some().then(|| scene.without_daylight()),
            options,
            maintenance_factor: mf,
            indirect,
            grid_points: scene.grids.iter().map(surface_points).collect(),
        })
    }

    /// What lights this request: the scene, its luminaires alone (a scene with a sky:
    /// the sky is [`Request::daylight`]'s), or its sky alone.
    pub fn lighting_scene(&self) -> &Scene {
        self.lighting.as_ref().unwrap_or(self.scene)
    }

    /// Whether the interreflected light is to be solved: radiosity asked for and
    /// something in the lighting scene gives light (without any, it is exactly zero).
    pub fn solves(&self) -> bool {
        self.indirect == Indirect::Radiosity && self.lighting_scene().has_light()
    }

    /// The interreflected light where [`Request::solves`] is false: radiosity asked for
    /// and nothing gives light, so zero everywhere, exactly (converged).
    pub fn unlit_interreflection(&self) -> Option<(Vec<f64>, f64)> {
        (self.indirect == Indirect::Radiosity && !self.solves())
            .then(|| (vec![0.0; self.gather_points().len()], 1.0))
    }

    /// The request for the scene's daylight alone (its sky; no luminaires, no emitting
    /// surfaces, not maintained), the same grids and light asked for; `None` without a sky.
    pub fn daylight(&self) -> Option<Request<'s>> {
        self.scene.daylight.as_ref()?;
        Some(Request {
            scene: self.scene,
            lighting: Some(self.scene.daylight_only()),
            options: self.options,
            maintenance_factor: 1.0,
            indirect: self.indirect,
            grid_points: self.grid_points.clone(),
        })
    }

    /// The daylight of a [`Request::daylight`] request from its direct light and, with
    /// radiosity, the interreflected light at [`Request::gather_points`]: per grid and
    /// point (directions combined), with the daylight factor under the CIE overcast sky.
    pub fn finish_daylight(
        self,
        direct: Direct,
        interreflected: Option<(Vec<f64>, f64)>,
    ) -> Result<DaylightGrids, CalcError> {
        let mut at = 0;
        let mut lux = Vec::with_capacity(direct.lux.len());
        for (g, mut values) in self.scene.grids.iter().zip(direct.lux) {
            if let Some((inter, _)) = &interreflected {
                for v in values.iter_mut() {
                    *v += inter[at];
                    at += 1;
                }
            }
            usable_lux(&mut values).map_err(|u| unusable(&g.entry.name, u))?;
            lux.push(
                combine(g, &values)
                    .into_iter()
                    .map(|v| v.max(0.0))
                    .collect(),
            );
        }
        Ok(DaylightGrids::new(
            self.scene,
            lux,
            interreflected.map(|(_, c)| c),
        ))
    }

    /// The direct illuminance at every grid point (per grid, per point and direction) of
    /// what lights the request ([`Request::lighting_scene`]), on `gpu` (`None`: the CPU);
    /// `cancel` stops between grids.
    pub fn direct(&self, gpu: Option<&Gpu>, cancel: &AtomicBool) -> Result<Direct, CalcError> {
        let mut shadows = crate::render::ShadowSettings::with(self.options.shadows);
        let mut lux = Vec::with_capacity(self.grid_points.len());
        let scene = self.lighting_scene();
        for (g, points) in self.scene.grids.iter().zip(&self.grid_points) {
            if cancel.load(Ordering::SeqCst) {
                return Err(CalcError::Cancelled);
            }
            let direct = scene_illuminance(gpu, scene, points, self.options.interp, &mut shadows)
                .map_err(|e| match e {
                IlluminanceError::Gpu(g) => CalcError::Gpu(g),
                IlluminanceError::Unusable(u) => unusable(&g.entry.name, u),
            })?;
            lux.push(direct);
        }
        Ok(Direct {
            lux,
            warnings: shadows.warning().into_iter().collect(),
        })
    }

    /// Where the interreflected light is gathered: every grid point (and direction),
    /// then each observer's eye, in one list (one gather for all).
    pub fn gather_points(&self) -> Vec<SurfacePoint> {
        let eyes = self.scene.observers.iter().map(background_point);
        self.grid_points
            .iter()
            .flatten()
            .copied()
            .chain(eyes)
            .collect()
    }

    /// The calculation from the direct light ([`Request::direct`]) and, with the
    /// radiosity indirect light, the interreflected light at [`Request::gather_points`]
    /// and the solution's convergence: the maintained values and their statistics per
    /// grid, the UGR of each observer (from the initial light, as UGR tables are: the
    /// maintenance factor scales neither the luminaires' luminance nor the background).
    pub fn finish(
        self,
        direct: Direct,
        interreflected: Option<(Vec<f64>, f64)>,
    ) -> Result<Calculation<'s>, CalcError> {
        let Direct {
            lux: mut direct,
            warnings,
        } = direct;
        let scene = self.scene;
        let mut background = vec![0.0; scene.observers.len()];
        let mut convergence = None;
        if let Some((inter, converged)) = &interreflected {
            convergence = Some(*converged);
            let mut at = 0;
            for (g, lux) in scene.grids.iter().zip(direct.iter_mut()) {
                for v in lux.iter_mut() {
                    *v += inter[at];
                    at += 1;
                }
                usable_lux(lux).map_err(|u| unusable(&g.entry.name, u))?;
            }
            for b in &mut background {
                *b = inter[at].max(0.0) / std::f64::consts::PI;
                at += 1;
            }
        }
        let mf = self.maintenance_factor;
        let grids: Vec<GridResult> = scene
            .grids
            .iter()
            .zip(&direct)
            .map(|(g, lux)| {
                let values: Vec<f64> = combine(g, lux)
                    .into_iter()
                    .map(|v| v.max(0.0) * mf)
                    .collect();
                GridResult {
                    stats: grid_stats(&values),
                    values,
                }
            })
            .collect();
        let glare: Vec<ObserverGlare> = scene
            .observers
            .iter()
            .zip(&background)
            .map(|(o, &lb)| {
                observer_glare(scene, o, lb, self.options.interp)
                    .map_err(|e| CalcError::Scene(format!("observer {:?}: {e}", o.entry.name)))
            })
            .collect::<Result<_, _>>()?;
        let stats: Vec<GridStats> = grids.iter().map(|g| g.stats).collect();
        let requirements = judge(
            scene,
            &stats,
            &glare,
            (convergence.is_none(), self.options.interp),
        );
        let light = match convergence {
            Some(c) => vec![
                "direct + interreflected".to_string(),
                format!("(radiosity, {:.1} % converged)", 100.0 * c),
            ],
            None => vec!["direct light only".to_string()],
        };
        Ok(Calculation {
            scene,
            maintenance_factor: mf,
            indirect: self.indirect,
            convergence,
            interp: self.options.interp,
            shadows: self.options.shadows,
            cpu: self.options.cpu,
            grids,
            glare,
            requirements,
            light,
            warnings,
            daylight: None,
        })
    }
}

/// The interreflected light at [`Request::gather_points`] with the solution's
/// convergence; `None` without radiosity.
pub type Gathered = Option<(Vec<f64>, f64)>;

/// The luminaires' direct light at the grids' points ([`Request::direct`]).
#[derive(Debug, Clone)]
pub struct Direct {
    /// Per grid, per point (and direction), lux.
    pub lux: Vec<Vec<f64>>,
    /// What the caller should be told (options named in backquotes).
    pub warnings: Vec<String>,
}

/// The error naming the grid and point of a computed illuminance that is not a usable number.
fn unusable(grid: &str, u: UnusableLux) -> CalcError {
    CalcError::Unusable {
        grid: grid.to_string(),
        point: u.point,
        value: u.value,
    }
}

/// One grid's result.
#[derive(Debug, Clone, PartialEq)]
pub struct GridResult {
    /// The maintained illuminance at each point, lux.
    pub values: Vec<f64>,
    /// Their statistics.
    pub stats: GridStats,
}

/// A scene's calculation: per grid the maintained values and statistics, per observer
/// the UGR.
pub struct Calculation<'s> {
    scene: &'s Scene,
    /// The maintenance factor the values include.
    pub maintenance_factor: f64,
    /// The light computed.
    pub indirect: Indirect,
    /// The radiosity solution's convergence, with the radiosity indirect light.
    pub convergence: Option<f64>,
    interp: Interp,
    shadows: ShadowTechnique,
    cpu: bool,
    /// Per grid of the scene, in order.
    pub grids: Vec<GridResult>,
    /// Per observer of the scene, in order.
    pub glare: Vec<ObserverGlare>,
    /// Every requirement of the scene's areas, judged (in the areas' order).
    pub requirements: Vec<Verdict>,
    /// What light the values hold, in words (one or two short lines).
    pub light: Vec<String>,
    /// What the caller should be told (options named in backquotes), e.g. a paraboloid
    /// tessellation made coarser to fit the GPU.
    pub warnings: Vec<String>,
    /// The scene's daylight, included in [`Calculation::grids`]' values
    /// ([`Calculation::add_daylight`]).
    pub daylight: Option<DaylightGrids>,
}

impl Calculation<'_> {
    /// Adds the scene's daylight to the luminaires' maintained values: every grid's
    /// values and statistics, and the requirements judged again on them.
    pub fn add_daylight(&mut self, daylight: DaylightGrids) {
        for (g, day) in self.grids.iter_mut().zip(&daylight.lux) {
            for (v, d) in g.values.iter_mut().zip(day) {
                *v += d;
            }
            g.stats = grid_stats(&g.values);
        }
        let stats: Vec<GridStats> = self.grids.iter().map(|g| g.stats).collect();
        self.requirements = judge(
            self.scene,
            &stats,
            &self.glare,
            (self.convergence.is_none(), self.interp),
        );
        let solved = daylight
            .convergence
            .map(|c| format!("(radiosity, {:.1} % converged)", 100.0 * c));
        if self.scene.has_electric_light() {
            self.light.push(format!("+ daylight: {}", daylight.sky));
        } else {
            // Nothing but the sky gives light: its solution is the calculation's.
            self.convergence = daylight.convergence;
            self.light = vec![format!("daylight: {}", daylight.sky)];
            match solved {
                Some(s) => self.light.extend(["direct + interreflected".into(), s]),
                None => self.light.push("direct light only".into()),
            }
        }
        self.daylight = Some(daylight);
    }

    /// The scene's grids with their results.
    pub fn grid_results(&self) -> impl Iterator<Item = (&CalcGrid, &GridResult)> {
        self.scene.grids.iter().zip(&self.grids)
    }

    /// The `calc.json` entry of grid `k`.
    pub fn grid_json(&self, k: usize) -> serde_json::Value {
        let g = &self.scene.grids[k];
        let s = self.grids[k].stats;
        let csv = csv_name(&g.entry.name);
        let mut entry = json!({
            "name": g.entry.name,
            "kind": g.entry.kind,
            "points": s.points,
            "em": s.em,
            "emin": s.emin,
            "emax": s.emax,
            "u0": s.u0,
            "g2": s.g2,
            "maintenance_factor": self.maintenance_factor,
            "indirect": self.indirect == Indirect::Radiosity,
            "spacing_m": g.spacing,
            "plans": [csv.replace(".csv", ".png"), csv.replace(".csv", ".svg")],
            "csv": csv,
        });
        if let Some(d) = &self.daylight {
            let day = grid_stats(&d.lux[k]);
            entry["daylight"] =
                json!({"em": day.em, "emin": day.emin, "emax": day.emax, "u0": day.u0});
            if let Some(f) = &d.factor_stats {
                entry["daylight_factor"] = json!(f[k]);
                entry["plans"].as_array_mut().expect("plans").extend([
                    json!(df_plan_name(&csv, "png")),
                    json!(df_plan_name(&csv, "svg")),
                ]);
            }
        }
        entry
    }

    /// The whole `calc.json` document; `scene_label` is how the scene file is named
    /// (as given on the command line).
    pub fn json(&self, scene_label: &str) -> serde_json::Value {
        let observers: Vec<_> = self
            .scene
            .observers
            .iter()
            .zip(&self.glare)
            .map(|(o, g)| {
                json!({
                    "name": o.entry.name,
                    "position": o.entry.position,
                    "direction": o.entry.direction,
                    "ugr": g.ugr,
                    "background_cd_m2": g.background_cd_m2,
                    "glare_sum": g.glare_sum,
                    "luminaires": g.luminaires,
                })
            })
            .collect();
        json!({
            "scene": scene_label,
            "interp": self.interp.name().to_string(),
            "shadows": format!("{:?}", self.shadows).to_lowercase(),
            "device": if self.cpu { "cpu" } else { "gpu" },
            "indirect": self.indirect,
            "convergence": self.convergence,
            "grids": (0..self.grids.len()).map(|k| self.grid_json(k)).collect::<Vec<_>>(),
            "observers": observers,
            "requirements": self.requirements,
            "method": self.method_json(),
        })
    }

    /// How the values were found, for a reviewer to reproduce them: the software, the
    /// standards judged, the grid rule, the maintenance factor, the light and how it was
    /// computed.
    pub fn method_json(&self) -> serde_json::Value {
        json!({
            "software": format!("goniolight {}", env!("CARGO_PKG_VERSION")),
            "standards": self.standards(),
            "emergency": self.is_emergency(),
            "grid_rule": GRID_RULE,
            "maintenance_factor": self.maintenance_factor,
            "values": match &self.daylight {
                Some(_) => "the luminaires' light × maintenance factor, plus daylight (not scaled)",
                None => "maintained: computed × maintenance factor",
            },
            "daylight": self.daylight.as_ref().map(|d| json!({
                "sky": d.sky,
                "convergence": d.convergence,
                "daylight_factor": d.factor.is_some(),
                "glazing": "one pane of uncoated glass, n = 1.52 (Fresnel, as Radiance's glass)",
                "method": "the sky and ground seen from each point through openings and glazing (128 × 512 rays), the sun's disc (19 rays); interreflections by radiosity",
            })),
            "light": self.light.join(" "),
            "solver": match self.convergence {
                Some(c) => json!({"name": "progressive radiosity", "convergence": c}),
                None => serde_json::Value::Null,
            },
            "shadows": self.shadows_text(),
            "interp": self.interp.name(),
            "device": if self.cpu { "cpu" } else { "gpu" },
        })
    }

    /// The standards the scene's areas are judged by, each once.
    pub fn standards(&self) -> Vec<&'static str> {
        let mut out: Vec<&'static str> = Vec::new();
        for a in &self.scene.areas {
            if !out.contains(&a.standard.name()) {
                out.push(a.standard.name());
            }
        }
        out
    }

    /// Whether this is the emergency lighting ([`Scene::in_emergency`]).
    pub fn is_emergency(&self) -> bool {
        self.scene
            .areas
            .iter()
            .any(|a| a.standard == crate::scene::area::Standard::En1838)
    }

    fn shadows_text(&self) -> &'static str {
        match (self.shadows, self.cpu) {
            (ShadowTechnique::None, _) => "no shadows",
            (ShadowTechnique::Paraboloid, false) => "paraboloid shadow maps",
            _ => "exact shadows (a ray from each point to each luminaire)",
        }
    }

    /// Grid `k`'s CSV: `x,y,z,lux` with a header, one row per point (coordinates exact,
    /// so the points can be fed back to `illuminance`); with the daylight factor a `df`
    /// column (per cent).
    pub fn grid_csv(&self, k: usize) -> String {
        let g = &self.scene.grids[k];
        let factor = self
            .daylight
            .as_ref()
            .and_then(|d| d.factor.as_ref())
            .map(|f| &f[k]);
        let mut out = String::from(match factor {
            Some(_) => "x,y,z,lux,df\n",
            None => "x,y,z,lux\n",
        });
        for (i, (p, v)) in g.points.iter().zip(&self.grids[k].values).enumerate() {
            out.push_str(&format!("{},{},{},{v:.6}", p.x, p.y, p.z));
            if let Some(f) = factor {
                out.push_str(&format!(",{:.6}", f[i]));
            }
            out.push('\n');
        }
        out
    }

    /// Grid `k`'s plan, coloured by `palette` (default: the scene's `display.palette`)
    /// in `steps` hard steps (default the scene's, else smooth), with the value at every
    /// point where `values_at_points`.
    pub fn plan(
        &self,
        k: usize,
        palette: Option<Palette>,
        steps: Option<u32>,
        values_at_points: bool,
    ) -> Plan<'_> {
        let scene = self.scene;
        let r = &self.grids[k];
        Plan {
            grid: &scene.grids[k],
            values: &r.values,
            stats: r.stats,
            maintenance_factor: self.maintenance_factor,
            luminaires: scene
                .luminaires
                .iter()
                .enumerate()
                .map(|(i, l)| (l.position, format!("L{}", i + 1)))
                .collect(),
            observers: scene
                .observers
                .iter()
                .zip(&self.glare)
                .map(|(o, gl)| {
                    let ugr = gl.ugr.map_or("—".into(), |u| format!("{u:.1}"));
                    (o.eye, o.forward, format!("{} UGR {ugr}", o.entry.name))
                })
                .collect(),
            areas: scene
                .areas
                .iter()
                .filter(|a| {
                    a.entry.kind != crate::scene::area::AreaKind::Room && a.outline.len() >= 3
                })
                .map(|a| (a.outline.clone(), a.entry.name.clone()))
                .collect(),
            light: self.light.clone(),
            palette: (
                palette.or(scene.display.palette).unwrap_or_default(),
                steps.or(scene.display.steps).unwrap_or(0),
            ),
            values_at_points,
            north_offset_deg: scene.site.as_ref().map(|s| s.north_offset_deg),
            daylight_factor: None,
        }
    }

    /// Grid `k`'s daylight-factor plan (as [`Calculation::plan`], the values per cent);
    /// `None` without a daylight factor (no CIE overcast sky).
    pub fn df_plan(
        &self,
        k: usize,
        palette: Option<Palette>,
        steps: Option<u32>,
        values_at_points: bool,
    ) -> Option<Plan<'_>> {
        let d = self.daylight.as_ref()?;
        let (factor, stats) = (d.factor.as_ref()?, d.factor_stats.as_ref()?);
        let lux = self.plan(k, palette, steps, values_at_points);
        Some(Plan {
            values: &factor[k],
            stats: grid_stats(&factor[k]),
            light: vec![d.sky.clone()],
            daylight_factor: Some(stats[k]),
            ..lux
        })
    }

    /// The report's settings table: scene, maintenance factor, light, interpolation,
    /// device, and with areas the standard and the grid rule.
    pub fn report_settings(&self, scene_label: &str) -> Vec<(&'static str, String)> {
        let mut rows = vec![
            ("scene", scene_label.to_string()),
            ("maintenance factor", self.maintenance_factor.to_string()),
            (
                "light",
                format!("{}; {}", self.light.join(" "), self.shadows_text()),
            ),
            ("interpolation", self.interp.name().to_string()),
            (
                "computed on",
                if self.cpu { "CPU" } else { "GPU" }.to_string(),
            ),
        ];
        if let Some(d) = &self.daylight {
            rows.push((
                "daylight",
                format!(
                    "{}; added to the luminaires' maintained light (not scaled)",
                    d.sky
                ),
            ));
        }
        if !self.scene.areas.is_empty() {
            rows.push(("standard", self.standards().join(", ")));
            rows.push(("grid rule", GRID_RULE.to_string()));
        }
        if self.is_emergency() {
            rows.push((
                "emergency",
                "the luminaires with an emergency output at it, direct light only (EN 1838)"
                    .to_string(),
            ));
        }
        rows
    }
}

/// Runs a calculation of `scene` with `options` start to end: the direct light (on the
/// shared GPU unless `options.cpu`), the radiosity solution and its gather where asked
/// (`events` sees the solve's progress), the results; with a sky, the same again for the
/// daylight alone, added to the luminaires' maintained light. `cancel` stops it with an
/// error.
pub fn compute<'s>(
    scene: &'s Scene,
    options: &'s CalcOptions,
    cancel: &AtomicBool,
    events: &mut dyn FnMut(Event),
) -> Result<Calculation<'s>, CalcError> {
    let request = Request::new(scene, options)?;
    let gpu = if options.cpu {
        None
    } else {
        Some(Gpu::shared()?)
    };
    let daylight = request.daylight();
    let (direct, interreflected, warning) = light_of(&request, gpu.as_ref(), cancel, events)?;
    let mut calc = request.finish(direct, interreflected)?;
    if let Some(day) = daylight {
        let (direct, interreflected, _) = light_of(&day, gpu.as_ref(), cancel, events)?;
        calc.add_daylight(day.finish_daylight(direct, interreflected)?);
    }
    if let Some(w) = warning.filter(|w| !calc.warnings.contains(w)) {
        calc.warnings.push(w);
    }
    Ok(calc)
}

/// The direct light of `request` and, where it solves, the interreflected light at its
/// gather points with the solution's convergence; and what the solver's shadows warn of.
fn light_of(
    request: &Request,
    gpu: Option<&Gpu>,
    cancel: &AtomicBool,
    events: &mut dyn FnMut(Event),
) -> Result<(Direct, Gathered, Option<String>), CalcError> {
    let direct = request.direct(gpu, cancel)?;
    let (Some(gpu), true) = (gpu, request.solves()) else {
        return Ok((direct, request.unlit_interreflection(), None));
    };
    let scene = request.lighting_scene();
    let options = request.options;
    let mut settings = crate::render::RenderSettings::from_display(&scene.display);
    settings.shadows = crate::render::ShadowSettings::with(options.shadows);
    let setup = session::Setup {
        scene,
        options: &options.radiosity,
        interp: options.interp,
        shadows: &mut settings.shadows,
        view: None,
    };
    let solution = session::solve(gpu, setup, cancel, events)?;
    if solution.stop() == crate::radiosity::solve::StopReason::Cancelled {
        return Err(CalcError::Cancelled);
    }
    let points = request.gather_points();
    let lux = solution.interreflected_lux(&points, cancel, &|_| {})?;
    Ok((
        direct,
        Some((lux, solution.convergence())),
        settings.shadows.warning(),
    ))
}
