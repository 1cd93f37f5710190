//! The world: bodies with meshes, per-pair contact state, the stepper and the event log.
//!
//! A run advances on the grid t_start + k dt, stopping early at every first overlap
//! (found by conservative advancement, then bisection to `TIME_TOLERANCE`) and landing
//! exactly on every exchange instant t0 + dt_p. Per pair the phases are:
//! apart -> timer (meshes pass through each other) -> engaged (after an exchange, while
//! the meshes overlap) -> apart on separation, or -> timer again when the relative velocity
//! at the centroid along the normal turns closing (a secondary exchange).
//!
//! The parts: [`stepper`] (the schedule of a run and its samples), [`first_contact`] (the
//! first-overlap search), [`geometry`] (normal, centroid, contact frame, automatic dt_p),
//! [`exchange`] (timers, the impulse exchange, engaged pairs), [`events`] (what a run
//! returns).

mod events;
mod exchange;
mod first_contact;
mod geometry;
mod stepper;

use std::sync::Arc;

use crate::body::{BodyState, MassProperties, RigidBody};
use crate::contact::{CentroidMode, ContactParams};
use crate::error::{Error, Result};
use crate::math::{Point, Real, Vector};
use crate::overlap::QueryWorkspace;
use crate::shape::MeshShape;
use crate::stiffness::{Face, Stiffness};

pub use events::{ContactEvent, ContactEventKind, Impact, RunOutput};

/// First-overlap instants are resolved to this (s).
pub const TIME_TOLERANCE: Real = 1e-9;
/// The automatic normal of a first exchange is the overlap's volume normal taken while the
/// overlap is at most this deep (m): at the exchange a deep, narrow overlap (an offset
/// frontal) puts the side walls that sank into each other ahead of the faces that met, and
/// its volume normal turns toward the side (52 deg for two boxes 0.9 m offset, 1.16 m deep).
pub const NORMAL_DEPTH: Real = 0.02;

#[derive(Clone, Debug)]
enum Phase {
    Apart,
    Timer {
        started: Real,
        exchange_at: Real,
        secondary: bool,
        notes: Vec<String>,
        /// The volume normal of the shallow overlap, body 1's frame, and when it was taken.
        early_normal: Option<(Vector, Real)>,
        /// The share of the model's impulse exchanged, in (0, 1]: below 1 when the overlap
        /// ends before dt_p (exchange.rs, `overlap_ends_early`).
        impulse_share: Real,
    },
    Engaged {
        /// The centroid as material points of body 1 and body 2 (their frames, m).
        centroid_in: [Point; 2],
        /// The normal, body 1's frame.
        normal_in_1: Vector,
    },
}

#[derive(Clone, Debug)]
struct Pair {
    body1: usize,
    body2: usize,
    params: ContactParams,
    phase: Phase,
    exchanges: usize,
}

#[derive(Clone, Debug)]
struct WorldBody {
    shape: Arc<MeshShape>,
    body: RigidBody,
    stiffness: Stiffness,
}

/// Bodies, pairs and the clock.
#[derive(Debug, Default)]
pub struct World {
    bodies: Vec<WorldBody>,
    pairs: Vec<Pair>,
    time: Real,
    started: bool,
    ws: QueryWorkspace,
}

impl World {
    /// An empty world at t = 0.
    pub fn new() -> World {
        World::default()
    }

    /// Current time (s).
    pub fn time(&self) -> Real {
        self.time
    }

    /// Number of bodies.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Body `i`'s current state.
    pub fn state(&self, i: usize) -> BodyState {
        self.bodies[i].body.state()
    }

    /// Adds a body; every new pair gets default contact parameters. Returns its index.
    pub fn add_body(
        &mut self,
        shape: Arc<MeshShape>,
        props: MassProperties,
        state: &BodyState,
    ) -> Result<usize> {
        if self.started {
            return Err(Error::Parameter(
                "bodies must be added before the first run".into(),
            ));
        }
        let body = RigidBody::new(props, state)?;
        let index = self.bodies.len();
        for other in 0..index {
            self.pairs.push(Pair {
                body1: other,
                body2: index,
                params: ContactParams::default(),
                phase: Phase::Apart,
                exchanges: 0,
            });
        }
        self.bodies.push(WorldBody {
            shape,
            body,
            stiffness: Stiffness::none(),
        });
        Ok(index)
    }

    /// Sets body `i`'s face stiffness (used by automatic dt_p, the stiffness centroid and
    /// reported per impact).
    pub fn set_stiffness(&mut self, i: usize, stiffness: Stiffness) -> Result<()> {
        let n = self.bodies.len();
        let body = self.bodies.get_mut(i).ok_or_else(|| {
            Error::Parameter(format!(
                "body {i} does not exist (the world has {n} bodies)"
            ))
        })?;
        body.stiffness = stiffness;
        Ok(())
    }

    /// An error when the pair's parameters need face stiffness that a body lacks.
    fn check_stiffness(&self, body1: usize, body2: usize, params: &ContactParams) -> Result<()> {
        if !params.needs_stiffness() {
            return Ok(());
        }
        for i in [body1, body2] {
            let s = &self.bodies[i].stiffness;
            if let Some(face) = Face::ALL.iter().find(|f| s.face(**f).is_none()) {
                return Err(Error::Parameter(format!(
                    "body {i} has no stiffness on its {} face: depth_of_penetration = auto and \
                     centroid = stiffness need CRASH3 A and B on every face of both vehicles \
                     (give the vehicle a stiffness, or use a fixed dt_p and the automatic \
                     centroid)",
                    face.name()
                )));
            }
        }
        Ok(())
    }

    /// Sets the contact parameters of the pair; the normal points from `body1` into `body2`.
    pub fn set_contact(&mut self, body1: usize, body2: usize, params: ContactParams) -> Result<()> {
        let n = self.bodies.len();
        if body1 >= n || body2 >= n || body1 == body2 {
            return Err(Error::Parameter(format!(
                "contact ({body1}, {body2}) must name two different bodies among 0..{n}"
            )));
        }
        params.validate()?;
        self.check_stiffness(body1, body2, &params)?;
        if let CentroidMode::Body { body, .. } = params.centroid {
            if body != body1 && body != body2 {
                return Err(Error::Parameter(format!(
                    "the centroid is fixed in body {body}, which is not in the pair ({body1}, {body2})"
                )));
            }
        }
        let pair = self
            .pairs
            .iter_mut()
            .find(|p| (p.body1, p.body2) == (body1, body2) || (p.body1, p.body2) == (body2, body1))
            .expect("every pair of bodies exists");
        pair.body1 = body1;
        pair.body2 = body2;
        pair.params = params;
        Ok(())
    }

    /// Advances by `duration` s with steps of at most `dt` s.
    pub fn run(&mut self, duration: Real, dt: Real) -> Result<RunOutput> {
        self.run_with_progress(duration, dt, &mut |_| true)
    }
}
