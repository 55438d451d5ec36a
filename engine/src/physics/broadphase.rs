//! Broad phase: rapier2d's BVH prunes which puck pairs need a prediction.
//!
//! rapier's solver is not used at all. Each puck is a collider without a
//! rigid body; its AABB is *swept*: it covers everywhere the puck can be
//! from now to the end of the current look-ahead window. Two pucks whose
//! swept AABBs do not overlap cannot meet within the window, so only
//! overlapping pairs (rapier's `AddPair` events, kept in our own adjacency
//! lists until `DeletePair`) get a closed-form prediction. When the window
//! ends every AABB is swept anew.

use glam::DVec2;
use rapier2d_f64::prelude::*;

/// The BVH and the candidate pairs it has reported.
pub struct BroadPhase {
    bvh: BroadPhaseBvh,
    params: IntegrationParameters,
    colliders: ColliderSet,
    bodies: RigidBodySet,
    handles: Vec<ColliderHandle>,
    /// For each puck, its current candidate partners.
    partners: Vec<Vec<u32>>,
    events: Vec<BroadPhasePairEvent>,
}

impl BroadPhase {
    /// A broad phase for `n` pucks; `length_unit` (m) sets rapier's AABB
    /// skin, 4 % of it, so it should be about a puck radius.
    pub fn new(n: usize, length_unit: f64) -> Self {
        let mut colliders = ColliderSet::new();
        let handles = (0..n)
            .map(|_| {
                colliders.insert(
                    ColliderBuilder::ball(length_unit)
                        .active_collision_types(ActiveCollisionTypes::all())
                        .build(),
                )
            })
            .collect();
        let params = IntegrationParameters {
            length_unit,
            ..IntegrationParameters::default()
        };
        Self {
            bvh: BroadPhaseBvh::new(),
            params,
            colliders,
            bodies: RigidBodySet::new(),
            handles,
            partners: vec![Vec::new(); n],
            events: Vec::new(),
        }
    }

    /// Sets puck `i`'s swept AABB (board frame, m).
    pub fn set_swept(&mut self, i: usize, mins: DVec2, maxs: DVec2) {
        self.bvh
            .set_aabb(&self.params, self.handles[i], Aabb::new(mins, maxs));
    }

    /// Applies the AABBs set since the last call; returns the pairs that
    /// became candidates (lower index first).
    pub fn flush(&mut self, added: &mut Vec<(u32, u32)>) {
        self.events.clear();
        self.bvh.update(
            &self.params,
            &self.colliders,
            &self.bodies,
            &[],
            &[],
            &mut self.events,
        );
        for event in &self.events {
            match event {
                BroadPhasePairEvent::AddPair(pair) => {
                    let (a, b) = ordered(pair);
                    self.partners[a as usize].push(b);
                    self.partners[b as usize].push(a);
                    added.push((a, b));
                }
                BroadPhasePairEvent::DeletePair(pair) => {
                    let (a, b) = ordered(pair);
                    self.partners[a as usize].retain(|&x| x != b);
                    self.partners[b as usize].retain(|&x| x != a);
                }
            }
        }
    }

    /// Current candidate partners of puck `i`.
    pub fn partners(&self, i: usize) -> &[u32] {
        &self.partners[i]
    }
}

fn ordered(pair: &ColliderPair) -> (u32, u32) {
    let a = pair.collider1.into_raw_parts().0;
    let b = pair.collider2.into_raw_parts().0;
    (a.min(b), a.max(b))
}
