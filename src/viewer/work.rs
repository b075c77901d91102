//! The sun and radiosity panels: the site, date and time of the sun (its light and a
//! background shadow profile), and the progressive radiosity solver with its convergence
//! plot. The work they start runs in the background ([`super::background`]).

use egui_plot::{Line, Plot, PlotPoints};

use super::app::ProfileShown;
use super::app::ViewerApp;
use super::viewport_ui::parsed_field;
use crate::radiosity::gpu::Visibility;
use crate::radiosity::shooters::Hierarchy;
use crate::radiosity::view::Drive;
use crate::radiosity::{Ambient, FormFactorKind};
use crate::render::ShadowTechnique;

impl ViewerApp {
    /// Site, date, time (slider, animation), the sun light and the shadow profile.
    pub fn sun_panel(&mut self, ui: &mut egui::Ui) {
        let before = self.sun.clone();
        let s = &mut self.sun;
        if ui
            .checkbox(&mut s.enabled, "Sun lights the scene")
            .changed()
            && s.enabled
            && self.display.shadows.technique == ShadowTechnique::Paraboloid
        {
            // A paraboloid map around a light this far cannot resolve the scene.
            self.display.shadows.technique = ShadowTechnique::Volumes;
            self.messages.push(super::app::Message {
                level: super::app::Level::Info,
                text: "shadows switched to volumes: they are exact for the distant sun".into(),
            });
        }
        let s = &mut self.sun;
        egui::Grid::new("site").num_columns(2).show(ui, |ui| {
            let label = ui.label("Latitude (°N)");
            ui.add(
                egui::DragValue::new(&mut s.latitude)
                    .range(-90.0..=90.0)
                    .speed(0.05),
            )
            .labelled_by(label.id);
            ui.end_row();
            let label = ui.label("Longitude (°E)");
            ui.add(
                egui::DragValue::new(&mut s.longitude)
                    .range(-180.0..=180.0)
                    .speed(0.05),
            )
            .labelled_by(label.id);
            ui.end_row();
            let label = ui.label("Time zone");
            ui.text_edit_singleline(&mut s.zone).labelled_by(label.id);
            ui.end_row();
            parsed_field(
                ui,
                "Date",
                &mut s.date,
                |d| d.to_string(),
                |t| chrono::NaiveDate::parse_from_str(t, "%Y-%m-%d").ok(),
                100.0,
            );
            ui.end_row();
            let label = ui.label("North offset (°)");
            ui.add(egui::DragValue::new(&mut s.north_offset_deg).range(-180.0..=180.0))
                .labelled_by(label.id);
            ui.end_row();
        });
        ui.horizontal(|ui| {
            let label = ui.label(format!("Time {}", s.time_label()));
            ui.add(egui::Slider::new(&mut s.minutes, 0.0..=1439.0).show_value(false))
                .labelled_by(label.id);
        });
        ui.horizontal(|ui| {
            ui.checkbox(&mut s.animate, "Animate");
            ui.add(egui::Slider::new(&mut s.hours_per_second, 0.1..=6.0).text("h/s"));
        });
        match s.position() {
            Ok(p) => {
                let lux = crate::lighting::sun::clear_sky_direct_normal_lux(p.elevation_deg);
                ui.label(format!(
                    "azimuth {:.1}°, elevation {:.1}°, direct normal {:.0} lx (clear sky)",
                    p.azimuth_deg, p.elevation_deg, lux
                ));
            }
            Err(e) => {
                ui.colored_label(ui.visuals().error_fg_color, e);
            }
        }
        if self.sun != before && (self.sun.enabled || before.enabled) {
            self.lights_changed();
        }
        ui.separator();
        self.profile_controls(ui);
    }

    fn profile_controls(&mut self, ui: &mut egui::Ui) {
        ui.label("Shadow profile of the scene over the period");
        let s = &mut self.sun;
        ui.horizontal(|ui| {
            let time = |t: &chrono::NaiveTime| t.format("%H:%M").to_string();
            let parse = |t: &str| chrono::NaiveTime::parse_from_str(t, "%H:%M").ok();
            parsed_field(ui, "from", &mut s.profile_from, time, parse, 44.0);
            parsed_field(ui, "to", &mut s.profile_to, time, parse, 44.0);
            let label = ui.label("every");
            ui.add(
                egui::DragValue::new(&mut s.profile_step)
                    .range(1..=240)
                    .suffix(" min"),
            )
            .labelled_by(label.id);
        });
        ui.horizontal(|ui| {
            if let Some(w) = &self.profile.worker {
                let (d, t) = self.profile.progress;
                ui.add(
                    egui::ProgressBar::new(d as f32 / t.max(1) as f32)
                        .text(format!("{d}/{t} steps"))
                        .desired_width(160.0),
                );
                if ui.button("Cancel").clicked() {
                    w.cancel();
                }
            } else if ui.button("Compute shadow profile").clicked() {
                self.start_profile();
            }
        });
    }

    /// Settings, start / pause / reset, progress and the convergence plot.
    pub fn radiosity_panel(&mut self, ui: &mut egui::Ui) {
        let running = self.radiosity.worker.is_some();
        let r = &mut self.radiosity;
        ui.add_enabled_ui(!running, |ui| {
            let st = &mut r.settings;
            egui::Grid::new("radiosity settings")
                .num_columns(2)
                .show(ui, |ui| {
                    let label = ui.label("Texels per metre");
                    ui.add(egui::DragValue::new(&mut st.options.texel_density).range(1.0..=100.0))
                        .labelled_by(label.id);
                    ui.end_row();
                    let label = ui.label("Patch level");
                    ui.add(egui::Slider::new(&mut st.options.level, 0..=6))
                        .labelled_by(label.id);
                    ui.end_row();
                    let label = ui.label("Split at shadow edges (levels)");
                    ui.add(egui::Slider::new(&mut st.options.adaptive, 0..=3))
                        .labelled_by(label.id)
                        .on_hover_text(
                            "Adaptive subdivision: elements split up to this many times \
                             where a luminaire's shadow or beam edge crosses them",
                        );
                    ui.end_row();
                    let label = ui.label("Converge to");
                    ui.add(
                        egui::Slider::new(&mut st.options.converge, 0.5..=0.999).fixed_decimals(3),
                    )
                    .labelled_by(label.id);
                    ui.end_row();
                    choice_row(
                        ui,
                        "Visibility",
                        &mut st.options.visibility,
                        &[
                            (Visibility::Hemicube, "hemicube"),
                            (Visibility::Stereographic, "stereographic"),
                        ],
                    );
                    choice_row(
                        ui,
                        "Charts and shooters",
                        &mut st.options.hierarchy,
                        &[
                            (Hierarchy::Clusters, "face clusters"),
                            (Hierarchy::None, "every triangle"),
                        ],
                    );
                    choice_row(
                        ui,
                        "Form factor",
                        &mut st.options.form_factor,
                        &[
                            (FormFactorKind::Polygon, "polygon"),
                            (FormFactorKind::Disc, "disc"),
                        ],
                    );
                    choice_row(
                        ui,
                        "Driven by",
                        &mut st.options.drive,
                        &[
                            (Drive::Global, "whole scene"),
                            (Drive::Importance, "importance (view)"),
                            (Drive::Perspective, "perspective (view)"),
                        ],
                    );
                    let label = ui.label("Margin around the view (°)");
                    ui.add(egui::DragValue::new(&mut st.options.fov_margin).range(0.0..=90.0))
                        .labelled_by(label.id);
                    ui.end_row();
                    let label = ui.label("Solver ms per frame (0: all)");
                    ui.add(egui::DragValue::new(&mut st.frame_budget_ms).range(0.0..=1000.0))
                        .labelled_by(label.id);
                    ui.end_row();
                    choice_row(
                        ui,
                        "Ambient term",
                        &mut st.options.ambient,
                        &[
                            (Ambient::Display, "display"),
                            (Ambient::Overshoot, "overshoot"),
                            (Ambient::None, "none"),
                        ],
                    );
                });
        });
        ui.horizontal(|ui| {
            if !running {
                if ui.button("Start").clicked() {
                    self.start_radiosity();
                }
            } else {
                let label = if self.radiosity.paused {
                    "Resume"
                } else {
                    "Pause"
                };
                if ui.button(label).clicked() {
                    self.toggle_radiosity_pause();
                }
            }
            if ui.button("Reset").clicked() {
                self.reset_radiosity();
            }
        });
        let r = &self.radiosity;
        if !r.status.is_empty() {
            ui.label(&r.status);
        }
        if let Some(last) = r.log.last() {
            ui.label(format!(
                "{} shots, {:.2} % converged, {:.1} s, {} elements",
                r.shots,
                100.0 * last[1],
                last[0],
                r.elements
            ));
            Plot::new("convergence")
                .height(140.0)
                .include_y(0.0)
                .include_y(1.0)
                .x_axis_label("seconds")
                .y_axis_label("converged")
                .show(ui, |plot| {
                    plot.line(Line::new("converged", PlotPoints::from(r.log.clone())));
                });
        }
    }

    /// The shadow profile window.
    pub fn profile_window(&mut self, ctx: &egui::Context) {
        if !self.profile.open {
            return;
        }
        let mut open = true;
        let p = &mut self.profile;
        egui::Window::new("Shadow profile")
            .open(&mut open)
            .default_size([520.0, 560.0])
            .show(ctx, |ui| {
                ui.horizontal(|ui| {
                    for (shown, label) in [
                        (ProfileShown::Profile, "Profile"),
                        (ProfileShown::HoursInShadow, "Hours in shadow"),
                        (ProfileShown::SunOnModel, "Sun on the model"),
                    ] {
                        if ui.selectable_label(p.shown == shown, label).clicked() && p.shown != shown
                        {
                            p.shown = shown;
                            p.texture = None;
                        }
                    }
                });
                match (&p.texture, &p.result, &p.view) {
                    (Some(t), _, Some(v)) if p.shown == ProfileShown::SunOnModel => {
                        ui.label(format!(
                            "hours of sun on what the view showed when started ({:.1} h with the sun up)",
                            v.sun_up_h
                        ));
                        let [w, h] = t.size().map(|s| s as f32);
                        let width = ui.available_width().max(64.0);
                        ui.image((t.id(), egui::vec2(width, width * h / w)));
                    }
                    (Some(t), Some(r), _) if p.shown != ProfileShown::SunOnModel => {
                        ui.label(format!(
                            "{} steps, {} skipped (sun down), {:.0} m square",
                            r.steps.len(),
                            r.skipped.len(),
                            r.extent_m
                        ));
                        let side = ui.available_width().min(ui.available_height()).max(64.0);
                        ui.image((t.id(), egui::vec2(side, side)));
                    }
                    _ => {
                        ui.label("Compute one in the Sun panel.");
                    }
                }
            });
        self.profile.open = open;
    }
}

/// A grid row: `label`, then one selectable button per option setting `value`.
fn choice_row<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut T,
    options: &[(T, &str)],
) {
    ui.label(label);
    ui.horizontal(|ui| {
        for &(option, text) in options {
            ui.selectable_value(value, option, text);
        }
    });
    ui.end_row();
}
