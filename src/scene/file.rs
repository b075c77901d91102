//! The scene file format (TOML), as read by serde. Every table rejects unknown keys so a
//! typo is an error that names the key, not a silently ignored setting.
//!
//! ```toml
//! [[model]]
//! path = "models/room.obj"      # OBJ with its MTL, relative to this file
//! up = "z"                      # "y" (default, most OBJ exporters) or "z"
//! translation = [0.0, 0.0, 0.0] # optional transform: scale, then rotation, then translation
//! rotation_deg = [0.0, 0.0, 90.0]
//! scale = 1.0
//! bake = "map"                  # optional: radiosity export bakes every surface into the
//!                               # light map ("map") or vertex colours ("vertex")
//! bake_materials = { chrome = "vertex" } # optional, per MTL material, over `bake`
//!
//! [[luminaire]]
//! file = "../luminaires/eulumdat-plot/sample_06_isym1.ldt"
//! position = [2.0, 1.5, 2.95]   # metres, world frame (+Z up)
//! aim = [0.0, 0.0, -1.0]        # optional: direction of γ = 0 (or aim_at = a point)
//! roll = 0.0                    # degrees about the aim direction
//! rotation_deg = [0.0, 0.0, 0.0]# optional: then rotate about world X, Y, Z
//! multiplier = 1.0              # dimming
//! color = [1.0, 0.9, 0.8]       # optional tint (normalised to luminance 1)
//!
//! [camera]
//! position = [0.5, 0.5, 1.6]
//! look_at = [3.0, 2.0, 1.0]
//! fov_deg = 60.0                # or orthographic_height = 6.0
//!
//! [[grid]]                      # a calculation surface: see [`super::grid`]
//! name = "work plane"
//! corner = [0.0, 0.0]
//! size = [6.0, 4.0]
//! height = 0.8
//!
//! [[material]]                  # overrides an MTL material: see [`super::materials`]
//! name = "opal"
//! diffuse_transmittance = 0.3
//!
//! [[area]]                      # EN 12464-1 task area with requirements: see [`super::area`]
//! name = "desk"
//! corner = [1.0, 1.0]
//! size = [1.6, 0.8]
//! height = 0.75
//! em = 500
//! u0 = 0.6
//!
//! [[emergency]]                 # EN 1838 escape route etc.: see [`super::emergency`]
//! name = "corridor"
//! kind = "route"
//! line = [[0.5, 1.0], [5.5, 1.0]]
//! width = 1.0
//!
//! [[observer]]                  # glare (UGR) at an eye: see [`super::observer`]
//! name = "desk"
//! position = [1.5, 2.0, 1.2]
//! direction = [1.0, 0.0, 0.0]
//!
//! [display]
//! mode = "shaded"               # or "illuminance"
//! tonemap = "reinhard"          # or "exposure"
//! interp = "catmull-rom"        # nearest | bilinear | catmull-rom | monotone
//! width = 1280
//! height = 720
//! ```

use serde::{Deserialize, Serialize};

/// Largest image side the renderer accepts (wgpu's guaranteed 2D texture size), for scene
/// files and image flags alike.
pub const MAX_IMAGE_SIZE: u32 = 8192;

/// The JSON Schema (draft 7) of the scene file, generated from these types: every table,
/// key, type, allowed value and default, with the doc comments as descriptions. Editors
/// that read TOML through a schema (Taplo, Even Better TOML) complete and check a scene
/// file that starts with a `#:schema PATH` line naming it; the book's scene-file
/// reference is made from it.
pub fn json_schema() -> serde_json::Value {
    let mut schema = schemars::generate::SchemaSettings::draft07()
        .for_deserialize()
        .into_generator()
        .into_root_schema_for::<SceneFile>()
        .to_value();
    schema["title"] = "goniolight scene file".into();
    schema
}

/// The whole file.
#[derive(Debug, Clone, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Geometry.
    #[serde(default)]
    pub model: Vec<ModelEntry>,
    /// Light sources.
    #[serde(default)]
    pub luminaire: Vec<LuminaireEntry>,
    /// The view; without it, commands that make an image frame the scene from above
    /// ([`super::Camera::framing`]), and the others need none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraEntry>,
    /// Display settings.
    #[serde(default)]
    pub display: DisplayEntry,
    /// Calculation surfaces (virtual: they neither block nor reflect light).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub grid: Vec<super::grid::GridEntry>,
    /// EN 1838 emergency lighting: escape routes, open areas, high-risk task areas and
    /// safety equipment, judged by `goniolight calc --emergency`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub emergency: Vec<super::emergency::EmergencyEntry>,
    /// EN 12464-1 areas with their requirements (task areas with their surrounding and
    /// background), judged by `goniolight calc`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub area: Vec<super::area::AreaEntry>,
    /// Settings of `goniolight calc`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub calc: Option<super::grid::CalcSettings>,
    /// Observers rated for glare (UGR) by `goniolight calc`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub observer: Vec<super::observer::ObserverEntry>,
    /// Overrides of the models' MTL materials, by name ([`super::materials`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub material: Vec<MaterialEntry>,
    /// Where the building is: for the sun's position (`[sky] time`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub site: Option<super::daylight::SiteEntry>,
    /// The sky and sun lighting the scene through its openings ([`crate::daylight`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sky: Option<super::daylight::SkyEntry>,
    /// `[[window]]`: window reference points of the planning tests.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub window: Vec<super::planning::WindowEntry>,
    /// `[[open_space]]`: gardens and open spaces of the planning tests.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub open_space: Vec<super::planning::OpenSpaceEntry>,
}

/// A colour as the scene file writes it: one number (grey) or linear RGB.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum Rgb {
    /// The same value in every channel.
    Grey(f64),
    /// Red, green, blue.
    Colour([f64; 3]),
}

impl Rgb {
    /// The colour as linear RGB.
    pub fn vec3(self) -> glam::Vec3 {
        match self {
            Rgb::Grey(v) => glam::Vec3::splat(v as f32),
            Rgb::Colour(c) => glam::Vec3::from_array(c.map(|v| v as f32)),
        }
    }
}

/// `[[material]]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialEntry {
    /// The MTL material name it overrides.
    pub name: String,
    /// The diffuse reflectance radiosity uses (`Kd` is set so that `Kd` × the diffuse
    /// texture's mean colour equals it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffuse_reflectance: Option<Rgb>,
    /// The share of the light arriving on one side that the other side emits diffusely.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffuse_transmittance: Option<Rgb>,
    /// Specular reflectance: a mirror (on the side its surface faces; both sides of
    /// clear glass).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub specular_reflectance: Option<Rgb>,
    /// Specular transmittance: clear glass (light passes undeviated).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub specular_transmittance: Option<Rgb>,
}

/// The up axis of an OBJ file.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default, schemars::JsonSchema,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum UpAxis {
    /// +Y up (converted to the world's +Z up).
    #[default]
    Y,
    /// +Z up (as the world).
    Z,
}

/// A scale: one factor or one per axis.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum Scale {
    /// The same factor on every axis.
    Uniform(f64),
    /// Per axis.
    PerAxis([f64; 3]),
}

/// `[[model]]`.
#[derive(Debug, Clone, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ModelEntry {
    /// OBJ or glTF (`.gltf`, `.glb`) file, relative to the scene file.
    pub path: String,
    /// The file's up axis (glTF files are +Y up).
    #[serde(default)]
    pub up: UpAxis,
    /// Translation in metres (applied last).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub translation: Option<[f64; 3]>,
    /// Rotation about world X, then Y, then Z, degrees.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub rotation_deg: Option<[f64; 3]>,
    /// Scale (applied first).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scale: Option<Scale>,
    /// How `radiosity --export` bakes this model's surfaces (default: chosen per surface).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bake: Option<Bake>,
    /// Per MTL material name, how its surfaces are baked (over `bake`).
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub bake_materials: std::collections::BTreeMap<String, Bake>,
    /// glTF models: whether the file's lights (`KHR_lights_punctual` point and spot,
    /// `EXT_lights_ies`) become luminaires (default true).
    #[serde(default = "yes", skip_serializing_if = "is_true")]
    pub import_lights: bool,
    /// glTF models: per light node name, a luminaire file (`.ldt`, `.ies`, TM-33 `.xml` or
    /// ATLA `.json`; relative to the scene file) placed and aimed by that node instead of
    /// the file's light.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub light_files: std::collections::BTreeMap<String, String>,
}

fn yes() -> bool {
    true
}

fn is_true(b: &bool) -> bool {
    *b
}

/// How a solved surface carries its light in the exported scene (Edström §5.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Bake {
    /// A light-map texture over the surface's input triangles.
    Map,
    /// Colours at the corners of its triangles, split where the light map is finer.
    Vertex,
}

/// `[[luminaire]]`.
#[derive(Debug, Clone, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LuminaireEntry {
    /// `.ldt`, `.ies`, TM-33-23 / ATLA S001 `.xml` or `.json` file, relative to the scene
    /// file.
    pub file: String,
    /// Photometric centre in metres.
    #[serde(deserialize_with = "crate::io::exact::array")]
    pub position: [f64; 3],
    /// Direction of γ = 0.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub aim: Option<[f64; 3]>,
    /// A point γ = 0 points at (instead of `aim`).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub aim_at: Option<[f64; 3]>,
    /// Rotation about the aim direction, degrees.
    #[serde(default)]
    pub roll: f64,
    /// Rotation about world X, then Y, then Z (degrees), after aiming.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub rotation_deg: Option<[f64; 3]>,
    /// Dimming factor on the declared flux.
    #[serde(default = "one")]
    pub multiplier: f64,
    /// Light colour (linear RGB), normalised to luminance 1 so lux stay photometric.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub color: Option<[f64; 3]>,
    /// A display name (defaults to the file name).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The model object that is this luminaire's own body (OBJ `o` name): it never
    /// shadows this luminaire's light (the measured distribution already contains it),
    /// but it shadows every other luminaire. Of several objects with that name, those
    /// within [`HOUSING_REACH_M`] of the photometric centre.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub housing: Option<String>,
    /// Effect lights: turning about the luminaire's own up axis (local +Z, away from
    /// γ = 0), degrees per second (positive: counter-clockwise seen from above its top).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spin_deg_per_s: Option<f64>,
    /// Effect lights: one colour per equal C sector, in the luminaire's own frame (the
    /// first from C0 counter-clockwise toward C90), each normalised to luminance 1; they
    /// turn with the luminaire. Replaces `color`.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option_vec"
    )]
    pub sector_colors: Option<Vec<[f64; 3]>>,
    /// Emergency lighting (`calc --emergency`): the luminaire's rated emergency output,
    /// lm. Luminaires without it (or `ballast_lumen_factor`) are dark in emergency mode.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emergency_flux_lm: Option<f64>,
    /// Emergency lighting: the emergency output as a fraction of the declared flux (the
    /// ballast lumen factor), in (0, 1].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ballast_lumen_factor: Option<f64>,
}

/// Most C sectors an effect light may colour.
pub const MAX_SECTORS: usize = 360;

/// How far (metres) a housing object's bounding box may be from its luminaire's
/// photometric centre.
pub const HOUSING_REACH_M: f64 = 0.05;

fn one() -> f64 {
    1.0
}

/// Writes an interpolation by the name the file format reads (`catmull-rom`).
fn interp_name<S: serde::Serializer>(
    interp: &Option<crate::photometry::Interp>,
    s: S,
) -> Result<S::Ok, S::Error> {
    match interp {
        Some(i) => s.serialize_str(i.name()),
        None => s.serialize_none(),
    }
}

/// `[camera]`.
#[derive(Debug, Clone, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CameraEntry {
    /// Eye position, metres.
    #[serde(deserialize_with = "crate::io::exact::array")]
    pub position: [f64; 3],
    /// The point looked at.
    #[serde(deserialize_with = "crate::io::exact::array")]
    pub look_at: [f64; 3],
    /// Up direction (default +Z).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub up: Option<[f64; 3]>,
    /// Vertical field of view of a perspective camera, degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fov_deg: Option<f64>,
    /// Height of the view of an orthographic camera, metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orthographic_height: Option<f64>,
    /// Near plane distance, metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub near: Option<f64>,
}

/// The output mode.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default, schemars::JsonSchema,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// Shaded image (luminance, tone mapped).
    #[default]
    Shaded,
    /// False-colour direct illuminance in lux with a legend.
    Illuminance,
}

/// The tone-mapping operator.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default, schemars::JsonSchema,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Tonemap {
    /// y = 1 − exp(−k·x).
    Exposure,
    /// Reinhard's global operator with an automatic key.
    #[default]
    Reinhard,
}

/// `[display]`.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DisplayEntry {
    /// Shaded or false-colour illuminance.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mode: Option<Mode>,
    /// Tone mapping.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tonemap: Option<Tonemap>,
    /// k of the exposure operator, 1/(cd/m²) (default: automatic).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exposure: Option<f64>,
    /// LDT interpolation: nearest, bilinear, catmull-rom, monotone.
    #[serde(
        skip_serializing_if = "Option::is_none",
        serialize_with = "interp_name"
    )]
    pub interp: Option<crate::photometry::Interp>,
    /// Image width, pixels.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width: Option<u32>,
    /// Image height, pixels.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height: Option<u32>,
    /// Top of the false-colour scale, lux (default: from the image).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lux_max: Option<f64>,
    /// False-colour palette (`rainbow`, `viridis`, `cividis`, `inferno`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub palette: Option<super::Palette>,
    /// Hard colour bands on the false-colour scale (DIALux style); continuous when absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<u32>,
    /// Colour of pixels that show no surface (linear RGB in cd/m²).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub background: Option<[f64; 3]>,
    /// Shadows: "none", "paraboloid" (default) or "volumes".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shadows: Option<crate::shadow::ShadowTechnique>,
    /// The light shown besides the luminaires' direct light: "none", "ambient" or
    /// "radiosity" (`render --indirect`; default: none for `render`, radiosity for
    /// `demo`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub indirect: Option<DisplayIndirect>,
}

/// What an image shows of the light that surfaces send each other.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default, schemars::JsonSchema,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum DisplayIndirect {
    /// The luminaires' direct light only (exact per pixel).
    #[default]
    None,
    /// Plus an ambient term (Cohen et al. 1988): the luminaires' first bounce spread
    /// evenly over the scene as 1 / (1 − ρ̄) times its mean — an estimate, shown at the
    /// light map's resolution.
    Ambient,
    /// Plus the interreflected light of a radiosity solution run for the command's time
    /// budget (with the ambient term for what is not shot yet), at the light map's
    /// resolution.
    Radiosity,
}

impl DisplayIndirect {
    /// What the image's lux are, in a word or two (a legend's title).
    pub fn legend_word(self) -> &'static str {
        match self {
            DisplayIndirect::None => "direct",
            DisplayIndirect::Ambient => "+ ambient",
            DisplayIndirect::Radiosity => "total",
        }
    }

    /// What the image's light is, for reports.
    pub fn describe(self) -> &'static str {
        match self {
            DisplayIndirect::None => "direct",
            DisplayIndirect::Ambient => "direct + ambient estimate",
            DisplayIndirect::Radiosity => "total",
        }
    }
}
