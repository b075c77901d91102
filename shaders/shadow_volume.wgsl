// Stencil shadow volumes (Wallner ch. 1): the volume geometry is extruded to infinity in
// the vertex shader (w = 0), counted in the stencil buffer with two-sided stencil, then a
// full-screen pass writes 1 into the light's layer of the shadow mask wherever the count
// is not 0 (a colour output, so the stencil test applies on every backend).
// Also the debug views: volumes (translucent yellow) and silhouette edges (pink).

struct VolumeLight {
    view_proj: mat4x4<f32>,
    // xyz: the light's position (w = 1) or the direction toward it (w = 0).
    light: vec4<f32>,
    // Lights at infinity in orthographic (plan) views, whose far plane would otherwise
    // cut volumes extruded to infinity (and the cut edges of neighbouring sides need not
    // meet): w > 0: each vertex along the light down to the plane z = x (metres), so a
    // side reaches no further than the lowest receiver and a low edge's side covers only
    // the plan its own shadow can fall on (the stencil fill follows the edges' heights;
    // Wallner §1.9's depth bounds, which WebGPU lacks, bound it the same way); else
    // x > 0: every vertex by the length x.
    // y: the depth bias of the volume's finite vertices (added to the depth, z/w), so a lit
    // face's own cap counts as behind it. Added here rather than by the rasterizer's depth
    // bias: that one is scaled by the largest exponent of the primitive's depth, which is
    // unbounded for a side that passes the camera's eye plane without depth clipping
    // (camera inside a volume, z-fail): some drivers then push the whole side to the far
    // plane.
    extrude: vec4<f32>,
};

@group(0) @binding(0) var<uniform> volume: VolumeLight;

// p.w = 1: a mesh vertex; p.w = 0: the same vertex pushed to infinity away from the light.
@vertex
fn vs_volume(@location(0) p: vec4<f32>) -> @builtin(position) @invariant vec4<f32> {
    var v = vec4<f32>(p.xyz, 1.0);
    var biased = true;
    if (p.w == 0.0) {
        if (volume.light.w == 0.0) {
            if (volume.extrude.w > 0.0) {
                let t = (p.z - volume.extrude.x) / max(volume.light.z, 1e-3);
                v = vec4<f32>(p.xyz - volume.light.xyz * t, 1.0);
            } else if (volume.extrude.x > 0.0) {
                v = vec4<f32>(p.xyz - volume.light.xyz * volume.extrude.x, 1.0);
            } else {
                v = vec4<f32>(-volume.light.xyz, 0.0);
                biased = false;
            }
        } else {
            v = vec4<f32>(p.xyz - volume.light.xyz, 0.0);
            biased = false;
        }
    }
    var clip = volume.view_proj * v;
    if (biased) {
        // z/w grows by the bias wherever only finite vertices span the primitive (z is
        // linear in clip space), and less toward a vertex at infinity.
        clip.z = clip.z + volume.extrude.y * clip.w;
    }
    return clip;
}

@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

// Runs where the stencil count is not 0: the pixel is inside the light's shadow volume.
@fragment
fn fs_mark() -> @location(0) u32 {
    return 1u;
}

// The counting pass writes no colour (its target's write mask is empty).
@fragment
fn fs_count() -> @location(0) u32 {
    return 0u;
}

@fragment
fn fs_debug_volume() -> @location(0) vec4<f32> {
    return vec4<f32>(1.0, 0.85, 0.0, 0.18);
}

@fragment
fn fs_debug_edge() -> @location(0) vec4<f32> {
    return vec4<f32>(1.0, 0.2, 0.75, 1.0);
}

// Plan views (shadow profiles): the visible surfaces' depth and which surface each pixel
// sees (the instance index of the draw: 1 ground, 2 model).
struct SurfaceOut {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) @interpolate(flat) id: u32,
};

@vertex
fn vs_surface(@location(0) p: vec4<f32>, @builtin(instance_index) id: u32) -> SurfaceOut {
    var out: SurfaceOut;
    out.clip = volume.view_proj * vec4<f32>(p.xyz, 1.0);
    out.id = id;
    return out;
}

@fragment
fn fs_surface(in: SurfaceOut) -> @location(0) u32 {
    return in.id;
}
