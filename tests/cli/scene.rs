//! Scenes: the bundled scenes load; bad scene files name the file and the key and exit 2;
//! the CPU reference of the direct illuminance equals E = I · cos θ / d² at measured
//! angles (values from an independent reader of the file).

use crate::common;

use std::path::{Path, PathBuf};

use common::{luminaire, raw_ldt, root, run_cli};
use glam::{DMat3, DVec3, Vec3};
use goniolight::geometry::generate::XorShift;
use goniolight::photometry::{angles_to_direction, Interp};
use goniolight::render::illuminance::{illuminance_cpu, SurfacePoint};
use goniolight::scene::file::Bake;
use goniolight::scene::Projection;
use goniolight::scene::{Scene, SceneError};

fn scene(rel: &str) -> PathBuf {
    root().join("assets/scenes").join(rel)
}

#[test]
fn bundled_scenes_load_with_their_luminaires_materials_and_textures() {
    let s = Scene::load(&scene("furnished_room.toml")).unwrap();
    assert_eq!(s.luminaires.len(), 5);
    assert!(s.triangle_count() > 400, "{}", s.triangle_count());
    let wood = s.materials.iter().find(|m| m.name == "floor_wood").unwrap();
    assert_eq!(wood.diffuse_map.as_ref().unwrap().dimensions(), (256, 256));
    let bricks = s
        .materials
        .iter()
        .find(|m| m.name == "plaster_bricks")
        .unwrap();
    assert!(bricks.normal_map.is_some());
    // The wall spots point at the pictures: γ = 0 toward the aim point.
    let spot = &s.luminaires[2];
    let aim = (DVec3::new(1.9, 3.97, 1.55) - spot.position).normalize();
    assert!((spot.world_direction(0.0, 0.0) - aim).length() < 1e-12);
    // Colours are normalised to luminance 1.
    assert!((spot.color.dot(DVec3::new(0.2126, 0.7152, 0.0722)) - 1.0).abs() < 1e-12);
    let room = Scene::load(&scene("box_room.toml")).unwrap();
    assert_eq!(room.triangle_count(), 12);
    let (lo, hi) = room.bounds();
    assert_eq!((lo, hi), (DVec3::ZERO, DVec3::new(6.0, 4.0, 3.0)));
    // Each downlight's housing is the `downlight` object above it, not its twin's.
    for (l, x) in [(&s.luminaires[0], 2.0), (&s.luminaires[1], 4.0)] {
        let h = l.housing.as_ref().unwrap();
        assert_eq!((h.name.as_str(), h.meshes.len()), ("downlight", 1));
        let mesh = &s.meshes[h.meshes[0]];
        assert_eq!(mesh.name, "downlight");
        assert!(mesh
            .positions
            .iter()
            .all(|p| (p.x as f64 - x).abs() <= 0.1 + 1e-6));
        let ignored = s.ignored_by(l);
        assert_eq!(ignored.0.iter().map(|r| r.len()).sum::<usize>(), 12);
    }
    // Moved away from its body (the viewer moves luminaires), the tie lapses: the
    // object shadows it like any other geometry, and a save does not write it.
    let mut moved = s.luminaires[0].clone();
    moved.position.x += 0.2;
    assert!(s.ignored_by(&moved).is_empty() && s.housing_in_reach(&moved).is_none());
    assert!(s.luminaires[2].housing.is_none());
    assert!(s.ignored_by(&s.luminaires[2]).is_empty());
    let stage = Scene::load(&scene("effect_stage.toml")).unwrap();
    // The mirror ball turns 30°/s with six coloured sectors, inside its own body.
    let ball = &stage.luminaires[0];
    assert_eq!((ball.spin_deg_per_s, ball.sector_colors.len()), (30.0, 6));
    assert!(stage.is_animated() && !s.is_animated());
    assert!(!stage.ignored_by(ball).is_empty());
    let turned = ball.at_time(2.0);
    let axis = ball.rotation.z_axis;
    assert!(
        (turned.rotation.z_axis - axis).length() < 1e-12,
        "turns about its own axis"
    );
    let c0 = ball
        .rotation
        .x_axis
        .dot(turned.rotation.x_axis)
        .acos()
        .to_degrees();
    assert!((c0 - 60.0).abs() < 1e-9, "{c0}");
    // Its C0 direction (sector 0) is sector 0's colour, C90 sector 1's (60–120°).
    let c = |deg: f64| ball.color_toward(ball.world_direction(deg, 45.0));
    assert_eq!(
        (c(10.0), c(90.0), c(359.0)),
        (
            ball.sector_colors[0],
            ball.sector_colors[1],
            ball.sector_colors[5]
        )
    );
    assert_eq!(stage.luminaires[0].luminaire.data.c_angles.len(), 144);
}

#[test]
fn y_up_models_turn_to_z_up_and_transforms_apply_scale_rotation_translation() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let write = |extra: &str| {
        let p = dir.path().join("s.toml");
        std::fs::write(
            &p,
            format!(
                "[[model]]\npath = \"tri.obj\"\n{extra}\n[camera]\nposition = [5, 5, 5]\nlook_at = [0, 0, 0]\n"
            ),
        )
        .unwrap();
        Scene::load(&p).unwrap()
    };
    // Y up (the default): OBJ +Y becomes world +Z, OBJ +Z becomes world −Y.
    let s = write("");
    assert!((s.meshes[0].positions[2].as_dvec3() - DVec3::Z).length() < 1e-6);
    assert!((s.meshes[0].normals[0].as_dvec3() - DVec3::NEG_Y).length() < 1e-6);
    // Z up with scale 2, a 90° turn about Z, then a translation.
    let s = write("up = \"z\"\nscale = 2.0\nrotation_deg = [0, 0, 90]\ntranslation = [10, 0, 0]");
    let p = s.meshes[0].positions[1].as_dvec3();
    assert!((p - DVec3::new(10.0, 2.0, 0.0)).length() < 1e-5, "{p}");
}

/// Writes `text` as a scene next to nothing and loads it.
fn load_text(text: &str) -> (tempfile::TempDir, Result<Scene, SceneError>) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bad.toml");
    std::fs::write(&p, text).unwrap();
    let r = Scene::load(&p);
    (dir, r)
}

fn good_parts() -> (String, String) {
    let model = format!(
        "[[model]]\npath = {:?}\nup = \"z\"\n",
        scene("box_room.obj").display().to_string()
    );
    let camera = "[camera]\nposition = [1, 1, 1.5]\nlook_at = [3, 2, 1]\n".to_string();
    (model, camera)
}

fn luminaire_entry(file: &Path, position: &str) -> String {
    format!(
        "[[luminaire]]\nfile = {:?}\nposition = {position}\n",
        file.display().to_string()
    )
}

#[test]
fn bad_scene_files_name_the_file_and_the_key() {
    let (model, camera) = good_parts();
    let lum = luminaire("eulumdat-plot/sample_06_isym1.ldt");
    let cases: Vec<(String, &str, &str)> = vec![
        (
            format!("[[model]]\npath = \"missing.obj\"\n{camera}"),
            "model[0].path",
            "no such file",
        ),
        (format!("{model}{camera}position = [1, 2\n"), "line 7", ""),
        (
            format!(
                "{model}{}{camera}",
                luminaire_entry(Path::new("nope.ldt"), "[1, 1, 2]")
            ),
            "luminaire[0].file",
            "nope.ldt",
        ),
        (
            format!("{model}{}{camera}", luminaire_entry(&lum, "[1, nan, 2]")),
            "luminaire[0].position",
            "finite",
        ),
        (
            format!(
                "{model}{}multiplier = -1\n{camera}",
                luminaire_entry(&lum, "[1, 1, 2]")
            ),
            "luminaire[0].multiplier",
            "",
        ),
        (
            format!(
                "{model}{}positon = [1, 1, 1]\n{camera}",
                luminaire_entry(&lum, "[1, 1, 2]")
            ),
            "luminaire.positon",
            "unknown field",
        ),
        (
            format!("{model}[camera]\nposition = [1, 1, 1]\nlook_at = [1, 1, 1]\n"),
            "camera.look_at",
            "",
        ),
        (
            format!(
                "{model}{}sector_colors = []\n{camera}",
                luminaire_entry(&lum, "[1, 1, 2]")
            ),
            "luminaire[0].sector_colors",
            "give 1 to 360",
        ),
        (
            format!(
                "{model}{}sector_colors = [[1, 0, 0], [0, 0, 0]]\n{camera}",
                luminaire_entry(&lum, "[1, 1, 2]")
            ),
            "luminaire[0].sector_colors[1]",
            "not all 0",
        ),
        (
            format!(
                "{model}{}spin_deg_per_s = inf\n{camera}",
                luminaire_entry(&lum, "[1, 1, 2]")
            ),
            "luminaire[0].spin_deg_per_s",
            "finite",
        ),
        (
            format!(
                "{model}{}housing = \"lamp\"\n{camera}",
                luminaire_entry(&lum, "[1, 1, 2]")
            ),
            "luminaire[0].housing",
            "no model object is named \"lamp\"",
        ),
        (
            format!(
                "{model}{}housing = \"walls\"\n{camera}",
                luminaire_entry(&lum, "[-1, 1, 2]")
            ),
            "luminaire[0].housing",
            "1.000 m from the luminaire",
        ),
        (
            format!("{model}bake_materials = {{ marble = \"map\" }}\n{camera}"),
            "model[0].bake_materials.marble",
            "no material \"marble\"",
        ),
        (
            format!("{model}bake = \"texture\"\n{camera}"),
            "model",
            "unknown variant",
        ),
        (
            format!("{model}{camera}[display]\nwidth = 0\n"),
            "display.width",
            "",
        ),
        (
            format!("{model}{camera}[display]\nheight = 10000\n"),
            "display.height",
            "8192",
        ),
    ];
    for (text, key, words) in cases {
        let (_dir, r) = load_text(&text);
        let e = r.expect_err(&text);
        let msg = e.to_string();
        assert!(e.key.contains(key), "key {key:?} not in {msg:?}");
        assert!(msg.contains("bad.toml"), "{msg}");
        assert!(msg.contains(words), "{words:?} not in {msg:?}");
    }
    // A missing required key of a table is named under that table.
    let (_dir, r) = load_text(&format!("{model}[camera]\nposition = [1, 1, 1]\n"));
    assert_eq!(r.expect_err("no look_at").key, "camera.look_at");
}

/// `bake` sets every material of a model (and its faces without one), `bake_materials`
/// one by name over it; without either the choice is left to the export.
#[test]
fn bake_keys_set_the_models_materials() {
    let (model, camera) = good_parts();
    let (_dir, r) = load_text(&format!(
        "{model}bake = \"vertex\"\nbake_materials = {{ floor = \"map\" }}\n{camera}"
    ));
    let s = r.unwrap();
    let bake = |name: &str| s.materials.iter().find(|m| m.name == name).unwrap().bake;
    assert_eq!(bake("floor"), Some(Bake::Map));
    assert_eq!(bake("wall"), Some(Bake::Vertex));
    assert_eq!(bake("ceiling"), Some(Bake::Vertex));
    // The default material keeps no choice; faces without a material get a copy that does.
    assert_eq!(s.materials[0].bake, None);
    assert_eq!(s.materials.last().unwrap().bake, Some(Bake::Vertex));
    let saved = s.to_toml(&s.path).unwrap();
    assert!(
        saved.contains("bake = \"vertex\"") && saved.contains("floor = \"map\""),
        "{saved}"
    );
    let (_dir, r) = load_text(&format!("{model}{camera}"));
    assert!(r.unwrap().materials.iter().all(|m| m.bake.is_none()));
}

/// `[[material]]` overrides an MTL material by name (and is saved back); a wrong name, a
/// value out of range or reflectances plus transmittances above 1 is an error naming the
/// key; the specular keys make a mirror or clear glass. MTL `d`/`Tr`/`Tf` give the diffuse transmittance, except for
/// glass (`illum` 4, 6, 7, 9), which stays opaque.
#[test]
fn material_overrides_and_mtl_transparency_set_the_transmittance() {
    let (model, camera) = good_parts();
    let (_dir, r) = load_text(&format!(
        "{model}{camera}[[material]]\nname = \"wall\"\ndiffuse_transmittance = [0.1, 0.2, 0.3]\n"
    ));
    let s = r.unwrap();
    let wall = s.materials.iter().find(|m| m.name == "wall").unwrap();
    assert_eq!(wall.diffuse_transmittance, Vec3::new(0.1, 0.2, 0.3));
    assert!(s.specular_material().is_none());
    let (_dir, r) = load_text(&format!(
        "{model}{camera}[[material]]\nname = \"wall\"\ndiffuse_reflectance = 0\n\
         specular_reflectance = 0.9\n"
    ));
    let mirrored = r.unwrap();
    let mirror = mirrored.specular_material().expect("the wall is a mirror");
    assert_eq!(
        (mirror.name.as_str(), mirror.specular_reflectance),
        ("wall", Vec3::splat(0.9))
    );
    let saved = mirrored.to_toml(&mirrored.path).unwrap();
    assert!(saved.contains("specular_reflectance = 0.9"), "{saved}");
    let floor = s.materials.iter().find(|m| m.name == "floor").unwrap();
    assert_eq!(floor.diffuse_transmittance, Vec3::ZERO);
    let saved = s.to_toml(&s.path).unwrap();
    assert!(
        saved.contains("[[material]]") && saved.contains("diffuse_transmittance"),
        "{saved}"
    );
    for (entry, key, says) in [
        (
            "name = \"wal\"\ndiffuse_transmittance = 0.1",
            "material[0].name",
            "\"wall\"",
        ),
        (
            "name = \"wall\"\ndiffuse_transmittance = 1.5",
            "material[0].diffuse_transmittance",
            "0..=1",
        ),
        (
            "name = \"wall\"\ndiffuse_transmittance = 0.6",
            "material[0]",
            "more than it receives",
        ),
        (
            "name = \"wall\"\nspecular_reflectance = 0.9",
            "material[0]",
            "more than it receives",
        ),
        (
            "name = \"wall\"\nopacity = 0.9",
            "material",
            "unknown field",
        ),
    ] {
        let (_dir, r) = load_text(&format!("{model}{camera}[[material]]\n{entry}\n"));
        let e = r.unwrap_err().to_string();
        assert!(
            e.contains("bad.toml") && e.contains(key) && e.contains(says),
            "{entry}: {e}"
        );
    }

    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("m.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl frosted\nf 1 2 3\nusemtl tinted\nf 1 2 3\nusemtl glass\nf 1 2 3\nusemtl white\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("m.mtl"),
        "newmtl frosted\nKd 0.5 0.5 0.5\nd 0.75\nTf 1 1 1\nillum 2\n\
         newmtl tinted\nKd 0.2 0.2 0.2\nTr 0.5\nTf 1 0.5 0.25\n\
         newmtl glass\nKd 0 0 0\nd 0.2\nTf 0.9 0.9 0.9\nillum 7\n\
         newmtl white\nKd 0.9 0.9 0.9\nd 0.5\n",
    )
    .unwrap();
    let p = dir.path().join("m.toml");
    std::fs::write(&p, "[[model]]\npath = \"m.obj\"\nup = \"z\"\n").unwrap();
    let s = Scene::load(&p).unwrap();
    let t = |name: &str| {
        s.materials
            .iter()
            .find(|m| m.name == name)
            .unwrap()
            .diffuse_transmittance
    };
    assert!((t("frosted") - Vec3::splat(0.25)).abs().max_element() < 1e-6);
    assert!(
        (t("tinted") - Vec3::new(0.5, 0.25, 0.125))
            .abs()
            .max_element()
            < 1e-6
    );
    assert_eq!(
        t("glass"),
        Vec3::ZERO,
        "glass is specular: set in the scene file, not from the MTL"
    );
    // Kd 0.9 leaves room for 0.1 only.
    assert!(
        (t("white") - Vec3::splat(0.1)).abs().max_element() < 1e-6,
        "{}",
        t("white")
    );
}

/// A scene without `[camera]` loads: commands without an image need none, and images get
/// a plan view of the bounds, cut above the luminaires hanging under the ceiling.
#[test]
fn a_scene_without_a_camera_gets_a_plan_view_cut_under_the_ceiling() {
    let (model, _) = good_parts();
    let lum = luminaire("eulumdat-plot/sample_06_isym1.ldt");
    let (_dir, r) = load_text(&format!("{model}{}", luminaire_entry(&lum, "[3, 2, 2.9]")));
    let s = r.unwrap();
    let c = s.camera;
    assert_eq!(c.up, DVec3::Y);
    assert!(
        (c.look_at - DVec3::new(3.0, 2.0, 0.0)).length() < 1e-12,
        "{:?}",
        c.look_at
    );
    assert_eq!((c.position.x, c.position.y), (3.0, 2.0));
    // The box room is 6 × 4 × 3 m: the plan shows all of it, and the view starts 1 cm
    // above the luminaire (2.91 m), under the ceiling (3 m).
    match c.projection {
        Projection::Orthographic { height } => assert!((4.0..5.0).contains(&height)),
        p => panic!("{p:?}"),
    }
    assert!((c.position.z - c.near - 2.91).abs() < 1e-9, "{c:?}");
    // Without luminaires under the top nothing is cut.
    let (_dir, r) = load_text(&model);
    let c = r.unwrap().camera;
    assert!((c.position.z - c.near - 3.0).abs() < 1e-9, "{c:?}");
}

#[test]
fn render_of_a_bad_scene_exits_2_and_writes_nothing() {
    let (model, camera) = good_parts();
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("scene.toml");
    let lum = luminaire("eulumdat-plot/sample_06_isym1.ldt");
    std::fs::write(
        &bad,
        format!("{model}{}{camera}", luminaire_entry(&lum, "[1, nan, 2]")),
    )
    .unwrap();
    let out = dir.path().join("img.png");
    let (code, _, err) = run_cli(
        &[
            "render",
            bad.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("scene.toml") && err.contains("luminaire[0].position"),
        "{err}"
    );
    assert!(!out.exists());
    // Wrong flags: exit 2 before any work.
    let good = scene("box_room.toml");
    for args in [
        vec!["--out", "x.jpg"],
        vec!["--out", "x.png", "--width", "0"],
        vec!["--out", "x.png", "--exposure", "-1"],
        vec!["--out", "x.png", "--interp", "cubic"],
    ] {
        let mut all = vec!["render", good.to_str().unwrap()];
        all.extend(args.iter());
        let (code, _, err) = run_cli(&all, "");
        assert_eq!(code, 2, "{args:?}: {err}");
    }
    // The render-quality options are checked by the library and named by their flags.
    for (args, said) in [
        (["--supersample", "2"], "--supersample 2 must be 1, 3 or 5"),
        (
            ["--shadow-map-size", "8"],
            "--shadow-map-size 8 is not in 16..=8192",
        ),
    ] {
        let mut all = vec!["render", good.to_str().unwrap(), "--out", "x.png"];
        all.extend(args.iter());
        let (code, _, err) = run_cli(&all, "");
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(said), "{args:?}: {err}");
    }
    // Bad point lines for `illuminance`.
    let (code, _, err) = run_cli(
        &["illuminance", good.to_str().unwrap(), "--cpu"],
        "1 2 1 0 0 1\n1 2 x 0 0 1\n",
    );
    assert_eq!(code, 2);
    assert!(err.contains("line 2"), "{err}");
}

/// Measured (C, γ, cd/klm) of a file, from the independent reader, for stored planes.
fn measured(file: &Path) -> Vec<(f64, f64, f64)> {
    let (_isym, c, g, planes) = raw_ldt(file);
    let mut out = Vec::new();
    for (ci, plane) in planes.iter().enumerate() {
        for (gi, &v) in plane.iter().enumerate() {
            if g[gi] > 0.0 && g[gi] < 180.0 {
                out.push((c[ci.min(c.len() - 1)], g[gi], v));
            }
        }
    }
    out
}

#[test]
fn cpu_illuminance_equals_intensity_cos_over_d2_at_measured_angles() {
    let mut rng = XorShift::new(7);
    for (file, planes_are_c) in [
        ("eulumdat-analysis/sample_18.ldt", true),
        ("eulumdat-plot/sample_06_isym1.ldt", false),
    ] {
        let path = luminaire(file);
        let text = format!(
            "[[luminaire]]\nfile = {:?}\nposition = [1.0, 2.0, 2.5]\naim = [0.3, -0.2, -1.0]\nroll = 25\nmultiplier = 0.7\n[camera]\nposition = [0, 0, 0]\nlook_at = [1, 1, 1]\n",
            path.display().to_string()
        );
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.toml");
        std::fs::write(&p, text).unwrap();
        let s = Scene::load(&p).unwrap();
        let l = &s.luminaires[0];
        let flux = l.luminaire.distribution.lamp_flux_lm();
        let values = measured(&path);
        let mut checked = 0;
        for (k, &(c, g, cd_klm)) in values.iter().enumerate() {
            if (values.len() > 2000 && k % 7 != 0) || cd_klm <= 0.0 {
                continue;
            }
            // A rotationally symmetric file stores one plane: any C has its values.
            let c = if planes_are_c {
                c
            } else {
                rng.next_f64() * 360.0
            };
            let dir_world = l.rotation * angles_to_direction(c, g);
            let r = 1.0 + 3.0 * rng.next_f64();
            let point = l.position + dir_world * r;
            let tilt = DMat3::from_axis_angle(
                DVec3::new(rng.next_f64(), rng.next_f64(), 1.0).normalize(),
                rng.next_f64() * 1.2,
            );
            let normal = tilt * -dir_world;
            let cos = normal.dot(-dir_world);
            let expected = cd_klm * flux / 1000.0 * 0.7 * cos / (r * r);
            for interp in Interp::ALL {
                let got = illuminance_cpu(
                    &s.luminaires,
                    &SurfacePoint {
                        position: point,
                        normal,
                    },
                    interp,
                );
                let rel = (got - expected).abs() / expected;
                assert!(
                    rel <= 1e-3,
                    "{file} C {c} γ {g} {interp:?}: {got} vs {expected} ({rel:e})"
                );
            }
            // The back of the surface gets nothing.
            let back = illuminance_cpu(
                &s.luminaires,
                &SurfacePoint {
                    position: point,
                    normal: -normal,
                },
                Interp::CatmullRom,
            );
            assert_eq!(back, 0.0);
            checked += 1;
        }
        assert!(checked > 20, "{file}: {checked}");
    }
}

/// The furnished room bundled in the binary (what `view` and `demo` open outside a
/// checkout) is complete: extracted anywhere, it loads with the same model, materials,
/// textures and luminaires as the checkout's. Extracting again rewrites nothing.
#[test]
fn the_bundled_scene_extracts_whole() {
    let dir = tempfile::tempdir().unwrap();
    let path = goniolight::io::bundled::extract(dir.path()).unwrap();
    let extracted = Scene::load(&path).unwrap();
    let checkout = Scene::load(&scene("furnished_room.toml")).unwrap();
    assert_eq!(extracted.triangle_count(), checkout.triangle_count());
    assert_eq!(extracted.luminaires.len(), 5);
    for (a, b) in extracted.luminaires.iter().zip(&checkout.luminaires) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.position, b.position);
        let flux = |l: &goniolight::scene::PlacedLuminaire| l.luminaire.distribution.flux_lm();
        assert_eq!(flux(a), flux(b), "{}", a.name);
    }
    assert_eq!(extracted.materials.len(), checkout.materials.len());
    let textured = |s: &Scene| {
        let maps = s
            .materials
            .iter()
            .map(|m| m.diffuse_map.is_some() as usize * 2);
        maps.zip(&s.materials)
            .map(|(d, m)| d + m.normal_map.is_some() as usize)
            .collect::<Vec<_>>()
    };
    assert_eq!(textured(&extracted), textured(&checkout));
    let licence = dir.path().join("luminaires/eulumdat-plot/LICENSE");
    let written = std::fs::metadata(&licence).unwrap().modified().unwrap();
    goniolight::io::bundled::extract(dir.path()).unwrap();
    assert_eq!(
        std::fs::metadata(&licence).unwrap().modified().unwrap(),
        written
    );
}

/// The radiosity benchmark pair: the box room with four boxes (52 triangles) and the same
/// surfaces as 2 600 CAD-like strips — equal bounds and equal area per material, the
/// second made of slivers.
#[test]
fn the_cad_room_is_the_boxes_room_in_strips() {
    let coarse = Scene::load(&scene("boxes_room.toml")).unwrap();
    let fine = Scene::load(&scene("cad_room.toml")).unwrap();
    assert_eq!(coarse.triangle_count(), 52);
    assert_eq!(fine.triangle_count(), 2600);
    assert_eq!(coarse.bounds(), fine.bounds());
    let per_material = |s: &Scene| {
        let (mesh, mats) = (s.caster_mesh(), s.caster_materials());
        let mut area: std::collections::BTreeMap<String, f64> = Default::default();
        for (t, m) in mats.iter().enumerate() {
            *area.entry(s.materials[*m].name.clone()).or_default() +=
                mesh.face_normal(t).length() / 2.0;
        }
        area
    };
    let (a, b) = (per_material(&coarse), per_material(&fine));
    assert_eq!(
        a.keys().collect::<Vec<_>>(),
        ["ceiling", "floor", "furniture", "wall"]
    );
    for (k, v) in &a {
        assert!((b[k] - v).abs() < 1e-4 * v, "{k}: {v} vs {}", b[k]);
    }
    assert!((a["floor"] - 24.0).abs() < 1e-4, "a 6 × 4 m floor");
    let mesh = fine.caster_mesh();
    let slivers = (0..mesh.triangles.len())
        .filter(|&t| {
            let [p, q, r] = mesh.triangles[t].map(|i| mesh.positions[i as usize]);
            let longest = p.distance(q).max(q.distance(r)).max(r.distance(p));
            longest * longest / mesh.face_normal(t).length() > 50.0
        })
        .count();
    assert!(slivers * 2 > mesh.triangles.len(), "{slivers} slivers");
}

#[test]
fn a_grey_bump_map_is_a_height_map_turned_into_a_normal_map_and_a_coloured_one_is_kept() {
    let dir = tempfile::tempdir().unwrap();
    // Height rising 0.1 per texel along x; a normal map tilted toward +x.
    image::RgbaImage::from_fn(16, 4, |x, _| {
        let v = (x as f32 * 0.1 * 255.0).round() as u8;
        image::Rgba([v, v, v, 255])
    })
    .save(dir.path().join("ramp.png"))
    .unwrap();
    let tilted = image::Rgba([191, 128, 238, 255]);
    image::RgbaImage::from_pixel(4, 4, tilted)
        .save(dir.path().join("tilted.png"))
        .unwrap();
    let s = common::load_quad_scene(
        dir.path(),
        "usemtl height\nf 1/1 2/2 3/3\nusemtl normal\nf 1/1 3/3 4/4\n",
        "newmtl height\nKd 0.5 0.5 0.5\nbump -bm 2 ramp.png\nnewmtl normal\nKd 0.5 0.5 0.5\nmap_Bump tilted.png\n",
    );
    let map = |name: &str| {
        s.materials
            .iter()
            .find(|m| m.name == name)
            .and_then(|m| m.normal_map.clone())
            .unwrap()
    };
    // The ramp with -bm 2: slope 0.1 per texel × 2 → n = normalise(−0.2, 0, 1).
    let texel = map("height").get_pixel(5, 1).0;
    let decode = |c: u8| c as f64 / 255.0 * 2.0 - 1.0;
    let n = DVec3::new(decode(texel[0]), decode(texel[1]), decode(texel[2]));
    assert!(
        (n - DVec3::new(-0.2, 0.0, 1.0).normalize()).length() < 0.01,
        "{n}"
    );
    assert_eq!(map("normal").get_pixel(1, 1), &tilted);
}
