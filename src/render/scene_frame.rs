//! One image of a scene as every front end renders it: the read-back size and the scene
//! checked against the GPU's limits, what the image cannot show said (or refused), the
//! scene uploaded (with a solved light map when given) and rendered. `goniolight render`,
//! `demo` and Python's `render` call [`render_scene`].

use crate::gpu::{Gpu, GpuError};
use crate::scene::{DisplayIndirect, Mode, Scene};
use crate::shadow::ShadowTechnique;

use super::legend::format_lux;
use super::lightmap::LightMap;
use super::{RenderSettings, RenderedFrame, Renderer};

/// Why a scene was not rendered.
#[derive(Debug, thiserror::Error)]
pub enum SceneFrameError {
    /// A mirror or clear glass in a direct-light illuminance image, which would leave
    /// out the light it passes on (the option to change named in backquotes).
    #[error("{file}: material {material:?} is a mirror or clear glass: this direct-light illuminance image would leave out the light it passes on; use `indirect` radiosity (its light map holds it), or `calc`, `illuminance` or a radiosity solution's lux at points")]
    Specular {
        /// The scene file.
        file: String,
        /// The material's name.
        material: String,
    },
    /// The GPU refused or failed (a size beyond its limits is [`GpuError::Limit`]).
    #[error(transparent)]
    Gpu(#[from] GpuError),
}

/// A rendered scene and what its caller should be told (options named in backquotes).
pub struct SceneFrame {
    /// The image, its HDR values when `settings.read_hdr`, its statistics.
    pub frame: RenderedFrame,
    /// The settings it was rendered with (the shadows as the GPU's check fitted them).
    pub settings: RenderSettings,
    /// What the image leaves out or changed to fit.
    pub warnings: Vec<String>,
}

impl SceneFrame {
    /// One line on the light in the image: in a shaded image the log-average and maximum
    /// luminance; in an illuminance image the lux percentiles over the surface pixels
    /// (the maximum beside the 99th percentile, with a note when a few pixels next to a
    /// luminaire dominate it) and the false-colour scale.
    pub fn light_summary(&self) -> String {
        match self.settings.mode {
            Mode::Shaded => format!(
                "log-average luminance {:.1} cd/m², max {:.0} cd/m²",
                self.frame.stats.log_average_luminance, self.frame.stats.max_luminance
            ),
            Mode::Illuminance => lux_summary(&self.frame, self.settings.shown_light),
        }
    }
}

/// The illuminance line of a report: percentiles over the surface pixels, the maximum
/// beside the 99th percentile (it is usually a surface touching a luminaire), the scale.
fn lux_summary(frame: &RenderedFrame, light: DisplayIndirect) -> String {
    let scale = format!("scale 0–{} lx", format_lux(frame.tone.lux_max));
    match frame.stats.lux {
        Some(p) => {
            let note = if p.max > 5.0 * p.p99 {
                " (a few pixels next to a luminaire: quote the percentiles)"
            } else {
                ""
            };
            format!(
                "illuminance ({}) over the surfaces in view: mean {:.0} lx, median {:.0}, 5 % {:.0}, 95 % {:.0}, 99 % {:.0}, max {:.0}{note}; {scale}",
                light.describe(),
                p.mean,
                p.median,
                p.p5,
                p.p95,
                p.p99,
                p.max
            )
        }
        None => format!("no surface in view; {scale}"),
    }
}

/// Renders `scene` from its camera with `settings` (and `light_map`, a solved radiosity
/// light map, when given).
pub fn render_scene(
    gpu: &Gpu,
    renderer: &Renderer,
    scene: &Scene,
    light_map: Option<&LightMap>,
    settings: &RenderSettings,
) -> Result<SceneFrame, SceneFrameError> {
    let mut settings = settings.clone();
    // The HDR image (RGBA32F) is read back whole: refuse a size the device cannot.
    gpu.check_read_back(
        settings.width,
        settings.height,
        u64::from(settings.width) * u64::from(settings.height) * 16,
    )?;
    super::limits::check_scene(gpu, scene, &mut settings.shadows)?;
    let solved = light_map.is_some();
    let mut warnings: Vec<String> = settings.shadows.warning().into_iter().collect();
    warnings.extend(what_volumes_miss(scene, &settings, solved));
    warnings.extend(what_specular_misses(scene, &settings, solved)?);
    let uploaded = match light_map {
        Some(map) => renderer.upload_solved(gpu, scene, map),
        None => renderer.upload(gpu, scene),
    };
    let frame = renderer.render(gpu, &uploaded, &scene.camera, &settings)?;
    Ok(SceneFrame {
        frame,
        settings,
        warnings,
    })
}

/// Stencil shadow volumes start at a surface turned from the light, so a translucent
/// surface lit from behind stays dark in a direct render (a solved light map holds the
/// transmitted light either way); and they are built from whole triangles, so
/// alpha-masked holes cast shadows.
fn what_volumes_miss(scene: &Scene, settings: &RenderSettings, solved: bool) -> Vec<String> {
    if settings.shadows.technique != ShadowTechnique::Volumes {
        return Vec::new();
    }
    let mut out = Vec::new();
    if !solved && crate::scene::back_faces::has_translucent_surfaces(scene) {
        out.push(
            "stencil shadow volumes cannot light a translucent surface from behind; it stays dark in this image (`shadows` paraboloid shows it)"
                .to_string(),
        );
    }
    if scene.materials.iter().any(|m| m.alpha_mask.is_some()) {
        out.push(
            "stencil shadow volumes cannot see the holes of alpha-masked materials; they cast solid shadows in this image (`shadows` paraboloid lets light through them)"
                .to_string(),
        );
    }
    out
}

/// A mirror or clear glass: refused in a direct-light illuminance image, else a warning
/// that the image draws it by its diffuse part.
fn what_specular_misses(
    scene: &Scene,
    settings: &RenderSettings,
    solved: bool,
) -> Result<Option<String>, SceneFrameError> {
    let Some(m) = scene.specular_material() else {
        return Ok(None);
    };
    if settings.mode == Mode::Illuminance && !solved {
        return Err(SceneFrameError::Specular {
            file: scene.path.display().to_string(),
            material: m.name.clone(),
        });
    }
    Ok(Some(format!(
        "material {:?} is a mirror or clear glass: the image draws it by its diffuse part (no mirror reflection pass){}; lux from calc, illuminance and radiosity include the light it passes on",
        m.name,
        if solved {
            ""
        } else {
            ", and its direct light stops at the glass"
        }
    )))
}
