//! The commands' error: what went wrong and whose fault it was (exit 2 for bad input, 1
//! for anything else), with a conversion from each library error.

use crate::geometry::GeometryError;
use crate::gpu::GpuError;
use crate::photometry::PhotometryError;
use crate::scene::SceneError;
use crate::study::profile::ProfileError;
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

/// The library's field names (the sun study's spec, the site and time, the photometry
/// arguments) and the flags that set them.
const FLAGS_OF_FIELDS: [(&str, &str); 14] = [
    ("step_minutes", "--step"),
    ("extent_m", "--extent"),
    ("resolution", "--resolution"),
    ("from", "--from"),
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
];

/// The flag that sets the library's `field` (the field itself where none does).
fn flag_of(field: &str) -> &str {
    FLAGS_OF_FIELDS
        .iter()
        .find(|(f, _)| *f == field)
        .map_or(field, |(_, flag)| flag)
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
                let message = message.replace("`to`", "--to");
                CliError::input(anyhow::anyhow!("{flag} {message}"))
            }
            ProfileError::Input(_) => CliError::input(e),
            ProfileError::Gpu(_) | ProfileError::Cancelled => CliError::failure(e),
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

impl From<SceneError> for CliError {
    fn from(e: SceneError) -> CliError {
        CliError::input(e)
    }
}

impl From<GpuError> for CliError {
    fn from(e: GpuError) -> CliError {
        // A scene too large for the device is the input's doing: exit 2.
        if matches!(e, GpuError::Limit(_)) {
            CliError::input(e)
        } else {
            CliError::failure(e)
        }
    }
}

impl From<crate::lighting::PointsError> for CliError {
    fn from(e: crate::lighting::PointsError) -> CliError {
        CliError::input(e)
    }
}
