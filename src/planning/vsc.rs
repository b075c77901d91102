//! The vertical sky component (BRE 209 section 2.2): the illuminance a window's reference point
//! receives straight from a CIE standard overcast sky, on the plane of the window, over
//! the simultaneous illuminance on an unobstructed horizontal plane, per cent — no light
//! reflected by the ground or the buildings. An unobstructed vertical window gets 39.6 %.

use crate::daylight::cie_sky::SkyDistribution;
use crate::daylight::points::{daylight_at_points, Obstructions, HEMISPHERE_CELLS};
use crate::daylight::sky::{Sky, SkyInput};
use crate::lighting::SurfacePoint;
use crate::scene::planning::Window;

/// BRE 209's test: a window with at least this VSC keeps enough skylight, per cent.
pub const VSC_TARGET_PCT: f64 = 27.0;

/// The sky of the vertical sky component: the traditional CIE overcast sky, no ground.
fn overcast_sky() -> Sky {
    Sky::new(SkyInput {
        distribution: SkyDistribution::CieOvercast,
        sun_direction: None,
        // Per cent of the unobstructed horizontal illuminance, directly.
        diffuse_horizontal_lux: 100.0,
        sun: None,
        ground_reflectance: 0.0,
    })
    .expect("the overcast sky needs no sun")
}

/// The vertical sky component of each window, per cent, its sky obstructed by `model`
/// (every triangle opaque); each point is moved off its wall by the model's offset.
pub fn vertical_sky_components(windows: &[Window], model: &Obstructions) -> Vec<f64> {
    let points: Vec<SurfacePoint> = windows
        .iter()
        .map(|w| SurfacePoint {
            position: w.position + w.normal * model.eps,
            normal: w.normal,
        })
        .collect();
    daylight_at_points(&overcast_sky(), Some(model), &points, HEMISPHERE_CELLS)
        .iter()
        .map(|d| d.sky)
        .collect()
}
