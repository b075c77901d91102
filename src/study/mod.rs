//! Sun and shadow studies of a building on top of the renderer's shadow volumes: sun-path
//! shadow profiles over a period, hours in shadow per plan cell, and their images and
//! tables.

pub mod output;
pub mod profile;

pub use profile::{compute, Profile, ProfileError, ProfileSpec};
