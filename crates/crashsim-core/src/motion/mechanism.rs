//! Bodies on the ground joined by joints (a mechanism: a tractor and its trailers), advanced
//! together (docs/joints.md).
//!
//! Each member keeps its own state and forces ([`OnGround`]: gravity, wheels, tyres, its
//! contact with the ground); the members share the sub-steps (the finest any member or joint
//! needs) and every Runge-Kutta evaluation adds the joints' torques (stiffness, damping,
//! friction) and reactions (joint/constraint.rs). After each sub-step the poses and velocities
//! are projected back onto the joints, so the joints' drift stays at rounding however long the
//! run; a limit passed (or on its bound, within `RESTING_ANGLE`) is stopped there by the
//! impulse that zeroes its outward rate (an inelastic stop, [`LimitHit`]). The same start and
//! span give the same bits, as for a single body.

use super::{MotionBound, OnGround, Stage, MAX_SUBSTEPS_PER_SECOND, MAX_SUBSTEP_SUSPENSION};
use crate::body::RigidBody;
use crate::error::{Error, Place, Result};
use crate::ground::Ground;
use crate::joint::{
    applied_torques, limit_angles, limit_rows, passive_slope, project_positions,
    project_velocities, reactions, JointBody, JointSample, JointSpec, RESTING_ANGLE,
};
use crate::math::{Point, Real, Rotation, Vector};

/// Newton steps of the position projection after a sub-step (each solves the joints'
/// linearised rows; two bring a sub-step's drift, O(h^5), to rounding).
const POSITION_PROJECTIONS: usize = 3;
/// The joints' largest drift (m or rad) below which the position projection stops (and
/// solves nothing more): rounding's worth.
const SETTLED_DRIFT: Real = 1e-13;

/// How far (rad, about 0.6 deg) a joint must come back inside a limit's range before its next
/// stop there is a new event: a joint resting on its limit under a load leaves and re-enters
/// the range by a rounding's worth each sub-step (a standing pedestrian's knees and ankles
/// made 1586 events in 1 s with no margin). The stop itself is applied every time.
pub const LIMIT_RELEASE: Real = 0.01;

/// A limit a joint ran into: the inelastic stop's impulse was applied.
#[derive(Clone, Debug, PartialEq)]
pub struct LimitHit {
    /// The joint (the mechanism's index).
    pub joint: usize,
    /// The limit (the joint's index).
    pub limit: usize,
    /// When (s).
    pub time: Real,
    /// The relative angular rate stopped (rad/s).
    pub rate: Real,
}

/// What a mechanism's span did besides moving its members.
#[derive(Clone, Debug, Default)]
pub struct MechanismSpan {
    /// Per member, how its motion is bounded over the span.
    pub bounds: Vec<MotionBound>,
    /// The limits hit, in order.
    pub hits: Vec<LimitHit>,
}

fn joint_body(body: &RigidBody, s: &Stage) -> JointBody {
    let r = *Rotation::new_normalize(s.q).to_rotation_matrix().matrix();
    let props = body.props();
    let inv_inertia = r * props.inverse_inertia() * r.transpose();
    JointBody {
        x: Point::from(s.x),
        r,
        v: s.v,
        w: inv_inertia * s.l,
        inv_mass: 1.0 / props.mass(),
        inv_inertia,
    }
}

/// Beyond the angle a joint can turn in a span at its present rate, the passive moments'
/// stiffness is looked for this much further (rad, about 3 deg): the rate may grow within the
/// span.
const PASSIVE_REACH: Real = 0.05;

/// A bound (1/s) on the fastest mode of a joint's rotational spring and damper, as
/// [`super::suspension_rate`] bounds the wheels'; `passive` (N m/rad) is its passive moments'
/// stiffest slope over the span ([`passive_slope`]), added to its linear stiffness.
fn joint_rate(joint: &JointSpec, bodies: &[RigidBody], passive: Real) -> Real {
    let inverse = |b: &RigidBody| b.props().largest_inverse_moment();
    let inv = inverse(&bodies[joint.body1]) + joint.body2.map_or(0.0, |b| inverse(&bodies[b]));
    joint.damping * inv + ((joint.stiffness + passive) * inv).sqrt()
}

/// Per joint, its passive moments' stiffest slope (N m/rad) over the angles it can reach in
/// `dt` s from the members' states now (zeros, nothing computed, without passive moments).
fn passive_slopes(
    bodies: &[RigidBody],
    motions: &[OnGround],
    joints: &[JointSpec],
    dt: Real,
) -> Vec<Real> {
    if joints.iter().all(|j| j.passive.is_empty()) {
        return vec![0.0; joints.len()];
    }
    let jb: Vec<JointBody> = bodies
        .iter()
        .zip(motions)
        .map(|(b, m)| joint_body(b, &m.stage_of(b)))
        .collect();
    joints
        .iter()
        .map(|j| {
            let wb = j.body2.map_or(Vector::zeros(), |b| jb[b].w);
            let reach = (wb - jb[j.body1].w).norm() * dt + PASSIVE_REACH;
            passive_slope(j, &jb, reach, joints)
        })
        .collect()
}

/// Advances the members (`bodies[k]` moving as `motions[k]`) joined by `joints` (their
/// body indices are the members' positions) by `dt` s (> 0) from `t0`; `engaged` holds, per
/// joint and limit, whether the joint rests against it (updated).
pub fn advance_mechanism(
    bodies: &mut [RigidBody],
    motions: &mut [OnGround],
    joints: &[JointSpec],
    engaged: &mut [Vec<bool>],
    ground: &Ground,
    t0: Real,
    dt: Real,
) -> Result<MechanismSpan> {
    let m = bodies.len();
    let mut span = MechanismSpan {
        bounds: vec![MotionBound::default(); m],
        hits: Vec::new(),
    };
    if dt <= 0.0 {
        return Ok(span);
    }
    let n = mechanism_substeps(bodies, motions, joints, dt)?;
    let h = dt / n as Real;
    for (body, motion) in bodies.iter().zip(motions.iter_mut()) {
        motion.keep_ground_near(body, ground, dt);
    }
    let mut excursions = Excursions::new(bodies);
    let mut s: Vec<Stage> = bodies
        .iter()
        .zip(motions.iter())
        .map(|(b, g)| g.stage_of(b))
        .collect();
    for i in 0..n {
        let t = t0 + i as Real * h;
        // The limits the joints rest on hold over the whole sub-step (updated by `project`).
        let mut next = runge_kutta_step(bodies, motions, joints, engaged, ground, &s, t, h)?;
        for (k, st) in next.iter_mut().enumerate() {
            st.q = *Rotation::new_normalize(st.q).quaternion();
            motions[k].land(bodies[k].props(), ground, st);
        }
        project(bodies, joints, engaged, &mut next, t + h, &mut span.hits);
        for (k, st) in next.iter().enumerate() {
            motions[k].hold_anchors(bodies[k].props(), ground, st);
        }
        s = next;
        for (k, st) in s.iter().enumerate() {
            check_finite(k, st, t + h)?;
            let w = joint_body(&bodies[k], st).w;
            excursions.record(k, st.v, w);
        }
    }
    for (k, st) in s.into_iter().enumerate() {
        let props = bodies[k].props().clone();
        bodies[k] = RigidBody::from_momentum(
            props,
            Point::from(st.x),
            Rotation::new_normalize(st.q),
            st.v,
            st.l,
        );
        motions[k].deflections = st.u;
        span.bounds[k] = excursions.bound(k);
    }
    Ok(span)
}

/// The sub-steps of a mechanism's span of `dt` s: the most any member needs, and enough for
/// the joints' fastest spring and damper mode; an error past MAX_SUBSTEPS_PER_SECOND.
fn mechanism_substeps(
    bodies: &[RigidBody],
    motions: &[OnGround],
    joints: &[JointSpec],
    dt: Real,
) -> Result<usize> {
    let mut n = 1;
    for (body, motion) in bodies.iter().zip(motions.iter()) {
        n = n.max(motion.substeps(body, dt)?);
    }
    let passive = passive_slopes(bodies, motions, joints, dt);
    let fastest = joints
        .iter()
        .zip(passive)
        .map(|(j, slope)| joint_rate(j, bodies, slope))
        .fold(0.0, Real::max);
    let by_joints = (dt * fastest / MAX_SUBSTEP_SUSPENSION).ceil();
    if by_joints > (dt * MAX_SUBSTEPS_PER_SECOND).max(1.0) {
        let (what, fix) = if joints.iter().any(|j| !j.passive.is_empty()) {
            (
                "stiffness, damping and passive moments",
                "less stiffness or damping, or passive moments less steep at the angles they \
                 reach,",
            )
        } else {
            ("stiffness and damping", "less stiffness or damping")
        };
        return Err(Error::simulation(format!(
            "the joints' {what} need {by_joints:.0} integration sub-steps for {dt} s, more \
             than {MAX_SUBSTEPS_PER_SECOND:.0} per simulated second: give them {fix} for the \
             bodies' inertia"
        )));
    }
    n = n.max(by_joints as usize);
    Ok(n)
}

/// One classical Runge-Kutta sub-step of `h` s from the members' stages `s` at time `t` (s),
/// the `engaged` limits held over it: the stages at `t + h`, before landing and projection.
#[allow(clippy::too_many_arguments)]
fn runge_kutta_step(
    bodies: &[RigidBody],
    motions: &[OnGround],
    joints: &[JointSpec],
    engaged: &[Vec<bool>],
    ground: &Ground,
    s: &[Stage],
    t: Real,
    h: Real,
) -> Result<Vec<Stage>> {
    let rates = |t: Real, s: &[Stage]| {
        mechanism_rates(bodies, motions, joints, engaged, ground, t, s, false).map(|r| r.0)
    };
    let combine = |s: &[Stage], d: &[Stage], h: Real| -> Vec<Stage> {
        s.iter().zip(d).map(|(a, b)| a.axpy(h, b)).collect()
    };
    let k1 = rates(t, s)?;
    let k2 = rates(t + 0.5 * h, &combine(s, &k1, 0.5 * h))?;
    let k3 = rates(t + 0.5 * h, &combine(s, &k2, 0.5 * h))?;
    let k4 = rates(t + h, &combine(s, &k3, h))?;
    let mut next = combine(s, &k1, h / 6.0);
    next = combine(&next, &k2, h / 3.0);
    next = combine(&next, &k3, h / 3.0);
    next = combine(&next, &k4, h / 6.0);
    Ok(next)
}

/// An error when member `k`'s stage at time `t` (s) is no longer finite.
fn check_finite(k: usize, st: &Stage, t: Real) -> Result<()> {
    if !st.is_finite() {
        return Err(Error::simulation(format!(
            "the motion of jointed body {k} became non-finite: the joints, wheels or inputs \
             ask for more than the integration can follow; check them"
        ))
        .at(Place::Time(t)));
    }
    Ok(())
}

/// How far each member's motion strays over a span from its start (world frame), for its
/// [`MotionBound`]: the largest changes seen at the sub-steps' ends, plus the largest
/// change in one sub-step (for what happens between them).
struct Excursions {
    /// Per member, the velocity (m/s) and angular velocity (rad/s) at the span's start.
    start: Vec<(Vector, Vector)>,
    /// Per member, the largest |v - v0| (m/s), |w - w0| (rad/s) and |w| (rad/s); the last
    /// is unused.
    track: Vec<[Real; 4]>,
    /// Per member, the largest change of v (m/s) and of w (rad/s) over one sub-step.
    steps: Vec<(Real, Real)>,
    /// Per member, v and w at the last sub-step's end.
    prev: Vec<(Vector, Vector)>,
}

impl Excursions {
    fn new(bodies: &[RigidBody]) -> Excursions {
        let start: Vec<(Vector, Vector)> = bodies
            .iter()
            .map(|b| (b.velocity(), b.angular_velocity()))
            .collect();
        let track: Vec<[Real; 4]> = start
            .iter()
            .map(|(_, w)| [0.0, 0.0, w.norm(), 0.0])
            .collect(); // dv, dw, |w| max, (unused)
        let steps = vec![(0.0, 0.0); bodies.len()];
        let prev = start.clone();
        Excursions {
            start,
            track,
            steps,
            prev,
        }
    }

    /// Member `k`'s velocity `v` (m/s) and angular velocity `w` (rad/s) at a sub-step's end.
    fn record(&mut self, k: usize, v: Vector, w: Vector) {
        let (v0, w0) = self.start[k];
        let tr = &mut self.track[k];
        tr[0] = tr[0].max((v - v0).norm());
        tr[1] = tr[1].max((w - w0).norm());
        tr[2] = tr[2].max(w.norm());
        let steps = &mut self.steps;
        steps[k].0 = Real::max(steps[k].0, (v - self.prev[k].0).norm());
        steps[k].1 = Real::max(steps[k].1, (w - self.prev[k].1).norm());
        self.prev[k] = (v, w);
    }

    /// Member `k`'s bound over the span.
    fn bound(&self, k: usize) -> MotionBound {
        MotionBound {
            velocity_change: self.track[k][0] + self.steps[k].0,
            angular_speed: self.track[k][2] + self.steps[k].1,
            angular_velocity_change: self.track[k][1] + self.steps[k].1,
        }
    }
}

/// The rates of the members' stages at time `t` with the joints' torques and reactions (the
/// `engaged` limits' among them while the joints rest on them), and with `samples`, what
/// each joint carries (its angles, force and torque: the record's, not needed by the
/// integration).
#[allow(clippy::too_many_arguments)]
fn mechanism_rates(
    bodies: &[RigidBody],
    motions: &[OnGround],
    joints: &[JointSpec],
    engaged: &[Vec<bool>],
    ground: &Ground,
    t: Real,
    s: &[Stage],
    samples: bool,
) -> Result<(Vec<Stage>, Vec<JointSample>)> {
    let m = bodies.len();
    let mut out = Vec::with_capacity(m);
    for k in 0..m {
        out.push(
            motions[k]
                .evaluate(bodies[k].props(), ground, t, &s[k])?
                .rate,
        );
    }
    let jb: Vec<JointBody> = (0..m).map(|k| joint_body(&bodies[k], &s[k])).collect();
    let mut out_samples = Vec::with_capacity(if samples { joints.len() } else { 0 });
    for joint in joints {
        let tau = applied_torques(joint, &jb, joints);
        out[joint.body1].l -= tau;
        if let Some(b) = joint.body2 {
            out[b].l += tau;
        }
        if samples {
            out_samples.push(JointSample {
                angles: limit_angles(joint, &jb).0,
                force: Vector::zeros(),
                torque: tau,
            });
        }
    }
    let free: Vec<(Vector, Vector)> = (0..m)
        .map(|k| {
            let (w, l) = (jb[k].w, s[k].l);
            (out[k].v, jb[k].inv_inertia * (out[k].l - w.cross(&l)))
        })
        .collect();
    let (per_body, per_joint) = reactions(joints, &jb, &free, engaged);
    for (k, (f, t)) in per_body.into_iter().enumerate() {
        out[k].v += f * jb[k].inv_mass;
        out[k].l += t;
    }
    for (sample, (f, t)) in out_samples.iter_mut().zip(per_joint) {
        sample.force = f;
        sample.torque += t;
    }
    Ok((out, out_samples))
}

/// What each joint of the mechanism carries now (its angles, force and torque, a resting
/// limit's reaction included), from the members' forces at time `t`.
pub fn joint_samples(
    bodies: &[RigidBody],
    motions: &[OnGround],
    joints: &[JointSpec],
    engaged: &[Vec<bool>],
    ground: &Ground,
    t: Real,
) -> Result<Vec<JointSample>> {
    let s: Vec<Stage> = bodies
        .iter()
        .zip(motions)
        .map(|(b, g)| g.stage_of(b))
        .collect();
    Ok(mechanism_rates(bodies, motions, joints, engaged, ground, t, &s, true)?.1)
}

/// Projects the stages back onto the joints (and the limits passed), stops the limits moving
/// out and records the ones newly hit.
fn project(
    bodies: &[RigidBody],
    joints: &[JointSpec],
    engaged: &mut [Vec<bool>],
    s: &mut [Stage],
    t: Real,
    hits: &mut Vec<LimitHit>,
) {
    let m = s.len();
    for _ in 0..POSITION_PROJECTIONS {
        let jb: Vec<JointBody> = (0..m).map(|k| joint_body(&bodies[k], &s[k])).collect();
        let mut extra = Vec::new();
        for joint in joints {
            limit_rows(joint, &jb, 0.0, &mut extra);
        }
        let (shift, worst) = project_positions(joints, &jb, &extra, SETTLED_DRIFT);
        if worst < SETTLED_DRIFT {
            break;
        }
        for (st, (dx, dtheta)) in s.iter_mut().zip(shift) {
            st.x += dx;
            let turn = Rotation::from_scaled_axis(dtheta);
            st.q = *(turn * Rotation::new_normalize(st.q)).quaternion();
        }
    }
    // Velocities: the joints' rates to zero, and each limit still past moving further out.
    let jb: Vec<JointBody> = (0..m).map(|k| joint_body(&bodies[k], &s[k])).collect();
    let mut extra = Vec::new();
    let mut stopped = Vec::new();
    for (j, joint) in joints.iter().enumerate() {
        let mut rows = Vec::new();
        // The limits on their bound too, not only past it: the position projection leaves a
        // joint a rounding inside its bound as often as outside, and one left inside with its
        // outward rate passed the bound again every sub-step, its positions held there while
        // its velocities moved on; the ground's damping and friction, computed from those
        // velocities, then did work on a motion that did not happen (a lying pedestrian's leg
        // gained energy at about 22 /s; docs/joints.md, "Limits").
        let which = limit_rows(joint, &jb, RESTING_ANGLE, &mut rows);
        // A limit the joint has come LIMIT_RELEASE back inside rests against it no more.
        if engaged[j].iter().any(|&flag| flag) {
            let (theta, _) = limit_angles(joint, &jb);
            for (limit, flag) in joint.limits.iter().zip(engaged[j].iter_mut()) {
                let angle = theta[limit.angle];
                if angle > limit.lower + LIMIT_RELEASE && angle < limit.upper - LIMIT_RELEASE {
                    *flag = false;
                }
            }
        }
        for (row, (k, outward)) in rows.into_iter().zip(which) {
            if outward {
                extra.push(row);
                stopped.push((j, k));
            }
        }
    }
    let change = project_velocities(joints, &jb, &extra);
    for (k, (st, (dv, dw))) in s.iter_mut().zip(change).enumerate() {
        st.v += dv;
        // L = I_w w: the angular velocity change as momentum.
        let inertia = jb[k].r * bodies[k].props().inertia() * jb[k].r.transpose();
        st.l += inertia * dw;
    }
    for (j, k) in stopped {
        if !engaged[j][k] {
            engaged[j][k] = true;
            let axis_rate = {
                let joint = &joints[j];
                let (_, axes) = limit_angles(joint, &jb);
                let axis = axes[joint.limits[k].angle];
                let wb = joint.body2.map_or(Vector::zeros(), |b| jb[b].w);
                (wb - jb[joint.body1].w).dot(&axis)
            };
            hits.push(LimitHit {
                joint: j,
                limit: k,
                time: t,
                rate: axis_rate,
            });
        }
    }
}
