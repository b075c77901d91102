//! Recording a batch's work: the shooting cells' records, their visibility maps (render
//! pipeline or compute rasterizer) into the atlas, and their receive dispatches.

use glam::Mat4;

use super::pipelines::Pipelines;
use super::setup::SceneUpload;
use super::Visibility;
use super::{
    dispatch_groups, faces_per_cell, raster, v4, virtual_cells, GpuSolver, TileView, FACE_STRIDE,
};
use crate::gpu::{Gpu, GpuError};
use crate::radiosity::atlas::VisibilityAtlas;
use crate::radiosity::cell_receivers;
use crate::radiosity::form_factor::FormFactorKind;
use crate::radiosity::links::{Links, LINK_LEVELS};
use crate::radiosity::polygon::frame;
use crate::radiosity::shooters::ShotPlan;

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
    receivers: [u32; 4],
    pad: [[f32; 4]; 4],
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

/// A cell a batch draws: one of the plan's patches, or a virtual cell of one.
#[derive(Clone, Copy)]
pub(super) struct BatchCell<'c> {
    /// The plan's patch (a virtual cell's real cell: it shoots that cell's power).
    pub(super) patch: usize,
    /// A virtual cell ([`virtual_cells`]) and the batch record of the cell it images.
    pub(super) image: Option<(&'c virtual_cells::VirtualCell, u32)>,
}

impl<'a> GpuSolver<'a> {
    /// The visibility faces' projection, and its far plane: around the scene's size.
    fn projection(&self) -> (Mat4, f32) {
        let (near, far) = (
            (1e-4 * self.upload.size) as f32,
            (2.0 * self.upload.size) as f32,
        );
        let m = Mat4::perspective_rh(std::f32::consts::FRAC_PI_2, 1.0, near, far);
        (m, far)
    }

    /// The shooting records of a batch's `cells` (the plan's patches and their virtual
    /// cells), each facing its own normal, with their links, and their visibility faces:
    /// those of the `k`-th are the atlas's tiles from `k` × faces per cell; `receivers`
    /// per cell its receive pass's records (first, count) and threads.
    fn shot_records(
        &self,
        plan: &ShotPlan,
        links: &Links,
        cells: &[BatchCell<'_>],
        receivers: &[[u32; 4]],
    ) -> (Vec<u8>, Vec<u8>, Vec<TileView>) {
        let faces_per_patch = faces_per_cell(self.gpu_settings.visibility) as usize;
        let (projection, far) = self.projection();
        let tolerance = self.upload.receivers.plane_tolerance() as f32;
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
            let eye = (p.centroid + n * 1e-6 * self.upload.size).as_vec3();
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
                    let [first, count] = self.upload.window_ranges[v.window];
                    let plane = v.plane.as_vec4().to_array();
                    (v4(v.tint, 0.0), plane, [first, count, parent, 0], 0.0)
                }
                None => ([1.0; 4], [0.0, 0.0, 0.0, 1.0], [0; 4], links.reach[patch]),
            };
            let mut clip = plane;
            if cell.image.is_some() {
                clip[3] -= (1e-4 * self.upload.size) as f32;
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
                    (1e-4 * self.upload.size) as f32,
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
                receivers: receivers[k],
                pad: [[0.0; 4]; 4],
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

    /// Records the maps of the cells `drawn` and their virtual cells into the atlas (which
    /// holds them; the virtual cells' after all drawn cells') and their receive
    /// dispatches.
    pub(super) fn record_part(
        &mut self,
        enc: &mut wgpu::CommandEncoder,
        plan: &ShotPlan,
        links: &Links,
        (drawn, images): (&[usize], &[Vec<virtual_cells::VirtualCell>]),
        stored: &[Option<u32>],
    ) -> Result<(), GpuError> {
        let cells = batch_cells(drawn, images);
        let (runs, receivers) = self.cell_receivers(plan, links, &cells);
        let (shots, faces, views) = self.shot_records(plan, links, &cells, &receivers);
        let faces_per_cell = faces_per_cell(self.gpu_settings.visibility);
        // Kept maps go back into their tiles; those tiles are not drawn.
        let restored: Vec<bool> = (0..views.len() as u32)
            .map(|tile| {
                stored
                    .get((tile / faces_per_cell) as usize)
                    .is_some_and(|s| s.is_some())
            })
            .collect();
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
        let shot_bind = self.gpu.bind_group(
            "shot",
            &self.pipelines.shot_layout,
            &[
                (0, binding(&shot_buf, std::mem::size_of::<ShotGpu>())),
                (1, wgpu::BindingResource::TextureView(&self.atlas.view)),
                (2, shot_buf.as_entire_binding()),
                (3, self.upload.window_corners.as_entire_binding()),
                (4, runs.as_entire_binding()),
            ],
        );
        let maps = MapPass {
            gpu: self.gpu,
            pipelines: &self.pipelines,
            atlas: &self.atlas,
            upload: &self.upload,
            chunk_culling: self.gpu_settings.chunk_culling,
            views: &views,
            restored: &restored,
        };
        self.stats.triangles_drawn += match &mut self.compute_raster {
            Some(compute) => maps.record_compute(
                compute,
                enc,
                &face_buf,
                queries.as_ref().map(|q| q.maps_compute()),
            ),
            None => maps.record_render(
                enc,
                &face_buf,
                // A virtual cell's tiles follow the real cells'.
                drawn.len() as u32 * faces_per_cell,
                queries.as_ref().map(|q| q.maps()),
            ),
        };
        // After the maps: the compute rasterizer writes every tile of the batch.
        for (k, slot) in stored.iter().enumerate() {
            if let &Some(at) = slot {
                let cell = (k as u32 * faces_per_cell, at, faces_per_cell);
                self.perspective
                    .map_store
                    .copy_cell(enc, &self.atlas, cell, false);
            }
        }
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("receive"),
            timestamp_writes: queries.as_ref().map(|q| q.receive()),
        });
        pass.set_pipeline(&self.pipelines.receive);
        pass.set_bind_group(0, &self.buffers.shared, &[]);
        for k in 0..cells.len() as u64 {
            // The real cells first, then their virtual cells.
            if k == drawn.len() as u64 {
                pass.set_pipeline(&self.pipelines.receive_through_windows);
            }
            let threads = receivers[k as usize][2];
            self.stats.receiver_threads += u64::from(threads);
            if threads > 0 {
                pass.set_bind_group(1, &shot_bind, &[(k * SHOT_STRIDE) as u32]);
                dispatch_groups(&mut pass, threads.div_ceil(64));
            }
        }
        Ok(())
    }

    /// The receive passes' records of a batch's `cells` ([`cell_receivers`]) in one
    /// buffer, and per cell its first record, record count and threads: a real cell's
    /// receivers are those of the batch's ranges that may take its light, a virtual
    /// cell's all of them.
    fn cell_receivers(
        &self,
        plan: &ShotPlan,
        links: &Links,
        cells: &[BatchCell<'_>],
    ) -> (wgpu::Buffer, Vec<[u32; 4]>) {
        let tolerance = self.upload.receivers.plane_tolerance();
        let mut runs: Vec<cell_receivers::ReceiverRecord> = Vec::new();
        // The batch's ranges whole, for the virtual cells.
        let mut threads = 0;
        for &(first, count, hold) in &self.batching.batch_ranges {
            runs.push([first, threads, count, hold]);
            threads += count;
        }
        let all = [0, runs.len() as u32, threads, 0];
        let mut receivers = Vec::with_capacity(cells.len());
        for cell in cells {
            if cell.image.is_some() {
                receivers.push(all);
                continue;
            }
            let start = runs.len();
            let own = self.batching.receiver_groups.cell_records(
                (plan, links),
                cell.patch,
                tolerance,
                &self.batching.batch_ranges,
                &mut runs,
            );
            receivers.push(match own {
                Some(threads) => [start as u32, (runs.len() - start) as u32, threads, 0],
                None => all,
            });
        }
        if runs.is_empty() {
            runs.push([0; 4]);
        }
        let buffer = self.gpu.buffer_with(
            "cell receivers",
            bytemuck::cast_slice(&runs),
            wgpu::BufferUsages::STORAGE,
        );
        (buffer, receivers)
    }
}

/// A buffer bound from its start, `size` bytes (a dynamic-offset uniform's one record).
fn binding(buffer: &wgpu::Buffer, size: usize) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset: 0,
        size: wgpu::BufferSize::new(size as u64),
    })
}

/// A batch's cells: the drawn (real) cells in order, then each one's virtual cells
/// ([`virtual_cells`]), each with the batch record of the cell it images (its real cell,
/// or the virtual cell before it in the chain).
fn batch_cells<'c>(
    drawn: &[usize],
    images: &'c [Vec<virtual_cells::VirtualCell>],
) -> Vec<BatchCell<'c>> {
    let mut cells: Vec<BatchCell<'c>> = drawn
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
    cells
}

/// What drawing a batch's visibility maps reads from its solver: the tiles' views and
/// which of them a kept map restores (those are not drawn).
struct MapPass<'s> {
    gpu: &'s Gpu,
    pipelines: &'s Pipelines,
    atlas: &'s VisibilityAtlas,
    upload: &'s SceneUpload,
    chunk_culling: bool,
    views: &'s [TileView],
    restored: &'s [bool],
}

impl MapPass<'_> {
    /// Draws the tiles with the compute rasterizer; returns the triangles drawn.
    fn record_compute(
        &self,
        compute: &mut raster::ComputeRaster,
        enc: &mut wgpu::CommandEncoder,
        face_buf: &wgpu::Buffer,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> u64 {
        let (mut ranges, mut triangles) = (Vec::new(), 0);
        let mut work = raster::RasterWork::new();
        for (tile, view) in self.views.iter().enumerate() {
            if self.restored[tile] {
                continue;
            }
            self.upload
                .chunks
                .visible(view, self.chunk_culling, &mut ranges);
            for &(first, count) in &ranges {
                work.push(tile as u32, first, count);
                triangles += u64::from(count / 3);
            }
        }
        compute.record(
            self.gpu,
            enc,
            self.atlas,
            (&self.upload.vertices, &self.upload.vertex_indices),
            face_buf,
            &work,
            self.views.len() as u32,
            timestamps,
        );
        triangles
    }

    /// Draws the tiles in one render pass, each cleared by its own draw; tiles from
    /// `clipped_from` on (the virtual cells') draw nothing beyond their clip plane.
    /// Returns the triangles drawn.
    fn record_render(
        &self,
        enc: &mut wgpu::CommandEncoder,
        face_buf: &wgpu::Buffer,
        clipped_from: u32,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> u64 {
        let (mut ranges, mut triangles) = (Vec::new(), 0);
        let face_bind = self.gpu.bind_group(
            "faces",
            &self.pipelines.face_layout,
            &[(0, binding(face_buf, std::mem::size_of::<FaceGpu>()))],
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
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_vertex_buffer(0, self.upload.vertices.slice(..));
        pass.set_index_buffer(
            self.upload.vertex_indices.slice(..),
            wgpu::IndexFormat::Uint32,
        );
        let size = self.atlas.size;
        for (tile, view) in self.views.iter().enumerate() {
            if self.restored[tile] {
                continue;
            }
            let tile = tile as u32;
            let (x, y) = self.atlas.origin(tile);
            pass.set_viewport(x as f32, y as f32, size as f32, size as f32, 0.0, 1.0);
            pass.set_scissor_rect(x, y, size, size);
            pass.set_bind_group(0, &face_bind, &[(u64::from(tile) * FACE_STRIDE) as u32]);
            pass.set_pipeline(&self.pipelines.clear_tile);
            pass.draw(0..3, 0..1);
            let clipped = tile >= clipped_from;
            pass.set_pipeline(if clipped {
                &self.pipelines.visibility_clipped
            } else {
                &self.pipelines.visibility
            });
            self.upload
                .chunks
                .visible(view, self.chunk_culling, &mut ranges);
            for &(first, count) in &ranges {
                pass.draw_indexed(first..first + count, 0, 0..1);
                triangles += u64::from(count / 3);
            }
            if let Some(masked) = &self.upload.masked {
                masked.draw(&mut pass, clipped);
                triangles += u64::from(masked.triangle_count());
                pass.set_vertex_buffer(0, self.upload.vertices.slice(..));
            }
        }
        triangles
    }
}
