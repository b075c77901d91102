//! Light-map charts from face clusters (`--hierarchy clusters`): a planar cluster's
//! triangles share one rectangle of the atlas, so the light map runs on across their shared
//! edges. Checked: no seam along the box-room floor's diagonal (and the check sees the seam
//! of one rectangle per triangle), the same light as the per-triangle layout, and that
//! charts tile their triangles exactly on the CAD-like room (the furnace on charts is in
//! `tests/gpu/radiosity.rs`, with ambient overshooting).

use std::path::Path;
use std::sync::Arc;

use glam::{DVec2, DVec3};
use goniolight::radiosity::scene::{luminance, RadiosityScene};
use goniolight::radiosity::shooters::Hierarchy;
use goniolight::radiosity::solve;
use goniolight::render::lightmap::LightMap;
use goniolight::scene::Scene;

use crate::gpu_common;
use crate::solve_common;

fn bundled(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes")
        .join(name);
    Scene::load(&path).unwrap()
}

/// The bundled scene `name` laid out by `hierarchy` (its charts and its shooters) at ten
/// texels a metre and solved to 99.9 % (once for the tests that compare with it:
/// [`solve_common::bundled_solve`]), and its displayed light map.
fn solved(
    gpu: &goniolight::gpu::Gpu,
    name: &str,
    hierarchy: Hierarchy,
) -> (Arc<solve_common::BundledSolve>, LightMap) {
    let s = solve_common::bundled_solve(gpu, name, 10.0, (hierarchy, hierarchy), 0.999);
    let map = solve::light_map(&s.r, &s.solved.radiosity, &s.solved.illuminance);
    (s, map)
}

/// The scene's triangle corners, in its order.
fn corners(scene: &Scene) -> Vec<[DVec3; 3]> {
    let mesh = scene.caster_mesh();
    mesh.triangles
        .iter()
        .map(|t| t.map(|i| mesh.positions[i as usize]))
        .collect()
}

/// Barycentric coordinates of `p` in the triangle `c` (in its plane).
fn barycentric(c: &[DVec3; 3], p: DVec3) -> [f64; 3] {
    let (v0, v1, d) = (c[1] - c[0], c[2] - c[0], p - c[0]);
    let (d00, d01, d11) = (v0.dot(v0), v0.dot(v1), v1.dot(v1));
    let (d20, d21) = (d.dot(v0), d.dot(v1));
    let den = d00 * d11 - d01 * d01;
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    [1.0 - v - w, v, w]
}

/// The displayed illuminance (the light map's alpha) at `p` on triangle `t`, filtered
/// bilinearly through the triangle's atlas coordinates as the renderer does.
fn shown(map: &LightMap, corners: &[[DVec3; 3]], t: usize, p: DVec3) -> f64 {
    let b = barycentric(&corners[t], p);
    let uv = map.triangle_uv[t];
    let q = (uv[0] * b[0] as f32 + uv[1] * b[1] as f32 + uv[2] * b[2] as f32)
        * glam::Vec2::new(map.width as f32, map.height as f32)
        - glam::Vec2::splat(0.5);
    let (x0, y0) = (q.x.floor(), q.y.floor());
    let (fx, fy) = ((q.x - x0) as f64, (q.y - y0) as f64);
    let at = |x: f32, y: f32| {
        let x = (x.max(0.0) as u32).min(map.width - 1);
        let y = (y.max(0.0) as u32).min(map.height - 1);
        map.texels[(y * map.width + x) as usize][3] as f64
    };
    let top = at(x0, y0) * (1.0 - fx) + at(x0 + 1.0, y0) * fx;
    let bottom = at(x0, y0 + 1.0) * (1.0 - fx) + at(x0 + 1.0, y0 + 1.0) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// Seam measures on the box-room floor (triangles 0 and 1 share the diagonal from (0, 0)
/// to (6, 4)): the largest jump between the two triangles' values at points of the
/// diagonal; the mean |second difference| across the diagonal (one texel each way); and
/// the same second difference on lines 0.5 m inside either triangle.
fn floor_seam(map: &LightMap, corners: &[[DVec3; 3]], texel: f64) -> (f64, f64, f64) {
    let along = DVec3::new(6.0, 4.0, 0.0);
    let across = DVec3::new(-4.0, 6.0, 0.0).normalize();
    let inside = |t: usize, p: DVec3| barycentric(&corners[t], p).iter().all(|&b| b >= 0.0);
    let value = |p: DVec3| {
        let t = if inside(0, p) { 0 } else { 1 };
        shown(map, corners, t, p)
    };
    let (mut jump, mut seam, mut interior) = (0.0f64, Vec::new(), Vec::new());
    for k in 1..40 {
        let p = along * (k as f64 / 40.0);
        let (a, b) = (shown(map, corners, 0, p), shown(map, corners, 1, p));
        jump = jump.max((a - b).abs() / a.abs().max(b.abs()).max(1e-9));
        let second = |q: DVec3, centre: f64| {
            (value(q + across * texel) - 2.0 * centre + value(q - across * texel)).abs()
        };
        seam.push(second(p, 0.5 * (a + b)));
        for offset in [-0.5, 0.5] {
            let q = p + across * offset;
            let both = [q, q + across * texel, q - across * texel];
            for t in 0..2 {
                if both.iter().all(|&x| inside(t, x)) {
                    interior.push(second(q, shown(map, corners, t, q)));
                }
            }
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    (jump, mean(&seam), mean(&interior))
}

#[test]
fn the_box_room_floor_has_no_seam_along_its_diagonal() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = bundled("box_room.toml");
    let c = corners(&scene);
    // The floor is triangles 0 and 1 (the fan of its quad).
    assert!(c[0].iter().chain(&c[1]).all(|p| p.z == 0.0));
    let (charted, map) = solved(&gpu, "box_room.toml", Hierarchy::Clusters);
    let el = &charted.r.elements;
    assert_eq!(el.triangles[0].chart, el.triangles[1].chart, "one chart");
    let (jump, seam, interior) = floor_seam(&map, &c, 0.1);
    eprintln!("charts: jump {jump:.2e}, seam {seam:.3} lx, interior {interior:.3} lx");
    assert!(
        jump < 1e-5,
        "the two triangles show different values: {jump}"
    );
    assert!(
        seam <= 1.5 * interior,
        "across the diagonal {seam} lx, inside {interior} lx"
    );
    // The check sees the seam of one rectangle per triangle.
    let (_, per_triangle) = solved(&gpu, "box_room.toml", Hierarchy::None);
    let (jump, seam, interior) = floor_seam(&per_triangle, &c, 0.1);
    eprintln!("per triangle: jump {jump:.2e}, seam {seam:.3} lx, interior {interior:.3} lx");
    assert!(
        jump > 1e-3 || seam > 1.5 * interior,
        "no seam seen: {jump} {seam} {interior}"
    );
}

/// Radiosity luminance × area and area per cube of `side` metres and facing direction
/// (elements binned by centroid).
fn binned(
    r: &RadiosityScene,
    b: &[DVec3],
    side: f64,
) -> std::collections::HashMap<[i64; 6], (f64, f64)> {
    let el = &r.elements;
    let mut bins: std::collections::HashMap<[i64; 6], (f64, f64)> = Default::default();
    for (e, b) in b.iter().enumerate() {
        // 12.5 cm in front of the surface: rounding across it moves nothing.
        let cell = ((el.position[e] + el.normal(e) * 0.125) / side)
            .floor()
            .as_i64vec3();
        let facing = el.normal(e).round().as_i64vec3();
        let key = [cell.x, cell.y, cell.z, facing.x, facing.y, facing.z];
        let bin = bins.entry(key).or_default();
        bin.0 += luminance(*b) * el.area[e];
        bin.1 += el.area[e];
    }
    bins
}

#[test]
fn charts_give_the_per_triangle_light_over_the_same_areas() {
    let Some(gpu) = gpu_common::gpu() else { return };
    for name in ["box_room.toml", "boxes_room.toml"] {
        let scene = bundled(name);
        let (flat, charted) = (
            solved(&gpu, name, Hierarchy::None).0,
            solved(&gpu, name, Hierarchy::Clusters).0,
        );
        let (flat, flat_b) = (&flat.r, &flat.solved.radiosity);
        let (charted, chart_b) = (&charted.r, &charted.solved.radiosity);
        assert!(charted.elements.charts.len() < flat.elements.charts.len());
        // The same surfaces, cut into texels along other axes: the power each direction's
        // surfaces send out, and the mean radiosity over half-metre pieces of them (but
        // next to a luminaire, 5 cm under the ceiling: there the texel at its foot carries
        // ten times its neighbours', and which piece it falls in depends on the grid).
        let (a, f) = (binned(charted, chart_b, 1e3), binned(flat, flat_b, 1e3));
        for (key, &(power, _)) in &f {
            let p = a[key].0;
            eprintln!("{name}: facing {:?}: {p:.1} vs {power:.1} lm", &key[3..]);
            assert!(
                (p / power - 1.0).abs() < 0.01,
                "{name} {key:?}: {p} vs {power}"
            );
        }
        let (a, f) = (binned(charted, chart_b, 0.5), binned(flat, flat_b, 0.5));
        let near_luminaire = |key: &[i64; 6]| {
            let centre = DVec3::new(key[0] as f64, key[1] as f64, key[2] as f64) * 0.5 + 0.25;
            let d = |l: &goniolight::scene::PlacedLuminaire| l.position.distance(centre);
            scene.luminaires.iter().any(|l| d(l) < 0.75)
        };
        let (mut diff, mut total) = (0.0, 0.0);
        for (key, &(power, area)) in f.iter().filter(|(k, _)| !near_luminaire(k)) {
            let Some(&(p, q)) = a.get(key) else {
                assert!(
                    area < 0.01,
                    "{name}: {key:?} ({area} m²) missing from the charts"
                );
                continue;
            };
            diff += (p / q - power / area).abs() * area;
            total += power;
        }
        let d = diff / total;
        eprintln!(
            "{name}: {} elements in {} charts vs {} in {}: mean difference {:.3} %",
            charted.elements.len(),
            charted.elements.charts.len(),
            flat.elements.len(),
            flat.elements.charts.len(),
            100.0 * d
        );
        assert!(d <= 0.01, "{name}: {d}");
    }
}

#[test]
fn the_cad_room_strips_share_charts_that_tile_them_exactly() {
    let scene = bundled("cad_room.toml");
    let flat = RadiosityScene::new(&scene, 10.0, 2).unwrap();
    let r = RadiosityScene::with_hierarchy(&scene, 10.0, 2, Hierarchy::Clusters).unwrap();
    let el = &r.elements;
    let c = corners(&scene);
    eprintln!(
        "CAD room: {} triangles; per triangle {} elements, charts {} elements in {} charts",
        c.len(),
        flat.elements.len(),
        el.len(),
        el.charts.len()
    );
    assert!(el.charts.len() * 20 < c.len(), "{} charts", el.charts.len());
    assert!(el.len() * 2 < flat.elements.len());
    let mut seen = vec![0; c.len()];
    for (k, chart) in el.charts.iter().enumerate() {
        let want: f64 = chart
            .triangles
            .iter()
            .map(|&t| {
                seen[t as usize] += 1;
                assert_eq!(el.triangles[t as usize].chart, k as u32);
                let [a, b, d] = c[t as usize];
                0.5 * (b - a).cross(d - a).length()
            })
            .sum();
        let elements = chart.first as usize..(chart.first + chart.count) as usize;
        let sum: f64 = el.area[elements.clone()].iter().sum();
        assert!(
            (sum - want).abs() <= 1e-9 * want.max(1.0),
            "{sum} vs {want}"
        );
        let patches = &el.patches[chart.first_patch as usize..][..chart.patch_count as usize];
        assert_eq!(
            patches.iter().map(|p| p.count).sum::<u32>(),
            chart.count,
            "patches cover the chart"
        );
        // Every element lies in the chart's plane, on one of its triangles' boxes.
        for e in elements {
            let p = el.position[e];
            assert!((p - chart.origin).dot(chart.normal).abs() < 1e-9);
            let on = chart.triangles.iter().any(|&t| {
                let [a, b, d] = c[t as usize];
                let (lo, hi) = (a.min(b).min(d), a.max(b).max(d));
                (p.cmpge(lo - 1e-9) & p.cmple(hi + 1e-9)).all()
            });
            assert!(on, "element {e} off its chart");
        }
        // Shared corners have the same atlas coordinates in every triangle.
        let mut at: std::collections::HashMap<[u64; 3], DVec2> = Default::default();
        for &t in &chart.triangles {
            for (k, p) in c[t as usize].iter().enumerate() {
                let uv = el.triangles[t as usize].atlas_uv[k];
                let key = p.to_array().map(f64::to_bits);
                let first = *at.entry(key).or_insert(uv);
                assert!(
                    first.distance(uv) < 1e-9,
                    "a shared corner moves in the atlas"
                );
            }
        }
    }
    assert!(seen.iter().all(|&n| n == 1), "every triangle in one chart");
}

#[test]
fn a_density_that_cannot_fit_is_refused_before_clustering() {
    let scene = bundled("cad_room.toml");
    let err = RadiosityScene::with_hierarchy(&scene, 1e6, 2, Hierarchy::Clusters).unwrap_err();
    assert!(
        matches!(err, goniolight::radiosity::elements::ElementError::TooLarge(n) if n > 1_000_000_000_000),
        "{err}"
    );
    assert!(err.to_string().starts_with("about 1."), "{err}");
}

/// A 4 m floor of two triangles (material 1) and, above it, a wavy 0.4 m sheet of 800
/// triangles 2 cm across (material 2), laid out at 10 texels per metre.
fn floor_and_sheet() -> RadiosityScene {
    use goniolight::scene::{Camera, Material, SceneMesh};
    let v = |x: f64, y: f64, z: f64| glam::Vec3::new(x as f32, y as f32, z as f32);
    let floor = [
        [v(0.0, 0.0, 0.0), v(4.0, 0.0, 0.0), v(4.0, 4.0, 0.0)],
        [v(0.0, 0.0, 0.0), v(4.0, 4.0, 0.0), v(0.0, 4.0, 0.0)],
    ];
    let (cells, side) = (20, 0.4);
    let at = |i: usize, j: usize| {
        let (x, y) = (
            1.0 + side * i as f64 / cells as f64,
            1.0 + side * j as f64 / cells as f64,
        );
        v(x, y, 0.5 + 0.02 * (std::f64::consts::TAU * x / 0.2).sin())
    };
    let mut sheet = Vec::new();
    for i in 0..cells {
        for j in 0..cells {
            sheet.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            sheet.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let scene = Scene::in_code(
        "floor and sheet",
        vec![
            SceneMesh::from_triangles("floor", &floor, 1),
            SceneMesh::from_triangles("sheet", &sheet, 2),
        ],
        vec![Material::default(); 3],
        Vec::new(),
        Camera::perspective(DVec3::ONE, DVec3::ZERO, 60.0),
    );
    RadiosityScene::with_hierarchy(&scene, 10.0, 2, Hierarchy::Clusters).unwrap()
}

/// Edström §5.3: surfaces that vertex lighting would split most are light-mapped until the
/// triangles it introduces fit the budget (default 10 % of the model's triangles); a
/// surface finer than its light map introduces none and keeps its vertices; the scene
/// file's choice and `--bake map|vertex` override the heuristic. The introduced triangles
/// are those of Edström's patch refinement: the floor's patches are at most a 32nd of its
/// diagonal long.
#[test]
fn representation_follows_the_introduced_triangles_and_the_overrides() {
    use goniolight::radiosity::bake::{patch_size, plan, BakeChoice};
    use goniolight::scene::file::Bake::{Map, Vertex};
    let r = floor_and_sheet();
    let size = patch_size(&r, 0);
    assert!((size - 4.0 * 2f64.sqrt() / 32.0).abs() < 1e-12, "{size}");
    // Each patch fits a size × size square, so the 16 m² floor has at least 16 / size²
    // of them; regular refinement (32 parts per side) would add 2 · (32² − 1) triangles.
    let floor_introduced = plan(&r, &[], BakeChoice::Vertex, None).introduced;
    let fewest = (16.0 / (size * size)).ceil() as u64 - 2;
    assert!(
        (fewest..2 * (32 * 32 - 1)).contains(&floor_introduced),
        "{floor_introduced} (at least {fewest})"
    );
    let is = |p: &goniolight::radiosity::bake::BakePlan, floor, sheet| {
        p.bake[..2].iter().all(|&b| b == Some(floor))
            && p.bake[2..].iter().all(|&b| b == Some(sheet))
    };
    let auto = plan(&r, &[], BakeChoice::Auto, None);
    assert!(is(&auto, Map, Vertex), "{:?}", auto.surfaces);
    assert!(
        auto.parts[2..].iter().all(|p| p.len() == 1),
        "the sheet is finer than its texels"
    );
    assert_eq!((auto.budget, auto.introduced), (80, 0));
    assert_eq!((auto.surfaces, auto.triangles), ([1, 1], [2, 800]));
    // A budget that holds the floor's split triangles keeps it vertex-lit.
    let roomy = plan(&r, &[], BakeChoice::Auto, Some(floor_introduced));
    assert!(is(&roomy, Vertex, Vertex));
    assert_eq!(roomy.introduced, floor_introduced);
    assert!((roomy.overhead() - floor_introduced as f64 / 802.0).abs() < 1e-12);
    assert!(is(
        &plan(&r, &[], BakeChoice::Auto, Some(floor_introduced - 1)),
        Map,
        Vertex
    ));
    // The scene file's choice stands over the budget.
    let fixed = plan(&r, &[None, Some(Vertex), Some(Map)], BakeChoice::Auto, None);
    assert!(is(&fixed, Vertex, Map));
    assert_eq!(fixed.introduced, floor_introduced);
    // --bake map|vertex over everything.
    let all_map = plan(&r, &[None, Some(Vertex), None], BakeChoice::Map, None);
    assert!(is(&all_map, Map, Map));
    assert_eq!(all_map.introduced, 0);
    let all_vertex = plan(&r, &[None, None, Some(Map)], BakeChoice::Vertex, None);
    assert!(is(&all_vertex, Vertex, Vertex));
    assert_eq!(all_vertex.introduced, floor_introduced);
}

/// Edström §4.4 on the CAD room's strips (each 2–4 m long and a few cm wide, 10 texels
/// per metre): vertex lighting refines each strip into patches no longer than a texel
/// rather than into `n²` strips as thin as itself, so it draws a fraction of regular
/// refinement's triangles, and their angles are no longer the strips' slivers.
#[test]
fn the_cad_room_strips_refine_into_few_well_shaped_patches() {
    use goniolight::radiosity::bake::{introduced_at_least, patch_size, plan, BakeChoice};
    use goniolight::radiosity::refine::smallest_angle;
    let r = RadiosityScene::with_hierarchy(&bundled("cad_room.toml"), 10.0, 2, Hierarchy::Clusters)
        .unwrap();
    let vertex = plan(&r, &[], BakeChoice::Vertex, None);
    let corners = |t: usize| r.casters.triangles[t].map(|i| r.casters.positions[i as usize]);
    let flat = |p: [DVec3; 3]| {
        let x = (p[1] - p[0]).normalize();
        let y = (p[1] - p[0]).cross(p[2] - p[0]).normalize().cross(x);
        p.map(|q| DVec2::new((q - p[0]).dot(x), (q - p[0]).dot(y)))
    };
    let (mut regular, mut input_angles, mut part_angles) = (0u64, Vec::new(), Vec::new());
    for (t, parts) in vertex.parts.iter().enumerate() {
        if parts.is_empty() {
            continue;
        }
        // The bound that lets `--bake auto` light-map a surface without refining it.
        let bound = introduced_at_least(&r, &[t as u32]);
        assert!(parts.len() as u64 > bound, "{t}: {} < {bound}", parts.len());
        let p = corners(t);
        let longest = (0..3)
            .map(|k| p[k].distance(p[(k + 1) % 3]))
            .fold(0.0, f64::max);
        let n = (longest / patch_size(&r, t) * (1.0 - 1e-9)).ceil() as u64;
        regular += n * n - 1;
        input_angles.push(smallest_angle(flat(p)).to_degrees());
        for w in parts {
            let q = w.map(|w| p[0] * w.x + p[1] * w.y + p[2] * w.z);
            part_angles.push(smallest_angle(flat(q)).to_degrees());
        }
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (input, parts) = (median(&mut input_angles), median(&mut part_angles));
    eprintln!(
        "CAD room, vertex-lit at 10 texels/m: {} introduced (regular refinement {regular}); median smallest angle {parts:.1}° (strips {input:.1}°)",
        vertex.introduced
    );
    assert!(vertex.introduced * 5 < regular);
    assert!(parts > 5.0 * input);
}
