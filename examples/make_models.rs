//! Writes the small procedural models bundled in `assets/models/`:
//! `cargo run --example make_models`.

use glam::DVec3;
use goniolight::geometry::generate::{building, bumpy_surface, cuboid, industrial_area, torus};
use goniolight::geometry::obj::to_obj_string;
use goniolight::geometry::Mesh;

fn main() -> anyhow::Result<()> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/models");
    std::fs::create_dir_all(&dir)?;
    let mut flipped = cuboid(DVec3::ZERO, DVec3::ONE);
    // Flip the winding of one face (two triangles): inconsistent edges.
    for t in &mut flipped.triangles[2..4] {
        t.swap(1, 2);
    }
    let fins = Mesh {
        positions: vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(-0.5, 0.8, 0.0),
            DVec3::new(-0.5, -0.8, 0.0),
        ],
        // Three fins sharing the edge 0–1: a non-manifold edge.
        triangles: vec![[0, 2, 1], [0, 3, 1], [0, 1, 4]],
    };
    let models: [(&str, Mesh, &str); 7] = [
        (
            "box.obj",
            cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 3.0)),
            "a 2 x 1 x 3 m box (closed)",
        ),
        (
            "torus.obj",
            torus(48, 24, 2.0, 0.6),
            "a torus, 2304 triangles (closed)",
        ),
        (
            "terrain_patch.obj",
            bumpy_surface(40, 10.0, 7),
            "a bumpy open surface, 3200 triangles (border edges)",
        ),
        (
            "building.obj",
            building(4, 3, 5),
            "a detailed building: slabs, window bands, mullions",
        ),
        (
            "industrial_area.obj",
            industrial_area(),
            "a small industrial area: sawtooth hall, warehouse, offices, lattice tower",
        ),
        (
            "flipped_box.obj",
            flipped,
            "a unit cube with one face wound the wrong way",
        ),
        (
            "fins.obj",
            fins,
            "three fins sharing one edge (non-manifold)",
        ),
    ];
    for (name, mesh, what) in models {
        let text = to_obj_string(
            &mesh,
            &format!("goniolight procedural model: {what}\nz up, metres"),
        );
        std::fs::write(dir.join(name), text)?;
        println!("{name}: {} triangles", mesh.triangles.len());
    }
    Ok(())
}
