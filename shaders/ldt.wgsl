// Light distribution texture (LDT) sampling: the WGSL twin of the CPU reference in
// src/photometry/grid.rs, on a uniform grid. Texels are normalised intensities, one row
// per C plane (y), one column per γ angle (x), one array layer per luminaire.
// C wraps; γ knots beyond a pole come from the opposite plane (C + 180°), beyond a γ range
// that stops short of a pole they are zero.

struct LdtInfo {
    c_count: u32,
    gamma_count: u32,
    gamma_start: f32,
    gamma_step: f32,
    // 1 when the first γ angle is 0° / the last is 180° (exactly, decided on the CPU).
    pole0: u32,
    pole180: u32,
    _pad0: u32,
    _pad1: u32,
};

const INTERP_NEAREST: u32 = 0u;
const INTERP_BILINEAR: u32 = 1u;
const INTERP_CATMULL_ROM: u32 = 2u;
const INTERP_MONOTONE: u32 = 3u;

fn ldt_texel(tex: texture_2d_array<f32>, layer: u32, plane: u32, g: u32) -> f32 {
    return textureLoad(tex, vec2<i32>(i32(g), i32(plane)), i32(layer), 0).x;
}

fn ldt_opposite(info: LdtInfo, plane: u32) -> u32 {
    if (info.c_count % 2u == 0u) {
        return (plane + info.c_count / 2u) % info.c_count;
    }
    return plane;
}

// Value of γ knot k (may lie beyond either end) of a plane.
fn ldt_knot(tex: texture_2d_array<f32>, layer: u32, info: LdtInfo, plane: u32, k: i32) -> f32 {
    let ng = i32(info.gamma_count);
    if (k >= 0 && k < ng) {
        return ldt_texel(tex, layer, plane, u32(k));
    }
    var m: i32;
    var pole: bool;
    if (k < 0) {
        m = -k;
        pole = info.pole0 == 1u;
    } else {
        m = 2 * (ng - 1) - k;
        pole = info.pole180 == 1u;
    }
    if (pole && m >= 0 && m < ng) {
        return ldt_texel(tex, layer, ldt_opposite(info, plane), u32(m));
    }
    return 0.0;
}

fn hermite_basis(t: vec4<f32>, x: f32) -> vec4<f32> {
    let h = t.z - t.y;
    let s = (x - t.y) / h;
    let s2 = s * s;
    let s3 = s2 * s;
    return vec4<f32>(2.0 * s3 - 3.0 * s2 + 1.0, (s3 - 2.0 * s2 + s) * h, -2.0 * s3 + 3.0 * s2, (s3 - s2) * h);
}

fn limited_slope(da: f32, db: f32, ha: f32, hb: f32) -> f32 {
    if (da * db <= 0.0) {
        return 0.0;
    }
    let w1 = 2.0 * hb + ha;
    let w2 = hb + 2.0 * ha;
    return (w1 + w2) / (w1 / da + w2 / db);
}

fn monotone_cubic(t: vec4<f32>, p: vec4<f32>, x: f32) -> f32 {
    let h = t.z - t.y;
    let d0 = (p.y - p.x) / (t.y - t.x);
    let d1 = (p.z - p.y) / h;
    let d2 = (p.w - p.z) / (t.w - t.z);
    let m1 = limited_slope(d0, d1, t.y - t.x, h);
    let m2 = limited_slope(d1, d2, h, t.w - t.z);
    let b = hermite_basis(t, x);
    return b.x * p.y + b.y * m1 + b.z * p.z + b.w * m2;
}

fn ldt_row(tex: texture_2d_array<f32>, layer: u32, info: LdtInfo, plane: u32, gi: i32) -> vec4<f32> {
    // Fast path: all four knots inside the stored γ range.
    if (gi >= 1 && gi + 2 < i32(info.gamma_count)) {
        let y = i32(plane);
        let l = i32(layer);
        return vec4<f32>(
            textureLoad(tex, vec2<i32>(gi - 1, y), l, 0).x,
            textureLoad(tex, vec2<i32>(gi, y), l, 0).x,
            textureLoad(tex, vec2<i32>(gi + 1, y), l, 0).x,
            textureLoad(tex, vec2<i32>(gi + 2, y), l, 0).x,
        );
    }
    return vec4<f32>(
        ldt_knot(tex, layer, info, plane, gi - 1),
        ldt_knot(tex, layer, info, plane, gi),
        ldt_knot(tex, layer, info, plane, gi + 1),
        ldt_knot(tex, layer, info, plane, gi + 2),
    );
}

// The two knots of the cell (bilinear needs no more).
fn ldt_pair(tex: texture_2d_array<f32>, layer: u32, info: LdtInfo, plane: u32, gi: i32) -> vec2<f32> {
    if (gi >= 0 && gi + 1 < i32(info.gamma_count)) {
        let y = i32(plane);
        let l = i32(layer);
        return vec2<f32>(
            textureLoad(tex, vec2<i32>(gi, y), l, 0).x,
            textureLoad(tex, vec2<i32>(gi + 1, y), l, 0).x,
        );
    }
    return vec2<f32>(ldt_knot(tex, layer, info, plane, gi), ldt_knot(tex, layer, info, plane, gi + 1));
}

// Catmull-Rom weights of the four knots at s in [0, 1] of a uniform grid: the same curve as
// the Hermite form with slopes (p₂ − p₀)/(t₂ − t₀) of the CPU reference.
fn catmull_rom_weights(s: f32) -> vec4<f32> {
    let s2 = s * s;
    let s3 = s2 * s;
    return vec4<f32>(
        -0.5 * s3 + s2 - 0.5 * s,
        1.5 * s3 - 2.5 * s2 + 1.0,
        -1.5 * s3 + 2.0 * s2 + 0.5 * s,
        0.5 * s3 - 0.5 * s2,
    );
}

fn ldt_along_gamma(tex: texture_2d_array<f32>, layer: u32, info: LdtInfo, plane: u32, gi: i32, tg: vec4<f32>, g: f32, interp: u32) -> f32 {
    if (interp == INTERP_BILINEAR) {
        let p = ldt_pair(tex, layer, info, plane, gi);
        return p.x + (p.y - p.x) * (g - tg.y) / (tg.z - tg.y);
    }
    return monotone_cubic(tg, ldt_row(tex, layer, info, plane, gi), g);
}

// Normalised intensity at C, γ (degrees), never negative.
// The γ cell of g (degrees, clamped to 0..180): the index gi of its lower knot, or
// LDT_DARK where the distribution is 0 (more than one step outside the stored range).
const LDT_DARK: i32 = -1000000;

fn ldt_gamma_cell(info: LdtInfo, g: f32) -> i32 {
    let ng = i32(info.gamma_count);
    let h = info.gamma_step;
    let g0 = info.gamma_start;
    let g_last = g0 + h * f32(ng - 1);
    if (g < g0) {
        if (g < g0 - h) {
            return LDT_DARK;
        }
        return -1;
    }
    if (g >= g_last) {
        if (g == g_last) {
            return ng - 2;
        }
        if (g > g_last + h) {
            return LDT_DARK;
        }
        return ng - 1;
    }
    return min(i32(floor((g - g0) / h)), ng - 2);
}

fn ldt_sample(tex: texture_2d_array<f32>, layer: u32, info: LdtInfo, c_deg: f32, gamma_deg: f32, interp: u32) -> f32 {
    let h = info.gamma_step;
    let g0 = info.gamma_start;
    let g = clamp(gamma_deg, 0.0, 180.0);
    let gi = ldt_gamma_cell(info, g);
    if (gi == LDT_DARK) {
        return 0.0;
    }
    // Uniform γ knots: across a pole the mirrored angles continue the grid.
    let tg = vec4<f32>(g0 + h * f32(gi - 1), g0 + h * f32(gi), g0 + h * f32(gi + 1), g0 + h * f32(gi + 2));
    let nc = i32(info.c_count);
    var c = c_deg - 360.0 * floor(c_deg / 360.0);
    if (c >= 360.0) {
        c = 0.0;
    }
    if (nc == 1) {
        if (interp == INTERP_NEAREST) {
            let k = select(gi + 1, gi, g - tg.y <= tg.z - g);
            return max(ldt_knot(tex, layer, info, 0u, k), 0.0);
        }
        if (interp == INTERP_CATMULL_ROM) {
            let wg = catmull_rom_weights((g - tg.y) / h);
            return max(dot(wg, ldt_row(tex, layer, info, 0u, gi)), 0.0);
        }
        return max(ldt_along_gamma(tex, layer, info, 0u, gi, tg, g, interp), 0.0);
    }
    let dc = 360.0 / f32(nc);
    let j = min(i32(floor(c / dc)), nc - 1);
    let tc = vec4<f32>(dc * f32(j - 1), dc * f32(j), dc * f32(j + 1), dc * f32(j + 2));
    let p0 = u32((j - 1 + nc) % nc);
    let p1 = u32(j);
    let p2 = u32((j + 1) % nc);
    let p3 = u32((j + 2) % nc);
    var v: f32;
    if (interp == INTERP_NEAREST) {
        let k = select(gi + 1, gi, g - tg.y <= tg.z - g);
        let plane = select(p2, p1, c - tc.y <= tc.z - c);
        v = ldt_knot(tex, layer, info, plane, k);
    } else if (interp == INTERP_BILINEAR) {
        let a = ldt_along_gamma(tex, layer, info, p1, gi, tg, g, interp);
        let b = ldt_along_gamma(tex, layer, info, p2, gi, tg, g, interp);
        v = a + (b - a) * (c - tc.y) / (tc.z - tc.y);
    } else if (interp == INTERP_CATMULL_ROM) {
        let wg = catmull_rom_weights((g - tg.y) / h);
        let q = vec4<f32>(
            dot(wg, ldt_row(tex, layer, info, p0, gi)),
            dot(wg, ldt_row(tex, layer, info, p1, gi)),
            dot(wg, ldt_row(tex, layer, info, p2, gi)),
            dot(wg, ldt_row(tex, layer, info, p3, gi)),
        );
        v = dot(catmull_rom_weights((c - tc.y) / dc), q);
    } else {
        let q = vec4<f32>(
            ldt_along_gamma(tex, layer, info, p0, gi, tg, g, interp),
            ldt_along_gamma(tex, layer, info, p1, gi, tg, g, interp),
            ldt_along_gamma(tex, layer, info, p2, gi, tg, g, interp),
            ldt_along_gamma(tex, layer, info, p3, gi, tg, g, interp),
        );
        v = monotone_cubic(tc, q, c);
    }
    return max(v, 0.0);
}

// (C, γ) in degrees of a direction in the luminaire frame (γ = 0 along −Z, C0 along +X).
fn ldt_angles(dir: vec3<f32>) -> vec2<f32> {
    // atan2 keeps full precision near the poles, where acos(−z) loses it in f32.
    let d = dir;
    let gamma = degrees(atan2(length(d.xy), -d.z));
    var c = degrees(atan2(d.y, d.x));
    if (c < 0.0) {
        c = c + 360.0;
    }
    return vec2<f32>(c, gamma);
}
