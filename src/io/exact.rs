//! serde helpers for fixed-length number arrays that refuse a wrong count: the TOML reader
//! fills `[f64; N]` from the first N numbers and drops the rest, so `corner = [0, 0, 5]`
//! would silently become `[0, 0]`. Use with `#[serde(deserialize_with = "…")]`.

use serde::de::Error;
use serde::{Deserialize, Deserializer};

/// N numbers, exactly.
struct Exact<const N: usize>([f64; N]);

impl<'de, const N: usize> Deserialize<'de> for Exact<N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        <[f64; N]>::try_from(v.as_slice())
            .map(Exact)
            .map_err(|_| D::Error::invalid_length(v.len(), &format!("{N} numbers").as_str()))
    }
}

/// An array of exactly N numbers.
pub fn array<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<[f64; N], D::Error> {
    Exact::<N>::deserialize(d).map(|e| e.0)
}

/// An optional array of exactly N numbers (pair with `#[serde(default)]`).
pub fn option<'de, D: Deserializer<'de>, const N: usize>(
    d: D,
) -> Result<Option<[f64; N]>, D::Error> {
    Option::<Exact<N>>::deserialize(d).map(|o| o.map(|e| e.0))
}

/// A list of arrays of exactly N numbers each.
pub fn vec<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<Vec<[f64; N]>, D::Error> {
    Vec::<Exact<N>>::deserialize(d).map(|v| v.into_iter().map(|e| e.0).collect())
}

/// An optional list of arrays of exactly N numbers each (pair with `#[serde(default)]`).
pub fn option_vec<'de, D: Deserializer<'de>, const N: usize>(
    d: D,
) -> Result<Option<Vec<[f64; N]>>, D::Error> {
    Option::<Vec<Exact<N>>>::deserialize(d).map(|o| o.map(|v| v.into_iter().map(|e| e.0).collect()))
}

#[cfg(test)]
mod tests {
    #[derive(Debug, serde::Deserialize)]
    struct T {
        #[serde(deserialize_with = "super::array")]
        a: [f64; 2],
        #[serde(default, deserialize_with = "super::option")]
        b: Option<[f64; 3]>,
        #[serde(default, deserialize_with = "super::option_vec")]
        c: Option<Vec<[f64; 2]>>,
    }

    #[test]
    fn extra_or_missing_numbers_are_refused() {
        let t: T = toml::from_str("a = [1, 2]\nc = [[1, 2], [3, 4]]").unwrap();
        assert_eq!((t.a, t.b), ([1.0, 2.0], None));
        assert_eq!(t.c.unwrap(), vec![[1.0, 2.0], [3.0, 4.0]]);
        for bad in [
            "a = [1, 2, 3]",
            "a = [1]",
            "a = [1, 2]\nb = [1, 2, 3, 4]",
            "a = [1, 2]\nc = [[1, 2, 5]]",
        ] {
            let e = toml::from_str::<T>(bad).unwrap_err().to_string();
            assert!(
                e.contains("invalid length") && e.contains("numbers"),
                "{bad}: {e}"
            );
        }
    }
}
