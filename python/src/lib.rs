//! The native part of the `goniolight` Python package: thin wrappers around the library;
//! the Python layer (`goniolight/__init__.py`) turns JSON into dicts and documents the API.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use goniolight::lighting::SurfacePoint;
use goniolight::photometry::check::{self, LeaveOut};
use goniolight::photometry::convert;
use goniolight::photometry::{Interp, Luminaire};
use goniolight::radiosity::bake::BakeChoice;
use goniolight::radiosity::session::{Options, SessionError, Solution};
use goniolight::shadow::ShadowTechnique;

mod planning;
mod render;
mod scene;
mod sun_study;

use scene::SceneArg;

pub(crate) fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Raises `message` as a Python warning of `category` (`warnings.warn`).
pub(crate) fn warn<T: pyo3::PyTypeInfo>(py: Python<'_>, message: &str) -> PyResult<()> {
    let text = std::ffi::CString::new(message.replace('\0', " ")).unwrap_or_default();
    PyErr::warn(py, &py.get_type::<T>(), &text, 1)
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

/// A lamp set number as the command line takes it (1-based).
/// The output format an extension names.
fn output_format(ext: &str) -> PyResult<convert::OutputFormat> {
    convert::OutputFormat::of_ext(ext).ok_or_else(|| {
        value_error(format!(
            "format {ext:?}: ldt, ies, xml (TM-33-23) or json (ATLA S001)"
        ))
    })
}

fn lamp_set_arg(lamp_set: Option<usize>) -> PyResult<Option<usize>> {
    match lamp_set {
        Some(0) => Err(value_error("lamp_set 0: lamp sets count from 1")),
        other => Ok(other),
    }
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

    /// `ldt ugr --json` of the file (CIE 117/190 UGR table at spacing `shr` × H, for lamp
    /// set `lamp_set`, 1-based), as a JSON string.
    #[pyo3(signature = (shr=0.25, lamp_set=None))]
    fn ugr_table_json(&self, shr: f64, lamp_set: Option<usize>) -> PyResult<String> {
        let set = lamp_set_arg(lamp_set)?;
        let t = goniolight::photometry::ugr::ugr_table(&self.lum, set, shr, Interp::Bilinear)
            .map_err(value_error)?;
        serde_json::to_string(&t).map_err(value_error)
    }

    /// `ldt luminance --json` of the file (cd/m² of the luminous area, C 0–345° every 15°,
    /// γ from `gamma_from` every 5° below 90°), as a JSON string.
    #[pyo3(signature = (lamp_set=None, gamma_from=65, interp="bilinear"))]
    fn luminance_table_json(
        &self,
        lamp_set: Option<usize>,
        gamma_from: u16,
        interp: &str,
    ) -> PyResult<String> {
        use goniolight::photometry::luminance::{gamma_rows, luminance_table, ugr_grid};
        let set = lamp_set_arg(lamp_set)?;
        let gammas = gamma_rows(gamma_from).ok_or_else(|| {
            value_error(format!(
                "gamma_from {gamma_from}: give a multiple of 5 below 90 (the rows are 5° apart)"
            ))
        })?;
        let (c_angles, _) = ugr_grid();
        let t = luminance_table(&self.lum, &c_angles, &gammas, set, parse_interp(interp)?)
            .map_err(value_error)?;
        serde_json::to_string(&t).map_err(value_error)
    }

    /// `ldt report`'s one-page datasheet of the file for lamp set `lamp_set` (1-based):
    /// a self-contained SVG page (`svg`) or HTML page.
    #[pyo3(signature = (svg=false, lamp_set=1))]
    fn datasheet_page(&self, svg: bool, lamp_set: usize) -> PyResult<String> {
        use goniolight::photometry::datasheet;
        let set = lamp_set_arg(Some(lamp_set))?;
        let file_name = self
            .path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let sheet = datasheet::sheet(&file_name, &self.lum, set).map_err(value_error)?;
        Ok(datasheet::page(&sheet, svg))
    }

    /// The file's data as EULUMDAT (`"ldt"`, every number exact), IES LM-63-2002
    /// (`"ies"`), TM-33-23 XML (`"xml"`) or ATLA S001 JSON (`"json"`) text.
    fn to_text(&self, format: &str) -> PyResult<String> {
        let to = output_format(format)?;
        convert::convert(&self.lum, to, true)
            .map(|c| c.text)
            .map_err(value_error)
    }

    /// What converting to `format` (`"ldt"`, `"ies"`, `"xml"`, `"json"`) loses, in words.
    fn losses(&self, format: &str) -> PyResult<Vec<String>> {
        Ok(convert::losses(&self.lum, output_format(format)?))
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
/// on the GPU unless `cpu`, with the daylight of the scene's `[sky]` (or of `sky`, a model
/// name, at `time`, a local time at its `[site]`, as `illuminance --sky --time`); returns
/// the lux and whether the GPU computed them.
#[pyfunction]
#[pyo3(signature = (scene, points, interp="catmull-rom", shadows=None, cpu=false, sky=None, time=None))]
#[allow(clippy::too_many_arguments)]
fn illuminance<'py>(
    py: Python<'py>,
    scene: SceneArg<'_>,
    points: PyReadonlyArray2<'py, f64>,
    interp: &str,
    shadows: Option<&str>,
    cpu: bool,
    sky: Option<&str>,
    time: Option<&str>,
) -> PyResult<(Bound<'py, PyArray1<f64>>, bool)> {
    use goniolight::gpu::{Gpu, GpuError};
    use goniolight::render::illuminance::scene_illuminance;
    let method = parse_interp(interp)?;
    let pts = surface_points(&points)?;
    let scene = scene.scene(py)?;
    let scene = scene
        .with_sky(sky, time)
        .map_err(|e| value_error(e.to_string()))?;
    let technique = parse_shadows(shadows, &scene)?;
    let gpu = if cpu {
        None
    } else {
        match Gpu::shared() {
            Ok(gpu) => Some(gpu),
            Err(GpuError::NoAdapter(why)) => {
                let message = format!("no GPU adapter{why}: computing on the CPU");
                warn::<pyo3::exceptions::PyRuntimeWarning>(py, &message)?;
                None
            }
            Err(e) => return Err(PyRuntimeError::new_err(e.to_string())),
        }
    };
    let on_gpu = gpu.is_some();
    let mut shadows = goniolight::render::ShadowSettings::with(technique);
    let lux = scene_illuminance(gpu.as_ref(), &scene, &pts, method, &mut shadows)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    if let Some(w) = shadows.warning() {
        warn::<pyo3::exceptions::PyUserWarning>(py, &w)?;
    }
    Ok((lux.into_pyarray(py), on_gpu))
}

/// Points from an N × 6 array (x y z nx ny nz), each finite with a normal.
fn surface_points(points: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<SurfacePoint>> {
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
    Ok(pts)
}

fn parse_shadows(
    shadows: Option<&str>,
    scene: &goniolight::scene::Scene,
) -> PyResult<ShadowTechnique> {
    Ok(match shadows {
        None => scene.display.shadows.unwrap_or_default(),
        Some("none") => ShadowTechnique::None,
        Some("paraboloid") => ShadowTechnique::Paraboloid,
        Some("volumes") => ShadowTechnique::Volumes,
        Some(other) => {
            return Err(value_error(format!(
                "shadows {other:?}: none, paraboloid or volumes"
            )))
        }
    })
}

fn glam_dvec3(x: f64, y: f64, z: f64) -> glam::DVec3 {
    glam::DVec3::new(x, y, z)
}

/// A radiosity error as Python raises it: bad options and scenes are `ValueError`s.
fn session_error(e: SessionError) -> PyErr {
    match e {
        SessionError::Cancelled(_) => pyo3::exceptions::PyKeyboardInterrupt::new_err(e.to_string()),
        e if e.is_bad_input() => value_error(e),
        e => PyRuntimeError::new_err(e.to_string()),
    }
}

/// A radiosity solution of a scene (what `goniolight radiosity` solves).
#[pyclass(module = "goniolight._native", unsendable)]
pub(crate) struct NativeRadiosity {
    solution: Solution,
    scene: goniolight::scene::Scene,
}

#[pymethods]
impl NativeRadiosity {
    /// Total illuminance (direct and interreflected, lux) at an N × 6 array of points, as
    /// `radiosity --points` prints it.
    fn lux<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.gathered(py, points, true)
    }

    /// The interreflected illuminance alone (lux) at an N × 6 array of points.
    fn interreflected_lux<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.gathered(py, points, false)
    }

    /// The converged fraction of the initial unshot power when the solver stopped.
    fn convergence(&self) -> f64 {
        self.solution.convergence()
    }

    /// Why the solver stopped ("converged", "shot limit reached", "interrupted", …).
    fn stop_reason(&self) -> String {
        self.solution.stop().to_string()
    }

    /// The convergence log, as `convergence.csv` holds it.
    fn convergence_csv(&self) -> String {
        self.solution.convergence_csv()
    }

    /// Elements (light-map texels) and shooting patches.
    fn sizes(&self) -> (usize, usize) {
        let el = &self.solution.prepared().scene().elements;
        (el.len(), el.patches.len())
    }

    /// Writes the solved scene as glTF 2.0 binary (`radiosity --export`).
    #[pyo3(signature = (path, bake="auto", bake_budget=None))]
    fn export(&self, path: PathBuf, bake: &str, bake_budget: Option<u64>) -> PyResult<()> {
        let choice: BakeChoice = serde_json::from_value(serde_json::Value::from(bake))
            .map_err(|_| value_error(format!("bake {bake:?}: auto, map or vertex")))?;
        let (bytes, _, _) = self
            .solution
            .export_glb(&self.scene, choice, bake_budget)
            .map_err(|e| PyRuntimeError::new_err(format!("{e:#}")))?;
        goniolight::io::write_atomic(&path, &bytes)
            .map_err(|e| value_error(format!("{}: {e:#}", path.display())))
    }
}

impl NativeRadiosity {
    /// The solution's light map (what `render --indirect radiosity` shows).
    pub(crate) fn light_map(&self) -> goniolight::render::lightmap::LightMap {
        self.solution.light_map()
    }

    /// The total (`total`) or interreflected illuminance at an N × 6 array of points.
    fn gathered<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
        total: bool,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let pts = surface_points(&points)?;
        let cancel = AtomicBool::new(false);
        let lux = if total {
            self.solution.lux(&pts, &cancel, &|_| {})
        } else {
            self.solution.interreflected_lux(&pts, &cancel, &|_| {})
        };
        Ok(lux.map_err(session_error)?.into_pyarray(py))
    }
}

/// The radiosity options' defaults as JSON (the command line's).
#[pyfunction]
fn radiosity_defaults_json() -> PyResult<String> {
    serde_json::to_string(&Options::default()).map_err(value_error)
}

/// Solves `scene`'s interreflected light on the GPU with the options in `options_json`
/// (the fields of `goniolight::radiosity::session::Options`; those left out take their
/// defaults). `progress(shot, convergence)` is called before each shot. Ctrl-C stops the
/// preparation with KeyboardInterrupt and the shooting with the solution so far.
#[pyfunction]
#[pyo3(signature = (scene, options_json, interp=None, shadows=None, progress=None))]
fn radiosity(
    py: Python<'_>,
    scene: SceneArg<'_>,
    options_json: &str,
    interp: Option<&str>,
    shadows: Option<&str>,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<NativeRadiosity> {
    use goniolight::radiosity::session::{self, Event};
    let options: Options = serde_json::from_str(options_json).map_err(value_error)?;
    let scene = scene.scene(py)?;
    let mut settings = goniolight::render::RenderSettings::from_display(&scene.display);
    if let Some(name) = interp {
        settings.light_model = goniolight::render::LightModel::Ldt(parse_interp(name)?);
    }
    settings.shadows = goniolight::render::ShadowSettings::with(parse_shadows(shadows, &scene)?);
    let gpu = goniolight::gpu::Gpu::shared().map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let aspect = settings.aspect();
    let cancel = AtomicBool::new(false);
    let mut failed: Option<PyErr> = None;
    let mut events = |e: Event| observe(py, e, progress.as_ref(), &cancel, &mut failed);
    let setup = session::Setup {
        scene: &scene,
        options: &options,
        interp: settings.light_model.interp(),
        shadows: &mut settings.shadows,
        view: Some((&scene.camera, aspect)),
    };
    let solved = session::solve(&gpu, setup, &cancel, &mut events);
    let solution = match solved {
        Ok(s) => s,
        // Stopped while preparing: what stopped it is the error.
        Err(e) => return Err(failed.take().unwrap_or_else(|| session_error(e))),
    };
    if let Some(w) = settings.shadows.warning() {
        warn::<pyo3::exceptions::PyUserWarning>(py, &w)?;
    }
    // A progress callable that raised is the caller's error; Ctrl-C keeps the solution.
    if let Some(err) = failed {
        if !err.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
            return Err(err);
        }
    }
    Ok(NativeRadiosity { solution, scene })
}

/// `goniolight calc` of a scene: the `calc.json` document as JSON text (the scene named
/// as `scene` is given) and each grid's maintained values. `options_json` holds the
/// fields of `goniolight::calc::compute::CalcOptions` but `radiosity`, which
/// `radiosity_json` holds (those left out take their defaults).
#[pyfunction]
#[pyo3(signature = (scene, maintenance_factor=None, cpu=false, interp="catmull-rom", shadows="volumes", indirect=None, max_points=None, radiosity_json="{}", progress=None, emergency=false))]
#[allow(clippy::too_many_arguments)]
fn calc_json(
    py: Python<'_>,
    scene: SceneArg<'_>,
    maintenance_factor: Option<f64>,
    cpu: bool,
    interp: &str,
    shadows: &str,
    indirect: Option<&str>,
    max_points: Option<usize>,
    radiosity_json: &str,
    progress: Option<Bound<'_, PyAny>>,
    emergency: bool,
) -> PyResult<(String, Vec<Vec<f64>>)> {
    use goniolight::calc::compute::{compute, CalcError, CalcOptions};
    let label = scene.path().display().to_string();
    let loaded = scene.scene(py)?;
    let loaded = match emergency {
        true if indirect == Some("radiosity") => {
            return Err(value_error(
                "emergency is direct light only (EN 1838): leave out indirect",
            ))
        }
        true => loaded.in_emergency().map_err(value_error)?,
        false => loaded,
    };
    let indirect = indirect
        .map(|name| {
            serde_json::from_value(serde_json::Value::from(name))
                .map_err(|_| value_error(format!("indirect {name:?}: none or radiosity")))
        })
        .transpose()?;
    let defaults = CalcOptions::default();
    let options = CalcOptions {
        maintenance_factor,
        cpu,
        interp: parse_interp(interp)?,
        shadows: parse_shadows(Some(shadows), &loaded)?,
        indirect,
        max_points: max_points.unwrap_or(defaults.max_points),
        radiosity: serde_json::from_str(radiosity_json).map_err(value_error)?,
    };
    let cancel = AtomicBool::new(false);
    let mut failed: Option<PyErr> = None;
    let mut events = |e: goniolight::radiosity::session::Event| {
        observe(py, e, progress.as_ref(), &cancel, &mut failed)
    };
    let calc = match compute(&loaded, &options, &cancel, &mut events) {
        Ok(c) => c,
        Err(e) => {
            return Err(failed.take().unwrap_or_else(|| match e {
                CalcError::Radiosity(e) => session_error(e),
                e if e.is_bad_input() => value_error(e),
                e => PyRuntimeError::new_err(e.to_string()),
            }))
        }
    };
    if let Some(err) = failed {
        return Err(err);
    }
    for w in &calc.warnings {
        warn::<pyo3::exceptions::PyUserWarning>(py, w)?;
    }
    let doc = serde_json::to_string(&calc.json(&label)).map_err(value_error)?;
    Ok((doc, calc.grids.into_iter().map(|g| g.values).collect()))
}

/// A solve's event seen from Python: Ctrl-C sets `cancel` (and is kept in `failed`), and
/// each shot goes to the `progress` callable as `(shot, convergence)`.
fn observe(
    py: Python<'_>,
    e: goniolight::radiosity::session::Event,
    progress: Option<&Bound<'_, PyAny>>,
    cancel: &AtomicBool,
    failed: &mut Option<PyErr>,
) {
    if let Err(err) = py.check_signals() {
        cancel.store(true, Ordering::SeqCst);
        failed.get_or_insert(err);
        return;
    }
    if let (goniolight::radiosity::session::Event::Shot(p), Some(f)) = (e, progress) {
        if let Err(err) = f.call1((p.shot, p.convergence)) {
            cancel.store(true, Ordering::SeqCst);
            failed.get_or_insert(err);
        }
    }
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeLuminaire>()?;
    m.add_class::<scene::NativeScene>()?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(sun_positions_json, m)?)?;
    m.add_function(wrap_pyfunction!(illuminance, m)?)?;
    m.add_class::<NativeRadiosity>()?;
    m.add_function(wrap_pyfunction!(radiosity, m)?)?;
    m.add_function(wrap_pyfunction!(radiosity_defaults_json, m)?)?;
    m.add_function(wrap_pyfunction!(calc_json, m)?)?;
    m.add_class::<sun_study::NativeSunStudy>()?;
    m.add_class::<render::NativeRendering>()?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(sun_study::sun_study, m)?)?;
    m.add_function(wrap_pyfunction!(planning::sunlight_json, m)?)?;
    Ok(())
}
