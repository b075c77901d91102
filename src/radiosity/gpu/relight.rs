//! A solution relit in place (Edström's restart semantics, §3.4): when luminaires move,
//! dim, come or go, the elements, shooters and everything shot so far stay; only the
//! luminaires' first shot changes, by `new − old`, and that difference — negative where
//! light went away — is added to every element's radiosity and unshot radiosity and then
//! shot like any other unshot light. Radiosity is linear in the emission, so once the
//! difference has been shot the solution is that of the new luminaires.

use glam::DVec3;

use super::super::initial::InitialState;
use super::super::scene::luminance;
use super::GpuSolver;
use crate::gpu::GpuError;

impl GpuSolver<'_> {
    /// Changes the luminaires' shot from `old` to `new` (both of this solver's scene, the
    /// elements in order): radiosity and unshot radiosity gain `new.radiosity −
    /// old.radiosity`, received illuminance `new.illuminance − old.illuminance`. The
    /// links' oracle is rescaled to the new start, as a fresh solve of it would be.
    pub fn relight(&mut self, old: &InitialState, new: &InitialState) -> Result<(), GpuError> {
        let n = self.scene.elements.len();
        assert!(old.radiosity.len() == n && new.radiosity.len() == n);
        let mut lit = self.gpu.read_f32(&self.buffers.radiosity)?;
        let mut unshot = self.gpu.read_f32(&self.buffers.unshot)?;
        for e in 0..n {
            let d = (new.radiosity[e] - old.radiosity[e]).as_vec3();
            let lux = (new.illuminance[e] - old.illuminance[e]) as f32;
            for (k, v) in [d.x, d.y, d.z, lux].into_iter().enumerate() {
                lit[4 * e + k] += v;
                if k < 3 {
                    unshot[4 * e + k] += v;
                }
            }
        }
        let queue = &self.gpu.queue;
        queue.write_buffer(&self.buffers.radiosity, 0, bytemuck::cast_slice(&lit));
        queue.write_buffer(&self.buffers.unshot, 0, bytemuck::cast_slice(&unshot));
        self.choice.initial_power = Some(self.start_power(&new.radiosity).0);
        Ok(())
    }

    /// The unshot power a solution starting from `radiosity` (one per element) has, lm, as
    /// convergence measures it ([`GpuSolver::measured`]): Σ |luminance| × area, weighed by
    /// the shooters' selection weights where the view drives the solution. It is what a
    /// fresh solve's first selection reports: the scale a relit solution's convergence is
    /// measured on, so that it stops where a fresh solve of the new luminaires would.
    pub fn start_scale(&self, radiosity: &[DVec3]) -> f64 {
        let (plain, weighted) = self.start_power(radiosity);
        if self.is_weighted() {
            weighted
        } else {
            plain
        }
    }

    /// [`GpuSolver::start_scale`]'s two measures: (all of it, weighted).
    pub fn start_power(&self, radiosity: &[DVec3]) -> (f64, f64) {
        let el = &self.scene.elements;
        let shooter_of = &self.upload.shooters.element_shooter;
        (0..el.len()).fold((0.0, 0.0), |(plain, weighted), e| {
            let p = luminance(radiosity[e]).abs() * el.area[e];
            let w = f32::from_bits(self.choice.shooter_info[shooter_of[e] as usize][2]) as f64;
            (plain + p, weighted + w * p)
        })
    }
}
