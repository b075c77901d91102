//! The GPU stages on whatever Vulkan adapter is there (lavapipe in CI), each against its CPU
//! twin or an analytic reference: the renderer, shadows, radiosity and its drives.
//!
//! One test binary per area: the crate is linked once for all of them, and the GPU
//! tests share one device (`Gpu::shared`).

#[path = "../common/mod.rs"]
mod common;
#[path = "../common/furnace.rs"]
mod furnace_common;
#[path = "../common/gpu.rs"]
mod gpu_common;
#[path = "../common/radiosity_scenes.rs"]
mod radiosity_scenes_common;
#[path = "../common/solve.rs"]
mod solve_common;

mod adaptive;
mod alpha_masks;
mod charts;
mod cie171;
mod gltf_emissive;
mod gpu_ldt;
mod hierarchy;
mod links;
mod preview_indirect;
mod radiosity;
mod radiosity_restart;
mod radiosity_shading;
mod radiosity_view;
mod render;
mod shadows;
mod shooter_groups;
mod specular;
mod transmission;
