//! A billiard driven from outside (a CAVE render node's copy): fed the new
//! segments of another billiard's worldlines frame by frame, it holds the
//! same worldlines bit for bit, predicts nothing of its own, and refuses a
//! segment that does not fit.

use lightcone_engine::physics::Billiard;
use lightcone_engine::physics::gas::dense_box;
use lightcone_engine::worldline::{Segment, WorldlineError};
use proptest::prelude::*;

/// Copies into `copy` what `master`'s worldlines gained since `sent` (the
/// number of segments each had, by start time of its last one).
fn copy_new(master: &Billiard, copy: &mut Billiard, sent: &mut [Option<Segment>]) {
    for (i, last) in sent.iter_mut().enumerate() {
        let w = master.worldline(i);
        let segments = w.segments();
        let from = last.map_or(0, |s| w.segment_index_at(s.start.t) + 1);
        match last {
            Some(s) if segments[from - 1] == *s => {
                copy.extend_worldline(i, &segments[from..]).unwrap();
            }
            _ => copy.replace_worldline(i, w.clone()),
        }
        *last = segments.last().copied();
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn a_driven_copy_holds_the_same_worldlines(seed in 0u64..1000, frames in 20usize..120, dt in 0.005f64..0.05) {
        let r = 0.0305;
        let mut master = dense_box(12, r, 3.0 * r, 0.8, 1.42, seed);
        master.set_history(Some(2.0));
        let mut copy = dense_box(12, r, 3.0 * r, 0.8, 1.42, seed + 1);
        copy.set_history(Some(2.0));
        copy.drive_from_outside();
        prop_assert!(copy.is_driven());
        let predicted = copy.stats().predictions;
        let mut sent = vec![None; master.len()];
        for k in 1..=frames {
            let t = k as f64 * dt;
            master.advance_to(t);
            if k % 7 == 0 {
                // A cue stroke, as the game's `strike`.
                master.apply_impulse(k % 12, t, glam::DVec3::new(0.3, -0.2, 0.0)).unwrap();
            }
            copy_new(&master, &mut copy, &mut sent);
            copy.advance_to(t);
            for i in 0..master.len() {
                let (a, b) = (master.worldline(i), copy.worldline(i));
                // Bit for bit where both keep history: the copy's last
                // segments are the master's.
                let n = a.segments().len().min(b.segments().len());
                prop_assert_eq!(&a.segments()[a.segments().len() - n..], &b.segments()[b.segments().len() - n..]);
                for probe in [t, t - 0.5 * dt, t - 1.0] {
                    prop_assert_eq!(a.state_at(probe), b.state_at(probe));
                }
            }
            prop_assert_eq!(copy.time(), t);
        }
        // It predicted and processed nothing of its own.
        prop_assert_eq!(copy.stats().predictions, predicted);
        prop_assert!(copy.collisions().is_empty());
    }
}

#[test]
fn a_segment_that_does_not_fit_is_refused() {
    let r = 0.0305;
    let mut master = dense_box(4, r, 3.0 * r, 0.8, 1.42, 5);
    master.advance_to(1.0);
    let mut copy = dense_box(4, r, 3.0 * r, 0.8, 1.42, 5);
    copy.drive_from_outside();
    copy.replace_worldline(0, master.worldline(0).clone());
    let first = master.worldline(0).segments()[0];
    // Not after the last segment.
    assert!(matches!(
        copy.extend_worldline(0, &[first]),
        Err(WorldlineError::BeforeLastSegment { .. })
    ));
    // Not finite.
    let mut bad = *master.worldline(0).last();
    bad.start.t = f64::NAN;
    assert_eq!(
        copy.extend_worldline(0, &[bad]),
        Err(WorldlineError::NotFinite)
    );
    // What was there is kept.
    assert_eq!(copy.worldline(0), master.worldline(0));
}
