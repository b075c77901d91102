// Direct light from goniometric luminaires: B = I · LDT(θ, φ) / d² (Wallner Eq. 3.4).
// Shared by the renderer's fragment shader and the illuminance compute shader, so the
// image and `goniolight illuminance` run the same code. Needs ldt.wgsl before it.

struct Light {
    // xyz: photometric centre (metres); w: the LDT layer.
    position: vec4<f32>,
    // The luminaire frame's axes in world coordinates: C0, C90 and up (away from γ = 0).
    // axis_x.w: number of coloured C sectors (0: `color` everywhere); axis_y.w: the
    // first one's index in `sector_colors`.
    axis_x: vec4<f32>,
    axis_y: vec4<f32>,
    axis_z: vec4<f32>,
    // rgb: colour normalised to luminance 1; w: candela per texel unit.
    color: vec4<f32>,
};

// 0 nearest, 1 bilinear, 2 Catmull-Rom, 3 monotone; 4 = plain point light of constant
// intensity (the baseline of the renderer benchmark); 5 = Catmull-Rom from the table
// (two gathers, within 1e-3 · I_max of 2; see ldt_table.wgsl).
override LIGHT_MODEL: u32 = 2u;
const LIGHT_MODEL_POINT: u32 = 4u;
const LIGHT_MODEL_TABLE: u32 = 5u;
// 6 = Catmull-Rom resampled into a cube map per distribution (one filtered fetch by the
// direction in the luminaire's frame, no angles; see src/gpu/ldt_cube.rs).
const LIGHT_MODEL_CUBE: u32 = 6u;
// The table's columns: C from 0° in 0.125° steps.
const TABLE_COLUMNS: f32 = 2880.0;

@group(0) @binding(1) var<storage, read> lights: array<Light>;
@group(0) @binding(2) var ldt_tex: texture_2d_array<f32>;
@group(0) @binding(3) var<storage, read> ldt_info: array<LdtInfo>;
@group(0) @binding(7) var ldt_table: texture_2d_array<f32>;
@group(0) @binding(14) var ldt_table_sampler: sampler;
@group(0) @binding(15) var ldt_cube: texture_cube_array<f32>;
// The table's value at (C, γ) degrees: Catmull-Rom across the four γ knots of its cell
// (exactly the per-pixel spline's γ part) and linear across the two table columns of C
// around it (wrapping), from two gathers of 2 × 2 texels. The CPU twin is
// `gpu::ldt_table::table_value`.
fn ldt_table_lookup(layer: u32, c_deg: f32, gamma_deg: f32) -> f32 {
    let info = ldt_info[layer];
    let g = clamp(gamma_deg, 0.0, 180.0);
    let gi = ldt_gamma_cell(info, g);
    if (gi == LDT_DARK) {
        return 0.0;
    }
    let size = vec2<f32>(textureDimensions(ldt_table));
    let x = c_deg / 360.0 * TABLE_COLUMNS;
    let base = floor(x);
    let f = x - base;
    // Knot gi − 1 is table row gi + 1 (two padding rows first). Gather footprints:
    // columns (base, base + 1), rows (gi + 1, gi + 2) then (gi + 3, gi + 4); components
    // w = (left, top), z = (right, top), x = (left, bottom), y = (right, bottom).
    let r = f32(gi + 1);
    let upper = textureGather(0, ldt_table, ldt_table_sampler, vec2<f32>(base + 1.0, r + 1.0) / size, i32(layer));
    let lower = textureGather(0, ldt_table, ldt_table_sampler, vec2<f32>(base + 1.0, r + 3.0) / size, i32(layer));
    let wg = catmull_rom_weights((g - (info.gamma_start + info.gamma_step * f32(gi))) / info.gamma_step);
    let left = dot(wg, vec4<f32>(upper.w, upper.x, lower.w, lower.x));
    let right = dot(wg, vec4<f32>(upper.z, upper.y, lower.z, lower.y));
    return max(mix(left, right, f), 0.0);
}

// Effect lights' sector colours (rgb, luminance 1), every light's run after another.
@group(0) @binding(6) var<storage, read> sector_colors: array<vec4<f32>>;

const TAU: f32 = 6.28318530717959;

// The colour (luminance 1) light `l` sends along the unit world direction `dir`: its C
// sector's colour, or its one colour. The twin of PlacedLuminaire::color_toward.
fn light_color(l: Light, dir: vec3<f32>) -> vec3<f32> {
    let n = u32(l.axis_x.w);
    if (n == 0u) {
        return l.color.rgb;
    }
    var c = atan2(dot(dir, l.axis_y.xyz), dot(dir, l.axis_x.xyz));
    if (c < 0.0) {
        c = c + TAU;
    }
    let k = min(u32(c / TAU * f32(n)), n - 1u);
    return sector_colors[u32(l.axis_y.w) + k].rgb;
}

// Intensity in candela of light `l` toward the unit world direction `dir`.
fn light_intensity(l: Light, dir: vec3<f32>) -> f32 {
    if (LIGHT_MODEL == LIGHT_MODEL_POINT) {
        return l.color.w;
    }
    let local = vec3<f32>(dot(dir, l.axis_x.xyz), dot(dir, l.axis_y.xyz), dot(dir, l.axis_z.xyz));
    let layer = u32(l.position.w);
    if (LIGHT_MODEL == LIGHT_MODEL_CUBE) {
        return textureSampleLevel(ldt_cube, ldt_table_sampler, local, i32(layer), 0.0).x * l.color.w;
    }
    let a = ldt_angles(local);
    if (LIGHT_MODEL == LIGHT_MODEL_TABLE) {
        return ldt_table_lookup(layer, a.x, a.y) * l.color.w;
    }
    return ldt_sample(ldt_tex, layer, ldt_info[layer], a.x, a.y, LIGHT_MODEL) * l.color.w;
}

// Illuminance on a surface facing the light (lux = I / d²) and the unit direction to it.
struct Incident {
    normal_lux: f32,
    to_light: vec3<f32>,
};

fn light_incident(l: Light, p: vec3<f32>) -> Incident {
    var out: Incident;
    let d = l.position.xyz - p;
    let d2 = max(dot(d, d), 1e-12);
    out.to_light = d * inverseSqrt(d2);
    out.normal_lux = light_intensity(l, -out.to_light) / d2;
    return out;
}

// Direct illuminance (lux) at p on a surface with unit normal n from light l.
fn light_illuminance(l: Light, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let d = l.position.xyz - p;
    if (dot(d, n) <= 0.0) {
        return 0.0;
    }
    let inc = light_incident(l, p);
    return inc.normal_lux * dot(n, inc.to_light);
}
