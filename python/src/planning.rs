//! `goniolight sunlight` from Python: the planning tests of a scene's windows and open
//! spaces.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use chrono::NaiveDate;
use goniolight::planning::output::sunlight_json as document;
use goniolight::planning::{
    add_areas_file, add_points_file, assess, PlanningError, SunlightOptions, SunlightRequest,
};
use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;

use crate::scene::SceneArg;
use crate::warn;

/// A library error as Python's: bad input is ValueError naming the keyword or the scene
/// key.
fn planning_error(e: PlanningError) -> PyErr {
    match e {
        PlanningError::Cancelled => PyKeyboardInterrupt::new_err("interrupted"),
        PlanningError::Input { key, message } => PyValueError::new_err(format!("{key}: {message}")),
    }
}

/// A date keyword (`YYYY-MM-DD`).
fn date(keyword: &str, text: Option<&str>) -> PyResult<Option<NaiveDate>> {
    text.map(|t| {
        NaiveDate::parse_from_str(t, "%Y-%m-%d")
            .map_err(|e| PyValueError::new_err(format!("{keyword} {t:?}: {e} (give YYYY-MM-DD)")))
    })
    .transpose()
}

/// `goniolight sunlight` of a scene: the `sunlight.json` document as JSON text (the scene
/// and baseline named as given) and each open space's hours of sun per point.
#[pyfunction]
#[pyo3(signature = (scene, baseline=None, weather=None, date=None, en17037_date=None, year=None, step=None, min_elevation=None, points=None, areas=None, area_spacing=None))]
#[allow(clippy::too_many_arguments)]
pub fn sunlight_json(
    py: Python<'_>,
    scene: SceneArg<'_>,
    baseline: Option<SceneArg<'_>>,
    weather: Option<PathBuf>,
    date: Option<&str>,
    en17037_date: Option<&str>,
    year: Option<i32>,
    step: Option<f64>,
    min_elevation: Option<f64>,
    points: Option<PathBuf>,
    areas: Option<PathBuf>,
    area_spacing: Option<f64>,
) -> PyResult<(String, Vec<Vec<f64>>)> {
    let label = scene.path().display().to_string();
    let baseline_label = baseline.as_ref().map(|b| b.path().display().to_string());
    let request = SunlightRequest {
        weather: weather.as_deref(),
        date: self::date("date", date)?,
        en17037_date: self::date("en17037_date", en17037_date)?,
        year,
        step_min: step,
        min_elevation_deg: min_elevation,
    };
    let (options, warnings): (SunlightOptions, _) =
        SunlightOptions::from_request(&request).map_err(planning_error)?;
    let mut loaded = scene.scene(py)?;
    if let Some(points) = &points {
        add_points_file(&mut loaded, points).map_err(planning_error)?;
    }
    if let Some(areas) = &areas {
        let spacing =
            area_spacing.unwrap_or(goniolight::scene::planning::DEFAULT_OPEN_SPACE_SPACING);
        add_areas_file(&mut loaded, areas, spacing).map_err(planning_error)?;
    }
    let before = baseline.map(|b| b.scene(py)).transpose()?;
    let cancel = AtomicBool::new(false);
    let assessment = assess(&loaded, before.as_ref(), &options, &cancel).map_err(planning_error)?;
    for w in warnings.iter().chain(&assessment.warnings) {
        warn::<pyo3::exceptions::PyUserWarning>(py, w)?;
    }
    let rows = goniolight::planning::output::window_rows(&loaded, &assessment);
    let json = document(
        &loaded,
        &assessment,
        &rows,
        &label,
        baseline_label.as_deref(),
    );
    let text = serde_json::to_string(&json).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let hours = assessment
        .proposed
        .open_spaces
        .into_iter()
        .map(|o| o.hours)
        .collect();
    Ok((text, hours))
}
