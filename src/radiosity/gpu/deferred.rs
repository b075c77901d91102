//! Receivers that wait (perspective-driven radiosity, Bozalina §5.2): while a chart lies
//! outside the area of interest it receives nothing, and each shot it misses is kept —
//! the shooter's cells, their links and the unshot radiosity they shot — instead of
//! Bozalina's N × N table of stored radiosity. When the chart joins the area, the shots
//! it missed are shot again at it alone, in order, so its light is what it would have
//! been had it received all along.

use super::super::links::{Links, ReceiverBoxes};
use super::super::shooters::ShotPlan;
use super::{cell_planes, GpuSolver, ShotTimes};
use crate::gpu::GpuError;

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

/// The area of interest's stages (perspective-driven radiosity), and where it stands.
pub(super) struct Stages {
    /// Per stage, per chart of the elements, whether it receives; the last: every chart.
    stages: Vec<Vec<bool>>,
    at: usize,
    /// The weighted unshot power when the stage began.
    start: Option<f64>,
}

/// The area of interest widens when the weighted unshot power has fallen to this share
/// of what it was when its stage began ("a pre-determined amount of processing",
/// Bozalina §5.1).
pub const WIDEN_AT: f64 = 0.25;

/// Which receivers wait, and what they missed.
pub(super) struct Deferral {
    /// Per receiver chart ([`super::ReceiverBoxes::range`]), whether it receives now.
    pub(super) receiving: Vec<bool>,
    /// Per waiting chart, the first shot of `missed` it has not had.
    missed_from: Vec<usize>,
    missed: Vec<MissedShot>,
}

impl GpuSolver<'_> {
    /// Which charts receive (`receiving`, one per chart of the scene's elements,
    /// `elements.charts` order); the others wait. A chart that starts receiving is first
    /// given the shots it missed. Returns how many shots were shot again (those with a
    /// joining chart in front of them).
    /// Refused for a scene with mirrors or clear glass: their virtual cells are not kept
    /// for a catch-up.
    pub fn set_receiving(&mut self, receiving: &[bool]) -> Result<usize, GpuError> {
        if !self.scene.specular.is_empty() {
            return Err(GpuError::Unsupported(
                "perspective-driven radiosity (receivers that wait) does not handle mirrors \
                 and clear glass yet; use --drive global or importance"
                    .into(),
            ));
        }
        let el = &self.scene.elements;
        assert_eq!(receiving.len(), el.charts.len());
        let wanted: Vec<bool> = (0..self.receivers.len())
            .map(|k| receiving[el.chart[self.receivers.range(k).0 as usize] as usize])
            .collect();
        let deferral = self.deferral.get_or_insert_with(|| Deferral {
            receiving: vec![true; wanted.len()],
            missed_from: vec![0; wanted.len()],
            missed: Vec::new(),
        });
        // Charts grouped by the first shot they missed (most join together).
        let mut joining: Vec<(usize, Vec<usize>)> = Vec::new();
        for (k, &now) in wanted.iter().enumerate() {
            match (deferral.receiving[k], now) {
                (true, false) => deferral.missed_from[k] = deferral.missed.len(),
                (false, true) => {
                    let from = deferral.missed_from[k];
                    match joining.iter_mut().find(|(f, _)| *f == from) {
                        Some((_, charts)) => charts.push(k),
                        None => joining.push((from, vec![k])),
                    }
                }
                _ => {}
            }
        }
        deferral.receiving = wanted;
        let mut given = 0;
        let missed = std::mem::take(&mut deferral.missed);
        let started = std::time::Instant::now();
        // The shots' own phases are not counted twice.
        let before = self.times;
        for (from, charts) in &joining {
            let boxes = self.receivers.subset(charts);
            for shot in &missed[*from..] {
                if self.shoot_again(shot, (&boxes, charts))? {
                    given += 1;
                }
            }
        }
        self.times = ShotTimes {
            catch_up: before.catch_up + started.elapsed().as_secs_f64(),
            ..before
        };
        let deferral = self.deferral.as_mut().expect("set above");
        if deferral.receiving.iter().all(|&r| r) {
            // Nobody waits: nothing missed needs keeping, nor do its maps.
            deferral.missed_from.fill(0);
            self.map_store.clear();
        } else {
            deferral.missed = missed;
        }
        Ok(given)
    }

    /// Limits the receivers to an area of interest that widens stage by stage (per
    /// stage, per chart of the elements, whether it receives; narrowest first, the last
    /// stage every chart): see [`GpuSolver::widen_if_due`].
    pub fn set_area_of_interest(&mut self, stages: Vec<Vec<bool>>) -> Result<(), GpuError> {
        assert!(stages.last().is_some_and(|s| s.iter().all(|&r| r)));
        self.set_receiving(&stages[0])?;
        self.stages = Some(Stages {
            stages,
            at: 0,
            start: None,
        });
        Ok(())
    }

    /// Widens the area of interest to its next stage (giving the charts that join the
    /// shots they missed) when the selection `s` shows the stage's work done: its
    /// weighted unshot power down to [`WIDEN_AT`] of the stage's start, or nothing left
    /// to shoot. True when it widened (select again: what joined has light to shoot).
    pub fn widen_if_due(&mut self, s: &super::Selection) -> Result<bool, GpuError> {
        let Some(stages) = &mut self.stages else {
            return Ok(false);
        };
        if stages.at + 1 >= stages.stages.len() {
            return Ok(false);
        }
        let start = *stages.start.get_or_insert(s.weighted_power);
        if s.shooter.is_some() && s.weighted_power > WIDEN_AT * start {
            return Ok(false);
        }
        stages.at += 1;
        stages.start = None;
        let next = stages.stages[stages.at].clone();
        self.set_receiving(&next)?;
        Ok(true)
    }

    /// Whether every chart receives (no area of interest, or its last stage).
    pub fn area_is_whole(&self) -> bool {
        self.stages
            .as_ref()
            .is_none_or(|s| s.at + 1 >= s.stages.len())
    }

    /// The area of interest's stage (0: the narrowest) and how many there are.
    pub fn area_stage(&self) -> Option<(usize, usize)> {
        self.stages.as_ref().map(|s| (s.at, s.stages.len()))
    }

    /// Receiver charts that wait now.
    pub fn waiting_charts(&self) -> usize {
        self.deferral
            .as_ref()
            .map_or(0, |d| d.receiving.iter().filter(|&&r| !r).count())
    }

    /// Shots kept for waiting receivers.
    pub fn missed_shots(&self) -> usize {
        self.deferral.as_ref().map_or(0, |d| d.missed.len())
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
        if let Some(d) = &mut self.deferral {
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
    /// [`super::ReceiverBoxes::subset`]; nothing is cleared: its shooter's unshot radiosity
    /// was taken when it was first shot). False when none of them is in front of its
    /// cells (nothing to shoot).
    fn shoot_again(
        &mut self,
        shot: &MissedShot,
        (boxes, charts): (&ReceiverBoxes, &[usize]),
    ) -> Result<bool, GpuError> {
        self.gpu
            .queue
            .write_buffer(&self.patch_delta, 0, bytemuck::cast_slice(&shot.delta));
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
        self.set_receivers(&receivers);
        // Specular scenes never defer ([`GpuSolver::set_receiving`]): no images.
        let images = vec![Vec::new(); cells.len()];
        self.shoot_batch(
            shot.shooter,
            &shot.plan,
            &shot.links,
            (&cells, &images),
            0..0,
            super::CellMaps::Restore(&kept),
        )?;
        self.drawn += kept.iter().filter(|k| k.is_none()).count();
        Ok(true)
    }
}

impl Deferral {
    /// Forgets where the missed cells' maps were kept (they are drawn again).
    pub(super) fn forget_kept_maps(&mut self) {
        for shot in &mut self.missed {
            shot.kept.fill(None);
        }
    }
}
