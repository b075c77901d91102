// Shadows seen from the shading code: a per-pixel (or per-point) mask, one layer per light,
// written by the stencil shadow-volume passes (1 = in the light's shadow volume), or dual-paraboloid
// shadow maps (Brabec et al.) sampled with percentage-closer filtering.
// Needs lighting.wgsl before it (the Light struct).

struct ShadowInfo {
    // 0 none, 1 dual-paraboloid maps, 2 shadow-volume mask.
    mode: u32,
    // Entries per mask row (the image width; a fixed width for point queries).
    mask_width: u32,
    _pad: u32,
    // Side of a paraboloid map, texels.
    map_size: u32,
    // Distance (metres) that maps to depth 1 in the paraboloid maps.
    far: f32,
    // Constant depth bias, metres.
    bias: f32,
    // Slope bias: a multiple of the depth change across the PCF kernel on the receiver.
    bias_slope: f32,
    // PCF kernel radius in texels (0: one comparison).
    pcf_radius: i32,
};

const SHADOW_NONE: u32 = 0u;
const SHADOW_PARABOLOID: u32 = 1u;
const SHADOW_MASK: u32 = 2u;

@group(0) @binding(8) var<uniform> shadow: ShadowInfo;
@group(0) @binding(9) var shadow_mask: texture_2d_array<u32>;
@group(0) @binding(10) var shadow_maps: texture_depth_2d_array;
@group(0) @binding(11) var shadow_sampler: sampler_comparison;

// Whether the mask marks entry `slot` as outside light `i`'s shadow volume.
fn shadow_mask_lit(slot: u32, i: u32) -> bool {
    let at = vec2<u32>(slot % shadow.mask_width, slot / shadow.mask_width);
    return textureLoad(shadow_mask, at, i, 0).r == 0u;
}

// A direction in a luminaire's frame on its paraboloid map: xy in [-1, 1] (the map's
// clip coordinates), z = 0 for the lower hemisphere (toward γ = 0, local −Z), 1 for the
// upper one.
fn paraboloid_project(local_dir: vec3<f32>) -> vec3<f32> {
    if (local_dir.z <= 0.0) {
        return vec3<f32>(local_dir.xy / (1.0 - local_dir.z), 0.0);
    }
    return vec3<f32>(local_dir.xy / (1.0 + local_dir.z), 1.0);
}

// Fraction (0..1) of light `i` (record `l`) reaching `p`, from its paraboloid maps
// (layers 2i and 2i + 1), with a PCF kernel. `n` is the unit surface normal.
fn paraboloid_visibility(l: Light, i: u32, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let d = p - l.position.xyz;
    let dist = length(d);
    if (dist <= 0.0) {
        return 1.0;
    }
    let w = d / dist;
    let local = vec3<f32>(dot(w, l.axis_x.xyz), dot(w, l.axis_y.xyz), dot(w, l.axis_z.xyz));
    let m = paraboloid_project(local);
    let uv = vec2<f32>(m.x * 0.5 + 0.5, 0.5 - m.y * 0.5);
    let layer = i32(2u * i + u32(m.z));
    let cos_i = clamp(abs(dot(n, w)), 0.02, 1.0);
    let tan_i = sqrt(1.0 - cos_i * cos_i) / cos_i;
    // The widest angle a map texel spans (at the paraboloid's centre: 4 / size), times the
    // kernel's reach, is how far apart in depth the surface is at neighbouring samples.
    let texel = 1.0 / f32(shadow.map_size);
    let reach = 4.0 * texel * (1.5 * f32(shadow.pcf_radius) + 1.0);
    let slope = dist * min(tan_i, 50.0) * reach * shadow.bias_slope;
    let reference = (dist - shadow.bias - slope) / shadow.far;
    var sum = 0.0;
    var count = 0.0;
    for (var y = -shadow.pcf_radius; y <= shadow.pcf_radius; y++) {
        for (var x = -shadow.pcf_radius; x <= shadow.pcf_radius; x++) {
            let o = vec2<f32>(f32(x), f32(y)) * texel;
            sum += textureSampleCompareLevel(shadow_maps, shadow_sampler, uv + o, layer, reference);
            count += 1.0;
        }
    }
    return sum / count;
}

// Fraction of light `i` reaching `p` under the current shadow mode; `slot` is the pixel
// (or point) index of the shadow-volume mask.
fn light_visibility(l: Light, i: u32, p: vec3<f32>, n: vec3<f32>, slot: u32) -> f32 {
    if (shadow.mode == SHADOW_PARABOLOID) {
        return paraboloid_visibility(l, i, p, n);
    }
    if (shadow.mode == SHADOW_MASK) {
        return select(0.0, 1.0, shadow_mask_lit(slot, i));
    }
    return 1.0;
}
