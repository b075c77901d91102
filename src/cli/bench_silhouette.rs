//! `goniolight bench silhouette`: the hextree's silhouette queries against brute force.

use super::error::CliError;
use crate::bench::silhouette as bench;

/// Runs `bench silhouette`.
pub fn run(as_json: bool, queries: usize, depth: u32, scale: f64) -> Result<(), CliError> {
    if queries == 0 || !(scale > 0.0 && scale <= 1.0) {
        return Err(CliError::input(anyhow::anyhow!(
            "--queries must be > 0 and --scale in (0, 1]"
        )));
    }
    let meshes = bench::bench_meshes(scale);
    let rows = bench::run(&meshes, queries, depth, |name| {
        eprintln!("benchmarking {name} …")
    })
    .map_err(CliError::failure)?;
    println!("{}", bench::report(&rows).text(as_json));
    Ok(())
}
