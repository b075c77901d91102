//! Shooters are whole surfaces (`--hierarchy clusters`): each connected surface of one
//! material is one shooter, its flat clusters its pieces. Checked: the real models shoot
//! from far fewer shooters than triangles (goal: at most a tenth), every element is in
//! exactly one piece and one shooter, a shot's plan shoots each element at most once —
//! strong pieces from cells sized by their own power, weak curved parts from merged cells
//! within the error bound, the weakest not yet — and a shooter whose pieces light each
//! other still gives the furnace's B = E / (1 − ρ) when shots are stopped after a batch and
//! resumed.

use crate::common;

use glam::DVec3;
use goniolight::radiosity::cpu::CpuSolver;
use goniolight::radiosity::gpu::{GpuSettings, GpuSolver};
use goniolight::radiosity::links::LINK_LEVELS;
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::shooters::{
    Hierarchy, PlanCache, Shooters, ShotPlan, DEFAULT_PLAN_CACHE_BYTES, MERGE_NORMALS, SKIP_SHARE,
};
use goniolight::radiosity::SolverSettings;
use goniolight::scene::Scene;

use crate::furnace_common;
use crate::gpu_common;

fn cathedral() -> RadiosityScene {
    let obj = common::shared_dir().join("models/sibenik/sibenik.obj");
    let toml = format!(
        "[[model]]\npath = {:?}\nup = \"y\"\n",
        obj.display().to_string()
    );
    let scene = Scene::from_toml(&obj.with_file_name("test.toml"), &toml).unwrap();
    RadiosityScene::with_hierarchy(&scene, 2.0, 1, Hierarchy::Clusters).unwrap()
}

/// Every element of shooter `s` is in `plan.order` once, the top cells tile the shot part,
/// and every cell shoots pieces of `s` only.
fn check_plan(shooters: &Shooters, s: usize, plan: &ShotPlan) {
    let mut order = plan.order.clone();
    let mut elements = shooters.elements_of(s).to_vec();
    order.sort_unstable();
    elements.sort_unstable();
    assert_eq!(order, elements, "shooter {s}: every element once");
    let mut next = 0;
    let pieces = shooters.pieces_of(s);
    for cell in &plan.patches {
        if cell.parent == u32::MAX {
            assert_eq!(cell.first, next, "shooter {s}: top cells tile the shot");
            next = cell.first + cell.count;
        }
        let [a, b] = cell.pieces.map(|p| p as usize);
        assert!(pieces.start <= a && a < b && b <= pieces.end);
        for &e in &plan.order[cell.first as usize..][..cell.count as usize] {
            let p = shooters.element_piece[e as usize] as usize;
            assert!((a..b).contains(&p), "shooter {s}: element {e} of piece {p}");
        }
    }
    assert_eq!(next, plan.shot);
}

#[test]
fn the_cathedral_shoots_from_fewer_than_a_tenth_of_its_triangles() {
    let r = cathedral();
    let triangles = r.elements.triangles.len();
    let shooters = Shooters::clusters(&r);
    let planar = Shooters::planar(&r);
    eprintln!(
        "cathedral: {triangles} triangles, {} shooters of {} pieces",
        shooters.len(),
        shooters.pieces.len()
    );
    assert!(
        shooters.len() * 10 <= triangles,
        "{} shooters",
        shooters.len()
    );
    // The pieces are the planar clusters, one shooter each in the planar reference.
    assert_eq!(shooters.pieces, planar.pieces);
    assert_eq!(planar.len(), planar.pieces.len());
    let el = &r.elements;
    let mut seen = vec![0u32; el.len()];
    for s in 0..shooters.len() {
        for p in shooters.pieces_of(s) {
            for &e in shooters.piece_elements(p) {
                seen[e as usize] += 1;
                assert_eq!(shooters.element_piece[e as usize] as usize, p);
                assert_eq!(shooters.element_shooter[e as usize] as usize, s);
                assert_eq!(
                    r.element_reflectance(e as usize),
                    r.reflectance[shooters.material[s]],
                    "one material per shooter"
                );
            }
        }
        let area: f64 = shooters.pieces_of(s).map(|p| shooters.pieces[p].area).sum();
        assert!((area - shooters.area[s]).abs() <= 1e-9 * area);
    }
    assert!(
        seen.iter().all(|&n| n == 1),
        "an element not in exactly one piece"
    );
}

#[test]
fn a_shot_sizes_cells_by_each_pieces_power_merges_weak_curved_parts_and_defers_the_weakest() {
    let r = cathedral();
    let shooters = Shooters::clusters(&r);
    // The shooters with the most pieces (the curved ones).
    let mut by_pieces: Vec<usize> = (0..shooters.len()).collect();
    by_pieces.sort_by_key(|&s| std::cmp::Reverse(shooters.piece_count[s]));
    let mut merged_cells = 0;
    let mut deferred = 0;
    for &s in by_pieces.iter().take(8) {
        let pieces = shooters.pieces_of(s);
        // Uneven power: a piece's area times a factor from 0.001 to 1.
        let power: Vec<f64> = pieces
            .clone()
            .enumerate()
            .map(|(k, p)| shooters.pieces[p].area * 10f64.powi(-((k % 4) as i32)))
            .collect();
        let total: f64 = power.iter().sum();
        let strongest_piece = power.iter().copied().fold(0.0, f64::max);
        // Strong: a cell may carry a millionth of the shooter's power; nothing merges, and
        // each shot piece shoots from the oracle's cells for its own power.
        let budget = 1e-6 * total;
        let plan = shooters.plan_shot(&r, s, &power, budget, 0, &mut PlanCache::new(0));
        check_plan(&shooters, s, &plan);
        for (k, p) in pieces.clone().enumerate() {
            let cells: Vec<_> = plan
                .patches
                .iter()
                .filter(|c| c.pieces == [p as u32, p as u32 + 1])
                .collect();
            if power[k] < SKIP_SHARE * strongest_piece {
                assert!(cells.is_empty(), "piece {p} is too weak to shoot now");
                deferred += 1;
                continue;
            }
            assert!(!cells.is_empty(), "piece {p} shoots");
            let side = shooters.cell_side(p, power[k], budget);
            for c in &cells {
                assert!(!c.merged);
                assert_eq!(c.normal, shooters.pieces[p].normal);
                // Its cell fits the oracle's side (the grid's cell, clipped to the piece).
                let extent = c
                    .polygon
                    .iter()
                    .flat_map(|a| c.polygon.iter().map(move |b| a.distance(*b)))
                    .fold(0.0, f64::max);
                assert!(
                    extent <= side * 2f64.sqrt() * (1.0 + 1e-9) + 1e-9,
                    "{extent} > {side}"
                );
            }
        }
        // Weak: the whole shooter carries less than a cell's budget, so its curved parts
        // merge into cells facing their summed area normal.
        let budget = 2.0 * total;
        let plan = shooters.plan_shot(&r, s, &power, budget, 0, &mut PlanCache::new(0));
        check_plan(&shooters, s, &plan);
        for c in plan.patches.iter().filter(|c| c.merged) {
            merged_cells += 1;
            let [a, b] = c.pieces.map(|p| p as usize);
            assert!(b - a >= 2, "a merged cell holds two pieces or more");
            let k = a - pieces.start;
            let held: f64 = power[k..k + (b - a)].iter().sum();
            assert!(held <= budget);
            let s_vec: DVec3 = (a..b)
                .map(|p| shooters.pieces[p].normal * shooters.pieces[p].area)
                .sum();
            let area: f64 = (a..b).map(|p| shooters.pieces[p].area).sum();
            // The pieces' own normals agree within the bound (a node's summed normal is
            // its triangles', so this recomputes it from the pieces').
            assert!(
                s_vec.length() >= MERGE_NORMALS * area * 0.999,
                "{} of {area}",
                s_vec.length()
            );
            assert!(c.normal.dot(s_vec.normalize()) > 0.999);
            // It shoots its elements' power: polygon area × scale = elements' area.
            let elements: f64 = (a..b)
                .flat_map(|p| shooters.piece_elements(p))
                .map(|&e| r.elements.area[e as usize])
                .sum();
            assert!((c.element_area - elements).abs() <= 1e-9 * elements);
            assert!((c.area * c.power_scale() - elements).abs() <= 1e-6 * elements);
        }
        assert!(
            plan.patches.len() < pieces.len(),
            "shooter {s}: {} cells for {} pieces",
            plan.patches.len(),
            pieces.len()
        );
    }
    eprintln!("{merged_cells} merged cells, {deferred} pieces deferred");
    assert!(merged_cells > 0 && deferred > 0);
}

#[test]
fn a_cached_plan_is_the_plan_made_afresh() {
    let r = cathedral();
    let shooters = Shooters::clusters(&r);
    let mut by_pieces: Vec<usize> = (0..shooters.len()).collect();
    by_pieces.sort_by_key(|&s| std::cmp::Reverse(shooters.piece_count[s]));
    let mut cache = PlanCache::new(DEFAULT_PLAN_CACHE_BYTES);
    let mut units = 0;
    // The same shooters at three powers (strong: fine cells; middling; weak: merged
    // cells), twice over: the second round is all hits and equal to the first.
    for round in 0..2 {
        for &s in by_pieces.iter().take(6) {
            let power: Vec<f64> = shooters
                .pieces_of(s)
                .map(|p| shooters.pieces[p].area)
                .collect();
            let total: f64 = power.iter().sum();
            for budget in [1e-4 * total, 0.05 * total, 2.0 * total] {
                let fresh =
                    shooters.plan_shot(&r, s, &power, budget, LINK_LEVELS, &mut PlanCache::new(0));
                let misses = cache.misses;
                let cached = shooters.plan_shot(&r, s, &power, budget, LINK_LEVELS, &mut cache);
                assert_eq!(cached, fresh, "shooter {s}, budget {budget}");
                if round == 1 {
                    assert_eq!(cache.misses, misses, "shooter {s}: all from the cache");
                } else {
                    units += cache.misses - misses;
                }
            }
        }
    }
    assert!(
        units > 0 && cache.hits >= units,
        "{units} units, {} hits",
        cache.hits
    );
    // A cache with no room makes every plan and keeps none.
    let mut none = PlanCache::new(0);
    let s = by_pieces[0];
    let power: Vec<f64> = shooters
        .pieces_of(s)
        .map(|p| shooters.pieces[p].area)
        .collect();
    let budget = 0.05 * power.iter().sum::<f64>();
    for _ in 0..2 {
        let plan = shooters.plan_shot(&r, s, &power, budget, LINK_LEVELS, &mut none);
        assert_eq!(
            plan,
            shooters.plan_shot(&r, s, &power, budget, LINK_LEVELS, &mut PlanCache::new(0))
        );
    }
    assert_eq!((none.hits, none.bytes()), (0, 0));
}

#[test]
fn furnace_shots_stopped_after_a_batch_still_give_e_over_one_minus_rho() {
    let Some(gpu) = gpu_common::gpu() else { return };
    // A closed box of one material: one surface, so one shooter whose six faces (its
    // pieces) light each other during its shots. ρ = 0.5, E = 100 lm/m²: B = 200 lm/m².
    let scene = furnace_common::closed_box(0.5, 100.0);
    let r = RadiosityScene::with_hierarchy(&scene, 8.0, 0, Hierarchy::Clusters).unwrap();
    let settings = SolverSettings::default();
    let initial = CpuSolver::new(&r, settings).state();
    let gpu_settings = GpuSettings {
        hierarchy: Hierarchy::Clusters,
        ..GpuSettings::default()
    };
    let mut solver = GpuSolver::new(&gpu, &r, &initial, settings, gpu_settings);
    assert_eq!(solver.shooters().len(), 1);
    assert_eq!(solver.shooters().pieces.len(), 6);
    let mut stopped = 0;
    let mut start = None;
    for shot in 0..400 {
        let selection = solver.select().unwrap();
        let total = *start.get_or_insert(selection.unshot_power);
        let Some(s) = selection.shooter else { break };
        if selection.unshot_power <= 1e-4 * total {
            break;
        }
        // Every other shot stops after its first batch (stopping every shot would shoot
        // the same first cells again and again).
        let before = (solver.unshot().unwrap(), solver.radiosity().unwrap());
        if !solver.shoot_until(s, &|| shot % 2 == 0).unwrap() {
            stopped += 1;
        }
        // Energy: what left the unshot radiosity (less what came back as received light)
        // is what was shot, and half of it (ρ) comes back: nothing lost, nothing twice.
        let power =
            |b: &[DVec3]| -> f64 { b.iter().zip(&r.elements.area).map(|(b, a)| b.x * a).sum() };
        let received = power(&solver.radiosity().unwrap()) - power(&before.1);
        let shot_power = power(&before.0) - power(&solver.unshot().unwrap()) + received;
        assert!(
            (received - 0.5 * shot_power).abs() <= 2e-3 * shot_power,
            "shot {shot}: {shot_power} lm shot, {received} lm received"
        );
    }
    let b = solver.radiosity().unwrap();
    let worst = b
        .iter()
        .map(|b| (b.x / 200.0 - 1.0).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "furnace, one shooter of six pieces: {} shots ({stopped} stopped after a batch), worst {:.3} %",
        solver.stats.shots,
        100.0 * worst
    );
    assert!(stopped > 0, "no shot was stopped");
    assert!(worst <= 0.005, "worst relative error {worst}");
}
