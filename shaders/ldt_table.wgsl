// The Catmull-Rom tables of LDT layers: per layer, each row is one γ knot of the stored
// grid (two padding knots beyond either end, with the values Catmull-Rom reads there:
// mirrored across a pole, else 0), and each column one C of a dense 0.125° grid holding
// the Catmull-Rom interpolation across the C planes at that knot. Catmull-Rom is a tensor
// product, so the renderer's lookup (LIGHT_MODEL 5 in lighting.wgsl: Catmull-Rom across
// four rows, linear across two columns, two gathers) equals the per-pixel spline up to
// the linear step in C. Needs ldt.wgsl before it.

struct TableParams {
    layer: u32,
    columns: u32,
    _pad0: u32,
    _pad1: u32,
};

@group(0) @binding(0) var ldt_tex: texture_2d_array<f32>;
@group(0) @binding(1) var<storage, read> ldt_info: array<LdtInfo>;
@group(0) @binding(2) var<uniform> table: TableParams;

@vertex
fn vs_table(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(i & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_table(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let info = ldt_info[table.layer];
    let k = i32(floor(pos.y)) - 2;
    if (k > i32(info.gamma_count) + 1) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let nc = i32(info.c_count);
    if (nc == 1) {
        return vec4<f32>(ldt_knot(ldt_tex, table.layer, info, 0u, k), 0.0, 0.0, 1.0);
    }
    let c = floor(pos.x) * 360.0 / f32(table.columns);
    let dc = 360.0 / f32(nc);
    let j = min(i32(floor(c / dc)), nc - 1);
    let q = vec4<f32>(
        ldt_knot(ldt_tex, table.layer, info, u32((j - 1 + nc) % nc), k),
        ldt_knot(ldt_tex, table.layer, info, u32(j), k),
        ldt_knot(ldt_tex, table.layer, info, u32((j + 1) % nc), k),
        ldt_knot(ldt_tex, table.layer, info, u32((j + 2) % nc), k),
    );
    let v = dot(catmull_rom_weights((c - dc * f32(j)) / dc), q);
    return vec4<f32>(v, 0.0, 0.0, 1.0);
}
