// The real-time renderer's geometry passes: a depth pre-pass, then one shading pass that
// sums every luminaire (Blinn-Phong, E = I · cos θ / d²) into an HDR target:
// rgb = luminance (cd/m²), a = direct illuminance (lux) on the surface, −1 = no surface.
// With a solved radiosity light map (frame.light_map = 1) the diffuse light and the lux
// come from the map (direct + interreflected) and the luminaires add their specular term.
// Needs ldt.wgsl, lighting.wgsl and shadow.wgsl before it.

struct Frame {
    view_proj: mat4x4<f32>,
    // xyz: eye; w: 1 for an orthographic camera.
    eye: vec4<f32>,
    // xyz: view direction (used by orthographic cameras).
    view_dir: vec4<f32>,
    light_count: u32,
    light_map: u32,
    _pad1: u32,
    _pad2: u32,
};

struct MaterialParams {
    // rgb: Kd; w: 1 when a diffuse map is bound.
    diffuse: vec4<f32>,
    // rgb: Ks; w: Ns.
    specular: vec4<f32>,
    // x: 1 when a normal map is bound; y: 1 when the diffuse map's alpha cuts holes.
    flags: vec4<u32>,
    // rgb: the diffuse map's mean colour (linear; white without one). A solved light map
    // already holds it in its reflectance (radiosity/scene.rs).
    texture_mean: vec4<f32>,
    // rgb: diffuse transmittance (radiosity/transmission.rs): a luminaire behind the
    // surface lights it through; a solved light map already holds that.
    transmittance: vec4<f32>,
};

@group(0) @binding(0) var<uniform> frame: Frame;
// rgb: radiosity (lm/m²); a: illuminance received (lux).
@group(0) @binding(12) var light_map: texture_2d<f32>;
@group(0) @binding(13) var light_map_sampler: sampler;
@group(1) @binding(0) var<uniform> material: MaterialParams;
@group(1) @binding(1) var diffuse_map: texture_2d<f32>;
@group(1) @binding(2) var normal_map: texture_2d<f32>;
@group(1) @binding(3) var material_sampler: sampler;

const PI: f32 = 3.14159265358979;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
    @location(4) lightmap_uv: vec2<f32>,
};

struct VertexOut {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
    @location(4) lightmap_uv: vec2<f32>,
};

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = frame.view_proj * vec4<f32>(v.position, 1.0);
    out.world = v.position;
    out.normal = v.normal;
    out.uv = v.uv;
    out.tangent = v.tangent;
    out.lightmap_uv = v.lightmap_uv;
    return out;
}

struct DepthOut {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_depth(v: VertexIn) -> DepthOut {
    var out: DepthOut;
    out.clip = frame.view_proj * vec4<f32>(v.position, 1.0);
    out.uv = v.uv;
    return out;
}

// Whether the pipeline tests alpha masks (those of masked materials): without, it has no
// discard and keeps early depth tests.
override ALPHA_TEST: bool = false;

// Whether `uv` falls in a hole of the material's alpha mask: the texel under
// floor(fract(uv) · size) has alpha below one half, the rule of shadow/cutout.rs.
fn in_hole(uv: vec2<f32>) -> bool {
    if (!ALPHA_TEST || material.flags.y == 0u) {
        return false;
    }
    let size = textureDimensions(diffuse_map);
    let texel = min(vec2<u32>(fract(uv) * vec2<f32>(size)), size - vec2<u32>(1u));
    return textureLoad(diffuse_map, texel, 0).a < 0.5;
}

@fragment
fn fs_depth(in: DepthOut) {
    if (in_hole(in.uv)) {
        discard;
    }
}

// The shading normal: the interpolated normal, turned toward the viewer on back faces,
// perturbed by the tangent-space normal map when there is one. On the map's coarser mip
// levels it is shortened to the mean length of the normals it stands for (alpha), so the
// diffuse light is the mean over the relief (see render/mipmaps.rs).
fn shading_normal(in: VertexOut, geometric: vec3<f32>) -> vec3<f32> {
    if (material.flags.x == 0u) {
        return geometric;
    }
    return perturbed(in, geometric, textureSample(normal_map, material_sampler, in.uv));
}

// `geometric` perturbed by the normal-map texel `texel` (shortened by its alpha).
fn perturbed(in: VertexOut, geometric: vec3<f32>, texel: vec4<f32>) -> vec3<f32> {
    let t = normalize(in.tangent.xyz - geometric * dot(geometric, in.tangent.xyz));
    let b = cross(geometric, t) * in.tangent.w;
    let m = texel.xyz * 2.0 - 1.0;
    return normalize(t * m.x + b * m.y + geometric * m.z) * texel.a;
}

// The normal map's mip level whose texels each cover one light-map texel: there the map
// holds the mean normal an element of the solution received with
// (radiosity/shading.rs).
fn element_level(in: VertexOut) -> f32 {
    let map = vec2<f32>(textureDimensions(normal_map));
    let atlas = vec2<f32>(textureDimensions(light_map));
    let across = length(dpdx(in.uv * map)) / max(length(dpdx(in.lightmap_uv * atlas)), 1e-12);
    let down = length(dpdy(in.uv * map)) / max(length(dpdy(in.lightmap_uv * atlas)), 1e-12);
    return log2(max(max(across, down), 1.0));
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    if (in_hole(in.uv)) {
        discard;
    }
    let solved = frame.light_map != 0u;
    // Solved, a translucent surface has a back face of its own with its far side's light
    // (scene/back_faces.rs): each side is drawn from its front only.
    if (solved && !front && any(material.transmittance.rgb > vec3<f32>(0.0))) {
        discard;
    }
    var n_geo = normalize(in.normal);
    if (!front) {
        n_geo = -n_geo;
    }
    let n = shading_normal(in, n_geo);
    var texture_rgb = vec3<f32>(1.0);
    if (material.diffuse.w > 0.5) {
        texture_rgb = textureSample(diffuse_map, material_sampler, in.uv).rgb;
    }
    // A solved normal-mapped surface: the light map holds what each element received
    // with its mean normal; the relief finer than an element is the direct light with
    // the pixel's normal less that with the element's.
    let relief = solved && material.flags.x != 0u;
    var n_element = n;
    if (relief) {
        n_element = perturbed(in, n_geo, textureSampleLevel(normal_map, material_sampler, in.uv, element_level(in)));
    }
    // The direct light with the pixel's normal and with the element's.
    var lit_pixel = vec3<f32>(0.0);
    var lit_element = vec3<f32>(0.0);
    // With a light map the diffuse light is the map's; only the specular term is direct.
    let kd = select(material.diffuse.rgb * texture_rgb, vec3<f32>(0.0), solved);
    let ks = material.specular.rgb;
    let ns = material.specular.w;
    var v = normalize(frame.eye.xyz - in.world);
    if (frame.eye.w > 0.5) {
        v = -frame.view_dir.xyz;
    }
    // Normalised Blinn-Phong lobe, so Ks is an energy fraction.
    let spec_norm = (ns + 8.0) / (8.0 * PI);
    var radiance = vec3<f32>(0.0);
    var lux = 0.0;
    let pixel = vec2<u32>(in.clip.xy);
    let slot = pixel.y * shadow.mask_width + pixel.x;
    for (var i = 0u; i < frame.light_count; i++) {
        let l = lights[i];
        let d = l.position.xyz - in.world;
        let lit_geo = dot(d, n_geo) > 0.0;
        let lit_shading = dot(d, n) > 0.0;
        if (!lit_geo && !solved && any(material.transmittance.rgb > vec3<f32>(0.0))) {
            // Behind a translucent surface: what arrives on its far side, τ of it
            // emitted diffusely on this one.
            let through = light_visibility(l, i, in.world, -n_geo, slot);
            let inc = light_incident(l, in.world);
            let e = through * inc.normal_lux * max(dot(-n_geo, inc.to_light), 0.0);
            radiance += material.transmittance.rgb / PI * light_color(l, -inc.to_light) * e;
        }
        if (!(lit_geo || lit_shading)) {
            continue;
        }
        let visible = light_visibility(l, i, in.world, n_geo, slot);
        if (visible <= 0.0) {
            continue;
        }
        let inc = light_incident(l, in.world);
        lux += visible * inc.normal_lux * max(dot(n_geo, inc.to_light), 0.0);
        let e = visible * inc.normal_lux * max(dot(n, inc.to_light), 0.0);
        let h = normalize(inc.to_light + v);
        let spec = ks * spec_norm * pow(max(dot(n, h), 0.0), ns);
        radiance += (kd / PI + spec) * light_color(l, -inc.to_light) * e;
        if (relief) {
            let light = light_color(l, -inc.to_light) * visible * inc.normal_lux;
            lit_pixel += light * max(dot(n, inc.to_light), 0.0);
            lit_element += light * max(dot(n_element, inc.to_light), 0.0);
        }
    }
    if (solved) {
        let map = textureSampleLevel(light_map, light_map_sampler, in.lightmap_uv, 0.0);
        // Lambertian: L = B / π. The solution reflects the diffuse map's mean colour; the
        // map's texels vary it about that mean.
        let relative = texture_rgb / max(material.texture_mean.rgb, vec3<f32>(1e-6));
        let kd_texel = material.diffuse.rgb * texture_rgb;
        let base = map.rgb * relative;
        // Where a shadow's edge crosses the element, the map holds less than a lit
        // pixel's direct light: the relief is scaled by the share it holds, so it never
        // takes away more than is there.
        let direct = kd_texel * lit_element;
        let share = select(vec3<f32>(1.0), clamp(base / direct, vec3<f32>(0.0), vec3<f32>(1.0)), direct > vec3<f32>(0.0));
        radiance += max(base + share * kd_texel * (lit_pixel - lit_element), vec3<f32>(0.0)) / PI;
        lux = map.a;
    }
    return vec4<f32>(radiance, lux);
}
