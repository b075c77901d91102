//! The BVH ray cast against the brute-force loop it replaces: the same nearest hit (index
//! and distance, bit for bit) and the same shadow answers on random scenes — triangle
//! soups, shared edges (equal distances), slivers, degenerate triangles, scenes far from
//! the origin — for rays from inside and far outside, axis-aligned ones included.

use crate::common;

use common::run_cli;
use glam::DVec3;
use goniolight::geometry::Mesh;
use goniolight::shadow::raycast::{first_hit, in_shadow_ignoring};
use goniolight::shadow::{IgnoredTriangles, Light, TriangleBvh};
use proptest::prelude::*;

/// A random scene: `soup` free triangles in a box of `size` around `offset`, plus a grid of
/// quads split along their diagonals (shared edges), long thin strips and a few degenerate
/// triangles.
fn scene(seed: u64, soup: usize, size: f64, offset: DVec3) -> Mesh {
    let mut rng = Lcg(seed);
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let push = |p: &mut Vec<DVec3>, t: &mut Vec<[u32; 3]>, c: [DVec3; 3]| {
        let i = p.len() as u32;
        p.extend(c.map(|v| v * size + offset));
        t.push([i, i + 1, i + 2]);
    };
    for _ in 0..soup {
        let a = rng.point();
        let b = a + (rng.point() - 0.5) * 0.3;
        let c = a + (rng.point() - 0.5) * 0.3;
        push(&mut positions, &mut triangles, [a, b, c]);
    }
    // A floor of 4 × 4 quads at z = 0.1, two triangles each (diagonals and edges shared).
    for i in 0..4 {
        for j in 0..4 {
            let (x, y) = (i as f64 * 0.25, j as f64 * 0.25);
            let q = [(0.0, 0.0), (0.25, 0.0), (0.25, 0.25), (0.0, 0.25)]
                .map(|(dx, dy)| DVec3::new(x + dx, y + dy, 0.1));
            push(&mut positions, &mut triangles, [q[0], q[1], q[2]]);
            push(&mut positions, &mut triangles, [q[0], q[2], q[3]]);
        }
    }
    // CAD-like strips: long and 1/1000 as wide, upright at x = 0.6.
    for k in 0..8 {
        let z = k as f64 * 0.1;
        let w = 0.001;
        let [a, b, c, d] = [
            DVec3::new(0.6, 0.0, z),
            DVec3::new(0.6, 1.0, z),
            DVec3::new(0.6, 1.0, z + w),
            DVec3::new(0.6, 0.0, z + w),
        ];
        push(&mut positions, &mut triangles, [a, b, c]);
        push(&mut positions, &mut triangles, [a, c, d]);
    }
    // Degenerate: a repeated vertex and three collinear points.
    let p = rng.point();
    push(&mut positions, &mut triangles, [p, p, p + DVec3::X * 0.1]);
    push(
        &mut positions,
        &mut triangles,
        [p, p + DVec3::Y * 0.1, p + DVec3::Y * 0.2],
    );
    Mesh {
        positions,
        triangles,
    }
}

/// A small deterministic generator (the scenes vary with proptest's seed).
struct Lcg(u64);

impl Lcg {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn point(&mut self) -> DVec3 {
        DVec3::new(self.unit(), self.unit(), self.unit())
    }
    /// A direction: random, or (one time in four) along an axis, or (one in eight) almost
    /// along one.
    fn direction(&mut self) -> DVec3 {
        let pick = self.unit();
        let axis = [DVec3::X, DVec3::Y, DVec3::Z][(self.unit() * 3.0) as usize % 3];
        let sign = if self.unit() < 0.5 { -1.0 } else { 1.0 };
        if pick < 0.25 {
            axis * sign
        } else if pick < 0.375 {
            (axis * sign + (self.point() - 0.5) * 1e-7).normalize()
        } else {
            (self.point() - 0.5).normalize()
        }
    }
}

fn check_scene(seed: u64, soup: usize, size: f64, offset: DVec3) {
    let mesh = scene(seed, soup, size, offset);
    let bvh = TriangleBvh::new(&mesh);
    assert_eq!(bvh.len(), mesh.triangles.len());
    let mut rng = Lcg(seed ^ 0x9e37_79b9_7f4a_7c15);
    let n = mesh.triangles.len();
    let mut hits = 0;
    for r in 0..300 {
        // Origins inside the scene, on its floor grid, or 1000 sizes away aimed at it.
        let o = match r % 3 {
            0 => rng.point() * size + offset,
            1 => DVec3::new(rng.unit(), rng.unit(), 0.1) * size + offset,
            _ => (rng.point() - 0.5) * 2000.0 * size + offset,
        };
        let dir = if r % 3 == 2 {
            ((rng.point() * size + offset) - o).normalize()
        } else {
            rng.direction()
        };
        let tmin = if r % 2 == 0 { 0.0 } else { 1e-6 * size };
        let brute = first_hit(&mesh, o, dir, tmin);
        let fast = bvh.first_hit(o, dir, tmin);
        assert_eq!(fast, brute, "first hit, ray {r}: o {o} dir {dir}");
        hits += brute.is_some() as usize;

        // Shadow rays toward a random point light, leaving out a random range.
        let light = Light((rng.point() * size + offset).extend(1.0));
        let (a, b) = (
            (rng.unit() * n as f64) as usize,
            (rng.unit() * n as f64) as usize,
        );
        let ignored = IgnoredTriangles(vec![a..(a + 1 + r % 7).min(n), b..b + 1]);
        let eps = 1e-6 * size;
        assert_eq!(
            bvh.in_shadow(&light, o, eps, &ignored),
            in_shadow_ignoring(&mesh, &light, o, eps, &ignored),
            "shadow, ray {r}"
        );
        let sun = Light(rng.direction().extend(0.0));
        let none = IgnoredTriangles::default();
        assert_eq!(
            bvh.in_shadow(&sun, o, eps, &none),
            in_shadow_ignoring(&mesh, &sun, o, eps, &none),
            "sun shadow, ray {r}"
        );
    }
    // The rays are not all misses (the comparison would then prove little).
    assert!(hits > 40, "only {hits} of 300 rays hit");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn bvh_equals_brute_force(seed in any::<u64>(), soup in 0usize..400) {
        check_scene(seed, soup, 1.0, DVec3::ZERO);
    }

    #[test]
    fn bvh_equals_brute_force_far_from_the_origin(seed in any::<u64>(), soup in 0usize..200) {
        // A 30 m site in georeferenced metres: f32 has 1/64 m steps out there.
        check_scene(seed, soup, 30.0, DVec3::new(512_345.6, 5_432_109.8, 250.0));
    }
}

#[test]
fn an_empty_mesh_hits_nothing() {
    let mesh = Mesh::default();
    let bvh = TriangleBvh::new(&mesh);
    assert!(bvh.is_empty());
    assert_eq!(bvh.first_hit(DVec3::ZERO, DVec3::Z, 0.0), None);
    let light = Light(DVec3::new(0.0, 0.0, 5.0).extend(1.0));
    assert!(!bvh.in_shadow(&light, DVec3::ZERO, 1e-6, &IgnoredTriangles::default()));
}

#[test]
fn a_floor_hit_from_above_reports_its_distance() {
    // Analytic: a ray straight down from 2.5 m meets a floor at z = 0.5 after 2 m.
    let mesh = Mesh {
        positions: vec![
            DVec3::new(0.0, 0.0, 0.5),
            DVec3::new(4.0, 0.0, 0.5),
            DVec3::new(4.0, 3.0, 0.5),
            DVec3::new(0.0, 3.0, 0.5),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    };
    let bvh = TriangleBvh::new(&mesh);
    let (t, k) = bvh
        .first_hit(DVec3::new(1.0, 2.0, 2.5), -DVec3::Z, 0.0)
        .unwrap();
    assert!((t - 2.0).abs() < 1e-12, "distance {t}");
    assert_eq!(k, 1, "the point (1, 2) lies in the second triangle");
    let ignored = IgnoredTriangles(vec![1..2, 5..5]);
    let light = Light(DVec3::new(1.0, 2.0, 2.5).extend(1.0));
    assert!(bvh.in_shadow(
        &light,
        DVec3::new(1.0, 2.0, -1.0),
        1e-6,
        &IgnoredTriangles::default()
    ));
    assert!(!bvh.in_shadow(&light, DVec3::new(1.0, 2.0, -1.0), 1e-6, &ignored));
}

#[test]
fn bench_raycast_json_contract() {
    // The bench itself refuses (exit 1) when a brute-force answer differs from the BVH's.
    let args = [
        "bench", "raycast", "--json", "--scale", "0.01", "--rays", "300",
    ];
    let (code, out, err) = run_cli(&[&args[..], &["--brute-rays", "100"]].concat(), "");
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    let sizes: Vec<u64> = rows
        .iter()
        .map(|r| r["triangles"].as_u64().unwrap())
        .collect();
    assert!(sizes.windows(2).all(|w| w[0] < w[1]), "{sizes:?}");
    for r in rows {
        for k in [
            "brute_shadow_rays_per_s",
            "bvh_shadow_rays_per_s",
            "bvh_hit_rays_per_s",
        ] {
            assert!(r[k].as_f64().unwrap() > 0.0, "{k} in {r}");
        }
        let blocked = r["blocked_fraction"].as_f64().unwrap();
        assert!(
            blocked > 0.05 && blocked < 0.95,
            "blocked {blocked}: the shadow rays test little"
        );
    }
    let (code, _, err) = run_cli(
        &["bench", "raycast", "--rays", "10", "--brute-rays", "20"],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--brute-rays"), "{err}");
}

/// A real model nobody here made: the Šibenik cathedral (73 564 triangles, 1 973 slivers),
/// read from the shared test data. Rays from a grid of points over the floor toward a
/// light in the nave, and nearest hits in every direction from inside: the BVH's answers
/// are the brute force's.
#[test]
fn bvh_equals_brute_force_in_the_sibenik_cathedral() {
    let obj = common::shared_dir().join("models/sibenik/sibenik.obj");
    let dir = tempfile::tempdir().unwrap();
    let toml = dir.path().join("sibenik.toml");
    let text = format!(
        "[[model]]\npath = {:?}\nup = \"y\"\n",
        obj.display().to_string()
    );
    std::fs::write(&toml, text).unwrap();
    let mesh = goniolight::scene::Scene::load(&toml).unwrap().caster_mesh();
    let bvh = TriangleBvh::new(&mesh);
    let eps = goniolight::shadow::raycast::self_hit_epsilon(&mesh);
    let light = Light(DVec3::new(0.0, 0.0, 0.0).extend(1.0));
    let none = IgnoredTriangles::default();
    let (mut shadowed, mut hits) = (0, 0);
    for i in 0..40 {
        for j in 0..10 {
            let p = DVec3::new(
                -18.0 + 36.0 * i as f64 / 39.0,
                -7.0 + 14.0 * j as f64 / 9.0,
                -15.2,
            );
            let brute = in_shadow_ignoring(&mesh, &light, p, eps, &none);
            assert_eq!(bvh.in_shadow(&light, p, eps, &none), brute, "shadow at {p}");
            shadowed += brute as usize;
            let dir = DVec3::new(
                (i as f64).cos(),
                (j as f64 * 0.7).sin(),
                0.3 * (i + j) as f64 % 1.0 - 0.5,
            )
            .normalize();
            let o = DVec3::new(p.x * 0.5, p.y * 0.5, -5.0);
            let brute = first_hit(&mesh, o, dir, 0.0);
            assert_eq!(
                bvh.first_hit(o, dir, 0.0),
                brute,
                "ray from {o} along {dir}"
            );
            hits += brute.is_some() as usize;
        }
    }
    eprintln!("{shadowed} of 400 floor points shadowed, {hits} of 400 rays hit");
    assert!(hits > 300, "{hits}");
}
