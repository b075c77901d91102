//! The CPU reference solver: progressive refinement (Cohen et al. 1988) over the same
//! elements and patches as the GPU solver, with exact visibility (a ray from the patch
//! centre to each receiver, brute force over the triangles). Slow, simple and exact
//! enough to check the GPU on small scenes. It also transfers light through mirrors and
//! clear glass ([`super::specular`]): the luminaires' and every patch's virtual shooters,
//! with ray-cast legs.

use glam::DVec3;

use super::form_factor::{self, FormFactorKind};
use super::gather;
use super::initial::{DirectSamples, InitialState};
use super::scene::{luminance, RadiosityScene};
use super::solve;
use super::specular::SpecularLight;
use super::{Ambient, SolverSettings};
use crate::lighting::SurfacePoint;
use crate::shadow::{IgnoredTriangles, Light};

/// The state of a CPU solution.
#[derive(Debug, Clone)]
pub struct CpuSolver<'a> {
    scene: &'a RadiosityScene,
    settings: SolverSettings,
    /// Radiosity per element (luminous exitance, lm/m², RGB).
    pub radiosity: Vec<DVec3>,
    /// Unshot radiosity per element.
    pub unshot: Vec<DVec3>,
    /// Illuminance received per element, lux (luminance).
    pub illuminance: Vec<f64>,
    /// Unshot power when progressive shooting started (after the luminaires), lm.
    pub initial_unshot: f64,
    /// Shots from triangles so far.
    pub shots: usize,
    eps: f64,
    /// The luminaires' light through the specular windows.
    specular_light: SpecularLight<'a>,
}

impl<'a> CpuSolver<'a> {
    /// Starts a solution: every element's radiosity and unshot radiosity are its
    /// emission; then the luminaires shoot their direct light (with ray-cast shadows).
    pub fn new(scene: &'a RadiosityScene, settings: SolverSettings) -> CpuSolver<'a> {
        let n = scene.elements.len();
        let emission: Vec<DVec3> = (0..n).map(|e| scene.element_emission(e)).collect();
        let mut s = CpuSolver {
            scene,
            settings,
            radiosity: emission.clone(),
            unshot: emission,
            illuminance: vec![0.0; n],
            initial_unshot: 0.0,
            shots: 0,
            eps: scene.self_hit_epsilon,
            specular_light: scene.specular_light(),
        };
        s.shoot_luminaires();
        s.initial_unshot = s.unshot_power();
        s
    }

    fn visible(&self, from: DVec3, from_n: DVec3, to: DVec3, to_n: DVec3) -> bool {
        let light = Light((from + from_n * self.eps).extend(1.0));
        let none = IgnoredTriangles::default();
        let bvh = self.scene.visibility_bvh();
        !bvh.in_shadow(&light, to + to_n * self.eps, self.eps, &none)
    }

    /// Direct illuminance (lux, RGB) from the luminaires at `p` with unit normal `n`,
    /// straight and by way of mirrors and clear glass.
    pub fn direct(&self, p: DVec3, n: DVec3) -> DVec3 {
        self.direct_straight(p, n) + self.direct_specular(p, n)
    }

    /// The luminaires' light at `p` (unit normal `n`) through the specular windows
    /// ([`SpecularLight`]).
    fn direct_specular(&self, p: DVec3, n: DVec3) -> DVec3 {
        self.specular_light.at(p, n, self.settings.interp)
    }

    /// Direct illuminance (lux, RGB) from the luminaires straight to `p` (unit normal `n`).
    fn direct_straight(&self, p: DVec3, n: DVec3) -> DVec3 {
        let none = IgnoredTriangles::default();
        self.scene
            .luminaires
            .iter()
            .enumerate()
            .filter(|(k, l)| {
                let ignored = self.scene.ignored.get(*k).unwrap_or(&none);
                let light = Light(l.position.extend(1.0));
                let q = p + n * self.eps;
                !self
                    .scene
                    .caster_bvh()
                    .in_shadow(&light, q, self.eps, ignored)
            })
            .map(|(_, l)| {
                let colour = l.color_toward((p - l.position).normalize_or_zero());
                colour * l.illuminance_at(p, n, self.settings.interp)
            })
            .sum()
    }

    fn shoot_luminaires(&mut self) {
        let samples = DirectSamples::new(self.scene);
        let at_samples: Vec<DVec3> = samples
            .points
            .iter()
            .map(|p| self.direct(p.position, p.normal))
            .collect();
        let mut state = InitialState::with_direct(self.scene, &samples.direct(&at_samples));
        if let Some(daylight) = super::initial::daylight_direct(self.scene) {
            state.add_direct(self.scene, &daylight);
        }
        for (e, (b, lux)) in state.radiosity.iter().zip(&state.illuminance).enumerate() {
            let gained = *b - self.scene.element_emission(e);
            self.radiosity[e] += gained;
            self.unshot[e] += gained;
            self.illuminance[e] += lux;
        }
    }

    /// Σ |unshot luminance| × area, lm.
    pub fn unshot_power(&self) -> f64 {
        let el = &self.scene.elements;
        (0..el.len())
            .map(|e| luminance(self.unshot[e]).abs() * el.area[e])
            .sum()
    }

    /// Fraction of the initial unshot power that has been shot (1 when there was none).
    pub fn convergence(&self) -> f64 {
        if self.initial_unshot <= 0.0 {
            return 1.0;
        }
        1.0 - self.unshot_power() / self.initial_unshot
    }

    /// The ambient term (Cohen et al. 1988; Wallner Eq. 2.4–2.6): the unshot radiosity
    /// averaged over the area, times the interreflection factor 1 / (1 − ρ̄).
    pub fn ambient(&self) -> DVec3 {
        solve::ambient_term(self.scene, &self.unshot)
    }

    /// Chart `t`'s unshot radiosity (area-weighted mean).
    fn chart_unshot(&self, t: usize) -> DVec3 {
        let el = &self.scene.elements;
        let te = &el.charts[t];
        let range = te.first as usize..(te.first + te.count) as usize;
        let power: DVec3 = range.map(|e| self.unshot[e] * el.area[e]).sum();
        power / te.area.max(1e-300)
    }

    /// The next shooter and the overshoot it adds to its unshot radiosity: the chart
    /// (with per-triangle charts: the triangle) with the largest unshot power, with ambient overshooting (Feda and Purgathofer;
    /// Wallner Eq. 4.9) the largest (ΔB + ΔB′) A.
    pub fn select(&self) -> Option<(usize, DVec3)> {
        let el = &self.scene.elements;
        let total: DVec3 = (0..el.len()).map(|e| self.unshot[e] * el.area[e]).sum();
        let ambient = self.ambient();
        let mut best: Option<(usize, DVec3, f64)> = None;
        for (t, te) in el.charts.iter().enumerate() {
            if te.count == 0 {
                continue;
            }
            let unshot = self.chart_unshot(t);
            let extra = match self.settings.ambient {
                Ambient::Overshoot => {
                    let rho =
                        self.scene.reflectance[te.material] + self.scene.transmittance[te.material];
                    (rho * ambient)
                        .min(total / te.area - unshot)
                        .max(DVec3::ZERO)
                }
                _ => DVec3::ZERO,
            };
            let power = luminance(unshot + extra).abs() * te.area;
            if best.is_none_or(|b| power > b.2) {
                best = Some((t, extra, power));
            }
        }
        best.filter(|b| b.2 > 0.0).map(|b| (b.0, b.1))
    }

    /// Shoots chart `t`'s unshot radiosity plus `extra` from each of its patches to
    /// every visible element; its unshot radiosity becomes −`extra`.
    pub fn shoot(&mut self, t: usize, extra: DVec3) {
        let el = &self.scene.elements;
        let te = &el.charts[t];
        let nt = te.normal;
        let patches = &el.patches[te.first_patch as usize..][..te.patch_count as usize];
        // What each patch shoots, taken before any is shot: through a mirror a chart
        // lights itself.
        let deltas: Vec<DVec3> = patches
            .iter()
            .map(|p| {
                let range = p.first as usize..(p.first + p.count) as usize;
                let power: DVec3 = range.map(|e| (self.unshot[e] + extra) * el.area[e]).sum();
                power / p.area.max(1e-300)
            })
            .collect();
        for e in te.first as usize..(te.first + te.count) as usize {
            self.unshot[e] = -extra;
        }
        for (p, &delta) in patches.iter().zip(&deltas) {
            self.shoot_specular(t, p, delta);
            for i in 0..el.len() {
                if el.chart[i] as usize == t {
                    continue;
                }
                let (pi, ni) = (el.position[i], el.normal(i));
                let form_factor = |n: DVec3| match self.settings.form_factor {
                    FormFactorKind::Disc => form_factor::disc(pi, n, p.centroid, nt, p.area),
                    FormFactorKind::Polygon => form_factor::polygon(pi, n, &p.polygon, nt),
                };
                let f = self.scene.element_receives(i, p.centroid - pi, form_factor);
                if f > 0.0 && self.visible(p.centroid, nt, pi, ni) {
                    let gained = self.scene.element_reflectance(i) * delta * f;
                    self.radiosity[i] += gained;
                    self.unshot[i] += gained;
                    self.illuminance[i] += luminance(delta * f);
                }
                // A translucent receiver sends on what arrives on its back.
                let tau = self.scene.element_transmittance(i);
                if tau != DVec3::ZERO {
                    let f = form_factor(-ni);
                    if f > 0.0 && self.visible(p.centroid, nt, pi, -ni) {
                        self.radiosity[i] += tau * delta * f;
                        self.unshot[i] += tau * delta * f;
                    }
                }
            }
        }
        self.shots += 1;
    }

    /// Patch `p` of chart `t` shoots `delta` through the specular windows: each path's
    /// virtual shooter (the patch's polygon imaged through the windows) gives every
    /// element it reaches its form factor times the path's coefficients.
    fn shoot_specular(&mut self, t: usize, p: &super::elements::Patch, delta: DVec3) {
        let scene = self.scene;
        let nt = scene.elements.charts[t].normal;
        let source = p.centroid + nt * self.eps;
        let none = IgnoredTriangles::default();
        let el = &scene.elements;
        // Unlike a straight shot, a chart may take light from itself (its mirror image).
        for (path, polygon, normal) in scene.specular.images(&p.polygon, p.centroid, nt) {
            let centre = path.virtual_source();
            for i in 0..el.len() {
                let (pi, ni) = (el.position[i], el.normal(i));
                let form_factor = |n: DVec3| match self.settings.form_factor {
                    FormFactorKind::Disc => form_factor::disc(pi, n, centre, normal, p.area),
                    FormFactorKind::Polygon => form_factor::polygon(pi, n, &polygon, normal),
                };
                let bvh = scene.caster_bvh();
                let reaches = |side: DVec3| {
                    let q = pi + side * self.eps;
                    scene
                        .specular
                        .trace(bvh, source, &path, q, self.eps, &none)
                        .is_some()
                };
                let f = scene.element_receives(i, centre - pi, form_factor);
                if f > 0.0 && reaches(ni) {
                    let arriving = path.weight * delta * f;
                    let gained = scene.element_reflectance(i) * arriving;
                    self.radiosity[i] += gained;
                    self.unshot[i] += gained;
                    self.illuminance[i] += luminance(arriving);
                }
                let tau = scene.element_transmittance(i);
                if tau != DVec3::ZERO {
                    let f = form_factor(-ni);
                    if f > 0.0 && reaches(-ni) {
                        let gained = tau * path.weight * delta * f;
                        self.radiosity[i] += gained;
                        self.unshot[i] += gained;
                    }
                }
            }
        }
    }

    /// One shot; false when nothing is left to shoot.
    pub fn step(&mut self) -> bool {
        match self.select() {
            Some((t, extra)) => {
                self.shoot(t, extra);
                true
            }
            None => false,
        }
    }

    /// Shoots until `converge` (fraction of the initial unshot power shot) or `max_shots`.
    pub fn solve(&mut self, converge: f64, max_shots: usize) {
        while self.shots < max_shots && self.convergence() < converge && self.step() {}
    }

    /// Radiosity for display: with an ambient mode, plus ρ × the ambient term.
    pub fn display_radiosity(&self) -> Vec<DVec3> {
        let ambient = self.settings.ambient;
        solve::displayed(
            self.scene,
            &self.radiosity,
            &self.illuminance,
            &self.unshot,
            ambient,
        )
        .0
    }

    /// Total illuminance (lux, RGB) at a point: the luminaires' direct light plus the
    /// light from every patch (its mean radiosity × the form factor, if visible).
    pub fn illuminance(&self, point: &SurfacePoint) -> DVec3 {
        self.illuminance_at_points(std::slice::from_ref(point))[0]
    }

    /// [`CpuSolver::illuminance`] at many points (the patches' radiosity gathered once).
    pub fn illuminance_at_points(&self, points: &[SurfacePoint]) -> Vec<DVec3> {
        let shooters = super::shooters::Shooters::flat(self.scene);
        let patches = gather::patches(self.scene, &shooters, &self.radiosity);
        points
            .iter()
            .map(|point| {
                let (p, n) = (point.position, point.normal.normalize_or_zero());
                self.direct(p, n)
                    + gather::from_patches(self.scene, &patches, point, self.settings.form_factor)
            })
            .collect()
    }

    /// The state reached so far, as a start for another solver.
    pub fn state(&self) -> InitialState {
        InitialState {
            radiosity: self.radiosity.clone(),
            illuminance: self.illuminance.clone(),
        }
    }
}
