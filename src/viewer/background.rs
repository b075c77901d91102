//! The viewer's background work driven from its state: starting the live radiosity solve
//! and the shadow profile, pausing, following the camera, and taking in what the workers
//! report each frame. The panels that start them are in [`super::work`].

use std::sync::atomic::Ordering;
use std::sync::Arc;

use super::app::{ProfileShown, ViewerApp};
use super::jobs::{self, ProfileUpdate};
use super::live_radiosity::{self, RadiosityCommand, RadiosityUpdate};
use crate::scene::Projection;
use crate::study::output::{hours_image, profile_image};
use crate::study::shadow_profile::ProfileSpec;
use crate::study::view_hours::view_image;
use crate::study::HoursMetric;
use crate::sun::{Site, Zone};

/// Seconds the camera stands still before a view-driven solver follows it.
pub const FOLLOW_AFTER_S: f64 = 0.3;

/// The size of the hours-of-sun view computed with a profile, pixels.
const MODEL_VIEW_SIZE: (u32, u32) = (800, 600);

impl ViewerApp {
    /// Starts the shadow profile of the scene's geometry for the sun panel's period.
    pub fn start_profile(&mut self) {
        let Some(gpu) = self.gpu.clone() else {
            return self.error("no GPU for the shadow profile");
        };
        let s = &self.sun;
        let spec = (|| -> Result<ProfileSpec, String> {
            Ok(ProfileSpec {
                site: Site::new(s.latitude, s.longitude, 0.0).map_err(|e| e.to_string())?,
                zone: Zone::parse(&s.zone).map_err(|e| e.to_string())?,
                date: s.date,
                from: s.profile_from,
                to: s.profile_to,
                step_minutes: s.profile_step,
                sun: s.options(),
                extent_m: None,
                resolution: s.profile_resolution,
                silhouette: self.display.shadows.silhouette,
                non_casters: Default::default(),
                volume_ends: Default::default(),
            })
        })();
        let spec = match spec.and_then(|sp| sp.local_times().map(|_| sp).map_err(|e| e.to_string()))
        {
            Ok(sp) => sp,
            Err(e) => return self.error(format!("shadow profile: {e}")),
        };
        // The hours of sun on the model from this view too (perspective views only: the
        // volumes go to infinity).
        let camera = self.camera.camera(self.extent());
        let view = matches!(camera.projection, Projection::Perspective { .. })
            .then_some((camera, MODEL_VIEW_SIZE));
        match jobs::start_profile(gpu, self.scene.caster_mesh(), spec, view) {
            Ok(w) => {
                self.profile.worker = Some(w);
                self.profile.progress = (0, 0);
                self.profile.view = None;
                self.profile.open = true;
            }
            Err(e) => self.error(format!("shadow profile: {e}")),
        }
    }

    /// Starts radiosity on the scene as shown (the sun included when it is on).
    pub fn start_radiosity(&mut self) {
        let Some(gpu) = self.gpu.clone() else {
            return self.error("no GPU for radiosity");
        };
        self.reset_radiosity();
        let mut settings = self.radiosity.settings.clone();
        settings.interp = self.display.light_model.interp();
        let view = self.radiosity_view();
        self.radiosity.followed = Some(view);
        match live_radiosity::start(
            gpu,
            self.render_scene(),
            settings,
            self.display.shadows.clone(),
            Some(view),
        ) {
            Ok((w, link)) => {
                self.radiosity.worker = Some(w);
                self.radiosity.link = Some(link);
                self.radiosity.status = "meshing and shooting the luminaires…".into();
            }
            Err(e) => self.error(format!("radiosity: {e}")),
        }
    }

    /// Starts what `start_with` asks for once (`view --indirect`): a radiosity solution,
    /// or one that stops before its first shot (the luminaires' first bounce and the
    /// ambient term).
    pub fn start_indirect(&mut self) {
        use crate::scene::DisplayIndirect;
        let wanted = std::mem::take(&mut self.radiosity.start_with);
        let converge = self.radiosity.settings.options.converge;
        match wanted {
            DisplayIndirect::None => return,
            DisplayIndirect::Ambient => self.radiosity.settings.options.converge = 0.0,
            DisplayIndirect::Radiosity => {}
        }
        self.start_radiosity();
        self.radiosity.settings.options.converge = converge;
    }

    /// Pauses or resumes the solver.
    pub fn toggle_radiosity_pause(&mut self) {
        if let Some(w) = &self.radiosity.worker {
            self.radiosity.paused = !self.radiosity.paused;
            w.control
                .pause
                .store(self.radiosity.paused, Ordering::SeqCst);
        }
    }

    /// The camera and the viewport's width / height, as a view-driven solver sees them.
    fn radiosity_view(&self) -> (crate::scene::Camera, f64) {
        let [w, h] = self.status.viewport_px;
        let aspect = if w > 0 && h > 0 {
            w as f64 / h as f64
        } else {
            16.0 / 9.0
        };
        (self.camera.camera(self.extent()), aspect)
    }

    /// Tells a view-driven solver the view once the camera has stood still for
    /// [`FOLLOW_AFTER_S`] away from the view it has.
    fn follow_the_view(&mut self, ctx: &egui::Context) {
        let r = &self.radiosity;
        if r.settings.options.drive == crate::radiosity::view::Drive::Global || r.link.is_none() {
            return;
        }
        let view = self.radiosity_view();
        let r = &mut self.radiosity;
        // The camera decides; a resized viewport alone does not re-solve the importance.
        if r.followed.as_ref().map(|f| &f.0) == Some(&view.0) {
            r.moved_at = None;
            return;
        }
        let now = std::time::Instant::now();
        let since = *r.moved_at.get_or_insert(now);
        if (now - since).as_secs_f64() < FOLLOW_AFTER_S {
            // A waiting solver does not keep the window painting: come back then.
            ctx.request_repaint_after(std::time::Duration::from_secs_f64(FOLLOW_AFTER_S));
            return;
        }
        let (camera, aspect) = view;
        if let Some(link) = &r.link {
            if link
                .commands
                .send(RadiosityCommand::View(camera, aspect))
                .is_ok()
            {
                r.followed = Some(view);
                r.moved_at = None;
                r.waiting = false;
            }
        }
    }

    /// Takes what the workers reported since the last frame, and grants the radiosity
    /// solver this frame's share of time.
    pub fn poll_jobs(&mut self, ctx: &egui::Context) {
        if let Some(link) = &self.radiosity.link {
            link.credit.grant();
        }
        self.follow_the_view(ctx);
        if let Some(w) = &mut self.radiosity.worker {
            let updates = w.poll();
            let finished = w.finished();
            for u in updates {
                self.radiosity_update(u);
            }
            if finished {
                self.radiosity.worker = None;
                self.radiosity.link = None;
                self.radiosity.paused = false;
            }
        }
        if let Some(w) = &mut self.profile.worker {
            let updates = w.poll();
            let finished = w.finished();
            for u in updates {
                match u {
                    ProfileUpdate::Progress(d, t) => self.profile.progress = (d, t),
                    ProfileUpdate::Done(p) => {
                        self.profile.result = Some(Arc::from(p));
                        self.profile.texture = None;
                        self.info("shadow profile done");
                    }
                    ProfileUpdate::View(v) => {
                        self.profile.view = Some(Arc::from(v));
                        self.profile.texture = None;
                    }
                    ProfileUpdate::Failed(e) => self.error(format!("shadow profile: {e}")),
                }
            }
            if finished {
                self.profile.worker = None;
            }
        }
        if self.profile.texture.is_none() {
            let img = match (self.profile.shown, &self.profile.result, &self.profile.view) {
                (ProfileShown::Profile, Some(p), _) => Some(profile_image(p)),
                (ProfileShown::HoursInShadow, Some(p), _) => {
                    Some(hours_image(p, HoursMetric::Shadow))
                }
                (ProfileShown::SunOnModel, _, Some(v)) => Some(view_image(v, HoursMetric::Sun)),
                _ => None,
            };
            if let Some(img) = img {
                let size = [img.width() as usize, img.height() as usize];
                let colour = egui::ColorImage::from_rgba_unmultiplied(size, img.as_raw());
                self.profile.texture =
                    Some(ctx.load_texture("shadow profile", colour, egui::TextureOptions::LINEAR));
            }
        }
    }

    fn radiosity_update(&mut self, u: RadiosityUpdate) {
        let r = &mut self.radiosity;
        match u {
            RadiosityUpdate::Prepared { elements, patches } => {
                r.elements = elements;
                r.status = format!("solving: {elements} elements, {patches} patches");
            }
            RadiosityUpdate::Progress {
                shots,
                seconds,
                convergence,
                light_map,
            } => {
                r.shots = shots;
                r.log.push([seconds, convergence]);
                if let Some(m) = light_map {
                    // The viewport swaps the texture (a new layout: the whole scene).
                    r.light_map = Some(m);
                }
            }
            RadiosityUpdate::Note(note) => r.status = note,
            RadiosityUpdate::Done(reason) => {
                r.status = format!("done: {reason}; waiting for changes");
                r.waiting = true;
            }
            RadiosityUpdate::Failed(e) => {
                r.status = format!("failed: {e}");
                self.error(format!("radiosity: {e}"));
            }
        }
    }
}
