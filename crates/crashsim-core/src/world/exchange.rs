//! Timers and exchanges: a pair's timer starts at a first overlap (or when an engaged pair
//! turns closing again), the impulse is exchanged when it expires, and an engaged pair is
//! followed until it separates or closes again.

use super::{Motion, Pair, Phase, World, TIME_TOLERANCE};
use crate::bisect::bisect;
use crate::contact::{DepthOfPenetration, MAX_DEPTH_OF_PENETRATION};
use crate::impulse::ImpulseProblem;
use crate::math::{Point, Real, Vector};
use crate::overlap::shapes_overlap;

use super::events::{ContactEvent, ContactEventKind, Impact, RunOutput};

/// Separation instants are resolved to this (s).
const SEPARATION_TOLERANCE: Real = 1e-6;
/// A relative normal velocity above this (m/s) counts as closing again.
const CLOSING_TOLERANCE: Real = 1e-6;

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

    /// Exchange the impulse of pair `pi` now (its timer expired).
    pub(super) fn exchange(&mut self, pi: usize, out: &mut RunOutput) {
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
        for i in [i1, i2] {
            if let Motion::OnGround(g) = &mut self.bodies[i].motion {
                g.exchanges += 1; // wheel states may switch at an exchange
            }
        }
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
    pub(super) fn closing_speed(
        &self,
        pair: &Pair,
        centroid_in: &[Point; 2],
        normal_in_1: &Vector,
        dt: Real,
    ) -> Real {
        let b1 = self.predicted(pair.body1, dt);
        let b2 = self.predicted(pair.body2, dt);
        let (p1, p2) = (b1.pose(), b2.pose());
        let c = nalgebra::center(&(p1 * centroid_in[0]), &(p2 * centroid_in[1]));
        let n = p1 * normal_in_1;
        (b1.point_velocity(&c) - b2.point_velocity(&c)).dot(&n)
    }

    /// After a step, an engaged pair either separates, turns closing again, or stays.
    pub(super) fn follow_engaged(&mut self, pi: usize, t_prev: Real, out: &mut RunOutput) {
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
            let (s1, s2) = (self.bodies[i1].shape.clone(), self.bodies[i2].shape.clone());
            let mut ws = std::mem::take(&mut self.ws);
            let hi = bisect(t_prev - self.time, 0.0, SEPARATION_TOLERANCE, |dt| {
                let (p1, p2) = (self.predicted(i1, dt).pose(), self.predicted(i2, dt).pose());
                !shapes_overlap(&s1, &p1, &s2, &p2, &mut ws)
            });
            self.ws = ws;
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
            let hi = bisect(t_prev - self.time, 0.0, TIME_TOLERANCE, |dt| {
                self.closing_speed(&pair, &centroid_in, &normal_in_1, dt) > CLOSING_TOLERANCE
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
