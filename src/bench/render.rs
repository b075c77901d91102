//! The renderer benchmark, after Wallner's Table 3.1: scenes of about 100, 2 000, 15 000
//! and 115 000 triangles lit by 1, 4 and 7 luminaires, frame time with plain point lights
//! vs bilinear vs Catmull-Rom LDT sampling (per pixel, from the table, from the cube maps).
//! The light models are timed round-robin,
//! round by round, so drift of the machine affects them alike. A round submits `frames`
//! frames at once and waits for the GPU to finish them (throughput, GPU work included, as
//! frames per second are measured); the frame time is the median over rounds of the
//! round's time divided by `frames`.

use std::time::Instant;

use glam::{DVec3, Vec3};

use super::median;
use crate::geometry::generate::torus;
use crate::gpu::Gpu;
use crate::photometry::{Interp, Luminaire, PhotometryError};
use crate::render::passes::LightModel;
use crate::render::targets::Targets;
use crate::render::Renderer;
use crate::scene::placement::aim_frame;
use crate::scene::{Camera, Material, PlacedLuminaire, Scene, SceneMesh};

/// Torus tessellations (major, minor) giving ≈ 100, 2 000, 15 000 and 115 000 triangles
/// together with the 12 of the room.
pub const TESSELLATIONS: [(u32, u32); 4] = [(8, 6), (32, 31), (100, 75), (300, 192)];
/// Luminaire counts.
pub const LIGHT_COUNTS: [usize; 3] = [1, 4, 7];

/// One row of the table.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RenderBenchRow {
    /// Triangles in the scene.
    pub triangles: usize,
    /// Luminaires.
    pub lights: usize,
    /// Median frame time with point lights, ms.
    pub point_ms: f64,
    /// Median frame time with bilinear LDT sampling, ms.
    pub bilinear_ms: f64,
    /// Median frame time with Catmull-Rom LDT sampling, ms.
    pub catmull_rom_ms: f64,
    /// Median frame time with Catmull-Rom from the dense table (one filtered fetch), ms.
    pub catmull_rom_table_ms: f64,
    /// Median frame time with Catmull-Rom from the cube maps (one filtered fetch by
    /// direction, no angles), ms.
    pub catmull_rom_cube_ms: f64,
}

impl RenderBenchRow {
    /// Catmull-Rom over point lights.
    pub fn catmull_rom_ratio(&self) -> f64 {
        self.catmull_rom_ms / self.point_ms
    }

    /// Catmull-Rom from the table over point lights.
    pub fn table_ratio(&self) -> f64 {
        self.catmull_rom_table_ms / self.point_ms
    }

    /// Catmull-Rom from the cube maps over point lights.
    pub fn cube_ratio(&self) -> f64 {
        self.catmull_rom_cube_ms / self.point_ms
    }

    /// Bilinear over point lights.
    pub fn bilinear_ratio(&self) -> f64 {
        self.bilinear_ms / self.point_ms
    }
}

/// The seven luminaires (real files of several symmetry types) on the ceiling of a
/// 6 × 4 × 3 m room; the first `n` are used.
fn bench_luminaires(root: &std::path::Path) -> Result<Vec<PlacedLuminaire>, PhotometryError> {
    let files = [
        "eulumdat-plot/sample_06_isym1.ldt",
        "eulumdat-luminance/sample_07.ldt",
        "eulumdat-luminance/sample_04.ldt",
        "eulumdat-plot/sample_14_isym1.ldt",
        "eulumdat-luminance/sample_03.ldt",
        "eulumdat-analysis/sample_18.ldt",
        "eulumdat-luminance/sample_10.ldt",
    ];
    let spots = [
        (1.0, 1.0),
        (3.0, 1.0),
        (5.0, 1.0),
        (1.0, 3.0),
        (3.0, 3.0),
        (5.0, 3.0),
        (3.0, 2.0),
    ];
    files
        .iter()
        .zip(spots)
        .enumerate()
        .map(|(i, (f, (x, y)))| {
            let lum = Luminaire::load(&root.join("luminaires").join(f))?;
            let mut l = PlacedLuminaire::new(f, lum, DVec3::new(x, y, 2.9));
            l.rotation = aim_frame(
                Some(DVec3::new(0.1 * i as f64 - 0.3, 0.05, -1.0)),
                15.0 * i as f64,
            );
            Ok(l)
        })
        .collect()
}

/// A room with a torus of (`major`, `minor`) segments in it and `lights` luminaires.
pub fn bench_scene(major: u32, minor: u32, luminaires: &[PlacedLuminaire]) -> Scene {
    let p = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let (x, y, z) = (6.0, 4.0, 3.0);
    let quad = |a: Vec3, b: Vec3, c: Vec3, d: Vec3| [[a, b, c], [a, c, d]];
    let mut room = Vec::new();
    room.extend(quad(
        p(0.0, 0.0, 0.0),
        p(x, 0.0, 0.0),
        p(x, y, 0.0),
        p(0.0, y, 0.0),
    ));
    room.extend(quad(p(0.0, y, z), p(x, y, z), p(x, 0.0, z), p(0.0, 0.0, z)));
    room.extend(quad(
        p(x, 0.0, 0.0),
        p(0.0, 0.0, 0.0),
        p(0.0, 0.0, z),
        p(x, 0.0, z),
    ));
    room.extend(quad(
        p(0.0, 0.0, 0.0),
        p(0.0, y, 0.0),
        p(0.0, y, z),
        p(0.0, 0.0, z),
    ));
    room.extend(quad(p(x, y, 0.0), p(x, 0.0, 0.0), p(x, 0.0, z), p(x, y, z)));
    room.extend(quad(p(0.0, y, 0.0), p(x, y, 0.0), p(x, y, z), p(0.0, y, z)));
    let t = torus(major, minor, 1.0, 0.4);
    let offset = DVec3::new(3.0, 2.0, 1.0);
    let tris: Vec<[Vec3; 3]> = t
        .triangles
        .iter()
        .map(|tri| tri.map(|i| (t.positions[i as usize] + offset).as_vec3()))
        .collect();
    Scene::in_code(
        &format!("bench room + torus {major}×{minor}"),
        vec![
            SceneMesh::from_triangles("room", &room, 0),
            SceneMesh::from_triangles("torus", &tris, 0),
        ],
        vec![Material {
            specular: Vec3::splat(0.1),
            shininess: 30.0,
            ..Material::default()
        }],
        luminaires.to_vec(),
        Camera::perspective(DVec3::new(0.3, 0.3, 1.7), DVec3::new(3.0, 2.0, 1.0), 70.0),
    )
}

/// How long to measure.
#[derive(Debug, Clone, Copy)]
pub struct BenchPlan {
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// Frames submitted together in one round.
    pub frames: usize,
    /// Timed rounds per light model and cell (after one warm-up round).
    pub rounds: usize,
}

/// Runs the benchmark; `progress` is told each cell before it runs.
pub fn run(
    gpu: &Gpu,
    root: &std::path::Path,
    plan: BenchPlan,
    tessellations: &[(u32, u32)],
    mut progress: impl FnMut(usize, usize),
) -> Result<Vec<RenderBenchRow>, super::BenchError> {
    let all = bench_luminaires(root)?;
    let renderer = Renderer::new(gpu);
    let targets = Targets::new(gpu, plan.width, plan.height);
    let models = [
        LightModel::Point,
        LightModel::Ldt(Interp::Bilinear),
        LightModel::Ldt(Interp::CatmullRom),
        LightModel::CatmullRomTable,
        LightModel::CatmullRomCube,
    ];
    let mut rows = Vec::new();
    for &(major, minor) in tessellations {
        for &lights in &LIGHT_COUNTS {
            let scene = bench_scene(major, minor, &all[..lights]);
            progress(scene.triangle_count(), lights);
            let uploaded = renderer.upload(gpu, &scene);
            let mut times = [(); 5].map(|()| Vec::new());
            for round in 0..=plan.rounds {
                for (k, model) in models.iter().enumerate() {
                    let t = Instant::now();
                    renderer.draw_hdr(
                        gpu,
                        &uploaded,
                        &scene.camera,
                        &targets,
                        *model,
                        &crate::render::ShadowSettings::none(),
                        plan.frames,
                    )?;
                    if round > 0 {
                        times[k].push(t.elapsed().as_secs_f64() * 1e3 / plan.frames as f64);
                    }
                }
            }
            let [p, b, c, t, cube] = times.map(median);
            rows.push(RenderBenchRow {
                triangles: scene.triangle_count(),
                lights,
                point_ms: p,
                bilinear_ms: b,
                catmull_rom_ms: c,
                catmull_rom_table_ms: t,
                catmull_rom_cube_ms: cube,
            });
        }
    }
    Ok(rows)
}

/// The report of `bench render`: frame times per light model and their ratios to point
/// lights; `gpu` names the adapter.
pub fn report(rows: &[RenderBenchRow], plan: BenchPlan, gpu: &str) -> super::report::BenchReport {
    use super::report::{BenchReport, Table};
    let BenchPlan {
        width,
        height,
        frames,
        rounds,
    } = plan;
    let mut r = BenchReport::new(serde_json::json!({
        "rows": rows, "gpu": gpu, "width": width, "height": height, "frames": frames,
        "rounds": rounds
    }));
    r.line(format!(
        "{gpu}, {width}×{height}, median of {rounds} rounds of {frames} frames"
    ));
    let mut t = Table::new(&[
        "triangles",
        "lights",
        "point ms",
        "bilinear ms",
        "catmull-rom ms",
        "cr-table ms",
        "cr-cube ms",
        "bil/pt",
        "cr/pt",
        "table/pt",
        "cube/pt",
    ])
    .numbers_from(0);
    for row in rows {
        t.row(vec![
            row.triangles.to_string(),
            row.lights.to_string(),
            format!("{:.2}", row.point_ms),
            format!("{:.2}", row.bilinear_ms),
            format!("{:.2}", row.catmull_rom_ms),
            format!("{:.2}", row.catmull_rom_table_ms),
            format!("{:.2}", row.catmull_rom_cube_ms),
            format!("{:.3}×", row.bilinear_ratio()),
            format!("{:.3}×", row.catmull_rom_ratio()),
            format!("{:.3}×", row.table_ratio()),
            format!("{:.3}×", row.cube_ratio()),
        ]);
    }
    r.table(t);
    r
}
