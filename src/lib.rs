//! goniolight: real luminaires (EULUMDAT/IES) in real-time rendering, radiosity and
//! sun-path shadow studies.
//!
//! The library holds all logic; the `goniolight` binary's commands only call it.
//! See `DESIGN.md` in the repository's shared notes and the README for the data flow.
//!
//! Features: without any, the CPU parts (photometry, sun, geometry, silhouettes, scene
//! files, the CPU lighting twin); `gpu` adds the renderer, radiosity, the shadow studies and
//! the benchmarks; `cli` the command line; `viewer` the interactive viewer (default: `cli`
//! and `viewer`).

#![warn(missing_docs)]

#[cfg(feature = "gpu")]
pub mod bench;
#[cfg(feature = "cli")]
pub mod cli;
pub mod geometry;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod io;
pub mod lighting;
pub mod photometry;
#[cfg(feature = "gpu")]
pub mod radiosity;
#[cfg(feature = "gpu")]
pub mod render;
pub mod scene;
pub mod shadow;
#[cfg(feature = "gpu")]
pub mod study;
pub mod sun;
#[cfg(feature = "viewer")]
pub mod viewer;
