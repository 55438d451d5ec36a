//! The event calendar: predicted events in board-time order, invalidated
//! lazily. Every prediction carries the versions of the pucks it was made
//! from; a puck's version grows whenever its worldline changes, and a popped
//! event whose versions are stale is dropped.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::predict::Cushion;

/// What a calendar entry is about, ranked for ties at the same board time:
/// velocity changes first, then cushion contacts, then pair contacts, then
/// the broad phase's horizon; within a kind, by puck index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Slot {
    /// A pending velocity change (index into the kick table).
    Kick(usize),
    /// A puck meets a cushion.
    Cushion(u32, Cushion),
    /// Two pucks meet (lower index first).
    Pair(u32, u32),
    /// End of the broad phase's look-ahead window.
    Horizon,
}

/// One calendar entry.
#[derive(Clone, Copy, Debug)]
pub struct Entry {
    /// Board time, s.
    pub t: f64,
    /// What happens.
    pub slot: Slot,
    /// Versions of the pucks involved when it was predicted.
    pub versions: [u32; 2],
    /// Board time at which the prediction was made (a pair contact is
    /// recomputed from it when due, bit for bit, rather than stored).
    pub predicted_at: f64,
}

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    /// Reversed (earliest first) for the max-heap, deterministic on ties.
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .t
            .total_cmp(&self.t)
            .then_with(|| other.slot.cmp(&self.slot))
            .then_with(|| other.versions.cmp(&self.versions))
    }
}

/// The queue.
#[derive(Default, Debug)]
pub struct Calendar {
    heap: BinaryHeap<Entry>,
}

impl Calendar {
    /// Schedules an entry.
    pub fn push(&mut self, entry: Entry) {
        self.heap.push(entry);
    }

    /// The earliest entry, without removing it.
    pub fn peek(&self) -> Option<&Entry> {
        self.heap.peek()
    }

    /// Removes and returns the earliest entry.
    pub fn pop(&mut self) -> Option<Entry> {
        self.heap.pop()
    }

    /// Entries held, stale ones included.
    pub fn len(&self) -> usize {
        self.heap.len()
    }

    /// Drops every entry for which `keep` is false (compaction of stale
    /// entries, so the heap does not grow without bound).
    pub fn retain(&mut self, keep: impl FnMut(&Entry) -> bool) {
        self.heap.retain(keep);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn earliest_first_and_ties_are_deterministic() {
        let mut c = Calendar::default();
        let e = |t, slot| Entry {
            t,
            slot,
            versions: [0, 0],
            predicted_at: 0.0,
        };
        c.push(e(2.0, Slot::Pair(0, 1)));
        c.push(e(1.0, Slot::Pair(3, 4)));
        c.push(e(1.0, Slot::Cushion(7, Cushion::Y1)));
        c.push(e(1.0, Slot::Kick(9)));
        c.push(e(1.0, Slot::Pair(2, 5)));
        let order: Vec<_> = std::iter::from_fn(|| c.pop()).map(|e| e.slot).collect();
        assert_eq!(
            order,
            vec![
                Slot::Kick(9),
                Slot::Cushion(7, Cushion::Y1),
                Slot::Pair(2, 5),
                Slot::Pair(3, 4),
                Slot::Pair(0, 1)
            ]
        );
    }
}
