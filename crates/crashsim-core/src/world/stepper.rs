//! The schedule of a run: the step grid, stopping at first overlaps and exchange instants,
//! following engaged pairs, and the samples of every body's state.

use super::{Phase, World};
use crate::error::{require_finite, Error, Result};
use crate::math::Real;

use super::events::{ContactEvent, ContactEventKind, RunOutput};

/// Most steps one run may take.
const MAX_STEPS: Real = 1e8;

impl World {
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

    pub(super) fn record(&self, out: &mut RunOutput) {
        if out.times.last() == Some(&self.time) {
            out.states.pop();
            out.times.pop();
        }
        out.times.push(self.time);
        out.states
            .push(self.bodies.iter().map(|b| b.body.state()).collect());
    }

    pub(super) fn advance_to(&mut self, t: Real) {
        let dt = t - self.time;
        if dt > 0.0 {
            for b in &mut self.bodies {
                b.body.advance(dt);
            }
        }
        self.time = t;
    }
}
