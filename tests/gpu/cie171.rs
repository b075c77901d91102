//! Validation against the analytic test cases of CIE 171:2006 ("Test cases to assess the
//! accuracy of lighting computer programs") that follow from geometry alone. Every
//! reference value is computed here from the geometry (inverse-square law, the
//! differential-area-to-rectangle form factor, energy conservation in a closed room), not
//! copied from the report's tables, so the report's erratum tables do not enter.
//!
//! Each case runs the command a user runs (`calc`, `illuminance`, `radiosity --points`)
//! and prints its row of the error table on docs/src/measurements/cie171.md (`cargo test --test gpu cie171:: --
//! --nocapture`).
//!
//! - 5.3-like: a point source with an isotropic distribution, direct illuminance on a
//!   horizontal work plane and on a vertical plane (calc on the GPU and on the CPU).
//! - 5.4-like: a Lambertian rectangular area source (a luminous ceiling panel), direct
//!   illuminance on the work plane: E = M · F(dA → rectangle), through the radiosity gather.
//! - 5.6-like: a point source above an opaque square obstruction: zero in the umbra, the
//!   inverse-square law outside it.
//! - 5.8/5.9-like: interreflection in a closed room of one reflectance ρ, empty and with an
//!   internal obstruction (a cube): the area mean of the interreflected illuminance over
//!   every surface is ρ Φ / (A (1 − ρ)) exactly (every lumen is absorbed somewhere, a
//!   fraction 1 − ρ at each reflection).

use crate::common;
use crate::gpu_common;

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use common::{calc_csv_rows, run_cli};
use glam::DVec3;

/// The isotropic source's intensity, cd (in every direction).
const CANDELA: f64 = 100.0;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// An IES file of an isotropic point source of `CANDELA` cd (flux 4π · CANDELA lm), no
/// luminous area.
fn isotropic_ies(dir: &Path) -> PathBuf {
    let path = dir.join("isotropic.ies");
    let gammas: Vec<String> = (0..=36).map(|k| (5 * k).to_string()).collect();
    let values = vec![format!("{CANDELA}"); gammas.len()].join(" ");
    let text = format!(
        "IESNA:LM-63-2002\n[TEST] isotropic point source\nTILT=NONE\n1 {:.4} 1.0 {} 1 1 2 0 0 0\n1.0 1.0 10\n{}\n0\n{values}\n",
        4.0 * PI * CANDELA,
        gammas.len(),
        gammas.join(" ")
    );
    std::fs::write(&path, text).unwrap();
    path
}

/// A rectangle: a corner and two edges; its front (lit) side is along `u × v`.
#[derive(Clone, Copy)]
struct Quad {
    corner: DVec3,
    u: DVec3,
    v: DVec3,
    material: &'static str,
}

impl Quad {
    fn normal(&self) -> DVec3 {
        self.u.cross(self.v).normalize()
    }

    fn area(&self) -> f64 {
        self.u.cross(self.v).length()
    }

    /// Cell centres of an n_u × n_v grid, 1 mm in front of the surface.
    fn points(&self, n_u: usize, n_v: usize) -> Vec<(DVec3, DVec3)> {
        let n = self.normal();
        let mut out = Vec::new();
        for j in 0..n_v {
            for i in 0..n_u {
                let p = self.corner
                    + self.u * ((i as f64 + 0.5) / n_u as f64)
                    + self.v * ((j as f64 + 0.5) / n_v as f64)
                    + n * 1e-3;
                out.push((p, n));
            }
        }
        out
    }
}

/// The inside of a box from `lo` to `hi` (faces toward the inside).
fn room(lo: DVec3, hi: DVec3, material: &'static str) -> Vec<Quad> {
    let d = hi - lo;
    let (x, y, z) = (DVec3::X * d.x, DVec3::Y * d.y, DVec3::Z * d.z);
    vec![
        Quad {
            corner: lo,
            u: x,
            v: y,
            material,
        }, // floor, up
        Quad {
            corner: lo + z,
            u: y,
            v: x,
            material,
        }, // ceiling, down
        Quad {
            corner: lo,
            u: z,
            v: x,
            material,
        }, // y = lo, +y
        Quad {
            corner: lo + y,
            u: x,
            v: z,
            material,
        }, // y = hi, −y
        Quad {
            corner: lo,
            u: y,
            v: z,
            material,
        }, // x = lo, +x
        Quad {
            corner: lo + x,
            u: z,
            v: y,
            material,
        }, // x = hi, −x
    ]
}

/// The outside of a box from `lo` to `hi` without its bottom (standing on a floor).
fn block(lo: DVec3, hi: DVec3, material: &'static str) -> Vec<Quad> {
    let d = hi - lo;
    let (x, y, z) = (DVec3::X * d.x, DVec3::Y * d.y, DVec3::Z * d.z);
    vec![
        Quad {
            corner: lo + z,
            u: x,
            v: y,
            material,
        }, // top, up
        Quad {
            corner: lo,
            u: x,
            v: z,
            material,
        }, // y = lo, −y
        Quad {
            corner: lo + y,
            u: z,
            v: x,
            material,
        }, // y = hi, +y
        Quad {
            corner: lo,
            u: z,
            v: y,
            material,
        }, // x = lo, −x
        Quad {
            corner: lo + x,
            u: y,
            v: z,
            material,
        }, // x = hi, +x
    ]
}

/// Writes `quads` as an OBJ (two triangles each, wound to face along u × v) with an MTL of
/// `materials` (name, Kd, Ke) and a scene file with `extra` TOML; returns the scene path.
fn write_scene(dir: &Path, quads: &[Quad], materials: &[(&str, f64, f64)], extra: &str) -> PathBuf {
    let mut obj = String::from("mtllib cie.mtl\n");
    for (k, q) in quads.iter().enumerate() {
        for p in [
            q.corner,
            q.corner + q.u,
            q.corner + q.u + q.v,
            q.corner + q.v,
        ] {
            let _ = writeln!(obj, "v {} {} {}", p.x, p.y, p.z);
        }
        let b = 4 * k + 1;
        let _ = writeln!(
            obj,
            "o quad{k}\nusemtl {}\nf {} {} {}\nf {} {} {}",
            q.material,
            b,
            b + 1,
            b + 2,
            b,
            b + 2,
            b + 3
        );
    }
    std::fs::write(dir.join("cie.obj"), obj).unwrap();
    let mut mtl = String::new();
    for (name, kd, ke) in materials {
        let _ = writeln!(mtl, "newmtl {name}\nKd {kd} {kd} {kd}\nKe {ke} {ke} {ke}\n");
    }
    std::fs::write(dir.join("cie.mtl"), mtl).unwrap();
    let path = dir.join("cie.toml");
    std::fs::write(
        &path,
        format!("[[model]]\npath = \"cie.obj\"\nup = \"z\"\n\n{extra}"),
    )
    .unwrap();
    path
}

fn luminaire_toml(file: &Path, at: DVec3) -> String {
    format!(
        "[[luminaire]]\nfile = {:?}\nposition = [{}, {}, {}]\n\n",
        s(file),
        at.x,
        at.y,
        at.z
    )
}

fn points_text(points: &[(DVec3, DVec3)]) -> String {
    points
        .iter()
        .map(|(p, n)| format!("{} {} {} {} {} {}\n", p.x, p.y, p.z, n.x, n.y, n.z))
        .collect()
}

fn lux_lines(stdout: &str) -> Vec<f64> {
    stdout
        .lines()
        .map(|l| {
            l.trim()
                .parse()
                .unwrap_or_else(|_| panic!("not lux: {l:?}"))
        })
        .collect()
}

/// `illuminance` (direct) or `radiosity --points` (total) at `points`.
fn lux_at(cmd: &[&str], points: &[(DVec3, DVec3)]) -> Vec<f64> {
    let (code, out, err) = run_cli(cmd, &points_text(points));
    assert_eq!(code, 0, "{cmd:?}: {err}");
    let lux = lux_lines(&out);
    assert_eq!(lux.len(), points.len(), "{err}");
    lux
}

/// Runs `calc SCENE --out DIR EXTRA…` and returns the rows of each grid CSV in `grids`.
fn calc_rows(scene: &Path, out: &Path, extra: &[&str], grids: &[&str]) -> Vec<Vec<[f64; 4]>> {
    let mut args = vec!["calc", s(scene), "--out", s(out)];
    args.extend(extra);
    let (code, _, err) = run_cli(&args, "");
    assert_eq!(code, 0, "{err}");
    grids
        .iter()
        .map(|g| calc_csv_rows(&out.join(format!("{g}.csv"))))
        .collect()
}

/// E = I cos θ / d² of the isotropic source at `source` on a surface at `p` facing `n`.
fn point_source_lux(source: DVec3, p: DVec3, n: DVec3) -> f64 {
    let to = source - p;
    let d = to.length();
    (CANDELA * n.dot(to) / (d * d * d)).max(0.0)
}

/// The form factor from a differential area to a rectangle a × b in a parallel plane at
/// distance c, the area's normal through one corner of the rectangle (Howell, case B-3).
fn corner_form_factor(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

/// The form factor from a differential area at plan position (px, py) to the rectangle
/// [x0, x1] × [y0, y1] in a parallel plane at distance c: corner rectangles added and
/// subtracted (signed extents).
fn rectangle_form_factor(px: f64, py: f64, x: [f64; 2], y: [f64; 2], c: f64) -> f64 {
    let signed = |a: f64, b: f64| a.signum() * b.signum() * corner_form_factor(a.abs(), b.abs(), c);
    signed(x[1] - px, y[1] - py) - signed(x[0] - px, y[1] - py) - signed(x[1] - px, y[0] - py)
        + signed(x[0] - px, y[0] - py)
}

/// Largest and mean relative difference, %.
fn errors(got: &[f64], want: &[f64]) -> (f64, f64) {
    let rel: Vec<f64> = got
        .iter()
        .zip(want)
        .map(|(g, w)| 100.0 * (g - w).abs() / w.abs().max(1e-12))
        .collect();
    (
        rel.iter().copied().fold(0.0, f64::max),
        rel.iter().sum::<f64>() / rel.len() as f64,
    )
}

fn report(case: &str, what: &str, n: usize, (max, mean): (f64, f64), limit: f64) {
    println!("| {case} | {what} | {n} | {mean:.3} % | {max:.3} % | {limit} % |");
    assert!(
        max <= limit,
        "{case}, {what}: worst {max:.3} % over the {limit} % limit (mean {mean:.3} %)"
    );
}

const LO: DVec3 = DVec3::ZERO;
const HI: DVec3 = DVec3::new(4.0, 4.0, 3.0);

/// 5.3: direct illuminance of an isotropic point source on a horizontal and a vertical grid
/// (calc, GPU and CPU), in a black room.
#[test]
fn point_source_direct_illuminance() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let ies = isotropic_ies(tmp.path());
    let source = DVec3::new(2.0, 2.0, 2.5);
    let scene = write_scene(
        tmp.path(),
        &room(LO, HI, "black"),
        &[("black", 0.0, 0.0)],
        &format!(
            "{}[[grid]]\nname = \"work plane\"\ncorner = [0.0, 0.0]\nsize = [4.0, 4.0]\nheight = 0.8\nspacing = 0.25\n\n[[grid]]\nname = \"wall\"\nkind = \"vertical\"\ncorner = [0.05, 0.1]\nsize = [3.8, 2.6]\nheight = 0.2\nnormal = [1.0, 0.0, 0.0]\nspacing = 0.2\n",
            luminaire_toml(&ies, source)
        ),
    );
    for (device, extra) in [("GPU", &[][..]), ("CPU", &["--cpu"][..])] {
        let out = tmp.path().join(format!("out-{device}"));
        let grids = calc_rows(&scene, &out, extra, &["work-plane", "wall"]);
        for ((grid, normal), rows) in [("work-plane", DVec3::Z), ("wall", DVec3::X)]
            .into_iter()
            .zip(grids)
        {
            assert!(rows.len() > 100, "{grid}: {} points", rows.len());
            let got: Vec<f64> = rows.iter().map(|r| r[3]).collect();
            let want: Vec<f64> = rows
                .iter()
                .map(|r| point_source_lux(source, DVec3::new(r[0], r[1], r[2]), normal))
                .collect();
            report(
                "5.3 point source",
                &format!("{grid} ({device})"),
                rows.len(),
                errors(&got, &want),
                1.0,
            );
        }
    }
}

/// 5.4: a Lambertian 1 × 1.5 m luminous panel (exitance M) 1 cm under the ceiling of a
/// black room: E = M · F(dA → panel) on the work plane, by the radiosity gather (calc
/// --indirect radiosity: the panel's light is the solution's, there are no luminaires).
#[test]
fn area_source_direct_illuminance() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    const M: f64 = 1000.0;
    let (x, y, z) = ([1.5, 2.5], [1.25, 2.75], 2.99);
    let mut quads = room(LO, HI, "black");
    quads.push(Quad {
        corner: DVec3::new(x[0], y[0], z),
        u: DVec3::Y * (y[1] - y[0]),
        v: DVec3::X * (x[1] - x[0]),
        material: "panel",
    });
    let scene = write_scene(
        tmp.path(),
        &quads,
        &[("black", 0.0, 0.0), ("panel", 0.0, M)],
        "[[grid]]\nname = \"work plane\"\ncorner = [0.0, 0.0]\nsize = [4.0, 4.0]\nheight = 0.8\nspacing = 0.25\n",
    );
    let out = tmp.path().join("out");
    let rows = calc_rows(&scene, &out, &["--indirect", "radiosity"], &["work-plane"]).remove(0);
    let got: Vec<f64> = rows.iter().map(|r| r[3]).collect();
    let want: Vec<f64> = rows
        .iter()
        .map(|r| M * rectangle_form_factor(r[0], r[1], x, y, z - r[2]))
        .collect();
    report(
        "5.4 area source",
        "work plane (GPU solve, CPU gather)",
        rows.len(),
        errors(&got, &want),
        2.0,
    );
}

/// 5.6: an isotropic source 1 m above an opaque 1 × 1 m plate: no direct light in the
/// plate's shadow on the work plane, the inverse-square law outside it (points within
/// 5 cm of the shadow's edge left out).
#[test]
fn point_source_with_obstruction() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let ies = isotropic_ies(tmp.path());
    let source = DVec3::new(2.0, 2.0, 2.5);
    let mut quads = room(LO, HI, "black");
    // The plate faces both ways (two quads), 1 m under the source.
    for (corner, u, v) in [
        (DVec3::new(1.5, 1.5, 1.5), DVec3::X, DVec3::Y),
        (DVec3::new(1.5, 1.5, 1.5), DVec3::Y, DVec3::X),
    ] {
        quads.push(Quad {
            corner,
            u,
            v,
            material: "black",
        });
    }
    let scene = write_scene(
        tmp.path(),
        &quads,
        &[("black", 0.0, 0.0)],
        &format!(
            "{}[[grid]]\nname = \"work plane\"\ncorner = [0.0, 0.0]\nsize = [4.0, 4.0]\nheight = 0.8\nspacing = 0.1\n",
            luminaire_toml(&ies, source)
        ),
    );
    // The shadow of the plate's edge (0.5 m from the axis at 1 m) on the plane 1.7 m down.
    let edge = 0.5 * 1.7;
    for (device, extra) in [("GPU", &[][..]), ("CPU", &["--cpu"][..])] {
        let out = tmp.path().join(format!("out-{device}"));
        let (mut lit, mut want, mut dark) = (Vec::new(), Vec::new(), 0);
        for r in calc_rows(&scene, &out, extra, &["work-plane"]).remove(0) {
            let p = DVec3::new(r[0], r[1], r[2]);
            let off = (p.x - source.x).abs().max((p.y - source.y).abs());
            if (off - edge).abs() < 0.05 {
                continue;
            }
            if off < edge {
                assert!(r[3] == 0.0, "{device}: {r:?} is in the plate's shadow");
                dark += 1;
            } else {
                lit.push(r[3]);
                want.push(point_source_lux(source, p, DVec3::Z));
            }
        }
        assert!(
            dark > 200 && lit.len() > 900,
            "{dark} shadowed, {} lit",
            lit.len()
        );
        report(
            "5.6 obstruction",
            &format!("work plane, lit points ({device}; {dark} shadowed points exactly 0)"),
            lit.len(),
            errors(&lit, &want),
            1.0,
        );
    }
}

/// The area mean of the interreflected illuminance over every surface of `quads` (one
/// reflectance ρ, closed) lit by the isotropic source at `source`, against
/// ρ Φ / (A (1 − ρ)); returns (got, want).
fn closed_room_interreflection(quads: &[Quad], rho: f64, source: DVec3) -> (f64, f64) {
    let tmp = tempfile::tempdir().unwrap();
    let ies = isotropic_ies(tmp.path());
    let scene = write_scene(
        tmp.path(),
        quads,
        &[("grey", rho, 0.0)],
        &luminaire_toml(&ies, source),
    );
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for q in quads {
        let (n_u, n_v) = (
            (q.u.length() / 0.2).round() as usize,
            (q.v.length() / 0.2).round() as usize,
        );
        let cell = q.area() / (n_u * n_v) as f64;
        for p in q.points(n_u, n_v) {
            points.push(p);
            weights.push(cell);
        }
    }
    let direct = lux_at(&["illuminance", s(&scene), "--shadows", "volumes"], &points);
    let total = lux_at(
        &[
            "radiosity",
            s(&scene),
            "--points",
            "--converge",
            "0.999",
            "--shadows",
            "volumes",
        ],
        &points,
    );
    let area: f64 = weights.iter().sum();
    let mean = total
        .iter()
        .zip(&direct)
        .zip(&weights)
        .map(|((t, d), w)| (t - d) * w)
        .sum::<f64>()
        / area;
    let flux = 4.0 * PI * CANDELA;
    (mean, rho * flux / (area * (1.0 - rho)))
}

/// 5.8: a closed empty room of ρ = 0.5 around an isotropic source.
#[test]
fn interreflection_in_a_closed_room() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let (got, want) =
        closed_room_interreflection(&room(LO, HI, "grey"), 0.5, DVec3::new(2.0, 2.0, 1.5));
    report(
        "5.8 closed room",
        &format!("area mean of the interreflected lux ({got:.3} vs {want:.3} lx)"),
        1,
        errors(&[got], &[want]),
        2.0,
    );
}

/// 5.9: the same room with a 1 m cube of the same reflectance standing on the floor.
#[test]
fn interreflection_with_an_internal_obstruction() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let mut quads = room(LO, HI, "grey");
    quads.extend(block(
        DVec3::new(0.6, 0.6, 0.0),
        DVec3::new(1.6, 1.6, 1.0),
        "grey",
    ));
    let (got, want) = closed_room_interreflection(&quads, 0.5, DVec3::new(2.5, 2.5, 1.5));
    report(
        "5.9 internal obstruction",
        &format!("area mean of the interreflected lux ({got:.3} vs {want:.3} lx)"),
        1,
        errors(&[got], &[want]),
        2.0,
    );
}

#[test]
fn form_factor_oracle_is_right() {
    // A large rectangle far from the corner's edges: F → 1/4 for the corner formula.
    assert!((corner_form_factor(1e4, 1e4, 1.0) - 0.25).abs() < 1e-3);
    // Centred under a square of side 2c at distance c: Howell's tabulated 0.2395 (4 × B-3
    // with a = b = c).
    let f = rectangle_form_factor(0.0, 0.0, [-1.0, 1.0], [-1.0, 1.0], 1.0);
    assert!((f - 4.0 * corner_form_factor(1.0, 1.0, 1.0)).abs() < 1e-12);
    assert!(
        (corner_form_factor(1.0, 1.0, 1.0) - 0.1385).abs() < 1e-3,
        "{f}"
    );
}
