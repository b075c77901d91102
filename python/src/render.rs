//! `goniolight.render`: one image of a scene (`goniolight render`) from Python, its HDR
//! values as arrays.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyArray2, PyArray3, PyArrayMethods};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

use goniolight::render::scene_frame::{render_scene, SceneFrameError};
use goniolight::render::{RenderSettings, RenderedFrame, Renderer};
use goniolight::scene::DisplayEntry;

use crate::scene::SceneArg;
use crate::{value_error, warn, NativeRadiosity};

/// A rendered image: the displayable picture and, per pixel, luminance and illuminance.
#[pyclass(module = "goniolight._native", unsendable)]
pub struct NativeRendering {
    frame: RenderedFrame,
    width: u32,
    height: u32,
}

impl NativeRendering {
    /// The HDR values read back (rows from the top).
    fn read_back(&self) -> PyResult<&Vec<[f32; 4]>> {
        self.frame
            .hdr
            .as_ref()
            .ok_or_else(|| PyRuntimeError::new_err("no HDR values were read back"))
    }
}

#[pymethods]
impl NativeRendering {
    /// The picture as `render --out` writes it: rows × columns × RGBA (uint8), with the
    /// legend panel beside the view in false-colour lux.
    fn image<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let (w, h) = self.frame.image.dimensions();
        let bytes = self.frame.image.as_raw().clone();
        bytes.into_pyarray(py).reshape([h as usize, w as usize, 4])
    }

    /// Per pixel of the view (rows from the top): the linear RGB of the surface seen, in
    /// cd/m² (what `render --exr` writes in shaded mode), rows × columns × 3.
    fn rgb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let values: Vec<f32> = self
            .read_back()?
            .iter()
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        values
            .into_pyarray(py)
            .reshape([self.height as usize, self.width as usize, 3])
    }

    /// Per pixel of the view (rows from the top): illuminance on the surface seen, lux
    /// (NaN where no surface shows, as the EXR's alpha marks it).
    fn lux<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let values: Vec<f32> = self
            .read_back()?
            .iter()
            .map(|p| if p[3] < 0.0 { f32::NAN } else { p[3] })
            .collect();
        values
            .into_pyarray(py)
            .reshape([self.height as usize, self.width as usize])
    }

    /// The image's statistics as `render` reports them, JSON.
    fn stats_json(&self) -> PyResult<String> {
        let s = &self.frame.stats;
        let lux = s.lux.map(|p| {
            serde_json::json!({
                "mean": p.mean, "median": p.median, "p5": p.p5, "p95": p.p95,
                "p99": p.p99, "max": p.max
            })
        });
        serde_json::to_string(&serde_json::json!({
            "log_average_luminance": s.log_average_luminance,
            "max_luminance": s.max_luminance,
            "lux": lux,
            "lux_max_shown": self.frame.tone.lux_max,
        }))
        .map_err(value_error)
    }

    /// Writes the picture as PNG (`render --out`) and, with `exr`, the HDR values as
    /// OpenEXR (`render --exr`: luminance RGB in shaded mode, lux in illuminance mode).
    #[pyo3(signature = (png, exr=None))]
    fn save(&self, png: PathBuf, exr: Option<PathBuf>) -> PyResult<()> {
        use goniolight::render::output::{linear_image, write_image};
        let failed =
            |p: &PathBuf, e: &dyn std::fmt::Display| value_error(format!("{}: {e}", p.display()));
        write_image(&png, &self.frame.image).map_err(|e| failed(&png, &format!("{e:#}")))?;
        if let Some(exr) = exr {
            let linear = linear_image(&self.frame, self.width, self.height)
                .ok_or_else(|| PyRuntimeError::new_err("no HDR values were read back"))?;
            write_image(&exr, &linear).map_err(|e| failed(&exr, &format!("{e:#}")))?;
        }
        Ok(())
    }
}

/// Renders `scene` from its camera as `goniolight render` does, with `display_json` (keys
/// of the scene file's `[display]`) over the scene's own and `supersample` samples per
/// pixel side; with `solution`, its light map shows the interreflected light.
#[pyfunction]
#[pyo3(signature = (scene, display_json="{}", supersample=3, solution=None))]
pub fn render(
    py: Python<'_>,
    scene: SceneArg<'_>,
    display_json: &str,
    supersample: u32,
    solution: Option<PyRef<'_, NativeRadiosity>>,
) -> PyResult<NativeRendering> {
    let over: DisplayEntry = serde_json::from_str(display_json).map_err(value_error)?;
    let scene = scene.scene(py)?;
    let display = scene.display.overlay(&over);
    display.check().map_err(value_error)?;
    let quality = goniolight::render::quality::RenderQuality {
        supersample,
        shadow_map_size: None,
    };
    let mut settings = quality
        .apply(RenderSettings::from_display(&display))
        .map_err(value_error)?;
    settings.read_hdr = true;
    let map = solution.map(|s| s.light_map());
    if map.is_some() {
        settings.shown_light = goniolight::scene::DisplayIndirect::Radiosity;
    }
    let gpu = goniolight::gpu::Gpu::shared().map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let renderer = Renderer::new(&gpu);
    let done =
        render_scene(&gpu, &renderer, &scene, map.as_ref(), &settings).map_err(|e| match e {
            SceneFrameError::Gpu(g) => match g {
                goniolight::gpu::GpuError::Limit(_) => value_error(g),
                g => PyRuntimeError::new_err(g.to_string()),
            },
            e => value_error(e),
        })?;
    for w in &done.warnings {
        warn::<pyo3::exceptions::PyUserWarning>(py, w)?;
    }
    Ok(NativeRendering {
        frame: done.frame,
        width: done.settings.width,
        height: done.settings.height,
    })
}
