// The stereographic projection of a visibility map's hemisphere (Wallner §2.3), in the
// map's frame (x tangent, y bitangent, z normal): the rasterizers (radiosity_face.wgsl,
// radiosity_raster.wgsl, radiosity_visibility.wgsl) and the receive pass (radiosity.wgsl)
// project and unproject with these.

// Map coordinates (the unit disc for the hemisphere) of the unit direction `u`.
fn stereographic_project(u: vec3<f32>) -> vec2<f32> {
    return u.xy / max(1.0 + u.z, 1e-3);
}

// The direction that projects to map coordinates `uv` (length 1 + |uv|²).
fn stereographic_ray(uv: vec2<f32>) -> vec3<f32> {
    return vec3<f32>(2.0 * uv, 1.0 - dot(uv, uv));
}
