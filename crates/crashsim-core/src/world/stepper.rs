//! The schedule of a run: the step grid, stopping at first overlaps and exchange instants,
//! following engaged pairs, and the samples of every body's state.
//!
//! Every loop of a run is bounded: the steps (at most [`MAX_STEPS`]), the events at one
//! instant (at most [`MAX_EVENTS_PER_INSTANT`] per pair), the first-contact search and every
//! bisection; a bound that is hit ends the run with [`Error::Simulation`] naming the pair and
//! the time. The caller's hook is asked after every step and inside the first-contact search,
//! so an interrupt (Ctrl-C from Python) is honoured within the hook's own polling interval.

use super::{Phase, World};
use crate::body::BodyState;
use crate::error::{require_finite, Error, Result};
use crate::math::Real;

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

/// How a run keeps its history of states.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Recording {
    /// Interval between kept samples (s), rounded down to a whole number of steps (at least
    /// one). None: every step for runs of at most [`DEFAULT_SAMPLES`] steps, else about
    /// [`DEFAULT_SAMPLES`] evenly spaced samples. The start, the end, every first overlap and
    /// every exchange are kept whatever the interval.
    pub interval: Option<Real>,
    /// Largest history a run may keep (bytes, default [`DEFAULT_MAX_HISTORY_BYTES`]): a run
    /// whose estimate is larger is refused before it starts, with the interval that fits.
    pub max_bytes: u64,
}

impl Default for Recording {
    fn default() -> Self {
        Recording {
            interval: None,
            max_bytes: DEFAULT_MAX_HISTORY_BYTES,
        }
    }
}

/// Bytes one sample takes: its time and every body's state.
fn sample_bytes(bodies: usize) -> u64 {
    (std::mem::size_of::<Real>() + bodies * std::mem::size_of::<BodyState>()) as u64
}

/// Human-readable bytes (binary units, as the 1 GiB default).
fn show_bytes(b: u64) -> String {
    let b = b as f64;
    if b >= (1u64 << 30) as f64 {
        format!("{:.2} GiB", b / (1u64 << 30) as f64)
    } else if b >= (1u64 << 20) as f64 {
        format!("{:.1} MiB", b / (1u64 << 20) as f64)
    } else {
        format!("{:.1} KiB", b / 1024.0)
    }
}

impl Recording {
    /// Steps between kept samples for a run of `steps` steps of `dt` s.
    fn stride(&self, steps: usize, dt: Real) -> Result<usize> {
        match self.interval {
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
    fn check_size(&self, steps: usize, stride: usize, dt: Real, bodies: usize) -> Result<()> {
        // The start, the kept steps, the end; events come on top (a few per contact).
        let samples = (steps / stride + 2) as u64;
        let need = samples.saturating_mul(sample_bytes(bodies));
        if need <= self.max_bytes {
            return Ok(());
        }
        let fits = (self.max_bytes / sample_bytes(bodies))
            .saturating_sub(2)
            .max(1);
        let interval = dt * steps.div_ceil(fits as usize) as Real;
        Err(Error::Parameter(format!(
            "the run would keep {samples} samples of {bodies} bodies ({}), more than the \
             history limit of {}: record less often (record_interval = {interval:.3e} s or \
             more fits), shorten the run, or raise the limit (max_history_bytes)",
            show_bytes(need),
            show_bytes(self.max_bytes)
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
        self.run_recorded(duration, dt, &Recording::default(), progress)
    }

    /// [`World::run_with_progress`] keeping the history as `recording` says.
    pub fn run_recorded(
        &mut self,
        duration: Real,
        dt: Real,
        recording: &Recording,
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
        let steps = (duration / dt).ceil() as usize;
        let stride = recording.stride(steps, dt)?;
        recording.check_size(steps, stride, dt, self.bodies.len())?;
        if !self.started {
            for p in &self.pairs {
                self.check_stiffness(p.body1, p.body2, &p.params)?;
            }
            self.check_initial_overlaps()?;
            self.started = true;
        }
        let t_start = self.time;
        let t_end = t_start + duration;
        let mut out = RunOutput {
            body_count: self.bodies.len(),
            record_interval: stride as Real * dt,
            ..RunOutput::default()
        };
        let samples = steps / stride + 8;
        out.times
            .try_reserve_exact(samples)
            .map_err(|_| out_of_memory(self.time))?;
        out.states
            .try_reserve_exact(samples * self.bodies.len())
            .map_err(|_| out_of_memory(self.time))?;
        self.record(&mut out)?;
        // Events at the current instant per pair, to stop a pair that makes no progress.
        let mut at_instant = (self.time, vec![0usize; self.pairs.len()]);
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
            // The earliest first overlap among apart pairs inside (time, target], as an
            // offset from now.
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
            if let Some((offset, pi)) = earliest {
                self.advance_by(offset);
                self.count_event(&mut at_instant, pi)?;
                let (b1, b2) = (self.pairs[pi].body1, self.pairs[pi].body2);
                out.contacts.push(ContactEvent {
                    body1: b1,
                    body2: b2,
                    time: self.time,
                    kind: ContactEventKind::FirstOverlap,
                });
                self.pairs[pi].exchanges = 0;
                self.start_timer(pi, self.time, None, &mut out);
                self.record(&mut out)?;
                continue;
            }
            let t_prev = self.time;
            let (impacts, contacts) = (out.impacts.len(), out.contacts.len());
            self.advance_to(target);
            for pi in 0..self.pairs.len() {
                match self.pairs[pi].phase {
                    Phase::Timer { exchange_at, .. } if exchange_at <= self.time => {
                        self.count_event(&mut at_instant, pi)?;
                        self.exchange(pi, &mut out)
                    }
                    Phase::Engaged { .. } => self.follow_engaged(pi, t_prev, &mut out),
                    _ => {}
                }
            }
            let on_grid = target == grid;
            let event = out.impacts.len() > impacts || out.contacts.len() > contacts;
            if !on_grid || event || k % stride == 0 || k >= steps {
                self.record(&mut out)?;
            }
            if on_grid {
                k += 1;
            }
            if !progress(self.time) {
                return Err(interrupted(self.time));
            }
        }
        Ok(out)
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
            return Err(Error::Simulation(format!(
                "bodies {} and {} had more than {MAX_EVENTS_PER_INSTANT} contact events at \
                 t = {} s without time advancing; the run was stopped (please report the scene)",
                p.body1, p.body2, self.time
            )));
        }
        Ok(())
    }

    /// Appends the current states (replacing a sample already taken at this instant).
    pub(super) fn record(&self, out: &mut RunOutput) -> Result<()> {
        let n = self.bodies.len();
        if out.times.last() == Some(&self.time) {
            out.times.pop();
            out.states.truncate(out.states.len() - n);
        }
        out.times
            .try_reserve(1)
            .map_err(|_| out_of_memory(self.time))?;
        out.states
            .try_reserve(n)
            .map_err(|_| out_of_memory(self.time))?;
        out.times.push(self.time);
        out.states
            .extend(self.bodies.iter().map(|b| b.body.state()));
        Ok(())
    }

    /// Moves every body and the clock to `t` (s).
    pub(super) fn advance_to(&mut self, t: Real) {
        let dt = t - self.time;
        if dt > 0.0 {
            for b in &mut self.bodies {
                b.body.advance(dt);
            }
        }
        self.time = t;
    }

    /// Moves every body and the clock on by `dt` s: the same motion as the predictions
    /// `RigidBody::advanced(dt)` that found the instant, bit for bit.
    pub(super) fn advance_by(&mut self, dt: Real) {
        if dt > 0.0 {
            for b in &mut self.bodies {
                b.body.advance(dt);
            }
            self.time += dt;
        }
    }
}

/// The error of an interrupted run.
pub(super) fn interrupted(t: Real) -> Error {
    Error::Simulation(format!("the run was interrupted at t = {t} s"))
}

fn out_of_memory(t: Real) -> Error {
    Error::Simulation(format!(
        "out of memory while recording the run at t = {t} s: record less often \
         (record_interval) or shorten the run"
    ))
}
