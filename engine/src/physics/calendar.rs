//! The event calendar: one pending event per puck, in board-time order.
//!
//! Each puck holds at most one entry, its earliest event (next contact,
//! cushion, shell exit or pending velocity change); re-predicting a puck
//! replaces its entry in place. An entry about a pair carries the partner's
//! version: if the partner has changed since, the entry is stale and the
//! puck is simply predicted again when it comes up (lazy invalidation; the
//! partner's own new entry covers the pair meanwhile).
//!
//! The queue is an indexed 4-ary min-heap of the pucks keyed by their
//! entries, with each puck's place in it kept, so an entry is replaced or
//! removed in O(log N) with no search and no hashing.

/// An entry's place in the order of simultaneous events: velocity changes
/// first, then cushion contacts, then pair contacts, then shell exits; within
/// a kind by puck index (the canonical, name order), then by partner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Rank(u64);

impl Rank {
    /// A pending velocity change of puck `i`.
    pub fn kick(i: u32) -> Self {
        Self((i as u64) << 31)
    }
    /// Puck `i` meets cushion number `k` (0–3).
    pub fn cushion(i: u32, k: u32) -> Self {
        Self(1 << 62 | (i as u64) << 31 | k as u64)
    }
    /// Pucks `a` < `b` meet.
    pub fn pair(a: u32, b: u32) -> Self {
        Self(2 << 62 | (a as u64) << 31 | b as u64)
    }
    /// Puck `i` leaves its broad-phase shell.
    pub fn shell(i: u32) -> Self {
        Self(3 << 62 | i as u64)
    }
    /// Puck `i`'s braking segment ends (after its shell exit at that time).
    pub fn stop(i: u32) -> Self {
        Self(3 << 62 | 1 << 32 | i as u64)
    }
}

/// A key: board time (s), then rank.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key {
    /// Board time, s.
    pub t: f64,
    /// Tie-break.
    pub rank: Rank,
}

impl Key {
    /// Never (no entry).
    pub const NEVER: Key = Key {
        t: f64::INFINITY,
        rank: Rank(u64::MAX),
    };

    /// Whether `self` comes strictly before `other`.
    #[inline]
    pub fn before(&self, other: &Key) -> bool {
        self.t < other.t || (self.t == other.t && self.rank < other.rank)
    }
}

const ABSENT: u32 = u32::MAX;
const ARITY: usize = 4;

/// The queue of the pucks' entries.
#[derive(Clone, Default, Debug)]
pub struct Calendar {
    /// Heap order: (key, puck).
    heap: Vec<(Key, u32)>,
    /// Each puck's index in `heap`, or `ABSENT`.
    place: Vec<u32>,
}

impl Calendar {
    /// A calendar for `n` pucks, all without entries.
    pub fn new(n: usize) -> Self {
        Self {
            heap: Vec::with_capacity(n),
            place: vec![ABSENT; n],
        }
    }

    /// Sets puck `i`'s entry to `key` (a key at infinite time removes it).
    pub fn set(&mut self, i: u32, key: Key) {
        let at = self.place[i as usize];
        if key.t == f64::INFINITY {
            if at != ABSENT {
                self.remove_at(at as usize);
            }
            return;
        }
        if at == ABSENT {
            self.heap.push((key, i));
            let k = self.heap.len() - 1;
            self.place[i as usize] = k as u32;
            self.up(k);
        } else {
            let k = at as usize;
            let old = self.heap[k].0;
            self.heap[k].0 = key;
            if key.before(&old) {
                self.up(k);
            } else {
                self.down(k);
            }
        }
    }

    /// Removes puck `i`'s entry, if any.
    pub fn remove(&mut self, i: u32) {
        let at = self.place[i as usize];
        if at != ABSENT {
            self.remove_at(at as usize);
        }
    }

    /// Puck `i`'s entry's key, if it has one.
    pub fn key(&self, i: u32) -> Option<Key> {
        let at = self.place[i as usize];
        (at != ABSENT).then(|| self.heap[at as usize].0)
    }

    /// The earliest entry: its key and puck.
    #[inline]
    pub fn peek(&self) -> Option<(Key, u32)> {
        self.heap.first().copied()
    }

    fn remove_at(&mut self, k: usize) {
        let (_, i) = self.heap[k];
        self.place[i as usize] = ABSENT;
        let last = self.heap.len() - 1;
        if k != last {
            self.heap.swap(k, last);
            self.heap.pop();
            self.place[self.heap[k].1 as usize] = k as u32;
            let key = self.heap[k].0;
            if k > 0 && key.before(&self.heap[(k - 1) / ARITY].0) {
                self.up(k);
            } else {
                self.down(k);
            }
        } else {
            self.heap.pop();
        }
    }

    fn up(&mut self, mut k: usize) {
        let item = self.heap[k];
        while k > 0 {
            let parent = (k - 1) / ARITY;
            if !item.0.before(&self.heap[parent].0) {
                break;
            }
            self.heap[k] = self.heap[parent];
            self.place[self.heap[k].1 as usize] = k as u32;
            k = parent;
        }
        self.heap[k] = item;
        self.place[item.1 as usize] = k as u32;
    }

    fn down(&mut self, mut k: usize) {
        let item = self.heap[k];
        let n = self.heap.len();
        loop {
            let first = ARITY * k + 1;
            if first >= n {
                break;
            }
            let mut best = first;
            for c in first + 1..(first + ARITY).min(n) {
                if self.heap[c].0.before(&self.heap[best].0) {
                    best = c;
                }
            }
            if !self.heap[best].0.before(&item.0) {
                break;
            }
            self.heap[k] = self.heap[best];
            self.place[self.heap[k].1 as usize] = k as u32;
            k = best;
        }
        self.heap[k] = item;
        self.place[item.1 as usize] = k as u32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn earliest_first_and_ties_are_deterministic() {
        let mut c = Calendar::new(8);
        let k = |t, rank| Key { t, rank };
        c.set(0, k(2.0, Rank::pair(0, 1)));
        c.set(3, k(1.0, Rank::pair(3, 4)));
        c.set(7, k(1.0, Rank::cushion(7, 3)));
        c.set(6, k(1.0, Rank::kick(6)));
        c.set(2, k(1.0, Rank::pair(2, 5)));
        c.set(5, k(0.5, Rank::shell(5)));
        // Replacing and removing in place.
        c.set(5, k(3.0, Rank::shell(5)));
        c.set(1, k(0.1, Rank::shell(1)));
        c.remove(1);
        let mut order = Vec::new();
        while let Some((_, i)) = c.peek() {
            order.push(i);
            c.remove(i);
        }
        assert_eq!(order, vec![6, 7, 2, 3, 0, 5]);
    }

    #[test]
    fn agrees_with_sorting_under_random_updates() {
        let mut c = Calendar::new(64);
        let mut keys = vec![f64::INFINITY; 64];
        let mut state = 12345u64;
        for step in 0..5000u64 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let i = (state % 64) as u32;
            let t = if state.is_multiple_of(7) {
                f64::INFINITY
            } else {
                (state >> 20) as f64 % 1000.0
            };
            keys[i as usize] = t;
            c.set(
                i,
                Key {
                    t,
                    rank: Rank::shell(i),
                },
            );
            if step.is_multiple_of(50) {
                let best = (0..64u32)
                    .filter(|&j| keys[j as usize].is_finite())
                    .min_by(|&a, &b| {
                        keys[a as usize]
                            .total_cmp(&keys[b as usize])
                            .then(a.cmp(&b))
                    });
                assert_eq!(c.peek().map(|(_, i)| i), best);
            }
        }
    }
}
