//! goniolight: real luminaires (EULUMDAT/IES) in real-time rendering, radiosity and
//! sun-path shadow studies.
//!
//! The library holds all logic; the `goniolight` binary's commands only call it.
//! See `DESIGN.md` in the repository's shared notes and ARCHITECTURE.md and the book under `docs/` for the data flow.
//!
//! Features: without any, the CPU parts (photometry, sun, geometry, silhouettes, scene
//! files, the CPU lighting twin); `gpu` adds the renderer, radiosity, the shadow studies and
//! the benchmarks; `cli` the command line; `viewer` the interactive viewer (default: `cli`
//! and `viewer`).
//!
//! A luminaire file, its interpolated distribution and flux, and the sun (no GPU needed):
//!
//! ```
//! use std::path::Path;
//! use goniolight::photometry::{Interp, Luminaire};
//! use goniolight::sun::{parse_time, position, Site, SunOptions, Zone};
//!
//! let lum = Luminaire::load(Path::new("luminaires/eulumdat-analysis/sample_18.ldt"))?;
//! let at_30 = lum.distribution.sample(0.0, 30.0, Interp::CatmullRom); // cd/klm
//! assert!(at_30 > 0.0);
//! assert!((lum.summary().flux_lm - 2445.4).abs() < 1.0); // lm, as the file declares
//!
//! let vienna = Site::new(48.21, 16.37, 0.0)?;
//! let zone = Zone::parse("Europe/Vienna")?;
//! let (utc, _) = parse_time("2026-06-21T12:00", Some(&zone))?;
//! let sun = position(&vienna, utc, &SunOptions::default())?;
//! assert!(sun.elevation_deg > 55.0 && sun.elevation_deg < 66.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

#[cfg(feature = "gpu")]
pub mod bench;
pub mod calc;
#[cfg(feature = "cli")]
pub mod cli;
pub mod daylight;
pub mod geometry;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod io;
pub mod lighting;
pub mod photometry;
pub mod planning;
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
pub mod weather;
