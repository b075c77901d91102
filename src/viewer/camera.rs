//! The viewer's camera: orbit about a target (drag to orbit, right/middle drag to pan,
//! scroll to zoom) or fly (drag to look, W/A/S/D/Q/E to move), kept as target + yaw +
//! pitch + distance so both modes share one state.

use glam::DVec3;

use crate::scene::{Camera, Projection};

/// How mouse and keys move the camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CameraMode {
    /// Orbit about the target.
    Orbit,
    /// Look around from the eye and move it with the keys.
    Fly,
}

/// The interactive camera (world frame: +Z up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewCamera {
    /// The point orbited about (and looked at).
    pub target: DVec3,
    /// Heading of the view direction, degrees counter-clockwise from +X.
    pub yaw_deg: f64,
    /// Elevation of the view direction, degrees (negative: looking down).
    pub pitch_deg: f64,
    /// Eye to target, metres.
    pub distance: f64,
    /// Vertical field of view, degrees.
    pub fov_deg: f64,
    /// Near plane, metres.
    pub near: f64,
    /// Orbit or fly.
    pub mode: CameraMode,
    /// Fly speed, metres per second.
    pub speed_m_s: f64,
    /// Height of the view of an orthographic camera, metres (`None`: perspective).
    pub ortho_height: Option<f64>,
}

/// Degrees per pixel of mouse drag.
const DEGREES_PER_PIXEL: f64 = 0.3;

impl ViewCamera {
    /// The interactive version of a scene's camera (an orthographic one stays
    /// orthographic; switching it to perspective gives 60°).
    pub fn from_camera(c: &Camera) -> ViewCamera {
        let dir = (c.look_at - c.position).normalize_or(DVec3::NEG_Y);
        let (fov_deg, ortho_height) = match c.projection {
            Projection::Perspective { fov_deg } => (fov_deg, None),
            Projection::Orthographic { height } => (60.0, Some(height)),
        };
        ViewCamera {
            target: c.look_at,
            // Straight up or down the heading comes from the camera's up vector (looking
            // down, the camera faces where its up vector points; looking up, away), and
            // [`ViewCamera::camera`] takes its up vector from the heading.
            yaw_deg: if dir.truncate().length() < 1e-6 {
                let u = c.up * -dir.z.signum();
                u.y.atan2(u.x).to_degrees()
            } else {
                dir.y.atan2(dir.x).to_degrees()
            },
            pitch_deg: dir.z.clamp(-1.0, 1.0).asin().to_degrees(),
            distance: (c.look_at - c.position).length().max(1e-3),
            fov_deg,
            near: c.near,
            mode: CameraMode::Orbit,
            speed_m_s: 2.0,
            ortho_height,
        }
    }

    /// Unit view direction.
    pub fn direction(&self) -> DVec3 {
        let (y, p) = (self.yaw_deg.to_radians(), self.pitch_deg.to_radians());
        DVec3::new(y.cos() * p.cos(), y.sin() * p.cos(), p.sin())
    }

    /// Eye position.
    pub fn eye(&self) -> DVec3 {
        self.target - self.direction() * self.distance
    }

    /// The renderer's camera; `extent` (metres) sets the far plane.
    pub fn camera(&self, extent: f64) -> Camera {
        let mut c = Camera::perspective(self.eye(), self.target, self.fov_deg);
        if self.pitch_deg.abs() > 89.0 {
            // Near the vertical, +Z is (almost) the view direction: screen-up is the
            // heading instead (away from it when looking up).
            let yaw = self.yaw_deg.to_radians();
            c.up = DVec3::new(yaw.cos(), yaw.sin(), 0.0) * -self.pitch_deg.signum();
        }
        c.near = self.near;
        c.far = (self.distance + extent) * 2.0 + 1.0;
        if let Some(height) = self.ortho_height {
            c.projection = Projection::Orthographic { height };
        }
        c
    }

    /// The view's height in metres at the target: what a pixel of pan moves.
    fn view_height_m(&self) -> f64 {
        self.ortho_height
            .unwrap_or_else(|| 2.0 * self.distance * (self.fov_deg.to_radians() / 2.0).tan())
    }

    /// Turns the view by a mouse drag of (dx, dy) pixels: about the target when
    /// orbiting, about the eye when flying.
    pub fn rotate(&mut self, dx: f64, dy: f64) {
        let eye = self.eye();
        self.yaw_deg = (self.yaw_deg - dx * DEGREES_PER_PIXEL).rem_euclid(360.0);
        self.pitch_deg = (self.pitch_deg - dy * DEGREES_PER_PIXEL).clamp(-89.0, 89.0);
        if self.mode == CameraMode::Fly {
            self.target = eye + self.direction() * self.distance;
        }
    }

    /// Moves target and eye across the view by a drag of (dx, dy) pixels in a view
    /// `height_px` pixels high (the point under the cursor follows it).
    pub fn pan(&mut self, dx: f64, dy: f64, height_px: f64) {
        let dir = self.direction();
        let right = dir.cross(DVec3::Z).normalize_or(DVec3::X);
        let up = right.cross(dir);
        let metres_per_px = self.view_height_m() / height_px.max(1.0);
        self.target += (-right * dx + up * dy) * metres_per_px;
    }

    /// Zooms by scroll `steps` (positive: closer), 10 % per step.
    pub fn zoom(&mut self, steps: f64) {
        match &mut self.ortho_height {
            Some(h) => *h = (*h * 0.9f64.powf(steps)).clamp(0.05, 1e5),
            None => self.distance = (self.distance * 0.9f64.powf(steps)).clamp(0.05, 1e5),
        }
    }

    /// Moves eye and target by (forward, right, up) × speed × `dt_s` (fly keys).
    pub fn fly(&mut self, forward: f64, right: f64, up: f64, dt_s: f64) {
        let dir = self.direction();
        let side = dir.cross(DVec3::Z).normalize_or(DVec3::X);
        self.target += (dir * forward + side * right + DVec3::Z * up) * self.speed_m_s * dt_s;
    }

    /// Looks at the box (lo, hi) from the current direction so it fills the view.
    pub fn frame(&mut self, lo: DVec3, hi: DVec3) {
        let radius = ((hi - lo).length() / 2.0).max(0.5);
        self.target = (lo + hi) / 2.0;
        self.distance = radius / (self.fov_deg.to_radians() / 2.0).sin();
        if let Some(h) = &mut self.ortho_height {
            *h = 2.0 * radius;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> ViewCamera {
        ViewCamera::from_camera(&Camera::perspective(
            DVec3::new(0.0, -5.0, 2.0),
            DVec3::new(0.0, 0.0, 1.0),
            60.0,
        ))
    }

    #[test]
    fn orthographic_cameras_stay_orthographic_and_zoom_by_their_height() {
        let plan = Camera::top_down(DVec3::new(3.0, 2.0, 0.0), 5.0, 4.0);
        let mut v = ViewCamera::from_camera(&plan);
        assert_eq!(v.ortho_height, Some(5.0));
        assert_eq!(
            v.camera(10.0).projection,
            Projection::Orthographic { height: 5.0 }
        );
        let distance = v.distance;
        v.zoom(1.0);
        assert!((v.ortho_height.unwrap() - 4.5).abs() < 1e-12 && v.distance == distance);
        // A drag of the full view height pans by the view's height in metres.
        let before = v.target;
        v.pan(0.0, 100.0, 100.0);
        assert!(((v.target - before).length() - 4.5).abs() < 1e-9);
        // The plan view of a scene (what a scene without a camera gets, and the View
        // menu's "Plan view"): straight down, north up, the whole 6 × 4 m room in view.
        let framing = Camera::framing((DVec3::ZERO, DVec3::new(6.0, 4.0, 3.0)), &[]);
        let c = ViewCamera::from_camera(&framing).camera(10.0);
        assert_eq!(c.projection, framing.projection);
        let m = c.view_projection(16.0 / 9.0);
        for corner in [DVec3::ZERO, DVec3::new(6.0, 4.0, 0.0)] {
            let q = m.project_point3(corner.as_vec3());
            assert!(q.x.abs() < 1.0 && q.y.abs() < 1.0, "{q}");
        }
        let north = m.project_point3(glam::Vec3::new(3.0, 3.5, 0.0));
        assert!(north.y > 0.5 && north.x.abs() < 1e-2, "{north}");
    }

    #[test]
    fn a_straight_down_camera_keeps_a_defined_view() {
        let down = Camera {
            up: DVec3::Y,
            ..Camera::perspective(DVec3::new(3.0, 2.0, 10.0), DVec3::new(3.0, 2.0, 0.0), 50.0)
        };
        let v = ViewCamera::from_camera(&down);
        assert_eq!((v.pitch_deg, v.yaw_deg), (-90.0, 90.0));
        // It looks straight down at the target, with north (+Y) up on screen.
        let eye = v.eye();
        assert!((eye - DVec3::new(3.0, 2.0, 10.0)).length() < 1e-9, "{eye}");
        let m = v.camera(20.0).view_projection(1.0);
        let p = m.project_point3(glam::Vec3::new(3.0, 2.0, 0.0));
        assert!(p.is_finite() && p.x.abs() < 1e-3 && p.y.abs() < 1e-3, "{p}");
        let north = m.project_point3(glam::Vec3::new(3.0, 3.0, 0.0));
        assert!(north.y > 0.1 && north.x.abs() < 1e-2, "{north}");
    }

    #[test]
    fn round_trips_the_scene_camera() {
        let v = camera();
        assert!((v.eye() - DVec3::new(0.0, -5.0, 2.0)).length() < 1e-9);
        let c = v.camera(10.0);
        assert!((c.look_at - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-9);
    }

    #[test]
    fn orbit_keeps_the_target_and_distance_fly_keeps_the_eye() {
        let mut v = camera();
        let (target, d) = (v.target, v.distance);
        // A drag of 300 px to the right turns the view 90° clockwise seen from above:
        // the eye goes from south of the target to west of it.
        v.rotate(300.0, 0.0);
        assert!((v.target - target).length() < 1e-12);
        assert!(((v.eye() - v.target).length() - d).abs() < 1e-9);
        assert!(
            (v.eye() - DVec3::new(-5.0, 0.0, 2.0)).length() < 1e-9,
            "{}",
            v.eye()
        );
        let mut f = camera();
        f.mode = CameraMode::Fly;
        let eye = f.eye();
        f.rotate(100.0, 20.0);
        assert!((f.eye() - eye).length() < 1e-9);
        assert!((f.target - target).length() > 0.1);
    }

    #[test]
    fn pan_moves_the_target_by_the_view_width_per_drag() {
        let mut v = camera();
        let d = v.distance;
        // A drag over the whole view height moves by the view's height at the target.
        v.pan(0.0, 1000.0, 1000.0);
        let moved = (v.target - DVec3::new(0.0, 0.0, 1.0)).length();
        let expected = 2.0 * d * (30f64).to_radians().tan();
        assert!((moved - expected).abs() < 1e-9, "{moved} vs {expected}");
    }

    #[test]
    fn zoom_and_fly() {
        let mut v = camera();
        let d = v.distance;
        v.zoom(1.0);
        assert!((v.distance - 0.9 * d).abs() < 1e-12);
        let before = v.target;
        v.fly(1.0, 0.0, 0.0, 0.5);
        assert!(((v.target - before).length() - 1.0).abs() < 1e-12);
    }
}
