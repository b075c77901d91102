//! The display and shadow panels and the viewport: the rendered image, mouse and key
//! control of the camera, the lux read-out under the cursor and the false-colour legend.

use super::app::ViewerApp;
use super::camera::CameraMode;
use crate::render::legend::format_lux;
use crate::render::tonemap::scale_labels;
use crate::render::{ShadowTechnique, VolumeTest};
use crate::scene::{Mode, Palette, Tonemap};
use crate::shadow::SilhouetteMethod;

impl ViewerApp {
    /// Display mode, tone mapping, false-colour scale and screenshots.
    pub fn display_panel(&mut self, ui: &mut egui::Ui) {
        let d = &mut self.display;
        ui.horizontal(|ui| {
            ui.selectable_value(&mut d.mode, Mode::Shaded, "Shaded");
            ui.selectable_value(&mut d.mode, Mode::Illuminance, "False-colour lux");
        });
        match d.mode {
            Mode::Shaded => {
                ui.horizontal(|ui| {
                    ui.label("Tone mapping");
                    ui.selectable_value(&mut d.tonemap, Tonemap::Reinhard, "Reinhard");
                    ui.selectable_value(&mut d.tonemap, Tonemap::Exposure, "Exposure");
                });
                if d.tonemap == Tonemap::Exposure {
                    optional_value(
                        ui,
                        "Exposure k (1/(cd/m²))",
                        &mut d.exposure,
                        0.05,
                        1e-4..=100.0,
                        true,
                    );
                }
            }
            Mode::Illuminance => {
                optional_value(
                    ui,
                    "Scale top (lx)",
                    &mut d.lux_max,
                    500.0,
                    1.0..=1e6,
                    false,
                );
                egui::ComboBox::from_label("Palette")
                    .selected_text(d.palette.name())
                    .show_ui(ui, |ui| {
                        for p in Palette::ALL {
                            ui.selectable_value(&mut d.palette, p, p.name());
                        }
                    });
                ui.add(egui::Slider::new(&mut d.steps, 0..=12).text("Steps (0: smooth)"));
            }
        }
        ui.horizontal(|ui| {
            let label = ui.label("File");
            ui.add(egui::TextEdit::singleline(&mut self.screenshot_path).desired_width(140.0))
                .labelled_by(label.id);
            if ui
                .button("Screenshot")
                .on_hover_text("the view as PNG and, beside it, EXR (luminance, lux in alpha)")
                .clicked()
            {
                self.requests.screenshot = Some(self.screenshot_path.trim().into());
            }
        });
    }

    /// Technique, volume test, silhouettes, debug views.
    pub fn shadows_panel(&mut self, ui: &mut egui::Ui) {
        let s = &mut self.display.shadows;
        ui.horizontal(|ui| {
            ui.selectable_value(&mut s.technique, ShadowTechnique::None, "None");
            ui.selectable_value(
                &mut s.technique,
                ShadowTechnique::Paraboloid,
                "Paraboloid maps",
            );
            ui.selectable_value(&mut s.technique, ShadowTechnique::Volumes, "Volumes");
        });
        match s.technique {
            ShadowTechnique::Volumes => {
                ui.horizontal(|ui| {
                    ui.label("Stencil test");
                    ui.selectable_value(&mut s.volume_test, VolumeTest::Auto, "auto");
                    ui.selectable_value(&mut s.volume_test, VolumeTest::Zpass, "z-pass");
                    ui.selectable_value(&mut s.volume_test, VolumeTest::Zfail, "z-fail");
                });
                ui.horizontal(|ui| {
                    ui.label("Silhouettes");
                    ui.selectable_value(&mut s.silhouette, SilhouetteMethod::Brute, "brute force");
                    ui.selectable_value(&mut s.silhouette, SilhouetteMethod::Hextree, "hextree");
                });
                ui.checkbox(&mut s.show_volumes, "Show volumes");
                ui.checkbox(&mut s.show_silhouettes, "Show silhouettes");
            }
            ShadowTechnique::Paraboloid => {
                ui.horizontal(|ui| {
                    ui.label("Map size");
                    for size in [512, 1024, 2048] {
                        ui.selectable_value(&mut s.map_size, size, size.to_string());
                    }
                });
            }
            ShadowTechnique::None => {}
        }
    }

    /// The central area: the rendered view, camera control and overlays.
    pub fn viewport(&mut self, ui: &mut egui::Ui, dt: f64) {
        let rect = ui.max_rect();
        let ppp = ui.ctx().pixels_per_point();
        let px = |v: f32| (v * ppp).round().max(1.0) as u32;
        self.status.viewport_px = [px(rect.width()), px(rect.height())];
        self.status.viewport_rect_px = [
            (rect.min.x * ppp).round() as u32,
            (rect.min.y * ppp).round() as u32,
            px(rect.width()),
            px(rect.height()),
        ];
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        if let Some(id) = self.viewport_texture {
            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter().image(id, rect, uv, egui::Color32::WHITE);
        }
        self.camera_input(ui, &response, dt);
        self.status.cursor_px = response.hover_pos().map(|p| {
            let v = (p - rect.min) * ppp;
            [v.x.max(0.0) as u32, v.y.max(0.0) as u32]
        });
        if self.display.mode == Mode::Illuminance {
            draw_legend(
                ui,
                rect,
                self.status.lux_max,
                (self.display.palette, self.display.steps),
            );
        }
        let emissive = self
            .scene
            .materials
            .iter()
            .any(|m| m.emission.max_element() > 0.0);
        if self.scene.luminaires.is_empty() && !self.sun.enabled && !emissive {
            let hint = egui::Rect::from_center_size(rect.center(), egui::vec2(rect.width(), 40.0));
            ui.put(
                hint,
                egui::Label::new(
                    egui::RichText::new(
                        "No lights: add a luminaire (drop an .ldt, .ies or TM-33 file here) or turn on the sun",
                    )
                    .size(16.0)
                    .color(egui::Color32::from_gray(220)),
                ),
            );
        }
    }

    fn camera_input(&mut self, ui: &egui::Ui, response: &egui::Response, dt: f64) {
        let cam = &mut self.camera;
        let d = response.drag_delta();
        let (dx, dy) = (d.x as f64, d.y as f64);
        if response.dragged_by(egui::PointerButton::Primary) {
            cam.rotate(dx, dy);
        } else if response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
        {
            cam.pan(dx, dy, response.rect.height() as f64);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y) as f64;
            if scroll != 0.0 {
                cam.zoom(scroll / 50.0);
            }
        }
        if cam.mode == CameraMode::Fly && !ui.ctx().egui_wants_keyboard_input() {
            let key = |k| {
                if ui.input(|i| i.key_down(k)) {
                    1.0
                } else {
                    0.0
                }
            };
            use egui::Key;
            let forward = key(Key::W) - key(Key::S);
            let right = key(Key::D) - key(Key::A);
            let up = key(Key::E) - key(Key::Q);
            if forward != 0.0 || right != 0.0 || up != 0.0 {
                cam.fly(forward, right, up, dt);
                ui.ctx().request_repaint();
            }
        }
    }
}

/// A text field for a value of type `T`: the text being typed is kept (in egui's
/// memory) until it parses, so partial input is not thrown away.
pub fn parsed_field<T>(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut T,
    show: impl Fn(&T) -> String,
    parse: impl Fn(&str) -> Option<T>,
    width: f32,
) -> egui::Response {
    let label = ui.label(label);
    let id = label.id.with("text");
    let mut text = ui
        .data_mut(|d| d.get_temp::<String>(id))
        .unwrap_or_else(|| show(value));
    let response = ui
        .add(
            egui::TextEdit::singleline(&mut text)
                .id(id)
                .desired_width(width),
        )
        .labelled_by(label.id);
    if let Some(v) = parse(text.trim()) {
        if response.changed() {
            *value = v;
        }
    }
    if response.has_focus() {
        ui.data_mut(|d| d.insert_temp(id, text));
    } else {
        ui.data_mut(|d| d.remove::<String>(id));
    }
    response
}

/// A value with an "auto" box: `None` when automatic.
fn optional_value(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut Option<f64>,
    default: f64,
    range: std::ops::RangeInclusive<f64>,
    logarithmic: bool,
) {
    ui.horizontal(|ui| {
        let mut auto = value.is_none();
        if ui.checkbox(&mut auto, "auto").changed() {
            *value = if auto { None } else { Some(default) };
        }
        let label = ui.label(label);
        if let Some(v) = value {
            ui.add(egui::Slider::new(v, range).logarithmic(logarithmic))
                .labelled_by(label.id);
        }
    });
}

/// The false-colour scale at the viewport's right edge.
fn draw_legend(ui: &egui::Ui, rect: egui::Rect, lux_max: f64, (palette, steps): (Palette, u32)) {
    let bar = egui::Rect::from_min_size(
        egui::pos2(rect.max.x - 90.0, rect.min.y + 20.0),
        egui::vec2(18.0, (rect.height() - 40.0).clamp(40.0, 300.0)),
    );
    let p = ui.painter();
    p.rect_filled(
        bar.expand2(egui::vec2(6.0, 10.0))
            .with_max_x(rect.max.x - 8.0),
        4.0,
        egui::Color32::from_black_alpha(160),
    );
    let steps_drawn = 64;
    for k in 0..steps_drawn {
        let t0 = k as f32 / steps_drawn as f32;
        let c = palette.stepped_colour(1.0 - t0 - 0.5 / steps_drawn as f32, steps);
        let colour = egui::Color32::from_rgb(
            crate::render::tonemap::linear_to_srgb(c.x),
            crate::render::tonemap::linear_to_srgb(c.y),
            crate::render::tonemap::linear_to_srgb(c.z),
        );
        let y0 = bar.min.y + bar.height() * t0;
        let y1 = bar.min.y + bar.height() * (k + 1) as f32 / steps_drawn as f32;
        p.rect_filled(
            egui::Rect::from_x_y_ranges(bar.x_range(), y0..=y1),
            0.0,
            colour,
        );
    }
    for v in scale_labels(lux_max, steps) {
        let y = bar.max.y - bar.height() * (v / lux_max) as f32;
        p.text(
            egui::pos2(bar.max.x + 4.0, y),
            egui::Align2::LEFT_CENTER,
            format!("{} lx", format_lux(v)),
            egui::FontId::proportional(11.0),
            egui::Color32::WHITE,
        );
    }
}
