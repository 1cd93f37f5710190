//! The schedule of a run: the step grid, stopping at first overlaps and exchange instants,
//! following engaged pairs, and the samples of every body's state.
//!
//! Every loop of a run is bounded: the steps (at most [`MAX_STEPS`]), the events at one
//! instant (at most [`MAX_EVENTS_PER_INSTANT`] per pair), the first-contact search and every
//! bisection; a bound that is hit ends the run with a simulation error
//! ([`crate::error::ErrorKind::Simulation`]) naming the pair and the time. The caller's hook
//! is asked after every step and inside the first-contact search, so an interrupt (Ctrl-C
//! from Python) is honoured within the hook's own polling interval.

use super::{Motion, Phase, World, WorldBody};
use crate::body::BodyState;
use crate::error::{require_finite, Error, Place, Result};
use crate::joint::JointSample;
use crate::math::Real;
use crate::motion::{joint_samples, WheelSample};

use super::events::{ContactEvent, ContactEventKind, RunOutput};

/// Most steps one run may take.
const MAX_STEPS: Real = 1e8;
/// Most events (first overlaps, exchanges) one pair may have at one instant before the run is
/// stopped as stuck: a healthy pair has at most a first overlap and an exchange there.
const MAX_EVENTS_PER_INSTANT: usize = 64;
/// Samples kept by default: every step of a run of at most this many steps, else about this
/// many (one every `ceil(steps / DEFAULT_SAMPLES)` steps); events are always kept.
pub const DEFAULT_SAMPLES: usize = 100_000;
/// Default limit of a run's history (bytes): 1 GiB. The Python result holds a copy of the
/// same size while it is built, so a run's peak is about twice this.
pub const DEFAULT_MAX_HISTORY_BYTES: u64 = 1 << 30;

/// A vehicle is at rest once its CG speed along the ground stays below this (m/s) ...
pub const REST_SPEED: Real = 0.05;
/// ... and its yaw rate below this (rad/s, 0.5 deg/s) ...
pub const REST_YAW_RATE: Real = 0.5 * std::f64::consts::PI / 180.0;
/// ... for this long (s) (docs/model.md, "Vehicles on the ground").
pub const REST_TIME: Real = 0.2;
/// A body smaller than 0.57 m from its CG to its box's farthest corner is slow enough in
/// yaw below this speed (m/s) over that distance (a pedestrian's hand, 0.1 m: 2.9 deg/s)
/// rather than below [`REST_YAW_RATE`]: no point of it turns faster. Settled, likewise, below
/// [`SETTLED_SPEED`] over that distance. A lying pedestrian's segments crept on the ground's
/// regularised friction at a few mm/s and turned at up to 1.3 deg/s for seconds before they
/// had static friction (docs/human.md, "Rest of a lying body"); a car, larger, keeps the
/// fixed rates.
pub const REST_TURN_SPEED: Real = 0.005;
/// A body faster than this along the ground (m/s) is moving again: its time to rest starts
/// over.
pub const MOVING_SPEED: Real = 10.0 * REST_SPEED;
/// A run until rest stops once, besides, every body on the ground has settled for
/// [`REST_TIME`]: its angular speed about every axis below this (rad/s, 2 deg/s) ... Speed and
/// yaw rate alone stopped a run while the car still rocked on its springs after a skid (wheel
/// loads 5 % off the axle shares), and a settled instant alone stopped a dropped car at the
/// bottom of its bounce (its CG 0.40 m up against a static 0.55 m); the rest time reported is
/// the one of travel and yaw.
pub const SETTLED_ANGULAR_SPEED: Real = 2.0 * std::f64::consts::PI / 180.0;
/// ... and its CG speed (vertical too) below this (m/s): a bounce on 1.3 Hz springs whose
/// speed stays under it for [`REST_TIME`] is under 1.5 mm high. At REST_SPEED a dropped car
/// ended its run 5 mm above its static height, still moving at 0.04 m/s.
pub const SETTLED_SPEED: Real = 0.01;

/// How a run stops and keeps its history of states.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// Interval between kept samples (s), rounded down to a whole number of steps (at least
    /// one). None: every step for runs of at most [`DEFAULT_SAMPLES`] steps, else about
    /// [`DEFAULT_SAMPLES`] evenly spaced samples. The start, the end, every first overlap and
    /// every exchange are kept whatever the interval.
    pub record_interval: Option<Real>,
    /// Largest history a run may keep (bytes, default [`DEFAULT_MAX_HISTORY_BYTES`]): a run
    /// whose estimate is larger is refused before it starts, with the interval that fits.
    pub max_history_bytes: u64,
    /// Stop as soon as every body on the ground is at rest (on the ground, speed along it
    /// below [`REST_SPEED`] and yaw rate below [`REST_YAW_RATE`] for [`REST_TIME`]) and settled
    /// as long ([`SETTLED_SPEED`], [`SETTLED_ANGULAR_SPEED`]); the duration is then the longest
    /// the run may take. Needs a ground.
    pub until_rest: bool,
    /// Keep the history of states (default true). False keeps only the last sample (the end
    /// of the run) besides the impacts, the contact log and the rest times: what a batch's
    /// summary needs, in memory that does not grow with the run. The run itself is the same
    /// bits either way (recording only reads the state).
    pub history: bool,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            record_interval: None,
            max_history_bytes: DEFAULT_MAX_HISTORY_BYTES,
            until_rest: false,
            history: true,
        }
    }
}

/// Bytes one sample takes: its time, every body's state and every wheel's.
fn sample_bytes(bodies: usize, wheels: usize, joints: usize) -> u64 {
    (std::mem::size_of::<Real>()
        + bodies * std::mem::size_of::<BodyState>()
        + wheels * std::mem::size_of::<WheelSample>()
        + joints * std::mem::size_of::<JointSample>()) as u64
}

/// Human-readable bytes (binary units, as the 1 GiB default).
fn show_bytes(b: u64) -> String {
    let b = b as Real;
    if b >= (1u64 << 30) as Real {
        format!("{:.2} GiB", b / (1u64 << 30) as Real)
    } else if b >= (1u64 << 20) as Real {
        format!("{:.1} MiB", b / (1u64 << 20) as Real)
    } else {
        format!("{:.1} KiB", b / 1024.0)
    }
}

impl RunOptions {
    /// Steps between kept samples for a run of `steps` steps of `dt` s.
    pub(crate) fn stride(&self, steps: usize, dt: Real) -> Result<usize> {
        match self.record_interval {
            None => Ok(steps.div_ceil(DEFAULT_SAMPLES).max(1)),
            Some(interval) => {
                require_finite("record_interval", interval)?;
                if interval <= 0.0 {
                    return Err(Error::parameter(
                        "record_interval",
                        interval,
                        "the recording interval must be > 0 s",
                    ));
                }
                // A relative hair of slack: 0.05 s / 1 ms is 49.999... in floats.
                Ok((((interval / dt) * (1.0 + 1e-9)).floor() as usize).max(1))
            }
        }
    }

    /// Checks that a run of `steps` steps of `dt` s keeping a sample every `stride` steps fits
    /// in `max_bytes`, else says which interval would.
    fn check_size(
        &self,
        steps: usize,
        stride: usize,
        dt: Real,
        bodies: usize,
        wheels: usize,
        joints: usize,
    ) -> Result<()> {
        // The start, the kept steps, the end; events come on top (a few per contact).
        let samples = (steps / stride + 2) as u64;
        let need = samples.saturating_mul(sample_bytes(bodies, wheels, joints));
        if need <= self.max_history_bytes {
            return Ok(());
        }
        let fits = (self.max_history_bytes / sample_bytes(bodies, wheels, joints))
            .saturating_sub(2)
            .max(1);
        let interval = dt * steps.div_ceil(fits as usize) as Real;
        Err(Error::invalid(format!(
            "the run would keep {samples} samples of {bodies} bodies ({}), more than the \
             history limit of {}: record less often (record_interval = {interval:.3e} s or \
             more fits), shorten the run, or raise the limit (max_history_bytes)",
            show_bytes(need),
            show_bytes(self.max_history_bytes)
        )))
    }
}

impl World {
    /// [`World::run`] calling `progress(t)` (the current time, s) after every step and while
    /// searching for a first overlap; when it returns false the run stops with an error (an
    /// interrupted run has no output). The hook cannot change the results: a run with a hook
    /// gives the same bits as one without.
    pub fn run_with_progress(
        &mut self,
        duration: Real,
        dt: Real,
        progress: &mut dyn FnMut(Real) -> bool,
    ) -> Result<RunOutput> {
        self.run_with_options(duration, dt, &RunOptions::default(), progress)
    }

    /// [`World::run_with_progress`] stopping and keeping the history as `options` say.
    pub fn run_with_options(
        &mut self,
        duration: Real,
        dt: Real,
        options: &RunOptions,
        progress: &mut dyn FnMut(Real) -> bool,
    ) -> Result<RunOutput> {
        let steps = self.check_run(duration, dt, options)?;
        let stride = options.stride(steps, dt)?;
        // Every run's step, not only the first's: a run resumed with another step is sized
        // again.
        self.size_soft_substeps(dt)?;
        self.start()?;
        let mut out = self.new_output(steps, stride, dt, options)?;
        if options.history {
            self.record(&mut out)?;
        }
        let t_start = self.time;
        let t_end = t_start + duration;
        // Events at the current instant per pair, to stop a pair that makes no progress.
        let mut at_instant = (self.time, vec![0usize; self.pairs.len()]);
        let mut k = 1usize;
        while self.time < t_end {
            if options.until_rest && self.all_at_rest() {
                break;
            }
            self.keep_step_start();
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
            // A soft pair pressing too stiffly for the step: the step's next sub-step (not
            // recorded unless something happens in it).
            let substep = self.soft_substep_end(grid, dt).filter(|&end| end < target);
            if let Some(end) = substep {
                target = end;
            }
            target = target.max(self.time);
            if let Some((offset, pi)) = self.earliest_first_overlap(target, progress)? {
                self.advance_by(offset)?;
                out.joint_events.append(&mut self.joint_events);
                self.count_event(&mut at_instant, pi)?;
                self.begin_contact(pi, &mut out);
                if options.history {
                    self.record(&mut out)?;
                }
                continue;
            }
            let t_prev = self.time;
            let (impacts, contacts, joint_events) = (
                out.impacts.len(),
                out.contacts.len(),
                out.joint_events.len(),
            );
            self.advance_to(target)?;
            out.joint_events.append(&mut self.joint_events);
            self.follow_pairs(t_prev, &mut at_instant, &mut out)?;
            if let Some(e) = self.deferred.lock().expect("not poisoned").take() {
                return Err(e);
            }
            self.track_rest();
            // At or past the grid point (never past it, but a step that could end beyond it
            // must not stall the count).
            let on_grid = target >= grid;
            let event = out.impacts.len() > impacts
                || out.contacts.len() > contacts
                || out.joint_events.len() > joint_events;
            let off_grid = !on_grid && substep.is_none();
            if options.history
                && (off_grid || event || (on_grid && (k % stride == 0 || k >= steps)))
            {
                self.record(&mut out)?;
            }
            if on_grid {
                k += 1;
            }
            if !progress(self.time) {
                return Err(interrupted(self.time));
            }
        }
        self.record(&mut out)?;
        self.rest_at_end(&mut out);
        self.step_start = None;
        Ok(out)
    }

    /// Checks a run's duration (s), step (s) and options; the number of grid steps.
    fn check_run(&self, duration: Real, dt: Real, options: &RunOptions) -> Result<usize> {
        let steps = check_run_length(duration, dt)?;
        if options.until_rest && self.ground.is_none() {
            return Err(Error::invalid(
                "a run until rest needs a ground (without one nothing slows the vehicles)",
            ));
        }
        Ok(steps)
    }

    /// The first run's set-up (nothing on a resumed run): the pairs' stiffness, the initial
    /// overlaps, the couplings' loads, the motion on the ground and the mechanisms.
    fn start(&mut self) -> Result<()> {
        if self.started {
            return Ok(());
        }
        for p in &self.pairs {
            self.check_stiffness(p.body1, p.body2, &p.params)?;
        }
        self.check_initial_overlaps()?;
        if self.ground.is_some() {
            self.carry_coupling_loads()?;
        }
        self.start_motion()?;
        self.build_mechanisms()?;
        self.started = true;
        Ok(())
    }

    /// An empty output for a run of `steps` grid steps of `dt` s sampled every `stride`-th,
    /// its memory reserved (a history first checked against its size limit).
    fn new_output(
        &self,
        steps: usize,
        stride: usize,
        dt: Real,
        options: &RunOptions,
    ) -> Result<RunOutput> {
        let wheel_counts: Vec<usize> = (0..self.bodies.len())
            .map(|i| self.wheel_count(i))
            .collect();
        let wheels: usize = wheel_counts.iter().sum();
        if options.history {
            options.check_size(
                steps,
                stride,
                dt,
                self.bodies.len(),
                wheels,
                self.joints.len(),
            )?;
        }
        let mut out = RunOutput {
            body_count: self.bodies.len(),
            wheel_counts,
            rest: vec![None; self.bodies.len()],
            joint_count: self.joints.len(),
            record_interval: stride as Real * dt,
            ..RunOutput::default()
        };
        let samples = if options.history {
            steps / stride + 8
        } else {
            1
        };
        out.times
            .try_reserve_exact(samples)
            .map_err(|_| out_of_memory(self.time))?;
        out.states
            .try_reserve_exact(samples * self.bodies.len())
            .map_err(|_| out_of_memory(self.time))?;
        out.wheels
            .try_reserve_exact(samples * wheels)
            .map_err(|_| out_of_memory(self.time))?;
        out.joints
            .try_reserve_exact(samples * self.joints.len())
            .map_err(|_| out_of_memory(self.time))?;
        Ok(out)
    }

    /// Keeps every body's state and motion (and the mechanisms' engaged limits) at the
    /// step's start, for the searches that look back into the step (on the ground only).
    fn keep_step_start(&mut self) {
        if self.ground.is_some() {
            let snapshot = self
                .bodies
                .iter()
                .map(|b| (b.body().clone(), b.motion.clone()));
            self.step_start = Some((self.time, snapshot.collect()));
            self.engaged_at_step_start =
                self.mechanisms.iter().map(|m| m.engaged.clone()).collect();
        }
    }

    /// The earliest first overlap among the apart pairs in (now, `target`]: its offset from
    /// now (s) and the pair.
    fn earliest_first_overlap(
        &mut self,
        target: Real,
        progress: &mut dyn FnMut(Real) -> bool,
    ) -> Result<Option<(Real, usize)>> {
        let mut earliest: Option<(Real, usize)> = None;
        for pi in 0..self.pairs.len() {
            if !matches!(self.pairs[pi].phase, Phase::Apart) {
                continue;
            }
            let horizon = earliest.map_or(target - self.time, |(dt, _)| dt);
            if let Some(dt) = self.first_contact(pi, horizon, progress)? {
                if earliest.is_none_or(|(de, _)| dt < de) {
                    earliest = Some((dt, pi));
                }
            }
        }
        Ok(earliest)
    }

    /// Logs pair `pi`'s first overlap now and starts its contact: pressing (a soft pair),
    /// resting, or the depth-of-penetration timer.
    fn begin_contact(&mut self, pi: usize, out: &mut RunOutput) {
        let (b1, b2) = (self.pairs[pi].body1, self.pairs[pi].body2);
        out.contacts.push(ContactEvent {
            body1: b1,
            body2: b2,
            time: self.time,
            kind: ContactEventKind::FirstOverlap,
        });
        self.pairs[pi].exchanges = 0;
        if self.pairs[pi].soft.is_some() {
            self.pairs[pi].phase = Phase::Pressing { depth: 0.0 };
            self.pairs[pi].front = None;
        } else if !self.start_resting_contact(pi, out) {
            self.start_timer(pi, self.time, None, out);
        }
    }

    /// Each pair after an advance from `t_prev`: its exchange when its timer has run out, or
    /// following it while engaged, touching or pressing.
    fn follow_pairs(
        &mut self,
        t_prev: Real,
        at_instant: &mut (Real, Vec<usize>),
        out: &mut RunOutput,
    ) -> Result<()> {
        for pi in 0..self.pairs.len() {
            match self.pairs[pi].phase {
                Phase::Timer { exchange_at, .. } if exchange_at <= self.time => {
                    self.count_event(at_instant, pi)?;
                    self.exchange(pi, out)
                }
                Phase::Engaged { .. } => self.follow_engaged(pi, t_prev, out),
                Phase::Touching { .. } => self.follow_touching(pi, t_prev, out),
                Phase::Pressing { .. } => self.press(pi, t_prev, out),
                _ => {}
            }
        }
        Ok(())
    }

    /// At a run's end, the rest time of each body on the ground slow for [`REST_TIME`]: when
    /// it came to rest after it last moved, else when it became slow.
    fn rest_at_end(&self, out: &mut RunOutput) {
        for (i, since) in self.slow_since.iter().enumerate() {
            if matches!(self.bodies[i].motion, Motion::OnGround(_))
                && since.is_some_and(|t0| self.time - t0 >= REST_TIME - 1e-12)
            {
                out.rest[i] = self.stopped_at[i].or(*since);
            }
        }
    }

    /// Updates, for each body on the ground, since when it has been slow enough to be at rest,
    /// when it first came to rest after it last moved, and since when it has settled.
    ///
    /// Slow: on the ground (see [`crate::motion::OnGround::supported`]) with its speed along the ground below
    /// [`REST_SPEED`] and its yaw rate below [`REST_YAW_RATE`]. Moving again: faster than
    /// [`MOVING_SPEED`] along the ground or vertically, yawing faster than ten times
    /// [`REST_YAW_RATE`], or off the ground. The time it came to rest is the time to rest
    /// reported: the bounce and rock on the springs after a skid (a few cm/s back and forth)
    /// do not push it back, but a fall or a bounce off the ground does (a car dropped from
    /// 10 m was "at rest at t = 0.001 s" while it fell). Settled: on the ground with every
    /// velocity component below [`SETTLED_SPEED`] and every angular one below
    /// [`SETTLED_ANGULAR_SPEED`]; a run until rest waits for [`REST_TIME`] of it, so it does
    /// not stop at the bottom of a bounce.
    fn track_rest(&mut self) {
        let Some(ground) = &self.ground else {
            return;
        };
        // Per mechanism, whether the ground carries one of its members (found when needed):
        // a member held up by its joints (a pedestrian's arm lying on his chest) is carried
        // through them.
        let mut mechanism_carried: Vec<Option<bool>> = vec![None; self.mechanisms.len()];
        let mut carried = |i: usize, bodies: &[WorldBody]| -> bool {
            let on = |k: usize| match &bodies[k].motion {
                Motion::OnGround(m) => m.supported(bodies[k].body(), ground),
                _ => false,
            };
            if on(i) {
                return true;
            }
            let Some(g) = self.mechanism_of.get(i).copied().flatten() else {
                return false;
            };
            *mechanism_carried[g]
                .get_or_insert_with(|| self.mechanisms[g].members.iter().any(|&k| on(k)))
        };
        for (i, wb) in self.bodies.iter().enumerate() {
            let Motion::OnGround(motion) = &wb.motion else {
                continue;
            };
            let v = wb.body().velocity();
            let w = wb.body().angular_velocity();
            let along = v.x.hypot(v.y);
            let yaw_limit = REST_YAW_RATE.max(REST_TURN_SPEED / wb.reach);
            let travel_slow = along < REST_SPEED && w.z.abs() < yaw_limit;
            let fast = along > MOVING_SPEED
                || v.z.abs() > MOVING_SPEED
                || w.z.abs() > 10.0 * REST_YAW_RATE;
            // Only a body that may be or stay at rest needs to know whether it is carried.
            let on_ground = if travel_slow || (!fast && self.stopped_at[i].is_some()) {
                let _ = motion;
                carried(i, &self.bodies)
            } else {
                true
            };
            let slow = travel_slow && on_ground;
            self.slow_since[i] = if slow {
                self.slow_since[i].or(Some(self.time))
            } else {
                None
            };
            if fast || !on_ground {
                self.stopped_at[i] = None;
            } else if slow && self.stopped_at[i].is_none() {
                self.stopped_at[i] = Some(self.time);
            }
            let turn_limit = SETTLED_ANGULAR_SPEED.max(SETTLED_SPEED / wb.reach);
            let settled = slow && v.norm() < SETTLED_SPEED && w.norm() < turn_limit;
            self.settled_since[i] = if settled {
                self.settled_since[i].or(Some(self.time))
            } else {
                None
            };
        }
    }

    /// True when body `i` is at rest: a fixed obstacle, or a body on the ground that has come
    /// to rest since it last moved (it may still rock on its springs).
    pub(super) fn at_rest(&self, i: usize) -> bool {
        match self.bodies[i].motion {
            Motion::Fixed => true,
            Motion::OnGround(_) => self.stopped_at[i].is_some(),
            Motion::Free => false,
        }
    }

    /// True when every body on the ground has been slow for [`REST_TIME`] and settled for as
    /// long.
    fn all_at_rest(&self) -> bool {
        let held =
            |since: Option<Real>| since.is_some_and(|t0| self.time - t0 >= REST_TIME - 1e-12);
        self.bodies.iter().enumerate().all(|(i, wb)| {
            !matches!(wb.motion, Motion::OnGround(_))
                || (held(self.slow_since[i]) && held(self.settled_since[i]))
        })
    }

    /// Counts an event of pair `pi` now; an error when the pair keeps having events at the
    /// same instant (a run that would never advance).
    fn count_event(&self, at_instant: &mut (Real, Vec<usize>), pi: usize) -> Result<()> {
        if at_instant.0 != self.time {
            at_instant.0 = self.time;
            at_instant.1.iter_mut().for_each(|n| *n = 0);
        }
        at_instant.1[pi] += 1;
        if at_instant.1[pi] > MAX_EVENTS_PER_INSTANT {
            let p = &self.pairs[pi];
            return Err(Error::simulation(format!(
                "they had more than {MAX_EVENTS_PER_INSTANT} contact events without time \
                 advancing; the run was stopped (please report the scene)"
            ))
            .at(Place::Time(self.time))
            .at(Place::bodies(p.body1, p.body2)));
        }
        Ok(())
    }

    /// Appends the current states (replacing a sample already taken at this instant).
    pub(super) fn record(&self, out: &mut RunOutput) -> Result<()> {
        let n = self.bodies.len();
        let wheels: usize = out.wheel_counts.iter().sum();
        if out.times.last() == Some(&self.time) {
            out.times.pop();
            out.states.truncate(out.states.len() - n);
            out.wheels.truncate(out.wheels.len() - wheels);
            out.joints.truncate(out.joints.len() - out.joint_count);
        }
        let oom = |_| out_of_memory(self.time);
        out.times.try_reserve(1).map_err(oom)?;
        out.states.try_reserve(n).map_err(oom)?;
        out.wheels.try_reserve(wheels).map_err(oom)?;
        for wb in &self.bodies {
            if let (Motion::OnGround(g), Some(ground)) = (&wb.motion, &self.ground) {
                out.wheels
                    .extend(g.wheel_samples(wb.body(), ground, self.time)?);
            }
        }
        if !self.joints.is_empty() {
            out.joints.try_reserve(self.joints.len()).map_err(oom)?;
            let start = out.joints.len();
            out.joints
                .resize(start + self.joints.len(), JointSample::default());
            let ground = self.ground.as_ref().expect("joints need a ground");
            for m in &self.mechanisms {
                let (bodies, motions): (Vec<_>, Vec<_>) = m
                    .members
                    .iter()
                    .map(|&k| {
                        let wb = &self.bodies[k];
                        let Motion::OnGround(g) = &wb.motion else {
                            unreachable!("a mechanism's members move on the ground")
                        };
                        (wb.body().clone(), g.as_ref().clone())
                    })
                    .unzip();
                let samples =
                    joint_samples(&bodies, &motions, &m.joints, &m.engaged, ground, self.time)?;
                for (id, sample) in m.ids.iter().zip(samples) {
                    out.joints[start + id] = sample;
                }
            }
        }
        out.times.push(self.time);
        out.states
            .extend(self.bodies.iter().map(|b| b.body().state()));
        Ok(())
    }

    /// Moves every body on by `dt` s from now (> 0), as [`World::predicted`] does.
    fn move_bodies(&mut self, dt: Real) -> Result<()> {
        for i in 0..self.bodies.len() {
            if matches!(self.bodies[i].motion, Motion::OnGround(_)) {
                // The prediction the step's search made is the same integration.
                let p = self.predicted_on_ground(i, dt);
                if let Some(e) = self.deferred.lock().expect("not poisoned").take() {
                    return Err(e);
                }
                let p = p.expect("a failed prediction leaves its error");
                if let (Some(outcome), Some(g)) = (&p.mechanism, self.mechanism_of[i]) {
                    if self.mechanisms[g].members[0] == i {
                        self.settle_mechanism(g, &outcome.clone());
                    }
                }
                let wb = &mut self.bodies[i];
                wb.move_to(p.state);
                wb.motion = Motion::OnGround(Box::new(p.motion));
                continue;
            }
            let wb = &mut self.bodies[i];
            match &mut wb.motion {
                Motion::Free => wb.advance(dt),
                Motion::Fixed | Motion::OnGround(_) => {}
            }
        }
        Ok(())
    }

    /// Moves every body and the clock to `t` (s).
    pub(super) fn advance_to(&mut self, t: Real) -> Result<()> {
        let dt = t - self.time;
        if dt > 0.0 {
            self.move_bodies(dt)?;
        }
        self.time = t;
        Ok(())
    }

    /// Moves every body and the clock on by `dt` s: the same motion as the predictions
    /// [`World::predicted`] that found the instant, bit for bit.
    pub(super) fn advance_by(&mut self, dt: Real) -> Result<()> {
        if dt > 0.0 {
            self.move_bodies(dt)?;
            self.time += dt;
        }
        Ok(())
    }
}

/// Checks a run's duration (s, finite, >= 0) and step (s, finite, > 0, at most 1e8 steps);
/// the number of grid steps.
pub fn check_run_length(duration: Real, dt: Real) -> Result<usize> {
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
    Ok((duration / dt).ceil() as usize)
}

/// The error of an interrupted run.
pub(super) fn interrupted(t: Real) -> Error {
    Error::simulation("the run was interrupted").at(Place::Time(t))
}

fn out_of_memory(t: Real) -> Error {
    Error::simulation(
        "out of memory while recording the run: record less often (record_interval) or \
         shorten the run",
    )
    .at(Place::Time(t))
}
