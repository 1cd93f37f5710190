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

mod clearance;
mod events;
mod exchange;
mod first_contact;
mod geometry;
mod joints;
mod predictions;
mod soft;
mod stepper;
mod world_body;

use std::borrow::Cow;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use crate::body::{BodyState, MassProperties, RigidBody};
use crate::contact::{CentroidMode, ContactParams};
use crate::error::{Error, Place, Result};
use crate::ground::Ground;
use crate::joint::JointSpec;
use crate::math::{Isometry, Point, Real, Vector};
use crate::motion::{BodyContact, OnGround};
use crate::overlap::QueryWorkspace;
use crate::shape::MeshShape;
use crate::soft::SoftContact;
use crate::stiffness::Stiffness;
use crate::vehicle::VehicleSpec;
use clearance::Front;
use predictions::{Prediction, PredictionKey, Predictions};
use world_body::WorldBody;

pub use events::{
    degrees, delta_v_in_body, heading, magnitude, pdof_deg, ContactEvent, ContactEventKind, Impact,
    RunOutput,
};
pub use joints::{JointEvent, ANCHOR_REACH};
pub use stepper::{
    check_run_length, RunOptions, DEFAULT_MAX_HISTORY_BYTES, DEFAULT_SAMPLES, REST_SPEED,
    REST_TIME, REST_TURN_SPEED, REST_YAW_RATE,
};

/// First-overlap instants are resolved to this (s).
pub const TIME_TOLERANCE: Real = 1e-9;
/// How far (m) a body's mesh (outside its wheels) may reach into the ground at the start of a
/// run: a few mm are a resting body's sinking or a mesh's detail; 15 cm (a box car whose CG
/// sat at its wheels' height) made the ground's spring throw the car 8 m up.
pub const PLACEMENT_TOLERANCE: Real = 0.02;
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
        /// The timer's length, s: dt_p, or less when the overlap ends early.
        timer: Real,
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
    /// A soft pair overlapping: its compliant force acts each step (soft.rs).
    Pressing {
        /// The overlap's depth (m) at the end of the last step (0 at the first overlap).
        depth: Real,
    },
    /// Two bodies at rest touching without an exchange (exchange.rs, a resting contact).
    Touching {
        /// Where they first touched, as material points of body 1 and body 2 (their frames,
        /// m).
        point_in: [Point; 2],
    },
}

#[derive(Clone, Debug)]
struct Pair {
    body1: usize,
    body2: usize,
    params: ContactParams,
    phase: Phase,
    exchanges: usize,
    /// The apart pair's clearance front (clearance.rs): which parts of the meshes are kept
    /// apart, so most steps need no mesh query. None until the pair is first searched,
    /// and again once it is out of reach or in contact.
    front: Option<Box<Front>>,
    /// Before this time (s) the apart pair of torque-free or fixed bodies cannot touch (the
    /// front's margin over their speed bound, which holds until an exchange changes a
    /// velocity): no work at all. It holds while both bodies' jump counts are still
    /// `clear_jumps`, the counts when it was found.
    clear_until: Real,
    clear_jumps: [u64; 2],
    /// The closest pair of triangles (of body 1, body 2) at the pair's last distance query:
    /// the next query starts from it.
    closest: Option<(u32, u32)>,
    /// A pair of triangles (of body 1, body 2) whose surfaces crossed at the engaged pair's
    /// last overlap test: the next test tries it first (overlap/intersect.rs,
    /// shapes_overlap_hinted).
    crossing: Option<(u32, u32)>,
    /// The compliant contact that replaces the timer and the exchange (None: the impulse
    /// model of `params`).
    soft: Option<SoftContact>,
    /// While the soft pair presses, each step of the run is cut into this many sub-steps
    /// (soft.rs, [`World::size_soft_substeps`]); 1 for every other pair.
    soft_substeps: usize,
}

/// How a body moves between exchanges.
#[derive(Clone, Debug)]
enum Motion {
    /// Torque-free, exactly (a world without ground).
    Free,
    /// Under gravity on the ground: wheels, tyres, the body's contact with the ground.
    OnGround(Box<OnGround>),
    /// Fixed in the world (an obstacle): never moves, infinite mass in the exchange.
    Fixed,
}

/// Bodies, pairs, the ground and the clock.
#[derive(Debug, Default)]
pub struct World {
    bodies: Vec<WorldBody>,
    pairs: Vec<Pair>,
    time: Real,
    started: bool,
    ws: QueryWorkspace,
    ground: Option<Ground>,
    /// The bodies at the start of the current step (time, states), from which a body on the
    /// ground is predicted at an instant before now (bisections run backwards in a step).
    step_start: Option<(Real, Vec<(RigidBody, Motion)>)>,
    /// An error met inside a prediction that cannot return one (a wheel off the terrain in a
    /// bisection); the stepper returns it after the step.
    deferred: Mutex<Option<Error>>,
    /// Distance queries between meshes made by the first-contact search so far (a count for
    /// tests and benchmarks: a step with every pair out of reach makes none).
    distance_queries: AtomicU64,
    /// Parts of meshes (node or triangle pairs) evaluated by the pairs' clearance fronts so
    /// far (a count for tests and benchmarks).
    clearance_evaluations: AtomicU64,
    /// Clearance-front entries looked at so far (profiling).
    clearance_checks: AtomicU64,
    /// Since when each body on the ground has been slow enough to be at rest (s), if it is
    /// (stepper.rs, rest detection).
    slow_since: Vec<Option<Real>>,
    /// When each body on the ground came to rest after it last moved (s), if it has.
    stopped_at: Vec<Option<Real>>,
    /// Since when each body on the ground has been settled (s), if it is: on the ground with
    /// every velocity component small (stepper.rs, a run until rest).
    settled_since: Vec<Option<Real>>,
    /// The latest predictions of bodies on the ground (predictions.rs).
    predictions: Predictions,
    /// The joints, in the order added (joints.rs).
    joints: Vec<JointSpec>,
    /// The jointed bodies' mechanisms (built at the first run).
    mechanisms: Vec<joints::Mechanism>,
    /// Each body's mechanism, if it is jointed.
    mechanism_of: Vec<Option<usize>>,
    /// Each mechanism's limits engaged at the start of the current step.
    engaged_at_step_start: Vec<Vec<Vec<bool>>>,
    /// Limits hit since the stepper last took them into the run's output.
    joint_events: Vec<JointEvent>,
}

/// How many predictions are kept.
const PREDICTIONS_KEPT: usize = 32;

impl World {
    /// An empty world at t = 0.
    pub fn new() -> World {
        World::default()
    }

    /// Current time (s).
    pub fn time(&self) -> Real {
        self.time
    }

    /// Distance queries between meshes the first-contact search has made so far.
    pub fn distance_queries(&self) -> u64 {
        self.distance_queries.load(Ordering::Relaxed)
    }

    /// Parts of meshes (pairs of tree nodes or of triangles) the clearance fronts evaluated
    /// so far: the work that stands in for most distance queries.
    pub fn clearance_evaluations(&self) -> u64 {
        self.clearance_evaluations.load(Ordering::Relaxed)
    }

    /// Clearance-front entries looked at so far (each a bound of a few dozen flops).
    pub fn clearance_checks(&self) -> u64 {
        self.clearance_checks.load(Ordering::Relaxed)
    }

    /// Number of bodies.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Body `i`'s current state.
    pub fn state(&self, i: usize) -> BodyState {
        self.bodies[i].body().state()
    }

    /// Adds a body; every new pair gets default contact parameters. Returns its index.
    pub fn add_body(
        &mut self,
        shape: Arc<MeshShape>,
        props: MassProperties,
        state: &BodyState,
    ) -> Result<usize> {
        if self.started {
            return Err(Error::invalid("bodies must be added before the first run"));
        }
        let body = RigidBody::new(props, state)?;
        Ok(self.push_body(shape, body, Motion::Free))
    }

    /// Adds a fixed obstacle (a wall, pole, barrier, kerb, tree) with its mesh (its frame, m)
    /// at `pose` (world): it takes part in first overlaps, timers and exchanges like a
    /// vehicle, with infinite mass and inertia, and never moves. Obstacles form no pair with
    /// each other. Returns its index.
    pub fn add_obstacle(&mut self, shape: Arc<MeshShape>, pose: &Isometry) -> Result<usize> {
        if self.started {
            return Err(Error::invalid(
                "obstacles must be added before the first run",
            ));
        }
        let t = pose.translation.vector;
        let q = pose.rotation.coords;
        if !(t.iter().all(|x| x.is_finite()) && q.iter().all(|x| x.is_finite())) {
            return Err(Error::invalid("an obstacle's pose has a non-finite number"));
        }
        for x in t.iter() {
            crate::error::require_coordinate("an obstacle's position", *x)?;
        }
        let body = RigidBody::immovable(Point::from(t), pose.rotation);
        Ok(self.push_body(shape, body, Motion::Fixed))
    }

    fn push_body(&mut self, shape: Arc<MeshShape>, body: RigidBody, motion: Motion) -> usize {
        let index = self.bodies.len();
        let fixed = matches!(motion, Motion::Fixed);
        for other in 0..index {
            if fixed && matches!(self.bodies[other].motion, Motion::Fixed) {
                continue; // two obstacles never meet
            }
            self.pairs.push(Pair {
                body1: other,
                body2: index,
                params: ContactParams::default(),
                phase: Phase::Apart,
                exchanges: 0,
                front: None,
                clear_until: Real::NEG_INFINITY,
                clear_jumps: [0, 0],
                closest: None,
                crossing: None,
                soft: None,
                soft_substeps: 1,
            });
        }
        self.bodies.push(WorldBody::new(shape, body, motion));
        self.slow_since.push(None);
        self.stopped_at.push(None);
        self.settled_since.push(None);
        index
    }

    /// True when body `i` is a fixed obstacle.
    pub fn is_obstacle(&self, i: usize) -> bool {
        matches!(self.bodies[i].motion, Motion::Fixed)
    }

    /// True when body `i` is rigid in the spring model: a fixed obstacle without stiffness
    /// data on any face (its spring rate is infinite; contact.rs, the depth of penetration
    /// and centroid modes).
    pub fn is_rigid(&self, i: usize) -> bool {
        self.is_obstacle(i) && self.bodies[i].stiffness.is_none()
    }

    /// Body `i`, or an error naming it when the world has no such body.
    fn body_mut(&mut self, i: usize) -> Result<&mut WorldBody> {
        let n = self.bodies.len();
        self.bodies.get_mut(i).ok_or_else(|| {
            Error::invalid(format!("it does not exist (the world has {n} bodies)"))
                .at(Place::body(i))
        })
    }

    /// Gives body `i` wheels, a tyre and driver inputs (used when the world has a ground).
    pub fn set_vehicle(&mut self, i: usize, spec: VehicleSpec) -> Result<()> {
        if self.started {
            return Err(Error::invalid("wheels must be given before the first run"));
        }
        let wb = self.body_mut(i)?;
        if matches!(wb.motion, Motion::Fixed) {
            return Err(
                Error::invalid("it is a fixed obstacle: it has no wheels".to_string())
                    .at(Place::body(i)),
            );
        }
        spec.validate(Some(wb.shape.aabb()), wb.body().props().mass())?;
        wb.vehicle = Some(Arc::new(spec));
        Ok(())
    }

    /// Puts the world on the ground (gravity along -z, the bodies on their wheels or their
    /// bodies); without it every body moves torque-free.
    pub fn set_ground(&mut self, ground: Ground) -> Result<()> {
        if self.started {
            return Err(Error::invalid(
                "the ground must be set before the first run",
            ));
        }
        self.ground = Some(ground);
        Ok(())
    }

    /// The ground, if any.
    pub fn ground(&self) -> Option<&Ground> {
        self.ground.as_ref()
    }

    /// Number of wheels of body `i` that run on the ground (0 without ground or wheels).
    pub fn wheel_count(&self, i: usize) -> usize {
        match &self.bodies[i].motion {
            Motion::OnGround(g) => g.deflections.len(),
            _ => 0,
        }
    }

    /// Sets up every body's motion for the first run: on the ground when the world has one.
    fn start_motion(&mut self) -> Result<()> {
        if self.ground.is_none() {
            return Ok(());
        }
        let ground = self.ground.as_ref().expect("checked above");
        for (i, wb) in self.bodies.iter_mut().enumerate() {
            if matches!(wb.motion, Motion::Fixed) {
                continue;
            }
            let mass = wb.body().props().mass();
            let contact = BodyContact::new(&wb.shape, mass, mass, wb.vehicle.as_deref())?
                .with_friction(wb.ground_friction);
            let on_ground = OnGround::new(wb.vehicle.clone(), Arc::new(contact));
            if let Some((depth, p)) = on_ground.deepest(wb.body(), ground) {
                if depth > PLACEMENT_TOLERANCE {
                    return Err(Error::initial_overlap(format!(
                        "it starts {depth:.3} m into the ground (its lowest point outside \
                         the wheels at ({:.3}, {:.3}, {:.3}) m): the ground's contact would \
                         throw it out. Place it higher (the CG height), or give its wheels the \
                         CG height and radius that carry the body clear of the road",
                        p.x, p.y, p.z
                    ))
                    .at(Place::body(i)));
                }
            }
            wb.motion = Motion::OnGround(Box::new(on_ground));
        }
        Ok(())
    }

    /// How many times the bodies' velocities have jumped, in all ([`WorldBody::jumps`]).
    fn jumps(&self) -> u64 {
        self.bodies.iter().map(WorldBody::jumps).sum()
    }

    /// Body `i` as it will be `dt` s from now (or was, for dt < 0, within the current step),
    /// moving as the run moves it. For a body on the ground an error (a wheel off the
    /// terrain) is kept for the stepper and the torque-free prediction returned meanwhile.
    /// A fixed body, and a torque-free one now (dt = 0), is the body itself, not a copy.
    fn predicted(&self, i: usize, dt: Real) -> Cow<'_, RigidBody> {
        let wb = &self.bodies[i];
        match &wb.motion {
            Motion::Free if dt == 0.0 => Cow::Borrowed(wb.body()),
            Motion::Free => Cow::Owned(wb.body().advanced(dt)),
            Motion::Fixed => Cow::Borrowed(wb.body()),
            Motion::OnGround(_) => Cow::Owned(
                self.predicted_on_ground(i, dt)
                    .map_or_else(|| wb.body().advanced(dt), |p| p.state),
            ),
        }
    }

    /// A prediction of body `i` (on the ground) `dt` s from now, from the kept ones when
    /// there; None (the error kept for the stepper) when a wheel leaves the terrain.
    fn predicted_on_ground(&self, i: usize, dt: Real) -> Option<Prediction> {
        let key = PredictionKey::new(i, self.time, dt, self.jumps());
        if let Some(p) = self.predictions.find(&key) {
            return Some(p);
        }
        if let Some(g) = self.mechanism_of.get(i).copied().flatten() {
            return self.predicted_mechanism(g, i, dt, key);
        }
        let wb = &self.bodies[i];
        match &wb.motion {
            Motion::OnGround(g) => {
                let ground = self
                    .ground
                    .as_ref()
                    .expect("a body on the ground has a ground");
                let (mut body, mut motion, from, span) = if dt >= 0.0 {
                    (wb.body().clone(), g.as_ref().clone(), self.time, dt)
                } else {
                    let (t0, states) = self
                        .step_start
                        .as_ref()
                        .expect("a step is under way when predicting backwards");
                    let (b, m) = &states[i];
                    let Motion::OnGround(g0) = m else {
                        unreachable!("motions do not change kind during a run")
                    };
                    (b.clone(), g0.as_ref().clone(), *t0, self.time + dt - t0)
                };
                let advanced = if dt >= 0.0 {
                    motion
                        .advance_bounded(&mut body, ground, from, span)
                        .map(Some)
                } else {
                    motion
                        .advance(&mut body, ground, from, span.max(0.0))
                        .map(|_| None)
                };
                let bound = match advanced {
                    Ok(bound) => bound,
                    Err(e) => {
                        let e = e.at(Place::body(i));
                        self.deferred.lock().expect("not poisoned").get_or_insert(e);
                        return None;
                    }
                };
                let p = Prediction {
                    key,
                    state: body,
                    motion,
                    bound,
                    mechanism: None,
                };
                self.predictions.keep(p.clone(), self.predictions_kept());
                Some(p)
            }
            _ => None,
        }
    }

    /// Sets body `i`'s face stiffness (used by automatic dt_p, the stiffness centroid and
    /// reported per impact).
    pub fn set_stiffness(&mut self, i: usize, stiffness: Stiffness) -> Result<()> {
        let body = self.body_mut(i)?;
        body.stiffness = stiffness;
        Ok(())
    }

    /// Gives moving body `i` its own friction with the ground (in (0, 2]), in place of the
    /// ground's body friction: a person's clothing on the road. Before the first run.
    pub fn set_ground_friction(&mut self, i: usize, mu: Real) -> Result<()> {
        if self.started {
            return Err(Error::invalid(
                "a body's ground friction must be set before the first run",
            ));
        }
        crate::ground::check_body_friction("ground friction", mu)
            .map_err(|e| e.at(Place::body(i)))?;
        let body = self.body_mut(i)?;
        if matches!(body.motion, Motion::Fixed) {
            return Err(Error::invalid(
                "it is a fixed obstacle: it does not slide on the ground".to_string(),
            )
            .at(Place::body(i)));
        }
        body.ground_friction = Some(mu);
        Ok(())
    }

    /// An error when the pair's parameters need face stiffness that a body lacks.
    fn check_stiffness(&self, body1: usize, body2: usize, params: &ContactParams) -> Result<()> {
        let side = |i: usize| (i, &self.bodies[i].stiffness, self.is_obstacle(i));
        params.check_stiffness([side(body1), side(body2)])
    }

    /// Makes bodies `body1` and `body2` never collide: their pair is dropped (no overlap
    /// search, no contact, no exchange), as a joint without `collide` drops it.
    pub fn set_no_contact(&mut self, body1: usize, body2: usize) -> Result<()> {
        let n = self.bodies.len();
        if body1 >= n || body2 >= n || body1 == body2 {
            return Err(Error::invalid(format!(
                "no-contact pair ({body1}, {body2}) must name two different bodies among 0..{n}"
            )));
        }
        let key = (body1.min(body2), body1.max(body2));
        self.pairs
            .retain(|p| (p.body1.min(p.body2), p.body1.max(p.body2)) != key);
        Ok(())
    }

    /// Gives the pair a compliant contact (soft.rs) in place of the timer and the exchange;
    /// its friction and normal come from the pair's contact parameters.
    pub fn set_soft_contact(
        &mut self,
        body1: usize,
        body2: usize,
        soft: SoftContact,
    ) -> Result<()> {
        soft.validate()?;
        let key = (body1.min(body2), body1.max(body2));
        let pair = self
            .pairs
            .iter_mut()
            .find(|p| (p.body1.min(p.body2), p.body1.max(p.body2)) == key)
            .ok_or_else(|| {
                Error::invalid(
                    "they form no pair (joined, never colliding, two \
                     obstacles or not in the world): they take no soft contact"
                        .to_string(),
                )
                .at(Place::bodies(body1, body2))
            })?;
        pair.soft = Some(soft);
        Ok(())
    }

    /// Sets the contact parameters of the pair; the normal points from `body1` into `body2`.
    pub fn set_contact(&mut self, body1: usize, body2: usize, params: ContactParams) -> Result<()> {
        let n = self.bodies.len();
        if body1 >= n || body2 >= n || body1 == body2 {
            return Err(Error::invalid(format!(
                "contact ({body1}, {body2}) must name two different bodies among 0..{n}"
            )));
        }
        params.validate()?;
        self.check_stiffness(body1, body2, &params)?;
        if let CentroidMode::Body { body, .. } = params.centroid {
            if body != body1 && body != body2 {
                return Err(Error::invalid(format!(
                    "the centroid is fixed in body {body}, which is not in the pair ({body1}, {body2})"
                )));
            }
        }
        let pair = self
            .pairs
            .iter_mut()
            .find(|p| (p.body1, p.body2) == (body1, body2) || (p.body1, p.body2) == (body2, body1))
            .ok_or_else(|| {
                Error::invalid(
                    "they are joined by a joint and do not collide: give \
                     the joint collide = true to set their contact"
                        .to_string(),
                )
                .at(Place::bodies(body1, body2))
            })?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Matrix;

    /// A 1 m, 1,000 kg box sliding along x at 5 m/s on the plane z = 0, after a first run
    /// of 0.01 s (which puts it on the ground).
    fn sliding_box() -> World {
        let mut w = World::new();
        w.set_ground(Ground::plane(0.0).unwrap()).unwrap();
        let props = MassProperties::new(1000.0, Matrix::identity() * (1000.0 / 6.0)).unwrap();
        let state = BodyState {
            position: Point::new(0.0, 0.0, 0.5),
            orientation: crate::math::Rotation::identity(),
            velocity: Vector::x() * 5.0,
            angular_velocity: Vector::zeros(),
        };
        let cube = Arc::new(MeshShape::cuboid(Vector::zeros(), Vector::repeat(0.5)));
        w.add_body(cube, props, &state).unwrap();
        w.run(0.01, 1e-3).unwrap();
        w
    }

    #[test]
    fn a_kept_prediction_is_not_used_after_an_impulse_changed_the_body() {
        let mut w = sliding_box();
        let before = w.predicted(0, 0.01).into_owned();
        assert_eq!(w.predicted(0, 0.01).velocity(), before.velocity(), "kept");
        // 1,000 N s along y at the CG: +1 m/s sideways, at the same instant.
        let cg = w.bodies[0].body().position();
        w.bodies[0].apply_impulse(&(Vector::y() * 1000.0), &cg);
        let after = w.predicted(0, 0.01).into_owned();
        assert!(after.velocity().y > 0.9, "{:?}", after.velocity());
        // The same as a prediction that was never kept.
        w.predictions = Predictions::default();
        let fresh = w.predicted(0, 0.01);
        assert_eq!(after.velocity(), fresh.velocity());
        assert_eq!(after.position(), fresh.position());
    }
}
