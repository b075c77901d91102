//! `ldt ugr` against an independent numerical evaluation of the CIE 117 formula over the
//! CIE 190 standard rooms, written here from the definitions without the library's UGR
//! code: every luminaire of the array summed with its full (C, γ) distribution, the direct
//! flux split between floor, walls and ceiling by tracing the whole distribution (not the
//! zonal average) from every luminaire, and the three surfaces' interreflection by
//! iteration. Agreement within 0.1 UGR on every cell of two bundled luminaires.

use crate::common;

use std::f64::consts::PI;

use common::{luminaire, run_cli};
use goniolight::photometry::{Interp, Luminaire};
use serde_json::Value;

const H: f64 = 2.0;

/// The luminous area as the test reads it: (bottom, [side toward C0, C90, C180, C270],
/// round), m², from the file's dimensions.
fn faces(lum: &Luminaire) -> (f64, [f64; 4], bool) {
    let d = &lum.data.dimensions;
    let (l, w) = (d.area_length / 1000.0, d.area_width / 1000.0);
    let h = d.area_heights.map(|v| v / 1000.0);
    if w > 0.0 {
        (l * w, [l * h[0], w * h[1], l * h[2], w * h[3]], false)
    } else {
        (
            PI * l * l / 4.0,
            [l * h[0], l * h[1], l * h[2], l * h[3]],
            true,
        )
    }
}

fn projected(lum: &Luminaire, c: f64, g: f64) -> f64 {
    let (bottom, side, round) = faces(lum);
    let (c, g) = (c.to_radians(), g.to_radians());
    let toward_c0 = if c.cos() >= 0.0 { side[0] } else { side[2] };
    let toward_c90 = if c.sin() >= 0.0 { side[1] } else { side[3] };
    let sides = if round {
        c.cos().powi(2) * toward_c0 + c.sin().powi(2) * toward_c90
    } else {
        c.cos().abs() * toward_c0 + c.sin().abs() * toward_c90
    };
    bottom * g.cos() + sides * g.sin()
}

fn guth(t: f64, h: f64, r: f64) -> f64 {
    // IES's closed form of Guth's position index (α, β in degrees).
    let alpha = (t / h).atan().to_degrees();
    let beta = ((t * t + h * h).sqrt() / r).atan().to_degrees();
    let a = 35.2 - 0.31889 * alpha - 1.22 * (-2.0 * alpha / 9.0).exp();
    let b = 21.0 + 0.26667 * alpha - 0.002963 * alpha.powi(2);
    (a * 1e-3 * beta + b * 1e-5 * beta.powi(2)).exp()
}

/// Luminaire centres (x from the left wall, y from the observer's wall), metres.
fn grid(x_m: f64, y_m: f64, s: f64) -> Vec<(f64, f64)> {
    let (nx, ny) = ((x_m / s).round() as usize, (y_m / s).round() as usize);
    (0..nx)
        .flat_map(|i| (0..ny).map(move |j| ((i as f64 + 0.5) * s, (j as f64 + 0.5) * s)))
        .collect()
}

/// Σ L² ω / p² for both views (crosswise, endwise) of a room x_m × y_m (metres) lit at
/// spacing `s`, the eye moved `eye` metres (across, ahead) from the middle of the wall,
/// H below the luminaires.
fn independent_sums(
    lum: &Luminaire,
    flux: f64,
    x_m: f64,
    y_m: f64,
    s: f64,
    eye: [f64; 2],
) -> [f64; 2] {
    let cd = |c: f64, g: f64| lum.distribution.sample(c, g, Interp::Bilinear) * flux / 1000.0;
    let mut sums = [0.0; 2];
    for (lx, ly) in grid(x_m, y_m, s) {
        let (t, r) = ((lx - x_m / 2.0 - eye[0]).abs(), ly - eye[1]);
        if r <= 0.0 || H / r > 1.9 || t / r > 3.0 {
            continue;
        }
        let horizontal = (t * t + r * r).sqrt();
        let g = (horizontal / H).atan().to_degrees();
        let d2 = horizontal * horizontal + H * H;
        let cross = (t / r).atan().to_degrees();
        for (k, c) in [cross, 90.0 - cross].into_iter().enumerate() {
            let a = projected(lum, c, g);
            let l = cd(c, g) / a;
            sums[k] += l * l * (a / d2) / guth(t, H, r).powi(2);
        }
    }
    sums
}

/// UGR of one room for both views and all five reflectance combinations.
fn independent_room(lum: &Luminaire, flux: f64, x: f64, y: f64) -> [[f64; 5]; 2] {
    let (x_m, y_m) = (x * H, y * H);
    let lamps = grid(x_m, y_m, 0.25 * H);
    let cd = |c: f64, g: f64| lum.distribution.sample(c, g, Interp::Bilinear) * flux / 1000.0;
    let sums = independent_sums(lum, flux, x_m, y_m, 0.25 * H, [0.0, 0.0]);
    // Direct flux by tracing the whole distribution (2° × 1° directions) from every
    // luminaire, C0 along the room's y axis.
    let (mut ceiling, mut walls, mut floor) = (0.0, 0.0, 0.0);
    for gi in 0..180 {
        let g = gi as f64 + 0.5;
        for ci in 0..180 {
            let c = ci as f64 * 2.0 + 1.0;
            let d_omega = 2f64.to_radians()
                * ((gi as f64).to_radians().cos() - ((gi + 1) as f64).to_radians().cos());
            let phi = cd(c, g) * d_omega;
            if g > 90.0 {
                ceiling += phi * lamps.len() as f64;
                continue;
            }
            let reach = H * g.to_radians().tan();
            let (dx, dy) = (reach * c.to_radians().sin(), reach * c.to_radians().cos());
            for &(lx, ly) in &lamps {
                let (hx, hy) = (lx + dx, ly + dy);
                if (0.0..=x_m).contains(&hx) && (0.0..=y_m).contains(&hy) {
                    floor += phi;
                } else {
                    walls += phi;
                }
            }
        }
    }
    // Form factors of the box (floor to ceiling: parallel rectangles, Howell C-11).
    let (a, b) = (x_m / H, y_m / H);
    let f_fc = 2.0 / (PI * a * b)
        * ((((1.0 + a * a) * (1.0 + b * b)) / (1.0 + a * a + b * b))
            .sqrt()
            .ln()
            + a * (1.0 + b * b).sqrt() * (a / (1.0 + b * b).sqrt()).atan()
            + b * (1.0 + a * a).sqrt() * (b / (1.0 + a * a).sqrt()).atan()
            - a * a.atan()
            - b * b.atan());
    let (a_f, a_w) = (x_m * y_m, 2.0 * (x_m + y_m) * H);
    let f_wf = a_f * (1.0 - f_fc) / a_w;
    let mut out = [[0.0; 5]; 2];
    for (k, rho) in [
        [0.7, 0.5, 0.2],
        [0.7, 0.3, 0.2],
        [0.5, 0.5, 0.2],
        [0.5, 0.3, 0.2],
        [0.3, 0.3, 0.2],
    ]
    .iter()
    .enumerate()
    {
        // Exitances by Jacobi iteration: M = ρ (E_direct + Σ F M).
        let e0 = [ceiling / a_f, walls / a_w, floor / a_f];
        let mut m = [0.0f64; 3];
        for _ in 0..500 {
            let into_ceiling = e0[0] + (1.0 - f_fc) * m[1] + f_fc * m[2];
            let into_walls = e0[1] + f_wf * m[0] + (1.0 - 2.0 * f_wf) * m[1] + f_wf * m[2];
            let into_floor = e0[2] + f_fc * m[0] + (1.0 - f_fc) * m[1];
            m = [
                rho[0] * into_ceiling,
                rho[1] * into_walls,
                rho[2] * into_floor,
            ];
        }
        let e_indirect = f_wf * m[0] + (1.0 - 2.0 * f_wf) * m[1] + f_wf * m[2];
        let lb = e_indirect / PI;
        for v in 0..2 {
            out[v][k] = 8.0 * (0.25 / lb * sums[v]).log10();
        }
    }
    out
}

fn ugr_json(file: &std::path::Path, extra: &[&str]) -> Value {
    let mut args = vec!["ldt", "ugr", file.to_str().unwrap(), "--json"];
    args.extend(extra);
    let (code, out, err) = run_cli(&args, "");
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn ugr_tables_agree_with_an_independent_evaluation() {
    // A round downlight with a luminous height (Isym 1) and a linear one (Isym 2).
    for name in [
        "eulumdat-luminance/sample_01.ldt",
        "eulumdat-luminance/sample_02.ldt",
    ] {
        let file = luminaire(name);
        let lum = Luminaire::load(&file).unwrap();
        let flux = lum.data.lamp_sets[0].flux_lm;
        let table = ugr_json(&file, &[]);
        let rooms = table["rooms"].as_array().unwrap();
        let mut worst = 0.0f64;
        for (i, room) in rooms.iter().enumerate() {
            let (x, y) = (room[0].as_f64().unwrap(), room[1].as_f64().unwrap());
            let ours = independent_room(&lum, flux, x, y);
            for (v, key) in ["crosswise", "endwise"].iter().enumerate() {
                for k in 0..5 {
                    let got = table[key][i][k].as_f64().unwrap();
                    let diff = (got - ours[v][k]).abs();
                    worst = worst.max(diff);
                    assert!(
                        diff <= 0.1,
                        "{name} {x}H×{y}H {key} #{k}: {got:.2} vs independent {:.2}",
                        ours[v][k]
                    );
                }
            }
        }
        eprintln!("{name}: worst difference {worst:.3} UGR");
    }
}

#[test]
fn the_json_has_the_datasheet_layout() {
    let t = ugr_json(&luminaire("eulumdat-luminance/sample_09.ldt"), &[]);
    assert_eq!(t["shr"], 0.25);
    let rooms: Vec<[f64; 2]> = t["rooms"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| [r[0].as_f64().unwrap(), r[1].as_f64().unwrap()])
        .collect();
    assert_eq!(rooms.len(), 19);
    assert_eq!(rooms[0], [2.0, 2.0]);
    assert_eq!(rooms[18], [12.0, 8.0]);
    let refl = t["reflectances"].as_array().unwrap();
    assert_eq!(refl.len(), 5);
    assert_eq!(refl[0], serde_json::json!([0.7, 0.5, 0.2]));
    assert_eq!(refl[4], serde_json::json!([0.3, 0.3, 0.2]));
    for key in ["crosswise", "endwise"] {
        let rows = t[key].as_array().unwrap();
        assert_eq!(rows.len(), 19);
        for row in rows {
            assert_eq!(row.as_array().unwrap().len(), 5);
        }
    }
    // Darker rooms glare more: less reflected light, lower background luminance.
    for row in t["crosswise"].as_array().unwrap() {
        let v: Vec<f64> = row
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!(v[1] > v[0] && v[4] > v[3], "{v:?}");
    }
}

#[test]
fn more_flux_raises_ugr_by_8_log_of_the_ratio() {
    // sample_06 has two lamp sets of 1983 and 2643 lm: UGR grows by 8·log10(2643/1983).
    let file = luminaire("eulumdat-luminance/sample_06.ldt");
    let (a, b) = (ugr_json(&file, &[]), ugr_json(&file, &["--lamp-set", "2"]));
    let step = 8.0 * (2643.0f64 / 1983.0).log10();
    for i in 0..19 {
        for k in 0..5 {
            let (x, y) = (
                a["crosswise"][i][k].as_f64().unwrap(),
                b["crosswise"][i][k].as_f64().unwrap(),
            );
            assert!((y - x - step).abs() < 1e-9, "{x} → {y}");
        }
    }
}

#[test]
fn bad_requests_are_refused_by_name() {
    let file = luminaire("photometric-viewer/ies95/point_opening.ies");
    let (code, _, err) = run_cli(&["ldt", "ugr", file.to_str().unwrap()], "");
    assert_eq!(code, 2);
    assert!(
        err.contains("point_opening.ies") && err.contains("luminous area"),
        "{err}"
    );
    let file = luminaire("eulumdat-luminance/sample_01.ldt");
    let (code, _, err) = run_cli(&["ldt", "ugr", file.to_str().unwrap(), "--shr", "0"], "");
    assert_eq!(code, 2);
    // The library names its argument `shr`; the command, its flag.
    assert!(
        err.contains("--shr 0 is not a spacing-to-height ratio between 0.05 and 4"),
        "{err}"
    );
    // An uplight (DFF 0 %) sends nothing toward the eye: no table, and it says why.
    let file = luminaire("eulumdat-plot/sample_13_isym1.ldt");
    let (code, out, err) = run_cli(&["ldt", "ugr", file.to_str().unwrap()], "");
    assert_eq!(code, 2, "{out}");
    assert!(
        err.contains("sample_13_isym1.ldt") && err.contains("indirect luminaire"),
        "{err}"
    );
}

#[test]
fn the_observer_variation_agrees_with_the_independent_glare_sums() {
    // The eye moved over one spacing (4 × 4 positions) in the 4H × 8H room: the UGR change
    // is 8 log10 of the glare sums' ratio (the background luminance does not move).
    for file in [
        common::luminaire("eulumdat-luminance/sample_06.ldt"),
        common::luminaire("eulumdat-plot/sample_01_isym3.ldt"),
    ] {
        let lum = Luminaire::load(&file).unwrap();
        let v = ugr_json(&file, &[]);
        let rows = v["observer_variation"].as_array().unwrap();
        assert_eq!(rows.len(), 3);
        for (row, spacing) in rows.iter().zip([1.0, 1.5, 2.0]) {
            assert_eq!(row["spacing"], spacing);
            let s = spacing * H;
            let standard = independent_sums(&lum, 1000.0, 4.0 * H, 8.0 * H, s, [0.0, 0.0]);
            let (mut up, mut down) = ([0.0f64; 2], [0.0f64; 2]);
            for i in 0..4 {
                for j in 0..4 {
                    let eye = [i as f64 * s / 4.0, j as f64 * s / 4.0];
                    let sums = independent_sums(&lum, 1000.0, 4.0 * H, 8.0 * H, s, eye);
                    for k in 0..2 {
                        let change = 8.0 * (sums[k] / standard[k]).log10();
                        up[k] = up[k].max(change);
                        down[k] = down[k].max(-change);
                    }
                }
            }
            for (k, view) in ["crosswise", "endwise"].into_iter().enumerate() {
                let got = row[view].as_array().unwrap();
                let (u, d) = (got[0].as_f64().unwrap(), got[1].as_f64().unwrap());
                assert!(
                    (u - up[k]).abs() < 0.05 && (d - down[k]).abs() < 0.05,
                    "{} S={spacing}H {view}: +{u:.2}/−{d:.2} vs +{:.2}/−{:.2}",
                    file.display(),
                    up[k],
                    down[k]
                );
            }
        }
    }
}
