//! False-colour palettes for illuminance images and plans: goniolight's own rainbow (the
//! default), and the perceptually uniform, colour-blind-safe maps of matplotlib
//! (viridis, cividis, inferno; taken from the `colorous` crate). A palette is a list of
//! at most [`MAX_STOPS`] stops interpolated linearly in linear RGB, the same on the CPU
//! and in `shaders/tonemap.wgsl`; `steps` quantises the scale into hard bands as DIALux
//! and Relux draw them.

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Most hard bands a scale may have.
pub const MAX_STEPS: u32 = 20;

/// Most stops a palette has (the shader's array size).
pub const MAX_STOPS: usize = 16;

/// A false-colour palette.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default, schemars::JsonSchema,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Palette {
    /// goniolight's rainbow: dark blue, cyan, green, yellow, orange, red, pink.
    #[default]
    Rainbow,
    /// matplotlib's viridis: perceptually uniform, readable by colour-blind viewers and
    /// in grey.
    Viridis,
    /// cividis: viridis optimised for red-green colour blindness.
    Cividis,
    /// inferno: perceptually uniform, black to yellow.
    Inferno,
}

/// goniolight's rainbow: (position 0..1, sRGB colour).
pub const RAINBOW_STOPS: [(f32, [u8; 3]); 8] = [
    (0.0, [20, 10, 70]),
    (0.14, [30, 60, 200]),
    (0.29, [20, 160, 230]),
    (0.43, [40, 190, 90]),
    (0.57, [225, 225, 40]),
    (0.71, [250, 150, 20]),
    (0.86, [225, 30, 20]),
    (1.0, [255, 170, 230]),
];

/// 8-bit sRGB → linear.
pub fn srgb_to_linear(c: u8) -> f32 {
    let v = c as f32 / 255.0;
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear → 8-bit sRGB.
pub fn linear_to_srgb(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 {
        v * 12.92
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

fn linear(c: [u8; 3]) -> Vec3 {
    Vec3::new(
        srgb_to_linear(c[0]),
        srgb_to_linear(c[1]),
        srgb_to_linear(c[2]),
    )
}

impl Palette {
    /// Every palette, in the order menus list them.
    pub const ALL: [Palette; 4] = [
        Palette::Rainbow,
        Palette::Viridis,
        Palette::Cividis,
        Palette::Inferno,
    ];

    /// The name the scene file and the command line use.
    pub fn name(self) -> &'static str {
        match self {
            Palette::Rainbow => "rainbow",
            Palette::Viridis => "viridis",
            Palette::Cividis => "cividis",
            Palette::Inferno => "inferno",
        }
    }

    /// The stops: (position 0..1, linear RGB), at most [`MAX_STOPS`].
    pub fn stops(self) -> Vec<(f32, Vec3)> {
        let gradient = match self {
            Palette::Rainbow => {
                return RAINBOW_STOPS.iter().map(|&(t, c)| (t, linear(c))).collect();
            }
            Palette::Viridis => colorous::VIRIDIS,
            Palette::Cividis => colorous::CIVIDIS,
            Palette::Inferno => colorous::INFERNO,
        };
        let n = MAX_STOPS;
        (0..n)
            .map(|k| {
                let t = k as f64 / (n - 1) as f64;
                let c = gradient.eval_continuous(t);
                (t as f32, linear([c.r, c.g, c.b]))
            })
            .collect()
    }

    /// The colour (linear RGB) at `t` in 0..1 (clamped), continuous: the CPU twin of
    /// `false_colour` in `shaders/tonemap.wgsl`.
    pub fn colour(self, t: f32) -> Vec3 {
        let x = t.clamp(0.0, 1.0);
        let stops = self.stops();
        let mut c = stops[0].1;
        for w in stops.windows(2) {
            let ((a, ca), (b, cb)) = (w[0], w[1]);
            if x >= a && x <= b {
                c = ca.lerp(cb, (x - a) / (b - a).max(1e-6));
            }
        }
        c
    }

    /// The colour of `t` on a scale of `steps` hard bands (0: continuous): each band has
    /// the colour of its middle; values at or above the top take the top band.
    pub fn stepped_colour(self, t: f32, steps: u32) -> Vec3 {
        self.colour(step_position(t, steps))
    }

    /// [`Palette::stepped_colour`] as 8-bit sRGB, for pictures.
    pub fn srgb8(self, t: f32, steps: u32) -> [u8; 3] {
        let c = self.stepped_colour(t, steps);
        [
            linear_to_srgb(c.x),
            linear_to_srgb(c.y),
            linear_to_srgb(c.z),
        ]
    }
}

/// Where `t` falls on a scale of `steps` bands (the middle of its band; `t` itself when
/// `steps` is 0): the CPU twin of `step_position` in `shaders/tonemap.wgsl`.
pub fn step_position(t: f32, steps: u32) -> f32 {
    if steps == 0 {
        return t;
    }
    let n = steps as f32;
    let band = (t.clamp(0.0, 1.0) * n).floor().min(n - 1.0);
    (band + 0.5) / n
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palettes_run_dark_to_light_and_fit_the_shader() {
        for p in Palette::ALL {
            let stops = p.stops();
            assert!(stops.len() <= MAX_STOPS && stops.len() >= 2, "{p:?}");
            assert_eq!((stops[0].0, stops.last().unwrap().0), (0.0, 1.0));
            let luma = |c: Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722));
            assert!(luma(p.colour(0.0)) < luma(p.colour(1.0)) * 0.5, "{p:?}");
        }
        // Viridis is monotone in lightness: readable in grey.
        let luma = |t: f32| {
            Palette::Viridis
                .colour(t)
                .dot(Vec3::new(0.2126, 0.7152, 0.0722))
        };
        for k in 0..50 {
            assert!(luma(k as f32 / 50.0) < luma((k + 1) as f32 / 50.0));
        }
        // viridis(0) is matplotlib's #440154.
        let c = Palette::Viridis.colour(0.0);
        assert!((c - linear([0x44, 0x01, 0x54])).abs().max_element() < 1e-6);
    }

    #[test]
    fn steps_give_hard_bands_coloured_by_their_middle() {
        assert_eq!(step_position(0.0, 5), 0.1);
        assert_eq!(step_position(0.199, 5), 0.1);
        assert_eq!(step_position(0.2, 5), 0.3);
        assert_eq!(step_position(1.0, 5), 0.9);
        assert_eq!(step_position(7.0, 5), 0.9);
        assert_eq!(step_position(0.37, 0), 0.37);
    }
}
