//! GPU access for tests: never skipped silently.

use goniolight::gpu::Gpu;

/// The test binary's one GPU context (`Gpu::shared`: created by the first test that asks,
/// then shared), or `None` only when the user opted out with `GONIOLIGHT_SKIP_GPU_TESTS=1`
/// (said on stderr). Without an adapter the test fails with the reason and how to install
/// the software Vulkan driver.
pub fn gpu() -> Option<Gpu> {
    if std::env::var("GONIOLIGHT_SKIP_GPU_TESTS").as_deref() == Ok("1") {
        eprintln!("GPU test skipped: GONIOLIGHT_SKIP_GPU_TESTS=1");
        return None;
    }
    match Gpu::shared() {
        Ok(g) => {
            eprintln!("GPU: {}", g.describe());
            Some(g)
        }
        Err(e) => {
            panic!("GPU test needs an adapter: {e} (set GONIOLIGHT_SKIP_GPU_TESTS=1 to skip)")
        }
    }
}
