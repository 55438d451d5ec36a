//! How much two pucks overlap on the board, and how much relativity forces
//! them to.
//!
//! **Measure.** At one board time each puck is an ellipse (its rest disc
//! contracted by `1/γ` along its motion). The overlap is the *penetration
//! depth*: the shortest translation that separates the two shapes,
//! `max(0, min over unit m of [h_A(m) + h_B(m) − m·(x_B − x_A)])`, where
//! `h(m) = R |contract(m)|` is a contracted disc's support function (the
//! contraction is symmetric, so the support of `{contract(r) : |r| ≤ R}` in
//! direction `m` is `R |contract(m)|`).
//!
//! **Bound.** Rigid bodies cannot exist in relativity (the paper's §3.3.1):
//! a contact cannot change a whole body's velocity at once in every frame.
//! Lightcone changes both pucks' velocities at the events simultaneous with
//! the contact in the pair frame (see `predict::puck_puck`). Three things
//! then let the board-frame shapes overlap, and nothing else:
//!
//! 1. **The board slice is not the pair frame's.** Until the first kick both
//!    pucks move uniformly, and their world tubes meet first (in pair-frame
//!    time) at the contact event. A board-time slice is tilted against the
//!    pair frame's: the slice through the first kick can already cut the
//!    tubes' intersection, which lies wholly after the contact in pair time
//!    (no kick could have been placed there: it is not yet "after the
//!    contact" at both centres). Its depth, `early`, is that of the two
//!    unperturbed shapes at the first kick's board time; before the first
//!    kick the depth is smaller (it grows with the approach).
//! 2. **Contraction changes at once.** A kick changes a puck's contraction
//!    for its whole body at the kick event. In the pair frame, where the two
//!    shapes are exactly touching at the contact, each puck moves with the
//!    same Lorentz factor `γ′`; a kick can grow it back towards its rest
//!    disc by at most `R (1 − 1/γ′)` along the old direction of motion.
//! 3. **The kicks are simultaneous only in the pair frame.** On the board
//!    the two kicks are `Δt` apart; meanwhile the first-kicked puck already
//!    moves with its new velocity and the other still with its old one, so
//!    the two can close by at most `Δt |v_first,after − v_second,before|`.
//!
//! So the overlap a contact can leave is at most
//! `early + R_a (1 − 1/γ′) + R_b (1 − 1/γ′) + Δt |Δv|` ([`bound`]). After
//! both kicks the pucks separate (elastic) or move together (restitution
//! 0), so it does not grow. Terms 1 and 3 vanish when the pair frame is the
//! board frame (a symmetric head-on hit); term 2 vanishes as `γ′ → 1`; all
//! vanish in the Newtonian limit.
//!
//! This file measures (the gap function, its scan, the first touch);
//! `outline` holds a puck's contracted shape ([`Outline`]), `contact`
//! where and along what two touching shapes meet ([`contact_point`],
//! [`contact_normal`]), and `proofs` the cheap one-sided tests that let
//! the event loop skip the measurement ([`apart_throughout`],
//! [`overlap_certain`]).

use glam::DVec3;

use crate::worldline::Segment;

mod contact;
mod outline;
mod proofs;

pub use contact::{contact_normal, contact_point, contact_point_at};
pub use outline::Outline;
pub use proofs::{apart_throughout, overlap_certain};

/// The most two pucks of rest radii `radii` (m) can overlap on the board
/// because of one contact: `early` (m), the depth of the two unperturbed
/// shapes at the first kick's board time, plus each puck's growth back
/// towards its rest disc, `R (1 − 1/γ′)` with `γ′` their Lorentz factor in
/// the pair frame before the contact, plus `slide` (m), the closing
/// distance on the board between the two kicks
/// (`Δt |v_first,after − v_second,before|`).
#[must_use]
pub fn bound(radii: [f64; 2], gamma_pair: f64, slide: f64, early: f64) -> f64 {
    let grow = (gamma_pair - 1.0).max(0.0) / gamma_pair.max(1.0);
    early.max(0.0) + (radii[0] + radii[1]) * grow + slide.abs()
}

/// The linear function of the separation `d` (m, b − a) whose minimum over
/// unit directions `(cos, sin)` is the gap function: `h_a(m) + h_b(m) −
/// m·d`. One expression, so that every caller computes the same bits.
#[inline(always)]
fn gap_along(a: &Outline, b: &Outline, cos: f64, sin: f64, d: DVec3) -> f64 {
    (a.support(cos, sin) + b.support(cos, sin)) - (cos * d.x + sin * d.y)
}

/// Penetration depth of two pucks at board time `t` on the board, m: 0 if
/// their shapes do not overlap. `a` and `b` are the segments in force at `t`.
/// Accurate to about 1e-12 of the radii (a sampled minimum of a smooth
/// function of one angle, refined by Newton's method).
#[must_use]
pub fn depth(a: &Segment, radius_a: f64, b: &Segment, radius_b: f64, t: f64) -> f64 {
    penetration(a, radius_a, b, radius_b, t).map_or(0.0, |(d, _)| d)
}

/// The penetration depth (m, > 0) and its direction (unit, board frame,
/// from `a` towards `b`: translating `b` by `depth` along it separates
/// them) if the two pucks overlap at board time `t`; `None` if they do not.
/// Between kicks the depth changes at the rate `−m·(v_b − v_a)`.
#[must_use]
pub fn penetration(
    a: &Segment,
    radius_a: f64,
    b: &Segment,
    radius_b: f64,
    t: f64,
) -> Option<(f64, DVec3)> {
    let d = b.position_at(t) - a.position_at(t);
    if d.length() >= radius_a + radius_b {
        return None; // rest discs apart: shapes, which lie inside, are too
    }
    let (g, m) = gap(a, radius_a, b, radius_b, d);
    (g > 0.0).then_some((g, m))
}

/// The signed gap function of two shapes whose centres are `d` apart (b −
/// a): `min over unit m of [h_a(m) + h_b(m) − m·d]` and its minimiser: the
/// penetration depth when positive. When the line of centres already
/// separates the shapes, that axis and its (negative) value are returned
/// at once: a separating axis, not always the widest.
#[must_use]
pub fn gap(a: &Segment, radius_a: f64, b: &Segment, radius_b: f64, d: DVec3) -> (f64, DVec3) {
    gap_of(&Outline::of(a, radius_a), &Outline::of(b, radius_b), d)
}

/// [`gap`] of two shapes given as outlines.
#[must_use]
pub fn gap_of(oa: &Outline, ob: &Outline, d: DVec3) -> (f64, DVec3) {
    centre_line_gap_of(oa, ob, d).unwrap_or_else(|| gap_min_of(oa, ob, d))
}

/// [`gap`]'s quick answer: the line of centres separates the shapes often
/// (its value is an upper bound of the minimum, exact for two discs); its
/// (non-positive) value and direction if it does, `None` if [`gap_min`] is
/// needed.
fn centre_line_gap(
    a: &Segment,
    radius_a: f64,
    b: &Segment,
    radius_b: f64,
    d: DVec3,
) -> Option<(f64, DVec3)> {
    centre_line_gap_of(&Outline::of(a, radius_a), &Outline::of(b, radius_b), d)
}

/// [`centre_line_gap`] of two outlines.
fn centre_line_gap_of(oa: &Outline, ob: &Outline, d: DVec3) -> Option<(f64, DVec3)> {
    let dist = d.length();
    if dist > 0.0 {
        let m = d / dist;
        let g = oa.support(m.x, m.y) + ob.support(m.x, m.y) - dist;
        if g <= 0.0 {
            return Some((g, m)); // separated: the exact value is not needed
        }
    }
    None
}

/// Whether [`penetration`] of two pucks whose centres are `d` apart (m,
/// b − a) runs the full overlap scan ([`gap_min`]): only when their rest
/// discs overlap and the line of centres does not separate their shapes.
/// Otherwise it finds no overlap at once.
#[must_use]
pub fn penetration_needs_scan(
    a: &Segment,
    radius_a: f64,
    b: &Segment,
    radius_b: f64,
    d: DVec3,
) -> bool {
    d.length() < radius_a + radius_b && centre_line_gap(a, radius_a, b, radius_b, d).is_none()
}

/// [`refine_warm_within`] keeps an axis once Newton's next step would
/// lower the value by less than this fraction of it.
const ACCEPT: f64 = 1e-9;

/// Number of directions [`gap_min`] scans (uniform in angle).
const SAMPLES: usize = 90;

/// The directions [`gap_min`] scans, `cos θ_k` then `sin θ_k` with `θ_k =
/// k 2π / SAMPLES`, as two arrays (the scan's loop over them vectorises),
/// computed once.
fn scan() -> &'static ([f64; SAMPLES], [f64; SAMPLES]) {
    static SCAN: std::sync::OnceLock<([f64; SAMPLES], [f64; SAMPLES])> = std::sync::OnceLock::new();
    SCAN.get_or_init(|| {
        let theta = |k: usize| k as f64 * (std::f64::consts::TAU / SAMPLES as f64);
        (
            std::array::from_fn(|k| theta(k).cos()),
            std::array::from_fn(|k| theta(k).sin()),
        )
    })
}

/// The gap function itself, `min over unit m of [h_a(m) + h_b(m) − m·d]`,
/// and its minimiser, also where the shapes are apart (then negative: minus
/// the widest separation). Unlike [`gap`]'s quick answer, this is concave
/// in `d` moving linearly (a minimum of functions linear in it), which
/// [`first_touch`] needs.
#[must_use]
pub fn gap_min(a: &Segment, radius_a: f64, b: &Segment, radius_b: f64, d: DVec3) -> (f64, DVec3) {
    gap_min_of(&Outline::of(a, radius_a), &Outline::of(b, radius_b), d)
}

/// [`gap_min`] of two outlines.
#[must_use]
pub fn gap_min_of(oa: &Outline, ob: &Outline, d: DVec3) -> (f64, DVec3) {
    let f = |cos: f64, sin: f64| gap_along(oa, ob, cos, sin, d);
    // Candidates: a uniform scan, plus where the function has its kinks and
    // narrow valleys: a fast puck's shape is a thin ellipse whose support
    // is smallest (a valley of angular width ~1/γ) along its motion.
    let (cos, sin) = scan();
    let mut values = [0.0; SAMPLES];
    for k in 0..SAMPLES {
        values[k] = f(cos[k], sin[k]);
    }
    let mut best = (f64::INFINITY, DVec3::X);
    for (k, &v) in values.iter().enumerate() {
        if v < best.0 {
            best = (v, DVec3::new(cos[k], sin[k], 0.0));
        }
    }
    for axis in [oa.velocity, ob.velocity, d] {
        let axis = DVec3::new(axis.x, axis.y, 0.0);
        let length = axis.length();
        if length > 0.0 {
            for m in [axis / length, -axis / length] {
                let v = f(m.x, m.y);
                if v < best.0 {
                    best = (v, m);
                }
            }
        }
    }
    let refine = |m0: DVec3| {
        refine_near(oa, ob, d, m0).unwrap_or_else(|| {
            let (across, half) = (DVec3::new(-m0.y, m0.x, 0.0), half_step_tangent());
            let s = golden_min(
                |s| {
                    let m = turned(m0, across, s);
                    f(m.x, m.y)
                },
                -half,
                half,
                80,
            )
            .1;
            let m = turned(m0, across, s);
            (f(m.x, m.y), m)
        })
    };
    let mut result = best;
    let mut keep = |(v, m): (f64, DVec3)| {
        if v < result.0 {
            result = (v, m);
        }
    };
    keep(refine(best.1));
    // Every other valley the scan sees that could hold the minimum: a
    // local minimum of the samples whose value is within what one step
    // away from a minimum can add, `K Δφ²/8` with `K ≥ f″ = Σ R γ + |d|`
    // (the support's curvature is at most `R γ`). Two nearly equal
    // valleys (an elongated shape and a separation across it) are then
    // both refined, not only the one whose sample fell nearer its floor.
    // A sample within one step of the best candidate is in the valley
    // just refined.
    let step = std::f64::consts::TAU / SAMPLES as f64;
    let curvature = oa.radius / oa.inverse_gamma + ob.radius / ob.inverse_gamma + d.length();
    let slack = curvature * step * step / 8.0 * (1.0 + 1e-9);
    let (threshold, near_best) = (best.0 + slack, cos[1]);
    for k in 0..SAMPLES {
        if values[k] > threshold {
            continue; // nearly every sample: the test that decides is cheap
        }
        let before = values[if k == 0 { SAMPLES - 1 } else { k - 1 }];
        let after = values[if k + 1 == SAMPLES { 0 } else { k + 1 }];
        let m = DVec3::new(cos[k], sin[k], 0.0);
        if values[k] <= before && values[k] <= after && m.dot(best.1) < near_best {
            keep(refine(m));
        }
    }
    result
}

/// The direction `m0` turned by the angle `φ = 2 atan s` towards `across`
/// (`m0` turned by +90°), without trigonometry: `((1 − s²) m0 + 2 s
/// across) / (1 + s²)`, monotone in `φ`.
#[inline(always)]
fn turned(m0: DVec3, across: DVec3, s: f64) -> DVec3 {
    (m0 * (1.0 - s * s) + across * (2.0 * s)) * (1.0 + s * s).recip()
}

/// The minimum of the gap function's integrand `h_a(m) + h_b(m) − m·d`
/// within one scan step (`2π / SAMPLES`) either side of the unit direction
/// `m0`, and where it is, if the slope brackets one there: Newton's method
/// on the slope in `s = tan(φ/2)` (a search over `s` sees the same one
/// valley), kept inside a bracket of its sign changes. `None` where the
/// slopes at the two ends do not bracket a minimum.
///
/// A value below zero is minus the length of a separating axis's gap, so
/// minus a lower bound of the shapes' distance whatever its accuracy; and
/// where the shapes are apart the integrand has one valley below zero (its
/// sublevel sets below zero are arcs: the directions that separate two
/// convex shapes by more than a given amount form one arc), so a local
/// minimum below zero is the global one, [`gap_min`]'s value to rounding.
#[must_use]
pub fn refine_near(oa: &Outline, ob: &Outline, d: DVec3, m0: DVec3) -> Option<(f64, DVec3)> {
    refine_within(oa, ob, d, m0, half_step_tangent())
}

/// [`refine_near`] over directions within `2 atan(half)` of `m0` either
/// side (`half = tan(π/12)`: 30°), for a start that may be farther from
/// the minimum than one scan step (the line of centres of contracted
/// shapes). What it returns means the same: a value below zero is the
/// global minimum (one valley below zero), any value is the integrand's at
/// the direction returned.
#[must_use]
pub fn refine_within(
    oa: &Outline,
    ob: &Outline,
    d: DVec3,
    m0: DVec3,
    half: f64,
) -> Option<(f64, DVec3)> {
    let across = DVec3::new(-m0.y, m0.x, 0.0);
    let slopes = |s: f64| {
        let m = turned(m0, across, s);
        let (a1, a2) = oa.support_slopes(m.x, m.y);
        let (b1, b2) = ob.support_slopes(m.x, m.y);
        // In the angle φ, then in s (dφ/ds = 2/(1 + s²)).
        let first = a1 + b1 - (m.x * d.y - m.y * d.x);
        let second = a2 + b2 + (m.x * d.x + m.y * d.y);
        let w = 1.0 + s * s;
        let (ds, dds) = (2.0 / w, -4.0 * s / (w * w));
        (first * ds, second * ds * ds + first * dds)
    };
    let s = slope_root(slopes, -half, half)?;
    let m = turned(m0, across, s);
    Some((gap_along(oa, ob, m.x, m.y, d), m))
}

/// [`refine_near`] for a start `m0` near the minimum already (the last
/// probe's axis in a search over time): Newton's method on the slope from
/// `m0` itself, without first checking the ends of the step either side;
/// `None` if a step leaves them or the function is not convex there.
/// Whatever it returns is the integrand's value at the direction returned
/// (so a negative one is minus a separating axis's gap), as for
/// [`refine_near`].
#[must_use]
pub fn refine_warm(oa: &Outline, ob: &Outline, d: DVec3, m0: DVec3) -> Option<(f64, DVec3)> {
    refine_warm_within(oa, ob, d, m0, half_step_tangent())
}

/// [`refine_warm`] over directions within `2 atan(half)` of `m0` either
/// side (as [`refine_within`] is to [`refine_near`]).
#[must_use]
pub fn refine_warm_within(
    oa: &Outline,
    ob: &Outline,
    d: DVec3,
    m0: DVec3,
    half: f64,
) -> Option<(f64, DVec3)> {
    let across = DVec3::new(-m0.y, m0.x, 0.0);
    let mut s = 0.0f64;
    for _ in 0..8 {
        let m = turned(m0, across, s);
        let (ha, a1, a2) = oa.support_with_slopes(m.x, m.y);
        let (hb, b1, b2) = ob.support_with_slopes(m.x, m.y);
        let first = a1 + b1 - (m.x * d.y - m.y * d.x);
        let second = a2 + b2 + (m.x * d.x + m.y * d.y);
        // In `s` (`dφ/ds = 2/w`, `d²φ/ds² = −4s/w²`, `w = 1 + s²`) the
        // slopes are `f₁ = 2 first/w` and `f₂ = 4 (second − s first)/w²`,
        // so Newton's step `f₁/f₂` is `w first / (2 (second − s first))`.
        let w = 1.0 + s * s;
        let curvature = second - s * first;
        if curvature.is_nan() || curvature <= 0.0 {
            return None;
        }
        let step = w * first / (2.0 * curvature);
        // What the step would still take off the value (Newton's
        // quadratic model's fall, `f₁ step/2 = first step/w`) is below
        // 1e-9 of it: this axis's value (the bits of `gap_along`) is kept.
        let value = (ha + hb) - (m.x * d.x + m.y * d.y);
        if first * step <= ACCEPT * value.abs() * w {
            return Some((value, m));
        }
        s -= step;
        if s.is_nan() || s.abs() > half {
            return None;
        }
        if step.abs() <= 8.0 * f64::EPSILON * half {
            let m = turned(m0, across, s);
            return Some((gap_along(oa, ob, m.x, m.y, d), m));
        }
    }
    let m = turned(m0, across, s);
    Some((gap_along(oa, ob, m.x, m.y, d), m))
}

/// Whether two shapes whose centres are `d` apart (m, b − a) are shown to
/// overlap near the unit direction `m` (the one of a local minimum of the
/// gap function's integrand above zero, [`refine_near`]): the midpoint of
/// `a`'s farthest point along `m` and `b`'s farthest along `−m` lies inside
/// both (elliptic norms below 1, to rounding). Where the shapes overlap
/// along `m` by a depth `δ` and `m` is the contact normal, that midpoint is
/// `δ/2` inside each. `false` says nothing.
#[must_use]
pub fn overlap_near(oa: &Outline, ob: &Outline, d: DVec3, m: DVec3) -> bool {
    let pa = oa.support_point(m.x, m.y);
    let pb = d - ob.support_point(m.x, m.y);
    let q = (pa + pb) * 0.5;
    oa.elliptic_norm(q) < 1.0 && ob.elliptic_norm(q - d) < 1.0
}

/// Whether two shapes whose centres are `d` apart (m, b − a) are shown to
/// touch or overlap, to within `slack` (m), from one unit direction `m`
/// alone, without a scan: where the shapes merely touch (a root isolation's
/// probe at its contact) [`overlap_near`] finds no point inside both, and
/// the gap `g(m) = h_a(m) + h_b(m) − m·d` only says `m` does not separate
/// them. `true` when `g(m) ≥ 0`, `g(m) < ρ/2` and `g′(m)²/ρ − g(m) ≤
/// slack`, `ρ` the sum of the two ellipses' least radii of curvature
/// (`R/γ²` each); `false` says nothing.
///
/// Why: with `f(φ) = m(φ)·d − h(m(φ))`, `h = h_a + h_b` the support of the
/// Minkowski sum `K` of the two shapes, whose radius of curvature `h + h″`
/// is at least `ρ` everywhere (radii of curvature add at one normal),
/// `f″ = −m·d − h″ = −f − (h + h″) ≤ −f − ρ`. The shapes are apart iff
/// `max f > 0`. Where `f > −ρ`, `m·d > h(m) − ρ`, the support of `K`
/// shrunk by a disc of radius `ρ` (convex, since `(h − ρ) + (h − ρ)″ ≥ 0`):
/// the directions that separate the point `d` from a convex body form one
/// arc (a positive combination of two separating directions separates), so
/// `{f > −ρ}` is one arc, on which `f″ < 0`. With `f(m) > −ρ/2` the set
/// `{f ≥ f(m)}` is a sub-arc holding `m` and the maximum, on which `f″ ≤
/// −ρ/2`, so `max f ≤ f(m) + f′(m)²/ρ`: at most `slack` apart.
#[must_use]
pub fn touch_shown(oa: &Outline, ob: &Outline, d: DVec3, m: DVec3, slack: f64) -> bool {
    let rho = oa.least_curvature_radius() + ob.least_curvature_radius();
    let (ha, a1, _) = oa.support_with_slopes(m.x, m.y);
    let (hb, b1, _) = ob.support_with_slopes(m.x, m.y);
    let g = ha + hb - (m.x * d.x + m.y * d.y);
    let slope = a1 + b1 - (m.x * d.y - m.y * d.x);
    g >= 0.0 && g < 0.5 * rho && slope * slope / rho - g <= slack
}

/// Where the slope of a function of `s` changes sign from negative to
/// positive on `[lo, hi]` (its minimum there), by Newton's method on the
/// slope (`slopes(s)` = first and second derivatives), each step kept
/// inside the bracket and halving it when Newton's would not (Numerical
/// Recipes' `rtsafe`); done when a Newton step is down to the rounding of
/// `s` (a few ulps of the bracket's size), or the bracket to 10⁻¹⁶. `None`
/// unless the slope is negative at `lo` and positive at `hi`.
fn slope_root(slopes: impl Fn(f64) -> (f64, f64), mut lo: f64, mut hi: f64) -> Option<f64> {
    if !(slopes(lo).0 < 0.0 && slopes(hi).0 > 0.0) {
        return None;
    }
    // A Newton step this small is rounding: taking it (or not) changes
    // nothing, and refusing it would bisect the rest of the bracket.
    let converged = 8.0 * f64::EPSILON * lo.abs().max(hi.abs());
    let mut s = 0.5 * (lo + hi);
    let mut step = hi - lo;
    for _ in 0..200 {
        let (first, second) = slopes(s);
        if first == 0.0 {
            break;
        }
        if first < 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        let newton = first / second;
        if second > 0.0 && newton.abs() <= converged {
            let next = s - newton;
            if next > lo && next < hi {
                s = next;
            }
            break;
        }
        let step_before = std::mem::replace(&mut step, newton);
        if second > 0.0
            && s - newton > lo
            && s - newton < hi
            && newton.abs() < 0.5 * step_before.abs()
        {
            s -= newton;
        } else {
            step = 0.5 * (hi - lo);
            s = lo + step;
        }
        if hi - lo <= 1e-16 {
            break;
        }
    }
    Some(s)
}

/// `tan(π / SAMPLES)`: one scan step, `2π / SAMPLES`, as the half-angle
/// tangent [`gap_min`]'s refinement searches over.
fn half_step_tangent() -> f64 {
    static HALF: std::sync::OnceLock<f64> = std::sync::OnceLock::new();
    *HALF.get_or_init(|| (std::f64::consts::PI / SAMPLES as f64).tan())
}

/// Golden-section search for the minimum of `f` on `[lo, hi]` (unimodal
/// there): at most `steps` steps, stopping early once the interval is down
/// to rounding. Returns the best `(value, x)` of the last two points.
fn golden_min(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, steps: usize) -> (f64, f64) {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..steps {
        if hi - lo <= 1e-15 * hi.abs().max(1.0) {
            break;
        }
        if f1 < f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = f(x2);
        }
    }
    if f1 <= f2 { (f1, x1) } else { (f2, x2) }
}

/// The first board time in `[t0, t1]` at which two uniformly moving pucks
/// (apart at `t0`) start to overlap on the board, if they do.
///
/// The gap function `G(t)` ([`gap_min`], not [`gap`]'s quick separating
/// axis) is concave in time between kicks: a minimum of functions linear in
/// `t`, with slope `−m·(v_b − v_a)` at its minimiser `m` (Danskin). So a
/// tangent at any time bounds it from above everywhere; more precisely, for
/// the direction `m` the minimisation returns (exact or not), the line
/// `h_a(m) + h_b(m) − m·d(t)` lies above `G` for every `t`, so the bounds
/// below hold whatever the accuracy of that minimisation. The search keeps a
/// bracket whose left end rises and right end falls; the two tangents meet
/// above the bracket's maximum, and where they meet at or below zero the
/// shapes never touch (a proof, not a sample). Otherwise `G` is evaluated
/// there (or at the middle, alternately) and the bracket shrinks. The
/// first crossing of zero before a point where `G > 0` is then bisected
/// with the sign of [`gap`], which is exact. The time returned is just past
/// the crossing (the shapes overlap there, by at most a few ulps of the
/// distance). (Maximising `gap` itself, which is not concave where the shapes
/// are apart, could step over a short overlap of two thin, fast shapes
/// crossing: seeds 41 and 531 of `collision_integrity`.)
#[must_use]
pub fn first_touch(
    a: &Segment,
    radius_a: f64,
    b: &Segment,
    radius_b: f64,
    t0: f64,
    t1: f64,
) -> Option<f64> {
    if t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let v = b.velocity() - a.velocity();
    let d = |t: f64| b.position_at(t) - a.position_at(t);
    // G and its slope at t.
    let eval = |t: f64| {
        let (g, m) = gap_min(a, radius_a, b, radius_b, d(t));
        (g, -m.dot(v))
    };
    let (g0, s0) = eval(t0);
    let peak = if g0 > 0.0 {
        return Some(t0);
    } else if s0 <= 0.0 {
        return None; // not rising: concave, it never will
    } else {
        let (g1, s1) = eval(t1);
        if g1 > 0.0 {
            t1
        } else if s1 >= 0.0 {
            return None; // still rising at t1, and not above zero there
        } else {
            let (mut lo, mut hi) = ((t0, g0, s0), (t1, g1, s1));
            let mut found = None;
            for step in 0..200 {
                // The tangents at lo (rising) and hi (falling) meet at tx.
                let tx = (hi.1 - lo.1 + lo.2 * lo.0 - hi.2 * hi.0) / (lo.2 - hi.2);
                let bound = lo.1 + lo.2 * (tx - lo.0);
                if bound <= 0.0 {
                    return None;
                }
                let mid = if step % 2 == 0 && tx > lo.0 && tx < hi.0 {
                    tx
                } else {
                    0.5 * (lo.0 + hi.0)
                };
                if mid <= lo.0 || mid >= hi.0 {
                    return None; // down to rounding, and never above zero
                }
                let (gm, sm) = eval(mid);
                if gm > 0.0 {
                    found = Some(mid);
                    break;
                }
                if sm > 0.0 {
                    lo = (mid, gm, sm);
                } else {
                    hi = (mid, gm, sm);
                }
            }
            found?
        }
    };
    // Bisection for the crossing on the rising side: G(lo) ≤ 0 < G(hi).
    let sign = |t: f64| gap(a, radius_a, b, radius_b, d(t)).0 > 0.0;
    let (mut lo, mut hi) = (t0, peak);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if sign(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The braking search's support and slopes from one root
    /// (`Outline::support_with_slopes`): the support to the bit of
    /// `Outline::support`, the slopes those of `support_slopes` to 1e-12.
    #[test]
    fn the_support_with_its_slopes_is_the_support_to_the_bit() {
        let mut rng = crate::physics::gas::Rng::new(0x5109e);
        let mut next = move || rng.next_f64();
        for _ in 0..2000 {
            let angle = std::f64::consts::TAU * next();
            let n = DVec3::new(angle.cos(), angle.sin(), 0.0);
            let inverse_gamma = 10f64.powf(-4.0 * next());
            let o = Outline::along(n, inverse_gamma, 0.01 + next(), DVec3::ZERO);
            let phi = std::f64::consts::TAU * next();
            let (cos, sin) = (phi.cos(), phi.sin());
            let (h, h1, h2) = o.support_with_slopes(cos, sin);
            assert_eq!(h.to_bits(), o.support(cos, sin).to_bits());
            let (g1, g2) = o.support_slopes(cos, sin);
            let scale = o.radius() / inverse_gamma;
            assert!((h1 - g1).abs() <= 1e-12 * scale, "{h1} against {g1}");
            assert!((h2 - g2).abs() <= 1e-12 * scale, "{h2} against {g2}");
        }
    }

    /// `touch_shown` against the closed form: two ellipses (`R` across,
    /// `R/γ` along their motion, γ to 10) placed touching with the common
    /// normal `n` (centres apart by the sum of their support points along
    /// `n`, written out here from the ellipse), then moved `δ` along `n`, so
    /// that the largest separation is `δ` exactly (`|δ|` far below the
    /// least radius of curvature); the direction given is `n` turned by up
    /// to 10⁻³ rad. Whenever the shapes are shown touching they are apart
    /// by no more than the slack (plus the construction's rounding); shown
    /// for most touches within rounding along the normal that neither the
    /// gap (< 0: apart) nor the overlap test (a point inside both) decides,
    /// the cases that went to the scan. Without the slope term the test would fail: the
    /// gap alone is ≥ 0 along a turned direction for pairs apart by far
    /// more (counted).
    #[test]
    fn a_touch_shown_from_one_direction_is_a_touch() {
        let mut rng = crate::physics::gas::Rng::new(0x70c4);
        let mut next = move || rng.next_f64();
        let support_point = |n_e: DVec3, radius: f64, inverse_gamma: f64, m: DVec3| {
            let across = DVec3::new(-n_e.y, n_e.x, 0.0);
            let along_r = radius * inverse_gamma;
            let (ma, mc) = (m.dot(n_e), m.dot(across));
            let h = ((along_r * ma).powi(2) + (radius * mc).powi(2)).sqrt();
            n_e * (along_r * along_r * ma / h) + across * (radius * radius * mc / h)
        };
        let (mut shown_at_touch, mut touches, mut fooled_without_slope) = (0, 0, 0);
        for _ in 0..20_000 {
            let unit = |angle: f64| DVec3::new(angle.cos(), angle.sin(), 0.0);
            let (na, nb) = (
                unit(std::f64::consts::TAU * next()),
                unit(std::f64::consts::TAU * next()),
            );
            let (ra, rb) = (0.01 + 0.05 * next(), 0.01 + 0.05 * next());
            let (ga, gb) = (1.0 / (1.0 + 9.0 * next()), 1.0 / (1.0 + 9.0 * next()));
            let oa = Outline::along(na, ga, ra, DVec3::ZERO);
            let ob = Outline::along(nb, gb, rb, DVec3::ZERO);
            let n = unit(std::f64::consts::TAU * next());
            let touching = support_point(na, ra, ga, n) + support_point(nb, rb, gb, n);
            let scale = ra + rb;
            // δ from 10⁻¹⁸ to 10⁻⁶ of the radii, either sign, or 0.
            let delta = match (next() * 3.0) as u32 {
                0 => 0.0,
                1 => scale * 10f64.powf(-18.0 + 12.0 * next()),
                _ => -scale * 10f64.powf(-18.0 + 12.0 * next()),
            };
            let d = touching + n * delta;
            let turn = if next() < 0.5 {
                0.0
            } else {
                10f64.powf(-12.0 + 9.0 * next())
            };
            let m = n * turn.cos() + DVec3::new(-n.y, n.x, 0.0) * turn.sin();
            let slack = 4.0 * f64::EPSILON * scale;
            // The construction's own rounding: a few ulps of the radii.
            let rounding = 16.0 * f64::EPSILON * scale;
            let shown = touch_shown(&oa, &ob, d, m, slack);
            if shown {
                assert!(
                    delta <= slack + rounding,
                    "shown touching, but apart by {delta:e} (slack {slack:e}), turn {turn:e}"
                );
            }
            let g = oa.support(m.x, m.y) + ob.support(m.x, m.y) - m.dot(d);
            // What went to the scan: not shown apart (g < 0) along the
            // normal, nor shown overlapping by a point inside both.
            if delta.abs() <= slack && turn == 0.0 && g >= 0.0 && !overlap_near(&oa, &ob, d, m) {
                touches += 1;
                shown_at_touch += usize::from(shown);
            }
            let rho = oa.least_curvature_radius() + ob.least_curvature_radius();
            if delta > 100.0 * (slack + rounding) && g >= 0.0 && g < 0.5 * rho {
                fooled_without_slope += 1;
            }
        }
        assert!(touches > 1000, "{touches} touches");
        assert!(
            shown_at_touch * 10 >= touches * 9,
            "only {shown_at_touch} of {touches} touches shown"
        );
        assert!(fooled_without_slope > 100, "{fooled_without_slope}");
    }

    use crate::spacetime::{Event, ProperVelocity};
    use crate::worldline::Worldline;

    fn at(x: f64, u: DVec3) -> Worldline {
        Worldline::new(
            Event::new(0.0, DVec3::new(x, 0.0, 0.0)),
            ProperVelocity(u),
            1.0,
        )
    }

    #[test]
    fn discs_at_rest_overlap_by_the_sum_of_radii_minus_distance() {
        let (a, b) = (at(0.0, DVec3::ZERO), at(0.05, DVec3::ZERO));
        let d = depth(a.last(), 0.03, b.last(), 0.03, 0.0);
        assert!((d - 0.01).abs() < 1e-12, "{d}");
        let b = at(0.07, DVec3::ZERO);
        assert_eq!(depth(a.last(), 0.03, b.last(), 0.03, 0.0), 0.0);
    }

    #[test]
    fn contracted_pucks_touch_at_the_sum_of_their_half_widths() {
        // Both moving along x at γ = 2 (u = √3): half-widths R/2 along x.
        let u = DVec3::new(3f64.sqrt(), 0.0, 0.0);
        let (a, b) = (at(0.0, u), at(0.03 - 0.004, u));
        let d = depth(a.last(), 0.03, b.last(), 0.03, 0.0);
        assert!((d - 0.004).abs() < 1e-12, "{d}");
        // Across the motion the full radius counts: a depth of 0.01 there.
        let a = Worldline::new(Event::default(), ProperVelocity(u), 1.0);
        let b = Worldline::new(
            Event::new(0.0, DVec3::new(0.0, 0.05, 0.0)),
            ProperVelocity(u),
            1.0,
        );
        let d = depth(a.last(), 0.03, b.last(), 0.03, 0.0);
        assert!((d - 0.01).abs() < 1e-12, "{d}");
    }

    /// Two equal pucks moving together at γ from 1.5 to 10⁸ in a direction
    /// at any angle, centres `x` apart across their motion: the depth is the
    /// distance from the separation to the edge of the ellipse their shapes
    /// sweep round each other (semi-axes `A = 2R` across the motion, `B =
    /// 2R/γ` along it), and for a point on the major axis within
    /// `(A² − B²)/A` of the centre that distance has a closed form,
    /// `B √(1 − x²/(A² − B²))`, reached in a direction that is none of the
    /// scan's or the axes' candidates: the refinement must find it.
    #[test]
    fn depth_across_a_contracted_pair_matches_the_ellipse_distance() {
        let r = 0.03;
        let mut rng = crate::physics::gas::Rng::new(0x5eed_0fe1_1195);
        for k in 0..400 {
            let gamma = 1.5 * (1e8f64 / 1.5).powf(k as f64 / 399.0);
            let alpha = std::f64::consts::TAU * rng.next_f64();
            let along = DVec3::new(alpha.cos(), alpha.sin(), 0.0);
            let u = along * (gamma * gamma - 1.0).sqrt();
            let (big, small) = (2.0 * r, 2.0 * r / gamma);
            let reach = (big * big - small * small) / big;
            let x = reach * (0.05 + 0.9 * rng.next_f64());
            let across = DVec3::new(-along.y, along.x, 0.0);
            let a = Worldline::new(Event::default(), ProperVelocity(u), 1.0);
            let b = Worldline::new(Event::new(0.0, across * x), ProperVelocity(u), 1.0);
            let expected = small * (1.0 - x * x / (big * big - small * small)).sqrt();
            let d = depth(a.last(), r, b.last(), r, 0.0);
            assert!(
                (d - expected).abs() <= 1e-12 * r + 1e-9 * expected,
                "γ = {gamma:e}, angle {alpha}: depth {d:e}, expected {expected:e}"
            );
        }
    }

    /// The refinement finds the gap function's minimum: never above what
    /// the golden-section search it replaced finds (the scan, the axes,
    /// then golden section about the best), and equal, to 10⁻¹³ of the
    /// lengths, to the least of golden-section searches started about
    /// every one of the scan's directions and axes (so a second valley,
    /// one whose sample fell farther from its floor, is not missed), on
    /// random pairs at any angle with γ from 1 to 10⁸ each (thin ellipses:
    /// valleys 1/γ wide) and centres anywhere within reach, apart or
    /// overlapping.
    #[test]
    fn refinement_finds_the_least_of_every_valley() {
        let mut rng = crate::physics::gas::Rng::new(0x0dd_ba11_5eed);
        let mut next = move || rng.next_f64();
        for case in 0..3000 {
            let mut segment = || {
                let gamma = 1e8f64.powf(next().powi(2));
                let alpha = std::f64::consts::TAU * next();
                let u = DVec3::new(alpha.cos(), alpha.sin(), 0.0) * (gamma * gamma - 1.0).sqrt();
                let at = DVec3::new(next(), next(), 0.0);
                Worldline::new(Event::new(0.0, at), ProperVelocity(u), 1.0)
            };
            let (a, b) = (segment(), segment());
            let (ra, rb) = (0.02 + 0.02 * next(), 0.02 + 0.02 * next());
            let beta = std::f64::consts::TAU * next();
            let d = DVec3::new(beta.cos(), beta.sin(), 0.0) * (ra + rb) * 1.2 * next();
            let (sa, sb) = (a.last(), b.last());
            let (got, m) = gap_min(sa, ra, sb, rb, d);
            // The previous refinement, as it was.
            let (oa, ob) = (Outline::of(sa, ra), Outline::of(sb, rb));
            let f = |m: DVec3| gap_along(&oa, &ob, m.x, m.y, d);
            let (cos, sin) = scan();
            let mut best = (f64::INFINITY, DVec3::X);
            let axes = [
                sa.velocity(),
                sb.velocity(),
                d,
                -sa.velocity(),
                -sb.velocity(),
                -d,
            ];
            let candidates = (0..SAMPLES).map(|k| DVec3::new(cos[k], sin[k], 0.0)).chain(
                axes.iter()
                    .filter(|w| w.length() > 0.0)
                    .map(|w| w.normalize()),
            );
            for m in candidates {
                if f(m) < best.0 {
                    best = (f(m), m);
                }
            }
            let (m0, across) = (best.1, DVec3::new(-best.1.y, best.1.x, 0.0));
            let turned = |s: f64| (m0 * (1.0 - s * s) + across * (2.0 * s)) / (1.0 + s * s);
            let half = half_step_tangent();
            let golden = golden_min(|s| f(turned(s)), -half, half, 80).0;
            let before = golden.min(best.0);
            // Golden section about every candidate direction.
            let everywhere = (0..SAMPLES)
                .map(|k| DVec3::new(cos[k], sin[k], 0.0))
                .chain(
                    axes.iter()
                        .filter(|w| w.length() > 0.0)
                        .map(|w| w.normalize()),
                )
                .map(|m0| {
                    let across = DVec3::new(-m0.y, m0.x, 0.0);
                    let turned = |s: f64| (m0 * (1.0 - s * s) + across * (2.0 * s)) / (1.0 + s * s);
                    golden_min(|s| f(turned(s)), -half, half, 80).0
                })
                .fold(before, f64::min);
            let scale = 1e-13 * (ra + rb + d.length());
            let gammas = (sa.gamma(), sb.gamma());
            assert!(
                got <= before + scale,
                "case {case}: {got} above {before} ({gammas:?})"
            );
            assert!(
                (got - everywhere).abs() <= scale,
                "case {case}: {got} against {everywhere} ({gammas:?})"
            );
            assert!((f(m) - got).abs() <= scale && (m.length() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn bound_grows_from_nothing_to_the_radii() {
        assert_eq!(bound([0.03, 0.03], 1.0, 0.0, 0.0), 0.0);
        assert!((bound([0.03, 0.03], 2.0, 0.001, 0.0) - 0.031).abs() < 1e-15);
        assert!((bound([0.03, 0.03], 2.0, 0.001, 0.002) - 0.033).abs() < 1e-15);
        assert!(bound([0.03, 0.03], 1e8, 0.0, 0.0) < 0.06);
    }
}
