//! goniolight: real luminaires (EULUMDAT/IES) in real-time rendering, radiosity and
//! sun-path shadow studies.
//!
//! The library holds all logic; the `goniolight` binary's commands only call it.
//! See `DESIGN.md` in the repository's shared notes and the README for the data flow.

#![warn(missing_docs)]

pub mod cli;
pub mod geometry;
pub mod gpu;
pub mod io;
pub mod photometry;
pub mod radiosity;
pub mod render;
pub mod scene;
pub mod shadow;
pub mod sun;
pub mod viewer;
