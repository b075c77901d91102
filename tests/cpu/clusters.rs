//! The face-cluster hierarchy (Edström §4.2) on a real model nobody here made: the Šibenik
//! cathedral (73 553 triangles with an area, 14 materials, 1 973 slivers), read from the
//! shared test data. Every triangle lies in exactly one leaf, each cluster's triangles are
//! its children's, each root is exactly one connected surface of one material (checked by
//! an independent flood fill over shared corners), and every box holds its triangles.

use crate::common;

use std::collections::HashMap;

use goniolight::radiosity::clusters::{ClusterSettings, FaceClusters};
use goniolight::scene::Scene;

/// Connected surfaces of one material: triangles joined where they share two corners
/// (positions compared bit for bit), by flood fill.
fn surfaces(mesh: &goniolight::geometry::Mesh, materials: &[usize]) -> Vec<Vec<u32>> {
    let key = |i: u32| mesh.positions[i as usize].to_array().map(f64::to_bits);
    let mut by_edge: HashMap<([u64; 3], [u64; 3]), Vec<u32>> = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (key(tri[k]), key(tri[(k + 1) % 3]));
            if a != b {
                by_edge
                    .entry((a.min(b), a.max(b)))
                    .or_default()
                    .push(t as u32);
            }
        }
    }
    let mut next: Vec<Vec<u32>> = vec![Vec::new(); mesh.triangles.len()];
    for faces in by_edge.values() {
        for &f in faces {
            for &g in faces {
                if f != g && materials[f as usize] == materials[g as usize] {
                    next[f as usize].push(g);
                }
            }
        }
    }
    let mut done = vec![false; next.len()];
    let mut out = Vec::new();
    for s in 0..next.len() {
        if done[s] {
            continue;
        }
        done[s] = true;
        let (mut members, mut stack) = (Vec::new(), vec![s as u32]);
        while let Some(t) = stack.pop() {
            members.push(t);
            for &g in &next[t as usize] {
                if !std::mem::replace(&mut done[g as usize], true) {
                    stack.push(g);
                }
            }
        }
        members.sort();
        out.push(members);
    }
    out.sort();
    out
}

#[test]
fn the_cathedral_clusters_into_one_root_per_surface() {
    let obj = common::shared_dir().join("models/sibenik/sibenik.obj");
    let toml = format!(
        "[[model]]\npath = {:?}\nup = \"y\"\n",
        obj.display().to_string()
    );
    let scene = Scene::from_toml(&obj.with_file_name("test.toml"), &toml).unwrap();
    let (mesh, materials) = (scene.caster_mesh(), scene.caster_materials());
    assert_eq!(mesh.triangles.len(), materials.len());
    let h = FaceClusters::build(&mesh, &materials, ClusterSettings::default());
    let n = mesh.triangles.len();
    let mut order = h.order.clone();
    order.sort();
    assert_eq!(
        order,
        (0..n as u32).collect::<Vec<_>>(),
        "each triangle in one leaf"
    );
    assert_eq!(h.nodes.len(), 2 * n - h.roots.len(), "a binary forest");
    for (k, c) in h.nodes.iter().enumerate() {
        if let Some([a, b]) = c.children {
            let joined = [h.triangles(a), h.triangles(b)].concat();
            assert_eq!(h.triangles(k as u32), &joined[..]);
            assert!((c.area - h.nodes[a as usize].area - h.nodes[b as usize].area).abs() < 1e-9);
        }
        let tol = 1e-9 * (1.0 + c.obb.half.length());
        for &t in h.triangles(k as u32) {
            for i in mesh.triangles[t as usize] {
                assert!(
                    c.obb.contains(mesh.positions[i as usize], tol),
                    "cluster {k}"
                );
            }
        }
    }
    let roots = h.root_surfaces();
    let expected = surfaces(&mesh, &materials);
    assert_eq!(roots.len(), expected.len());
    assert!(
        roots == expected,
        "roots are not the connected surfaces of one material"
    );
    // Far fewer big clusters than triangles: the cathedral's surfaces are few.
    assert!(h.roots.len() * 100 < n, "{} roots", h.roots.len());
}

#[test]
fn bench_clusters_without_the_shared_data_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out, err) = common::run_cli(
        &[
            "bench",
            "clusters",
            "--shared",
            &dir.path().display().to_string(),
        ],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty());
    assert!(err.contains("sibenik.obj"), "{err}");
}
