//! The event calendar: one pending event per puck, in board-time order.
//!
//! Each puck holds at most one entry, its earliest event (next contact,
//! cushion, shell exit or pending velocity change); re-predicting a puck
//! replaces its entry in place. An entry about a pair carries the partner's
//! version: if the partner has changed since, the entry is stale and the
//! puck is simply predicted again when it comes up (lazy invalidation; the
//! partner's own new entry covers the pair meanwhile).
//!
//! The queue is Paul's calendar queue of the pucks' entries ([`Calendar`]):
//! each puck's place in it is kept, so an entry is replaced or removed in
//! O(1) with no search and no hashing.

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
/// `place` of an entry in the heap: this bit and its index there.
const IN_HEAP: u32 = 1 << 31;
/// End of a bucket list.
const NIL: u32 = u32::MAX;
const ARITY: usize = 4;
/// Events per bucket the width is tuned for (in the 10⁴-puck gas, 1 to 4
/// cost the same within 0.2 % of the instructions, 8 and 16 0.7 and 1.3 %
/// more).
const PER_BUCKET: f64 = 4.0;

/// Whether entry `(a, i)` comes before `(b, j)`: by key, then by puck (two
/// pucks predicting the same pair contact have equal keys), so the order of
/// events is fully given by the entries, whatever the queue's layout.
#[inline]
fn first(a: &Key, i: u32, b: &Key, j: u32) -> bool {
    a.before(b) || (a.t == b.t && a.rank == b.rank && i < j)
}

/// A puck's entry in the [`Calendar`] (32 bytes).
#[derive(Clone, Copy, Debug)]
struct Slot {
    /// The key (meaningless when absent).
    key: Key,
    /// Where the entry is: `ABSENT`, `IN_HEAP | index in heap`, or the
    /// number of its list (a ring slot, or `ring` for the overflow).
    place: u32,
    /// The list's links (`NIL` ends a list).
    prev: u32,
    next: u32,
}

/// The queue of the pucks' entries: Paul's calendar queue (G. Paul, J.
/// Comput. Phys. 221, 615 (2007), as Smallenburg uses it, Eur. Phys. J. E
/// 45, 22 (2022)). Board time is cut into buckets of a tuned width; the
/// current bucket's entries (and any earlier) are in a small indexed
/// min-heap, the entries of the next buckets in a ring of doubly linked
/// lists (O(1) to add or remove), and later ones in an overflow list that
/// is distributed into the ring when the ring runs empty. The width is
/// tuned from the event rate (about [`PER_BUCKET`] events a bucket), so
/// the heap holds a handful of entries whatever N, and an update costs
/// O(1) instead of the O(log N) of one heap of every puck.
#[derive(Clone, Debug)]
pub struct Calendar {
    /// Each puck's entry: its key, where it is, its list links (one
    /// record, so that an update touches one cache line of the puck's).
    slots: Vec<Slot>,
    /// Each list's first puck: the ring's slots, then the overflow.
    heads: Vec<u32>,
    /// Entries at or before the current bucket: a 4-ary min-heap.
    heap: Vec<(Key, u32)>,
    /// Bucket width, s (infinite until tuned: every entry in the heap), and
    /// its inverse.
    width: f64,
    inverse: f64,
    /// Number of the current bucket ([`Self::bucket`] of its times).
    current: i64,
    /// The ring holds the buckets after the current one and before this.
    end: i64,
    /// Entries in the ring, in the overflow.
    in_ring: usize,
    in_overflow: usize,
    /// Tuning: entries taken from the top since the last tuning, the board
    /// time of the first and of the last, empty buckets stepped over.
    pops: usize,
    since: f64,
    last: f64,
    empty_steps: usize,
}

impl Default for Calendar {
    fn default() -> Self {
        Self::new(0)
    }
}

impl Calendar {
    /// A calendar for `n` pucks, all without entries.
    pub fn new(n: usize) -> Self {
        // At most 2²⁹ slots, so that the overflow list's number never
        // reads as a heap place (`IN_HEAP`).
        let ring = (2 * n).next_power_of_two().clamp(16, 1 << 29);
        Self {
            slots: vec![
                Slot {
                    key: Key::NEVER,
                    place: ABSENT,
                    prev: NIL,
                    next: NIL,
                };
                n
            ],
            heads: vec![NIL; ring + 1],
            heap: Vec::new(),
            width: f64::INFINITY,
            inverse: 0.0,
            current: 0,
            end: ring as i64,
            in_ring: 0,
            in_overflow: 0,
            pops: 0,
            since: f64::NAN,
            last: f64::NAN,
            empty_steps: 0,
        }
    }

    /// Number of ring slots (the overflow list is the one after them).
    #[inline]
    fn ring(&self) -> usize {
        self.heads.len() - 1
    }

    /// The bucket board time `t` falls in: `t / width` rounded towards zero
    /// (monotone in `t`, which is all the queue needs; no call to `floor`),
    /// saturating; NaN falls in bucket 0.
    #[inline]
    fn bucket(&self, t: f64) -> i64 {
        (t * self.inverse) as i64
    }

    /// Sets puck `i`'s entry to `key` (a key at infinite or NaN time removes
    /// it).
    pub fn set(&mut self, i: u32, key: Key) {
        if key.t == f64::INFINITY || key.t.is_nan() {
            self.remove(i); // a NaN time has no place in the order
            return;
        }
        let b = self.bucket(key.t);
        let at = self.slots[i as usize].place;
        if at != ABSENT && at & IN_HEAP != 0 && b <= self.current {
            // Stays in the heap: moved in place.
            let k = (at & !IN_HEAP) as usize;
            let old = self.heap[k].0;
            self.heap[k].0 = key;
            self.slots[i as usize].key = key;
            if first(&key, i, &old, i) {
                self.up(k);
            } else {
                self.down(k);
            }
            return;
        }
        self.remove(i);
        // Worked out again: removing the top entry can retune the width.
        let b = self.bucket(key.t);
        self.slots[i as usize].key = key;
        self.insert(i, b);
    }

    /// Removes puck `i`'s entry, if any.
    pub fn remove(&mut self, i: u32) {
        let at = self.slots[i as usize].place;
        if at == ABSENT {
            return;
        }
        if at & IN_HEAP != 0 {
            let k = (at & !IN_HEAP) as usize;
            let t = self.heap[k].0.t;
            self.remove_at(k);
            // Counted once the entry is out: a retune rebuilds the queue.
            if k == 0 {
                self.popped(t);
            }
        } else {
            self.unlink(i, at as usize);
        }
    }

    /// Puck `i`'s entry's key, if it has one.
    pub fn key(&self, i: u32) -> Option<Key> {
        (self.slots[i as usize].place != ABSENT).then(|| self.slots[i as usize].key)
    }

    /// The earliest entry: its key and puck.
    #[inline]
    pub fn peek(&mut self) -> Option<(Key, u32)> {
        if self.heap.is_empty() && !self.advance() {
            return None;
        }
        self.heap.first().copied()
    }

    /// The puck of the earliest entry if the current bucket holds any (the
    /// queue is not advanced): the event after the one being handled, as a
    /// hint for fetching its records ahead.
    #[inline]
    pub fn upcoming(&self) -> Option<u32> {
        self.heap.first().map(|&(_, i)| i)
    }

    /// Puck `i` (its key in its slot, bucket `b`) into the heap, the ring or
    /// the overflow.
    fn insert(&mut self, i: u32, b: i64) {
        if b <= self.current {
            self.heap.push((self.slots[i as usize].key, i));
            let k = self.heap.len() - 1;
            self.slots[i as usize].place = IN_HEAP | k as u32;
            self.up(k);
        } else if b < self.end {
            let slot = b.rem_euclid(self.ring() as i64) as usize;
            self.link(i, slot);
            self.in_ring += 1;
        } else {
            let overflow = self.ring();
            self.link(i, overflow);
            self.in_overflow += 1;
        }
    }

    fn link(&mut self, i: u32, list: usize) {
        let head = self.heads[list];
        self.slots[i as usize].prev = NIL;
        self.slots[i as usize].next = head;
        if head != NIL {
            self.slots[head as usize].prev = i;
        }
        self.heads[list] = i;
        self.slots[i as usize].place = list as u32;
    }

    fn unlink(&mut self, i: u32, list: usize) {
        let (p, n) = (self.slots[i as usize].prev, self.slots[i as usize].next);
        if p == NIL {
            self.heads[list] = n;
        } else {
            self.slots[p as usize].next = n;
        }
        if n != NIL {
            self.slots[n as usize].prev = p;
        }
        self.slots[i as usize].place = ABSENT;
        if list == self.ring() {
            self.in_overflow -= 1;
        } else {
            self.in_ring -= 1;
        }
    }

    /// The heap ran empty: moves on to the next bucket that has entries
    /// (distributing the overflow when the ring is empty). Returns whether
    /// there is any entry.
    fn advance(&mut self) -> bool {
        loop {
            if self.in_ring == 0 {
                if self.in_overflow == 0 {
                    return false;
                }
                // Jump to the overflow's earliest bucket and take the next
                // ring's worth of buckets from it.
                let mut earliest = i64::MAX;
                let mut i = self.heads[self.ring()];
                while i != NIL {
                    earliest = earliest.min(self.bucket(self.slots[i as usize].key.t));
                    i = self.slots[i as usize].next;
                }
                self.current = earliest.max(self.current);
                self.end = self.current.saturating_add(self.ring() as i64);
                self.distribute_overflow();
            } else {
                self.current += 1;
                let slot = self.current.rem_euclid(self.ring() as i64) as usize;
                if self.heads[slot] == NIL {
                    self.empty_steps += 1;
                    continue;
                }
                let mut i = self.heads[slot];
                self.heads[slot] = NIL;
                while i != NIL {
                    let next = self.slots[i as usize].next;
                    self.in_ring -= 1;
                    self.slots[i as usize].place = ABSENT;
                    self.insert(i, self.current);
                    i = next;
                }
            }
            if !self.heap.is_empty() {
                return true;
            }
        }
    }

    /// Moves the overflow's entries that now fall before `end` into the heap
    /// or the ring.
    fn distribute_overflow(&mut self) {
        let overflow = self.ring();
        let mut i = self.heads[overflow];
        while i != NIL {
            let next = self.slots[i as usize].next;
            let b = self.bucket(self.slots[i as usize].key.t);
            if b < self.end || b <= self.current {
                self.unlink(i, overflow);
                self.insert(i, b);
            }
            i = next;
        }
    }

    /// The top entry (board time `t`) was removed (handled, or moved by
    /// `set` to a later bucket): counts it, and now and then tunes the
    /// bucket width to the event rate (which rebuilds the queue: called
    /// only between operations).
    fn popped(&mut self, t: f64) {
        if self.pops == 0 {
            self.since = t;
        }
        self.pops += 1;
        self.last = t;
        if self.pops + self.empty_steps >= 2 * self.slots.len().max(128) {
            self.tune();
        }
    }

    /// Sets the width from the board time the last pops spanned, and
    /// redistributes every entry if it changed by more than a factor two.
    fn tune(&mut self) {
        let span = self.last - self.since;
        let pops = self.pops;
        self.pops = 0;
        self.empty_steps = 0;
        if pops < 2 || !(span > 0.0 && span.is_finite()) {
            return;
        }
        let width = PER_BUCKET * span / (pops - 1) as f64;
        let ratio = width / self.width;
        if !(width > 0.0 && width.is_finite()) || (0.5..=2.0).contains(&ratio) {
            return;
        }
        let live: Vec<u32> = (0..self.slots.len() as u32)
            .filter(|&i| self.slots[i as usize].place != ABSENT)
            .collect();
        self.heap.clear();
        self.heads.fill(NIL);
        for slot in &mut self.slots {
            slot.place = ABSENT;
        }
        self.in_ring = 0;
        self.in_overflow = 0;
        self.width = width;
        self.inverse = 1.0 / width;
        self.current = self.bucket(self.last);
        self.end = self.current.saturating_add(self.ring() as i64);
        for i in live {
            let b = self.bucket(self.slots[i as usize].key.t);
            self.insert(i, b);
        }
    }

    fn remove_at(&mut self, k: usize) {
        let (_, i) = self.heap[k];
        self.slots[i as usize].place = ABSENT;
        let last = self.heap.len() - 1;
        if k != last {
            self.heap.swap(k, last);
            self.heap.pop();
            let (key, j) = self.heap[k];
            self.slots[j as usize].place = IN_HEAP | k as u32;
            if k > 0 && {
                let (pk, pj) = self.heap[(k - 1) / ARITY];
                first(&key, j, &pk, pj)
            } {
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
            let (pk, pj) = self.heap[parent];
            if !first(&item.0, item.1, &pk, pj) {
                break;
            }
            self.heap[k] = self.heap[parent];
            self.slots[self.heap[k].1 as usize].place = IN_HEAP | k as u32;
            k = parent;
        }
        self.heap[k] = item;
        self.slots[item.1 as usize].place = IN_HEAP | k as u32;
    }

    fn down(&mut self, mut k: usize) {
        let item = self.heap[k];
        let n = self.heap.len();
        loop {
            let first_child = ARITY * k + 1;
            if first_child >= n {
                break;
            }
            let mut best = first_child;
            for c in first_child + 1..(first_child + ARITY).min(n) {
                let (ck, cj) = self.heap[c];
                let (bk, bj) = self.heap[best];
                if first(&ck, cj, &bk, bj) {
                    best = c;
                }
            }
            let (bk, bj) = self.heap[best];
            if !first(&bk, bj, &item.0, item.1) {
                break;
            }
            self.heap[k] = self.heap[best];
            self.slots[self.heap[k].1 as usize].place = IN_HEAP | k as u32;
            k = best;
        }
        self.heap[k] = item;
        self.slots[item.1 as usize].place = IN_HEAP | k as u32;
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
        let mut rng = crate::physics::gas::Rng::new(12345);
        for step in 0..5000u64 {
            let state = rng.next_u64();
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

    /// Events as the billiard makes them: the earliest is taken (or set
    /// again while earliest) and its puck (and a few others) given new
    /// entries at or after it, some far
    /// ahead, some removed, with ties of time and rank and a thousandfold
    /// change of the event rate halfway (the width is tuned twice); the
    /// queue must give exactly the order a sort of the entries gives.
    #[test]
    fn calendar_queue_gives_the_sorted_order_as_the_rate_changes() {
        let n = 200u32;
        let mut c = Calendar::new(n as usize);
        let mut keys: Vec<Option<Key>> = vec![None; n as usize];
        let mut rng = crate::physics::gas::Rng::new(0x9e37_79b9_7f4a_7c15);
        let mut rand = move || rng.next_u64();
        let key_at = |t: f64, r: u64, i: u32| Key {
            t,
            rank: match r % 3 {
                0 => Rank::kick(i),
                1 => Rank::pair(0, 1), // shared by many: ties of rank
                _ => Rank::shell(i),
            },
        };
        for i in 0..n {
            let k = key_at((rand() % 1000) as f64 * 1e-3, rand(), i);
            keys[i as usize] = Some(k);
            c.set(i, k);
        }
        let mut now = 0.0;
        let mut taken = 0;
        let (mut ring_used, mut overflow_used, mut widths) = (0, 0, vec![c.width]);
        for step in 0..40_000u64 {
            let scale = if step < 20_000 { 1e-3 } else { 1.0 };
            let expected = (0..n)
                .filter_map(|i| keys[i as usize].map(|k| (k, i)))
                .min_by(|(a, i), (b, j)| {
                    if first(a, *i, b, *j) {
                        std::cmp::Ordering::Less
                    } else {
                        std::cmp::Ordering::Greater
                    }
                });
            let got = c.peek();
            ring_used = ring_used.max(c.in_ring);
            overflow_used = overflow_used.max(c.in_overflow);
            if c.width != *widths.last().unwrap() {
                widths.push(c.width);
            }
            assert_eq!(
                got.map(|(k, i)| (k.t, k.rank, i)),
                expected.map(|(k, i)| (k.t, k.rank, i)),
                "step {step}"
            );
            let Some((key, i)) = got else { break };
            assert!(key.t >= now, "time never goes back");
            now = key.t;
            // Taken; or (as the second puck of a pair whose first was just
            // handled) set again while it is still the earliest, below.
            if step % 2 == 0 {
                c.remove(i);
                keys[i as usize] = None;
            }
            taken += 1;
            // The puck and a few others predicted again from now on.
            for j in [i, (rand() % n as u64) as u32, (rand() % n as u64) as u32] {
                let r = rand();
                let k = match r % 16 {
                    0 => None,                                                               // nothing ahead
                    1 => Some(key_at(now, r >> 4, j)), // now: a tie of time
                    2 => Some(key_at(now + (r >> 8) as f64 % 1e3 * scale * 1e3, r >> 4, j)), // far ahead
                    _ => Some(key_at(
                        now + ((r >> 8) % 1000) as f64 * scale * 1e-3 * n as f64,
                        r >> 4,
                        j,
                    )),
                };
                match k {
                    Some(k) => c.set(j, k),
                    None => c.remove(j),
                }
                keys[j as usize] = k;
            }
        }
        assert!(taken > 30_000, "the queue kept running ({taken} taken)");
        // Every part of the queue was used, and the width followed the rate.
        assert!(
            ring_used > 10 && overflow_used > 0,
            "{ring_used} {overflow_used}"
        );
        assert!(widths.len() >= 3, "widths {widths:?}");
        assert!(
            widths[widths.len() - 1] > 100.0 * widths[1],
            "widths {widths:?}"
        );
    }

    /// Times far from the tuned width's scale (negative, subnormal, ±0,
    /// 10¹⁸, ±10³⁰⁰) and NaN (no entry) after the width is tuned: popped in
    /// the sorted order all the same.
    #[test]
    fn extreme_times_keep_the_sorted_order() {
        let n = 300u32;
        let mut c = Calendar::new(n as usize);
        let key = |t: f64, i: u32| Key {
            t,
            rank: Rank::shell(i),
        };
        // A steady rate first, so that the width is tuned (to about 4 ms).
        for i in 0..n {
            c.set(i, key(f64::from(i) * 1e-3, i));
        }
        let mut now = 0.0;
        for _ in 0..2000 {
            let (k, i) = c.peek().expect("entries");
            now = k.t;
            c.remove(i);
            c.set(i, key(now + 0.3, i));
        }
        assert!(c.width.is_finite(), "tuned");
        let extremes = [
            -1e300,
            -5.0,
            -0.0,
            0.0,
            5e-324,
            now,
            now + 1e-12,
            1e18,
            1e300,
            f64::NAN,
            f64::INFINITY,
        ];
        let mut expected: Vec<(f64, u32)> = Vec::new();
        for i in 0..n {
            let t = if i % 3 == 0 {
                extremes[(i as usize / 3) % extremes.len()]
            } else {
                now + f64::from(i) * 1e-2
            };
            c.set(i, key(t, i));
            if t.is_finite() {
                expected.push((t, i));
            }
        }
        // By time (±0 equal: ties broken by puck, not by sign), then puck.
        expected.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap().then(a.1.cmp(&b.1)));
        let mut got = Vec::new();
        while let Some((k, i)) = c.peek() {
            got.push((k.t, i));
            c.remove(i);
        }
        assert_eq!(got, expected);
    }
}
