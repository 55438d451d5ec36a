//! Reading the state: the table, the pucks by the caller's index, their
//! worldlines, the collision records and the counters.

use super::*;

impl Billiard {
    /// Speed of light, m/s.
    #[must_use]
    pub fn c(&self) -> f64 {
        self.c
    }

    /// Table size, m.
    #[must_use]
    pub fn table(&self) -> DVec2 {
        self.table
    }

    /// Board time up to which every event has been processed, s.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Number of pucks.
    #[must_use]
    pub fn len(&self) -> usize {
        self.pucks.len()
    }

    /// Whether there are no pucks.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.pucks.is_empty()
    }

    pub(super) fn puck(&self, i: usize) -> &Puck {
        &self.pucks[self.internal[i] as usize]
    }

    /// Puck `i`'s name.
    #[must_use]
    pub fn name(&self, i: usize) -> &str {
        &self.puck(i).name
    }

    /// Index of the puck called `name`.
    #[must_use]
    pub fn index_of(&self, name: &str) -> Option<usize> {
        let k = self.pucks.partition_point(|p| p.name.as_str() < name);
        self.pucks
            .get(k)
            .filter(|p| p.name == name)
            .map(|p| p.external as usize)
    }

    /// Puck `i`'s rest radius, m.
    #[must_use]
    pub fn radius(&self, i: usize) -> f64 {
        self.puck(i).radius
    }

    /// Puck `i`'s current rest mass, kg (grows in inelastic collisions).
    #[must_use]
    pub fn mass(&self, i: usize) -> f64 {
        self.puck(i).mass
    }

    /// Puck `i`'s worldline (its centre), complete up to [`Self::time`]
    /// (and back to [`Self::forgotten_before`], if history is bounded).
    #[must_use]
    pub fn worldline(&self, i: usize) -> &Worldline {
        &self.puck(i).worldline
    }

    /// The kept collision records, in the order processed (that of each
    /// collision's first velocity change, which for a puck–puck contact can
    /// come slightly before the contact itself). A puck–puck collision's second velocity change stays
    /// `pending` until its board time. With a history horizon the oldest
    /// records are dropped: the first one kept has global index
    /// [`Self::collisions_forgotten`].
    #[must_use]
    pub fn collisions(&self) -> &[Collision] {
        &self.collisions
    }

    /// How many collision records have been dropped (the global index of
    /// `collisions()[0]`).
    #[must_use]
    pub fn collisions_forgotten(&self) -> u64 {
        self.collisions_dropped
    }

    /// How many collisions have been recorded in all (kept or dropped).
    #[must_use]
    pub fn collision_count(&self) -> u64 {
        self.collisions_dropped + self.collisions.len() as u64
    }

    /// The kept records from global index `from` on (those before it and
    /// any dropped ones are skipped).
    #[must_use]
    pub fn collisions_from(&self, from: u64) -> &[Collision] {
        let k = from.saturating_sub(self.collisions_dropped) as usize;
        &self.collisions[k.min(self.collisions.len())..]
    }

    /// Board time before which history has been forgotten (worldline
    /// segments and collision records), if any has.
    #[must_use]
    pub fn forgotten_before(&self) -> Option<f64> {
        self.forgotten_before
    }

    /// Messages about degraded behaviour (a Zeno sequence ended, …): each
    /// kind is said once; [`Self::stats`] counts every occurrence.
    #[must_use]
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Total 4-momentum of the pucks at [`Self::time`], including what is
    /// in transit: the part of a puck–puck collision's transfer whose
    /// second kick is still ahead. Exactly conserved by puck–puck
    /// collisions; cushions change it (they are external).
    #[must_use]
    pub fn total_momentum(&self) -> crate::spacetime::FourMomentum {
        let bodies = self.pucks.iter().fold(Default::default(), |sum, p| {
            sum + crate::spacetime::FourMomentum::of_body(
                p.mass,
                p.worldline.last().u_at(self.time),
            )
        });
        self.kicks.iter().flatten().fold(bodies, |sum, k| {
            sum + (k.after.momentum() - k.before.momentum())
        })
    }

    /// Counters.
    #[must_use]
    pub fn stats(&self) -> Stats {
        self.stats
    }
}
