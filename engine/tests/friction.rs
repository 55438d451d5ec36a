//! Sliding friction in the billiard (issue 17, items 1–3): pucks on braking
//! worldlines, tested against closed-form relativity and conservation laws.
//!
//! * a lone puck brakes to rest after `(c²/μg)(γ₀ − 1)` in `(c/μg) u₀` of
//!   board time and `(c/μg) asinh u₀` of proper time, γ₀ from 1 to 10⁴
//!   (1e-12 relative);
//! * the Newtonian limit (c = 10⁶ m/s): `v²/2μg` (1e-9 m);
//! * a cushion bounce folds the same path (elastic: |u| is kept);
//! * a head-on hit on a braking worldline at the closed-form time, velocities
//!   exchanged, 4-momentum conserved (1e-12);
//! * a puck that stops against another rests there, with no event;
//! * random scenes with friction: finite, 4-momentum conserved at each
//!   contact, no re-collision, overlap within the bound, everything at rest
//!   in finite board time.

mod common;
use common::assert_conserved;
use glam::{DVec2, DVec3};
use lightcone_engine::physics::{Billiard, CollisionKind, PuckInit, overlap};
use lightcone_engine::spacetime::ProperVelocity;
use proptest::prelude::*;

const R: f64 = 0.03;

fn puck(name: &str, x: f64, y: f64, u: DVec3) -> PuckInit {
    PuckInit {
        name: name.to_owned(),
        position: DVec2::new(x, y),
        u: ProperVelocity(u),
        radius: R,
        mass: 0.2,
    }
}

fn billiard(c: f64, table: DVec2, restitution: f64, a: f64, pucks: Vec<PuckInit>) -> Billiard {
    let mut b = Billiard::new(c, table, restitution, 1.0, pucks);
    b.set_sliding_friction(a);
    b
}

#[test]
fn a_lone_puck_brakes_to_rest_as_the_closed_forms_say() {
    // c = 1 m/s, μg = 1 m/s²: stopping distance (γ₀ − 1) m, time u₀ s.
    for u0 in [1e-3, 0.1, 1.0, 10.0, 1e3, 1e4] {
        let (c, a) = (1.0, 1.0);
        let g0 = (1.0f64 + u0 * u0).sqrt();
        let distance = c * c / a * u0 * u0 / (g0 + 1.0); // (c²/a)(γ₀ − 1), no cancellation
        let stop = c / a * u0;
        let tau = c / a * u0.asinh();
        let table = DVec2::new(distance + 1.0, 1.0);
        let mut b = billiard(c, table, 1.0, a, vec![puck("p", 0.5, 0.5, DVec3::X * u0)]);
        b.advance_to(stop * 1.5 + 1.0);
        assert_eq!(b.stats().contacts(), 0);
        let w = b.worldline(0);
        // Braking, then an explicit rest segment at the stop.
        let segs = w.segments();
        assert_eq!(segs.len(), 2, "{u0}");
        assert!(segs[0].is_braking() && segs[1].is_rest());
        assert!((segs[1].start.t - stop).abs() <= 1e-12 * stop, "{u0}");
        let end = w.position_at(stop * 1.5 + 1.0);
        // (1e-12 of the distance, plus the rounding of the position 0.5 + d.)
        assert!(
            (end.x - 0.5 - distance).abs() <= 1e-12 * distance + 1e-15 * end.x,
            "{u0}: {} vs {distance}",
            end.x - 0.5
        );
        assert_eq!(end.y, 0.5);
        assert!((w.proper_time_at(stop) - tau).abs() <= 1e-12 * tau, "{u0}");
        // Proper speed linear in board time on the way.
        let u_mid = w.proper_velocity_at(0.25 * stop).0.x;
        assert!((u_mid - 0.75 * u0).abs() <= 1e-12 * u0, "{u0}");
        assert_eq!(w.proper_velocity_at(stop * 1.2).0, DVec3::ZERO);
    }
}

#[test]
fn newtonian_limit_of_a_carom_shot_from_a_scene_file() {
    // c = 10⁶ m/s, a 2 m/s shot on a carom cloth (μ = 0.2, g = 9.81):
    // classical stopping distance v²/2μg ≈ 1.0194 m, time v/μg.
    let text = "c = 1.0e6\n[table]\nsize = [2.84, 1.42]\nfriction = 0.2\ngravity = 9.81\n\
                [[puck]]\nname = \"w\"\nposition = [0.3, 0.7]\nvelocity = [2.0, 0.0]\n";
    let scene = lightcone_engine::scene::parse(text, "newton.toml").unwrap();
    let mut b = Billiard::from_scene(&scene);
    let (v, a) = (2.0, 0.2 * 9.81);
    b.advance_to(5.0);
    let x = b.worldline(0).position_at(5.0).x - 0.3;
    assert!((x - v * v / (2.0 * a)).abs() < 1e-9, "{x}");
    // (before_start = "rest": a rest segment, the braking one, the rest.)
    let stop = b.worldline(0).segments().last().unwrap().start.t;
    assert!((stop - v / a).abs() < 1e-9, "{stop}");
    // Half-way in time: v t − a t²/2.
    let t = 0.5 * v / a;
    let x = b.worldline(0).position_at(t).x - 0.3;
    assert!((x - (v * t - 0.5 * a * t * t)).abs() < 1e-9);
}

#[test]
fn an_elastic_cushion_folds_the_braking_path() {
    // Elastic cushion: |u| is kept and the braking law depends on |u| only,
    // so the puck travels the same path length as on an endless table,
    // folded at the contact (centre at W − R/γ_c, γ_c the Lorentz factor at
    // the contact; the contracted half-width is the same after).
    for u0 in [0.5, 3.0, 30.0] {
        let (c, a) = (1.0, 0.5);
        let g0 = (1.0f64 + u0 * u0).sqrt();
        let distance = c * c / a * u0 * u0 / (g0 + 1.0);
        let width = 1.0 + 0.6 * distance + R; // hit the far cushion, come back
        let mut b = billiard(
            c,
            DVec2::new(width, 1.0),
            1.0,
            a,
            vec![puck("p", 1.0, 0.5, DVec3::X * u0)],
        );
        let end = 2.0 * c * u0 / a + 1.0;
        b.advance_to(end);
        let hits: Vec<_> = b.collisions().to_vec();
        assert_eq!(hits.len(), 1, "{u0}: {hits:?}");
        let t_c = hits[0].t;
        let gamma_c = hits[0].pucks[0].u_before.gamma();
        assert!((hits[0].pucks[0].u_after.0.x + hits[0].pucks[0].u_before.0.x).abs() < 1e-12 * u0);
        let wall = width - R / gamma_c;
        // The contact: the centre at W − R/γ_c, on the braking law.
        let at = b.worldline(0).position_at(t_c).x;
        assert!((at - wall).abs() < 1e-12 * wall, "{u0}: {at} vs {wall}");
        let x_end = b.worldline(0).position_at(end).x;
        let folded = 2.0 * wall - (1.0 + distance);
        assert!(
            (x_end - folded).abs() < 1e-11 * distance,
            "{u0}: {x_end} vs {folded}"
        );
        // Stopped at the unreflected stop time: the law only sees |u|.
        let last = b.worldline(0).segments().last().unwrap();
        assert!(last.is_rest());
        assert!((last.start.t - c * u0 / a).abs() < 1e-12 * c * u0 / a);
    }
}

#[test]
fn head_on_on_a_resting_puck_while_braking() {
    // a slides onto b at rest, same line. Contact when a's front meets b's
    // back: x₀ + s(t) + R/γ(t) = x_b − R, solved here by bisection on the
    // closed forms (s(t) = c t (u₀ + u)/(γ₀ + γ), u = u₀ − a t/c).
    for u0 in [1.0, 2.0, 50.0] {
        let (c, a) = (1.0, 0.3);
        let (xa, xb) = (0.5, 0.9);
        let mut b = billiard(
            c,
            DVec2::new(3.0, 1.0),
            1.0,
            a,
            vec![
                puck("a", xa, 0.5, DVec3::X * u0),
                puck("b", xb, 0.5, DVec3::ZERO),
            ],
        );
        let front = |t: f64| {
            let u = u0 - a * t / c;
            let (g0, g) = ((1.0 + u0 * u0).sqrt(), (1.0 + u * u).sqrt());
            xa + c * t * (u0 + u) / (g0 + g) + R / g - (xb - R)
        };
        let (mut lo, mut hi) = (0.0, c * u0 / a);
        assert!(front(hi) > 0.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if front(mid) < 0.0 { lo = mid } else { hi = mid }
        }
        b.advance_to(hi + 0.01);
        let hit = b
            .collisions()
            .iter()
            .find(|c| c.kind == CollisionKind::PuckPuck)
            .expect("they meet")
            .clone();
        assert!((hit.t - hi).abs() <= 1e-12 * hi, "{u0}: {} vs {hi}", hit.t);
        assert_conserved(&hit, 1e-12);
        // Equal masses, elastic, head-on: the velocities are exchanged (b
        // takes a's velocity at a's kick, a stops).
        let (pa, pb) = (&hit.pucks[0], &hit.pucks[1]);
        assert!(pa.u_after.0.length() < 1e-12 * u0, "{pa:?}");
        assert!(
            (pb.u_after.0 - pa.u_before.0).length() < 1e-12 * u0,
            "{pb:?}"
        );
        // a's kick comes first (the pair frame moves along +x).
        assert!(pa.t <= hit.t && hit.t <= pb.t);
    }
}

#[test]
fn a_puck_that_stops_against_another_rests_there_without_events() {
    // a stops exactly touching b: (c²/a)(γ₀ − 1) = gap. Then a little
    // short, and a little long (one soft contact, then rest).
    let (c, a) = (1.0, 0.3);
    let u0: f64 = 0.4;
    let g0 = (1.0 + u0 * u0).sqrt();
    let distance = c * c / a * u0 * u0 / (g0 + 1.0);
    for (extra, contacts) in [(0.0, 0), (1e-6, 0), (-1e-6, 1)] {
        let xb = 0.5 + distance + 2.0 * R + extra;
        let mut b = billiard(
            c,
            DVec2::new(xb + 1.0, 1.0),
            1.0,
            a,
            vec![
                puck("a", 0.5, 0.5, DVec3::X * u0),
                puck("b", xb, 0.5, DVec3::ZERO),
            ],
        );
        b.advance_to(100.0);
        assert_eq!(b.stats().pair_contacts, contacts, "{extra}");
        assert!(b.stats().predictions < 100, "{:?}", b.stats());
        for i in 0..2 {
            assert_eq!(b.worldline(i).proper_velocity_at(100.0).0, DVec3::ZERO);
        }
    }
}

#[test]
fn frictionless_tables_are_untouched() {
    // μ = 0: uniform segments as before.
    let scene = lightcone_engine::scene::parse(
        "[table]\nfriction = 0\n[[puck]]\nposition = [0.5, 0.5]\nbeta = [0.5, 0.0]\n",
        "s.toml",
    )
    .unwrap();
    let mut b = Billiard::from_scene(&scene);
    b.advance_to(1.0);
    assert!(b.worldline(0).segments().iter().all(|s| !s.is_braking()));
}

/// A random scene with friction: `n` pucks from a deterministic generator.
fn random_friction(seed: u64, n: usize, log_u_max: f64, restitution: f64) -> Billiard {
    let mut rng = lightcone_engine::physics::gas::Rng::new(seed);
    let mut next = move || rng.next_f64();
    let mut list: Vec<PuckInit> = Vec::new();
    while list.len() < n {
        let p = DVec2::new(0.05 + 1.9 * next(), 0.05 + 0.9 * next());
        if list
            .iter()
            .any(|q| (q.position - p).length() < 2.0 * R + 1e-6)
        {
            continue;
        }
        let speed = 10f64.powf(-2.0 + (log_u_max + 2.0) * next());
        let angle = std::f64::consts::TAU * next();
        list.push(puck(
            &format!("p{}", list.len()),
            p.x,
            p.y,
            DVec3::new(speed * angle.cos(), speed * angle.sin(), 0.0),
        ));
    }
    billiard(1.0, DVec2::new(2.0, 1.0), restitution, 1.5, list)
}

/// The invariants on a finished run (history kept).
fn check(b: &Billiard, until: f64) {
    let n = b.len();
    let mut gamma_max = 1.0f64;
    let mut bound_max = 0.0f64;
    for c in b.collisions() {
        for p in &c.pucks {
            assert!(p.u_after.is_finite() && p.position.is_finite() && p.t.is_finite());
            gamma_max = gamma_max.max(p.u_before.gamma()).max(p.u_after.gamma());
        }
        if c.kind == CollisionKind::PuckPuck {
            assert_conserved(c, 1e-12);
            bound_max = bound_max.max(c.overlap_bound);
        }
    }
    for i in 0..n {
        gamma_max = gamma_max.max(b.worldline(i).segments()[0].gamma());
    }
    // No re-collision with nothing between.
    let mut last: Vec<Option<usize>> = vec![None; n];
    for (k, c) in b.collisions().iter().enumerate() {
        if c.kind == CollisionKind::PuckPuck {
            let (i, j) = (c.pucks[0].puck, c.pucks[1].puck);
            if let (Some(li), Some(lj)) = (last[i], last[j]) {
                let prev = &b.collisions()[li];
                assert!(
                    !(li == lj && prev.kind == CollisionKind::PuckPuck),
                    "pair {i}-{j} collided again at t = {}: {prev:?} then {c:?}",
                    c.t
                );
            }
        }
        for p in &c.pucks {
            last[p.puck] = Some(k);
        }
    }
    // Overlap on the board (shapes of the instantaneous motion) within what
    // the contacts allow: the largest pair bound plus the growth back of a
    // kicked puck, 2R(1 − 1/γ_max). Tolerance 1e-9 m.
    let allow = bound_max + 2.0 * R * (1.0 - 1.0 / gamma_max) + 1e-9;
    for k in 0..=200 {
        let t = until * k as f64 / 200.0;
        for i in 0..n {
            let si = b.worldline(i).segment_at(t).tangent_at(t);
            assert!(si.start.position.is_finite());
            for j in i + 1..n {
                let sj = b.worldline(j).segment_at(t).tangent_at(t);
                let d = overlap::depth(&si, R, &sj, R, t);
                assert!(d <= allow, "{i}-{j} overlap {d} > {allow} at t = {t}");
            }
            // On the table.
            let p = si.start.position;
            assert!(p.x > -1e-9 && p.x < 2.0 + 1e-9 && p.y > -1e-9 && p.y < 1.0 + 1e-9);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        rng_seed: proptest::test_runner::RngSeed::Fixed(17),
        ..ProptestConfig::default()
    })]

    /// Random scenes with friction: 2 to 6 pucks, proper speeds 10⁻² to 10,
    /// restitution 1 or 0.5; every invariant holds and everything rests in
    /// finite board time.
    #[test]
    fn invariants_hold_with_friction(
        seed in 0u64..1_000_000,
        n in 2usize..7,
        restitution in prop::sample::select(vec![1.0, 0.5]),
    ) {
        let mut b = random_friction(seed, n, 1.0, restitution);
        // Every puck stops within its own stopping time after its last
        // contact; run long enough and require rest.
        let until = 40.0;
        b.advance_to(until);
        prop_assert!(b.stats().contacts() < 100_000);
        check(&b, until);
        for i in 0..b.len() {
            let w = b.worldline(i);
            prop_assert_eq!(w.proper_velocity_at(until).0, DVec3::ZERO, "puck {} moves", i);
            prop_assert!(w.segments().last().unwrap().is_rest());
        }
    }
}

#[test]
fn random_scenes_with_friction_collide_and_come_to_rest() {
    // The random scenes are not vacuous: they hold many contacts of both
    // kinds, and everything still rests by t = 40 s. Dense boxes too.
    let (mut pairs, mut cushions) = (0u64, 0u64);
    let until = 150.0;
    for seed in 0..40 {
        let n = 2 + (seed as usize % 19);
        let mut b = random_friction(seed, n, 2.0, [1.0, 0.5][seed as usize % 2]);
        b.advance_to(until);
        check(&b, until);
        for i in 0..b.len() {
            assert_eq!(b.worldline(i).proper_velocity_at(until).0, DVec3::ZERO);
        }
        pairs += b.stats().pair_contacts;
        cushions += b.stats().cushion_contacts;
    }
    eprintln!("40 random friction scenes: {pairs} pair and {cushions} cushion contacts");
    assert!(pairs > 40 && cushions > 100, "{pairs} {cushions}");
}

#[test]
fn friction_set_after_loading_a_scene_that_rests_before_start_is_the_scenes_own() {
    // The paper's scene (μ = 0.2) rests before its start (the default `before_start`):
    // friction set on the frictionless scene afterwards must give the same
    // run as the scene with its friction, bit for bit.
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/paper_carom.toml");
    let scene = lightcone_engine::scene::load(&path).expect("the shipped scene");
    assert!(scene.table.deceleration() > 0.0);
    let mut frictionless = scene.clone();
    frictionless.table.friction = 0.0;
    let mut later = Billiard::from_scene(&frictionless);
    later.set_sliding_friction(scene.table.deceleration());
    let mut own = Billiard::from_scene(&scene);
    own.advance_to(5.0);
    later.advance_to(5.0);
    assert!(own.stats().contacts() > 0);
    for i in 0..own.len() {
        for t in [-1.0, 0.5, 1.0, 2.0, 5.0] {
            assert_eq!(
                own.worldline(i).state_at(t),
                later.worldline(i).state_at(t),
                "puck {i} at t = {t}"
            );
        }
    }
}

#[test]
fn slower_light_on_a_cloth_keeps_every_puck_inside_the_rindler_horizon() {
    // The paper's scene on its cloth (μg ≈ 1.96 m/s², pucks 30.5 mm): the
    // horizon c²/(μg) passes the radius at c = √(R μ g) ≈ 0.245 m/s. Slower
    // light is refused, saying how slow it may go; the scene is unchanged.
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/paper_carom.toml");
    let scene = lightcone_engine::scene::load(&path).expect("the shipped scene");
    let floor = (0.0305 * scene.table.deceleration()).sqrt();
    let ok = scene.with_c(floor * 1.01).expect("just above the floor");
    let r = ok.pucks[0].radius;
    assert!(r < ok.c * ok.c / ok.table.deceleration());
    let err = scene.with_c(0.2).expect_err("below the floor").to_string();
    assert!(
        err.contains("cannot brake rigidly") && err.contains("c must be above 0.24"),
        "{err}"
    );
    // Frictionless, any c.
    let mut bare = scene.clone();
    bare.table.friction = 0.0;
    assert!(bare.with_c(0.01).is_ok());
    // A puck added in code is held to the same horizon.
    let mut slow = scene.with_c(0.3).unwrap();
    let mut big = slow.pucks[0].clone();
    big.name = "big".into();
    big.position = glam::DVec2::new(1.5, 0.3);
    big.radius = 0.06;
    let err = slow
        .add_puck(big)
        .expect_err("beyond the horizon")
        .to_string();
    assert!(err.contains("\"big\"") && err.contains("c²/(μg)"), "{err}");
}
