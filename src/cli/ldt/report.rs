//! `ldt report`: a one-page datasheet of a luminaire as one self-contained HTML or SVG
//! file — the summary, the polar, cartesian and isocandela diagrams, the UGR table, the
//! luminance table and the file's warnings. [`sheet`] gathers them once; [`html`] and
//! [`super::report_svg::svg`] lay them out ([`super::sheet`] is what they share).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::Args;

use super::sheet::{escape, Section, Sheet, Table};
use super::{info, write_each, CliError, Outputs};
use crate::io::write_atomic;
use crate::photometry::datasheet_plot::{Diagram, DiagramKind};
use crate::photometry::luminance::{lamp_set_flux, luminance_table, ugr_grid};
use crate::photometry::ugr::{ugr_table, STANDARD_SHR, VARIATION_ROOM};
use crate::photometry::{Interp, Luminaire};

/// Options of `ldt report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Luminaire files or directories.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Output .html or .svg (one input file; the extension picks the format).
    #[arg(long, required_unless_present = "out_dir", conflicts_with = "out_dir")]
    pub out: Option<PathBuf>,
    /// Write one `NAME.html` per input here.
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// The lamp set the sheet's fluxes, UGR and luminance are for (1-based; default the
    /// first, as Relux and DIALux read EULUMDAT's sets as alternatives).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..))]
    pub lamp_set: u16,
}

/// Writes the report of each file.
pub(super) fn run(args: &ReportArgs) -> Result<(), CliError> {
    let lamp_set = Some(usize::from(args.lamp_set));
    let outputs = Outputs {
        out: args.out.as_deref(),
        out_dir: args.out_dir.as_deref(),
        ext: "html",
        allowed: &["html", "htm", "svg"],
    };
    write_each(&args.files, outputs, |file, lum, target| {
        let sheet = sheet(file, lum, lamp_set).map_err(|e| super::about(file, e))?;
        let svg = target
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        let text = if svg {
            super::report_svg::svg(&sheet)
        } else {
            html(&sheet)
        };
        write_atomic(target, text.as_bytes()).map_err(CliError::failure)
    })
}

const STYLE: &str = "body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}\
h1{margin-bottom:0}.sub{color:#666;margin-top:.2em}\
table{border-collapse:collapse;margin:.5em 0 1.5em}td,th{padding:2px 8px;border-bottom:1px solid #ddd}\
th{background:#f3f3f3}.num td{text-align:right;font-variant-numeric:tabular-nums}\
.small{font-size:80%}svg{max-width:100%;height:auto}.diagrams{display:flex;flex-wrap:wrap}\
.diagrams>div{flex:1 1 480px}footer{color:#777;font-size:80%;margin-top:2em}";

/// The sheet of `lum` (read from `file`).
pub(super) fn sheet(
    file: &Path,
    lum: &Luminaire,
    lamp_set: Option<usize>,
) -> Result<Sheet, crate::photometry::PhotometryError> {
    let file_name = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = match lum.data.luminaire_name.trim() {
        "" => file_name.clone(),
        n => n.to_string(),
    };
    let subtitle = format!("{} · {}", lum.data.company.trim(), file_name);
    let summary = info::summary_rows(lum, lamp_set)?;
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
    .collect::<Result<Vec<_>, _>>()
    .map_err(crate::photometry::PhotometryError::Invalid)?;
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
pub(super) fn html(sheet: &Sheet) -> String {
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
