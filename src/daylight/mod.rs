//! Daylight: the CIE sky models (ISO 15469), the sun as a disc, the ground, clear glazing,
//! and the daylight that reaches points through a model's openings. Directions are in the
//! scene's frame (+X east, +Y north once the site's north offset is applied, +Z up).

pub mod cie_sky;
pub mod glazing;
pub mod points;
pub mod sky;

pub use cie_sky::SkyDistribution;
pub use glazing::Glazing;
pub use points::{daylight_at_points, DaylightAtPoint, Obstructions};
pub use sky::{Sky, SkyInput, Sun, SunIlluminance};
