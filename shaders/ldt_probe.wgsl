// Samples one LDT layer at many directions: the GPU side of the CPU/GPU comparison.

struct ProbeParams {
    layer: u32,
    interp: u32,
    count: u32,
    _pad: u32,
};

@group(0) @binding(0) var ldt_tex: texture_2d_array<f32>;
@group(0) @binding(1) var<storage, read> ldt_info: array<LdtInfo>;
@group(0) @binding(2) var<uniform> params: ProbeParams;
@group(0) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> results: array<f32>;

@compute @workgroup_size(64)
fn probe(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= params.count) {
        return;
    }
    let a = ldt_angles(directions[i].xyz);
    results[i] = ldt_sample(ldt_tex, params.layer, ldt_info[params.layer], a.x, a.y, params.interp);
}
