//! Broad phase: rapier2d's BVH finds which puck pairs need a prediction.
//!
//! rapier's solver is not used at all. Each puck is a collider without a
//! rigid body; its AABB is a *position shell*: the puck's rest disc about a
//! fixed centre, grown by a margin. A contracted puck always lies inside its
//! rest disc, so while every puck's centre stays within the margin of its
//! shell's centre, two pucks whose shells' AABBs do not overlap cannot touch,
//! whatever their velocities: a velocity change touches no AABB. Only
//! overlapping pairs (rapier's `AddPair` events, kept in our own adjacency
//! lists until `DeletePair`) get predictions. A puck's AABB changes only
//! when its centre leaves its shell (an event on the calendar).

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

    /// Sets puck `i`'s shell: a square of half-width `half` (m, its rest
    /// radius plus the margin) about `centre` (board frame, m).
    pub fn set_shell(&mut self, i: usize, centre: DVec2, half: f64) {
        let h = DVec2::splat(half);
        self.bvh.set_aabb(
            &self.params,
            self.handles[i],
            Aabb::new(centre - h, centre + h),
        );
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
