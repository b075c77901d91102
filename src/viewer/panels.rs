//! The viewer's frame in egui: the menu, the status bar, the side panel's sections and the
//! viewport, drawn from [`ViewerApp`]'s state (which lives in [`super::app`], free of egui
//! drawing).

use std::path::PathBuf;

use super::app::{Level, ViewerApp};

impl ViewerApp {
    /// Builds the whole UI for one frame.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        let dt = ctx.input(|i| i.stable_dt as f64).min(0.5);
        if self.sun.animate && self.sun.enabled {
            self.sun.advance(dt);
            self.revision += 1;
        }
        if self.effects_turning() {
            self.effects_time_s += dt;
            self.revision += 1;
        }
        self.poll_jobs(&ctx);
        self.poll_dialog();
        self.take_dropped_files(&ctx);
        egui::Panel::top("menu").show(ui, |ui| self.menu_bar(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        egui::Panel::left("controls")
            .resizable(true)
            .default_size(330.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| self.side_panel(ui));
            });
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.viewport(ui, dt));
        self.photometry_window(&ctx);
        self.profile_window(&ctx);
        if self.busy() {
            ctx.request_repaint_after(std::time::Duration::from_millis(50));
        }
    }

    fn side_panel(&mut self, ui: &mut egui::Ui) {
        egui::CollapsingHeader::new("Luminaires")
            .default_open(true)
            .show(ui, |ui| self.luminaires_panel(ui));
        egui::CollapsingHeader::new("Display")
            .default_open(true)
            .show(ui, |ui| self.display_panel(ui));
        egui::CollapsingHeader::new("Shadows")
            .default_open(false)
            .show(ui, |ui| self.shadows_panel(ui));
        egui::CollapsingHeader::new("Sun")
            .default_open(false)
            .show(ui, |ui| self.sun_panel(ui));
        egui::CollapsingHeader::new("Radiosity")
            .default_open(false)
            .show(ui, |ui| self.radiosity_panel(ui));
    }

    fn status_bar(&mut self, ui: &mut egui::Ui) {
        if let Some(m) = self.messages.last().cloned() {
            ui.horizontal(|ui| {
                let colour = match m.level {
                    Level::Error => ui.visuals().error_fg_color,
                    Level::Info => ui.visuals().text_color(),
                };
                ui.colored_label(colour, &m.text);
                if ui.small_button("dismiss").clicked() {
                    self.messages.pop();
                }
            });
        }
        ui.horizontal(|ui| {
            let s = &self.status;
            let fps = if s.frame_ms > 0.0 {
                1000.0 / s.frame_ms
            } else {
                0.0
            };
            ui.label(format!("frame {:.1} ms ({fps:.0} fps)", s.frame_ms));
            ui.separator();
            ui.label(format!("{} × {}", s.viewport_px[0], s.viewport_px[1]));
            ui.separator();
            match (s.cursor_lux, s.cursor_luminance) {
                (Some(lux), Some(l)) => {
                    ui.label(format!("{lux:.1} lx, {l:.2} cd/m² under the cursor"))
                }
                _ => ui.label("— lx"),
            };
            ui.separator();
            ui.label(&s.gpu);
            if let Some(w) = &self.radiosity.worker {
                ui.separator();
                let c = self.radiosity.log.last().map_or(0.0, |p| p[1]);
                use std::sync::atomic::Ordering::Relaxed;
                let state = match (
                    w.control.pause.load(Relaxed),
                    w.control.holding.load(Relaxed),
                ) {
                    (true, true) => "paused",
                    (true, false) => "pausing (the shot under way ends first)",
                    _ => "solving",
                };
                ui.label(format!("radiosity {state} {:.1} %", 100.0 * c));
            }
            if self.profile.worker.is_some() {
                ui.separator();
                let (d, t) = self.profile.progress;
                ui.label(format!("profile {d}/{t}"));
            }
        });
    }

    /// Everything dropped on the window: luminaires are added, a scene or model opened.
    fn take_dropped_files(&mut self, ctx: &egui::Context) {
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .filter(|p| !p.as_os_str().is_empty())
                .collect()
        });
        for path in dropped {
            self.open_any(&path);
        }
    }
}
