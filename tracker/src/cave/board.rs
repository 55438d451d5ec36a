//! How tracker space sits in board space: the tracker's up axis, its yaw,
//! scale and origin on the board (`board = origin + scale · Rz(yaw) · A ·
//! p`, see [`crate::cave`]).

use glam::{DMat4, DQuat, DVec3};

/// Which tracker axis points up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum UpAxis {
    /// y up (OpenVR, OptiTrack default).
    #[default]
    Y,
    /// z up.
    Z,
}

/// Placement of tracker space in board space (see module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackerToBoard {
    /// Board-space position of the tracker origin.
    pub origin: DVec3,
    /// Rotation about board +z, degrees.
    pub yaw_deg: f64,
    /// Board units per tracker metre.
    pub scale: f64,
    /// Tracker up axis.
    pub up_axis: UpAxis,
}

impl Default for TrackerToBoard {
    fn default() -> Self {
        Self {
            origin: DVec3::ZERO,
            yaw_deg: 0.0,
            scale: 1.0,
            up_axis: UpAxis::Y,
        }
    }
}

impl TrackerToBoard {
    /// The rotation part (axis change, then yaw).
    #[must_use]
    pub fn rotation(&self) -> DQuat {
        let axes = match self.up_axis {
            UpAxis::Y => DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2),
            UpAxis::Z => DQuat::IDENTITY,
        };
        DQuat::from_rotation_z(self.yaw_deg.to_radians()) * axes
    }

    /// Tracker → board as a 4×4 affine matrix.
    #[must_use]
    pub fn matrix(&self) -> DMat4 {
        DMat4::from_scale_rotation_translation(
            DVec3::splat(self.scale),
            self.rotation(),
            self.origin,
        )
    }

    /// Board → tracker (the inverse of [`TrackerToBoard::matrix`]).
    #[must_use]
    pub fn inverse_matrix(&self) -> DMat4 {
        let inv_rot = self.rotation().conjugate();
        DMat4::from_scale(DVec3::splat(1.0 / self.scale))
            * DMat4::from_quat(inv_rot)
            * DMat4::from_translation(-self.origin)
    }

    /// Maps a tracker-space point to board space.
    #[must_use]
    pub fn point(&self, p: DVec3) -> DVec3 {
        self.origin + self.scale * (self.rotation() * p)
    }

    /// Maps a tracker-space orientation to board space.
    #[must_use]
    pub fn orientation(&self, q: DQuat) -> DQuat {
        self.rotation() * q
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tracker_to_board_transform() {
        let t = TrackerToBoard {
            origin: DVec3::new(1.0, 2.0, 0.0),
            yaw_deg: 90.0,
            scale: 2.0,
            up_axis: UpAxis::Y,
        };
        // Tracker up (+y) becomes board up (+z), scaled.
        let up = t.point(DVec3::Y) - t.origin;
        assert!((up - DVec3::new(0.0, 0.0, 2.0)).length() < 1e-12);
        // Tracker +x, yawed 90° about board z, becomes board +y.
        let x = t.point(DVec3::X) - t.origin;
        assert!((x - DVec3::new(0.0, 2.0, 0.0)).length() < 1e-12);
        let p = DVec3::new(0.3, -0.2, 0.7);
        assert!((t.matrix().transform_point3(p) - t.point(p)).length() < 1e-12);
        let back = t.inverse_matrix().transform_point3(t.point(p));
        assert!((back - p).length() < 1e-12);
        let z_up = TrackerToBoard {
            up_axis: UpAxis::Z,
            ..TrackerToBoard::default()
        };
        assert_eq!(z_up.point(p), p);
        assert!(t.orientation(DQuat::IDENTITY).is_normalized());
    }
}
