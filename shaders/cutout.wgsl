// Holes of alpha-masked casters in the passes that draw bare casters (paraboloid shadow
// maps): each mask is a run of bits (1 = solid) in `mask_bits`; `mask_info[m]` holds its
// first bit, width and height. The rule is scene/alpha.rs's: the texel under
// floor(fract(uv) · size), row 0 the image's top row.

@group(1) @binding(0) var<storage, read> mask_bits: array<u32>;
@group(1) @binding(1) var<storage, read> mask_info: array<vec4<u32>>;

const NO_MASK: u32 = 0xffffffffu;

// Whether texture coordinate `uv` of a triangle with mask `mask` falls in a hole.
fn in_cutout_hole(uv: vec2<f32>, mask: u32) -> bool {
    if (mask == NO_MASK) {
        return false;
    }
    let info = mask_info[mask];
    let size = vec2<f32>(f32(info.y), f32(info.z));
    let t = min(vec2<u32>(fract(uv) * size), vec2<u32>(info.y - 1u, info.z - 1u));
    let bit = info.x + t.y * info.y + t.x;
    return (mask_bits[bit >> 5u] & (1u << (bit & 31u))) == 0u;
}
