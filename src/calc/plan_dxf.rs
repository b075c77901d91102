//! A grid's plan as DXF (AutoCAD R12, ASCII, metres), for CAD users taking results back
//! into their drawings. The coordinates are the plan's: the model's x and y for grids in
//! plan, along the wall and up for a vertical grid. Layers:
//!
//! - `OUTLINE`: the grid's outline (and the polygon it leaves out), closed polylines;
//! - `ISOLUX`: each piece of each isolux line (the plan's levels) as a polyline, its value
//!   in the entity's extended data (application `GONIOLIGHT`, a real) and as a `TEXT` on
//!   `ISOLUX_LABELS`;
//! - `VALUES`: the value at every point as a `TEXT` centred on it (lux to 0.1; daylight
//!   factors, per cent, to 0.01);
//! - `LUMINAIRES`: each luminaire over the plan an `INSERT` of the block `LUMINAIRE` (a
//!   circle and a cross), its name in the insert's extended data and as a `TEXT`
//!   (horizontal grids);
//! - `AREAS`: the areas judged by a standard, closed polylines with their names.
//!
//! R12 is the DXF every CAD program reads; the writer is this module's (a few entity
//! kinds of a plain text format), checked with `ezdxf` in the Python tests.

use std::fmt::Write as _;

use super::plan::Plan;
use crate::photometry::plot::DrawError;
use crate::scene::grid::GridKind;

/// The layers and their AutoCAD colour numbers.
const LAYERS: [(&str, u8); 6] = [
    ("OUTLINE", 7),
    ("ISOLUX", 1),
    ("ISOLUX_LABELS", 1),
    ("VALUES", 8),
    ("LUMINAIRES", 5),
    ("AREAS", 6),
];

/// The extended data's application name.
pub const DXF_APP: &str = "GONIOLIGHT";

/// A DXF text being written: group codes and values, one per line.
struct Dxf(String);

impl Dxf {
    fn pair(&mut self, code: u16, value: impl std::fmt::Display) {
        let _ = writeln!(self.0, "{code:>3}\n{value}");
    }

    /// A point's group codes (10/20/30 + `offset`).
    fn point(&mut self, offset: u16, x: f64, y: f64) {
        self.pair(10 + offset, format!("{x:.6}"));
        self.pair(20 + offset, format!("{y:.6}"));
        self.pair(30 + offset, "0.0");
    }

    fn polyline(&mut self, layer: &str, points: &[[f64; 2]], closed: bool, value: Option<f64>) {
        self.pair(0, "POLYLINE");
        self.pair(8, layer);
        self.pair(66, 1);
        self.point(0, 0.0, 0.0);
        self.pair(70, u8::from(closed));
        if let Some(v) = value {
            self.pair(1001, DXF_APP);
            self.pair(1040, v);
        }
        for p in points {
            self.pair(0, "VERTEX");
            self.pair(8, layer);
            self.point(0, p[0], p[1]);
        }
        self.pair(0, "SEQEND");
        self.pair(8, layer);
    }

    /// A text of `height` metres, centred on (x, y).
    fn text(&mut self, layer: &str, [x, y]: [f64; 2], height: f64, text: &str) {
        self.pair(0, "TEXT");
        self.pair(8, layer);
        self.point(0, x, y);
        self.pair(40, format!("{height:.4}"));
        self.pair(1, dxf_text(text));
        self.pair(72, 1);
        self.point(1, x, y);
        self.pair(73, 2);
    }

    fn table(&mut self, name: &str, entries: usize) {
        self.pair(0, "TABLE");
        self.pair(2, name);
        self.pair(70, entries);
    }
}

/// Text as R12 keeps it: one line of ASCII, anything else as `\U+XXXX`.
fn dxf_text(s: &str) -> String {
    s.chars()
        .map(|c| match c {
            ' '..='~' => c.to_string(),
            '\n' | '\r' | '\t' => " ".into(),
            c => format!("\\U+{:04X}", c as u32),
        })
        .collect()
}

/// The header, the tables (line type, layers, text style, the extended data's
/// application) and the block of a luminaire.
fn preamble(d: &mut Dxf, lo: [f64; 2], hi: [f64; 2]) {
    d.pair(0, "SECTION");
    d.pair(2, "HEADER");
    d.pair(9, "$ACADVER");
    d.pair(1, "AC1009");
    d.pair(9, "$EXTMIN");
    d.point(0, lo[0], lo[1]);
    d.pair(9, "$EXTMAX");
    d.point(0, hi[0], hi[1]);
    d.pair(9, "$MEASUREMENT");
    d.pair(70, 1);
    d.pair(0, "ENDSEC");
    d.pair(0, "SECTION");
    d.pair(2, "TABLES");
    d.table("LTYPE", 1);
    d.pair(0, "LTYPE");
    d.pair(2, "CONTINUOUS");
    d.pair(70, 0);
    d.pair(3, "Solid line");
    d.pair(72, 65);
    d.pair(73, 0);
    d.pair(40, "0.0");
    d.pair(0, "ENDTAB");
    d.table("LAYER", LAYERS.len() + 1);
    for (name, colour) in [("0", 7)].into_iter().chain(LAYERS) {
        d.pair(0, "LAYER");
        d.pair(2, name);
        d.pair(70, 0);
        d.pair(62, colour);
        d.pair(6, "CONTINUOUS");
    }
    d.pair(0, "ENDTAB");
    d.table("STYLE", 1);
    d.pair(0, "STYLE");
    d.pair(2, "STANDARD");
    d.pair(70, 0);
    d.pair(40, "0.0");
    d.pair(41, "1.0");
    d.pair(50, "0.0");
    d.pair(71, 0);
    d.pair(42, "0.2");
    d.pair(3, "txt");
    d.pair(4, "");
    d.pair(0, "ENDTAB");
    d.table("APPID", 2);
    for app in ["ACAD", DXF_APP] {
        d.pair(0, "APPID");
        d.pair(2, app);
        d.pair(70, 0);
    }
    d.pair(0, "ENDTAB");
    d.pair(0, "ENDSEC");
    d.pair(0, "SECTION");
    d.pair(2, "BLOCKS");
    d.pair(0, "BLOCK");
    d.pair(8, "0");
    d.pair(2, "LUMINAIRE");
    d.pair(70, 0);
    d.point(0, 0.0, 0.0);
    d.pair(3, "LUMINAIRE");
    d.pair(0, "CIRCLE");
    d.pair(8, "0");
    d.point(0, 0.0, 0.0);
    d.pair(40, "0.15");
    for (a, b) in [([-0.1, 0.0], [0.1, 0.0]), ([0.0, -0.1], [0.0, 0.1])] {
        d.pair(0, "LINE");
        d.pair(8, "0");
        d.point(0, a[0], a[1]);
        d.point(1, b[0], b[1]);
    }
    d.pair(0, "ENDBLK");
    d.pair(8, "0");
    d.pair(0, "ENDSEC");
}

/// `plan` as DXF text.
pub fn plan_dxf(plan: &Plan) -> Result<String, DrawError> {
    let outline = plan.outline();
    let (lo, hi) = crate::geometry::polygon::bounds(&outline);
    let mut d = Dxf(String::new());
    preamble(&mut d, lo, hi);
    d.pair(0, "SECTION");
    d.pair(2, "ENTITIES");
    d.polyline("OUTLINE", &outline, true, None);
    if let Some(hole) = &plan.grid.entry.exclude {
        d.polyline("OUTLINE", hole, true, None);
    }
    let [du, dv] = plan.grid.spacing;
    let height = (0.2 * du.min(dv)).clamp(0.02, 0.5);
    for (level, pieces) in plan.isolux()? {
        for piece in &pieces {
            d.polyline("ISOLUX", piece, false, Some(level));
        }
        if let Some(longest) = pieces.iter().max_by_key(|p| p.len()) {
            d.text(
                "ISOLUX_LABELS",
                longest[longest.len() / 2],
                height * 1.5,
                &plan.label(level),
            );
        }
    }
    for (&p, &v) in plan.grid.points.iter().zip(plan.values) {
        let c = plan.plane_coords(p);
        let text = match plan.daylight_factor {
            Some(_) => format!("{v:.2}"),
            None => format!("{v:.1}"),
        };
        d.text("VALUES", [c.x, c.y], height, &text);
    }
    if plan.grid.entry.kind != GridKind::Vertical {
        for (position, name) in &plan.luminaires {
            let (x, y) = (position.x, position.y);
            if !(lo[0]..=hi[0]).contains(&x) || !(lo[1]..=hi[1]).contains(&y) {
                continue;
            }
            d.pair(0, "INSERT");
            d.pair(8, "LUMINAIRES");
            d.pair(2, "LUMINAIRE");
            d.point(0, x, y);
            d.pair(1001, DXF_APP);
            d.pair(1000, dxf_text(name));
            d.text("LUMINAIRES", [x + 0.25, y + 0.25], height * 1.5, name);
        }
    }
    if !matches!(plan.grid.entry.kind, GridKind::Vertical | GridKind::Ceiling) {
        for (area, name) in &plan.areas {
            d.polyline("AREAS", area, true, None);
            let (a, b) = crate::geometry::polygon::bounds(area);
            d.text(
                "AREAS",
                [a[0] + (b[0] - a[0]) / 2.0, b[1] - height],
                height * 1.5,
                name,
            );
        }
    }
    d.pair(0, "ENDSEC");
    d.pair(0, "EOF");
    Ok(d.0)
}
