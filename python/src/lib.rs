//! The native part of the `goniolight` Python package: thin wrappers around the library;
//! the Python layer (`goniolight/__init__.py`) turns JSON into dicts and documents the API.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use goniolight::lighting::SurfacePoint;
use goniolight::photometry::check::{self, LeaveOut};
use goniolight::photometry::ies::write_ies;
use goniolight::photometry::{Interp, Luminaire};
use goniolight::shadow::ShadowTechnique;

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

fn parse_interp(name: &str) -> PyResult<Interp> {
    Interp::ALL
        .into_iter()
        .find(|i| i.name() == name)
        .ok_or_else(|| {
            let names: Vec<&str> = Interp::ALL.iter().map(|i| i.name()).collect();
            value_error(format!("interp {name:?}: expected one of {names:?}"))
        })
}

/// A luminaire file (EULUMDAT or IES) read into goniolight's distribution.
#[pyclass(module = "goniolight._native", frozen)]
struct NativeLuminaire {
    lum: Luminaire,
    path: PathBuf,
}

#[pymethods]
impl NativeLuminaire {
    /// `ldt info --json` of the file, as a JSON string.
    fn info_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.lum.info_json()).map_err(value_error)
    }

    /// The full-circle table as stored: C angles × γ angles, cd/klm (what `ldt info`
    /// lists and `ldt convert` writes).
    fn intensities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self.lum.data.expanded().into_iter().map(|p| p.1).collect();
        PyArray2::from_vec2(py, &rows).map_err(value_error)
    }

    /// Samples at (C, γ) pairs (degrees) with `interp`; cd/klm.
    fn sample<'py>(
        &self,
        py: Python<'py>,
        c_deg: PyReadonlyArray1<'py, f64>,
        gamma_deg: PyReadonlyArray1<'py, f64>,
        interp: &str,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let method = parse_interp(interp)?;
        let c = c_deg.as_slice()?;
        let g = gamma_deg.as_slice()?;
        if c.len() != g.len() {
            return Err(value_error("c and gamma must have the same length"));
        }
        if let Some(bad) = g.iter().find(|v| !(0.0..=180.0).contains(*v)) {
            return Err(value_error(format!("γ {bad} outside [0°, 180°]")));
        }
        if c.iter().any(|v| !v.is_finite()) {
            return Err(value_error("C angles must be finite"));
        }
        let dist = &self.lum.distribution;
        let out: Vec<f64> = c
            .iter()
            .zip(g)
            .map(|(&c, &g)| dist.sample(c, g, method))
            .collect();
        Ok(out.into_pyarray(py))
    }

    /// The interpolation check as `ldt check --json` gives it (a JSON string): leave-out
    /// (`leave_out` = gamma|c|both), downsampling (`downsample` = (ΔC, Δγ)) or against a
    /// finer measurement (`reference`, a path).
    #[pyo3(signature = (leave_out="both", downsample=None, reference=None))]
    fn check_json(
        &self,
        leave_out: &str,
        downsample: Option<(f64, f64)>,
        reference: Option<PathBuf>,
    ) -> PyResult<String> {
        let dist = &self.lum.distribution;
        let report = if let Some(fine) = reference {
            let fine = Luminaire::load(&fine).map_err(value_error)?;
            check::against_reference(dist, &fine.distribution)
        } else if let Some((dc, dg)) = downsample {
            check::downsample(dist, dc, dg)
        } else {
            let which = match leave_out {
                "gamma" => LeaveOut::Gamma,
                "c" => LeaveOut::C,
                "both" => LeaveOut::Both,
                other => {
                    return Err(value_error(format!(
                        "leave_out {other:?}: gamma, c or both"
                    )))
                }
            };
            check::leave_out(dist, which)
        }
        .map_err(value_error)?;
        serde_json::to_string(&report).map_err(value_error)
    }

    /// The file's data as EULUMDAT (`"ldt"`) or IES LM-63-2002 (`"ies"`) text.
    fn to_text(&self, format: &str) -> PyResult<String> {
        match format {
            "ldt" => Ok(self.lum.data.to_ldt_string()),
            "ies" => Ok(write_ies(&self.lum.data, self.lum.source_label())),
            other => Err(value_error(format!("format {other:?}: ldt or ies"))),
        }
    }

    /// Warnings collected while reading.
    fn warnings(&self) -> Vec<String> {
        self.lum.warnings.clone()
    }

    /// The path it was read from.
    fn path(&self) -> PathBuf {
        self.path.clone()
    }
}

/// Reads an `.ldt` or `.ies` file.
#[pyfunction]
fn read(path: PathBuf) -> PyResult<NativeLuminaire> {
    let lum = Luminaire::load(&path).map_err(value_error)?;
    Ok(NativeLuminaire { lum, path })
}

/// The sun's position at instants (ISO 8601 with an offset, or local with `tz`): a JSON
/// list of objects with the keys of `sun --json`.
#[pyfunction]
#[pyo3(signature = (lat, lon, times, tz=None, elevation=0.0, delta_t=None, pressure=1013.25, temperature=12.0, north_offset=0.0))]
#[allow(clippy::too_many_arguments)]
fn sun_positions_json(
    lat: f64,
    lon: f64,
    times: Vec<String>,
    tz: Option<String>,
    elevation: f64,
    delta_t: Option<f64>,
    pressure: f64,
    temperature: f64,
    north_offset: f64,
) -> PyResult<String> {
    use goniolight::sun::{self, Site, SunOptions, Zone};
    let site = Site::new(lat, lon, elevation).map_err(value_error)?;
    let zone = tz
        .as_deref()
        .map(Zone::parse)
        .transpose()
        .map_err(value_error)?;
    let opts = SunOptions {
        delta_t,
        pressure_hpa: pressure,
        temperature_c: temperature,
        north_offset_deg: north_offset,
    };
    let mut out = Vec::with_capacity(times.len());
    for t in &times {
        let (utc, _) = sun::parse_time(t, zone.as_ref()).map_err(value_error)?;
        let p = sun::position(&site, utc, &opts).map_err(value_error)?;
        out.push(p.to_json());
    }
    serde_json::to_string(&out).map_err(value_error)
}

/// Direct illuminance (lux) at points (an N × 6 array of x y z nx ny nz) in a scene file,
/// on the GPU unless `cpu`; returns the lux and whether the GPU computed them.
#[pyfunction]
#[pyo3(signature = (scene, points, interp="catmull-rom", shadows=None, cpu=false))]
fn illuminance<'py>(
    py: Python<'py>,
    scene: PathBuf,
    points: PyReadonlyArray2<'py, f64>,
    interp: &str,
    shadows: Option<&str>,
    cpu: bool,
) -> PyResult<(Bound<'py, PyArray1<f64>>, bool)> {
    use goniolight::gpu::{Gpu, GpuError};
    use goniolight::render::illuminance::scene_illuminance;
    let method = parse_interp(interp)?;
    let view = points.as_array();
    if view.ncols() != 6 {
        return Err(value_error(format!(
            "points must be an N × 6 array (x y z nx ny nz), got {} columns",
            view.ncols()
        )));
    }
    let mut pts = Vec::with_capacity(view.nrows());
    for (i, row) in view.rows().into_iter().enumerate() {
        let v: Vec<f64> = row.iter().copied().collect();
        if v.iter().any(|x| !x.is_finite()) {
            return Err(value_error(format!("points[{i}] is not finite")));
        }
        let normal = glam_dvec3(v[3], v[4], v[5]);
        if normal.length() < 1e-12 {
            return Err(value_error(format!(
                "points[{i}]: the normal has zero length"
            )));
        }
        pts.push(SurfacePoint {
            position: glam_dvec3(v[0], v[1], v[2]),
            normal,
        });
    }
    let scene = goniolight::scene::Scene::load(&scene).map_err(value_error)?;
    let technique = match shadows {
        None => scene.display.shadows.unwrap_or_default(),
        Some("none") => ShadowTechnique::None,
        Some("paraboloid") => ShadowTechnique::Paraboloid,
        Some("volumes") => ShadowTechnique::Volumes,
        Some(other) => {
            return Err(value_error(format!(
                "shadows {other:?}: none, paraboloid or volumes"
            )))
        }
    };
    let gpu = if cpu {
        None
    } else {
        match Gpu::shared() {
            Ok(gpu) => Some(gpu),
            Err(GpuError::NoAdapter(why)) => {
                let warn = format!("no GPU adapter{why}: computing on the CPU");
                PyErr::warn(
                    py,
                    &py.get_type::<pyo3::exceptions::PyRuntimeWarning>(),
                    &std::ffi::CString::new(warn).unwrap_or_default(),
                    1,
                )?;
                None
            }
            Err(e) => return Err(PyRuntimeError::new_err(e.to_string())),
        }
    };
    let on_gpu = gpu.is_some();
    let lux = scene_illuminance(gpu.as_ref(), &scene, &pts, method, technique)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok((lux.into_pyarray(py), on_gpu))
}

fn glam_dvec3(x: f64, y: f64, z: f64) -> glam::DVec3 {
    glam::DVec3::new(x, y, z)
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeLuminaire>()?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(sun_positions_json, m)?)?;
    m.add_function(wrap_pyfunction!(illuminance, m)?)?;
    Ok(())
}
