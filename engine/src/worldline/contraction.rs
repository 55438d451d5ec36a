//! Lorentz contraction along a worldline, segment by segment: where each
//! point of a body lies from its reference point, as data the optics
//! kernels apply (the kinematics phase computes it; a view without
//! contraction passes the rest shape, [`Rigid`]).
//!
//! On a uniform segment contraction is a linear map of the rest-frame
//! offset ([`LorentzMap`], the paper's §3.2.2); on a braking segment
//! (sliding friction) the Born-rigid body's points each brake on a
//! hyperbola of their own ([`crate::worldline::sliding::Braking::material_point`]),
//! which is no linear map: [`SegmentShape::BornRigid`].

use glam::DVec3;

use super::{Segment, Worldline};
use crate::spacetime::ProperVelocity;

/// Lorentz contraction by `1/γ` along the unit direction of motion `n̂`,
/// a linear map of a rest-frame offset `r`:
///
/// ```text
/// r ↦ r − (1 − 1/γ)(r·n̂) n̂ = r⊥ + n̂ (n̂·r)/γ
/// ```
///
/// evaluated in the second form, so that no `1 − 1/γ` is formed (see
/// [`super::contract`]), with `1/γ = 1/√(1 + u²)` from the proper
/// velocity. At rest it is the identity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LorentzMap {
    /// Unit direction of motion, board frame (zero at rest).
    direction: DVec3,
    /// `1/γ`.
    inverse_gamma: f64,
}

impl LorentzMap {
    /// The identity (a body at rest).
    pub const IDENTITY: Self = Self {
        direction: DVec3::ZERO,
        inverse_gamma: 1.0,
    };

    /// The contraction of a body moving with proper velocity `u`.
    #[must_use]
    pub fn of(u: ProperVelocity) -> Self {
        let speed = u.0.length();
        if speed == 0.0 {
            return Self::IDENTITY;
        }
        Self {
            direction: u.0 / speed,
            inverse_gamma: 1.0 / u.gamma(),
        }
    }

    /// From a segment's cached direction and `1/γ`.
    pub(super) fn from_parts(direction: DVec3, inverse_gamma: f64) -> Self {
        Self {
            direction,
            inverse_gamma,
        }
    }

    /// Unit direction of motion `n̂` (zero at rest).
    #[must_use]
    pub fn direction(&self) -> DVec3 {
        self.direction
    }

    /// `1/γ`.
    #[must_use]
    pub fn inverse_gamma(&self) -> f64 {
        self.inverse_gamma
    }

    /// The contracted offset `r⊥ + n̂ (n̂·r)/γ`, m (same frame as `r`).
    #[inline]
    #[must_use]
    pub fn apply(&self, r: DVec3) -> DVec3 {
        let n = self.direction;
        let along = n.dot(r);
        (r - n * along) + n * (along * self.inverse_gamma)
    }
}

/// A body's shape on one segment of its worldline: where the point at a
/// rest-frame offset lies from the reference point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SegmentShape {
    /// The rest shape: every point at its rest-frame offset (turned by the
    /// segment's orientation), following the reference point's motion.
    Rest,
    /// Contracted by a fixed linear map all along the segment (uniform
    /// motion): every point at `map(turned offset)` from the reference
    /// point.
    Lorentz(LorentzMap),
    /// Born-rigid under the segment's braking: each point on a braking
    /// hyperbola of its own, its offset along the motion shrinking from
    /// `r∥/γ₀` to `r∥` as the body stops
    /// ([`crate::worldline::sliding::Braking::contracted_offset_at`]).
    BornRigid,
}

impl SegmentShape {
    /// The body's Lorentz-contracted shape on `segment`: the rest shape on
    /// a rest segment, Born-rigid on a braking one, the segment's
    /// [`LorentzMap`] on a uniform one.
    #[must_use]
    pub fn contracted(segment: &Segment) -> Self {
        if segment.is_rest() {
            Self::Rest
        } else if segment.is_braking() {
            Self::BornRigid
        } else {
            Self::Lorentz(segment.lorentz_map())
        }
    }

    /// Board-frame offset from the reference point, at board time `t`, of
    /// the point at rest-frame offset `r` (the mesh's axes, m) on
    /// `segment`: `r` turned by the segment's orientation, then mapped.
    #[inline]
    #[must_use]
    pub fn place(self, segment: &Segment, t: f64, r: DVec3) -> DVec3 {
        let r = segment.rotate(r);
        match self {
            Self::Rest => r,
            Self::Lorentz(map) => map.apply(r),
            Self::BornRigid => segment.born_rigid_offset(t, r),
        }
    }
}

/// A body's shape along its worldline, segment by segment: what the optics
/// kernels place its points with. [`Rigid`] (the rest shape) and
/// [`ContractedShape`] (Lorentz contraction, written by the kinematics
/// phase) implement it.
pub trait ShapeMaps: Sync {
    /// The shape on `segment`, the `k`-th of the body's worldline.
    fn on_segment(&self, k: usize, segment: &Segment) -> SegmentShape;

    /// The shape while the body moves with proper velocity `u`: for a
    /// sample of the paper's history, which holds the velocity of each
    /// frame rather than a segment (the instantaneous contraction then).
    fn moving_with(&self, u: ProperVelocity) -> LorentzMap;
}

/// The rest shape on every segment (a view without contraction).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rigid;

impl ShapeMaps for Rigid {
    #[inline]
    fn on_segment(&self, _: usize, _: &Segment) -> SegmentShape {
        SegmentShape::Rest
    }

    #[inline]
    fn moving_with(&self, _: ProperVelocity) -> LorentzMap {
        LorentzMap::IDENTITY
    }
}

/// A body's Lorentz-contracted shape along its worldline: the
/// [`SegmentShape::contracted`] of each segment, kept from frame to frame
/// by [`Self::update`], which computes only the maps of segments that are
/// new or changed.
///
/// A worldline grows at its end, replaces its last segment, or forgets its
/// oldest ([`Worldline::push`], [`Worldline::relocate`],
/// [`Worldline::forget_before`]); [`Self::update`] checks its first segment
/// and the one before its last against those it saw and starts again when
/// either changed (a history forgotten, friction put on). A worldline
/// rewritten in its middle with both of those unchanged
/// ([`Worldline::truncate_after`], or another worldline put in its place)
/// would keep stale maps: [`Self::clear`] first (as
/// `ecs::Simulation::replace_physics` does).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContractedShape {
    maps: Vec<SegmentShape>,
    /// The first segment seen at the last update.
    first: Option<Segment>,
    /// The last segment but one seen at the last update (if there were two).
    settled: Option<Segment>,
}

impl ContractedShape {
    /// The contracted shape along `worldline`.
    #[must_use]
    pub fn of(worldline: &Worldline) -> Self {
        let mut shape = Self::default();
        shape.update(worldline);
        shape
    }

    /// Brings the maps up to `worldline`: recomputes the last one seen and
    /// adds those of the segments added since (all of them if the
    /// worldline's start or settled past changed).
    pub fn update(&mut self, worldline: &Worldline) {
        let segments = worldline.segments();
        let m = self.maps.len();
        let same = |i: usize, seen: &Segment| segments.get(i) == Some(seen);
        let keep = match (&self.first, &self.settled) {
            (Some(first), settled)
                if m <= segments.len()
                    && same(0, first)
                    && settled.as_ref().is_none_or(|s| m >= 2 && same(m - 2, s)) =>
            {
                m.saturating_sub(1)
            }
            _ => 0,
        };
        self.maps.truncate(keep);
        self.maps
            .extend(segments[keep..].iter().map(SegmentShape::contracted));
        let n = segments.len();
        self.first = Some(segments[0]);
        self.settled = (n >= 2).then(|| segments[n - 2]);
    }

    /// The maps, one per segment of the worldline last updated from.
    #[must_use]
    pub fn maps(&self) -> &[SegmentShape] {
        &self.maps
    }

    /// Forgets every map (a body no view sees contracted).
    pub fn clear(&mut self) {
        *self = Self::default();
    }
}

impl ShapeMaps for ContractedShape {
    /// The map computed for segment `k`; computed now if the maps do not
    /// reach it (not updated since the worldline grew).
    #[inline]
    fn on_segment(&self, k: usize, segment: &Segment) -> SegmentShape {
        self.maps
            .get(k)
            .copied()
            .unwrap_or_else(|| SegmentShape::contracted(segment))
    }

    #[inline]
    fn moving_with(&self, u: ProperVelocity) -> LorentzMap {
        LorentzMap::of(u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::Event;

    #[test]
    fn the_map_is_r_minus_one_minus_inverse_gamma_along_the_motion() {
        // β = 0.6 along (0.6, 0.8): γ = 1.25 exactly, 1 − 1/γ = 0.2.
        let n = DVec3::new(0.6, 0.8, 0.0);
        let u = ProperVelocity(n * 0.75); // γβ = 1.25 × 0.6
        let map = LorentzMap::of(u);
        assert!((map.inverse_gamma() - 0.8).abs() < 1e-15);
        for r in [
            DVec3::new(0.03, 0.0, 0.01),
            DVec3::new(-0.01, 0.02, 0.0),
            n * 0.5,
            DVec3::new(-0.8, 0.6, 0.3),
        ] {
            let expected = r - 0.2 * r.dot(n) * n;
            assert!(
                (map.apply(r) - expected).length() <= 4.0 * f64::EPSILON * r.length(),
                "{r}"
            );
        }
        assert_eq!(LorentzMap::of(ProperVelocity::ZERO), LorentzMap::IDENTITY);
        assert_eq!(
            LorentzMap::IDENTITY.apply(DVec3::new(1.0, -2.0, 3.0)),
            DVec3::new(1.0, -2.0, 3.0)
        );
    }

    #[test]
    fn on_a_uniform_segment_the_shape_is_the_segments_contraction() {
        let u = ProperVelocity(DVec3::new(2.0, -1.0, 0.0));
        let mut w = Worldline::new(Event::new(0.0, DVec3::ZERO), u, 1.42);
        w.push(0.5, ProperVelocity(DVec3::new(-0.3, 0.7, 0.0)))
            .unwrap();
        let r = DVec3::new(0.03, 0.01, 0.02);
        for (k, s) in w.segments().iter().enumerate() {
            let shape = ContractedShape::of(&w).on_segment(k, s);
            assert_eq!(shape.place(s, 0.7, r), s.place_at(0.7, r));
            assert_eq!(Rigid.on_segment(k, s).place(s, 0.7, r), s.rotate(r));
        }
    }

    #[test]
    fn a_moving_puck_is_an_ellipse_of_semi_axes_r_over_gamma_and_r() {
        let shape = crate::worldline::RestShape::puck(0.5, 0.1, 64);
        let u = ProperVelocity::try_from_beta(DVec3::new(0.8, 0.0, 0.0)).unwrap();
        let w = Worldline::new(Event::new(0.0, DVec3::new(1.0, 1.0, 0.0)), u, 1.0);
        let s = &w.segments()[0];
        let contracted = ContractedShape::of(&w).on_segment(0, s);
        for &r in &shape.vertices {
            let d = contracted.place(s, 1.0, r);
            // (x γ / R)² + (y / R)² = 1 on the rim (γ = 5/3); the axis points at 0.
            let e = (d.x / 0.6 / 0.5).powi(2) + (d.y / 0.5).powi(2);
            assert!(e < 1.0 + 1e-12, "{e}");
        }
        let max_x = |m: SegmentShape| {
            shape
                .vertices
                .iter()
                .map(|&r| m.place(s, 1.0, r).x)
                .fold(0.0, f64::max)
        };
        assert!((max_x(contracted) - 0.3).abs() < 1e-15);
        assert!((max_x(Rigid.on_segment(0, s)) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn updated_maps_equal_maps_built_afresh() {
        // Grown, last segment replaced, braking, come to rest, history
        // forgotten, a rest segment put first: each update equals `of`.
        let c = 1.42;
        let mut w = Worldline::braking(
            Event::new(0.0, DVec3::new(0.3, 0.2, 0.0)),
            ProperVelocity(DVec3::new(1.5, 0.4, 0.0)),
            c,
            0.8,
        );
        let mut shape = ContractedShape::default();
        let check = |w: &Worldline, shape: &mut ContractedShape| {
            shape.update(w);
            assert_eq!(shape.maps(), ContractedShape::of(w).maps());
            assert_eq!(shape.maps().len(), w.segments().len());
        };
        check(&w, &mut shape);
        w.rest_before_start();
        check(&w, &mut shape);
        for k in 1..8 {
            let t = 0.1 * f64::from(k);
            let u = ProperVelocity(DVec3::new(f64::from(k % 3) - 1.0, 0.5, 0.0));
            w.push(t, u).unwrap();
            check(&w, &mut shape);
            // A second kink at the same time replaces the last segment.
            w.push(t, ProperVelocity(u.0 * 1.5)).unwrap();
            check(&w, &mut shape);
        }
        w.come_to_rest();
        check(&w, &mut shape);
        w.forget_before(0.45);
        check(&w, &mut shape);
        w.forget_history();
        check(&w, &mut shape);
        assert!(
            shape
                .maps()
                .iter()
                .all(|m| matches!(m, SegmentShape::Rest | SegmentShape::BornRigid))
        );
    }
}
