//! The camera: eye, target, up, perspective (vertical field of view) or orthographic.

use std::path::Path;

use glam::{DMat4, DVec3, Mat4};

use super::file::CameraEntry;
use super::{finite_vec, SceneError};

/// Perspective or orthographic projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Vertical field of view, degrees.
    Perspective {
        /// Vertical field of view, degrees.
        fov_deg: f64,
    },
    /// Height of the view, metres.
    Orthographic {
        /// Height of the view, metres.
        height: f64,
    },
}

/// A camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position, metres.
    pub position: DVec3,
    /// Point looked at.
    pub look_at: DVec3,
    /// Up direction.
    pub up: DVec3,
    /// Projection.
    pub projection: Projection,
    /// Near plane distance, metres.
    pub near: f64,
    /// Far plane distance of an orthographic camera (perspective ones have none).
    pub far: f64,
}

impl Camera {
    /// A perspective camera; `far` covers a scene of `extent` metres.
    pub fn perspective(position: DVec3, look_at: DVec3, fov_deg: f64) -> Camera {
        // +Z up, or +Y when the camera looks straight up or down (+Z would be degenerate).
        let vertical = (look_at - position)
            .normalize_or_zero()
            .cross(DVec3::Z)
            .length()
            < 1e-6;
        Camera {
            position,
            look_at,
            up: if vertical { DVec3::Y } else { DVec3::Z },
            projection: Projection::Perspective { fov_deg },
            near: 0.05,
            far: 1000.0,
        }
    }

    /// The camera of a scene file without `[camera]`: a plan view (orthographic, looking
    /// straight down, north up) of the geometry's bounds `(lo, hi)` with a margin. When
    /// a luminaire hangs more than 5 cm under the top of the model (under a ceiling),
    /// the view is cut 1 cm above the highest such luminaire, so the plan shows the
    /// lit room rather than the roof.
    pub fn framing((lo, hi): (DVec3, DVec3), luminaires: &[super::PlacedLuminaire]) -> Camera {
        let size = (hi - lo).max(DVec3::splat(1e-3));
        let center = (lo + hi) * 0.5;
        let cut = luminaires
            .iter()
            .map(|l| l.position.z)
            .filter(|&z| z < hi.z - 0.05)
            .fold(f64::NEG_INFINITY, f64::max);
        let top = if cut.is_finite() { cut + 0.01 } else { hi.z };
        let z_eye = hi.z + 1.0;
        // 16:9 is the default image; a taller image shows more around the plan.
        let height = size.y.max(size.x * 9.0 / 16.0) * 1.1;
        Camera {
            near: z_eye - top,
            ..Camera::top_down(DVec3::new(center.x, center.y, lo.z), height, z_eye)
        }
    }

    /// A camera looking straight down at `center`, `height` metres of view, from `z_eye`.
    pub fn top_down(center: DVec3, height: f64, z_eye: f64) -> Camera {
        Camera {
            position: DVec3::new(center.x, center.y, z_eye),
            look_at: center,
            up: DVec3::Y,
            projection: Projection::Orthographic { height },
            near: 0.01,
            far: (z_eye - center.z).abs() * 2.0 + 1.0,
        }
    }

    pub(super) fn from_entry(
        scene: &Path,
        e: &CameraEntry,
        bounds: (DVec3, DVec3),
    ) -> Result<Camera, SceneError> {
        let position = finite_vec(scene, "camera.position", e.position)?;
        let look_at = finite_vec(scene, "camera.look_at", e.look_at)?;
        let up = match e.up {
            Some(u) => finite_vec(scene, "camera.up", u)?,
            None => DVec3::Z,
        };
        let view = look_at - position;
        if view.length() < 1e-9 {
            return Err(SceneError::new(
                scene,
                "camera.look_at",
                "equals camera.position: the view direction is undefined",
            ));
        }
        if view.normalize().cross(up.normalize_or_zero()).length() < 1e-6 {
            return Err(SceneError::new(
                scene,
                "camera.up",
                "is parallel to the view direction (or zero); set camera.up",
            ));
        }
        let projection = match (e.fov_deg, e.orthographic_height) {
            (Some(_), Some(_)) => {
                return Err(SceneError::new(
                    scene,
                    "camera.orthographic_height",
                    "give either fov_deg or orthographic_height, not both",
                ))
            }
            (None, Some(h)) if h.is_finite() && h > 0.0 => Projection::Orthographic { height: h },
            (None, Some(h)) => {
                return Err(SceneError::new(
                    scene,
                    "camera.orthographic_height",
                    format!("{h} must be a positive number"),
                ))
            }
            (f, None) => {
                let fov_deg = f.unwrap_or(60.0);
                if !(fov_deg > 0.0 && fov_deg < 179.0) {
                    return Err(SceneError::new(
                        scene,
                        "camera.fov_deg",
                        format!("{fov_deg} is not in (0, 179)"),
                    ));
                }
                Projection::Perspective { fov_deg }
            }
        };
        let near = e.near.unwrap_or(0.05);
        if !(near.is_finite() && near > 0.0) {
            return Err(SceneError::new(
                scene,
                "camera.near",
                format!("{near} must be a positive number"),
            ));
        }
        // Far enough for every point of the scene.
        let center = (bounds.0 + bounds.1) / 2.0;
        let far = ((center - position).length() + (bounds.1 - bounds.0).length()) * 1.5 + 1.0;
        Ok(Camera {
            position,
            look_at,
            up,
            projection,
            near,
            far,
        })
    }

    /// World → view matrix.
    pub fn view(&self) -> DMat4 {
        DMat4::look_at_rh(self.position, self.look_at, self.up)
    }

    /// View → clip matrix (depth 0..1; perspective with an infinite far plane).
    pub fn projection(&self, aspect: f64) -> DMat4 {
        match self.projection {
            Projection::Perspective { fov_deg } => {
                DMat4::perspective_infinite_rh(fov_deg.to_radians(), aspect, self.near)
            }
            Projection::Orthographic { height } => {
                let h = height / 2.0;
                let w = h * aspect;
                DMat4::orthographic_rh(-w, w, -h, h, self.near, self.far)
            }
        }
    }

    /// The corners of the near-plane rectangle in world coordinates, counter-clockwise
    /// seen from the eye: what the z-pass / z-fail decision of shadow volumes tests.
    pub fn near_rectangle(&self, aspect: f64) -> [DVec3; 4] {
        let f = (self.look_at - self.position).normalize();
        let r = f.cross(self.up).normalize();
        let u = r.cross(f);
        let half_h = match self.projection {
            Projection::Perspective { fov_deg } => self.near * (fov_deg.to_radians() / 2.0).tan(),
            Projection::Orthographic { height } => height / 2.0,
        };
        let half_w = half_h * aspect;
        let c = self.position + f * self.near;
        [
            c - r * half_w - u * half_h,
            c + r * half_w - u * half_h,
            c + r * half_w + u * half_h,
            c - r * half_w + u * half_h,
        ]
    }

    /// World → clip, f32 for the GPU.
    pub fn view_projection(&self, aspect: f64) -> Mat4 {
        (self.projection(aspect) * self.view()).as_mat4()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_perspective_camera_is_z_up_unless_it_looks_straight_up_or_down() {
        let level = Camera::perspective(DVec3::ZERO, DVec3::new(1.0, 2.0, 0.5), 60.0);
        assert_eq!(level.up, DVec3::Z);
        for z in [-3.0, 3.0] {
            let vertical = Camera::perspective(DVec3::ZERO, DVec3::new(0.0, 0.0, z), 60.0);
            assert_eq!(vertical.up, DVec3::Y);
        }
    }
}
