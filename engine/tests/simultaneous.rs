//! Mirror-image scenes end mirror images (issue 30, item 4): contacts on
//! one puck at one board time are resolved together, whatever the order
//! the loop meets them in, the file order or the names; the head-on case
//! against its closed form.
//!
//! A scene and its mirror image about the table's vertical mid-line
//! (`x → W − x`, `uₓ → −uₓ`) are run side by side in one billiard: every
//! puck and its image must stay mirror images to 1e-9 m (positions) and
//! 1e-9 of the fastest start's `|u|` (proper velocities), from the start through the first few
//! puck–puck contacts. (The mirror of a float is rounded, so the two
//! halves start apart by an ulp; each dispersing contact of round pucks
//! can multiply that by `distance / R`, so a run is cut after a few.)

use glam::{DVec2, DVec3};
use lightcone_engine::physics::{Billiard, CollisionKind, PuckInit};
use lightcone_engine::spacetime::ProperVelocity;
use proptest::prelude::*;

const W: f64 = 2.0;
const H: f64 = 1.0;

#[derive(Clone, Debug)]
struct Spec {
    x: f64,
    y: f64,
    u: (f64, f64),
    radius: f64,
    mass: f64,
}

fn init(name: String, s: &Spec) -> PuckInit {
    PuckInit {
        name,
        position: DVec2::new(s.x, s.y),
        u: ProperVelocity(DVec3::new(s.u.0, s.u.1, 0.0)),
        radius: s.radius,
        mass: s.mass,
    }
}

fn mirrored(s: &Spec) -> Spec {
    Spec {
        x: W - s.x,
        u: (-s.u.0, s.u.1),
        ..s.clone()
    }
}

/// A scene of `left` pucks, their mirror images and `axis` pucks on the
/// mid-line (`x = W/2`, `uₓ = 0`), named and listed so that the two halves
/// come in different orders (`names` picks, for each left puck, whether
/// its name sorts before or after its image's), run to `until` (s) or just
/// before puck–puck contact `max_pair` (whichever first). Returns the
/// largest mirror asymmetry of positions (m) and of proper velocities
/// (relative to the fastest start's `|u|`) at the end, and the number of
/// simultaneous groups resolved.
fn mirror_asymmetry(
    left: &[Spec],
    axis: &[Spec],
    names: &[bool],
    restitution: f64,
    friction: f64,
    until: f64,
    max_pair: usize,
) -> (f64, f64, u64) {
    let mut pucks = Vec::new();
    for (k, s) in left.iter().enumerate() {
        let (mine, image) = if names[k % names.len()] {
            (format!("a{k}"), format!("b{k}"))
        } else {
            (format!("b{k}"), format!("a{k}"))
        };
        pucks.push(init(image, &mirrored(s)));
        pucks.insert(0, init(mine, s));
    }
    for (k, s) in axis.iter().enumerate() {
        pucks.push(init(format!("m{k}"), s));
    }
    let n = left.len();
    let build = || {
        let mut b = Billiard::new(1.0, DVec2::new(W, H), restitution, 1.0, pucks.clone());
        if friction > 0.0 {
            b.set_sliding_friction(friction);
        }
        b.set_recording(true);
        b
    };
    // Where to stop: before the contact `max_pair` (a first run finds it).
    let mut probe = build();
    probe.advance_to(until);
    let pair_times: Vec<f64> = probe
        .collisions()
        .iter()
        .filter(|c| c.kind == CollisionKind::PuckPuck)
        .map(|c| c.pucks.iter().map(|p| p.t).fold(f64::INFINITY, f64::min))
        .collect();
    let end = pair_times
        .get(max_pair)
        .map_or(until, |&t| (t - 1e-6).min(until));
    let mut b = build();
    b.advance_to(end);
    // The list holds left puck k at index n − 1 − k, its image at n + k.
    // Proper velocities are compared against the fastest start's.
    let scale = left
        .iter()
        .chain(axis)
        .map(|s| s.u.0.hypot(s.u.1))
        .fold(f64::MIN_POSITIVE, f64::max);
    let (mut dx, mut du) = (0.0f64, 0.0f64);
    let state = |i: usize| {
        let w = b.worldline(i);
        (w.position_at(end), w.last().u_at(end).0)
    };
    for k in 0..n {
        let (x, u) = state(n - 1 - k);
        let (xi, ui) = state(n + k);
        dx = dx.max((x.x - (W - xi.x)).abs()).max((x.y - xi.y).abs());
        du = du.max(((u.x + ui.x).abs() + (u.y - ui.y).abs()) / scale);
    }
    for k in 0..axis.len() {
        let (x, u) = state(2 * n + k);
        dx = dx.max((x.x - W / 2.0).abs());
        du = du.max(u.x.abs() / scale);
    }
    (dx, du, b.stats().simultaneous_contacts)
}

fn striker(y: f64, u: (f64, f64)) -> Spec {
    Spec {
        x: 0.5,
        y,
        u,
        radius: 0.03,
        mass: 0.2,
    }
}

/// Two mirror-image strikers meet a resting puck on the mid-line at the
/// same board time (γ from 1.1 to about 40, restitution 1, 0.8 and 0.3),
/// in both name orders: mirror images afterwards, through the
/// cushion bounces and contacts that follow.
#[test]
fn two_mirror_strikers_on_a_resting_puck_come_back_mirror_images() {
    for u in [(0.5, 0.5), (3.0, 2.0), (30.0, 20.0), (2.0, 0.0)] {
        for restitution in [1.0, 0.8, 0.3] {
            for names in [[true], [false]] {
                let centre = Spec {
                    x: W / 2.0,
                    y: 0.3 + 0.5 * u.1 / u.0,
                    u: (0.0, 0.0),
                    radius: 0.03,
                    mass: 0.2,
                };
                let (dx, du, joint) = mirror_asymmetry(
                    &[striker(0.3, u)],
                    &[centre],
                    &names,
                    restitution,
                    0.0,
                    3.0,
                    usize::MAX,
                );
                assert!(joint >= 1, "u = {u:?}: no simultaneous contact");
                assert!(
                    dx <= 1e-9 && du <= 1e-9,
                    "u = {u:?}, e = {restitution}, names {names:?}: {dx:e} m, {du:e} of |u|"
                );
            }
        }
    }
}

/// Head-on from both sides, equal masses: by symmetry the centre stays
/// at rest and, energy conserved, each striker rebounds with its own
/// speed (at any γ; the contact is resolved in the pairs' frames, each
/// kick at its own board time).
#[test]
fn head_on_from_both_sides_both_rebound_and_the_centre_stays() {
    for ux in [0.2, 5.0, 300.0] {
        let left = [Spec {
            x: 0.4,
            y: 0.5,
            u: (ux, 0.0),
            radius: 0.03,
            mass: 0.2,
        }];
        let centre = [Spec {
            x: W / 2.0,
            y: 0.5,
            u: (0.0, 0.0),
            radius: 0.03,
            mass: 0.2,
        }];
        let pucks = vec![
            init("a".into(), &left[0]),
            init("b".into(), &mirrored(&left[0])),
            init("c".into(), &centre[0]),
        ];
        let mut b = Billiard::new(1.0, DVec2::new(W, H), 1.0, 1.0, pucks);
        b.set_recording(true);
        // Long enough for the contact, too short for a cushion.
        let meet = (W / 2.0 - 0.4 - 0.06) / (ux / (1.0 + ux * ux).sqrt());
        let end = meet + 0.2;
        b.advance_to(end);
        assert_eq!(b.stats().simultaneous_contacts, 1, "ux = {ux}");
        let ua = b.worldline(0).last().u_at(end).0;
        let ub = b.worldline(1).last().u_at(end).0;
        let uc = b.worldline(2).last().u_at(end).0;
        assert!((ua.x + ux).abs() <= 1e-12 * ux, "ux = {ux}: a {ua}");
        assert!((ub.x - ux).abs() <= 1e-12 * ux, "ux = {ux}: b {ub}");
        assert!(uc.length() <= 1e-12 * ux, "ux = {ux}: c {uc}");
        assert!(ua.y.abs() + ub.y.abs() <= 1e-12 * ux);
        assert_eq!(b.mass(2), 0.2);
    }
}

fn spec(half: f64) -> impl Strategy<Value = Spec> {
    (
        0.1..(half - 0.1),
        0.1..(H - 0.1),
        -1.5f64..1.5,
        0.0..std::f64::consts::TAU,
        0.02..0.05,
        0.1..0.5,
    )
        .prop_map(|(x, y, log_u, angle, radius, mass)| {
            let u = 10f64.powf(log_u);
            Spec {
                x,
                y,
                u: (u * angle.cos(), u * angle.sin()),
                radius,
                mass,
            }
        })
}

/// No two rest discs within `1.2 (Rᵢ + Rⱼ)`, none within 1.2 R of a
/// cushion, the left half clear of the mid-line.
fn apart(all: &[Spec]) -> bool {
    all.iter().enumerate().all(|(i, a)| {
        a.x > 1.2 * a.radius
            && a.y > 1.2 * a.radius
            && H - a.y > 1.2 * a.radius
            && all[..i]
                .iter()
                .all(|b| DVec2::new(a.x - b.x, a.y - b.y).length() > 1.2 * (a.radius + b.radius))
    })
}

/// Random mirror-image scenes: a puck and its image, with or without a
/// puck on the mid-line, proper speeds 0.03 to 30, either name order,
/// restitution 1 or 0.7, some braking on the cloth: mirror images through
/// the first three puck–puck contacts (simultaneous ones included,
/// cushions without limit), and some of the 2 000 resolve contacts together
/// (so the test is not passed by scenes where nothing meets at once).
/// Stars, chains and cycles of contacts at one board time are resolved
/// together (twins meeting each other while the third meets both; twins
/// whose own contact's kicks are still ahead when the third meets them;
/// the mirror image of a kick or cushion bounce an ulp later). Seeds
/// 1–250, 376, 1000 and 12345 (`LIGHTCONE_MIRROR_SEED`) were tried: all
/// pass (seed 71 needed the mirror images' equal gap minima told equal to
/// 1e-9 of the radii, `overlap::contact_normal`).
#[test]
fn random_mirror_scenes_end_mirror_images() {
    use proptest::test_runner::{RngSeed, TestRunner};
    let config = ProptestConfig {
        cases: 2000,
        rng_seed: RngSeed::Fixed(
            std::env::var("LIGHTCONE_MIRROR_SEED")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(307),
        ),
        ..ProptestConfig::default()
    };
    let scenes = (
        spec(W / 2.0),
        prop::option::of((0.1..(H - 0.1), -1.5f64..1.5, any::<bool>(), 0.02..0.05)),
        any::<bool>(),
        prop::sample::select(vec![1.0, 0.7]),
        prop::sample::select(vec![0.0, 0.0, 0.5]),
    );
    let together = std::cell::Cell::new(0u64);
    TestRunner::new(config)
        .run(&scenes, |(left, on_axis, names, restitution, friction)| {
            let axis: Vec<Spec> = on_axis
                .map(|(y, log_u, up, radius)| {
                    let u = 10f64.powf(log_u) * if up { 1.0 } else { -1.0 };
                    Spec {
                        x: W / 2.0,
                        y,
                        u: (0.0, u),
                        radius,
                        mass: 0.3,
                    }
                })
                .into_iter()
                .collect();
            let left = [left];
            let mut all: Vec<Spec> = left.to_vec();
            all.extend(left.iter().map(mirrored));
            all.extend(axis.iter().cloned());
            prop_assume!(apart(&all));
            let (dx, du, joint) =
                mirror_asymmetry(&left, &axis, &[names], restitution, friction, 3.0, 3);
            together.set(together.get() + joint);
            prop_assert!(dx <= 1e-9 && du <= 1e-9, "{dx:e} m, {du:e} of |u|");
            Ok(())
        })
        .unwrap();
    assert!(together.get() > 0, "no scene met at once");
}

/// A cycle: two mirror-image twins meet each other on the mid-line at the
/// board time a third puck, running up the mid-line, meets both (found by
/// seed 295 of the random test). The three contacts are one group (its
/// record names the three pairs), resolved by one rule: 4-momentum kept
/// to 1e-12, every rest mass kept (elastic), mirror images to 1e-9 m
/// after it and through the cushion bounces that follow.
#[test]
fn twins_meeting_each_other_and_a_third_at_once_are_one_group() {
    let left = Spec {
        x: 0.653534384531996,
        y: 0.7729247224465209,
        u: (-9.565366356342754, 6.544567250812004),
        radius: 0.02,
        mass: 0.1,
    };
    let axis = Spec {
        x: W / 2.0,
        y: 0.1,
        u: (0.0, 10f64.powf(1.351781518029404)),
        radius: 0.02244666733036812,
        mass: 0.3,
    };
    for names in [false, true] {
        let (dx, du, joint) = mirror_asymmetry(
            std::slice::from_ref(&left),
            std::slice::from_ref(&axis),
            &[names],
            1.0,
            0.0,
            3.0,
            usize::MAX,
        );
        assert_eq!(joint, 1, "names {names}");
        assert!(dx <= 1e-9 && du <= 1e-9, "names {names}: {dx:e} m, {du:e}");
    }
    let pucks = vec![
        init("b0".into(), &left),
        init("a0".into(), &mirrored(&left)),
        init("m0".into(), &axis),
    ];
    let mut b = Billiard::new(1.0, DVec2::new(W, H), 1.0, 1.0, pucks);
    b.set_recording(true);
    b.advance_to(2.0);
    let group = b
        .collisions()
        .iter()
        .find(|c| c.simultaneous)
        .expect("one group");
    let mut pairs: Vec<[usize; 2]> = group
        .pairs
        .iter()
        .map(|&[x, y]| {
            let (p, q) = (group.pucks[x].puck, group.pucks[y].puck);
            [p.min(q), p.max(q)]
        })
        .collect();
    pairs.sort_unstable();
    assert_eq!(pairs, vec![[0, 1], [0, 2], [1, 2]]);
    let (mut e0, mut e1, mut p0, mut p1) = (0.0, 0.0, DVec3::ZERO, DVec3::ZERO);
    for p in &group.pucks {
        assert_eq!(p.mass_before, p.mass_after);
        let four = |u: ProperVelocity| {
            (
                p.mass_before * (1.0 + u.0.length_squared()).sqrt(),
                u.0 * p.mass_before,
            )
        };
        let (e, m) = four(p.u_before);
        e0 += e;
        p0 += m;
        let (e, m) = four(p.u_after);
        e1 += e;
        p1 += m;
    }
    assert!((e0 - e1).abs() <= 1e-12 * e0, "{e0} {e1}");
    assert!((p0 - p1).length() <= 1e-12 * e0, "{p0} {p1}");
}
