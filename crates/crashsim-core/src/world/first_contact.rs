//! The first-overlap search: conservative advancement on the exact mesh-to-mesh distance with
//! a rigorous bound on the approach speed, then bisection to [`TIME_TOLERANCE`], so a thin
//! part cannot be stepped over.

use parry3d_f64::bounding_volume::BoundingVolume;

use std::sync::atomic::Ordering;

use super::clearance::{Certificate, Front, PairMotion};
use super::stepper::interrupted;
use super::{Motion, Pair, World, TIME_TOLERANCE};
use crate::bisect::{bisect, bisect_on_grid};
use crate::error::{Error, Place, Result};
use crate::math::{Aabb, Isometry, Point, Real, Vector};
use crate::motion::MotionBound;
use crate::overlap::{
    overlap_region, shapes_overlap, surface_distance_from, surfaces_intersect, QueryWorkspace,
};

/// Smallest conservative-advancement step (s), and as a fraction of the step searched:
/// a graze shorter than this may be skipped (surfaces within speed x this of each other).
const MIN_ADVANCE: Real = 1e-6;
const MIN_ADVANCE_FRACTION: Real = 1e-3;
/// A bound on a body's acceleration on the ground (m/s^2) for how far its path bends away
/// from its chord within a step: tyre friction and gravity give at most a few g.
const CHORD_ACCELERATION: Real = 100.0;
/// The grid (s, 2^-30, within [`TIME_TOLERANCE`]) a first overlap found on the critical
/// pairs is resolved to: the first grid point where a pair crosses, whatever bracket the
/// advancement ended with (a scene and its mirror image give the same bits).
const FIRST_OVERLAP_GRID: Real = 1.0 / 1_073_741_824.0;
/// Most conservative-advancement iterations in one step before giving up.
const MAX_ADVANCE_ITERATIONS: usize = 100_000;

impl World {
    pub(super) fn check_initial_overlaps(&mut self) -> Result<()> {
        for p in &self.pairs {
            let (a, b) = (&self.bodies[p.body1], &self.bodies[p.body2]);
            if shapes_overlap(
                &a.shape,
                &a.body().pose(),
                &b.shape,
                &b.body().pose(),
                &mut self.ws,
            ) {
                return Err(Error::initial_overlap(
                    "they already overlap at the start of the run: place them apart (the \
                     engine starts every contact at a first overlap it observes)",
                )
                .at(Place::bodies(p.body1, p.body2)));
            }
        }
        Ok(())
    }

    /// How body `i`'s motion is bounded over the next `span` s. Torque-free: the CG velocity
    /// constant, |w| at most the exact bound of [`RigidBody::angular_speed_bound`], and w
    /// turning at most |dw/dt| = |R I^-1 R^T (w x L)| <= |I^-1| |w| |L| (Frobenius norm).
    /// On the ground: read off the step's prediction (the integration the advance reuses).
    ///
    /// [`RigidBody::angular_speed_bound`]: crate::body::RigidBody::angular_speed_bound
    fn motion_bound(&self, i: usize, span: Real) -> MotionBound {
        let wb = &self.bodies[i];
        match wb.motion {
            Motion::Free => {
                let w = wb.body().angular_speed_bound();
                let turn = wb.body().props().inverse_inertia().norm()
                    * w
                    * wb.body().angular_momentum().norm();
                MotionBound {
                    velocity_change: 0.0,
                    angular_speed: w,
                    angular_velocity_change: (turn * span).min(2.0 * w),
                }
            }
            Motion::Fixed => MotionBound::default(),
            Motion::OnGround(_) => match self.predicted_on_ground(i, span) {
                Some(p) => p.bound.expect("a forward prediction carries its bound"),
                // A wheel leaves the terrain ahead: the stepper reports it (kept as deferred).
                None => MotionBound {
                    velocity_change: Real::INFINITY,
                    angular_speed: Real::INFINITY,
                    angular_velocity_change: Real::INFINITY,
                },
            },
        }
    }

    /// The pair's two bodies over the next `span` s as the clearance front reads them, with
    /// a bound on how fast any point of one surface can approach the other (m/s): the
    /// relative CG speed now, how much each CG velocity can change, and each body's largest
    /// angular speed times its reach.
    fn pair_motion(&self, pair: &Pair, span: Real) -> PairMotion {
        let (wb1, wb2) = (&self.bodies[pair.body1], &self.bodies[pair.body2]);
        let bound = [
            self.motion_bound(pair.body1, span),
            self.motion_bound(pair.body2, span),
        ];
        let (v, w) = (
            [wb1.body().velocity(), wb2.body().velocity()],
            [wb1.body().angular_velocity(), wb2.body().angular_velocity()],
        );
        let speed = (v[0] - v[1]).norm()
            + bound[0].velocity_change
            + bound[1].velocity_change
            + bound[0].angular_speed * wb1.shape.radius()
            + bound[1].angular_speed * wb2.shape.radius();
        let pose = [wb1.body().pose(), wb2.body().pose()];
        PairMotion {
            rot: [
                pose[0].rotation.to_rotation_matrix().into_inner(),
                pose[1].rotation.to_rotation_matrix().into_inner(),
            ],
            pose,
            v,
            w,
            bound,
            span,
            speed,
        }
    }

    /// Poses of the pair's bodies `dt` s after the current time.
    pub(super) fn poses_after(&self, pair: &Pair, dt: Real) -> (Isometry, Isometry) {
        (
            self.predicted(pair.body1, dt).pose(),
            self.predicted(pair.body2, dt).pose(),
        )
    }

    /// Box swept by a body over the next `dt` s (world).
    pub(super) fn swept_box(&self, i: usize, dt: Real) -> Aabb {
        let wb = &self.bodies[i];
        let b0 = wb.body().pose();
        let b1 = self.predicted(i, dt).pose();
        if let Motion::OnGround(_) = wb.motion {
            // Under forces the path bends: the chord's spheres grown by how far the path can
            // leave its chord, A dt^2 / 8 with A a generous bound on the acceleration.
            let r = Vector::repeat(wb.shape.radius() + CHORD_ACCELERATION * dt * dt / 8.0);
            let (c0, c1) = (
                Point::from(b0.translation.vector),
                Point::from(b1.translation.vector),
            );
            return Aabb::new(c0.inf(&c1) - r, c0.sup(&c1) + r);
        }
        if wb.body().angular_speed_bound() == 0.0 {
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

    /// The first instant at which the apart pair `pi` overlaps, as an offset (s) in
    /// [0, span] from now; None when it does not within `span`.
    ///
    /// The pair's clearance front (clearance.rs) certifies most steps without a mesh query;
    /// a step it cannot certify is searched exactly ([`World::search_first_contact`]).
    /// The instant is one where the overlap region is not empty at the poses the bodies will
    /// have there (`RigidBody::advanced(offset)`, which [`World::advance_by`] repeats bit for
    /// bit): surfaces that only touch (faces or edges meeting exactly, e.g. when the
    /// advancement lands on the gap) bound no overlap, and the search steps past them.
    /// `poll` is asked on every iteration (false: the run was interrupted).
    pub(super) fn first_contact(
        &mut self,
        pi: usize,
        span: Real,
        poll: &mut dyn FnMut(Real) -> bool,
    ) -> Result<Option<Real>> {
        let (i1, i2) = (self.pairs[pi].body1, self.pairs[pi].body2);
        let jumps = [self.bodies[i1].jumps(), self.bodies[i2].jumps()];
        let pair = &self.pairs[pi];
        if span <= 0.0 || (pair.clear_until >= self.time + span && pair.clear_jumps == jumps) {
            return Ok(None);
        }
        if !self
            .swept_box(i1, span)
            .intersects(&self.swept_box(i2, span))
        {
            // Out of reach: no query; the front is rebuilt when the boxes meet again.
            self.pairs[pi].front = None;
            return Ok(None);
        }
        let m = self.pair_motion(&self.pairs[pi], span);
        if m.speed == 0.0 {
            return Ok(None); // neither moves nor turns: nothing can meet
        }
        let (s1, s2) = (self.bodies[i1].shape.clone(), self.bodies[i2].shape.clone());
        let mut front = self.pairs[pi]
            .front
            .take()
            .unwrap_or_else(|| Box::new(Front::new(&s1, &s2, &m)));
        let before = (front.evaluations(), front.checks());
        let certificate = front.certify(&s1, &s2, &m);
        self.clearance_evaluations
            .fetch_add(front.evaluations() - before.0, Ordering::Relaxed);
        self.clearance_checks
            .fetch_add(front.checks() - before.1, Ordering::Relaxed);
        let found = match certificate {
            Certificate::Clear(margin) => {
                // Torque-free and fixed bodies keep their speed bound until an exchange: the
                // pair stays clear while the bound cannot close the margin, with no more work.
                let free = |i: usize| matches!(self.bodies[i].motion, Motion::Free | Motion::Fixed);
                if free(i1) && free(i2) && margin > 0.0 {
                    self.pairs[pi].clear_until = self.time + margin / m.speed;
                    self.pairs[pi].clear_jumps = jumps;
                }
                None
            }
            Certificate::Critical(critical) => self.search_critical(pi, &m, &critical, poll)?,
            Certificate::TooLarge => {
                // The exact search on the whole meshes; the front is rebuilt next step.
                let mut ws = std::mem::take(&mut self.ws);
                let found = self.search_first_contact(pi, span, m.speed, None, poll, &mut ws);
                self.ws = ws;
                let (found, closest) = found?;
                let pair = &mut self.pairs[pi];
                pair.closest = closest.or(pair.closest);
                return Ok(found);
            }
        };
        if found.is_none() {
            self.pairs[pi].front = Some(front);
        }
        Ok(found)
    }

    /// The first contact within the step `m` describes when only the `critical` triangle
    /// pairs can meet (the clearance front certified every other part apart over it):
    /// conservative advancement on those pairs' distances, each with its own rate bound along
    /// its closest points' direction (a pair parting, or closing slowly, is passed in one or
    /// a few iterations), then bisection to [`TIME_TOLERANCE`] on their crossing, which within
    /// the step is the meshes' ([`surfaces_intersect`]) and makes the overlap region non-empty
    /// (surfaces that only touch are stepped past, as in [`World::search_first_contact`]).
    fn search_critical(
        &self,
        pi: usize,
        m: &PairMotion,
        critical: &[(u32, u32)],
        poll: &mut dyn FnMut(Real) -> bool,
    ) -> Result<Option<Real>> {
        let pair = &self.pairs[pi];
        let (i1, i2) = (pair.body1, pair.body2);
        let (s1, s2) = (&self.bodies[i1].shape, &self.bodies[i2].shape);
        let span = m.span;
        let at = |dt: Real| -> PairMotion {
            if dt == 0.0 {
                return m.clone();
            }
            let (b1, b2) = (self.predicted(i1, dt), self.predicted(i2, dt));
            m.later(
                dt,
                [b1.pose(), b2.pose()],
                [b1.velocity(), b2.velocity()],
                [b1.angular_velocity(), b2.angular_velocity()],
            )
        };
        let min_advance = MIN_ADVANCE.max(MIN_ADVANCE_FRACTION * span);
        // Each pair with the earliest offset (s) at which it can meet: a pair is evaluated
        // again only once the search reaches that instant, so the many pairs of two faces
        // passing close cost one evaluation each while the search closes on the few that meet.
        let mut pairs: Vec<((u32, u32), Real)> = critical.iter().map(|&p| (p, 0.0)).collect();
        let mut due: Vec<(u32, u32)> = Vec::new();
        let (mut lo, mut t) = (0.0, 0.0);
        for _ in 0..MAX_ADVANCE_ITERATIONS {
            if !poll(self.time) {
                return Err(interrupted(self.time));
            }
            let md = at(t);
            let mut next = Real::INFINITY;
            let mut touching = false;
            due.clear();

            for (p, meets) in pairs.iter_mut() {
                if *meets <= t {
                    due.push(*p);
                    *meets = match md.triangles_apart(*p, s1, s2) {
                        None => {
                            touching = true; // at distance 0: the search creeps
                            t
                        }
                        Some((gap, slope)) if slope < 0.0 => t + gap / -slope,
                        Some(_) => Real::INFINITY, // parting for the rest of the step
                    };
                }
                next = next.min(*meets);
            }
            if touching && due.iter().any(|&p| md.triangles_cross(p, s1, s2)) {
                // Only the pairs due now can have met since `lo`.
                let crossing = |dt: Real| {
                    let md = at(dt);
                    due.iter().any(|&p| md.triangles_cross(p, s1, s2))
                };
                // A crossing pair puts its segment in the overlap region (the same test of
                // the same triangles, overlap/), so the region is not empty where the
                // bisection ends: the first overlap.
                let hi = if t == 0.0 {
                    0.0
                } else {
                    bisect_on_grid(lo, t, FIRST_OVERLAP_GRID, crossing)
                };
                if hi > span {
                    // The grid point rounds up past the step's end (by under one grid step):
                    // the next step meets the overlap at its start.
                    return Ok(None);
                }
                return Ok(Some(hi));
            } else if !touching && next >= span {
                return Ok(None);
            }
            if t >= span {
                return Ok(None);
            }
            lo = t;
            t = next.max(t + min_advance).min(span);
        }
        Err(Error::simulation(format!(
            "the first-contact search did not converge within {MAX_ADVANCE_ITERATIONS} \
             iterations (please report the scene)"
        ))
        .at(Place::Time(self.time))
        .at(Place::bodies(i1, i2)))
    }

    /// The exact first-contact search over the next `span` s: conservative advancement on
    /// the mesh distance with the approach-speed bound `speed` (m/s), warm-started from
    /// `hint` (two triangles likely near), then bisection to [`TIME_TOLERANCE`]. Returns the
    /// offset found, if any, and the closest triangles met.
    fn search_first_contact(
        &self,
        pi: usize,
        span: Real,
        speed: Real,
        hint: Option<(u32, u32)>,
        poll: &mut dyn FnMut(Real) -> bool,
        ws: &mut QueryWorkspace,
    ) -> Result<(Option<Real>, Option<(u32, u32)>)> {
        let pair = &self.pairs[pi];
        let mut closest = hint.or(pair.closest);
        let (s1, s2) = (
            self.bodies[pair.body1].shape.clone(),
            self.bodies[pair.body2].shape.clone(),
        );
        let mut lo = 0.0; // offset from self.time known apart
        let mut t = 0.0;
        let min_advance = MIN_ADVANCE.max(MIN_ADVANCE_FRACTION * span);
        for _ in 0..MAX_ADVANCE_ITERATIONS {
            if !poll(self.time) {
                return Err(interrupted(self.time));
            }
            let (p1, p2) = self.poses_after(pair, t);
            let cap = (span - t) * speed * (1.0 + 1e-9) + 1e-12;
            let (d, near) = surface_distance_from(&s1, &p1, &s2, &p2, cap, closest, ws);
            self.distance_queries.fetch_add(1, Ordering::Relaxed);
            closest = near.or(closest);
            // Zero distance without a crossing is a touch (e.g. coplanar faces on the ground):
            // not an overlap, so keep advancing by the smallest step.
            if d == 0.0 && surfaces_intersect(&s1, &p1, &s2, &p2, ws) {
                let hi = if t == 0.0 {
                    0.0
                } else {
                    bisect(lo, t, TIME_TOLERANCE, |dt| {
                        let (p1, p2) = self.poses_after(pair, dt);
                        surfaces_intersect(&s1, &p1, &s2, &p2, ws)
                    })
                };
                let overlaps = |dt: Real| {
                    let (p1, p2) = self.poses_after(pair, dt);
                    !overlap_region(&s1, &p1, &s2, &p2).is_empty()
                };
                if overlaps(hi) {
                    return Ok((Some(hi), closest));
                }
                // The surfaces only touch at hi; the overlap starts later, if at all.
                if hi < t && overlaps(t) {
                    return Ok((Some(bisect(hi, t, TIME_TOLERANCE, overlaps)), closest));
                }
                if t >= span {
                    return Ok((None, closest));
                }
                lo = t;
                t = (t + min_advance).min(span);
                continue;
            }
            if t >= span || t + d / speed > span {
                return Ok((None, closest));
            }
            lo = t;
            t = (t + (d / speed).max(min_advance)).min(span);
        }
        Err(Error::simulation(format!(
            "the first-contact search did not converge within {MAX_ADVANCE_ITERATIONS} \
             iterations (please report the scene)"
        ))
        .at(Place::Time(self.time))
        .at(Place::bodies(pair.body1, pair.body2)))
    }
}
