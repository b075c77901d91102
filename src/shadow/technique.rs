//! The renderer's shadow choices as plain values (scene files, the command line and the
//! viewer name them; the GPU passes in `render` implement them).

/// Which shadows the luminaires cast.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Default,
    serde::Deserialize,
    serde::Serialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum ShadowTechnique {
    /// No shadows: every surface facing a luminaire is lit.
    None,
    /// Dual-paraboloid shadow maps with PCF (the default for luminaires: soft-edged,
    /// cost independent of the geometry's complexity).
    #[default]
    Paraboloid,
    /// Stencil shadow volumes: exact hard shadows (the default for the sun).
    Volumes,
}

/// How a light's volume is counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum VolumeTest {
    /// z-fail where the camera's near plane may be inside a volume (the near-clip-volume
    /// test), z-pass elsewhere.
    #[default]
    Auto,
    /// Count volume faces in front of the visible surface (camera outside every volume).
    Zpass,
    /// Count volume faces behind the visible surface (robust, needs the caps).
    Zfail,
}
