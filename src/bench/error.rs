//! Why a benchmark could not run.

/// Why a benchmark stopped: the errors of the stages it times, or options it cannot run.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// The GPU failed or refused the scene.
    #[error(transparent)]
    Gpu(#[from] crate::gpu::GpuError),
    /// The radiosity session failed.
    #[error(transparent)]
    Session(#[from] crate::radiosity::session::SessionError),
    /// The scene's surfaces could not be cut into radiosity elements.
    #[error(transparent)]
    Elements(#[from] crate::radiosity::elements::ElementError),
    /// A benchmark scene could not be read.
    #[error(transparent)]
    Scene(#[from] crate::scene::SceneError),
    /// A benchmark luminaire could not be read.
    #[error(transparent)]
    Luminaire(#[from] crate::photometry::PhotometryError),
    /// A benchmark mesh has no triangle with area.
    #[error(transparent)]
    Geometry(#[from] crate::geometry::GeometryError),
    /// The options ask for something this benchmark cannot measure.
    #[error("{0}")]
    Refused(String),
    /// The fast method and its reference (brute force) disagree: no time is worth
    /// reporting.
    #[error("{0}: the benchmark stops (a timing of a wrong answer means nothing)")]
    Disagree(String),
}
