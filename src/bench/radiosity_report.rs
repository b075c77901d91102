//! The report of `bench radiosity`: each configuration's time to 90 % and 99 %, its
//! ratio to the first row, where the shots' time went and the GPU's own clock.

use super::radiosity::{RadiosityBenchPlan, RadiosityBenchRow};
use super::report::{or_none, phase_list, BenchReport, Table};

/// A row's settings, for the lines under the table.
fn row_label(r: &RadiosityBenchRow) -> String {
    format!(
        "{}{}, {} raster / {} / {} / link error {} / cell power {}",
        r.visibility,
        if r.chunk_culling { "" } else { ", whole mesh" },
        r.raster,
        r.ambient,
        r.hierarchy,
        r.link_error,
        r.cell_power
    )
}

/// The time to 90 % over the first row's (`< x` when the first row gave up first: an upper
/// bound).
fn ratio_to_first(r: &RadiosityBenchRow, first: &RadiosityBenchRow) -> String {
    match (r.seconds_90, first.seconds_90) {
        (Some(a), Some(b)) if b > 0.0 => format!("{:.3}", a / b),
        (Some(a), None) if first.seconds > 0.0 => format!("< {:.3}", a / first.seconds),
        _ => "—".into(),
    }
}

/// The table's row of `r`.
fn cells(r: &RadiosityBenchRow, first: &RadiosityBenchRow) -> Vec<String> {
    let shots = |v: Option<usize>| v.map_or("—".to_string(), |v| v.to_string());
    let (link, cell) = if r.hierarchy == "none" {
        ("—".to_string(), "—".to_string())
    } else {
        (r.link_error.to_string(), r.cell_power.to_string())
    };
    vec![
        format!(
            "{}{}, {}",
            r.visibility,
            if r.chunk_culling { "" } else { ", whole mesh" },
            r.raster
        ),
        r.ambient.to_string(),
        r.hierarchy.to_string(),
        link,
        cell,
        r.elements.to_string(),
        r.patches.to_string(),
        format!("{} ({:.2} s)", r.shooters, r.shooters_seconds),
        r.maps.to_string(),
        format!("{:.0}", r.triangles_per_map),
        shots(r.shots_90),
        or_none(r.seconds_90, 2, "—"),
        shots(r.shots_99),
        or_none(r.seconds_99, 2, "—"),
        format!("{:.1}", r.ms_per_shot),
        ratio_to_first(r, first),
    ]
}

/// The report of `bench radiosity` of the scene at `scene` on the adapter `gpu`.
pub fn report(
    rows: &[RadiosityBenchRow],
    plan: &RadiosityBenchPlan,
    gpu: &str,
    scene: &std::path::Path,
) -> BenchReport {
    let level = plan.level;
    let mut r = BenchReport::new(
        serde_json::json!({ "rows": rows, "gpu": gpu, "scene": scene, "level": level }),
    );
    let Some(first) = rows.first() else {
        r.line(format!("{gpu}: {}: no configuration", scene.display()));
        return r;
    };
    r.line(format!(
        "{gpu}: {}, {} triangles, {:.1} texels/m, level {level}",
        scene.display(),
        first.triangles,
        first.texel_density,
    ));
    let mut t = Table::new(&[
        "visibility, raster",
        "ambient",
        "hierarchy",
        "link error",
        "cell power",
        "elements",
        "patches",
        "shooters (built in)",
        "maps drawn",
        "triangles per map",
        "shots to 90 %",
        "s to 90 %",
        "shots to 99 %",
        "s to 99 %",
        "ms/shot",
        "time to 90 % / first row",
    ]);
    for row in rows {
        t.row(cells(row, first));
    }
    r.table(t);
    r.line("Where the shots' time went (s; a phase that reads from the GPU waits there for the work before it):");
    for row in rows {
        let t = &row.phase_seconds;
        r.line(format!(
            "{}: {}; the rest {:.2}; cells from the plan cache {:.0} %",
            row_label(row),
            phase_list(t, 2),
            (row.seconds - t.total()).max(0.0),
            100.0 * row.plan_cache_hits,
        ));
    }
    r.line("The GPU's own clock (timestamps around each batch's passes; s):");
    for row in rows {
        r.line(match &row.gpu_pass_seconds {
            Some(g) => format!(
                "{}: visibility maps {:.3} ({:.1} µs a map), receive {:.3} ({:.1} µs a map, {:.0} receivers a map), in {} batches; GPU busy in them {:.0} % of the run",
                row_label(row),
                g.maps,
                1e6 * g.maps / row.maps.max(1) as f64,
                g.receive,
                1e6 * g.receive / row.maps.max(1) as f64,
                row.receivers_per_map,
                g.batches,
                100.0 * (g.maps + g.receive) / row.seconds.max(1e-9),
            ),
            None => format!("{}: this adapter has no timestamp queries", row_label(row)),
        });
    }
    for row in rows.iter().filter(|r| r.seconds_99.is_none()) {
        r.line(format!(
            "{}: {:.2} % after {} shots in {:.1} s (— : not reached within the limit of {} shots or the time limit)",
            row_label(row),
            100.0 * row.convergence,
            row.shots,
            row.seconds,
            plan.max_shots,
        ));
    }
    r
}
