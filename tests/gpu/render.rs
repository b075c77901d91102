//! The renderer on the GPU (lavapipe in CI) against physics and the CPU references:
//! direct illuminance at points (the renderer's WGSL lighting code) = I · cos θ / d²; an
//! illuminance-mode image of a floor under one luminaire = the analytic value per pixel;
//! tone mapping = its CPU formulas; the bundled scenes = their reference images (FLIP).

use crate::common;

use crate::gpu_common;

use std::path::{Path, PathBuf};

use common::{luminaire, root};
use glam::{DVec3, Vec3};
use goniolight::geometry::generate::XorShift;
use goniolight::gpu::Gpu;
use goniolight::photometry::{Interp, Luminaire};
use goniolight::render::gpu_scene::GpuLights;
use goniolight::render::illuminance::{illuminance_cpu, IlluminanceProbe, SurfacePoint};
use goniolight::render::tonemap::linear_to_srgb;
use goniolight::render::{LightModel, RenderSettings, RenderedFrame, Renderer, ShadowSettings};
use goniolight::scene::placement::aim_frame;
use goniolight::scene::{
    Camera, Material, Mode, Palette, PlacedLuminaire, Scene, SceneMesh, Tonemap,
};

/// Two luminaires, one asymmetric and tilted, one rotationally symmetric.
fn test_luminaires() -> Vec<PlacedLuminaire> {
    let a = Luminaire::load(&luminaire("eulumdat-luminance/sample_07.ldt")).unwrap();
    let mut l1 = PlacedLuminaire::new("asymmetric", a, DVec3::new(0.3, -0.2, 2.5));
    l1.rotation = aim_frame(Some(DVec3::new(0.2, 0.1, -1.0)), 30.0);
    l1.multiplier = 0.8;
    let b = Luminaire::load(&luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    let l2 = PlacedLuminaire::new("round", b, DVec3::new(-1.5, 1.0, 2.0));
    vec![l1, l2]
}

fn random_points(n: usize, seed: u64) -> Vec<SurfacePoint> {
    let mut rng = XorShift::new(seed);
    let mut r = |lo: f64, hi: f64| lo + (hi - lo) * rng.next_f64();
    (0..n)
        .map(|_| SurfacePoint {
            position: DVec3::new(r(-4.0, 4.0), r(-4.0, 4.0), r(-0.5, 1.5)),
            normal: DVec3::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-0.2, 1.0)),
        })
        .collect()
}

#[test]
fn gpu_illuminance_at_points_equals_the_cpu_reference_within_half_a_percent() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let lums = test_luminaires();
    let lights = GpuLights::new(&gpu, &lums);
    let points = random_points(10_000, 3);
    for interp in Interp::ALL {
        let probe = IlluminanceProbe::new(&gpu, LightModel::Ldt(interp));
        let got = probe.run(&gpu, &lights, &points).unwrap();
        let want: Vec<f64> = points
            .iter()
            .map(|p| illuminance_cpu(&lums, p, interp))
            .collect();
        let e_max = want.iter().cloned().fold(0.0, f64::max);
        assert!(e_max > 10.0);
        let mut worst = 0.0f64;
        for (g, w) in got.iter().zip(&want) {
            // Relative error, with a floor at 1e-4 · E_max where E is tiny.
            let err = (g - w).abs() / w.max(1e-4 * e_max);
            worst = worst.max(err);
        }
        assert!(worst <= 5e-3, "{interp:?}: worst relative error {worst:e}");
        eprintln!("{interp:?}: worst relative GPU/CPU illuminance difference {worst:.2e}");
    }
}

/// A square floor of `size` metres at z = 0, seen from straight above.
fn floor_scene(luminaires: Vec<PlacedLuminaire>, size: f32) -> Scene {
    Scene::in_code(
        "floor",
        vec![uv_floor(size)],
        vec![Material::default()],
        luminaires,
        Camera::top_down(DVec3::ZERO, size as f64, 10.0),
    )
}

fn render(gpu: &Gpu, scene: &Scene, settings: &RenderSettings) -> RenderedFrame {
    let renderer = Renderer::new(gpu);
    let uploaded = renderer.upload(gpu, scene);
    renderer
        .render(gpu, &uploaded, &scene.camera, settings)
        .unwrap()
}

#[test]
fn illuminance_image_of_a_floor_matches_the_analytic_value_per_pixel() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let lum = test_luminaires().remove(0);
    let size = 8.0;
    let scene = floor_scene(vec![lum.clone()], size);
    let (w, h) = (96u32, 96u32);
    let hdr = floor_hdr(&gpu, &scene, w);
    let flux = lum.luminaire.distribution.lamp_flux_lm();
    // The analytic value from the file's distribution (f64), not from the GPU texture.
    let analytic = |p: DVec3| {
        let to_light = lum.position - p;
        let d2 = to_light.length_squared();
        let cos = to_light.z / d2.sqrt();
        let local = lum.rotation.transpose() * -to_light;
        let i = lum
            .luminaire
            .distribution
            .sample_dir(local, Interp::CatmullRom)
            * flux
            / 1000.0
            * lum.multiplier;
        i * cos / d2
    };
    let mut expected = Vec::new();
    for py in 0..h {
        for px in 0..w {
            expected.push(analytic(floor_point(px, py, w, size as f64)));
        }
    }
    let e_max = expected.iter().cloned().fold(0.0, f64::max);
    assert!(e_max > 10.0, "{e_max}");
    let mut checked = 0;
    for (k, (px, want)) in hdr.iter().zip(&expected).enumerate() {
        let got = px[3] as f64;
        if *want >= 0.01 * e_max {
            let rel = (got - want).abs() / want;
            assert!(rel <= 0.01, "pixel {k}: {got} lx vs analytic {want} lx");
            checked += 1;
        } else {
            assert!(
                (got - want).abs() <= 1e-4 * e_max,
                "pixel {k}: {got} vs {want}"
            );
        }
        // Diffuse only (Kd 0.6): luminance = Kd / π · E.
        let l = 0.6 / std::f64::consts::PI * got;
        assert!((px[1] as f64 - l).abs() <= 1e-4 * l.max(1e-3), "pixel {k}");
    }
    assert!(checked > (w * h) as usize / 4, "{checked}");
}

fn srgb(c: Vec3) -> [u8; 3] {
    [
        linear_to_srgb(c.x),
        linear_to_srgb(c.y),
        linear_to_srgb(c.z),
    ]
}

#[test]
fn tone_mapping_on_the_gpu_equals_its_cpu_formulas() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = Scene::load(&root().join("assets/scenes/furnished_room.toml")).unwrap();
    let renderer = Renderer::new(&gpu);
    let uploaded = renderer.upload(&gpu, &scene);
    for (mode, tonemap, palette, steps) in [
        (Mode::Shaded, Tonemap::Reinhard, Palette::Rainbow, 0),
        (Mode::Shaded, Tonemap::Exposure, Palette::Rainbow, 0),
        (Mode::Illuminance, Tonemap::Reinhard, Palette::Rainbow, 0),
        (Mode::Illuminance, Tonemap::Reinhard, Palette::Viridis, 6),
        (Mode::Illuminance, Tonemap::Reinhard, Palette::Cividis, 0),
    ] {
        let mut s = RenderSettings::from_display(&scene.display);
        (s.width, s.height, s.mode, s.tonemap, s.read_hdr) = (200, 120, mode, tonemap, true);
        (s.palette, s.steps) = (palette, steps);
        let frame = renderer.render(&gpu, &uploaded, &scene.camera, &s).unwrap();
        let hdr = frame.hdr.as_ref().unwrap();
        // The legend is a panel beside the view in illuminance mode, never over it.
        let width = frame.image.width();
        assert_eq!(width > 200, mode == Mode::Illuminance, "{width}");
        let (mut bad, mut total) = (0, 0);
        for y in 0..120u32 {
            for x in 0..200 {
                let want = srgb(
                    frame
                        .tone
                        .map_pixel(hdr[(y * 200 + x) as usize], s.background),
                );
                let got = frame.image.get_pixel(x, y).0;
                total += 1;
                if (0..3).any(|c| (got[c] as i32 - want[c] as i32).abs() > 1) {
                    bad += 1;
                }
            }
        }
        assert!(
            bad * 1000 <= total,
            "{mode:?} {tonemap:?} {palette:?}: {bad} of {total} pixels differ"
        );
        if steps > 0 {
            // Hard steps: at most `steps` colours over the surfaces.
            let colours: std::collections::HashSet<[u8; 4]> = (0..120u32)
                .flat_map(|y| (0..200u32).map(move |x| (x, y)))
                .filter(|&(x, y)| hdr[(y * 200 + x) as usize][3] >= 0.0)
                .map(|(x, y)| frame.image.get_pixel(x, y).0)
                .collect();
            assert!(colours.len() <= steps as usize, "{}", colours.len());
        }
        // The statistics pass equals a CPU pass over the same HDR values.
        let lux: Vec<f64> = hdr
            .iter()
            .filter(|p| p[3] >= 0.0)
            .map(|p| p[3] as f64)
            .collect();
        let mean = lux.iter().sum::<f64>() / lux.len() as f64;
        assert_eq!(frame.stats.pixels as usize, lux.len());
        assert!((frame.stats.mean_lux - mean).abs() <= 1e-4 * mean);
        let log_avg = (hdr
            .iter()
            .filter(|p| p[3] >= 0.0)
            .map(|p| {
                (1e-4 + Vec3::new(p[0], p[1], p[2]).dot(Vec3::new(0.2126, 0.7152, 0.0722)) as f64)
                    .ln()
            })
            .sum::<f64>()
            / lux.len() as f64)
            .exp();
        assert!((frame.stats.log_average_luminance - log_avg).abs() <= 1e-3 * log_avg);
        if mode == Mode::Illuminance {
            // Percentiles by nearest rank over the same pixels, and a nice scale top just
            // above the 95th percentile.
            let mut sorted = lux.clone();
            sorted.sort_by(f64::total_cmp);
            let rank = |q: f64| sorted[(q * sorted.len() as f64).ceil() as usize - 1];
            let p = frame.stats.lux.unwrap();
            assert_eq!(
                (p.median, p.p95, p.p99),
                (rank(0.5), rank(0.95), rank(0.99))
            );
            assert_eq!(p.max, sorted[sorted.len() - 1]);
            let top = frame.tone.lux_max;
            assert!(
                top >= p.p95 && top < 2.0 * p.p95.max(1.0),
                "{top} vs {}",
                p.p95
            );
            let labels = frame.tone.legend_labels();
            let step = labels[1] - labels[0];
            assert_eq!(
                goniolight::render::tonemap::nice_ceil(step),
                step,
                "{labels:?}"
            );
        }
    }
}

fn reference_path(name: &str) -> PathBuf {
    root().join("tests/data/images").join(format!("{name}.png"))
}

/// The FLIP error map of `actual` against the reference image `name`.
fn flip_error(name: &str, actual: &image::RgbImage) -> nv_flip::FlipImageFloat {
    let reference = reference_path(name);
    let want = image::open(&reference)
        .unwrap_or_else(|e| {
            panic!(
                "{}: {e} (GONIOLIGHT_BLESS=1 writes it)",
                reference.display()
            )
        })
        .to_rgb8();
    assert_eq!(want.dimensions(), actual.dimensions(), "{name}");
    let (w, h) = actual.dimensions();
    nv_flip::flip(
        nv_flip::FlipImageRgb8::with_data(w, h, want.as_raw()),
        nv_flip::FlipImageRgb8::with_data(w, h, actual.as_raw()),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    )
}

/// Checks `actual` against the reference image `name` (mean FLIP ≤ `tolerance`); writes
/// the reference with `GONIOLIGHT_BLESS=1`, and `-actual`/`-difference` PNGs on failure.
fn compare_with_reference(name: &str, actual: &image::RgbaImage, tolerance: f32) {
    let rgb = image::DynamicImage::ImageRgba8(actual.clone()).to_rgb8();
    if std::env::var("GONIOLIGHT_BLESS").as_deref() == Ok("1") {
        rgb.save(reference_path(name)).unwrap();
        eprintln!("blessed {name}");
        return;
    }
    let error = flip_error(name, &rgb);
    let mean = nv_flip::FlipPool::from_image(&error).mean();
    eprintln!("{name}: mean FLIP {mean:.4}");
    if mean > tolerance {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("image-tests");
        std::fs::create_dir_all(&dir).unwrap();
        rgb.save(dir.join(format!("{name}-actual.png"))).unwrap();
        let diff = error.apply_color_lut(&nv_flip::magma_lut());
        let (w, h) = rgb.dimensions();
        image::RgbImage::from_raw(w, h, diff.to_vec())
            .unwrap()
            .save(dir.join(format!("{name}-difference.png")))
            .unwrap();
        panic!(
            "{name}: mean FLIP {mean:.4} > {tolerance}; see {}",
            dir.display()
        );
    }
}

#[test]
fn bundled_scenes_match_their_reference_images() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let renderer = Renderer::new(&gpu);
    for (file, mode) in [
        ("furnished_room", Mode::Shaded),
        ("furnished_room", Mode::Illuminance),
        ("box_room", Mode::Illuminance),
        ("effect_stage", Mode::Shaded),
    ] {
        let scene = Scene::load(&root().join(format!("assets/scenes/{file}.toml"))).unwrap();
        let uploaded = renderer.upload(&gpu, &scene);
        let mut s = RenderSettings::from_display(&scene.display);
        (s.width, s.height, s.mode) = (320, 180, mode);
        let frame = renderer.render(&gpu, &uploaded, &scene.camera, &s).unwrap();
        let name = format!(
            "{file}-{}",
            if mode == Mode::Shaded {
                "shaded"
            } else {
                "illuminance"
            }
        );
        compare_with_reference(&name, &frame.image, 0.05);
    }
}

#[test]
fn the_image_test_fails_on_a_visibly_different_image() {
    // The comparison itself must be able to fail: a darker image is far over tolerance.
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = Scene::load(&root().join("assets/scenes/box_room.toml")).unwrap();
    let renderer = Renderer::new(&gpu);
    let uploaded = renderer.upload(&gpu, &scene);
    let mut s = RenderSettings::from_display(&scene.display);
    (s.width, s.height, s.mode, s.lux_max) = (320, 180, Mode::Illuminance, Some(1000.0));
    let frame = renderer.render(&gpu, &uploaded, &scene.camera, &s).unwrap();
    let rgb = image::DynamicImage::ImageRgba8(frame.image).to_rgb8();
    let mean = nv_flip::FlipPool::from_image(&flip_error("box_room-illuminance", &rgb)).mean();
    assert!(
        mean > 0.05,
        "a different lux scale passed the image test: FLIP {mean}"
    );
}

#[test]
fn render_cli_writes_an_exr_of_lux_that_the_illuminance_command_reproduces() {
    let Some(_gpu) = gpu_common::gpu() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let scene = common::box_room_scene(
        dir.path(),
        "floor",
        "eulumdat-luminance/sample_07.ldt",
        "position = [2.5, 2.2, 2.9]\naim = [0.2, 0.1, -1]\n[camera]\nposition = [3, 2, 2.5]\nlook_at = [3, 2, 0]\nup = [0, 1, 0]\northographic_height = 4.0\n",
    );
    let (png, exr) = (dir.path().join("f.png"), dir.path().join("f.exr"));
    let (code, out, err) = common::run_cli(
        &[
            "render",
            scene.to_str().unwrap(),
            "--out",
            png.to_str().unwrap(),
            "--exr",
            exr.to_str().unwrap(),
            "--mode",
            "illuminance",
            "--width",
            "60",
            "--height",
            "40",
        ],
        "",
    );
    assert_eq!(code, 0, "{out}{err}");
    assert_eq!(image::open(&png).unwrap().width(), 60);
    let lux = image::open(&exr).unwrap().to_rgb32f();
    // Pixel centres of the orthographic view are floor points 0.1 m apart.
    let mut points = String::new();
    let mut pixels = Vec::new();
    for (j, i) in [(3, 5), (20, 30), (25, 41), (38, 58), (10, 17)] {
        let (x, y) = (0.05 + 0.1 * i as f64, 3.95 - 0.1 * j as f64);
        points.push_str(&format!("{x} {y} 0 0 0 1\n"));
        pixels.push(lux.get_pixel(i, j).0[0] as f64);
    }
    for flags in [vec!["--cpu"], vec![]] {
        let mut args = vec!["illuminance", scene.to_str().unwrap()];
        args.extend(flags.iter());
        let (code, out, err) = common::run_cli(&args, &points);
        assert_eq!(code, 0, "{err}");
        let values: Vec<f64> = out.lines().map(|l| l.parse().unwrap()).collect();
        assert_eq!(values.len(), pixels.len());
        for (v, p) in values.iter().zip(&pixels) {
            assert!(
                *v > 1.0 && (v - p).abs() <= 0.01 * v,
                "{flags:?}: {v} lx vs EXR {p}"
            );
        }
    }
}

#[test]
fn bench_render_json_has_the_contract_keys() {
    let Some(_gpu) = gpu_common::gpu() else {
        return;
    };
    let (code, out, err) = common::run_cli(
        &[
            "bench", "render", "--json", "--quick", "--frames", "1", "--rounds", "1", "--width",
            "64", "--height", "36",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 6);
    let tris: Vec<u64> = rows
        .iter()
        .map(|r| r["triangles"].as_u64().unwrap())
        .collect();
    assert_eq!(tris, [108, 108, 108, 1996, 1996, 1996]);
    for r in rows {
        assert!([1, 4, 7].contains(&r["lights"].as_u64().unwrap()));
        for k in [
            "point_ms",
            "bilinear_ms",
            "catmull_rom_ms",
            "catmull_rom_table_ms",
        ] {
            assert!(r[k].as_f64().unwrap() > 0.0, "{k}");
        }
    }
}

/// A floor with texture coordinates equal to x and y (so the tangent is +X).
fn uv_floor(size: f32) -> SceneMesh {
    let h = size / 2.0;
    let corners = [(-h, -h), (h, -h), (h, h), (-h, h)];
    SceneMesh {
        name: "floor".into(),
        positions: corners.iter().map(|&(x, y)| Vec3::new(x, y, 0.0)).collect(),
        normals: vec![Vec3::Z; 4],
        uvs: corners
            .iter()
            .map(|&(x, y)| glam::Vec2::new(x, y))
            .collect(),
        indices: vec![0, 1, 2, 0, 2, 3],
        material: 0,
    }
}

fn floor_hdr(gpu: &Gpu, scene: &Scene, w: u32) -> Vec<[f32; 4]> {
    let mut s = RenderSettings::from_display(&scene.display);
    (s.width, s.height, s.mode, s.read_hdr) = (w, w, Mode::Illuminance, true);
    render(gpu, scene, &s).hdr.unwrap()
}

/// World point at the centre of pixel (px, py) of the top-down floor view.
fn floor_point(px: u32, py: u32, w: u32, size: f64) -> DVec3 {
    DVec3::new(
        ((px as f64 + 0.5) / w as f64 - 0.5) * size,
        (0.5 - (py as f64 + 0.5) / w as f64) * size,
        0.0,
    )
}

#[test]
fn sixteen_luminaires_in_one_pass_sum_like_the_cpu_reference() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let files = [
        "eulumdat-plot/sample_06_isym1.ldt",
        "eulumdat-luminance/sample_07.ldt",
        "eulumdat-luminance/sample_04.ldt",
        "eulumdat-plot/sample_14_isym1.ldt",
    ];
    let mut lums = Vec::new();
    for k in 0..16 {
        let lum = Luminaire::load(&luminaire(files[k % 4])).unwrap();
        let (x, y) = ((k % 4) as f64 * 2.0 - 3.0, (k / 4) as f64 * 2.0 - 3.0);
        let mut l = PlacedLuminaire::new("l", lum, DVec3::new(x, y, 2.0 + 0.1 * k as f64));
        l.rotation = aim_frame(
            Some(DVec3::new(0.05 * k as f64 - 0.4, 0.2, -1.0)),
            20.0 * k as f64,
        );
        l.multiplier = 0.5 + 0.05 * k as f64;
        lums.push(l);
    }
    let size = 10.0;
    let scene = floor_scene(lums.clone(), size);
    let w = 64;
    let hdr = floor_hdr(&gpu, &scene, w);
    let mut worst = 0.0f64;
    for py in 0..w {
        for px in 0..w {
            let p = SurfacePoint {
                position: floor_point(px, py, w, size as f64),
                normal: DVec3::Z,
            };
            let want = illuminance_cpu(&lums, &p, Interp::CatmullRom);
            let got = hdr[(py * w + px) as usize][3] as f64;
            worst = worst.max((got - want).abs() / want.max(1.0));
        }
    }
    assert!(worst <= 0.005, "worst relative difference {worst:e}");
}

/// A translucent floor lit from below: the side in view shows τ/π × the illuminance on
/// its far side (CPU reference, per pixel) and receives no lux itself; an opaque one
/// shows nothing.
#[test]
fn a_translucent_surface_glows_with_the_light_on_its_far_side() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let mut lum = test_luminaires().remove(0);
    lum.position = DVec3::new(0.3, -0.2, -1.5);
    lum.rotation = aim_frame(Some(DVec3::new(0.1, 0.0, 1.0)), 0.0);
    let size = 6.0;
    let w = 48;
    for tau in [0.3f32, 0.0] {
        let mut scene = floor_scene(vec![lum.clone()], size);
        scene.materials[0].diffuse_transmittance = Vec3::splat(tau);
        let hdr = floor_hdr(&gpu, &scene, w);
        let mut checked = 0;
        for py in 0..w {
            for px in 0..w {
                let p = SurfacePoint {
                    position: floor_point(px, py, w, size as f64),
                    normal: -DVec3::Z,
                };
                let far_side = illuminance_cpu(std::slice::from_ref(&lum), &p, Interp::CatmullRom);
                let want = tau as f64 / std::f64::consts::PI * far_side;
                let got = hdr[(py * w + px) as usize];
                assert_eq!(got[3], 0.0, "no lux on the side in view");
                let rel = (got[1] as f64 - want).abs() / want.max(1e-3);
                assert!(
                    rel <= 0.01,
                    "τ {tau}: pixel {px},{py}: {} cd/m² vs {want}",
                    got[1]
                );
                checked += (want > 1.0) as usize;
            }
        }
        assert!(tau == 0.0 || checked > (w * w / 4) as usize, "{checked}");
    }
}

#[test]
fn normal_maps_tilt_the_shading_normal_but_not_the_illuminance() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let lum = test_luminaires().remove(1);
    let size = 8.0f64;
    // A normal map tilted 30° toward the tangent (+X, since u = x).
    let tilt = 30f64.to_radians();
    let n_tangent = DVec3::new(tilt.sin(), 0.0, tilt.cos());
    let enc = |c: f64| ((c * 0.5 + 0.5) * 255.0).round() as u8;
    let map = image::RgbaImage::from_pixel(
        4,
        4,
        image::Rgba([enc(n_tangent.x), enc(n_tangent.y), enc(n_tangent.z), 255]),
    );
    // The stored normal after 8-bit encoding, as the shader decodes it.
    let dec = |c: u8| c as f64 / 255.0 * 2.0 - 1.0;
    let n_world = DVec3::new(
        dec(map.get_pixel(0, 0)[0]),
        dec(map.get_pixel(0, 0)[1]),
        dec(map.get_pixel(0, 0)[2]),
    )
    .normalize();
    let mut scene = floor_scene(vec![lum.clone()], size as f32);
    scene.materials[0].normal_map = Some(std::sync::Arc::new(map));
    let w = 48;
    let hdr = floor_hdr(&gpu, &scene, w);
    let kd = 0.6 / std::f64::consts::PI;
    let mut checked = 0;
    for py in 0..w {
        for px in 0..w {
            let p = floor_point(px, py, w, size);
            let lux_geo = lum.illuminance_at(p, DVec3::Z, Interp::CatmullRom);
            let lux_tilted = lum.illuminance_at(p, n_world, Interp::CatmullRom);
            let got = hdr[(py * w + px) as usize];
            let tol = |v: f64| 2e-3 * v.max(1.0);
            assert!(
                (got[3] as f64 - lux_geo).abs() <= tol(lux_geo),
                "lux at {p}"
            );
            let l = kd * lux_tilted;
            assert!(
                (got[1] as f64 - l).abs() <= tol(l) * kd,
                "luminance at {p}: {} vs {l}",
                got[1]
            );
            if (lux_tilted - lux_geo).abs() > 0.05 * lux_geo {
                checked += 1;
            }
        }
    }
    // The tilt makes a visible difference on much of the floor.
    assert!(checked > (w * w / 4) as usize, "{checked}");
}

/// The RMS difference (grey levels) between `a` and `b` over `(x0, y0, w, h)`: moiré is
/// fine texture aliased into coarse false patterns, so it shows as a difference from a
/// properly filtered reference.
fn region_rms(
    a: &image::RgbImage,
    b: &image::RgbImage,
    (x0, y0, w, h): (u32, u32, u32, u32),
) -> f64 {
    let grey = |img: &image::RgbImage, x: u32, y: u32| {
        let p = img.get_pixel(x, y).0;
        (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0
    };
    let mut sum = 0.0;
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            sum += (grey(a, x, y) - grey(b, x, y)).powi(2);
        }
    }
    (sum / (w * h) as f64).sqrt()
}

/// `img` reduced by `k` in each direction, averaging k × k pixels in linear light.
fn box_down(img: &image::RgbaImage, k: u32) -> image::RgbImage {
    let lin = goniolight::scene::palette::srgb_to_linear;
    image::RgbImage::from_fn(img.width() / k, img.height() / k, |x, y| {
        let mut sum = [0f32; 3];
        for j in 0..k {
            for i in 0..k {
                let p = img.get_pixel(x * k + i, y * k + j).0;
                for c in 0..3 {
                    sum[c] += lin(p[c]);
                }
            }
        }
        image::Rgb(sum.map(|v| linear_to_srgb(v / (k * k) as f32)))
    })
}

/// Anti-aliasing (3 × 3 samples per pixel, what images get by default) against a
/// reference drawn at 4 × the resolution and averaged down: the supersampled image is
/// closer to it (FLIP 0.0100 against 0.0369 with one sample on lavapipe), and the brick
/// wall at 640 × 360 is within 1–1.2 grey levels RMS of it (0.5–0.7 over 4 × 4 pixels,
/// where moiré would show as a false coarse pattern; one sample: 4.5–4.8).
#[test]
fn supersampling_and_mipmaps_approach_a_supersampled_reference() {
    const GOAL_RMS: f64 = 4.0;
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = Scene::load(&root().join("assets/scenes/furnished_room.toml")).unwrap();
    let renderer = Renderer::new(&gpu);
    let uploaded = renderer.upload(&gpu, &scene);
    let (w, h) = (640, 360);
    let image = |scale: u32, supersample: u32| {
        let mut s = RenderSettings::from_display(&scene.display);
        (s.width, s.height, s.supersample) = (w * scale, h * scale, supersample);
        // One fixed exposure, so every image maps luminance to colour alike.
        (s.tonemap, s.exposure) = (Tonemap::Exposure, Some(0.11));
        renderer
            .render(&gpu, &uploaded, &scene.camera, &s)
            .unwrap()
            .image
    };
    let reference = box_down(&image(4, 1), 4);
    let rgb = |img: image::RgbaImage| image::DynamicImage::ImageRgba8(img).to_rgb8();
    let (plain, antialiased) = (rgb(image(1, 1)), rgb(image(1, 3)));
    let flip = |actual: &image::RgbImage| {
        let error = nv_flip::flip(
            nv_flip::FlipImageRgb8::with_data(w, h, reference.as_raw()),
            nv_flip::FlipImageRgb8::with_data(w, h, actual.as_raw()),
            nv_flip::DEFAULT_PIXELS_PER_DEGREE,
        );
        nv_flip::FlipPool::from_image(&error).mean()
    };
    let (f_plain, f_aa) = (flip(&plain), flip(&antialiased));
    // The brick wall left of the pictures and its far end, where it is seen at a slant.
    let walls = [(4, 40, 96, 140), (210, 60, 60, 90)];
    let rms = |img: &image::RgbImage| walls.map(|r| region_rms(img, &reference, r));
    let (rms_plain, rms_aa) = (rms(&plain), rms(&antialiased));
    // Moiré is a false coarse pattern: it stays when both are averaged over 4 × 4 pixels,
    // where the fine relief of the bricks (flattened by mipmapped normal maps) does not.
    let coarse = |img: &image::RgbImage| {
        box_down(&image::DynamicImage::ImageRgb8(img.clone()).to_rgba8(), 4)
    };
    let coarse_reference = coarse(&reference);
    let moire = |img: &image::RgbImage| {
        let c = coarse(img);
        walls.map(|(x, y, w, h)| region_rms(&c, &coarse_reference, (x / 4, y / 4, w / 4, h / 4)))
    };
    let (moire_plain, moire_aa) = (moire(&plain), moire(&antialiased));
    eprintln!("FLIP to the 16-sample reference: 1 sample {f_plain:.4}, 9 samples {f_aa:.4}");
    eprintln!("brick wall RMS difference to it (grey levels): 1 sample {rms_plain:.2?}, 9 samples {rms_aa:.2?}");
    eprintln!("over 4 × 4 pixels (moiré): 1 sample {moire_plain:.2?}, 9 samples {moire_aa:.2?}");
    assert!(f_aa < 0.75 * f_plain, "{f_aa} vs {f_plain}");
    for k in 0..walls.len() {
        assert!(rms_aa[k] <= GOAL_RMS, "wall {k}, 9 samples: {}", rms_aa[k]);
        assert!(
            moire_aa[k] <= GOAL_RMS / 4.0,
            "wall {k}, 9 samples: {}",
            moire_aa[k]
        );
        assert!(
            moire_plain[k] > moire_aa[k] * 3.0,
            "wall {k}: the test must see the difference"
        );
    }
}

/// Effect lights: a luminaire turning at 40°/s with four coloured C sectors, probed at
/// t = 1.3 s: the GPU's colour per point (the shader's `light_color`) = the CPU twin
/// (`color_toward`) × lux, and the sectors have turned by 52° from t = 0.
#[test]
fn effect_lights_turn_and_colour_their_c_sectors_on_the_gpu_like_the_cpu() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let mut light = test_luminaires().remove(1);
    light.spin_deg_per_s = 40.0;
    light.sector_colors = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
    ]
    .map(|c| {
        let c = DVec3::from_array(c);
        c / c.dot(DVec3::new(0.2126, 0.7152, 0.0722))
    })
    .to_vec();
    let mut rng = XorShift::new(7);
    let points: Vec<SurfacePoint> = (0..2000)
        .map(|_| {
            let (c, g) = (rng.next_f64() * 360.0, rng.next_f64() * 75.0);
            let dir = goniolight::photometry::angles_to_direction(c, g);
            SurfacePoint {
                position: light.position + dir * 2.0,
                normal: -dir,
            }
        })
        .collect();
    let probe = IlluminanceProbe::new(&gpu, LightModel::Ldt(Interp::CatmullRom));
    let renderer = Renderer::new(&gpu);
    let gpu_rgb = |l: &PlacedLuminaire| {
        let scene = floor_scene(vec![l.clone()], 1.0);
        let uploaded = renderer.upload(&gpu, &scene);
        probe
            .run_in_scene_rgb(&gpu, &uploaded, &points, &ShadowSettings::none())
            .unwrap()
    };
    let turned = light.at_time(1.3);
    let (at_start, at_1_3) = (gpu_rgb(&light.at_time(0.0)), gpu_rgb(&turned));
    let (mut checked, mut changed) = (0, 0);
    for (k, p) in points.iter().enumerate() {
        let dir = (p.position - turned.position).normalize();
        // Skip points within 0.5° of a sector edge (f32 against f64 there).
        let local = turned.to_local(dir);
        let c = local.y.atan2(local.x).to_degrees().rem_euclid(90.0);
        if !(0.5..=89.5).contains(&c) {
            continue;
        }
        let lux = turned.illuminance_at(p.position, p.normal, Interp::CatmullRom);
        let want = turned.color_toward(dir) * lux;
        let got = at_1_3[k];
        assert!(
            (got - want).abs().max_element() <= 0.005 * want.max_element().max(1.0),
            "point {k}: {got} vs {want}"
        );
        checked += 1;
        changed += usize::from((at_start[k] - got).abs().max_element() > 0.1 * lux);
    }
    assert!(checked > 1900, "{checked}");
    // 52° of turn moves 52/90 of every sector's points into the next colour.
    let share = changed as f64 / checked as f64;
    assert!((share - 52.0 / 90.0).abs() < 0.05, "{share}");
}

/// Shaded images draw Catmull-Rom from the cube maps (the cost of a point light); the lux
/// they carry agree with the exact spline of illuminance mode within 1e-3 of the image's
/// largest lux at every pixel, and the model is chosen by the mode.
#[test]
fn shaded_images_sample_the_cube_maps_and_agree_with_the_exact_spline() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = floor_scene(test_luminaires(), 8.0);
    let mut s = RenderSettings::from_display(&scene.display);
    assert_eq!(s.drawn_light_model(), LightModel::CatmullRomCube);
    s.mode = Mode::Illuminance;
    assert_eq!(s.drawn_light_model(), LightModel::Ldt(Interp::CatmullRom));
    let exact = floor_hdr(&gpu, &scene, 256);
    (s.width, s.height, s.mode, s.read_hdr) = (256, 256, Mode::Shaded, true);
    let cube = render(&gpu, &scene, &s).hdr.unwrap();
    let top = exact.iter().map(|p| p[3]).fold(0.0f32, f32::max);
    assert!(top > 10.0, "the floor is lit: {top} lx");
    let worst = exact
        .iter()
        .zip(&cube)
        .filter(|(e, _)| e[3] >= 0.0)
        .map(|(e, c)| (e[3] - c[3]).abs())
        .fold(0.0f32, f32::max);
    eprintln!(
        "cube vs exact spline: worst {:.2e} of the largest lux",
        worst / top
    );
    assert!(worst <= 1e-3 * top, "{worst} lx of {top}");
    let mut bilinear = s.clone();
    bilinear.light_model = LightModel::Ldt(Interp::Bilinear);
    assert_eq!(bilinear.drawn_light_model(), bilinear.light_model);
}
