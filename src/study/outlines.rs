//! Per-step shadow outlines as vectors: the ground shadow of each step (and the model's
//! footprint) traced by marching squares (the `contour` crate) over the plan's cells,
//! written as GeoJSON (for GIS and CAD) and as an SVG plan in metres. Coordinates are the
//! model file's plan coordinates.

use std::fmt::Write as _;

use glam::DVec2;
use serde_json::json;

use super::colours::time_colour;
use super::shadow_profile::{Profile, ProfileStep, SURFACE_GROUND, SURFACE_MODEL};
use crate::io::xml_escape;
use crate::photometry::plot::{nice_ceiling, DrawError};

/// Polygons (outer ring then holes), model file's plan coordinates, metres.
pub type Polygons = Vec<Vec<Vec<DVec2>>>;

/// The outline of the cells where `inside` holds: pixel squares traced at their edges'
/// midpoints, so a polygon's area equals its cells' area up to the corners it cuts.
pub fn trace(profile: &Profile, inside: impl Fn(usize) -> bool) -> Result<Polygons, DrawError> {
    let n = profile.resolution as usize;
    let cell = profile.extent_m / n as f64;
    // Rows from the south edge up, so y grows with the row.
    let values: Vec<f64> = (0..n * n)
        .map(|k| {
            let (x, row) = (k % n, k / n);
            inside((n - 1 - row) * n + x) as u8 as f64
        })
        .collect();
    let south_west =
        profile.pixel_center(0, n as u32 - 1) - DVec2::splat(cell / 2.0) + profile.origin;
    let contours = contour::ContourBuilder::new(n, n, false)
        .x_origin(south_west.x)
        .y_origin(south_west.y)
        .x_step(cell)
        .y_step(cell)
        .contours(&values, &[0.5])
        .map_err(|e| DrawError::new("the shadow outlines", format!("{e:?}")))?;
    Ok(contours
        .into_iter()
        .flat_map(|c| c.into_inner().0 .0)
        .map(|polygon| {
            let (exterior, interiors) = polygon.into_inner();
            std::iter::once(exterior)
                .chain(interiors)
                .map(|ring| ring.0.into_iter().map(|c| DVec2::new(c.x, c.y)).collect())
                .collect()
        })
        .collect())
}

/// The area of polygons (outer rings minus holes), m².
pub fn area_m2(polygons: &Polygons) -> f64 {
    polygons
        .iter()
        .map(|rings| {
            let ring_area = |r: &Vec<DVec2>| {
                let mut a = 0.0;
                for i in 0..r.len() {
                    let (p, q) = (r[i], r[(i + 1) % r.len()]);
                    a += p.x * q.y - q.x * p.y;
                }
                (a / 2.0).abs()
            };
            ring_area(&rings[0]) - rings[1..].iter().map(ring_area).sum::<f64>()
        })
        .sum()
}

/// The ground shadow of `step` (outside the footprint).
pub fn step_outline(profile: &Profile, step: &ProfileStep) -> Result<Polygons, DrawError> {
    trace(profile, |k| {
        step.in_shadow(k) && profile.surface[k] == SURFACE_GROUND
    })
}

/// The model's footprint seen from above.
pub fn footprint_outline(profile: &Profile) -> Result<Polygons, DrawError> {
    trace(profile, |k| profile.surface[k] == SURFACE_MODEL)
}

fn coordinates(polygons: &Polygons) -> serde_json::Value {
    json!(polygons
        .iter()
        .map(|rings| rings
            .iter()
            .map(|ring| ring
                .iter()
                .chain(ring.first())
                .map(|p| [round_mm(p.x), round_mm(p.y)])
                .collect::<Vec<_>>())
            .collect::<Vec<_>>())
        .collect::<Vec<_>>())
}

fn round_mm(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

/// `outlines.geojson`: a FeatureCollection with the footprint (`"kind": "footprint"`) and
/// one MultiPolygon per step (`"kind": "shadow"`, `time`, `azimuth_deg`, `elevation_deg`,
/// `area_m2` as the traced polygons' area).
pub fn outlines_geojson(profile: &Profile) -> Result<String, DrawError> {
    let footprint = footprint_outline(profile)?;
    let mut features = vec![json!({
        "type": "Feature",
        "properties": { "kind": "footprint", "area_m2": area_m2(&footprint) },
        "geometry": { "type": "MultiPolygon", "coordinates": coordinates(&footprint) },
    })];
    for s in &profile.steps {
        let shadow = step_outline(profile, s)?;
        features.push(json!({
            "type": "Feature",
            "properties": {
                "kind": "shadow",
                "time": s.time.to_rfc3339_opts(chrono::SecondsFormat::Secs, true),
                "azimuth_deg": s.azimuth_deg,
                "elevation_deg": s.elevation_deg,
                "area_m2": area_m2(&shadow),
            },
            "geometry": { "type": "MultiPolygon", "coordinates": coordinates(&shadow) },
        }));
    }
    Ok(serde_json::to_string_pretty(&json!({
        "type": "FeatureCollection",
        "features": features,
    }))
    .expect("JSON of numbers and strings"))
}

fn svg_path(polygons: &Polygons, to_svg: impl Fn(DVec2) -> (f64, f64)) -> String {
    let mut d = String::new();
    for ring in polygons.iter().flatten() {
        for (i, p) in ring.iter().enumerate() {
            let (x, y) = to_svg(*p);
            let _ = write!(d, "{}{x:.2} {y:.2} ", if i == 0 { "M" } else { "L" });
        }
        d.push_str("Z ");
    }
    d
}

/// `outlines.svg`: the plan (800 px square, metres to the right and up) with the
/// footprint in grey and each step's shadow outlined in its time colour, a time legend, a
/// north arrow and a scale bar beside it.
pub fn outlines_svg(
    profile: &Profile,
    title: &str,
    north_offset_deg: f64,
) -> Result<String, DrawError> {
    const SIZE: f64 = 800.0;
    const SIDE: f64 = 220.0;
    const HEAD: f64 = 50.0;
    let scale = SIZE / profile.extent_m;
    let west = profile.center.x - profile.extent_m / 2.0 + profile.origin.x;
    let north = profile.center.y + profile.extent_m / 2.0 + profile.origin.y;
    let to_svg = |p: DVec2| ((p.x - west) * scale, HEAD + (north - p.y) * scale);
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif">
<rect width="100%" height="100%" fill="white"/>
<text x="10" y="30" font-size="18">{title}</text>
<rect x="0" y="{HEAD}" width="{SIZE}" height="{SIZE}" fill="rgb(246,246,243)" stroke="black"/>
"#,
        w = SIZE + SIDE,
        h = SIZE + HEAD + 10.0,
        title = xml_escape(title),
    );
    let count = profile.steps.len();
    for (i, s) in profile.steps.iter().enumerate() {
        let t = if count > 1 {
            i as f32 / (count - 1) as f32
        } else {
            0.5
        };
        let [r, g, b] = time_colour(t);
        let _ = writeln!(
            svg,
            r#"<path d="{}" fill="rgb({r},{g},{b})" fill-opacity="0.08" stroke="rgb({r},{g},{b})" stroke-width="1" fill-rule="evenodd"><title>{}</title></path>"#,
            svg_path(&step_outline(profile, s)?, to_svg),
            s.time.format("%H:%M")
        );
    }
    let _ = writeln!(
        svg,
        r#"<path d="{}" fill="rgb(128,128,132)" stroke="black" stroke-width="1.5" fill-rule="evenodd"><title>footprint</title></path>"#,
        svg_path(&footprint_outline(profile)?, to_svg)
    );
    // Beside the plan: the time legend, a north arrow and a scale bar.
    let x0 = SIZE + 20.0;
    let _ = writeln!(
        svg,
        r#"<text x="{x0}" y="{}" font-size="15">time</text>"#,
        HEAD + 20.0
    );
    for (k, s) in profile.steps.iter().enumerate() {
        if count > 12 && k % count.div_ceil(12) != 0 && k + 1 != count {
            continue;
        }
        let t = if count > 1 {
            k as f32 / (count - 1) as f32
        } else {
            0.5
        };
        let [r, g, b] = time_colour(t);
        let y = HEAD + 40.0 + 320.0 * t as f64;
        let _ = writeln!(
            svg,
            r#"<rect x="{x0}" y="{}" width="24" height="10" fill="rgb({r},{g},{b})"/><text x="{}" y="{}" font-size="13">{}</text>"#,
            y - 9.0,
            x0 + 30.0,
            y,
            s.time.format("%H:%M")
        );
    }
    let (cx, cy) = (x0 + 60.0, HEAD + 480.0);
    let a = north_offset_deg.to_radians();
    let (dx, dy) = (a.sin(), -a.cos());
    let _ = writeln!(
        svg,
        r#"<circle cx="{cx}" cy="{cy}" r="34" fill="none" stroke="black"/><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="black" stroke-width="3"/><circle cx="{:.1}" cy="{:.1}" r="5"/><text x="{:.1}" y="{:.1}" font-size="16" text-anchor="middle">N</text>"#,
        cx - 28.0 * dx,
        cy - 28.0 * dy,
        cx + 28.0 * dx,
        cy + 28.0 * dy,
        cx + 28.0 * dx,
        cy + 28.0 * dy,
        cx + 48.0 * dx,
        cy + 48.0 * dy + 6.0,
    );
    let metres = nice_ceiling(120.0 / scale);
    let length = metres * scale;
    let y = HEAD + 600.0;
    let _ = writeln!(
        svg,
        r#"<path d="M{x0} {y} h{length:.1} M{x0} {} v12 M{:.1} {} v12" stroke="black" stroke-width="2" fill="none"/><text x="{x0}" y="{}" font-size="14">{metres} m</text>
<text x="{x0}" y="{}" font-size="12" fill="rgb(90,90,90)">plan, model coordinates (m)</text>
<text x="{x0}" y="{}" font-size="12" fill="rgb(90,90,90)">grey: footprint</text>
</svg>"#,
        y - 6.0,
        x0 + length,
        y - 6.0,
        y + 24.0,
        y + 50.0,
        y + 66.0
    );
    Ok(svg)
}
