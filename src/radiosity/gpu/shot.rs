//! One shot of a [`GpuSolver`]: the shooter's cells planned and gathered, then shot in
//! batches (receivers culled per batch, maps drawn, received), which a caller may stop
//! between batches.

use super::{
    faces_per_cell, lap, unshot_magnitude, virtual_cells, GpuSolver, Reception, PATCHES_PER_BATCH,
    RECEIVER_GROUP,
};
use crate::gpu::GpuError;
use crate::radiosity::atlas::VisibilityAtlas;
use crate::radiosity::links::{Links, LINK_LEVELS};
use crate::radiosity::shooters::{cell_planes, PlannedPatch, ShotPlan};

/// How a shot's cells are cut into batches, and the receivers of the batch at work.
pub(super) struct Batching {
    /// Patches in the next batch of a shot: adapted so a batch takes about
    /// [`super::BATCH_SECONDS`] (between 1 and [`PATCHES_PER_BATCH`]).
    pub(super) batch: usize,
    /// What a batch should take, seconds ([`super::BATCH_SECONDS`] unless set).
    pub(super) batch_seconds: f64,
    /// Whether `batch` stays as set ([`GpuSolver::fix_batch`]).
    pub(super) fixed_batch: bool,
    /// The shot's receiver ranges and threads (every element of them) …
    pub(super) culled: (u32, u32),
    /// … and the ranges themselves (first element, count, 1 where they hold).
    pub(super) batch_ranges: Vec<(u32, u32, u32)>,
    /// The receivers by patch, for each drawn cell's own receivers.
    pub(super) receiver_groups: crate::radiosity::cell_receivers::ReceiverGroups,
}

/// How a batch's cells get their visibility maps.
#[derive(Clone, Copy)]
pub(super) enum CellMaps<'a> {
    /// Drawn.
    Draw,
    /// Drawn, and kept for receivers that wait ([`super::map_store`]).
    DrawAndKeep,
    /// Copied back from the kept maps where a cell has a slot (one per cell), drawn
    /// where not.
    Restore(&'a [Option<u32>]),
}

/// A batch's drawn cells in parts the atlas holds: consecutive cells whose own and
/// virtual maps (`images`, one list per cell) number at most `most`.
fn batch_parts(
    images: &[Vec<virtual_cells::VirtualCell>],
    most: usize,
) -> Result<Vec<std::ops::Range<usize>>, GpuError> {
    let mut parts = Vec::new();
    let (mut start, mut held) = (0, 0);
    for (k, list) in images.iter().enumerate() {
        let need = 1 + list.len();
        if need > most {
            return Err(GpuError::Limit(format!(
                "a cell and its {} mirror and glass images need {need} visibility maps at \
                 once; the atlas holds {most} (fewer specular surfaces facing each other, \
                 or a smaller `map_size`)",
                list.len()
            )));
        }
        if held + need > most {
            parts.push(start..k);
            (start, held) = (k, 0);
        }
        held += need;
    }
    if start < images.len() {
        parts.push(start..images.len());
    }
    Ok(parts)
}

impl<'a> GpuSolver<'a> {
    /// Shoots shooter `s` (plus the overshoot the last [`GpuSolver::select`] chose).
    pub fn shoot(&mut self, s: usize) -> Result<(), GpuError> {
        self.shoot_until(s, &|| false).map(|_| ())
    }

    /// How shooter `s` shoots now ([`Shooters::plan_shot`](crate::radiosity::shooters::Shooters::plan_shot)): each piece's cells sized by
    /// the oracle from its own unshot power ([`GpuSolver::piece_powers`]), with
    /// [`LINK_LEVELS`] coarser levels when links are on; weak curved parts merged, the
    /// weakest deferred. Its element order and cells go to the GPU, every cell's unshot
    /// radiosity is gathered there (before any is cleared), and — when there are coarse
    /// cells — read back for the links' oracle.
    fn plan(&mut self, s: usize) -> Result<(ShotPlan, Links, Vec<[f32; 4]>), GpuError> {
        let initial = self.choice.initial_power.unwrap_or(0.0);
        let budget = self.gpu_settings.cell_power * initial;
        let levels = if self.gpu_settings.link_error > 0.0 {
            LINK_LEVELS
        } else {
            0
        };
        let mut clock = std::time::Instant::now();
        let mut power = self.piece_powers(s)?;
        // Importance-weighted refinement: the cells' oracle sees a piece's power times its
        // weight.
        if let Some(w) = &self.choice.cell_weights {
            for (p, k) in power.iter_mut().zip(self.upload.shooters.pieces_of(s)) {
                *p *= w[k];
            }
        }
        lap(&mut self.stats.times.piece_powers, &mut clock);
        let plan = self.upload.shooters.plan_shot(
            self.scene,
            s,
            &power,
            budget,
            levels,
            &mut self.stats.plan_cache,
        );
        lap(&mut self.stats.times.plan, &mut clock);
        let first = self.upload.shooters.first[s];
        self.gpu.queue.write_buffer(
            &self.buffers.shooter_elements,
            4 * first as u64,
            bytemuck::cast_slice(&plan.order),
        );
        let patches: Vec<[u32; 4]> = plan
            .patches
            .iter()
            .map(|p| {
                [
                    first + p.first,
                    p.count,
                    (p.element_area as f32).to_bits(),
                    u32::from(p.parent == u32::MAX),
                ]
            })
            .collect();
        self.gpu
            .queue
            .write_buffer(&self.buffers.patches, 0, bytemuck::cast_slice(&patches));
        let cells = plan.patches.len() as u32;
        self.write_params(s as u32, 0, cells, 0..0);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        self.dispatch(&mut enc, &self.pipelines.gather, cells, 1);
        self.gpu.queue.submit([enc.finish()]);
        // Read back for the links' oracle, and to be shot again later when receivers
        // wait (perspective-driven radiosity).
        let coarse = plan.patches.iter().any(|p| p.level > 0);
        let waiting = self
            .perspective
            .deferral
            .as_ref()
            .is_some_and(|d| d.any_waiting());
        let delta: Vec<[f32; 4]> = if coarse || waiting {
            let d = self
                .gpu
                .read_f32_prefix(&self.buffers.patch_delta, 16 * cells as u64)?;
            d.chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect()
        } else {
            Vec::new()
        };
        let radiosity: Vec<f64> = if coarse {
            delta.iter().map(unshot_magnitude).collect()
        } else {
            vec![0.0; plan.patches.len()]
        };
        lap(&mut self.stats.times.gather, &mut clock);
        let epsilon = self.gpu_settings.link_error * initial / self.scene.total_area.max(1e-300);
        let receivers = self
            .choice
            .link_receivers
            .as_ref()
            .unwrap_or(&self.upload.receivers);
        let links = crate::radiosity::links::link(&plan, &radiosity, receivers, epsilon);
        lap(&mut self.stats.times.links, &mut clock);
        Ok((plan, links, delta))
    }

    /// Per piece of shooter `s`, its unshot power (with the overshoot), lm: summed on the
    /// GPU over the pieces' elements (laid out piece after piece again first) and read
    /// back. A lone piece's is the selection's.
    fn piece_powers(&mut self, s: usize) -> Result<Vec<f64>, GpuError> {
        let pieces = self.upload.shooters.pieces_of(s);
        if pieces.len() == 1 {
            return Ok(vec![self.choice.last_power]);
        }
        let first = self.upload.shooters.first[s];
        self.gpu.queue.write_buffer(
            &self.buffers.shooter_elements,
            4 * first as u64,
            bytemuck::cast_slice(self.upload.shooters.elements_of(s)),
        );
        let records: Vec<[u32; 4]> = pieces
            .clone()
            .map(|p| {
                let piece = &self.upload.shooters.pieces[p];
                [piece.first, piece.count, 1f32.to_bits(), 0]
            })
            .collect();
        self.gpu
            .queue
            .write_buffer(&self.buffers.patches, 0, bytemuck::cast_slice(&records));
        let count = records.len() as u32;
        self.write_params(s as u32, 0, count, 0..0);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        self.dispatch(&mut enc, &self.pipelines.gather, count, 1);
        self.gpu.queue.submit([enc.finish()]);
        let sums = self
            .gpu
            .read_f32_prefix(&self.buffers.patch_delta, 16 * u64::from(count))?;
        Ok(sums
            .chunks_exact(4)
            .map(|d| unshot_magnitude(&[d[0], d[1], d[2], d[3]]))
            .collect())
    }

    /// [`GpuSolver::shoot`] in batches of top cells (drawing at most
    /// [`PATCHES_PER_BATCH`] visibility maps, sized so one takes about 50 ms), asking
    /// `stop` between batches (once the GPU has finished the batch before the one it
    /// works on: the CPU culls and records the next batch meanwhile): a shooter of
    /// thousands of patches no longer overruns a time limit or Ctrl-C by more than two
    /// batches. Every shot element loses its unshot radiosity before the first batch (a
    /// shooter's pieces light each other: light one takes from another during the shot
    /// stays unshot) and the GPU holds it; a shot stopped early gives the elements of the
    /// cells it did not shoot what it held back, so energy is neither lost nor counted
    /// twice. True when the whole shooter was shot.
    pub fn shoot_until(&mut self, s: usize, stop: &dyn Fn() -> bool) -> Result<bool, GpuError> {
        let (plan, links, delta) = self.plan(s)?;
        // The cells shot while some receiver in front of them waited.
        let mut missed = Vec::new();
        // Where their maps were kept (per missed cell; `None`: drawn again to catch up).
        let mut kept = Vec::new();
        // Top cells and their subtrees (depth first: a subtree runs to the next top).
        let tops: Vec<usize> = (0..plan.patches.len())
            .filter(|&k| plan.patches[k].parent == u32::MAX)
            .collect();
        let subtree_end = |t: usize| tops.get(t + 1).copied().unwrap_or(plan.patches.len());
        let mut t = 0;
        // The batch before the one just submitted: the CPU culls and records the next
        // batch while the GPU works on this one, and waits only for the one before.
        let mut previous: Option<wgpu::SubmissionIndex> = None;
        while t < tops.len() {
            let started = std::time::Instant::now();
            let mut drawn = Vec::new();
            let from = t;
            // A batch's cells may face many ways (a curved piece, the pieces of a vault):
            // its receivers are culled to the front of any of their planes. Batches of
            // one facing were each one GPU round trip per cell on a curved model (2.5 ms
            // a cell on an H200 whatever the map size: the cathedral's shots).
            while t < tops.len() && (t == from || drawn.len() < self.batching.batch) {
                drawn.extend((tops[t]..subtree_end(t)).filter(|&k| links.drawn[k]));
                t += 1;
            }
            let mut clock = std::time::Instant::now();
            let images: Vec<Vec<virtual_cells::VirtualCell>> = drawn
                .iter()
                .map(|&k| self.virtual_cells(&plan.patches[k]))
                .collect();
            let imaged: Vec<PlannedPatch> =
                images.iter().flatten().map(|v| v.planned.clone()).collect();
            let waiting = self.cull(&plan.patches[tops[from]..subtree_end(t - 1)], &imaged);
            lap(&mut self.stats.times.cull, &mut clock);
            let clear = if from == 0 { 0..plan.shot } else { 0..0 };
            let maps = if waiting && self.perspective.map_store.is_enabled() {
                CellMaps::DrawAndKeep
            } else {
                CellMaps::Draw
            };
            let batch = (drawn.as_slice(), images.as_slice());
            let (submitted, slots) = self.shoot_batch(s, &plan, &links, batch, clear, maps)?;
            lap(&mut self.stats.times.record, &mut clock);
            if waiting {
                missed.extend_from_slice(&drawn);
                kept.extend(slots);
            }
            let cells: usize = (tops[from]..subtree_end(t - 1)).count();
            self.stats.drawn += drawn.len();
            self.stats.virtual_drawn += imaged.len();
            self.stats.skipped += cells - drawn.len();
            if t < tops.len() {
                if let Some(index) = previous.replace(submitted) {
                    self.gpu.wait_for(index)?;
                }
                lap(&mut self.stats.times.batch_wait, &mut clock);
                // Twice as many next time while well under the target, half when over.
                let took = started.elapsed().as_secs_f64();
                if self.batching.fixed_batch {
                } else if took < 0.5 * self.batching.batch_seconds {
                    self.batching.batch = (self.batching.batch * 2).min(PATCHES_PER_BATCH);
                } else if took > self.batching.batch_seconds {
                    self.batching.batch = (self.batching.batch / 2).max(1);
                }
                if stop() {
                    self.restore(s, tops[t], plan.patches.len());
                    self.stats.shots += 1;
                    self.defer(s, plan, links, delta, missed, kept);
                    return Ok(false);
                }
            }
        }
        self.stats.shots += 1;
        self.defer(s, plan, links, delta, missed, kept);
        Ok(true)
    }

    /// The virtual cells of `cell` ([`virtual_cells`]): none without specular windows.
    fn virtual_cells(&self, cell: &PlannedPatch) -> Vec<virtual_cells::VirtualCell> {
        if self.scene.specular.is_empty() {
            return Vec::new();
        }
        virtual_cells::virtual_cells(&self.scene.specular, cell)
    }

    /// Receiver culling for the cells `patches` and their virtual cells `imaged`: only the
    /// charts in front of one of their planes receive (their element ranges follow the
    /// cells in the patch buffer), and of those only the ones not waiting, the ones that
    /// hold into the held-back buffer ([`GpuSolver::set_reception`]). True when some
    /// chart in front waits.
    fn cull(&mut self, patches: &[PlannedPatch], imaged: &[PlannedPatch]) -> bool {
        let deferral = self
            .perspective
            .deferral
            .as_ref()
            .filter(|d| d.any_not_receiving());
        // Exact where receivers wait or hold (perspective-driven: what is skipped is
        // caught up later), else by groups of charts: a superset, far cheaper on many
        // tiny charts.
        let group = if deferral.is_some() {
            1
        } else {
            RECEIVER_GROUP
        };
        let mut planes = cell_planes(patches);
        planes.extend(cell_planes(imaged));
        let mut charts = self
            .upload
            .receivers
            .charts_roughly_in_front_of_any(&planes, group);
        let in_front = charts.len();
        let mut holding = Vec::new();
        if let Some(d) = deferral {
            let mut receiving = Vec::with_capacity(charts.len());
            for k in charts {
                match d.reception[k] {
                    Reception::Receives => receiving.push(k),
                    Reception::Holds => holding.push(k),
                    Reception::Waits => {}
                }
            }
            charts = receiving;
        }
        let taking = charts.len() + holding.len();
        self.set_receivers(&charts, &holding);
        taking < in_front
    }

    /// The receivers of the next batch: the elements of `charts` and of `holding` (which
    /// keep what they receive back: [`Reception::Holds`]), receiver indices, as
    /// [`ReceiverBoxes::merged_ranges`](crate::radiosity::links::ReceiverBoxes::merged_ranges).
    pub(super) fn set_receivers(&mut self, charts: &[usize], holding: &[usize]) {
        let mut threads = 0u32;
        self.batching.batch_ranges.clear();
        let records: Vec<[u32; 4]> = [(charts, 0), (holding, 1)]
            .into_iter()
            .flat_map(|(charts, hold)| {
                self.upload
                    .receivers
                    .merged_ranges(charts)
                    .into_iter()
                    .map(move |range| (range, hold))
            })
            .map(|((first, count), hold)| {
                self.batching.batch_ranges.push((first, count, hold));
                let r = [first, threads, 0, hold];
                threads += count;
                r
            })
            .collect();
        if !records.is_empty() {
            self.gpu.queue.write_buffer(
                &self.buffers.patches,
                16 * self.upload.max_patches as u64,
                bytemuck::cast_slice(&records),
            );
        }
        self.batching.culled = (records.len() as u32, threads);
    }

    /// Gives the elements of the top cells among patches `first..end` of shooter `s`'s
    /// plan the unshot radiosity the shot's clear held (a shot stopped before them).
    fn restore(&self, s: usize, first: usize, end: usize) {
        let count = (end - first) as u32;
        self.write_params(s as u32, first as u32, count, 0..0);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        self.dispatch(&mut enc, &self.pipelines.restore, count, 1);
        self.gpu.queue.submit([enc.finish()]);
    }

    /// Shoots the cells `drawn` of shooter `s`'s `plan` with their virtual cells (one
    /// list per drawn cell), first clearing the unshot radiosity of the elements `clear`
    /// (a range of the plan's order): their maps in one render pass (as many cells at a
    /// time as the atlas holds, each with its virtual cells), then their receive
    /// dispatches in one compute pass; `maps` says whether they are drawn, kept or
    /// copied back. Returns each drawn cell's slot among the kept maps (`None`: not kept).
    pub(super) fn shoot_batch(
        &mut self,
        s: usize,
        plan: &ShotPlan,
        links: &Links,
        (drawn, images): (&[usize], &[Vec<virtual_cells::VirtualCell>]),
        clear: std::ops::Range<u32>,
        maps: CellMaps<'_>,
    ) -> Result<(wgpu::SubmissionIndex, Vec<Option<u32>>), GpuError> {
        let stored = match maps {
            CellMaps::Restore(stored) => stored,
            _ => &[],
        };
        let first = self.upload.shooters.first[s];
        let cells = plan.patches.len() as u32;
        self.write_params(s as u32, 0, cells, first + clear.start..first + clear.end);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        if !clear.is_empty() {
            self.dispatch(&mut enc, &self.pipelines.clear, clear.len() as u32, 64);
        }
        let faces = faces_per_cell(self.gpu_settings.visibility);
        let most = (VisibilityAtlas::max_tiles(self.gpu, self.atlas.size) / faces).max(1) as usize;
        let mut slots = Vec::new();
        for range in batch_parts(images, most)? {
            let part = &drawn[range.clone()];
            let cells = part.len() + images[range.clone()].iter().map(Vec::len).sum::<usize>();
            self.atlas.reserve(self.gpu, cells as u32 * faces);
            let part_stored = stored.get(range.start..range.end.min(stored.len()));
            let part_images = &images[range];
            let batch = (part, part_images);
            self.record_part(&mut enc, plan, links, batch, part_stored.unwrap_or(&[]))?;
            if matches!(maps, CellMaps::DrawAndKeep) {
                for k in 0..part.len() as u32 {
                    let slot = self.perspective.map_store.allocate(
                        self.gpu,
                        &mut enc,
                        self.atlas.size,
                        faces,
                    );
                    if let Some(at) = slot {
                        let cell = (k * faces, at, faces);
                        self.perspective
                            .map_store
                            .copy_cell(&mut enc, &self.atlas, cell, true);
                    }
                    slots.push(slot);
                }
            }
        }
        if !matches!(maps, CellMaps::DrawAndKeep) {
            slots = vec![None; drawn.len()];
        }
        Ok((self.gpu.queue.submit([enc.finish()]), slots))
    }
}
