//! A luminaire's one-page datasheet (`ldt report`): the summary, the polar, cartesian and
//! isocandela diagrams, the UGR table, the luminance table and the file's warnings.
//! [`sheet`] gathers them once as text and SVG diagrams ([`Sheet`]); [`html`] and
//! [`svg::svg`] lay them out as one self-contained page.

pub mod summary;
pub mod svg;

use std::fmt::Write as _;

use crate::io::xml_escape as escape;
use crate::photometry::datasheet_plot::{Diagram, DiagramKind};
use crate::photometry::luminance::{lamp_set_flux, luminance_table, ugr_grid};
use crate::photometry::ugr::{ugr_table, STANDARD_SHR, VARIATION_ROOM};
use crate::photometry::{Interp, Luminaire, PhotometryError};

/// One table of the sheet, as text (each renderer escapes it).
pub struct Table {
    /// An optional first header row of (label, columns spanned), after the row labels.
    pub groups: Vec<(String, usize)>,
    /// The header row (the first cell heads the row labels).
    pub header: Vec<String>,
    /// The rows: a label, then the values.
    pub rows: Vec<Vec<String>>,
}

/// A titled part of the sheet: a note and a table, or why there is none.
pub struct Section {
    /// The heading.
    pub heading: String,
    /// A line under the heading.
    pub note: Option<String>,
    /// The table, or the reason it is missing.
    pub table: Result<Table, String>,
}

/// Everything a datasheet shows, as text and SVG diagrams, ready for HTML or SVG.
pub struct Sheet {
    /// The luminaire's name (the file's when it has none).
    pub name: String,
    /// Company and file name.
    pub subtitle: String,
    /// The summary rows (label, value).
    pub summary: Vec<(String, String)>,
    /// The polar, cartesian and isocandela diagrams, as SVG documents.
    pub diagrams: Vec<String>,
    /// The UGR and luminance tables.
    pub sections: Vec<Section>,
    /// The file's warnings.
    pub warnings: Vec<String>,
    /// The last line: tool, version, units, conditions.
    pub footer: String,
}

const STYLE: &str = "body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}\
h1{margin-bottom:0}.sub{color:#666;margin-top:.2em}\
table{border-collapse:collapse;margin:.5em 0 1.5em}td,th{padding:2px 8px;border-bottom:1px solid #ddd}\
th{background:#f3f3f3}.num td{text-align:right;font-variant-numeric:tabular-nums}\
.small{font-size:80%}svg{max-width:100%;height:auto}.diagrams{display:flex;flex-wrap:wrap}\
.diagrams>div{flex:1 1 480px}footer{color:#777;font-size:80%;margin-top:2em}";

/// The sheet of `lum`, read from a file named `file_name`, for lamp set `lamp_set`
/// (1-based; `None`: the first).
pub fn sheet(
    file_name: &str,
    lum: &Luminaire,
    lamp_set: Option<usize>,
) -> Result<Sheet, PhotometryError> {
    let file_name = file_name.to_string();
    let name = match lum.data.luminaire_name.trim() {
        "" => file_name.clone(),
        n => n.to_string(),
    };
    let subtitle = format!("{} · {}", lum.data.company.trim(), file_name);
    let summary = summary::summary_rows(lum, lamp_set)?;
    let diagram = Diagram {
        lum,
        file_name,
        planes: vec![0.0, 90.0],
        interp: Interp::CatmullRom,
        lamp_flux_lm: Some(lamp_set_flux(lum, lamp_set)?),
    };
    let diagrams = [
        DiagramKind::Polar,
        DiagramKind::Cartesian,
        DiagramKind::Isocandela,
    ]
    .into_iter()
    .map(|kind| diagram.svg(kind))
    .collect::<Result<Vec<_>, _>>()?;
    Ok(Sheet {
        name,
        subtitle,
        summary,
        diagrams,
        sections: ugr_sections(lum, lamp_set)
            .into_iter()
            .chain([luminance_section(lum, lamp_set)])
            .collect(),
        warnings: lum.warnings.clone(),
        footer: format!(
            "goniolight {} · ldt report · intensities in cd/klm; UGR by CIE 117/190 at SHR {STANDARD_SHR}; luminance and UGR for lamp set {}",
            env!("CARGO_PKG_VERSION"),
            lamp_set.unwrap_or(1)
        ),
    })
}

/// The sheet as one self-contained HTML page.
pub fn html(sheet: &Sheet) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{} — datasheet</title><style>{STYLE}</style></head><body>",
        escape(&sheet.name)
    );
    let _ = write!(
        h,
        "<h1>{}</h1><p class=\"sub\">{}</p>",
        escape(&sheet.name),
        escape(&sheet.subtitle)
    );
    h.push_str("<table>");
    for (label, value) in &sheet.summary {
        let _ = write!(
            h,
            "<tr><th>{}</th><td>{}</td></tr>",
            escape(label),
            escape(value)
        );
    }
    h.push_str("</table><div class=\"diagrams\">");
    for svg in &sheet.diagrams {
        let _ = write!(h, "<div>{svg}</div>");
    }
    h.push_str("</div>");
    for section in &sheet.sections {
        let _ = write!(h, "<h2>{}</h2>", escape(&section.heading));
        if let Some(note) = &section.note {
            let _ = write!(h, "<p class=\"small\">{}</p>", escape(note));
        }
        match &section.table {
            Ok(t) => html_table(&mut h, t),
            Err(why) => {
                let _ = write!(h, "<p>{}</p>", escape(why));
            }
        }
    }
    if !sheet.warnings.is_empty() {
        h.push_str("<h2>Warnings</h2><ul>");
        for w in &sheet.warnings {
            let _ = write!(h, "<li>{}</li>", escape(w));
        }
        h.push_str("</ul>");
    }
    let _ = write!(
        h,
        "<footer>{}</footer></body></html>",
        escape(&sheet.footer)
    );
    h
}

fn html_table(h: &mut String, t: &Table) {
    h.push_str("<table class=\"num small\">");
    let grouped = !t.groups.is_empty();
    if grouped {
        let _ = write!(h, "<tr><th rowspan=\"2\">{}</th>", escape(&t.header[0]));
        for (label, span) in &t.groups {
            let _ = write!(h, "<th colspan=\"{span}\">{}</th>", escape(label));
        }
        h.push_str("</tr>");
    }
    h.push_str("<tr>");
    for cell in &t.header[usize::from(grouped)..] {
        let _ = write!(h, "<th>{}</th>", escape(cell));
    }
    h.push_str("</tr>");
    for row in &t.rows {
        h.push_str("<tr>");
        for cell in row {
            let _ = write!(h, "<td>{}</td>", escape(cell));
        }
        h.push_str("</tr>");
    }
    h.push_str("</table>");
}

/// The UGR table and the variation of the observer position (or why there is none).
fn ugr_sections(lum: &Luminaire, lamp_set: Option<usize>) -> Vec<Section> {
    let heading = "UGR table (CIE 117/190)".to_string();
    let t = match ugr_table(lum, lamp_set, STANDARD_SHR, Interp::Bilinear) {
        Ok(t) => t,
        Err(e) => {
            return vec![Section {
                heading,
                note: None,
                table: Err(format!("No UGR table: {e}.")),
            }]
        }
    };
    let rho: Vec<String> = t
        .reflectances
        .iter()
        .map(|r| {
            format!(
                "{:.0}/{:.0}/{:.0}",
                r[0] * 100.0,
                r[1] * 100.0,
                r[2] * 100.0
            )
        })
        .collect();
    let header = std::iter::once("X × Y".to_string())
        .chain(rho.iter().cloned())
        .chain(rho.iter().cloned())
        .collect();
    let rows = t
        .rooms
        .iter()
        .enumerate()
        .map(|(i, room)| {
            let cells = t.crosswise[i].iter().chain(&t.endwise[i]).map(|v| match v {
                Some(v) if *v < 10.0 => "<10".to_string(),
                Some(v) => format!("{v:.1}"),
                None => "—".to_string(),
            });
            std::iter::once(format!("{}H × {}H", room[0], room[1]))
                .chain(cells)
                .collect()
        })
        .collect();
    let range = |v: Option<[f64; 2]>| match v {
        Some([up, down]) => format!("+{up:.1} / −{down:.1}"),
        None => "—".to_string(),
    };
    let variation = Table {
        groups: Vec::new(),
        header: ["spacing", "viewed crosswise", "viewed endwise"]
            .map(String::from)
            .to_vec(),
        rows: t
            .observer_variation
            .iter()
            .map(|v| {
                vec![
                    format!("S = {:.1}H", v.spacing),
                    range(v.crosswise),
                    range(v.endwise),
                ]
            })
            .collect(),
    };
    vec![
        Section {
            heading,
            note: Some(format!(
                "Spacing {} H, {:.0} lm; reflectances ceiling/walls/reference plane.",
                t.shr, t.flux_lm
            )),
            table: Ok(Table {
                groups: vec![
                    ("viewed crosswise".to_string(), rho.len()),
                    ("viewed endwise".to_string(), rho.len()),
                ],
                header,
                rows,
            }),
        },
        Section {
            heading: "Variation of the observer position".to_string(),
            note: Some(format!(
                "Room {}H × {}H; the eye moved over one spacing S across and ahead; change of UGR from the standard position.",
                VARIATION_ROOM[0], VARIATION_ROOM[1]
            )),
            table: Ok(variation),
        },
    ]
}

fn luminance_section(lum: &Luminaire, lamp_set: Option<usize>) -> Section {
    let heading = "Luminance (cd/m²)".to_string();
    let (cs, _) = ugr_grid();
    let gammas: Vec<f64> = (9..18).map(|k| 5.0 * k as f64).collect();
    let table = luminance_table(lum, &cs, &gammas, lamp_set, Interp::Bilinear)
        .map(|t| Table {
            groups: Vec::new(),
            header: std::iter::once("γ \\ C".to_string())
                .chain(t.c_angles.iter().map(|c| format!("{c}°")))
                .collect(),
            rows: t
                .gamma_angles
                .iter()
                .enumerate()
                .map(|(gi, g)| {
                    std::iter::once(format!("{g}°"))
                        .chain(t.cd_m2.iter().map(|row| format!("{:.0}", row[gi])))
                        .collect()
                })
                .collect(),
        })
        .map_err(|e| format!("No luminance table: {e}."));
    Section {
        heading,
        note: None,
        table,
    }
}

/// The sheet laid out as a self-contained SVG page (`svg`) or HTML page.
pub fn page(sheet: &Sheet, svg: bool) -> String {
    if svg {
        svg::svg(sheet)
    } else {
        html(sheet)
    }
}
