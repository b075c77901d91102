//! The library's CPU parts: photometry files and their interpolation, the fuzzed readers,
//! meshes, ray casts, face clusters and shadow silhouettes.
//!
//! One test binary per area: the crate is linked once for all of them, and the GPU
//! tests share one device (`Gpu::shared`).

#[path = "../common/mod.rs"]
mod common;

mod clusters;
mod daylight;
mod fuzz_parsers;
mod gltf_models;
mod interpolation_props;
mod photometry_details;
mod photometry_files;
mod ray_bvh;
mod real_meshes;
mod roundtrip;
mod sample18;
mod silhouette;
mod tm33_files;
mod wild_corpus;
