//! Soft pairs in the world: from the first overlap the compliant contact of soft.rs acts at
//! the end of every step until the meshes separate (no timer, no exchange).

use super::events::{ContactEvent, ContactEventKind, RunOutput};
use super::{Phase, World};
use crate::error::{Error, Place, Result};
use crate::math::{Point, Real, Vector};
use crate::overlap::OverlapRegion;
use crate::soft::{MAX_SOFT_STEP_ANGLE, MAX_SOFT_SUBSTEPS};

impl World {
    /// Sizes each soft pair's sub-steps for a run at step `dt` (s): while it presses, a step
    /// is cut into n = ceil(sqrt(k / m) dt / [`MAX_SOFT_STEP_ANGLE`]) sub-steps, `m` the
    /// lighter moving body's mass (1 when the step is short enough: the run is then the
    /// same, bit for bit, as without sub-steps). Refuses a pair that would need more than
    /// [`MAX_SOFT_SUBSTEPS`].
    pub(super) fn size_soft_substeps(&mut self, dt: Real) -> Result<()> {
        for pi in 0..self.pairs.len() {
            let p = &self.pairs[pi];
            let Some(soft) = p.soft else { continue };
            let mass = [p.body1, p.body2]
                .iter()
                .map(|&i| self.bodies[i].body().props().mass())
                .filter(|m| m.is_finite())
                .fold(Real::INFINITY, Real::min);
            let angle = (soft.stiffness / mass).sqrt() * dt;
            let n = (angle / MAX_SOFT_STEP_ANGLE).ceil().max(1.0);
            if n > MAX_SOFT_SUBSTEPS as Real {
                let most = MAX_SOFT_STEP_ANGLE * MAX_SOFT_SUBSTEPS as Real;
                let stiffest = mass * (most / dt).powi(2);
                let longest = most / (soft.stiffness / mass).sqrt();
                return Err(Error::invalid(format!(
                    "their soft contact is too stiff for the step: {:.3e} N/m on {mass:.3} kg \
                     turns sqrt(k/m) dt = {angle:.2} rad per step, more than \
                     {MAX_SOFT_SUBSTEPS} sub-steps of {MAX_SOFT_STEP_ANGLE} take; give a \
                     stiffness of at most {stiffest:.3e} N/m or a step of at most \
                     {longest:.2e} s",
                    soft.stiffness
                ))
                .at(Place::bodies(p.body1, p.body2)));
            }
            self.pairs[pi].soft_substeps = n as usize;
        }
        Ok(())
    }

    /// Where the step now under way ends while a soft pair presses and needs sub-steps: the
    /// next of the grid step's n equal parts past now (the grid step from `grid - dt` to
    /// `grid`, n the most any pressing pair needs); None when no pair needs them or the next
    /// part is the grid point itself.
    pub(super) fn soft_substep_end(&self, grid: Real, dt: Real) -> Option<Real> {
        let n = self
            .pairs
            .iter()
            .filter(|p| matches!(p.phase, Phase::Pressing { .. }))
            .map(|p| p.soft_substeps)
            .max()?;
        if n <= 1 {
            return None;
        }
        let (start, h) = (grid - dt, dt / n as Real);
        // The part now is the one that holds `time` (a point on a boundary, within a
        // millionth of a part, belongs to the part it starts).
        let j = ((self.time - start) / h + 1e-6).floor().max(0.0) + 1.0;
        let end = start + j * h;
        (end < grid - 1e-6 * h).then_some(end)
    }

    /// After a step from `t_prev`, a pressing soft pair either separated (logged, apart) or
    /// gets its compliant impulse for the step: normal from the overlap's depth and closing
    /// speed, friction against the sliding at the centroid, both through the joints' mobility.
    pub(super) fn press(&mut self, pi: usize, t_prev: Real, out: &mut RunOutput) {
        let (Some(soft), Phase::Pressing { depth: before }) =
            (self.pairs[pi].soft, &self.pairs[pi].phase)
        else {
            return;
        };
        let before = *before;
        let (i1, i2) = (self.pairs[pi].body1, self.pairs[pi].body2);
        let span = self.time - t_prev;
        let (b1, b2) = (self.bodies[i1].body(), self.bodies[i2].body());
        let Some(g) = self.contact_geometry(&self.pairs[pi], b1, b2, None) else {
            out.contacts.push(ContactEvent {
                body1: i1,
                body2: i2,
                time: self.time,
                kind: ContactEventKind::Separation,
            });
            self.pairs[pi].phase = Phase::Apart;
            return;
        };
        let n = g.normal;
        let c = center_of_pressure(&g.region, &n).unwrap_or(g.centroid);
        // Closing > 0: body 1's point moving into body 2's along n (n from 1 into 2).
        let u = b1.point_velocity(&c) - b2.point_velocity(&c);
        let k = self.pair_mobility(i1, i2, &c);
        let along = |d: &crate::math::Vector| 1.0 / d.dot(&(k * d));
        let depth = g.region_max.x - g.region_min.x;
        self.pairs[pi].phase = Phase::Pressing { depth };
        // The damper takes the step's mean closing speed, the depth's change over it: the
        // speed at the step's end lags by half a step and held a body resting on the slab
        // up by zeta sqrt(k/m) dt of its weight (3 % at 1 ms; tests/integration/soft.rs).
        let closing = if span > 0.0 {
            (depth - before) / span
        } else {
            u.dot(&n)
        };
        let normal = soft.normal_impulse(depth, closing, along(&n), span);
        if normal <= 0.0 {
            return;
        }
        // On body 2: the normal along n, the friction along body 1's sliding past it.
        let mut j = n * normal;
        let sliding = u - n * u.dot(&n);
        if let Some(t) = sliding.try_normalize(1e-12) {
            let stop = along(&t) * sliding.norm();
            j += t * (self.pairs[pi].params.friction * normal).min(stop);
        }
        self.bodies[i1].apply_impulse(&(-j), &c);
        self.bodies[i2].apply_impulse(&j, &c);
        self.share_impulse(i1);
        self.share_impulse(i2);
    }
}

/// Where a distributed spring's force acts on an overlap (m, world): the mean of the vertices
/// inside the other mesh weighted by how deep they are along `n` (mesh 1's into mesh 2 along
/// n, mesh 2's against it) below the mean of the surfaces' crossing points: a flat body
/// resting level presses at its middle, a tilted one towards its deeper edge (the overlap's
/// box centre would let a sliding block roll over its front edge). None without crossings or
/// deep vertices.
fn center_of_pressure(region: &OverlapRegion, n: &Vector) -> Option<Point> {
    let crossings = 2 * region.segment_count;
    if crossings == 0 {
        return None;
    }
    let level = region.points[..crossings]
        .iter()
        .map(|p| p.coords.dot(n))
        .sum::<Real>()
        / crossings as Real;
    let inside = &region.points[crossings..];
    let (mut sum, mut weight) = (Vector::zeros(), 0.0);
    for (k, p) in inside.iter().enumerate() {
        let along = p.coords.dot(n) - level;
        let depth = if k < region.inside_1_count {
            along
        } else {
            -along
        };
        if depth > 0.0 {
            sum += p.coords * depth;
            weight += depth;
        }
    }
    (weight > 0.0).then(|| Point::from(sum / weight))
}
