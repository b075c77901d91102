//! Receivers outside the area of interest (perspective-driven radiosity, Bozalina §5.2)
//! take no part in the solution: they show nothing new and shoot nothing. Each does so in
//! one of two ways ([`Reception`]):
//!
//! - It **holds**: it receives as usual, but into a buffer of its own (`held_back`,
//!   Bozalina's table of stored radiosity, one record per element instead of N × N); when
//!   it joins, one pass adds what it holds to its radiosity and unshot radiosity. Joining
//!   costs nothing but that pass; holding costs its receive passes. For the charts that
//!   join as the area widens around the view.
//! - It **waits**: it receives nothing, and each shot it misses is kept — the shooter's
//!   cells, their links and the unshot radiosity they shot. When it joins, the shots it
//!   missed are shot again at it alone, in order (their maps drawn again). Waiting costs
//!   nothing; joining costs the missed cells' maps. For the charts that join only with
//!   the whole scene, once the view's light has settled.
//!
//! Either way its light on joining is what it would have been had it received all along.

use super::super::links::{Links, ReceiverBoxes};
use super::super::shooters::ShotPlan;
use super::{cell_planes, GpuSolver, ShotTimes};
use crate::gpu::GpuError;

/// The perspective-driven part of a solver: receivers that wait and the shots they
/// missed, the area of interest's stages, and the maps kept for their catch-up.
pub(super) struct Perspective {
    /// Receivers that wait, and the shots they missed.
    pub(super) deferral: Option<Deferral>,
    /// The area of interest's stages.
    pub(super) stages: Option<Stages>,
    /// The maps of the cells shot while receivers waited, for their catch-up.
    pub(super) map_store: super::map_store::MapStore,
}

/// A shot some waiting receiver missed.
pub(super) struct MissedShot {
    shooter: usize,
    plan: ShotPlan,
    links: Links,
    /// Per cell of the plan, the rgb unshot radiosity it shot.
    delta: Vec<[f32; 4]>,
    /// The cells whose maps were drawn while a receiver waited …
    cells: Vec<usize>,
    /// … and where each one's maps were kept ([`super::map_store`]; `None`: not kept).
    kept: Vec<Option<u32>>,
}

/// How a chart outside the area of interest keeps out of the solution (see the module's
/// notes), or that it takes part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reception {
    /// It receives, shows and shoots its light.
    Receives,
    /// It receives into the held-back buffer, given to it when it joins.
    Holds,
    /// It receives nothing; the shots it misses are shot at it again when it joins.
    Waits,
}

/// The area of interest's stages (perspective-driven radiosity), and where it stands.
pub(super) struct Stages {
    /// Per stage, per chart of the elements, how it receives; the last: every chart
    /// receives.
    stages: Vec<Vec<Reception>>,
    at: usize,
    /// The weighted unshot power when the stage began …
    start: Option<f64>,
    /// … and when the first stage began.
    first_start: Option<f64>,
}

/// The held-back buffer's binding in the solver's bind group 0 (radiosity.wgsl).
pub(super) const HELD_BACK_BINDING: usize = 12;

/// The area of interest widens when the weighted unshot power has fallen to this share
/// of what it was when its stage began ("a pre-determined amount of processing",
/// Bozalina §5.1).
pub const WIDEN_AT: f64 = 0.25;

/// The last stage (the charts the eye does not see and the view's importance barely
/// reaches, which wait) joins when the weighted unshot power has also fallen to this
/// share of what it was when the first stage began: once the view is 99 % converged, so
/// that drawing again the maps of the shots they missed does not hold the view up. In
/// the furnished room, joining at [`WIDEN_AT`] drew most maps again just before the view
/// came within 5 % (3 208 maps against global's 1 571, lavapipe).
pub const WIDEN_LAST_AT: f64 = 0.01;

/// Which receivers hold or wait, and what the waiting ones missed.
pub(super) struct Deferral {
    /// Per receiver chart ([`ReceiverBoxes::range`](crate::radiosity::links::ReceiverBoxes::range)), how it receives now.
    pub(super) reception: Vec<Reception>,
    /// Whether the held-back buffer has a record per element (some chart has held).
    held_back: bool,
    /// Per waiting chart, the first shot of `missed` it has not had.
    missed_from: Vec<usize>,
    missed: Vec<MissedShot>,
}

impl GpuSolver<'_> {
    /// Which charts receive (`receiving`, one per chart of the scene's elements,
    /// `elements.charts` order); the others wait ([`GpuSolver::set_reception`]).
    pub fn set_receiving(&mut self, receiving: &[bool]) -> Result<usize, GpuError> {
        let reception: Vec<Reception> = receiving
            .iter()
            .map(|&r| {
                if r {
                    Reception::Receives
                } else {
                    Reception::Waits
                }
            })
            .collect();
        self.set_reception(&reception)
    }

    /// How each chart receives (`reception`, one per chart of the scene's elements,
    /// `elements.charts` order). A chart that starts receiving is first given what it held
    /// back and the shots it missed; a chart that waits keeps waiting until it receives
    /// (asked to hold, it waits). Returns how many shots were shot again (those with a
    /// joining chart in front of them).
    /// Refused for a scene with mirrors or clear glass: their virtual cells are not kept
    /// for a catch-up.
    pub fn set_reception(&mut self, reception: &[Reception]) -> Result<usize, GpuError> {
        if !self.scene.specular.is_empty() {
            return Err(GpuError::Unsupported(
                "perspective-driven radiosity (receivers that wait) does not handle mirrors \
                 and clear glass yet; use `drive` global or importance"
                    .into(),
            ));
        }
        let el = &self.scene.elements;
        assert_eq!(reception.len(), el.charts.len());
        let wanted: Vec<Reception> = (0..self.upload.receivers.len())
            .map(|k| reception[el.chart[self.upload.receivers.range(k).0 as usize] as usize])
            .collect();
        let deferral = self.perspective.deferral.get_or_insert_with(|| Deferral {
            reception: vec![Reception::Receives; wanted.len()],
            held_back: false,
            missed_from: vec![0; wanted.len()],
            missed: Vec::new(),
        });
        // Charts grouped by the first shot they missed (most join together).
        let mut joining: Vec<(usize, Vec<usize>)> = Vec::new();
        // Charts that receive again after holding (or waiting: it may have held before).
        let mut released = Vec::new();
        for (k, &now) in wanted.iter().enumerate() {
            let was = deferral.reception[k];
            let now = match (was, now) {
                (Reception::Waits, Reception::Holds) => Reception::Waits,
                _ => now,
            };
            match (was, now) {
                (Reception::Receives | Reception::Holds, Reception::Waits) => {
                    deferral.missed_from[k] = deferral.missed.len();
                }
                (Reception::Waits, Reception::Receives) => {
                    let from = deferral.missed_from[k];
                    match joining.iter_mut().find(|(f, _)| *f == from) {
                        Some((_, charts)) => charts.push(k),
                        None => joining.push((from, vec![k])),
                    }
                    released.push(k);
                }
                (Reception::Holds, Reception::Receives) => released.push(k),
                _ => {}
            }
            deferral.reception[k] = now;
        }
        let holds = deferral.reception.contains(&Reception::Holds);
        let started = std::time::Instant::now();
        if holds {
            self.allocate_held_back();
        }
        self.release_held_back(&released);
        let deferral = self.perspective.deferral.as_mut().expect("set above");
        let mut given = 0;
        let missed = std::mem::take(&mut deferral.missed);
        // The shots' own phases are not counted twice.
        let before = self.stats.times;
        for (from, charts) in &joining {
            let boxes = self.upload.receivers.subset(charts);
            for shot in &missed[*from..] {
                if self.shoot_again(shot, (&boxes, charts))? {
                    given += 1;
                }
            }
        }
        self.stats.times = ShotTimes {
            catch_up: before.catch_up + started.elapsed().as_secs_f64(),
            ..before
        };
        let deferral = self.perspective.deferral.as_mut().expect("set above");
        if !deferral.any_waiting() {
            // Nobody waits: nothing missed needs keeping, nor do its maps.
            deferral.missed_from.fill(0);
            self.perspective.map_store.clear();
        } else {
            deferral.missed = missed;
        }
        Ok(given)
    }

    /// Gives the held-back buffer a record per element (zero), once.
    fn allocate_held_back(&mut self) {
        let deferral = self
            .perspective
            .deferral
            .as_mut()
            .expect("receivers deferred");
        if deferral.held_back {
            return;
        }
        deferral.held_back = true;
        let size = 16 * self.scene.elements.len().max(1) as u64;
        self.buffers.shared_buffers[HELD_BACK_BINDING] =
            self.gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("held back"),
                size,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
        self.buffers.shared =
            super::shared_bind_group(self.gpu, &self.pipelines, &self.buffers.shared_buffers);
    }

    /// Adds what the receiver charts `charts` held back to their radiosity and unshot
    /// radiosity, and clears it.
    fn release_held_back(&mut self, charts: &[usize]) {
        let allocated = self
            .perspective
            .deferral
            .as_ref()
            .is_some_and(|d| d.held_back);
        if !allocated || charts.is_empty() {
            return;
        }
        self.set_receivers(charts, &[]);
        self.write_params(u32::MAX, 0, 0, 0..0);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        self.dispatch(
            &mut enc,
            &self.pipelines.release_held_back,
            self.batching.culled.1,
            64,
        );
        self.gpu.queue.submit([enc.finish()]);
    }

    /// Limits the receivers to an area of interest that widens stage by stage (per
    /// stage, per chart of the elements, whether it receives; narrowest first, the last
    /// stage every chart): see [`GpuSolver::widen_if_due`]. A chart outside the stage
    /// holds when a stage before the last has it (it joins as the area widens), and
    /// waits when only the last has it.
    pub fn set_area_of_interest(&mut self, stages: Vec<Vec<bool>>) -> Result<(), GpuError> {
        assert!(stages.last().is_some_and(|s| s.iter().all(|&r| r)));
        let last = stages.len() - 1;
        let joins_early: Vec<bool> = (0..stages[last].len())
            .map(|k| stages[..last].iter().any(|s| s[k]))
            .collect();
        let stages: Vec<Vec<Reception>> = stages
            .iter()
            .map(|stage| {
                stage
                    .iter()
                    .zip(&joins_early)
                    .map(|(&receives, &early)| match (receives, early) {
                        (true, _) => Reception::Receives,
                        (false, true) => Reception::Holds,
                        (false, false) => Reception::Waits,
                    })
                    .collect()
            })
            .collect();
        self.set_reception(&stages[0])?;
        self.perspective.stages = Some(Stages {
            stages,
            at: 0,
            start: None,
            first_start: None,
        });
        Ok(())
    }

    /// Widens the area of interest to its next stage (giving the charts that join the
    /// shots they missed) when the selection `s` shows the stage's work done: its
    /// weighted unshot power down to [`WIDEN_AT`] of the stage's start (and, for the last
    /// stage, to [`WIDEN_LAST_AT`] of the first stage's), or nothing left to shoot. True
    /// when it widened (select again: what joined has light to shoot).
    pub fn widen_if_due(&mut self, s: &super::Selection) -> Result<bool, GpuError> {
        let Some(stages) = &mut self.perspective.stages else {
            return Ok(false);
        };
        if stages.at + 1 >= stages.stages.len() {
            return Ok(false);
        }
        let start = *stages.start.get_or_insert(s.weighted_power);
        let first = *stages.first_start.get_or_insert(s.weighted_power);
        let last = stages.at + 2 == stages.stages.len();
        let done = s.weighted_power <= WIDEN_AT * start
            && (!last || s.weighted_power <= WIDEN_LAST_AT * first);
        if s.shooter.is_some() && !done {
            return Ok(false);
        }
        stages.at += 1;
        stages.start = None;
        let next = stages.stages[stages.at].clone();
        self.set_reception(&next)?;
        Ok(true)
    }

    /// Whether every chart receives (no area of interest, or its last stage).
    pub fn area_is_whole(&self) -> bool {
        self.perspective
            .stages
            .as_ref()
            .is_none_or(|s| s.at + 1 >= s.stages.len())
    }

    /// The area of interest's stage (0: the narrowest) and how many there are.
    pub fn area_stage(&self) -> Option<(usize, usize)> {
        self.perspective
            .stages
            .as_ref()
            .map(|s| (s.at, s.stages.len()))
    }

    /// Per element, the unshot radiosity (rgb, lm/m²) with what it holds back added: all
    /// the light it will still shoot once every chart has joined ([`Reception::Holds`]:
    /// a chart that holds adds what it received to its unshot radiosity on joining). The
    /// view's ambient term stands for this light; [`GpuSolver::unshot`] alone leaves out
    /// what the charts outside the area of interest received meanwhile.
    /// Once every chart receives, nothing is held (joining released it) and only the
    /// unshot radiosity is read back.
    pub fn unshot_to_come(&self) -> Result<Vec<glam::DVec3>, GpuError> {
        let mut unshot = self.unshot()?;
        let holding = self.perspective.deferral.as_ref();
        if holding.is_some_and(|d| d.held_back && d.any_not_receiving()) {
            let held = self.read_rgb(&self.buffers.shared_buffers[HELD_BACK_BINDING])?;
            for (u, h) in unshot.iter_mut().zip(held) {
                *u += h;
            }
        }
        Ok(unshot)
    }

    /// Receiver charts that wait now.
    pub fn waiting_charts(&self) -> usize {
        self.charts_that(Reception::Waits)
    }

    /// Receiver charts that hold now.
    pub fn holding_charts(&self) -> usize {
        self.charts_that(Reception::Holds)
    }

    fn charts_that(&self, reception: Reception) -> usize {
        self.perspective.deferral.as_ref().map_or(0, |d| {
            d.reception.iter().filter(|&&r| r == reception).count()
        })
    }

    /// Shots kept for waiting receivers.
    pub fn missed_shots(&self) -> usize {
        self.perspective
            .deferral
            .as_ref()
            .map_or(0, |d| d.missed.len())
    }

    /// Keeps shot `cells` of shooter `s` for the receivers that waited (none: nothing
    /// kept).
    pub(super) fn defer(
        &mut self,
        s: usize,
        plan: ShotPlan,
        links: Links,
        delta: Vec<[f32; 4]>,
        cells: Vec<usize>,
        kept: Vec<Option<u32>>,
    ) {
        if cells.is_empty() {
            return;
        }
        if let Some(d) = &mut self.perspective.deferral {
            d.missed.push(MissedShot {
                shooter: s,
                plan,
                links,
                delta,
                cells,
                kept,
            });
        }
    }

    /// Shoots `shot` again at the receiver charts `charts` only (their hierarchy `boxes`,
    /// [`ReceiverBoxes::subset`](crate::radiosity::links::ReceiverBoxes::subset); nothing is cleared: its shooter's unshot radiosity
    /// was taken when it was first shot). False when none of them is in front of its
    /// cells (nothing to shoot).
    fn shoot_again(
        &mut self,
        shot: &MissedShot,
        (boxes, charts): (&ReceiverBoxes, &[usize]),
    ) -> Result<bool, GpuError> {
        self.gpu.queue.write_buffer(
            &self.buffers.patch_delta,
            0,
            bytemuck::cast_slice(&shot.delta),
        );
        // Only the cells with one of `charts` in front of them are drawn again, and only
        // those charts receive (as when it was first shot: the culling's own test).
        let joining = |planes: &[(glam::DVec3, glam::DVec3, f64)]| -> Vec<usize> {
            let found = boxes.charts_in_front_of_any(planes);
            found.into_iter().map(|k| charts[k]).collect()
        };
        let (cells, kept): (Vec<usize>, Vec<Option<u32>>) = shot
            .cells
            .iter()
            .zip(&shot.kept)
            .filter(|(&c, _)| !joining(&cell_planes(&shot.plan.patches[c..=c])).is_empty())
            .map(|(&c, &k)| (c, k))
            .unzip();
        if cells.is_empty() {
            return Ok(false);
        }
        let patches: Vec<_> = cells
            .iter()
            .map(|&c| shot.plan.patches[c].clone())
            .collect();
        let receivers = joining(&cell_planes(&patches));
        self.set_receivers(&receivers, &[]);
        // Specular scenes never defer ([`GpuSolver::set_receiving`]): no images.
        let images = vec![Vec::new(); cells.len()];
        self.shoot_batch(
            shot.shooter,
            &shot.plan,
            &shot.links,
            (&cells, &images),
            0..0,
            super::shot::CellMaps::Restore(&kept),
        )?;
        self.stats.drawn += kept.iter().filter(|k| k.is_none()).count();
        Ok(true)
    }
}

impl Deferral {
    /// Whether some chart waits.
    pub(super) fn any_waiting(&self) -> bool {
        self.reception.contains(&Reception::Waits)
    }

    /// Whether some chart holds or waits.
    pub(super) fn any_not_receiving(&self) -> bool {
        self.reception.iter().any(|&r| r != Reception::Receives)
    }

    /// Forgets where the missed cells' maps were kept (they are drawn again).
    pub(super) fn forget_kept_maps(&mut self) {
        for shot in &mut self.missed {
            shot.kept.fill(None);
        }
    }
}
