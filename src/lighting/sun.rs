//! The sun as a light: the clear-sky direct normal illuminance at a solar elevation (IES
//! Lighting Handbook model) and a distant isotropic source that gives it across a scene.
//! The viewer lights its scene with it; the daylight work builds on it.

use glam::DVec3;

use crate::photometry::Luminaire;
use crate::scene::{PlacedLuminaire, Scene};
use crate::sun::SunPosition;

/// Extraterrestrial illuminance used by the clear-sky model, lux (IES Lighting
/// Handbook: 127.5 klx).
pub const EXTRATERRESTRIAL_LUX: f64 = 127_500.0;
/// Optical extinction coefficient of a clear sky (IES Lighting Handbook).
pub const CLEAR_SKY_EXTINCTION: f64 = 0.21;
/// The sun is placed this many scene radii away: its direction varies by less than
/// 0.06° and its illuminance by less than 0.2 % over the scene.
pub const SUN_DISTANCE_RADII: f64 = 1000.0;

/// Direct normal illuminance of a clear sky with the sun at `elevation_deg`, lux:
/// E = E_xt · exp(−c · m), air mass m = 1 / sin(elevation); 0 below the horizon.
pub fn clear_sky_direct_normal_lux(elevation_deg: f64) -> f64 {
    if elevation_deg <= 0.0 {
        return 0.0;
    }
    let air_mass = 1.0 / elevation_deg.to_radians().sin();
    EXTRATERRESTRIAL_LUX * (-CLEAR_SKY_EXTINCTION * air_mass).exp()
}

/// The clear-sky sun at `position` as a light for `scene` ([`sun_luminaire`] round the
/// centre of its bounds, giving [`clear_sky_direct_normal_lux`]); `None` when the sun is
/// below the horizon.
pub fn clear_sky_sun(scene: &Scene, position: &SunPosition) -> Option<PlacedLuminaire> {
    let lux = clear_sky_direct_normal_lux(position.elevation_deg);
    (lux > 0.0).then(|| {
        let (lo, hi) = scene.bounds();
        let radius = (hi - lo).length() / 2.0;
        sun_luminaire(
            DVec3::from_array(position.direction),
            lux,
            (lo + hi) / 2.0,
            radius,
        )
    })
}

/// An isotropic luminaire of 1000 cd (what the sun light is scaled from).
fn isotropic() -> Luminaire {
    crate::photometry::synthetic::rotational("sun", &[0.0, 90.0, 180.0], &[1000.0; 3])
        .expect("a constant positive intensity is a valid distribution")
}

/// The sun as a light for a scene centred at `center` of radius `radius` metres: an
/// isotropic source `SUN_DISTANCE_RADII` radii away toward `direction` giving
/// `normal_lux` on a surface facing it at the centre.
pub fn sun_luminaire(
    direction: DVec3,
    normal_lux: f64,
    center: DVec3,
    radius: f64,
) -> PlacedLuminaire {
    let distance = SUN_DISTANCE_RADII * radius.max(10.0);
    let mut sun = PlacedLuminaire::new(
        "sun",
        isotropic(),
        center + direction.normalize() * distance,
    );
    // 1000 cd × multiplier / d² = normal_lux.
    sun.multiplier = normal_lux * distance * distance / 1000.0;
    sun.color = DVec3::ONE;
    sun
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::Interp;

    #[test]
    fn clear_sky_model_matches_the_handbook_values() {
        // Zenith sun: 127.5 klx · e^−0.21 = 103.35 klx; 30°: air mass 2 → 83.8 klx.
        assert!((clear_sky_direct_normal_lux(90.0) - 103_350.0).abs() < 10.0);
        assert!((clear_sky_direct_normal_lux(30.0) - 83_779.0).abs() < 10.0);
        assert_eq!(clear_sky_direct_normal_lux(-1.0), 0.0);
    }

    #[test]
    fn sun_light_gives_the_normal_illuminance_at_the_centre() {
        let dir = DVec3::new(1.0, 0.5, 2.0).normalize();
        let sun = sun_luminaire(dir, 80_000.0, DVec3::new(3.0, 2.0, 0.0), 5.0);
        let to_sun = sun.position - DVec3::new(3.0, 2.0, 0.0);
        assert!((to_sun.normalize() - dir).length() < 1e-12);
        let cd = sun
            .luminaire
            .distribution
            .candela(0.0, 37.0, Interp::CatmullRom, sun.multiplier);
        let lux = cd / to_sun.length_squared();
        assert!((lux - 80_000.0).abs() < 1e-6 * 80_000.0, "{lux}");
        // The GPU texture says the same in every direction.
        for (c, g) in [(0.0, 0.0), (90.0, 45.0), (200.0, 120.0), (300.0, 180.0)] {
            let texel = sun.texture.sample(c, g, Interp::CatmullRom) * sun.candela_scale();
            assert!(
                (texel / cd - 1.0).abs() < 1e-6,
                "C{c} γ{g}: {texel} vs {cd}"
            );
        }
    }

    #[test]
    fn the_clear_sky_sun_lights_the_scene_from_its_direction_or_not_at_all() {
        let scene = Scene::load(&crate::io::data_root().join("assets/scenes/box_room.toml"))
            .expect("the bundled box room");
        let site = crate::sun::Site::new(48.21, 16.37, 0.0).unwrap();
        let at = |hour: u32| {
            let utc = chrono::NaiveDate::from_ymd_opt(2026, 6, 21)
                .unwrap()
                .and_hms_opt(hour, 0, 0)
                .unwrap()
                .and_utc();
            crate::sun::position(&site, utc, &crate::sun::SunOptions::default()).unwrap()
        };
        let up = at(11);
        assert!(up.elevation_deg > 60.0, "{}", up.elevation_deg);
        let sun = clear_sky_sun(&scene, &up).expect("the sun is up");
        let (lo, hi) = scene.bounds();
        let centre = (lo + hi) / 2.0;
        let to_sun = sun.position - centre;
        assert!((to_sun.normalize() - DVec3::from_array(up.direction)).length() < 1e-9);
        let lux = sun
            .luminaire
            .distribution
            .candela(0.0, 0.0, Interp::Bilinear, sun.multiplier)
            / to_sun.length_squared();
        let expected = clear_sky_direct_normal_lux(up.elevation_deg);
        assert!((lux / expected - 1.0).abs() < 1e-9, "{lux} vs {expected}");
        let midnight = at(23);
        assert!(midnight.elevation_deg < 0.0);
        assert!(clear_sky_sun(&scene, &midnight).is_none());
    }
}
