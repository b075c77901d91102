//! The command line's contract: flags, exit codes, output files and their numbers, the
//! calc, datasheets, sun studies, batch jobs and the fuzz reproducers.
//!
//! One test binary per area: the crate is linked once for all of them, and the GPU
//! tests share one device (`Gpu::shared`).

#[path = "../common/mod.rs"]
mod common;
#[path = "../common/gpu.rs"]
mod gpu_common;
#[path = "../common/svg.rs"]
mod svg_common;

mod areas;
mod batch;
mod calc;
mod catalogue;
mod cli;
mod datasheet_plot;
mod daylight;
mod docs;
mod emergency;
mod faults;
mod fuzz_crashes;
mod gltf_cli;
mod luminance;
mod malformed;
mod outputs_and_limits;
mod profile;
mod radiosity_cli;
mod scene;
mod silhouette_cli;
mod sun;
mod sun_study;
mod sunlight;
mod tm33_cli;
mod ugr;
