//! Hours of sun (or of shadow) on the model itself, seen from a camera: every surface the
//! camera sees — roofs, facades, the ground — coloured by the hours it gets over a study's
//! period, as sun-hours analyses show a 3D model.
//!
//! Per step, the same stencil shadow volumes as the plan ([`super::profile`]), now from a
//! perspective camera (infinite far plane, z-pass or z-fail per step by the near-plane
//! test, as the renderer), and the side of a surface seen marked as shadowed when it is
//! turned away from the sun whatever the volumes say (an open mesh's faces cast no volume
//! when unlit; a face's back side gets the sun its front does not). A pixel's
//! hours are the weights of the steps in which it is lit, exactly as the plan counts them.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use glam::DVec3;

use super::annotate::{titled, PlanLabels};
use super::colours::hours_colour;
use super::output::with_hours_legend;
use super::shadow_profile::{
    depth_target, ground_square, plan_square, surfaces_seen, HoursMetric, ProfileError,
    ProfileSpec, SURFACE_NONE,
};
use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::render::output::write_image;
use crate::render::shadows::mask_texture;
use crate::render::volumes::{VolumeGeometry, VolumePasses};
use crate::scene::{Camera, MAX_IMAGE_SIZE};
use crate::shadow::{Light, VolumeTest};

/// Hours per pixel of a camera's view.
#[derive(Debug, Clone)]
pub struct ViewHours {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Per pixel (row-major, top row first): [`super::shadow_profile::SURFACE_GROUND`],
    /// [`super::shadow_profile::SURFACE_MODEL`] or [`SURFACE_NONE`] (sky).
    pub surface: Vec<u8>,
    /// Per pixel: hours of direct sun (0 where nothing is seen).
    pub sun_h: Vec<f32>,
    /// The part of the period with the sun up, hours (sun + shadow at every surface).
    pub sun_up_h: f64,
    /// The period's length, hours.
    pub period_h: f64,
}

impl ViewHours {
    /// Hours of `metric` per pixel (0 where nothing is seen).
    pub fn hours(&self, metric: HoursMetric) -> Vec<f32> {
        match metric {
            HoursMetric::Sun => self.sun_h.clone(),
            HoursMetric::Shadow => self
                .sun_h
                .iter()
                .zip(&self.surface)
                .map(|(&h, &s)| {
                    if s == SURFACE_NONE {
                        0.0
                    } else {
                        (self.sun_up_h as f32 - h).max(0.0)
                    }
                })
                .collect(),
        }
    }
}

/// The default view of a study: from the south-west (true azimuth 225°), 35° above the
/// horizon, the whole model in a 40° field of view. `north_offset_deg` is the angle from
/// the model's +Y clockwise to true north.
pub fn default_camera(model: &Mesh, north_offset_deg: f64) -> Option<Camera> {
    let (lo, hi) = model.bounds()?;
    let center = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(0.5);
    let fov_deg = 40.0;
    let distance = radius / (fov_deg * 0.5f64).to_radians().sin() * 1.05;
    let toward = crate::sun::direction_from_angles(225.0, 35.0, north_offset_deg);
    let mut camera = Camera::perspective(center + toward * distance, center, fov_deg);
    // The near plane well in front of the model, for depth precision at site scale.
    camera.near = (distance - radius).max(0.05) * 0.5;
    Some(camera)
}

/// Hours of sun per pixel of `camera`'s `width` × `height` view of a model
/// ([`super::shadow_profile::prepare`]d: prepare once for a profile and a view) and of the ground
/// square a plan of `spec` would show, at the model's lowest point, over `spec`'s period.
/// `progress(done, total)` after each step; `cancel` stops between steps.
pub fn compute(
    gpu: &Gpu,
    geometry: &VolumeGeometry,
    spec: &ProfileSpec,
    camera: &Camera,
    (width, height): (u32, u32),
    mut progress: impl FnMut(usize, usize),
    cancel: &AtomicBool,
) -> Result<ViewHours, ProfileError> {
    for (field, v) in [("width", width), ("height", height)] {
        if !(16..=MAX_IMAGE_SIZE).contains(&v) {
            return Err(ProfileError::Input(format!(
                "view {field} {v} is not in 16..={MAX_IMAGE_SIZE}"
            )));
        }
    }
    let (suns, _) = spec.suns()?;
    let plan = plan_square(geometry, &suns, spec)?;
    let aspect = width as f64 / height as f64;
    let view_proj = camera.view_projection(aspect);
    let near = camera.near_rectangle(aspect);
    let ground = ground_square(gpu, plan.center, plan.side * 0.5, plan.lo.z);
    let ids = mask_texture(gpu, width, height, 1);
    let mask = mask_texture(gpu, width, height, 1);
    let mask_view = mask.create_view(&Default::default());
    let depth = depth_target(gpu, width, height);
    let depth_view = depth.create_view(&Default::default());
    let passes = VolumePasses::new(gpu, crate::render::targets::LDR_FORMAT);
    let (camera_bind, surface) = surfaces_seen(
        gpu,
        &passes,
        geometry,
        (&ground.0, &ground.1),
        view_proj,
        (&ids, &depth_view),
    )?;

    let mut sun_h = vec![0f32; surface.len()];
    let total = suns.len();
    let sun_up_h = suns.iter().map(|(_, _, w)| w).sum();
    for (k, (_, p, weight_h)) in suns.into_iter().enumerate() {
        if cancel.load(Ordering::Relaxed) {
            return Err(ProfileError::Cancelled);
        }
        let d = p.direction;
        let light = Light::new([d[0], d[1], d[2], 0.0]).map_err(ProfileError::Input)?;
        let zfail = geometry.zfail(&light, VolumeTest::Auto, near);
        let volumes = [geometry.volume(gpu, light, spec.silhouette, zfail, &spec.non_casters)];
        let faces = geometry.faces_by_light(gpu, &light);
        let bind = passes.bind_group(gpu, view_proj, &volumes, None);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        passes.record_mask(&mut enc, geometry, &volumes, &bind, &mask, &depth_view);
        passes.record_faces_mark(
            &mut enc,
            geometry,
            &faces,
            &camera_bind,
            &mask_view,
            &depth_view,
        );
        gpu.queue.submit([enc.finish()]);
        let shadowed = gpu.read_texture(&mask)?;
        for ((h, &m), &s) in sun_h.iter_mut().zip(&shadowed).zip(&surface) {
            if m == 0 && s != SURFACE_NONE {
                *h += weight_h as f32;
            }
        }
        progress(k + 1, total);
    }
    Ok(ViewHours {
        width,
        height,
        surface,
        sun_h,
        sun_up_h,
        period_h: spec.period_h(),
    })
}

/// The world point (and the unit direction of the ray) through the centre of pixel
/// (`px`, `py`) of `camera`'s `width` × `height` view: the eye and the direction toward
/// the pixel (for CPU references that cast the same rays).
pub fn pixel_ray(camera: &Camera, (width, height): (u32, u32), px: u32, py: u32) -> (DVec3, DVec3) {
    let aspect = width as f64 / height as f64;
    let inv = (camera.projection(aspect) * camera.view()).inverse();
    let ndc_x = (px as f64 + 0.5) / width as f64 * 2.0 - 1.0;
    let ndc_y = 1.0 - (py as f64 + 0.5) / height as f64 * 2.0;
    let far = inv.project_point3(DVec3::new(ndc_x, ndc_y, 0.5));
    let dir = (far - camera.position).normalize();
    (camera.position, dir)
}

/// The view coloured by hours of `metric` on the study's scale (0 to the period's length,
/// as `hours.png`), the outlines between model, ground and sky dark, the sky white, the
/// legend beside it.
pub fn view_image(v: &ViewHours, metric: HoursMetric) -> image::RgbaImage {
    let hours = v.hours(metric);
    let scale = (v.period_h as f32).max(1e-3);
    let w = v.width as usize;
    // A pixel whose right or lower neighbour sees another surface (model, ground, sky).
    let seen = |k: usize| v.surface[k];
    let outline = |k: usize| {
        let (x, y) = (k % w, k / w);
        (x + 1 < w && seen(k + 1) != seen(k))
            || (y + 1 < v.height as usize && seen(k + w) != seen(k))
    };
    let image = image::RgbaImage::from_fn(v.width, v.height, |x, y| {
        let k = y as usize * w + x as usize;
        let [r, g, b] = if outline(k) {
            [40, 40, 40]
        } else if v.surface[k] == SURFACE_NONE {
            [255, 255, 255]
        } else {
            hours_colour(hours[k], scale)
        };
        image::Rgba([r, g, b, 255])
    });
    with_hours_legend(&image, metric, scale)
}

/// `model.png` (the framed [`view_image`]) and `model.exr` (hours of `metric` per pixel,
/// 0 where the sky shows) in `dir`.
pub fn write_model_view(
    v: &ViewHours,
    metric: HoursMetric,
    labels: &PlanLabels,
    dir: &Path,
) -> Result<(), crate::io::WriteError> {
    let hours = v.hours(metric);
    write_image(
        &dir.join("model.png"),
        &titled(&view_image(v, metric), labels),
    )?;
    let exr = image::Rgb32FImage::from_fn(v.width, v.height, |x, y| {
        image::Rgb([hours[(y * v.width + x) as usize]; 3])
    });
    write_image(&dir.join("model.exr"), &exr)
}
