//! The emission events of a body's vertices in batches: the per-vertex
//! closed form of [`super::emission`] on structure-of-arrays data (one
//! `f64` array per coordinate, [`LANES`] vertices at a time), written as
//! plain loops over those arrays that the compiler turns into vector
//! instructions. Exact: each vertex's result is the one
//! [`super::emission::solve`] gives, bit for bit (the same operations in
//! the same order), or the vertex is handed back to it.
//!
//! **Which vertices a batch solves.** The body's segment search is shared:
//! one search for the reference point gives segment `k`. When `k`
//! is uniform (not braking), every vertex is solved on `k`, and it keeps
//! that answer when the per-vertex search would also have stopped at `k`:
//! the start of `k` (with `k`'s shape) is in the observation's past light
//! cone and the start of `k + 1` (with `k + 1`'s shape) is not. That test
//! is made per vertex (two distances), or skipped for a whole batch when
//! a bound proves it:
//!
//! **The safe margin.** Let `f₀(t) = c (t₀ − t) − |x₀ − x(t)|` for the
//! reference point `x(t)` on segment `k`'s line, `f₀(t_ref) = 0`. Along
//! the line `d/dt |x₀ − x(t)| ≥ −v`, so `f₀(t) ≥ (c − v)(t_ref − t)` for
//! `t ≤ t_ref` and `f₀(t) ≤ −(c − v)(t − t_ref)` for `t ≥ t_ref`. A vertex
//! at placed offset `q` (any segment's shape: a turn and a contraction,
//! or the Born-rigid offset at a braking segment's start, never longer
//! than the rest-frame offset `r`, so `|q| ≤ ρ = max |r|`) changes the
//! distance by at most `ρ`. So with
//!
//! ```text
//! δ = ρ / (c − v) = ρ (c + v) / (c/γ)²      (no 1 − v²/c²: c² − v² = c²/γ²)
//! ```
//!
//! `t_ref − t_k > δ` puts every vertex's start of `k` inside the cone and
//! `t_{k+1} − t_ref > δ` puts every vertex's start of `k + 1` outside it:
//! no vertex leaves segment `k`. The bound is taken with `ρ` enlarged by
//! `10⁻¹²` of the scale of the positions and times involved, far above
//! the rounding of either side.
//!
//! **Braking segments** (sliding friction) keep the same margin with `v`
//! the segment's start speed: the reference point (the centre) only slows
//! along it (and rests after its stop; before the first segment it keeps
//! its start motion), so `f₀` obeys the same two bounds, and every
//! shape's offset, the Born-rigid one at any time of the braking included
//! (`r∥ (2 − ρ)/(γ + √((1 − ρ)² + u²)) ≤ r∥`), is still no longer than
//! `ρ`. The reference emission is the centre's, from its braking law. A
//! batch inside the margin is solved on `k` vertex by vertex
//! ([`emission::solve_on_segment`], each point on its own braking
//! hyperbola), without the per-vertex search; outside it, every vertex
//! takes that search from `k`, as does every vertex of a uniform segment
//! whose test fails (its emission near a kink).

// The loops index several arrays in step, the form that vectorises.
#![allow(clippy::needless_range_loop)]

use glam::DVec3;

use super::emission::{self, Emission};
use crate::spacetime::Event;
use crate::worldline::{Segment, SegmentShape, ShapeMaps, Worldline};

/// Vertices per batch: the arrays live on the stack.
pub const LANES: usize = 64;

/// One coordinate triple per vertex, as three arrays (`len` used).
struct Soa {
    x: [f64; LANES],
    y: [f64; LANES],
    z: [f64; LANES],
}

impl Soa {
    const ZERO: Self = Self {
        x: [0.0; LANES],
        y: [0.0; LANES],
        z: [0.0; LANES],
    };

    /// The largest length of the first `n` triples (a comparison, not
    /// `f64::max`: the offsets are finite).
    fn max_length(&self, n: usize) -> f64 {
        let mut far = 0.0f64;
        for i in 0..n.min(LANES) {
            let l = self.x[i] * self.x[i] + self.y[i] * self.y[i] + self.z[i] * self.z[i];
            far = if l > far { l } else { far };
        }
        far.sqrt()
    }

    fn load(&mut self, points: &[DVec3]) {
        for (i, p) in points.iter().take(LANES).enumerate() {
            self.x[i] = p.x;
            self.y[i] = p.y;
            self.z[i] = p.z;
        }
    }
}

/// Work on arrays of lanes that [`vectorised`] runs: `run` should be
/// `#[inline(always)]`, so that its loops get the wider instructions.
pub trait LaneWork {
    /// Does the work.
    fn run(self);
}

/// Runs `work` compiled for AVX2 (4 lanes of `f64`) when the processor has
/// it, for SSE2 (2 lanes) otherwise: the same operations either way (no
/// fused multiply-add), so the same results.
#[inline(always)]
pub fn vectorised(work: impl LaneWork) {
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2")]
        fn wide(work: impl LaneWork) {
            work.run();
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor was just found to have AVX2.
            unsafe { wide(work) };
            return;
        }
    }
    work.run();
}

/// Board-frame positions at the start of segment `s` (shape `shape`) of
/// the points at rest-frame offsets `r` (first `n`): the start plus
/// [`SegmentShape::place`], with the operations of `Segment::rotate` and
/// `LorentzMap::apply` in their order (so the same bits).
#[inline(always)]
fn start_positions(s: &Segment, shape: SegmentShape, r: &Soa, n: usize, out: &mut Soa) {
    let n = n.min(LANES); // no bounds checks: the loops vectorise
    let p = s.start.position;
    let (sin, cos) = s.turn();
    let (nx, ny, nz, inv) = match shape {
        SegmentShape::Lorentz(map) => {
            let d = map.direction();
            (d.x, d.y, d.z, map.inverse_gamma())
        }
        SegmentShape::Rest => (0.0, 0.0, 0.0, 1.0),
        SegmentShape::BornRigid => {
            for i in 0..n {
                let q = shape.place(s, s.start.t, DVec3::new(r.x[i], r.y[i], r.z[i]));
                out.x[i] = p.x + q.x;
                out.y[i] = p.y + q.y;
                out.z[i] = p.z + q.z;
            }
            return;
        }
    };
    let lorentz = matches!(shape, SegmentShape::Lorentz(_));
    for i in 0..n {
        let x = cos * r.x[i] - sin * r.y[i];
        let y = sin * r.x[i] + cos * r.y[i];
        let z = r.z[i];
        let (qx, qy, qz) = if lorentz {
            let along = nx * x + ny * y + nz * z;
            let a = along * inv;
            (
                (x - nx * along) + nx * a,
                (y - ny * along) + ny * a,
                (z - nz * along) + nz * a,
            )
        } else {
            (x, y, z)
        };
        out.x[i] = p.x + qx;
        out.y[i] = p.y + qy;
        out.z[i] = p.z + qz;
    }
}

/// Whether each point at `a` (first `n`) has its event at board time `t`
/// in the past light cone of `observation`, as `emission`'s segment
/// search decides it, into `inside`.
#[inline(always)]
fn in_past_cone(a: &Soa, n: usize, t: f64, observation: Event, c: f64, inside: &mut [bool; LANES]) {
    let lhs = c * (observation.t - t);
    let o = observation.position;
    let n = n.min(LANES);
    for i in 0..n {
        let (dx, dy, dz) = (o.x - a.x[i], o.y - a.y[i], o.z - a.z[i]);
        inside[i] = lhs >= (dx * dx + dy * dy + dz * dz).sqrt();
    }
}

/// The module doc's safe margin on segment `k`: where the reference
/// point's emission lies on the segment, and how far a point `ρ` from it
/// can be.
#[derive(Clone, Copy, Debug)]
struct Margin {
    /// The reference point's emission time on the segment, from its start.
    dt_ref: f64,
    /// The segment's duration (∞ for the last).
    end: f64,
    /// Whether a segment precedes it (the first extends back for ever).
    has_previous: bool,
    /// `1/(c − v)`, s/m, as `(c + v)/(c/γ)²`, for the segment's start speed
    /// (its fastest: a braking centre only slows).
    per_metre: f64,
    /// Size of the positions and times involved, m (for rounding).
    scale: f64,
}

impl Margin {
    /// The margin on segment `k` of `worldline` (shape `shapes`) for
    /// `observation`. The reference point's emission: the uniform line's
    /// closed form, or on a braking segment the centre's braking law
    /// ([`emission::solve_on_segment`] at offset zero).
    fn of(worldline: &Worldline, k: usize, shapes: &impl ShapeMaps, observation: Event) -> Self {
        let segments = worldline.segments();
        let s = &segments[k];
        let c = worldline.speed_of_light();
        let v = s.velocity();
        let since = observation.t - s.start.t;
        let d0 = observation.position - (s.start.position + v * since);
        // The braking law's emission time is clamped to its stop within
        // `2·10⁻¹²` of the time from the segment's start: its scale grows
        // by that much more (a review's finding).
        let (dt_ref, clamped) = if s.is_braking() {
            let e = emission::solve_on_segment(worldline, k, DVec3::ZERO, shapes, observation);
            (e.event.t - s.start.t, 2.0 * c * since.abs())
        } else {
            (since - emission::light_catch_up(d0, v, c, s.gamma()), 0.0)
        };
        let c_over_gamma = c / s.gamma();
        Self {
            dt_ref,
            end: segments
                .get(k + 1)
                .map_or(f64::INFINITY, |n| n.start.t - s.start.t),
            has_previous: k > 0,
            per_metre: (c + v.length()) / (c_over_gamma * c_over_gamma),
            scale: c * since.abs()
                + clamped
                + d0.length()
                + observation.position.length()
                + s.start.position.length(),
        }
    }

    /// Whether every point within `rho` (m) of the reference point keeps
    /// the segment: its emission more than `ρ/(c − v)` (ρ enlarged by
    /// `10⁻¹²` of the scale, for rounding) from both ends.
    fn safe(&self, rho: f64) -> bool {
        let delta = (rho + 1e-12 * (self.scale + rho)) * self.per_metre * (1.0 + 1e-12);
        (!self.has_previous || self.dt_ref > delta) && self.end - self.dt_ref > delta
    }
}

/// One batch's work on a uniform segment, all in loops over arrays.
struct Lanes<'a> {
    s: &'a Segment,
    shape: SegmentShape,
    /// Whether a segment precedes this one.
    previous: bool,
    next: Option<(&'a Segment, SegmentShape)>,
    observation: Event,
    c: f64,
    /// Observation time from the segment start.
    since: f64,
    /// The emission's allowed times from the segment start.
    range: (f64, f64),
    /// `c² − v²`, as `light_catch_up` forms it.
    a2: f64,
}

/// [`Lanes`] applied to one batch: the points at rest-frame offsets `r`
/// (first `n`); their start positions into `a`; whether the start of the
/// segment and of the next is in the cone for each (`cone`, not tested
/// when `safe`); their emission events on the segment (`emitted`: times,
/// positions), [`emission::solve_on_segment`]'s operations lane by lane.
struct Batch<'a, 'b> {
    lanes: &'a Lanes<'b>,
    r: &'a Soa,
    n: usize,
    safe: bool,
    a: &'a mut Soa,
    a_next: &'a mut Soa,
    cone: (&'a mut [bool; LANES], &'a mut [bool; LANES]),
    emitted: (&'a mut [f64; LANES], &'a mut Soa),
}

impl LaneWork for Batch<'_, '_> {
    #[inline(always)]
    fn run(self) {
        let Batch {
            lanes: this,
            r,
            n,
            safe,
            a,
            a_next,
            cone,
            emitted,
        } = self;
        let (s, observation, c) = (this.s, this.observation, this.c);
        let (below, above) = cone;
        let (t_out, e) = emitted;
        let n = n.min(LANES);
        start_positions(s, this.shape, r, n, a);
        below[..n].fill(true);
        above[..n].fill(false);
        if !safe {
            if this.previous {
                in_past_cone(a, n, s.start.t, observation, c, below);
            }
            if let Some((s1, shape1)) = this.next {
                start_positions(s1, shape1, r, n, a_next);
                in_past_cone(a_next, n, s1.start.t, observation, c, above);
            }
        }
        let (o, v, since, a2) = (observation.position, s.velocity(), this.since, this.a2);
        let inv_a2 = 1.0 / a2;
        let (lo, end) = this.range;
        for i in 0..n {
            let (ax, ay, az) = (a.x[i], a.y[i], a.z[i]);
            let dx = o.x - (ax + v.x * since);
            let dy = o.y - (ay + v.y * since);
            let dz = o.z - (az + v.z * since);
            let dv = dx * v.x + dy * v.y + dz * v.z;
            let dd = dx * dx + dy * dy + dz * dz;
            let root = (dv * dv + a2 * dd).sqrt();
            // Both roots' forms, then the one `light_catch_up` takes
            // (selects, not branches: the loop vectorises).
            let receding = dd / (root - dv);
            let approaching = (dv + root) * inv_a2;
            let tau = if dv <= 0.0 { receding } else { approaching };
            let tau = if dd == 0.0 { 0.0 } else { tau };
            let dt = (since - tau).max(lo).min(end);
            t_out[i] = s.start.t + dt;
            e.x[i] = ax + v.x * dt;
            e.y[i] = ay + v.y * dt;
            e.z[i] = az + v.z * dt;
        }
    }
}

/// Batches deeper than this many segments from the reference point's are
/// left to the per-vertex walk (it bounds the recursion's stack).
const MAX_STEPS: usize = 8;

/// Emission events of every point of a body (rest-frame `offsets`, shape
/// `shapes`), the segment search shared: one search for
/// `reference`, then the points solved in batches on that segment
/// ([`solve_from`], structure of arrays, vectorised), each
/// with a short walk only when it may lie on another. Appends to `out`;
/// with the centre as `reference` each result equals [`emission::solve`]'s for its
/// point.
pub fn solve_body(
    worldline: &Worldline,
    offsets: &[DVec3],
    reference: DVec3,
    shapes: &impl ShapeMaps,
    observation: Event,
    out: &mut Vec<Emission>,
) {
    let k0 = emission::segment_index(worldline, reference, shapes, observation);
    solve_from(worldline, k0, offsets, shapes, observation, out);
}

/// The emission events of the points at rest-frame `offsets` of a body
/// moving along `worldline` with shape `shapes`, for light reaching
/// `observation`, given segment `k` found for the body's reference point;
/// appended to `out` in order, each equal to
/// `emission::solve_on_segment(worldline, emission::refine_index(worldline, k, r, …), r, …)`.
///
/// A point whose start of `k` is outside the cone is solved from `k − 1`,
/// one whose start of `k + 1` is inside from `k + 1` (a batch of those
/// points each): `refine_index` from there stops where it stops from `k`.
pub fn solve_from(
    worldline: &Worldline,
    k: usize,
    offsets: &[DVec3],
    shapes: &impl ShapeMaps,
    observation: Event,
    out: &mut Vec<Emission>,
) {
    solve_near(worldline, k, offsets, shapes, observation, out, 0);
}

/// [`solve_from`], `steps` segments away from the reference point's.
fn solve_near(
    worldline: &Worldline,
    k: usize,
    offsets: &[DVec3],
    shapes: &impl ShapeMaps,
    observation: Event,
    out: &mut Vec<Emission>,
    steps: usize,
) {
    let segments = worldline.segments();
    let s = &segments[k];
    let shape = shapes.on_segment(k, s);
    let too_deep = steps > MAX_STEPS;
    if too_deep || s.is_braking() || matches!(shape, SegmentShape::BornRigid) {
        // Vertex by vertex (on a braking segment each point on its own
        // braking hyperbola), the search skipped for a batch inside the
        // margin.
        let margin = (!too_deep).then(|| Margin::of(worldline, k, shapes, observation));
        for chunk in offsets.chunks(LANES) {
            let rho = chunk.iter().fold(0.0f64, |far, r| far.max(r.length()));
            let safe = margin.is_some_and(|m| m.safe(rho));
            out.extend(chunk.iter().map(|&r| {
                let k = if safe {
                    k
                } else {
                    emission::refine_index(worldline, k, r, shapes, observation)
                };
                emission::solve_on_segment(worldline, k, r, shapes, observation)
            }));
        }
        return;
    }
    let c = worldline.speed_of_light();
    let next = segments
        .get(k + 1)
        .map(|n| (n, shapes.on_segment(k + 1, n)));
    let since = observation.t - s.start.t;
    let end = next.map_or(f64::INFINITY, |(n, _)| n.start.t - s.start.t);
    let lo = if k > 0 { 0.0 } else { f64::NEG_INFINITY };
    let a2 = (c / s.gamma()) * (c / s.gamma()); // c² − v², as `light_catch_up`
    let margin = Margin::of(worldline, k, shapes, observation);
    let mut a = Soa::ZERO;
    let mut a_next = Soa::ZERO;
    let mut r = Soa::ZERO;
    let mut t_out = [0.0; LANES];
    let mut e = Soa::ZERO;
    let mut below = [true; LANES]; // start of k in the cone
    let mut above = [false; LANES]; // start of k + 1 in the cone
    // Points handed to a neighbouring segment (allocated only if any are).
    let (mut moved, mut points, mut solved) = (Vec::new(), Vec::new(), Vec::new());
    for chunk in offsets.chunks(LANES) {
        let n = chunk.len().min(LANES);
        r.load(chunk);
        let rho = r.max_length(n);
        let safe = margin.safe(rho);
        let lanes = Lanes {
            s,
            shape,
            previous: k > 0,
            next,
            observation,
            c,
            since,
            range: (lo, end),
            a2,
        };
        vectorised(Batch {
            lanes: &lanes,
            r: &r,
            n,
            safe,
            a: &mut a,
            a_next: &mut a_next,
            cone: (&mut below, &mut above),
            emitted: (&mut t_out, &mut e),
        });
        let base = out.len();
        let u = s.u;
        out.extend((0..n).map(|i| Emission {
            event: Event::new(t_out[i], DVec3::new(e.x[i], e.y[i], e.z[i])),
            u,
        }));
        if safe {
            continue;
        }
        // The points on another segment, each side in a batch of its own.
        for (step_down, k_other) in [(true, k.wrapping_sub(1)), (false, k + 1)] {
            moved.clear();
            moved.extend((0..n).filter(|&i| {
                if step_down {
                    !below[i]
                } else {
                    below[i] && above[i]
                }
            }));
            if moved.is_empty() {
                continue;
            }
            points.clear();
            points.extend(moved.iter().map(|&i| chunk[i]));
            solved.clear();
            solve_near(
                worldline,
                k_other,
                &points,
                shapes,
                observation,
                &mut solved,
                steps + 1,
            );
            for (&i, e) in moved.iter().zip(solved.iter().copied()) {
                out[base + i] = e;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::ProperVelocity;
    use crate::worldline::{ContractedShape, Rigid};

    const C: f64 = 1.42;

    /// The workspace's seeded generator, with the draws these tests make.
    struct Rng(crate::physics::gas::Rng);

    impl Rng {
        fn next(&mut self) -> f64 {
            self.0.next_f64()
        }
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            lo + (hi - lo) * self.next()
        }
        fn velocity(&mut self, max: f64) -> ProperVelocity {
            ProperVelocity(DVec3::new(
                self.range(-max, max),
                self.range(-max, max),
                0.0,
            ))
        }
    }

    /// A worldline with kinks every few tens of ms (velocity changes in
    /// every direction, so the body turns), braking if `friction`, with a
    /// rest segment first or last now and then.
    fn worldline(rng: &mut Rng, friction: bool) -> Worldline {
        let start = Event::new(
            0.0,
            DVec3::new(rng.range(0.0, 2.0), rng.range(0.0, 1.0), 0.0),
        );
        let mut w = if friction {
            Worldline::braking(start, rng.velocity(3.0), C, rng.range(0.5, 3.0))
        } else {
            Worldline::new(start, rng.velocity(3.0), C)
        };
        if rng.next() < 0.2 {
            w.rest_before_start();
        }
        let mut t = 0.0;
        for _ in 0..(rng.next() * 40.0) as usize {
            t += rng.range(0.005, 0.15);
            w.push(t, rng.velocity(3.0)).unwrap();
        }
        if friction && rng.next() < 0.3 {
            w.come_to_rest();
        }
        w
    }

    /// Every vertex of random bodies, worldlines and observers (many seen
    /// near a kink: the observation on the light cone of one) solved in
    /// batches equals the per-vertex solve, bit for bit, contracted and
    /// at rest.
    #[test]
    fn batches_equal_the_per_vertex_solve() {
        let mut rng = Rng(crate::physics::gas::Rng::new(0x9E37_79B9_7F4A_7C15));
        let mut out = Vec::new();
        for case in 0..300 {
            let w = worldline(&mut rng, case % 3 == 0);
            let radius = rng.range(0.01, 0.3);
            let offsets: Vec<DVec3> = (0..(1 + (rng.next() * 200.0) as usize))
                .map(|_| {
                    DVec3::new(
                        rng.range(-1.0, 1.0),
                        rng.range(-1.0, 1.0),
                        rng.range(0.0, 0.3),
                    ) * radius
                })
                .collect();
            let eye = DVec3::new(
                rng.range(-1.0, 3.0),
                rng.range(-1.5, 2.0),
                rng.range(0.0, 1.0),
            );
            let segments = w.segments();
            let t0 = if rng.next() < 0.5 {
                // Seen as the centre passes a kink, give or take a little.
                let s = &segments[(rng.next() * segments.len() as f64) as usize];
                s.start.t + (eye - s.start.position).length() / C + rng.range(-0.05, 0.05)
            } else {
                rng.range(-0.5, 6.0)
            };
            let observation = Event::new(t0, eye);
            let contracted = ContractedShape::of(&w);
            for reference in [DVec3::ZERO, offsets[0]] {
                out.clear();
                solve_body(&w, &offsets, reference, &contracted, observation, &mut out);
                assert_eq!(out.len(), offsets.len());
                for (r, e) in offsets.iter().zip(&out) {
                    let k = emission::segment_index(&w, reference, &contracted, observation);
                    let k = emission::refine_index(&w, k, *r, &contracted, observation);
                    let expect = emission::solve_on_segment(&w, k, *r, &contracted, observation);
                    assert_eq!(*e, expect, "case {case}, offset {r}");
                }
                out.clear();
                solve_body(&w, &offsets, reference, &Rigid, observation, &mut out);
                for (r, e) in offsets.iter().zip(&out) {
                    let k = emission::segment_index(&w, reference, &Rigid, observation);
                    let k = emission::refine_index(&w, k, *r, &Rigid, observation);
                    assert_eq!(
                        *e,
                        emission::solve_on_segment(&w, k, *r, &Rigid, observation)
                    );
                }
            }
        }
    }

    /// The safe margin is a bound: wherever it holds, no vertex of the
    /// chunk's radius is found off the reference point's segment by the
    /// per-vertex search, on uniform and braking (Born-rigid) segments.
    #[test]
    fn inside_the_margin_no_vertex_changes_segment() {
        let mut rng = Rng(crate::physics::gas::Rng::new(0x0123_4567_89AB_CDEF));
        let mut safe_seen = 0;
        let mut braking_safe = 0;
        for case in 0..800 {
            let w = worldline(&mut rng, case % 2 == 1);
            let shapes = ContractedShape::of(&w);
            let radius = rng.range(0.01, 0.2);
            let eye = DVec3::new(
                rng.range(-1.0, 3.0),
                rng.range(-1.5, 2.0),
                rng.range(0.0, 1.0),
            );
            let observation = Event::new(rng.range(0.0, 5.0), eye);
            let k = emission::segment_index(&w, DVec3::ZERO, &shapes, observation);
            if !Margin::of(&w, k, &shapes, observation).safe(radius) {
                continue;
            }
            safe_seen += 1;
            braking_safe += usize::from(w.segments()[k].is_braking());
            for _ in 0..64 {
                // Points on the sphere of the radius, the worst case.
                let r = DVec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                )
                .normalize()
                    * radius;
                assert_eq!(emission::refine_index(&w, k, r, &shapes, observation), k);
            }
        }
        assert!(
            safe_seen > 100 && braking_safe > 30,
            "{safe_seen} {braking_safe}"
        );
    }
}
