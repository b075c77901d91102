//! The viewer's UI driven headless with egui_kittest (no window, no GPU unless a test
//! runs background work): dropping files, editing luminaires, the photometry window,
//! display and sun choices, camera control, saving and loading, and the background jobs.

use crate::common;
use crate::gpu_common;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use common::{luminaire, root};
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use goniolight::photometry::Interp;
use goniolight::render::ShadowTechnique;
use goniolight::scene::Scene;
use goniolight::viewer::app::ViewerApp;
use goniolight::viewer::files::{load_scene_or_model, RecentFiles};

fn scene_path(name: &str) -> PathBuf {
    root().join("assets/scenes").join(name)
}

fn app(name: &str) -> ViewerApp {
    let path = scene_path(name);
    let scene = Scene::load(&path).unwrap();
    ViewerApp::new(scene, Some(path), RecentFiles::default())
}

fn harness(app: ViewerApp) -> Harness<'static, ViewerApp> {
    Harness::builder()
        .with_size([1280.0, 900.0])
        .build_ui_state(|ui, app: &mut ViewerApp| app.ui(ui), app)
}

/// A file dropped on the window (what egui-winit hands over).
#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }
    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

fn drop_file(h: &mut Harness<'_, ViewerApp>, path: &Path) {
    h.input_mut()
        .dropped_files
        .push(Arc::new(Dropped(path.to_path_buf())));
    h.run();
}

fn placements(scene: &Scene) -> Vec<String> {
    scene
        .luminaires
        .iter()
        .map(|l| {
            format!(
                "{} {:?} {:?} {} {:?}",
                l.name, l.position, l.rotation, l.multiplier, l.color
            )
        })
        .collect()
}

#[test]
fn dropping_a_malformed_luminaire_shows_an_error_and_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("broken.ldt");
    // A valid header cut off in the middle of the angles.
    let good = std::fs::read_to_string(luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    let cut: String = good.lines().take(30).map(|l| format!("{l}\n")).collect();
    std::fs::write(&bad, cut).unwrap();
    let mut h = harness(app("box_room.toml"));
    let before = placements(&h.state().scene);
    let (revision, camera, display) = (
        h.state().revision,
        h.state().camera,
        h.state().display.clone(),
    );
    drop_file(&mut h, &bad);
    let error = h
        .state()
        .last_error()
        .expect("an error message")
        .to_string();
    assert!(error.contains("broken.ldt"), "{error}");
    assert!(error.contains("not added"), "{error}");
    // Shown in the UI.
    h.get_by_label_contains("broken.ldt");
    let s = h.state();
    assert_eq!(placements(&s.scene), before);
    assert_eq!(
        (s.revision, s.camera, &s.display),
        (revision, camera, &display)
    );
}

#[test]
fn dropping_luminaires_adds_them_and_remove_takes_them_away() {
    let mut h = harness(app("box_room.toml"));
    let n = h.state().scene.luminaires.len();
    let ies_file = luminaire("photometric-viewer/ies95/metric_units.ies");
    drop_file(&mut h, &luminaire("eulumdat-luminance/sample_07.ldt"));
    drop_file(&mut h, &ies_file);
    assert_eq!(h.state().scene.luminaires.len(), n + 2);
    assert_eq!(h.state().selected, Some(n + 1));
    // Hung 10 cm under the top of the scene, pointing down.
    let (_, hi) = h.state().scene.bounds();
    let added = &h.state().scene.luminaires[n];
    assert!((added.position.z - (hi.z - 0.1)).abs() < 1e-9);
    assert_eq!(added.rotation, glam::DMat3::IDENTITY);
    h.get_by_label("Remove").click();
    h.run();
    assert_eq!(h.state().scene.luminaires.len(), n + 1);
    assert!(h
        .state()
        .scene
        .luminaires
        .iter()
        .all(|l| l.file != ies_file));
}

#[test]
fn interpolation_choice_reaches_the_render_settings() {
    let mut h = harness(app("box_room.toml"));
    let r0 = h.state().revision;
    h.get_by_role_and_label(egui::accesskit::Role::ComboBox, "Interpolation")
        .click();
    h.run();
    h.get_by_label("nearest").click();
    h.run();
    assert_eq!(h.state().display.light_model.interp(), Interp::Nearest);
    assert!(h.state().revision > r0);
    let s = h.state().render_settings(320, 200);
    assert_eq!(
        s.light_model,
        goniolight::render::LightModel::Ldt(Interp::Nearest)
    );
    assert_eq!((s.width, s.height), (320, 200));
}

#[test]
fn aim_controls_reproduce_every_rotation_of_the_bundled_scenes() {
    use goniolight::viewer::app::AimControls;
    for name in ["furnished_room.toml", "effect_stage.toml", "box_room.toml"] {
        let scene = Scene::load(&scene_path(name)).unwrap();
        for l in &scene.luminaires {
            let back = AimControls::of(l.rotation).rotation();
            let err = (back - l.rotation)
                .to_cols_array()
                .iter()
                .map(|v| v.abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-9, "{name} {}: {err}", l.name);
        }
    }
}

#[test]
fn photometry_window_shows_the_summary_and_the_curves() {
    let mut h = harness(app("box_room.toml"));
    h.get_by_label_contains("1: ").click();
    h.run();
    h.get_by_label("Photometry…").click();
    h.run();
    let summary = h.state().scene.luminaires[0].luminaire.summary();
    h.get_by_label_contains("Photometry: ");
    h.get_by_label(&format!("{:.0} lm", summary.flux_lm));
    h.get_by_label("Beam angle (50 %)");
    // The curves pass through the measured values: at measured angles every
    // interpolation returns the measurement.
    let lum = &h.state().scene.luminaires[0].luminaire;
    let measured = goniolight::viewer::luminaires::measured_points(lum, 0.0);
    assert!(!measured.is_empty());
    for (interp, _) in goniolight::viewer::luminaires::INTERPOLATIONS {
        let curve = goniolight::viewer::luminaires::polar_curve(lum, 0.0, interp, 0.5);
        assert_eq!(curve.len(), 2 * 361);
        for m in &measured {
            let nearest = curve
                .iter()
                .map(|c| ((c[0] - m[0]).powi(2) + (c[1] - m[1]).powi(2)).sqrt())
                .fold(f64::INFINITY, f64::min);
            let size = (m[0] * m[0] + m[1] * m[1]).sqrt();
            assert!(
                nearest <= 1e-6 * size.max(1.0),
                "{interp:?}: {m:?} off the curve by {nearest}"
            );
        }
    }
}

#[test]
fn dragging_the_viewport_orbits_and_scrolling_zooms() {
    let mut h = harness(app("box_room.toml"));
    h.run();
    let before = h.state().camera;
    let centre = egui::pos2(800.0, 450.0);
    h.event(egui::Event::PointerMoved(centre));
    h.event(egui::Event::PointerButton {
        pos: centre,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: Default::default(),
    });
    h.run();
    h.event(egui::Event::PointerMoved(centre + egui::vec2(100.0, 0.0)));
    h.run();
    h.event(egui::Event::PointerButton {
        pos: centre + egui::vec2(100.0, 0.0),
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: Default::default(),
    });
    h.run();
    let after = h.state().camera;
    assert!(
        (after.target - before.target).length() < 1e-9,
        "orbiting keeps the target"
    );
    let turned = (after.yaw_deg - before.yaw_deg).rem_euclid(360.0);
    assert!(turned > 1.0, "yaw {} → {}", before.yaw_deg, after.yaw_deg);
}

#[test]
fn false_colour_mode_and_shadow_choices() {
    let mut h = harness(app("box_room.toml"));
    h.get_by_label("False-colour lux").click();
    h.run();
    assert_eq!(h.state().display.mode, goniolight::scene::Mode::Illuminance);
    h.get_by_label("Shadows").click();
    h.run();
    h.get_by_label("Volumes").click();
    h.run();
    h.get_by_label("hextree").click();
    h.run();
    h.get_by_label("Show silhouettes").click();
    h.run();
    let s = h.state().render_settings(100, 100).shadows;
    assert_eq!(s.technique, ShadowTechnique::Volumes);
    assert_eq!(s.silhouette, goniolight::shadow::SilhouetteMethod::Hextree);
    assert!(s.show_silhouettes);
}

#[test]
fn the_sun_adds_a_light_and_switches_to_shadow_volumes() {
    let mut h = harness(app("box_room.toml"));
    let n = h.state().scene.luminaires.len();
    h.get_by_label("Sun").click();
    h.run();
    h.get_by_label("Sun lights the scene").click();
    h.run();
    let app = h.state();
    assert!(app.sun.enabled);
    assert_eq!(app.display.shadows.technique, ShadowTechnique::Volumes);
    let scene = app.render_scene();
    assert_eq!(scene.luminaires.len(), n + 1);
    assert_eq!(
        app.scene.luminaires.len(),
        n,
        "the sun is not part of the saved scene"
    );
    // Its light at the scene's centre, on a surface facing it, is the clear-sky value.
    let p = app.sun.position().unwrap();
    let sun = scene.luminaires.last().unwrap();
    let (lo, hi) = app.scene.bounds();
    let to_sun = sun.position - (lo + hi) / 2.0;
    let lux = sun
        .luminaire
        .distribution
        .candela(0.0, 90.0, Interp::CatmullRom, sun.multiplier)
        / to_sun.length_squared();
    let expected = goniolight::lighting::sun::clear_sky_direct_normal_lux(p.elevation_deg);
    assert!((lux / expected - 1.0).abs() < 1e-9, "{lux} vs {expected}");
    // Turning it off takes it out of the view again.
    let revision = h.state().revision;
    h.get_by_label("Sun lights the scene").click();
    h.run();
    assert!(h.state().revision > revision);
    assert_eq!(h.state().render_scene().luminaires.len(), n);
}

#[test]
fn save_and_load_round_trip_and_recent_files() {
    let dir = tempfile::tempdir().unwrap();
    let store = dir.path().join("config/recent.txt");
    let path = scene_path("furnished_room.toml");
    let scene = Scene::load(&path).unwrap();
    let mut app = ViewerApp::new(
        scene,
        Some(path.clone()),
        RecentFiles::load(Some(store.clone())),
    );
    // Edit: dim and move the first luminaire, turn the camera.
    app.scene.luminaires[0].multiplier = 0.5;
    app.scene.luminaires[0].position.x += 0.25;
    app.camera.rotate(50.0, 10.0);
    app.display.mode = goniolight::scene::Mode::Illuminance;
    let saved = dir.path().join("sub/saved.toml");
    std::fs::create_dir_all(saved.parent().unwrap()).unwrap();
    app.save_scene(&saved);
    assert_eq!(app.last_error(), None);
    let back = Scene::load(&saved).unwrap();
    assert_eq!(back.luminaires.len(), app.scene.luminaires.len());
    for (a, b) in app.scene.luminaires.iter().zip(&back.luminaires) {
        assert!((a.position - b.position).length() < 1e-9);
        let err = (a.rotation - b.rotation)
            .to_cols_array()
            .iter()
            .map(|v| v.abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-9, "{}: rotation off by {err}", a.name);
        assert!((a.multiplier - b.multiplier).abs() < 1e-12);
        assert!((a.color - b.color).length() < 1e-9);
        assert_eq!(a.name, b.name);
    }
    assert_eq!(back.triangle_count(), app.scene.triangle_count());
    assert!((back.camera.position - app.camera.eye()).length() < 1e-9);
    assert_eq!(
        back.display.mode,
        Some(goniolight::scene::Mode::Illuminance)
    );
    // Recent files: newest first, kept on disk.
    let recent = RecentFiles::load(Some(store));
    assert_eq!(recent.paths[0], std::path::absolute(&saved).unwrap());
    assert_eq!(recent.paths[1], std::path::absolute(&path).unwrap());
    // Opening it again through the app replaces the scene.
    let mut other = self::app("box_room.toml");
    other.open_scene(&saved);
    assert_eq!(other.scene.luminaires.len(), back.luminaires.len());
    // A broken scene changes nothing.
    let broken = dir.path().join("broken.toml");
    std::fs::write(&broken, "[camera]\nposition = [0, 0]\n").unwrap();
    let before = placements(&other.scene);
    other.open_scene(&broken);
    assert!(other.last_error().unwrap().contains("broken.toml"));
    assert_eq!(placements(&other.scene), before);
}

#[test]
fn an_obj_model_opens_framed_with_no_lights() {
    let scene = load_scene_or_model(
        &root().join("assets/models/industrial_area.obj"),
        goniolight::scene::UpAxis::Z,
    )
    .unwrap();
    assert!(scene.luminaires.is_empty());
    assert!(scene.triangle_count() > 0);
    let (lo, hi) = scene.bounds();
    let centre = (lo + hi) / 2.0;
    assert!((scene.camera.look_at - centre).length() < 1e-9);
    let mut h = harness(ViewerApp::new(scene, None, RecentFiles::default()));
    h.run();
    h.get_by_label_contains("No lights");
}

/// A glTF model opens as an OBJ does, its own lights placed (the shared Khronos lamp's
/// five point lights), and `open_any` takes it by its extension.
#[test]
fn a_gltf_model_opens_framed_with_its_lights() {
    let lamp = common::shared_dir().join("models/gltf/LightsPunctualLamp/LightsPunctualLamp.gltf");
    let scene = load_scene_or_model(&lamp, goniolight::scene::UpAxis::Y).unwrap();
    assert_eq!(scene.luminaires.len(), 5);
    assert_eq!(scene.triangle_count(), 6_000);
    let mut a = app("box_room.toml");
    a.open_any(&lamp);
    assert!(a.last_error().is_none(), "{:?}", a.last_error());
    assert_eq!(a.scene.luminaires.len(), 5);
}

/// A TM-33 or ATLA file is added as a luminaire by `open_any`, as an LDT is.
#[test]
fn a_tm33_file_is_added_as_a_luminaire() {
    let mut a = app("box_room.toml");
    let before = a.scene.luminaires.len();
    for name in ["tm33-23_minimal.xml", "sample-luminaire.json"] {
        a.open_any(&common::shared_dir().join("luminaires/tm33").join(name));
        assert!(a.last_error().is_none(), "{name}: {:?}", a.last_error());
    }
    assert_eq!(a.scene.luminaires.len(), before + 2);
    let added = &a.scene.luminaires[before + 1];
    assert_eq!(added.luminaire.tm33.as_ref().unwrap().emitters.len(), 1);
}

#[test]
fn background_jobs_without_a_gpu_say_so() {
    let mut a = app("box_room.toml");
    a.start_radiosity();
    assert!(a.last_error().unwrap().contains("no GPU"));
    a.start_profile();
    assert!(a.last_error().unwrap().contains("no GPU"));
}

/// A scene with a mirror says, in the status bar, what the view does with it; one
/// without says nothing of the kind, and a loaded mirror scene says it too.
#[test]
fn a_mirror_scene_says_how_the_view_draws_it() {
    let says = |a: &ViewerApp| {
        a.messages
            .iter()
            .any(|m| m.text.contains("mirror or clear glass"))
    };
    let mut plain = app("box_room.toml");
    assert!(!says(&plain));
    assert!(says(&app("mirror_room.toml")));
    let glass = scene_path("glass_partition.toml");
    plain.replace_scene(Scene::load(&glass).unwrap(), Some(glass));
    assert!(says(&plain));
    let mut h = harness(plain);
    h.run();
    h.get_by_label_contains("\"glass\" is a mirror or clear glass");
}

/// Runs frames until `done` holds (at most two minutes).
fn run_until(h: &mut Harness<'_, ViewerApp>, done: impl Fn(&ViewerApp) -> bool) {
    let start = std::time::Instant::now();
    while !done(h.state()) {
        assert!(
            start.elapsed().as_secs() < 120,
            "background job did not finish"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
}

#[test]
fn radiosity_runs_in_the_background_pauses_and_converges() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let mut a = app("box_room.toml");
    a.gpu = Some(Arc::new(gpu));
    a.radiosity.settings.options.texel_density = 4.0;
    a.radiosity.settings.options.converge = 0.95;
    a.radiosity.settings.update_every_s = 0.0;
    let mut h = harness(a);
    h.get_by_label("Radiosity").click();
    h.run();
    h.get_by_label("Start").click();
    h.step();
    assert!(h.state().radiosity.worker.is_some());
    // Pause as soon as a solution is shown; while paused no shots are made.
    run_until(&mut h, |a| {
        a.radiosity.light_map.is_some() || a.radiosity.worker.is_none()
    });
    if h.state().radiosity.worker.is_some() {
        h.get_by_label("Pause").click();
        h.step();
        // A shot already under way ends first (a whole surface's shot may take a while on
        // a loaded machine): wait until the worker holds, then the count must stay still.
        let holding = |h: &Harness<'static, ViewerApp>| {
            h.state()
                .radiosity
                .worker
                .as_ref()
                .is_some_and(|w| w.control.holding.load(std::sync::atomic::Ordering::SeqCst))
        };
        for _ in 0..600 {
            if holding(&h) {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        assert!(holding(&h), "the paused worker never held");
        h.step();
        let shots = h.state().radiosity.shots;
        std::thread::sleep(std::time::Duration::from_millis(600));
        h.step();
        assert_eq!(
            h.state().radiosity.shots,
            shots,
            "paused solver kept shooting"
        );
        h.get_by_label("Resume").click();
        h.step();
    }
    run_until(&mut h, converged);
    let r = &h.state().radiosity;
    assert!(r.worker.is_some(), "a converged solver waits for changes");
    assert!(
        !h.state().busy(),
        "a waiting solver does not keep the window painting"
    );
    let last = r.log.last().unwrap();
    assert!(last[1] >= 0.95, "{last:?}");
    assert!(
        r.log.windows(2).all(|w| w[1][0] >= w[0][0]),
        "time runs forward"
    );
    let map = r.light_map.as_ref().expect("a light map");
    assert!(map.texels.iter().any(|t| t[3] > 0.0));
    // Reset drops the solution and the solver.
    h.get_by_label("Reset").click();
    h.run();
    assert!(h.state().radiosity.light_map.is_none());
    assert!(h.state().radiosity.worker.is_none());
}

#[test]
fn radiosity_splits_elements_at_shadow_edges_from_the_panel() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let mut a = app("boxes_room.toml");
    a.gpu = Some(Arc::new(gpu));
    a.radiosity.settings.options.texel_density = 4.0;
    a.radiosity.settings.options.converge = 0.9;
    a.radiosity.settings.update_every_s = 0.0;
    let mut h = harness(a);
    h.get_by_label("Radiosity").click();
    h.run();
    // The panel's slider sets the levels (the arrow key steps it by one).
    let slider = h.get_by_role_and_label(
        egui::accesskit::Role::Slider,
        "Split at shadow edges (levels)",
    );
    slider.focus();
    h.run();
    for _ in 0..2 {
        h.key_press(egui::Key::ArrowRight);
        h.run();
    }
    assert_eq!(h.state().radiosity.settings.options.adaptive, 2);
    h.get_by_label("Start").click();
    h.step();
    run_until(&mut h, converged);
    // The light map holds the finest texels: 16 per element of 1/4 m where unsplit.
    let area = goniolight::bench::radiosity::surface_area(&h.state().scene);
    let map = h.state().radiosity.light_map.clone().expect("a light map");
    let covered = map.texels.iter().filter(|t| t[3] > 0.0).count() as f64;
    assert!(
        covered > 0.8 * area * 16.0 * 16.0,
        "{covered} lit texels for {area} m²"
    );
}

/// Whether the solver says it has converged (and waits for changes).
fn converged(a: &ViewerApp) -> bool {
    a.radiosity.status.starts_with("done: converged")
}

/// Starts radiosity in `a` (box room, coarse elements, to 99.5 %) and runs it to
/// convergence.
fn solved_in_the_viewer(
    mut a: ViewerApp,
    gpu: &Arc<goniolight::gpu::Gpu>,
) -> Harness<'static, ViewerApp> {
    a.gpu = Some(gpu.clone());
    a.radiosity.settings.options.texel_density = 4.0;
    a.radiosity.settings.options.converge = 0.995;
    let mut h = harness(a);
    h.state_mut().start_radiosity();
    run_until(&mut h, converged);
    h
}

/// Mean |a − b| / mean |b| of two light maps' illuminance.
fn map_difference(
    a: &goniolight::render::lightmap::LightMap,
    b: &goniolight::render::lightmap::LightMap,
) -> f64 {
    assert_eq!(a.texels.len(), b.texels.len());
    let diff: f64 = a
        .texels
        .iter()
        .zip(&b.texels)
        .map(|(x, y)| (x[3] - y[3]).abs() as f64)
        .sum();
    let size: f64 = b.texels.iter().map(|y| y[3].abs() as f64).sum();
    diff / size
}

/// Moving and dimming a luminaire while radiosity runs re-shoots the change in place: the
/// solver goes on (its shots keep counting) and ends where a fresh solve of the changed
/// scene ends.
#[test]
fn moving_a_luminaire_relights_the_running_solution() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let gpu = Arc::new(gpu);
    let mut h = solved_in_the_viewer(app("box_room.toml"), &gpu);
    let shots = h.state().radiosity.shots;
    let before = h.state().radiosity.light_map.clone().unwrap();
    let change = |a: &mut ViewerApp| {
        a.scene.luminaires[0].position += glam::DVec3::new(1.5, 0.8, -0.3);
        a.scene.luminaires[0].multiplier *= 0.5;
    };
    change(h.state_mut());
    h.state_mut().lights_changed();
    assert!(h.state().radiosity.status.starts_with("relighting"));
    assert!(h.state().busy());
    run_until(&mut h, converged);
    let r = &h.state().radiosity;
    assert!(r.shots > shots, "relit from scratch: {} ≤ {shots}", r.shots);
    let relit = r.light_map.clone().unwrap();

    let mut moved = app("box_room.toml");
    change(&mut moved);
    let fresh = solved_in_the_viewer(moved, &gpu);
    let fresh = fresh.state().radiosity.light_map.clone().unwrap();
    let off = map_difference(&relit, &fresh);
    let stale = map_difference(&before, &fresh);
    eprintln!(
        "relit {:.3} % off the fresh solve (before the change {:.1} %)",
        100.0 * off,
        100.0 * stale
    );
    assert!(stale > 0.2, "{stale}");
    assert!(off < 0.01, "relit light map {:.3} % off", 100.0 * off);
}

/// The viewer's live solver (shooting a slice of each frame at a time, through
/// `radiosity::session::Session::step`) ends with the solution that the library's one
/// solve (what `goniolight radiosity` runs) gives from the same options.
#[test]
fn the_live_solver_gives_the_radiosity_commands_solution() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let gpu = Arc::new(gpu);
    let h = solved_in_the_viewer(app("box_room.toml"), &gpu);
    let a = h.state();
    let live = a.radiosity.light_map.clone().unwrap();
    let mut shadows = a.display.shadows.clone();
    let scene = a.render_scene();
    let setup = goniolight::radiosity::session::Setup {
        scene: &scene,
        options: &a.radiosity.settings.options,
        interp: a.display.light_model.interp(),
        shadows: &mut shadows,
        view: None,
    };
    let never = std::sync::atomic::AtomicBool::new(false);
    let solution = goniolight::radiosity::session::solve(&gpu, setup, &never, &mut |_| {}).unwrap();
    assert_eq!(solution.stop().to_string(), "converged");
    let off = map_difference(&live, &solution.light_map());
    eprintln!("live solution {:.4} % off the command's", 100.0 * off);
    assert!(off < 0.005, "live light map {:.3} % off", 100.0 * off);
}

#[test]
fn shadow_profile_runs_in_the_background_and_is_shown() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = load_scene_or_model(
        &root().join("assets/models/industrial_area.obj"),
        goniolight::scene::UpAxis::Z,
    )
    .unwrap();
    let mut a = ViewerApp::new(scene, None, RecentFiles::default());
    a.gpu = Some(Arc::new(gpu));
    a.sun.profile_resolution = 128;
    a.sun.profile_step = 60;
    let mut h = harness(a);
    h.get_by_label("Sun").click();
    h.run();
    h.get_by_label("Compute shadow profile").click();
    h.step();
    run_until(&mut h, |a| a.profile.worker.is_none());
    let app = h.state();
    let p = app.profile.result.as_ref().expect("a profile");
    // 08:00 to 16:00 every hour: 9 steps, all with the sun up in June in Vienna.
    assert_eq!(p.steps.len() + p.skipped.len(), 9);
    // The profile's steps, then as many for the hours of sun on the model from the view.
    let steps = p.steps.len();
    assert_eq!(app.profile.progress, (2 * steps, 2 * steps));
    assert!(app.profile.texture.is_some());
    let v = app
        .profile
        .view
        .as_ref()
        .expect("the model's hours from the view");
    assert_eq!((v.width, v.height, v.sun_up_h), (800, 600, p.sun_up_h));
    let seen: Vec<f32> = (0..v.sun_h.len())
        .filter(|&k| v.surface[k] != goniolight::study::shadow_profile::SURFACE_NONE)
        .map(|k| v.sun_h[k])
        .collect();
    let full = seen
        .iter()
        .filter(|&&h| (h as f64 - v.sun_up_h).abs() < 1e-4)
        .count();
    let shaded = seen
        .iter()
        .filter(|&&h| (h as f64) < v.sun_up_h - 0.5)
        .count();
    assert!(
        full > seen.len() / 4 && shaded > 1_000,
        "{full} {shaded} of {}",
        seen.len()
    );
    h.get_by_label_contains("steps, ");
    h.get_by_label("Sun on the model").click();
    h.run();
    assert!(h.state().profile.texture.is_some());
    h.get_by_label_contains("hours of sun on what the view showed");
}

#[test]
fn sunlit_roofs_get_the_clear_sky_illuminance() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = load_scene_or_model(
        &root().join("assets/models/industrial_area.obj"),
        goniolight::scene::UpAxis::Z,
    )
    .unwrap();
    let mut app = ViewerApp::new(scene, None, RecentFiles::default());
    app.sun.enabled = true;
    app.sun.minutes = 13.0 * 60.0;
    let p = app.sun.position().unwrap();
    let expected = goniolight::lighting::sun::clear_sky_direct_normal_lux(p.elevation_deg)
        * p.elevation_deg.to_radians().sin();
    // Straight down on the site: roofs and ground are horizontal and face the sky.
    let (lo, hi) = app.scene.bounds();
    app.camera.yaw_deg = 90.0;
    app.camera.pitch_deg = -89.0;
    app.camera.frame(lo, hi);
    let normal = goniolight::lighting::sun::clear_sky_direct_normal_lux(p.elevation_deg);
    let renderer = goniolight::render::Renderer::new(&gpu);
    let mut dark = Vec::new();
    for technique in [ShadowTechnique::None, ShadowTechnique::Volumes] {
        app.display.shadows.technique = technique;
        app.display.mode = goniolight::scene::Mode::Illuminance;
        let mut settings = app.render_settings(200, 200);
        settings.read_hdr = true;
        let uploaded = renderer.upload(&gpu, &app.render_scene());
        let frame = renderer
            .render(&gpu, &uploaded, &app.camera.camera(app.extent()), &settings)
            .unwrap();
        let lux: Vec<f64> = frame
            .hdr
            .unwrap()
            .iter()
            .map(|p| p[3] as f64)
            .filter(|&l| l >= 0.0)
            .collect();
        let flat = lux
            .iter()
            .filter(|&&l| (l / expected - 1.0).abs() < 0.02)
            .count();
        let max = lux.iter().copied().fold(0.0, f64::max);
        dark.push(lux.iter().filter(|&&l| l < 1.0).count());
        eprintln!("{technique:?}: {flat} of {} seen pixels at {expected:.0} lx ± 2 % (flat roofs), max {max:.0} (normal {normal:.0}), {} dark", lux.len(), dark.last().unwrap());
        // The flat roofs are the largest family of surfaces seen from above; no surface
        // gets more than the normal illuminance.
        assert!(
            flat * 4 > lux.len(),
            "{technique:?}: {flat} of {}",
            lux.len()
        );
        assert!(max <= normal * 1.01, "{max} > {normal}");
    }
    // Shadow volumes put the lower roofs partly in the shade of the higher buildings.
    assert!(
        dark[1] > dark[0],
        "dark pixels: no shadows {}, volumes {}",
        dark[0],
        dark[1]
    );
}

#[test]
fn viewport_reads_the_lux_under_the_cursor_and_saves_png_and_exr() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let dir = tempfile::tempdir().unwrap();
    let mut app = app("box_room.toml");
    app.display.mode = goniolight::scene::Mode::Illuminance;
    app.status.viewport_px = [200, 150];
    app.status.cursor_px = Some([100, 120]);
    let shot = dir.path().join("view.png");
    app.requests.screenshot = Some(shot.clone());
    let mut egui_renderer = egui_wgpu::Renderer::new(
        &gpu.device,
        wgpu::TextureFormat::Rgba8Unorm,
        egui_wgpu::RendererOptions::default(),
    );
    let mut viewport = goniolight::viewer::viewport_gpu::Viewport::new(&gpu);
    viewport.update(&gpu, &mut app, &mut egui_renderer).unwrap();
    assert!(app.viewport_texture.is_some());
    assert_eq!(app.last_error(), None);
    let png = image::open(&shot).unwrap();
    // The lux legend is a panel beside the 200 × 150 view; the EXR is the view alone.
    assert!(
        png.width() > 200 && png.height() == 150,
        "{:?}",
        (png.width(), png.height())
    );
    let exr = image::open(shot.with_extension("exr")).unwrap().to_rgb32f();
    assert_eq!(exr.dimensions(), (200, 150));
    let at_cursor = exr.get_pixel(100, 120)[0] as f64;
    let read = app.status.cursor_lux.expect("lux under the cursor");
    assert!(read > 1.0, "{read}");
    assert!(
        (read / at_cursor - 1.0).abs() < 1e-5,
        "{read} vs {at_cursor}"
    );
    app.status.cursor_px = Some([20, 10]);
    viewport.update(&gpu, &mut app, &mut egui_renderer).unwrap();
    let other = app.status.cursor_lux.unwrap_or(-1.0);
    assert!((other - exr.get_pixel(20, 10)[0] as f64).abs() <= 1e-5 * other.abs().max(1.0));
}

#[test]
fn photometry_window_shows_the_datasheet_diagrams_ldt_plot_draws() {
    let mut h = harness(app("box_room.toml"));
    h.get_by_label_contains("1: ").click();
    h.run();
    h.get_by_label("Photometry…").click();
    h.run();
    assert_eq!(h.state().photometry_view.sheet_size(), None);
    h.get_by_label("Isocandela").click();
    h.run();
    assert_eq!(h.state().photometry_view.sheet_size(), Some([1100, 860]));
    // The picture is `ldt plot`'s, pixel for pixel.
    let interp = h.state().display.light_model.interp();
    let l = &h.state().scene.luminaires[0];
    let shown = goniolight::viewer::photometry_sheet::datasheet_image(
        l,
        goniolight::photometry::datasheet_plot::DiagramKind::Isocandela,
        interp,
    )
    .unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let png = tmp.path().join("iso.png");
    let name = match interp {
        Interp::Nearest => "nearest",
        Interp::Bilinear => "bilinear",
        Interp::CatmullRom => "catmull-rom",
        Interp::Monotone => "monotone",
    };
    let (code, _, err) = common::run_cli(
        &[
            "ldt",
            "plot",
            l.file.to_str().unwrap(),
            "--kind",
            "isocandela",
            "--interp",
            name,
            "--out",
            png.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let plotted = image::open(&png).unwrap().to_rgba8();
    assert_eq!(
        shown.size,
        [plotted.width() as usize, plotted.height() as usize]
    );
    assert!(
        shown.as_raw() == plotted.as_raw(),
        "the viewer's diagram differs from ldt plot's"
    );
    // Back to the interpolation comparison.
    h.get_by_label("Interpolations").click();
    h.run();
    h.get_by_label("Beam angle (50 %)");
}

/// A perspective-driven solver in the viewer follows the camera once it stands still:
/// the importance is solved again for the new view and the solution goes on (no restart).
#[test]
fn a_view_driven_solver_follows_the_camera() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let mut a = app("boxes_room.toml");
    a.gpu = Some(Arc::new(gpu));
    a.radiosity.settings.options.texel_density = 4.0;
    a.radiosity.settings.options.converge = 0.999;
    a.radiosity.settings.options.drive = goniolight::radiosity::view::Drive::Perspective;
    let mut h = harness(a);
    h.state_mut().start_radiosity();
    run_until(&mut h, |a| a.radiosity.shots > 0);
    let shots = h.state().radiosity.shots;
    // A little to the side and down: the eye stays in the room.
    h.state_mut().camera.rotate(-3.0, -10.0);
    run_until(&mut h, |a| {
        a.radiosity.status.starts_with("following the view")
    });
    let r = &h.state().radiosity;
    assert!(r.shots >= shots, "restarted: {} < {shots}", r.shots);
    let view = h.state().camera.camera(h.state().extent());
    assert_eq!(r.followed.as_ref().map(|f| &f.0), Some(&view));
    run_until(&mut h, converged);
}
