//! The first-overlap search: conservative advancement on the exact mesh-to-mesh distance with
//! a rigorous bound on the approach speed, then bisection to [`TIME_TOLERANCE`], so a thin
//! part cannot be stepped over.

use parry3d_f64::bounding_volume::BoundingVolume;

use super::stepper::interrupted;
use super::{Pair, World, TIME_TOLERANCE};
use crate::bisect::bisect;
use crate::error::{Error, Result};
use crate::math::{Aabb, Isometry, Point, Real, Vector};
use crate::overlap::{overlap_region, shapes_overlap, surface_distance, surfaces_intersect};

/// Smallest conservative-advancement step (s), and as a fraction of the step searched:
/// a graze shorter than this may be skipped (surfaces within speed x this of each other).
const MIN_ADVANCE: Real = 1e-6;
const MIN_ADVANCE_FRACTION: Real = 1e-3;
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

    /// Poses of the pair's bodies `dt` s after the current time.
    pub(super) fn poses_after(&self, pair: &Pair, dt: Real) -> (Isometry, Isometry) {
        (
            self.bodies[pair.body1].body.advanced(dt).pose(),
            self.bodies[pair.body2].body.advanced(dt).pose(),
        )
    }

    /// Box swept by a body over the next `dt` s (world).
    pub(super) fn swept_box(&self, i: usize, dt: Real) -> Aabb {
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
        let pair = self.pairs[pi].clone();
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
            if !poll(self.time) {
                return Err(interrupted(self.time));
            }
            let (p1, p2) = self.poses_after(&pair, t);
            let cap = (span - t) * speed * (1.0 + 1e-9) + 1e-12;
            let d = surface_distance(&s1, &p1, &s2, &p2, cap, &mut self.ws);
            // Zero distance without a crossing is a touch (e.g. coplanar faces on the ground):
            // not an overlap, so keep advancing by the smallest step.
            if d == 0.0 && surfaces_intersect(&s1, &p1, &s2, &p2, &mut self.ws) {
                let (b1, b2) = (&self.bodies[pair.body1].body, &self.bodies[pair.body2].body);
                let ws = &mut self.ws;
                let hi = if t == 0.0 {
                    0.0
                } else {
                    bisect(lo, t, TIME_TOLERANCE, |dt| {
                        let (p1, p2) = (b1.advanced(dt).pose(), b2.advanced(dt).pose());
                        surfaces_intersect(&s1, &p1, &s2, &p2, ws)
                    })
                };
                let overlaps = |dt: Real| {
                    let (p1, p2) = (b1.advanced(dt).pose(), b2.advanced(dt).pose());
                    !overlap_region(&s1, &p1, &s2, &p2).is_empty()
                };
                if overlaps(hi) {
                    return Ok(Some(hi));
                }
                // The surfaces only touch at hi; the overlap starts later, if at all.
                if hi < t && overlaps(t) {
                    return Ok(Some(bisect(hi, t, TIME_TOLERANCE, overlaps)));
                }
                if t >= span {
                    return Ok(None);
                }
                lo = t;
                t = (t + min_advance).min(span);
                continue;
            }
            if t >= span || t + d / speed > span {
                return Ok(None);
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
