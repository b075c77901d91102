//! glTF models on the command line wherever an OBJ goes: `silhouette` and `profile` give
//! the same output for an OBJ and the same triangles written as glTF (Y-up, as glTF is).

use std::path::{Path, PathBuf};

use base64::Engine as _;
use serde_json::json;

use crate::common::{self, root, run_cli};

/// `obj`'s triangles as a `.gltf` (one buffer as a data URI) in `dir`, its vertices in the
/// file's order; `z_up`: the OBJ is +Z up, so its positions are turned to glTF's +Y up.
fn gltf_of(obj: &Path, dir: &Path, z_up: bool) -> PathBuf {
    let mesh = goniolight::geometry::obj::read_obj(obj).unwrap();
    let mut bytes = Vec::new();
    let positions: Vec<[f32; 3]> = mesh
        .positions
        .iter()
        .map(|p| {
            let p = if z_up {
                glam::DVec3::new(p.x, p.z, -p.y)
            } else {
                *p
            };
            p.as_vec3().to_array()
        })
        .collect();
    for v in positions.iter().flatten() {
        bytes.extend(v.to_le_bytes());
    }
    let offset = bytes.len();
    for i in mesh.triangles.iter().flatten() {
        bytes.extend(i.to_le_bytes());
    }
    let lo = [0, 1, 2].map(|k| positions.iter().map(|p| p[k]).fold(f32::MAX, f32::min));
    let hi = [0, 1, 2].map(|k| positions.iter().map(|p| p[k]).fold(f32::MIN, f32::max));
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "box"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": positions.len(), "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5125, "count": 3 * mesh.triangles.len(), "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": offset},
            {"buffer": 0, "byteOffset": offset, "byteLength": bytes.len() - offset}
        ],
        "buffers": [{"byteLength": bytes.len(), "uri": format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&bytes)
        )}]
    });
    let path = dir.join("model.gltf");
    std::fs::write(&path, doc.to_string()).unwrap();
    path
}

#[test]
fn silhouette_reads_a_gltf_as_the_same_obj() {
    let dir = tempfile::tempdir().unwrap();
    let obj = root().join("assets/models/box.obj");
    let gltf = gltf_of(&obj, dir.path(), false);
    let edges = |model: &Path| {
        let args = [
            "silhouette",
            model.to_str().unwrap(),
            "--light",
            "0.3,-0.2,1,0",
            "--json",
        ];
        let (code, out, err) = run_cli(&args, "");
        assert_eq!(code, 0, "{err}");
        serde_json::from_str::<serde_json::Value>(&out).unwrap()
    };
    let (a, b) = (edges(&obj), edges(&gltf));
    assert!(a["count"].as_u64().unwrap() >= 4, "{a}");
    assert_eq!(a, b);
}

#[test]
fn profile_reads_a_gltf_as_the_same_obj() {
    if crate::gpu_common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let obj = root().join("assets/models/box.obj");
    let gltf = gltf_of(&obj, dir.path(), true);
    let csv = |model: &Path, up: &[&str], name: &str| {
        let out = dir.path().join(name);
        let mut args = common::profile_args(model.to_str().unwrap(), "08:00", "16:00", "120", up);
        args.extend(["--resolution", "96", "--out", out.to_str().unwrap()].map(String::from));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, _, err) = run_cli(&args, "");
        assert_eq!(code, 0, "{err}");
        std::fs::read_to_string(out.join("profile.csv")).unwrap()
    };
    let from_obj = csv(&obj, &["--up", "z"], "obj");
    let from_gltf = csv(&gltf, &[], "gltf");
    assert!(from_obj.lines().count() > 2, "{from_obj}");
    assert_eq!(from_obj, from_gltf);
}
