//! Lighting calculations a designer hands over: calculation surfaces (`[[grid]]`), the
//! directions each point measures, and the statistics of the values (Em, Emin, U0, g2).

#[cfg(feature = "gpu")]
pub mod compute;
pub mod daylight;
pub mod directions;
pub mod glare;
pub mod plan;
pub mod plan_dxf;
pub mod report;
pub mod requirements;
pub mod stats;

pub use crate::scene::grid::{CalcGrid, CalcSettings, GridEntry, GridKind};
pub use stats::{grid_stats, GridStats};
