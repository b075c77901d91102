//! `ldt report`: a one-page datasheet of a luminaire as one self-contained HTML file —
//! the summary, the polar and cartesian diagrams (inline SVG), the UGR table, the
//! luminance table and the file's warnings.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::Args;

use super::{info, write_each, CliError, Outputs};
use crate::io::write_atomic;
use crate::photometry::datasheet_plot::{Diagram, DiagramKind};
use crate::photometry::luminance::{luminance_table, ugr_grid};
use crate::photometry::ugr::{ugr_table, STANDARD_SHR};
use crate::photometry::{Interp, Luminaire};

/// Options of `ldt report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Luminaire files or directories.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Output .html (one input file).
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
        allowed: &["html", "htm"],
    };
    write_each(&args.files, outputs, |file, lum, target| {
        let html = report_html(file, lum, lamp_set).map_err(|e| super::about(file, e))?;
        write_atomic(target, html.as_bytes()).map_err(CliError::failure)
    })
}

/// Text made safe for HTML.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const STYLE: &str = "body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}\
h1{margin-bottom:0}.sub{color:#666;margin-top:.2em}\
table{border-collapse:collapse;margin:.5em 0 1.5em}td,th{padding:2px 8px;border-bottom:1px solid #ddd}\
th{background:#f3f3f3}.num td{text-align:right;font-variant-numeric:tabular-nums}\
.small{font-size:80%}svg{max-width:100%;height:auto}.diagrams{display:flex;flex-wrap:wrap}\
.diagrams>div{flex:1 1 480px}footer{color:#777;font-size:80%;margin-top:2em}";

/// The report of `lum` (read from `file`) as HTML.
pub(super) fn report_html(
    file: &Path,
    lum: &Luminaire,
    lamp_set: Option<usize>,
) -> Result<String, crate::photometry::PhotometryError> {
    let file_name = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = match lum.data.luminaire_name.trim() {
        "" => file_name.clone(),
        n => n.to_string(),
    };
    let mut h = String::new();
    let _ = write!(
        h,
        "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{} — datasheet</title><style>{STYLE}</style></head><body>",
        escape(&name)
    );
    let _ = write!(
        h,
        "<h1>{}</h1><p class=\"sub\">{} · {}</p>",
        escape(&name),
        escape(lum.data.company.trim()),
        escape(&file_name)
    );
    h.push_str("<table>");
    for (label, value) in info::summary_rows(lum, lamp_set)? {
        let _ = write!(
            h,
            "<tr><th>{}</th><td>{}</td></tr>",
            escape(&label),
            escape(&value)
        );
    }
    h.push_str("</table>");
    let diagram = Diagram {
        lum,
        file_name,
        planes: vec![0.0, 90.0],
        interp: Interp::CatmullRom,
    };
    h.push_str("<div class=\"diagrams\">");
    for kind in [DiagramKind::Polar, DiagramKind::Cartesian] {
        let svg = diagram
            .svg(kind)
            .map_err(crate::photometry::PhotometryError::Invalid)?;
        let _ = write!(h, "<div>{svg}</div>");
    }
    h.push_str("</div>");
    ugr_section(&mut h, lum, lamp_set);
    luminance_section(&mut h, lum, lamp_set);
    if !lum.warnings.is_empty() {
        h.push_str("<h2>Warnings</h2><ul>");
        for w in &lum.warnings {
            let _ = write!(h, "<li>{}</li>", escape(w));
        }
        h.push_str("</ul>");
    }
    let _ = write!(
        h,
        "<footer>goniolight {} · <code>ldt report</code> · intensities in cd/klm; UGR by CIE 117/190 at SHR {STANDARD_SHR}; luminance and UGR for lamp set {}</footer></body></html>",
        env!("CARGO_PKG_VERSION"),
        lamp_set.unwrap_or(1)
    );
    Ok(h)
}

fn ugr_section(h: &mut String, lum: &Luminaire, lamp_set: Option<usize>) {
    h.push_str("<h2>UGR table (CIE 117/190)</h2>");
    let t = match ugr_table(lum, lamp_set, STANDARD_SHR, Interp::Bilinear) {
        Ok(t) => t,
        Err(e) => {
            let _ = write!(h, "<p>No UGR table: {}.</p>", escape(&e.to_string()));
            return;
        }
    };
    let _ = write!(
        h,
        "<p class=\"small\">Spacing {} H, {:.0} lm; reflectances ceiling/walls/reference plane.</p>",
        t.shr, t.flux_lm
    );
    h.push_str("<table class=\"num small\"><tr><th rowspan=\"2\">X × Y</th><th colspan=\"5\">viewed crosswise</th><th colspan=\"5\">viewed endwise</th></tr><tr>");
    for _ in 0..2 {
        for r in &t.reflectances {
            let _ = write!(
                h,
                "<th>{:.0}/{:.0}/{:.0}</th>",
                r[0] * 100.0,
                r[1] * 100.0,
                r[2] * 100.0
            );
        }
    }
    h.push_str("</tr>");
    for (i, room) in t.rooms.iter().enumerate() {
        let _ = write!(h, "<tr><td>{}H × {}H</td>", room[0], room[1]);
        for v in t.crosswise[i].iter().chain(&t.endwise[i]) {
            let cell = match v {
                Some(v) if *v < 10.0 => "&lt;10".to_string(),
                Some(v) => format!("{v:.1}"),
                None => "—".to_string(),
            };
            let _ = write!(h, "<td>{cell}</td>");
        }
        h.push_str("</tr>");
    }
    h.push_str("</table>");
}

fn luminance_section(h: &mut String, lum: &Luminaire, lamp_set: Option<usize>) {
    h.push_str("<h2>Luminance (cd/m²)</h2>");
    let (cs, _) = ugr_grid();
    let gammas: Vec<f64> = (9..18).map(|k| 5.0 * k as f64).collect();
    let t = match luminance_table(lum, &cs, &gammas, lamp_set, Interp::Bilinear) {
        Ok(t) => t,
        Err(e) => {
            let _ = write!(h, "<p>No luminance table: {}.</p>", escape(&e.to_string()));
            return;
        }
    };
    h.push_str("<table class=\"num small\"><tr><th>γ \\ C</th>");
    for c in &t.c_angles {
        let _ = write!(h, "<th>{c}°</th>");
    }
    h.push_str("</tr>");
    for (gi, g) in t.gamma_angles.iter().enumerate() {
        let _ = write!(h, "<tr><td>{g}°</td>");
        for row in &t.cd_m2 {
            let _ = write!(h, "<td>{:.0}</td>", row[gi]);
        }
        h.push_str("</tr>");
    }
    h.push_str("</table>");
}
