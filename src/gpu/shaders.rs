//! WGSL sources, compiled into the binary. WGSL has no includes: a pipeline's module is
//! the concatenation of the library files it needs and its entry file.

/// LDT sampling functions (nearest, bilinear, Catmull-Rom, monotone) on a texture array.
pub const LDT: &str = include_str!("../../shaders/ldt.wgsl");
/// Compute entry point that samples one LDT at many directions (tests, checks).
pub const LDT_PROBE: &str = include_str!("../../shaders/ldt_probe.wgsl");

/// Every shader module as (name, full source), for validation.
pub fn modules() -> Vec<(&'static str, String)> {
    vec![("ldt_probe", format!("{LDT}\n{LDT_PROBE}"))]
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
