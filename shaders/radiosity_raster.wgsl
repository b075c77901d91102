// Visibility maps rasterized by compute shaders (radiosity/gpu/raster.rs): every GPU unit
// draws, where a render pass runs on the few units that do graphics (an H100 or H200 has
// only a handful). Each texel keeps the distance to the nearest surface, as the render
// pass's depth test and distance target do; atomics take the nearest of all triangles.
//
// A pixel's ray is tested against a triangle in clip space (homogeneous rasterization,
// Olano and Greer 1997): the barycentric coordinates of the point of the triangle that
// projects to the pixel centre solve a 3 × 3 system, so no triangle needs clipping at the
// eye's plane and no projected coordinate is divided by a small w. The point is kept
// where its barycentrics are all ≥ 0, it lies in front of the eye and within the depth
// range, and (stereographic) in front of the map's plane.
//
// The stereographic map is drawn exactly: a texel's ray is the direction whose projection
// is the texel's centre, tested against the triangle in 3-D (edge functions are triple
// products), and the box of texels to test is that of the triangle's projection, whose
// edges are circle arcs. The render pipeline draws the chords between the projected
// vertices instead; where an edge lies in the map's plane (a wall's foot seen from a floor
// cell), the sliver between chord and rim lets through what lies beyond the wall.
//
// Small triangles are drawn by one thread each; a triangle whose box holds more than
// SMALL_PIXELS texels is listed and drawn by a workgroup (the texels strided over its
// threads). The large pass has a fixed number of workgroups that take the list's entries
// in turn, so no dispatch is sized on the GPU.

struct FaceSlot {
    face: Face,
    // The hardware pipeline reads the same records at 256-byte dynamic offsets.
    pad: array<vec4<f32>, 7>,
};

struct RasterParams {
    // Work items (tile, first triangle, triangles, first thread) and their threads.
    item_count: u32,
    thread_count: u32,
    // Side of a tile, texels; tiles of the batch; tiles per row of the atlas.
    size: u32,
    tiles: u32,
    columns: u32,
    // Room in the list of large triangles.
    large_capacity: u32,
    _pad0: u32,
    _pad1: u32,
};

@group(0) @binding(0) var<uniform> rp: RasterParams;
@group(0) @binding(1) var<storage, read> positions: array<f32>;
@group(0) @binding(2) var<storage, read> indices: array<u32>;
@group(0) @binding(3) var<storage, read> faces: array<FaceSlot>;
@group(0) @binding(4) var<storage, read> items: array<vec4<u32>>;
// Per texel of the batch's tiles (tile after tile): 0xffffffff − the bits of the nearest
// distance (positive floats order as their bits), 0 where nothing was drawn.
@group(0) @binding(5) var<storage, read_write> nearest: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read_write> large: array<vec2<u32>>;
// [0]: large triangles listed.
@group(0) @binding(7) var<storage, read_write> control: array<atomic<u32>, 4>;
@group(0) @binding(8) var maps: texture_storage_2d<r32float, write>;

const SMALL_PIXELS: i32 = 64;
const LARGE_GROUP: u32 = 64u;
// What an empty texel holds in the maps (the render pass's clear).
const NOTHING: f32 = 1e30;

// A triangle as one tile sees it: clip positions, world positions, the texels to test.
struct Setup {
    c0: vec4<f32>,
    c1: vec4<f32>,
    c2: vec4<f32>,
    v0: vec3<f32>,
    v1: vec3<f32>,
    v2: vec3<f32>,
    lo: vec2<i32>,
    hi: vec2<i32>,
    // False when the tile sees none of it.
    seen: bool,
    // A stereographic map's triangle, tested by rays (see `draw_texel_on_rays`): c0, c1, c2
    // then hold its corners relative to the eye in the map's frame (w 1).
    stereographic: bool,
};

fn vertex(i: u32) -> vec3<f32> {
    return vec3<f32>(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]);
}

// The texel (x right, y down) where clip position `c` (w > 0) projects.
fn to_texel(c: vec4<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * f32(rp.size);
}

fn setup(tile: u32, triangle: u32) -> Setup {
    let f = faces[tile].face;
    var s: Setup;
    s.v0 = vertex(indices[3u * triangle]);
    s.v1 = vertex(indices[3u * triangle + 1u]);
    s.v2 = vertex(indices[3u * triangle + 2u]);
    s.c0 = face_clip_of(f, s.v0);
    s.c1 = face_clip_of(f, s.v1);
    s.c2 = face_clip_of(f, s.v2);
    s.seen = false;
    var c = array<vec4<f32>, 3>(s.c0, s.c1, s.c2);
    // Wholly outside one plane of the view volume (x, y within ±w; 0 ≤ z ≤ w).
    var out = vec4<u32>(0u);
    var beyond = vec2<u32>(0u);
    for (var k = 0; k < 3; k++) {
        let p = c[k];
        out += select(vec4<u32>(0u), vec4<u32>(1u), vec4<bool>((p.x > p.w), (p.x < -p.w), (p.y > p.w), (p.y < -p.w)));
        beyond += select(vec2<u32>(0u), vec2<u32>(1u), vec2<bool>((p.z < 0.0), (p.z > p.w)));
    }
    if (any(out == vec4<u32>(3u)) || any(beyond == vec2<u32>(3u))) {
        return s;
    }
    // The box of its part in front of the near plane (z ≥ 0, where w > 0), one texel
    // wider each way: the texels themselves are tested exactly.
    var lo = vec2<f32>(1e30);
    var hi = vec2<f32>(-1e30);
    s.stereographic = f.eye.w > 0.5;
    if (s.stereographic) {
        let frame = transpose(mat3x3<f32>(f.tangent.xyz, f.bitangent.xyz, f.normal.xyz));
        s.c0 = vec4<f32>(frame * (s.v0 - f.eye.xyz), 1.0);
        s.c1 = vec4<f32>(frame * (s.v1 - f.eye.xyz), 1.0);
        s.c2 = vec4<f32>(frame * (s.v2 - f.eye.xyz), 1.0);
        let front = stereographic_box(array<vec3<f32>, 3>(s.c0.xyz, s.c1.xyz, s.c2.xyz));
        lo = to_texel(vec4<f32>(front.x, front.w, 0.0, 1.0));
        hi = to_texel(vec4<f32>(front.z, front.y, 0.0, 1.0));
    } else {
        for (var k = 0; k < 3; k++) {
            let a = c[k];
            let b = c[(k + 1) % 3];
            if (a.z >= 0.0) {
                let t = to_texel(a);
                lo = min(lo, t);
                hi = max(hi, t);
            }
            if ((a.z >= 0.0) != (b.z >= 0.0)) {
                let cut = mix(a, b, a.z / (a.z - b.z));
                if (cut.w > 0.0) {
                    let t = to_texel(cut);
                    lo = min(lo, t);
                    hi = max(hi, t);
                }
            }
        }
    }
    let last = f32(rp.size - 1u);
    let first = clamp(floor(lo - 1.0), vec2<f32>(0.0), vec2<f32>(last));
    let end = clamp(ceil(hi), vec2<f32>(0.0), vec2<f32>(last));
    s.lo = vec2<i32>(first);
    s.hi = vec2<i32>(end);
    s.seen = lo.x <= hi.x && lo.x < f32(rp.size) + 1.0 && lo.y < f32(rp.size) + 1.0 && hi.x > -1.0 && hi.y > -1.0;
    return s;
}

// Direction `v` (the map's frame, z ≥ 0) in map coordinates: inside the unit disc.
fn stereographic_point(v: vec3<f32>) -> vec2<f32> {
    return v.xy / (length(v) + v.z);
}

// The box (min x, min y, max x, max y) in map coordinates of the projection of the
// segment from `a` to `b` (eye-relative, the map's frame, both at or in front of its
// plane). The segment's directions run along a great circle, whose projection is the circle
// of centre (m.x, m.y) / m.z and radius 1 / |m.z| for the circle's unit normal m (a line
// through the centre where m.z = 0): the box of its ends, and of the circle's extreme points
// on the arc between them (the side of the chord where the segment's middle projects).
fn arc_box(a: vec3<f32>, b: vec3<f32>) -> vec4<f32> {
    let pa = stereographic_point(a);
    let pb = stereographic_point(b);
    var box = vec4<f32>(min(pa, pb), max(pa, pb));
    let m = cross(a, b);
    let n = m / max(length(m), 1e-30);
    // A great circle through the axis projects to a line; nearly so, the arc strays from
    // its chord by at most |m.z| / 2 (here under a ten-thousandth of the map's radius).
    if (abs(n.z) < 2e-4 || length(m) <= 1e-7 * length(a) * length(b)) {
        return box;
    }
    // Ends nearly opposite (the segment passes by the eye): the arc could be either half.
    let halfway = normalize(a) + normalize(b);
    if (length(halfway) < 1e-3) {
        return vec4<f32>(-1.0, -1.0, 1.0, 1.0);
    }
    let centre = n.xy / n.z;
    let radius = 1.0 / abs(n.z);
    let middle = stereographic_point(halfway);
    let chord = pb - pa;
    let side = chord.x * (middle.y - pa.y) - chord.y * (middle.x - pa.x);
    // The arc nearly straight (its sagitta, R − √(R² − c²/4), under a thousandth of the
    // map's radius, and its middle as near the chord): the ends' box, widened by it. (The
    // side of the chord its middle is on would be rounding there.)
    let half_chord_squared = 0.25 * dot(chord, chord);
    let sagitta = half_chord_squared / (radius + sqrt(max(radius * radius - half_chord_squared, 0.0)));
    let off_chord = abs(side) / max(length(chord), 1e-30);
    if (sagitta < 1e-3 && off_chord <= 2.0 * sagitta + 1e-4) {
        return box + vec4<f32>(-sagitta, -sagitta, sagitta, sagitta);
    }
    let extremes = array<vec2<f32>, 4>(vec2<f32>(radius, 0.0), vec2<f32>(-radius, 0.0), vec2<f32>(0.0, radius), vec2<f32>(0.0, -radius));
    for (var k = 0; k < 4; k++) {
        let q = centre + extremes[k];
        let here = chord.x * (q.y - pa.y) - chord.y * (q.x - pa.x);
        if (here * side >= 0.0) {
            box = vec4<f32>(min(box.xy, q), max(box.zw, q));
        }
    }
    return box;
}

// The box in map coordinates of the part of the triangle of `corners` (eye-relative, in a
// stereographic map's frame) in front of the map's plane (clipped at it), within the unit
// disc's box.
fn stereographic_box(corners: array<vec3<f32>, 3>) -> vec4<f32> {
    // The clipped polygon: at most four corners.
    var front = array<vec3<f32>, 4>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    var count = 0;
    for (var k = 0; k < 3; k++) {
        let a = corners[k];
        let b = corners[(k + 1) % 3];
        if (a.z >= 0.0) {
            front[count] = a;
            count++;
        }
        if ((a.z >= 0.0) != (b.z >= 0.0)) {
            front[count] = mix(a, b, a.z / (a.z - b.z));
            front[count].z = 0.0;
            count++;
        }
    }
    let disc = vec4<f32>(-1.0, -1.0, 1.0, 1.0);
    var box = vec4<f32>(1e30, 1e30, -1e30, -1e30);
    for (var k = 0; k < count; k++) {
        let a = front[k];
        let b = front[(k + 1) % count];
        // A corner at the eye: every direction may see it.
        if (length(a) < 1e-20 || length(b) < 1e-20) {
            return disc;
        }
        let arc = arc_box(a, b);
        box = vec4<f32>(min(box.xy, arc.xy), max(box.zw, arc.zw));
    }
    return vec4<f32>(max(box.xy, disc.xy), min(box.zw, disc.zw));
}

// Texels in `s`'s box.
fn box_texels(s: Setup) -> i32 {
    let d = s.hi - s.lo + vec2<i32>(1);
    return d.x * d.y;
}

// Whether world position `p` comes before `q` (x, then y, then z): the same for every
// triangle that holds those two corners, whatever their indices.
fn before(p: vec3<f32>, q: vec3<f32>) -> bool {
    if (p.x != q.x) {
        return p.x < q.x;
    }
    if (p.y != q.y) {
        return p.y < q.y;
    }
    return p.z < q.z;
}

// The edge function of the edge from corner `i` to corner `j` (at `pi`, `pj`; `ri`, `rj`
// their rows, see `row`): ri.x rj.y − rj.x ri.y, always evaluated from the corner that
// comes first (so two triangles that share an edge evaluate it alike), and (y) a bound on
// its rounding error: a compiler may fuse either product into a multiply-add, so two
// triangles' values need not be exactly opposite, and a texel on their shared edge could
// fall between them. A texel within that bound of an edge counts as inside (both
// triangles then cover it: a crack would let light through, a texel of overlap does not).
fn edge(ri: vec2<f32>, pi: vec3<f32>, rj: vec2<f32>, pj: vec3<f32>) -> vec2<f32> {
    let a = ri.x * rj.y;
    let b = rj.x * ri.y;
    let bound = 4.0e-7 * (abs(a) + abs(b));
    if (before(pi, pj)) {
        return vec2<f32>(a - b, bound);
    }
    return vec2<f32>(-(b - a), bound);
}

// A corner's row for the texel at clip (x, y): (X − x w, Y − y w).
fn row(c: vec4<f32>, x: f32, y: f32) -> vec2<f32> {
    return vec2<f32>(c.x - x * c.w, c.y - y * c.w);
}

// Keeps distance `d` at texel `q` of tile `tile` where it is the nearest.
fn keep_nearest(tile: u32, q: vec2<i32>, d: f32) {
    let at = tile * rp.size * rp.size + u32(q.y) * rp.size + u32(q.x);
    atomicMax(&nearest[at], 0xffffffffu - bitcast<u32>(d));
}

// The edge function of the edge from corner `i` to corner `j` (eye-relative `ai`, `aj`, at
// `pi`, `pj`) for the ray `d`: the triple product (ai × aj) · d, the cross product always
// taken from the corner that comes first, and (y) a bound on its rounding error, as `edge`.
fn ray_edge(ai: vec3<f32>, pi: vec3<f32>, aj: vec3<f32>, pj: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let terms = abs(ai.yzx * aj.zxy) + abs(ai.zxy * aj.yzx);
    let bound = 1.0e-6 * dot(terms, abs(d));
    if (before(pi, pj)) {
        return vec2<f32>(dot(cross(ai, aj), d), bound);
    }
    return vec2<f32>(-dot(cross(aj, ai), d), bound);
}

// The barycentric coordinates the edge functions `e0`, `e1`, `e2` (x: the value, y: its
// rounding bound) give, with w 1 where the texel is inside: every edge function on the side
// of their sum, or within its rounding of 0. All 0 outside.
fn barycentrics(e0: vec2<f32>, e1: vec2<f32>, e2: vec2<f32>) -> vec4<f32> {
    let k = vec3<f32>(e0.x, e1.x, e2.x);
    let sum = k.x + k.y + k.z;
    if (sum == 0.0) {
        return vec4<f32>(0.0);
    }
    let side = k * sign(sum);
    if (any(side < -vec3<f32>(e0.y, e1.y, e2.y))) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(k / sum, 1.0);
}

// Tests the ray of texel `q` of stereographic tile `tile` against `s` in 3-D (exact where
// the projection bends the triangle's edges) and keeps the nearer distance.
fn draw_texel_on_rays(s: Setup, tile: u32, q: vec2<i32>, x: f32, y: f32) {
    // In the map's frame: the corners set up once per triangle, the ray from the texel.
    let d = stereographic_ray(vec2<f32>(x, y));
    let a0 = s.c0.xyz;
    let a1 = s.c1.xyz;
    let a2 = s.c2.xyz;
    let e0 = ray_edge(a1, s.v1, a2, s.v2, d);
    let e1 = ray_edge(a2, s.v2, a0, s.v0, d);
    let e2 = ray_edge(a0, s.v0, a1, s.v1, d);
    let inside = barycentrics(e0, e1, e2);
    if (inside.w == 0.0) {
        return;
    }
    let beta = inside.xyz;
    // The point of the triangle's plane on the ray's line: in front of the eye, not past
    // the far plane.
    let p = beta.x * a0 + beta.y * a1 + beta.z * a2;
    let dist = length(p);
    let f = faces[tile].face;
    if (dot(p, d) <= 0.0 || dist > f.normal.w) {
        return;
    }
    let world = f.eye.xyz + p.x * f.tangent.xyz + p.y * f.bitangent.xyz + p.z * f.normal.xyz;
    if (face_skips(f, world)) {
        return;
    }
    keep_nearest(tile, q, dist);
}

// Tests texel `q` of tile `tile` against `s` and keeps the nearer distance.
fn draw_texel(s: Setup, tile: u32, q: vec2<i32>) {
    let size = f32(rp.size);
    let x = (f32(q.x) + 0.5) / size * 2.0 - 1.0;
    let y = 1.0 - (f32(q.y) + 0.5) / size * 2.0;
    if (s.stereographic) {
        draw_texel_on_rays(s, tile, q, x, y);
        return;
    }
    // The clip-space point Σ β c_k on the pixel's ray: β ⟂ (X − x w) and (Y − y w) (the
    // columns of the corners' rows), that is β ∝ their cross product, taken edge by edge.
    let r0 = row(s.c0, x, y);
    let r1 = row(s.c1, x, y);
    let r2 = row(s.c2, x, y);
    let e0 = edge(r1, s.v1, r2, s.v2);
    let e1 = edge(r2, s.v2, r0, s.v0);
    let e2 = edge(r0, s.v0, r1, s.v1);
    let inside = barycentrics(e0, e1, e2);
    if (inside.w == 0.0) {
        return;
    }
    let beta = inside.xyz;
    let w = dot(beta, vec3<f32>(s.c0.w, s.c1.w, s.c2.w));
    let z = dot(beta, vec3<f32>(s.c0.z, s.c1.z, s.c2.z));
    if (w <= 0.0 || z < 0.0 || z > w) {
        return;
    }
    let f = faces[tile].face;
    let world = beta.x * s.v0 + beta.y * s.v1 + beta.z * s.v2;
    if (face_skips(f, world)) {
        return;
    }
    keep_nearest(tile, q, distance(world, f.eye.xyz));
}

fn linear_index(id: vec3<u32>, nw: vec3<u32>, size: u32) -> u32 {
    return id.y * nw.x * size + id.x;
}

// The work item of thread `t`: the last whose first thread is at most `t`.
fn item_of(t: u32) -> u32 {
    var lo = 0u;
    var hi = rp.item_count;
    while (hi - lo > 1u) {
        let mid = (lo + hi) / 2u;
        if (items[mid].w <= t) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

// One thread per (tile, triangle): small triangles drawn here, large ones listed.
@compute @workgroup_size(64)
fn raster_small(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) nw: vec3<u32>) {
    let t = linear_index(id, nw, 64u);
    if (t >= rp.thread_count) {
        return;
    }
    let item = items[item_of(t)];
    let tile = item.x;
    let triangle = item.y + (t - item.w);
    let s = setup(tile, triangle);
    if (!s.seen) {
        return;
    }
    if (box_texels(s) > SMALL_PIXELS) {
        let slot = atomicAdd(&control[0], 1u);
        if (slot < rp.large_capacity) {
            large[slot] = vec2<u32>(tile, triangle);
            return;
        }
        // The list is full: drawn here, slowly but drawn.
    }
    for (var y = s.lo.y; y <= s.hi.y; y++) {
        for (var x = s.lo.x; x <= s.hi.x; x++) {
            draw_texel(s, tile, vec2<i32>(x, y));
        }
    }
}

// The large triangles, a workgroup at a time: the groups take the list's entries in
// turn, the threads of one stride over its box.
@compute @workgroup_size(64)
fn raster_large(@builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) nw: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let listed = min(atomicLoad(&control[0]), rp.large_capacity);
    let groups = nw.x * nw.y;
    for (var index = wid.y * nw.x + wid.x; index < listed; index += groups) {
        let entry = large[index];
        let s = setup(entry.x, entry.y);
        let width = s.hi.x - s.lo.x + 1;
        let count = box_texels(s);
        for (var i = i32(lane); i < count; i += i32(LARGE_GROUP)) {
            draw_texel(s, entry.x, s.lo + vec2<i32>(i % width, i / width));
        }
    }
}

// Writes the batch's tiles into the atlas the receive pass reads.
@compute @workgroup_size(64)
fn raster_resolve(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) nw: vec3<u32>) {
    let t = linear_index(id, nw, 64u);
    let per_tile = rp.size * rp.size;
    if (t >= rp.tiles * per_tile) {
        return;
    }
    let tile = t / per_tile;
    let local = t % per_tile;
    let origin = vec2<u32>(tile % rp.columns, tile / rp.columns) * rp.size;
    let texel = origin + vec2<u32>(local % rp.size, local / rp.size);
    let v = atomicLoad(&nearest[t]);
    let d = select(bitcast<f32>(0xffffffffu - v), NOTHING, v == 0u);
    textureStore(maps, vec2<i32>(texel), vec4<f32>(d, 0.0, 0.0, 0.0));
}
