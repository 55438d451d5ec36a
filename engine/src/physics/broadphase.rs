//! Broad phase: rapier2d's broad-phase BVH finds which puck pairs need a
//! prediction.
//!
//! rapier's solver is not used at all, only the bounding-volume tree its
//! broad phase is built on (`parry`'s `Bvh`, which `rapier`'s
//! `BroadPhaseBvh` wraps). Each puck is a leaf whose AABB is a *position
//! shell*: the puck's rest disc about a fixed centre, grown by a margin. A
//! contracted puck always lies inside its rest disc, so while every puck's
//! centre stays within the margin of its shell's centre, two pucks whose
//! AABBs do not overlap cannot touch, whatever their velocities: a velocity
//! change touches no AABB. A puck's AABB changes only when its centre
//! leaves its shell (an event on the calendar); its leaf is then updated in
//! place (its ancestors grown to enclose it, O(log N)) and the tree is asked
//! which AABBs overlap the new one (O(log N) plus the partners), of which
//! only those whose shells' discs overlap are kept: a puck's centre stays
//! within the margin of its shell's centre, so its shape stays inside the
//! disc of its rest radius plus the margin about it, and the square AABB's
//! corners would add a fifth more partners to bound for nothing. In-place
//! updates only loosen the tree, so it is rebuilt from the leaves after
//! every 4N shell moves, at least 256 (O(N log N), amortised O(log N) per
//! move; every N moves cost 3 % more in all at N = 10⁴, the looser tree's
//! queries less than the rebuilds); a re-insertion by SAH descent per move
//! cost more. The tree's shape changes only the order in which partners
//! are found, never which.
//! `BroadPhaseBvh::update` is not used: it walks the whole tree on every
//! call, O(N) per shell move (measured: a third of the time at N = 10⁴).

use glam::DVec2;
use rapier2d_f64::parry::bounding_volume::Aabb;
use rapier2d_f64::parry::partitioning::{Bvh, BvhBuildStrategy, BvhWorkspace};
use smallvec::SmallVec;

/// The tree and the candidate pairs: for each puck, the pucks whose shells'
/// AABBs overlap its own.
#[derive(Clone)]
pub struct BroadPhase {
    tree: Bvh,
    /// Each shell's disc.
    discs: Vec<Disc>,
    partners: Vec<Partners>,
    /// Scratch: which pucks were partners of the moving one (by index).
    mark: Vec<bool>,
    found: Vec<u32>,
    /// Shell moves since the tree was last built from the leaves.
    moves: usize,
    /// Scratch of the rebuild (kept: no allocation per rebuild).
    workspace: BvhWorkspace,
}

impl BroadPhase {
    /// A broad phase of shells: puck `i`'s is a square of half-width
    /// `half[i]` (m, its rest radius plus the margin) about `centres[i]`
    /// (board frame, m).
    pub fn new(centres: &[DVec2], half: &[f64]) -> Self {
        let aabbs: Vec<Aabb> = centres
            .iter()
            .zip(half)
            .map(|(&c, &h)| square(c, h))
            .collect();
        let tree = Bvh::from_leaves(BvhBuildStrategy::Binned, &aabbs);
        let n = aabbs.len();
        let mut broad = Self {
            tree,
            discs: centres
                .iter()
                .zip(half)
                .map(|(&centre, &half)| Disc { centre, half })
                .collect(),
            partners: vec![Partners::default(); n],
            mark: vec![false; n],
            found: Vec::new(),
            moves: 0,
            workspace: BvhWorkspace::default(),
        };
        for (i, aabb) in aabbs.iter().enumerate() {
            let list: SmallVec<[u32; 14]> = broad
                .tree
                .intersect_aabb(aabb)
                .filter(|&j| j as usize != i && discs_meet(&broad.discs, i, j as usize))
                .collect();
            broad.partners[i] = Partners(list);
        }
        broad
    }

    /// Moves puck `i`'s shell to `centre` (half-width `half`, m) and updates
    /// the candidate pairs it is in.
    pub fn set_shell(&mut self, i: usize, centre: DVec2, half: f64) {
        let aabb = square(centre, half);
        self.discs[i] = Disc { centre, half };
        // In place: the leaf's AABB replaced, its ancestors grown as needed.
        self.tree.insert_with_change_detection(aabb, i as u32, 0.0);
        self.moves += 1;
        if self.moves >= 4 * self.discs.len().max(64) {
            self.moves = 0;
            self.tree
                .rebuild(&mut self.workspace, BvhBuildStrategy::Binned);
        }
        self.found.clear();
        let (tree, discs) = (&self.tree, &self.discs);
        self.found.extend(
            tree.intersect_aabb(&aabb)
                .filter(|&j| j as usize != i && discs_meet(discs, i, j as usize)),
        );
        let old = std::mem::take(&mut self.partners[i]).0;
        for &j in &old {
            self.mark[j as usize] = true;
        }
        for &j in &self.found {
            if self.mark[j as usize] {
                self.mark[j as usize] = false; // still a partner
            } else {
                self.partners[j as usize].0.push(i as u32); // new
            }
        }
        for &j in &old {
            if self.mark[j as usize] {
                self.mark[j as usize] = false; // gone
                let list = &mut self.partners[j as usize].0;
                if let Some(k) = list.iter().position(|&x| x as usize == i) {
                    list.swap_remove(k);
                }
            }
        }
        let mut list = old;
        list.clear();
        list.extend_from_slice(&self.found);
        self.partners[i] = Partners(list);
    }

    /// Current candidate partners of puck `i`.
    pub fn partners(&self, i: usize) -> &[u32] {
        &self.partners[i].0
    }

    /// Where puck `i`'s partner list is kept (for prefetching).
    pub fn partners_record(&self, i: usize) -> &impl Sized {
        &self.partners[i]
    }
}

/// Whether the discs of shells `i` and `j` (of `discs`) overlap, with a
/// slack of 1e-9 of their radii far above the rounding of the centres:
/// pucks whose discs do not cannot touch while both centres are in their
/// shells.
#[inline]
fn discs_meet(discs: &[Disc], i: usize, j: usize) -> bool {
    let (a, b) = (discs[i], discs[j]);
    let reach = (a.half + b.half) * (1.0 + 1e-9);
    a.centre.distance_squared(b.centre) <= reach * reach
}

/// A shell's disc: centre (m, board frame) and radius (m, the rest radius
/// plus the margin), together because every partner found reads both.
#[derive(Clone, Copy)]
struct Disc {
    centre: DVec2,
    half: f64,
}

/// A puck's partners, in one aligned 64-byte line while there are at most
/// 14 (about 9 in a dense gas; more spill to the heap): reading them, or
/// adding or removing one, touches one line, not a list header and a heap
/// block elsewhere.
#[derive(Clone, Default)]
#[repr(align(64))]
struct Partners(SmallVec<[u32; 14]>);

fn square(centre: DVec2, half: f64) -> Aabb {
    let h = DVec2::splat(half);
    Aabb::new(centre - h, centre + h)
}
