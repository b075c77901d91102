//! Daylight at points against closed forms and independent quadratures (the CIE 171 test
//! cases' approach): the sky component of unglazed and glazed rectangular openings in a
//! roof and a façade under a uniform and the CIE overcast sky, with and without an
//! external obstruction, the ground seen through a window, and the sun through it.

use std::f64::consts::PI;
use std::path::Path;

use glam::DVec3;
use goniolight::daylight::points::scene_daylight;
use goniolight::daylight::{DaylightAtPoint, Glazing};
use goniolight::lighting::SurfacePoint;
use goniolight::scene::Scene;

/// An axis-aligned rectangle: `axis` is the constant coordinate (0 x, 1 y, 2 z) at `at`;
/// the other two (in x, y, z order) span `a` and `b`.
struct Rect {
    axis: usize,
    at: f64,
    a: (f64, f64),
    b: (f64, f64),
}

/// The corners of `r` in order.
fn corners(r: &Rect) -> [DVec3; 4] {
    let pick = |u: f64, v: f64| {
        let mut c = [0.0; 3];
        let others: Vec<usize> = (0..3).filter(|&k| k != r.axis).collect();
        c[r.axis] = r.at;
        c[others[0]] = u;
        c[others[1]] = v;
        DVec3::from_array(c)
    };
    [
        pick(r.a.0, r.b.0),
        pick(r.a.1, r.b.0),
        pick(r.a.1, r.b.1),
        pick(r.a.0, r.b.1),
    ]
}

/// A box room `lo`..`hi` whose face `axis`/`side` (0 low, 1 high) has the opening
/// `hole` (in that face's two coordinates), plus `extra` opaque rectangles, glazing
/// (`glass`: its normal transmittance) in the hole if given; written as OBJ and loaded
/// with a `[sky]` of `sky` (TOML lines).
fn room_scene(
    dir: &Path,
    (lo, hi): (DVec3, DVec3),
    (axis, side): (usize, usize),
    hole: ((f64, f64), (f64, f64)),
    extra: &[Rect],
    glass: Option<f64>,
    sky: &str,
) -> Scene {
    let mut opaque: Vec<Rect> = Vec::new();
    for ax in 0..3 {
        let others: Vec<usize> = (0..3).filter(|&k| k != ax).collect();
        let span = |k: usize| (lo[others[k]], hi[others[k]]);
        for (s, at) in [(0, lo[ax]), (1, hi[ax])] {
            if (ax, s) != (axis, side) {
                opaque.push(Rect {
                    axis: ax,
                    at,
                    a: span(0),
                    b: span(1),
                });
                continue;
            }
            // The face less the hole: four rectangles round it.
            let ((a0, a1), (b0, b1)) = hole;
            let ((fa0, fa1), (fb0, fb1)) = (span(0), span(1));
            for (a, b) in [
                ((fa0, a0), (fb0, fb1)),
                ((a1, fa1), (fb0, fb1)),
                ((a0, a1), (fb0, b0)),
                ((a0, a1), (b1, fb1)),
            ] {
                opaque.push(Rect { axis: ax, at, a, b });
            }
        }
    }
    let mut obj = String::from("mtllib room.mtl\nusemtl wall\n");
    let mut n = 0;
    let mut quad = |obj: &mut String, r: &Rect| {
        for c in corners(r) {
            obj.push_str(&format!("v {} {} {}\n", c.x, c.y, c.z));
        }
        obj.push_str(&format!("f {} {} {} {}\n", n + 1, n + 2, n + 3, n + 4));
        n += 4;
    };
    for r in opaque.iter().chain(extra) {
        quad(&mut obj, r);
    }
    if glass.is_some() {
        obj.push_str("usemtl glass\n");
        let at = if side == 0 { lo[axis] } else { hi[axis] };
        quad(
            &mut obj,
            &Rect {
                axis,
                at,
                a: hole.0,
                b: hole.1,
            },
        );
    }
    std::fs::write(dir.join("room.obj"), obj).unwrap();
    std::fs::write(
        dir.join("room.mtl"),
        "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl glass\nKd 0 0 0\n",
    )
    .unwrap();
    let glass_toml = glass.map_or(String::new(), |t| {
        format!("[[material]]\nname = \"glass\"\ndiffuse_reflectance = 0.0\nspecular_transmittance = {t}\n")
    });
    let path = dir.join("room.toml");
    std::fs::write(
        &path,
        format!("[[model]]\npath = \"room.obj\"\nup = \"z\"\n{glass_toml}{sky}"),
    )
    .unwrap();
    Scene::load(&path).unwrap()
}

/// `n`-point Gauss–Legendre nodes and weights on [a, b].
fn gauss_legendre(n: usize, a: f64, b: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut t = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, t);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * t * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (t * p1 - p0) / (t * t - 1.0);
                t -= p1 / dp;
            }
            (
                0.5 * (b - a) * t + 0.5 * (b + a),
                (b - a) / ((1.0 - t * t) * dp * dp),
            )
        })
        .collect()
}

/// ∫ L(ω) cos θ_p dω over the rectangle `r` seen from `p` (normal `n`): the rectangle's
/// area integral L · cos θ_p · cos θ_r / d², by 2-D Gauss–Legendre, each coordinate range
/// split at the point's own height so the horizon's step falls on a boundary.
fn through_rect(p: DVec3, n: DVec3, r: &Rect, luminance: &dyn Fn(DVec3) -> f64) -> f64 {
    let others: Vec<usize> = (0..3).filter(|&k| k != r.axis).collect();
    let split = |range: (f64, f64), k: usize| -> Vec<(f64, f64)> {
        let cut = p[others[k]];
        if others[k] == 2 && cut > range.0 && cut < range.1 {
            vec![(range.0, cut), (cut, range.1)]
        } else {
            vec![range]
        }
    };
    let mut sum = 0.0;
    for ra in split(r.a, 0) {
        for rb in split(r.b, 1) {
            for (u, wu) in gauss_legendre(48, ra.0, ra.1) {
                for (v, wv) in gauss_legendre(48, rb.0, rb.1) {
                    let mut q = [0.0; 3];
                    q[r.axis] = r.at;
                    q[others[0]] = u;
                    q[others[1]] = v;
                    let d = DVec3::from_array(q) - p;
                    let dist = d.length();
                    let dir = d / dist;
                    let cos_p = n.dot(dir).max(0.0);
                    let cos_r = dir[r.axis].abs();
                    sum += wu * wv * luminance(dir) * cos_p * cos_r / (dist * dist);
                }
            }
        }
    }
    sum
}

fn daylight(scene: &Scene, p: DVec3, n: DVec3) -> DaylightAtPoint {
    scene_daylight(
        scene,
        &[SurfacePoint {
            position: p,
            normal: n,
        }],
    )
    .unwrap()[0]
}

fn close(ours: f64, reference: f64, tol: f64, what: &str) {
    assert!(
        (ours / reference - 1.0).abs() < tol,
        "{what}: {ours:.4} lux, reference {reference:.4} lux ({:+.3} %)",
        100.0 * (ours / reference - 1.0)
    );
}

const ROOM: (DVec3, DVec3) = (DVec3::new(0.0, 0.0, 0.0), DVec3::new(6.0, 4.0, 3.0));

/// The configuration factor from a horizontal element to a parallel rectangle with one
/// corner straight above it (sides a, b at height h): the closed form of the textbooks
/// (e.g. Howell's catalogue, C-11); a rectangle anywhere above is a sum of four of them.
fn corner_factor(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

/// A roof light 2 × 1.5 m in a 3 m high room under a uniform sky of 10 000 lx: at the
/// floor the sky component is L·π·F with L = 10 000/π and F the closed-form factor; the
/// CIE overcast sky against its area integral (L_z = 9 E / 7π).
#[test]
fn a_roof_opening_passes_the_sky_as_its_configuration_factor_says() {
    let dir = tempfile::tempdir().unwrap();
    let hole = ((2.0, 4.0), (1.5, 3.0));
    let sky = |model: &str| {
        format!(
            "[sky]\nmodel = \"{model}\"\ndiffuse_horizontal_lux = 10000\nground_reflectance = 0\n"
        )
    };
    let uniform = room_scene(dir.path(), ROOM, (2, 1), hole, &[], None, &sky("uniform"));
    for p in [
        DVec3::new(3.0, 2.0, 0.0),
        DVec3::new(1.0, 1.0, 0.8),
        DVec3::new(5.5, 3.5, 0.0),
    ] {
        let h = 3.0 - p.z;
        // The opening as ± sums of rectangles with a corner above the point.
        let f = |x: f64, y: f64| {
            (x - p.x).signum()
                * (y - p.y).signum()
                * corner_factor((x - p.x).abs(), (y - p.y).abs(), h)
        };
        let factor = f(4.0, 3.0) - f(2.0, 3.0) - f(4.0, 1.5) + f(2.0, 1.5);
        let got = daylight(&uniform, p, DVec3::Z);
        close(
            got.sky,
            10_000.0 * factor,
            0.002,
            &format!("uniform sky at {p}"),
        );
        assert_eq!(got.ground, 0.0);
    }
    let overcast = room_scene(
        dir.path(),
        ROOM,
        (2, 1),
        hole,
        &[],
        None,
        &sky("cie-overcast"),
    );
    let lz = 10_000.0 * 9.0 / (7.0 * PI);
    let cie = move |d: DVec3| lz * (1.0 + 2.0 * d.z) / 3.0;
    let roof = Rect {
        axis: 2,
        at: 3.0,
        a: hole.0,
        b: hole.1,
    };
    for p in [DVec3::new(3.0, 2.0, 0.0), DVec3::new(0.5, 0.5, 0.0)] {
        let reference = through_rect(p, DVec3::Z, &roof, &cie);
        close(
            daylight(&overcast, p, DVec3::Z).sky,
            reference,
            0.002,
            &format!("overcast at {p}"),
        );
    }
}

/// A window 2 × 1.4 m (sill 0.9 m) in the south wall: horizontal and vertical
/// illuminance under the CIE overcast sky, then with a 6 m high building 10 m away cutting
/// off the window's lower part, then glazed (88 % at normal incidence, Fresnel at
/// other angles), and the ground (ρ_g = 0.2) seen through it.
#[test]
fn a_facade_opening_passes_sky_and_ground_as_its_area_integral_says() {
    let dir = tempfile::tempdir().unwrap();
    let hole = ((2.0, 4.0), (0.9, 2.3));
    let window = Rect {
        axis: 1,
        at: 0.0,
        a: hole.0,
        b: hole.1,
    };
    let lz = 10_000.0 * 9.0 / (7.0 * PI);
    let sky_only = move |d: DVec3| {
        if d.z > 0.0 {
            lz * (1.0 + 2.0 * d.z) / 3.0
        } else {
            0.0
        }
    };
    let sky =
        "[sky]\nmodel = \"cie-overcast\"\ndiffuse_horizontal_lux = 10000\nground_reflectance = 0\n";
    let open = room_scene(dir.path(), ROOM, (1, 0), hole, &[], None, sky);
    let points = [
        (DVec3::new(3.0, 1.0, 0.85), DVec3::Z),
        (DVec3::new(1.0, 3.0, 0.85), DVec3::Z),
        (DVec3::new(3.0, 2.0, 1.2), -DVec3::Y),
        // Beside the window, seeing it at a grazing angle.
        (DVec3::new(5.25, 0.25, 0.8), DVec3::Z),
    ];
    for (p, n) in points {
        let reference = through_rect(p, n, &window, &sky_only);
        close(
            daylight(&open, p, n).sky,
            reference,
            0.005,
            &format!("open window at {p}"),
        );
    }
    // A long building across the street: 6 m high, 10 m out; its top edge seen from the
    // point cuts the window at z = p.z + (6 − p.z)·y / (y + 10).
    let building = Rect {
        axis: 1,
        at: -10.0,
        a: (-60.0, 60.0),
        b: (-1.0, 6.0),
    };
    let obstructed = room_scene(dir.path(), ROOM, (1, 0), hole, &[building], None, sky);
    for (p, n) in points {
        let cut = p.z + (6.0 - p.z) * p.y / (p.y + 10.0);
        assert!(
            cut > 0.9 && cut < 2.3,
            "the building hides part of the window: {cut}"
        );
        let visible = Rect {
            axis: 1,
            at: 0.0,
            a: hole.0,
            b: (cut, 2.3),
        };
        let reference = through_rect(p, n, &visible, &sky_only);
        close(
            daylight(&obstructed, p, n).sky,
            reference,
            0.005,
            &format!("obstructed at {p}"),
        );
    }
    // Glazed: each direction × the pane's transmittance at its incidence on the pane.
    let pane = Glazing::with_normal_transmittance(0.88).unwrap();
    let glazed = room_scene(dir.path(), ROOM, (1, 0), hole, &[], Some(0.88), sky);
    for (p, n) in points {
        let through_glass = |d: DVec3| sky_only(d) * pane.transmittance(d.y);
        let reference = through_rect(p, n, &window, &through_glass);
        close(
            daylight(&glazed, p, n).sky,
            reference,
            0.005,
            &format!("glazed at {p}"),
        );
        let bare = daylight(&open, p, n).sky;
        let ratio = daylight(&glazed, p, n).sky / bare;
        assert!(
            ratio > 0.25 && ratio < 0.88,
            "glass passes less than its normal 88 %: {ratio}"
        );
    }
    // The ground below the horizon: L_g = ρ_g E_h / π, seen through the window's part
    // below the eye.
    let ground_sky = "[sky]\nmodel = \"cie-overcast\"\ndiffuse_horizontal_lux = 10000\nground_reflectance = 0.2\n";
    let grounded = room_scene(dir.path(), ROOM, (1, 0), hole, &[], None, ground_sky);
    let (p, n) = (DVec3::new(3.0, 2.0, 1.2), -DVec3::Y);
    let lg = 0.2 * 10_000.0 / PI;
    let ground = |d: DVec3| if d.z <= 0.0 { lg } else { 0.0 };
    let got = daylight(&grounded, p, n);
    close(
        got.ground,
        through_rect(p, n, &window, &ground),
        0.005,
        "ground through the window",
    );
    close(
        got.sky,
        through_rect(p, n, &window, &sky_only),
        0.005,
        "sky beside the ground",
    );
}

/// The sun through the window: E_n · cos θ on a point the sun's line reaches through the
/// opening, × the pane's transmittance when glazed, nothing behind the wall.
#[test]
fn the_sun_lights_what_it_sees_through_the_window() {
    let dir = tempfile::tempdir().unwrap();
    let hole = ((2.0, 4.0), (0.9, 2.3));
    // 21 March, 12:00 in Vienna: the sun ~42° high, almost due south (−Y).
    let sky = "[site]\nlatitude = 48.21\nlongitude = 16.37\ntimezone = \"Europe/Vienna\"\n\
               [sky]\nmodel = \"cie-clear\"\ndiffuse_horizontal_lux = 0\ndirect_normal_lux = 60000\n\
               time = \"2026-03-21T12:00\"\nground_reflectance = 0\n";
    let open = room_scene(dir.path(), ROOM, (1, 0), hole, &[], None, sky);
    let sun = open.daylight.as_ref().unwrap().sky.sun.unwrap();
    // Follow the sun's line back from the window's middle to the floor.
    let through = DVec3::new(3.0, 0.0, 1.6);
    let lit = through - sun.direction * (1.6 / sun.direction.z);
    assert!(lit.y > 0.5 && lit.y < 3.5, "{lit}");
    let got = daylight(&open, lit, DVec3::Z);
    close(got.sun, 60_000.0 * sun.direction.z, 1e-3, "sunlit floor");
    assert_eq!(got.sky, 0.0, "a sky of 0 lux gives nothing");
    let shaded = DVec3::new(0.5, 3.8, 0.0);
    assert_eq!(
        daylight(&open, shaded, DVec3::Z).sun,
        0.0,
        "behind the wall"
    );
    let glazed = room_scene(dir.path(), ROOM, (1, 0), hole, &[], Some(0.8), sky);
    let pane = Glazing::with_normal_transmittance(0.8).unwrap();
    close(
        daylight(&glazed, lit, DVec3::Z).sun,
        60_000.0 * sun.direction.z * pane.transmittance(sun.direction.y),
        1e-3,
        "sun through glass",
    );
}
