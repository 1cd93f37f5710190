//! A scene document's joints ([`super`]): a joint's kind, bodies, frames, limits, resistance
//! and passive moments (with their coupled angles) as plain values, and back.

use serde::{Deserialize, Serialize};

use super::{point, quat, rotation, v3};
use crate::error::{Error, Result};
use crate::joint::{AngleLimit, CoupledAngle, JointKind, JointSpec, PassiveMoment, PassiveTerm};
use crate::math::Real;

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct JointDoc {
    #[serde(default)]
    name: String,
    kind: String,
    body1: usize,
    body2: Option<usize>,
    /// Anchor (m) and axes (w, x, y, z) in body 1's frame; the same in body 2's (or the
    /// world's).
    frame1: ([Real; 3], [Real; 4]),
    frame2: ([Real; 3], [Real; 4]),
    /// (angle index, lower rad, upper rad).
    limits: Vec<(usize, Real, Real)>,
    stiffness: Real,
    damping: Real,
    friction: Real,
    collide: bool,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    passive: Vec<PassiveDoc>,
}

/// A joint's passive moment: the angle's index, offset rad, terms (scale N m, rate 1/rad,
/// centre rad) and constant N m.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PassiveDoc {
    angle: usize,
    offset: Real,
    terms: Vec<(Real, Real, Real)>,
    constant: Real,
    /// The terms' coupled angles: (term index, joint name, angle name, offset rad, rate
    /// 1/rad); written only when there are some.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    coupled: Vec<(usize, String, String, Real, Real)>,
}

/// A joint as the document writes it (its passive moments only when it has some).
pub(super) fn joint_doc(j: &JointSpec) -> JointDoc {
    JointDoc {
        name: j.name.clone(),
        kind: j.kind.name().into(),
        body1: j.body1,
        body2: j.body2,
        frame1: (v3(&j.frame1.0.coords), quat(&j.frame1.1)),
        frame2: (v3(&j.frame2.0.coords), quat(&j.frame2.1)),
        limits: j
            .limits
            .iter()
            .map(|l| (l.angle, l.lower, l.upper))
            .collect(),
        stiffness: j.stiffness,
        damping: j.damping,
        friction: j.friction,
        collide: j.collide,
        passive: j
            .passive
            .iter()
            .map(|m| PassiveDoc {
                angle: m.angle,
                offset: m.offset,
                terms: m
                    .terms
                    .iter()
                    .map(|t| (t.scale, t.rate, t.centre))
                    .collect(),
                constant: m.constant,
                coupled: m
                    .terms
                    .iter()
                    .enumerate()
                    .flat_map(|(k, t)| {
                        t.coupled
                            .iter()
                            .map(move |c| (k, c.joint.clone(), c.angle.clone(), c.offset, c.rate))
                    })
                    .collect(),
            })
            .collect(),
    }
}

/// A joint read back through the core's constructor (the world checks it when added).
pub(super) fn joint(j: JointDoc) -> Result<JointSpec> {
    let mut joint = JointSpec::new(
        JointKind::from_name(&j.kind)?,
        j.body1,
        j.body2,
        (point(j.frame1.0), rotation(j.frame1.1)?),
        (point(j.frame2.0), rotation(j.frame2.1)?),
    );
    joint.limits = j
        .limits
        .iter()
        .map(|&(angle, lower, upper)| AngleLimit {
            angle,
            lower,
            upper,
        })
        .collect();
    joint.stiffness = j.stiffness;
    joint.damping = j.damping;
    joint.friction = j.friction;
    joint.collide = j.collide;
    joint.passive = j
        .passive
        .into_iter()
        .map(|m| {
            let mut terms: Vec<PassiveTerm> = m
                .terms
                .into_iter()
                .map(|(scale, rate, centre)| PassiveTerm::new(scale, rate, centre))
                .collect();
            for (k, joint, angle, offset, rate) in m.coupled {
                let Some(term) = terms.get_mut(k) else {
                    return Err(Error::invalid(format!(
                        "a passive moment's coupled angle names term {k} of {}",
                        terms.len()
                    )));
                };
                term.coupled
                    .push(CoupledAngle::new(&joint, &angle, offset, rate));
            }
            Ok(PassiveMoment {
                angle: m.angle,
                offset: m.offset,
                terms,
                constant: m.constant,
            })
        })
        .collect::<Result<_>>()?;
    joint.name = j.name;
    Ok(joint)
}
