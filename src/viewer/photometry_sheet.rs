//! The photometry window's datasheet diagrams: the pictures `ldt plot` draws (polar,
//! cartesian, isocandela) from the same drawing code, shown as a texture beside the
//! interactive comparison of the interpolations.

use std::path::PathBuf;

use crate::photometry::datasheet_plot::{Diagram, DiagramKind};
use crate::photometry::Interp;
use crate::scene::placement::PlacedLuminaire;

/// What the photometry window shows.
#[derive(Default)]
pub struct PhotometryView {
    /// The C plane of the interpolation comparison, degrees.
    pub c_deg: f64,
    /// The datasheet diagram shown instead of the comparison, if one is chosen.
    pub sheet: Option<DiagramKind>,
    /// The datasheet picture on the GPU and what it shows.
    texture: Option<(SheetKey, egui::TextureHandle)>,
}

/// What a datasheet picture was drawn for.
#[derive(Debug, Clone, PartialEq)]
struct SheetKey {
    file: PathBuf,
    kind: DiagramKind,
    interp: Interp,
}

/// The choices of the window's view selector.
const VIEWS: [(Option<DiagramKind>, &str); 4] = [
    (None, "Interpolations"),
    (Some(DiagramKind::Polar), "Polar"),
    (Some(DiagramKind::Cartesian), "Cartesian"),
    (Some(DiagramKind::Isocandela), "Isocandela"),
];

/// The datasheet diagram of `l` exactly as `ldt plot FILE --kind KIND --interp INTERP
/// --out x.png` draws it (C0–C180 and C90–C270, all lamp sets' flux in the title).
pub fn datasheet_image(
    l: &PlacedLuminaire,
    kind: DiagramKind,
    interp: Interp,
) -> Result<egui::ColorImage, String> {
    let diagram = Diagram {
        lum: &l.luminaire,
        file_name: l
            .file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default(),
        planes: vec![0.0, 90.0],
        interp,
        lamp_flux_lm: None,
    };
    let img = diagram.rgb(kind).map_err(|e| e.to_string())?;
    let size = [img.width() as usize, img.height() as usize];
    Ok(egui::ColorImage::from_rgb(size, img.as_raw()))
}

impl PhotometryView {
    /// The view selector; true when a datasheet diagram is chosen.
    pub fn selector(&mut self, ui: &mut egui::Ui) -> bool {
        ui.horizontal(|ui| {
            for (sheet, label) in VIEWS {
                if ui.selectable_label(self.sheet == sheet, label).clicked() {
                    self.sheet = sheet;
                }
            }
        });
        self.sheet.is_some()
    }

    /// The chosen datasheet diagram of `l`, drawn once per file, kind and interpolation,
    /// scaled to the window's width.
    pub fn sheet_ui(&mut self, ui: &mut egui::Ui, l: &PlacedLuminaire, interp: Interp) {
        let Some(kind) = self.sheet else { return };
        let key = SheetKey {
            file: l.file.clone(),
            kind,
            interp,
        };
        if self.texture.as_ref().map(|(k, _)| k) != Some(&key) {
            match datasheet_image(l, kind, interp) {
                Ok(image) => {
                    let texture =
                        ui.ctx()
                            .load_texture("datasheet diagram", image, Default::default());
                    self.texture = Some((key, texture));
                }
                Err(e) => {
                    ui.label(format!("The diagram could not be drawn: {e}"));
                    return;
                }
            }
        }
        if let Some((_, texture)) = &self.texture {
            let size = texture.size_vec2();
            let width = ui.available_width().max(100.0);
            ui.image((texture.id(), size * (width / size.x)));
        }
    }

    /// The size of the datasheet picture held, pixels (None before one is drawn).
    pub fn sheet_size(&self) -> Option<[usize; 2]> {
        self.texture.as_ref().map(|(_, t)| t.size())
    }
}
