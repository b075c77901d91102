//! Sun and shadow studies of a building on top of the renderer's shadow volumes: sun-path
//! shadow profiles over a period, hours of sun or shadow per plan cell with thresholds and
//! analysis areas, their framed plans, rasters, outlines and tables, and sun-path diagrams.

pub mod annotate;
pub mod colours;
pub mod mask;
pub mod model;
pub mod outlines;
pub mod output;
pub mod rasters;
pub mod shadow_profile;
pub mod study_files;
pub mod sun_study;
pub mod sunpath;
pub mod surface_output;
pub mod surface_set;
pub mod surfaces;
pub mod view_hours;

pub use shadow_profile::{compute, HoursMetric, Profile, ProfileError, ProfileSpec};
pub use sun_study::{StudyDay, SunStudy, SunStudyOptions};
