//! Diagnostics for the hextree: how many edges live at each depth and how many a query
//! touches. `cargo run --release --example hextree_stats`.

use glam::DVec3;
use goniolight::geometry::generate::torus;
use goniolight::shadow::{Hextree, Light, SilhouetteMesh};

fn main() {
    let mesh = torus(300, 300, 3.0, 1.0);
    let sm = SilhouetteMesh::new(&mesh, "torus", 1e-9).unwrap();
    for depth in [3, 5, 7, 9, 11] {
        let tree = Hextree::build(&sm, depth);
        let light = Light::new([8.0, 3.0, 5.0, 1.0]).unwrap();
        let stats = tree.query_stats(&sm, &light);
        let _ = DVec3::ZERO;
        println!(
            "depth {depth}: nodes {}, per level edges {:?}, visited nodes {}, tested edges {} of {}",
            tree.node_count(),
            tree.edges_per_level(),
            stats.0,
            stats.1,
            sm.manifold.len()
        );
        let t = std::time::Instant::now();
        for _ in 0..100 {
            std::hint::black_box(tree.query(&sm, &light));
        }
        let hq = t.elapsed().as_secs_f64() * 10.0;
        let t = std::time::Instant::now();
        for _ in 0..100 {
            std::hint::black_box(sm.brute(&light));
        }
        let bq = t.elapsed().as_secs_f64() * 10.0;
        println!("   hextree {hq:.3} ms, brute {bq:.3} ms per query");
    }
}
