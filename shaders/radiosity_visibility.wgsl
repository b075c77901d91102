// The visibility map of a shooting patch: the distance from the patch centre to the
// nearest surface, per texel of a hemicube face (a 90° perspective view) or of the
// stereographic projection of the hemisphere (Wallner §2.3: only vertices are projected,
// so long edges bend wrongly; the hemicube is exact). Needs cutout.wgsl and
// radiosity_face.wgsl before it.

@group(0) @binding(0) var<uniform> face: Face;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    // The map coordinates (clip.xy): at a fragment, its pixel centre's.
    @location(1) map: vec2<f32>,
};

// The clip position of `position` in the face's projection.
fn face_clip(position: vec3<f32>) -> vec4<f32> {
    return face_clip_of(face, position);
}

// The distance stored for a fragment at `world` (behind a stereographic map: none), at
// map coordinates `map` on a triangle with normal `normal` (any length). A hemicube face
// interpolates `world` with perspective, so it lies on the pixel centre's ray; a
// stereographic map interpolates it linearly across the chords it draws, so it lies on
// the triangle beside that ray: the distance is taken where the ray meets the triangle's
// plane, as the compute rasterizer stores it and the receive pass expects it.
fn face_distance(world: vec3<f32>, map: vec2<f32>, normal: vec3<f32>) -> vec4<f32> {
    if (behind_stereographic(face, world)) {
        discard;
    }
    var d = distance(world, face.eye.xyz);
    if (face.eye.w > 0.5) {
        let local = stereographic_ray(map);
        let ray = local.x * face.tangent.xyz + local.y * face.bitangent.xyz + local.z * face.normal.xyz;
        let along = dot(normal, ray);
        let t = dot(normal, world - face.eye.xyz) / along;
        if (t > 0.0 && abs(along) > 1e-6 * length(normal) * length(ray)) {
            d = t * length(ray);
        }
    }
    return vec4<f32>(d, 0.0, 0.0, 0.0);
}

// A fragment's triangle's normal (unnormalised), from how `world` changes across pixels;
// taken before anything is discarded (derivatives need the whole quad).
fn triangle_normal(world: vec3<f32>) -> vec3<f32> {
    return cross(dpdx(world), dpdy(world));
}

@vertex
fn vs_visibility(@location(0) position: vec3<f32>) -> VertexOut {
    var out: VertexOut;
    out.world = position;
    out.clip = face_clip(position);
    out.map = out.clip.xy;
    return out;
}

@fragment
fn fs_visibility(in: VertexOut) -> @location(0) vec4<f32> {
    return face_distance(in.world, in.map, triangle_normal(in.world));
}

// A virtual shooter's face (radiosity/gpu/virtual_cells.rs): nothing beyond its clip
// plane. An entry of its own, so a real shooter's fragments pay nothing for it.
@fragment
fn fs_visibility_clipped(in: VertexOut) -> @location(0) vec4<f32> {
    let normal = triangle_normal(in.world);
    if (clipped_away(face, in.world)) {
        discard;
    }
    return face_distance(in.world, in.map, normal);
}

// Alpha-masked casters (cutout.wgsl, before this file): their holes block nothing.
struct MaskedOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) @interpolate(flat) mask: u32,
    @location(3) map: vec2<f32>,
};

@vertex
fn vs_visibility_masked(@location(0) position: vec3<f32>, @location(1) uv: vec2<f32>, @location(2) mask: u32) -> MaskedOut {
    var out: MaskedOut;
    out.world = position;
    out.clip = face_clip(position);
    out.uv = uv;
    out.mask = mask;
    out.map = out.clip.xy;
    return out;
}

@fragment
fn fs_visibility_masked(in: MaskedOut) -> @location(0) vec4<f32> {
    let normal = triangle_normal(in.world);
    if (in_cutout_hole(in.uv, in.mask)) {
        discard;
    }
    return face_distance(in.world, in.map, normal);
}

@fragment
fn fs_visibility_masked_clipped(in: MaskedOut) -> @location(0) vec4<f32> {
    let normal = triangle_normal(in.world);
    if (in_cutout_hole(in.uv, in.mask) || clipped_away(face, in.world)) {
        discard;
    }
    return face_distance(in.world, in.map, normal);
}

// A tile's clear: one triangle over its viewport at the far plane, nothing seen.
@vertex
fn vs_clear(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 1.0, 1.0);
}

@fragment
fn fs_clear() -> @location(0) vec4<f32> {
    return vec4<f32>(1e30, 0.0, 0.0, 0.0);
}
