//! The planning tests' site plan (SVG): the model's roofs from above, each open space's
//! points coloured by whether they get 2 hours of sun, each window as a dot with an arrow
//! along its normal and its verdicts; beside the plan a legend, a north arrow and a scale
//! bar.

use std::fmt::Write as _;

use glam::{DVec2, DVec3};

use super::output::WindowRow;
use super::{ModelFigures, OPEN_SPACE_HOURS};
use crate::geometry::Mesh;
use crate::io::xml_escape;
use crate::scene::Scene;

/// The plan's drawing area, pixels.
const PLAN_PX: f64 = 760.0;
/// Width of the legend panel to the right of the plan, pixels.
const SIDE_PX: f64 = 300.0;
/// Margin round the plan and above it (title), pixels.
const MARGIN_PX: f64 = 30.0;
const TITLE_PX: f64 = 60.0;
/// Colours: sun for 2 h or more, shade for less, pass and fail.
const SUNNY: &str = "#f2c14e";
const SHADY: &str = "#6f7f99";
const PASS: &str = "#1a7f37";
const FAIL: &str = "#c62828";

/// Metres to pixels: x right, y up in the model becomes up on the page.
struct PlanFrame {
    lo: DVec2,
    scale: f64,
    width_m: f64,
    height_m: f64,
}

impl PlanFrame {
    fn px(&self, p: DVec2) -> (f64, f64) {
        (
            MARGIN_PX + (p.x - self.lo.x) * self.scale,
            TITLE_PX + (self.height_m - (p.y - self.lo.y)) * self.scale,
        )
    }
}

/// The plan's extent: the open spaces, the windows with their arrows, and the model,
/// with a margin.
fn extent(mesh: &Mesh, scene: &Scene) -> (DVec2, DVec2) {
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    let mut add = |p: DVec2| {
        lo = lo.min(p);
        hi = hi.max(p);
    };
    if let Some((a, b)) = mesh.bounds() {
        add(a.truncate());
        add(b.truncate());
    }
    for w in &scene.planning.windows {
        add(w.position.truncate());
    }
    for o in &scene.planning.open_spaces {
        for p in &o.grid.points {
            add(p.truncate());
        }
    }
    let pad = ((hi - lo).max_element() * 0.04).max(1.0);
    (lo - pad, hi + pad)
}

/// The SVG plan of `scene`'s planning tests with the proposed `figures` and the windows'
/// `rows`; `title` heads it.
pub fn site_plan_svg(
    scene: &Scene,
    figures: &ModelFigures,
    rows: &[WindowRow],
    title: &str,
) -> String {
    let mesh = scene.caster_mesh();
    let (lo, hi) = extent(&mesh, scene);
    let size = hi - lo;
    let scale = PLAN_PX / size.max_element();
    let frame = PlanFrame {
        lo,
        scale,
        width_m: size.x,
        height_m: size.y,
    };
    let (w_px, h_px) = (size.x * scale, size.y * scale);
    let width = MARGIN_PX * 2.0 + w_px + SIDE_PX;
    let height = (TITLE_PX + h_px + MARGIN_PX * 2.0).max(560.0);
    let mut svg = format!(
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="DejaVu Sans, sans-serif" font-size="13">
<rect width="100%" height="100%" fill="white"/>
<text x="{MARGIN_PX}" y="26" font-size="18" font-weight="bold">{}</text>
<text x="{MARGIN_PX}" y="46" fill="#444">Plan, metres (model coordinates); open spaces: hours of sun on the day</text>
<rect x="{MARGIN_PX}" y="{TITLE_PX}" width="{w_px:.1}" height="{h_px:.1}" fill="#f7f7f7" stroke="#999"/>
"##,
        xml_escape(title)
    );
    roofs(&mut svg, &mesh, &frame);
    for (o, f) in scene.planning.open_spaces.iter().zip(&figures.open_spaces) {
        open_space(&mut svg, o, f, &frame);
    }
    for (k, r) in rows.iter().enumerate() {
        // Windows above one another share a plan spot: their labels stack.
        let below = rows[..k]
            .iter()
            .filter(|o| (o.window.position - r.window.position).truncate().length() < 0.3)
            .count();
        window(&mut svg, k, r, &frame, below);
    }
    axes(&mut svg, &frame, lo, hi);
    let x0 = MARGIN_PX * 2.0 + w_px;
    legend(&mut svg, x0, scene, rows, &frame);
    svg.push_str("</svg>\n");
    svg
}

/// The model's upward-facing faces above its lowest point (roofs), light grey.
fn roofs(svg: &mut String, mesh: &Mesh, frame: &PlanFrame) {
    let ground = mesh.bounds().map_or(0.0, |(a, _)| a.z);
    let _ = write!(
        svg,
        r##"<g fill="#c9c9c9" stroke="#c9c9c9" stroke-width="0.6">"##
    );
    for t in &mesh.triangles {
        let v = t.map(|i| mesh.positions[i as usize]);
        let normal = (v[1] - v[0]).cross(v[2] - v[0]);
        let high = (v[0].z + v[1].z + v[2].z) / 3.0 > ground + 0.05;
        if normal.z > 0.05 * normal.length() && high {
            let pts: Vec<String> = v
                .iter()
                .map(|p| {
                    let (x, y) = frame.px(p.truncate());
                    format!("{x:.1},{y:.1}")
                })
                .collect();
            let _ = write!(svg, r#"<polygon points="{}"/>"#, pts.join(" "));
        }
    }
    svg.push_str("</g>\n");
}

/// An open space's cells (runs along each row of one colour), its outline and its name.
fn open_space(
    svg: &mut String,
    o: &crate::scene::planning::OpenSpace,
    figures: &super::OpenSpaceFigures,
    frame: &PlanFrame,
) {
    let hours = &figures.hours;
    let [du, dv] = o.grid.spacing;
    let sunny = |k: usize| hours[k] >= OPEN_SPACE_HOURS - 1e-9;
    let mut k = 0;
    let points = &o.grid.points;
    while k < points.len() {
        let mut end = k + 1;
        while end < points.len()
            && sunny(end) == sunny(k)
            && (points[end].y - points[k].y).abs() < 1e-9
            && (points[end].x - points[end - 1].x - du).abs() < 1e-6
        {
            end += 1;
        }
        let corner = DVec2::new(points[k].x - du / 2.0, points[k].y + dv / 2.0);
        let (x, y) = frame.px(corner);
        let _ = write!(
            svg,
            r#"<rect x="{x:.2}" y="{y:.2}" width="{:.2}" height="{:.2}" fill="{}"/>"#,
            (end - k) as f64 * du * frame.scale + 0.6,
            dv * frame.scale + 0.6,
            if sunny(k) { SUNNY } else { SHADY }
        );
        k = end;
    }
    for outline in &o.outlines {
        let pts: Vec<String> = outline
            .iter()
            .map(|p| {
                let (x, y) = frame.px(DVec2::from_array(*p));
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let _ = writeln!(
            svg,
            "\n<polygon points=\"{}\" fill=\"none\" stroke=\"#222\" stroke-width=\"1.5\"/>",
            pts.join(" ")
        );
    }
    let centre = points.iter().fold(DVec3::ZERO, |a, p| a + *p) / points.len().max(1) as f64;
    let (x, y) = frame.px(centre.truncate());
    let _ = writeln!(
        svg,
        r#"<text x="{x:.1}" y="{y:.1}" text-anchor="middle" font-weight="bold" stroke="white" stroke-width="3" paint-order="stroke">{}: {:.0} % ≥ {OPEN_SPACE_HOURS} h</text>"#,
        xml_escape(&o.entry.name),
        figures.sunlit_fraction_2h * 100.0
    );
}

/// Window `index`: a dot, an arrow along its normal and its number, coloured by its
/// verdicts (`stacked`: how many windows at the same spot came before it).
fn window(svg: &mut String, index: usize, r: &WindowRow, frame: &PlanFrame, stacked: usize) {
    let (x, y) = frame.px(r.window.position.truncate());
    let n = r.window.normal.truncate().normalize_or_zero();
    let (ax, ay) = (x + n.x * 22.0, y - n.y * 22.0);
    let ok = r.verdict.vsc && r.verdict.sunlight != Some(false) && r.verdict.en17037;
    let colour = if ok { PASS } else { FAIL };
    // The window's number beside its arrow (numbers of windows above one another side
    // by side); the legend lists them.
    let number = stacked_number(frame, ax, ay, stacked);
    let _ = writeln!(
        svg,
        r#"<line x1="{x:.1}" y1="{y:.1}" x2="{ax:.1}" y2="{ay:.1}" stroke="{colour}" stroke-width="2"/><circle cx="{x:.1}" cy="{y:.1}" r="4.5" fill="{colour}"/><text x="{:.1}" y="{:.1}" fill="{colour}" font-size="13" font-weight="bold" stroke="white" stroke-width="3" paint-order="stroke">{}</text>"#,
        number.0,
        number.1,
        index + 1
    );
}

/// Where a window's number goes: beside its arrow's tip, `stacked` places to the right.
fn stacked_number(frame: &PlanFrame, ax: f64, ay: f64, stacked: usize) -> (f64, f64) {
    let right_edge = MARGIN_PX + frame.width_m * frame.scale;
    let x = ax + 5.0 + 16.0 * stacked as f64;
    if x + 12.0 > right_edge {
        (ax - 18.0 - 16.0 * stacked as f64, ay + 16.0)
    } else {
        (x, ay + 5.0)
    }
}

/// A window's line in the legend: its number, name, VSC and the tests it fails.
fn window_line(index: usize, r: &WindowRow) -> String {
    let failing: Vec<&str> = [
        (!r.verdict.vsc, "VSC"),
        (r.verdict.sunlight == Some(false), "APSH/WPSH"),
        (!r.verdict.en17037, "EN 17037"),
    ]
    .iter()
    .filter(|(f, _)| *f)
    .map(|(_, name)| *name)
    .collect();
    let mut name: String = r.window.entry.name.chars().take(22).collect();
    if r.window.entry.name.chars().count() > 22 {
        name.push('…');
    }
    let verdict = if failing.is_empty() {
        String::new()
    } else {
        format!(", fails {}", failing.join(", "))
    };
    format!(
        "{}: {} · VSC {:.1} %{verdict}",
        index + 1,
        xml_escape(&name),
        r.now.vsc
    )
}

/// Metre ticks along the bottom and the left of the plan.
fn axes(svg: &mut String, frame: &PlanFrame, lo: DVec2, hi: DVec2) {
    let step = crate::photometry::plot::round_step((hi - lo).max_element(), 6.0);
    let mut v = (lo.x / step).ceil() * step;
    while v <= hi.x {
        let (x, y) = frame.px(DVec2::new(v, lo.y));
        let _ = write!(
            svg,
            r##"<line x1="{x:.1}" y1="{y:.1}" x2="{x:.1}" y2="{:.1}" stroke="#666"/><text x="{x:.1}" y="{:.1}" text-anchor="middle" font-size="11" fill="#444">{}</text>"##,
            y + 5.0,
            y + 18.0,
            v + 0.0
        );
        v += step;
    }
    let mut v = (lo.y / step).ceil() * step;
    while v <= hi.y {
        let (x, y) = frame.px(DVec2::new(lo.x, v));
        let _ = write!(
            svg,
            r##"<line x1="{x:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#666"/><text x="{:.1}" y="{:.1}" text-anchor="end" font-size="11" fill="#444">{}</text>"##,
            x - 5.0,
            x - 7.0,
            y + 4.0,
            v + 0.0
        );
        v += step;
    }
    svg.push('\n');
}

/// The legend, the north arrow and the scale bar, in the panel from `x0`.
fn legend(svg: &mut String, x0: f64, scene: &Scene, rows: &[WindowRow], frame: &PlanFrame) {
    let key = |svg: &mut String, y: f64, fill: &str, text: &str| {
        let _ = write!(
            svg,
            r##"<rect x="{x0}" y="{:.0}" width="18" height="14" fill="{fill}" stroke="#444" stroke-width="0.5"/><text x="{:.0}" y="{:.0}">{text}</text>"##,
            y - 11.0,
            x0 + 26.0,
            y
        );
    };
    let mut y = TITLE_PX + 14.0;
    let _ = write!(
        svg,
        r#"<text x="{x0}" y="{y}" font-weight="bold">Legend</text>"#
    );
    y += 24.0;
    if !scene.planning.open_spaces.is_empty() {
        key(
            svg,
            y,
            SUNNY,
            &format!("≥ {OPEN_SPACE_HOURS} h of sun on the day"),
        );
        y += 22.0;
        key(svg, y, SHADY, &format!("&lt; {OPEN_SPACE_HOURS} h of sun"));
        y += 22.0;
    }
    key(svg, y, "#c9c9c9", "buildings (roofs)");
    y += 26.0;
    let window_keys = [
        (PASS, "window: every test passes"),
        (FAIL, "window: a test fails"),
    ];
    let shown = if scene.planning.windows.is_empty() {
        0
    } else {
        2
    };
    for (colour, text) in &window_keys[..shown] {
        let _ = write!(
            svg,
            r#"<circle cx="{:.0}" cy="{:.0}" r="4.5" fill="{colour}"/><line x1="{:.0}" y1="{:.0}" x2="{:.0}" y2="{:.0}" stroke="{colour}" stroke-width="2"/><text x="{:.0}" y="{:.0}">{text}</text>"#,
            x0 + 4.0,
            y - 4.0,
            x0 + 4.0,
            y - 4.0,
            x0 + 18.0,
            y - 4.0,
            x0 + 26.0,
            y
        );
        y += 22.0;
    }
    if shown > 0 {
        let _ = write!(
            svg,
            r##"<text x="{x0}" y="{y}" fill="#444" font-size="11">arrow: the window's outward normal</text>"##
        );
        y += 8.0;
    }
    for (k, r) in rows.iter().enumerate() {
        y += 17.0;
        let ok = r.verdict.vsc && r.verdict.sunlight != Some(false) && r.verdict.en17037;
        let _ = write!(
            svg,
            r#"<text x="{x0}" y="{y}" font-size="11.5" fill="{}">{}</text>"#,
            if ok { PASS } else { FAIL },
            window_line(k, r)
        );
    }
    y += 50.0;
    let north = scene.site.as_ref().map_or(0.0, |s| s.north_offset_deg);
    north_arrow(svg, x0 + 40.0, y + 30.0, north);
    y += 100.0;
    scale_bar(svg, x0, y, frame.scale);
}

/// A north arrow centred at (`cx`, `cy`), turned `north_offset_deg` clockwise.
fn north_arrow(svg: &mut String, cx: f64, cy: f64, north_offset_deg: f64) {
    let _ = writeln!(
        svg,
        r##"<g transform="translate({cx:.1},{cy:.1}) rotate({north_offset_deg:.2})"><polygon points="0,-30 10,12 0,4 -10,12" fill="#222"/><text x="0" y="-36" text-anchor="middle" font-weight="bold">N</text></g>"##
    );
}

/// A scale bar of a round length about 150 pixels long, labelled in metres.
fn scale_bar(svg: &mut String, x0: f64, y: f64, px_per_m: f64) {
    let metres = crate::photometry::plot::round_step(150.0 / px_per_m, 1.0);
    let len = metres * px_per_m;
    let _ = writeln!(
        svg,
        r##"<rect x="{x0}" y="{y:.0}" width="{:.1}" height="6" fill="#222"/><rect x="{x0}" y="{y:.0}" width="{:.1}" height="6" fill="white" stroke="#222"/><rect x="{x0}" y="{y:.0}" width="{len:.1}" height="6" fill="none" stroke="#222"/><text x="{x0}" y="{:.0}">0</text><text x="{:.1}" y="{:.0}" text-anchor="end">{metres} m</text>"##,
        len,
        len / 2.0,
        y + 22.0,
        x0 + len,
        y + 22.0
    );
}
