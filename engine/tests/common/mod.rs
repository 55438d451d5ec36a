//! Checks shared by the engine's integration tests.

use lightcone_engine::physics::Collision;
use lightcone_engine::spacetime::FourMomentum;

/// Asserts that a contact conserves 4-momentum: the sum over its pucks of
/// `m u` (and energy) before equals the sum after, to `rel` of the energy.
pub fn assert_conserved(c: &Collision, rel: f64) {
    let sum = |after: bool| {
        c.pucks.iter().fold(FourMomentum::default(), |s, p| {
            s + if after {
                FourMomentum::of_body(p.mass_after, p.u_after)
            } else {
                FourMomentum::of_body(p.mass_before, p.u_before)
            }
        })
    };
    let (p0, p1) = (sum(false), sum(true));
    let scale = p0.energy;
    assert!(
        (p0.energy - p1.energy).abs() <= rel * scale,
        "energy {p0:?} → {p1:?} in {c:?}"
    );
    assert!(
        (p0.momentum - p1.momentum).length() <= rel * scale,
        "momentum {p0:?} → {p1:?} in {c:?}"
    );
}
