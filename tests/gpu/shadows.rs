//! Shadows in the renderer (lavapipe in CI) against the CPU ray-cast reference: per pixel,
//! the surface seen through the pixel centre (a CPU ray from the camera) is in shadow when
//! a triangle lies between it and the luminaire. Stencil shadow volumes (z-pass, z-fail,
//! chosen by the near-clip-volume test) and dual-paraboloid maps must agree on ≥ 99.5 %
//! of the pixels, ignoring a one-pixel band along shadow edges.

use crate::common;

use crate::gpu_common;

use common::{luminaire, root};
use glam::{DMat4, DVec3, DVec4, Vec3};
use goniolight::geometry::Mesh;
use goniolight::gpu::Gpu;
use goniolight::photometry::{Interp, Luminaire};
use goniolight::render::illuminance::{
    illuminance_cpu_in_scene, point_visibility, IlluminanceProbe, Occluders, SurfacePoint,
};
use goniolight::render::{
    LightModel, RenderSettings, Renderer, ShadowSettings, ShadowTechnique, VolumeTest,
};
use goniolight::scene::{
    Camera, DisplayEntry, Housing, Material, PlacedLuminaire, Scene, SceneMesh,
};
use goniolight::shadow::raycast::{first_hit, in_shadow_ignoring};
use goniolight::shadow::{Light, SilhouetteMethod};

const W: u32 = 160;
const H: u32 = 120;

fn mesh_to_scene_mesh(name: &str, m: &Mesh) -> SceneMesh {
    let tris: Vec<[Vec3; 3]> = m
        .triangles
        .iter()
        .map(|t| t.map(|i| m.positions[i as usize].as_vec3()))
        .collect();
    SceneMesh::from_triangles(name, &tris, 0)
}

fn floor(size: f64) -> Mesh {
    let h = size / 2.0;
    Mesh {
        positions: vec![
            DVec3::new(-h, -h, 0.0),
            DVec3::new(h, -h, 0.0),
            DVec3::new(h, h, 0.0),
            DVec3::new(-h, h, 0.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

fn sphere(center: DVec3, r: f64, rings: u32, segments: u32) -> Mesh {
    let mut m = Mesh::default();
    for i in 0..=rings {
        let theta = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..segments {
            let phi = std::f64::consts::TAU * j as f64 / segments as f64;
            m.positions.push(
                center
                    + r * DVec3::new(
                        theta.sin() * phi.cos(),
                        theta.sin() * phi.sin(),
                        theta.cos(),
                    ),
            );
        }
    }
    let idx = |i: u32, j: u32| i * segments + j % segments;
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            if i != 0 {
                m.triangles.push([a, b, d]);
            }
            if i + 1 != rings {
                m.triangles.push([d, b, c]);
            }
        }
    }
    m
}

fn scene(meshes: &[Mesh], luminaires: Vec<PlacedLuminaire>, camera: Camera) -> Scene {
    let meshes = meshes
        .iter()
        .enumerate()
        .map(|(k, m)| mesh_to_scene_mesh(&format!("mesh {k}"), m))
        .collect();
    Scene::in_code(
        "shadow test",
        meshes,
        vec![Material::default()],
        luminaires,
        camera,
    )
}

fn downlight(position: DVec3) -> PlacedLuminaire {
    let l = Luminaire::load(&luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    PlacedLuminaire::new("downlight", l, position)
}

/// The CPU reference per pixel for luminaire `index`: `None` where no surface is seen or
/// it faces away from the light (unlit either way), else whether it is in shadow (its
/// own housing never shadows it).
fn reference(scene: &Scene, index: usize) -> Vec<Option<bool>> {
    let light = scene.luminaires[index].position;
    let ignored = scene.ignored_by(&scene.luminaires[index]);
    let mesh = scene.caster_mesh();
    let aspect = W as f64 / H as f64;
    let inverse: DMat4 = (scene.camera.projection(aspect) * scene.camera.view()).inverse();
    let unproject = |x: f64, y: f64, z: f64| {
        let p = inverse * DVec4::new(x, y, z, 1.0);
        p.truncate() / p.w
    };
    let l = Light::new([light.x, light.y, light.z, 1.0]).unwrap();
    let mut out = Vec::with_capacity((W * H) as usize);
    for py in 0..H {
        for px in 0..W {
            let x = (px as f64 + 0.5) / W as f64 * 2.0 - 1.0;
            let y = 1.0 - (py as f64 + 0.5) / H as f64 * 2.0;
            let o = unproject(x, y, 0.0);
            let dir = (unproject(x, y, 0.5) - o).normalize();
            let Some((t, tri)) = first_hit(&mesh, o, dir, 0.0) else {
                out.push(None);
                continue;
            };
            let p = o + dir * t;
            let mut n = mesh.face_normal(tri).normalize();
            if n.dot(dir) > 0.0 {
                n = -n;
            }
            if n.dot(light - p) <= 1e-9 {
                out.push(None);
                continue;
            }
            out.push(Some(in_shadow_ignoring(
                &mesh,
                &l,
                p + n * 1e-6,
                1e-6,
                &ignored,
            )));
        }
    }
    out
}

/// Pixels next to a pixel with a different reference value (the edge band).
fn edge_band(reference: &[Option<bool>]) -> Vec<bool> {
    let at = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= W as i64 || y >= H as i64 {
            None
        } else {
            Some(reference[(y * W as i64 + x) as usize])
        }
    };
    (0..(W * H) as i64)
        .map(|k| {
            let (x, y) = (k % W as i64, k / W as i64);
            let me = reference[k as usize];
            (-1..=1).any(|dy| (-1..=1).any(|dx| at(x + dx, y + dy).is_some_and(|v| v != me)))
        })
        .collect()
}

struct Agreement {
    fraction: f64,
    counted: usize,
    shadowed: usize,
    /// Pixels lit in the reference that the GPU darkens at all (below 99 % of the
    /// unshadowed lux; paraboloid maps only): acne, seams and self-shadowing.
    darkened: usize,
}

/// Compares the GPU's shadows of luminaire `index` with the reference: the shadow-volume
/// mask bit, or (paraboloid) the lux falling below half the unshadowed lux.
fn agreement(gpu: &Gpu, scene: &Scene, index: usize, shadows: &ShadowSettings) -> Agreement {
    let renderer = Renderer::new(gpu);
    let uploaded = renderer.upload(gpu, scene);
    let settings = |shadows: ShadowSettings| RenderSettings {
        width: W,
        height: H,
        read_hdr: true,
        shadows,
        ..RenderSettings::from_display(&DisplayEntry::default())
    };
    let shadowed = renderer
        .render(gpu, &uploaded, &scene.camera, &settings(shadows.clone()))
        .unwrap();
    let plain = renderer
        .render(
            gpu,
            &uploaded,
            &scene.camera,
            &settings(ShadowSettings::none()),
        )
        .unwrap();
    let hdr = shadowed.hdr.unwrap();
    let lux_plain: Vec<f32> = plain.hdr.unwrap().iter().map(|p| p[3]).collect();
    let layer = (W * H) as usize;
    let gpu_shadow = |k: usize| -> Option<bool> {
        match shadows.technique {
            ShadowTechnique::Volumes => Some(shadowed.shadow_mask[index * layer + k] != 0),
            _ => (lux_plain[k] > 0.1).then(|| hdr[k][3] < 0.5 * lux_plain[k]),
        }
    };
    let want = reference(scene, index);
    let band = edge_band(&want);
    let (mut counted, mut agree, mut in_shadow, mut darkened) = (0, 0, 0, 0);
    for k in 0..want.len() {
        let (Some(w), false) = (want[k], band[k]) else {
            continue;
        };
        let Some(g) = gpu_shadow(k) else { continue };
        counted += 1;
        agree += (g == w) as usize;
        in_shadow += w as usize;
        darkened += (!w && hdr[k][3] < 0.99 * lux_plain[k]) as usize;
    }
    Agreement {
        fraction: agree as f64 / counted.max(1) as f64,
        counted,
        shadowed: in_shadow,
        darkened,
    }
}

fn assert_agrees(name: &str, a: &Agreement) {
    eprintln!(
        "{name}: {:.3} % of {} pixels agree ({} in shadow)",
        100.0 * a.fraction,
        a.counted,
        a.shadowed
    );
    assert!(
        a.counted > 3000,
        "{name}: only {} pixels compared",
        a.counted
    );
    assert!(
        a.shadowed > 200 && a.counted - a.shadowed > 200,
        "{name}: the view must hold both shadow and light ({} of {})",
        a.shadowed,
        a.counted
    );
    assert!(a.fraction >= 0.995, "{name}: {:.4}", a.fraction);
}

fn volumes(test: VolumeTest, method: SilhouetteMethod) -> ShadowSettings {
    ShadowSettings {
        volume_test: test,
        silhouette: method,
        ..ShadowSettings::with(ShadowTechnique::Volumes)
    }
}

fn paraboloid() -> ShadowSettings {
    ShadowSettings {
        map_size: 2048,
        tessellation_m: 0.1,
        ..ShadowSettings::with(ShadowTechnique::Paraboloid)
    }
}

fn box_on_floor() -> Scene {
    let cube = goniolight::geometry::generate::cuboid(
        DVec3::new(-0.5, -0.5, 0.0),
        DVec3::new(0.5, 0.5, 1.0),
    );
    scene(
        &[floor(10.0), cube],
        vec![downlight(DVec3::new(2.0, 1.2, 2.2))],
        Camera::perspective(DVec3::new(4.0, -5.0, 4.5), DVec3::new(-0.5, 0.5, 0.0), 60.0),
    )
}

fn sphere_over_plane() -> Scene {
    scene(
        &[floor(10.0), sphere(DVec3::new(0.0, 0.0, 1.2), 0.6, 24, 48)],
        vec![downlight(DVec3::new(0.5, 0.3, 3.5))],
        Camera::perspective(DVec3::new(3.0, -4.0, 3.5), DVec3::new(0.0, 0.0, 0.3), 55.0),
    )
}

#[test]
fn box_on_a_floor_volumes_and_paraboloid_match_the_ray_cast() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let s = box_on_floor();
    for method in [SilhouetteMethod::Brute, SilhouetteMethod::Hextree] {
        for test in [VolumeTest::Zpass, VolumeTest::Zfail, VolumeTest::Auto] {
            let a = agreement(&gpu, &s, 0, &volumes(test, method));
            assert_agrees(&format!("box volumes {test:?} {method:?}"), &a);
        }
    }
    assert_agrees("box paraboloid", &agreement(&gpu, &s, 0, &paraboloid()));
}

#[test]
fn sphere_over_a_plane_volumes_and_paraboloid_match_the_ray_cast() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let s = sphere_over_plane();
    assert_agrees(
        "sphere volumes",
        &agreement(
            &gpu,
            &s,
            0,
            &volumes(VolumeTest::Auto, SilhouetteMethod::Hextree),
        ),
    );
    assert_agrees("sphere paraboloid", &agreement(&gpu, &s, 0, &paraboloid()));
}

#[test]
fn camera_inside_a_shadow_volume_needs_z_fail() {
    let Some(gpu) = gpu_common::gpu() else { return };
    // The camera stands under a slab lit from above, so its near plane is in the slab's
    // shadow volume: z-pass counts wrong there, z-fail (chosen by the test) is right.
    let slab = goniolight::geometry::generate::cuboid(
        DVec3::new(-1.5, -1.5, 1.6),
        DVec3::new(1.5, 1.5, 1.8),
    );
    let s = scene(
        &[floor(12.0), slab],
        vec![downlight(DVec3::new(0.3, 0.2, 3.5))],
        Camera::perspective(DVec3::new(0.0, 0.0, 1.0), DVec3::new(4.0, 1.0, 0.0), 70.0),
    );
    let renderer = Renderer::new(&gpu);
    let uploaded = renderer.upload(&gpu, &s);
    let geometry = uploaded.volume_geometry(&gpu).unwrap();
    let p = s.luminaires[0].position;
    let light = Light::new([p.x, p.y, p.z, 1.0]).unwrap();
    let near = s.camera.near_rectangle(W as f64 / H as f64);
    assert!(geometry.zfail(&light, VolumeTest::Auto, near));
    let auto = agreement(
        &gpu,
        &s,
        0,
        &volumes(VolumeTest::Auto, SilhouetteMethod::Brute),
    );
    assert_agrees("camera in shadow, auto", &auto);
    let zpass = agreement(
        &gpu,
        &s,
        0,
        &volumes(VolumeTest::Zpass, SilhouetteMethod::Brute),
    );
    eprintln!("forced z-pass agrees on {:.1} %", 100.0 * zpass.fraction);
    assert!(zpass.fraction < 0.9, "z-pass should fail here");
}

#[test]
fn furnished_room_shadows_of_every_luminaire_match_the_ray_cast() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let room = Scene::load(&root().join("assets/scenes/furnished_room.toml")).unwrap();
    let mut shadowed = 0;
    for index in 0..room.luminaires.len() {
        let a = agreement(
            &gpu,
            &room,
            index,
            &volumes(VolumeTest::Auto, SilhouetteMethod::Hextree),
        );
        let name = &room.luminaires[index].name;
        eprintln!(
            "room volumes {name}: {:.3} % of {}",
            100.0 * a.fraction,
            a.counted
        );
        assert!(a.fraction >= 0.995 && a.counted > 3000, "{name}");
        shadowed += a.shadowed;
        // Paraboloid maps, one luminaire at a time (the image sums every luminaire), with
        // the default settings a user gets and with finer maps.
        let mut single = room.clone();
        single.luminaires = vec![room.luminaires[index].clone()];
        for (settings, what) in [
            (ShadowSettings::with(ShadowTechnique::Paraboloid), "default"),
            (paraboloid(), "fine"),
        ] {
            let p = agreement(&gpu, &single, 0, &settings);
            eprintln!(
                "room paraboloid {what} {name}: {:.3} % of {}, {} darkened",
                100.0 * p.fraction,
                p.counted,
                p.darkened
            );
            assert!(p.fraction >= 0.995 && p.counted > 1000, "{what} {name}");
        }
    }
    assert!(
        shadowed > 2000,
        "the room's furniture casts shadows: {shadowed} pixels"
    );
}

/// A luminaire 5 cm under a ceiling, its housing (a 20 cm box from 1 cm above the light
/// centre up to the ceiling, tied to it by `housing`) between: the ceiling is seen at
/// grazing angles near the seam of the two paraboloids, and only the housing could shadow
/// it. No technique may darken a ceiling pixel the ray cast finds lit, and the housing
/// shadows nothing of its own light (CPU twin included).
#[test]
fn downlight_under_a_ceiling_leaves_the_ceiling_unshadowed() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let mut ceiling = floor(12.0);
    for p in &mut ceiling.positions {
        p.z = 3.0;
    }
    for t in &mut ceiling.triangles {
        t.swap(1, 2);
    }
    let centre = DVec3::new(0.3, -0.2, 2.95);
    let housing = goniolight::geometry::generate::cuboid(
        centre + DVec3::new(-0.1, -0.1, 0.01),
        centre + DVec3::new(0.1, 0.1, 0.05),
    );
    let mut light = downlight(centre);
    light.housing = Some(Housing {
        name: "housing".into(),
        meshes: vec![2],
    });
    let s = scene(
        &[floor(12.0), ceiling, housing],
        vec![light],
        Camera::perspective(DVec3::new(-2.5, -3.0, 1.6), DVec3::new(0.5, 0.5, 3.0), 80.0),
    );
    for (name, settings) in [
        ("default", ShadowSettings::with(ShadowTechnique::Paraboloid)),
        ("fine", paraboloid()),
        (
            "volumes",
            volumes(VolumeTest::Auto, SilhouetteMethod::Hextree),
        ),
    ] {
        let a = agreement(&gpu, &s, 0, &settings);
        eprintln!(
            "ceiling {name}: {} of {} pixels darkened, {:.3} % agree",
            a.darkened,
            a.counted,
            100.0 * a.fraction
        );
        assert!(a.counted > 5000, "{name}: the view sees the ceiling lit");
        assert_eq!(a.shadowed, 0, "{name}: nothing shadows the ceiling");
        assert_eq!(a.darkened, 0, "{name}: the lit ceiling is darkened");
    }
    // The CPU twin: a ceiling point 30 cm from the light gets its unshadowed lux.
    let point = [SurfacePoint {
        position: centre + DVec3::new(0.3, 0.0, 0.05),
        normal: DVec3::NEG_Z,
    }];
    let casters = s.caster_mesh();
    let plain = illuminance_cpu_in_scene(&s.luminaires, None, &point, Interp::CatmullRom);
    let ignored = s.ignored_per_luminaire();
    let got = illuminance_cpu_in_scene(
        &s.luminaires,
        Some(&Occluders {
            ignored: &ignored,
            ..Occluders::solid(&casters)
        }),
        &point,
        Interp::CatmullRom,
    );
    let blocked = illuminance_cpu_in_scene(
        &s.luminaires,
        Some(&Occluders::solid(&casters)),
        &point,
        Interp::CatmullRom,
    );
    assert!(plain[0] > 1.0, "the light reaches the ceiling: {plain:?}");
    assert_eq!(got, plain);
    assert_eq!(blocked, [0.0], "without the tie the housing shadows it");
}

#[test]
fn debug_view_draws_volumes_yellow_and_silhouettes_pink() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let s = box_on_floor();
    let renderer = Renderer::new(&gpu);
    let uploaded = renderer.upload(&gpu, &s);
    let render = |show: bool| {
        let settings = RenderSettings {
            width: W,
            height: H,
            shadows: ShadowSettings {
                show_volumes: show,
                show_silhouettes: show,
                ..volumes(VolumeTest::Auto, SilhouetteMethod::Brute)
            },
            ..RenderSettings::from_display(&DisplayEntry::default())
        };
        renderer
            .render(&gpu, &uploaded, &s.camera, &settings)
            .unwrap()
            .image
    };
    let (plain, debug) = (render(false), render(true));
    let (mut pink, mut yellower) = (0, 0);
    for (a, b) in plain.pixels().zip(debug.pixels()) {
        // Silhouette edges: opaque pink (linear 1, 0.2, 0.75 in an sRGB target).
        pink += (b[0] == 255 && b[1] == 124 && b[2] == 225) as usize;
        // Volumes: blended toward yellow, so red and green rise more than blue.
        let gain = |c: usize| b[c] as i32 - a[c] as i32;
        yellower += (gain(0) > 2 && gain(1) > 2 && gain(2) < gain(1)) as usize;
    }
    eprintln!("pink {pink}, yellower {yellower} of {}", W * H);
    assert!(pink > 50, "{pink}");
    assert!(yellower > 1000, "{yellower}");
}

/// Floor points on a grid of `n` × `n` over `[-h, h]²`, normal +Z.
fn floor_grid(n: usize, h: f64) -> Vec<SurfacePoint> {
    let step = 2.0 * h / n as f64;
    (0..n * n)
        .map(|k| SurfacePoint {
            position: DVec3::new(
                -h + step * ((k % n) as f64 + 0.5),
                -h + step * ((k / n) as f64 + 0.5),
                0.0,
            ),
            normal: DVec3::Z,
        })
        .collect()
}

/// Grid points whose visibility of some light differs from a neighbour's (the edge band).
fn grid_edge_band(visible: &[Vec<bool>], n: usize) -> Vec<bool> {
    (0..n * n)
        .map(|k| {
            let (x, y) = ((k % n) as i64, (k / n) as i64);
            visible.iter().any(|layer| {
                (-1..=1).any(|dy: i64| {
                    (-1..=1).any(|dx: i64| {
                        let (u, v) = (x + dx, y + dy);
                        (0..n as i64).contains(&u)
                            && (0..n as i64).contains(&v)
                            && layer[(v * n as i64 + u) as usize] != layer[k]
                    })
                })
            })
        })
        .collect()
}

#[test]
fn illuminance_at_points_respects_shadows_on_gpu_and_cpu() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let mut s = box_on_floor();
    // A second luminaire on the other side: points in one shadow keep the other's light.
    s.luminaires.push(downlight(DVec3::new(-1.8, -0.9, 2.6)));
    let n = 60;
    let points = floor_grid(n, 3.0);
    let casters = s.caster_mesh();
    let plain = illuminance_cpu_in_scene(&s.luminaires, None, &points, Interp::CatmullRom);
    let want = illuminance_cpu_in_scene(
        &s.luminaires,
        Some(&Occluders::solid(&casters)),
        &points,
        Interp::CatmullRom,
    );
    let positions: Vec<DVec3> = s.luminaires.iter().map(|l| l.position).collect();
    let visible = point_visibility(&Occluders::solid(&casters), &positions, &points);
    let band = grid_edge_band(&visible, n);
    let shadowed = (0..points.len())
        .filter(|&k| want[k] < 0.9 * plain[k] && want[k] > 0.05 * plain[k])
        .count();
    assert!(
        shadowed > 100,
        "only {shadowed} points in one light's shadow"
    );
    let under_box = points
        .iter()
        .position(|p| p.position.truncate().length() < 0.1);
    assert_eq!(want[under_box.unwrap()], 0.0, "under the box is dark");

    let renderer = Renderer::new(&gpu);
    let uploaded = renderer.upload(&gpu, &s);
    let probe = IlluminanceProbe::new(&gpu, LightModel::Ldt(Interp::CatmullRom));
    for settings in [
        ShadowSettings::with(ShadowTechnique::Volumes),
        paraboloid(),
        ShadowSettings::with(ShadowTechnique::None),
    ] {
        let got = probe
            .run_in_scene(&gpu, &uploaded, &points, &settings)
            .unwrap();
        let reference = match settings.technique {
            ShadowTechnique::None => &plain,
            _ => &want,
        };
        let (mut counted, mut agree) = (0, 0);
        for k in 0..points.len() {
            if band[k] && settings.technique == ShadowTechnique::Paraboloid {
                continue;
            }
            counted += 1;
            agree += ((got[k] - reference[k]).abs() <= 0.005 * reference[k].max(1.0)) as usize;
        }
        let fraction = agree as f64 / counted as f64;
        eprintln!(
            "points, {:?}: {:.2} % of {counted} within 0.5 %",
            settings.technique,
            100.0 * fraction
        );
        let goal = if settings.technique == ShadowTechnique::Paraboloid {
            0.995
        } else {
            1.0
        };
        assert!(fraction >= goal, "{:?}: {fraction}", settings.technique);
    }
}

#[test]
fn illuminance_command_shadows_points_behind_an_occluder() {
    let Some(_gpu) = gpu_common::gpu() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut mesh = floor(10.0);
    goniolight::geometry::generate::push_box(
        &mut mesh,
        DVec3::new(-0.5, -0.5, 0.0),
        DVec3::new(0.5, 0.5, 1.0),
    );
    std::fs::write(
        dir.path().join("box.obj"),
        goniolight::geometry::obj::to_obj_string(&mesh, "box on a floor"),
    )
    .unwrap();
    let scene = dir.path().join("box.toml");
    std::fs::write(
        &scene,
        format!(
            "[[model]]\npath = \"box.obj\"\nup = \"z\"\n[[luminaire]]\nfile = {:?}\nposition = [2.0, 1.2, 2.2]\n[camera]\nposition = [4, -5, 4.5]\nlook_at = [0, 0, 0]\n",
            luminaire("eulumdat-plot/sample_06_isym1.ldt").display().to_string()
        ),
    )
    .unwrap();
    // Behind the box as seen from the luminaire, then in the open.
    let points = "-1.0 -0.6 0 0 0 1\n3.0 2.0 0 0 0 1\n";
    let run = |flags: &[&str]| -> Vec<f64> {
        let mut args = vec!["illuminance", scene.to_str().unwrap()];
        args.extend(flags);
        let (code, out, err) = common::run_cli(&args, points);
        assert_eq!(code, 0, "{flags:?}: {err}");
        out.lines().map(|l| l.parse().unwrap()).collect()
    };
    let open = run(&["--shadows", "none"]);
    assert!(open[0] > 10.0 && open[1] > 10.0, "{open:?}");
    for flags in [
        vec![],
        vec!["--shadows", "volumes"],
        vec!["--shadows", "paraboloid"],
        vec!["--cpu"],
        vec!["--cpu", "--shadows", "volumes"],
    ] {
        let lux = run(&flags);
        assert!(lux[0] < 1e-3, "{flags:?}: behind the box {} lx", lux[0]);
        assert!(
            (lux[1] - open[1]).abs() <= 0.005 * open[1],
            "{flags:?}: in the open {} lx vs {}",
            lux[1],
            open[1]
        );
    }
    let (code, _, err) = common::run_cli(
        &["illuminance", scene.to_str().unwrap(), "--shadows", "maps"],
        points,
    );
    assert_eq!(code, 2, "{err}");
}
