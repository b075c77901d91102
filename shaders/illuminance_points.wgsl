// Direct illuminance at many points: `goniolight illuminance` and the GPU side of the
// illuminance tests. Needs ldt.wgsl, lighting.wgsl and shadow.wgsl before it; the shadow
// mask's entry for point i is slot i.

struct PointParams {
    count: u32,
    light_count: u32,
    _pad0: u32,
    _pad1: u32,
};

@group(0) @binding(0) var<uniform> point_params: PointParams;
// Pairs of vec4: position, normal (binding 6, the sector colours, is in lighting.wgsl).
@group(0) @binding(4) var<storage, read> points: array<vec4<f32>>;
// Per point: rgb illuminance weighted by each luminaire's colour, a lux.
@group(0) @binding(5) var<storage, read_write> lux: array<vec4<f32>>;

@compute @workgroup_size(64)
fn illuminance_points(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= point_params.count) {
        return;
    }
    let p = points[2u * i].xyz;
    let n = normalize(points[2u * i + 1u].xyz);
    var e = vec4<f32>(0.0);
    for (var k = 0u; k < point_params.light_count; k++) {
        let l = lights[k];
        let lit = light_illuminance(l, p, n) * light_visibility(l, k, p, n, i);
        e += vec4<f32>(light_color(l, normalize(p - l.position.xyz)) * lit, lit);
    }
    lux[i] = e;
}
