//! A grid's plan (PNG or SVG): the values in false colour cell by cell, isolux lines at
//! round values with their labels (marching squares, the `contour` crate), optionally the
//! value at every point, the luminaires' plan positions, metre axes; beside the plan the
//! statistics (Em, Emin, Emax, U0, g2, MF), the colour scale in lux and a scale bar.
//! Horizontal kinds are drawn in plan (x right, y up); a vertical grid as seen from the
//! front (along the wall to the right, height up).

use glam::{DVec2, DVec3};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use super::daylight::FactorStats;
use super::stats::GridStats;
use crate::photometry::isocandela::round_levels;
use crate::photometry::plot::{nice_ceiling, png_bytes, svg_string, DrawError, DrawResult};
use crate::scene::grid::{CalcGrid, GridKind};
use crate::scene::Palette;

const WIDTH: u32 = 1200;
const HEIGHT: u32 = 860;
/// Width of the panel beside the plan.
const SIDE: u32 = 300;

/// What a plan shows.
pub struct Plan<'a> {
    /// The grid.
    pub grid: &'a CalcGrid,
    /// The value at each of its points, lux.
    pub values: &'a [f64],
    /// Its statistics.
    pub stats: GridStats,
    /// The maintenance factor the values include.
    pub maintenance_factor: f64,
    /// The luminaires' positions and labels (drawn on horizontal grids).
    pub luminaires: Vec<(DVec3, String)>,
    /// The observers: eye, line of sight and label (drawn on horizontal grids).
    pub observers: Vec<(DVec3, DVec3, String)>,
    /// The areas judged by a standard (EN 12464-1 task areas and areas, not rooms; EN 1838
    /// routes and areas): outline in plan and name (drawn on horizontal grids).
    pub areas: Vec<(Vec<[f64; 2]>, String)>,
    /// What light the values hold, for the statistics box: one or two short lines
    /// ("direct light only"; "direct + interreflected", "radiosity 99.0 % converged").
    pub light: Vec<String>,
    /// The palette, and its number of hard steps (0: smooth).
    pub palette: (Palette, u32),
    /// Print the value at every point.
    pub values_at_points: bool,
    /// Angle from the plan's +Y clockwise to true north, degrees, where the scene has a
    /// `[site]` (a north arrow on horizontal plans).
    pub north_offset_deg: Option<f64>,
    /// With the daylight factor's statistics, the values are daylight factors (per cent)
    /// rather than lux: the plan's title, lines (at 0.5, 1, 2, 5, 10 … %), scale and
    /// statistics say so.
    pub daylight_factor: Option<FactorStats>,
}

/// The levels of a daylight-factor plan's lines, per cent (the usual 1/2/5 % bands and
/// their neighbours).
pub const DF_LEVELS: [f64; 7] = [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0];

/// A lux value as a label: whole lux from 10 up, two decimals below (zeros dropped).
fn lux_label(v: f64) -> String {
    if v >= 10.0 {
        format!("{v:.0}")
    } else {
        let s = format!("{v:.2}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Where on a line (`piece`, plan metres) its label goes: the vertex farthest from the
/// labels already `placed` (the middle one when there are none), so that lines that
/// crowd together in one place are labelled where they part.
fn label_spot(piece: &[[f64; 2]], placed: &[[f64; 2]]) -> [f64; 2] {
    let middle = piece[piece.len() / 2];
    let clearance = |p: &[f64; 2]| {
        placed
            .iter()
            .map(|q| (p[0] - q[0]).hypot(p[1] - q[1]))
            .fold(f64::INFINITY, f64::min)
    };
    if placed.is_empty() {
        return middle;
    }
    piece
        .iter()
        .copied()
        .max_by(|a, b| clearance(a).total_cmp(&clearance(b)))
        .unwrap_or(middle)
}

/// Ticks of a colour scale from 0 to `top` at a round step (1, 2, 2.5 or 5 × 10^k) giving
/// two to five intervals.
fn scale_ticks(top: f64) -> Vec<f64> {
    let magnitude = 10f64.powf((top / 4.0).log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * magnitude)
        .find(|s| top / s <= 5.0 + 1e-9)
        .unwrap_or(10.0 * magnitude);
    (0..)
        .map(|k| k as f64 * step)
        .take_while(|v| *v <= top * (1.0 + 1e-9))
        .collect()
}

/// The isolux lines of a plan: (level, pieces of [u, v] points).
pub type IsoluxLines = Vec<(f64, Vec<Vec<[f64; 2]>>)>;

impl Plan<'_> {
    /// The grid's points in the plan's 2D frame (metres).
    pub(crate) fn plane_coords(&self, p: DVec3) -> DVec2 {
        match (self.grid.entry.kind, self.grid.facing) {
            (GridKind::Vertical, Some(f)) => {
                let along = DVec3::Z.cross(f);
                let c = self.grid.entry.corner.unwrap_or_default();
                DVec2::new((p - DVec3::new(c[0], c[1], p.z)).dot(along), p.z)
            }
            _ => p.truncate(),
        }
    }

    /// The outline in the plan's frame.
    pub(crate) fn outline(&self) -> Vec<[f64; 2]> {
        let e = &self.grid.entry;
        match (e.kind, &e.outline, e.corner, e.size) {
            (GridKind::Vertical, _, _, Some(s)) => {
                let h = e.height;
                vec![[0.0, h], [s[0], h], [s[0], h + s[1]], [0.0, h + s[1]]]
            }
            (_, Some(o), _, _) => o.clone(),
            (_, None, Some(c), Some(s)) => vec![
                c,
                [c[0] + s[0], c[1]],
                [c[0] + s[0], c[1] + s[1]],
                [c[0], c[1] + s[1]],
            ],
            _ => Vec::new(),
        }
    }

    /// The isolux lines at round levels between the grid's minimum and maximum, over the
    /// regular lattice of its points (points left out by an outline or border take the
    /// value of the nearest point kept; lines through them are dropped).
    pub fn isolux(&self) -> Result<IsoluxLines, DrawError> {
        let uv: Vec<DVec2> = self
            .grid
            .points
            .iter()
            .map(|&p| self.plane_coords(p))
            .collect();
        let [du, dv] = self.grid.spacing;
        let lo = uv
            .iter()
            .fold(DVec2::splat(f64::INFINITY), |a, &b| a.min(b));
        let hi = uv
            .iter()
            .fold(DVec2::splat(f64::NEG_INFINITY), |a, &b| a.max(b));
        let nu = ((hi.x - lo.x) / du).round() as usize + 1;
        let nv = ((hi.y - lo.y) / dv).round() as usize + 1;
        let index = |p: DVec2| {
            (
                ((p.x - lo.x) / du).round() as usize,
                ((p.y - lo.y) / dv).round() as usize,
            )
        };
        let mut lattice = vec![None; nu * nv];
        for (p, &v) in uv.iter().zip(self.values) {
            let (i, j) = index(*p);
            lattice[j * nu + i] = Some(v);
        }
        let filled: Vec<f64> = (0..nu * nv)
            .map(|k| {
                lattice[k].unwrap_or_else(|| {
                    let (i, j) = ((k % nu) as f64, (k / nu) as f64);
                    uv.iter()
                        .zip(self.values)
                        .min_by(|a, b| {
                            let d = |p: &DVec2| {
                                let (pi, pj) = index(*p);
                                (pi as f64 - i).hypot(pj as f64 - j)
                            };
                            d(a.0).total_cmp(&d(b.0))
                        })
                        .map_or(0.0, |(_, v)| *v)
                })
            })
            .collect();
        let kept = lattice;
        if nu < 2 || nv < 2 {
            return Ok(Vec::new());
        }
        let levels: Vec<f64> = match self.daylight_factor {
            Some(_) => DF_LEVELS.to_vec(),
            None => round_levels(self.stats.emax),
        }
        .into_iter()
        .filter(|&l| l > self.stats.emin && l <= self.stats.emax)
        .collect();
        let lines = contour::ContourBuilder::new(nu, nv, true)
            .x_origin(lo.x - du / 2.0)
            .y_origin(lo.y - dv / 2.0)
            .x_step(du)
            .y_step(dv)
            .lines(&filled, &levels)
            .map_err(|e| DrawError::new("the isolux lines", format!("{e:?}")))?;
        let inside = |x: f64, y: f64| {
            let (i, j) = (
                ((x - lo.x) / du).round().clamp(0.0, (nu - 1) as f64) as usize,
                ((y - lo.y) / dv).round().clamp(0.0, (nv - 1) as f64) as usize,
            );
            kept[j * nu + i].is_some()
        };
        Ok(lines
            .into_iter()
            .map(|line| {
                let (geometry, level) = line.into_inner();
                let pieces = geometry
                    .0
                    .into_iter()
                    .map(|ls| ls.0.into_iter().map(|c| [c.x, c.y]).collect::<Vec<_>>())
                    .filter(|piece: &Vec<[f64; 2]>| piece.iter().all(|&[x, y]| inside(x, y)))
                    .collect();
                (level, pieces)
            })
            .collect())
    }

    /// Renders as PNG bytes.
    pub fn png(&self) -> Result<Vec<u8>, DrawError> {
        png_bytes(WIDTH, HEIGHT, "the plan", |root| self.draw(root))
    }

    /// Renders as SVG.
    pub fn svg(&self) -> Result<String, DrawError> {
        svg_string(WIDTH, HEIGHT, "the plan", |root| self.draw(root))
    }

    /// A value as a label: lux as [`lux_label`], daylight factors with a % sign.
    pub(crate) fn label(&self, v: f64) -> String {
        match self.daylight_factor {
            Some(_) => format!("{} %", lux_label(v)),
            None => lux_label(v),
        }
    }

    fn colour(&self, lux: f64, top: f64) -> RGBColor {
        let (palette, steps) = self.palette;
        let [r, g, b] = palette.srgb8((lux / top) as f32, steps);
        RGBColor(r, g, b)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (head, body) = root.split_vertically(56);
        let e = &self.grid.entry;
        let kind = format!("{:?}", e.kind).to_lowercase();
        let what = match self.daylight_factor {
            Some(_) => "daylight factor (%, CIE overcast sky)",
            None => "illuminance (lx, maintained)",
        };
        head.draw(&Text::new(
            format!("{} — {kind} {what}", e.name),
            (20, 16),
            ("sans-serif", 22).into_font(),
        ))?;
        let (chart_area, side) = body.split_horizontally(WIDTH - SIDE);
        let top = nice_ceiling(self.stats.emax.max(1e-9));
        let px_per_m = self.draw_plan(&chart_area, top)?;
        self.draw_side(&side, top, px_per_m)
    }

    /// Draws the plan; returns its scale in pixels per metre.
    fn draw_plan<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        top: f64,
    ) -> Result<f64, Box<dyn std::error::Error>>
    where
        DB::ErrorType: 'static,
    {
        let outline = self.outline();
        let (mut lo, mut hi) = outline.iter().fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1])],
                    [hi[0].max(p[0]), hi[1].max(p[1])],
                )
            },
        );
        // Equal metres on both axes: pad the shorter range to the area's proportions.
        let (w, h) = area.dim_in_pixel();
        let (plot_w, plot_h) = (w as f64 - 90.0, h as f64 - 80.0);
        let margin = 0.05 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
        for k in 0..2 {
            lo[k] -= margin;
            hi[k] += margin;
        }
        let scale = (plot_w / (hi[0] - lo[0])).min(plot_h / (hi[1] - lo[1]));
        let pad = |lo: &mut f64, hi: &mut f64, pixels: f64| {
            let extra = (pixels / scale - (*hi - *lo)) / 2.0;
            *lo -= extra;
            *hi += extra;
        };
        pad(&mut lo[0], &mut hi[0], plot_w);
        pad(&mut lo[1], &mut hi[1], plot_h);
        let mut chart = ChartBuilder::on(area)
            .margin_top(10)
            .margin_right(10)
            .margin_left(14)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(lo[0]..hi[0], lo[1]..hi[1])?;
        let (x_desc, y_desc) = match self.grid.entry.kind {
            GridKind::Vertical => ("along the wall (m)", "height (m)"),
            _ => ("x (m)", "y (m)"),
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .label_style(("sans-serif", 14))
            .draw()?;
        let [du, dv] = self.grid.spacing;
        chart.draw_series(self.grid.points.iter().zip(self.values).map(|(&p, &v)| {
            let c = self.plane_coords(p);
            Rectangle::new(
                [
                    (c.x - du / 2.0, c.y - dv / 2.0),
                    (c.x + du / 2.0, c.y + dv / 2.0),
                ],
                self.colour(v, top).filled(),
            )
        }))?;
        let closed = |o: &[[f64; 2]]| -> Vec<(f64, f64)> {
            o.iter().chain(o.first()).map(|p| (p[0], p[1])).collect()
        };
        chart.draw_series(std::iter::once(PathElement::new(
            closed(&outline),
            BLACK.stroke_width(2),
        )))?;
        if let Some(hole) = &self.grid.entry.exclude {
            chart.draw_series(std::iter::once(PathElement::new(
                closed(hole),
                BLACK.stroke_width(1),
            )))?;
        }
        let label = ("sans-serif", 13).into_font();
        let mut placed: Vec<[f64; 2]> = Vec::new();
        for (level, pieces) in self.isolux()? {
            for piece in &pieces {
                chart.draw_series(LineSeries::new(
                    piece.iter().map(|p| (p[0], p[1])),
                    BLACK.stroke_width(1),
                ))?;
            }
            if let Some(longest) = pieces.iter().max_by_key(|p| p.len()) {
                let [x, y] = label_spot(longest, &placed);
                placed.push([x, y]);
                chart.draw_series(std::iter::once(Text::new(
                    self.label(level),
                    (x, y),
                    label.clone(),
                )))?;
            }
        }
        if self.values_at_points {
            let small = ("sans-serif", 11).into_font();
            chart.draw_series(self.grid.points.iter().zip(self.values).map(|(&p, &v)| {
                let c = self.plane_coords(p);
                let text = match self.daylight_factor {
                    Some(_) => format!("{v:.1}"),
                    None => format!("{v:.0}"),
                };
                Text::new(text, (c.x, c.y), small.clone())
            }))?;
        }
        // On the floor's plans: the areas and the observers; on a ceiling's only the
        // luminaires.
        let floor = !matches!(self.grid.entry.kind, GridKind::Vertical | GridKind::Ceiling);
        if floor {
            self.draw_areas(&mut chart, scale)?;
        }
        if self.grid.entry.kind != GridKind::Vertical {
            for (position, name) in &self.luminaires {
                let (x, y) = (position.x, position.y);
                if !(lo[0]..hi[0]).contains(&x) || !(lo[1]..hi[1]).contains(&y) {
                    continue;
                }
                chart.draw_series(std::iter::once(Circle::new(
                    (x, y),
                    7,
                    BLACK.stroke_width(2),
                )))?;
                chart.draw_series(std::iter::once(Cross::new(
                    (x, y),
                    5,
                    BLACK.stroke_width(1),
                )))?;
                let offset = 10.0 / scale;
                chart.draw_series(std::iter::once(Text::new(
                    name.clone(),
                    (x + offset, y + offset),
                    ("sans-serif", 13).into_font().color(&BLACK),
                )))?;
            }
            if floor {
                self.draw_observers(&mut chart, (lo, hi), scale)?;
            }
        }
        Ok(scale)
    }

    /// The observers: each eye as a filled triangle along its line of sight, labelled.
    fn draw_observers<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        (lo, hi): ([f64; 2], [f64; 2]),
        scale: f64,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let blue = RGBColor(20, 60, 200);
        for (eye, forward, name) in &self.observers {
            let (x, y) = (eye.x, eye.y);
            if !(lo[0]..hi[0]).contains(&x) || !(lo[1]..hi[1]).contains(&y) {
                continue;
            }
            // The eye as a filled triangle pointing along the line of sight, 24 px long.
            let f = DVec2::new(forward.x, forward.y).normalize_or_zero() / scale;
            let side = f.perp();
            let tip = (x + 16.0 * f.x, y + 16.0 * f.y);
            chart.draw_series(std::iter::once(Polygon::new(
                vec![
                    tip,
                    (x - 8.0 * f.x + 7.0 * side.x, y - 8.0 * f.y + 7.0 * side.y),
                    (x - 8.0 * f.x - 7.0 * side.x, y - 8.0 * f.y - 7.0 * side.y),
                ],
                blue.filled(),
            )))?;
            chart.draw_series(std::iter::once(Text::new(
                name.clone(),
                (x + 10.0 / scale, y - 12.0 / scale),
                ("sans-serif", 13).into_font().color(&blue),
            )))?;
        }
        Ok(())
    }

    /// The task areas: a dashed purple outline with the area's name inside its first
    /// corner.
    fn draw_areas<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        scale: f64,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let purple = RGBColor(128, 0, 140);
        for (outline, name) in &self.areas {
            let closed: Vec<(f64, f64)> = outline
                .iter()
                .chain(outline.first())
                .map(|p| (p[0], p[1]))
                .collect();
            chart.draw_series(std::iter::once(DashedPathElement::new(
                closed,
                8,
                5,
                purple.stroke_width(2),
            )))?;
            let (lo, hi) = crate::geometry::polygon::bounds(outline);
            chart.draw_series(std::iter::once(Text::new(
                name.clone(),
                (lo[0] + 4.0 / scale, hi[1] - 4.0 / scale),
                ("sans-serif", 13).into_font().color(&purple),
            )))?;
        }
        Ok(())
    }

    fn draw_side<DB: DrawingBackend>(
        &self,
        side: &DrawingArea<DB, Shift>,
        top: f64,
        px_per_m: f64,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let s = &self.stats;
        let font = ("sans-serif", 15).into_font();
        let mut rows = match self.daylight_factor {
            Some(f) => vec![
                format!("DF mean    {:.2} %", f.mean),
                format!("DF median  {:.2} %", f.median),
                format!("DF min  {:.2} %, max {:.2} %", f.min, f.max),
                format!("U0 = min/mean  {:.2}", f.u0),
            ],
            None => vec![
                format!("Em    {:.1} lx", s.em),
                format!("Emin  {:.1} lx", s.emin),
                format!("Emax  {:.1} lx", s.emax),
                format!("U0 = Emin/Em  {:.2}", s.u0),
                format!("g2 = Emin/Emax  {:.2}", s.g2),
                format!("maintenance factor {}", self.maintenance_factor),
            ],
        };
        rows.extend([
            format!(
                "{} points, {:.2} × {:.2} m",
                s.points, self.grid.spacing[0], self.grid.spacing[1]
            ),
            format!("height {} m", self.grid.entry.height),
        ]);
        rows.extend(self.light.iter().cloned());
        for (k, row) in rows.iter().enumerate() {
            side.draw(&Text::new(
                row.as_str(),
                (10, 20 + 22 * k as i32),
                font.clone(),
            ))?;
        }
        // The colour scale: a vertical bar with lux ticks.
        let (x0, y0, bar_h) = (14, 300, 300);
        let unit = if self.daylight_factor.is_some() {
            "%"
        } else {
            "lx"
        };
        side.draw(&Text::new(unit, (x0, y0 - 22), font.clone()))?;
        for k in 0..bar_h {
            let t = 1.0 - k as f64 / bar_h as f64;
            side.draw(&Rectangle::new(
                [(x0, y0 + k), (x0 + 26, y0 + k + 1)],
                self.colour(t * top, top).filled(),
            ))?;
        }
        side.draw(&Rectangle::new([(x0, y0), (x0 + 26, y0 + bar_h)], BLACK))?;
        for v in scale_ticks(top) {
            let y = y0 + bar_h - (bar_h as f64 * v / top).round() as i32;
            side.draw(&PathElement::new([(x0 + 26, y), (x0 + 32, y)], BLACK))?;
            side.draw(&Text::new(self.label(v), (x0 + 36, y - 7), font.clone()))?;
        }
        // The scale bar: a round length near 100 pixels.
        let metres = nice_ceiling(100.0 / px_per_m);
        let length = (metres * px_per_m).round() as i32;
        let y = y0 + bar_h + 50;
        side.draw(&PathElement::new(
            [(x0, y), (x0 + length, y)],
            BLACK.stroke_width(3),
        ))?;
        for x in [x0, x0 + length] {
            side.draw(&PathElement::new(
                [(x, y - 6), (x, y + 6)],
                BLACK.stroke_width(2),
            ))?;
        }
        side.draw(&Text::new(
            format!("{metres} m"),
            (x0, y + 12),
            font.clone(),
        ))?;
        let note = ("sans-serif", 12).into_font().color(&RGBColor(90, 90, 90));
        let mut lines = match self.grid.entry.kind {
            GridKind::Vertical => vec!["seen from the front of the wall"],
            GridKind::Ceiling => vec!["plan seen from above: x to the right, y up"],
            _ => vec!["plan: x to the right, y up"],
        };
        if self.grid.entry.kind != GridKind::Vertical && !self.luminaires.is_empty() {
            lines.push("○ luminaires (plan position)");
        }
        if !matches!(self.grid.entry.kind, GridKind::Vertical | GridKind::Ceiling) {
            if !self.observers.is_empty() {
                lines.push("▶ observers (eye, line of sight), UGR");
            }
            if !self.areas.is_empty() {
                lines.push("- - areas (EN 12464-1, EN 1838)");
            }
        }
        let contours = match self.daylight_factor {
            Some(_) => "lines at DF 0.5, 1, 2, 5, 10, 20 %",
            None => "isolux lines at round values",
        };
        if let (
            Some(north),
            GridKind::Horizontal | GridKind::Cylindrical | GridKind::Semicylindrical,
        ) = (self.north_offset_deg, self.grid.entry.kind)
        {
            crate::photometry::plot::draw_north_arrow(
                side,
                (x0 + length + 120, y),
                22.0,
                north,
                font.color(&BLACK),
            )?;
        }
        for (k, line) in lines.into_iter().chain([contours]).enumerate() {
            side.draw(&Text::new(line, (x0, y + 40 + 16 * k as i32), note.clone()))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::{label_spot, scale_ticks};

    #[test]
    fn labels_go_where_the_lines_part() {
        let line = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]];
        assert_eq!(label_spot(&line, &[]), [2.0, 0.0]);
        assert_eq!(label_spot(&line, &[[0.0, 0.1]]), [3.0, 0.0]);
        assert_eq!(label_spot(&line, &[[0.0, 0.1], [2.9, 0.1]]), [1.0, 0.0]);
    }

    #[test]
    fn colour_scale_ticks_are_round() {
        assert_eq!(scale_ticks(150.0), vec![0.0, 50.0, 100.0, 150.0]);
        assert_eq!(scale_ticks(200.0), vec![0.0, 50.0, 100.0, 150.0, 200.0]);
        assert_eq!(
            scale_ticks(1000.0),
            vec![0.0, 200.0, 400.0, 600.0, 800.0, 1000.0]
        );
        assert_eq!(scale_ticks(25.0), vec![0.0, 5.0, 10.0, 15.0, 20.0, 25.0]);
    }
}
