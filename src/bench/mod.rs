//! Benchmarks behind `goniolight bench …`: each measures goniolight against a peer or a goal
//! side by side in one run and returns rows, and each builds its [`report::BenchReport`] (Markdown
//! tables or JSON) that the command prints.

pub mod adaptive;
pub mod clusters;
mod error;
pub mod radiosity;
pub mod radiosity_report;
pub mod radiosity_view;
pub mod radiosity_view_report;
pub mod raycast;
pub mod render;
pub mod report;
pub mod shadow_profile;
pub mod silhouette;

pub use error::BenchError;

/// The median of `v` (the mean of the two middle values for an even count); NaN when empty.
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn median_of_odd_even_and_empty() {
        assert_eq!(super::median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(super::median(vec![4.0, 1.0, 3.0, 2.0]), 2.5);
        assert!(super::median(Vec::new()).is_nan());
    }
}
