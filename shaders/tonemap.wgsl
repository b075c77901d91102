// HDR → display: exposure (y = 1 − e^(−k·x)), Reinhard's global operator, or false
// colour of the illuminance channel. The target is an sRGB format, so the hardware does
// the sRGB encoding. Also the statistics pass the automatic settings come from.

struct ToneParams {
    // 0 exposure, 1 Reinhard, 2 false-colour illuminance.
    tone_operator: u32,
    stop_count: u32,
    // Hard bands on the false-colour scale (0: continuous).
    steps: u32,
    // Samples per pixel side of `hdr` (1: one sample per output pixel).
    supersample: u32,
    // exposure: k; Reinhard: key / log-average luminance, 1 / L_white²; false colour: lux
    // at the top of the scale.
    k: f32,
    key_scale: f32,
    inv_white2: f32,
    lux_max: f32,
    background: vec4<f32>,
    // rgb: colour (linear); w: position on the scale, 0..1.
    stops: array<vec4<f32>, 16>,
};

@group(0) @binding(0) var hdr: texture_2d<f32>;
@group(0) @binding(1) var<uniform> tone: ToneParams;

const LUMA: vec3<f32> = vec3<f32>(0.2126, 0.7152, 0.0722);

@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(i & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}

// The middle of t's band on a scale of `steps` bands (t itself when steps is 0).
fn step_position(t: f32, steps: u32) -> f32 {
    if (steps == 0u) {
        return t;
    }
    let n = f32(steps);
    return (min(floor(clamp(t, 0.0, 1.0) * n), n - 1.0) + 0.5) / n;
}

fn false_colour(t: f32) -> vec3<f32> {
    let x = clamp(step_position(t, tone.steps), 0.0, 1.0);
    var c = tone.stops[0].rgb;
    for (var i = 1u; i < tone.stop_count; i++) {
        let a = tone.stops[i - 1u];
        let b = tone.stops[i];
        if (x >= a.w && x <= b.w) {
            c = mix(a.rgb, b.rgb, (x - a.w) / max(b.w - a.w, 1e-6));
        }
    }
    return c;
}

// The display colour (linear) of one HDR sample: the twin of ToneSettings::map_pixel.
fn map_sample(texel: vec4<f32>) -> vec3<f32> {
    if (texel.a < 0.0) {
        return tone.background.rgb;
    }
    if (tone.tone_operator == 2u) {
        return false_colour(texel.a / tone.lux_max);
    }
    if (tone.tone_operator == 0u) {
        return 1.0 - exp(-tone.k * texel.rgb);
    }
    let lw = dot(texel.rgb, LUMA);
    if (lw <= 0.0) {
        return vec3<f32>(0.0);
    }
    let l = tone.key_scale * lw;
    let ld = l * (1.0 + l * tone.inv_white2) / (1.0 + l);
    return min(texel.rgb * (ld / lw), vec3<f32>(1.0));
}

// The displayed pixel: the mean (in linear light; the target encodes sRGB) of the
// display colours of its supersample × supersample samples.
@fragment
fn fs_tonemap(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let s = i32(tone.supersample);
    let base = vec2<i32>(pos.xy) * s;
    var sum = vec3<f32>(0.0);
    for (var j = 0; j < s; j++) {
        for (var i = 0; i < s; i++) {
            sum += map_sample(textureLoad(hdr, base + vec2<i32>(i, j), 0));
        }
    }
    return vec4<f32>(sum / f32(s * s), 1.0);
}

// The centre sample of each pixel of a supersampled HDR target (supersample is odd): the
// pixel-centre values the numbers are read from.
@fragment
fn fs_centre(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let s = i32(tone.supersample);
    return textureLoad(hdr, vec2<i32>(pos.xy) * s + vec2<i32>(s / 2), 0);
}

// Per 16 × 16 tile of surface pixels: (Σ ln(δ + L), count, min L > 0, max L) and
// (max lux, Σ lux, 0, 0). The CPU sums the tiles.
const TILE: u32 = 16u;
var<workgroup> part_a: array<vec4<f32>, 256>;
var<workgroup> part_b: array<vec4<f32>, 256>;
@group(0) @binding(2) var<storage, read_write> tiles: array<vec4<f32>>;

@compute @workgroup_size(16, 16)
fn stats(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(local_invocation_index) li: u32, @builtin(workgroup_id) wg: vec3<u32>, @builtin(num_workgroups) nwg: vec3<u32>) {
    let size = textureDimensions(hdr);
    var a = vec4<f32>(0.0, 0.0, 3.0e38, 0.0);
    var b = vec4<f32>(0.0);
    if (gid.x < size.x && gid.y < size.y) {
        let t = textureLoad(hdr, vec2<i32>(gid.xy), 0);
        if (t.a >= 0.0) {
            let l = dot(t.rgb, LUMA);
            a = vec4<f32>(log(1e-4 + max(l, 0.0)), 1.0, select(3.0e38, l, l > 0.0), l);
            b = vec4<f32>(t.a, t.a, 0.0, 0.0);
        }
    }
    part_a[li] = a;
    part_b[li] = b;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s = s >> 1u) {
        if (li < s) {
            let x = part_a[li];
            let y = part_a[li + s];
            part_a[li] = vec4<f32>(x.x + y.x, x.y + y.y, min(x.z, y.z), max(x.w, y.w));
            let u = part_b[li];
            let w = part_b[li + s];
            part_b[li] = vec4<f32>(max(u.x, w.x), u.y + w.y, 0.0, 0.0);
        }
        workgroupBarrier();
    }
    if (li == 0u) {
        let tile = wg.y * nwg.x + wg.x;
        tiles[2u * tile] = part_a[0];
        tiles[2u * tile + 1u] = part_b[0];
    }
}
