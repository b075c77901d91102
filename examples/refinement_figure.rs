//! Draws the README's figure of Edström's patch refinement (§4.4, Fig. 4.9): a 2 × 1 m
//! wall exported by a CAD tool as 20 long thin strips, vertex-lit under 0.1 m texels —
//! refined regularly (each strip into `n²` strips like itself) and by patch refinement
//! (`radiosity/refine.rs`).
//!
//! `cargo run --release --example refinement_figure -- docs/src/images/patch-refinement.svg`

use std::fmt::Write as _;

use glam::{DVec2, DVec3};
use goniolight::geometry::generate::fan_split;
use goniolight::geometry::Mesh;
use goniolight::radiosity::refine::{refine_surface, regular};

/// Texel side, metres.
const TEXEL: f64 = 0.2;
/// Pixels per metre in the drawing.
const SCALE: f64 = 300.0;

/// Each drawn triangle's corners, metres in the wall's plane.
type Triangles = Vec<[DVec2; 3]>;

fn wall() -> Mesh {
    let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    let quad = Mesh {
        positions: vec![v(0.0, 0.0), v(2.0, 0.0), v(2.0, 1.0), v(0.0, 1.0)],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    };
    fan_split(&quad, 10)
}

fn corners(mesh: &Mesh, t: usize) -> [DVec2; 3] {
    mesh.triangles[t].map(|i| mesh.positions[i as usize].truncate())
}

/// Each side cut into `n` where the longest spans `n` texels.
fn regular_refinement(mesh: &Mesh) -> Triangles {
    (0..mesh.triangles.len())
        .flat_map(|t| {
            let c = corners(mesh, t);
            let longest = (0..3)
                .map(|k| c[k].distance(c[(k + 1) % 3]))
                .fold(0.0, f64::max);
            let p = regular(c, (longest / TEXEL).ceil() as u32);
            p.leaves
                .iter()
                .map(|l| [0, 1, 2].map(|k| p.points[l[k] as usize]))
                .collect::<Vec<_>>()
        })
        .collect()
}

fn patch_refinement(mesh: &Mesh) -> Triangles {
    let all: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
    refine_surface(mesh, &all, |_| TEXEL)
        .iter()
        .enumerate()
        .flat_map(|(t, parts)| {
            let c = corners(mesh, t);
            parts
                .iter()
                .map(move |w| w.map(|w| c[0] * w.x + c[1] * w.y + c[2] * w.z))
        })
        .collect()
}

/// One panel: its title, the triangles, at `x0, y0` pixels (the wall's top-left corner).
fn panel(svg: &mut String, title: &str, triangles: &Triangles, x0: f64, y0: f64) {
    let px = |p: DVec2| (x0 + p.x * SCALE, y0 + (1.0 - p.y) * SCALE);
    writeln!(
        svg,
        r#"<text x="{x0}" y="{}" font-size="16">{title}: {} triangles</text>"#,
        y0 - 12.0,
        triangles.len()
    )
    .unwrap();
    for t in triangles {
        let points: Vec<String> = t
            .iter()
            .map(|&p| {
                let (x, y) = px(p);
                format!("{x:.2},{y:.2}")
            })
            .collect();
        writeln!(
            svg,
            r##"<polygon points="{}" fill="#f4efe6" stroke="#27408b" stroke-width="0.4"/>"##,
            points.join(" ")
        )
        .unwrap();
    }
}

fn main() -> anyhow::Result<()> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "patch-refinement.svg".into());
    let mesh = wall();
    let (regular, patches) = (regular_refinement(&mesh), patch_refinement(&mesh));
    let (width, height) = (2.0 * 2.0 * SCALE + 120.0, SCALE + 150.0);
    let mut svg = String::new();
    writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif">"#
    )?;
    writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#)?;
    panel(&mut svg, "Regular refinement", &regular, 40.0, 50.0);
    panel(
        &mut svg,
        "Patch refinement (Edström §4.4)",
        &patches,
        80.0 + 2.0 * SCALE,
        50.0,
    );
    // Scale bar under the left panel, caption under both.
    let y = 50.0 + SCALE + 30.0;
    writeln!(
        svg,
        r#"<path d="M40 {y} h{SCALE} M40 {} v10 M{} {} v10" stroke="black" stroke-width="1.5"/>"#,
        y - 5.0,
        40.0 + SCALE,
        y - 5.0
    )?;
    writeln!(
        svg,
        r#"<text x="{}" y="{}" font-size="14" text-anchor="middle">1 m</text>"#,
        40.0 + SCALE / 2.0,
        y + 18.0
    )?;
    writeln!(
        svg,
        r#"<text x="40" y="{}" font-size="14">A 2 × 1 m wall exported as 20 CAD strips fanned from its lower-left corner, vertex-lit under {TEXEL} m texels.</text>"#,
        y + 48.0
    )?;
    writeln!(svg, "</svg>")?;
    std::fs::write(&out, svg)?;
    println!(
        "wrote {out}: regular {} triangles, patches {}",
        regular.len(),
        patches.len()
    );
    Ok(())
}
