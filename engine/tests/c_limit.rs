//! c that means c: a scene under a larger speed of light keeps each puck's
//! proper velocity in m/s (its momentum), so at c = 10⁶ m/s the paper's
//! carom is Newton's, checked against a classical event loop written here
//! (equal discs, elastic hits, elastic cushions) and against nothing the
//! engine computed.

use std::path::Path;

use glam::DVec2;
use lightcone_engine::physics::Billiard;
use lightcone_engine::scene;

/// Classical elastic discs of equal mass and radius `r` on the table
/// `[0, size.x] × [0, size.y]`, run from t = 0 to `until`.
fn newton(mut x: Vec<DVec2>, mut v: Vec<DVec2>, r: f64, size: DVec2, until: f64) -> Vec<DVec2> {
    let n = x.len();
    let mut t = 0.0;
    loop {
        // The earliest event: a disc reaching a cushion, or two discs touching.
        let mut next = (until - t, None::<(usize, Option<usize>)>);
        for i in 0..n {
            for (pos, vel, hi) in [(x[i].x, v[i].x, size.x), (x[i].y, v[i].y, size.y)] {
                let dt = if vel > 0.0 {
                    (hi - r - pos) / vel
                } else if vel < 0.0 {
                    (r - pos) / vel
                } else {
                    f64::INFINITY
                };
                if dt >= 0.0 && dt < next.0 {
                    next = (dt, Some((i, None)));
                }
            }
            for j in i + 1..n {
                // |d + w t| = 2r, approaching (d·w < 0).
                let (d, w) = (x[j] - x[i], v[j] - v[i]);
                let (a, b, c) = (w.dot(w), d.dot(w), d.dot(d) - 4.0 * r * r);
                let disc = b * b - a * c;
                if b < 0.0 && disc >= 0.0 && a > 0.0 {
                    let dt = c / (-b + disc.sqrt()); // the smaller root, stably
                    if dt >= 0.0 && dt < next.0 {
                        next = (dt, Some((i, Some(j))));
                    }
                }
            }
        }
        let (dt, event) = next;
        for i in 0..n {
            x[i] += v[i] * dt;
        }
        t += dt;
        match event {
            None => return x,
            Some((i, None)) => {
                if x[i].x <= r + 1e-12 || x[i].x >= size.x - r - 1e-12 {
                    v[i].x = -v[i].x;
                }
                if x[i].y <= r + 1e-12 || x[i].y >= size.y - r - 1e-12 {
                    v[i].y = -v[i].y;
                }
            }
            Some((i, Some(j))) => {
                // Equal masses: the normal components swap.
                let nrm = (x[j] - x[i]).normalize();
                let (a, b) = (v[i].dot(nrm), v[j].dot(nrm));
                v[i] += nrm * (b - a);
                v[j] += nrm * (a - b);
            }
        }
    }
}

/// The paper's scene as the paper ran it: without the cloth's friction
/// (uniform motion between contacts, which `newton` integrates).
fn frictionless(mut scene: scene::Scene) -> scene::Scene {
    scene.table.friction = 0.0;
    scene
}

#[test]
fn at_a_million_metres_per_second_the_papers_carom_is_newtons() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/paper_carom.toml");
    let paper = frictionless(scene::load(&path).unwrap());
    let fast = paper.with_c(1.0e6).unwrap();
    // The momenta (γ v, m/s) are the paper's.
    for (a, b) in paper.pucks.iter().zip(&fast.pucks) {
        assert!((a.u.0 * paper.c - b.u.0 * fast.c).length() < 1e-12);
    }
    let until = 6.0;
    let mut billiard = Billiard::from_scene(&fast);
    billiard.advance_to(until);
    let r = paper.pucks[0].radius;
    assert!(
        paper
            .pucks
            .iter()
            .all(|p| p.radius == r && p.mass == paper.pucks[0].mass)
    );
    let x0: Vec<DVec2> = paper.pucks.iter().map(|p| p.position).collect();
    let v0: Vec<DVec2> = paper
        .pucks
        .iter()
        .map(|p| (p.u.0 * paper.c).truncate())
        .collect();
    let expected = newton(x0, v0, r, paper.table.size, until);
    let hits = billiard.collisions().len();
    assert!(hits >= 4, "only {hits} collisions by t = {until} s");
    for (i, e) in expected.iter().enumerate() {
        let got = billiard.worldline(i).position_at(until).truncate();
        assert!(
            got.distance(*e) < 1e-6,
            "{}: {got} vs Newton's {e} ({} m apart)",
            paper.pucks[i].name,
            got.distance(*e)
        );
    }
}

#[test]
fn lowering_c_keeps_the_momentum_below_c() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/paper_carom.toml");
    let paper = frictionless(scene::load(&path).unwrap());
    let slow = paper.with_c(0.05).unwrap();
    let u = slow.pucks[0].u;
    assert!((u.0 * 0.05 - paper.pucks[0].u.0 * paper.c).length() < 1e-12);
    // 1 − |β| = 1/(2u²) (1 − 3/(4u²) + 5/(8u⁴) − …): at |u| ≈ 87 the
    // second term is 1e-4 and the third, left out, 8e-9 of the first.
    let m = u.0.length();
    let series = 1.0 / (2.0 * m * m) * (1.0 - 0.75 / (m * m));
    assert!(m > 80.0, "{m}");
    assert!(
        (u.speed_deficit() / series - 1.0).abs() < 1.0 / m.powi(4),
        "{}",
        u.speed_deficit()
    );
    assert!(paper.with_c(0.0).is_err() && paper.with_c(f64::NAN).is_err());
}

/// Largest distance from Newton's positions at t = 6 s, the paper's carom
/// at speed of light `c` (momenta kept).
fn newton_error(c: f64) -> f64 {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/paper_carom.toml");
    let paper = frictionless(scene::load(&path).unwrap());
    let fast = paper.with_c(c).unwrap();
    let until = 6.0;
    let mut billiard = Billiard::from_scene(&fast);
    billiard.advance_to(until);
    let x0: Vec<DVec2> = paper.pucks.iter().map(|p| p.position).collect();
    let v0: Vec<DVec2> = paper
        .pucks
        .iter()
        .map(|p| (p.u.0 * paper.c).truncate())
        .collect();
    let expected = newton(x0, v0, paper.pucks[0].radius, paper.table.size, until);
    expected
        .iter()
        .enumerate()
        .map(|(i, e)| {
            billiard
                .worldline(i)
                .position_at(until)
                .truncate()
                .distance(*e)
        })
        .fold(0.0, f64::max)
}

/// The Newtonian limit keeps its digits as c grows: the distance to
/// Newton's positions shrinks with c (the relativistic corrections, ~ (v/c)²)
/// down to rounding. Measured with the paper's momenta on the shipped scene
/// (white γv = 4.3 m/s, friction off): 2.4e-8 m at c = 1e5, 2.4e-10 at
/// 1e6, 2.4e-12 at 1e7 (the 1/c² of the corrections), then rounding:
/// 6e-14 at 1e8 and 7e-14 at 1e9. (Before boosts of slow frames were
/// computed in the textbook form, the error grew again with c: 7.4e-7 m at
/// 1e9 with the slower stroke of round one.)
#[test]
fn the_newtonian_limit_keeps_its_digits_up_to_a_billion_metres_per_second() {
    let at = |c: f64| newton_error(c);
    let (e6, e7, e9) = (at(1e6), at(1e7), at(1e9));
    assert!(e6 < 1e-9, "c = 1e6: {e6:e} m");
    assert!(e7 < 1e-11, "c = 1e7: {e7:e} m");
    // The 1/c² of the leading correction, while it is above rounding.
    assert!((e6 / e7 / 100.0 - 1.0).abs() < 0.1, "{e6:e} / {e7:e}");
    assert!(e9 < 1e-12, "c = 1e9: {e9:e} m");
}
