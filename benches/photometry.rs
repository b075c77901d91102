//! Photometry benchmarks.
//!
//! - `parse`: every bundled `.ldt` file, goniolight vs the `eulumdat` crate 0.3.0 (the
//!   strongest Rust peer, MIT/Apache), side by side, bytes per second.
//! - `sample`: ns per sample for each interpolation on one core (10 000 random directions
//!   on a 15° × 5° asymmetric file and on the 1° × 1° lab file).

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use goniolight::photometry::{Eulumdat, Interp, Luminaire};
use std::path::{Path, PathBuf};

fn ldt_files() -> Vec<(String, Vec<u8>)> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "ldt") {
                out.push(p);
            }
        }
    }
    let mut paths = Vec::new();
    walk(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("luminaires"),
        &mut paths,
    );
    paths.sort();
    paths
        .into_iter()
        .map(|p| (p.display().to_string(), std::fs::read(&p).unwrap()))
        .collect()
}

fn parse(c: &mut Criterion) {
    let files = ldt_files();
    let texts: Vec<String> = files
        .iter()
        .map(|(_, b)| String::from_utf8(b.clone()).unwrap())
        .collect();
    // Both parsers must accept every file for the comparison to be fair.
    for (t, (name, _)) in texts.iter().zip(&files) {
        eulumdat::Eulumdat::parse(t)
            .unwrap_or_else(|e| panic!("eulumdat 0.3.0 rejects {name}: {e}"));
    }
    let bytes: usize = files.iter().map(|f| f.1.len()).sum();
    let mut g = c.benchmark_group("parse_all_ldt");
    g.throughput(Throughput::Bytes(bytes as u64));
    g.bench_function("goniolight", |b| {
        b.iter(|| {
            for (name, data) in &files {
                black_box(Eulumdat::parse(name, black_box(data)).unwrap());
            }
        })
    });
    g.bench_function("goniolight_with_distribution", |b| {
        b.iter(|| {
            for (name, data) in &files {
                black_box(Luminaire::from_bytes(name, black_box(data)).unwrap());
            }
        })
    });
    g.bench_function("eulumdat_0_3_0", |b| {
        b.iter(|| {
            for t in &texts {
                black_box(eulumdat::Eulumdat::parse(black_box(t)).unwrap());
            }
        })
    });
    g.finish();
}

fn sample(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("luminaires");
    let mut rng = goniolight::geometry::generate::XorShift::new(0x9E37_79B9_7F4A_7C15);
    let mut next = move || rng.next_f64();
    let queries: Vec<(f64, f64)> = (0..10_000)
        .map(|_| (next() * 360.0, next() * 180.0))
        .collect();
    for (label, rel) in [
        ("15x5_isym3", "eulumdat-plot/sample_01_isym3.ldt"),
        ("1x1_lab", "eulumdat-analysis/sample_18.ldt"),
    ] {
        let lum = Luminaire::load(&root.join(rel)).unwrap();
        let mut g = c.benchmark_group(format!("sample_{label}"));
        g.throughput(Throughput::Elements(queries.len() as u64));
        for interp in Interp::ALL {
            g.bench_function(interp.name(), |b| {
                b.iter(|| {
                    let mut acc = 0.0;
                    for &(cc, gg) in &queries {
                        acc += lum.distribution.sample(cc, gg, interp);
                    }
                    black_box(acc)
                })
            });
        }
        g.finish();
    }
}

criterion_group!(benches, parse, sample);
criterion_main!(benches);
