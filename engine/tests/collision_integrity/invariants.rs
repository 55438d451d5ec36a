//! The invariants every run of `collision_integrity` is checked against:
//! no overlap beyond the bound, no re-collision, 4-momentum, finite
//! values, no shape reaching into a cushion (each with its tolerance, as
//! the test file's header states).

use super::R;
use super::common::assert_conserved;
use lightcone_engine::physics::predict::puck_puck;
use lightcone_engine::physics::{Billiard, Collision, CollisionKind, overlap};
use lightcone_engine::worldline::{Segment, Worldline};

/// The pairs in contact in a record: the two pucks of a two-puck contact,
/// each striker with the puck it meets in contacts resolved together
/// (`Collision::simultaneous`: that puck first). A Zeno cluster's merge has
/// none (it counts for each puck as a kick from something else).
pub fn pairs_of(c: &Collision) -> Vec<(usize, usize)> {
    if c.kind != CollisionKind::PuckPuck {
        return Vec::new();
    }
    let pair = |a: usize, b: usize| (a.min(b), a.max(b));
    if c.simultaneous {
        c.pairs
            .iter()
            .map(|&[x, y]| pair(c.pucks[x].puck, c.pucks[y].puck))
            .collect()
    } else if c.pucks.len() == 2 {
        vec![pair(c.pucks[0].puck, c.pucks[1].puck)]
    } else {
        Vec::new()
    }
}

/// Whether pucks `i` < `j` are a pair in contact in a record
/// ([`pairs_of`], without building the list: the checks ask it of every
/// pair and record).
pub fn in_contact(c: &Collision, i: usize, j: usize) -> bool {
    if c.kind != CollisionKind::PuckPuck {
        return false;
    }
    let is = |p: usize| p == i || p == j;
    if c.simultaneous {
        c.pairs.iter().any(|&[x, y]| {
            let (p, q) = (c.pucks[x].puck, c.pucks[y].puck);
            p != q && is(p) && is(q)
        })
    } else {
        c.pucks.len() == 2 && is(c.pucks[0].puck) && is(c.pucks[1].puck)
    }
}

/// The board times of the kicks of pucks `i` and `j` in a record
/// (theirs only, in a record of several pucks).
pub fn kick_times(c: &Collision, i: usize, j: usize) -> impl Iterator<Item = f64> + Clone + '_ {
    c.pucks
        .iter()
        .filter(move |p| p.puck == i || p.puck == j)
        .map(|p| p.t)
}

/// Checks every invariant on a run kept whole (history on), at the given
/// board times and at every kick. Returns the largest overlap seen, m.
pub fn check_invariants(b: &Billiard, until: f64, samples: usize) -> f64 {
    let n = b.len();
    let mut times: Vec<f64> = (0..=samples)
        .map(|k| until * k as f64 / samples as f64)
        .collect();
    for c in b.collisions() {
        for p in &c.pucks {
            if p.t <= until {
                times.push(p.t);
                times.push((p.t + 1e-9).min(until));
            }
        }
        if c.kind == CollisionKind::PuckPuck {
            assert_conserved(c, 1e-12);
        }
        for p in &c.pucks {
            assert!(p.u_after.is_finite() && p.position.is_finite(), "{c:?}");
        }
    }
    // No re-collision: between two contacts of one pair, one of the two
    // must have met something else, or the two must have parted on the
    // board (no overlap at some instant between, 400 samples). A pair of
    // contacts resolved together counts as having met something else.
    let mut last: Vec<Option<usize>> = vec![None; n]; // index of last collision
    for (k, c) in b.collisions().iter().enumerate() {
        for (i, j) in pairs_of(c) {
            let (Some(li), Some(lj)) = (last[i], last[j]) else {
                continue;
            };
            // Contacts resolved together need not separate every pair
            // (`Collision::simultaneous`: the other strikers change the
            // puck they meet too), so such a pair may meet again at once.
            if li != lj || !in_contact(&b.collisions()[li], i, j) || b.collisions()[li].simultaneous
            {
                continue;
            }
            let before = &b.collisions()[li];
            let from = kick_times(before, i, j).fold(f64::MIN, f64::max);
            let to = kick_times(c, i, j).fold(f64::MAX, f64::min);
            let parted = (1..400).any(|s| {
                let t = from + (to - from) * s as f64 / 400.0;
                let (si, sj) = (b.worldline(i).segment_at(t), b.worldline(j).segment_at(t));
                overlap::depth(si, R, sj, R, t) == 0.0
            });
            assert!(
                parted,
                "pair {i}-{j} collided again at t = {} with nothing between and no parting: \
                 {before:?} then {c:?}",
                c.t
            );
        }
        for p in &c.pucks {
            last[p.puck] = Some(k);
        }
    }
    let mut worst = 0.0f64;
    for i in 0..n {
        for j in i + 1..n {
            worst = worst.max(check_pair(b, i, j, &times));
        }
        check_cushions(b, i, &times);
    }
    worst
}

/// No puck reaches into a cushion (issue 30, item 4): at every sample, and
/// at and just after every kick (at every segment's start, with the new
/// velocity), the contracted puck's half-width along each table axis,
/// `R √(1 − βₖ²)` from the board velocity `β = v/c` (not the engine's own
/// half-width), leaves it on the table, to 1e-12 m.
pub fn check_cushions(b: &Billiard, i: usize, samples: &[f64]) {
    let w = b.worldline(i);
    let table = b.table();
    let mut times: Vec<f64> = samples.to_vec();
    times.extend(w.segments().iter().map(|s| s.start.t).filter(|&t| t >= 0.0));
    for t in times {
        let s = w.segment_at(t);
        let (x, beta) = (s.position_at(t), s.velocity_at(t) / b.c());
        for axis in 0..2 {
            let h = R * (1.0 - beta[axis] * beta[axis]).sqrt();
            let depth = (h - x[axis]).max(x[axis] + h - table[axis]);
            assert!(
                depth <= 1e-12,
                "puck {} reaches {depth} m into a cushion (axis {axis}) at t = {t}: {s:?}",
                b.name(i)
            );
        }
    }
}

/// The overlap bound of the next recorded contact of `i` and `j` whose first
/// kick is after `t` and within 0.1 s of it; 0 if none.
pub fn next_contact_bound(b: &Billiard, i: usize, j: usize, t: f64) -> f64 {
    b.collisions()
        .iter()
        .filter(|c| in_contact(c, i, j))
        .map(|c| {
            let first = kick_times(c, i, j).fold(f64::INFINITY, f64::min);
            (first, c.overlap_bound)
        })
        .filter(|&(first, _)| first > t && first < t + 0.1)
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .map_or(0.0, |(_, bound)| bound)
}

/// The segment of `w` in force just before board time `t`.
pub fn before(w: &Worldline, t: f64) -> &Segment {
    let k = w.segment_index_at(t);
    if k > 0 && w.segments()[k].start.t == t {
        &w.segments()[k - 1]
    } else {
        &w.segments()[k]
    }
}

/// The overlap invariant for one pair, at every sample and every kick of
/// either puck. What may overlap, and nothing more:
/// * at a contact of the pair: its `overlap_bound` (`physics::overlap`);
/// * at a kick of either from anything else (a cushion, a third puck): the
///   depth just before plus the kicked puck's sudden growth back towards
///   its rest disc, at most R(1 − 1/γ) (γ its board factor before);
/// * at any kick, plus the distance the kick moved the centre back from a
///   cushion its new shape would have reached into (at most R(1 − 1/γ),
///   checked: `Billiard::hold_off_cushions`);
/// * between kicks: no growth, except towards the pair's next predicted
///   contact: at most the unperturbed shapes' depth at its first kick (the
///   board slice cuts the pair frame's contact early).
///
/// Tolerance 1e-9 m. Returns the largest overlap seen.
pub fn check_pair(b: &Billiard, i: usize, j: usize, samples: &[f64]) -> f64 {
    let (wi, wj) = (b.worldline(i), b.worldline(j));
    // The kicks of i and j: (time, jump allowance or pair bound, is pair).
    let mut kicks: Vec<(f64, f64, bool)> = Vec::new();
    for c in b.collisions() {
        let own = in_contact(c, i, j);
        for p in &c.pucks {
            if p.puck == i || p.puck == j {
                // A kick whose new contraction would have reached into a
                // cushion moves the centre back from it (the body
                // re-contracts about the rim point the cushion holds): by
                // at most R(1 − 1/γ), towards whatever lies inward.
                // (the new half-width along an axis exceeds the old one,
                // which reached no cushion, by at most R(1 − 1/γ), γ the
                // factor of the segment before this instant: several
                // changes at one instant are one jump).
                let w = b.worldline(p.puck);
                let (held, gamma) = if p.t.is_finite() && !p.pending {
                    let s = before(w, p.t);
                    ((p.position - s.position_at(p.t)).length(), s.gamma())
                } else {
                    (0.0, 1.0)
                };
                assert!(
                    held <= R * (1.0 - 1.0 / gamma) + 1e-12,
                    "held {held} at t = {}: {p:?}",
                    p.t
                );
                let jump = held
                    + if own {
                        c.overlap_bound
                    } else {
                        R * (1.0 - 1.0 / p.u_before.gamma())
                    };
                kicks.push((p.t, jump, own));
            }
        }
    }
    let mut times: Vec<(f64, Option<(f64, bool)>)> = samples.iter().map(|&t| (t, None)).collect();
    times.extend(kicks.iter().map(|&(t, jump, own)| (t, Some((jump, own)))));
    times.sort_by(|x, y| x.0.total_cmp(&y.0).then(y.1.is_some().cmp(&x.1.is_some())));
    let until = samples.iter().copied().fold(0.0, f64::max);
    // The pair's own contacts: from first to last kick, the pair is in
    // contact and its allowance stands even where the depth is 0.
    let windows: Vec<(f64, f64)> = b
        .collisions()
        .iter()
        .filter(|c| in_contact(c, i, j))
        .map(|c| {
            let ts = kick_times(c, i, j);
            (
                ts.clone().fold(f64::INFINITY, f64::min),
                ts.fold(f64::NEG_INFINITY, f64::max),
            )
        })
        .collect();
    let in_contact = |t: f64| windows.iter().any(|&(a, z)| a <= t && t <= z);
    let mut allow = 0.0f64;
    let mut worst = 0.0f64;
    for (t, kick) in times {
        if t > until {
            break;
        }
        if let Some((jump, own)) = kick {
            let d_before = overlap::depth(before(wi, t), R, before(wj, t), R, t);
            allow = if own {
                allow.max(d_before).max(jump)
            } else {
                allow.max(d_before) + jump
            };
            // Checked at the samples at and just after each kick, once every
            // kick at this instant has been counted.
            continue;
        }
        let (si, sj) = (wi.segment_at(t), wj.segment_at(t));
        let d = overlap::depth(si, R, sj, R, t);
        if d == 0.0 {
            if kick.is_none() && !in_contact(t) {
                allow = 0.0;
            }
            continue;
        }
        // Towards the next contact: the early slice. Its recorded bound if
        // it happened (its first kick within 0.1 s, light crossing 3 radii);
        // else (a third body changed one of them first, so it never did)
        // the unperturbed depth at the first kick the pair frame predicts,
        // if that is still ahead (a pair overlapping and closing now must
        // meet now, and gets no allowance from its own prediction).
        let mover = |s| puck_puck::Mover {
            segment: s,
            radius: R,
        };
        let recorded = next_contact_bound(b, i, j, t);
        let predicted = puck_puck::predict(mover(si), mover(sj), 1.0, t).map_or(0.0, |hit| {
            let first = hit.kicks[0].t.min(hit.kicks[1].t);
            if first > t {
                overlap::depth(si, R, sj, R, first)
            } else {
                0.0
            }
        });
        let early = recorded.max(predicted);
        assert!(
            d <= allow.max(early) + 1e-9,
            "pucks {} and {} overlap by {d} m at t = {t}, allowed {allow} (early {early})",
            b.name(i),
            b.name(j)
        );
        worst = worst.max(d);
    }
    worst
}

pub fn pair_contacts(b: &Billiard) -> usize {
    b.collisions()
        .iter()
        .filter(|c| c.kind == CollisionKind::PuckPuck)
        .count()
}
