//! The GPU solver: element arrays in storage buffers; per shot the shooter (a triangle or
//! a flat face cluster, [`super::shooters`]) is chosen on the GPU by reduction (only a
//! 48-byte selection record is read back), its patches' unshot radiosity gathered
//! (substructuring), and per batch of patches their visibility maps rendered (hemicube or
//! stereographic) side by side in one atlas ([`super::atlas`]) and every element in front
//! of them updated, one compute dispatch per patch.

use glam::{DVec3, Vec3};

use super::atlas::VisibilityAtlas;
use super::links::DEFAULT_LINK_ERROR;
use super::scene::RadiosityScene;
use super::shooters::{cell_planes, Hierarchy, PlanCache, Shooters, DEFAULT_CELL_POWER};
use super::{Ambient, SolverSettings};
use crate::gpu::{Gpu, GpuError};
use pipelines::{shared_bind_group, Pipelines};

mod chunks;
mod deferred;
mod map_store;
mod masked;
mod pipelines;
mod raster;
mod record;
mod relight;
mod setup;
mod shot;
mod timers;
mod virtual_cells;

pub use chunks::{MeshChunks, TileView};
pub use deferred::{Reception, WIDEN_AT};
pub use map_store::DEFAULT_MAP_STORE_BYTES;
pub use raster::Raster;
pub use timers::GpuPassSeconds;

/// How a shooting patch sees what it can reach.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Visibility {
    /// Five perspective faces (Cohen and Greenberg): exact projection, five renders.
    #[default]
    Hemicube,
    /// The stereographic projection of the hemisphere (Wallner §2.3; Coombe et al.): one
    /// map. Drawn by compute shaders it is exact (each texel's ray tested in 3-D); the
    /// render pipeline projects only vertices, so it draws chords where edges project to
    /// arcs ([`Raster`]).
    Stereographic,
}

/// GPU-only options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpuSettings {
    /// Visibility maps.
    pub visibility: Visibility,
    /// Side of a hemicube face or of the stereographic map, texels.
    pub map_size: u32,
    /// Relative depth tolerance of the visibility test: an occluder nearer than the
    /// receiver by less than this share of its distance does not shadow it.
    pub tolerance: f32,
    /// Who shoots: triangles, or flat face clusters.
    pub hierarchy: Hierarchy,
    /// With clusters: the largest share of the initial unshot power one shooting cell
    /// may carry (smaller: finer cells, slower and closer to the flat solution).
    pub cell_power: f64,
    /// With clusters: the irradiance error a receiver accepts from a coarse cell, as a
    /// share of the mean initial exitance ([`super::links`]); 0 links every receiver to
    /// the finest cells.
    pub link_error: f64,
    /// Each visibility face draws only the chunks of the mesh its view can hold
    /// ([`MeshChunks`]; the same maps); false draws the whole mesh every time (the
    /// reference).
    pub chunk_culling: bool,
    /// How the maps are drawn: the render pipeline, or compute shaders on every unit of
    /// the GPU ([`Raster`]).
    pub raster: Raster,
}

impl Default for GpuSettings {
    fn default() -> GpuSettings {
        GpuSettings {
            visibility: Visibility::Hemicube,
            map_size: 256,
            tolerance: 0.01,
            hierarchy: Hierarchy::None,
            cell_power: DEFAULT_CELL_POWER,
            link_error: DEFAULT_LINK_ERROR,
            chunk_culling: true,
            raster: Raster::Auto,
        }
    }
}

/// An element's records on the GPU, each in its own binding: position and area; normal
/// and piece (its shooter's reflectance is the element's; it does not receive from a
/// cell that shoots its piece). With radiosity and unshot radiosity
/// they are the solver's per-element buffers, none wider than this.
type ElementRecord = [f32; 4];
const _: () = assert!(
    std::mem::size_of::<ElementRecord>() as u64 == crate::render::limits::RADIOSITY_ELEMENT_BYTES
);

/// Where a solver's shots spend their time, seconds of wall clock on the thread that
/// drives it, by phase (`bench radiosity --json`: `phase_seconds`). A phase that reads
/// from the GPU also waits there for the work submitted before it.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct ShotTimes {
    /// Choosing the shooter: the reduction and the read-back of its record (waits for
    /// the last shot's GPU work).
    pub select: f64,
    /// A shooter of several pieces: each piece's unshot power, summed on the GPU and read
    /// back.
    pub piece_powers: f64,
    /// Planning the shot's cells on the CPU ([`Shooters::plan_shot`]; a unit planned
    /// before is copied from [`GpuSolver::plan_cache`]).
    pub plan: f64,
    /// Gathering the cells' unshot radiosity on the GPU, and reading it back where the
    /// links or waiting receivers need it.
    pub gather: f64,
    /// Linking receivers to cells on the CPU ([`super::links::link`]).
    pub links: f64,
    /// Culling the receivers of each batch on the CPU.
    pub cull: f64,
    /// Recording and submitting each batch's maps and receive passes.
    pub record: f64,
    /// Waiting for a batch before the next (so a shot can stop between batches).
    pub batch_wait: f64,
    /// Perspective-driven radiosity: giving the charts that join the area of interest
    /// the shots they missed (their culls, maps and receive passes).
    pub catch_up: f64,
}

impl ShotTimes {
    /// The sum of the phases, seconds.
    pub fn total(&self) -> f64 {
        self.select
            + self.piece_powers
            + self.plan
            + self.gather
            + self.links
            + self.cull
            + self.record
            + self.batch_wait
            + self.catch_up
    }
}

/// Adds the seconds since `since` to `phase` and restarts the clock.
fn lap(phase: &mut f64, since: &mut std::time::Instant) {
    let now = std::time::Instant::now();
    *phase += (now - *since).as_secs_f64();
    *since = now;
}

/// Receiver culling takes a subtree of at most this many charts whole where its box is
/// in front of a cell ([`ReceiverBoxes::charts_roughly_in_front_of_any`](super::links::ReceiverBoxes::charts_roughly_in_front_of_any)).
const RECEIVER_GROUP: u32 = 16;
/// The least receiver weight [`GpuSolver::set_receiver_weights`] takes: reaches at least
/// a hundredth of what they are.
pub const LEAST_RECEIVER_WEIGHT: f64 = 1e-4;
/// The receivers' reach scales' binding in the solver's bind group 0 (radiosity.wgsl).
const REACH_SCALE_BINDING: usize = 13;

/// Most patches shot per GPU submission; the solver may stop between batches.
pub const PATCHES_PER_BATCH: usize = 64;
/// Patches in a solver's first batch (then adapted to the machine and scene).
const FIRST_BATCH: usize = 4;
/// The time a batch should take, seconds: how far a time limit or Ctrl-C may be overrun.
pub const BATCH_SECONDS: f64 = 0.05;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SolveParams {
    element_count: u32,
    shooter_count: u32,
    shooter: u32,
    overshoot: u32,
    patch_first: u32,
    patch_count: u32,
    total_area: f32,
    mean_reflectance: f32,
    clear_first: u32,
    clear_count: u32,
    range_count: u32,
    range_total: u32,
    range_first: u32,
    large_shooters: u32,
    receiving_normals: u32,
    _pad: u32,
}

/// The shooter the GPU chose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Selection {
    /// The shooter (see [`GpuSolver::shooters`]), `None` when nothing is left to shoot.
    pub shooter: Option<usize>,
    /// Its unshot power (with overshoot), lm (luminance).
    pub power: f64,
    /// Σ |unshot luminance| × area over all elements, lm.
    pub unshot_power: f64,
    /// The same sum with each shooter's power times its weight
    /// ([`GpuSolver::set_shooter_weights`]; without weights, `unshot_power`).
    pub weighted_power: f64,
}

/// A solution in progress on the GPU, in parts each owned by a stage: the buffers and
/// their bind group ([`setup`]), the shooters' records and how the selection weighs them
/// ([`GpuSolver::select`]), the batching of a shot's cells ([`shot`]), the
/// perspective-driven state ([`deferred`]) and the counters ([`ShotStats`]).
pub struct GpuSolver<'a> {
    gpu: &'a Gpu,
    scene: &'a RadiosityScene,
    settings: SolverSettings,
    gpu_settings: GpuSettings,
    /// Built once per device ([`Gpu::cached`]).
    pipelines: std::sync::Arc<Pipelines>,
    /// The solution's and the shot's buffers, and the bind group over them.
    buffers: setup::Buffers,
    /// What solvers of this scene share: shooters, element records, visibility mesh,
    /// receivers' boxes ([`GpuSolver::sibling`]).
    upload: setup::SceneUpload,
    /// The shooters' records and the selection's weights.
    choice: ShooterChoice,
    /// The compute rasterizer, where the maps are drawn by compute shaders.
    compute_raster: Option<raster::ComputeRaster>,
    /// The visibility maps of a batch.
    atlas: VisibilityAtlas,
    /// How a shot's cells are cut into batches, and the current batch's receivers.
    batching: shot::Batching,
    /// Perspective-driven radiosity: waiting receivers, stages and stored maps.
    perspective: deferred::Perspective,
    /// The GPU's timestamps around each batch's passes ([`GpuSolver::time_passes`]).
    timers: Option<timers::PassTimers>,
    /// What the shots did so far, and where their time went.
    pub stats: ShotStats,
}

/// The shooters' records as uploaded and how the selection weighs them.
struct ShooterChoice {
    /// The shooters' records as uploaded (their weights in `[2]`).
    shooter_info: Vec<ShooterRecord>,
    /// Shooters of more than [`SMALL_SHOOTER`] elements (a workgroup sums each).
    large_shooters: u32,
    /// Whether the selection weighs the shooters ([`GpuSolver::set_shooter_weights`]).
    weighted: bool,
    /// Per piece of the shooters, the share of its unshot power the cells' oracle sizes
    /// its cells by ([`GpuSolver::set_cell_weights`]; none: all of it).
    cell_weights: Option<Vec<f64>>,
    /// The link search's receivers in boxes of a few elements with their reach scales
    /// ([`GpuSolver::set_receiver_weights`]; none: the charts', every scale 1).
    link_receivers: Option<crate::radiosity::links::ReceiverBoxes>,
    /// The first selection's total unshot power, lm (the oracle's scale).
    initial_power: Option<f64>,
    /// The last selection's shooter power, lm.
    last_power: f64,
}

/// What the shots of a [`GpuSolver`] did so far, and where their time went.
#[derive(Debug)]
pub struct ShotStats {
    /// Shots so far.
    pub shots: usize,
    /// Visibility-mesh triangles drawn so far, over all faces of all maps.
    pub triangles_drawn: u64,
    /// Receiver threads dispatched so far (elements in front of the shooters, per map).
    pub receiver_threads: u64,
    /// Visibility maps drawn so far (one per drawn cell or patch).
    pub drawn: usize,
    /// Cells or patches whose visibility map was skipped so far: no receiver takes light
    /// from them (behind the shooter, or linked to a coarser or finer cell).
    pub skipped: usize,
    /// Virtual cells' visibility maps drawn so far (mirrors and clear glass).
    pub virtual_drawn: usize,
    /// Where the shots' time went so far (wall clock on the calling thread).
    pub times: ShotTimes,
    /// The shooting units planned so far, for shots that repeat their layout.
    pub plan_cache: PlanCache,
}

/// The longest edge of the stereographic map's mesh, as a fraction of the scene's
/// diagonal: in the room with a box the power one shot delivers converges by 1/24 (1/8:
/// −2.0 %, 1/16: −0.9 %, 1/24 and 1/32: the map's resolution's own +0.3 % at 512²).
pub const STEREOGRAPHIC_EDGE_FRACTION: f64 = 1.0 / 32.0;

/// Visibility maps (tiles of the atlas) per shooting cell.
fn faces_per_cell(visibility: Visibility) -> u32 {
    match visibility {
        Visibility::Hemicube => 5,
        Visibility::Stereographic => 1,
    }
}

/// Shooters of at most this many elements are summed by one GPU thread each (in f32, and
/// llvmpipe ends a thread's loops after 65 535 iterations); larger ones by a workgroup.
/// `SMALL_SHOOTER` in radiosity.wgsl.
const SMALL_SHOOTER: u32 = 1024;

/// A shooter's record as the shader reads it (`ShooterInfo`): first element, element
/// count, weight (f32 bits), first piece; reflectance (RGB) and area; transmittance (RGB)
/// and a pad.
type ShooterRecord = [u32; 12];

/// Bytes between the visibility faces' records of a batch (`FaceGpu` in record.rs): the
/// render passes bind each at a dynamic offset, the compute rasterizer reads them as an
/// array.
const FACE_STRIDE: u64 = 256;

/// Most workgroups along one dimension of a dispatch (WebGPU's limit).
const MAX_GROUPS_X: u32 = 65_535;

/// Dispatches `groups` workgroups (at least one), in rows of at most [`MAX_GROUPS_X`]: the
/// shaders number them row by row (`linear_group`, `linear_thread` in radiosity.wgsl).
fn dispatch_groups(pass: &mut wgpu::ComputePass<'_>, groups: u32) {
    let groups = groups.max(1);
    let rows = groups.div_ceil(MAX_GROUPS_X);
    pass.dispatch_workgroups(groups.div_ceil(rows), rows, 1);
}

/// How much a gathered cell or piece shoots (`gather_patches`: rgb the unshot radiosity,
/// w the mean |unshot luminance|): the larger of its signed luminance and w, so light of
/// both signs (a relit solution, [`GpuSolver::relight`]) does not cancel.
fn unshot_magnitude(d: &[f32; 4]) -> f64 {
    let signed = super::scene::luminance(DVec3::new(d[0] as f64, d[1] as f64, d[2] as f64));
    signed.abs().max(d[3] as f64)
}

fn v4(v: DVec3, w: f32) -> [f32; 4] {
    let v = v.as_vec3();
    [v.x, v.y, v.z, w]
}

impl<'a> GpuSolver<'a> {
    fn write_params(
        &self,
        shooter: u32,
        patch_first: u32,
        patch_count: u32,
        clear: std::ops::Range<u32>,
    ) {
        let el = &self.scene.elements;
        let p = SolveParams {
            element_count: el.len() as u32,
            shooter_count: self.upload.shooters.len() as u32,
            shooter,
            overshoot: u32::from(self.settings.ambient == Ambient::Overshoot),
            patch_first,
            patch_count,
            total_area: self.scene.total_area as f32,
            mean_reflectance: self.scene.mean_reflectance as f32,
            clear_first: clear.start,
            clear_count: clear.len() as u32,
            range_count: self.batching.culled.0,
            range_total: self.batching.culled.1,
            range_first: self.upload.max_patches as u32,
            large_shooters: self.choice.large_shooters,
            receiving_normals: u32::from(!self.scene.receiving_normals.is_empty()),
            _pad: 0,
        };
        self.gpu
            .queue
            .write_buffer(&self.buffers.params, 0, bytemuck::bytes_of(&p));
    }

    /// Runs `pipeline` over `threads` threads in groups of `group` (a group per item for
    /// the passes that sum with one workgroup each: `group` 1).
    fn dispatch(
        &self,
        enc: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::ComputePipeline,
        threads: u32,
        group: u32,
    ) {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &self.buffers.shared, &[]);
        dispatch_groups(&mut pass, threads.div_ceil(group));
    }

    /// Chooses the next shooter on the GPU (reduction over the shooters).
    pub fn select(&mut self) -> Result<Selection, GpuError> {
        let mut clock = std::time::Instant::now();
        self.write_params(u32::MAX, 0, 0, 0..0);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        let shooters = self.upload.shooters.len() as u32;
        self.dispatch(&mut enc, &self.pipelines.shooter_sums, shooters, 64);
        self.dispatch(
            &mut enc,
            &self.pipelines.large_shooter_sums,
            self.choice.large_shooters,
            1,
        );
        self.dispatch(&mut enc, &self.pipelines.select, 1, 1);
        // Only the 48-byte selection record comes back.
        enc.copy_buffer_to_buffer(
            &self.buffers.shooter_power,
            16 * shooters as u64,
            &self.buffers.selection,
            0,
            48,
        );
        self.gpu.queue.submit([enc.finish()]);
        let v = self.gpu.read_f32(&self.buffers.selection)?;
        lap(&mut self.stats.times.select, &mut clock);
        let index = v[0].to_bits();
        let shooter = (index != u32::MAX && v[1] > 0.0).then_some(index as usize);
        // The shader's choice is by weighted power; the shot's cells are sized by the
        // power itself.
        let weight = shooter.map_or(1.0, |k| f32::from_bits(self.choice.shooter_info[k][2]));
        let selection = Selection {
            shooter,
            power: (v[1] / weight) as f64,
            unshot_power: v[2] as f64,
            weighted_power: v[3] as f64,
        };
        self.choice
            .initial_power
            .get_or_insert(selection.unshot_power);
        self.choice.last_power = selection.power;
        Ok(selection)
    }

    /// Weighs each shooter's unshot power by `weights` (one per shooter, ≥ 0) in the
    /// selection and in [`Selection::weighted_power`]: importance-driven shooting.
    pub fn set_shooter_weights(&mut self, weights: &[f64]) {
        assert_eq!(weights.len(), self.upload.shooters.len());
        for (record, w) in self.choice.shooter_info.iter_mut().zip(weights) {
            record[2] = (w.max(0.0) as f32).to_bits();
        }
        self.gpu.queue.write_buffer(
            &self.buffers.shooter_buf,
            0,
            bytemuck::cast_slice(&self.choice.shooter_info),
        );
        self.choice.weighted = true;
    }

    /// Sizes each piece's cells by `weights` (one per piece of the shooters, in (0, 1])
    /// times its unshot power: importance-weighted refinement, coarser cells where the
    /// light they shoot matters little to the view.
    pub fn set_cell_weights(&mut self, weights: Vec<f64>) {
        assert_eq!(weights.len(), self.upload.shooters.pieces.len());
        self.choice.cell_weights = Some(weights);
    }

    /// Gives each receiver its share of the link error, `weights` (one per element, in
    /// (0, 1]; Smits, Arvo and Salesin's importance-driven link error on the receiving
    /// side): a receiver of weight w (at least [`LEAST_RECEIVER_WEIGHT`]) takes a coarse
    /// cell's light where its error is below ε / w, so its reaches are scaled by √w
    /// ([`Links::reach_for`](crate::radiosity::links::Links::reach_for)), on the GPU and in
    /// the link search, which then asks boxes of a few elements
    /// ([`ReceiverBoxes::of_elements`](crate::radiosity::links::ReceiverBoxes::of_elements)).
    pub fn set_receiver_weights(&mut self, weights: &[f64]) {
        assert_eq!(weights.len(), self.scene.elements.len());
        let scale: Vec<f64> = weights
            .iter()
            .map(|w| w.clamp(LEAST_RECEIVER_WEIGHT, 1.0).sqrt())
            .collect();
        self.batching.receiver_groups.set_scales(&scale);
        let gpu_scale: Vec<f32> = scale.iter().map(|&s| s as f32).collect();
        if !gpu_scale.is_empty() {
            self.gpu.queue.write_buffer(
                &self.buffers.shared_buffers[REACH_SCALE_BINDING],
                0,
                bytemuck::cast_slice(&gpu_scale),
            );
        }
        self.choice.link_receivers = Some(crate::radiosity::links::ReceiverBoxes::of_elements(
            self.scene, &scale,
        ));
    }

    /// Sizes the batches of a shot to take about `seconds` each (default [`BATCH_SECONDS`],
    /// at most that): a shot stopped by [`GpuSolver::shoot_until`] overruns its stop by
    /// at most about one batch (the viewer's per-frame budget).
    pub fn set_batch_seconds(&mut self, seconds: f64) {
        self.batching.batch_seconds = seconds.clamp(1e-3, BATCH_SECONDS);
    }

    /// Shoots `cells` cells per batch from now on, whatever they take (at least 1, at
    /// most [`PATCHES_PER_BATCH`]), instead of adapting the batch to the clock: two runs
    /// then split their shots alike, for comparisons that must be exact. (Where a cell's
    /// maps lie in the atlas follows the batch, and rasterization at another place in
    /// the atlas may flip a texel along an edge seen at a grazing angle: a receiver
    /// there may differ by a percent between runs, the total by about 10⁻⁷.)
    pub fn fix_batch(&mut self, cells: usize) {
        self.batching.batch = cells.clamp(1, PATCHES_PER_BATCH);
        self.batching.fixed_batch = true;
    }

    /// The scene it solves.
    pub fn scene(&self) -> &RadiosityScene {
        self.scene
    }

    /// The share of the elements each visibility map's receive pass took in, on average
    /// (the rest culled as behind or outside the shooter), 0..=1.
    pub fn receiver_share(&self) -> f64 {
        let maps = (self.stats.drawn + self.stats.virtual_drawn).max(1) as f64;
        self.stats.receiver_threads as f64 / (maps * self.scene.elements.len().max(1) as f64)
    }

    /// Whether the selection weighs the shooters.
    pub fn is_weighted(&self) -> bool {
        self.choice.weighted
    }

    /// Triangles each visibility map draws (the casters with CAD fans merged).
    pub fn visibility_triangles(&self) -> usize {
        self.upload.index_count as usize / 3
    }

    /// How its maps are drawn ([`GpuSettings::raster`] as resolved for this GPU and
    /// scene: never [`Raster::Auto`]).
    pub fn raster(&self) -> Raster {
        self.gpu_settings.raster
    }

    /// The shooters: triangles, or flat face clusters ([`GpuSettings::hierarchy`]).
    pub fn shooters(&self) -> &Shooters {
        &self.upload.shooters
    }

    /// Keeps this many bytes of maps at most for the catch-up of waiting receivers (0:
    /// none; missed cells are then drawn again), dropping what is kept now.
    pub fn set_map_store_bytes(&mut self, bytes: u64) {
        self.perspective.map_store = map_store::MapStore::new(bytes);
        if let Some(d) = &mut self.perspective.deferral {
            d.forget_kept_maps();
        }
    }

    /// Maps copied back from the kept maps for a catch-up so far (not drawn).
    pub fn maps_reused(&self) -> usize {
        self.perspective.map_store.reused
    }

    /// Times each batch's visibility and receive passes by the GPU's own clock from now
    /// on ([`GpuSolver::gpu_pass_seconds`]). False (and nothing timed) where the device
    /// has no timestamp queries.
    pub fn time_passes(&mut self) -> bool {
        if self.timers.is_none() {
            self.timers = timers::PassTimers::new(self.gpu);
        }
        self.timers.is_some()
    }

    /// The GPU's seconds in the timed passes so far (`None` unless
    /// [`GpuSolver::time_passes`] holds): waits for the GPU.
    pub fn gpu_pass_seconds(&mut self) -> Result<Option<GpuPassSeconds>, GpuError> {
        match &mut self.timers {
            Some(t) => {
                t.read_back(self.gpu)?;
                Ok(Some(t.seconds))
            }
            None => Ok(None),
        }
    }

    /// One shot: select, then shoot. False when nothing is left.
    pub fn step(&mut self) -> Result<Option<Selection>, GpuError> {
        let s = self.select()?;
        match s.shooter {
            Some(t) => {
                self.shoot(t)?;
                Ok(Some(s))
            }
            None => Ok(None),
        }
    }

    fn read_rgb(&self, buffer: &wgpu::Buffer) -> Result<Vec<DVec3>, GpuError> {
        let v = self.gpu.read_f32(buffer)?;
        Ok(v.chunks_exact(4)
            .map(|c| Vec3::new(c[0], c[1], c[2]).as_dvec3())
            .collect())
    }

    /// Radiosity per element.
    pub fn radiosity(&self) -> Result<Vec<DVec3>, GpuError> {
        self.read_rgb(&self.buffers.radiosity)
    }

    /// Radiosity (RGB, lm/m²) and received illuminance (lux) per element.
    pub fn radiosity_and_illuminance(&self) -> Result<(Vec<DVec3>, Vec<f64>), GpuError> {
        let v = self.gpu.read_f32(&self.buffers.radiosity)?;
        Ok(v.chunks_exact(4)
            .map(|c| (Vec3::new(c[0], c[1], c[2]).as_dvec3(), c[3] as f64))
            .unzip())
    }

    /// Unshot radiosity per element.
    pub fn unshot(&self) -> Result<Vec<DVec3>, GpuError> {
        self.read_rgb(&self.buffers.unshot)
    }
}

#[cfg(test)]
mod tests {
    use super::SMALL_SHOOTER;

    #[test]
    fn the_shader_sums_the_shooters_the_solver_lists_as_small() {
        let line = format!("const SMALL_SHOOTER = {SMALL_SHOOTER}u;");
        assert!(crate::gpu::shaders::RADIOSITY.contains(&line), "{line}");
    }
}
