//! Exact at the edges (issue 30): restitution on every contact path and
//! braking emission events on the light cone, each checked against an
//! independent evaluation in double-double arithmetic (`common/dd.rs`), not
//! against the engine's own intermediate numbers.
//!
//! * **Restitution** (item 1): the guide (docs/guide/src/scenes.md) defines `e` as the fraction of
//!   the centre-of-momentum kinetic energy kept. Here it is worked out from
//!   the before and after 4-momenta alone: `K = M − Σ mᵢ`, `M² = E² − |P|²`
//!   (`c = 1` units, mass units), in double-double. The input-rounding
//!   floor: each body's f64 proper velocity and mass, rounded by `ε`, move
//!   `M` by `(mᵢ/M)|E βᵢ − P| ε|uᵢ|` and `ε mᵢ γᵢ′`; the tolerance is a
//!   multiple of that floor over `K`, plus 1e-12.
//! * **Braking light cones** (item 2): an emission event `(tₑ, xₑ)` the
//!   engine reports for a vertex of a braking puck is on the observer's
//!   past light cone, `|c (t₀ − tₑ) − |x₀ − xₑ|| / (c (t₀ − tₑ))` below
//!   1e-12 plus the rounding floor of the reported coordinates
//!   (`2ε (c|tₑ| + |xₑ|)` over the delay), and on the vertex's worldline.
//! * **A kick next to a cushion** (item 4): the new contraction never
//!   reaches into the cushion; the half-widths come from the board velocity
//!   (`R √(1 − βₖ²)`), not from the engine's own half-width.

#[path = "common/dd.rs"]
mod dd;

use dd::{Dd, Dd3};
use glam::{DVec2, DVec3};
use lightcone_engine::optics::emission;
use lightcone_engine::physics::resolve::{self, Body};
use lightcone_engine::physics::{Billiard, CollisionKind, PuckInit};
use lightcone_engine::spacetime::{Event, FourMomentum, ProperVelocity};
use lightcone_engine::worldline::{ContractedShape, Worldline};
use proptest::prelude::*;

const EPS: f64 = f64::EPSILON;

// ---------------------------------------------------------------- item 1

/// CM kinetic energy `M − Σ m` of `bodies` in double-double, and its
/// input-rounding floor (see the module doc), both in kg.
fn cm_kinetic(bodies: &[Body]) -> (f64, f64) {
    let mut e = Dd::new(0.0);
    let mut p = Dd3::of(DVec3::ZERO);
    let mut masses = Dd::new(0.0);
    for b in bodies {
        let u = Dd3::of(b.u.0);
        let m = Dd::new(b.mass);
        e = e + m * (Dd::new(1.0) + u.dot(u)).sqrt();
        p = p + u.scale(m);
        masses = masses + m;
    }
    let big_m = (e * e - p.dot(p)).sqrt();
    let k = (big_m - masses).f64();
    let (ef, pf, mf) = (
        e.f64(),
        DVec3::new(p.0[0].f64(), p.0[1].f64(), p.0[2].f64()),
        big_m.f64(),
    );
    let floor = bodies
        .iter()
        .map(|b| {
            let g = b.u.gamma();
            let lever = (b.u.0 / g * ef - pf).length();
            // γᵢ′ = (E γᵢ − P·uᵢ)/M ≤ 2 E γᵢ / M.
            b.mass / mf * lever * EPS * b.u.0.length() + EPS * b.mass * (2.0 * ef * g / mf + 1.0)
        })
        .sum::<f64>();
    (k, floor)
}

/// The total 4-momentum of `bodies` in double-double, as f64.
fn total(bodies: &[Body]) -> (f64, DVec3) {
    let mut e = Dd::new(0.0);
    let mut p = Dd3::of(DVec3::ZERO);
    for b in bodies {
        let u = Dd3::of(b.u.0);
        let m = Dd::new(b.mass);
        e = e + m * (Dd::new(1.0) + u.dot(u)).sqrt();
        p = p + u.scale(m);
    }
    (
        e.f64(),
        DVec3::new(p.0[0].f64(), p.0[1].f64(), p.0[2].f64()),
    )
}

/// Asserts the CM kinetic-energy fraction kept from `before` to `after` is
/// `e` to its rounding floor, and 4-momentum (heat as rest mass included)
/// conserved; `what` names the path. Returns the fraction.
fn assert_keeps(before: &[Body], after: &[Body], e: f64, what: &str) -> f64 {
    let (k0, f0) = cm_kinetic(before);
    let (k1, f1) = cm_kinetic(after);
    let fraction = k1 / k0;
    let tol = 1e-12 + 64.0 * (f0 / k0 + f1 / k0.max(f64::MIN_POSITIVE));
    assert!(
        (fraction - e).abs() <= tol,
        "{what}: kept {fraction} of the CM kinetic energy, e = {e} (tolerance {tol:e}): \
         {before:?} → {after:?}"
    );
    let (e0, p0) = total(before);
    let (e1, p1) = total(after);
    assert!(
        (e1 - e0).abs() <= 1e-12 * e0 && (p1 - p0).length() <= 1e-12 * e0,
        "{what}: 4-momentum ({e0}, {p0}) → ({e1}, {p1})"
    );
    fraction
}

fn body(mass: f64, log_u: f64, angle: f64) -> Body {
    let speed = 10f64.powf(log_u);
    Body {
        mass,
        u: ProperVelocity(DVec3::new(angle.cos(), angle.sin(), 0.0) * speed),
    }
}

fn dir(angle: f64) -> DVec3 {
    DVec3::new(angle.cos(), angle.sin(), 0.0)
}

type RandomBody = (f64, f64, f64);

fn random_body() -> impl Strategy<Value = RandomBody> {
    (0.05f64..1.0, -3.0f64..6.0, 0.0f64..std::f64::consts::TAU)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 2000,
        rng_seed: proptest::test_runner::RngSeed::Fixed(30),
        ..ProptestConfig::default()
    })]

    /// Every contact path of `resolve` keeps the fraction `e` of the CM
    /// kinetic energy: the pair-frame contact ([`resolve::puck_puck`], any
    /// normal in the pair frame), the board contact
    /// ([`resolve::puck_puck_board`], any board normal along which the pair
    /// closes) and the cushion (the board is its CM frame); γ to 10⁶,
    /// `e` in 0.25…1.
    #[test]
    fn every_contact_path_keeps_the_fraction_e(
        a in random_body(),
        b in random_body(),
        normal_angle in 0.0f64..std::f64::consts::TAU,
        e in prop_oneof![0.25f64..1.0, Just(1.0)],
    ) {
        let (a, b) = (body(a.0, a.1, a.2), body(b.0, b.1, b.2));
        let n = dir(normal_angle);
        let m = FourMomentum::pair_invariant_mass(a.mass, a.u, b.mass, b.u);
        let cm = (a.momentum() + b.momentum()).centre_of_momentum_velocity(m);

        // Pair frame (here the CM frame; any frame gives a valid normal).
        let mut out = resolve::puck_puck(a, b, n, cm, e);
        if out == [a, b] {
            out = resolve::puck_puck(a, b, -n, cm, e);
        }
        if out != [a, b] {
            assert_keeps(&[a, b], &out, e, "pair frame");
        }

        // Board contact: along the board normal on which they close.
        let closing = (b.u.beta() - a.u.beta()).dot(n);
        let board_n = if closing < 0.0 { n } else { -n };
        let out = resolve::puck_puck_board(a, b, board_n, e);
        if out != [a, b] {
            assert_keeps(&[a, b], &out, e, "board contact");
            // Opening along the normal on the board (or, the energy taken
            // from the tangential motion too, moving alike along it).
            let opening = (out[1].u.beta() - out[0].u.beta()).dot(board_n);
            prop_assert!(opening >= -1e-10, "board contact still closing: {opening}");
        }

        // Cushion: the board is the CM frame of a puck and a cushion.
        let outward = if a.u.0.dot(n) > 0.0 { n } else { -n };
        let after = resolve::puck_cushion(a.u, outward, e);
        if after != a.u {
            let k0 = a.u.gamma_minus_one();
            let k1 = after.gamma_minus_one();
            prop_assert!((k1 / k0 - e).abs() <= 1e-12 + 8.0 * EPS * a.u.gamma() / k0.min(1.0),
                "cushion kept {}", k1 / k0);
        }
    }
}

fn puck(name: &str, x: f64, y: f64, u: (f64, f64), radius: f64, mass: f64) -> PuckInit {
    PuckInit {
        name: name.to_owned(),
        position: DVec2::new(x, y),
        u: ProperVelocity(DVec3::new(u.0, u.1, 0.0)),
        radius,
        mass,
    }
}

/// The body of puck outcome `k` of a collision, before or after.
fn outcome(c: &lightcone_engine::physics::Collision, k: usize, after: bool) -> Body {
    let p = &c.pucks[k];
    if after {
        Body {
            mass: p.mass_after,
            u: p.u_after,
        }
    } else {
        Body {
            mass: p.mass_before,
            u: p.u_before,
        }
    }
}

/// The issue's reproducing scene: a board contact (both kicks at one board
/// time) at t ≈ 0.54497 that kept 0.7949 of the CM kinetic energy with
/// `restitution = 0.9` (Newton's coefficient on the normal momentum, `e²`,
/// and each repeated push at the same instant `e` again).
#[test]
fn issue_30_board_contact_keeps_the_fraction_e() {
    let pucks = vec![
        puck(
            "a",
            100.0,
            100.0,
            (-5.550166923626416, -0.12660073126285237),
            0.039190132166116026,
            0.2,
        ),
        puck(
            "b",
            99.64513385386932,
            100.43303137536289,
            (-0.6370421567968783, -1.2568961764295268),
            0.020403380720921818,
            0.2,
        ),
    ];
    let mut b = Billiard::new(1.0, DVec2::new(200.0, 200.0), 0.9, 1.0, pucks);
    b.set_recording(true);
    b.advance_to(3.39);
    let contacts: Vec<_> = b
        .collisions()
        .iter()
        .filter(|c| c.kind == CollisionKind::PuckPuck)
        .collect();
    assert!(!contacts.is_empty());
    let mut board = 0;
    for c in &contacts {
        let before = [outcome(c, 0, false), outcome(c, 1, false)];
        let after = [outcome(c, 0, true), outcome(c, 1, true)];
        assert_keeps(&before, &after, 0.9, &format!("contact at t = {}", c.t));
        if (c.t - 0.54497).abs() < 1e-4 {
            assert_eq!(c.pucks[0].t, c.pucks[1].t, "a board contact");
            board += 1;
        }
    }
    assert_eq!(board, 1, "{contacts:?}");
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        rng_seed: proptest::test_runner::RngSeed::Fixed(30),
        ..ProptestConfig::default()
    })]

    /// Through the billiard: random frictionless scenes of two or three
    /// pucks, γ to 10⁶, `e` in 0.25…1. Every puck–puck record whose kicks
    /// reached unchanged pucks (no overlapping kick, no Zeno merge) kept
    /// the fraction `e`, board contacts (both kicks at one board time,
    /// repeated pushes included) and pair-frame contacts alike.
    #[test]
    fn billiard_contacts_keep_the_fraction_e(
        raw in prop::collection::vec(
            (0.05f64..0.95, 0.05f64..0.95, -2.0f64..6.0, 0.0f64..std::f64::consts::TAU),
            2..4,
        ),
        e in 0.25f64..1.0,
    ) {
        let mut list: Vec<PuckInit> = Vec::new();
        for (k, &(x, y, log_u, angle)) in raw.iter().enumerate() {
            if list.iter().any(|q| (q.position - DVec2::new(x, y)).length() < 0.06 + 1e-6) {
                continue;
            }
            let s = 10f64.powf(log_u);
            list.push(puck(&format!("p{k}"), x, y, (s * angle.cos(), s * angle.sin()), 0.03, 0.2));
        }
        prop_assume!(list.len() >= 2);
        let mut b = Billiard::new(1.0, DVec2::new(1.0, 1.0), e, 1.0, list);
        b.set_recording(true);
        prop_assume!(b.step_until(1.0, 20_000));
        let stats = b.stats();
        prop_assume!(stats.overlapping_kicks == 0 && stats.zeno_merges == 0);
        for c in b.collisions() {
            if c.kind != CollisionKind::PuckPuck || c.pucks.iter().any(|p| p.pending) {
                continue;
            }
            let before = [outcome(c, 0, false), outcome(c, 1, false)];
            let after = [outcome(c, 0, true), outcome(c, 1, true)];
            assert_keeps(&before, &after, e, &format!("contact at t = {}", c.t));
        }
    }
}

// ---------------------------------------------------------------- item 2

/// `|c Δt − |Δx|| / (c Δt)` for light from `emitted` reaching `observed`,
/// with the differences and the length in double-double, and the rounding
/// floor of the emission event's f64 coordinates over the delay.
fn cone_residual(emitted: Event, observed: Event, c: f64) -> (f64, f64) {
    let dt = Dd::new(observed.t) - Dd::new(emitted.t);
    let dx = Dd3::of(observed.position) - Dd3::of(emitted.position);
    let delay = dt * Dd::new(c);
    let residual = (delay - dx.length()).abs().f64() / delay.f64();
    let floor = 2.0 * EPS * (c * emitted.t.abs() + emitted.position.length()) / delay.f64();
    (residual, floor)
}

/// Braking pucks (μ g = 0.2 · 9.81 m/s², c = 1, u₀ to 10⁴) seen by
/// observers at rest up to 10³ table lengths (2.84 km) away in every
/// direction: every vertex's emission event is on the observer's past light
/// cone to 1e-12 of the light delay plus the rounding floor, and on the
/// vertex's worldline, emission times spread over the braking and crowded
/// near the stop.
#[test]
fn braking_emission_events_lie_on_the_light_cone_for_far_observers() {
    let (c, a) = (1.0, 0.2 * 9.81);
    let table = 2.84;
    let radius = 0.03;
    let vertices: Vec<DVec3> = (0..24)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 24.0;
            DVec3::new(radius * t.cos(), radius * t.sin(), 0.01)
        })
        .collect();
    let mut worst = 0.0f64;
    let mut checked = 0;
    let mut near_stop = 0;
    for (k, &u0) in [1e-2, 0.3, 3.0, 60.0, 1e3, 1e4].iter().enumerate() {
        let heading = 0.3 + 1.1 * k as f64;
        let start = Event::new(0.25 * k as f64, DVec3::new(1.2, 0.7, 0.0));
        let w = Worldline::braking(start, ProperVelocity(dir(heading) * u0), c, a);
        let shapes = ContractedShape::of(&w);
        let s = w.segments()[0];
        let stop = s.stop_time().unwrap() - start.t;
        for (j, lengths) in [0.1, 3.0, 30.0, 300.0, 1e3].iter().enumerate() {
            for side in 0..8 {
                let angle = side as f64 * 0.785 + 0.1 * j as f64;
                let observer =
                    start.position + DVec3::new(angle.cos(), angle.sin(), 0.1) * (lengths * table);
                for frac in [0.0, 1e-9, 0.01, 0.3, 0.77, 0.999, 1.0 - 1e-6, 1.0 - 1e-9] {
                    // Observed when light from the centre at this time of
                    // its braking arrives.
                    let te = start.t + frac * stop;
                    let t_obs = te + (observer - w.position_at(te)).length() / c;
                    let observed = Event::new(t_obs, observer);
                    for &r in &vertices {
                        let seen = emission::solve(&w, r, &shapes, observed);
                        let te = seen.event.t;
                        let (res, floor) = cone_residual(seen.event, observed, c);
                        worst = worst.max(res - floor);
                        assert!(
                            res <= 1e-12 + floor,
                            "u0 {u0}, {lengths} table lengths, frac {frac}: {res:e} of the delay \
                             (floor {floor:e})"
                        );
                        // On the vertex's own worldline.
                        let on = w.position_at(te) + s.place_at(te, r);
                        let scale = 1e-12 * (1.0 + (c * stop).min(1e6));
                        assert!(
                            (seen.event.position - on).length() <= scale,
                            "off the worldline by {}",
                            (seen.event.position - on).length()
                        );
                        checked += 1;
                        if te > start.t + 0.99 * stop && te < start.t + stop {
                            near_stop += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(
        checked > 40_000 && near_stop > 5_000,
        "{checked} {near_stop}"
    );
    eprintln!(
        "braking emission: {checked} vertex events, {near_stop} near the stop, worst {worst:e}"
    );
}

// ---------------------------------------------------------------- item 4

/// The deepest any puck's contracted shape reaches into a cushion at board
/// time `t`, m (negative: clear of every cushion), from the board velocity
/// alone: half-width `R √(1 − βₖ²)` along each table axis.
fn cushion_depth(b: &Billiard, i: usize, t: f64) -> f64 {
    let s = b.worldline(i).segment_at(t);
    let (x, beta) = (s.position_at(t), s.velocity_at(t) / b.c());
    let table = b.table();
    (0..2)
        .map(|k| {
            let h = b.radius(i) * (1.0 - beta[k] * beta[k]).sqrt();
            (h - x[k]).max(x[k] + h - table[k])
        })
        .fold(f64::NEG_INFINITY, f64::max)
}

/// A kick next to a cushion: puck a (|u| = 20, a sliver R/γ wide along
/// its motion) bounces off x = 0, 45° from the normal, and at once hits
/// puck b, at rest just beyond the bounce on its way out. The kick slows a
/// and it grows back towards its rest disc, up to `R (1 − 1/γ)` wider
/// along x, while its centre is still closer to the cushion than R:
/// re-contracted about its centre it would reach millimetres into the
/// cushion. It re-contracts about the rim point the cushion holds: no
/// shape reaches into a cushion at any board time (to 1e-12 m), the
/// centre's jump is what the shape would have reached in (5 mm to
/// R (1 − 1/γ)), and 4-momentum is kept exactly.
#[test]
fn a_kick_next_to_a_cushion_leaves_the_puck_touching_it_not_inside() {
    let (r, speed, c) = (0.03, 20.0, 1.0);
    let theta = 45f64.to_radians();
    let u_in = (-speed * theta.cos(), speed * theta.sin());
    let gamma = (1.0f64 + speed * speed).sqrt();
    // a's centre when it touches x = 0: its half-width along x.
    let bounce = DVec2::new(r * (1.0 + u_in.1 * u_in.1).sqrt() / gamma, 0.5);
    let (t_bounce, beta) = (0.3, speed / gamma);
    let start = bounce - DVec2::new(u_in.0, u_in.1) / speed * beta * c * t_bounce;
    // Off the incoming path by 2.05 R (its rest discs clear by 0.05 R).
    let b_at = bounce + DVec2::new(theta.cos(), theta.sin()) * 2.05 * r;
    let pucks = vec![
        puck("a", start.x, start.y, u_in, r, 0.2),
        puck("b", b_at.x, b_at.y, (0.0, 0.0), r, 0.2),
    ];
    let mut b = Billiard::new(c, DVec2::new(1.0, 1.0), 1.0, 1.0, pucks);
    b.set_recording(true);
    b.advance_to(0.6);
    assert_eq!(b.stats().cushion_holds, 1, "{:?}", b.stats());
    // The order: the bounce, then the contact with b (then whatever a's
    // new motion meets: the cushion again if it moves into it).
    let kinds: Vec<_> = b.collisions().iter().map(|c| c.kind).collect();
    assert_eq!(
        kinds[..2],
        [
            CollisionKind::Cushion(lightcone_engine::physics::Cushion::X0),
            CollisionKind::PuckPuck
        ]
    );
    // The contact keeps 4-momentum: a's after the bounce, b at rest.
    let contact = &b.collisions()[1];
    let before = [
        Body {
            mass: 0.2,
            u: b.collisions()[0].pucks[0].u_after,
        },
        outcome(contact, 1, false),
    ];
    let after = [outcome(contact, 0, true), outcome(contact, 1, true)];
    let (e0, p0) = total(&before);
    let (e1, p1) = total(&after);
    assert!((e1 - e0).abs() < 1e-12 * e0 && (p1 - p0).length() < 1e-12 * e0);
    // a's kick: the centre moved back from the cushion, by the depth its
    // new shape would have had about the old centre.
    let wa = b.worldline(0);
    let kick = &b.collisions()[1].pucks[0];
    let k = wa.segment_index_at(kick.t);
    let (old, new) = (&wa.segments()[k - 1], &wa.segments()[k]);
    let jump = new.start.position - old.position_at(kick.t);
    let new_half_x = r * (1.0 - (new.velocity().x / c).powi(2)).sqrt();
    assert!(jump.y == 0.0 && jump.x > 5e-3 && jump.x < r * (1.0 - 1.0 / gamma));
    assert!((new_half_x - old.position_at(kick.t).x - jump.x).abs() < 1e-12);
    assert!(
        (new.start.position.x - new_half_x).abs() < 1e-12,
        "touching"
    );
    // No shape in a cushion: at every segment start (with the new velocity)
    // and on a fine grid of board times.
    for i in 0..2 {
        let starts = b.worldline(i).segments().iter().map(|s| s.start.t);
        let grid = (0..=6000).map(|k| k as f64 * 1e-4);
        for t in starts.filter(|&t| t >= 0.0).chain(grid) {
            let d = cushion_depth(&b, i, t);
            assert!(d <= 1e-12, "puck {i} {d} m into a cushion at t = {t}");
        }
    }
}
