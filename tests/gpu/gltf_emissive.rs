//! A glTF's emissive surface is a radiosity source like an OBJ's `Ke`: the shared Cornell
//! box (its ceiling panel `emissiveFactor` 1 × `KHR_materials_emissive_strength` 100, read
//! as 100 cd/m²) lights its floor as the same triangles written as OBJ with `Ke` = π·100
//! lm/m² do.

use std::fmt::Write as _;

use goniolight::geometry::gltf_file;

use crate::common::{run_cli, shared_dir};

/// The glTF's triangles (file frame, nodes applied) as OBJ + MTL with each material's
/// base colour as `Kd` and π × its emissive as `Ke`.
fn obj_twin(model: &gltf_file::GltfModel, dir: &std::path::Path) {
    let (mut obj, mut mtl) = (String::from("mtllib twin.mtl\n"), String::new());
    let mut base = 1;
    for (k, p) in model.primitives.iter().enumerate() {
        let _ = writeln!(obj, "o part{k}\nusemtl m{}", p.material.unwrap());
        for v in &p.positions {
            let _ = writeln!(obj, "v {} {} {}", v.x, v.y, v.z);
        }
        for t in &p.triangles {
            let _ = writeln!(obj, "f {} {} {}", t[0] + base, t[1] + base, t[2] + base);
        }
        base += p.positions.len() as u32;
    }
    for (k, m) in model.materials.iter().enumerate() {
        let [r, g, b, _] = m.base_color;
        let ke = m.emissive.map(|e| e * std::f32::consts::PI);
        let _ = writeln!(
            mtl,
            "newmtl m{k}\nKd {r} {g} {b}\nKe {} {} {}\n",
            ke[0], ke[1], ke[2]
        );
    }
    std::fs::write(dir.join("twin.obj"), obj).unwrap();
    std::fs::write(dir.join("twin.mtl"), mtl).unwrap();
}

#[test]
fn the_cornell_box_glb_emitter_lights_the_floor_as_its_obj_twin() {
    let glb = shared_dir().join("models/gltf/CornellBox/CornellBox.glb");
    let model = gltf_file::read(&glb).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    obj_twin(&model, tmp.path());
    let scene = |path: &str, name: &str| {
        let file = tmp.path().join(name);
        std::fs::write(
            &file,
            format!("[[model]]\npath = {path:?}\nscale = 0.001\n"),
        )
        .unwrap();
        file
    };
    let glb_scene = scene(glb.to_str().unwrap(), "glb.toml");
    let obj_scene = scene("twin.obj", "obj.toml");
    // Floor points (the box spans world x −0.556…0, y 0…0.559 m) that see the whole panel.
    let floor = [(-0.50, 0.05), (-0.05, 0.50), (-0.20, 0.50)];
    let points: String = floor
        .iter()
        .map(|(x, y)| format!("{x} {y} 0.001 0 0 1\n"))
        .collect();
    let lux = |scene: &std::path::Path| -> Vec<f64> {
        let args = [
            "radiosity",
            scene.to_str().unwrap(),
            "--points",
            "--converge",
            "0.95",
        ];
        let (code, out, err) = run_cli(&args, &points);
        assert_eq!(code, 0, "{err}");
        out.lines().map(|l| l.trim().parse().unwrap()).collect()
    };
    let (from_glb, from_obj) = (lux(&glb_scene), lux(&obj_scene));
    assert_eq!(from_glb.len(), 3);
    // The panel (130 × 105 mm, 100 cd/m² facing down at z = 0.5479 m, centred on
    // x −0.278, y 0.2795) as a point source: E = L·A·cos²θ / d², the direct part.
    let (area, height) = (0.130 * 0.105, 0.5479);
    for (((a, b), (x, y)), k) in from_glb.iter().zip(&from_obj).zip(floor).zip(0..) {
        let d2 = (x + 0.278f64).powi(2) + (y - 0.2795f64).powi(2) + height * height;
        let direct = 100.0 * area * height * height / (d2 * d2);
        assert!(
            (0.97 * direct..1.6 * direct).contains(b),
            "point {k}: {b} lx with the interreflections, {direct} lx direct from the panel"
        );
        assert!((a - b).abs() <= 1e-3 * b, "glTF {a} lx, OBJ twin {b} lx");
    }
}
