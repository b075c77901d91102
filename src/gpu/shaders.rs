//! WGSL sources, compiled into the binary. WGSL has no includes: a pipeline's module is
//! the concatenation of the library files it needs and its entry file.

/// LDT sampling functions (nearest, bilinear, Catmull-Rom, monotone) on a texture array.
pub const LDT: &str = include_str!("../../shaders/ldt.wgsl");
/// Compute entry point that samples one LDT at many directions (tests, checks).
pub const LDT_PROBE: &str = include_str!("../../shaders/ldt_probe.wgsl");

/// The Catmull-Rom tables of LDT layers (needs [`LDT`]).
pub const LDT_TABLE: &str = include_str!("../../shaders/ldt_table.wgsl");
/// Direct light of goniometric luminaires (needs [`LDT`]).
pub const LIGHTING: &str = include_str!("../../shaders/lighting.wgsl");
/// Direct illuminance at many points (needs [`LDT`] and [`LIGHTING`]).
pub const ILLUMINANCE_POINTS: &str = include_str!("../../shaders/illuminance_points.wgsl");
/// Shadow lookups of the shading code: volume mask and paraboloid maps (needs [`LIGHTING`]).
pub const SHADOW: &str = include_str!("../../shaders/shadow.wgsl");
/// Stencil shadow volumes, the shadow mask and their debug views.
pub const SHADOW_VOLUME: &str = include_str!("../../shaders/shadow_volume.wgsl");
/// Dual-paraboloid shadow maps (needs [`CUTOUT`]).
pub const PARABOLOID: &str = include_str!("../../shaders/paraboloid.wgsl");
/// Holes of alpha-masked casters, read from mask bits.
pub const CUTOUT: &str = include_str!("../../shaders/cutout.wgsl");
/// The renderer's depth and shading passes (needs [`LDT`], [`LIGHTING`] and [`SHADOW`]).
pub const SCENE: &str = include_str!("../../shaders/scene.wgsl");
/// The stereographic projection of a visibility map and its inverse.
pub const STEREOGRAPHIC: &str = include_str!("../../shaders/stereographic.wgsl");
/// Progressive radiosity: shooter selection, patches, receivers (needs [`STEREOGRAPHIC`]).
pub const RADIOSITY: &str = include_str!("../../shaders/radiosity.wgsl");
/// A visibility map's face, shared by the hardware and the compute rasterizer (needs
/// [`STEREOGRAPHIC`]).
pub const RADIOSITY_FACE: &str = include_str!("../../shaders/radiosity_face.wgsl");
/// Radiosity visibility maps (hemicube faces, stereographic; needs [`CUTOUT`] and
/// [`RADIOSITY_FACE`]).
pub const RADIOSITY_VISIBILITY: &str = include_str!("../../shaders/radiosity_visibility.wgsl");
/// Visibility maps rasterized by compute shaders (needs [`RADIOSITY_FACE`]).
pub const RADIOSITY_RASTER: &str = include_str!("../../shaders/radiosity_raster.wgsl");
/// Tone mapping, false colour and image statistics.
pub const TONEMAP: &str = include_str!("../../shaders/tonemap.wgsl");

/// The LDT probe module.
pub fn ldt_probe() -> String {
    format!("{LDT}\n{LDT_PROBE}")
}

/// The Catmull-Rom table module.
pub fn ldt_table() -> String {
    format!("{LDT}\n{LDT_TABLE}")
}

/// The illuminance-at-points module.
pub fn illuminance_points() -> String {
    format!("{LDT}\n{LIGHTING}\n{SHADOW}\n{ILLUMINANCE_POINTS}")
}

/// The paraboloid-map module.
pub fn paraboloid() -> String {
    format!("{CUTOUT}\n{PARABOLOID}")
}

/// The radiosity module (shooting and receiving).
pub fn radiosity() -> String {
    format!("{STEREOGRAPHIC}\n{RADIOSITY}")
}

/// The radiosity visibility-map module.
pub fn radiosity_visibility() -> String {
    format!("{CUTOUT}\n{STEREOGRAPHIC}\n{RADIOSITY_FACE}\n{RADIOSITY_VISIBILITY}")
}

/// The compute rasterizer's module.
pub fn radiosity_raster() -> String {
    format!("{STEREOGRAPHIC}\n{RADIOSITY_FACE}\n{RADIOSITY_RASTER}")
}

/// The scene (depth + shading) module.
pub fn scene() -> String {
    format!("{LDT}\n{LIGHTING}\n{SHADOW}\n{SCENE}")
}

/// Every shader module as (name, full source), for validation.
pub fn modules() -> Vec<(&'static str, String)> {
    vec![
        ("ldt_probe", ldt_probe()),
        ("ldt_table", ldt_table()),
        ("illuminance_points", illuminance_points()),
        ("scene", scene()),
        ("tonemap", TONEMAP.to_string()),
        ("shadow_volume", SHADOW_VOLUME.to_string()),
        ("paraboloid", paraboloid()),
        ("radiosity", radiosity()),
        ("radiosity_visibility", radiosity_visibility()),
        ("radiosity_raster", radiosity_raster()),
    ]
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_shader_parses_and_validates_with_naga() {
        for (name, source) in super::modules() {
            let module = naga::front::wgsl::parse_str(&source)
                .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&source)));
            naga::valid::Validator::new(
                naga::valid::ValidationFlags::all(),
                naga::valid::Capabilities::all(),
            )
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        }
    }
}
