//! Timers and exchanges: a pair's timer starts at a first overlap (or when an engaged pair
//! turns closing again), the impulse is exchanged when it expires, and an engaged pair is
//! followed until it separates or closes again.

use super::{Motion, Pair, Phase, World, TIME_TOLERANCE};
use crate::bisect::bisect;
use crate::contact::{
    DepthOfPenetration, DEEPEST_ITERATIONS, MAX_DEPTH_OF_PENETRATION, OVERLAP_SAMPLES,
};
use crate::impulse::{ImpulseProblem, ImpulseSolution};
use crate::math::{Point, Real, Vector};
use crate::overlap::{overlap_region, shapes_overlap_hinted, QueryWorkspace};

use super::events::{delta_v_in_body, pdof_deg, ContactEvent, ContactEventKind, Impact, RunOutput};
use super::geometry::ContactGeometry;

/// Separation instants are resolved to this (s).
const SEPARATION_TOLERANCE: Real = 1e-6;
/// A relative normal velocity above this (m/s) counts as closing again.
const CLOSING_TOLERANCE: Real = 1e-6;
/// The same for a pair with a body on the ground (m/s). Under tyre forces engaged bodies
/// close again by the elastic give of the treads and the suspension: a car wrapped round a
/// pole (locked wheels) rattled through 11 secondary exchanges at 0.06-0.3 m/s, each changing
/// its speed by at most 0.3 m/s. A secondary impulse from a closing below 0.5 m/s changes a
/// car's speed by about as little, below what a reconstruction resolves.
const CLOSING_TOLERANCE_ON_GROUND: Real = 0.5;
/// Two bodies at rest (stepper.rs: come to rest since they last moved, or fixed) whose meshes
/// touch with a relative speed below this (m/s) at the touch are in resting contact: no timer
/// and no impulse while both stay at rest and the touch stays this slow. Cars that came to
/// rest side by side rock on their springs and treads into each other at a few cm/s (0.06 to
/// 0.08 m/s in the seed's side impact run to rest, benches/compare_peers.py): an exchange there
/// changed each car's speed by 0.03 m/s, after its rest time. A vehicle still travelling
/// (faster than REST_SPEED along the ground) is not at rest, so a slow first impact (a car
/// creeping into a parked one) exchanges as any other.
const RESTING_CONTACT_SPEED: Real = 0.5;

impl World {
    /// Starts pair `pi`'s timer at `started` (s, at most now); exchanges at once when it has
    /// already expired. A secondary timer (an engaged pair closing again) keeps the engaged
    /// normal `engaged_normal` (body 1's frame), along which it was found closing; a first
    /// one takes the volume normal of the shallow overlap.
    pub(super) fn start_timer(
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
        let mut early_note = None;
        let mut early_normal = match engaged_normal {
            Some(n) => Some((n, started)),
            None => self.early_normal(pi, started, cap).map(|(n, t, note)| {
                early_note = note;
                (n, t)
            }),
        };
        let (dtp, mut notes) = match self.pairs[pi].params.depth_of_penetration {
            DepthOfPenetration::Fixed(dtp) => (dtp, Vec::new()),
            DepthOfPenetration::Auto => {
                let (dtp, notes) = self.auto_depth_of_penetration(pi, started, early_normal);
                if early_normal.is_some_and(|(_, t)| t > started + dtp) {
                    // The exchange comes before the normal's reading depth: use its own.
                    early_normal = None;
                    early_note = None;
                }
                (dtp, notes)
            }
        };
        notes.extend(early_note);
        let mut timer = dtp;
        let mut impulse_share = 1.0;
        // A first overlap that ends before its timer expires is exchanged at its deepest. A
        // secondary timer starts inside an overlap that may only shrink: it keeps its instant
        // (and, if the meshes have separated by then, a no-exchange event says so).
        if !secondary {
            if let Some((deepest_after, share, note)) =
                self.overlap_ends_early(pi, started, dtp, early_normal)
            {
                timer = deepest_after;
                impulse_share = share;
                notes.push(note);
            }
        }
        let exchange_at = (started + timer).max(self.time);
        self.pairs[pi].phase = Phase::Timer {
            started,
            timer,
            exchange_at,
            secondary,
            notes,
            early_normal,
            impulse_share,
        };
        if exchange_at <= self.time {
            self.exchange(pi, out);
        }
    }

    /// When pair `pi`'s overlap, started at `started`, ends before its exchange at
    /// `started + dtp`: the time from `started` to its deepest overlap (s), the share of the
    /// impulse it exchanges, and a note saying so; else None.
    ///
    /// The share is the seed's spring model's (eqs. 24, 28: crush C(t) = v dt_p sin(t / dt_p),
    /// force k C, so the impulse transmitted by time t is m' v (1 - cos(t / dt_p))): what the
    /// spring transmits by the time T the overlap ends, over what it transmits by dt_p, where
    /// the model exchanges the whole impulse: (1 - cos(T / dt_p)) / (1 - cos 1), in (0, 1).
    /// The contact ends before common velocity: a graze that ends at once exchanges nothing,
    /// and the share grows continuously to 1 as the overlap lasts up to dt_p.
    ///
    /// The motion during the timer is free, so the future overlap is examined now: the
    /// overlap test at OVERLAP_SAMPLES instants across the timer; at the first one apart, the
    /// end is bisected (to TIME_TOLERANCE) from the last one overlapping. The depth is
    /// the extent of the overlap region along the normal (the early normal turned with body 1,
    /// else the region's own volume normal, else the approach direction at the region's
    /// centre); its largest value over the overlap is found from OVERLAP_SAMPLES samples and
    /// DEEPEST_ITERATIONS golden-section steps around the best one. Bounded throughout.
    fn overlap_ends_early(
        &self,
        pi: usize,
        started: Real,
        dtp: Real,
        early_normal: Option<(Vector, Real)>,
    ) -> Option<(Real, Real, String)> {
        if dtp <= 0.0 {
            return None;
        }
        let pair = self.pairs[pi].clone();
        let base = started - self.time;
        let (s1, s2) = (
            self.bodies[pair.body1].shape.clone(),
            self.bodies[pair.body2].shape.clone(),
        );
        let (i1, i2) = (pair.body1, pair.body2);
        let mut ws = QueryWorkspace::default();
        // Each sample tries the crossing pair the last one found first (the same answers).
        let mut hint = pair.crossing;
        let mut overlaps = |dt: Real| {
            let (p1, p2) = (
                self.predicted(i1, base + dt).pose(),
                self.predicted(i2, base + dt).pose(),
            );
            shapes_overlap_hinted(&s1, &p1, &s2, &p2, &mut ws, &mut hint)
        };
        let step = dtp / OVERLAP_SAMPLES as Real;
        let apart = (1..=OVERLAP_SAMPLES).find(|k| !overlaps(*k as Real * step))?;
        let lo = (apart - 1) as Real * step;
        let end = lo + bisect(0.0, step, TIME_TOLERANCE, |dt| !overlaps(lo + dt));
        // The deepest overlap in (0, end).
        let depth = |dt: Real| -> Real {
            let (a1, a2) = (self.predicted(i1, base + dt), self.predicted(i2, base + dt));
            let region = overlap_region(&s1, &a1.pose(), &s2, &a2.pose());
            let Some(first) = region.points.first() else {
                return 0.0;
            };
            let n = match early_normal {
                Some((n, _)) => a1.pose() * n,
                None => region.volume_normal().unwrap_or_else(|| {
                    let u = a1.point_velocity(first) - a2.point_velocity(first);
                    if u.norm() > 0.0 {
                        u.normalize()
                    } else {
                        Vector::x()
                    }
                }),
            };
            let (mut lo, mut hi) = (Real::INFINITY, Real::NEG_INFINITY);
            for p in &region.points {
                let s = p.coords.dot(&n);
                lo = lo.min(s);
                hi = hi.max(s);
            }
            hi - lo
        };
        let h = end / OVERLAP_SAMPLES as Real;
        let (mut best, mut best_depth) = (0.5 * end, Real::NEG_INFINITY);
        for k in 1..OVERLAP_SAMPLES {
            let d = depth(k as Real * h);
            if d > best_depth {
                (best, best_depth) = (k as Real * h, d);
            }
        }
        // Golden-section refinement in the bracket around the best sample.
        let (mut a, mut b) = ((best - h).max(0.0), (best + h).min(end));
        let g = 0.5 * (5.0_f64.sqrt() - 1.0);
        let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
        let (mut f1, mut f2) = (depth(x1), depth(x2));
        for _ in 0..DEEPEST_ITERATIONS {
            if f1 >= f2 {
                (b, x2, f2) = (x2, x1, f1);
                x1 = b - g * (b - a);
                f1 = depth(x1);
            } else {
                (a, x1, f1) = (x1, x2, f2);
                x2 = a + g * (b - a);
                f2 = depth(x2);
            }
        }
        let (at, deepest) = if f1 >= f2 { (x1, f1) } else { (x2, f2) };
        let (at, deepest) = if deepest >= best_depth {
            (at, deepest)
        } else {
            (best, best_depth)
        };
        let share = ((1.0 - (end / dtp).cos()) / (1.0 - (1.0 as Real).cos())).min(1.0);
        let note = format!(
            "the overlap ended {:.3} ms after the first overlap, before the {:.1} ms timer \
             expired: exchanged at its deepest ({:.1} mm along the normal), {:.3} ms after the \
             first overlap, with a share {:.3e} of the impulse (what the seed's spring \
             transmits by the time the overlap ends: (1 - cos(T/dt_p)) / (1 - cos 1))",
            end * 1e3,
            dtp * 1e3,
            deepest * 1e3,
            at * 1e3,
            share
        );
        Some((at, share, note))
    }

    /// Exchange the impulse of pair `pi` now (its timer expired).
    pub(super) fn exchange(&mut self, pi: usize, out: &mut RunOutput) {
        let Some(timer) = self.expired_timer(pi) else {
            return;
        };
        let pair = self.pairs[pi].clone();
        let (i1, i2) = (pair.body1, pair.body2);
        let elapsed_ms = (self.time - timer.started) * 1e3;
        let (b1, b2) = (self.bodies[i1].body(), self.bodies[i2].body());
        let normal = timer.early_normal.map(|(n, t)| (b1.pose() * n, t));
        let Some(geometry) = self.contact_geometry(&pair, b1, b2, normal) else {
            let why = separated_note(elapsed_ms, timer.secondary);
            self.no_exchange(pi, out, why, Phase::Apart);
            return;
        };
        let (pose1, pose2) = (b1.pose(), b2.pose());
        let (centroid, normal) = (geometry.centroid, geometry.normal);
        let problem = self.impulse_problem(&pair, &centroid, &normal);
        let u = problem.relative_velocity;
        let engaged = Phase::Engaged {
            centroid_in: [
                pose1.inverse_transform_point(&centroid),
                pose2.inverse_transform_point(&centroid),
            ],
            normal_in_1: pose1.inverse_transform_vector(&normal),
        };
        let Some(solution) = problem.solve() else {
            let why = not_approaching_note(&u, &geometry, elapsed_ms, timer.secondary);
            self.no_exchange(pi, out, why, engaged);
            return;
        };
        let impact = self.exchange_and_record(&pair, timer, geometry, u, &solution);
        out.impacts.push(impact);
        self.pairs[pi].exchanges += 1;
        self.pairs[pi].phase = engaged;
    }

    /// Pair `pi`'s timer as set when it started; None when the pair has no timer running.
    fn expired_timer(&self, pi: usize) -> Option<ExpiredTimer> {
        match &self.pairs[pi].phase {
            Phase::Timer {
                started,
                timer,
                secondary,
                notes,
                early_normal,
                impulse_share,
                ..
            } => Some(ExpiredTimer {
                started: *started,
                timer: *timer,
                secondary: *secondary,
                notes: notes.clone(),
                early_normal: *early_normal,
                share: *impulse_share,
            }),
            _ => None,
        }
    }

    /// Logs that pair `pi` exchanges nothing now, and why, and puts it in `phase`.
    fn no_exchange(&mut self, pi: usize, out: &mut RunOutput, why: String, phase: Phase) {
        out.contacts.push(ContactEvent {
            body1: self.pairs[pi].body1,
            body2: self.pairs[pi].body2,
            time: self.time,
            kind: ContactEventKind::NoExchange(why),
        });
        self.pairs[pi].phase = phase;
    }

    /// The impulse problem of `pair` with its bodies as they are now, at `centroid` (world,
    /// m) along the unit `normal` (world, from body 1 into body 2); its relative
    /// velocity is body 1's point velocity less body 2's at the centroid (m/s).
    fn impulse_problem(&self, pair: &Pair, centroid: &Point, normal: &Vector) -> ImpulseProblem {
        let (i1, i2) = (pair.body1, pair.body2);
        let (b1, b2) = (self.bodies[i1].body(), self.bodies[i2].body());
        let r1 = centroid - b1.position();
        let r2 = centroid - b2.position();
        let u = b1.point_velocity(centroid) - b2.point_velocity(centroid);
        ImpulseProblem {
            inverse_mass_sum: 1.0 / b1.props().mass() + 1.0 / b2.props().mass(),
            inverse_inertia: [b1.world_inverse_inertia(), b2.world_inverse_inertia()],
            lever: [r1, r2],
            relative_velocity: u,
            normal: *normal,
            restitution: pair.params.restitution,
            friction: pair.params.friction,
            mode: pair.params.restitution_mode,
            joined: (self.mechanism_of[i1].is_some() || self.mechanism_of[i2].is_some())
                .then(|| self.pair_mobility(i1, i2, centroid)),
        }
    }

    /// Applies `solution`'s impulse (times the timer's share) to `pair` at the geometry's
    /// centroid and returns the Impact record (world frame, SI); `u` is the relative velocity
    /// at the centroid before it (m/s).
    fn exchange_and_record(
        &mut self,
        pair: &Pair,
        timer: ExpiredTimer,
        geometry: ContactGeometry,
        u: Vector,
        solution: &ImpulseSolution,
    ) -> Impact {
        let (i1, i2) = (pair.body1, pair.body2);
        let (started, timer_set) = (timer.started, timer.timer);
        let (centroid, normal) = (geometry.centroid, geometry.normal);
        let (b1, b2) = (self.bodies[i1].body(), self.bodies[i2].body());
        let before = [b1.state(), b2.state()];
        let j = solution.impulse * timer.share;
        let energy_dissipated = self.apply_exchange(i1, i2, &centroid, &j);
        let (b1, b2) = (self.bodies[i1].body(), self.bodies[i2].body());
        let after = [b1.state(), b2.state()];
        let u_after = b1.point_velocity(&centroid) - b2.point_velocity(&centroid);
        let delta_v_body = [0, 1].map(|k| {
            delta_v_in_body(
                &after[k].orientation,
                &(after[k].velocity - before[k].velocity),
            )
        });
        Impact {
            body1: i1,
            body2: i2,
            first_contact_time: started,
            time: self.time,
            // The timer as set (dt_p itself, not started + dt_p - started rounded), unless
            // the exchange came later than set (a timer started at an instant already past).
            depth_of_penetration: if self.time == started + timer_set {
                timer_set
            } else {
                self.time - started
            },
            depth_of_penetration_mode: pair.params.depth_of_penetration,
            secondary: timer.secondary || pair.exchanges > 0,
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
            energy_dissipated,
            region_points: geometry.region.points,
            contact_frame: geometry.frame,
            region_min: geometry.region_min,
            region_max: geometry.region_max,
            struck_faces: geometry.faces,
            overlap_width: geometry.width,
            spring_rates: geometry.spring_rates,
            effective_mass: geometry.effective_mass,
            normal_time: geometry.normal_time.unwrap_or(self.time),
            notes: timer.notes,
            delta_v_body,
            pdof_deg: delta_v_body.map(|dv| pdof_deg(&dv)),
        }
    }

    /// Applies the impulse `j` (N s) at `centroid` (world) to body `i2` and `-j` to body
    /// `i1` and shares it through their joints (jumps: what was predicted from the bodies'
    /// motions is stale, world_body.rs); the kinetic energy (J) the bodies it moves lose:
    /// the pair and, through joints, their mechanisms' other members.
    fn apply_exchange(&mut self, i1: usize, i2: usize, centroid: &Point, j: &Vector) -> Real {
        let moved = self.moved_by(i1, i2);
        let energy_before: Real = moved
            .iter()
            .map(|&k| self.bodies[k].body().kinetic_energy())
            .sum();
        self.bodies[i1].apply_impulse(&(-j), centroid);
        self.bodies[i2].apply_impulse(j, centroid);
        self.share_impulse(i1);
        self.share_impulse(i2);
        for i in [i1, i2] {
            if let Motion::OnGround(g) = &mut self.bodies[i].motion {
                g.exchanges += 1; // wheel states may switch at an exchange
            }
        }
        let energy_after: Real = moved
            .iter()
            .map(|&k| self.bodies[k].body().kinetic_energy())
            .sum();
        energy_before - energy_after
    }

    /// At pair `pi`'s first overlap (now): when both bodies are at rest and their meshes
    /// touch slowly ([`RESTING_CONTACT_SPEED`]), logs why there is no exchange, puts the pair
    /// in resting contact and returns true; else false (a timer is to start).
    pub(super) fn start_resting_contact(&mut self, pi: usize, out: &mut RunOutput) -> bool {
        let (i1, i2) = (self.pairs[pi].body1, self.pairs[pi].body2);
        if !(self.at_rest(i1) && self.at_rest(i2)) {
            return false;
        }
        let (a, b) = (&self.bodies[i1], &self.bodies[i2]);
        let (pose1, pose2) = (a.body().pose(), b.body().pose());
        let region = overlap_region(&a.shape, &pose1, &b.shape, &pose2);
        let Some(point) = region.center() else {
            return false;
        };
        let speed = (a.body().point_velocity(&point) - b.body().point_velocity(&point)).norm();
        if speed >= RESTING_CONTACT_SPEED {
            return false;
        }
        out.contacts.push(ContactEvent {
            body1: i1,
            body2: i2,
            time: self.time,
            kind: ContactEventKind::NoExchange(format!(
                "resting contact: both vehicles were at rest and their meshes touched at \
                 {speed:.3} m/s (below {RESTING_CONTACT_SPEED} m/s): no impulse while they \
                 stay at rest; an exchange follows if either moves again or the touch closes \
                 faster"
            )),
        });
        self.pairs[pi].phase = Phase::Touching {
            point_in: [
                pose1.inverse_transform_point(&point),
                pose2.inverse_transform_point(&point),
            ],
        };
        true
    }

    /// After a step, a pair in resting contact either separates, starts a timer (a body
    /// moved again, or the touch closes at [`RESTING_CONTACT_SPEED`] or more) or stays.
    pub(super) fn follow_touching(&mut self, pi: usize, t_prev: Real, out: &mut RunOutput) {
        let Phase::Touching { point_in } = self.pairs[pi].phase else {
            return;
        };
        if !self.still_overlapping(pi) {
            self.separate(pi, t_prev, out);
            return;
        }
        let (i1, i2) = (self.pairs[pi].body1, self.pairs[pi].body2);
        let (b1, b2) = (self.bodies[i1].body(), self.bodies[i2].body());
        let c = nalgebra::center(&(b1.pose() * point_in[0]), &(b2.pose() * point_in[1]));
        let speed = (b1.point_velocity(&c) - b2.point_velocity(&c)).norm();
        if self.at_rest(i1) && self.at_rest(i2) && speed < RESTING_CONTACT_SPEED {
            return;
        }
        out.contacts.push(ContactEvent {
            body1: i1,
            body2: i2,
            time: self.time,
            kind: ContactEventKind::ClosingAgain,
        });
        self.start_timer(pi, self.time, None, out);
    }

    /// True when the pair's meshes overlap now (the last crossing triangles tried first).
    fn still_overlapping(&mut self, pi: usize) -> bool {
        let (i1, i2) = (self.pairs[pi].body1, self.pairs[pi].body2);
        let (a, b) = (&self.bodies[i1], &self.bodies[i2]);
        let mut hint = self.pairs[pi].crossing;
        let overlapping = shapes_overlap_hinted(
            &a.shape,
            &a.body().pose(),
            &b.shape,
            &b.body().pose(),
            &mut self.ws,
            &mut hint,
        );
        self.pairs[pi].crossing = hint;
        overlapping
    }

    /// The pair, overlapping at `t_prev` and not now, separated in between: logs the instant
    /// (bisected backwards; the bodies move freely here) and puts it apart.
    fn separate(&mut self, pi: usize, t_prev: Real, out: &mut RunOutput) {
        let (i1, i2) = (self.pairs[pi].body1, self.pairs[pi].body2);
        let (s1, s2) = (self.bodies[i1].shape.clone(), self.bodies[i2].shape.clone());
        let mut ws = std::mem::take(&mut self.ws);
        let mut hint = self.pairs[pi].crossing;
        let hi = bisect(t_prev - self.time, 0.0, SEPARATION_TOLERANCE, |dt| {
            let (p1, p2) = (self.predicted(i1, dt).pose(), self.predicted(i2, dt).pose());
            !shapes_overlap_hinted(&s1, &p1, &s2, &p2, &mut ws, &mut hint)
        });
        self.ws = ws;
        out.contacts.push(ContactEvent {
            body1: i1,
            body2: i2,
            time: self.time + hi,
            kind: ContactEventKind::Separation,
        });
        self.pairs[pi].phase = Phase::Apart;
    }

    /// Relative normal velocity (m/s, closing > 0) of an engaged pair of bodies (`i1`, `i2`)
    /// `dt` s from now.
    pub(super) fn closing_speed(
        &self,
        (i1, i2): (usize, usize),
        centroid_in: &[Point; 2],
        normal_in_1: &Vector,
        dt: Real,
    ) -> Real {
        let (b1, b2) = (self.predicted(i1, dt), self.predicted(i2, dt));
        let (p1, p2) = (b1.pose(), b2.pose());
        let c = nalgebra::center(&(p1 * centroid_in[0]), &(p2 * centroid_in[1]));
        let n = p1 * normal_in_1;
        (b1.point_velocity(&c) - b2.point_velocity(&c)).dot(&n)
    }

    /// After a step, an engaged pair either separates, turns closing again, or stays.
    pub(super) fn follow_engaged(&mut self, pi: usize, t_prev: Real, out: &mut RunOutput) {
        let Phase::Engaged {
            centroid_in,
            normal_in_1,
        } = self.pairs[pi].phase
        else {
            return;
        };
        let (i1, i2) = (self.pairs[pi].body1, self.pairs[pi].body2);
        if !self.still_overlapping(pi) {
            self.separate(pi, t_prev, out);
            return;
        }
        let on_ground = [i1, i2]
            .iter()
            .any(|&i| matches!(self.bodies[i].motion, Motion::OnGround(_)));
        let tolerance = if on_ground {
            CLOSING_TOLERANCE_ON_GROUND
        } else {
            CLOSING_TOLERANCE
        };
        if self.closing_speed((i1, i2), &centroid_in, &normal_in_1, 0.0) > tolerance {
            // Find when it turned closing inside the step (s is smooth: bisection).
            let hi = bisect(t_prev - self.time, 0.0, TIME_TOLERANCE, |dt| {
                self.closing_speed((i1, i2), &centroid_in, &normal_in_1, dt) > tolerance
            });
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

/// What a pair's timer started at, for the notes: its first overlap, or its closing again.
fn timer_start(secondary: bool) -> &'static str {
    if secondary {
        "closing again"
    } else {
        "first overlap"
    }
}

/// A pair's timer as it was set, read when it expires.
struct ExpiredTimer {
    /// When the timer started (s).
    started: Real,
    /// Its length (s): dt_p, or less when the overlap ends early.
    timer: Real,
    /// True for an engaged pair closing again.
    secondary: bool,
    notes: Vec<String>,
    /// The volume normal of the shallow overlap (body 1's frame) and when it was taken (s).
    early_normal: Option<(Vector, Real)>,
    /// The share of the model's impulse exchanged, in (0, 1].
    share: Real,
}

/// Why there is no exchange when the meshes separated during the timer (`elapsed_ms` ms
/// after its start).
fn separated_note(elapsed_ms: Real, secondary: bool) -> String {
    format!(
        "the meshes no longer overlap at the exchange instant, {elapsed_ms:.1} ms after \
         the {} (they separated during the timer): no impulse. A shorter \
         depth_of_penetration exchanges while they still overlap",
        timer_start(secondary)
    )
}

/// Why there is no exchange when the bodies do not approach at the centroid along the
/// normal: `u` the relative velocity there (m/s, world), the geometry's overlap depth along
/// the normal and width (m), `elapsed_ms` ms after the timer's start.
fn not_approaching_note(
    u: &Vector,
    geometry: &ContactGeometry,
    elapsed_ms: Real,
    secondary: bool,
) -> String {
    let normal = geometry.normal;
    let depth = geometry.region_max.x - geometry.region_min.x;
    format!(
        "the vehicles are not approaching at the centroid along the normal \
         (relative normal velocity {:.3} m/s; normal ({:.3}, {:.3}, {:.3}); overlap \
         {:.3} m deep along it, {:.3} m wide, {elapsed_ms:.1} ms after the {}): no \
         impulse; the pair stays engaged and gets one if it turns closing. If the \
         overlap represents a real impact, give the normal (or a shorter \
         depth_of_penetration)",
        u.dot(&normal),
        normal.x,
        normal.y,
        normal.z,
        depth,
        geometry.width,
        timer_start(secondary)
    )
}
