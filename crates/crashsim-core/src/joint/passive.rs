//! Passive moments (docs/joints.md, "Passive moments"): a joint's nonlinear moment about one
//! of its free angles, a sum of exponentials whose terms may read other joints' angles (the
//! form the published passive moments of relaxed human joints take); its checks, its torque,
//! the bound on its stiffness the integration's sub-steps follow, and the search for the
//! coupled angles' joints when the world builds its mechanisms.

use super::angles::angles;
use super::row::JointBody;
use super::{JointKind, JointSpec};
use crate::error::{require_finite, Error, Result};
use crate::math::{Real, Vector};

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
/// is 0 then, but for a ball joint whose two frames differ, which starts at the rotation
/// between them), so published laws, written in anatomical angles, are used as published. A
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

impl JointSpec {
    /// Checks the passive moments: an angle the kind has, once each; finite numbers within
    /// [`MAX_PASSIVE_RATE`] and [`MAX_PASSIVE_MOMENT`]; offsets and centres within +-2 pi.
    pub(super) fn validate_passive(&self, name: &str) -> Result<()> {
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

/// A coupled angle's value now (rad): its joint's angle, found among the mechanism's `joints`
/// when the world built it (0, where it was made, if it was not: a joint outside a world).
fn coupled_angle(c: &CoupledAngle, bodies: &[JointBody], joints: &[JointSpec]) -> Real {
    match c.found {
        Some((j, a)) => angles(&joints[j], bodies).0[a],
        None => 0.0,
    }
}

/// The passive moments' torque (N m, world) on body b: each [`super::PassiveMoment`]'s M at
/// its angle (and its terms' coupled angles), about that angle's axis (a hinge's z; a fifth
/// wheel's kingpin or pivot; F1's axis of a ball joint's rotation-vector component), so that
/// a positive M turns body b towards a larger angle. Zero without passive moments.
pub(super) fn passive_torque(
    joint: &JointSpec,
    bodies: &[JointBody],
    joints: &[JointSpec],
) -> Vector {
    if joint.passive.is_empty() {
        return Vector::zeros();
    }
    let (theta, axes) = angles(joint, bodies);
    let other = |c: &CoupledAngle| coupled_angle(c, bodies, joints);
    joint
        .passive
        .iter()
        .map(|law| axes[law.angle] * law.moment_reading(theta[law.angle], &other))
        .sum()
}

/// A bound on the passive moments' stiffness (N m/rad) over their angles now give or take
/// `reach` (rad), the coupled angles as they are: each term's |scale| (|rate| + the sum of
/// its coupled |rate|s) exp(its exponent), a sum of exponentials, convex in the angle, so its
/// largest over the range is at one of its ends (for the integration's sub-steps: the
/// stiffest the span may meet; the coupled rates bound what the other joints' turning adds).
pub(crate) fn passive_slope(
    joint: &JointSpec,
    bodies: &[JointBody],
    reach: Real,
    joints: &[JointSpec],
) -> Real {
    if joint.passive.is_empty() {
        return 0.0;
    }
    let (theta, _) = angles(joint, bodies);
    let other = |c: &CoupledAngle| coupled_angle(c, bodies, joints);
    joint
        .passive
        .iter()
        .map(|law| {
            let at = theta[law.angle];
            [at - reach, at + reach]
                .into_iter()
                .map(|a| {
                    law.terms
                        .iter()
                        .map(|t| {
                            let rates =
                                t.rate.abs() + t.coupled.iter().map(|c| c.rate.abs()).sum::<Real>();
                            t.scale.abs() * rates * t.exponent(law.offset + a, &other).exp()
                        })
                        .sum::<Real>()
                })
                .fold(0.0, Real::max)
        })
        .fold(0.0, Real::max)
}

/// Finds every coupled angle of `joints` (a mechanism's) among them, by the joint's name and
/// the angle's; an error naming the joint and the law when one is not there.
pub(crate) fn find_coupled_angles(joints: &mut [JointSpec], ids: &[usize]) -> Result<()> {
    let names: Vec<(String, JointKind)> = joints.iter().map(|j| (j.name.clone(), j.kind)).collect();
    for (joint, id) in joints.iter_mut().zip(ids) {
        let label = joint.label(*id);
        let own = joint.kind.passive_names();
        for law in &mut joint.passive {
            for term in &mut law.terms {
                for c in &mut term.coupled {
                    let Some(j) = names.iter().position(|(n, _)| *n == c.joint) else {
                        return Err(Error::invalid(format!(
                            "{label}'s passive moment about its {} reads joint {:?}: no joint of \
                             that name joins the bodies it moves with (a coupled angle is \
                             another joint's of the same jointed set)",
                            own[law.angle], c.joint
                        )));
                    };
                    let kind = names[j].1;
                    let Some(a) = kind.passive_names().iter().position(|n| *n == c.angle) else {
                        return Err(Error::invalid(format!(
                            "{label}'s passive moment reads joint {:?}'s angle {:?}: a {} joint's \
                             angles are {}",
                            c.joint,
                            c.angle,
                            kind.name(),
                            kind.passive_names().join(", ")
                        )));
                    };
                    c.found = Some((j, a));
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::joint::row::JointBody;
    use crate::joint::{JointKind, JointSpec};
    use crate::math::{Matrix, Point, Rotation, Vector};

    fn body(r: Matrix) -> JointBody {
        JointBody {
            x: Point::origin(),
            r,
            v: Vector::zeros(),
            w: Vector::zeros(),
            inv_mass: 1.0,
            inv_inertia: Matrix::identity(),
        }
    }

    /// Two hinges about z: "hip" (bodies 0-1, at 0) and "knee" (bodies 1-2, body 2 turned
    /// `knee` rad); the hip's law reads the knee's angle.
    fn hip_and_knee(knee: Real, coupled: CoupledAngle) -> (Vec<JointSpec>, Vec<JointBody>) {
        let frame = (Point::origin(), Rotation::identity());
        let mut hip = JointSpec::new(JointKind::Revolute, 0, Some(1), frame, frame);
        hip.name = "hip".into();
        let mut term = PassiveTerm::new(2.0, 0.5, 0.0);
        term.coupled.push(coupled);
        hip.passive = vec![PassiveMoment {
            angle: 0,
            offset: 0.0,
            terms: vec![term],
            constant: -1.0,
        }];
        let mut knee_joint = JointSpec::new(JointKind::Revolute, 1, Some(2), frame, frame);
        knee_joint.name = "knee".into();
        let turned = *Rotation::from_axis_angle(&Vector::z_axis(), knee)
            .to_rotation_matrix()
            .matrix();
        let bodies = vec![
            body(Matrix::identity()),
            body(Matrix::identity()),
            body(turned),
        ];
        (vec![hip, knee_joint], bodies)
    }

    #[test]
    fn a_coupled_term_reads_the_other_joints_angle() {
        for knee in [-0.7, 0.0, 0.4] {
            let (mut joints, bodies) =
                hip_and_knee(knee, CoupledAngle::new("knee", "angle", 0.1, -3.0));
            find_coupled_angles(&mut joints, &[0, 1]).unwrap();
            let torque = passive_torque(&joints[0], &bodies, &joints);
            // M = 2 exp(0.5 * 0 - 3 (0.1 + knee)) - 1 about the hip's z
            let expected = 2.0 * (-3.0 * (0.1 + knee)).exp() - 1.0;
            assert!((torque - Vector::z() * expected).norm() <= 1e-12 * expected.abs().max(1.0));
            // its stiffness bound takes the coupled rate too: 2 (0.5 + 3) exp(...)
            let slope = passive_slope(&joints[0], &bodies, 0.0, &joints);
            let bound = 2.0 * 3.5 * (-3.0 * (0.1 + knee)).exp();
            assert!((slope - bound).abs() <= 1e-12 * bound);
        }
    }

    #[test]
    fn a_coupled_angle_that_is_not_there_is_refused_by_name() {
        let (mut joints, _) = hip_and_knee(0.0, CoupledAngle::new("ankle", "angle", 0.0, 1.0));
        let e = find_coupled_angles(&mut joints, &[0, 1])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("reads joint \"ankle\": no joint of that name"),
            "{e}"
        );
        let (mut joints, _) = hip_and_knee(0.0, CoupledAngle::new("knee", "pitch", 0.0, 1.0));
        let e = find_coupled_angles(&mut joints, &[0, 1])
            .unwrap_err()
            .to_string();
        assert!(e.contains("a revolute joint's angles are angle"), "{e}");
    }
}
