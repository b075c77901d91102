//! The viewer: its panels (egui_kittest) and a real window under Xvfb.
//!
//! One test binary per area: the crate is linked once for all of them, and the GPU
//! tests share one device (`Gpu::shared`).

#[path = "../common/mod.rs"]
mod common;
#[path = "../common/gpu.rs"]
mod gpu_common;

mod viewer_ui;
mod viewer_window;
