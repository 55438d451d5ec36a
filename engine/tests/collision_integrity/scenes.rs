//! The scenes `collision_integrity` runs: pucks by position and proper
//! velocity, a box of random pucks, random proptest scenes, and a scene
//! file with its pucks listed in another order.

use super::R;
use glam::{DVec2, DVec3};
use lightcone_engine::physics::{Billiard, PuckInit};
use lightcone_engine::spacetime::ProperVelocity;

/// A puck of radius `R`, mass 0.2 kg, at (x, y) m with proper velocity `u`.
pub fn puck(name: &str, x: f64, y: f64, u: ProperVelocity) -> PuckInit {
    PuckInit {
        name: name.to_owned(),
        position: DVec2::new(x, y),
        u,
        radius: R,
        mass: 0.2,
    }
}

/// A proper velocity γβ in the board plane.
pub fn u(x: f64, y: f64) -> ProperVelocity {
    ProperVelocity(DVec3::new(x, y, 0.0))
}

/// The proper velocity of board velocity β = (bx, by).
pub fn beta(bx: f64, by: f64) -> ProperVelocity {
    ProperVelocity::try_from_beta(DVec3::new(bx, by, 0.0)).unwrap()
}

/// A box of `n` pucks on a grid with random velocities (a deterministic
/// generator, so failures repeat).
pub fn random_box(n: usize, max_u: f64, restitution: f64, seed: u64) -> Billiard {
    let mut rng = lightcone_engine::physics::gas::Rng::new(seed);
    let mut next = move || rng.next_f64();
    let side = (n as f64).sqrt().ceil() as usize;
    let spacing = 3.0 * R;
    let table = DVec2::splat(side as f64 * spacing + R);
    let pucks = (0..n)
        .map(|k| {
            let (gx, gy) = ((k % side) as f64, (k / side) as f64);
            let angle = std::f64::consts::TAU * next();
            let speed = max_u * next();
            puck(
                &format!("p{k:04}"),
                R + spacing * (gx + 0.5),
                R + spacing * (gy + 0.5),
                u(speed * angle.cos(), speed * angle.sin()),
            )
        })
        .collect();
    Billiard::new(1.0, table, restitution, 1.0, pucks)
}

/// A scene file with its `[[puck]]` tables in another order: the same
/// text otherwise (each table's lines travel with it).
pub fn permute_pucks(text: &str, order: &[usize]) -> String {
    // Sections: the lines before the first table, then one per table header.
    let mut sections: Vec<Vec<&str>> = vec![Vec::new()];
    for line in text.lines() {
        if line.trim_start().starts_with('[') {
            sections.push(Vec::new());
        }
        sections
            .last_mut()
            .expect("one section at least")
            .push(line);
    }
    let slots: Vec<usize> = (0..sections.len())
        .filter(|&k| sections[k].first().is_some_and(|l| l.trim() == "[[puck]]"))
        .collect();
    let pucks: Vec<Vec<&str>> = slots.iter().map(|&k| sections[k].clone()).collect();
    for (n, &k) in slots.iter().enumerate() {
        sections[k] = pucks[order[n]].clone();
    }
    sections.concat().join("\n")
}

/// A random puck: x, y (m), log₁₀ of its proper speed, direction (rad).
pub type RandomPuck = (f64, f64, f64, f64);

/// A frictionless 2 m × 1 m table with the pucks `raw` (c = 1 m/s).
pub fn random_scene(restitution: f64, raw: &[RandomPuck]) -> Billiard {
    let pucks = raw
        .iter()
        .enumerate()
        .map(|(k, &(x, y, log_u, angle))| {
            let speed = 10f64.powf(log_u);
            puck(
                &format!("p{k}"),
                x,
                y,
                u(speed * angle.cos(), speed * angle.sin()),
            )
        })
        .collect();
    Billiard::new(1.0, DVec2::new(2.0, 1.0), restitution, 1.0, pucks)
}
