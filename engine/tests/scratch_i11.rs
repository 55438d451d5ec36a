//! Scratch diagnostics (not committed).
use glam::{DVec2, DVec3};
use lightcone_engine::physics::{Billiard, PuckInit, overlap};
use lightcone_engine::spacetime::ProperVelocity;

const R: f64 = 0.03;

fn scene(restitution: f64, raw: &[(f64, f64, f64, f64)]) -> Billiard {
    let pucks = raw
        .iter()
        .enumerate()
        .map(|(k, &(x, y, log_u, angle))| {
            let speed = 10f64.powf(log_u);
            PuckInit {
                name: format!("p{k}"),
                position: DVec2::new(x, y),
                u: ProperVelocity(DVec3::new(speed * angle.cos(), speed * angle.sin(), 0.0)),
                radius: R,
                mass: 0.2,
            }
        })
        .collect();
    Billiard::new(1.0, DVec2::new(2.0, 1.0), restitution, 1.0, pucks)
}

#[test]
fn dump() {
    let raw = [
        (0.17217586743589933, 0.9331471554419596, 0.5926550063091633, 5.762626948216999),
        (0.15446066146866852, 0.8729566053179851, 3.6782072282796165, 6.168007227709471),
    ];
    let mut b = scene(0.0, &raw);
    b.advance_to(2.0);
    for c in b.collisions() {
        eprintln!("{c:#?}");
    }
    eprintln!("{:?}", b.stats());
    for i in 0..2 {
        for s in b.worldline(i).segments() {
            eprintln!("puck {i}: {s:?}");
        }
    }
    let mut t = 0.0;
    let mut last = -1.0;
    while t < 2.0 {
        let d = overlap::depth(b.worldline(0).segment_at(t), R, b.worldline(1).segment_at(t), R, t);
        if (d - last).abs() > 1e-5 {
            eprintln!("t = {t:.6}: depth {d:.6e}");
            last = d;
        }
        t += 1e-4;
    }
}
