//! The world: bodies with meshes, per-pair contact state, the stepper and the event log.
//!
//! A run advances on the grid t_start + k dt, stopping early at every first overlap
//! (found by conservative advancement, then bisection to `TIME_TOLERANCE`) and landing
//! exactly on every exchange instant t0 + dt_p. Per pair the phases are:
//! apart -> timer (meshes pass through each other) -> engaged (after an exchange, while
//! the meshes overlap) -> apart on separation, or -> timer again when the relative velocity
//! at the centroid along the normal turns closing (a secondary exchange).

use std::sync::Arc;

use crate::body::{BodyState, MassProperties, RigidBody};
use crate::contact::{
    CentroidMode, ContactParams, DepthOfPenetration, NormalMode, MAX_DEPTH_OF_PENETRATION,
    TYPICAL_DEPTH_OF_PENETRATION,
};
use crate::error::{require_finite, Error, Result};
use crate::impulse::ImpulseProblem;
use crate::math::{Aabb, Isometry, Matrix, Point, Real, Vector};
use crate::overlap::{
    overlap_region, shapes_overlap, surface_distance, surfaces_intersect, OverlapRegion,
    QueryWorkspace,
};
use crate::shape::MeshShape;
use crate::stiffness::{effective_mass, Face, Stiffness};
use parry3d_f64::bounding_volume::BoundingVolume;

/// First-overlap instants are resolved to this (s).
pub const TIME_TOLERANCE: Real = 1e-9;
/// Smallest conservative-advancement step (s), and as a fraction of the step searched:
/// a graze shorter than this may be skipped (surfaces within speed x this of each other).
const MIN_ADVANCE: Real = 1e-6;
const MIN_ADVANCE_FRACTION: Real = 1e-3;
/// Separation instants are resolved to this (s).
const SEPARATION_TOLERANCE: Real = 1e-6;
/// The automatic normal of a first exchange is the overlap's volume normal taken while the
/// overlap is at most this deep (m): at the exchange a deep, narrow overlap (an offset
/// frontal) puts the side walls that sank into each other ahead of the faces that met, and
/// its volume normal turns toward the side (52 deg for two boxes 0.9 m offset, 1.16 m deep).
pub const NORMAL_DEPTH: Real = 0.02;
/// A relative normal velocity above this (m/s) counts as closing again.
const CLOSING_TOLERANCE: Real = 1e-6;
/// Most steps one run may take.
const MAX_STEPS: Real = 1e8;
/// Most conservative-advancement iterations in one step before giving up.
const MAX_ADVANCE_ITERATIONS: usize = 100_000;

/// What happened to a pair, besides impulse exchanges.
#[derive(Clone, Debug, PartialEq)]
pub enum ContactEventKind {
    /// The meshes first overlap; a timer starts.
    FirstOverlap,
    /// The relative velocity at the centroid turned closing while engaged; a timer starts.
    ClosingAgain,
    /// The meshes no longer overlap.
    Separation,
    /// The timer expired but no impulse was exchanged (the reason says why).
    NoExchange(String),
}

/// One entry of the contact log.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactEvent {
    /// World index of body 1 of the pair.
    pub body1: usize,
    /// World index of body 2.
    pub body2: usize,
    /// When (s).
    pub time: Real,
    /// What.
    pub kind: ContactEventKind,
}

/// One impulse exchange, world frame, SI.
#[derive(Clone, Debug, PartialEq)]
pub struct Impact {
    /// World index of body 1 (the normal points from it into body 2).
    pub body1: usize,
    /// World index of body 2.
    pub body2: usize,
    /// When the timer started (s): the first overlap, or the closing-again instant.
    pub first_contact_time: Real,
    /// The exchange instant (s).
    pub time: Real,
    /// The depth-of-penetration time used (s): exchange time minus timer start.
    pub depth_of_penetration: Real,
    /// How it was chosen: the pair's fixed value, or automatic (sqrt(m'/k')).
    pub depth_of_penetration_mode: DepthOfPenetration,
    /// True for an exchange after the first one of an engagement.
    pub secondary: bool,
    /// Impulse centroid P (m).
    pub centroid: Point,
    /// Unit normal from body 1 into body 2.
    pub normal: Vector,
    /// Impulse on body 2 (N s); body 1 receives its negative.
    pub impulse: Vector,
    /// True for a sliding impact.
    pub sliding: bool,
    /// CG velocities of bodies 1 and 2 before and after (m/s).
    pub velocity_before: [Vector; 2],
    /// See `velocity_before`.
    pub velocity_after: [Vector; 2],
    /// Angular velocities before and after (rad/s).
    pub angular_velocity_before: [Vector; 2],
    /// See `angular_velocity_before`.
    pub angular_velocity_after: [Vector; 2],
    /// u at P before: body 1's point velocity minus body 2's (m/s).
    pub relative_velocity_before: Vector,
    /// u at P after (m/s).
    pub relative_velocity_after: Vector,
    /// Kinetic energy lost (J).
    pub energy_dissipated: Real,
    /// The overlap region S (m).
    pub region_points: Vec<Point>,
    /// Contact frame: rows n, t (horizontal tangent), b = n x t.
    pub contact_frame: Matrix,
    /// Extent of S in the contact frame: minimum (m).
    pub region_min: Vector,
    /// Extent of S in the contact frame: maximum (m).
    pub region_max: Vector,
    /// The struck face of body 1 (facing +n) and of body 2 (facing -n).
    pub struck_faces: [Face; 2],
    /// Overlap width W: extent of S along the contact tangent t (m).
    pub overlap_width: Real,
    /// Spring rates k_i = B_i W of the struck faces (N/m), when both have stiffness data.
    pub spring_rates: Option<[Real; 2]>,
    /// Effective masses of bodies 1 and 2 along n at the centroid (kg).
    pub effective_mass: [Real; 2],
    /// When the overlap's volume normal behind `normal` was taken (s): early in the timer
    /// for a first exchange (overlap at most [`NORMAL_DEPTH`] deep), else the exchange.
    pub normal_time: Real,
    /// Remarks on this exchange (e.g. an automatic dt_p outside the typical 10-60 ms).
    pub notes: Vec<String>,
}

/// Where and how a pair touches at one instant (world frame, SI).
#[derive(Clone, Debug)]
struct ContactGeometry {
    region: OverlapRegion,
    normal: Vector,
    /// Rows n, t, b.
    frame: Matrix,
    region_min: Vector,
    region_max: Vector,
    centroid: Point,
    faces: [Face; 2],
    width: Real,
    spring_rates: Option<[Real; 2]>,
    effective_mass: [Real; 2],
    /// When the volume normal was taken, if not at these states.
    normal_time: Option<Real>,
}

impl ContactGeometry {
    /// sqrt(m'/k') (s) from the reduced effective mass and the series spring rate; infinite
    /// without stiffness data or contact width.
    fn spring_time(&self) -> Real {
        let Some([k1, k2]) = self.spring_rates else {
            return Real::INFINITY;
        };
        let [m1, m2] = self.effective_mass;
        let k = k1 * k2 / (k1 + k2);
        let m = m1 * m2 / (m1 + m2);
        if k > 0.0 && m.is_finite() {
            (m / k).sqrt()
        } else {
            Real::INFINITY
        }
    }
}

/// What a run returns: samples of every body's state and the logs.
#[derive(Clone, Debug, Default)]
pub struct RunOutput {
    /// Sample times (s): every grid step end, every first overlap and every exchange.
    pub times: Vec<Real>,
    /// `states[k][i]`: body i at `times[k]` (after any exchange at that instant).
    pub states: Vec<Vec<BodyState>>,
    /// Impulse exchanges in time order.
    pub impacts: Vec<Impact>,
    /// First overlaps, separations, closings and skipped exchanges in time order.
    pub contacts: Vec<ContactEvent>,
}

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

    /// [`World::run`] calling `progress(t)` (the current time, s) after every step; when it
    /// returns false the run stops with an error (an interrupted run has no output). The hook
    /// cannot change the results: a run with a hook gives the same bits as one without.
    pub fn run_with_progress(
        &mut self,
        duration: Real,
        dt: Real,
        progress: &mut dyn FnMut(Real) -> bool,
    ) -> Result<RunOutput> {
        require_finite("duration", duration)?;
        require_finite("dt", dt)?;
        if duration < 0.0 {
            return Err(Error::parameter("duration", duration, "it must be >= 0 s"));
        }
        if dt <= 0.0 {
            return Err(Error::parameter("dt", dt, "the time step must be > 0 s"));
        }
        if duration / dt > MAX_STEPS {
            return Err(Error::parameter(
                "dt",
                dt,
                "duration / dt exceeds 1e8 steps: use a larger step",
            ));
        }
        if !self.started {
            for p in &self.pairs {
                self.check_stiffness(p.body1, p.body2, &p.params)?;
            }
            self.check_initial_overlaps()?;
            self.started = true;
        }
        let t_start = self.time;
        let t_end = t_start + duration;
        let steps = (duration / dt).ceil() as usize;
        let mut out = RunOutput::default();
        out.times.reserve(steps + 8);
        out.states.reserve(steps + 8);
        self.record(&mut out);
        let mut k = 1usize;
        while self.time < t_end {
            let grid = if k >= steps {
                t_end
            } else {
                t_start + k as Real * dt
            };
            let mut target = grid;
            for p in &self.pairs {
                if let Phase::Timer { exchange_at, .. } = p.phase {
                    target = target.min(exchange_at);
                }
            }
            target = target.max(self.time);
            // The earliest first overlap among apart pairs inside (time, target].
            let mut earliest: Option<(Real, usize)> = None;
            for pi in 0..self.pairs.len() {
                if !matches!(self.pairs[pi].phase, Phase::Apart) {
                    continue;
                }
                let horizon = earliest.map_or(target, |(t, _)| t);
                if let Some(t) = self.first_contact(pi, horizon)? {
                    if earliest.is_none_or(|(te, _)| t < te) {
                        earliest = Some((t, pi));
                    }
                }
            }
            if let Some((tc, pi)) = earliest {
                self.advance_to(tc);
                let (b1, b2) = (self.pairs[pi].body1, self.pairs[pi].body2);
                out.contacts.push(ContactEvent {
                    body1: b1,
                    body2: b2,
                    time: tc,
                    kind: ContactEventKind::FirstOverlap,
                });
                self.pairs[pi].exchanges = 0;
                self.start_timer(pi, tc, None, &mut out);
                self.record(&mut out);
                continue;
            }
            let t_prev = self.time;
            self.advance_to(target);
            for pi in 0..self.pairs.len() {
                match self.pairs[pi].phase {
                    Phase::Timer { exchange_at, .. } if exchange_at <= self.time => {
                        self.exchange(pi, &mut out)
                    }
                    Phase::Engaged { .. } => self.follow_engaged(pi, t_prev, &mut out),
                    _ => {}
                }
            }
            self.record(&mut out);
            if target == grid {
                k += 1;
            }
            if !progress(self.time) {
                return Err(Error::Simulation(format!(
                    "the run was interrupted at t = {} s",
                    self.time
                )));
            }
        }
        Ok(out)
    }

    fn record(&self, out: &mut RunOutput) {
        if out.times.last() == Some(&self.time) {
            out.states.pop();
            out.times.pop();
        }
        out.times.push(self.time);
        out.states
            .push(self.bodies.iter().map(|b| b.body.state()).collect());
    }

    fn advance_to(&mut self, t: Real) {
        let dt = t - self.time;
        if dt > 0.0 {
            for b in &mut self.bodies {
                b.body.advance(dt);
            }
        }
        self.time = t;
    }

    fn check_initial_overlaps(&mut self) -> Result<()> {
        for p in &self.pairs {
            let (a, b) = (&self.bodies[p.body1], &self.bodies[p.body2]);
            if shapes_overlap(
                &a.shape,
                &a.body.pose(),
                &b.shape,
                &b.body.pose(),
                &mut self.ws,
            ) {
                return Err(Error::InitialOverlap(format!(
                    "bodies {} and {} already overlap at the start of the run: place them apart \
                     (the engine starts every contact at a first overlap it observes)",
                    p.body1, p.body2
                )));
            }
        }
        Ok(())
    }

    /// Poses of the pair's bodies `dt` s after the current time.
    fn poses_after(&self, pair: &Pair, dt: Real) -> (Isometry, Isometry) {
        (
            self.bodies[pair.body1].body.advanced(dt).pose(),
            self.bodies[pair.body2].body.advanced(dt).pose(),
        )
    }

    /// Box swept by a body over the next `dt` s (world).
    fn swept_box(&self, i: usize, dt: Real) -> Aabb {
        let wb = &self.bodies[i];
        let b0 = wb.body.pose();
        let b1 = wb.body.advanced(dt).pose();
        if wb.body.angular_speed_bound() == 0.0 {
            wb.shape
                .aabb()
                .transform_by(&b0)
                .merged(&wb.shape.aabb().transform_by(&b1))
        } else {
            let r = Vector::repeat(wb.shape.radius());
            let (c0, c1) = (
                Point::from(b0.translation.vector),
                Point::from(b1.translation.vector),
            );
            Aabb::new(c0.inf(&c1) - r, c0.sup(&c1) + r)
        }
    }

    /// The first instant in (time, horizon] at which the apart pair's surfaces meet.
    fn first_contact(&mut self, pi: usize, horizon: Real) -> Result<Option<Real>> {
        let pair = self.pairs[pi].clone();
        let span = horizon - self.time;
        if span <= 0.0 {
            return Ok(None);
        }
        if !self
            .swept_box(pair.body1, span)
            .intersects(&self.swept_box(pair.body2, span))
        {
            return Ok(None);
        }
        let (wb1, wb2) = (&self.bodies[pair.body1], &self.bodies[pair.body2]);
        let (s1, s2) = (wb1.shape.clone(), wb2.shape.clone());
        // Bound on how fast any point of one surface can approach the other (m/s).
        let speed = (wb1.body.velocity() - wb2.body.velocity()).norm()
            + wb1.body.angular_speed_bound() * s1.radius()
            + wb2.body.angular_speed_bound() * s2.radius();
        if speed == 0.0 {
            return Ok(None);
        }
        let mut lo = 0.0; // offset from self.time known apart
        let mut t = 0.0;
        let min_advance = MIN_ADVANCE.max(MIN_ADVANCE_FRACTION * span);
        for _ in 0..MAX_ADVANCE_ITERATIONS {
            let (p1, p2) = self.poses_after(&pair, t);
            let cap = (span - t) * speed * (1.0 + 1e-9) + 1e-12;
            let d = surface_distance(&s1, &p1, &s2, &p2, cap, &mut self.ws);
            // Zero distance without a crossing is a touch (e.g. coplanar faces on the ground):
            // not an overlap, so keep advancing by the smallest step.
            if d == 0.0 && surfaces_intersect(&s1, &p1, &s2, &p2, &mut self.ws) {
                if t == 0.0 {
                    return Ok(Some(self.time));
                }
                let mut hi = t;
                while hi - lo > TIME_TOLERANCE {
                    let mid = 0.5 * (lo + hi);
                    let (p1, p2) = self.poses_after(&pair, mid);
                    if surfaces_intersect(&s1, &p1, &s2, &p2, &mut self.ws) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                return Ok(Some(self.time + hi));
            }
            if t >= span || t + d / speed > span {
                return Ok(None);
            }
            lo = t;
            t = (t + (d / speed).max(min_advance)).min(span);
        }
        Err(Error::Simulation(format!(
            "the first-contact search for bodies {} and {} did not converge near t = {} s",
            pair.body1, pair.body2, self.time
        )))
    }

    /// Starts pair `pi`'s timer at `started` (s, at most now); exchanges at once when it has
    /// already expired. A secondary timer (an engaged pair closing again) keeps the engaged
    /// normal `engaged_normal` (body 1's frame), along which it was found closing; a first
    /// one takes the volume normal of the shallow overlap.
    fn start_timer(
        &mut self,
        pi: usize,
        started: Real,
        engaged_normal: Option<Vector>,
        out: &mut RunOutput,
    ) {
        let secondary = engaged_normal.is_some();
        let cap = match self.pairs[pi].params.depth_of_penetration {
            DepthOfPenetration::Fixed(dtp) => dtp,
            DepthOfPenetration::Auto => MAX_DEPTH_OF_PENETRATION,
        };
        let mut early_normal = match engaged_normal {
            Some(n) => Some((n, started)),
            None => self.early_normal(pi, started, cap),
        };
        let (dtp, notes) = match self.pairs[pi].params.depth_of_penetration {
            DepthOfPenetration::Fixed(dtp) => (dtp, Vec::new()),
            DepthOfPenetration::Auto => {
                let (dtp, notes) = self.auto_depth_of_penetration(pi, started, early_normal);
                if early_normal.is_some_and(|(_, t)| t > started + dtp) {
                    // The exchange comes before the overlap is NORMAL_DEPTH deep: use its own.
                    early_normal = None;
                }
                (dtp, notes)
            }
        };
        let exchange_at = (started + dtp).max(self.time);
        self.pairs[pi].phase = Phase::Timer {
            started,
            exchange_at,
            secondary,
            notes,
            early_normal,
        };
        if exchange_at <= self.time {
            self.exchange(pi, out);
        }
    }

    /// The volume normal (body 1's frame) of pair `pi`'s overlap once it is at most
    /// NORMAL_DEPTH deep (no later than `cap` s after `started`), and its time; None when
    /// the meshes no longer overlap then or the normal vanishes.
    fn early_normal(&self, pi: usize, started: Real, cap: Real) -> Option<(Vector, Real)> {
        let pair = &self.pairs[pi];
        let (wb1, wb2) = (&self.bodies[pair.body1], &self.bodies[pair.body2]);
        // The fastest two surface points can approach now (m/s): over the few ms this covers
        // the overlap grows by at most about NORMAL_DEPTH.
        let speed = (wb1.body.velocity() - wb2.body.velocity()).norm()
            + wb1.body.angular_velocity().norm() * wb1.shape.radius()
            + wb2.body.angular_velocity().norm() * wb2.shape.radius();
        let dt = if speed > 0.0 {
            (NORMAL_DEPTH / speed).min(cap)
        } else {
            cap
        };
        let offset = started - self.time + dt;
        let (b1, b2) = (wb1.body.advanced(offset), wb2.body.advanced(offset));
        let (pose1, pose2) = (b1.pose(), b2.pose());
        let n = overlap_region(&wb1.shape, &pose1, &wb2.shape, &pose2).volume_normal()?;
        Some((pose1.inverse_transform_vector(&n), started + dt))
    }

    /// The automatic dt_p of pair `pi` whose timer starts at `started`: the dt in
    /// (0, 0.060] s with dt = sqrt(m'/k') evaluated at started + dt, where the bodies will be
    /// (they move freely while the timer runs). Bisection to `TIME_TOLERANCE`; clamped to
    /// 0.060 s, with a note, when sqrt(m'/k') is still longer there.
    fn auto_depth_of_penetration(
        &self,
        pi: usize,
        started: Real,
        early_normal: Option<(Vector, Real)>,
    ) -> (Real, Vec<String>) {
        let pair = &self.pairs[pi];
        let offset = started - self.time;
        let spring_time = |dt: Real| -> Real {
            let b1 = self.bodies[pair.body1].body.advanced(offset + dt);
            let b2 = self.bodies[pair.body2].body.advanced(offset + dt);
            // Before the early normal's instant the overlap's own normal is used.
            let normal = early_normal
                .filter(|(_, t)| *t <= started + dt)
                .map(|(n, t)| (b1.pose() * n, t));
            self.contact_geometry(pair, &b1, &b2, normal)
                .map_or(Real::INFINITY, |g| g.spring_time())
        };
        let max = MAX_DEPTH_OF_PENETRATION;
        let at_max = spring_time(max);
        if at_max >= max {
            return (
                max,
                vec![format!(
                    "automatic depth of penetration: sqrt(m'/k') = {:.1} ms at 60 ms after the \
                     first overlap, longer than the accepted 60 ms; clamped to 60 ms",
                    at_max * 1e3
                )],
            );
        }
        let (mut lo, mut hi) = (0.0, max);
        while hi - lo > TIME_TOLERANCE {
            let mid = 0.5 * (lo + hi);
            if mid < spring_time(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let mut notes = Vec::new();
        let (typical_lo, typical_hi) = TYPICAL_DEPTH_OF_PENETRATION;
        if hi < typical_lo || hi > typical_hi {
            notes.push(format!(
                "automatic depth of penetration {:.2} ms lies outside the typical 10-60 ms",
                hi * 1e3
            ));
        }
        (hi, notes)
    }

    /// The pair's contact geometry with its bodies at the given states (world frame): the
    /// overlap region, normal, contact frame, centroid, struck faces, width, spring rates and
    /// effective masses. `volume_normal` replaces the region's own volume normal (world frame,
    /// with the time it was taken). None when the meshes do not overlap.
    fn contact_geometry(
        &self,
        pair: &Pair,
        b1: &RigidBody,
        b2: &RigidBody,
        volume_normal: Option<(Vector, Real)>,
    ) -> Option<ContactGeometry> {
        let (w1, w2) = (&self.bodies[pair.body1], &self.bodies[pair.body2]);
        let (pose1, pose2) = (b1.pose(), b2.pose());
        let region = overlap_region(&w1.shape, &pose1, &w2.shape, &pose2);
        if region.is_empty() {
            return None;
        }
        let bbox_center = {
            let (mut lo, mut hi) = (region.points[0], region.points[0]);
            for p in &region.points {
                lo = lo.inf(p);
                hi = hi.sup(p);
            }
            nalgebra::center(&lo, &hi)
        };
        let (volume_normal, normal_time) = volume_normal.map_or_else(
            || {
                let n = region.volume_normal().unwrap_or_else(|| {
                    // No usable inside area (e.g. open meshes): fall back on the approach direction.
                    let u = b1.point_velocity(&bbox_center) - b2.point_velocity(&bbox_center);
                    if u.norm() > 0.0 {
                        u.normalize()
                    } else {
                        (b2.position() - b1.position()).normalize()
                    }
                });
                (n, None)
            },
            |(n, t)| (n, Some(t)),
        );
        let normal = match &pair.params.normal {
            NormalMode::Volume => volume_normal,
            NormalMode::Fixed(v) => v.normalize(),
            NormalMode::Horizontal { pitch } => {
                let h = Vector::new(volume_normal.x, volume_normal.y, 0.0);
                if h.norm() < 1e-9 {
                    volume_normal
                } else {
                    h.normalize() * pitch.cos() + Vector::z() * pitch.sin()
                }
            }
        };
        let tangent = {
            let t = Vector::z().cross(&normal);
            if t.norm() > 1e-9 {
                t.normalize()
            } else {
                Vector::x().cross(&normal).normalize()
            }
        };
        let binormal = normal.cross(&tangent);
        let frame = Matrix::from_rows(&[
            normal.transpose(),
            tangent.transpose(),
            binormal.transpose(),
        ]);
        let (mut rmin, mut rmax) = (
            frame * region.points[0].coords,
            frame * region.points[0].coords,
        );
        for p in &region.points {
            let c = frame * p.coords;
            rmin = rmin.inf(&c);
            rmax = rmax.sup(&c);
        }
        let faces = [
            Face::facing(&pose1.inverse_transform_vector(&normal)),
            Face::facing(&pose2.inverse_transform_vector(&-normal)),
        ];
        let width = rmax.y - rmin.y;
        let spring_rates = match (w1.stiffness.face(faces[0]), w2.stiffness.face(faces[1])) {
            (Some(s1), Some(s2)) => Some([s1.spring_rate(width), s2.spring_rate(width)]),
            _ => None,
        };
        let centroid = match &pair.params.centroid {
            CentroidMode::Auto => Point::from(frame.transpose() * ((rmin + rmax) * 0.5)),
            CentroidMode::Stiffness => {
                // Body 1's undeformed surface is at the region's far end along +n, body 2's at
                // the near end: C1 = rmax.n - P.n, C2 = P.n - rmin.n, C1 : C2 = k2 : k1.
                let mut c = (rmin + rmax) * 0.5;
                if let Some([k1, k2]) = spring_rates {
                    if k1 + k2 > 0.0 {
                        c.x = rmax.x - k2 / (k1 + k2) * (rmax.x - rmin.x);
                    }
                }
                Point::from(frame.transpose() * c)
            }
            CentroidMode::World(p) => *p,
            CentroidMode::Body { body, point } => {
                if *body == pair.body1 {
                    pose1 * point
                } else {
                    pose2 * point
                }
            }
        };
        let effective_mass = [
            effective_mass(
                b1.props().mass(),
                &b1.world_inverse_inertia(),
                &(centroid - b1.position()),
                &normal,
            ),
            effective_mass(
                b2.props().mass(),
                &b2.world_inverse_inertia(),
                &(centroid - b2.position()),
                &normal,
            ),
        ];
        Some(ContactGeometry {
            region,
            normal,
            frame,
            region_min: rmin,
            region_max: rmax,
            centroid,
            faces,
            width,
            spring_rates,
            effective_mass,
            normal_time,
        })
    }

    /// Exchange the impulse of pair `pi` now (its timer expired).
    fn exchange(&mut self, pi: usize, out: &mut RunOutput) {
        let (started, secondary, notes, early_normal) = match &self.pairs[pi].phase {
            Phase::Timer {
                started,
                secondary,
                notes,
                early_normal,
                ..
            } => (*started, *secondary, notes.clone(), *early_normal),
            _ => return,
        };
        let pair = self.pairs[pi].clone();
        let (i1, i2) = (pair.body1, pair.body2);
        let skip = |world: &mut World, out: &mut RunOutput, why: &str, phase: Phase| {
            out.contacts.push(ContactEvent {
                body1: i1,
                body2: i2,
                time: world.time,
                kind: ContactEventKind::NoExchange(why.into()),
            });
            world.pairs[pi].phase = phase;
        };
        let (b1, b2) = (&self.bodies[i1].body, &self.bodies[i2].body);
        let normal = early_normal.map(|(n, t)| (b1.pose() * n, t));
        let Some(geometry) = self.contact_geometry(&pair, b1, b2, normal) else {
            skip(
                self,
                out,
                "the meshes no longer overlap at the exchange instant",
                Phase::Apart,
            );
            return;
        };
        let (pose1, pose2) = (b1.pose(), b2.pose());
        let (centroid, normal) = (geometry.centroid, geometry.normal);
        let r1 = centroid - b1.position();
        let r2 = centroid - b2.position();
        let u = b1.point_velocity(&centroid) - b2.point_velocity(&centroid);
        let problem = ImpulseProblem {
            inverse_mass_sum: 1.0 / b1.props().mass() + 1.0 / b2.props().mass(),
            inverse_inertia: [b1.world_inverse_inertia(), b2.world_inverse_inertia()],
            lever: [r1, r2],
            relative_velocity: u,
            normal,
            restitution: pair.params.restitution,
            friction: pair.params.friction,
            mode: pair.params.restitution_mode,
        };
        let engaged = Phase::Engaged {
            centroid_in: [
                pose1.inverse_transform_point(&centroid),
                pose2.inverse_transform_point(&centroid),
            ],
            normal_in_1: pose1.inverse_transform_vector(&normal),
        };
        let Some(solution) = problem.solve() else {
            skip(
                self,
                out,
                "the vehicles are not approaching at the centroid along the normal",
                engaged,
            );
            return;
        };
        let before = [b1.state(), b2.state()];
        let energy_before = b1.kinetic_energy() + b2.kinetic_energy();
        let j = solution.impulse;
        self.bodies[i1].body.apply_impulse(&(-j), &centroid);
        self.bodies[i2].body.apply_impulse(&j, &centroid);
        let (b1, b2) = (&self.bodies[i1].body, &self.bodies[i2].body);
        let after = [b1.state(), b2.state()];
        let energy_after = b1.kinetic_energy() + b2.kinetic_energy();
        let u_after = b1.point_velocity(&centroid) - b2.point_velocity(&centroid);
        out.impacts.push(Impact {
            body1: i1,
            body2: i2,
            first_contact_time: started,
            time: self.time,
            depth_of_penetration: self.time - started,
            depth_of_penetration_mode: pair.params.depth_of_penetration,
            secondary: secondary || pair.exchanges > 0,
            centroid,
            normal,
            impulse: j,
            sliding: solution.sliding,
            velocity_before: [before[0].velocity, before[1].velocity],
            velocity_after: [after[0].velocity, after[1].velocity],
            angular_velocity_before: [before[0].angular_velocity, before[1].angular_velocity],
            angular_velocity_after: [after[0].angular_velocity, after[1].angular_velocity],
            relative_velocity_before: u,
            relative_velocity_after: u_after,
            energy_dissipated: energy_before - energy_after,
            region_points: geometry.region.points,
            contact_frame: geometry.frame,
            region_min: geometry.region_min,
            region_max: geometry.region_max,
            struck_faces: geometry.faces,
            overlap_width: geometry.width,
            spring_rates: geometry.spring_rates,
            effective_mass: geometry.effective_mass,
            normal_time: geometry.normal_time.unwrap_or(self.time),
            notes,
        });
        self.pairs[pi].exchanges += 1;
        self.pairs[pi].phase = engaged;
    }

    /// Relative normal velocity (m/s, closing > 0) of an engaged pair `dt` s from now.
    fn closing_speed(
        &self,
        pair: &Pair,
        centroid_in: &[Point; 2],
        normal_in_1: &Vector,
        dt: Real,
    ) -> Real {
        let b1 = self.bodies[pair.body1].body.advanced(dt);
        let b2 = self.bodies[pair.body2].body.advanced(dt);
        let (p1, p2) = (b1.pose(), b2.pose());
        let c = nalgebra::center(&(p1 * centroid_in[0]), &(p2 * centroid_in[1]));
        let n = p1 * normal_in_1;
        (b1.point_velocity(&c) - b2.point_velocity(&c)).dot(&n)
    }

    /// After a step, an engaged pair either separates, turns closing again, or stays.
    fn follow_engaged(&mut self, pi: usize, t_prev: Real, out: &mut RunOutput) {
        let pair = self.pairs[pi].clone();
        let Phase::Engaged {
            centroid_in,
            normal_in_1,
        } = pair.phase
        else {
            return;
        };
        let (i1, i2) = (pair.body1, pair.body2);
        let (a, b) = (&self.bodies[i1], &self.bodies[i2]);
        if !shapes_overlap(
            &a.shape,
            &a.body.pose(),
            &b.shape,
            &b.body.pose(),
            &mut self.ws,
        ) {
            // Bisect the separation instant backwards from now (bodies move freely here).
            let (mut lo, mut hi) = (t_prev - self.time, 0.0);
            while hi - lo > SEPARATION_TOLERANCE {
                let mid = 0.5 * (lo + hi);
                let (p1, p2) = (
                    self.bodies[i1].body.advanced(mid).pose(),
                    self.bodies[i2].body.advanced(mid).pose(),
                );
                let (s1, s2) = (self.bodies[i1].shape.clone(), self.bodies[i2].shape.clone());
                if shapes_overlap(&s1, &p1, &s2, &p2, &mut self.ws) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            out.contacts.push(ContactEvent {
                body1: i1,
                body2: i2,
                time: self.time + hi,
                kind: ContactEventKind::Separation,
            });
            self.pairs[pi].phase = Phase::Apart;
            return;
        }
        if self.closing_speed(&pair, &centroid_in, &normal_in_1, 0.0) > CLOSING_TOLERANCE {
            // Find when it turned closing inside the step (s is smooth: bisection).
            let (mut lo, mut hi) = (t_prev - self.time, 0.0);
            while hi - lo > TIME_TOLERANCE {
                let mid = 0.5 * (lo + hi);
                let s = {
                    let b1 = self.bodies[i1].body.advanced(mid);
                    let b2 = self.bodies[i2].body.advanced(mid);
                    let (p1, p2) = (b1.pose(), b2.pose());
                    let c = nalgebra::center(&(p1 * centroid_in[0]), &(p2 * centroid_in[1]));
                    (b1.point_velocity(&c) - b2.point_velocity(&c)).dot(&(p1 * normal_in_1))
                };
                if s > CLOSING_TOLERANCE {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let started = self.time + hi;
            out.contacts.push(ContactEvent {
                body1: i1,
                body2: i2,
                time: started,
                kind: ContactEventKind::ClosingAgain,
            });
            self.start_timer(pi, started, Some(normal_in_1), out);
        }
    }
}
