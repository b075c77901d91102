//! The sun-path diagram of a site, stereographic (as architects read them: the sky seen
//! from below with the zenith in the centre, north up and east to the right; altitude
//! circles every 10°, azimuth spokes every 30°) or cylindrical (azimuth across from north
//! through east, south and west back to north, elevation up, both linear; grid lines every
//! 30° and 10°); the path of the 21st of every month (the solstices and equinoxes drawn
//! heavier); hour lines (the sun at each whole hour of standard time through the year, half
//! an analemma); and the study's own suns as dots carrying their time and position
//! (`data-time`, `data-azimuth`, `data-elevation`).

use std::fmt::Write as _;

use chrono::{DateTime, FixedOffset, NaiveDate, NaiveTime, TimeZone, Utc};

use super::mask::ObstructionMask;
use crate::io::xml_escape;
use crate::sun::{self, Site, SunOptions, Zone};

/// Centre of the diagram's horizon circle in the SVG, pixels.
pub const CENTRE: (f64, f64) = (420.0, 460.0);
/// Radius of the horizon circle, pixels.
pub const RADIUS: f64 = 340.0;

/// The cylindrical chart's plot rectangle in the SVG: left, top, width, height, pixels
/// (azimuth 0°–360° across, elevation 90°–0° down).
pub const CHART: (f64, f64, f64, f64) = (70.0, 150.0, 720.0, 580.0);

/// How a diagram draws the sky.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Projection {
    /// Seen from below, zenith in the centre: [`project`].
    #[default]
    Stereographic,
    /// Azimuth across, elevation up, both linear, in [`CHART`].
    Cylindrical,
}

impl Projection {
    /// The SVG position of a sun at `azimuth_deg` (clockwise from north) and
    /// `elevation_deg`.
    pub fn project(self, azimuth_deg: f64, elevation_deg: f64) -> (f64, f64) {
        match self {
            Projection::Stereographic => project(azimuth_deg, elevation_deg),
            Projection::Cylindrical => {
                let (left, top, width, height) = CHART;
                (
                    left + width * azimuth_deg.rem_euclid(360.0) / 360.0,
                    top + height * (1.0 - elevation_deg / 90.0),
                )
            }
        }
    }

    /// The inverse of [`Projection::project`]: (azimuth, elevation), degrees.
    pub fn unproject(self, x: f64, y: f64) -> (f64, f64) {
        match self {
            Projection::Stereographic => unproject(x, y),
            Projection::Cylindrical => {
                let (left, top, width, height) = CHART;
                (
                    360.0 * (x - left) / width,
                    90.0 * (1.0 - (y - top) / height),
                )
            }
        }
    }

    /// The sky's lines through `(azimuth, elevation)` points as SVG polylines: a
    /// cylindrical chart breaks a line where it runs past north, off one edge and in at the
    /// other.
    fn polylines(self, sky: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
        let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        let mut last_azimuth: Option<f64> = None;
        for &(az, el) in sky {
            let az = az.rem_euclid(360.0);
            let wraps = last_azimuth.is_some_and(|a| (az - a).abs() > 180.0);
            if wraps && self == Projection::Cylindrical {
                pieces.push(Vec::new());
            }
            pieces
                .last_mut()
                .expect("one piece")
                .push(self.project(az, el));
            last_azimuth = Some(az);
        }
        pieces.into_iter().filter(|p| p.len() > 1).collect()
    }
}

/// The SVG position of a sun at `azimuth_deg` (clockwise from north) and `elevation_deg`
/// in the stereographic diagram: r = R · tan(zenith / 2), so the horizon lies on the
/// circle of radius R.
pub fn project(azimuth_deg: f64, elevation_deg: f64) -> (f64, f64) {
    let zenith = (90.0 - elevation_deg).to_radians();
    let r = RADIUS * (zenith / 2.0).tan();
    let a = azimuth_deg.to_radians();
    (CENTRE.0 + r * a.sin(), CENTRE.1 - r * a.cos())
}

/// The inverse of [`project`]: (azimuth, elevation), degrees.
pub fn unproject(x: f64, y: f64) -> (f64, f64) {
    let (dx, dy) = (x - CENTRE.0, CENTRE.1 - y);
    let r = dx.hypot(dy);
    let zenith = 2.0 * (r / RADIUS).atan();
    let azimuth = dx.atan2(dy).to_degrees().rem_euclid(360.0);
    (azimuth, 90.0 - zenith.to_degrees())
}

/// A site's sun-path diagram.
#[derive(Debug, Clone)]
pub struct SunPathDiagram {
    /// The site.
    pub site: Site,
    /// Its zone (the hour lines use its standard time: the smaller of its January and July
    /// offsets).
    pub zone: Zone,
    /// The year of the date arcs.
    pub year: i32,
    /// Atmosphere and ΔT (the north offset is ignored: the diagram is in true north).
    pub sun: SunOptions,
    /// The title.
    pub title: String,
    /// The study's suns: local time, azimuth and elevation (degrees, true north).
    pub marked: Vec<(DateTime<FixedOffset>, f64, f64)>,
    /// The sky a point does not see, drawn grey under the paths; its suns hidden from the
    /// point are drawn hollow.
    pub mask: Option<ObstructionMask>,
    /// How the sky is drawn.
    pub projection: Projection,
}

impl SunPathDiagram {
    fn position(&self, utc: DateTime<Utc>) -> Result<(f64, f64), crate::sun::SunError> {
        let opts = SunOptions {
            north_offset_deg: 0.0,
            ..self.sun
        };
        let p = sun::position(&self.site, utc, &opts)?;
        Ok((p.azimuth_deg, p.elevation_deg))
    }

    /// The zone's standard offset, seconds east.
    fn standard_offset(&self) -> i32 {
        let at = |m| {
            Utc.with_ymd_and_hms(self.year, m, 1, 12, 0, 0)
                .single()
                .map_or(0, |t| self.zone.offset_seconds(t))
        };
        at(1).min(at(7))
    }

    /// The day's path above the horizon in pieces (SVG points), every 5 minutes of UTC.
    fn day_path(&self, date: NaiveDate) -> Result<Vec<Vec<(f64, f64)>>, crate::sun::SunError> {
        let start = date.and_time(NaiveTime::MIN).and_utc()
            - chrono::Duration::seconds(self.standard_offset() as i64);
        let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for k in 0..=288 {
            let (az, el) = self.position(start + chrono::Duration::minutes(5 * k))?;
            if el > 0.0 {
                pieces.last_mut().expect("one piece").push((az, el));
            } else if !pieces.last().expect("one piece").is_empty() {
                pieces.push(Vec::new());
            }
        }
        Ok(pieces
            .iter()
            .flat_map(|sky| self.projection.polylines(sky))
            .collect())
    }

    /// The diagram as SVG.
    pub fn svg(&self) -> Result<String, crate::sun::SunError> {
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="1080" height="860" viewBox="0 0 1080 860" font-family="sans-serif">
<rect width="100%" height="100%" fill="white"/>
<text x="20" y="34" font-size="20">{}</text>
<text x="20" y="58" font-size="14">{:.4}° {}, {:.4}° {} — {}</text>"#,
            xml_escape(&self.title),
            self.site.latitude.abs(),
            if self.site.latitude >= 0.0 { "N" } else { "S" },
            self.site.longitude.abs(),
            if self.site.longitude >= 0.0 { "E" } else { "W" },
            match self.projection {
                Projection::Stereographic =>
                    "stereographic, seen from below: zenith in the centre, north up, east right",
                Projection::Cylindrical =>
                    "cylindrical: azimuth across (north at both edges, south in the middle), elevation up",
            }
        );
        if let Some(mask) = &self.mask {
            s.push_str(&mask.svg(|az, el| self.projection.project(az, el)));
        }
        match self.projection {
            Projection::Stereographic => stereographic_grid(&mut s),
            Projection::Cylindrical => cylindrical_grid(&mut s),
        }
        self.paths(&mut s)?;
        self.legend(&mut s);
        Ok(s)
    }

    /// The date arcs, the hour lines and the study's suns.
    fn paths(&self, s: &mut String) -> Result<(), crate::sun::SunError> {
        // Date arcs: the 21st of every month.
        for month in 1..=12 {
            let Some(date) = NaiveDate::from_ymd_opt(self.year, month, 21) else {
                continue;
            };
            let heavy = matches!(month, 3 | 6 | 12);
            for piece in self.day_path(date)? {
                let _ = writeln!(
                    s,
                    r#"<polyline class="date" data-date="{date}" points="{}" fill="none" stroke="{}" stroke-width="{}"/>"#,
                    points(&piece),
                    if heavy {
                        "rgb(200,120,0)"
                    } else {
                        "rgb(230,180,110)"
                    },
                    if heavy { 2.0 } else { 1.0 }
                );
            }
            if heavy {
                if let Some(&(x, y)) = self
                    .day_path(date)?
                    .first()
                    .and_then(|p| p.get(p.len() / 2))
                {
                    let _ = writeln!(
                        s,
                        r#"<text x="{:.1}" y="{:.1}" font-size="12" fill="rgb(160,90,0)">{}</text>"#,
                        x + 4.0,
                        y - 4.0,
                        date.format("%d %b")
                    );
                }
            }
        }
        // Hour lines: each whole hour of standard time on the 21st of Dec … Jun and on
        // the 6th between, so the line is smooth.
        let offset = self.standard_offset();
        let mut days: Vec<NaiveDate> = Vec::new();
        for (y, m) in [(self.year - 1, 12)]
            .into_iter()
            .chain((1..=6).map(|m| (self.year, m)))
        {
            for d in [6, 21] {
                if let Some(date) = NaiveDate::from_ymd_opt(y, m, d) {
                    if date >= NaiveDate::from_ymd_opt(self.year - 1, 12, 21).expect("date")
                        && date <= NaiveDate::from_ymd_opt(self.year, 6, 21).expect("date")
                    {
                        days.push(date);
                    }
                }
            }
        }
        for hour in 0..24 {
            let mut sky = Vec::new();
            for d in &days {
                let utc = d.and_hms_opt(hour, 0, 0).expect("hour").and_utc()
                    - chrono::Duration::seconds(offset as i64);
                let (az, el) = self.position(utc)?;
                if el > 0.0 {
                    sky.push((az, el));
                }
            }
            let pieces = self.projection.polylines(&sky);
            for pts in &pieces {
                let _ = writeln!(
                    s,
                    r#"<polyline class="hour" data-hour="{hour}" points="{}" fill="none" stroke="rgb(90,120,200)" stroke-width="1"/>"#,
                    points(pts)
                );
            }
            if let Some(pts) = pieces.first() {
                let (x, y) = pts[pts.len() / 2];
                // Below the line's middle, but above a cylindrical chart's axis labels.
                let (_, horizon) = self.projection.project(0.0, 0.0);
                let label_y = match self.projection {
                    Projection::Stereographic => y + 12.0,
                    Projection::Cylindrical => (y + 12.0).min(horizon - 4.0),
                };
                let _ = writeln!(
                    s,
                    r#"<text x="{:.1}" y="{label_y:.1}" font-size="12" fill="rgb(50,80,170)">{hour}h</text>"#,
                    x + 3.0,
                );
            }
        }
        // The study's suns (hollow where the mask hides them).
        for (t, az, el) in &self.marked {
            let (x, y) = self.projection.project(*az, *el);
            let hidden = self.mask.as_ref().is_some_and(|m| m.hides(*az, *el));
            let _ = writeln!(
                s,
                r#"<circle class="sun" cx="{x:.3}" cy="{y:.3}" r="5" fill="{}" stroke="{}" stroke-width="{}" data-time="{}" data-azimuth="{az:.4}" data-elevation="{el:.4}" data-hidden="{hidden}"><title>{} az {az:.1}° el {el:.1}°</title></circle>"#,
                if hidden { "white" } else { "rgb(230,40,30)" },
                if hidden { "rgb(230,40,30)" } else { "black" },
                if hidden { 2 } else { 1 },
                t.to_rfc3339_opts(chrono::SecondsFormat::Secs, true),
                t.format("%Y-%m-%d %H:%M")
            );
        }
        Ok(())
    }

    /// The legend and notes beside the diagram.
    fn legend(&self, s: &mut String) {
        let offset = self.standard_offset();
        // The legend beside the diagram.
        let x0 = 840.0;
        let hours = offset / 60;
        let legend = [
            (
                "rgb(200,120,0)",
                "21 Mar / Jun / Dec (heavy), 21st of other months".to_string(),
            ),
            (
                "rgb(90,120,200)",
                format!(
                    "hour lines, standard time UTC{}{:02}:{:02}",
                    if hours < 0 { '-' } else { '+' },
                    hours.abs() / 60,
                    hours.abs() % 60
                ),
            ),
            ("rgb(230,40,30)", "the study's suns".to_string()),
        ];
        let mask_legend = self.mask.as_ref().map(|m| {
            (
                "rgb(170,170,170)",
                format!(
                    "sky hidden from point \"{}\" by the model ({:.0} % of the sky); its suns drawn hollow are in shade",
                    m.name,
                    100.0 * m.hidden_sky_fraction()
                ),
            )
        });
        let legend: Vec<_> = legend.into_iter().chain(mask_legend).collect();
        let mut bottom = 0.0f64;
        for (k, (colour, text)) in legend.iter().enumerate() {
            let y = 110.0 + 70.0 * k as f64;
            let _ = writeln!(
                s,
                r#"<rect x="{x0}" y="{}" width="26" height="8" fill="{colour}"/>"#,
                y - 8.0
            );
            for (j, line) in crate::io::wrap_words(text, 24).iter().enumerate() {
                let ty = y + 16.0 + 16.0 * j as f64;
                bottom = bottom.max(ty);
                let _ = writeln!(
                    s,
                    r#"<text x="{}" y="{}" font-size="13">{}</text>"#,
                    x0,
                    ty,
                    xml_escape(line)
                );
            }
        }
        let notes = (bottom + 32.0).max(360.0);
        let (elevations, azimuths) = match self.projection {
            Projection::Stereographic => {
                ("circles: altitude every 10°", "spokes: azimuth every 30°")
            }
            Projection::Cylindrical => (
                "level lines: elevation every 10°",
                "upright lines: azimuth every 30°",
            ),
        };
        let _ = writeln!(
            s,
            r#"<text x="{x0}" y="{notes}" font-size="12" fill="rgb(90,90,90)">{elevations}</text>
<text x="{x0}" y="{}" font-size="12" fill="rgb(90,90,90)">{azimuths}</text>
<text x="{x0}" y="{}" font-size="12" fill="rgb(90,90,90)">year {}</text>
</svg>"#,
            notes + 16.0,
            notes + 32.0,
            self.year
        );
    }
}

/// The stereographic frame: altitude circles (the horizon heavy) and azimuth spokes.
fn stereographic_grid(s: &mut String) {
    let (cx, cy) = CENTRE;
    for el in (0..90).step_by(10) {
        let (_, y) = project(0.0, el as f64);
        let r = cy - y;
        let stroke = if el == 0 {
            "black\" stroke-width=\"1.5"
        } else {
            "rgb(200,200,200)"
        };
        let id = if el == 0 { r#" id="horizon""# } else { "" };
        let _ = writeln!(
            s,
            r#"<circle{id} cx="{cx}" cy="{cy}" r="{r:.2}" fill="none" stroke="{stroke}"/>"#
        );
        if el > 0 {
            let _ = writeln!(
                s,
                r#"<text x="{:.1}" y="{:.1}" font-size="11" fill="rgb(120,120,120)">{el}°</text>"#,
                cx + 3.0,
                y - 3.0
            );
        }
    }
    for az in (0..360).step_by(30) {
        let (x, y) = project(az as f64, 0.0);
        let _ = writeln!(
            s,
            r#"<line x1="{cx}" y1="{cy}" x2="{x:.1}" y2="{y:.1}" stroke="rgb(200,200,200)"/>"#
        );
        let label = match az {
            0 => "N".to_string(),
            90 => "E".to_string(),
            180 => "S".to_string(),
            270 => "W".to_string(),
            a => format!("{a}°"),
        };
        let a = (az as f64).to_radians();
        let (lx, ly) = (
            cx + (RADIUS + 22.0) * a.sin(),
            cy - (RADIUS + 22.0) * a.cos(),
        );
        let _ = writeln!(
            s,
            r#"<text x="{lx:.1}" y="{:.1}" font-size="14" text-anchor="middle">{label}</text>"#,
            ly + 5.0
        );
    }
}

/// The cylindrical frame: the chart's rectangle (`id="frame"`, with the azimuth and
/// elevation its edges stand for), elevation lines every 10° (the horizon heavy) and
/// azimuth lines every 30°, labelled on the left and below.
fn cylindrical_grid(s: &mut String) {
    let (left, top, width, height) = CHART;
    for el in (0..=90).step_by(10) {
        let (_, y) = Projection::Cylindrical.project(0.0, el as f64);
        let (stroke, id) = if el == 0 {
            ("black\" stroke-width=\"1.5", r#" id="horizon""#)
        } else {
            ("rgb(200,200,200)", "")
        };
        let _ = writeln!(
            s,
            r#"<line{id} x1="{left}" y1="{y:.2}" x2="{}" y2="{y:.2}" stroke="{stroke}"/>
<text x="{}" y="{:.1}" font-size="11" fill="rgb(120,120,120)" text-anchor="end">{el}°</text>"#,
            left + width,
            left - 6.0,
            y + 4.0
        );
    }
    for az in (0..=360).step_by(30) {
        // 360° is north again, at the right edge.
        let x = left + width * az as f64 / 360.0;
        let label = match az {
            0 | 360 => "N".to_string(),
            90 => "E".to_string(),
            180 => "S".to_string(),
            270 => "W".to_string(),
            a => format!("{a}°"),
        };
        let _ = writeln!(
            s,
            r#"<line x1="{x:.1}" y1="{top}" x2="{x:.1}" y2="{}" stroke="rgb(200,200,200)"/>
<text x="{x:.1}" y="{}" font-size="14" text-anchor="middle">{label}</text>"#,
            top + height,
            top + height + 22.0
        );
    }
    let _ = writeln!(
        s,
        r#"<rect id="frame" x="{left}" y="{top}" width="{width}" height="{height}" fill="none" stroke="black" data-azimuth="0-360" data-elevation="0-90"/>
<text x="{}" y="{}" font-size="13" text-anchor="middle">azimuth, degrees clockwise from true north</text>
<text x="{}" y="{}" font-size="13" text-anchor="middle" transform="rotate(-90 {} {})">elevation, degrees</text>"#,
        left + width / 2.0,
        top + height + 46.0,
        left - 44.0,
        top + height / 2.0,
        left - 44.0,
        top + height / 2.0
    );
}

fn points(p: &[(f64, f64)]) -> String {
    p.iter()
        .map(|(x, y)| format!("{x:.2},{y:.2}"))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::{Projection, CHART};

    #[test]
    fn projection_round_trips() {
        for projection in [Projection::Stereographic, Projection::Cylindrical] {
            for (az, el) in [(0.0, 0.0), (90.0, 45.0), (200.0, 10.0), (359.0, 80.0)] {
                let (x, y) = projection.project(az, el);
                let (a, e) = projection.unproject(x, y);
                assert!(
                    (a - az).abs() < 1e-9 && (e - el).abs() < 1e-9,
                    "{projection:?} {az} {el}: {a} {e}"
                );
            }
        }
        // The horizon on the circle, east to the right.
        let (x, y) = super::project(90.0, 0.0);
        assert!(
            (x - super::CENTRE.0 - super::RADIUS).abs() < 1e-9
                && (y - super::CENTRE.1).abs() < 1e-9
        );
    }

    #[test]
    fn a_cylindrical_line_breaks_where_it_passes_north() {
        // A midsummer night's sun in the far north: west, north, east.
        let sky = [
            (300.0, 5.0),
            (330.0, 3.0),
            (355.0, 2.0),
            (5.0, 2.0),
            (30.0, 3.0),
        ];
        let pieces = Projection::Cylindrical.polylines(&sky);
        assert_eq!(pieces.len(), 2);
        let (left, _, width, _) = CHART;
        assert!(pieces[0].iter().all(|p| p.0 > left + width / 2.0));
        assert!(pieces[1].iter().all(|p| p.0 < left + width / 2.0));
        // The stereographic diagram draws it as one line.
        assert_eq!(Projection::Stereographic.polylines(&sky).len(), 1);
    }
}
