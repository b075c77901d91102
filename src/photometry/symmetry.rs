//! EULUMDAT symmetry types (Isym) and the plane bookkeeping they imply.

use serde::Serialize;

/// How the stored C planes expand to the full circle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Symmetry {
    /// Isym 0: every plane stored.
    None,
    /// Isym 1: one plane, rotationally symmetric about the vertical axis.
    Rotational,
    /// Isym 2: symmetric about the C0–C180 plane; C0 … C180 stored.
    C0C180,
    /// Isym 3: symmetric about the C90–C270 plane; C270 → C0 → C90 stored.
    C90C270,
    /// Isym 4: symmetric about both planes; C0 … C90 stored.
    Quadrant,
}

impl Symmetry {
    /// From the EULUMDAT indicator.
    pub fn from_isym(isym: u8) -> Option<Symmetry> {
        Some(match isym {
            0 => Symmetry::None,
            1 => Symmetry::Rotational,
            2 => Symmetry::C0C180,
            3 => Symmetry::C90C270,
            4 => Symmetry::Quadrant,
            _ => return None,
        })
    }

    /// The symmetry in words ("symmetric about the C0–C180 plane").
    pub fn describe(self) -> &'static str {
        match self {
            Symmetry::None => "no symmetry",
            Symmetry::Rotational => "rotationally symmetric",
            Symmetry::C0C180 => "symmetric about the C0–C180 plane",
            Symmetry::C90C270 => "symmetric about the C90–C270 plane",
            Symmetry::Quadrant => "symmetric about both planes",
        }
    }

    /// The EULUMDAT indicator.
    pub fn isym(self) -> u8 {
        match self {
            Symmetry::None => 0,
            Symmetry::Rotational => 1,
            Symmetry::C0C180 => 2,
            Symmetry::C90C270 => 3,
            Symmetry::Quadrant => 4,
        }
    }

    /// Whether `mc` planes of the full circle can be split as this symmetry needs.
    pub fn check_plane_count(self, mc: usize) -> Result<(), String> {
        let ok = match self {
            Symmetry::None | Symmetry::Rotational => mc >= 1,
            Symmetry::C0C180 => mc >= 2 && mc.is_multiple_of(2),
            Symmetry::C90C270 | Symmetry::Quadrant => mc >= 4 && mc.is_multiple_of(4),
        };
        if ok {
            Ok(())
        } else {
            Err(format!(
                "Mc = {mc} C planes cannot be split for Isym {} (needs a multiple of {})",
                self.isym(),
                match self {
                    Symmetry::C0C180 => 2,
                    Symmetry::C90C270 | Symmetry::Quadrant => 4,
                    _ => 1,
                }
            ))
        }
    }

    /// Indices (into the full circle of `mc` C angles) of the planes a file stores, in
    /// file order: Mc1 … Mc2 of the format, wrapping for Isym 3 (C270 → C0 → C90).
    pub fn stored_plane_indices(self, mc: usize) -> Vec<usize> {
        match self {
            Symmetry::None => (0..mc).collect(),
            Symmetry::Rotational => vec![0],
            Symmetry::C0C180 => (0..=mc / 2).collect(),
            Symmetry::C90C270 => (0..=mc / 2).map(|k| (3 * mc / 4 + k) % mc).collect(),
            Symmetry::Quadrant => (0..=mc / 4).collect(),
        }
    }

    /// The stored C angle whose plane equals the plane at `c` (degrees, any value).
    /// Rotational symmetry folds everything onto C0.
    pub fn fold(self, c: f64) -> f64 {
        let c = c.rem_euclid(360.0);
        match self {
            Symmetry::None => c,
            Symmetry::Rotational => 0.0,
            Symmetry::C0C180 => mirror_0_180(c),
            Symmetry::C90C270 => {
                if c <= 90.0 || c >= 270.0 {
                    c
                } else {
                    (180.0 - c).rem_euclid(360.0)
                }
            }
            Symmetry::Quadrant => {
                let h = mirror_0_180(c);
                if h <= 90.0 {
                    h
                } else {
                    180.0 - h
                }
            }
        }
    }
}

fn mirror_0_180(c: f64) -> f64 {
    if c <= 180.0 {
        c
    } else {
        360.0 - c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isym3_stores_c270_to_c90() {
        // 24 planes at 15°: stored 18, 19, …, 23, 0, …, 6 → C270 … C345, C0 … C90.
        let idx = Symmetry::C90C270.stored_plane_indices(24);
        assert_eq!(idx.len(), 13);
        assert_eq!(idx[0], 18);
        assert_eq!(idx[6], 0);
        assert_eq!(idx[12], 6);
    }

    #[test]
    fn folds_map_onto_stored_halves() {
        assert_eq!(Symmetry::C0C180.fold(200.0), 160.0);
        assert_eq!(Symmetry::C90C270.fold(100.0), 80.0);
        assert_eq!(Symmetry::C90C270.fold(200.0), 340.0);
        assert_eq!(Symmetry::C90C270.fold(300.0), 300.0);
        assert_eq!(Symmetry::Quadrant.fold(200.0), 20.0);
        assert_eq!(Symmetry::Quadrant.fold(350.0), 10.0);
        assert_eq!(Symmetry::Quadrant.fold(135.0), 45.0);
        assert_eq!(Symmetry::Rotational.fold(135.0), 0.0);
    }

    #[test]
    fn plane_counts() {
        assert!(Symmetry::C90C270.check_plane_count(36).is_ok());
        assert!(Symmetry::C90C270.check_plane_count(30).is_err());
        assert!(Symmetry::C0C180.check_plane_count(3).is_err());
        assert!(Symmetry::None.check_plane_count(0).is_err());
    }
}
