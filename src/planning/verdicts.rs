//! The pass/fail rules of the planning tests, each with its clause:
//!
//! - VSC (BRE 209 section 2.2, existing buildings): a window keeps enough skylight with a VSC of at least 27 %,
//!   or, against the existing situation, at least 0.8 times its former value.
//! - Sunlight to windows (BRE 209 section 3.2, existing buildings; for windows facing within 90° of due south —
//!   due north in the southern hemisphere): affected when the window gets less than 25 %
//!   APSH or less than 5 % WPSH, *and* less than 0.8 times its former hours in either
//!   period, *and* over the year loses more than 4 % of the annual probable sunlight hours.
//!   Without a baseline, only the first part is judged.
//! - EN 17037 sunlight exposure (clause 5.4 and Annex A): at least 1.5 h on the day is the
//!   minimum level.
//! - Gardens and open spaces (BRE 209 section 3.3): at least half of the area with 2 hours of
//!   sun on 21 March, or, against the existing situation, at least 0.8 times its former
//!   share.

use glam::DVec3;

use super::vsc::VSC_TARGET_PCT;
use super::{OpenSpaceFigures, WindowFigures};

/// Annual probable sunlight hours a window should get, per cent of the year's.
pub const APSH_TARGET_PCT: f64 = 25.0;
/// Winter probable sunlight hours a window should get, per cent of the year's.
pub const WPSH_TARGET_PCT: f64 = 5.0;
/// The share of its former value below which a loss is noticeable.
pub const FORMER_VALUE_RATIO: f64 = 0.8;
/// A year's loss of probable sunlight hours that counts, percentage points.
pub const APSH_LOSS_POINTS: f64 = 4.0;
/// The share of an open space that should get 2 hours of sun.
pub const OPEN_SPACE_SHARE: f64 = 0.5;
/// EN 17037's minimum level of sunlight exposure, hours.
pub const EN17037_MINIMUM_H: f64 = 1.5;

/// The verdicts of one window.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WindowVerdict {
    /// The VSC test.
    pub vsc: bool,
    /// The sunlight (APSH/WPSH) test; `None` without a weather file or for a window that
    /// does not face the sun's side (BRE 209 does not test those).
    pub sunlight: Option<bool>,
    /// EN 17037's minimum level of sunlight exposure.
    pub en17037: bool,
}

/// Whether a window facing `normal` faces within 90° of due south (due north for a site
/// south of the equator), in the scene's frame with true north `north_offset_deg` clockwise
/// from +Y.
pub fn faces_the_sun_side(normal: DVec3, latitude: f64, north_offset_deg: f64) -> bool {
    let north = crate::sun::direction_from_angles(0.0, 0.0, north_offset_deg);
    let towards_north = normal.truncate().dot(north.truncate());
    if latitude >= 0.0 {
        towards_north < 0.0
    } else {
        towards_north > 0.0
    }
}

/// The verdicts of a window with `now` and, given, its `former` figures.
pub fn judge_window(
    now: &WindowFigures,
    former: Option<&WindowFigures>,
    sun_side: bool,
) -> WindowVerdict {
    let vsc =
        now.vsc >= VSC_TARGET_PCT || former.is_some_and(|f| now.vsc >= FORMER_VALUE_RATIO * f.vsc);
    let sunlight = match (now.apsh, now.wpsh, sun_side) {
        (Some(apsh), Some(wpsh), true) => {
            let low = apsh < APSH_TARGET_PCT || wpsh < WPSH_TARGET_PCT;
            let affected = match former {
                Some(f) => {
                    let (fa, fw) = (f.apsh.unwrap_or(0.0), f.wpsh.unwrap_or(0.0));
                    low && (apsh < FORMER_VALUE_RATIO * fa || wpsh < FORMER_VALUE_RATIO * fw)
                        && fa - apsh > APSH_LOSS_POINTS
                }
                None => low,
            };
            Some(!affected)
        }
        _ => None,
    };
    WindowVerdict {
        vsc,
        sunlight,
        en17037: now.en17037_hours >= EN17037_MINIMUM_H - 1e-9,
    }
}

/// Whether an open space passes with `now` and, given, its `former` figures.
pub fn judge_open_space(now: &OpenSpaceFigures, former: Option<&OpenSpaceFigures>) -> bool {
    now.sunlit_fraction_2h >= OPEN_SPACE_SHARE - 1e-12
        || former
            .is_some_and(|f| now.sunlit_fraction_2h >= FORMER_VALUE_RATIO * f.sunlit_fraction_2h)
}

/// EN 17037's recommendation level for sunlight exposure reached with `hours` on the
/// chosen day (1 February … 21 March): "high" (≥ 4 h), "medium" (≥ 3 h), "minimum"
/// (≥ 1.5 h) or "none".
pub fn en17037_level(hours: f64) -> &'static str {
    const EPS: f64 = 1e-6;
    if hours >= 4.0 - EPS {
        "high"
    } else if hours >= 3.0 - EPS {
        "medium"
    } else if hours >= 1.5 - EPS {
        "minimum"
    } else {
        "none"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn window(vsc: f64, apsh: f64, wpsh: f64) -> WindowFigures {
        WindowFigures {
            vsc,
            apsh: Some(apsh),
            wpsh: Some(wpsh),
            en17037_hours: 2.0,
        }
    }

    #[test]
    fn vsc_passes_at_27_or_at_four_fifths_of_the_former_value() {
        assert!(judge_window(&window(27.0, 30.0, 8.0), None, true).vsc);
        assert!(!judge_window(&window(26.9, 30.0, 8.0), None, true).vsc);
        let former = window(30.0, 30.0, 8.0);
        assert!(judge_window(&window(24.0, 30.0, 8.0), Some(&former), true).vsc);
        assert!(!judge_window(&window(23.9, 30.0, 8.0), Some(&former), true).vsc);
    }

    #[test]
    fn sunlight_fails_only_when_low_and_reduced_and_the_loss_exceeds_four_points() {
        assert_eq!(
            judge_window(&window(30.0, 24.9, 8.0), None, true).sunlight,
            Some(false)
        );
        assert_eq!(
            judge_window(&window(30.0, 25.0, 5.0), None, true).sunlight,
            Some(true)
        );
        // Low and below 0.8× but a loss of only 4 points: not affected.
        let former = window(30.0, 18.0, 8.0);
        assert_eq!(
            judge_window(&window(30.0, 14.0, 8.0), Some(&former), true).sunlight,
            Some(true)
        );
        // Low, below 0.8×, a loss of 6 points: affected.
        let former = window(30.0, 20.0, 8.0);
        assert_eq!(
            judge_window(&window(30.0, 14.0, 8.0), Some(&former), true).sunlight,
            Some(false)
        );
        // Winter below 0.8× is enough with the annual loss.
        let former = window(30.0, 24.0, 6.0);
        assert_eq!(
            judge_window(&window(30.0, 19.5, 4.0), Some(&former), true).sunlight,
            Some(false)
        );
        // North-facing windows are not tested.
        assert_eq!(
            judge_window(&window(30.0, 1.0, 0.0), None, false).sunlight,
            None
        );
    }

    #[test]
    fn windows_on_the_sun_side() {
        assert!(faces_the_sun_side(DVec3::new(0.0, -1.0, 0.0), 51.5, 0.0));
        assert!(faces_the_sun_side(DVec3::new(1.0, -0.1, 0.0), 51.5, 0.0));
        assert!(!faces_the_sun_side(DVec3::new(0.0, 1.0, 0.0), 51.5, 0.0));
        assert!(faces_the_sun_side(DVec3::new(0.0, 1.0, 0.0), -33.9, 0.0));
        // True north 90° clockwise from +Y (+X is north): a window facing +X is on the sun side.
        assert!(faces_the_sun_side(DVec3::new(-1.0, 0.0, 0.0), 51.5, 90.0));
    }

    #[test]
    fn open_spaces_pass_at_half_or_four_fifths_of_the_former_share() {
        let f = |s| OpenSpaceFigures {
            hours: Vec::new(),
            sunlit_fraction_2h: s,
        };
        assert!(judge_open_space(&f(0.5), None));
        assert!(!judge_open_space(&f(0.49), None));
        assert!(judge_open_space(&f(0.4), Some(&f(0.5))));
        assert!(!judge_open_space(&f(0.39), Some(&f(0.5))));
    }
}
