//! `ldt ugr`: the UGR table of one or many luminaire files.

use std::path::{Path, PathBuf};

use super::{tables_per_file, CliError};
use crate::photometry::ugr::{ugr_table, UgrTable, VARIATION_ROOM};
use crate::photometry::Interp;

/// Prints the UGR table of each file, as text (a datasheet's layout) or JSON.
pub(super) fn run(
    files: &[PathBuf],
    as_json: bool,
    shr: f64,
    lamp_set: Option<usize>,
) -> Result<(), CliError> {
    tables_per_file(
        files,
        as_json,
        |lum| ugr_table(lum, lamp_set, shr, Interp::Bilinear),
        print_table,
    )
}

fn print_table(path: &Path, name: &str, t: &UgrTable) {
    println!(
        "{} — {name}: UGR table (CIE 117/190), SHR {} H, {:.0} lm",
        path.display(),
        t.shr,
        t.flux_lm
    );
    let refl = |k: usize| -> String {
        let r = t.reflectances[k];
        format!(
            "{:.0}/{:.0}/{:.0}",
            r[0] * 100.0,
            r[1] * 100.0,
            r[2] * 100.0
        )
    };
    println!("{:>9}  {:<45}  viewed endwise", "", "viewed crosswise");
    let mut head = format!("{:>9}  ", "ρ c/w/p");
    for _ in 0..2 {
        for k in 0..5 {
            head.push_str(&format!("{:>9}", refl(k)));
        }
        head.push_str("  ");
    }
    println!("{}", head.trim_end());
    println!("{:>9}", "X × Y");
    for (i, room) in t.rooms.iter().enumerate() {
        let mut line = format!("{:>9}  ", format!("{}H×{}H", room[0], room[1]));
        for row in [&t.crosswise[i], &t.endwise[i]] {
            for v in row {
                match v {
                    Some(v) if *v < 10.0 => line.push_str(&format!("{:>9}", "<10")),
                    Some(v) => line.push_str(&format!("{v:>9.1}")),
                    None => line.push_str(&format!("{:>9}", "—")),
                }
            }
            line.push_str("  ");
        }
        println!("{}", line.trim_end());
    }
    println!(
        "variation of the observer position (room {}H×{}H, the eye moved over one spacing across and ahead):",
        VARIATION_ROOM[0], VARIATION_ROOM[1]
    );
    let range = |v: Option<[f64; 2]>| match v {
        Some([up, down]) => format!("+{up:.1} / −{down:.1}"),
        None => "—".to_string(),
    };
    for v in &t.observer_variation {
        println!(
            "{:>9}  crosswise {:<14} endwise {}",
            format!("S = {:.1}H", v.spacing),
            range(v.crosswise),
            range(v.endwise)
        );
    }
}
