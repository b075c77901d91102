// GPU progressive radiosity (Wallner ch. 2 and 4; Coombe et al. 2004), on element arrays.
// A shooter is a triangle (flat) or a flat face cluster (radiosity/shooters.rs): a list of
// elements in `shooter_elements`. Per shot: shooter_sums (unshot power per shooter),
// select_shooter (one workgroup: the ambient term and the shooter with the largest unshot
// power, with ambient overshooting when asked), gather_patches (the shot's patches' unshot
// radiosity: substructuring), clear_shooter, then per patch a visibility map
// (radiosity_visibility.wgsl) and receive (the elements of the charts in front of the
// shooter, the form factor to the patch, if visible).

struct SolveParams {
    element_count: u32,
    shooter_count: u32,
    shooter: u32,
    overshoot: u32,
    patch_first: u32,
    patch_count: u32,
    total_area: f32,
    mean_reflectance: f32,
    // The elements whose unshot radiosity this batch shoots: a range of shooter_elements.
    clear_first: u32,
    clear_count: u32,
    // The shot's receivers (receiver culling): patches[range_first..][..range_count] hold
    // per chart in front of the shooter its first element and first thread (range.xy),
    // and 1 in `top` where it holds what it receives (held_back); range_total threads in
    // all.
    range_count: u32,
    range_total: u32,
    range_first: u32,
    // Shooters of more than SMALL_SHOOTER elements (listed after the shooters).
    large_shooters: u32,
    // 1 when element_receiving holds receiving normals (radiosity/shading.rs).
    receiving_normals: u32,
    _pad4: u32,
};

struct ShooterInfo {
    // first entry of shooter_elements, element count, z: the shooter's weight in the
    // selection (f32 bits; importance-driven shooting) or, in a workgroup's record, the
    // shooter; first piece.
    range: vec4<u32>,
    // rgb reflectance, w area.
    reflectance_area: vec4<f32>,
    // rgb diffuse transmittance (radiosity/transmission.rs), w unused.
    transmittance: vec4<f32>,
};

// What a shooter's surface sends back out of light arriving on both its sides (the
// ambient term's): reflectance plus transmittance.
fn reemittance(info: ShooterInfo) -> vec3<f32> {
    return info.reflectance_area.rgb + info.transmittance.rgb;
}

struct PatchInfo {
    // first entry of shooter_elements, element count.
    range: vec2<u32>,
    area: f32,
    // 1 for a top cell (its elements are no other top cell's).
    top: u32,
};

@group(0) @binding(0) var<uniform> params: SolveParams;
// Per element two 16-byte records in two bindings, so one binding of 128 MiB holds 8.4 M
// elements: xyz position, w area; xyz unit normal, w shooter index (as f32 bits). The
// reflectance is its shooter's (one material per shooter).
@group(0) @binding(1) var<storage, read> element_points: array<vec4<f32>>;
// Every shooter's elements, shooter after shooter (the shot's in patch order).
@group(0) @binding(2) var<storage, read> shooter_elements: array<u32>;
// rgb radiosity, w illuminance received (lux).
@group(0) @binding(3) var<storage, read_write> radiosity: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> unshot: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> shooters: array<ShooterInfo>;
// Per shooter: rgb unshot power, w Σ |luminance| power; then the selection record at
// shooter_count + 0: shooter (bits), its power (weighted), Σ |unshot power|, Σ weight ×
// |unshot power|; + 1: overshoot rgb;
// + 2: total unshot power rgb.
@group(0) @binding(6) var<storage, read_write> shooter_power: array<vec4<f32>>;
// The shot's patches.
@group(0) @binding(7) var<storage, read> patches: array<PatchInfo>;
// Per patch of the shooter: rgb unshot radiosity to shoot.
@group(0) @binding(8) var<storage, read_write> patch_delta: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read> element_normals: array<vec4<f32>>;
// Per element of the shot, in its order: its unshot radiosity when clear_shooter took it.
@group(0) @binding(10) var<storage, read_write> held: array<vec4<f32>>;
// Per element (when params.receiving_normals is 1): xyz the normal it receives with (not
// unit: a normal map's relief shortens it), w 1 where that is not its chart's normal.
@group(0) @binding(11) var<storage, read> element_receiving: array<vec4<f32>>;
// Per element (one unused record until some chart holds): what a chart that holds
// (perspective-driven radiosity, radiosity/gpu/deferred.rs) received and has not been
// given yet: rgb radiosity, w illuminance (lux).
@group(0) @binding(12) var<storage, read_write> held_back: array<vec4<f32>>;
// Per element, the factor on the reaches it sees (radiosity/links.rs, reach_for): the
// square root of its share of the link error, 1 without a view driving.
@group(0) @binding(13) var<storage, read> reach_scale: array<f32>;

const LUMA = vec3<f32>(0.2126, 0.7152, 0.0722);
// Shooters of at most this many elements are summed by one thread (SMALL_SHOOTER in gpu.rs).
const SMALL_SHOOTER = 1024u;

var<workgroup> wg_sum: array<vec4<f32>, 256>;
var<workgroup> wg_best: array<f32, 256>;
var<workgroup> wg_index: array<u32, 256>;

// Dispatches wider than 65 535 workgroups are two-dimensional (rows of `nw.x` groups).
fn linear_thread(id: vec3<u32>, nw: vec3<u32>, size: u32) -> u32 {
    return id.y * nw.x * size + id.x;
}

fn linear_group(wid: vec3<u32>, nw: vec3<u32>) -> u32 {
    return wid.y * nw.x + wid.x;
}

// Sums over a range of shooter_elements with one workgroup, each thread striding over a
// share: a cluster of millions of elements is neither added one by one in f32 (the sum
// outgrows the terms) nor looped over by one thread (llvmpipe ends every loop of an
// invocation after 65 535 iterations in all). rgb: Σ (unshot + extra) × area; w: Σ
// |unshot luminance| × area. The total is in wg_sum[0] on return.
fn workgroup_range_sum(first: u32, count: u32, extra: vec3<f32>, l: u32) -> vec4<f32> {
    var part = vec4<f32>(0.0);
    for (var k = first + l; k < first + count; k += 256u) {
        let e = shooter_elements[k];
        let a = element_points[e].w;
        let u = unshot[e].rgb;
        part += vec4<f32>((u + extra) * a, abs(dot(u, LUMA)) * a);
    }
    wg_sum[l] = part;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s >>= 1u) {
        if (l < s) {
            wg_sum[l] += wg_sum[l + s];
        }
        workgroupBarrier();
    }
    return wg_sum[0];
}

// Per shooter: rgb unshot power, w Σ |luminance| power. Shooters of at most SMALL_SHOOTER
// elements (a triangle, a small cluster) are summed by one thread each here; the larger
// ones by large_shooter_sums.
@compute @workgroup_size(64)
fn shooter_sums(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) nw: vec3<u32>,
) {
    let t = linear_thread(id, nw, 64u);
    if (t >= params.shooter_count) {
        return;
    }
    let r = shooters[t].range;
    if (r.y > SMALL_SHOOTER) {
        return;
    }
    var sum = vec4<f32>(0.0);
    for (var k = r.x; k < r.x + r.y; k++) {
        let e = shooter_elements[k];
        let a = element_points[e].w;
        let u = unshot[e].rgb;
        sum += vec4<f32>(u * a, abs(dot(u, LUMA)) * a);
    }
    shooter_power[t] = sum;
}

// The shooters of more than SMALL_SHOOTER elements, one workgroup each: listed after the
// shooters' records (range.z: the shooter).
@compute @workgroup_size(256)
fn large_shooter_sums(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nw: vec3<u32>,
    @builtin(local_invocation_index) l: u32,
) {
    let g = linear_group(wid, nw);
    if (g >= params.large_shooters) {
        return;
    }
    let r = shooters[params.shooter_count + g].range;
    let sum = workgroup_range_sum(r.x, r.y, vec3<f32>(0.0), l);
    if (l == 0u) {
        shooter_power[r.z] = sum;
    }
}

@compute @workgroup_size(256)
fn select_shooter(@builtin(local_invocation_index) l: u32) {
    var sum = vec4<f32>(0.0);
    var weighted = 0.0;
    for (var t = l; t < params.shooter_count; t += 256u) {
        sum += shooter_power[t];
        weighted += shooter_power[t].w * bitcast<f32>(shooters[t].range.z);
    }
    wg_sum[l] = sum;
    wg_best[l] = weighted;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s >>= 1u) {
        if (l < s) {
            wg_sum[l] += wg_sum[l + s];
            wg_best[l] += wg_best[l + s];
        }
        workgroupBarrier();
    }
    let total = wg_sum[0];
    let total_weighted = wg_best[0];
    workgroupBarrier();
    let ambient = total.rgb / params.total_area / (1.0 - params.mean_reflectance);
    var best = -1.0;
    var best_index = 0xffffffffu;
    for (var t = l; t < params.shooter_count; t += 256u) {
        let info = shooters[t];
        let area = info.reflectance_area.w;
        if (info.range.y == 0u || area <= 0.0) {
            continue;
        }
        let mean = shooter_power[t].rgb / area;
        var extra = vec3<f32>(0.0);
        if (params.overshoot != 0u) {
            extra = max(min(reemittance(info) * ambient, total.rgb / area - mean), vec3<f32>(0.0));
        }
        // Unshot light of both signs (a luminaire moved: negative where its light went,
        // GpuSolver::relight) must not cancel in the ranking: at least Σ |unshot| × area.
        let power = max(abs(dot(mean + extra, LUMA)) * area, shooter_power[t].w) * bitcast<f32>(info.range.z);
        if (power > best) {
            best = power;
            best_index = t;
        }
    }
    wg_best[l] = best;
    wg_index[l] = best_index;
    workgroupBarrier();
    for (var s = 128u; s > 0u; s >>= 1u) {
        if (l < s && wg_best[l + s] > wg_best[l]) {
            wg_best[l] = wg_best[l + s];
            wg_index[l] = wg_index[l + s];
        }
        workgroupBarrier();
    }
    if (l == 0u) {
        let t = wg_index[0];
        var extra = vec3<f32>(0.0);
        if (params.overshoot != 0u && t != 0xffffffffu) {
            let info = shooters[t];
            let area = info.reflectance_area.w;
            let mean = shooter_power[t].rgb / area;
            extra = max(min(reemittance(info) * ambient, total.rgb / area - mean), vec3<f32>(0.0));
        }
        let at = params.shooter_count;
        shooter_power[at] = vec4<f32>(bitcast<f32>(t), wg_best[0], total.w, total_weighted);
        shooter_power[at + 1u] = vec4<f32>(extra, 0.0);
        shooter_power[at + 2u] = vec4<f32>(total.rgb, 0.0);
    }
}

// Per patch of the shot (one workgroup each): its unshot radiosity to shoot.
@compute @workgroup_size(256)
fn gather_patches(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nw: vec3<u32>,
    @builtin(local_invocation_index) l: u32,
) {
    let i = linear_group(wid, nw);
    if (i >= params.patch_count) {
        return;
    }
    let p = patches[params.patch_first + i];
    let extra = shooter_power[params.shooter_count + 1u].rgb;
    let sum = workgroup_range_sum(p.range.x, p.range.y, extra, l);
    if (l == 0u) {
        // w: the mean |unshot luminance|, for the cells' sizes and the links' oracle.
        patch_delta[i] = sum / max(p.area, 1e-30);
    }
}

@compute @workgroup_size(64)
fn clear_shooter(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) nw: vec3<u32>,
) {
    // The elements of this batch's top cells (contiguous in shooter_elements).
    let i = linear_thread(id, nw, 64u);
    if (i >= params.clear_count) {
        return;
    }
    let e = shooter_elements[params.clear_first + i];
    held[params.clear_first + i - shooters[params.shooter].range.x] = unshot[e];
    unshot[e] = vec4<f32>(-shooter_power[params.shooter_count + 1u].rgb, 0.0);
}

// A shot stopped early (one workgroup per patch from patch_first): the elements of every
// top cell not shot get back what clear_shooter held (and the overshoot it took).
@compute @workgroup_size(64)
fn restore_unshot(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nw: vec3<u32>,
    @builtin(local_invocation_index) l: u32,
) {
    let i = params.patch_first + linear_group(wid, nw);
    if (i >= params.patch_first + params.patch_count || patches[i].top == 0u) {
        return;
    }
    let r = patches[i].range;
    let base = shooters[params.shooter].range.x;
    let extra = shooter_power[params.shooter_count + 1u].rgb;
    for (var j = l; j < r.y; j += 64u) {
        let at = r.x + j;
        unshot[shooter_elements[at]] += vec4<f32>(held[at - base].rgb + extra, 0.0);
    }
}

// One shooting patch as seen by the receive pass.
struct Shot {
    // The hemicube faces' view-projections: top (along the normal), +t, −t, +b, −b.
    faces: array<mat4x4<f32>, 5>,
    // Patch frame: tangent, bitangent, normal (xyz); centroid.
    tangent: vec4<f32>,
    bitangent: vec4<f32>,
    normal: vec4<f32>,
    centroid: vec4<f32>,
    // The patch polygon (counter-clockwise from the front), up to 8 corners.
    polygon: array<vec4<f32>, 8>,
    // patch (local index), corner count, form factor (0 disc, 1 polygon), map size.
    info: vec4<u32>,
    // area, relative depth tolerance, absolute depth tolerance (m), visibility (0 hemicube, 1 stereographic).
    extra: vec4<f32>,
    // The cells above this one, nearest first (radiosity/links.rs): xyz centre, w reach
    // (m; negative: none).
    ancestors: array<vec4<f32>, 4>,
    // Its reach (m), the plane tolerance (m), the form factor's scale (a coarse cell's
    // elements' area over its polygon's), 1 for a top cell.
    link: vec4<f32>,
    // The pieces it shoots (first, end): their elements do not receive from it; its
    // first tile in the atlas of visibility maps, and the atlas's tiles per row.
    pieces: vec4<u32>,
    // Mirrors and clear glass (lighting/specular.rs): rgb the product of the windows'
    // coefficients its light has passed (1 for a real cell).
    tint: vec4<f32>,
    // A virtual cell's window plane, oriented to where its light goes: it lights only
    // where dot(plane.xyz, p) + plane.w > 0.
    plane: vec4<f32>,
    // Its window's triangles (first, count) in window_corners (count 0: a real cell); the
    // record of the cell it images (its parent in the reflection tree).
    window: vec4<u32>,
    // Its receive pass's records in cell_receivers (first, count) and its threads
    // (radiosity/gpu/cell_receivers.rs: the receivers that may take its light).
    receivers: vec4<u32>,
    // Up to the records' 768-byte stride.
    pad: array<vec4<f32>, 4>,
};

@group(1) @binding(0) var<uniform> shot: Shot;
// The batch's visibility maps, square tiles of info.w texels (radiosity/atlas.rs).
@group(1) @binding(1) var visibility: texture_2d<f32>;
// The batch's records (the same as `shot`'s), for a virtual cell's parents.
@group(1) @binding(2) var<storage, read> records: array<Shot>;
// The specular windows' triangles, three corners each.
@group(1) @binding(3) var<storage, read> window_corners: array<vec4<f32>>;
// The batch's receive records: elements first..first + count are threads
// before..before + count of a cell's pass; hold 1 where they keep what they receive back.
struct ReceiverRun {
    first: u32,
    before: u32,
    count: u32,
    hold: u32,
};
@group(1) @binding(4) var<storage, read> cell_receivers: array<ReceiverRun>;

const PI = 3.14159265358979;

fn disc_form_factor(p: vec3<f32>, n: vec3<f32>) -> f32 {
    let d = shot.centroid.xyz - p;
    let d2 = dot(d, d);
    let w = d * inverseSqrt(d2);
    let cos_p = dot(n, w);
    let cos_q = -dot(shot.normal.xyz, w);
    if (cos_p <= 0.0 || cos_q <= 0.0) {
        return 0.0;
    }
    let a = shot.extra.x;
    return a * cos_p * cos_q / (PI * d2 + a);
}

// Lambert's contour integral over the patch polygon clipped to the receiver's horizon.
// Zero behind the patch's plane: a patch emits from its front only.
fn polygon_form_factor(p: vec3<f32>, n: vec3<f32>) -> f32 {
    if (dot(shot.normal.xyz, p - shot.polygon[0].xyz) <= 0.0) {
        return 0.0;
    }
    var clipped: array<vec3<f32>, 10>;
    var count = 0u;
    let corners = shot.info.y;
    for (var i = 0u; i < corners; i++) {
        let a = shot.polygon[i].xyz;
        let b = shot.polygon[(i + 1u) % corners].xyz;
        let sa = dot(n, a - p);
        let sb = dot(n, b - p);
        if (sa >= 0.0) {
            clipped[count] = a - p;
            count++;
        }
        if ((sa >= 0.0) != (sb >= 0.0)) {
            clipped[count] = a + (b - a) * (sa / (sa - sb)) - p;
            count++;
        }
    }
    if (count < 3u) {
        return 0.0;
    }
    var sum = 0.0;
    for (var i = 0u; i < count; i++) {
        let ra = clipped[i];
        let rb = clipped[(i + 1u) % count];
        let c = cross(ra, rb);
        let len = length(c);
        if (len > 1e-20) {
            sum += atan2(len, dot(ra, rb)) * dot(n, c / len);
        }
    }
    return abs(sum) / (2.0 * PI);
}

// The shot's form factor (disc or polygon, as the shot says) at `p` with unit normal `n`.
fn form_factor(p: vec3<f32>, n: vec3<f32>) -> f32 {
    if (shot.info.z == 1u) {
        return polygon_form_factor(p, n);
    }
    return disc_form_factor(p, n);
}

// The hemicube face a direction (x, y, z in the cell's frame) falls on.
fn hemicube_layer(x: f32, y: f32, z: f32) -> i32 {
    if (z >= max(abs(x), abs(y))) {
        return 0;
    } else if (abs(x) >= abs(y)) {
        return select(2, 1, x > 0.0);
    }
    return select(4, 3, y > 0.0);
}

// The texel of map coordinates `uv` (−1..1) in a tile of `size` texels.
fn map_texel(uv: vec2<f32>, size: i32) -> vec2<i32> {
    let texel = vec2<i32>(floor((vec2<f32>(uv.x, -uv.y) * 0.5 + 0.5) * f32(size)));
    return clamp(texel, vec2<i32>(0), vec2<i32>(size - 1));
}

// What the receive pass needs of one shooting cell's map to follow its texels' rays:
// the cell's centre and frame, its hemicube faces' view-projections, where its tiles lie
// in the atlas and its depth tolerances.
struct MapView {
    centre: vec3<f32>,
    tangent: vec3<f32>,
    bitangent: vec3<f32>,
    normal: vec3<f32>,
    // The batch's record the map is (its hemicube faces' view-projections are read from
    // there, not copied), or SHOT_MAP for `shot`.
    record: u32,
    stereographic: bool,
    // Texels per side, its first tile, the atlas's tiles per row.
    size: i32,
    tile: u32,
    columns: u32,
    // Relative (of the distance) and absolute (m) depth tolerances.
    relative: f32,
    absolute: f32,
};

// MapView.record of the shot's own map.
const SHOT_MAP = 0xffffffffu;

// The view-projection of `m`'s hemicube face `layer`.
fn map_face(m: MapView, layer: i32) -> mat4x4<f32> {
    if (m.record == SHOT_MAP) {
        return shot.faces[layer];
    }
    return records[m.record].faces[layer];
}

// The map of this shot's cell.
fn shot_view() -> MapView {
    return MapView(shot.centroid.xyz, shot.tangent.xyz, shot.bitangent.xyz, shot.normal.xyz,
        SHOT_MAP, shot.extra.w > 0.5, i32(shot.info.w), shot.pieces.z, shot.pieces.w,
        shot.extra.y, shot.extra.z);
}

// The map of the batch's record `r`.
fn record_view(r: u32) -> MapView {
    return MapView(records[r].centroid.xyz, records[r].tangent.xyz, records[r].bitangent.xyz,
        records[r].normal.xyz, r, records[r].extra.w > 0.5, i32(records[r].info.w),
        records[r].pieces.z, records[r].pieces.w, records[r].extra.y, records[r].extra.z);
}

// Map coordinates (−1..1) of texel `at`'s centre in a tile of `size` texels.
fn texel_centre(at: vec2<i32>, size: i32) -> vec2<f32> {
    let uv = (vec2<f32>(at) + 0.5) / f32(size) * 2.0 - 1.0;
    return vec2<f32>(uv.x, -uv.y);
}

// The face of `m`'s map that `p` projects to (0 for a stereographic map).
fn map_layer(m: MapView, p: vec3<f32>) -> i32 {
    if (m.stereographic) {
        return 0;
    }
    let v = p - m.centre;
    return hemicube_layer(dot(v, m.tangent), dot(v, m.bitangent), dot(v, m.normal));
}

// The texel of `m`'s map that `p` projects to, on the hemicube face whose view-projection
// is `face` (map_face; unused for a stereographic map).
fn map_texel_of(m: MapView, face: mat4x4<f32>, p: vec3<f32>) -> vec2<i32> {
    if (m.stereographic) {
        let v = p - m.centre;
        let u = vec3<f32>(dot(v, m.tangent), dot(v, m.bitangent), dot(v, m.normal)) / length(v);
        return map_texel(stereographic_project(u), m.size);
    }
    let clip = face * vec4<f32>(p, 1.0);
    return map_texel(clip.xy / clip.w, m.size);
}

// The unit direction from `m`'s centre through the centre of texel `at` of the hemicube
// face whose view-projection is `face` (map_face; unused for a stereographic map).
fn texel_ray(m: MapView, face: mat4x4<f32>, at: vec2<i32>) -> vec3<f32> {
    let uv = texel_centre(at, m.size);
    if (m.stereographic) {
        let d = stereographic_ray(uv);
        return normalize(d.x * m.tangent + d.y * m.bitangent + d.z * m.normal);
    }
    // The ray is where the planes clip.x = u clip.w and clip.y = v clip.w through the eye
    // meet; w grows along it.
    let x = vec3<f32>(face[0].x, face[1].x, face[2].x);
    let y = vec3<f32>(face[0].y, face[1].y, face[2].y);
    let w = vec3<f32>(face[0].w, face[1].w, face[2].w);
    let d = normalize(cross(x - uv.x * w, y - uv.y * w));
    return select(d, -d, dot(d, w) < 0.0);
}

// What a map holds where nothing was drawn (the render pass's clear, the compute
// rasterizer's empty texel).
const NOTHING_DRAWN: f32 = 1e30;

// How far from a receiver, in stretched footprints (map_reaches), the surface a texel shows
// may lie and still be tested as an occluder by its plane.
const REACH = 5.0;

// map_reaches's receiver size for a point of a window's plane: it is no surface of its own,
// so only the texel's depth decides (rule 2 below is left out).
const WINDOW_POINT: f32 = 0.0;

// Whether `m`'s light reaches a receiver at `p` with plane normal `n` and size `size` (m;
// WINDOW_POINT for a point of a window, which the surface-plane test below leaves out).
// The texel `p` projects to is read, once:
// 1. Seen when the map holds something at least as far (less the tolerances) as the
//    receiver's plane along that texel's ray (where that ray meets the plane within a
//    stretched footprint of `p`, else as `p`): a grazing receiver does not shadow itself
//    where the depth changes across a texel, and no tolerance lets light past nearby
//    occluders.
// 2. Else seen when the surface the texel shows, near `p`, does not part `p` from the
//    centre: its plane, fitted through the texels beside it that continue it best, has
//    `p` on the centre's side (by a hundredth of the receiver's size). This keeps the
//    light of a receiver next to a concave corner whose texel shows the other wall.
// Wallner's lookup (Fig. 2.3), a receiver seen when one of the nine texels around its own
// is at least as far as `p`, lit every receiver within a texel and a half of an
// occluder's outline (5.7 % too much light in a room with 144 boxes on its floor,
// hemicube at 256²) and let light through thin walls near their junctions.
// A stereographic map's texel where nothing was drawn counts as nothing reached: every
// receiver is a surface drawn into the map, and such a map's empty texels inside the disc
// are the slivers between the chords the render pipeline draws and the arcs the edges
// project to, beyond which lies what the edges' walls hide.
fn map_reaches(m: MapView, p: vec3<f32>, n: vec3<f32>, size: f32) -> bool {
    // The face's view-projection, read once for the texel and the rays of its texels.
    let layer = map_layer(m, p);
    let face = map_face(m, layer);
    let at = vec3<i32>(map_texel_of(m, face, p), layer);
    let tile = m.tile + u32(at.z);
    let origin = vec2<i32>(vec2<u32>(tile % m.columns, tile / m.columns)) * m.size;
    let d = textureLoad(visibility, origin + at.xy, 0).r;
    if (m.stereographic && d >= NOTHING_DRAWN) {
        return false;
    }
    let own = distance(p, m.centre);
    let ray = texel_ray(m, face, at.xy);
    let along = dot(n, ray);
    let t = dot(n, p - m.centre) / along;
    // A texel's footprint at p's distance (its width in radians is at most 4 / size).
    let footprint = own * 4.0 / f32(m.size);
    var plane = own;
    let stretch = footprint / max(abs(along), 0.2);
    if (t > 0.0 && distance(m.centre + ray * t, p) <= stretch) {
        plane = min(t, own);
    }
    if (d >= plane * (1.0 - m.relative) - m.absolute) {
        return true;
    }
    let hit = m.centre + ray * d;
    if (size <= WINDOW_POINT || distance(hit, p) > REACH * stretch) {
        return false;
    }
    let across = surface_step(m, face, at, origin, hit, d, vec2<i32>(1, 0));
    let down = surface_step(m, face, at, origin, hit, d, vec2<i32>(0, 1));
    let normal = cross(across, down);
    let scale = length(normal);
    if (scale <= 0.0) {
        return false;
    }
    let side = dot(normal, m.centre - hit);
    return dot(normal, p - hit) * sign(side) / scale > 0.01 * size;
}

// The step across the surface a map shows from `hit` (texel `at`, depth `d`) to the
// surface at a neighbour along `axis`: of the two, the one whose next texel continues it
// best (the other may lie across a crease or an outline); zero where neither holds
// anything.
fn surface_step(m: MapView, face: mat4x4<f32>, at: vec3<i32>, origin: vec2<i32>, hit: vec3<f32>, d: f32, axis: vec2<i32>) -> vec3<f32> {
    var step = vec3<f32>(0.0);
    var best = NOTHING_DRAWN;
    for (var k = -1; k <= 1; k += 2) {
        let q = at.xy + axis * k;
        if (any(q < vec2<i32>(0)) || any(q >= vec2<i32>(m.size))) {
            continue;
        }
        let dq = textureLoad(visibility, origin + q, 0).r;
        if (dq >= NOTHING_DRAWN) {
            continue;
        }
        let hq = m.centre + texel_ray(m, face, q) * dq;
        var bend = abs(dq - d);
        let q2 = q + axis * k;
        if (all(q2 >= vec2<i32>(0)) && all(q2 < vec2<i32>(m.size))) {
            let d2 = textureLoad(visibility, origin + q2, 0).r;
            if (d2 < NOTHING_DRAWN) {
                let h2 = m.centre + texel_ray(m, face, q2) * d2;
                bend = length(h2 - 2.0 * hq + hit);
            }
        }
        if (bend < best) {
            best = bend;
            step = (hq - hit) * f32(k);
        }
    }
    return step;
}


// Whether `m`, a point of a window's plane with normal `n`, lies within one of its
// triangles window_corners[first..][..count].
fn in_window(first: u32, count: u32, m: vec3<f32>, n: vec3<f32>) -> bool {
    for (var k = 0u; k < count; k++) {
        let a = window_corners[3u * (first + k)].xyz;
        let b = window_corners[3u * (first + k) + 1u].xyz;
        let c = window_corners[3u * (first + k) + 2u].xyz;
        let area = dot(cross(b - a, c - a), n);
        let tolerance = -1e-5 * abs(area);
        let wa = dot(cross(c - b, m - b), n) * sign(area);
        let wb = dot(cross(a - c, m - c), n) * sign(area);
        let wc = dot(cross(b - a, m - a), n) * sign(area);
        if (wa >= tolerance && wb >= tolerance && wc >= tolerance) {
            return true;
        }
    }
    return false;
}

// Whether this virtual cell's light reaches `p` (lighting/specular.rs, trace): the
// straight line from each image in turn meets its window inside the outline, and the cell
// it images sees that point in its own map, down to the real cell. The last leg (to `p`)
// is this cell's own map.
fn through_windows(p: vec3<f32>) -> bool {
    if (dot(shot.plane.xyz, p) + shot.plane.w <= shot.extra.z) {
        return false;
    }
    var y = p;
    var eye = shot.centroid.xyz;
    var plane = shot.plane;
    var window = shot.window;
    for (var depth = 0u; depth < 8u; depth++) {
        let dv = dot(plane.xyz, eye) + plane.w;
        let dy = dot(plane.xyz, y) + plane.w;
        if (dv >= 0.0 || dy <= 0.0) {
            return false;
        }
        let m = eye + (y - eye) * (dv / (dv - dy));
        if (!in_window(window.x, window.y, m, plane.xyz)) {
            return false;
        }
        let parent = window.z;
        if (!map_reaches(record_view(parent), m, plane.xyz, WINDOW_POINT)) {
            return false;
        }
        if (records[parent].window.y == 0u) {
            return true;
        }
        y = m;
        eye = records[parent].centroid.xyz;
        plane = records[parent].plane;
        window = records[parent].window;
    }
    return false;
}

// Whether a receiver at `p` whose reaches are scaled by `scale` takes its light from this
// cell (radiosity/links.rs, takes_light_from): beyond its reach and within every
// ancestor's; receivers next to the shooter's plane take it from top cells only.
fn takes_light(p: vec3<f32>, scale: f32) -> bool {
    if (dot(shot.normal.xyz, p - shot.centroid.xyz) <= shot.link.y) {
        return shot.link.w > 0.5;
    }
    if (distance(p, shot.centroid.xyz) < shot.link.x * scale) {
        return false;
    }
    for (var a = 0u; a < 4u; a++) {
        let up = shot.ancestors[a];
        if (up.w >= 0.0 && distance(p, up.xyz) >= up.w * scale) {
            return false;
        }
    }
    return true;
}

// The receive thread `t`'s element (x) and whether its chart holds (y): the last range
// starting at or before it.
fn receiver_element(t: u32) -> vec2<u32> {
    var lo = 0u;
    var hi = params.range_count;
    while (hi - lo > 1u) {
        let mid = (lo + hi) / 2u;
        if (patches[params.range_first + mid].range.y <= t) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let record = patches[params.range_first + lo];
    return vec2<u32>(record.range.x + (t - record.range.y), record.top);
}

// [`receiver_element`] of the cell's own receivers (Shot.receivers).
fn cell_receiver(t: u32) -> vec2<u32> {
    let first = shot.receivers.x;
    var lo = 0u;
    var hi = shot.receivers.y;
    while (hi - lo > 1u) {
        let mid = (lo + hi) / 2u;
        if (cell_receivers[first + mid].before <= t) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let run = cell_receivers[first + lo];
    return vec2<u32>(run.first + (t - run.before), run.hold);
}

// The shooter holding `piece`: the last whose first piece (range.w) is at most it.
fn shooter_of_piece(piece: u32) -> u32 {
    var lo = 0u;
    var hi = params.shooter_count;
    while (hi - lo > 1u) {
        let mid = (lo + hi) / 2u;
        if (shooters[mid].range.w <= piece) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

// What a receive thread's element takes from the shot before visibility: its element,
// position, form factors to the front and back, and its reflectance and transmittance.
struct Receiving {
    i: u32,
    // Its chart holds what it receives (held_back).
    hold: bool,
    p: vec3<f32>,
    // Its plane's normal and its size (the square root of its area, m).
    n: vec3<f32>,
    size: f32,
    f: f32,
    back: f32,
    reflectance: vec3<f32>,
    transmittance: vec3<f32>,
};

// The receiving of thread `thread`, or none (the element is not the shot's to light).
fn receiving(thread: u32) -> Receiving {
    var none: Receiving;
    none.f = 0.0;
    none.back = 0.0;
    if (thread >= shot.receivers.z) {
        return none;
    }
    let element = cell_receiver(thread);
    let i = element.x;
    let normal_piece = element_normals[i];
    let piece = bitcast<u32>(normal_piece.w);
    if (piece >= shot.pieces.x && piece < shot.pieces.y) {
        return none;
    }
    let p = element_points[i].xyz;
    let geometric = normal_piece.xyz;
    var n = geometric;
    if (!takes_light(p, reach_scale[i])) {
        return none;
    }
    let info = shooters[shooter_of_piece(piece)];
    // A translucent receiver sends on what arrives on its back (radiosity/transmission.rs).
    var back = 0.0;
    if (any(info.transmittance.rgb > vec3<f32>(0.0))) {
        back = form_factor(p, -geometric);
    }
    // A curved or normal-mapped receiver: the form factor with its receiving normal's
    // direction times its length, never through its geometric back.
    var scale = 1.0;
    var front = true;
    if (params.receiving_normals != 0u) {
        let r = element_receiving[i];
        let len = length(r.xyz);
        if (r.w > 0.5) {
            front = dot(n, shot.centroid.xyz - p) > 0.0 && len > 0.0;
            n = r.xyz / max(len, 1e-30);
            scale = len;
        }
    }
    var f = 0.0;
    if (front) {
        f = form_factor(p, n) * scale;
    }
    return Receiving(i, element.y != 0u, p, geometric, sqrt(element_points[i].w), f, back, info.reflectance_area.rgb, info.transmittance.rgb);
}

// Adds what `r` takes of the shot's power times `tint`.
fn deliver(r: Receiving, tint: vec3<f32>) {
    let delta = patch_delta[shot.info.x].rgb * shot.link.z * tint;
    let incident = delta * r.f;
    let gained = r.reflectance * incident + r.transmittance * delta * r.back;
    if (r.hold) {
        held_back[r.i] += vec4<f32>(gained, dot(incident, LUMA));
        return;
    }
    radiosity[r.i] += vec4<f32>(gained, dot(incident, LUMA));
    unshot[r.i] += vec4<f32>(gained, 0.0);
}

// The charts of the receiver ranges (none holding) are given what they held back: it
// joins their radiosity, illuminance and unshot radiosity.
@compute @workgroup_size(64)
fn release_held_back(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) nw: vec3<u32>,
) {
    let t = linear_thread(id, nw, 64u);
    if (t >= params.range_total) {
        return;
    }
    let i = receiver_element(t).x;
    let h = held_back[i];
    radiosity[i] += h;
    unshot[i] += vec4<f32>(h.rgb, 0.0);
    held_back[i] = vec4<f32>(0.0);
}

// A real cell's shot.
@compute @workgroup_size(64)
fn receive(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) nw: vec3<u32>,
) {
    let r = receiving(linear_thread(id, nw, 64u));
    if ((r.f <= 0.0 && r.back <= 0.0) || !map_reaches(shot_view(), r.p, r.n, r.size)) {
        return;
    }
    deliver(r, vec3<f32>(1.0));
}

// A virtual cell's shot (radiosity/gpu/virtual_cells.rs): through its windows, its
// power times their coefficients.
@compute @workgroup_size(64)
fn receive_through_windows(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) nw: vec3<u32>,
) {
    let r = receiving(linear_thread(id, nw, 64u));
    let seen = map_reaches(shot_view(), r.p, r.n, r.size);
    if ((r.f <= 0.0 && r.back <= 0.0) || !seen || !through_windows(r.p)) {
        return;
    }
    deliver(r, shot.tint.rgb);
}
