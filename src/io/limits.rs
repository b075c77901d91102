//! Bounds on the numbers a run accepts: time limits, and the budgets over a whole run
//! (points over all grids, bytes a study writes) that keep a typo from filling memory or
//! disk. Every limit is refused up front with the estimate and what raises it.

use std::time::Duration;

/// The longest time limit accepted, seconds (about 115 days).
pub const MAX_SECONDS: f64 = 1e7;

/// `seconds` as a duration: a positive, finite number of seconds up to [`MAX_SECONDS`];
/// the error says what is wrong (never a panic, unlike `Duration::from_secs_f64`).
pub fn duration(seconds: f64) -> Result<Duration, String> {
    if !(seconds.is_finite() && seconds > 0.0) {
        return Err(format!("{seconds} must be a positive number of seconds"));
    }
    if seconds > MAX_SECONDS {
        return Err(format!(
            "{seconds} s is more than the {MAX_SECONDS:e} s (about 115 days) accepted"
        ));
    }
    Duration::try_from_secs_f64(seconds).map_err(|e| format!("{seconds} s: {e}"))
}

/// The sum of the points over all grids one `calc` may compute (each grid holds at most
/// [`crate::scene::grid::MAX_POINTS`]): about 2.5 GB of memory and 1 GB of files.
pub const MAX_TOTAL_POINTS: usize = 4_000_000;

/// The most bytes one study or report may write before it is refused (estimated first).
pub const MAX_OUTPUT_BYTES: u64 = 2 << 30;

/// A byte count as people read it: "1.5 GB", "320 MB", "12 kB".
pub fn bytes(n: u64) -> String {
    match n {
        n if n >= 1 << 30 => format!("{:.1} GB", n as f64 / f64::from(1u32 << 30)),
        n if n >= 1 << 20 => format!("{:.0} MB", n as f64 / f64::from(1u32 << 20)),
        n if n >= 1 << 10 => format!("{:.0} kB", n as f64 / 1024.0),
        n => format!("{n} B"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_are_bounded_and_never_panic() {
        assert_eq!(duration(1.5).unwrap(), Duration::from_millis(1500));
        assert_eq!(duration(MAX_SECONDS).unwrap().as_secs(), 10_000_000);
        for bad in [
            0.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            2e19,
            1e20,
            MAX_SECONDS * 1.01,
        ] {
            assert!(duration(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn byte_counts_read_as_people_write_them() {
        assert_eq!(bytes(12), "12 B");
        assert_eq!(bytes(12 * 1024), "12 kB");
        assert_eq!(bytes(470 << 20), "470 MB");
        assert_eq!(bytes(3 << 30), "3.0 GB");
    }
}
