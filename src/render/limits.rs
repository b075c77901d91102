//! What a scene asks of the GPU, checked against the device's limits before anything is
//! uploaded: a refusal that says what to change, instead of a wgpu validation panic or an
//! allocation that ends in the out-of-memory killer.

use crate::gpu::{Gpu, GpuError};
use crate::scene::Scene;
use crate::shadow::ShadowTechnique;

use super::gpu_scene::Vertex;
use super::paraboloid::tessellated_count;
use super::shadows::ShadowSettings;

/// Bytes per tessellated paraboloid caster triangle (three `f32` positions).
const CASTER_TRIANGLE_BYTES: u64 = 36;

/// Checks `scene` drawn with `shadows` fits `gpu`: the vertex buffer, the shadow layers
/// (two paraboloid maps or one mask layer per luminaire) and the paraboloid casters after
/// tessellation.
pub fn check_scene(gpu: &Gpu, scene: &Scene, shadows: &ShadowSettings) -> Result<(), GpuError> {
    let limits = gpu.device.limits();
    let max_buffer = limits.max_buffer_size;
    let triangles = scene.triangle_count() as u64;
    let vertex_bytes = triangles * 3 * std::mem::size_of::<Vertex>() as u64;
    if vertex_bytes > max_buffer {
        return Err(scene_refusal(scene, format!(
            "the scene's {triangles} triangles need {} MB of vertices; this GPU allows buffers of {} MB: simplify or split the model (about {} triangles fit)",
            vertex_bytes >> 20,
            max_buffer >> 20,
            max_buffer / (3 * std::mem::size_of::<Vertex>() as u64)
        )));
    }
    let lights = scene.luminaires.len() as u64;
    let max_layers = u64::from(limits.max_texture_array_layers);
    let (layers, per) = match shadows.technique {
        ShadowTechnique::Paraboloid => (2 * lights, "two paraboloid shadow maps"),
        ShadowTechnique::Volumes => (lights, "one shadow-volume mask layer"),
        ShadowTechnique::None => (0, ""),
    };
    if layers > max_layers {
        return Err(scene_refusal(scene, format!(
            "the scene's {lights} luminaires need {per} each, {layers} texture layers; this GPU allows {max_layers}: use {}--shadows none, or fewer luminaires",
            if shadows.technique == ShadowTechnique::Paraboloid {
                "--shadows volumes (one layer each), "
            } else {
                ""
            }
        )));
    }
    if shadows.technique == ShadowTechnique::Paraboloid && lights > 0 {
        let budget = (max_buffer / CASTER_TRIANGLE_BYTES) as usize;
        let count = tessellated_count(&scene.caster_mesh(), shadows.tessellation_m, budget + 1);
        if count > budget {
            return Err(scene_refusal(scene, format!(
                "paraboloid shadows tessellate every caster to {} m edges: this scene's large faces would need more than {budget} triangles ({} MB; this GPU allows {} MB). Use --shadows volumes, or split the large faces",
                shadows.tessellation_m,
                (count as u64 * CASTER_TRIANGLE_BYTES) >> 20,
                max_buffer >> 20
            )));
        }
    }
    Ok(())
}

fn refusal(message: String) -> GpuError {
    GpuError::Limit(message)
}

fn scene_refusal(scene: &Scene, message: String) -> GpuError {
    refusal(format!("{}: {message}", scene.path.display()))
}

/// Bytes per radiosity element in the solver's largest storage buffer (position + area,
/// normal + triangle).
const RADIOSITY_ELEMENT_BYTES: u64 = 32;

/// Checks the radiosity solver's per-element buffers for `elements` fit `gpu`.
pub fn check_radiosity(gpu: &Gpu, elements: usize) -> Result<(), GpuError> {
    let limits = gpu.device.limits();
    let max = limits
        .max_buffer_size
        .min(limits.max_storage_buffer_binding_size);
    let need = elements as u64 * RADIOSITY_ELEMENT_BYTES;
    if need > max {
        return Err(refusal(format!(
            "{elements} radiosity elements need {} MB per buffer; this GPU binds at most {} MB: lower --texel-density (about {} elements fit)",
            need >> 20,
            max >> 20,
            max / RADIOSITY_ELEMENT_BYTES
        )));
    }
    Ok(())
}
