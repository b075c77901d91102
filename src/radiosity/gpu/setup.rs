//! Building a [`GpuSolver`]: what its scene shares with every solver of it
//! ([`SceneUpload`]: shooters, element records, visibility mesh, receivers' boxes), then
//! the solver's own solution buffers, shooter records, atlas and bind group.

use wgpu::util::DeviceExt;

use super::deferred::Perspective;
use super::pipelines::{shared_bind_group, Pipelines};
use super::shot::Batching;
use super::{
    faces_per_cell, map_store, masked, raster, v4, virtual_cells, ElementRecord, GpuSettings,
    GpuSolver, MeshChunks, Raster, ShooterChoice, ShooterRecord, ShotStats, ShotTimes, SolveParams,
    Visibility, BATCH_SECONDS, DEFAULT_MAP_STORE_BYTES, FIRST_BATCH, SMALL_SHOOTER,
    STEREOGRAPHIC_EDGE_FRACTION,
};
use crate::geometry::split::split_long_edges;
use crate::gpu::Gpu;
use crate::radiosity::atlas::VisibilityAtlas;
use crate::radiosity::initial::InitialState;
use crate::radiosity::links::{ReceiverBoxes, LINK_LEVELS};
use crate::radiosity::scene::RadiosityScene;
use crate::radiosity::shooters::{PlanCache, Shooters, DEFAULT_PLAN_CACHE_BYTES};
use crate::radiosity::{Hierarchy, SolverSettings};
use std::sync::Arc;

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

/// What the solvers of one scene with the same shooters and visibility share, built once:
/// the shooters, the elements' records on the GPU, the visibility mesh and its chunks,
/// the receivers' boxes and the specular windows. A second solver of the scene (the
/// importance solve of a view-driven one) takes it from the first ([`GpuSolver::sibling`])
/// instead of building it again.
#[derive(Clone)]
pub(super) struct SceneUpload {
    /// The hierarchy the shooters were built with …
    hierarchy: Hierarchy,
    /// … and the visibility the mesh was split for.
    visibility: Visibility,
    /// The shooters (triangles or flat face clusters) and their elements' order.
    pub(super) shooters: Arc<Shooters>,
    /// Per element: centre and area; normal and piece; receiving normal (bindings of group 0).
    elements: [wgpu::Buffer; 3],
    /// Entries of the patch buffer for cells (the largest plan); the receiver ranges follow.
    pub(super) max_patches: usize,
    /// Whether the largest plan with its links fits one binding (else links are off).
    links_fit: bool,
    /// The visibility mesh's vertices (CAD fans merged, split for the stereographic map).
    pub(super) vertices: wgpu::Buffer,
    /// The visibility mesh's triangles (three vertex indices each).
    pub(super) vertex_indices: wgpu::Buffer,
    pub(super) index_count: u32,
    /// The visibility mesh's chunks, for culling per face.
    pub(super) chunks: Arc<MeshChunks>,
    /// Its alpha-masked triangles, drawn whole into every map.
    pub(super) masked: Option<Arc<masked::MaskedCasters>>,
    /// The receivers' boxes, for the links and the cull.
    pub(super) receivers: Arc<ReceiverBoxes>,
    /// The specular windows' triangles ([`virtual_cells::window_corners`]).
    pub(super) window_corners: wgpu::Buffer,
    /// Per window, its first triangle and count there.
    pub(super) window_ranges: Vec<[u32; 2]>,
    /// The scene's diagonal, metres.
    pub(super) size: f64,
}

impl SceneUpload {
    /// `shooters` are [`Shooters::build`] of `scene` with `hierarchy`.
    fn new(
        gpu: &Gpu,
        scene: &RadiosityScene,
        shooters: Shooters,
        (hierarchy, visibility): (Hierarchy, Visibility),
    ) -> Self {
        let el = &scene.elements;
        let n = el.len();
        let points: Vec<ElementRecord> = (0..n)
            .map(|e| v4(el.position[e], el.area[e] as f32))
            .collect();
        let normals: Vec<ElementRecord> = (0..n)
            .map(|e| v4(el.normal(e), f32::from_bits(shooters.element_piece[e])))
            .collect();
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
        let elements = [
            storage(gpu, "element points", bytemuck::cast_slice(&points), false),
            storage(
                gpu,
                "element normals",
                bytemuck::cast_slice(&normals),
                false,
            ),
            storage(
                gpu,
                "element receiving normals",
                bytemuck::cast_slice(&receiving),
                false,
            ),
        ];
        // Room for the largest plan; links are left out where its cells would not fit
        // one binding (a cluster of millions of elements).
        let max_binding = gpu
            .device
            .limits()
            .max_storage_buffer_binding_size
            .min(gpu.device.limits().max_buffer_size);
        let mut max_patches = shooters.max_cells(scene, LINK_LEVELS);
        let links_fit = 16 * max_patches as u64 <= max_binding;
        if !links_fit {
            max_patches = shooters.max_cells(scene, 0);
        }
        let pipelines = gpu.cached(|| Pipelines::new(gpu));
        // Visibility needs only the surfaces, not their tessellation: a CAD fan's strips
        // are drawn as the triangle they fill (the same points, far fewer triangles).
        let size = scene
            .casters
            .bounds()
            .map_or(1.0, |(lo, hi)| (hi - lo).length());
        // The stereographic map projects only vertices, so a long edge bends wrongly
        // (Wallner Fig. 4.4): its mesh has no edge longer than a fraction of the scene.
        let max_edge = match visibility {
            Visibility::Hemicube => f64::INFINITY,
            Visibility::Stereographic => size * STEREOGRAPHIC_EDGE_FRACTION,
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
        let mesh = match visibility {
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
        let (corners, window_ranges) = virtual_cells::window_corners(&scene.specular);
        let window_corners = storage(gpu, "window corners", bytemuck::cast_slice(&corners), false);
        SceneUpload {
            hierarchy,
            visibility,
            shooters: Arc::new(shooters),
            elements,
            max_patches,
            links_fit,
            vertices,
            vertex_indices,
            index_count: indices.len() as u32,
            chunks: Arc::new(chunks),
            masked: masked.map(Arc::new),
            receivers: Arc::new(ReceiverBoxes::new(scene)),
            window_corners,
            window_ranges,
            size,
        }
    }
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
        let upload = SceneUpload::new(
            gpu,
            scene,
            shooters,
            (gpu_settings.hierarchy, gpu_settings.visibility),
        );
        GpuSolver::with_upload(gpu, scene, upload, initial, settings, gpu_settings)
    }

    /// A solver of the same scene for other light (`initial`) and settings: the
    /// importance solve of a view-driven one ([`crate::radiosity::view::importance`]).
    /// With the same hierarchy and visibility it shares this one's shooters, element
    /// records, visibility mesh and receivers' boxes instead of building them again
    /// (most of a solver's setup); its solution, settings and maps are its own.
    pub fn sibling(
        &self,
        initial: &InitialState,
        settings: SolverSettings,
        gpu_settings: GpuSettings,
    ) -> GpuSolver<'a> {
        let upload = &self.upload;
        if upload.hierarchy == gpu_settings.hierarchy
            && upload.visibility == gpu_settings.visibility
        {
            let upload = upload.clone();
            GpuSolver::with_upload(
                self.gpu,
                self.scene,
                upload,
                initial,
                settings,
                gpu_settings,
            )
        } else {
            GpuSolver::new(self.gpu, self.scene, initial, settings, gpu_settings)
        }
    }

    /// A solver over `upload` (of `scene`) starting from `initial`.
    fn with_upload(
        gpu: &'a Gpu,
        scene: &'a RadiosityScene,
        upload: SceneUpload,
        initial: &InitialState,
        settings: SolverSettings,
        gpu_settings: GpuSettings,
    ) -> GpuSolver<'a> {
        debug_assert!((0..scene.elements.len()).all(|e| {
            let shooters = &upload.shooters;
            let k = shooters.element_shooter[e] as usize;
            scene.reflectance[shooters.material[k]] == scene.element_reflectance(e)
        }));
        let (mut shooter_info, large_shooters) = shooter_records(scene, &upload.shooters);
        let mut gpu_settings = gpu_settings;
        // Virtual cells shoot to every receiver their window shows: no links (a cell a
        // link leaves undrawn could light receivers through a mirror).
        if !scene.specular.is_empty() || !upload.links_fit {
            gpu_settings.link_error = 0.0;
        }
        let pipelines = gpu.cached(|| Pipelines::new(gpu));
        let buffers = Buffers::new(gpu, &pipelines, scene, &upload, initial, &shooter_info);
        // The large shooters' second records live on the GPU only.
        shooter_info.truncate(upload.shooters.len());
        gpu_settings.raster = gpu_settings.raster.resolve(gpu, upload.masked.is_some());
        let compute_raster = (gpu_settings.raster == Raster::Compute).then(|| {
            raster::ComputeRaster::new(gpu, gpu.cached(|| raster::RasterPipelines::new(gpu)))
        });
        let atlas = VisibilityAtlas::new(
            gpu,
            gpu_settings.map_size,
            FIRST_BATCH as u32 * faces_per_cell(gpu_settings.visibility),
        );
        let receiver_groups = crate::radiosity::cell_receivers::ReceiverGroups::new(scene);
        let solver = GpuSolver {
            gpu,
            scene,
            settings,
            gpu_settings,
            pipelines,
            buffers,
            upload,
            choice: ShooterChoice {
                shooter_info,
                large_shooters,
                weighted: false,
                cell_weights: None,
                link_receivers: None,
                initial_power: None,
                last_power: 0.0,
            },
            compute_raster,
            atlas,
            batching: Batching {
                batch: FIRST_BATCH,
                batch_seconds: BATCH_SECONDS,
                fixed_batch: false,
                culled: (0, 0),
                batch_ranges: Vec::new(),
                receiver_groups,
            },
            perspective: Perspective {
                deferral: None,
                stages: None,
                map_store: map_store::MapStore::new(DEFAULT_MAP_STORE_BYTES),
            },
            timers: None,
            stats: ShotStats {
                shots: 0,
                triangles_drawn: 0,
                receiver_threads: 0,
                drawn: 0,
                skipped: 0,
                virtual_drawn: 0,
                times: ShotTimes::default(),
                plan_cache: PlanCache::new(DEFAULT_PLAN_CACHE_BYTES),
            },
        };
        solver.write_params(u32::MAX, 0, 0, 0..0);
        solver
    }
}

/// The shooters' records as the shader reads them (weight 1), then a second record of
/// each shooter of more than [`SMALL_SHOOTER`] elements (summed by a workgroup each;
/// `[2]` the shooter); and how many of those there are.
fn shooter_records(scene: &RadiosityScene, shooters: &Shooters) -> (Vec<ShooterRecord>, u32) {
    let mut records: Vec<ShooterRecord> = (0..shooters.len())
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
    let large: Vec<ShooterRecord> = (0..shooters.len())
        .filter(|&k| shooters.count[k] > SMALL_SHOOTER)
        .map(|k| {
            let mut record = records[k];
            record[2] = k as u32;
            record
        })
        .collect();
    let count = large.len() as u32;
    records.extend(large);
    (records, count)
}

/// A solver's own GPU buffers (its solution, the shooters' records and sums, the shot's
/// cells) and the bind group over them with the scene's shared element buffers.
pub(super) struct Buffers {
    /// The uniform [`SolveParams`].
    pub(super) params: wgpu::Buffer,
    /// Per element: rgb radiosity and the illuminance in `w`.
    pub(super) radiosity: wgpu::Buffer,
    /// Per element: rgb unshot radiosity.
    pub(super) unshot: wgpu::Buffer,
    /// The selection's record (the chosen shooter and the power sums).
    pub(super) selection: wgpu::Buffer,
    /// Per shooter its unshot power, then the selection's record.
    pub(super) shooter_power: wgpu::Buffer,
    /// The shooters' elements, shooter by shooter.
    pub(super) shooter_elements: wgpu::Buffer,
    /// The shot's cells, then per chart in front of the shooter its receivers' range.
    pub(super) patches: wgpu::Buffer,
    /// The bind group over `shared_buffers`.
    pub(super) shared: wgpu::BindGroup,
    /// The buffers `shared` binds, binding by binding (it is bound again when the
    /// held-back buffer grows: [`super::deferred`]).
    pub(super) shared_buffers: Vec<wgpu::Buffer>,
    /// Per cell of the shot: rgb unshot radiosity it shoots.
    pub(super) patch_delta: wgpu::Buffer,
    /// The shooters' records (writable: the selection's weights change).
    pub(super) shooter_buf: wgpu::Buffer,
}

impl Buffers {
    /// The buffers of a solver of `scene` over `upload`, starting from `initial`, with the
    /// shooters' `records` ([`shooter_records`]).
    fn new(
        gpu: &Gpu,
        pipelines: &Pipelines,
        scene: &RadiosityScene,
        upload: &SceneUpload,
        initial: &InitialState,
        records: &[ShooterRecord],
    ) -> Buffers {
        let shooters = &upload.shooters;
        let el = &scene.elements;
        let n = el.len();
        let start: Vec<[f32; 4]> = initial.radiosity.iter().map(|b| v4(*b, 0.0)).collect();
        let start_lit: Vec<[f32; 4]> = (0..n)
            .map(|e| v4(initial.radiosity[e], initial.illuminance[e] as f32))
            .collect();
        let max_patches = upload.max_patches;
        let params = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("radiosity params"),
            size: std::mem::size_of::<SolveParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let shooter_elements = storage(
            gpu,
            "shooter elements",
            bytemuck::cast_slice(&shooters.elements),
            true,
        );
        let radiosity = storage(gpu, "radiosity", bytemuck::cast_slice(&start_lit), true);
        let unshot = storage(gpu, "unshot", bytemuck::cast_slice(&start), true);
        // Writable: the selection's weights change (view-driven shooting).
        let shooter_buf = storage(gpu, "shooters", bytemuck::cast_slice(records), true);
        // The selection record follows the shooters' sums.
        let shooter_power = storage(
            gpu,
            "shooter power",
            &vec![0u8; 16 * (shooters.len() + 3)],
            true,
        );
        let selection = storage(gpu, "selection", &[0u8; 48], true);
        let patches = storage(
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
        // Every receiver's reaches as the link search gives them until a view scales them
        // (`REACH_SCALE_BINDING`, [`GpuSolver::set_receiver_weights`]).
        let reach_scale = storage(
            gpu,
            "reach scale",
            bytemuck::cast_slice(&vec![1f32; n.max(1)]),
            true,
        );
        let [element_points, element_normals, element_receiving] = upload.elements.clone();
        let shared_buffers = vec![
            params.clone(),
            element_points,
            shooter_elements.clone(),
            radiosity.clone(),
            unshot.clone(),
            shooter_buf.clone(),
            shooter_power.clone(),
            patches.clone(),
            patch_delta.clone(),
            element_normals,
            held,
            element_receiving,
            held_back,
            reach_scale,
        ];
        let shared = shared_bind_group(gpu, pipelines, &shared_buffers);
        Buffers {
            params,
            radiosity,
            unshot,
            selection,
            shooter_power,
            shooter_elements,
            patches,
            shared,
            shared_buffers,
            patch_delta,
            shooter_buf,
        }
    }
}
