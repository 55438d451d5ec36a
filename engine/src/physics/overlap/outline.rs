//! A puck's board-frame shape as the overlap measures read it: its rest
//! disc contracted along its motion, with the support function, its
//! slopes and the support point in closed form.

use glam::DVec3;

use crate::worldline::Segment;

/// A puck's board-frame shape as the gap function reads it: its rest disc
/// (radius `radius`, m) contracted by `1/γ` along the unit direction `n` of
/// its motion on the board (any unit direction at rest, where `1/γ = 1`).
/// Pucks move in the board plane, so directions are `(cos, sin)` in it.
///
/// It also keeps the board velocity (m/s) it moves with: [`super::gap_min`] tries
/// the direction of motion as a candidate axis.
#[derive(Clone, Copy, Debug)]
pub struct Outline {
    pub(super) nx: f64,
    pub(super) ny: f64,
    pub(super) inverse_gamma: f64,
    pub(super) radius: f64,
    pub(super) velocity: DVec3,
}

impl Outline {
    /// The shape of a puck of rest radius `radius` (m) on `segment` (a
    /// uniform or rest one: its one contraction).
    #[must_use]
    pub fn of(segment: &Segment, radius: f64) -> Self {
        let map = segment.lorentz_map();
        Self::from_map(
            map.direction(),
            map.inverse_gamma(),
            radius,
            segment.velocity(),
        )
    }

    /// The shape of a puck of rest radius `radius` (m) moving with proper
    /// velocity `u` on a board where light moves at `c` (m/s): the same
    /// values, to the bit, as [`Self::of`] the uniform segment with that
    /// proper velocity (what a braking segment's tangent is), without
    /// building the segment.
    #[must_use]
    pub fn moving(u: crate::spacetime::ProperVelocity, radius: f64, c: f64) -> Self {
        let gamma = u.gamma();
        let speed = u.0.length();
        let direction = if speed > 0.0 {
            u.0 / speed
        } else {
            DVec3::ZERO
        };
        Self::from_map(direction, 1.0 / gamma, radius, u.0 * (c / gamma))
    }

    /// The shape of a puck of rest radius `radius` (m) moving along the
    /// unit direction `n` (zero at rest) with `1/γ = inverse_gamma` and
    /// board velocity `velocity` (m/s).
    #[must_use]
    pub fn along(n: DVec3, inverse_gamma: f64, radius: f64, velocity: DVec3) -> Self {
        Self::from_map(n, inverse_gamma, radius, velocity)
    }

    fn from_map(n: DVec3, inverse_gamma: f64, radius: f64, velocity: DVec3) -> Self {
        let (nx, ny) = if n.x == 0.0 && n.y == 0.0 {
            (1.0, 0.0)
        } else {
            (n.x, n.y)
        };
        Self {
            nx,
            ny,
            inverse_gamma,
            radius,
            velocity,
        }
    }

    /// The rest radius, m.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Support function in the unit direction `(cos, sin)`, m: `R
    /// |contract(m)| = R √((n⊥·m)² + ((n·m)/γ)²)`, the contracted
    /// component formed as a product (no `1 − 1/γ²`: exact to rounding at
    /// any γ).
    #[inline(always)]
    pub(super) fn support(&self, cos: f64, sin: f64) -> f64 {
        let along = (self.nx * cos + self.ny * sin) * self.inverse_gamma;
        let across = self.nx * sin - self.ny * cos;
        self.radius * (across * across + along * along).sqrt()
    }

    /// The point of the shape farthest along the unit direction `(cos,
    /// sin)`, as an offset from its centre, m: `R contract(contract(m)) /
    /// |contract(m)|` (the rest-frame rim point `R contract(m)/|contract(m)|`,
    /// contracted).
    #[inline(always)]
    pub(super) fn support_point(&self, cos: f64, sin: f64) -> DVec3 {
        let ig = self.inverse_gamma;
        let along = self.nx * cos + self.ny * sin;
        let across = self.nx * sin - self.ny * cos;
        let scale = self.radius / (across * across + along * ig * (along * ig)).sqrt();
        let (a, c) = (along * ig * ig * scale, across * scale);
        DVec3::new(self.nx * a - self.ny * c, self.ny * a + self.nx * c, 0.0)
    }

    /// The offset `w` (m, from the centre) in units of the shape: `|r|/R`
    /// for the rest-frame offset `r` it is the contraction of (1 on the
    /// rim, below 1 inside).
    #[inline(always)]
    pub(super) fn elliptic_norm(&self, w: DVec3) -> f64 {
        let along = self.nx * w.x + self.ny * w.y;
        let across = self.nx * w.y - self.ny * w.x;
        let rest = along / self.inverse_gamma;
        (across * across + rest * rest).sqrt() / self.radius
    }

    /// How fast the support in the unit direction `(cos, sin)` grows while
    /// `1/γ` changes at `rate` (1/s), m/s: `R ((n·m)²/γ) rate / |contract(m)|`.
    #[must_use]
    pub fn support_rate(&self, cos: f64, sin: f64, rate: f64) -> f64 {
        let ig = self.inverse_gamma;
        let along = self.nx * cos + self.ny * sin;
        let across = self.nx * sin - self.ny * cos;
        let contracted = along * ig;
        self.radius * along * contracted * rate / (across * across + contracted * contracted).sqrt()
    }

    /// `√A`, `A′` and `A″` of [`Self::support_slopes`] at `(cos, sin)`
    /// (the support is `R √A`).
    #[inline(always)]
    fn support_terms(&self, cos: f64, sin: f64) -> (f64, f64, f64) {
        let ig = self.inverse_gamma;
        let along = self.nx * cos + self.ny * sin;
        let across = self.nx * sin - self.ny * cos;
        let contracted = along * ig;
        let root = (across * across + contracted * contracted).sqrt();
        let k = 2.0 * (1.0 - ig) * (1.0 + ig);
        (
            root,
            k * along * across,
            k * (along - across) * (along + across),
        )
    }

    /// The support's first and second derivatives in the direction's angle
    /// at `(cos, sin)`, m/rad and m/rad²: with `A = (n⊥·m)² + ((n·m)/γ)²`,
    /// `A′ = 2 (1 − 1/γ²)(n·m)(n⊥·m)`, `A″ = 2 (1 − 1/γ²)((n·m)² − (n⊥·m)²)`
    /// and `h = R√A`.
    #[inline(always)]
    pub(super) fn support_slopes(&self, cos: f64, sin: f64) -> (f64, f64) {
        let (root, a1, a2) = self.support_terms(cos, sin);
        let first = 0.5 * a1 / root;
        (
            self.radius * first,
            self.radius * (0.5 * a2 - first * first) / root,
        )
    }

    /// The least radius of curvature of the outline, m: `R/γ²`, `b²/a` of an
    /// ellipse with semi-axes `a = R` (across the motion) and `b = R/γ`
    /// (along it), at the ends of the long axis, across the motion (at the
    /// ends of the contracted axis it is the largest, `R γ`).
    #[inline]
    pub(super) fn least_curvature_radius(&self) -> f64 {
        self.radius * self.inverse_gamma * self.inverse_gamma
    }

    /// The support in the unit direction `(cos, sin)` (m, the bits of
    /// [`Self::support`]) with its first and second derivatives in the
    /// direction's angle ([`Self::support_slopes`]'s to rounding), from one
    /// square root and one division (the braking search's axis refinement).
    #[inline(always)]
    pub(super) fn support_with_slopes(&self, cos: f64, sin: f64) -> (f64, f64, f64) {
        let (root, a1, a2) = self.support_terms(cos, sin);
        // One division: the slopes are over `root` and `root²`.
        let per_root = root.recip();
        let first = 0.5 * a1 * per_root;
        (
            self.radius * root,
            self.radius * first,
            self.radius * (0.5 * a2 - first * first) * per_root,
        )
    }
}
