//! Joints between bodies, or between a body and the world: what each one holds, its limits and
//! its resistance (docs/joints.md).
//!
//! A joint joins a frame fixed in body 1 (the joint frame F1: an anchor point and axes, body
//! 1's frame, m) to a frame fixed in body 2 (F2, body 2's frame; or a world frame for a joint
//! to the world). The two frames coincide when the joint is made; the kind says what stays
//! held:
//!
//! | kind | held (3 + rows) | free | angles (rad) |
//! |---|---|---|---|
//! | [`JointKind::Spherical`] | the anchors meet | every rotation | swing and twist (below) |
//! | [`JointKind::Revolute`] | anchors; F2's z along F1's z | about z (the hinge axis) | about z |
//! | [`JointKind::Fixed`] | anchors; every axis | none | none |
//! | [`JointKind::FifthWheel`] | anchors; F2's z (the kingpin) across F1's y (the pivot) | yaw about the kingpin, pitch about the pivot | articulation (yaw) and pitch |
//!
//! The motion of jointed bodies is solved in the bodies' own coordinates (each body keeps its
//! position, orientation, velocity and angular momentum): at every evaluation of the
//! integrator the joints' reaction forces are solved from the condition that the held
//! quantities do not accelerate apart (constraint.rs), and after every sub-step the positions
//! and velocities are projected back onto the joints (drift stays at rounding). Limits act as
//! contacts: a joint driven past a limit gets the impulse that stops its rate there
//! (inelastic), reported as an event. A ball joint's limits are a cone and a twist (a
//! shoulder's or a hip's): the swing, the angle between F1's z and F2's z (a cone of half-angle
//! `upper` about F1's z), and the twist, F2's turn about its own z once the swing is taken out
//! (the swing-twist split of the relative rotation, the swing about an axis across F1's z).
//!
//! Besides a linear stiffness, damping and dry friction, a joint may carry passive moments:
//! nonlinear moments about its free angles, sums of exponentials, the form the published
//! passive (relaxed) moments of human joints take ([`PassiveMoment`]).

mod angles;
mod constraint;
mod passive;
mod row;
mod solve;

pub(crate) use angles::limit_angles;
pub(crate) use constraint::{
    applied_torques, drift_rate, limit_rows, project_positions, project_velocities,
    project_velocities_each, reactions, RESTING_ANGLE,
};
pub(crate) use passive::{find_coupled_angles, passive_slope};
pub use passive::{CoupledAngle, PassiveMoment, PassiveTerm, MAX_PASSIVE_MOMENT, MAX_PASSIVE_RATE};
pub(crate) use row::JointBody;

use crate::error::{require_finite, require_finite_vector, Error, Result};
use crate::math::{Point, Real, Rotation, Vector};

/// Largest accepted rotational stiffness of a joint (N m/rad): 1e9 (a steel coupling's is
/// 1e6-1e8). The integration's sub-steps follow the joint's fastest mode (motion/mechanism.rs),
/// so a stiffer spring only costs time.
pub const MAX_JOINT_STIFFNESS: Real = 1e9;
/// Largest accepted rotational damping (N m s/rad).
pub const MAX_JOINT_DAMPING: Real = 1e8;
/// Largest accepted dry-friction torque (N m): a fifth wheel's plate under a 15 t kingpin load
/// at friction 0.1 over a 0.5 m radius is about 7.5 kN m.
pub const MAX_JOINT_FRICTION: Real = 1e6;
/// A joint's dry friction is smoothed below this relative angular speed (rad/s, about 0.6
/// deg/s): the torque is `friction w / (|w| + FRICTION_SMOOTHING)`, so a joint at rest creeps
/// at most this fast under a torque below its friction, and no sign switch chatters.
pub const FRICTION_SMOOTHING: Real = 0.01;
/// What a joint holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// A ball joint: the anchors meet, every rotation is free (a hitch ball; later a
    /// shoulder or hip).
    Spherical,
    /// A hinge about the joint frame's z axis (a drawbar's pivot; later a knee or elbow).
    Revolute,
    /// The bodies move as one (a load strapped down; a test of the solver).
    Fixed,
    /// A tractor's fifth wheel: the kingpin (body 2's z) turns freely in yaw and the plate
    /// pitches about its pivot (body 1's y); no roll between the units.
    FifthWheel,
}

impl JointKind {
    /// The kind's name as scene files and the API spell it.
    pub fn name(self) -> &'static str {
        match self {
            JointKind::Spherical => "spherical",
            JointKind::Revolute => "revolute",
            JointKind::Fixed => "fixed",
            JointKind::FifthWheel => "fifth_wheel",
        }
    }

    /// The kind named `name` (see [`JointKind::name`]).
    pub fn from_name(name: &str) -> Result<JointKind> {
        match name {
            "spherical" | "ball" => Ok(JointKind::Spherical),
            "revolute" | "hinge" => Ok(JointKind::Revolute),
            "fixed" => Ok(JointKind::Fixed),
            "fifth_wheel" => Ok(JointKind::FifthWheel),
            other => Err(Error::invalid(format!(
                "joint kind {other:?} is unknown: give spherical (ball), revolute (hinge), \
                 fixed or fifth_wheel"
            ))),
        }
    }

    /// The angles a passive moment may act about, by name ([`PassiveMoment`]).
    pub fn passive_names(self) -> &'static [&'static str] {
        match self {
            JointKind::Revolute => &["angle"],
            JointKind::FifthWheel => &["articulation", "pitch"],
            JointKind::Spherical => &["x", "y", "z"],
            JointKind::Fixed => &[],
        }
    }

    /// The angles a limit may bound, by name (the kind's free rotations).
    pub fn limit_names(self) -> &'static [&'static str] {
        match self {
            JointKind::Revolute => &["angle"],
            JointKind::FifthWheel => &["articulation", "pitch"],
            JointKind::Spherical => &["swing", "twist"],
            JointKind::Fixed => &[],
        }
    }
}

/// A limit on one of a joint's angles (rad): the angle stays in `[lower, upper]`. A ball
/// joint's swing is never negative: its limit is `[0, cone half-angle]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngleLimit {
    /// Which angle: an index into [`JointKind::limit_names`].
    pub angle: usize,
    /// Lowest angle (rad), in [-pi, 0].
    pub lower: Real,
    /// Highest angle (rad), in [0, pi].
    pub upper: Real,
}

/// A joint between body 1 and body 2 (or the world).
#[derive(Clone, Debug, PartialEq)]
pub struct JointSpec {
    /// Its name in messages (empty: "joint k" by its index).
    pub name: String,
    /// What the joint holds.
    pub kind: JointKind,
    /// Body 1's index in the world.
    pub body1: usize,
    /// Body 2's index, or None for the world.
    pub body2: Option<usize>,
    /// The joint frame in body 1's frame (its origin the anchor, m).
    pub frame1: (Point, Rotation),
    /// The joint frame in body 2's frame (or the world's), coinciding with `frame1` when
    /// the joint is made.
    pub frame2: (Point, Rotation),
    /// Limits on the kind's angles.
    pub limits: Vec<AngleLimit>,
    /// Rotational stiffness (N m/rad) about the free angles, towards the angles at the
    /// start; default 0.
    pub stiffness: Real,
    /// Rotational damping (N m s/rad) of the relative angular velocity about the free
    /// angles; default 0.
    pub damping: Real,
    /// Dry friction (N m): a resistance torque against the relative rotation (smoothed below
    /// [`FRICTION_SMOOTHING`]); default 0.
    pub friction: Real,
    /// Passive moments about the free angles (default none), at most one per angle.
    pub passive: Vec<PassiveMoment>,
    /// True when the two bodies' meshes may still collide with each other (default false:
    /// jointed bodies pass through each other).
    pub collide: bool,
}

impl JointSpec {
    /// A joint of `kind` between `body1` and `body2` (None: the world) made at the frames
    /// given, with no limits, stiffness, damping or friction.
    pub fn new(
        kind: JointKind,
        body1: usize,
        body2: Option<usize>,
        frame1: (Point, Rotation),
        frame2: (Point, Rotation),
    ) -> JointSpec {
        JointSpec {
            name: String::new(),
            kind,
            body1,
            body2,
            frame1,
            frame2,
            limits: Vec::new(),
            stiffness: 0.0,
            damping: 0.0,
            friction: 0.0,
            passive: Vec::new(),
            collide: false,
        }
    }

    /// How messages name it: its name, or "joint `index`" without one.
    pub fn label(&self, index: usize) -> String {
        if self.name.is_empty() {
            format!("joint {index}")
        } else {
            format!("joint {:?}", self.name)
        }
    }

    /// Checks every number and the limits against the kind; `name` says which joint (for
    /// the messages).
    pub fn validate(&self, name: &str) -> Result<()> {
        if self.body2 == Some(self.body1) {
            return Err(Error::invalid(format!(
                "{name} joins body {} to itself: a joint needs two different bodies (or one \
                 body and the world)",
                self.body1
            )));
        }
        for (which, (p, q)) in [("body 1", &self.frame1), ("body 2", &self.frame2)] {
            require_finite_vector(&format!("{name}'s anchor in {which}"), &p.coords)?;
            if !q.coords.iter().all(|c| c.is_finite()) {
                return Err(Error::invalid(format!(
                    "{name}'s axes in {which} have a non-finite number"
                )));
            }
        }
        for (what, value, max, unit) in [
            ("stiffness", self.stiffness, MAX_JOINT_STIFFNESS, "N m/rad"),
            ("damping", self.damping, MAX_JOINT_DAMPING, "N m s/rad"),
            ("friction", self.friction, MAX_JOINT_FRICTION, "N m"),
        ] {
            require_finite(&format!("{name}'s {what}"), value)?;
            if !(0.0..=max).contains(&value) {
                return Err(Error::parameter(
                    &format!("{name}'s {what}"),
                    format!("{value} {unit}"),
                    &format!("it must lie in [0, {max:e}] {unit}"),
                ));
            }
        }
        if self.kind == JointKind::Fixed
            && (self.stiffness, self.damping, self.friction) != (0.0, 0.0, 0.0)
        {
            return Err(Error::invalid(format!(
                "{name} is fixed: it has no free rotation for a stiffness, damping or friction"
            )));
        }
        self.validate_passive(name)?;
        let names = self.kind.limit_names();
        for (k, limit) in self.limits.iter().enumerate() {
            let Some(angle) = names.get(limit.angle) else {
                return Err(Error::invalid(format!(
                    "{name} is {}: it has {}",
                    self.kind.name(),
                    if names.is_empty() {
                        "no angle to limit".to_string()
                    } else {
                        format!("the angles {}", names.join(", "))
                    }
                )));
            };
            require_finite(&format!("{name}'s {angle} limit"), limit.lower)?;
            require_finite(&format!("{name}'s {angle} limit"), limit.upper)?;
            if !(-std::f64::consts::PI..=0.0).contains(&limit.lower)
                || !(0.0..=std::f64::consts::PI).contains(&limit.upper)
            {
                return Err(Error::invalid(format!(
                    "{name}'s {angle} limit [{:.2}, {:.2}] deg is invalid: the lower limit \
                     must lie in [-180, 0] deg and the upper in [0, 180] deg (the joint starts \
                     at 0, between them)",
                    limit.lower.to_degrees(),
                    limit.upper.to_degrees()
                )));
            }
            if self.kind == JointKind::Spherical && *angle == "swing" && limit.lower != 0.0 {
                return Err(Error::invalid(format!(
                    "{name}'s swing limit has the lower bound {:.2} deg: a swing (the angle \
                     between the frames' z axes) is never negative; give [0, the cone's \
                     half-angle]",
                    limit.lower.to_degrees()
                )));
            }
            if self.limits[..k].iter().any(|l| l.angle == limit.angle) {
                return Err(Error::invalid(format!(
                    "{name} has two limits on its {angle}: give one"
                )));
            }
        }
        Ok(())
    }
}

/// A joint's state at an instant: its angles (rad) and what it carries (world frame).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointSample {
    /// The kind's angles (rad): revolute [angle, 0, 0]; fifth wheel [articulation, pitch,
    /// 0]; spherical [swing, twist, 0] (module notes); fixed zeros.
    pub angles: Vector,
    /// The force of body 1 on body 2 through the joint (N, world), constraint reaction only.
    pub force: Vector,
    /// The torque of body 1 on body 2 through the joint about the anchor (N m, world):
    /// reaction, stiffness, damping and friction.
    pub torque: Vector,
}
