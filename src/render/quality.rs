//! The render-quality options that are not display settings of a scene (a scene file's
//! `[display]` has no key for them): samples per pixel and the shadow maps' size. One
//! check for every front end (the commands' `--supersample`/`--shadow-map-size`,
//! Python's keywords).

use super::{RenderSettings, MAX_IMAGE_SIZE};

/// Supersampling and the shadow-map size for one image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderQuality {
    /// N × N samples per pixel for the displayed image: 1, 3 or 5 (an odd count has a
    /// sample at the pixel centre, where the lux and luminance values are read).
    pub supersample: u32,
    /// The paraboloid shadow map's side, texels per hemisphere and luminaire (`None`:
    /// the settings' own, 1024 by default).
    pub shadow_map_size: Option<u32>,
}

impl Default for RenderQuality {
    /// Three samples per pixel side and the default shadow maps (the commands' defaults).
    fn default() -> RenderQuality {
        RenderQuality {
            supersample: 3,
            shadow_map_size: None,
        }
    }
}

/// A render-quality option out of range, naming its field.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum QualityError {
    /// Not 1, 3 or 5 samples per pixel side.
    #[error("`supersample` {0} must be 1, 3 or 5 (an odd count has a sample at the pixel centre)")]
    Supersample(u32),
    /// A shadow map smaller than 16 or larger than the largest image.
    #[error("`shadow_map_size` {0} is not in 16..={MAX_IMAGE_SIZE}")]
    ShadowMapSize(u32),
}

impl RenderQuality {
    /// Checks both options.
    pub fn check(&self) -> Result<(), QualityError> {
        if ![1, 3, 5].contains(&self.supersample) {
            return Err(QualityError::Supersample(self.supersample));
        }
        match self.shadow_map_size {
            Some(size) if !(16..=MAX_IMAGE_SIZE).contains(&size) => {
                Err(QualityError::ShadowMapSize(size))
            }
            _ => Ok(()),
        }
    }

    /// `settings` with these options, checked first.
    pub fn apply(&self, mut settings: RenderSettings) -> Result<RenderSettings, QualityError> {
        self.check()?;
        settings.supersample = self.supersample;
        if let Some(size) = self.shadow_map_size {
            settings.shadows.map_size = size;
        }
        Ok(settings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> RenderSettings {
        RenderSettings::from_display(&crate::scene::DisplayEntry::default())
    }

    #[test]
    fn the_options_are_applied_or_refused_naming_the_field() {
        let quality = RenderQuality {
            supersample: 5,
            shadow_map_size: Some(2048),
        };
        let s = quality.apply(base()).unwrap();
        assert_eq!((s.supersample, s.shadows.map_size), (5, 2048));
        let kept = RenderQuality::default().apply(base()).unwrap();
        assert_eq!(kept.shadows.map_size, base().shadows.map_size);
        for bad in [0, 2, 4, 7] {
            let e = RenderQuality {
                supersample: bad,
                ..RenderQuality::default()
            }
            .check()
            .unwrap_err();
            assert_eq!(e, QualityError::Supersample(bad));
            assert!(e
                .to_string()
                .starts_with(&format!("`supersample` {bad} must be")));
        }
        for bad in [8, 15, MAX_IMAGE_SIZE + 1] {
            let e = RenderQuality {
                shadow_map_size: Some(bad),
                ..RenderQuality::default()
            }
            .check()
            .unwrap_err();
            assert_eq!(e, QualityError::ShadowMapSize(bad));
        }
        for ok in [16, MAX_IMAGE_SIZE] {
            let q = RenderQuality {
                shadow_map_size: Some(ok),
                ..RenderQuality::default()
            };
            assert_eq!(q.check(), Ok(()));
        }
    }
}
