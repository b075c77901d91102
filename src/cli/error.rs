//! The commands' error: what went wrong and whose fault it was (exit 2 for bad input, 1
//! for anything else), with a conversion from each library error.

use crate::geometry::GeometryError;
use crate::gpu::GpuError;
use crate::photometry::PhotometryError;
use crate::scene::SceneError;
use crate::study::shadow_profile::ProfileError;
use crate::sun::SunError;
#[cfg(feature = "viewer")]
use crate::viewer::ViewerError;

/// A failed command: the error and whether it was the input's fault (exit 2) or not (1).
#[derive(Debug)]
pub struct CliError {
    /// What went wrong, with context.
    pub error: anyhow::Error,
    /// True for bad input or usage.
    pub bad_input: bool,
}

impl CliError {
    /// The message with its causes, each cause left out where the message before it
    /// already ends with it (errors that print their source themselves).
    pub fn message(&self) -> String {
        let mut out = self.error.to_string();
        for cause in self.error.chain().skip(1) {
            let text = cause.to_string();
            if !out.ends_with(&text) {
                out.push_str(": ");
                out.push_str(&text);
            }
        }
        out
    }

    /// An error caused by the user's input (exit code 2).
    pub fn input(error: impl Into<anyhow::Error>) -> CliError {
        CliError {
            error: error.into(),
            bad_input: true,
        }
    }

    /// Any other failure (exit code 1).
    pub fn failure(error: impl Into<anyhow::Error>) -> CliError {
        CliError {
            error: error.into(),
            bad_input: false,
        }
    }

    /// Bad input (exit 2) or another failure (exit 1), as the library error says.
    pub fn classified(error: impl Into<anyhow::Error>, bad_input: bool) -> CliError {
        CliError {
            error: error.into(),
            bad_input,
        }
    }

    /// The process exit code.
    pub fn code(&self) -> u8 {
        if self.bad_input {
            2
        } else {
            1
        }
    }
}

/// The library's field names (the sun study's options, the site and time, the photometry
/// arguments) and the flags that set them.
const FLAGS_OF_FIELDS: &[(&str, &str)] = &[
    ("step_minutes", "--step"),
    ("extent_m", "--extent"),
    ("resolution", "--resolution"),
    ("from", "--from"),
    ("to", "--to"),
    ("latitude", "--lat"),
    ("longitude", "--lon"),
    ("elevation_m", "--elevation"),
    ("delta_t", "--delta-t"),
    ("pressure_hpa/temperature_c", "--pressure/--temperature"),
    ("zone", "--tz"),
    ("time", "--time"),
    ("shr", "--shr"),
    ("lamp_set", "--lamp-set"),
    ("downsample", "--downsample"),
    ("up", "--up"),
    ("casters", "--casters"),
    ("dates", "--dates"),
    ("threshold_h", "--threshold"),
    ("facade_cell_m", "--facade-cell"),
    ("min_facade_area_m2", "--min-facade-area"),
    ("points", "--points"),
    ("north_offset_deg", "--north-offset"),
    ("min_elevation_deg", "--min-elevation"),
    ("view_from", "--view-from"),
    ("view_at", "--view-at"),
    ("shadows", "--shadows"),
    ("texel_density", "--texel-density"),
    ("supersample", "--supersample"),
    ("shadow_map_size", "--shadow-map-size"),
    ("display.width", "--width"),
    ("display.height", "--height"),
    ("display.exposure", "--exposure"),
    ("display.lux_max", "--lux-max"),
    ("display.steps", "--steps"),
    ("indirect", "--indirect"),
    ("cpu", "--cpu"),
    ("drive", "--drive"),
    ("max_points", "--max-points"),
    ("hierarchy", "--hierarchy"),
    ("exact", "--exact"),
    ("map_size", "--map-size"),
];

/// The flag that sets the library's `field` (the field itself where none does).
pub(crate) fn flag_of(field: &str) -> &str {
    FLAGS_OF_FIELDS
        .iter()
        .find(|(f, _)| *f == field)
        .map_or(field, |(_, flag)| flag)
}

/// `text` with every field the library quotes in backquotes (`` `extent_m` ``) named by
/// its flag (`--extent`); other quoted words stay as they are.
pub(crate) fn flags_in(text: &str) -> String {
    let parts: Vec<&str> = text.split('`').collect();
    // An even count of parts: the last backquote is not closed.
    let unclosed = parts.len().is_multiple_of(2);
    let mut out = String::with_capacity(text.len());
    for (k, part) in parts.iter().enumerate() {
        let flag = FLAGS_OF_FIELDS.iter().find(|(f, _)| f == part);
        match (k % 2 == 1, flag) {
            (false, _) => out.push_str(part),
            (true, _) if unclosed && k + 1 == parts.len() => {
                out.push('`');
                out.push_str(part);
            }
            (true, Some((_, flag))) => out.push_str(flag),
            (true, None) => {
                out.push('`');
                out.push_str(part);
                out.push('`');
            }
        }
    }
    out
}

impl From<crate::photometry::polar_diagram::PolarDiagramError> for CliError {
    fn from(e: crate::photometry::polar_diagram::PolarDiagramError) -> CliError {
        use crate::photometry::polar_diagram::PolarDiagramError as E;
        match e {
            E::Downsample(e) => CliError::from(e),
            E::Write(e) => CliError::failure(e),
        }
    }
}

impl From<PhotometryError> for CliError {
    fn from(e: PhotometryError) -> CliError {
        let bad_input = e.is_bad_input();
        CliError::classified(photometry_message(e), bad_input)
    }
}

/// A photometry error as the command says it: an argument named by its flag (the library's
/// `shr` is `--shr`), anything else as the library says it.
pub(crate) fn photometry_message(e: PhotometryError) -> anyhow::Error {
    match e {
        PhotometryError::Field {
            field,
            value,
            problem,
        } => {
            let flag = flag_of(field);
            anyhow::anyhow!("{flag} {value} {problem}")
        }
        e => anyhow::Error::new(e),
    }
}

#[cfg(feature = "viewer")]
impl From<ViewerError> for CliError {
    fn from(e: ViewerError) -> CliError {
        let bad_input = e.is_bad_input();
        CliError::classified(e, bad_input)
    }
}

impl From<GeometryError> for CliError {
    fn from(e: GeometryError) -> CliError {
        match &e {
            GeometryError::Io { source, .. } if !crate::io::is_bad_input(source) => {
                CliError::failure(e)
            }
            _ => CliError::input(e),
        }
    }
}

impl From<crate::io::outputs::OutputError> for CliError {
    fn from(e: crate::io::outputs::OutputError) -> CliError {
        CliError::input(e)
    }
}

impl From<ProfileError> for CliError {
    fn from(e: ProfileError) -> CliError {
        match e {
            // The library names the spec's fields; the command names its flags.
            ProfileError::Invalid { field, message } => {
                let flag = flag_of(field);
                CliError::input(anyhow::anyhow!("{flag} {}", flags_in(&message)))
            }
            ProfileError::Model(e) => e.into(),
            ProfileError::Sun(e) => e.into(),
            ProfileError::Input(_) => CliError::input(e),
            ProfileError::Output(_) | ProfileError::Gpu(_) | ProfileError::Cancelled => {
                CliError::failure(e)
            }
        }
    }
}

impl From<crate::radiosity::session::OptionError> for CliError {
    /// The library names the option's field; the command, its flag (`map_size` is
    /// `--map-size`).
    fn from(e: crate::radiosity::session::OptionError) -> CliError {
        let flag = e.field.replace('_', "-");
        CliError::input(anyhow::anyhow!("--{flag} {} {}", e.value, e.problem))
    }
}

impl From<crate::radiosity::session::SessionError> for CliError {
    fn from(e: crate::radiosity::session::SessionError) -> CliError {
        use crate::radiosity::session::SessionError;
        match e {
            SessionError::Option(o) => o.into(),
            SessionError::Gpu(g) => g.into(),
            e => {
                let bad_input = e.is_bad_input();
                CliError::classified(e, bad_input)
            }
        }
    }
}

impl From<SunError> for CliError {
    /// The library names the site's and the time's fields; the command, its flags
    /// (`latitude` is `--lat`).
    fn from(e: SunError) -> CliError {
        match e {
            SunError::Invalid {
                field,
                value,
                problem,
            } => {
                let flag = flag_of(field);
                let problem = match problem.as_str() {
                    crate::sun::time::NO_OFFSET => {
                        "has no UTC offset: add one (e.g. +02:00) or give --tz".to_string()
                    }
                    _ => problem,
                };
                CliError::input(anyhow::anyhow!("{flag} {value} {problem}"))
            }
            SunError::Model(_) => CliError::input(e),
        }
    }
}

impl From<crate::scene::display::DisplayError> for CliError {
    /// The library names the `[display]` key; the command, its flag (`display.width` is
    /// `--width`).
    fn from(e: crate::scene::display::DisplayError) -> CliError {
        let flag = flag_of(e.field);
        CliError::input(anyhow::anyhow!("{flag} {} {}", e.value, e.problem))
    }
}

impl From<crate::render::scene_frame::SceneFrameError> for CliError {
    fn from(e: crate::render::scene_frame::SceneFrameError) -> CliError {
        use crate::render::scene_frame::SceneFrameError;
        match e {
            SceneFrameError::Gpu(g) => g.into(),
            e => CliError::input(anyhow::anyhow!(flags_in(&e.to_string()))),
        }
    }
}

impl From<SceneError> for CliError {
    fn from(e: SceneError) -> CliError {
        CliError::input(e)
    }
}

impl From<GpuError> for CliError {
    fn from(e: GpuError) -> CliError {
        // A scene too large for the device is the input's doing: exit 2.
        if let GpuError::Limit(message) = &e {
            CliError::input(anyhow::anyhow!(flags_in(message)))
        } else {
            CliError::failure(anyhow::anyhow!(flags_in(&e.to_string())))
        }
    }
}

impl From<crate::render::illuminance::IlluminanceError> for CliError {
    fn from(e: crate::render::illuminance::IlluminanceError) -> CliError {
        match e {
            crate::render::illuminance::IlluminanceError::Gpu(g) => g.into(),
            unusable => CliError::failure(unusable),
        }
    }
}

impl From<crate::lighting::PointsError> for CliError {
    fn from(e: crate::lighting::PointsError) -> CliError {
        CliError::input(e)
    }
}

#[cfg(test)]
mod tests {
    use super::flags_in;

    #[test]
    fn quoted_fields_become_their_flags_and_other_quotes_stay() {
        assert_eq!(
            flags_in("the file is Z-up, pass `up` z; use a larger `extent_m`"),
            "the file is Z-up, pass --up z; use a larger --extent"
        );
        assert_eq!(flags_in("`nothing` is `to`"), "`nothing` is --to");
        assert_eq!(flags_in("no quotes"), "no quotes");
        assert_eq!(flags_in("an odd ` quote"), "an odd ` quote");
    }
}
