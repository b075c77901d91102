//! Sun-path shadow profiles (Wallner §1.5, Figs. 1.5–1.7): for each step of a period, the
//! sun's position, then the shadows of a model on the ground and on itself in a plan view
//! (top-down orthographic), found with stencil shadow volumes (z-pass: the camera is above
//! everything, so it is outside every volume). The result keeps one shadow bit per pixel
//! and step, so overlays and hours-in-shadow maps are derived without rendering again.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use chrono::{DateTime, FixedOffset, NaiveDate, NaiveTime};
use glam::{DVec2, DVec3};
use wgpu::util::DeviceExt;

use crate::geometry::Mesh;
use crate::gpu::{Gpu, GpuError};
use crate::render::shadows::mask_texture;
use crate::render::volumes::{Extrusion, VolumeGeometry, VolumePasses};
use crate::scene::{Camera, MAX_IMAGE_SIZE};
use crate::shadow::{IgnoredTriangles, Light, SilhouetteMethod};
use crate::sun::{self, Site, SunOptions, Zone};

/// What went wrong computing a profile.
#[derive(Debug, thiserror::Error)]
pub enum ProfileError {
    /// Bad options or model (the user can fix them).
    #[error("{0}")]
    Input(String),
    /// A field of the [`ProfileSpec`] is out of range (the user can fix it).
    #[error("{field} {message}")]
    Invalid {
        /// The field's name in [`ProfileSpec`].
        field: &'static str,
        /// What is wrong with its value.
        message: String,
    },
    /// The model could not be read or has no triangles with area.
    #[error(transparent)]
    Model(#[from] crate::geometry::GeometryError),
    /// The site or time zone is out of range.
    #[error(transparent)]
    Sun(#[from] crate::sun::SunError),
    /// A file of the study could not be written.
    #[error(transparent)]
    Output(#[from] crate::io::WriteError),
    /// The GPU failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// Interrupted by the caller.
    #[error("interrupted before the last step: nothing written")]
    Cancelled,
}

impl ProfileError {
    /// A field of the options is out of range: `message` says how.
    pub fn invalid(field: &'static str, message: String) -> ProfileError {
        ProfileError::Invalid { field, message }
    }
}

/// The period, site and image of a profile.
#[derive(Debug, Clone)]
pub struct ProfileSpec {
    /// The site.
    pub site: Site,
    /// Its time zone (local times below are in it).
    pub zone: Zone,
    /// The day.
    pub date: NaiveDate,
    /// First step, local time.
    pub from: NaiveTime,
    /// Last step (inclusive when the steps land on it), local time.
    pub to: NaiveTime,
    /// Minutes between steps.
    pub step_minutes: u32,
    /// Atmosphere, ΔT and the model's north offset.
    pub sun: SunOptions,
    /// Side of the square plan view, metres (`None`: enough for the lowest sun).
    pub extent_m: Option<f64>,
    /// Pixels per side.
    pub resolution: u32,
    /// Silhouette search.
    pub silhouette: SilhouetteMethod,
    /// Triangles that receive shadows but cast none (components left out of the casters,
    /// e.g. the existing buildings when the new one's shadow is studied).
    pub non_casters: IgnoredTriangles,
    /// Where the shadow volumes end (the default, [`VolumeEnds::Ground`], fills least).
    pub volume_ends: VolumeEnds,
}

/// Where a plan's shadow volumes end below the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum VolumeEnds {
    /// Every vertex along the sun down to the plane half a metre under the ground: a low
    /// edge's side covers only the plan its own shadow can reach.
    #[default]
    Ground,
    /// Every vertex by the same length, enough for the highest one (the first release;
    /// kept to measure the difference, `bench profile`).
    OneLength,
}

impl ProfileSpec {
    /// The local instants of the steps.
    pub fn local_times(&self) -> Result<Vec<chrono::NaiveDateTime>, ProfileError> {
        if self.step_minutes == 0 {
            return Err(ProfileError::invalid(
                "step_minutes",
                "must be at least 1 minute".into(),
            ));
        }
        if self.from > self.to {
            return Err(ProfileError::invalid(
                "from",
                format!(
                    "{} is after `to` {}",
                    self.from.format("%H:%M"),
                    self.to.format("%H:%M")
                ),
            ));
        }
        let start = self.date.and_time(self.from);
        let end = self.date.and_time(self.to);
        let step = chrono::Duration::minutes(self.step_minutes as i64);
        let mut out = Vec::new();
        let mut t = start;
        while t <= end {
            out.push(t);
            t += step;
        }
        Ok(out)
    }

    /// The period's length, hours (`to` − `from`).
    pub fn period_h(&self) -> f64 {
        (self.to - self.from).num_seconds() as f64 / 3600.0
    }

    /// The hours each step of [`ProfileSpec::local_times`] stands for: the part of the
    /// period nearer to it than to any other step (the midpoint rule, which for evenly
    /// spaced steps is the trapezoid rule: the first and last steps stand for half a step
    /// each when the period ends on them). The weights add up to [`Self::period_h`], so
    /// 08:00–17:00 hourly gives 9 h of sun on open ground, not 10.
    pub fn sample_weights_h(&self) -> Result<Vec<f64>, ProfileError> {
        let times = self.local_times()?;
        let start = self.date.and_time(self.from);
        let end = self.date.and_time(self.to);
        let hours = |a: chrono::NaiveDateTime, b: chrono::NaiveDateTime| {
            (b - a).num_milliseconds() as f64 / 3.6e6
        };
        Ok((0..times.len())
            .map(|k| {
                let lo = if k == 0 {
                    start
                } else {
                    times[k - 1] + (times[k] - times[k - 1]) / 2
                };
                let hi = if k + 1 == times.len() {
                    end
                } else {
                    times[k] + (times[k + 1] - times[k]) / 2
                };
                hours(lo, hi)
            })
            .collect())
    }
}

/// One step with the sun up: its local time, the sun, and the hours it stands for.
pub type SunStep = (DateTime<FixedOffset>, sun::SunPosition, f64);

impl ProfileSpec {
    /// The steps with the sun above the horizon and the local times of those without;
    /// refused when the sun is down at every step.
    pub fn suns(&self) -> Result<(Vec<SunStep>, Vec<DateTime<FixedOffset>>), ProfileError> {
        let mut suns = Vec::new();
        let mut skipped = Vec::new();
        let weights = self.sample_weights_h()?;
        for (local, weight_h) in self.local_times()?.into_iter().zip(weights) {
            let (utc, _) = self
                .zone
                .resolve(local)
                .map_err(|e| ProfileError::Input(e.to_string()))?;
            let offset = FixedOffset::east_opt(self.zone.offset_seconds(utc))
                .ok_or_else(|| ProfileError::Input("bad time-zone offset".into()))?;
            let time = utc.with_timezone(&offset);
            let p = sun::position(&self.site, utc, &self.sun)
                .map_err(|e| ProfileError::Input(e.to_string()))?;
            if p.elevation_deg <= 0.0 {
                skipped.push(time);
            } else {
                suns.push((time, p, weight_h));
            }
        }
        if suns.is_empty() {
            return Err(ProfileError::Input(format!(
                "the sun is below the horizon at every step ({} steps on {} from {} to {})",
                skipped.len(),
                self.date,
                self.from.format("%H:%M"),
                self.to.format("%H:%M")
            )));
        }
        Ok((suns, skipped))
    }

    /// The lowest sun of the period, degrees.
    pub fn lowest_sun_deg(&self) -> Result<f64, ProfileError> {
        Ok(self
            .suns()?
            .0
            .iter()
            .map(|(_, p, _)| p.elevation_deg)
            .fold(90.0, f64::min))
    }
}

/// One plan side for several periods (the dates of a study): the default extent of the
/// lowest sun among them, so their plans can be compared cell by cell.
pub fn shared_extent(model: &Mesh, specs: &[ProfileSpec]) -> Result<f64, ProfileError> {
    let mut lowest = 90f64;
    for spec in specs {
        lowest = lowest.min(spec.lowest_sun_deg()?);
    }
    default_extent(model, lowest)
        .map(|(_, side)| side)
        .ok_or_else(|| ProfileError::Input("the model has no triangles".into()))
}

/// What an hours map counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum HoursMetric {
    /// Hours of direct sun (the sun above the horizon and not hidden by the model).
    Sun,
    /// Hours in the model's shadow while the sun is up (the first release's map).
    #[default]
    Shadow,
}

impl HoursMetric {
    /// `"sun"` or `"shadow"`.
    pub fn name(self) -> &'static str {
        match self {
            HoursMetric::Sun => "sun",
            HoursMetric::Shadow => "shadow",
        }
    }
}

/// One step of a profile.
#[derive(Debug, Clone)]
pub struct ProfileStep {
    /// Local time.
    pub time: DateTime<FixedOffset>,
    /// Sun azimuth, degrees clockwise from north.
    pub azimuth_deg: f64,
    /// Sun elevation, degrees (apparent).
    pub elevation_deg: f64,
    /// Ground in shadow outside the footprint, m².
    pub shadow_area_m2: f64,
    /// The same plus the footprint, m².
    pub shadow_area_with_footprint_m2: f64,
    /// Whether the shadow reaches the edge of the plan (its area is then cut).
    pub reaches_edge: bool,
    /// Hours of the period this step stands for (see [`ProfileSpec::sample_weights_h`]).
    pub weight_h: f64,
    /// One bit per pixel (row-major): in shadow.
    pub shadow: Vec<u64>,
}

impl ProfileStep {
    /// Whether pixel `k` is in shadow.
    pub fn in_shadow(&self, k: usize) -> bool {
        self.shadow[k / 64] >> (k % 64) & 1 == 1
    }
}

/// What each plan pixel sees.
pub const SURFACE_NONE: u8 = 0;
/// The ground.
pub const SURFACE_GROUND: u8 = 1;
/// The model (its footprint, seen from above).
pub const SURFACE_MODEL: u8 = 2;

/// Time spent per part, seconds.
#[derive(Debug, Clone, Copy, Default)]
pub struct ProfileTiming {
    /// Silhouettes and volume index buffers (CPU).
    pub silhouette_s: f64,
    /// Stencil passes and read-back (GPU).
    pub render_s: f64,
}

/// A computed profile.
#[derive(Debug, Clone)]
pub struct Profile {
    /// Pixels per side.
    pub resolution: u32,
    /// Side of the plan, metres.
    pub extent_m: f64,
    /// World x, y of the plan's centre.
    pub center: DVec2,
    /// What is added to world x, y to give the model file's own plan coordinates (the
    /// loader moves far-off models near the origin before the GPU sees them; outputs give
    /// the file's coordinates).
    pub origin: DVec2,
    /// Height of the ground plane (the model's lowest point), metres.
    pub ground_z: f64,
    /// Per pixel: [`SURFACE_GROUND`], [`SURFACE_MODEL`] or [`SURFACE_NONE`].
    pub surface: Vec<u8>,
    /// The steps with the sun above the horizon.
    pub steps: Vec<ProfileStep>,
    /// Steps skipped because the sun was below the horizon.
    pub skipped: Vec<DateTime<FixedOffset>>,
    /// Minutes between steps.
    pub step_minutes: u32,
    /// The period's length (`to` − `from`), hours.
    pub period_h: f64,
    /// The part of the period with the sun up (the weights of the steps kept), hours.
    pub sun_up_h: f64,
    /// Where the time went.
    pub timing: ProfileTiming,
}

impl Profile {
    /// Area of one pixel, m².
    pub fn pixel_area_m2(&self) -> f64 {
        (self.extent_m / self.resolution as f64).powi(2)
    }

    /// World (x, y) of pixel (px, py)'s centre (row 0 is the north edge).
    pub fn pixel_center(&self, px: u32, py: u32) -> DVec2 {
        let s = self.extent_m / self.resolution as f64;
        DVec2::new(
            self.center.x - self.extent_m / 2.0 + (px as f64 + 0.5) * s,
            self.center.y + self.extent_m / 2.0 - (py as f64 + 0.5) * s,
        )
    }

    /// Footprint area (pixels that see the model from above), m².
    pub fn footprint_area_m2(&self) -> f64 {
        self.surface.iter().filter(|&&s| s == SURFACE_MODEL).count() as f64 * self.pixel_area_m2()
    }

    /// Hours in shadow per pixel: the weights of the steps that shadow it (every pixel;
    /// the model's own pixels count the shadow on its roof).
    pub fn hours_in_shadow(&self) -> Vec<f32> {
        self.hours(HoursMetric::Shadow)
    }

    /// Hours per pixel of `metric`: the sum of the weights ([`ProfileStep::weight_h`]) of
    /// the steps with the sun up that shadow the pixel ([`HoursMetric::Shadow`]) or do not
    /// ([`HoursMetric::Sun`]). Pixels that see neither ground nor model get 0.
    pub fn hours(&self, metric: HoursMetric) -> Vec<f32> {
        let n = (self.resolution * self.resolution) as usize;
        let mut hours = vec![0f64; n];
        for s in &self.steps {
            for (k, v) in hours.iter_mut().enumerate() {
                if s.in_shadow(k) == (metric == HoursMetric::Shadow)
                    && self.surface[k] != SURFACE_NONE
                {
                    *v += s.weight_h;
                }
            }
        }
        hours.into_iter().map(|h| h as f32).collect()
    }
}

/// The plan square for `model`: centre, side. `min_elevation_deg` is the lowest sun.
pub fn default_extent(model: &Mesh, min_elevation_deg: f64) -> Option<(DVec2, f64)> {
    let (lo, hi) = model.bounds()?;
    let size = (hi - lo).truncate().max_element();
    let height = hi.z - lo.z;
    let reach = (height / min_elevation_deg.max(3.0).to_radians().tan()).min(20.0 * height);
    let side = ((size + 2.0 * reach) * 1.05).max(1e-3);
    Some((((lo + hi) / 2.0).truncate(), side))
}

/// Computes the profile of `model` (world frame: metres, +Z up) for `spec`, calling
/// `progress(done, total)` after each step; stops with [`ProfileError::Cancelled`] when
/// `cancel` is set.
pub fn compute(
    gpu: &Gpu,
    model: &Mesh,
    spec: &ProfileSpec,
    progress: impl FnMut(usize, usize),
    cancel: &AtomicBool,
) -> Result<Profile, ProfileError> {
    compute_on(gpu, &prepare(gpu, model)?, spec, progress, cancel)
}

/// `model` (world frame: metres, +Z up) prepared for studies: welded, with its edges, on
/// the GPU. Prepare once for several profiles or views of one model.
pub fn prepare(gpu: &Gpu, model: &Mesh) -> Result<VolumeGeometry, ProfileError> {
    VolumeGeometry::new(gpu, model, "model").map_err(|e| ProfileError::Input(e.to_string()))
}

/// [`compute`] on a model already [`prepare`]d.
pub fn compute_on(
    gpu: &Gpu,
    geometry: &VolumeGeometry,
    spec: &ProfileSpec,
    mut progress: impl FnMut(usize, usize),
    cancel: &AtomicBool,
) -> Result<Profile, ProfileError> {
    if spec.resolution < 16 || spec.resolution > MAX_IMAGE_SIZE {
        return Err(ProfileError::invalid(
            "resolution",
            format!("{} is not in 16..={}", spec.resolution, MAX_IMAGE_SIZE),
        ));
    }
    if let Some(e) = spec.extent_m {
        if !(e.is_finite() && e > 0.0) {
            return Err(ProfileError::invalid(
                "extent_m",
                format!("{e} must be a positive number"),
            ));
        }
    }
    // Sun positions first: they decide the extent and which steps are skipped.
    let (suns, skipped) = spec.suns()?;
    let PlanSquare {
        center,
        side: extent,
        lo,
        hi,
    } = plan_square(geometry, &suns, spec)?;
    let n = spec.resolution;
    let plan = PlanView::new(gpu, center, extent, lo.z, hi.z, n);
    let passes = VolumePasses::new(gpu, crate::render::targets::LDR_FORMAT);
    let (_, surface) = surfaces_seen(
        gpu,
        &passes,
        geometry,
        (&plan.ground_vertices, &plan.ground_indices),
        plan.view_proj,
        (&plan.ids, &plan.depth_view),
    )?;

    let pixel_area = (extent / n as f64).powi(2);
    let footprint = surface.iter().filter(|&&s| s == SURFACE_MODEL).count() as f64 * pixel_area;
    let mut steps = Vec::with_capacity(suns.len());
    let mut timing = ProfileTiming::default();
    let total = suns.len();
    let sun_up_h = suns.iter().map(|(_, _, w)| w).sum();
    for (k, (time, p, weight_h)) in suns.into_iter().enumerate() {
        if cancel.load(Ordering::Relaxed) {
            return Err(ProfileError::Cancelled);
        }
        let d = p.direction;
        let light = Light::new([d[0], d[1], d[2], 0.0]).map_err(ProfileError::Input)?;
        let t0 = Instant::now();
        let volume = geometry.volume(gpu, light, spec.silhouette, false, &spec.non_casters);
        timing.silhouette_s += t0.elapsed().as_secs_f64();
        let t1 = Instant::now();
        let volumes = [volume];
        // Down to half a metre below the ground, inside the camera's far plane.
        let ends = match spec.volume_ends {
            VolumeEnds::Ground => Extrusion::DownToZ((lo.z - 0.5) as f32),
            VolumeEnds::OneLength => {
                let sin_e = p.elevation_deg.to_radians().sin().max(1e-3);
                Extrusion::Length(((hi.z - lo.z + 0.5) / sin_e) as f32)
            }
        };
        let bind = passes.bind_group(gpu, plan.view_proj, &volumes, Some(ends));
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        passes.record_mask(
            &mut enc,
            geometry,
            &volumes,
            &bind,
            &plan.mask,
            &plan.depth_view,
        );
        gpu.queue.submit([enc.finish()]);
        let mask = gpu.read_texture(&plan.mask)?;
        timing.render_s += t1.elapsed().as_secs_f64();
        let mut step = step_from_mask(
            time,
            p.azimuth_deg,
            p.elevation_deg,
            &mask,
            &surface,
            n,
            pixel_area,
            footprint,
        );
        step.weight_h = weight_h;
        steps.push(step);
        progress(k + 1, total);
    }
    Ok(Profile {
        resolution: n,
        extent_m: extent,
        center,
        origin: DVec2::ZERO,
        ground_z: lo.z,
        surface,
        steps,
        skipped,
        step_minutes: spec.step_minutes,
        period_h: spec.period_h(),
        sun_up_h,
        timing,
    })
}

#[allow(clippy::too_many_arguments)]
fn step_from_mask(
    time: DateTime<FixedOffset>,
    azimuth_deg: f64,
    elevation_deg: f64,
    mask: &[u8],
    surface: &[u8],
    n: u32,
    pixel_area: f64,
    footprint: f64,
) -> ProfileStep {
    let mut shadow = vec![0u64; mask.len().div_ceil(64)];
    let mut ground = 0usize;
    let mut reaches_edge = false;
    let n = n as usize;
    for (k, (&m, &s)) in mask.iter().zip(surface).enumerate() {
        if m != 0 && s != SURFACE_NONE {
            shadow[k / 64] |= 1 << (k % 64);
            if s == SURFACE_GROUND {
                ground += 1;
                let (x, y) = (k % n, k / n);
                reaches_edge |= x == 0 || y == 0 || x == n - 1 || y == n - 1;
            }
        }
    }
    let area = ground as f64 * pixel_area;
    ProfileStep {
        time,
        azimuth_deg,
        elevation_deg,
        shadow_area_m2: area,
        shadow_area_with_footprint_m2: area + footprint,
        reaches_edge,
        weight_h: 0.0,
        shadow,
    }
}

/// The plan view's camera, ground and targets.
struct PlanView {
    view_proj: glam::Mat4,
    ground_vertices: wgpu::Buffer,
    ground_indices: wgpu::Buffer,
    ids: wgpu::Texture,
    mask: wgpu::Texture,
    depth_view: wgpu::TextureView,
}

impl PlanView {
    fn new(gpu: &Gpu, center: DVec2, extent: f64, ground_z: f64, top_z: f64, n: u32) -> Self {
        let height = (top_z - ground_z).max(1.0);
        let camera = Camera::top_down(
            DVec3::new(center.x, center.y, ground_z),
            extent,
            top_z + height,
        );
        let view_proj = camera.view_projection(1.0);
        // The ground: the plan square, a little larger so its edge never shows.
        let (ground_vertices, ground_indices) = ground_square(gpu, center, extent * 0.6, ground_z);
        let ids = mask_texture(gpu, n, n, 1);
        let depth = depth_target(gpu, n, n);
        PlanView {
            view_proj,
            ground_vertices,
            ground_indices,
            ids,
            mask: mask_texture(gpu, n, n, 1),
            depth_view: depth.create_view(&Default::default()),
        }
    }
}

/// Where a study's plan lies: the square centred at `center` of `side` metres (enough for
/// the shadow of the lowest sun unless the spec gives it), and the model's bounds.
pub(super) struct PlanSquare {
    pub center: DVec2,
    pub side: f64,
    pub lo: DVec3,
    pub hi: DVec3,
}

/// The plan square of `geometry` for `spec`, whose `suns` are given.
pub(super) fn plan_square(
    geometry: &VolumeGeometry,
    suns: &[SunStep],
    spec: &ProfileSpec,
) -> Result<PlanSquare, ProfileError> {
    let no_triangles = || ProfileError::Input("the model has no triangles".into());
    let (lo, hi) = geometry.mesh.mesh().bounds().ok_or_else(no_triangles)?;
    let min_elevation = suns
        .iter()
        .map(|(_, p, _)| p.elevation_deg)
        .fold(90.0, f64::min);
    let (center, auto_side) =
        default_extent(geometry.mesh.mesh(), min_elevation).ok_or_else(no_triangles)?;
    Ok(PlanSquare {
        center,
        side: spec.extent_m.unwrap_or(auto_side),
        lo,
        hi,
    })
}

/// Draws the surfaces of `geometry` and the `ground` square (vertex and index buffers)
/// seen through `view_proj` into `ids` and the depth target, and reads back which one
/// each pixel sees; returns the camera's bind group with it.
pub(super) fn surfaces_seen(
    gpu: &Gpu,
    passes: &VolumePasses,
    geometry: &VolumeGeometry,
    (ground_vertices, ground_indices): (&wgpu::Buffer, &wgpu::Buffer),
    view_proj: glam::Mat4,
    (ids, depth_view): (&wgpu::Texture, &wgpu::TextureView),
) -> Result<(wgpu::BindGroup, Vec<u8>), ProfileError> {
    let camera_bind = passes.bind_group(gpu, view_proj, &[], None);
    let ids_view = ids.create_view(&Default::default());
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    passes.record_surfaces(
        &mut enc,
        geometry,
        (ground_vertices, ground_indices, 6),
        &camera_bind,
        &ids_view,
        depth_view,
    );
    gpu.queue.submit([enc.finish()]);
    let surface = gpu.read_texture(ids)?;
    Ok((camera_bind, surface))
}

/// The ground as a square of half-side `half` metres about `center` at height `z`: its
/// vertex buffer (vec4 positions) and index buffer (6 indices).
pub(super) fn ground_square(
    gpu: &Gpu,
    center: DVec2,
    half: f64,
    z: f64,
) -> (wgpu::Buffer, wgpu::Buffer) {
    let corners: Vec<[f32; 4]> = [(-half, -half), (half, -half), (half, half), (-half, half)]
        .iter()
        .map(|&(dx, dy)| {
            [
                (center.x + dx) as f32,
                (center.y + dy) as f32,
                z as f32,
                1.0,
            ]
        })
        .collect();
    let dev = &gpu.device;
    let vertices = dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("ground"),
        contents: bytemuck::cast_slice(&corners),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let indices = dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("ground"),
        contents: bytemuck::cast_slice(&[0u32, 1, 2, 0, 2, 3]),
        usage: wgpu::BufferUsages::INDEX,
    });
    (vertices, indices)
}

/// A depth-stencil target of `width` × `height` for the surface and volume passes.
pub(super) fn depth_target(gpu: &Gpu, width: u32, height: u32) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("study depth"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: gpu.depth_stencil_format(),
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    })
}
