//! Thomas–Wigner rotation of a puck's rest frame, against the Lorentz
//! matrices: a puck bouncing around a square box at γ = 10 turns its rest
//! frame by the same angle at every cushion and comes back, after each
//! circuit, rotated by four times that angle (the velocity itself comes back
//! unchanged).

use glam::{DMat3, DVec2, DVec3};
use lightcone_engine::physics::{Billiard, CollisionKind, PuckInit};
use lightcone_engine::spacetime::ProperVelocity;

/// The (ct, x, y) Lorentz matrix of the pure boost taking a body's
/// rest-frame coordinates (proper velocity `u`, dimensionless) to the board's.
fn boost(u: DVec3) -> DMat3 {
    let g = (1.0 + u.length_squared()).sqrt();
    let k = 1.0 / (g + 1.0);
    DMat3::from_cols(
        DVec3::new(g, u.x, u.y),
        DVec3::new(u.x, 1.0 + k * u.x * u.x, k * u.x * u.y),
        DVec3::new(u.y, k * u.x * u.y, 1.0 + k * u.y * u.y),
    )
}

/// Reference: the rotation, counter-clockwise, that a torque-free change
/// from `u1` to `u2` (board frame) adds to a rest frame. The new rest frame
/// is `B(u1)·B(u′)` with `u′` the new velocity seen in the old rest frame;
/// whatever is left after taking out `B(u2)` is the rotation.
fn reference_rotation(u1: DVec3, u2: DVec3) -> f64 {
    let g2 = (1.0 + u2.length_squared()).sqrt();
    let seen = boost(-u1) * DVec3::new(g2, u2.x, u2.y); // B(u1)⁻¹ = B(−u1)
    let u_prime = DVec3::new(seen.y, seen.z, 0.0);
    let r = boost(-u2) * boost(u1) * boost(u_prime);
    r.y_axis.z.atan2(r.y_axis.y)
}

#[test]
fn square_box_circuit_at_gamma_10() {
    let speed = (10.0_f64 * 10.0 - 1.0).sqrt(); // γ = 10
    let dir = DVec3::new(1.0, 1.0, 0.0).normalize();
    let mut b = Billiard::new(
        1.0,
        DVec2::new(1.0, 1.0),
        1.0,
        1.0,
        vec![PuckInit {
            name: "a".to_owned(),
            position: DVec2::new(0.31, 0.47),
            u: ProperVelocity(dir * speed),
            radius: 0.03,
            mass: 0.2,
        }],
    );
    b.advance_to(40.0);
    let bounces: Vec<_> = b
        .collisions()
        .iter()
        .filter(|c| matches!(c.kind, CollisionKind::Cushion(_)))
        .collect();
    assert!(bounces.len() >= 40, "{} bounces", bounces.len());

    // Every bounce turns the velocity by ±90° at the same γ: the same
    // rotation each time, of the sign of the circulation.
    let first = &bounces[0].pucks[0];
    let per_bounce = reference_rotation(first.u_before.0, first.u_after.0);
    assert!(per_bounce.abs() > 0.1, "{per_bounce}");
    let w = b.worldline(0);
    for (k, c) in bounces.iter().enumerate() {
        let p = &c.pucks[0];
        let turn = reference_rotation(p.u_before.0, p.u_after.0);
        assert!(
            (turn - per_bounce).abs() < 1e-12,
            "bounce {k}: {turn} vs {per_bounce}"
        );
        let orientation = w.state_at(p.t + 1e-9).orientation;
        let expected = per_bounce * (k + 1) as f64;
        assert!(
            (orientation - expected).abs() < 1e-11 * (k + 1) as f64,
            "after bounce {k}: {orientation} vs {expected}"
        );
        if (k + 1) % 4 == 0 {
            // A whole circuit: the velocity is back, the rest frame is not.
            assert!((p.u_after.0 - first.u_before.0).length() < 1e-9 * speed);
        }
    }
    // The optics draws the mesh turned: a rest-frame stripe along +x is seen
    // (board-simultaneous, contraction off) turned by the orientation.
    let t = bounces[5].pucks[0].t + 1e-6;
    let stripe = DVec3::new(0.03, 0.0, 0.0);
    let at = lightcone_engine::optics::emission::simultaneous(
        w,
        stripe,
        &lightcone_engine::worldline::Rigid,
        t,
    );
    let offset = at.event.position - w.position_at(t);
    let angle = offset.y.atan2(offset.x);
    assert!(
        (angle - 6.0 * per_bounce).rem_euclid(std::f64::consts::TAU) < 1e-9
            || (angle - 6.0 * per_bounce).rem_euclid(std::f64::consts::TAU)
                > std::f64::consts::TAU - 1e-9
    );

    // The closed form for a 90° turn at equal γ, written out: in the old
    // rest frame the new velocity has γ′ = γ² and makes, with the old one,
    // tan(|ε|/2) = |u₁ × u′| / ((γ + 1)(γ′ + 1) + u₁·u′).
    let g = 10.0_f64;
    let u1 = DVec3::new(speed, 0.0, 0.0);
    let u2 = DVec3::new(0.0, speed, 0.0);
    let seen = boost(-u1) * DVec3::new(g, u2.x, u2.y);
    assert!((seen.x - g * g).abs() < 1e-10);
    let u_prime = DVec3::new(seen.y, seen.z, 0.0);
    let closed = 2.0
        * u1.cross(u_prime)
            .length()
            .atan2((g + 1.0) * (g * g + 1.0) + u1.dot(u_prime));
    assert!(
        (closed - per_bounce.abs()).abs() < 1e-12,
        "{closed} vs {per_bounce}"
    );
}

#[test]
fn head_on_and_collinear_changes_do_not_rotate() {
    // Two pucks head-on along x: every change is along the line of motion.
    let mut b = Billiard::new(
        1.0,
        DVec2::new(4.0, 4.0),
        1.0,
        1.0,
        vec![
            PuckInit {
                name: "a".to_owned(),
                position: DVec2::new(1.0, 2.0),
                u: ProperVelocity(DVec3::new(5.0, 0.0, 0.0)),
                radius: 0.03,
                mass: 0.2,
            },
            PuckInit {
                name: "b".to_owned(),
                position: DVec2::new(3.0, 2.0),
                u: ProperVelocity(DVec3::new(-5.0, 0.0, 0.0)),
                radius: 0.03,
                mass: 0.2,
            },
        ],
    );
    b.advance_to(10.0);
    assert!(b.collisions().len() >= 3);
    for i in 0..2 {
        assert_eq!(b.worldline(i).state_at(10.0).orientation, 0.0);
    }
}
