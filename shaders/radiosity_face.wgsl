// One face of a shooting cell's visibility map, as the hardware pipeline
// (radiosity_visibility.wgsl) and the compute rasterizer (radiosity_raster.wgsl) both read
// it: a hemicube face (a 90° perspective view) or the stereographic map of the hemisphere.

struct Face {
    view_proj: mat4x4<f32>,
    // xyz eye; w 1 for the stereographic projection.
    eye: vec4<f32>,
    // Stereographic frame: tangent, bitangent, normal; the far plane in normal.w.
    tangent: vec4<f32>,
    bitangent: vec4<f32>,
    normal: vec4<f32>,
    // A virtual shooter's clip plane (lighting/specular.rs): only what lies where
    // dot(clip.xyz, p) + clip.w >= 0 is drawn (what is behind its mirror or pane is not
    // seen through it); (0, 0, 0, 1) for a real shooter.
    clip: vec4<f32>,
};

// The clip position of `position` in face `f`'s projection.
fn face_clip_of(f: Face, position: vec3<f32>) -> vec4<f32> {
    if (f.eye.w > 0.5) {
        let v = position - f.eye.xyz;
        let dist = length(v);
        let local = vec3<f32>(dot(v, f.tangent.xyz), dot(v, f.bitangent.xyz), dot(v, f.normal.xyz)) / max(dist, 1e-20);
        let far = f.normal.w;
        // Behind the hemisphere: pushed outside the depth range (clipped).
        let depth = select(2.0, dist / far, local.z > -0.05);
        return vec4<f32>(stereographic_project(local), depth, 1.0);
    }
    return f.view_proj * vec4<f32>(position, 1.0);
}

// Whether a surface point at `world` lies behind a stereographic map's plane (it stores
// nothing there).
fn behind_stereographic(f: Face, world: vec3<f32>) -> bool {
    return f.eye.w > 0.5 && dot(world - f.eye.xyz, f.normal.xyz) < 0.0;
}

// Whether a virtual shooter's face clips a surface point at `world` away.
fn clipped_away(f: Face, world: vec3<f32>) -> bool {
    return dot(f.clip.xyz, world) + f.clip.w < 0.0;
}

// Whether face `f` stores nothing for a surface point at `world`: behind a stereographic
// map's plane, or clipped away.
fn face_skips(f: Face, world: vec3<f32>) -> bool {
    return behind_stereographic(f, world) || clipped_away(f, world);
}
