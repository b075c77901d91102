//! What a scene asks of the GPU, checked against the device's limits before anything is
//! uploaded: a refusal that says what to change, instead of a wgpu validation panic or an
//! allocation that ends in the out-of-memory killer.

use crate::gpu::{Gpu, GpuError};
use crate::scene::Scene;
use crate::shadow::ShadowTechnique;

use super::gpu_scene::Vertex;
use super::paraboloid::tessellated_count;
use super::shadows::ShadowSettings;

/// Bytes per tessellated paraboloid caster triangle (three vertices: position, texture
/// coordinate and mask).
const CASTER_TRIANGLE_BYTES: u64 =
    3 * std::mem::size_of::<super::cutout_gpu::CasterVertex>() as u64;
/// Most bytes of tessellated casters (1.9 M triangles): beyond, the edges get coarser,
/// so tessellation stays a fraction of a second and a few hundred MB at most.
const MAX_CASTER_BYTES: u64 = 128 << 20;

/// Checks `scene` drawn with `shadows` fits `gpu`: the vertex buffer, the shadow layers
/// (two paraboloid maps or one mask layer per luminaire) and the paraboloid casters after
/// tessellation, whose edge length is made coarser where the requested one would not fit
/// (then `shadows.coarsened_from_m` holds the one asked for and
/// [`ShadowSettings::warning`] says so). Refusals name the options to change in
/// backquotes (`` `shadows` ``, `` `texel_density` ``).
pub fn check_scene(gpu: &Gpu, scene: &Scene, shadows: &mut ShadowSettings) -> Result<(), GpuError> {
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
            "the scene's {lights} luminaires need {per} each, {layers} texture layers; this GPU allows {max_layers}: use {}`shadows` none, or fewer luminaires",
            if shadows.technique == ShadowTechnique::Paraboloid {
                "`shadows` volumes (one layer each), "
            } else {
                ""
            }
        )));
    }
    if shadows.technique == ShadowTechnique::Paraboloid && lights > 0 {
        fit_tessellation(scene, shadows, max_buffer)?;
    }
    Ok(())
}

/// Coarsest caster edge tried before paraboloid shadows are refused, metres.
const MAX_TESSELLATION_M: f64 = 64.0;

/// Doubles `shadows.tessellation_m` until the tessellated casters fit `max_buffer` bytes
/// (large faces of real buildings: a 300 m ground plane at 0.25 m is 2.9 M triangles).
fn fit_tessellation(
    scene: &Scene,
    shadows: &mut ShadowSettings,
    max_buffer: u64,
) -> Result<(), GpuError> {
    let budget = (max_buffer.min(MAX_CASTER_BYTES) / CASTER_TRIANGLE_BYTES) as usize;
    let cutouts = scene.caster_cutouts();
    let casters = super::paraboloid::merged_casters(
        &scene.caster_mesh(),
        &scene.caster_objects(),
        cutouts.as_deref(),
    )
    .mesh;
    let asked = shadows.tessellation_m;
    let mut edge = asked;
    while tessellated_count(&casters, edge, budget + 1) > budget {
        edge *= 2.0;
        if edge > MAX_TESSELLATION_M {
            return Err(scene_refusal(
                scene,
                format!(
                    "paraboloid shadows tessellate every caster: this scene's faces need more than {budget} triangles even at {MAX_TESSELLATION_M} m edges. Use `shadows` volumes, or split the large faces"
                ),
            ));
        }
    }
    if edge > asked {
        shadows.coarsened_from_m.get_or_insert(asked);
        shadows.tessellation_m = edge;
    }
    Ok(())
}

fn refusal(message: String) -> GpuError {
    GpuError::Limit(message)
}

fn scene_refusal(scene: &Scene, message: String) -> GpuError {
    refusal(format!("{}: {message}", scene.path.display()))
}

/// Bytes per radiosity element in each of the solver's per-element storage buffers
/// (position and area; normal and shooter; receiving normal; radiosity; unshot radiosity:
/// `radiosity/gpu.rs`
/// checks its records against this), so a binding of 128 MiB holds 8.4 M elements.
pub const RADIOSITY_ELEMENT_BYTES: u64 = 16;

/// Storage buffers the radiosity solver binds per compute stage (its receive passes: 13
/// in bind group 0, 3 in group 1; `radiosity.wgsl`).
pub const RADIOSITY_STORAGE_BUFFERS: u32 = 16;

/// Checks the radiosity solver's per-element buffers for `elements` fit `gpu`, and that it
/// binds as many storage buffers as the solver needs.
pub fn check_radiosity(gpu: &Gpu, elements: usize) -> Result<(), GpuError> {
    let limits = gpu.device.limits();
    if limits.max_storage_buffers_per_shader_stage < RADIOSITY_STORAGE_BUFFERS {
        return Err(refusal(format!(
            "radiosity binds {RADIOSITY_STORAGE_BUFFERS} storage buffers per shader stage; this GPU binds at most {}",
            limits.max_storage_buffers_per_shader_stage
        )));
    }
    let max = limits
        .max_buffer_size
        .min(limits.max_storage_buffer_binding_size);
    let need = elements as u64 * RADIOSITY_ELEMENT_BYTES;
    if need > max {
        return Err(refusal(format!(
            "{elements} radiosity elements need {} MB per buffer; this GPU binds at most {} MB: lower `texel_density` (about {} elements fit)",
            need >> 20,
            max >> 20,
            max / RADIOSITY_ELEMENT_BYTES
        )));
    }
    Ok(())
}
