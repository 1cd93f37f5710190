//! Motion between exchanges on the ground: gravity, each wheel's spring-damper and tyre, and
//! the body's own contact with the ground, integrated together.
//!
//! The state is the rigid body's (CG position, orientation, velocity, world angular momentum
//! about the CG) plus each tyre's tread deflection. Over a span `dt` the state is advanced by
//! classical Runge-Kutta in `n` equal sub-steps, n the smallest count that keeps each at most
//! [`MAX_SUBSTEP`] s and at most [`MAX_SUBSTEP_ANGLE`] rad of rotation: the same start state and
//! span give the same bits, so a prediction (`advanced`) and the run's own advance agree
//! exactly. Without ground a body keeps the exact torque-free motion of [`crate::body`].
//!
//! The body's contact with the ground (a rollover, a vehicle pushed onto its side, a body
//! without wheels) is a stiff spring-damper per point of the mesh's convex hull (the only
//! points of a solid that can touch a plane first), weighted by the hull area around each,
//! with Coulomb friction regularised below [`BODY_SLIP_SPEED`]; the points inside the
//! wheels are left to the wheels.

use std::sync::Arc;

use crate::body::{MassProperties, RigidBody};
use crate::error::{Error, Place, Result};
use crate::ground::{Ground, GroundPoint};
use crate::math::{Matrix, Point, Real, Rotation, Vector};
use crate::vehicle::{Braking, VehicleSpec, WheelAction, WheelState, GRAVITY};

mod ground_contact;
mod mechanism;

pub use mechanism::{advance_mechanism, joint_samples, LimitHit, MechanismSpan};

use ground_contact::GroundNear;
pub use ground_contact::{BodyContact, BODY_SLIP_SPEED};

/// Longest integration sub-step (s).
pub const MAX_SUBSTEP: Real = 1e-3;
/// Largest rotation (rad) in one sub-step.
pub const MAX_SUBSTEP_ANGLE: Real = 0.02;
/// Largest part of a tread's deflection the rolling may renew in one sub-step (h |v_x| /
/// sigma): classical Runge-Kutta is stable up to 2.8 on this decay; 1 keeps it accurate. It
/// binds only past about 100 m/s with the default 0.1 m relaxation length, or for short
/// ones (3 mm at 20 m/s: 7 sub-steps per ms; NaN from 0.17 s without it).
pub const MAX_SUBSTEP_RELAXATION: Real = 1.0;
/// Largest h |lambda| per sub-step of the fastest mode of the body on its spring-dampers
/// (see `OnGround::suspension_rate`): classical Runge-Kutta is stable to 2.78 on a decay and
/// 2.83 on an oscillation, and never adds energy to either below that. Damping ratios of 1e4
/// at 1 ms sub-steps (h |lambda| about 160) threw a locked car 107 m into the air.
pub const MAX_SUBSTEP_SUSPENSION: Real = 2.0;
/// Most sub-steps per simulated second: past this (a body spinning at about 20,000 rad/s or a
/// tread renewed as fast) the run stops with an error instead of running for hours.
pub const MAX_SUBSTEPS_PER_SECOND: Real = 1e6;

/// How far a body's motion can stray over a span from its state at the span's start (world
/// frame): what the first-contact search's guarantee (no contact stepped over) rests on.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MotionBound {
    /// Largest |v(t) - v(t0)| of the CG velocity (m/s).
    pub velocity_change: Real,
    /// Largest |w(t)| (rad/s).
    pub angular_speed: Real,
    /// Largest |w(t) - w(t0)| (rad/s).
    pub angular_velocity_change: Real,
}

/// What one wheel does at an instant (world frame, SI), for the record.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WheelSample {
    /// Where the tyre meets the ground (m); the point below the wheel centre when airborne.
    pub contact: Point,
    /// Normal load (N, >= 0).
    pub load: Real,
    /// The ground's force on the tyre (N): normal plus tyre forces.
    pub force: Vector,
    /// True when the patch slides at the friction limit (a tyre mark).
    pub sliding: bool,
    /// Road-wheel angle (rad, about the body z axis, + left).
    pub steer: Real,
}

/// A body on the ground: its wheels (if any), its contact points and the tyres' state.
#[derive(Clone, Debug)]
pub struct OnGround {
    /// Wheels, tyre and inputs; None for a body without wheels.
    pub vehicle: Option<Arc<VehicleSpec>>,
    /// The body's contact points with the ground.
    pub contact: Arc<BodyContact>,
    /// Tread deflection per wheel (m, wheel axes).
    pub deflections: Vec<[Real; 2]>,
    /// The vehicle's impulse exchanges so far (wheel-state switches at exchanges).
    pub exchanges: usize,
    /// A bound on the ground around the body, kept between steps while the body's box stays
    /// over its region (it only saves work: which points touch is decided exactly).
    ground_near: Option<GroundNear>,
    /// Static friction's anchor of each contact point on the ground (m, world), None off
    /// the ground; empty when none touches or the contact has no static friction.
    anchors: Vec<Option<Point>>,
}

/// A body state during integration (the quaternion unnormalised inside a step).
#[derive(Clone, Debug)]
struct Stage {
    x: Vector,
    q: nalgebra::Quaternion<Real>,
    v: Vector,
    l: Vector,
    u: Vec<[Real; 2]>,
}

impl Stage {
    /// Whether every component (position, velocity, angular momentum, wheel states) is
    /// finite (the quaternion is normalised from these, so it is not looked at).
    fn is_finite(&self) -> bool {
        self.x
            .iter()
            .chain(self.v.iter())
            .chain(self.l.iter())
            .all(|c| c.is_finite())
            && self.u.iter().flatten().all(|c| c.is_finite())
    }

    fn axpy(&self, h: Real, d: &Stage) -> Stage {
        Stage {
            x: self.x + d.x * h,
            q: self.q + d.q * h,
            v: self.v + d.v * h,
            l: self.l + d.l * h,
            u: self
                .u
                .iter()
                .zip(&d.u)
                .map(|(a, b)| [a[0] + b[0] * h, a[1] + b[1] * h])
                .collect(),
        }
    }
}

/// Forces of one evaluation: the stage's rate, and per wheel what the record needs.
struct Evaluation {
    rate: Stage,
    wheels: Vec<WheelSample>,
}

/// A bound (1/s) on |lambda| of every mode of the body on its wheels' spring-dampers,
/// linearised: with C and K the dampings and rates seen at the body's coordinates
/// (sum over the wheels of c_k J_k^T J_k, J_k the wheel's normal velocity per body
/// velocity), |lambda| <= lambda_max(M^-1 C) + sqrt(lambda_max(M^-1 K)), and each
/// lambda_max is at most the trace, sum_k c_k / m_k (and the anti-roll bars' k_bar (1 / m_l +
/// 1 / m_r)), with 1 / m_k = 1/m + |r_k|^2 /
/// I_min <= the inverse effective mass at the wheel for any orientation (r_k from the CG
/// to the farthest point of the tyre). For a car at 1.3 Hz and 0.3 it is about 45 /s:
/// 1 ms sub-steps are far inside it.
pub fn suspension_rate(spec: &VehicleSpec, props: &MassProperties) -> Real {
    let inverse_inertia_max = props.largest_inverse_moment();
    let inverse_mass = |w: &crate::vehicle::WheelSpec| {
        let reach = w.center.coords.norm() + w.radius;
        1.0 / props.mass() + reach * reach * inverse_inertia_max
    };
    let (mut damping, mut stiffness) = (0.0, 0.0);
    for w in &spec.wheels {
        damping += w.damping * inverse_mass(w);
        stiffness += w.spring_rate * inverse_mass(w);
    }
    // A bar couples its two wheels: k_bar (J_l - J_r)^T (J_l - J_r), trace k_bar (1/m_l + 1/m_r).
    for bar in &spec.anti_roll {
        let (l, r) = (&spec.wheels[bar.left], &spec.wheels[bar.right]);
        stiffness += bar.rate(&spec.wheels) * (inverse_mass(l) + inverse_mass(r));
    }
    damping + stiffness.sqrt()
}

/// The normal loads (N) of the wheels in load groups ([`VehicleSpec::load_groups`]), None
/// for the others (empty without groups): each group's springs and dampers act on its
/// wheels' mean travel and travel rate (a walking beam's pivot) and the group's load is
/// shared equally by its wheels on the ground. `below[k]` is wheel k's centre, the ground
/// below it and its height above it (m); `v`, `w`, `x` the body's velocity, angular velocity
/// and CG.
fn shared_loads(
    spec: &VehicleSpec,
    below: &[(Point, GroundPoint, Real)],
    v: &Vector,
    w: &Vector,
    x: &Point,
    bar_load: &[Real],
) -> Vec<Option<Real>> {
    if spec.load_groups.is_empty() {
        return Vec::new();
    }
    let mut out = vec![None; spec.wheels.len()];
    for set in &spec.load_groups {
        let n = set.len() as Real;
        let (mut travel, mut rate) = (0.0, 0.0);
        for &k in set {
            let (c, g, h) = &below[k];
            travel += (spec.wheels[k].radius - h) / n;
            rate += -(v + w.cross(&(c - x))).dot(&g.normal) / n;
        }
        let total: Real = set
            .iter()
            .map(|&k| spec.wheels[k].normal_load(travel, rate, bar_load[k]))
            .sum();
        // On the ground: the wheel's own spring would push (a wheel lifted past its spring's
        // travel carries nothing, the others the group's load).
        let touching: Vec<usize> = set
            .iter()
            .copied()
            .filter(|&k| {
                let (c, g, h) = &below[k];
                let own = -(v + w.cross(&(c - x))).dot(&g.normal);
                spec.wheels[k].normal_load(spec.wheels[k].radius - h, own, bar_load[k]) > 0.0
            })
            .collect();
        for &k in set {
            out[k] = Some(if touching.contains(&k) {
                total / touching.len() as Real
            } else {
                0.0
            });
        }
    }
    out
}

/// Each wheel's centre (world, m), the ground below it and its height above it (m), for
/// the body at CG `x` (m) with rotation `r` (body to world) at time `t` (s); an error (at
/// the wheel) when a wheel has left the terrain.
fn wheels_below(
    spec: &VehicleSpec,
    ground: &Ground,
    x: &Point,
    r: &Matrix,
    t: Real,
) -> Result<Vec<(Point, GroundPoint, Real)>> {
    let mut below = Vec::with_capacity(spec.wheels.len());
    for (k, wheel) in spec.wheels.iter().enumerate() {
        let c = x + r * wheel.center.coords;
        let g = ground.below(&c).ok_or_else(|| {
            Error::simulation(format!(
                "it left the terrain at ({:.2}, {:.2}) m: the terrain mesh has no surface \
                 there (extend it or add ground under the vehicle's path)",
                c.x, c.y
            ))
            .at(Place::Time(t))
            .at(Place::Wheel(k))
        })?;
        let h = (c - g.point).dot(&g.normal);
        below.push((c, g, h));
    }
    Ok(below)
}

/// The anti-roll bars' loads per wheel (N, + pushing the body up), each wheel's travel held
/// at its full droop (spring unloaded) once it hangs free; `below[k]` as from
/// [`wheels_below`].
fn anti_roll_loads(spec: &VehicleSpec, below: &[(Point, GroundPoint, Real)]) -> Vec<Real> {
    let mut bar_load = vec![0.0; spec.wheels.len()];
    for bar in &spec.anti_roll {
        let travel = |k: usize| {
            let wh = &spec.wheels[k];
            (wh.radius - below[k].2).max(-wh.static_load / wh.spring_rate)
        };
        let f = bar.rate(&spec.wheels) * (travel(bar.left) - travel(bar.right));
        bar_load[bar.left] += f;
        bar_load[bar.right] -= f;
    }
    bar_load
}

/// A tyre's rolling direction and lateral direction (world, unit, in the ground's plane of
/// unit normal `n`) for its wheel steered `steer` rad about the body's z axis, the body's
/// rotation `r` (body to world).
fn tyre_axes(r: &Matrix, n: &Vector, steer: Real) -> (Vector, Vector) {
    let heading = if steer != 0.0 {
        let (sin, cos) = steer.sin_cos();
        r * Vector::new(cos, sin, 0.0)
    } else {
        r * Vector::x()
    };
    let along = heading - n * heading.dot(n);
    let ex = if along.norm() > 1e-9 {
        along.normalize()
    } else {
        // The wheel points straight up or down: no rolling direction.
        n.cross(&(r * Vector::y())).normalize()
    };
    let ey = n.cross(&ex);
    (ex, ey)
}

impl OnGround {
    /// A body on the ground with its wheels (if any) at rest (no tread deflection).
    pub fn new(vehicle: Option<Arc<VehicleSpec>>, contact: Arc<BodyContact>) -> OnGround {
        let n = vehicle.as_ref().map_or(0, |v| v.wheels.len());
        OnGround {
            vehicle,
            contact,
            deflections: vec![[0.0; 2]; n],
            exchanges: 0,
            ground_near: None,
            anchors: Vec::new(),
        }
    }

    /// How wheel `k` of a vehicle of `mass` kg turns at time `t` with normal load `fz` (N) and
    /// friction `mu`.
    fn action(
        &self,
        spec: &VehicleSpec,
        k: usize,
        t: Real,
        fz: Real,
        mu: Real,
        mass: Real,
    ) -> WheelAction {
        match spec.inputs.wheel_state(k, t, self.exchanges) {
            WheelState::Locked => WheelAction {
                locked: true,
                brake_capacity: 0.0,
                drive: 0.0,
            },
            WheelState::Braked(f) => WheelAction {
                locked: false,
                brake_capacity: f * mu * fz,
                drive: 0.0,
            },
            WheelState::Free => {
                let capacity = match spec.inputs.brake.get(k).and_then(|b| b.as_ref()) {
                    Some(Braking::Fraction(table)) => table.at(t) * mu * fz,
                    Some(Braking::Deceleration(table)) => table.at(t) / GRAVITY * fz,
                    Some(Braking::Distributed {
                        deceleration,
                        share,
                    }) => share * mass * deceleration.at(t),
                    None => 0.0,
                };
                // Without ABS a brake asked for more than the friction locks its wheel.
                let locked = !spec.abs && capacity > mu * fz;
                WheelAction {
                    locked,
                    brake_capacity: if locked { 0.0 } else { capacity },
                    drive: if locked {
                        0.0
                    } else {
                        spec.inputs.drive_at(k, t)
                    },
                }
            }
        }
    }

    /// The rates of a stage at time `t`, and the wheels' samples.
    fn evaluate(
        &self,
        props: &MassProperties,
        ground: &Ground,
        t: Real,
        s: &Stage,
    ) -> Result<Evaluation> {
        let q = Rotation::new_normalize(s.q);
        let rot = q.to_rotation_matrix();
        let r = rot.matrix();
        let inv_i = r * props.inverse_inertia() * r.transpose();
        let w = inv_i * s.l;
        let x = Point::from(s.x);
        let m = props.mass();
        let mut force = Vector::new(0.0, 0.0, -m * GRAVITY);
        let mut torque = Vector::zeros();
        let mut du = vec![[0.0; 2]; s.u.len()];
        let mut wheels = Vec::with_capacity(s.u.len());
        if let Some(spec) = &self.vehicle {
            let steering = spec.steering_at(t, &x, r, &s.v);
            let below = wheels_below(spec, ground, &x, r, t)?;
            let bar_load = anti_roll_loads(spec, &below);
            let shared = shared_loads(spec, &below, &s.v, &w, &x, &bar_load);
            for (k, wheel) in spec.wheels.iter().enumerate() {
                let (c, g, h) = below[k];
                let n = g.normal;
                let contact = c - n * h;
                let vc = s.v + w.cross(&(c - x));
                let fz = match shared.get(k).copied().flatten() {
                    Some(fz) => fz,
                    None => wheel.normal_load(wheel.radius - h, -vc.dot(&n), bar_load[k]),
                };
                let steer = spec.wheel_steer(k, t, &steering);
                let (ex, ey) = tyre_axes(r, &n, steer);
                let vp = s.v + w.cross(&(contact - x));
                let mu = ground.tyre_friction_at(contact.x, contact.y);
                let action = self.action(spec, k, t, fz, mu, m);
                let tf = spec.tyre.force(
                    fz,
                    wheel.static_load,
                    mu,
                    vp.dot(&ex),
                    vp.dot(&ey),
                    s.u[k],
                    &action,
                );
                let f = n * fz + ex * tf.force[0] + ey * tf.force[1];
                force += f;
                torque += (contact - x).cross(&f);
                du[k] = tf.deflection_rate;
                wheels.push(WheelSample {
                    contact,
                    load: fz,
                    force: f,
                    sliding: tf.sliding,
                    steer,
                });
            }
        }
        self.body_contact(ground, &x, r, &s.v, &w, &mut force, &mut torque);
        let wq = nalgebra::Quaternion::from_parts(0.0, w);
        Ok(Evaluation {
            rate: Stage {
                x: s.v,
                q: wq * s.q * 0.5,
                v: force / m,
                l: torque,
                u: du,
            },
            wheels,
        })
    }

    fn stage_of(&self, body: &RigidBody) -> Stage {
        Stage {
            x: body.position().coords,
            q: *body.orientation().quaternion(),
            v: body.velocity(),
            l: body.angular_momentum(),
            u: self.deflections.clone(),
        }
    }

    /// Sub-steps for a span of `dt` s from `body`'s state: at most [`MAX_SUBSTEP`] s, a
    /// rotation of [`MAX_SUBSTEP_ANGLE`], a tread renewal of [`MAX_SUBSTEP_RELAXATION`]
    /// (from the fastest a contact patch can move now: CG speed plus angular speed times the
    /// farthest wheel's reach, each doubled for what the span may add) and
    /// [`MAX_SUBSTEP_SUSPENSION`] of the suspension's fastest mode.
    fn substeps(&self, body: &RigidBody, dt: Real) -> Result<usize> {
        let w = body.angular_velocity().norm();
        let by_time = (dt / MAX_SUBSTEP).ceil();
        let by_angle = (w * dt / MAX_SUBSTEP_ANGLE).ceil();
        let by_relaxation = match &self.vehicle {
            Some(spec) => {
                let reach = spec
                    .wheels
                    .iter()
                    .map(|wh| wh.center.coords.norm() + wh.radius)
                    .fold(0.0, Real::max);
                let patch_speed = 2.0 * (body.velocity().norm() + w * reach);
                (dt * patch_speed / spec.tyre.relaxation_length / MAX_SUBSTEP_RELAXATION).ceil()
            }
            None => 1.0,
        };
        let by_suspension = match &self.vehicle {
            Some(spec) => {
                (dt * suspension_rate(spec, body.props()) / MAX_SUBSTEP_SUSPENSION).ceil()
            }
            None => 1.0,
        };
        let n = by_time
            .max(by_angle)
            .max(by_relaxation)
            .max(by_suspension)
            .max(1.0);
        if n > (dt * MAX_SUBSTEPS_PER_SECOND).max(1.0) {
            return Err(Error::simulation(format!(
                "the motion on the ground needs {n:.0} integration sub-steps for {dt} s, more \
                 than {MAX_SUBSTEPS_PER_SECOND:.0} per simulated second (angular speed \
                 {w:.1} rad/s, speed {:.1} m/s): the run was stopped; check the vehicle's \
                 speeds and its tyre's relaxation length",
                body.velocity().norm()
            )));
        }
        Ok(n as usize)
    }

    /// Advances the body and the treads by `dt` s (> 0) from time `t0` (s).
    pub fn advance(
        &mut self,
        body: &mut RigidBody,
        ground: &Ground,
        t0: Real,
        dt: Real,
    ) -> Result<()> {
        self.advance_visiting(body, ground, t0, dt, &mut |_| {})
    }

    /// Advances as [`OnGround::advance`] does (the same bits) and returns how the motion is
    /// bounded over the span (see [`MotionBound`]): from the states at the integration's
    /// sub-step ends, each grown by the largest change between neighbouring ones (the motion
    /// within a sub-step stays within it).
    pub fn advance_bounded(
        &mut self,
        body: &mut RigidBody,
        ground: &Ground,
        t0: Real,
        dt: Real,
    ) -> Result<MotionBound> {
        let (v0, w0) = (body.velocity(), body.angular_velocity());
        let (mut dv, mut dw, mut w) = (0.0, 0.0, w0.norm());
        let (mut step_v, mut step_w) = (0.0, 0.0);
        let (mut prev_v, mut prev_w) = (v0, w0);
        self.advance_visiting(body, ground, t0, dt, &mut |s| {
            let (v, wk) = (s.0, s.1);
            dv = Real::max(dv, (v - v0).norm());
            dw = Real::max(dw, (wk - w0).norm());
            w = w.max(wk.norm());
            step_v = Real::max(step_v, (v - prev_v).norm());
            step_w = Real::max(step_w, (wk - prev_w).norm());
            (prev_v, prev_w) = (v, wk);
        })?;
        Ok(MotionBound {
            velocity_change: dv + step_v,
            angular_speed: w + step_w,
            angular_velocity_change: dw + step_w,
        })
    }

    /// [`OnGround::advance`], calling `visit((velocity, angular velocity))` after each
    /// sub-step (world frame).
    fn advance_visiting(
        &mut self,
        body: &mut RigidBody,
        ground: &Ground,
        t0: Real,
        dt: Real,
        visit: &mut dyn FnMut((Vector, Vector)),
    ) -> Result<()> {
        if dt <= 0.0 {
            return Ok(());
        }
        let n = self.substeps(body, dt)?;
        let h = dt / n as Real;
        self.keep_ground_near(body, ground, dt);
        let props = body.props().clone();
        let mut s = self.stage_of(body);
        for i in 0..n {
            let t = t0 + i as Real * h;
            let k1 = self.evaluate(&props, ground, t, &s)?.rate;
            let k2 = self
                .evaluate(&props, ground, t + 0.5 * h, &s.axpy(0.5 * h, &k1))?
                .rate;
            let k3 = self
                .evaluate(&props, ground, t + 0.5 * h, &s.axpy(0.5 * h, &k2))?
                .rate;
            let k4 = self.evaluate(&props, ground, t + h, &s.axpy(h, &k3))?.rate;
            let mut next = s.axpy(h / 6.0, &k1);
            next = next.axpy(h / 3.0, &k2);
            next = next.axpy(h / 3.0, &k3);
            next = next.axpy(h / 6.0, &k4);
            next.q = *Rotation::new_normalize(next.q).quaternion();
            self.land(&props, ground, &mut next);
            self.hold_anchors(&props, ground, &next);
            s = next;
            if !s.is_finite() {
                return Err(Error::simulation(
                    "the motion on the ground became non-finite: the wheels, tyre or inputs \
                     ask for more than the integration can follow (a very short relaxation \
                     length or very stiff springs); check them",
                )
                .at(Place::Time(t + h)));
            }
            let r = Rotation::new_normalize(s.q).to_rotation_matrix();
            let w = r.matrix() * props.inverse_inertia() * r.matrix().transpose() * s.l;
            visit((s.v, w));
        }
        *body = RigidBody::from_momentum(
            props,
            Point::from(s.x),
            Rotation::new_normalize(s.q),
            s.v,
            s.l,
        );
        self.deflections = s.u;
        Ok(())
    }

    /// What every wheel does at `body`'s state at time `t`.
    pub fn wheel_samples(
        &self,
        body: &RigidBody,
        ground: &Ground,
        t: Real,
    ) -> Result<Vec<WheelSample>> {
        let s = self.stage_of(body);
        Ok(self.evaluate(body.props(), ground, t, &s)?.wheels)
    }
}
