//! The wire format of one head-tracker measurement.
//!
//! [`TrackerSample`] is what travels through shared memory between the tracker
//! publisher process and the game. It is `#[repr(C)]`, fixed size (80 bytes),
//! contains no pointers and has *no implicit padding* (the trailing bytes are
//! an explicit `_pad` field), so that:
//!
//! * iceoryx2 can hand it across processes without serialisation
//!   (`ZeroCopySend` requires `#[repr(C)]` and self-contained data);
//! * a C/C++ tracker bridge can declare the identical struct;
//! * no uninitialised bytes are ever written into shared memory.
//!
//! The iceoryx2 type name is pinned with `#[type_name(...)]` to
//! [`TrackerSample::TYPE_NAME`]: by default iceoryx2 uses
//! `core::any::type_name`, which contains the Rust module path, so moving this
//! file inside the crate would silently make old and new processes
//! incompatible. Bump the `/vN` suffix whenever the layout changes; services
//! opened with a different type name fail with an "incompatible types" error
//! instead of misreading memory.

use glam::{DQuat, DVec3};
#[cfg(not(target_arch = "wasm32"))]
use iceoryx2::prelude::ZeroCopySend;
use std::time::{SystemTime, UNIX_EPOCH};

/// One pose measurement from the head tracker, as sent over IPC.
///
/// Units: metres in *tracker space* (see [`crate::cave`] for the transform to
/// board space). The orientation is a unit quaternion in `x, y, z, w` order
/// (glam's order). Nothing about the contents is trusted by the receiver:
/// [`crate::follow::Follower`] validates every field.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
// No iceoryx2 in the browser build (wasm32): the sample is plain data there.
#[cfg_attr(
    not(target_arch = "wasm32"),
    derive(ZeroCopySend),
    type_name("lightcone::TrackerSample/v1")
)]
pub struct TrackerSample {
    /// Publisher's wall clock at measurement time, nanoseconds since the Unix
    /// epoch. Wall-clock (not `Instant`) because `Instant` values cannot be
    /// compared between processes; both processes on one machine share
    /// `CLOCK_REALTIME`, which is what latency measurement needs.
    pub timestamp_ns: u64,
    /// Increments by one per sample from a publisher; restarts at (or near) 0
    /// when the publisher process restarts.
    pub sequence: u64,
    /// Head position in metres, tracker space.
    pub position: [f64; 3],
    /// Head orientation, unit quaternion `[x, y, z, w]`.
    pub orientation: [f64; 4],
    /// 1 when the tracker had a fix for this measurement, 0 otherwise.
    pub valid: u8,
    /// Explicit padding to an 8-byte multiple; always zero.
    pub _pad: [u8; 7],
}

// The layout is a cross-process contract: fail the build if it drifts.
const _: () = assert!(core::mem::size_of::<TrackerSample>() == 80);
const _: () = assert!(core::mem::align_of::<TrackerSample>() == 8);

impl TrackerSample {
    /// The iceoryx2 type name (must match the `#[type_name]` attribute).
    pub const TYPE_NAME: &'static str = "lightcone::TrackerSample/v1";

    /// Builds a sample from glam types. `valid` is stored as 1/0.
    #[must_use]
    pub fn new(
        timestamp_ns: u64,
        sequence: u64,
        position: DVec3,
        orientation: DQuat,
        valid: bool,
    ) -> Self {
        Self {
            timestamp_ns,
            sequence,
            position: position.to_array(),
            orientation: orientation.to_array(),
            valid: u8::from(valid),
            _pad: [0; 7],
        }
    }

    /// The position as a glam vector (unvalidated: may be NaN).
    #[must_use]
    pub fn position_vec(&self) -> DVec3 {
        DVec3::from_array(self.position)
    }

    /// The orientation as a glam quaternion, exactly as received (may be
    /// non-unit or non-finite; see [`crate::follow`] for validation).
    #[must_use]
    pub fn orientation_quat(&self) -> DQuat {
        DQuat::from_array(self.orientation)
    }

    /// True when the publisher flagged the measurement as having a fix.
    /// Any non-zero byte counts, so a C bridge writing `true` as 0xFF works.
    #[must_use]
    pub fn has_fix(&self) -> bool {
        self.valid != 0
    }
}

impl Default for TrackerSample {
    /// A sample at the origin with identity orientation and no fix.
    fn default() -> Self {
        Self::new(0, 0, DVec3::ZERO, DQuat::IDENTITY, false)
    }
}

/// Current wall-clock time in nanoseconds since the Unix epoch.
///
/// Returns 0 if the clock is before 1970 (misconfigured machine) and
/// saturates at `u64::MAX` (year 2554) rather than panicking.
#[must_use]
pub fn unix_now_ns() -> u64 {
    match SystemTime::now().duration_since(UNIX_EPOCH) {
        Ok(d) => u64::try_from(d.as_nanos()).unwrap_or(u64::MAX),
        Err(_) => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use iceoryx2::prelude::ZeroCopySend;

    #[test]
    fn layout_is_fixed_and_padding_explicit() {
        assert_eq!(core::mem::size_of::<TrackerSample>(), 80);
        assert_eq!(core::mem::offset_of!(TrackerSample, timestamp_ns), 0);
        assert_eq!(core::mem::offset_of!(TrackerSample, sequence), 8);
        assert_eq!(core::mem::offset_of!(TrackerSample, position), 16);
        assert_eq!(core::mem::offset_of!(TrackerSample, orientation), 40);
        assert_eq!(core::mem::offset_of!(TrackerSample, valid), 72);
        assert_eq!(core::mem::offset_of!(TrackerSample, _pad), 73);
    }

    #[test]
    fn type_name_is_pinned() {
        // SAFETY: type_name is `unsafe` only because implementors must keep
        // layouts in sync across languages; calling it is harmless.
        let name = unsafe { <TrackerSample as ZeroCopySend>::type_name() };
        assert_eq!(name, TrackerSample::TYPE_NAME);
    }

    #[test]
    fn glam_round_trip() {
        let q = DQuat::from_rotation_y(0.3);
        let s = TrackerSample::new(5, 7, DVec3::new(1.0, 2.0, 3.0), q, true);
        assert_eq!(s.position_vec(), DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(s.orientation_quat(), q);
        assert!(s.has_fix());
        assert_eq!(s._pad, [0; 7]);
        assert!(!TrackerSample::default().has_fix());
    }

    #[test]
    fn any_nonzero_valid_byte_is_a_fix() {
        let s = TrackerSample {
            valid: 0xff,
            ..TrackerSample::default()
        };
        assert!(s.has_fix());
    }

    #[test]
    fn clock_is_plausible() {
        // After 2020-01-01 and monotone enough for two successive calls.
        let a = unix_now_ns();
        let b = unix_now_ns();
        assert!(a > 1_577_836_800_000_000_000);
        assert!(b >= a);
    }
}
