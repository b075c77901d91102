//! `goniolight.sun_study`: the library's sun study (`goniolight profile`) from Python.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

use chrono::{NaiveDate, NaiveTime};
use numpy::{IntoPyArray, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError};
use pyo3::prelude::*;

use goniolight::io::outputs::Staging;
use goniolight::scene::UpAxis;
use goniolight::shadow::SilhouetteMethod;
use goniolight::study::shadow_profile::{HoursMetric, SURFACE_NONE};
use goniolight::study::sun_study::{ModelView, StudyFiles};
use goniolight::study::surface_set::FacadeOptions;
use goniolight::study::{ProfileError, StudyDay, SunStudy, SunStudyOptions};

use crate::{value_error, warn};

/// A study error as Python raises it: bad options and models are `ValueError`s (naming the
/// option), an interrupt `KeyboardInterrupt`.
fn study_error(e: ProfileError) -> PyErr {
    match e {
        ProfileError::Cancelled => PyKeyboardInterrupt::new_err(e.to_string()),
        ProfileError::Gpu(_) | ProfileError::Output(_) => PyRuntimeError::new_err(e.to_string()),
        e => value_error(e),
    }
}

fn parse<T>(what: &str, name: &str, known: &[(&str, T)]) -> PyResult<T>
where
    T: Copy,
{
    known
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, v)| *v)
        .ok_or_else(|| {
            let names: Vec<&str> = known.iter().map(|(n, _)| *n).collect();
            value_error(format!("{what} {name:?}: one of {}", names.join(", ")))
        })
}

fn date(s: &str) -> PyResult<NaiveDate> {
    NaiveDate::parse_from_str(s.trim(), "%Y-%m-%d")
        .map_err(|_| value_error(format!("dates: {s:?} is not a date YYYY-MM-DD")))
}

fn hhmm(field: &str, s: &str) -> PyResult<NaiveTime> {
    NaiveTime::parse_from_str(s.trim(), "%H:%M")
        .map_err(|_| value_error(format!("{field}: {s:?} is not a time HH:MM")))
}

/// A computed sun study: each date's profile, hours and summary.
#[pyclass(module = "goniolight._native", unsendable)]
pub struct NativeSunStudy {
    study: SunStudy,
    days: Vec<StudyDay>,
}

impl NativeSunStudy {
    fn day(&self, k: usize) -> PyResult<&StudyDay> {
        self.days.get(k).ok_or_else(|| {
            pyo3::exceptions::PyIndexError::new_err(format!(
                "date {k}: the study has {} date(s)",
                self.days.len()
            ))
        })
    }
}

#[pymethods]
impl NativeSunStudy {
    /// The dates, YYYY-MM-DD, in order.
    fn dates(&self) -> Vec<String> {
        self.days.iter().map(|d| d.spec.date.to_string()).collect()
    }

    /// Date `k`'s `study.json` as JSON text.
    fn study_json(&self, k: usize) -> PyResult<String> {
        serde_json::to_string(&self.study.summary(self.day(k)?)).map_err(value_error)
    }

    /// Date `k`'s hours per plan cell (rows from the north edge; NaN where the plan sees
    /// neither ground nor model).
    fn hours<'py>(&self, py: Python<'py>, k: usize) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let p = &self.day(k)?.profile;
        let hours = p.hours(self.study.options().metric);
        let n = p.resolution as usize;
        let rows: Vec<Vec<f64>> = (0..n)
            .map(|y| {
                (0..n)
                    .map(|x| match p.surface[y * n + x] {
                        SURFACE_NONE => f64::NAN,
                        _ => f64::from(hours[y * n + x]),
                    })
                    .collect()
            })
            .collect();
        Ok(numpy::PyArray2::from_vec2(py, &rows)?)
    }

    /// Date `k`'s rows of `hours.csv`: x, y (the model file's plan coordinates, metres),
    /// hours.
    fn cells<'py>(&self, py: Python<'py>, k: usize) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows = self.day(k)?.hours_cells(self.study.options().metric);
        let flat: Vec<f64> = rows.iter().flatten().copied().collect();
        flat.into_pyarray(py).reshape([rows.len(), 3])
    }

    /// Date `k`'s plan: (x, y) of its north-west corner in the model file's plan
    /// coordinates, its side (metres) and its pixels per side.
    fn plan(&self, k: usize) -> PyResult<((f64, f64), f64, u32)> {
        let p = &self.day(k)?.profile;
        let corner = p.center + p.origin + glam::DVec2::new(-0.5, 0.5) * p.extent_m;
        Ok(((corner.x, corner.y), p.extent_m, p.resolution))
    }

    /// What the study warned about (the model, each date).
    fn warnings(&self) -> Vec<String> {
        let mut all = self.study.warnings().to_vec();
        all.extend(self.days.iter().flat_map(|d| d.warnings()));
        all
    }

    /// Writes every file `goniolight profile --out OUT` writes into `out` (complete or
    /// none: through a folder beside it, moved into place at the end).
    #[pyo3(signature = (out, step_images=false))]
    fn write(&self, out: PathBuf, step_images: bool) -> PyResult<()> {
        let inputs = self.study.options().input_files();
        let place = |e: &dyn std::fmt::Display| value_error(format!("{}: {e}", out.display()));
        let staging = Staging::beside(&out, &inputs).map_err(|e| place(&e))?;
        let files = StudyFiles {
            step_images,
            gif: None,
        };
        self.study
            .write(&self.days, staging.dir(), &files)
            .map_err(study_error)?;
        staging
            .commit()
            .map(drop)
            .map_err(|e| place(&format!("{e:#}")))
    }
}

/// The model view as Python gives it: the eye, the target (each or none) and the size.
type ViewArgument = (Option<[f64; 3]>, Option<[f64; 3]>, (u32, u32));

/// Runs a sun study (`goniolight profile`): the model read, every date's shadow profile
/// on the GPU, the facades' and window points' hours. `progress(done, total)` after each
/// step; Ctrl-C stops it with KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (model, latitude, longitude, dates, start, end, step, tz=None, north_offset=0.0, extent=None, resolution=1024, up="y", silhouettes="hextree", metric="shadow", threshold=None, areas=None, casters=Vec::new(), facades=None, points=None, min_elevation=0.0, model_view=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn sun_study(
    py: Python<'_>,
    model: PathBuf,
    latitude: f64,
    longitude: f64,
    dates: Vec<String>,
    start: &str,
    end: &str,
    step: u32,
    tz: Option<String>,
    north_offset: f64,
    extent: Option<f64>,
    resolution: u32,
    up: &str,
    silhouettes: &str,
    metric: &str,
    threshold: Option<f64>,
    areas: Option<PathBuf>,
    casters: Vec<String>,
    facades: Option<(f64, f64)>,
    points: Option<PathBuf>,
    min_elevation: f64,
    model_view: Option<ViewArgument>,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<NativeSunStudy> {
    let dates = dates
        .iter()
        .map(|d| date(d))
        .collect::<PyResult<Vec<_>>>()?;
    let areas = match &areas {
        Some(p) => {
            goniolight::study::rasters::read_areas(p).map_err(|e| value_error(format!("{e:#}")))?
        }
        None => Vec::new(),
    };
    let points = match &points {
        Some(p) => {
            let text = goniolight::io::read_text_limited(p, goniolight::io::MAX_TEXT_BYTES)
                .map_err(|e| value_error(format!("{}: {e}", p.display())))?;
            goniolight::study::surfaces::parse_points(&text)
                .map_err(|e| value_error(format!("{}: {e}", p.display())))?
        }
        None => Vec::new(),
    };
    let options = SunStudyOptions {
        up: parse("up", up, &[("y", UpAxis::Y), ("z", UpAxis::Z)])?,
        casters,
        zone: tz,
        north_offset_deg: north_offset,
        extent_m: extent,
        resolution,
        silhouettes: parse(
            "silhouettes",
            silhouettes,
            &[
                ("hextree", SilhouetteMethod::Hextree),
                ("brute", SilhouetteMethod::Brute),
            ],
        )?,
        metric: parse(
            "metric",
            metric,
            &[("shadow", HoursMetric::Shadow), ("sun", HoursMetric::Sun)],
        )?,
        threshold_h: threshold,
        areas,
        facades: facades.map(|(cell_m, min_area_m2)| FacadeOptions {
            cell_m,
            min_area_m2,
        }),
        points,
        min_elevation_deg: min_elevation,
        model_view: model_view.map(|(from, at, size)| ModelView {
            from: from.map(glam::DVec3::from_array),
            at: at.map(glam::DVec3::from_array),
            size,
        }),
        ..SunStudyOptions::new(
            model,
            (latitude, longitude),
            dates,
            (hhmm("start", start)?, hhmm("end", end)?),
            step,
        )
    };
    let study = SunStudy::prepare(options).map_err(study_error)?;
    for w in study.warnings() {
        warn::<pyo3::exceptions::PyUserWarning>(py, w)?;
    }
    let gpu = goniolight::gpu::Gpu::shared().map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let cancel = AtomicBool::new(false);
    let mut failed: Option<PyErr> = None;
    let report = |done: usize, total: usize| {
        let called = py.check_signals().and_then(|()| {
            progress
                .as_ref()
                .map_or(Ok(()), |f| f.call1((done, total)).map(drop))
        });
        if let Err(err) = called {
            cancel.store(true, Ordering::SeqCst);
            failed.get_or_insert(err);
        }
    };
    let days = study.compute(&gpu, report, &cancel);
    let days = match (days, failed) {
        (_, Some(err)) => return Err(err),
        (days, None) => days.map_err(study_error)?,
    };
    for w in days.iter().flat_map(|d| d.warnings()) {
        warn::<pyo3::exceptions::PyUserWarning>(py, &w)?;
    }
    Ok(NativeSunStudy { study, days })
}
