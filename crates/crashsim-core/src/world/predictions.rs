//! The kept predictions of bodies on the ground. A step asks for the same integration of a
//! body's motion several times (the swept box, the speed bound, the search, the advance), so
//! each is kept, keyed by the body, the instant it starts from, its span and the world's
//! count of velocity jumps when it was made ([`super::world_body`]): after an impulse the
//! count differs, so every prediction made before it is stale without anyone forgetting it.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex};

use crate::body::RigidBody;
use crate::math::Real;
use crate::motion::{MotionBound, OnGround};

use super::joints::MechanismOutcome;

/// What a prediction was made for (the times as bits: exact matches only).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PredictionKey {
    body: usize,
    time: u64,
    dt: u64,
    jumps: u64,
}

impl PredictionKey {
    /// Body `body` predicted `dt` s from `time` (s), the world's bodies having jumped `jumps`
    /// times in all.
    pub(super) fn new(body: usize, time: Real, dt: Real, jumps: u64) -> PredictionKey {
        PredictionKey {
            body,
            time: time.to_bits(),
            dt: dt.to_bits(),
            jumps,
        }
    }

    /// The same instant, span and jump count for body `body` (a mechanism's other members,
    /// predicted together).
    pub(super) fn for_body(&self, body: usize) -> PredictionKey {
        PredictionKey { body, ..*self }
    }
}

/// A body on the ground as predicted.
#[derive(Clone, Debug)]
pub(super) struct Prediction {
    pub(super) key: PredictionKey,
    pub(super) state: RigidBody,
    pub(super) motion: OnGround,
    /// How the motion is bounded over the prediction's span (forward predictions only).
    pub(super) bound: Option<MotionBound>,
    /// For a mechanism's member: what the mechanism's span left (shared by its members).
    pub(super) mechanism: Option<Arc<MechanismOutcome>>,
}

/// The latest predictions (behind a lock: they are made through a shared reference to the
/// world).
#[derive(Debug, Default)]
pub(super) struct Predictions {
    /// Oldest first (a queue: dropping the oldest moves none of the others).
    kept: Mutex<VecDeque<Prediction>>,
}

impl Predictions {
    /// The prediction kept for `key`, if there is one.
    pub(super) fn find(&self, key: &PredictionKey) -> Option<Prediction> {
        let kept = self.kept.lock().expect("not poisoned");
        kept.iter().find(|p| p.key == *key).cloned()
    }

    /// Keeps `p`: first drops those made before a jump it was not (they can no longer be
    /// asked for), then the oldest while `capacity` is reached.
    pub(super) fn keep(&self, p: Prediction, capacity: usize) {
        let mut kept = self.kept.lock().expect("not poisoned");
        kept.retain(|q| q.key.jumps == p.key.jumps);
        if kept.len() >= capacity {
            kept.pop_front();
        }
        kept.push_back(p);
    }
}
