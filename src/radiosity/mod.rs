//! Progressive radiosity (Wallner ch. 2 and 4; Cohen et al. 1988; Coombe et al. 2004):
//! light-map elements, form factors, and the CPU reference solver.

pub mod atlas;
pub mod bake;
pub mod cell_receivers;
pub mod clusters;
pub mod coverage;
pub mod cpu;
pub mod elements;
pub mod export;
pub mod form_factor;
pub mod gather;
pub mod gpu;
pub mod initial;
pub mod links;
mod polygon;
pub mod refine;
pub mod scene;
pub mod session;
pub mod shading;
pub mod shadow_edges;
pub mod shooters;
pub mod solve;
/// Mirrors and clear glass ([`crate::lighting::specular`]).
pub use crate::lighting::specular;
pub mod transmission;
pub mod view;

use crate::photometry::Interp;
pub use form_factor::FormFactorKind;

/// How the light map's charts and the shooters are formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Hierarchy {
    /// Every triangle is its own chart and shoots from its own patches (the flat
    /// progressive solver).
    #[default]
    None,
    /// Planar face clusters are the charts (one light-map rectangle, no seams between
    /// their triangles); each connected surface of one material shoots as a whole, its
    /// flat clusters from cells sized by their power.
    Clusters,
}

/// What the ambient term is used for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Ambient {
    /// No ambient term.
    None,
    /// Added for display only (Cohen et al. 1988): early solutions look plausible.
    #[default]
    Display,
    /// Ambient overshooting (Feda and Purgathofer; Wallner Eq. 4.9), and for display.
    Overshoot,
}

/// Solver options shared by the GPU solver and the CPU reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Form factor evaluation.
    pub form_factor: FormFactorKind,
    /// Ambient term use.
    pub ambient: Ambient,
    /// Interpolation of the luminaires' distributions.
    pub interp: Interp,
}

impl Default for SolverSettings {
    fn default() -> SolverSettings {
        SolverSettings {
            form_factor: FormFactorKind::Polygon,
            ambient: Ambient::Display,
            interp: Interp::CatmullRom,
        }
    }
}
