//! The first-overlap search: conservative advancement on the exact mesh-to-mesh distance with
//! a rigorous bound on the approach speed, then bisection to [`TIME_TOLERANCE`], so a thin
//! part cannot be stepped over.

use parry3d_f64::bounding_volume::BoundingVolume;

use super::stepper::interrupted;
use super::{Motion, Pair, World, TIME_TOLERANCE};
use crate::bisect::bisect;
use crate::error::{Error, Result};
use crate::math::{Aabb, Isometry, Point, Real, Vector};
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
/// What a first-contact search found: the instant (an offset from now, s) if any, the time
/// (s) before which the pair is certified clear, and the closest pair of triangles met.
type Search = (Option<Real>, Real, Option<(u32, u32)>);

/// The farthest a pair's first distance query looks ahead, in steps: far enough that a pair
/// drifting apart is queried a few times, near enough that the query stays cheap.
const MAX_LOOKAHEAD: Real = 64.0;
/// Most conservative-advancement iterations in one step before giving up.
const MAX_ADVANCE_ITERATIONS: usize = 100_000;

impl World {
    pub(super) fn check_initial_overlaps(&mut self) -> Result<()> {
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

    /// How much body `i`'s CG velocity can change (m/s) and its largest angular speed
    /// (rad/s) over the next `span` s. Torque-free: no change and the exact bound of
    /// [`RigidBody::angular_speed_bound`]. On the ground: from the predicted states at
    /// sub-step nodes, each grown by the largest change between neighbouring nodes (the
    /// motion within a sub-step stays within it).
    ///
    /// [`RigidBody::angular_speed_bound`]: crate::body::RigidBody::angular_speed_bound
    fn motion_bound(&self, i: usize, span: Real) -> (Real, Real) {
        let wb = &self.bodies[i];
        match wb.motion {
            Motion::Free => (0.0, wb.body.angular_speed_bound()),
            Motion::Fixed => (0.0, 0.0),
            Motion::OnGround(ref g) => {
                let ground = self
                    .ground
                    .as_ref()
                    .expect("a body on the ground has a ground");
                match g.motion_bound(&wb.body, ground, self.time, span) {
                    Ok(bound) => bound,
                    Err(e) => {
                        // A wheel leaves the terrain ahead: the stepper reports it.
                        let e = match e {
                            Error::Simulation(m) => Error::Simulation(format!("body {i}: {m}")),
                            other => other,
                        };
                        self.deferred.lock().expect("not poisoned").get_or_insert(e);
                        (Real::INFINITY, Real::INFINITY)
                    }
                }
            }
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
        let b0 = wb.body.pose();
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

    /// The first instant at which the apart pair `pi` overlaps, as an offset (s) in
    /// [0, span] from now; None when it does not within `span`.
    ///
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
        let pair = &self.pairs[pi];
        if pair.clear_until >= self.time + span {
            return Ok(None); // certified clear: no mesh query
        }
        let mut ws = std::mem::take(&mut self.ws);
        let found = self.first_contact_with(pi, span, poll, &mut ws);
        self.ws = ws;
        let (found, clear, closest) = found?;
        let pair = &mut self.pairs[pi];
        pair.closest = closest.or(pair.closest);
        let horizon = span * pair.lookahead;
        pair.clear_until = clear;
        if clear >= self.time + horizon * (1.0 - 1e-6) {
            pair.lookahead = (pair.lookahead * 2.0).min(MAX_LOOKAHEAD); // it held: look further
        } else if clear < self.time + 2.0 * span {
            pair.lookahead = 1.0; // the surfaces are close
        }
        Ok(found)
    }

    /// [`World::first_contact`] with a query workspace of its own; also returns the time
    /// (s) before which the pair is certified clear.
    ///
    /// The certificate: the first distance query reaches `lookahead` spans ahead (its cap is
    /// the distance the surfaces can close over that horizon); a distance d with a speed
    /// bound S valid over the horizon (exact for torque-free and fixed bodies, whose bound
    /// holds for ever; predicted over the horizon for a body on the ground) means no contact
    /// for d / S. Steps inside it make no mesh query.
    fn first_contact_with(
        &self,
        pi: usize,
        span: Real,
        poll: &mut dyn FnMut(Real) -> bool,
        ws: &mut QueryWorkspace,
    ) -> Result<Search> {
        let pair = self.pairs[pi].clone();
        let mut closest = pair.closest;
        let none = Real::NEG_INFINITY;
        if span <= 0.0 {
            return Ok((None, none, closest));
        }
        if !self
            .swept_box(pair.body1, span)
            .intersects(&self.swept_box(pair.body2, span))
        {
            return Ok((None, self.time + span, closest));
        }
        let (wb1, wb2) = (&self.bodies[pair.body1], &self.bodies[pair.body2]);
        let (s1, s2) = (wb1.shape.clone(), wb2.shape.clone());
        // Bound on how fast any point of one surface can approach the other (m/s) over the
        // span: the relative CG speed now, how much each CG velocity can change, and each
        // body's largest angular speed times its reach.
        let (dv1, w1) = self.motion_bound(pair.body1, span);
        let (dv2, w2) = self.motion_bound(pair.body2, span);
        let speed = (wb1.body.velocity() - wb2.body.velocity()).norm()
            + dv1
            + dv2
            + w1 * s1.radius()
            + w2 * s2.radius();
        if speed == 0.0 {
            return Ok((None, self.time + span, closest));
        }
        // The horizon of the first query and the speed bound over it.
        let on_ground = [pair.body1, pair.body2]
            .iter()
            .any(|&i| matches!(self.bodies[i].motion, Motion::OnGround(_)));
        let horizon = span * pair.lookahead;
        let horizon_speed = if on_ground && pair.lookahead > 1.0 {
            let (dv1, w1) = self.motion_bound(pair.body1, horizon);
            let (dv2, w2) = self.motion_bound(pair.body2, horizon);
            ((wb1.body.velocity() - wb2.body.velocity()).norm()
                + dv1
                + dv2
                + w1 * s1.radius()
                + w2 * s2.radius())
            .max(speed)
        } else {
            speed
        };
        let mut lo = 0.0; // offset from self.time known apart
        let mut t = 0.0;
        let min_advance = MIN_ADVANCE.max(MIN_ADVANCE_FRACTION * span);
        for _ in 0..MAX_ADVANCE_ITERATIONS {
            if !poll(self.time) {
                return Err(interrupted(self.time));
            }
            let (p1, p2) = self.poses_after(&pair, t);
            let cap = if t == 0.0 {
                (span * speed).max(horizon * horizon_speed) * (1.0 + 1e-9) + 1e-12
            } else {
                (span - t) * speed * (1.0 + 1e-9) + 1e-12
            };
            let (d, near) = surface_distance_from(&s1, &p1, &s2, &p2, cap, closest, ws);
            self.distance_queries
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            closest = near.or(closest);
            // Zero distance without a crossing is a touch (e.g. coplanar faces on the ground):
            // not an overlap, so keep advancing by the smallest step.
            if d == 0.0 && surfaces_intersect(&s1, &p1, &s2, &p2, ws) {
                let hi = if t == 0.0 {
                    0.0
                } else {
                    bisect(lo, t, TIME_TOLERANCE, |dt| {
                        let (p1, p2) = self.poses_after(&pair, dt);
                        surfaces_intersect(&s1, &p1, &s2, &p2, ws)
                    })
                };
                let overlaps = |dt: Real| {
                    let (p1, p2) = self.poses_after(&pair, dt);
                    !overlap_region(&s1, &p1, &s2, &p2).is_empty()
                };
                if overlaps(hi) {
                    return Ok((Some(hi), none, closest));
                }
                // The surfaces only touch at hi; the overlap starts later, if at all.
                if hi < t && overlaps(t) {
                    return Ok((Some(bisect(hi, t, TIME_TOLERANCE, overlaps)), none, closest));
                }
                if t >= span {
                    return Ok((None, self.time + span, closest));
                }
                lo = t;
                t = (t + min_advance).min(span);
                continue;
            }
            if t >= span || t + d / speed > span {
                let clear = if t == 0.0 {
                    (d / horizon_speed).min(horizon)
                } else {
                    span
                };
                return Ok((None, self.time + clear.max(span), closest));
            }
            lo = t;
            t = (t + (d / speed).max(min_advance)).min(span);
        }
        Err(Error::Simulation(format!(
            "the first-contact search for bodies {} and {} did not converge within \
             {MAX_ADVANCE_ITERATIONS} iterations near t = {} s (please report the scene)",
            pair.body1, pair.body2, self.time
        )))
    }
}
