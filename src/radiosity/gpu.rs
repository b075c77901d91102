//! The GPU solver: element arrays in storage buffers; per shot the shooter (a triangle or
//! a flat face cluster, [`super::shooters`]) is chosen on the GPU by reduction (only a
//! 48-byte selection record is read back), its patches' unshot radiosity gathered
//! (substructuring), and per batch of patches their visibility maps rendered (hemicube or
//! stereographic) side by side in one atlas ([`super::atlas`]) and every element in front
//! of them updated, one compute dispatch per patch.

use glam::{DVec3, Mat4, Vec3};
use wgpu::util::DeviceExt;

use super::atlas::VisibilityAtlas;
use super::form_factor::FormFactorKind;
use super::initial::InitialState;
use super::links::{Links, ReceiverBoxes, DEFAULT_LINK_ERROR, LINK_LEVELS};
use super::polygon::frame;
use super::scene::RadiosityScene;
use super::shooters::{
    cell_planes, Hierarchy, PlanCache, PlannedPatch, Shooters, ShotPlan, DEFAULT_CELL_POWER,
    DEFAULT_PLAN_CACHE_BYTES,
};
use super::{Ambient, SolverSettings};
use crate::geometry::split::split_long_edges;
use crate::gpu::{Gpu, GpuError};
use pipelines::{shared_bind_group, Pipelines};

mod chunks;
mod deferred;
mod map_store;
mod masked;
mod pipelines;
mod raster;
mod relight;
mod timers;
mod virtual_cells;

pub use chunks::{MeshChunks, TileView};
pub use deferred::{Reception, WIDEN_AT};
pub use map_store::DEFAULT_MAP_STORE_BYTES;
pub use raster::Raster;
pub use timers::GpuPassSeconds;

/// How a shooting patch sees what it can reach.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Visibility {
    /// Five perspective faces (Cohen and Greenberg): exact projection, five renders.
    #[default]
    Hemicube,
    /// The stereographic projection of the hemisphere (Wallner §2.3; Coombe et al.): one
    /// render, but only vertices are projected, so long edges bend.
    Stereographic,
}

/// GPU-only options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpuSettings {
    /// Visibility maps.
    pub visibility: Visibility,
    /// Side of a hemicube face or of the stereographic map, texels.
    pub map_size: u32,
    /// Relative depth tolerance of the visibility test.
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
/// in front of a cell ([`ReceiverBoxes::charts_roughly_in_front_of_any`]).
const RECEIVER_GROUP: u32 = 16;

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

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ShotGpu {
    faces: [[f32; 16]; 5],
    tangent: [f32; 4],
    bitangent: [f32; 4],
    normal: [f32; 4],
    centroid: [f32; 4],
    polygon: [[f32; 4]; 8],
    info: [u32; 4],
    extra: [f32; 4],
    ancestors: [[f32; 4]; LINK_LEVELS as usize],
    link: [f32; 4],
    pieces: [u32; 4],
    tint: [f32; 4],
    plane: [f32; 4],
    window: [u32; 4],
    pad: [[f32; 4]; 5],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FaceGpu {
    view_proj: [f32; 16],
    eye: [f32; 4],
    tangent: [f32; 4],
    bitangent: [f32; 4],
    normal: [f32; 4],
    clip: [f32; 4],
}

const SHOT_STRIDE: u64 = 768;
// The receive pass reads the batch's records as an array too (a virtual cell's parents).
const _: () = assert!(std::mem::size_of::<ShotGpu>() as u64 == SHOT_STRIDE);
const FACE_STRIDE: u64 = 256;

/// How a batch's cells get their visibility maps.
#[derive(Clone, Copy)]
enum CellMaps<'a> {
    /// Drawn.
    Draw,
    /// Drawn, and kept for receivers that wait ([`map_store`]).
    DrawAndKeep,
    /// Copied back from the kept maps where a cell has a slot (one per cell), drawn
    /// where not.
    Restore(&'a [Option<u32>]),
}

/// A cell a batch draws: one of the plan's patches, or a virtual cell of one.
#[derive(Clone, Copy)]
struct BatchCell<'c> {
    /// The plan's patch (a virtual cell's real cell: it shoots that cell's power).
    patch: usize,
    /// A virtual cell ([`virtual_cells`]) and the batch record of the cell it images.
    image: Option<(&'c virtual_cells::VirtualCell, u32)>,
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

/// A solution in progress on the GPU.
pub struct GpuSolver<'a> {
    gpu: &'a Gpu,
    scene: &'a RadiosityScene,
    settings: SolverSettings,
    gpu_settings: GpuSettings,
    /// Built once per device ([`Gpu::cached`]).
    pipelines: std::sync::Arc<Pipelines>,
    params: wgpu::Buffer,
    radiosity: wgpu::Buffer,
    unshot: wgpu::Buffer,
    selection: wgpu::Buffer,
    shooter_power: wgpu::Buffer,
    shooter_elements: wgpu::Buffer,
    patches: wgpu::Buffer,
    shared: wgpu::BindGroup,
    /// The buffers `shared` binds, binding by binding (it is bound again when the
    /// held-back buffer grows: [`deferred`]).
    shared_buffers: Vec<wgpu::Buffer>,
    shooters: Shooters,
    /// The first selection's total unshot power, lm (the oracle's scale).
    initial_power: Option<f64>,
    /// The last selection's shooter power, lm.
    last_power: f64,
    vertices: wgpu::Buffer,
    /// The visibility mesh's triangles (three vertex indices each).
    vertex_indices: wgpu::Buffer,
    index_count: u32,
    /// The visibility mesh's chunks, for culling per face.
    chunks: MeshChunks,
    /// Its alpha-masked triangles, drawn whole into every map.
    masked: Option<masked::MaskedCasters>,
    /// The compute rasterizer, where the maps are drawn by compute shaders.
    compute_raster: Option<raster::ComputeRaster>,
    /// Visibility-mesh triangles drawn so far, over all faces of all maps.
    pub triangles_drawn: u64,
    /// The visibility maps of a batch.
    atlas: VisibilityAtlas,
    size: f64,
    /// Shots so far.
    pub shots: usize,
    /// The shooters' records as uploaded (their weights in `[2]`).
    shooter_info: Vec<ShooterRecord>,
    shooter_buf: wgpu::Buffer,
    /// Whether the selection weighs the shooters ([`GpuSolver::set_shooter_weights`]).
    weighted: bool,
    /// Receivers that wait, and the shots they missed (perspective-driven radiosity).
    deferral: Option<deferred::Deferral>,
    /// The area of interest's stages (perspective-driven radiosity).
    stages: Option<deferred::Stages>,
    /// Patches in the next batch of a shot: adapted so a batch takes about
    /// [`BATCH_SECONDS`] (between 1 and [`PATCHES_PER_BATCH`]).
    batch: usize,
    /// What a batch should take, seconds ([`BATCH_SECONDS`] unless set).
    batch_seconds: f64,
    /// Whether `batch` stays as set ([`GpuSolver::fix_batch`]).
    fixed_batch: bool,
    /// Per cell of the shot: rgb unshot radiosity it shoots.
    patch_delta: wgpu::Buffer,
    /// Entries of the patch buffer for cells; the receiver ranges follow.
    max_patches: usize,
    /// The shot's receiver ranges and threads (every element of them).
    culled: (u32, u32),
    /// Shooters of more than [`SMALL_SHOOTER`] elements (a workgroup sums each).
    large_shooters: u32,
    /// Receiver threads dispatched so far (elements in front of the shooters, per map).
    pub receiver_threads: u64,
    /// The receivers' boxes, for the links.
    receivers: ReceiverBoxes,
    /// Visibility maps drawn so far (one per drawn cell or patch).
    pub drawn: usize,
    /// Cells or patches whose visibility map was skipped so far: no receiver takes light
    /// from them (behind the shooter, or linked to a coarser or finer cell).
    pub skipped: usize,
    /// Where the shots' time went so far (wall clock on the calling thread).
    pub times: ShotTimes,
    /// The shooting units planned so far, for shots that repeat their layout.
    pub plan_cache: PlanCache,
    /// The GPU's timestamps around each batch's passes ([`GpuSolver::time_passes`]).
    timers: Option<timers::PassTimers>,
    /// The maps of the cells shot while receivers waited, for their catch-up.
    map_store: map_store::MapStore,
    /// The specular windows' triangles ([`virtual_cells::window_corners`]).
    window_corners: wgpu::Buffer,
    /// Per window, its first triangle and count there.
    window_ranges: Vec<[u32; 2]>,
    /// Virtual cells' visibility maps drawn so far (mirrors and clear glass).
    pub virtual_drawn: usize,
}

fn storage(gpu: &Gpu, label: &str, data: &[u8], writable: bool) -> wgpu::Buffer {
    use wgpu::BufferUsages as U;
    let usage = if writable {
        U::STORAGE | U::COPY_SRC | U::COPY_DST
    } else {
        U::STORAGE
    };
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: data,
            usage,
        })
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

/// Most workgroups along one dimension of a dispatch (WebGPU's limit).
const MAX_GROUPS_X: u32 = 65_535;

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
                 or a smaller --map-size)",
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
    /// Uploads `scene` with the `initial` radiosity (= unshot radiosity) and illuminance
    /// per element: the emission plus the reflected direct light of the luminaires.
    pub fn new(
        gpu: &'a Gpu,
        scene: &'a RadiosityScene,
        initial: &InitialState,
        settings: SolverSettings,
        gpu_settings: GpuSettings,
    ) -> GpuSolver<'a> {
        let shooters = Shooters::build(scene, gpu_settings.hierarchy);
        GpuSolver::with_shooters(gpu, scene, initial, settings, gpu_settings, shooters)
    }

    /// [`GpuSolver::new`] with shooters built by the caller (`Shooters::build(scene,
    /// gpu_settings.hierarchy)`, timed on its own).
    pub fn with_shooters(
        gpu: &'a Gpu,
        scene: &'a RadiosityScene,
        initial: &InitialState,
        settings: SolverSettings,
        gpu_settings: GpuSettings,
        shooters: Shooters,
    ) -> GpuSolver<'a> {
        let el = &scene.elements;
        let n = el.len();
        debug_assert!((0..n).all(|e| {
            let k = shooters.element_shooter[e] as usize;
            scene.reflectance[shooters.material[k]] == scene.element_reflectance(e)
        }));
        let points: Vec<ElementRecord> = (0..n)
            .map(|e| v4(el.position[e], el.area[e] as f32))
            .collect();
        let normals: Vec<ElementRecord> = (0..n)
            .map(|e| v4(el.normal(e), f32::from_bits(shooters.element_piece[e])))
            .collect();
        let start: Vec<[f32; 4]> = initial.radiosity.iter().map(|b| v4(*b, 0.0)).collect();
        let start_lit: Vec<[f32; 4]> = (0..n)
            .map(|e| v4(initial.radiosity[e], initial.illuminance[e] as f32))
            .collect();
        let mut shooter_info: Vec<ShooterRecord> = (0..shooters.len())
            .map(|k| {
                let r = scene.reflectance[shooters.material[k]].as_vec3();
                let t = scene.transmittance[shooters.material[k]].as_vec3();
                [
                    shooters.first[k],
                    shooters.count[k],
                    // The shooter's weight in the selection (1: its power alone).
                    1f32.to_bits(),
                    shooters.first_piece[k],
                    r.x.to_bits(),
                    r.y.to_bits(),
                    r.z.to_bits(),
                    (shooters.area[k] as f32).to_bits(),
                    t.x.to_bits(),
                    t.y.to_bits(),
                    t.z.to_bits(),
                    0,
                ]
            })
            .collect();
        // Shooters of more than SMALL_SHOOTER elements are summed by a workgroup each:
        // listed after the shooters (range.z: the shooter).
        let large: Vec<ShooterRecord> = (0..shooters.len())
            .filter(|&k| shooters.count[k] > SMALL_SHOOTER)
            .map(|k| {
                let mut record = shooter_info[k];
                record[2] = k as u32;
                record
            })
            .collect();
        let large_shooters = large.len() as u32;
        shooter_info.extend(large);
        // Room for the largest plan; links are left out where its cells would not fit
        // one binding (a cluster of millions of elements).
        let max_binding = gpu
            .device
            .limits()
            .max_storage_buffer_binding_size
            .min(gpu.device.limits().max_buffer_size);
        let mut gpu_settings = gpu_settings;
        // Virtual cells shoot to every receiver their window shows: no links (a cell a
        // link leaves undrawn could light receivers through a mirror).
        if !scene.specular.is_empty() {
            gpu_settings.link_error = 0.0;
        }
        let mut max_patches = shooters.max_cells(scene, LINK_LEVELS);
        if 16 * max_patches as u64 > max_binding {
            gpu_settings.link_error = 0.0;
            max_patches = shooters.max_cells(scene, 0);
        }
        let pipelines = gpu.cached(|| Pipelines::new(gpu));
        let bytes = |v: &[[f32; 4]]| bytemuck::cast_slice::<[f32; 4], u8>(v).to_vec();
        let params = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("radiosity params"),
            size: std::mem::size_of::<SolveParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let element_points = storage(gpu, "element points", &bytes(&points), false);
        let element_normals = storage(gpu, "element normals", &bytes(&normals), false);
        // Receiving normals (w 1 where not the chart's) only where some element has its
        // own; otherwise one unused record.
        let receiving: Vec<ElementRecord> = if scene.receiving_normals.is_empty() {
            vec![[0.0; 4]]
        } else {
            (0..n)
                .map(|e| {
                    let r = scene.element_receiving_normal(e);
                    v4(r, f32::from(u8::from(r != el.normal(e))))
                })
                .collect()
        };
        let element_receiving =
            storage(gpu, "element receiving normals", &bytes(&receiving), false);
        let shooter_elements = storage(
            gpu,
            "shooter elements",
            bytemuck::cast_slice(&shooters.elements),
            true,
        );
        let radiosity = storage(gpu, "radiosity", &bytes(&start_lit), true);
        let unshot = storage(gpu, "unshot", &bytes(&start), true);
        // Writable: the selection's weights change (view-driven shooting).
        let shooter_buf = storage(gpu, "shooters", bytemuck::cast_slice(&shooter_info), true);
        shooter_info.truncate(shooters.len());
        // The selection record follows the shooters' sums.
        let shooter_power = storage(
            gpu,
            "shooter power",
            &vec![0u8; 16 * (shooters.len() + 3)],
            true,
        );
        let selection = storage(gpu, "selection", &[0u8; 48], true);
        // The shot's cells, then per chart in front of the shooter its receivers' range.
        let patch_buf = storage(
            gpu,
            "patches",
            &vec![0u8; 16 * (max_patches + el.charts.len().max(1))],
            true,
        );
        let patch_delta = storage(gpu, "patch delta", &vec![0u8; 16 * max_patches], true);
        // The shot's elements' unshot radiosity as cleared, for a shot stopped early.
        let held = storage(
            gpu,
            "held unshot",
            &vec![0u8; 16 * shooters.max_elements()],
            true,
        );
        // What charts that hold keep back: one unused record until one holds (at
        // `deferred::HELD_BACK_BINDING`).
        let held_back = storage(gpu, "held back", &[0u8; 16], true);
        let shared_buffers = vec![
            params.clone(),
            element_points,
            shooter_elements.clone(),
            radiosity.clone(),
            unshot.clone(),
            shooter_buf.clone(),
            shooter_power.clone(),
            patch_buf.clone(),
            patch_delta.clone(),
            element_normals,
            held,
            element_receiving,
            held_back,
        ];
        let shared = shared_bind_group(gpu, &pipelines, &shared_buffers);
        // Visibility needs only the surfaces, not their tessellation: a CAD fan's strips
        // are drawn as the triangle they fill (the same points, far fewer triangles).
        let scene_size = scene
            .casters
            .bounds()
            .map_or(1.0, |(lo, hi)| (hi - lo).length());
        // The stereographic map projects only vertices, so a long edge bends wrongly
        // (Wallner Fig. 4.4): its mesh has no edge longer than a fraction of the scene.
        let max_edge = match gpu_settings.visibility {
            Visibility::Hemicube => f64::INFINITY,
            Visibility::Stereographic => scene_size * STEREOGRAPHIC_EDGE_FRACTION,
        };
        // The alpha-masked triangles at the mesh's end are drawn on their own.
        let masked = masked::MaskedCasters::new(
            gpu,
            scene,
            &pipelines.vis_module,
            &pipelines.face_layout,
            max_edge,
        );
        let solid = masked::solid_visibility_mesh(scene);
        let split;
        let mesh = match gpu_settings.visibility {
            Visibility::Hemicube => &*solid,
            Visibility::Stereographic => {
                split = split_long_edges(&solid, max_edge);
                &split
            }
        };
        // Indexed: a vertex shared by six triangles is transformed about once per face
        // drawn, not six times.
        let positions: Vec<[f32; 3]> = mesh
            .positions
            .iter()
            .map(|p| p.as_vec3().to_array())
            .collect();
        let mut triangles = mesh.triangles.clone();
        let chunks = MeshChunks::new(&mesh.positions, &mut triangles);
        let indices: Vec<u32> = triangles.iter().flatten().copied().collect();
        // Read as storage by the compute rasterizer.
        let vertices = gpu.buffer_with(
            "radiosity vertices",
            bytemuck::cast_slice(&positions),
            wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::STORAGE,
        );
        let vertex_indices = gpu.buffer_with(
            "radiosity vertex indices",
            bytemuck::cast_slice(&indices),
            wgpu::BufferUsages::INDEX | wgpu::BufferUsages::STORAGE,
        );
        gpu_settings.raster = gpu_settings.raster.resolve(gpu, masked.is_some());
        let compute_raster = (gpu_settings.raster == Raster::Compute).then(|| {
            raster::ComputeRaster::new(gpu, gpu.cached(|| raster::RasterPipelines::new(gpu)))
        });
        let atlas = VisibilityAtlas::new(
            gpu,
            gpu_settings.map_size,
            FIRST_BATCH as u32 * faces_per_cell(gpu_settings.visibility),
        );
        let (corners, window_ranges) = virtual_cells::window_corners(&scene.specular);
        let window_corners = storage(gpu, "window corners", bytemuck::cast_slice(&corners), false);
        let solver = GpuSolver {
            gpu,
            scene,
            settings,
            gpu_settings,
            pipelines,
            params,
            radiosity,
            unshot,
            selection,
            shooter_power,
            shooter_elements,
            patches: patch_buf,
            shared,
            shared_buffers,
            shooters,
            initial_power: None,
            last_power: 0.0,
            vertices,
            vertex_indices,
            index_count: indices.len() as u32,
            chunks,
            masked,
            compute_raster,
            triangles_drawn: 0,
            atlas,
            size: scene_size,
            shots: 0,
            shooter_info,
            shooter_buf,
            weighted: false,
            deferral: None,
            stages: None,
            batch: FIRST_BATCH,
            batch_seconds: BATCH_SECONDS,
            fixed_batch: false,
            patch_delta,
            max_patches,
            culled: (0, 0),
            large_shooters,
            receiver_threads: 0,
            timers: None,
            map_store: map_store::MapStore::new(DEFAULT_MAP_STORE_BYTES),
            receivers: ReceiverBoxes::new(scene),
            drawn: 0,
            skipped: 0,
            times: ShotTimes::default(),
            plan_cache: PlanCache::new(DEFAULT_PLAN_CACHE_BYTES),
            window_corners,
            window_ranges,
            virtual_drawn: 0,
        };
        solver.write_params(u32::MAX, 0, 0, 0..0);
        solver
    }

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
            shooter_count: self.shooters.len() as u32,
            shooter,
            overshoot: u32::from(self.settings.ambient == Ambient::Overshoot),
            patch_first,
            patch_count,
            total_area: self.scene.total_area as f32,
            mean_reflectance: self.scene.mean_reflectance as f32,
            clear_first: clear.start,
            clear_count: clear.len() as u32,
            range_count: self.culled.0,
            range_total: self.culled.1,
            range_first: self.max_patches as u32,
            large_shooters: self.large_shooters,
            receiving_normals: u32::from(!self.scene.receiving_normals.is_empty()),
            _pad: 0,
        };
        self.gpu
            .queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&p));
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
        pass.set_bind_group(0, &self.shared, &[]);
        dispatch_groups(&mut pass, threads.div_ceil(group));
    }

    /// Chooses the next shooter on the GPU (reduction over the shooters).
    pub fn select(&mut self) -> Result<Selection, GpuError> {
        let mut clock = std::time::Instant::now();
        self.write_params(u32::MAX, 0, 0, 0..0);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        let shooters = self.shooters.len() as u32;
        self.dispatch(&mut enc, &self.pipelines.shooter_sums, shooters, 64);
        self.dispatch(
            &mut enc,
            &self.pipelines.large_shooter_sums,
            self.large_shooters,
            1,
        );
        self.dispatch(&mut enc, &self.pipelines.select, 1, 1);
        // Only the 48-byte selection record comes back.
        enc.copy_buffer_to_buffer(
            &self.shooter_power,
            16 * shooters as u64,
            &self.selection,
            0,
            48,
        );
        self.gpu.queue.submit([enc.finish()]);
        let v = self.gpu.read_f32(&self.selection)?;
        lap(&mut self.times.select, &mut clock);
        let index = v[0].to_bits();
        let shooter = (index != u32::MAX && v[1] > 0.0).then_some(index as usize);
        // The shader's choice is by weighted power; the shot's cells are sized by the
        // power itself.
        let weight = shooter.map_or(1.0, |k| f32::from_bits(self.shooter_info[k][2]));
        let selection = Selection {
            shooter,
            power: (v[1] / weight) as f64,
            unshot_power: v[2] as f64,
            weighted_power: v[3] as f64,
        };
        self.initial_power.get_or_insert(selection.unshot_power);
        self.last_power = selection.power;
        Ok(selection)
    }

    /// Weighs each shooter's unshot power by `weights` (one per shooter, ≥ 0) in the
    /// selection and in [`Selection::weighted_power`]: importance-driven shooting.
    pub fn set_shooter_weights(&mut self, weights: &[f64]) {
        assert_eq!(weights.len(), self.shooters.len());
        for (record, w) in self.shooter_info.iter_mut().zip(weights) {
            record[2] = (w.max(0.0) as f32).to_bits();
        }
        self.gpu.queue.write_buffer(
            &self.shooter_buf,
            0,
            bytemuck::cast_slice(&self.shooter_info),
        );
        self.weighted = true;
    }

    /// Sizes the batches of a shot to take about `seconds` each (default [`BATCH_SECONDS`],
    /// at most that): a shot stopped by [`GpuSolver::shoot_until`] overruns its stop by
    /// at most about one batch (the viewer's per-frame budget).
    pub fn set_batch_seconds(&mut self, seconds: f64) {
        self.batch_seconds = seconds.clamp(1e-3, BATCH_SECONDS);
    }

    /// Shoots `cells` cells per batch from now on, whatever they take (at least 1, at
    /// most [`PATCHES_PER_BATCH`]), instead of adapting the batch to the clock: two runs
    /// then split their shots alike, for comparisons that must be exact. (Where a cell's
    /// maps lie in the atlas follows the batch, and rasterization at another place in
    /// the atlas may flip a texel along an edge seen at a grazing angle: a receiver
    /// there may differ by a percent between runs, the total by about 10⁻⁷.)
    pub fn fix_batch(&mut self, cells: usize) {
        self.batch = cells.clamp(1, PATCHES_PER_BATCH);
        self.fixed_batch = true;
    }

    /// The scene it solves.
    pub fn scene(&self) -> &RadiosityScene {
        self.scene
    }

    /// Whether the selection weighs the shooters.
    pub fn is_weighted(&self) -> bool {
        self.weighted
    }

    /// Triangles each visibility map draws (the casters with CAD fans merged).
    pub fn visibility_triangles(&self) -> usize {
        self.index_count as usize / 3
    }

    /// How its maps are drawn ([`GpuSettings::raster`] as resolved for this GPU and
    /// scene: never [`Raster::Auto`]).
    pub fn raster(&self) -> Raster {
        self.gpu_settings.raster
    }

    /// The shooters: triangles, or flat face clusters ([`GpuSettings::hierarchy`]).
    pub fn shooters(&self) -> &Shooters {
        &self.shooters
    }

    /// The visibility faces' projection, and its far plane: around the scene's size.
    fn projection(&self) -> (Mat4, f32) {
        let (near, far) = ((1e-4 * self.size) as f32, (2.0 * self.size) as f32);
        let m = Mat4::perspective_rh(std::f32::consts::FRAC_PI_2, 1.0, near, far);
        (m, far)
    }

    /// The shooting records of a batch's `cells` (the plan's patches and their virtual
    /// cells), each facing its own normal, with their links, and their visibility faces:
    /// those of the `k`-th are the atlas's tiles from `k` × faces per cell.
    fn shot_records(
        &self,
        plan: &ShotPlan,
        links: &Links,
        cells: &[BatchCell<'_>],
    ) -> (Vec<u8>, Vec<u8>, Vec<TileView>) {
        let faces_per_patch = faces_per_cell(self.gpu_settings.visibility) as usize;
        let (projection, far) = self.projection();
        let tolerance = self.receivers.plane_tolerance() as f32;
        let finite = |r: f64| r.min(f64::from(f32::MAX)) as f32;
        let mut shots = vec![0u8; cells.len() * SHOT_STRIDE as usize];
        let mut faces = vec![0u8; cells.len() * faces_per_patch * FACE_STRIDE as usize];
        let mut views = Vec::with_capacity(cells.len() * faces_per_patch);
        for (k, cell) in cells.iter().enumerate() {
            let patch = cell.patch;
            let p = match cell.image {
                Some((v, _)) => &v.planned,
                None => &plan.patches[patch],
            };
            let n = p.normal;
            let (tangent, bitangent) = frame(n);
            let eye = (p.centroid + n * 1e-6 * self.size).as_vec3();
            let (t3, b3, n3) = (tangent.as_vec3(), bitangent.as_vec3(), n.as_vec3());
            let looks = [(n3, t3), (t3, n3), (-t3, n3), (b3, n3), (-b3, n3)];
            let matrices = looks.map(|(dir, up)| projection * Mat4::look_to_rh(eye, dir, up));
            let mut polygon = [[0f32; 4]; 8];
            for (slot, v) in polygon.iter_mut().zip(&p.polygon) {
                *slot = v4(*v, 1.0);
            }
            // The cells above it, nearest first (reach −1: none).
            let mut ancestors = [[0.0, 0.0, 0.0, -1.0]; LINK_LEVELS as usize];
            let mut up = p.parent;
            for slot in &mut ancestors {
                if up == u32::MAX {
                    break;
                }
                let a = &plan.patches[up as usize];
                *slot = v4(a.centroid, finite(links.reach[up as usize]));
                up = a.parent;
            }
            // A coarse cell's polygon may be its hull's bounding rectangle, a merged
            // cell's is a projection: far away, the form factor goes with the area, so
            // it is scaled to its elements' area.
            let scale = p.power_scale();
            let stereographic = self.gpu_settings.visibility == Visibility::Stereographic;
            // A virtual cell: its path's coefficients, window and parent; its maps see
            // only what lies beyond its window's plane.
            let (tint, plane, window, reach) = match cell.image {
                Some((v, parent)) => {
                    let [first, count] = self.window_ranges[v.window];
                    let plane = v.plane.as_vec4().to_array();
                    (v4(v.tint, 0.0), plane, [first, count, parent, 0], 0.0)
                }
                None => ([1.0; 4], [0.0, 0.0, 0.0, 1.0], [0; 4], links.reach[patch]),
            };
            let mut clip = plane;
            if cell.image.is_some() {
                clip[3] -= (1e-4 * self.size) as f32;
            }
            let record = ShotGpu {
                faces: matrices.map(|m| m.to_cols_array()),
                tangent: v4(tangent, 0.0),
                bitangent: v4(bitangent, 0.0),
                normal: v4(n, 0.0),
                centroid: v4(p.centroid, 1.0),
                polygon,
                info: [
                    patch as u32,
                    p.polygon.len().min(8) as u32,
                    u32::from(self.settings.form_factor == FormFactorKind::Polygon),
                    self.gpu_settings.map_size,
                ],
                extra: [
                    p.area as f32,
                    self.gpu_settings.tolerance,
                    (1e-4 * self.size) as f32,
                    if stereographic { 1.0 } else { 0.0 },
                ],
                ancestors,
                link: [
                    finite(reach),
                    tolerance,
                    scale as f32,
                    if p.parent == u32::MAX { 1.0 } else { 0.0 },
                ],
                pieces: [
                    p.pieces[0],
                    p.pieces[1],
                    (k * faces_per_patch) as u32,
                    self.atlas.columns,
                ],
                tint,
                plane,
                window,
                pad: [[0.0; 4]; 5],
            };
            let at = k * SHOT_STRIDE as usize;
            shots[at..at + std::mem::size_of::<ShotGpu>()]
                .copy_from_slice(bytemuck::bytes_of(&record));
            for (f, m) in matrices.iter().take(faces_per_patch).enumerate() {
                let face = FaceGpu {
                    view_proj: m.to_cols_array(),
                    eye: [eye.x, eye.y, eye.z, if stereographic { 1.0 } else { 0.0 }],
                    tangent: v4(tangent, 0.0),
                    bitangent: v4(bitangent, 0.0),
                    normal: v4(n, far),
                    clip,
                };
                let at = (k * faces_per_patch + f) * FACE_STRIDE as usize;
                faces[at..at + std::mem::size_of::<FaceGpu>()]
                    .copy_from_slice(bytemuck::bytes_of(&face));
                views.push(if stereographic {
                    TileView::HalfSpace {
                        eye: eye.as_dvec3(),
                        normal: n3.as_dvec3(),
                    }
                } else {
                    TileView::Frustum(*m)
                });
            }
        }
        (shots, faces, views)
    }

    /// Shoots shooter `s` (plus the overshoot the last [`GpuSolver::select`] chose).
    pub fn shoot(&mut self, s: usize) -> Result<(), GpuError> {
        self.shoot_until(s, &|| false).map(|_| ())
    }

    /// How shooter `s` shoots now ([`Shooters::plan_shot`]): each piece's cells sized by
    /// the oracle from its own unshot power ([`GpuSolver::piece_powers`]), with
    /// [`LINK_LEVELS`] coarser levels when links are on; weak curved parts merged, the
    /// weakest deferred. Its element order and cells go to the GPU, every cell's unshot
    /// radiosity is gathered there (before any is cleared), and — when there are coarse
    /// cells — read back for the links' oracle.
    fn plan(&mut self, s: usize) -> Result<(ShotPlan, Links, Vec<[f32; 4]>), GpuError> {
        let initial = self.initial_power.unwrap_or(0.0);
        let budget = self.gpu_settings.cell_power * initial;
        let levels = if self.gpu_settings.link_error > 0.0 {
            LINK_LEVELS
        } else {
            0
        };
        let mut clock = std::time::Instant::now();
        let power = self.piece_powers(s)?;
        lap(&mut self.times.piece_powers, &mut clock);
        let plan =
            self.shooters
                .plan_shot(self.scene, s, &power, budget, levels, &mut self.plan_cache);
        lap(&mut self.times.plan, &mut clock);
        let first = self.shooters.first[s];
        self.gpu.queue.write_buffer(
            &self.shooter_elements,
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
            .write_buffer(&self.patches, 0, bytemuck::cast_slice(&patches));
        let cells = plan.patches.len() as u32;
        self.write_params(s as u32, 0, cells, 0..0);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        self.dispatch(&mut enc, &self.pipelines.gather, cells, 1);
        self.gpu.queue.submit([enc.finish()]);
        // Read back for the links' oracle, and to be shot again later when receivers
        // wait (perspective-driven radiosity).
        let coarse = plan.patches.iter().any(|p| p.level > 0);
        let waiting = self.deferral.as_ref().is_some_and(|d| d.any_waiting());
        let delta: Vec<[f32; 4]> = if coarse || waiting {
            let d = self
                .gpu
                .read_f32_prefix(&self.patch_delta, 16 * cells as u64)?;
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
        lap(&mut self.times.gather, &mut clock);
        let epsilon = self.gpu_settings.link_error * initial / self.scene.total_area.max(1e-300);
        let links = super::links::link(&plan, &radiosity, &self.receivers, epsilon);
        lap(&mut self.times.links, &mut clock);
        Ok((plan, links, delta))
    }

    /// Per piece of shooter `s`, its unshot power (with the overshoot), lm: summed on the
    /// GPU over the pieces' elements (laid out piece after piece again first) and read
    /// back. A lone piece's is the selection's.
    fn piece_powers(&mut self, s: usize) -> Result<Vec<f64>, GpuError> {
        let pieces = self.shooters.pieces_of(s);
        if pieces.len() == 1 {
            return Ok(vec![self.last_power]);
        }
        let first = self.shooters.first[s];
        self.gpu.queue.write_buffer(
            &self.shooter_elements,
            4 * first as u64,
            bytemuck::cast_slice(self.shooters.elements_of(s)),
        );
        let records: Vec<[u32; 4]> = pieces
            .clone()
            .map(|p| {
                let piece = &self.shooters.pieces[p];
                [piece.first, piece.count, 1f32.to_bits(), 0]
            })
            .collect();
        self.gpu
            .queue
            .write_buffer(&self.patches, 0, bytemuck::cast_slice(&records));
        let count = records.len() as u32;
        self.write_params(s as u32, 0, count, 0..0);
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        self.dispatch(&mut enc, &self.pipelines.gather, count, 1);
        self.gpu.queue.submit([enc.finish()]);
        let sums = self
            .gpu
            .read_f32_prefix(&self.patch_delta, 16 * u64::from(count))?;
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
            while t < tops.len() && (t == from || drawn.len() < self.batch) {
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
            lap(&mut self.times.cull, &mut clock);
            let clear = if from == 0 { 0..plan.shot } else { 0..0 };
            let maps = if waiting && self.map_store.is_enabled() {
                CellMaps::DrawAndKeep
            } else {
                CellMaps::Draw
            };
            let batch = (drawn.as_slice(), images.as_slice());
            let (submitted, slots) = self.shoot_batch(s, &plan, &links, batch, clear, maps)?;
            lap(&mut self.times.record, &mut clock);
            if waiting {
                missed.extend_from_slice(&drawn);
                kept.extend(slots);
            }
            let cells: usize = (tops[from]..subtree_end(t - 1)).count();
            self.drawn += drawn.len();
            self.virtual_drawn += imaged.len();
            self.skipped += cells - drawn.len();
            if t < tops.len() {
                if let Some(index) = previous.replace(submitted) {
                    self.gpu.wait_for(index)?;
                }
                lap(&mut self.times.batch_wait, &mut clock);
                // Twice as many next time while well under the target, half when over.
                let took = started.elapsed().as_secs_f64();
                if self.fixed_batch {
                } else if took < 0.5 * self.batch_seconds {
                    self.batch = (self.batch * 2).min(PATCHES_PER_BATCH);
                } else if took > self.batch_seconds {
                    self.batch = (self.batch / 2).max(1);
                }
                if stop() {
                    self.restore(s, tops[t], plan.patches.len());
                    self.shots += 1;
                    self.defer(s, plan, links, delta, missed, kept);
                    return Ok(false);
                }
            }
        }
        self.shots += 1;
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
        let deferral = self.deferral.as_ref().filter(|d| d.any_not_receiving());
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
    /// [`ReceiverBoxes::merged_ranges`].
    fn set_receivers(&mut self, charts: &[usize], holding: &[usize]) {
        let mut threads = 0u32;
        let records: Vec<[u32; 4]> = [(charts, 0), (holding, 1)]
            .into_iter()
            .flat_map(|(charts, hold)| {
                self.receivers
                    .merged_ranges(charts)
                    .into_iter()
                    .map(move |range| (range, hold))
            })
            .map(|((first, count), hold)| {
                let r = [first, threads, 0, hold];
                threads += count;
                r
            })
            .collect();
        if !records.is_empty() {
            self.gpu.queue.write_buffer(
                &self.patches,
                16 * self.max_patches as u64,
                bytemuck::cast_slice(&records),
            );
        }
        self.culled = (records.len() as u32, threads);
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
    fn shoot_batch(
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
        let first = self.shooters.first[s];
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
                    let slot = self
                        .map_store
                        .allocate(self.gpu, &mut enc, self.atlas.size, faces);
                    if let Some(at) = slot {
                        let cell = (k * faces, at, faces);
                        self.map_store.copy_cell(&mut enc, &self.atlas, cell, true);
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

    /// Keeps this many bytes of maps at most for the catch-up of waiting receivers (0:
    /// none; missed cells are then drawn again), dropping what is kept now.
    pub fn set_map_store_bytes(&mut self, bytes: u64) {
        self.map_store = map_store::MapStore::new(bytes);
        if let Some(d) = &mut self.deferral {
            d.forget_kept_maps();
        }
    }

    /// Maps copied back from the kept maps for a catch-up so far (not drawn).
    pub fn maps_reused(&self) -> usize {
        self.map_store.reused
    }

    /// Records the maps of the cells `drawn` and their virtual cells into the atlas (which
    /// holds them; the virtual cells' after all drawn cells') and their receive
    /// dispatches.
    fn record_part(
        &mut self,
        enc: &mut wgpu::CommandEncoder,
        plan: &ShotPlan,
        links: &Links,
        (drawn, images): (&[usize], &[Vec<virtual_cells::VirtualCell>]),
        stored: &[Option<u32>],
    ) -> Result<(), GpuError> {
        let mut cells: Vec<BatchCell<'_>> = drawn
            .iter()
            .map(|&patch| BatchCell { patch, image: None })
            .collect();
        for (k, (&patch, list)) in drawn.iter().zip(images).enumerate() {
            let first = cells.len();
            for v in list {
                let parent = match v.parent {
                    0 => k,
                    j => first + j - 1,
                };
                cells.push(BatchCell {
                    patch,
                    image: Some((v, parent as u32)),
                });
            }
        }
        let (shots, faces, views) = self.shot_records(plan, links, &cells);
        let faces_per_cell = faces_per_cell(self.gpu_settings.visibility);
        // Kept maps go back into their tiles; those tiles are not drawn.
        let restored = |tile: u32| {
            stored
                .get((tile / faces_per_cell) as usize)
                .is_some_and(|s| s.is_some())
        };
        let queries = match &mut self.timers {
            Some(t) => Some(t.next_batch(self.gpu)?),
            None => None,
        };
        use wgpu::BufferUsages as U;
        let shot_buf = self
            .gpu
            .buffer_with("shots", &shots, U::UNIFORM | U::STORAGE);
        // The compute rasterizer reads the faces as storage.
        let face_buf = self
            .gpu
            .buffer_with("faces", &faces, U::UNIFORM | U::STORAGE);
        fn binding(buffer: &wgpu::Buffer, size: usize) -> wgpu::BindingResource<'_> {
            wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: wgpu::BufferSize::new(size as u64),
            })
        }
        let shot_bind = self.gpu.bind_group(
            "shot",
            &self.pipelines.shot_layout,
            &[
                (0, binding(&shot_buf, std::mem::size_of::<ShotGpu>())),
                (1, wgpu::BindingResource::TextureView(&self.atlas.view)),
                (2, shot_buf.as_entire_binding()),
                (3, self.window_corners.as_entire_binding()),
            ],
        );
        let mut ranges = Vec::new();
        if let Some(compute) = &mut self.compute_raster {
            let mut work = raster::RasterWork::new();
            for (tile, view) in views.iter().enumerate() {
                let tile = tile as u32;
                if restored(tile) {
                    continue;
                }
                self.chunks
                    .visible(view, self.gpu_settings.chunk_culling, &mut ranges);
                for &(first, count) in &ranges {
                    work.push(tile, first, count);
                    self.triangles_drawn += u64::from(count / 3);
                }
            }
            compute.record(
                self.gpu,
                enc,
                &self.atlas,
                (&self.vertices, &self.vertex_indices),
                &face_buf,
                &work,
                views.len() as u32,
                queries.as_ref().map(|q| q.maps_compute()),
            );
        } else {
            let face_bind = self.gpu.bind_group(
                "faces",
                &self.pipelines.face_layout,
                &[(0, binding(&face_buf, std::mem::size_of::<FaceGpu>()))],
            );
            // Kept, not cleared: each tile is cleared by its own draw (and a discarded
            // depth would be cleared whole by wgpu before the next load).
            let kept = wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            };
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("visibility"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.atlas.view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: kept,
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.atlas.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: queries.as_ref().map(|q| q.maps()),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_vertex_buffer(0, self.vertices.slice(..));
            pass.set_index_buffer(self.vertex_indices.slice(..), wgpu::IndexFormat::Uint32);
            let size = self.atlas.size;
            for (tile, view) in views.iter().enumerate() {
                let tile = tile as u32;
                if restored(tile) {
                    continue;
                }
                let (x, y) = self.atlas.origin(tile);
                pass.set_viewport(x as f32, y as f32, size as f32, size as f32, 0.0, 1.0);
                pass.set_scissor_rect(x, y, size, size);
                pass.set_bind_group(0, &face_bind, &[(u64::from(tile) * FACE_STRIDE) as u32]);
                pass.set_pipeline(&self.pipelines.clear_tile);
                pass.draw(0..3, 0..1);
                // A virtual cell's tiles follow the real cells'.
                let clipped = tile / faces_per_cell >= drawn.len() as u32;
                pass.set_pipeline(if clipped {
                    &self.pipelines.visibility_clipped
                } else {
                    &self.pipelines.visibility
                });
                self.chunks
                    .visible(view, self.gpu_settings.chunk_culling, &mut ranges);
                for &(first, count) in &ranges {
                    pass.draw_indexed(first..first + count, 0, 0..1);
                    self.triangles_drawn += u64::from(count / 3);
                }
                if let Some(masked) = &self.masked {
                    masked.draw(&mut pass, clipped);
                    self.triangles_drawn += u64::from(masked.triangle_count());
                    pass.set_vertex_buffer(0, self.vertices.slice(..));
                }
            }
        }
        // After the maps: the compute rasterizer writes every tile of the batch.
        for (k, slot) in stored.iter().enumerate() {
            if let &Some(at) = slot {
                let cell = (k as u32 * faces_per_cell, at, faces_per_cell);
                self.map_store.copy_cell(enc, &self.atlas, cell, false);
            }
        }
        let receivers = self.culled.1;
        self.receiver_threads += u64::from(receivers) * cells.len() as u64;
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("receive"),
            timestamp_writes: queries.as_ref().map(|q| q.receive()),
        });
        pass.set_pipeline(&self.pipelines.receive);
        pass.set_bind_group(0, &self.shared, &[]);
        for k in 0..cells.len() as u64 {
            // The real cells first, then their virtual cells.
            if k == drawn.len() as u64 {
                pass.set_pipeline(&self.pipelines.receive_through_windows);
            }
            pass.set_bind_group(1, &shot_bind, &[(k * SHOT_STRIDE) as u32]);
            dispatch_groups(&mut pass, receivers.div_ceil(64));
        }
        Ok(())
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
        self.read_rgb(&self.radiosity)
    }

    /// Radiosity (RGB, lm/m²) and received illuminance (lux) per element.
    pub fn radiosity_and_illuminance(&self) -> Result<(Vec<DVec3>, Vec<f64>), GpuError> {
        let v = self.gpu.read_f32(&self.radiosity)?;
        Ok(v.chunks_exact(4)
            .map(|c| (Vec3::new(c[0], c[1], c[2]).as_dvec3(), c[3] as f64))
            .unzip())
    }

    /// Unshot radiosity per element.
    pub fn unshot(&self) -> Result<Vec<DVec3>, GpuError> {
        self.read_rgb(&self.unshot)
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
