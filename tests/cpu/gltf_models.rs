//! glTF models: the shared real files read with the triangle counts their sources state,
//! lights placed as luminaires against closed forms and against the same IES file as a
//! `[[luminaire]]`, and broken files refused with the element at fault.

use std::path::{Path, PathBuf};

use base64::Engine as _;
use glam::DVec3;
use goniolight::geometry::gltf_file::{self, spot_falloff};
use goniolight::photometry::{Interp, Luminaire};
use goniolight::scene::Scene;
use serde_json::{json, Value};

use crate::common;

/// A glTF document with one buffer (a data URI) holding `positions` (f32 xyz) and then
/// `indices` (u32), one mesh of them on node 0, and `more_nodes` after it.
pub(crate) fn document(
    positions: &[[f32; 3]],
    indices: &[u32],
    more_nodes: Value,
    extensions: Value,
) -> Value {
    let mut bytes = Vec::new();
    for p in positions.iter().flatten() {
        bytes.extend(p.to_le_bytes());
    }
    let index_offset = bytes.len();
    for i in indices {
        bytes.extend(i.to_le_bytes());
    }
    let (lo, hi) = positions
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                [0, 1, 2].map(|k| lo[k].min(p[k])),
                [0, 1, 2].map(|k| hi[k].max(p[k])),
            )
        });
    let mut nodes = vec![json!({"mesh": 0, "name": "floor"})];
    nodes.extend(more_nodes.as_array().cloned().unwrap_or_default());
    let node_list: Vec<usize> = (0..nodes.len()).collect();
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": node_list}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": positions.len(), "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5125, "count": indices.len(), "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": index_offset},
            {"buffer": 0, "byteOffset": index_offset, "byteLength": bytes.len() - index_offset}
        ],
        "buffers": [{
            "byteLength": bytes.len(),
            "uri": format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(&bytes))
        }],
        "extensionsUsed": extensions.as_object().map(|o| o.keys().cloned().collect::<Vec<_>>()).unwrap_or_default(),
        "extensions": extensions,
    })
}

/// A 10 × 10 m floor at glTF y = 0 (the world's z = 0), facing up.
pub(crate) const FLOOR: [[f32; 3]; 4] = [
    [-5.0, 0.0, 5.0],
    [5.0, 0.0, 5.0],
    [5.0, 0.0, -5.0],
    [-5.0, 0.0, -5.0],
];
pub(crate) const FLOOR_TRIANGLES: [u32; 6] = [0, 1, 2, 0, 2, 3];
/// −90° about glTF X: the node's −Z (where lights point) turned to glTF −Y, down.
const POINTING_DOWN: [f64; 4] = [
    -std::f64::consts::FRAC_1_SQRT_2,
    0.0,
    0.0,
    std::f64::consts::FRAC_1_SQRT_2,
];

fn scene_with(dir: &Path, file: &str, doc: &Value, model_extra: &str) -> Result<Scene, String> {
    std::fs::write(dir.join(file), serde_json::to_vec_pretty(doc).unwrap()).unwrap();
    let text = format!("[[model]]\npath = \"{file}\"\n{model_extra}");
    Scene::from_toml(&dir.join("scene.toml"), &text).map_err(|e| e.to_string())
}

#[test]
fn the_shared_models_read_with_the_triangle_counts_of_their_sources() {
    // SOURCES.md: triangles counted from the glTF JSON, instanced through the default scene.
    let dir = common::shared_dir().join("models/gltf");
    for (file, triangles) in [
        ("CornellBox/CornellBox.glb", 36),
        ("LightsPunctualLamp/LightsPunctualLamp.gltf", 6_000),
        ("TransmissionTest/TransmissionTest.glb", 128_775),
        ("GlassVaseFlowers/GlassVaseFlowers.glb", 14_036),
    ] {
        let model = gltf_file::read(&dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        let count: usize = model.primitives.iter().map(|p| p.triangles.len()).sum();
        assert_eq!(count, triangles, "{file}");
    }
    let lamp = gltf_file::read(&dir.join("LightsPunctualLamp/LightsPunctualLamp.gltf")).unwrap();
    let cd: Vec<f64> = lamp
        .lights
        .iter()
        .map(|l| match l.kind {
            gltf_file::LightKind::Point { candela } => candela,
            ref k => panic!("{k:?}"),
        })
        .collect();
    assert_eq!(cd, [15.0, 1.5, 80.0, 80.0, 180.0]);
}

#[test]
fn the_lamp_scene_places_its_five_point_lights_with_their_intensities() {
    let dir = common::shared_dir().join("models/gltf/LightsPunctualLamp");
    let text = "[[model]]\npath = \"LightsPunctualLamp.gltf\"\n";
    let scene = Scene::from_toml(&dir.join("lamp.toml"), text).unwrap();
    assert_eq!(scene.luminaires.len(), 5);
    // Point.004: 180 cd at glTF (0.292, 1.032, 1.559) → world (0.292, −1.559, 1.032).
    let l = scene
        .luminaires
        .iter()
        .find(|l| l.name == "Point.004_Orientation")
        .unwrap();
    assert!(
        (l.position - DVec3::new(0.2920210361480713, -1.5589159727096558, 1.0323998928070068))
            .length()
            < 1e-6
    );
    for dir in [
        DVec3::X,
        DVec3::NEG_Z,
        DVec3::new(0.3, -0.4, 0.5).normalize(),
    ] {
        let cd = l.intensity_toward(dir, Interp::Bilinear);
        assert!((cd - 180.0).abs() < 1e-6 * 180.0, "{cd}");
    }
    assert!((l.color.dot(DVec3::new(0.2126, 0.7152, 0.0722)) - 1.0).abs() < 1e-9);
    // The scene saved keeps the lights with the model, not as [[luminaire]] tables.
    assert!(scene.to_file(&dir.join("saved.toml")).luminaire.is_empty());
}

#[test]
fn a_khr_spot_gives_the_closed_form_illuminance_on_the_floor() {
    let tmp = tempfile::tempdir().unwrap();
    let (inner, outer) = (15f64.to_radians(), 30f64.to_radians());
    let lights = json!({"KHR_lights_punctual": {"lights": [{
        "type": "spot", "intensity": 500.0, "color": [1.0, 0.8, 0.6],
        "spot": {"innerConeAngle": inner, "outerConeAngle": outer}
    }]}});
    let spot = json!([{"name": "spot", "translation": [0.0, 2.0, 0.0], "rotation": POINTING_DOWN,
                      "extensions": {"KHR_lights_punctual": {"light": 0}}}]);
    let doc = document(&FLOOR, &FLOOR_TRIANGLES, spot, lights);
    let scene = scene_with(tmp.path(), "spot.gltf", &doc, "").unwrap();
    assert_eq!(scene.luminaires.len(), 1);
    let l = &scene.luminaires[0];
    assert!((l.position - DVec3::new(0.0, 0.0, 2.0)).length() < 1e-6);
    for deg in [0.0, 5.0, 10.0, 20.0, 24.0, 27.5, 31.0, 45.0] {
        let theta = f64::to_radians(deg);
        for azimuth in [0.0, 1.1, 2.5] {
            let r = 2.0 * theta.tan();
            let p = DVec3::new(r * f64::cos(azimuth), r * f64::sin(azimuth), 0.0);
            // E = I(θ) cos θ / d², d = 2 / cos θ.
            let expected = 500.0 * spot_falloff(theta, inner, outer) * theta.cos().powi(3) / 4.0;
            let lux = l.illuminance_at(p, DVec3::Z, Interp::Bilinear);
            assert!(
                (lux - expected).abs() <= 2e-3 * expected.max(1.0),
                "θ {deg}°: {lux} lx, closed form {expected}"
            );
        }
    }
}

/// An IES file whose planes all differ (an LDT without symmetry, written
/// as IES), so the frame's orientation shows.
fn asymmetric_ies(dir: &Path) -> PathBuf {
    let ldt = Luminaire::load(&common::luminaire("effects/disco.ldt")).unwrap();
    let path = dir.join("asymmetric.ies");
    std::fs::write(
        &path,
        goniolight::photometry::ies::write_ies(&ldt.data, "test"),
    )
    .unwrap();
    path
}

#[test]
fn an_ext_lights_ies_light_is_its_profile_placed_by_its_node() {
    let tmp = tempfile::tempdir().unwrap();
    let ies_file = asymmetric_ies(tmp.path());
    let ies = std::fs::read(&ies_file).unwrap();
    let uri = format!(
        "data:application/x-ies-lm-63;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&ies)
    );
    let profiles = json!({"EXT_lights_ies": {"lights": [{"uri": uri, "name": "ellipse"}]}});
    // Pointing down, then turned 30° about its own axis; multiplier 2, a grey colour 0.5.
    let turn =
        glam::DQuat::from_array(POINTING_DOWN) * glam::DQuat::from_rotation_z(30f64.to_radians());
    let node = json!([{"name": "downlight", "translation": [1.0, 3.0, -0.5], "rotation": turn.to_array(),
                      "extensions": {"EXT_lights_ies": {"light": 0, "multiplier": 2.0, "color": [0.5, 0.5, 0.5]}}}]);
    let doc = document(&FLOOR, &FLOOR_TRIANGLES, node, profiles);
    let scene = scene_with(tmp.path(), "ies.gltf", &doc, "").unwrap();
    let placed = &scene.luminaires[0];
    let profile = Luminaire::load(&ies_file).unwrap();
    // The node's frame in the world (glTF (x, y, z) → (x, −z, y)): −Z is γ = 0, +X is C0.
    let to_world = |v: DVec3| DVec3::new(v.x, -v.z, v.y);
    let (x, y, z) = (
        to_world(turn * DVec3::X),
        to_world(turn * DVec3::Y),
        to_world(turn * DVec3::Z),
    );
    assert!((placed.position - DVec3::new(1.0, 0.5, 3.0)).length() < 1e-9);
    for (k, d) in [
        DVec3::new(0.2, 0.1, -1.0),
        DVec3::new(-0.5, 0.7, -0.4),
        DVec3::new(0.9, -0.2, -0.3),
    ]
    .into_iter()
    .enumerate()
    {
        let d = d.normalize();
        let gamma = d.dot(-z).acos().to_degrees();
        let c = d.dot(y).atan2(d.dot(x)).to_degrees().rem_euclid(360.0);
        let expected = profile
            .distribution
            .candela(c, gamma, Interp::Bilinear, 1.0)
            * 2.0
            * 0.5;
        let cd = placed.intensity_toward(d, Interp::Bilinear);
        assert!(
            (cd - expected).abs() <= 1e-3 * expected.max(1e-3),
            "direction {k}: {cd} cd, profile {expected}"
        );
    }
    // The same file as a [[luminaire]] at the same place and frame gives the same lux.
    let lum = format!(
        "[[luminaire]]\nfile = {:?}\nposition = [1.0, 0.5, 3.0]\naim = [{}, {}, {}]\nroll = {}\nmultiplier = 1.0\n",
        ies_file.display(), -z.x, -z.y, -z.z, 0.0
    );
    let twin = Scene::from_toml(&tmp.path().join("twin.toml"), &lum).unwrap();
    let mut twin_l = twin.luminaires[0].clone();
    twin_l.rotation = placed.rotation;
    for p in [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.0, -1.0, 0.0),
        DVec3::new(-3.0, 2.0, 0.0),
    ] {
        let a = placed.illuminance_at(p, DVec3::Z, Interp::CatmullRom);
        let b = twin_l.illuminance_at(p, DVec3::Z, Interp::CatmullRom);
        assert!((a - b).abs() <= 1e-9 * b.max(1e-9), "{p}: {a} vs {b}");
    }
}

#[test]
fn light_files_replace_a_node_light_and_unknown_names_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let lights =
        json!({"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 100.0}]}});
    let node = json!([{"name": "pendant", "translation": [0.0, 2.5, 0.0], "rotation": POINTING_DOWN,
                      "extensions": {"KHR_lights_punctual": {"light": 0}}}]);
    let doc = document(&FLOOR, &FLOOR_TRIANGLES, node, lights);
    let ldt = common::luminaire("eulumdat-analysis/sample_18.ldt");
    let extra = format!("light_files = {{ pendant = {:?} }}\n", ldt.display());
    let scene = scene_with(tmp.path(), "p.gltf", &doc, &extra).unwrap();
    let l = &scene.luminaires[0];
    assert_eq!(l.file, ldt);
    let direct = Luminaire::load(&ldt).unwrap();
    let down = l.intensity_toward(DVec3::NEG_Z, Interp::Bilinear);
    assert!(
        (down - direct.distribution.candela(0.0, 0.0, Interp::Bilinear, 1.0)).abs() < 1e-3 * down
    );
    let err = scene_with(
        tmp.path(),
        "p.gltf",
        &doc,
        "light_files = { lamp = \"x.ldt\" }\n",
    )
    .unwrap_err();
    assert!(
        err.contains("model[0].light_files.lamp") && err.contains("\"pendant\""),
        "{err}"
    );
    let none = scene_with(tmp.path(), "p.gltf", &doc, "import_lights = false\n").unwrap();
    assert!(none.luminaires.is_empty());
}

#[test]
fn broken_gltf_files_are_refused_with_the_element_at_fault() {
    let tmp = tempfile::tempdir().unwrap();
    let good = document(&FLOOR, &FLOOR_TRIANGLES, json!([]), json!({}));
    assert!(scene_with(tmp.path(), "good.gltf", &good, "").is_ok());
    type Spoil = Box<dyn Fn(&mut Value)>;
    let cases: Vec<(&str, Spoil, &str)> = vec![
        (
            "index",
            Box::new(|d| *d = document(&FLOOR, &[0, 1, 7], json!([]), json!({}))),
            "index 7 is out of range",
        ),
        (
            "count",
            Box::new(|d| d["accessors"][0]["count"] = json!(400)),
            "run past the end of bufferViews[0]",
        ),
        (
            "zero",
            Box::new(|d| d["accessors"][1]["count"] = json!(0)),
            "count 0",
        ),
        (
            "view",
            Box::new(|d| d["bufferViews"][1]["byteLength"] = json!(1 << 20)),
            "outside its buffer",
        ),
        (
            "missing",
            Box::new(|d| d["buffers"][0]["uri"] = json!("gone.bin")),
            "buffers[0]",
        ),
        (
            "type",
            Box::new(|d| d["accessors"][0]["type"] = json!("VEC2")),
            "POSITION (accessors[0])",
        ),
        (
            "cycle",
            Box::new(|d| d["nodes"][0]["children"] = json!([0])),
            "deeper than 64",
        ),
        (
            "json",
            Box::new(|d| *d = json!({"asset": {"version": "2.0"}, "nodes": 3})),
            "not glTF 2.0",
        ),
    ];
    for (name, spoil, expected) in cases {
        let mut doc = good.clone();
        spoil(&mut doc);
        let err = scene_with(tmp.path(), &format!("{name}.gltf"), &doc, "").unwrap_err();
        assert!(
            err.contains(expected) && err.contains(&format!("{name}.gltf")),
            "{name}: {err}"
        );
    }
}

/// A 2 × 2 PNG (as a data URI) whose left column is solid and right column a hole.
fn half_holes_png() -> String {
    let img = image::RgbaImage::from_fn(2, 2, |x, _| {
        if x == 0 {
            image::Rgba([200, 100, 50, 255])
        } else {
            image::Rgba([0, 0, 0, 0])
        }
    });
    let mut png = std::io::Cursor::new(Vec::new());
    img.write_to(&mut png, image::ImageFormat::Png).unwrap();
    format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png.into_inner())
    )
}

#[test]
fn materials_become_reflectance_glass_holes_and_emitters() {
    let tmp = tempfile::tempdir().unwrap();
    let textured = json!({"index": 0});
    let cases = [
        (
            json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.4, 0.3, 1.0]}}),
            "plain",
        ),
        (
            json!({"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1.0], "roughnessFactor": 0.0},
                "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.8}}}),
            "glass",
        ),
        (
            json!({"pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "roughnessFactor": 0.6},
                "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}}}),
            "frosted",
        ),
        (
            json!({"pbrMetallicRoughness": {"baseColorTexture": textured}, "alphaMode": "MASK", "alphaCutoff": 0.5}),
            "mask",
        ),
        (
            json!({"pbrMetallicRoughness": {"baseColorTexture": textured}}),
            "opaque",
        ),
        (
            json!({"emissiveFactor": [1.0, 0.5, 0.0],
                "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}}),
            "emitter",
        ),
    ];
    for (material, name) in cases {
        let mut doc = document(&FLOOR, &FLOOR_TRIANGLES, json!([]), json!({}));
        doc["materials"] = json!([material]);
        doc["materials"][0]["name"] = json!(name);
        doc["meshes"][0]["primitives"][0]["material"] = json!(0);
        doc["images"] = json!([{"uri": half_holes_png()}]);
        doc["textures"] = json!([{"source": 0}]);
        let used = [
            "KHR_materials_transmission",
            "KHR_materials_emissive_strength",
        ];
        doc["extensionsUsed"] = json!(used);
        let scene = scene_with(tmp.path(), &format!("{name}.gltf"), &doc, "").unwrap();
        let m = &scene.materials[scene.meshes[0].material];
        assert_eq!(m.name, name);
        let close =
            |a: glam::Vec3, b: [f32; 3]| (a - glam::Vec3::from(b)).abs().max_element() < 1e-5;
        match name {
            "plain" => assert!(close(m.diffuse_reflectance(), [0.5, 0.4, 0.3])),
            "glass" => {
                assert!(close(m.specular_transmittance, [0.72; 3]), "{m:?}");
                assert!(close(m.diffuse_reflectance(), [0.18; 3]), "{m:?}");
            }
            "frosted" => {
                assert!(
                    close(m.diffuse_transmittance, [0.5; 3])
                        && m.specular_transmittance == glam::Vec3::ZERO
                )
            }
            "mask" => {
                let mask = m.alpha_mask.as_ref().expect("MASK cuts holes");
                assert_eq!(mask.solid_fraction(), 0.5);
                // The mean of the solid texels, sRGB decoded.
                let srgb = |c: f32| goniolight::scene::palette::srgb_to_linear(c as u8);
                assert!(
                    close(m.texture_mean(), [srgb(200.0), srgb(100.0), srgb(50.0)]),
                    "{}",
                    m.texture_mean()
                );
            }
            "opaque" => assert!(m.alpha_mask.is_none(), "OPAQUE ignores alpha"),
            _ => assert!(close(
                m.emission,
                [2.0 * std::f32::consts::PI, std::f32::consts::PI, 0.0]
            )),
        }
    }
}

#[test]
fn a_node_tree_that_instances_without_end_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let mut doc = document(&FLOOR, &FLOOR_TRIANGLES, json!([]), json!({}));
    // Node k has node k + 1 twice as children: 2^40 floors from a few lines.
    let mut nodes = vec![json!({"mesh": 0, "children": [1, 1]})];
    for k in 1..40 {
        nodes.push(json!({"mesh": 0, "children": [k + 1, k + 1]}));
    }
    nodes.push(json!({"mesh": 0}));
    doc["nodes"] = json!(nodes);
    doc["scenes"] = json!([{"nodes": [0]}]);
    let err = scene_with(tmp.path(), "tree.gltf", &doc, "").unwrap_err();
    assert!(
        err.contains("more than") && err.contains("instances counted"),
        "{err}"
    );
}

/// glTF's texture coordinates have their origin at the image's top left, as the renderer
/// and the alpha masks sample: they are kept as they are (v = 0.25 is the top row).
#[test]
fn texture_coordinates_keep_the_top_left_origin() {
    let tmp = tempfile::tempdir().unwrap();
    let mut doc = document(&FLOOR, &FLOOR_TRIANGLES, json!([]), json!({}));
    let uv: Vec<u8> = [[0.3f32, 0.25]; 4]
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    doc["buffers"].as_array_mut().unwrap().push(json!({
        "byteLength": uv.len(),
        "uri": format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(&uv))
    }));
    doc["bufferViews"]
        .as_array_mut()
        .unwrap()
        .push(json!({"buffer": 1, "byteLength": uv.len()}));
    doc["accessors"]
        .as_array_mut()
        .unwrap()
        .push(json!({"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"}));
    doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = json!(2);
    // Top row solid, bottom row holes.
    let img = image::RgbaImage::from_fn(2, 2, |_, y| {
        image::Rgba([90, 90, 90, if y == 0 { 255 } else { 0 }])
    });
    let mut png = std::io::Cursor::new(Vec::new());
    img.write_to(&mut png, image::ImageFormat::Png).unwrap();
    let uri = format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png.into_inner())
    );
    doc["images"] = json!([{"uri": uri}]);
    doc["textures"] = json!([{"source": 0}]);
    doc["materials"] =
        json!([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "alphaMode": "MASK"}]);
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    let scene = scene_with(tmp.path(), "uv.gltf", &doc, "").unwrap();
    let mesh = &scene.meshes[0];
    assert!(
        mesh.uvs
            .iter()
            .all(|uv| (*uv - glam::Vec2::new(0.3, 0.25)).length() < 1e-6),
        "{:?}",
        mesh.uvs
    );
    let mask = scene.materials[mesh.material].alpha_mask.as_ref().unwrap();
    assert!(
        mask.solid_at(mesh.uvs[0]),
        "v = 0.25 is the texture's solid top row"
    );
}
