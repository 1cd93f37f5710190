//! A compliant (force-penetration) contact for a pair of bodies, in place of the
//! depth-of-penetration timer and the one impulse exchange: for light, soft bodies whose
//! contact lasts and slides (a pedestrian's segments on a bumper, a bonnet and a windscreen),
//! as the published multibody pedestrian models do (docs/human.md).
//!
//! While the two meshes overlap, the pair carries a normal force
//!
//! `F = max(0, k d + c v)`,   `c = 2 zeta sqrt(k m)`,
//!
//! with `d` (m) the overlap's depth along its normal, `v` (m/s) the closing speed at its
//! centroid, `m` (kg) the pair's effective mass along the normal there (through joints), `k`
//! the stiffness (N/m) and `zeta` the damping ratio: a linear spring-dashpot that never pulls.
//! A friction force opposes the sliding at the centroid, at most `mu F` (the pair's friction)
//! and never more than stops the sliding within the step. The forces act as impulses at the
//! end of each step, from the poses and velocities there (a kick after the drift: the
//! symplectic Euler step, which keeps a spring's energy bounded): stable and accurate while
//! `sqrt(k / m) dt` is small: while a pair presses, the world cuts a longer step into
//! sub-steps of at most [`MAX_SOFT_STEP_ANGLE`].

use crate::error::{require_finite, Error, Result};
use crate::math::Real;

/// Largest stiffness accepted (N/m): a steel plate's local stiffness is of this order; the
/// pedestrian models' vehicle fronts are 1e4-1e6.
pub const MAX_SOFT_STIFFNESS: Real = 1e8;
/// Largest damping ratio accepted (2: well past critical).
pub const MAX_SOFT_DAMPING_RATIO: Real = 2.0;
/// Largest `sqrt(k / m) h` (rad) of a step h a soft pair presses over, `m` the lighter body's
/// mass: the contact's period must span at least 2 pi / 0.2 = 31 steps. The step is first
/// order: at 0.09 rad a head-on contact's restitution came out 2.0 % above its equation of
/// motion's (damping ratio 0.3), at 0.023 rad 0.47 % (tests/integration/soft.rs); 0.2 rad
/// allows about 4 %. A run whose step is longer cuts it into sub-steps while the pair presses
/// ([`MAX_SOFT_SUBSTEPS`] at most).
pub const MAX_SOFT_STEP_ANGLE: Real = 0.2;
/// Most sub-steps a run's step is cut into while a soft pair presses: a stiffer pair (or a
/// longer step) is refused with the stiffness and the step that fit. At 50 a step already
/// spans 1.6 periods of the contact (a period is 31 sub-steps), a step too long for what it
/// records; a 1e5 N/m pair on a 0.4 kg hand needs 3 at 1 ms.
pub const MAX_SOFT_SUBSTEPS: usize = 50;

/// The compliant contact of one pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoftContact {
    /// Stiffness k (N/m), in (0, [`MAX_SOFT_STIFFNESS`]].
    pub stiffness: Real,
    /// Damping ratio zeta, in [0, [`MAX_SOFT_DAMPING_RATIO`]]: the restitution of a head-on
    /// contact is about `exp(-zeta pi / sqrt(1 - zeta^2))` below 1.
    pub damping_ratio: Real,
}

impl SoftContact {
    /// Checks both numbers' ranges.
    pub fn validate(&self) -> Result<()> {
        require_finite("soft contact stiffness", self.stiffness)?;
        if !(self.stiffness > 0.0 && self.stiffness <= MAX_SOFT_STIFFNESS) {
            return Err(Error::parameter(
                "soft contact stiffness",
                format!("{} N/m", self.stiffness),
                &format!("it must lie in (0, {MAX_SOFT_STIFFNESS:e}] N/m"),
            ));
        }
        require_finite("soft contact damping ratio", self.damping_ratio)?;
        if !(0.0..=MAX_SOFT_DAMPING_RATIO).contains(&self.damping_ratio) {
            return Err(Error::parameter(
                "soft contact damping ratio",
                self.damping_ratio,
                &format!("it must lie in [0, {MAX_SOFT_DAMPING_RATIO}]"),
            ));
        }
        Ok(())
    }

    /// The normal impulse (N s, >= 0) over a step of `dt` s at depth `depth` (m), closing
    /// speed `closing` (m/s, > 0 approaching) and effective mass `mass` (kg).
    pub fn normal_impulse(&self, depth: Real, closing: Real, mass: Real, dt: Real) -> Real {
        let damping = 2.0 * self.damping_ratio * (self.stiffness * mass).sqrt();
        (self.stiffness * depth + damping * closing).max(0.0) * dt
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_soft_contacts_are_refused() {
        let ok = SoftContact {
            stiffness: 1e5,
            damping_ratio: 0.3,
        };
        assert!(ok.validate().is_ok());
        for bad in [
            SoftContact {
                stiffness: 0.0,
                ..ok
            },
            SoftContact {
                stiffness: 2e8,
                ..ok
            },
            SoftContact {
                stiffness: Real::NAN,
                ..ok
            },
            SoftContact {
                damping_ratio: -0.1,
                ..ok
            },
            SoftContact {
                damping_ratio: 2.5,
                ..ok
            },
        ] {
            assert!(bad.validate().is_err(), "{bad:?}");
        }
    }

    #[test]
    fn the_force_never_pulls() {
        let s = SoftContact {
            stiffness: 1e4,
            damping_ratio: 1.0,
        };
        // Parting fast at a small depth: the dashpot would pull; the contact does not.
        assert_eq!(s.normal_impulse(0.001, -5.0, 1.0, 1e-3), 0.0);
        // 1 cm deep, at rest: k d dt.
        assert!((s.normal_impulse(0.01, 0.0, 1.0, 1e-3) - 0.1).abs() < 1e-15);
    }
}
