//! The optics against closed forms of Special Relativity.

use glam::{DVec2, DVec3};
use lightcone_engine::optics::emission;
use lightcone_engine::optics::eye::{Eye, doppler};
use lightcone_engine::optics::view::{Method, observe};
use lightcone_engine::physics::{Billiard, PuckInit};
use lightcone_engine::scene::Effects;
use lightcone_engine::spacetime::{Event, ProperVelocity};
use lightcone_engine::worldline::{ContractedShape, RestShape, Worldline};

const C: f64 = 1.42;

fn beta(b: DVec3) -> ProperVelocity {
    ProperVelocity::try_from_beta(b).unwrap()
}

/// Apparent position of a point moving along the x axis, seen from the
/// origin, at observation time `t0`.
fn apparent_x(w: &Worldline, t0: f64) -> f64 {
    emission::solve(
        w,
        DVec3::ZERO,
        &ContractedShape::of(w),
        Event::new(t0, DVec3::ZERO),
    )
    .event
    .position
    .x
}

#[test]
fn apparent_speed_along_the_line_of_sight() {
    // Approaching at v: seen to move at v / (1 − β); receding: v / (1 + β).
    // β → 1 heading at the observer: without bound (γ up to 10⁴ here,
    // apparent speed 2γ² v ≈ 2·10⁸ v), and no NaN.
    for b in [0.1, 0.5, 0.9, 0.999, 1.0 - 1e-8] {
        let approach = Worldline::new(
            Event::new(0.0, DVec3::new(-1e3, 0.0, 0.0)),
            beta(DVec3::X * b),
            C,
        );
        let recede = Worldline::new(
            Event::new(0.0, DVec3::new(-1.0, 0.0, 0.0)),
            beta(-DVec3::X * b),
            C,
        );
        let v = b * C;
        let dt = 1e-3;
        let a = (apparent_x(&approach, 10.0 + dt) - apparent_x(&approach, 10.0)) / dt;
        let r = (apparent_x(&recede, 10.0 + dt) - apparent_x(&recede, 10.0)) / dt;
        // Tolerance: the difference quotient of exact positions, relative
        // error ~ ε |x| / (v dt / (1 − β)).
        assert!(
            (a / (v / (1.0 - b)) - 1.0).abs() < 1e-6,
            "β = {b}: {a} vs {}",
            v / (1.0 - b)
        );
        assert!((r / (-v / (1.0 + b)) - 1.0).abs() < 1e-9, "β = {b}: {r}");
        assert!(a.is_finite() && r.is_finite());
    }
}

#[test]
fn static_table_seen_by_a_moving_observer() {
    // Every corner of the table, seen from an observer flying along +x at
    // β: the textbook aberration cos θ' = (cos θ + β)/(1 + β cos θ), with θ
    // the angle to the motion in the board frame, and D = γ(1 + β cos θ)
    // (a resting source ahead of an approaching observer is blue-shifted).
    let corners = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.84, 0.0, 0.0),
        DVec3::new(0.0, 1.42, 0.0),
        DVec3::new(2.84, 1.42, 0.0),
    ];
    for b in [0.3, 0.9, 0.999] {
        let u = beta(DVec3::X * b);
        let eye = Eye {
            event: Event::new(3.0, DVec3::new(1.0, -1.0, 0.8)),
            u,
        };
        for p in corners {
            let seen = eye.see_static(p, C, true);
            let to = (p - eye.event.position).normalize();
            let cos = to.x;
            let expected = (cos + b) / (1.0 + b * cos);
            assert!((seen.direction().x - expected).abs() < 1e-12, "{b} {p}");
            let d = u.gamma() * (1.0 + b * cos);
            assert!((seen.doppler / d - 1.0).abs() < 1e-12);
            assert!((seen.doppler - doppler(-to, ProperVelocity::ZERO, u)).abs() < 1e-12);
        }
    }
}

#[test]
fn observer_at_gamma_1000_sees_finite_unit_directions() {
    let u = ProperVelocity(DVec3::new(0.0, 1e3, 0.0));
    let eye = Eye {
        event: Event::new(1.0, DVec3::new(1.4, -2.0, 0.5)),
        u,
    };
    for p in [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.84, 1.42, 0.0),
        DVec3::new(1.4, -3.0, 0.0),
    ] {
        let seen = eye.see_static(p, C, true);
        assert!(seen.position.is_finite() && seen.distance.is_finite() && seen.doppler.is_finite());
        assert!((seen.direction().length() - 1.0).abs() < 1e-12);
        // Aberration crowds everything ahead: cos θ' ≥ β − tiny, unless the
        // point is exactly behind. Against the closed form, tolerance 1e-9
        // (cos θ' near 1 at γ = 10³ loses ~γ² ε).
        let cos = (p - eye.event.position).normalize().y;
        let b = u.beta().y;
        let expected = (cos + b) / (1.0 + b * cos);
        assert!(
            (seen.direction().y - expected).abs() < 1e-9,
            "{} vs {expected}",
            seen.direction().y
        );
    }
}

#[test]
fn a_vertex_a_millimetre_from_the_eye() {
    let w = Worldline::new(
        Event::new(0.0, DVec3::new(1.0, 1.0, 0.0)),
        beta(DVec3::new(0.5, 0.2, 0.0)),
        C,
    );
    let t0 = 2.0;
    let p = w.position_at(t0);
    let eye = Event::new(t0, p + DVec3::new(0.0, 0.0, 1e-3));
    let e = emission::solve(&w, DVec3::ZERO, &ContractedShape::of(&w), eye);
    let lag = t0 - e.event.t;
    // Light delay of about 1 mm / c, the point moving meanwhile.
    assert!(lag > 0.0 && lag < 2e-3 / C, "{lag}");
    assert!(((eye.position - e.event.position).length() - C * lag).abs() < 1e-15);
    // And exactly at the eye: no delay, no NaN.
    let e = emission::solve(&w, DVec3::ZERO, &ContractedShape::of(&w), Event::new(t0, p));
    assert!((e.event.t - t0).abs() < 1e-15);
}

#[test]
fn observation_before_the_first_event() {
    // At t = −5 the pucks have not "started": the worldlines extend back
    // with the initial motion, and the view is finite and on the cone.
    let mut b = Billiard::new(
        C,
        DVec2::new(2.84, 1.42),
        1.0,
        1.0,
        vec![PuckInit {
            name: "a".into(),
            position: DVec2::new(1.0, 0.7),
            u: beta(DVec3::new(0.6, 0.0, 0.0)),
            radius: 0.03,
            mass: 0.21,
        }],
    );
    b.advance_to(0.0);
    let eye = Eye {
        event: Event::new(-5.0, DVec3::new(1.4, -1.0, 0.8)),
        u: ProperVelocity::ZERO,
    };
    let shapes = [RestShape::puck(0.03, 0.02, 16)];
    let mut effects = Effects::NONE;
    effects.light_delay = true;
    effects.contraction = true;
    let view = observe(&b, &shapes, &[0.02], eye, effects, Method::Exact, true);
    let body = &view.bodies[0];
    assert!(body.centre.emission.event.t < -5.0);
    for v in &body.vertices {
        let e = v.emission.event;
        assert!(e.is_finite());
        assert!(
            (C * (eye.event.t - e.t) - (eye.event.position - e.position).length()).abs() < 1e-12
        );
    }
}

#[test]
fn light_delay_off_is_the_board_simultaneous_truth() {
    let mut b = Billiard::new(
        C,
        DVec2::new(2.84, 1.42),
        1.0,
        1.0,
        vec![PuckInit {
            name: "a".into(),
            position: DVec2::new(0.3, 0.7),
            u: beta(DVec3::new(0.9, 0.0, 0.0)),
            radius: 0.03,
            mass: 0.21,
        }],
    );
    b.advance_to(1.0);
    let eye = Eye {
        event: Event::new(1.0, DVec3::new(1.4, -1.0, 0.8)),
        u: ProperVelocity::ZERO,
    };
    let shapes = [RestShape::puck(0.03, 0.02, 16)];
    let truth = observe(
        &b,
        &shapes,
        &[0.02],
        eye,
        Effects::NONE,
        Method::Exact,
        true,
    );
    let centre = truth.bodies[0].centre.emission.event;
    assert_eq!(centre.t, 1.0);
    assert!((centre.position - DVec3::new(0.3 + 0.9 * C, 0.7, 0.01)).length() < 1e-12);
    // The seen view (light delay on) shows it earlier, further back.
    let mut effects = Effects::NONE;
    effects.light_delay = true;
    let seen = observe(&b, &shapes, &[0.02], eye, effects, Method::Exact, false);
    let e = seen.bodies[0].centre.emission.event;
    assert!(e.t < 1.0 && e.position.x < centre.position.x);
}

#[test]
fn seen_clocks_run_behind_and_slow() {
    // A puck at β = 0.8 (γ = 5/3): its proper time at board time t is
    // t / γ; the clock seen in the image shows the proper time at the
    // emission event, earlier still.
    let mut b = Billiard::new(
        C,
        DVec2::new(40.0, 1.42),
        1.0,
        1.0,
        vec![PuckInit {
            name: "a".into(),
            position: DVec2::new(0.3, 0.7),
            u: beta(DVec3::new(0.8, 0.0, 0.0)),
            radius: 0.03,
            mass: 0.21,
        }],
    );
    b.advance_to(2.0);
    let eye = Eye {
        event: Event::new(2.0, DVec3::new(0.3, -1.0, 0.0)),
        u: ProperVelocity::ZERO,
    };
    let shapes = [RestShape::puck(0.03, 0.02, 8)];
    let view = observe(
        &b,
        &shapes,
        &[0.02],
        eye,
        Effects::default(),
        Method::Exact,
        false,
    );
    let body = &view.bodies[0];
    let te = body.centre.emission.event.t;
    assert!((body.seen_proper_time - te * 0.6).abs() < 1e-12);
    assert!(body.seen_proper_time < 2.0 * 0.6);
}
