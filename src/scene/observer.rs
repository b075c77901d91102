//! `[[observer]]`: where a person's eye is and where it looks, for glare (UGR) at that
//! position (`goniolight calc`).
//!
//! ```toml
//! [[observer]]
//! name = "desk 1"
//! position = [1.5, 2.0, 1.2]    # the eye, metres (1.2 m seated, 1.6–1.7 m standing)
//! direction = [1.0, 0.0, 0.0]   # the line of sight (horizontal as CIE 117 assumes)
//! ```

use std::path::Path;

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::{finite_vec, SceneError};

/// `[[observer]]` as written in the scene file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ObserverEntry {
    /// The observer's name in reports.
    pub name: String,
    /// The eye, metres.
    #[serde(deserialize_with = "crate::io::exact::array")]
    pub position: [f64; 3],
    /// The line of sight (any length; not vertical).
    #[serde(deserialize_with = "crate::io::exact::array")]
    pub direction: [f64; 3],
}

/// An observer ready to rate: the eye and its frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Observer {
    /// The entry it came from.
    pub entry: ObserverEntry,
    /// The eye, metres.
    pub eye: DVec3,
    /// Unit line of sight.
    pub forward: DVec3,
    /// Unit direction to the eye's right, horizontal.
    pub right: DVec3,
    /// Unit direction up, across the line of sight.
    pub up: DVec3,
}

/// Steepest line of sight accepted, degrees from the horizontal: CIE 117's position index
/// is for a roughly horizontal line of sight.
pub const MAX_TILT_DEG: f64 = 45.0;

impl ObserverEntry {
    /// The observer, or an error naming the key (`observer[i].…`) that is wrong.
    pub fn resolve(&self, path: &Path, i: usize) -> Result<Observer, SceneError> {
        let key = |k: &str| format!("observer[{i}].{k}");
        if self.name.trim().is_empty() {
            return Err(SceneError::new(
                path,
                key("name"),
                "give the observer a name",
            ));
        }
        let eye = finite_vec(path, &key("position"), self.position)?;
        let d = finite_vec(path, &key("direction"), self.direction)?;
        let Some(forward) = crate::geometry::unit(d) else {
            return Err(SceneError::new(
                path,
                key("direction"),
                "the line of sight has no length",
            ));
        };
        let tilt = forward.z.asin().to_degrees();
        if tilt.abs() > MAX_TILT_DEG {
            return Err(SceneError::new(
                path,
                key("direction"),
                format!(
                    "the line of sight is {tilt:.0}° from the horizontal; UGR (CIE 117) rates a roughly horizontal view (at most {MAX_TILT_DEG}°)"
                ),
            ));
        }
        let right = forward.cross(DVec3::Z).normalize();
        let up = right.cross(forward);
        Ok(Observer {
            entry: self.clone(),
            eye,
            forward,
            right,
            up,
        })
    }
}

impl Observer {
    /// A point `p` as seen from the eye: (T across, H above, R ahead), metres.
    pub fn relative(&self, p: DVec3) -> (f64, f64, f64) {
        let d = p - self.eye;
        (d.dot(self.right), d.dot(self.up), d.dot(self.forward))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(direction: [f64; 3]) -> ObserverEntry {
        ObserverEntry {
            name: "o".into(),
            position: [1.0, 2.0, 1.2],
            direction,
        }
    }

    #[test]
    fn frame_is_right_handed_and_horizontal() {
        let o = entry([0.0, 2.0, 0.0])
            .resolve(Path::new("s.toml"), 0)
            .unwrap();
        assert_eq!(o.forward, DVec3::Y);
        assert!((o.right - DVec3::X).length() < 1e-12);
        assert!((o.up - DVec3::Z).length() < 1e-12);
        let (t, h, r) = o.relative(DVec3::new(2.0, 5.0, 3.2));
        assert!((t - 1.0).abs() < 1e-12 && (h - 2.0).abs() < 1e-12 && (r - 3.0).abs() < 1e-12);
    }

    #[test]
    fn steep_or_empty_views_are_refused_by_key() {
        for d in [[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.2, 0.0, -1.0]] {
            let e = entry(d).resolve(Path::new("s.toml"), 3).unwrap_err();
            assert!(e.to_string().contains("observer[3].direction"), "{e}");
        }
    }
}
