//! A sky for an instant: a luminance distribution ([`SkyDistribution`]) scaled to a diffuse
//! horizontal illuminance, the sun as a 0.53° disc scaled to its direct illuminance, and
//! the ground below the horizon as a uniform luminance ρ_g·E_h/π. Directions are in the
//! scene's frame (+Z up; the sun's direction already turned by the site's north offset).

use std::f64::consts::PI;

use glam::DVec3;

use super::cie_sky::SkyDistribution;

/// The sun's angular diameter, degrees.
pub const SUN_DIAMETER_DEG: f64 = 0.53;

/// Default ground reflectance ρ_g.
pub const DEFAULT_GROUND_REFLECTANCE: f64 = 0.2;

/// How the sun's direct illuminance is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SunIlluminance {
    /// On a plane facing the sun, lux.
    Normal(f64),
    /// On the horizontal plane, lux.
    Horizontal(f64),
}

/// The sun as a light: its direction and its direct normal illuminance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    /// Unit vector toward the sun's centre.
    pub direction: DVec3,
    /// Illuminance on a plane facing the sun, lux.
    pub normal_lux: f64,
}

/// A sky and sun for one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct Sky {
    /// The angular shape.
    pub distribution: SkyDistribution,
    /// Unit vector toward the sun (what the distribution is shaped round; `None` for skies
    /// that do not depend on it and no time was given).
    pub sun_direction: Option<DVec3>,
    /// Zenith luminance, cd/m².
    pub zenith_luminance: f64,
    /// The sky's illuminance on the unobstructed horizontal plane, lux (the sun excluded).
    pub diffuse_horizontal_lux: f64,
    /// The sun, where it shines.
    pub sun: Option<Sun>,
    /// Ground reflectance ρ_g.
    pub ground_reflectance: f64,
    /// Luminance of the ground below the horizon, cd/m².
    pub ground_luminance: f64,
}

/// The inputs of [`Sky::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkyInput {
    /// The angular shape.
    pub distribution: SkyDistribution,
    /// Unit vector toward the sun, if known.
    pub sun_direction: Option<DVec3>,
    /// Diffuse horizontal illuminance the sky gives, lux.
    pub diffuse_horizontal_lux: f64,
    /// The sun's direct illuminance, if it shines.
    pub sun: Option<SunIlluminance>,
    /// Ground reflectance ρ_g.
    pub ground_reflectance: f64,
}

impl Sky {
    /// The sky of `input`, checked: illuminances finite and ≥ 0, ρ_g in [0, 1], the sun's
    /// direction known (and above the horizon) where the distribution or a direct
    /// illuminance needs it. The message names the field.
    pub fn new(input: SkyInput) -> Result<Sky, (&'static str, String)> {
        let SkyInput {
            distribution,
            sun_direction,
            diffuse_horizontal_lux,
            sun,
            ground_reflectance,
        } = input;
        if !(diffuse_horizontal_lux.is_finite() && diffuse_horizontal_lux >= 0.0) {
            return Err((
                "diffuse_horizontal_lux",
                format!("{diffuse_horizontal_lux} is not a finite illuminance ≥ 0 lux"),
            ));
        }
        if !(0.0..=1.0).contains(&ground_reflectance) {
            return Err((
                "ground_reflectance",
                format!("{ground_reflectance} is outside [0, 1]"),
            ));
        }
        let above = sun_direction.filter(|d| d.z > 0.0);
        if distribution.needs_sun() && above.is_none() {
            return Err((
                "model",
                format!(
                    "sky \"{}\" is shaped round the sun, which needs a site and a time with \
                     the sun above the horizon{}",
                    distribution.name(),
                    if sun_direction.is_some() {
                        " (at that time it is below it)"
                    } else {
                        ""
                    }
                ),
            ));
        }
        let sun = sun_of(sun, above)?;
        let integral = horizontal_integral(distribution, sun_direction);
        let global = diffuse_horizontal_lux + sun.map_or(0.0, |s| s.normal_lux * s.direction.z);
        Ok(Sky {
            distribution,
            sun_direction,
            zenith_luminance: diffuse_horizontal_lux / integral,
            diffuse_horizontal_lux,
            sun,
            ground_reflectance,
            ground_luminance: ground_reflectance * global / PI,
        })
    }

    /// Luminance of the sky (above the horizon) or the ground (below it) seen along the
    /// unit vector `dir`, cd/m²; the sun's disc is not included ([`Sky::sun`]).
    pub fn luminance(&self, dir: DVec3) -> f64 {
        if dir.z <= 0.0 {
            return self.ground_luminance;
        }
        self.zenith_luminance * relative(self.distribution, self.sun_direction, dir)
    }

    /// Global horizontal illuminance (sky and sun) on the unobstructed horizontal plane, lux.
    pub fn global_horizontal_lux(&self) -> f64 {
        self.diffuse_horizontal_lux + self.sun.map_or(0.0, |s| s.normal_lux * s.direction.z)
    }
}

/// The sun of the direct illuminance `given` with its direction `above` the horizon.
fn sun_of(
    given: Option<SunIlluminance>,
    above: Option<DVec3>,
) -> Result<Option<Sun>, (&'static str, String)> {
    let (field, lux) = match given {
        None => return Ok(None),
        Some(SunIlluminance::Normal(v)) => ("direct_normal_lux", v),
        Some(SunIlluminance::Horizontal(v)) => ("direct_horizontal_lux", v),
    };
    if !(lux.is_finite() && lux >= 0.0) {
        return Err((field, format!("{lux} is not a finite illuminance ≥ 0 lux")));
    }
    if lux == 0.0 {
        return Ok(None);
    }
    let Some(direction) = above else {
        return Err((
            field,
            format!("{lux} lux of sun needs a site and a time with the sun above the horizon"),
        ));
    };
    let normal_lux = match given {
        Some(SunIlluminance::Horizontal(_)) => lux / direction.z,
        _ => lux,
    };
    Ok(Some(Sun {
        direction,
        normal_lux,
    }))
}

/// Luminance relative to the zenith's along `dir` (above the horizon).
fn relative(distribution: SkyDistribution, sun: Option<DVec3>, dir: DVec3) -> f64 {
    let z = dir.z.clamp(-1.0, 1.0).acos();
    let (chi, z_sun) = sun.map_or((0.0, 0.0), |s| {
        (
            dir.dot(s).clamp(-1.0, 1.0).acos(),
            s.z.clamp(-1.0, 1.0).acos(),
        )
    });
    distribution.relative_luminance(z, chi, z_sun)
}

/// Cells of [`horizontal_integral`] along cos Z and the azimuth.
const INTEGRAL_CELLS: (usize, usize) = (400, 800);

/// ∫ (L/L_z) cos Z dω over the sky hemisphere: the horizontal illuminance of a sky of unit
/// zenith luminance. Midpoint rule in (cos Z, azimuth), where cos Z dω = cos Z d(cos Z)
/// d(azimuth): smooth in cos Z for every sky (the gradation's exp(b / cos Z) flattens at
/// the horizon).
pub fn horizontal_integral(distribution: SkyDistribution, sun: Option<DVec3>) -> f64 {
    if distribution == SkyDistribution::Uniform {
        return PI;
    }
    let (n_r, n_a) = INTEGRAL_CELLS;
    let mut sum = 0.0;
    for i in 0..n_r {
        let cos_z = (i as f64 + 0.5) / n_r as f64;
        let sin_z = (1.0 - cos_z * cos_z).sqrt();
        for j in 0..n_a {
            let a = 2.0 * PI * (j as f64 + 0.5) / n_a as f64;
            let dir = DVec3::new(sin_z * a.cos(), sin_z * a.sin(), cos_z);
            sum += cos_z * relative(distribution, sun, dir);
        }
    }
    2.0 * PI * sum / (n_r * n_a) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sun_at(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
        crate::sun::direction_from_angles(azimuth_deg, elevation_deg, 0.0)
    }

    /// Analytic: a uniform sky of luminance L gives πL; the CIE overcast sky 7πL_z/9.
    #[test]
    fn overcast_and_uniform_skies_integrate_to_their_closed_forms() {
        let overcast = horizontal_integral(SkyDistribution::CieOvercast, None);
        assert!((overcast - 7.0 * PI / 9.0).abs() < 1e-5, "{overcast}");
        let sky = Sky::new(SkyInput {
            distribution: SkyDistribution::CieOvercast,
            sun_direction: None,
            diffuse_horizontal_lux: 10_000.0,
            sun: None,
            ground_reflectance: 0.2,
        })
        .unwrap();
        assert!((sky.zenith_luminance - 10_000.0 * 9.0 / (7.0 * PI)).abs() < 0.01);
        assert!(
            (sky.luminance(DVec3::X * 0.999 + DVec3::Z * 0.0447) / sky.zenith_luminance
                - (1.0 + 2.0 * 0.0447) / 3.0)
                .abs()
                < 1e-3
        );
        assert!((sky.ground_luminance - 0.2 * 10_000.0 / PI).abs() < 1e-9);
    }

    /// Every general sky's horizontal integral against an independent quadrature:
    /// composite Simpson in the zenith angle and the azimuth (120 × 240 intervals), with
    /// the sun low, middle and high.
    #[test]
    fn general_skies_integrate_as_an_independent_quadrature_does() {
        let (nz, na) = (120usize, 240usize);
        let simpson = |k: usize, n: usize| match k {
            0 => 1.0,
            _ if k == n => 1.0,
            _ if k % 2 == 1 => 4.0,
            _ => 2.0,
        };
        let (hz, ha) = (PI / 2.0 / nz as f64, 2.0 * PI / na as f64);
        for n in 1..=15u8 {
            let d = SkyDistribution::CieGeneral(n);
            for elevation in [10.0, 35.0, 70.0] {
                let sun = sun_at(elevation, 160.0);
                let mut reference = 0.0;
                for i in 0..=nz {
                    let z = i as f64 * hz;
                    for j in 0..=na {
                        let a = j as f64 * ha;
                        let dir = DVec3::new(z.sin() * a.cos(), z.sin() * a.sin(), z.cos());
                        let w = simpson(i, nz) * simpson(j, na) * hz * ha / 9.0;
                        reference += w * relative(d, Some(sun), dir) * z.cos() * z.sin();
                    }
                }
                let ours = horizontal_integral(d, Some(sun));
                assert!(
                    (ours / reference - 1.0).abs() < 1e-4,
                    "type {n}, sun at {elevation}°: {ours} vs {reference}"
                );
            }
        }
    }

    #[test]
    fn the_sun_is_given_normal_or_horizontal_and_lights_the_ground() {
        let sun = sun_at(30.0, 180.0);
        let input = SkyInput {
            distribution: SkyDistribution::CieGeneral(12),
            sun_direction: Some(sun),
            diffuse_horizontal_lux: 15_000.0,
            sun: Some(SunIlluminance::Horizontal(40_000.0)),
            ground_reflectance: 0.2,
        };
        let sky = Sky::new(input).unwrap();
        let s = sky.sun.unwrap();
        assert!((s.normal_lux - 80_000.0).abs() < 1e-6, "sin 30° = 0.5");
        assert!((sky.global_horizontal_lux() - 55_000.0).abs() < 1e-6);
        assert!((sky.ground_luminance - 0.2 * 55_000.0 / PI).abs() < 1e-6);
        let below = SkyInput {
            sun_direction: Some(sun_at(-5.0, 180.0)),
            ..input
        };
        let (field, message) = Sky::new(below).unwrap_err();
        assert_eq!(field, "model");
        assert!(message.contains("below"), "{message}");
        let overcast_sun = SkyInput {
            distribution: SkyDistribution::CieOvercast,
            sun_direction: None,
            ..input
        };
        assert_eq!(
            Sky::new(overcast_sun).unwrap_err().0,
            "direct_horizontal_lux"
        );
        let bad = SkyInput {
            ground_reflectance: 1.5,
            ..input
        };
        assert_eq!(Sky::new(bad).unwrap_err().0, "ground_reflectance");
    }
}
