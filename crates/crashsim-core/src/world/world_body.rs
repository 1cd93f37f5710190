//! A body of the world: its mesh, its state and how it moves, and the count of its motion's
//! jumps. What the world works out ahead from a body's motion (the kept predictions, a pair's
//! clearance) holds while the body only moves along that motion; an impulse changes its
//! velocity in a way the motion did not foresee. The state is private here so that every such
//! change goes through a method that counts it, and a cache compares the counts instead of
//! being told by hand to forget.

use std::sync::Arc;

use crate::body::RigidBody;
use crate::math::{Point, Real, Vector};
use crate::shape::MeshShape;
use crate::stiffness::Stiffness;
use crate::vehicle::VehicleSpec;

use super::Motion;

#[derive(Clone, Debug)]
pub(super) struct WorldBody {
    pub(super) shape: Arc<MeshShape>,
    /// Distance (m) from the CG to the farthest corner of the mesh's box (body frame): how
    /// fast a turn moves the body's points, for the rest test.
    pub(super) reach: Real,
    pub(super) stiffness: Stiffness,
    /// Wheels, tyre and inputs, used when the world has a ground.
    pub(super) vehicle: Option<Arc<VehicleSpec>>,
    /// Its own friction with the ground (a person's clothing on the road), used when the
    /// world has a ground; None: the ground's body friction.
    pub(super) ground_friction: Option<Real>,
    pub(super) motion: Motion,
    /// Its state (world frame).
    body: RigidBody,
    /// Velocity changes its motion did not foresee, so far: impulses of exchanges and of
    /// soft contacts, and a joint's share of one.
    jumps: u64,
}

impl WorldBody {
    pub(super) fn new(shape: Arc<MeshShape>, body: RigidBody, motion: Motion) -> WorldBody {
        let b = shape.aabb();
        let reach = Vector::new(
            b.mins.x.abs().max(b.maxs.x.abs()),
            b.mins.y.abs().max(b.maxs.y.abs()),
            b.mins.z.abs().max(b.maxs.z.abs()),
        )
        .norm();
        WorldBody {
            shape,
            reach,
            stiffness: Stiffness::none(),
            vehicle: None,
            ground_friction: None,
            motion,
            body,
            jumps: 0,
        }
    }

    /// The body's state.
    pub(super) fn body(&self) -> &RigidBody {
        &self.body
    }

    /// How many times its velocity has jumped (see [`WorldBody::apply_impulse`]).
    pub(super) fn jumps(&self) -> u64 {
        self.jumps
    }

    /// Puts the body where its own motion took it (a step of the run, from a prediction):
    /// not a jump.
    pub(super) fn move_to(&mut self, body: RigidBody) {
        self.body = body;
    }

    /// Moves a torque-free body on by `dt` (s): not a jump.
    pub(super) fn advance(&mut self, dt: Real) {
        self.body.advance(dt);
    }

    /// Applies the impulse `j` (N s, world) at `p` (world): a jump.
    pub(super) fn apply_impulse(&mut self, j: &Vector, p: &Point) {
        self.body.apply_impulse(j, p);
        self.jumps += 1;
    }

    /// Adds `dv` (m/s) and `dw` (rad/s, world) to its velocities (a joint's reaction
    /// impulse): a jump.
    pub(super) fn change_velocity(&mut self, dv: &Vector, dw: &Vector) {
        let mut s = self.body.state();
        s.velocity += dv;
        s.angular_velocity += dw;
        self.body =
            RigidBody::new(self.body.props().clone(), &s).expect("a moved state stays finite");
        self.jumps += 1;
    }
}
