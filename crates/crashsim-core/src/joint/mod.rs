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

mod constraint;
mod row;
mod solve;

pub(crate) use constraint::{
    applied_torques, drift_rate, find_coupled_angles, limit_angles, limit_rows, passive_slope,
    project_positions, project_velocities, project_velocities_each, reactions, RESTING_ANGLE,
};
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
/// Largest accepted rate of a passive moment's exponential (1/rad): the published passive
/// moments of human joints reach 38 /rad (the ankle's dorsiflexion end in Anderson's
/// double exponential, 1999) and about 11 /rad in Riener and Edrich's (1999, 0.195 /deg).
pub const MAX_PASSIVE_RATE: Real = 200.0;
/// Largest accepted size of a passive moment's term or constant (N m), as for dry friction.
pub const MAX_PASSIVE_MOMENT: Real = 1e6;
/// A passive moment's exponent is evaluated at most at this (so a moment stays finite: e^50
/// times its term's scale, far past any joint's range, where the integration's sub-steps
/// would have refused the run first).
const PASSIVE_EXPONENT_CAP: Real = 50.0;

/// One term of a [`PassiveMoment`]: `scale exp(rate (phi - centre) + sum of the coupled
/// angles' rate_j phi_j)` (N m), phi in rad: without coupled angles a term of the joint's own
/// angle; with them, of a two-joint muscle's (Riener and Edrich's knee moment reads the hip's
/// and the ankle's angles).
#[derive(Clone, Debug, PartialEq)]
pub struct PassiveTerm {
    /// N m (either sign).
    pub scale: Real,
    /// 1/rad (either sign): positive grows towards large angles, negative towards small.
    pub rate: Real,
    /// rad: where the term is `scale` (the coupled angles' part aside).
    pub centre: Real,
    /// Other joints' angles the exponent reads (default none).
    pub coupled: Vec<CoupledAngle>,
}

impl PassiveTerm {
    /// A term of the joint's own angle alone.
    pub fn new(scale: Real, rate: Real, centre: Real) -> PassiveTerm {
        PassiveTerm {
            scale,
            rate,
            centre,
            coupled: Vec::new(),
        }
    }

    /// The exponent at `phi` (rad) with the coupled angles at `other(c)` (rad, each the
    /// angle of its joint, the offset added here), capped at [`PASSIVE_EXPONENT_CAP`].
    pub(crate) fn exponent(&self, phi: Real, other: &dyn Fn(&CoupledAngle) -> Real) -> Real {
        let coupled: Real = self
            .coupled
            .iter()
            .map(|c| c.rate * (c.offset + other(c)))
            .sum();
        (self.rate * (phi - self.centre) + coupled).min(PASSIVE_EXPONENT_CAP)
    }
}

/// Another joint's angle a [`PassiveTerm`]'s exponent reads: `rate (offset + that angle)`.
#[derive(Clone, Debug, PartialEq)]
pub struct CoupledAngle {
    /// The other joint's name (a joint of the same mechanism: the world checks it when it
    /// builds its mechanisms).
    pub joint: String,
    /// Its angle's name ([`JointKind::passive_names`] of its kind).
    pub angle: String,
    /// That angle's phi when the joints are made (rad).
    pub offset: Real,
    /// 1/rad (either sign).
    pub rate: Real,
    /// Where the world found it: the joint's index among its mechanism's joints and the
    /// angle's index (set when the mechanisms are built).
    pub(crate) found: Option<(usize, usize)>,
}

impl CoupledAngle {
    /// Joint `joint`'s angle `angle` at `offset` rad when made, read at `rate` 1/rad.
    pub fn new(joint: &str, angle: &str, offset: Real, rate: Real) -> CoupledAngle {
        CoupledAngle {
            joint: joint.to_string(),
            angle: angle.to_string(),
            offset,
            rate,
            found: None,
        }
    }
}

/// A nonlinear moment about one of a joint's free angles (docs/joints.md, "Passive moments"):
///
/// `M(phi) = sum of scale_k exp(rate_k (phi - centre_k)) + constant` (N m),
///
/// with `phi = offset + the angle` (rad): `offset` is phi when the joint is made (the angle
/// is 0 then), so published laws, written in anatomical angles, are used as published. A
/// positive M turns body 2 against body 1 towards a larger angle (body 1 gets the opposite).
/// The angles ([`JointKind::passive_names`]): a hinge's angle; a fifth wheel's articulation
/// and pitch; a ball joint's relative rotation as a rotation vector in F1's axes, its x, y
/// and z components (each an anatomical angle to first order: flexion about one axis,
/// abduction about another; the components of a large combined turn are not Cardan angles).
#[derive(Clone, Debug, PartialEq)]
pub struct PassiveMoment {
    /// Which angle: an index into [`JointKind::passive_names`].
    pub angle: usize,
    /// phi at the joint's making (rad).
    pub offset: Real,
    /// The exponential terms.
    pub terms: Vec<PassiveTerm>,
    /// N m.
    pub constant: Real,
}

impl PassiveMoment {
    /// M (N m) at the joint's angle `angle` (rad; phi = offset + angle), any coupled angles
    /// where they were made (0).
    pub fn moment(&self, angle: Real) -> Real {
        self.moment_reading(angle, &|_| 0.0)
    }

    /// M (N m) at the joint's angle `angle` (rad) with each coupled angle at `other(c)` (rad).
    pub fn moment_reading(&self, angle: Real, other: &dyn Fn(&CoupledAngle) -> Real) -> Real {
        let phi = self.offset + angle;
        self.terms
            .iter()
            .map(|t| t.scale * t.exponent(phi, other).exp())
            .sum::<Real>()
            + self.constant
    }

    /// dM/dphi (N m/rad) at the joint's angle `angle` (rad), any coupled angles where they
    /// were made.
    pub fn slope(&self, angle: Real) -> Real {
        let phi = self.offset + angle;
        self.terms
            .iter()
            .map(|t| t.scale * t.rate * t.exponent(phi, &|_| 0.0).exp())
            .sum()
    }
}

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

impl JointSpec {
    /// Checks the passive moments: an angle the kind has, once each; finite numbers within
    /// [`MAX_PASSIVE_RATE`] and [`MAX_PASSIVE_MOMENT`]; offsets and centres within +-2 pi.
    fn validate_passive(&self, name: &str) -> Result<()> {
        let names = self.kind.passive_names();
        let two_pi = 2.0 * std::f64::consts::PI;
        for (k, law) in self.passive.iter().enumerate() {
            let Some(angle) = names.get(law.angle) else {
                return Err(Error::invalid(format!(
                    "{name} is {}: it has {}",
                    self.kind.name(),
                    if names.is_empty() {
                        "no free angle for a passive moment".to_string()
                    } else {
                        format!("the angles {} for a passive moment", names.join(", "))
                    }
                )));
            };
            if self.passive[..k].iter().any(|l| l.angle == law.angle) {
                return Err(Error::invalid(format!(
                    "{name} has two passive moments about its {angle}: give one (with all \
                     its terms)"
                )));
            }
            let what = format!("{name}'s passive moment about its {angle}");
            let within = |field: &str, value: Real, max: Real, unit: &str| -> Result<()> {
                require_finite(&format!("{what}: {field}"), value)?;
                if value.abs() > max {
                    return Err(Error::parameter(
                        &format!("{what}: {field}"),
                        format!("{value} {unit}"),
                        &format!("it must lie in [-{max:e}, {max:e}] {unit}"),
                    ));
                }
                Ok(())
            };
            within("offset", law.offset, two_pi, "rad")?;
            within("constant", law.constant, MAX_PASSIVE_MOMENT, "N m")?;
            for term in &law.terms {
                within("scale", term.scale, MAX_PASSIVE_MOMENT, "N m")?;
                within("rate", term.rate, MAX_PASSIVE_RATE, "1/rad")?;
                within("centre", term.centre, two_pi, "rad")?;
                for c in &term.coupled {
                    if c.joint.is_empty() || c.angle.is_empty() {
                        return Err(Error::invalid(format!(
                            "{what} reads another joint's angle without naming both the \
                             joint and the angle"
                        )));
                    }
                    within("coupled offset", c.offset, two_pi, "rad")?;
                    within("coupled rate", c.rate, MAX_PASSIVE_RATE, "1/rad")?;
                }
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
