//! Collisions that hold at any γ: the invariants of the collision
//! convention (velocity changes simultaneous with the contact in the pair
//! frame), on hard cases and on random scenes.
//!
//! Invariants, each with its tolerance:
//! * overlap on the board never exceeds what rigid bodies in relativity
//!   cannot avoid (`physics::overlap::bound` of the pair's contacts; 1e-9 m
//!   of rounding on a table of metres);
//! * a pair never collides again before something else has changed one of
//!   the two (a collision's outcome separates, or moves together);
//! * 4-momentum conserved to 1e-12 relative in every puck–puck contact;
//! * every position and velocity finite.

mod common;
#[path = "collision_integrity/invariants.rs"]
mod invariants;
#[path = "collision_integrity/scenes.rs"]
mod scenes;
use common::assert_conserved;
use glam::DVec2;
use invariants::{check_invariants, pair_contacts, pairs_of};
use lightcone_engine::physics::{Billiard, PuckInit, overlap};
use proptest::prelude::*;
use scenes::{RandomPuck, beta, permute_pucks, puck, random_box, random_scene, u};

const R: f64 = 0.03;

#[test]
fn head_on_at_any_proper_velocity_is_one_contact() {
    // The failing input: u = (±10⁴, ±3) on a 4 m table, c = 1,
    // centres 2 m apart at the same y, and the same shape at every u (a
    // transverse part 3·10⁻⁴ of the speed: 0.3 mm of drift each). They meet
    // once near t = 1, fly back to the cushions (t ≈ 3) and would meet
    // again only near t = 5.
    for speed in [10.0, 1e3, 1e4, 1e6, 1e8] {
        let across = 3e-4 * speed;
        let mut b = Billiard::new(
            1.0,
            DVec2::new(4.0, 4.0),
            1.0,
            1.0,
            vec![
                puck("a", 1.0, 2.0, u(speed, across)),
                puck("b", 3.0, 2.0, u(-speed, -across)),
            ],
        );
        b.advance_to(2.9);
        assert_eq!(pair_contacts(&b), 1, "u = {speed}: {:?}", b.collisions());
        // Elastic, and the board is the CM frame: each keeps its speed and
        // turns back (the small offset tilts the normal a little).
        let after = (
            b.worldline(0).proper_velocity_at(2.9),
            b.worldline(1).proper_velocity_at(2.9),
        );
        let before = u(speed, across).0.length();
        for (w, sign) in [(after.0, -1.0), (after.1, 1.0)] {
            assert!(
                (w.0.length() - before).abs() < 1e-12 * before,
                "{speed}: {after:?}"
            );
            assert!(w.0.x * sign > 0.99 * speed, "{speed}: {after:?}");
        }
        check_invariants(&b, 2.9, 200);
    }
}

#[test]
fn inelastic_hit_stays_within_the_overlap_bound() {
    // The second input: a at (0.5, 0.5) with β = 0.5 onto b at rest
    // at (1.0, 0.5), c = 1, restitution 0. They leave together.
    let mut b = Billiard::new(
        1.0,
        DVec2::new(2.84, 1.42),
        0.0,
        1.0,
        vec![
            puck("a", 0.5, 0.5, beta(0.5, 0.0)),
            puck("b", 1.0, 0.5, u(0.0, 0.0)),
        ],
    );
    b.advance_to(2.0);
    assert_eq!(pair_contacts(&b), 1, "{:?}", b.collisions());
    let c = &b.collisions()[0];
    // The bound in closed form: the pair frame moves at β_f = u/(γ + 1)
    // (half the rapidity), each puck has γ' = √((γ + 1)/2) there and grows
    // back by R(1 − 1/γ'); between the kicks, 2Rβ_f/c apart on the board, a
    // already moves with the common velocity β_f and b is still at rest.
    let u0 = beta(0.5, 0.0);
    let g = u0.gamma();
    let beta_f = u0.0.x / (g + 1.0);
    let gamma_f = ((g + 1.0) / 2.0).sqrt();
    let bound = 2.0 * R * (1.0 - 1.0 / gamma_f) + (2.0 * R * beta_f) * beta_f;
    assert!(
        (c.overlap_bound - bound).abs() < 1e-12,
        "{} vs {bound}",
        c.overlap_bound
    );
    assert!(bound < 0.007, "{bound}"); // the light-travel convention left 14 mm
    // Moving together at the CM velocity, within the bound, never deeper.
    let (ua, ub) = (
        b.worldline(0).proper_velocity_at(2.0),
        b.worldline(1).proper_velocity_at(2.0),
    );
    assert!((ua.0 - ub.0).length() < 1e-12, "{ua:?} {ub:?}");
    let worst = check_invariants(&b, 2.0, 400);
    // The final overlap: at rest in the pair frame the rest discs are
    // 2R/γ_f apart, i.e. 2R(1 − 1/γ_f) deep, seen contracted on the board.
    let t = 1.5;
    let d = overlap::depth(
        b.worldline(0).segment_at(t),
        R,
        b.worldline(1).segment_at(t),
        R,
        t,
    );
    // (On the board both shapes and their distance are contracted by γ_f.)
    assert!(
        (d - 2.0 * R * (1.0 - 1.0 / gamma_f) / gamma_f).abs() < 1e-9,
        "{d}"
    );
    assert!(worst <= bound + 1e-9);
}

#[test]
fn grazing_hits_at_any_speed_hold_the_invariants() {
    for speed in [0.5, 10.0, 1e4, 1e8] {
        let mut b = Billiard::new(
            1.0,
            DVec2::new(4.0, 4.0),
            1.0,
            1.0,
            vec![
                puck("a", 1.0, 2.0, u(speed, 0.0)),
                puck("b", 2.0, 2.0 + 2.0 * R * (1.0 - 1e-12), u(0.0, 0.0)),
            ],
        );
        b.advance_to(2.5);
        assert!(pair_contacts(&b) <= 1, "{speed}: {:?}", b.collisions());
        check_invariants(&b, 2.5, 100);
    }
}

#[test]
fn newtons_cradle_passes_the_stroke_to_the_last_puck() {
    // Five touching pucks struck at β = 0.9: the last leaves with the
    // striker's velocity, the rest stay (equal masses, elastic, head-on:
    // every contact exchanges velocities exactly in the CM frame).
    let y = 0.7;
    let u0 = beta(0.9, 0.0);
    let mut pucks = vec![puck("striker", 0.3, y, u0)];
    for k in 0..5 {
        pucks.push(puck(
            &format!("row{k}"),
            1.0 + 2.0 * R * k as f64,
            y,
            u(0.0, 0.0),
        ));
    }
    let mut b = Billiard::new(1.0, DVec2::new(4.0, 1.42), 1.0, 1.0, pucks);
    let until = 2.0;
    b.advance_to(until);
    assert_eq!(pair_contacts(&b), 5, "{:?}", b.collisions());
    for i in 0..5 {
        let ui = b.worldline(i).proper_velocity_at(until);
        assert!(ui.0.length() < 1e-12, "{}: {ui:?}", b.name(i));
    }
    let last = b.worldline(5).proper_velocity_at(until);
    assert!((last.0 - u0.0).length() < 1e-12, "{last:?}");
    check_invariants(&b, until, 400);
}

#[test]
fn three_pucks_driven_into_a_corner() {
    let table = DVec2::new(1.0, 1.0);
    let mut b = Billiard::new(
        1.0,
        table,
        1.0,
        1.0,
        vec![
            puck("a", 0.8, 0.8, beta(0.6, 0.6)),
            puck("b", 0.9, 0.7, beta(0.7, 0.5)),
            puck("c", 0.7, 0.9, beta(0.5, 0.7)),
        ],
    );
    b.advance_to(3.0);
    assert!(b.stats().contacts() > 5);
    check_invariants(&b, 3.0, 600);
}

#[test]
fn crowded_inelastic_box_collapses_without_overlap_beyond_the_bound() {
    let mut b = random_box(200, 1.0, 0.5, 7);
    b.set_history(Some(0.0));
    let mut contacts = 0u64;
    let mut t = 0.0;
    while b.stats().contacts() < 100_000 && t < 50.0 {
        t += 0.05;
        b.advance_to(t);
        // Every contact's own bound holds at the contact instant and after:
        // check each kept pair at the current time.
        for c in b.collisions() {
            for (i, j) in pairs_of(c) {
                assert_conserved(c, 1e-12);
                let (wi, wj) = (b.worldline(i), b.worldline(j));
                let d = overlap::depth(wi.last(), R, wj.last(), R, t);
                // Restitution 0.5 and Zeno merges: overlaps can only come
                // from contacts; 0.3 R is far above any bound here (β ≤ 0.7)
                // and far below a pass-through.
                assert!(d < 0.3 * R, "{d} at {t}");
            }
        }
        contacts = b.stats().contacts();
    }
    assert!(contacts >= 100_000, "only {contacts} contacts by t = {t}");
    for i in 0..b.len() {
        assert!(b.worldline(i).last().u.is_finite());
    }
}

#[test]
fn a_scene_listed_in_another_order_gives_the_same_run() {
    // Simultaneous contacts: a striker meets two touching pucks at the same
    // instant, and a cradle. Listing the pucks in another order must not
    // change anything, bit for bit.
    let make = |order: &[usize]| {
        let all = [
            puck("a", 0.5, 0.7, beta(0.6, 0.0)),
            puck("b", 1.5, 0.7 + R, u(0.0, 0.0)),
            puck("c", 1.5, 0.7 - R, u(0.0, 0.0)),
            puck("d", 0.5, 0.3, beta(0.8, 0.0)),
            puck("e", 1.2, 0.3, u(0.0, 0.0)),
            puck("f", 1.2 + 2.0 * R, 0.3, u(0.0, 0.0)),
        ];
        let pucks = order.iter().map(|&k| all[k].clone()).collect();
        let mut b = Billiard::new(1.0, DVec2::new(2.84, 1.42), 1.0, 1.0, pucks);
        b.advance_to(6.0);
        let mut state: Vec<(String, [u64; 4])> = (0..b.len())
            .map(|i| {
                let s = b.worldline(i).state_at(6.0);
                (
                    b.name(i).to_owned(),
                    [
                        s.position.x.to_bits(),
                        s.position.y.to_bits(),
                        s.u.0.x.to_bits(),
                        s.u.0.y.to_bits(),
                    ],
                )
            })
            .collect();
        state.sort();
        let log: Vec<(u64, Vec<String>)> = b
            .collisions()
            .iter()
            .map(|c| {
                let mut names: Vec<String> =
                    c.pucks.iter().map(|p| b.name(p.puck).to_owned()).collect();
                names.sort();
                (c.t.to_bits(), names)
            })
            .collect();
        (state, log)
    };
    let reference = make(&[0, 1, 2, 3, 4, 5]);
    assert!(reference.1.len() > 4);
    for order in [[5, 4, 3, 2, 1, 0], [2, 0, 1, 5, 3, 4], [1, 2, 0, 4, 5, 3]] {
        assert_eq!(make(&order), reference, "order {order:?}");
    }
}

#[test]
fn every_shipped_scene_file_with_its_pucks_permuted_gives_the_same_run() {
    // The scene files as shipped, their `[[puck]]` tables reversed and
    // rotated: each puck's worldline state and the collision log (by
    // names) are the same, bit for bit.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("assets/scenes")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 5);
    let until = 6.0;
    let run = |text: &str, file: &str| {
        let scene = lightcone_engine::scene::parse(text, file).expect("a valid scene");
        let mut b = Billiard::from_scene(&scene);
        b.advance_to(until);
        let mut state: Vec<(String, [u64; 4])> = (0..b.len())
            .map(|i| {
                let s = b.worldline(i).state_at(until);
                (
                    b.name(i).to_owned(),
                    [
                        s.position.x.to_bits(),
                        s.position.y.to_bits(),
                        s.u.0.x.to_bits(),
                        s.u.0.y.to_bits(),
                    ],
                )
            })
            .collect();
        state.sort();
        let log: Vec<(u64, Vec<(String, u64)>)> = b
            .collisions()
            .iter()
            .map(|c| {
                let mut kicks: Vec<(String, u64)> = c
                    .pucks
                    .iter()
                    .map(|p| (b.name(p.puck).to_owned(), p.t.to_bits()))
                    .collect();
                kicks.sort();
                (c.t.to_bits(), kicks)
            })
            .collect();
        (state, log)
    };
    let mut permuted = 0;
    for path in files {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(&path).expect("readable scene");
        let reference = run(&text, &file);
        let n = reference.0.len();
        if n < 2 {
            continue;
        }
        let reversed: Vec<usize> = (0..n).rev().collect();
        let rotated: Vec<usize> = (0..n).map(|k| (k + 1) % n).collect();
        for (name, order) in [("reversed", reversed), ("rotated", rotated)] {
            let other = permute_pucks(&text, &order);
            assert_ne!(other, text, "{file}");
            assert_eq!(run(&other, &file), reference, "{file}, pucks {name}");
            permuted += 1;
        }
    }
    assert!(permuted >= 10, "{permuted}");
}

#[test]
fn bounded_history_forgets_and_says_so() {
    let mut b = random_box(50, 0.8, 1.0, 3);
    b.set_history(Some(0.5));
    b.advance_to(5.0);
    assert!(
        b.forgotten_before()
            .is_some_and(|t| t > 4.0 && t <= 4.5 + 1e-12)
    );
    b.advance_to(5.0 + 1e-9);
    // Dropped from the front up to the first record with a velocity change
    // after the horizon (records are in processing order).
    assert!(b.collisions()[0].pucks.iter().any(|p| p.t > 4.5 - 1e-9));
    let kept_old = b
        .collisions()
        .iter()
        .filter(|c| c.pucks.iter().all(|p| p.t <= 4.5))
        .count();
    assert!(kept_old * 10 < b.collisions().len() + 10, "{kept_old}");
    assert!(b.collisions_forgotten() > 0);
    for i in 0..b.len() {
        let w = b.worldline(i);
        // Segments older than the horizon are gone (the first kept one may
        // have started earlier: it is the one in force at the horizon).
        // Trimmed when the puck last changed: nothing older than the horizon
        // before that.
        let segs = w.segments();
        assert!(segs.len() < 2 || segs[1].start.t > w.last().start.t - 0.5 - 1e-9);
    }
}

/// The random scenes' seed: 3, or `LIGHTCONE_SCENE_SEED` (to try others
/// locally). The cases other seeds found are kept in
/// `found_cases_hold_the_invariants`.
fn random_scene_seed() -> u64 {
    std::env::var("LIGHTCONE_SCENE_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3)
}

proptest! {
    // A fixed seed: CI runs the same 1 000 scenes every time; another seed
    // (`LIGHTCONE_SCENE_SEED`) tries others. Cases found that way are kept
    // in `found_cases_hold_the_invariants`.
    #![proptest_config(ProptestConfig {
        cases: 1000,
        rng_seed: proptest::test_runner::RngSeed::Fixed(random_scene_seed()),
        ..ProptestConfig::default()
    })]

    /// Random scenes: 2 to 5 pucks, proper velocities from 10⁻² to 10⁶ in
    /// any direction, restitution 1, 0.5 or 0 between pucks, elastic
    /// cushions (an inelastic bounce still widens a shape into the cushion
    /// struck: `Billiard::cushion_contact`); every invariant holds.
    #[test]
    fn invariants_hold_on_random_scenes(
        pucks in prop::collection::vec(
            (0.05f64..1.95, 0.05f64..0.95, -2.0f64..6.0, 0.0f64..std::f64::consts::TAU),
            2..6,
        ),
        restitution in prop::sample::select(vec![1.0, 0.5, 0.0]),
    ) {
        let mut list: Vec<PuckInit> = Vec::new();
        for (k, &(x, y, log_u, angle)) in pucks.iter().enumerate() {
            let p = DVec2::new(x, y);
            if list.iter().any(|q| (q.position - p).length() < 2.0 * R + 1e-6) {
                continue; // overlapping start: not a valid scene
            }
            let speed = 10f64.powf(log_u);
            list.push(puck(&format!("p{k}"), x, y, u(speed * angle.cos(), speed * angle.sin())));
        }
        prop_assume!(list.len() >= 2);
        let mut b = Billiard::new(1.0, DVec2::new(2.0, 1.0), restitution, 1.0, list);
        // Bounded: a run that does not end (a Zeno sequence) fails here.
        prop_assert!(b.step_until(2.0, 400_000), "over 4·10⁵ events before t = 2 s");
        prop_assert!(b.stats().contacts() < 200_000);
        check_invariants(&b, 2.0, 40);
    }
}

/// Cases proptest found, kept as plain tests.
#[test]
fn found_cases_hold_the_invariants() {
    let cases: [(f64, &[RandomPuck]); 18] = [
        // Seed 15: restitution 0, a γ ≈ 5·10³ puck meets a γ ≈ 4 one near
        // a cushion. The board decides the contact (the pair frame moves at
        // u ≈ 73 on the board); an impulse along the board normal alone left
        // them sliding, and the shapes, reshaped by the kick, slid back into
        // each other (4 mm) while the pair was settled. Restitution 0 now
        // moves them together, as in the pair frame.
        (
            0.0,
            &[
                (
                    0.17217586743589933,
                    0.9331471554419596,
                    0.5926550063091633,
                    5.762626948216999,
                ),
                (
                    0.15446066146866852,
                    0.8729566053179851,
                    3.6782072282796165,
                    6.168007227709471,
                ),
            ],
        ),
        // Seed 11: restitution 0, γ ≈ 190 onto γ ≈ 39; the board push
        // leaves them sliding back into each other unless they move together.
        (
            0.0,
            &[
                (
                    0.40128556657662523,
                    0.3141412350387423,
                    1.5907910702061323,
                    5.828855354252207,
                ),
                (
                    0.759070051602169,
                    0.598227380331025,
                    2.284040345146608,
                    0.8973839873728007,
                ),
            ],
        ),
        // A γ ≈ 2·10⁴ puck crossing a slow one's path (restitution 0): the
        // board shapes meet before the pair frame's first kick.
        (
            0.0,
            &[
                (
                    1.4835426794757411,
                    0.10149507167655569,
                    4.3508804641747885,
                    1.5604157139537165,
                ),
                (
                    1.5464576567498427,
                    0.15670027082633176,
                    0.6236182208084808,
                    3.0700707497072335,
                ),
            ],
        ),
        (
            0.0,
            &[
                (
                    0.13282056959579547,
                    0.7088045377767644,
                    2.932801672348051,
                    6.162237636458212,
                ),
                (
                    0.1250039969350767,
                    0.5091693098745469,
                    3.305500352483935,
                    0.04344773190301386,
                ),
            ],
        ),
        (
            0.5,
            &[
                (
                    0.9254903156341419,
                    0.27874569996869225,
                    0.29662097740116555,
                    3.7429073467012435,
                ),
                (
                    0.4466965612044838,
                    0.6601571860615952,
                    5.218236845949514,
                    4.4838877826926815,
                ),
            ],
        ),
        (
            0.5,
            &[
                (
                    1.48044744721648,
                    0.2628464060483128,
                    5.796757150093374,
                    2.67149844335425,
                ),
                (
                    1.0103641972043778,
                    0.20153514709831322,
                    1.1494918563133758,
                    4.303611443497425,
                ),
            ],
        ),
        (
            0.0,
            &[
                (
                    1.3983290838543379,
                    0.2312789043998876,
                    0.8586342808125688,
                    4.679569545507608,
                ),
                (
                    1.6412487825434414,
                    0.5967806148433024,
                    4.521432820813968,
                    1.0379849112668913,
                ),
            ],
        ),
        // A jam of three at a cushion: a γ ≈ 300 puck crushes two slow ones.
        (
            0.5,
            &[
                (
                    0.39297240852140186,
                    0.6405478203555027,
                    4.163218504910568,
                    1.8200436577046128,
                ),
                (
                    0.17056806425699847,
                    0.5541202679682206,
                    -0.984045777064438,
                    0.9288526161937191,
                ),
                (
                    0.7596610490873167,
                    0.23335135774790172,
                    0.5956690889848277,
                    2.983526175886573,
                ),
            ],
        ),
        // A merged pair (restitution 0) at γ ≈ 29 squeezed by a cushion.
        (
            0.0,
            &[
                (
                    1.5422088114880221,
                    0.9082224497680265,
                    2.0218162895627656,
                    3.208072879091008,
                ),
                (
                    1.182170491841846,
                    0.4138844398271944,
                    5.113143970293357,
                    1.8891594733647519,
                ),
            ],
        ),
        // γ ≈ 3·10³ onto a slow puck by a cushion.
        (
            0.5,
            &[
                (
                    1.3455210711913006,
                    0.40474328607024823,
                    3.469413531329218,
                    3.7290109395483473,
                ),
                (
                    0.6785327857293731,
                    0.4930454752041854,
                    0.0,
                    5.09350839628769,
                ),
            ],
        ),
        // Three pucks at γ up to 10⁵ in a jam at a cushion.
        (
            0.5,
            &[
                (
                    1.3573083920096918,
                    0.8789853542320814,
                    5.121483269311188,
                    4.048142166612625,
                ),
                (
                    0.9815305676056633,
                    0.06706345041945315,
                    -0.4834760192276331,
                    2.100207156487637,
                ),
                (
                    0.248391762018209,
                    0.5082349930216611,
                    3.5591089783573495,
                    3.6529068733001644,
                ),
            ],
        ),
        // Seed 1: restitution 0, γ ≈ 5·10³ and 7·10⁵ pucks end up moving
        // together along the top cushion, the light one pressed into it by
        // the heavy one: cushion and pair contacts alternated at one board
        // time, the push into the cushion shrinking by 0.2 % a cycle, for
        // ever (a Zeno sequence). The cushion now stops the pressed pair.
        (
            0.0,
            &[
                (
                    0.8129627681977818,
                    0.5323450755578197,
                    -1.2587575038508951,
                    2.258571488943842,
                ),
                (
                    0.2767958168336244,
                    0.5109628256474029,
                    3.725929298740795,
                    0.033177210565920955,
                ),
                (
                    1.4836021979595484,
                    0.534557235669989,
                    5.839180151418599,
                    5.405602068538132,
                ),
            ],
        ),
        // Seed 1 again: restitution 0, a light puck crushed between two
        // heavy ones (γ ≈ 10⁵ before the heat of earlier contacts) that
        // converge on it: it bounced between them at one board time, each
        // inelastic pair contact only nudging the heavy one, for ever. The
        // three now move together (`resolve::together_all`).
        (
            0.0,
            &[
                (
                    0.6195177511598957,
                    0.47537979005823894,
                    3.4494960315719414,
                    2.529918661069406,
                ),
                (
                    1.4470578776559964,
                    0.5112482509706696,
                    5.210108548117238,
                    2.8891142012662874,
                ),
                (
                    0.09757907349361872,
                    0.22264939059655411,
                    3.76705141515649,
                    4.326184128364379,
                ),
            ],
        ),
        // Seed 41: restitution 0; a pair moving together at γ ≈ 113 meets
        // a cushion, one at a time: the first bounces back across the
        // other's path, two thin shapes crossing. The pair frame finds no
        // contact (its slice meets the first puck before its bounce) and the
        // board's first-touch search stepped over the 9 ms overlap (see
        // seed 531).
        (
            0.0,
            &[
                (
                    0.2760530816301697,
                    0.6084330337883384,
                    4.9578219338917915,
                    4.204774163028545,
                ),
                (
                    0.7162092328265648,
                    0.5446119407391773,
                    0.7475023277766294,
                    4.0453998252280075,
                ),
            ],
        ),
        // Seed 103: restitution 0, a light puck pressed into a cushion by a
        // heavy one moving with it; the pair's kicks came at the cushion's
        // time but were counted at their contact's later time, so the
        // sequence never looked quick at the cushion. Zeno counts at the
        // processing time now.
        (
            0.0,
            &[
                (
                    0.47813175116346945,
                    0.2573983496760726,
                    5.883777098843035,
                    1.9290355578823186,
                ),
                (
                    0.5859995054713428,
                    0.6653957698665809,
                    4.838532258193481,
                    4.259452063303114,
                ),
                (
                    0.653834843310941,
                    0.5426540793278396,
                    0.09220393989510296,
                    1.8860930127276583,
                ),
            ],
        ),
        // Seed 339: restitution 0.5, a γ ≈ 4·10⁵ puck onto a γ ≈ 230 one;
        // after their contact both move the same way, contracted by γ ≈ 15
        // and 200, side by side, and slide into each other 0.2 s after
        // parting (77 µm by t = 1.8 s). A pair that had collided was never
        // predicted again; now it is, on the board, once parted.
        (
            0.5,
            &[
                (
                    0.8540298584951544,
                    0.8161294502033031,
                    5.590436241545552,
                    4.090866867524551,
                ),
                (
                    0.27200248861449977,
                    0.9193104815932086,
                    2.368049645386507,
                    1.7170676505306608,
                ),
            ],
        ),
        // Seed 423: restitution 0, a chain pressed into a cushion (one puck
        // pushing a second pushing a third into it), the second contact a
        // pair-frame one whose far kick was still ahead: the cluster merge
        // now lands such kicks first and merges at the processing time.
        (
            0.0,
            &[
                (
                    1.2900550942203546,
                    0.5944148763314147,
                    4.37191080427232,
                    4.004583410017529,
                ),
                (
                    1.1316959116775296,
                    0.06147367263486218,
                    3.777619244035839,
                    1.66857085285592,
                ),
                (
                    0.6835832436502376,
                    0.0535108842231196,
                    -1.3050387883327967,
                    6.253293717485159,
                ),
                (
                    0.31020103824015904,
                    0.8102454706903052,
                    4.49884063249622,
                    3.755939972510902,
                ),
            ],
        ),
        // Seed 531: as seed 41 at restitution 0.5 (γ ≈ 40 and 500 after
        // their contact): the overlap after the bounce lasts under a
        // millisecond, which a scan could miss too; the first-touch search
        // now maximises the true (concave) gap function.
        (
            0.5,
            &[
                (
                    0.1446298186010257,
                    0.20767480108700553,
                    4.694940483370524,
                    4.034952938985014,
                ),
                (
                    0.39185041771490103,
                    0.23005476108614492,
                    -0.60659786096014,
                    3.403225751938179,
                ),
            ],
        ),
    ];
    for (k, (restitution, raw)) in cases.into_iter().enumerate() {
        if std::env::var("LIGHTCONE_CASE").is_ok_and(|c| c != k.to_string()) {
            continue;
        }
        let mut b = random_scene(restitution, raw);
        // Bounded: a Zeno sequence that is not ended runs for ever.
        assert!(
            b.step_until(2.0, 100_000),
            "case {k}: over 10⁵ events before t = 2 s"
        );
        check_invariants(&b, 2.0, 40);
    }
}
