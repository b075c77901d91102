//! The alpha-masked triangles of the visibility mesh (the tail after
//! [`RadiosityScene::visibility_solid_count`]): drawn into every visibility map after the
//! solid chunks, as their own vertex stream with texture coordinates, by a pipeline that
//! discards their holes (`shaders/cutout.wgsl`), so light passes the holes between
//! surfaces as it does from the luminaires.

use wgpu::util::DeviceExt;

use super::super::scene::RadiosityScene;
use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::render::cutout_gpu::{piece_vertices, CasterVertex, MaskBuffers};
use crate::render::paraboloid::tessellate_each;

/// The masked casters on the GPU, with the pipeline that draws them.
pub(super) struct MaskedCasters {
    pipeline: wgpu::RenderPipeline,
    /// The same for a virtual cell's tiles: with its clip plane.
    clipped: wgpu::RenderPipeline,
    masks: wgpu::BindGroup,
    vertices: wgpu::Buffer,
    vertex_count: u32,
}

impl MaskedCasters {
    /// The masked triangles of `scene`'s visibility mesh, split to `max_edge` metres (the
    /// stereographic map's limit; infinite for hemicubes), and their pipeline (`module`:
    /// the visibility shader, `faces`: its face bind group layout); `None` without masks.
    pub(super) fn new(
        gpu: &Gpu,
        scene: &RadiosityScene,
        module: &wgpu::ShaderModule,
        faces: &wgpu::BindGroupLayout,
        max_edge: f64,
    ) -> Option<MaskedCasters> {
        let cutouts = scene.visibility_cutouts()?;
        let mesh = scene.visibility_mesh();
        let solid = scene.visibility_solid_count();
        let tail = Mesh {
            positions: mesh.positions.clone(),
            triangles: mesh.triangles[solid..].to_vec(),
        };
        let mut data: Vec<CasterVertex> = Vec::new();
        tessellate_each(&tail, max_edge, |k, piece| {
            data.extend(piece_vertices(mesh, Some(cutouts), solid + k, piece));
            true
        });
        if data.is_empty() {
            return None;
        }
        let vertices = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("radiosity masked casters"),
                contents: bytemuck::cast_slice(&data),
                usage: wgpu::BufferUsages::VERTEX,
            });
        let mask_layout = MaskBuffers::layout(gpu);
        let layout = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("radiosity visibility, masked"),
                bind_group_layouts: &[Some(faces), Some(&mask_layout)],
                immediate_size: 0,
            });
        let pipeline = |fragment: &str| {
            gpu.caster_depth_pipeline(
                "radiosity visibility, masked",
                &layout,
                module,
                ("vs_visibility_masked", fragment),
                CasterVertex::LAYOUT,
                super::super::atlas::DEPTH_FORMAT,
                &[Some(super::super::atlas::MAP_FORMAT.into())],
            )
        };
        let (pipeline, clipped) = (
            pipeline("fs_visibility_masked"),
            pipeline("fs_visibility_masked_clipped"),
        );
        let masks = MaskBuffers::new(gpu, Some(cutouts)).bind_group(gpu, &mask_layout);
        Some(MaskedCasters {
            pipeline,
            clipped,
            masks,
            vertices,
            vertex_count: data.len() as u32,
        })
    }

    /// Draws them into the tile `pass` is set up for (its face bind group set; `clipped`:
    /// a virtual cell's, with its clip plane); leaves the pass with this pipeline.
    pub(super) fn draw(&self, pass: &mut wgpu::RenderPass<'_>, clipped: bool) {
        pass.set_pipeline(if clipped {
            &self.clipped
        } else {
            &self.pipeline
        });
        pass.set_bind_group(1, &self.masks, &[]);
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.draw(0..self.vertex_count, 0..1);
    }

    /// Triangles drawn per map.
    pub(super) fn triangle_count(&self) -> u32 {
        self.vertex_count / 3
    }
}

/// The solid part of `scene`'s visibility mesh (all of it without alpha masks).
pub(super) fn solid_visibility_mesh(scene: &RadiosityScene) -> std::borrow::Cow<'_, Mesh> {
    let mesh = scene.visibility_mesh();
    let solid = scene.visibility_solid_count();
    if solid == mesh.triangles.len() {
        return std::borrow::Cow::Borrowed(mesh);
    }
    std::borrow::Cow::Owned(Mesh {
        positions: mesh.positions.clone(),
        triangles: mesh.triangles[..solid].to_vec(),
    })
}
