//! The files of the surfaces' sun hours: `facades.csv` (every facade cell), one unfolded
//! elevation image per facade (`facades/NN-DIR.png`, the largest [`MAX_FACADE_IMAGES`]),
//! `points.csv` (window points with their EN 17037 level), and their summaries for
//! `study.json`. Coordinates are the model file's plan coordinates and heights.

use std::fmt::Write as _;
use std::path::Path;

use glam::DVec3;

use super::annotate::{framed, Frame, PlanLabels};
use super::colours::hours_colour;
use super::surfaces::{en17037_level, Facade, WindowPoint};
use crate::io::{create_dir, write_atomic, WriteError};
use crate::render::legend::with_legend_panel;
use crate::render::output::write_image;

/// The most facade images one study writes (the largest facades); `facades.csv` has all.
pub const MAX_FACADE_IMAGES: usize = 24;

/// The sun hours computed on the model's surfaces for one date.
#[derive(Debug, Clone, Default)]
pub struct SurfaceResults {
    /// The facades with their cells' hours.
    pub facades: Vec<Facade>,
    /// The window points and their hours.
    pub points: Vec<(WindowPoint, f64)>,
    /// The lowest sun counted, degrees.
    pub min_elevation_deg: f64,
}

/// One facade's line in `study.json`.
#[derive(Debug, Clone, serde::Serialize)]
pub struct FacadeSummary {
    /// Its number (1 = the largest).
    pub id: usize,
    /// The compass direction it faces, degrees from true north.
    pub faces_deg: f64,
    /// Its area, m².
    pub area_m2: f64,
    /// The least, mean and most hours over its cells.
    pub min_h: f64,
    /// The mean hours over its cells.
    pub mean_h: f64,
    /// The most hours over its cells.
    pub max_h: f64,
    /// Its image (relative to the study's folder), when one was written.
    pub image: Option<String>,
}

/// One window point's line in `study.json`.
#[derive(Debug, Clone, serde::Serialize)]
pub struct PointResult {
    /// Its name.
    pub name: String,
    /// Hours of direct sun.
    pub hours: f64,
    /// EN 17037's level reached ("high", "medium", "minimum", "none").
    pub en17037: &'static str,
}

/// The 16-wind compass name of `azimuth_deg` ("N", "NNE", …).
pub fn compass(azimuth_deg: f64) -> &'static str {
    const NAMES: [&str; 16] = [
        "N", "NNE", "NE", "ENE", "E", "ESE", "SE", "SSE", "S", "SSW", "SW", "WSW", "W", "WNW",
        "NW", "NNW",
    ];
    NAMES[((azimuth_deg.rem_euclid(360.0) / 22.5).round() as usize) % 16]
}

/// Pixels per cell side of a facade's image: about 640 pixels along its longer side, at
/// least 240 up its height, 2 to 40 per cell.
fn cell_px(f: &Facade) -> u32 {
    let (nu, nv) = f.cells;
    (640 / nu.max(nv)).max(240 / nv).clamp(2, 40) as u32
}

/// A facade's unfolded elevation seen from outside: each cell a square of its hours'
/// colour on the scale up to `scale_h`, white off the facade; the legend beside it.
pub fn facade_image(f: &Facade, scale_h: f32) -> image::RgbaImage {
    let (nu, nv) = f.cells;
    let k = cell_px(f);
    let raster = image::RgbaImage::from_fn(nu as u32 * k, nv as u32 * k, |x, y| {
        let (i, j) = ((x / k) as usize, nv - 1 - (y / k) as usize);
        match f.hours[j * nu + i] {
            Some(h) => {
                let [r, g, b] = hours_colour(h, scale_h);
                image::Rgba([r, g, b, 255])
            }
            None => image::Rgba([255, 255, 255, 255]),
        }
    });
    let labels: Vec<String> = (0..=4)
        .map(|q| format!("{:.1} h", scale_h * q as f32 / 4.0))
        .collect();
    with_legend_panel(&raster, "sun", &labels, |t| hours_colour(t, 1.0))
}

/// The summaries of `results` for `study.json`: each facade (its image's name, written by
/// [`write_surfaces`] for the largest [`MAX_FACADE_IMAGES`]) and each window point.
pub fn surface_summaries(
    results: &SurfaceResults,
    north_offset_deg: f64,
) -> (Vec<FacadeSummary>, Vec<PointResult>) {
    let facades = results
        .facades
        .iter()
        .enumerate()
        .map(|(n, f)| {
            let id = n + 1;
            let faces = f.azimuth_deg(north_offset_deg);
            let values: Vec<f64> = f.hours.iter().flatten().map(|&h| h as f64).collect();
            let count = values.len().max(1) as f64;
            FacadeSummary {
                id,
                faces_deg: faces,
                area_m2: f.area_m2,
                min_h: values.iter().copied().fold(f64::INFINITY, f64::min),
                mean_h: values.iter().sum::<f64>() / count + 0.0,
                max_h: values.iter().copied().fold(0.0, f64::max),
                image: (n < MAX_FACADE_IMAGES)
                    .then(|| format!("facades/{id:02}-{}.png", compass(faces))),
            }
        })
        .collect();
    let points = results
        .points
        .iter()
        .map(|(p, hours)| PointResult {
            name: p.name.clone(),
            hours: *hours,
            en17037: en17037_level(*hours),
        })
        .collect();
    (facades, points)
}

/// Writes `facades.csv`, the facade images and `points.csv` into `dir`; returns their
/// summaries ([`surface_summaries`]). `origin` is added to world x, y; heights are above
/// `ground_z`.
pub fn write_surfaces(
    dir: &Path,
    results: &SurfaceResults,
    labels: &PlanLabels,
    origin: glam::DVec2,
    ground_z: f64,
    scale_h: f32,
) -> Result<(Vec<FacadeSummary>, Vec<PointResult>), WriteError> {
    let to_file = |p: DVec3| DVec3::new(p.x + origin.x, p.y + origin.y, p.z - ground_z);
    let north = labels.north_offset_deg;
    let (facades, points) = surface_summaries(results, north);
    if !results.facades.is_empty() {
        let mut csv = String::from("facade,faces_deg,x,y,z,hours\n");
        let images = dir.join("facades");
        create_dir(&images)?;
        for (f, summary) in results.facades.iter().zip(&facades) {
            let (id, faces) = (summary.id, summary.faces_deg);
            let (nu, _) = f.cells;
            for (k, h) in f.hours.iter().enumerate() {
                if let Some(h) = h {
                    let p = to_file(f.cell_center(k % nu, k / nu));
                    let _ = writeln!(
                        csv,
                        "{id},{faces:.1},{:.3},{:.3},{:.3},{h:.4}",
                        p.x, p.y, p.z
                    );
                }
            }
            if let Some(name) = &summary.image {
                let k = cell_px(f);
                let frame = Frame {
                    size_px: (f.cells.0 as u32 * k, f.cells.1 as u32 * k),
                    px_per_m: k as f64 / f.cell_m,
                    left_bottom_m: (0.0, f.origin.z - ground_z),
                    axes: (
                        "along the facade seen from outside (m)".into(),
                        "height (m)".into(),
                    ),
                    north_offset_deg: None,
                };
                let l = PlanLabels {
                    title: format!(
                        "Facade {id} facing {} ({faces:.0}°), {:.0} m² — hours of sun",
                        compass(faces),
                        f.area_m2
                    ),
                    subtitle: labels.subtitle.clone(),
                    north_offset_deg: north,
                };
                write_image(
                    &dir.join(name),
                    &framed(&frame, &facade_image(f, scale_h), &l),
                )?;
            }
        }
        write_atomic(&dir.join("facades.csv"), csv.as_bytes())?;
    }
    if !results.points.is_empty() {
        let mut csv = String::from("name,x,y,z,nx,ny,nz,hours,en17037\n");
        for ((p, hours), summary) in results.points.iter().zip(&points) {
            let [x, y, z] = p.position;
            let [nx, ny, nz] = p.normal;
            let _ = writeln!(
                csv,
                "{},{x},{y},{z},{nx},{ny},{nz},{hours:.4},{}",
                p.name.replace(',', " "),
                summary.en17037
            );
        }
        write_atomic(&dir.join("points.csv"), csv.as_bytes())?;
    }
    Ok((facades, points))
}
