// Dual-paraboloid shadow maps (Brabec, Annen and Seidel 2002): the distance from a
// luminaire to the nearest surface, per direction, stored on two paraboloids around its
// local −Z (γ = 0, the lower map) and +Z (the upper map). The projection is not linear:
// the casters are tessellated on the CPU, and each fragment stores the exact distance
// along its own texel's direction to its triangle's plane (the plane from the screen
// derivatives of the interpolated position, which is linear within a triangle). Holes of
// alpha-masked casters (cutout.wgsl, before this file) let light through.

struct ParaboloidView {
    // xyz: the luminaire's position; w: 0 lower map, 1 upper map.
    position: vec4<f32>,
    axis_x: vec4<f32>,
    axis_y: vec4<f32>,
    axis_z: vec4<f32>,
    // x: the distance stored as depth 1; y: the map's side in texels.
    params: vec4<f32>,
};

@group(0) @binding(0) var<uniform> view: ParaboloidView;

struct ParaboloidOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) @interpolate(flat) mask: u32,
};

// The local direction with z pointing into the map's hemisphere.
fn map_local(world: vec3<f32>) -> vec3<f32> {
    let d = world - view.position.xyz;
    let local = vec3<f32>(dot(d, view.axis_x.xyz), dot(d, view.axis_y.xyz), dot(d, view.axis_z.xyz));
    let s = select(-1.0, 1.0, view.position.w > 0.5);
    return vec3<f32>(local.xy, local.z * s);
}

@vertex
fn vs_paraboloid(@location(0) p: vec3<f32>, @location(1) uv: vec2<f32>, @location(2) mask: u32) -> ParaboloidOut {
    var out: ParaboloidOut;
    out.uv = uv;
    out.mask = mask;
    let local = map_local(p);
    let dist = max(length(local), 1e-6);
    let w = local / dist;
    out.clip = vec4<f32>(w.xy / max(1.0 + w.z, 1e-4), clamp(dist / view.params.x, 0.0, 1.0), 1.0);
    out.world = p;
    return out;
}

// The unit direction (map-local, z into the hemisphere) of paraboloid point m.
fn paraboloid_direction(m: vec2<f32>) -> vec3<f32> {
    let r2 = dot(m, m);
    return vec3<f32>(2.0 * m, 1.0 - r2) / (1.0 + r2);
}

@fragment
fn fs_paraboloid(in: ParaboloidOut) -> @builtin(frag_depth) f32 {
    let local = map_local(in.world);
    let n = cross(dpdx(local), dpdy(local));
    if (local.z < 0.0 || in_cutout_hole(in.uv, in.mask)) {
        discard;
    }
    var dist = length(local);
    // This fragment's direction from its position on the map (clip xy = paraboloid xy).
    let size = view.params.y;
    let m = vec2<f32>(in.clip.x / size * 2.0 - 1.0, 1.0 - in.clip.y / size * 2.0);
    let dir = paraboloid_direction(m);
    let denom = dot(n, dir);
    if (abs(denom) > 1e-6 * length(n)) {
        let t = dot(n, local) / denom;
        if (t > 0.0) {
            dist = t;
        }
    }
    return clamp(dist / view.params.x, 0.0, 1.0);
}
