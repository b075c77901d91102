//! The report of `bench radiosity-view`: each drive's seconds until the image in view is
//! within the tolerance, its speed-up over global, where the time went and, over several
//! rounds, the least, median and greatest of each.

use super::radiosity_view::{Spread, ViewBench, ViewBenchRow};
use super::report::{phase_list, BenchReport, Table};

/// The report of `result` on the scene at `scene` (`rooms` in a row) on the adapter `gpu`.
pub fn report(result: &ViewBench, gpu: &str, scene: &std::path::Path, rooms: usize) -> BenchReport {
    let mut r =
        BenchReport::new(serde_json::json!({ "bench": result, "gpu": gpu, "scene": scene }));
    r.line(format!(
        "{gpu}: {}{}, {} elements ({} seen), reference: global to {:.2} % in {:.1} s",
        scene.display(),
        if rooms > 1 {
            format!(" × {rooms} rooms")
        } else {
            String::new()
        },
        result.elements,
        result.elements_seen,
        100.0 * result.reference_convergence,
        result.reference_seconds
    ));
    let tol = 100.0 * result.tolerance;
    let mut t = Table::new(&[
        "drive",
        "view weights s",
        "importance s",
        &format!("to {tol:.0} % shown s"),
        &format!("to {tol:.0} % shot s"),
        "shots",
        "× global (shot)",
        "maps",
        "maps reused",
    ]);
    let fmt = |v: Option<f64>| v.map_or("not reached".to_string(), |s| format!("{s:.2}"));
    let base = result.rows.first().and_then(|r| r.seconds_shot);
    for row in &result.rows {
        let ratio = match (base, row.seconds_shot) {
            (Some(b), Some(s)) if s > 0.0 => format!("{:.2}×", b / s),
            _ => "–".to_string(),
        };
        t.row(vec![
            row.drive.to_string(),
            format!("{:.3}", row.view_weights_seconds),
            format!("{:.2}", row.importance_seconds),
            fmt(row.seconds_shown),
            fmt(row.seconds_shot),
            row.shots_shot.map_or("–".to_string(), |s| s.to_string()),
            ratio,
            row.maps.to_string(),
            row.maps_reused.to_string(),
        ]);
    }
    r.table(t);
    r.line(format!(
        "Where the shots' time went until the shot light was within {tol:.0} % (s):"
    ));
    for row in &result.rows {
        r.line(format!(
            "{}: view weights {:.3}, importance {:.3} (its solver's setup {:.3}); {}",
            row.drive,
            row.view_weights_seconds,
            row.importance_seconds,
            row.importance_setup_seconds,
            phase_list(&row.phase_seconds, 3)
        ));
    }
    r.line("The GPU's own clock until then (timestamps around each batch's passes; s):");
    for row in &result.rows {
        r.line(match &row.gpu_pass_seconds {
            Some(g) => format!(
                "{}: visibility maps {:.3}, receive {:.3} ({:.0} receivers a map), in {} batches",
                row.drive, g.maps, g.receive, row.receivers_per_map, g.batches
            ),
            None => format!("{}: this adapter has no timestamp queries", row.drive),
        });
    }
    if result.rounds.len() > 1 {
        rounds(&mut r, result, tol);
    }
    r
}

/// The rounds of `--repeat`: each drive's time to `tol` % (shot light, and the image as
/// shown) and speed-up over global, least, median and greatest, then round by round.
fn rounds(r: &mut BenchReport, result: &ViewBench, tol: f64) {
    let spread = |s: Option<Spread>, unit: &str| {
        s.map_or("–".to_string(), |s| {
            format!(
                "{:.2}{unit} ({:.2}{unit} – {:.2}{unit})",
                s.median, s.min, s.max
            )
        })
    };
    let n = result.rounds.len();
    r.line(format!(
        "Over {n} rounds (the drives in turn, round after round; one reference):"
    ));
    let mut t = Table::new(&[
        "drive",
        &format!("rounds within {tol:.0} % (shot / shown)"),
        &format!("to {tol:.0} % shot s: median (least – most)"),
        "× global (shot)",
        &format!("to {tol:.0} % shown s"),
        "× global (shown)",
    ]);
    for d in &result.summary {
        t.row(vec![
            d.drive.to_string(),
            format!("{} / {} of {n}", d.rounds_reached, d.rounds_reached_shown),
            spread(d.seconds_shot, ""),
            spread(d.speedup, "×"),
            spread(d.seconds_shown, ""),
            spread(d.speedup_shown, "×"),
        ]);
    }
    r.table(t);
    let s = |s: Option<f64>| s.map_or("–".into(), |s| format!("{s:.2} s"));
    let line = |rows: &[ViewBenchRow]| {
        rows.iter()
            .map(|d| {
                format!(
                    "{} {} (shown {})",
                    d.drive,
                    s(d.seconds_shot),
                    s(d.seconds_shown)
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    for (k, rows) in result.rounds.iter().enumerate() {
        r.line(format!("round {}: {}", k + 1, line(rows)));
    }
}
