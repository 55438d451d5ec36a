//! Zeno sequences (inelastic collapse): pucks meeting others or a cushion
//! many times in quick succession, and the clusters merged to end them.

use super::*;

impl Billiard {
    /// Whether this contact of `a` and `b` at board time `t` is part of a
    /// Zeno sequence (inelastic collapse: contacts closer and closer in
    /// time); it is then perfectly inelastic. The first time, a warning says
    /// so.
    pub(super) fn in_zeno_sequence(&mut self, a: usize, b: usize, t: f64) -> bool {
        let streak = self.quick_streak(a, t).max(self.quick_streak(b, t));
        if streak < ZENO_COUNT {
            return false;
        }
        // Not reset: every contact of the sequence from here on is
        // inelastic, until a pause longer than the Zeno gap (a sequence
        // against a cushion ends there, see `cushion_contact`).
        self.stats.zeno_merges += 1;
        if !self.zeno_said {
            self.zeno_said = true;
            self.warnings.push(format!(
                "t = {t} s: pucks \"{}\" and \"{}\" met others {ZENO_COUNT} times within {:.3e} s \
                 (inelastic collapse); such a collision is made perfectly inelastic so they move \
                 together (said once; every one is counted)",
                self.pucks[a].name,
                self.pucks[b].name,
                ZENO_GAP * self.table.length() / self.c
            ));
        }
        true
    }

    /// Ends a Zeno sequence of three or more pucks at once (a light puck
    /// crushed between two heavy ones converging: pairwise inelastic
    /// contacts only approach the end, for ever): the cluster of touching
    /// pucks in the sequence (each had a contact within the Zeno gap),
    /// reached from `a` and `b`, moves together ([`resolve::together_all`])
    /// now, at this board time (the limit of the sequence, whatever the
    /// pair frames' kick times), after any kick still ahead of a member has
    /// landed. One collision record holds every puck of the cluster.
    /// Returns `false` (nothing done) if the cluster is just the pair.
    pub(super) fn merge_zeno_cluster(&mut self, a: usize, b: usize, contact: DVec3) -> bool {
        let t = self.time;
        let gap = ZENO_GAP * self.table.length() / self.c;
        let cluster = self.touching_cluster(vec![a, b], t, |p| t - p.quick.0 < gap);
        if cluster.len() < 3 {
            return false;
        }
        // Kicks still ahead of a member (the far end of an earlier contact)
        // land now, so the merge starts from each one's complete state.
        for &i in &cluster {
            self.flush_pending(i);
        }
        let before: Vec<Body> = cluster
            .iter()
            .map(|&i| Body {
                mass: self.pucks[i].mass,
                u: self.pucks[i].worldline.last().u_at(t),
            })
            .collect();
        let after = resolve::together_all(&before);
        self.stats.pair_contacts += 1;
        self.contacts_made += 1;
        let mut outcomes = Vec::with_capacity(cluster.len());
        for (k, &i) in cluster.iter().enumerate() {
            let puck = &mut self.pucks[i];
            if puck.worldline.push(t, after[k].u).is_err() {
                continue;
            }
            puck.mass = after[k].mass;
            self.hold_off_cushions(i);
            let puck = &mut self.pucks[i];
            self.stats.kicks += 1;
            outcomes.push(PuckOutcome {
                puck: puck.external as usize,
                t,
                position: puck.worldline.position_at(t),
                u_before: before[k].u,
                u_after: after[k].u,
                mass_before: before[k].mass,
                mass_after: after[k].mass,
                orientation_after: puck.worldline.last().orientation,
                pending: false,
            });
        }
        if self.record {
            self.collisions.push(Collision {
                kind: CollisionKind::PuckPuck,
                t,
                contact,
                pucks: outcomes,
                overlap_bound: 0.0,
                simultaneous: false,
                pairs: Vec::new(),
            });
        }
        for i in cluster {
            self.bump(i);
        }
        true
    }

    /// Counts a contact of puck `i` at board time `t` (s) towards its Zeno
    /// sequence: returns how many contacts in a row came within the Zeno gap
    /// of the one before.
    pub(super) fn quick_streak(&mut self, i: usize, t: f64) -> u32 {
        let gap = ZENO_GAP * self.table.length() / self.c;
        let quick = &mut self.pucks[i].quick;
        quick.1 = if t - quick.0 < gap { quick.1 + 1 } else { 0 };
        quick.0 = t;
        quick.1
    }
}
