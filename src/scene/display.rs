//! The one display model: the scene file's `[display]` ([`DisplayEntry`]), which the
//! command line's flags and the viewer's panel overlay ([`DisplayEntry::overlay`]), checked
//! by one validator ([`DisplayEntry::check`]) and turned into render settings by one
//! conversion (`render::RenderSettings::from_display`).

use super::file::{DisplayEntry, MAX_IMAGE_SIZE};
use super::palette::MAX_STEPS;

/// A `[display]` value out of range, named by its key (`display.width`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field} {value} {problem}")]
pub struct DisplayError {
    /// The key, `display.` and the field (`display.width`).
    pub field: &'static str,
    /// The value given.
    pub value: String,
    /// What is wrong with it.
    pub problem: String,
}

impl DisplayEntry {
    /// These settings with every value `over` gives in place of this one's.
    pub fn overlay(&self, over: &DisplayEntry) -> DisplayEntry {
        DisplayEntry {
            mode: over.mode.or(self.mode),
            tonemap: over.tonemap.or(self.tonemap),
            exposure: over.exposure.or(self.exposure),
            interp: over.interp.or(self.interp),
            width: over.width.or(self.width),
            height: over.height.or(self.height),
            lux_max: over.lux_max.or(self.lux_max),
            palette: over.palette.or(self.palette),
            steps: over.steps.or(self.steps),
            background: over.background.or(self.background),
            shadows: over.shadows.or(self.shadows),
            indirect: over.indirect.or(self.indirect),
        }
    }

    /// The first value out of range: a size outside 1..=[`MAX_IMAGE_SIZE`], an exposure
    /// or scale top that is not a positive number, colour bands outside 1..=[`MAX_STEPS`],
    /// a background colour that is not finite.
    pub fn check(&self) -> Result<(), DisplayError> {
        let error = |field, value: &dyn std::fmt::Display, problem: String| DisplayError {
            field,
            value: value.to_string(),
            problem,
        };
        for (field, v) in [
            ("display.width", self.width),
            ("display.height", self.height),
        ] {
            if let Some(v) = v.filter(|v| !(1..=MAX_IMAGE_SIZE).contains(v)) {
                return Err(error(field, &v, format!("is not in 1..={MAX_IMAGE_SIZE}")));
            }
        }
        for (field, v) in [
            ("display.exposure", self.exposure),
            ("display.lux_max", self.lux_max),
        ] {
            if let Some(v) = v.filter(|v| !(v.is_finite() && *v > 0.0)) {
                return Err(error(field, &v, "must be a positive number".into()));
            }
        }
        if let Some(n) = self.steps.filter(|n| !(1..=MAX_STEPS).contains(n)) {
            return Err(error(
                "display.steps",
                &n,
                format!("is not in 1..={MAX_STEPS}"),
            ));
        }
        if let Some(b) = self.background.filter(|b| !b.iter().all(|x| x.is_finite())) {
            return Err(error(
                "display.background",
                &format!("{b:?}"),
                "has a component that is not a finite number".into(),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::DisplayEntry;

    #[test]
    fn an_overlay_replaces_what_it_gives_and_keeps_the_rest() {
        let scene = DisplayEntry {
            width: Some(800),
            exposure: Some(0.5),
            steps: Some(8),
            ..Default::default()
        };
        let flags = DisplayEntry {
            width: Some(640),
            lux_max: Some(500.0),
            ..Default::default()
        };
        let d = scene.overlay(&flags);
        assert_eq!(
            (d.width, d.exposure, d.steps, d.lux_max, d.height),
            (Some(640), Some(0.5), Some(8), Some(500.0), None)
        );
    }

    #[test]
    fn the_check_names_the_first_key_out_of_range() {
        let said = |d: DisplayEntry| d.check().unwrap_err().to_string();
        assert_eq!(
            said(DisplayEntry {
                width: Some(0),
                ..Default::default()
            }),
            format!("display.width 0 is not in 1..={}", super::MAX_IMAGE_SIZE)
        );
        assert_eq!(
            said(DisplayEntry {
                lux_max: Some(-1.0),
                ..Default::default()
            }),
            "display.lux_max -1 must be a positive number"
        );
        assert!(said(DisplayEntry {
            steps: Some(0),
            ..Default::default()
        })
        .starts_with("display.steps 0 is not in 1..="));
        assert!(said(DisplayEntry {
            background: Some([0.0, f64::NAN, 0.0]),
            ..Default::default()
        })
        .starts_with("display.background"));
        assert!(DisplayEntry::default().check().is_ok());
    }
}
