//! What a tracking system's report must hold before it is published: a
//! finite position within the tracked room's bound and an orientation that
//! is a rotation. DTrack's and VRPN's readers ([`crate::dtrack`],
//! [`crate::vrpn`]) and the game's [`crate::follow::Follower`] apply the same
//! bound, so a report the guide says is dropped is dropped at the tracker,
//! and again in the game should another publisher send it.

use glam::{DQuat, DVec3};

/// Largest tracker-space coordinate a report may have, m, on every axis: a
/// tracked room, with a wide margin (no room is 2 km across).
pub const MAX_TRACKED_COORDINATE: f64 = 1000.0;

/// Checks a position (metres, tracker space): finite, and within
/// ±[`MAX_TRACKED_COORDINATE`] on every axis.
///
/// # Errors
/// What is wrong, with the position: `[1e300, 0.0, 0.0] m is beyond ±1
/// km`, `[NaN, 0.0, 0.0] is not finite`.
pub fn check_position(position: DVec3) -> Result<DVec3, String> {
    let shown = format!("[{}]", show(&position.to_array()));
    if !position.is_finite() {
        return Err(format!("{shown} is not finite"));
    }
    if position.abs().max_element() > MAX_TRACKED_COORDINATE {
        return Err(format!("{shown} m is beyond ±1 km"));
    }
    Ok(position)
}

/// Numbers as Rust's `Debug` writes them (`0.5`, `1e300`, `NaN`): short
/// whatever their size, unlike `Display`'s 301 digits for 1e300.
fn show(values: &[f64]) -> String {
    let shown: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
    shown.join(", ")
}

/// The unit quaternion of `q` (any non-zero finite length: a tracking
/// system's quaternion is unit up to its rounding), normalised without
/// overflow or underflow: `q` is first divided by its largest component,
/// so `(1e300, 1e300, 0, 0)` and `(1e-300, 0, 0, 0)` normalise as
/// `(1, 1, 0, 0)` and `(1, 0, 0, 0)` do.
///
/// # Errors
/// `q` has a component that is not finite, or all four are zero (no
/// rotation): the message shows `q` as `(x, y, z, w)`.
pub fn unit_quaternion(q: DQuat) -> Result<DQuat, String> {
    let shown = || format!("({}) is not a rotation", show(&q.to_array()));
    if !q.is_finite() {
        return Err(shown());
    }
    let largest = DVec3::new(q.x, q.y, q.z).abs().max_element().max(q.w.abs());
    if largest == 0.0 {
        return Err(shown());
    }
    let scaled = DQuat::from_xyzw(q.x / largest, q.y / largest, q.z / largest, q.w / largest);
    Ok(scaled.normalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_beyond_the_room_or_not_finite_are_refused() {
        assert_eq!(
            check_position(DVec3::new(1.0, 1.7, -0.5)),
            Ok(DVec3::new(1.0, 1.7, -0.5))
        );
        assert!(check_position(DVec3::splat(1000.0)).is_ok());
        for (p, says) in [
            (DVec3::new(1e300, 0.0, 0.0), "beyond ±1 km"),
            (DVec3::new(0.0, -1e6, 0.0), "beyond ±1 km"),
            (DVec3::new(0.0, 0.0, 1000.001), "beyond ±1 km"),
            (DVec3::new(f64::NAN, 0.0, 0.0), "not finite"),
            (DVec3::new(0.0, f64::INFINITY, 0.0), "not finite"),
        ] {
            let e = check_position(p).unwrap_err();
            assert!(e.contains(says), "{p}: {e}");
        }
        assert_eq!(
            check_position(DVec3::new(1e300, 0.0, 0.5)).unwrap_err(),
            "[1e300, 0.0, 0.5] m is beyond ±1 km"
        );
    }

    #[test]
    fn quaternions_of_any_finite_length_normalise_and_zero_is_refused() {
        let q = DQuat::from_rotation_y(0.3);
        for scale in [1.0, 0.9, 1e300, 1e-300] {
            let scaled = DQuat::from_xyzw(q.x * scale, q.y * scale, q.z * scale, q.w * scale);
            let u = unit_quaternion(scaled).unwrap();
            assert!((u.length() - 1.0).abs() < 1e-15, "{scale}: {u}");
            assert!(u.dot(q) > 1.0 - 1e-15, "{scale}: {u}");
        }
        // Overflowing lengths: (1e300, 1e300, 0, 0) is a half turn about
        // (1, 1, 0)/√2.
        let u = unit_quaternion(DQuat::from_xyzw(1e300, 1e300, 0.0, 0.0)).unwrap();
        let half = std::f64::consts::FRAC_1_SQRT_2;
        assert!(
            (u.x - half).abs() < 1e-15 && (u.y - half).abs() < 1e-15,
            "{u}"
        );
        for bad in [
            DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0),
            DQuat::from_xyzw(-0.0, 0.0, 0.0, -0.0),
            DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0),
            DQuat::from_xyzw(0.0, f64::INFINITY, 0.0, 1.0),
        ] {
            let e = unit_quaternion(bad).unwrap_err();
            assert!(e.contains("is not a rotation"), "{bad}: {e}");
        }
    }
}
