//! The luminaires panel (add, place, aim, dim, colour, remove, interpolation) and the
//! photometry window (polar diagram with the measured points and every interpolation,
//! and the photometric summary; or a datasheet diagram, [`super::photometry_sheet`]).

use egui_plot::{Legend, Line, MarkerShape, Plot, PlotPoints, Points};

use super::app::ViewerApp;
use super::files::DialogPurpose;
use crate::photometry::datasheet_plot::plane_pair_curve;
use crate::photometry::{Interp, Luminaire};
use crate::scene::placement::LUMINANCE_WEIGHTS;

/// The interpolations offered, with their labels.
pub const INTERPOLATIONS: [(Interp, &str); 4] = [
    (Interp::Nearest, "nearest"),
    (Interp::Bilinear, "bilinear"),
    (Interp::CatmullRom, "Catmull-Rom"),
    (Interp::Monotone, "monotone"),
];

impl ViewerApp {
    /// The luminaires panel.
    pub fn luminaires_panel(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            if ui.button("Add luminaire…").clicked() {
                self.open_dialog(DialogPurpose::AddLuminaire);
            }
            ui.label("or drop files here");
        });
        ui.horizontal(|ui| {
            let label = ui.label("Path");
            ui.add(
                egui::TextEdit::singleline(&mut self.add_path)
                    .hint_text("a .ldt, .ies or TM-33 .xml/.json file")
                    .desired_width(170.0),
            )
            .labelled_by(label.id);
            if ui.button("Add").clicked() && !self.add_path.trim().is_empty() {
                let path = std::path::PathBuf::from(self.add_path.trim());
                if self.add_luminaire(&path) {
                    self.add_path.clear();
                }
            }
        });
        ui.horizontal(|ui| {
            let label = ui.label("Interpolation");
            let mut interp = self.display.light_model.interp();
            egui::ComboBox::from_id_salt("interp")
                .selected_text(label_of(interp))
                .show_ui(ui, |ui| {
                    for (i, label) in INTERPOLATIONS {
                        ui.selectable_value(&mut interp, i, label);
                    }
                })
                .response
                .labelled_by(label.id);
            if interp != self.display.light_model.interp() {
                self.display.light_model = crate::render::LightModel::Ldt(interp);
                self.lights_changed();
            }
        });
        ui.separator();
        for i in 0..self.scene.luminaires.len() {
            let name = format!("{}: {}", i + 1, self.scene.luminaires[i].name);
            let selected = self.selected == Some(i);
            if ui.selectable_label(selected, name).clicked() {
                self.selected = if selected { None } else { Some(i) };
            }
        }
        if let Some(i) = self.selected.filter(|&i| i < self.scene.luminaires.len()) {
            ui.separator();
            self.luminaire_editor(ui, i);
        }
    }

    fn luminaire_editor(&mut self, ui: &mut egui::Ui, i: usize) {
        let mut changed = false;
        let l = &mut self.scene.luminaires[i];
        ui.label(egui::RichText::new(&l.name).strong());
        ui.horizontal(|ui| {
            ui.label("Position (m)");
            let axes = [&mut l.position.x, &mut l.position.y, &mut l.position.z];
            for (v, axis) in axes.into_iter().zip(["x", "y", "z"]) {
                let label = ui.label(axis);
                changed |= ui
                    .add(egui::DragValue::new(v).speed(0.02).fixed_decimals(2))
                    .labelled_by(label.id)
                    .changed();
            }
        });
        let aim = &mut self.aims[i];
        egui::Grid::new("aim").num_columns(2).show(ui, |ui| {
            let label = ui.label("Tilt from down (°)");
            changed |= ui
                .add(egui::Slider::new(&mut aim.tilt_deg, 0.0..=180.0))
                .labelled_by(label.id)
                .changed();
            ui.end_row();
            let label = ui.label("Tilt heading (°)");
            changed |= ui
                .add(egui::Slider::new(&mut aim.azimuth_deg, -180.0..=180.0))
                .labelled_by(label.id)
                .changed();
            ui.end_row();
            let label = ui.label("Roll (°)");
            changed |= ui
                .add(egui::Slider::new(&mut aim.roll_deg, -180.0..=180.0))
                .labelled_by(label.id)
                .changed();
            ui.end_row();
            let label = ui.label("Dimming");
            changed |= ui
                .add(egui::Slider::new(&mut l.multiplier, 0.0..=2.0).fixed_decimals(2))
                .labelled_by(label.id)
                .changed();
            ui.end_row();
            ui.label("Colour");
            let peak = l.color.max_element().max(1e-9);
            let mut rgb = (l.color / peak).as_vec3().to_array();
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                let c = glam::Vec3::from_array(rgb).as_dvec3();
                let y = c.dot(LUMINANCE_WEIGHTS);
                if y > 1e-6 {
                    l.color = c / y;
                    changed = true;
                }
            }
            ui.end_row();
        });
        if changed {
            l.rotation = aim.rotation();
            self.lights_changed();
        }
        ui.horizontal(|ui| {
            if ui.button("Photometry…").clicked() {
                self.photometry = Some(i);
            }
            if ui.button("Remove").clicked() {
                self.remove_luminaire(i);
            }
        });
    }

    /// The photometry window of the luminaire chosen with "Photometry…".
    pub fn photometry_window(&mut self, ctx: &egui::Context) {
        let Some(i) = self.photometry.filter(|&i| i < self.scene.luminaires.len()) else {
            return;
        };
        let mut open = true;
        let l = &self.scene.luminaires[i];
        let title = format!("Photometry: {}", l.name);
        let view = &mut self.photometry_view;
        let interp = self.display.light_model.interp();
        egui::Window::new(title)
            .open(&mut open)
            .default_size([460.0, 560.0])
            .show(ctx, |ui| {
                if view.selector(ui) {
                    view.sheet_ui(ui, l, interp);
                } else {
                    photometry_contents(ui, &l.luminaire, &mut view.c_deg);
                }
            });
        if !open {
            self.photometry = None;
        }
    }
}

fn label_of(interp: Interp) -> &'static str {
    INTERPOLATIONS
        .iter()
        .find(|(i, _)| *i == interp)
        .map_or("?", |(_, l)| l)
}

/// The polar curve of the plane pair (c, c + 180°) in candela: x = ±I sin γ, y = −I cos γ
/// (down is γ = 0), the c half on the right — the geometry `ldt plot` draws too.
pub fn polar_curve(lum: &Luminaire, c_deg: f64, interp: Interp, step_deg: f64) -> Vec<[f64; 2]> {
    let d = &lum.distribution;
    plane_pair_curve(|c, g| d.candela(c, g, interp, 1.0), c_deg, step_deg)
}

/// The measured values on the plane pair (c, c + 180°) where c is a measured plane.
pub fn measured_points(lum: &Luminaire, c_deg: f64) -> Vec<[f64; 2]> {
    let grid = lum.distribution.grid();
    let scale = lum.distribution.lamp_flux_lm() / 1000.0;
    let mut out = Vec::new();
    for (ci, &c) in grid.c_angles().iter().enumerate() {
        let side = if crate::photometry::grid::angle_eq(c, c_deg) {
            1.0
        } else if crate::photometry::grid::angle_eq(c, c_deg + 180.0) {
            -1.0
        } else {
            continue;
        };
        for (gi, &g) in grid.gamma_angles().iter().enumerate() {
            let i = grid.value(ci, gi) * scale;
            out.push([side * i * g.to_radians().sin(), -i * g.to_radians().cos()]);
        }
    }
    out
}

fn photometry_contents(ui: &mut egui::Ui, lum: &Luminaire, c_deg: &mut f64) {
    let s = lum.summary();
    egui::Grid::new("summary").num_columns(2).show(ui, |ui| {
        let row = |ui: &mut egui::Ui, k: &str, v: String| {
            ui.label(k);
            ui.label(v);
            ui.end_row();
        };
        let pair = |p: &crate::photometry::summary::PlanePair| {
            let f = |v: Option<f64>| v.map_or("—".into(), |v| format!("{v:.1}°"));
            format!("{} (C0–C180), {} (C90–C270)", f(p.c0_c180), f(p.c90_c270))
        };
        row(ui, "Lamp flux", format!("{:.0} lm", s.lamp_flux_lm));
        row(ui, "Luminaire flux", format!("{:.0} lm", s.flux_lm));
        row(
            ui,
            "LOR",
            format!(
                "{:.1} % (declared {:.1} %)",
                s.lorl_computed, s.lorl_declared
            ),
        );
        row(
            ui,
            "Peak",
            format!(
                "{:.0} cd/klm at C {:.0}°, γ {:.0}°",
                s.max_intensity, s.max_direction_deg[0], s.max_direction_deg[1]
            ),
        );
        row(ui, "Beam angle (50 %)", pair(&s.beam_angle_deg));
        row(ui, "Field angle (10 %)", pair(&s.field_angle_deg));
    });
    ui.horizontal(|ui| {
        ui.label("C plane");
        for c in [0.0, 45.0, 90.0] {
            if ui
                .selectable_label(*c_deg == c, format!("C{c:.0}–C{:.0}", c + 180.0))
                .clicked()
            {
                *c_deg = c;
            }
        }
        let label = ui.label("C");
        ui.add(egui::DragValue::new(c_deg).range(0.0..=179.0).suffix("°"))
            .labelled_by(label.id);
    });
    let colours = [
        egui::Color32::from_rgb(230, 159, 0),
        egui::Color32::from_rgb(86, 180, 233),
        egui::Color32::from_rgb(0, 158, 115),
        egui::Color32::from_rgb(204, 121, 167),
    ];
    let c = *c_deg;
    Plot::new("polar")
        .data_aspect(1.0)
        .legend(Legend::default())
        .show(ui, |plot| {
            for ((interp, label), colour) in INTERPOLATIONS.iter().zip(colours) {
                let curve = polar_curve(lum, c, *interp, 0.5);
                plot.line(Line::new(*label, PlotPoints::from(curve)).color(colour));
            }
            plot.points(
                Points::new("measured", PlotPoints::from(measured_points(lum, c)))
                    .shape(MarkerShape::Circle)
                    .radius(2.5)
                    .color(egui::Color32::WHITE),
            );
        });
}
