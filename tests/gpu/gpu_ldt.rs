//! GPU LDT sampling (WGSL, on whatever adapter is present — lavapipe in CI) equals the CPU
//! reference within 1e-4 · I_max over 10 000 random directions, for every symmetry type and
//! every interpolation.

use crate::common;

use crate::gpu_common;

use glam::DVec3;
use goniolight::geometry::generate::XorShift;
use goniolight::photometry::distribution::direction_to_angles;
use goniolight::photometry::{Interp, LdtTexture, Luminaire};
use goniolight::render::ldt::{LdtAtlas, LdtProbe};

/// One real file per Isym, a 1°×1° lab file, an IES file and a half-sphere file.
const FILES: [&str; 8] = [
    "eulumdat-analysis/sample_18.ldt",
    "eulumdat-plot/sample_13_isym1.ldt",
    "eulumdat-plot/sample_03_isym2.ldt",
    "eulumdat-plot/sample_01_isym3.ldt",
    "eulumdat-luminance/sample_06.ldt",
    "eulumdat-luminance/sample_07.ldt",
    "photometric-viewer/ies95/metric_units.ies",
    "photometric-viewer/ldt/symmetry_to_c90c270.ldt",
];

fn random_directions(n: usize, seed: u64) -> Vec<DVec3> {
    let mut rng = XorShift::new(seed);
    (0..n)
        .map(|_| loop {
            let v = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 2.0 - 1.0;
            let l = v.length();
            if l > 1e-3 && l <= 1.0 {
                break v / l;
            }
        })
        .collect()
}

#[test]
fn gpu_ldt_sampling_equals_the_cpu_reference() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let lums: Vec<Luminaire> = FILES
        .iter()
        .map(|f| Luminaire::load(&common::luminaire(f)).unwrap())
        .collect();
    let textures: Vec<LdtTexture> = lums
        .iter()
        .map(|l| LdtTexture::from_distribution(&l.distribution))
        .collect();
    let isyms: std::collections::BTreeSet<u8> =
        lums.iter().map(|l| l.data.symmetry.isym()).collect();
    assert_eq!(isyms.len(), 5, "every symmetry type covered");
    let atlas = LdtAtlas::new(&gpu, &textures.iter().collect::<Vec<_>>());
    let probe = LdtProbe::new(&gpu);
    let dirs = random_directions(10_000, 42);
    let dirs_f32: Vec<[f32; 3]> = dirs.iter().map(|d| d.as_vec3().to_array()).collect();
    for (layer, tex) in textures.iter().enumerate() {
        for interp in Interp::ALL {
            let got = probe.run(&gpu, &atlas, layer, interp, &dirs_f32).unwrap();
            let mut worst = 0.0f64;
            let mut skipped = 0;
            for (d, g) in dirs.iter().zip(&got) {
                let (c, gamma) = direction_to_angles(*d);
                if interp == Interp::Nearest && near_a_tie(tex, c, gamma) {
                    skipped += 1;
                    continue;
                }
                let want = tex.sample(c, gamma, interp);
                worst = worst.max((want - *g as f64).abs());
            }
            assert!(skipped < 50, "{} {interp:?}: {skipped} ties", FILES[layer]);
            // Values are normalised: 1e-4 of I_max.
            assert!(
                worst <= 1e-4,
                "{} {interp:?}: max error {worst:e} of I_max",
                FILES[layer]
            );
        }
    }
}

/// Nearest-neighbour lookups within f32 rounding of a midpoint may round either way.
fn near_a_tie(tex: &LdtTexture, c: f64, gamma: f64) -> bool {
    let frac = |x: f64, step: f64| {
        let f = (x / step).fract();
        (f - 0.5).abs() < 1e-4
    };
    frac(gamma - tex.gamma_start_deg, tex.gamma_step_deg)
        || (tex.c_count > 1 && frac(c, tex.c_step_deg()))
}

/// The Catmull-Rom table (the renderer's `CatmullRomTable` light model): its lookup (CPU
/// twin: linear across the 0.125° columns of C, the spline across γ) is within 1e-3 ·
/// I_max of exact Catmull-Rom for every bundled file at random directions (measured
/// 2.5e-4), and the GPU's lookup of the 16-bit table lights a point like the CPU's
/// Catmull-Rom within 1e-3 · I_max (measured 5.0e-4 on lavapipe).
#[test]
fn the_catmull_rom_table_stays_within_1e_3_of_i_max() {
    use goniolight::render::ldt::table::table_value;
    use goniolight::render::LightModel;
    let dirs = random_directions(3000, 11);
    let mut worst: f64 = 0.0;
    for path in common::all_luminaire_files() {
        let l = Luminaire::load(&path).unwrap();
        let tex = LdtTexture::from_distribution(&l.distribution);
        for d in &dirs {
            let (c, g) = direction_to_angles(*d);
            let exact = tex.sample(c, g, Interp::CatmullRom);
            // Texture values are normalised: fractions of I_max.
            let err = (table_value(&tex, c, g) - exact).abs();
            worst = worst.max(err);
            assert!(
                err <= 1e-3,
                "{}: C {c:.2} γ {g:.2}: {err:.2e}",
                path.display()
            );
            worst = worst.max(err);
        }
    }
    eprintln!("table lookup vs Catmull-Rom, worst over every bundled file: {worst:.2e} · I_max");
    let Some(worst_gpu) = worst_gpu_lookup(LightModel::CatmullRomTable, &dirs, &|_| 1e-3) else {
        return;
    };
    eprintln!("GPU table vs CPU Catmull-Rom, worst: {worst_gpu:.2e} · I_max");
}

/// The largest difference (fraction of I_max) between the GPU's `model` and the CPU's
/// Catmull-Rom toward `dirs` over [`FILES`], each file's worst asserted within
/// `limit(file)` and printed; `None` when the GPU tests are skipped.
fn worst_gpu_lookup(
    model: goniolight::render::LightModel,
    dirs: &[DVec3],
    limit: &dyn Fn(&str) -> f64,
) -> Option<f64> {
    use goniolight::render::illuminance::{IlluminanceProbe, SurfacePoint};
    use goniolight::render::{Renderer, ShadowSettings};
    use goniolight::scene::{Camera, Material, PlacedLuminaire, Scene};
    let gpu = gpu_common::gpu()?;
    let renderer = Renderer::new(&gpu);
    let mut worst_gpu: f64 = 0.0;
    for file in FILES {
        let l = Luminaire::load(&common::luminaire(file)).unwrap();
        let placed = PlacedLuminaire::new("lookup", l, DVec3::ZERO);
        // Points 1 m away facing the light: lux = candela.
        let points: Vec<SurfacePoint> = dirs
            .iter()
            .map(|&d| SurfacePoint {
                position: d,
                normal: -d,
            })
            .collect();
        let scene = Scene::in_code(
            "lookup test",
            Vec::new(),
            vec![Material::default()],
            vec![placed.clone()],
            Camera::perspective(DVec3::ONE, DVec3::ZERO, 60.0),
        );
        let uploaded = renderer.upload(&gpu, &scene);
        let got = IlluminanceProbe::new(&gpu, model)
            .run_in_scene(&gpu, &uploaded, &points, &ShadowSettings::none())
            .unwrap();
        let i_max = placed.candela_scale();
        let mut worst_file = (0.0, 0.0, 0.0);
        for (k, d) in dirs.iter().enumerate() {
            let (c, g) = direction_to_angles(*d);
            let want = placed.texture.sample(c, g, Interp::CatmullRom) * i_max;
            let err = (got[k] - want).abs() / i_max;
            if err > worst_file.0 {
                worst_file = (err, c, g);
            }
        }
        let (err, c, g) = worst_file;
        eprintln!("{model:?}, {file}: worst {err:.2e} · I_max at C {c:.2} γ {g:.2}");
        assert!(
            err <= limit(file),
            "{model:?}, {file}: C {c:.2} γ {g:.2}: {err:.2e}"
        );
        worst_gpu = worst_gpu.max(err);
    }
    Some(worst_gpu)
}

/// The cube maps (the renderer's `CatmullRomCube` light model: one filtered fetch by
/// direction, no angles) light a point like the CPU's Catmull-Rom within 1e-3 · I_max
/// (measured 3.6e-4 on lavapipe), bilinear between texel centres 0.18° apart — except
/// where a distribution falls off within a fraction of a degree: the half-sphere test file
/// drops from 680 cd/klm at γ 90° to 0 by γ 91°, and a texel there blends across the cut
/// (measured 1.7e-2 · I_max within 0.2° of it).
#[test]
fn the_catmull_rom_cube_maps_stay_close_to_the_spline() {
    use goniolight::render::LightModel;
    let dirs = random_directions(3000, 12);
    // The steep cut is the last file of FILES: every other one within 1e-3.
    let limits = |file: &str| {
        if file.ends_with("symmetry_to_c90c270.ldt") {
            2e-2
        } else {
            1e-3
        }
    };
    if let Some(worst) = worst_gpu_lookup(LightModel::CatmullRomCube, &dirs, &limits) {
        eprintln!("GPU cube maps vs CPU Catmull-Rom, worst: {worst:.2e} · I_max");
    }
}
