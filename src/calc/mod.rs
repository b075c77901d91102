//! Lighting calculations a designer hands over: calculation surfaces (`[[grid]]`), the
//! directions each point measures, and the statistics of the values (Em, Emin, U0, g2).

pub mod directions;
pub mod grid;
pub mod plan;
pub mod stats;

pub use grid::{CalcGrid, GridEntry, GridKind};
pub use stats::{grid_stats, GridStats};

/// `[calc]` in the scene file: settings of `goniolight calc`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct CalcSettings {
    /// Maintenance factor: the values reported are the computed ones times it (EN 12464-1's
    /// maintained illuminance). 1 (new installation) when not given.
    #[serde(default = "one")]
    pub maintenance_factor: f64,
}

fn one() -> f64 {
    1.0
}

impl Default for CalcSettings {
    fn default() -> Self {
        CalcSettings {
            maintenance_factor: 1.0,
        }
    }
}

impl CalcSettings {
    /// Refuses a maintenance factor outside (0, 1].
    pub fn check(maintenance_factor: f64) -> Result<f64, String> {
        if maintenance_factor.is_finite() && maintenance_factor > 0.0 && maintenance_factor <= 1.0 {
            Ok(maintenance_factor)
        } else {
            Err(format!(
                "{maintenance_factor}: a maintenance factor is above 0 and at most 1"
            ))
        }
    }
}
