//! `goniolight bench …`: benchmarks that print tables of ratios measured side by side in
//! one run.

use clap::Subcommand;

use super::error::CliError;
use crate::bench::render as render_bench;
use crate::gpu::Gpu;

/// A setting compared on and off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Switch {
    /// On.
    On,
    /// Off.
    Off,
}

/// Benchmarks.
#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Silhouette queries, brute force vs hextree, on ~10 k, 180 k and 1 M triangles.
    Silhouette {
        /// Print JSON {"meshes": [...]}.
        #[arg(long)]
        json: bool,
        /// Light positions per mesh, evenly along one orbit (120: 3° apart).
        #[arg(long, default_value_t = 120)]
        queries: usize,
        /// Maximum hextree depth.
        #[arg(long, default_value_t = crate::shadow::hextree::DEFAULT_DEPTH)]
        depth: u32,
        /// Shrink the meshes by this factor (1 = the full sizes).
        #[arg(long, default_value_t = 1.0)]
        scale: f64,
    },
    /// Renderer frame times (Wallner Table 3.1): point lights vs bilinear vs Catmull-Rom
    /// LDT sampling, ≈ 100 to 115 000 triangles, 1, 4 and 7 luminaires.
    Render {
        /// Print JSON {"rows": [...]}.
        #[arg(long)]
        json: bool,
        /// Frames submitted together per round.
        #[arg(long, default_value_t = 8)]
        frames: usize,
        /// Timed rounds per cell and light model (after a warm-up round); the median of the
        /// rounds' frame times is reported.
        #[arg(long, default_value_t = 5)]
        rounds: usize,
        /// Frame width.
        #[arg(long, default_value_t = 1280)]
        width: u32,
        /// Frame height.
        #[arg(long, default_value_t = 720)]
        height: u32,
        /// Only the two smallest scenes (a quick check).
        #[arg(long)]
        quick: bool,
    },
    /// A shadow profile of a ~180 000-triangle building, 08:00–16:00 every 5 minutes
    /// (97 steps): seconds in total and per step, silhouettes vs shadow volumes, brute
    /// force vs hextree, volumes ending at the ground vs all of one length.
    Profile {
        /// Print JSON {"rows": [...]}.
        #[arg(long)]
        json: bool,
        /// Plan pixels per side.
        #[arg(long, default_value_t = 1024)]
        resolution: u32,
        /// Minutes between steps.
        #[arg(long, default_value_t = 5)]
        step: u32,
        /// Storeys of the building (6: 180 000 triangles).
        #[arg(long, default_value_t = 6)]
        floors: u32,
        /// Also the real models of the shared test data (the Delft city block, in the
        /// Dutch national grid, and the high-rise block), read from this folder (usually
        /// `../shared`).
        #[arg(long)]
        shared: Option<std::path::PathBuf>,
    },
    /// CPU ray casts (exact shadows at points, the radiosity gather, the CPU references):
    /// rays per second through the BVH and by brute force, one thread, on terrain meshes
    /// of about 10 k, 100 k and 1 M triangles.
    Raycast {
        /// Print JSON {"rows": [...]}.
        #[arg(long)]
        json: bool,
        /// Rays of each kind (shadow, nearest hit) through the BVH per mesh.
        #[arg(long, default_value_t = 20_000)]
        rays: usize,
        /// How many of them are also cast by brute force (and checked to agree).
        #[arg(long, default_value_t = 200)]
        brute_rays: usize,
        /// Shrink the meshes by this factor (1 = the full sizes).
        #[arg(long, default_value_t = 1.0)]
        scale: f64,
    },
    /// The face-cluster hierarchy (Edström §4.2) of the real models in the shared test data
    /// (cathedral, conference room, high-rise block): seconds to load and to cluster.
    Clusters {
        /// Print JSON {"rows": [...]}.
        #[arg(long)]
        json: bool,
        /// The shared test data (default: `../shared` beside the checkout, or
        /// `$GONIOLIGHT_SHARED`).
        #[arg(long)]
        shared: Option<std::path::PathBuf>,
    },
    /// View-driven radiosity (Bozalina §6.2 as a number): seconds until the image in view
    /// is within --tolerance of the converged image, global vs importance-driven vs
    /// perspective-driven, from the scene's camera or --eye/--look-at/--fov.
    RadiosityView {
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// The scene (default: the bundled assets/scenes/furnished_room.toml).
        #[arg(long)]
        scene: Option<std::path::PathBuf>,
        /// Eye position "x,y,z", metres (default: the scene's camera).
        #[arg(long, value_delimiter = ',', requires = "look_at")]
        eye: Option<Vec<f64>>,
        /// The point looked at "x,y,z", metres.
        #[arg(long, value_delimiter = ',', requires = "eye")]
        look_at: Option<Vec<f64>>,
        /// Vertical field of view with --eye, degrees.
        #[arg(long, default_value_t = 60.0)]
        fov: f64,
        /// What it solves with.
        #[command(flatten)]
        plan: crate::bench::radiosity_view::ViewBenchPlan,
        /// The scene this many times in a row along +x (closed rooms; the camera in the
        /// first sees a small part of the whole).
        #[arg(long, default_value_t = 1)]
        rooms: usize,
    },
    /// Uniform against adaptive elements (Wallner Table 2.1), with and without normal
    /// maps: elements, preprocessing, solve time and shots.
    Adaptive(super::bench_adaptive::AdaptiveBenchArgs),
    /// GPU radiosity on a Cornell-box-like scene (Wallner Table 4.1, "Cornell box high":
    /// ~127 000 elements): time to 90 % and 99 % convergence, hemicube vs stereographic,
    /// flat vs face-cluster shooters.
    Radiosity {
        /// Print JSON {"rows": [...]}.
        #[arg(long)]
        json: bool,
        /// About this many elements (from the surface area: a floor drawn as strips has
        /// more, since texels along shared edges count twice without charts).
        #[arg(long, default_value_t = 127_000)]
        elements: usize,
        /// Texels per metre instead of `--elements`.
        #[arg(long, conflicts_with = "elements")]
        texel_density: Option<f64>,
        /// Patch level (patches of 2^level × 2^level texels).
        #[arg(long, default_value_t = 4)]
        level: u32,
        /// Give up after this many shots per solution.
        #[arg(long, default_value_t = 5000)]
        max_shots: usize,
        /// Give up after this many seconds per solution.
        #[arg(long, value_parser = super::args::seconds_arg)]
        time_limit: Option<f64>,
        /// Visibility maps to compare (comma-separated).
        #[arg(
            long,
            value_enum,
            value_delimiter = ',',
            default_value = "hemicube,stereographic"
        )]
        visibility: Vec<crate::radiosity::gpu::Visibility>,
        /// Shooters to compare (comma-separated): `none` (every triangle), `clusters`.
        #[arg(long, value_enum, value_delimiter = ',', default_value = "none")]
        hierarchy: Vec<crate::radiosity::shooters::Hierarchy>,
        /// Links' errors to compare with `--hierarchy clusters` (comma-separated; 0: every
        /// receiver takes the finest cells). One row per value for clusters.
        #[arg(long, value_delimiter = ',', default_value = "0.05")]
        link_error: Vec<f64>,
        /// Ambient term uses to compare (comma-separated): `display` (shown only) or
        /// `overshoot` (ambient overshooting, Wallner §4.3.5).
        #[arg(long, value_enum, value_delimiter = ',', default_value = "display")]
        ambient: Vec<crate::radiosity::Ambient>,
        /// Side of a visibility map (a hemicube face or the stereographic map), texels.
        #[arg(long, default_value_t = 256)]
        map_size: u32,
        /// With `--hierarchy clusters`: the largest shares of the initial unshot power one
        /// shooting cell carries, to compare (comma-separated; smaller: more, finer cells).
        #[arg(long, value_delimiter = ',', default_values_t = [crate::radiosity::shooters::DEFAULT_CELL_POWER])]
        cell_power: Vec<f64>,
        /// Whether each visibility face draws only the chunks of the mesh it can see, to
        /// compare (comma-separated: `on`, `off`; the same maps either way).
        #[arg(long, value_enum, value_delimiter = ',', default_value = "on")]
        chunk_culling: Vec<Switch>,
        /// How the maps are drawn, to compare (comma-separated: `auto`, `hardware` (the
        /// render pipeline), `compute` (compute shaders on all of the GPU's units)).
        #[arg(long, value_enum, value_delimiter = ',', default_value = "auto")]
        raster: Vec<crate::radiosity::gpu::Raster>,
        /// The scene (default: the bundled assets/scenes/cornell_box.toml).
        #[arg(long)]
        scene: Option<std::path::PathBuf>,
    },
}

/// Runs `bench …`.
pub fn run(cmd: BenchCommand) -> Result<(), CliError> {
    match cmd {
        BenchCommand::Silhouette {
            json,
            queries,
            depth,
            scale,
        } => super::bench_silhouette::run(json, queries, depth, scale),
        BenchCommand::Render {
            json,
            frames,
            rounds,
            width,
            height,
            quick,
        } => run_render(
            json,
            render_bench::BenchPlan {
                width,
                height,
                frames,
                rounds,
            },
            quick,
        ),
        BenchCommand::Profile {
            json,
            resolution,
            step,
            floors,
            shared,
        } => super::bench_profile::run(json, resolution, step, floors, shared),
        BenchCommand::Raycast {
            json,
            rays,
            brute_rays,
            scale,
        } => run_raycast(json, rays, brute_rays, scale),
        BenchCommand::Clusters { json, shared } => run_clusters(json, shared),
        BenchCommand::Adaptive(args) => super::bench_adaptive::run(args),
        BenchCommand::RadiosityView {
            json,
            scene,
            eye,
            look_at,
            fov,
            plan,
            rooms,
        } => {
            if eye.iter().chain(&look_at).any(|v| v.len() != 3) {
                return Err(CliError::input(anyhow::anyhow!(
                    "--eye and --look-at take three numbers \"x,y,z\""
                )));
            }
            let eye = eye.zip(look_at).map(|(e, l)| {
                (
                    glam::DVec3::from_slice(&e),
                    glam::DVec3::from_slice(&l),
                    fov,
                )
            });
            run_radiosity_view(json, scene, eye, rooms, plan)
        }
        BenchCommand::Radiosity {
            json,
            elements,
            texel_density,
            level,
            max_shots,
            time_limit,
            visibility,
            hierarchy,
            link_error,
            ambient,
            map_size,
            cell_power,
            chunk_culling,
            raster,
            scene,
        } => {
            let plan = crate::bench::radiosity::RadiosityBenchPlan {
                elements,
                texel_density,
                level,
                max_shots,
                time_limit,
                map_size,
            };
            use crate::radiosity::shooters::{Hierarchy, DEFAULT_CELL_POWER};
            if link_error
                .iter()
                .any(|e| !(e.is_finite() && (0.0..=1.0).contains(e)))
            {
                return Err(CliError::input(anyhow::anyhow!(
                    "--link-error values must be in [0, 1]"
                )));
            }
            if cell_power
                .iter()
                .any(|p| !(p.is_finite() && *p > 0.0 && *p <= 1.0))
            {
                return Err(CliError::input(anyhow::anyhow!(
                    "--cell-power values must be in (0, 1]"
                )));
            }
            let mut configs = Vec::new();
            for (&culling, &raster) in chunk_culling
                .iter()
                .flat_map(|c| raster.iter().map(move |r| (c, r)))
            {
                for &a in &ambient {
                    for &v in &visibility {
                        for &h in &hierarchy {
                            // Links and cells exist only with clusters.
                            let (errors, powers) = match h {
                                Hierarchy::None => (&[0.0][..], &[DEFAULT_CELL_POWER][..]),
                                Hierarchy::Clusters => (&link_error[..], &cell_power[..]),
                            };
                            for &e in errors {
                                configs.extend(powers.iter().map(|&p| {
                                    crate::bench::radiosity::RadiosityBenchConfig {
                                        visibility: v,
                                        hierarchy: h,
                                        link_error: e,
                                        ambient: a,
                                        cell_power: p,
                                        chunk_culling: culling == Switch::On,
                                        raster,
                                    }
                                }));
                            }
                        }
                    }
                }
            }
            run_radiosity(json, plan, &configs, scene)
        }
    }
}

fn run_raycast(as_json: bool, rays: usize, brute_rays: usize, scale: f64) -> Result<(), CliError> {
    use crate::bench::raycast as rbench;
    if rays == 0 || brute_rays == 0 || brute_rays > rays || !(scale > 0.0 && scale <= 1.0) {
        return Err(CliError::input(anyhow::anyhow!(
            "--rays and --brute-rays must be > 0, --brute-rays ≤ --rays, --scale in (0, 1]"
        )));
    }
    let meshes = rbench::bench_meshes(scale);
    let rows = rbench::run(&meshes, rays, brute_rays, |n| {
        eprintln!("benchmarking {n} triangles …")
    })
    .map_err(CliError::failure)?;
    println!("{}", rbench::report(&rows).text(as_json));
    Ok(())
}

fn run_clusters(as_json: bool, shared: Option<std::path::PathBuf>) -> Result<(), CliError> {
    let shared = shared
        .or_else(|| std::env::var_os("GONIOLIGHT_SHARED").map(Into::into))
        .unwrap_or_else(|| crate::io::data_root().join("../shared"));
    let rows = crate::bench::clusters::run(&shared, |m| eprintln!("clustering the {m} …"))
        .map_err(CliError::input)?;
    println!("{}", crate::bench::clusters::report(&rows).text(as_json));
    Ok(())
}

fn run_radiosity(
    as_json: bool,
    plan: crate::bench::radiosity::RadiosityBenchPlan,
    configs: &[crate::bench::radiosity::RadiosityBenchConfig],
    scene: Option<std::path::PathBuf>,
) -> Result<(), CliError> {
    use crate::bench::radiosity as rbench;
    let level = plan.level;
    let time_ok = plan.time_limit.is_none_or(|t| t.is_finite() && t > 0.0);
    let density_ok = plan.texel_density.is_none_or(|d| d.is_finite() && d > 0.0);
    if !(1..=50_000_000).contains(&plan.elements)
        || level > 6
        || plan.max_shots == 0
        || !time_ok
        || !density_ok
        || !(16..=4096).contains(&plan.map_size)
    {
        return Err(CliError::input(anyhow::anyhow!(
            "--elements must be in 1..=50000000, --texel-density > 0, --level in 0..=6, --max-shots > 0, --time-limit > 0, --map-size in 16..=4096"
        )));
    }
    let path =
        scene.unwrap_or_else(|| crate::io::data_root().join("assets/scenes/cornell_box.toml"));
    let scene = super::scene_input::load_scene(&path)?;
    let gpu = Gpu::shared()?;
    eprintln!("GPU: {}", gpu.describe());
    let bar = indicatif::ProgressBar::new(1000);
    let rows = rbench::run(&gpu, &scene, plan, configs, |config, c| {
        bar.set_message(format!(
            "{:?}, hierarchy {:?}, ambient {:?}",
            config.visibility, config.hierarchy, config.ambient
        ));
        bar.set_position(crate::radiosity::session::Session::progress_position(
            c, 1000,
        ));
    })
    .map_err(CliError::failure)?;
    bar.finish_and_clear();
    let report = crate::bench::radiosity_report::report(&rows, &plan, &gpu.describe(), &path);
    println!("{}", report.text(as_json));
    Ok(())
}

fn run_render(as_json: bool, plan: render_bench::BenchPlan, quick: bool) -> Result<(), CliError> {
    let render_bench::BenchPlan {
        width,
        height,
        frames,
        rounds,
    } = plan;
    if frames == 0 || rounds == 0 || !(1..=8192).contains(&width) || !(1..=8192).contains(&height) {
        return Err(CliError::input(anyhow::anyhow!(
            "--frames and --rounds must be > 0 and --width/--height in 1..=8192"
        )));
    }
    let gpu = Gpu::shared()?;
    eprintln!("GPU: {}", gpu.describe());
    let root = crate::io::data_root();
    let tess = if quick {
        &render_bench::TESSELLATIONS[..2]
    } else {
        &render_bench::TESSELLATIONS[..]
    };
    let rows = render_bench::run(&gpu, &root, plan, tess, |tris, lights| {
        eprintln!("benchmarking {tris} triangles, {lights} luminaires …")
    })
    .map_err(CliError::failure)?;
    println!(
        "{}",
        render_bench::report(&rows, plan, &gpu.describe()).text(as_json)
    );
    Ok(())
}

fn run_radiosity_view(
    as_json: bool,
    scene: Option<std::path::PathBuf>,
    eye: Option<(glam::DVec3, glam::DVec3, f64)>,
    rooms: usize,
    plan: crate::bench::radiosity_view::ViewBenchPlan,
) -> Result<(), CliError> {
    use crate::radiosity::view::ViewPoint;
    let ok = |v: f64, lo: f64, hi: f64| v.is_finite() && v > lo && v <= hi;
    if !(ok(plan.texel_density, 0.0, 1e4)
        && ok(plan.tolerance, 0.0, 1.0)
        && ok(plan.reference, 0.0, 1.0)
        && ok(plan.time_limit, 0.0, 1e6)
        && (0.0..=180.0).contains(&plan.fov_margin)
        && plan.level <= 6
        && (1..=64).contains(&rooms)
        && (1..=20).contains(&plan.repeat)
        && eye
            .is_none_or(|(e, l, f)| e.is_finite() && l.is_finite() && e != l && ok(f, 0.0, 179.0)))
    {
        return Err(CliError::input(anyhow::anyhow!(
            "--texel-density > 0, --tolerance and --reference in (0, 1], --time-limit > 0, --fov-margin in 0..=180, --level in 0..=6, --rooms in 1..=64, --repeat in 1..=20, --fov in (0, 179), --eye ≠ --look-at"
        )));
    }
    let path =
        scene.unwrap_or_else(|| crate::io::data_root().join("assets/scenes/furnished_room.toml"));
    let scene =
        crate::bench::radiosity_view::row_of_rooms(&super::scene_input::load_scene(&path)?, rooms);
    let mut camera = scene.camera;
    if let Some((e, l, fov)) = eye {
        camera = crate::scene::camera::Camera::perspective(e, l, fov);
    }
    let shown = crate::render::RenderSettings::from_display(&scene.display);
    let aspect = shown.aspect();
    let point = ViewPoint::new(&camera, aspect).ok_or_else(|| {
        CliError::input(anyhow::anyhow!(
            "{}: the camera is orthographic; give --eye and --look-at",
            path.display()
        ))
    })?;
    let gpu = Gpu::shared()?;
    eprintln!("GPU: {}", gpu.describe());
    let result = crate::bench::radiosity_view::run(&gpu, &scene, &point, plan, |what| {
        eprintln!("solving: {what} …")
    })
    .map_err(CliError::failure)?;
    let report =
        crate::bench::radiosity_view_report::report(&result, &gpu.describe(), &path, rooms);
    println!("{}", report.text(as_json));
    Ok(())
}
