//! Crush stiffness of a vehicle's faces (CRASH3 A and B) and which face an impact strikes.
//!
//! Over a contact width W (m) a face with coefficients A (N/m) and B (N/m^2) acts as a spring
//! of stiffness k = B W (N/m) (seed, "From k to B"). Faces are named in the body frame
//! (ISO 8855: x forward, y left).

use crate::error::{require_finite, Error, Result};
use crate::math::{Real, Vector};

/// A face of a vehicle, body frame (serialized by its [`name`](Face::name)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(rename_all = "lowercase")
)]
pub enum Face {
    /// +x.
    Front,
    /// -x.
    Rear,
    /// +y (the driver side in right-hand traffic).
    Left,
    /// -y.
    Right,
}

impl Face {
    /// Every face, in the order front, rear, left, right.
    pub const ALL: [Face; 4] = [Face::Front, Face::Rear, Face::Left, Face::Right];

    /// The face's lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Face::Front => "front",
            Face::Rear => "rear",
            Face::Left => "left",
            Face::Right => "right",
        }
    }

    /// The face whose outward normal is closest to the horizontal part of `direction`
    /// (body frame): front/rear when |x| >= |y|, else left/right.
    pub fn facing(direction: &Vector) -> Face {
        if direction.x.abs() >= direction.y.abs() {
            if direction.x >= 0.0 {
                Face::Front
            } else {
                Face::Rear
            }
        } else if direction.y > 0.0 {
            Face::Left
        } else {
            Face::Right
        }
    }

    fn index(self) -> usize {
        self as usize
    }
}

/// One face's CRASH3 coefficients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceStiffness {
    /// Force per unit width at the onset of permanent crush (N/m), >= 0.
    pub a: Real,
    /// Force per unit width per metre of crush (N/m^2), > 0.
    pub b: Real,
}

impl FaceStiffness {
    /// Checked coefficients.
    pub fn new(a: Real, b: Real) -> Result<FaceStiffness> {
        require_finite("stiffness A", a)?;
        require_finite("stiffness B", b)?;
        if a < 0.0 {
            return Err(Error::parameter("stiffness A", a, "it must be >= 0 N/m"));
        }
        if b <= 0.0 {
            return Err(Error::parameter("stiffness B", b, "it must be > 0 N/m^2"));
        }
        Ok(FaceStiffness { a, b })
    }

    /// k = B W (N/m) over a contact width W (m).
    pub fn spring_rate(&self, width: Real) -> Real {
        self.b * width
    }
}

/// The face stiffness of one vehicle; a face without data is None.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stiffness {
    faces: [Option<FaceStiffness>; 4],
}

impl Stiffness {
    /// No data on any face.
    pub fn none() -> Stiffness {
        Stiffness::default()
    }

    /// Sets one face.
    pub fn with(mut self, face: Face, value: FaceStiffness) -> Stiffness {
        self.faces[face.index()] = Some(value);
        self
    }

    /// One face's coefficients.
    pub fn face(&self, face: Face) -> Option<FaceStiffness> {
        self.faces[face.index()]
    }

    /// True when every face has data.
    pub fn is_complete(&self) -> bool {
        self.faces.iter().all(Option::is_some)
    }

    /// True when no face has data (a fixed obstacle without data is rigid).
    pub fn is_none(&self) -> bool {
        self.faces.iter().all(Option::is_none)
    }
}

/// Series stiffness k' = k1 k2 / (k1 + k2) (N/m) of two struck faces; an infinite rate is a
/// rigid face (a fixed obstacle without stiffness data), so k' is the other one.
pub fn series_rate(k1: Real, k2: Real) -> Real {
    match (k1.is_infinite(), k2.is_infinite()) {
        (true, true) => Real::INFINITY,
        (true, false) => k2,
        (false, true) => k1,
        (false, false) => k1 * k2 / (k1 + k2),
    }
}

/// The share of the total crush body 1 takes, C1 / (C1 + C2) = k2 / (k1 + k2) (seed eqs.
/// 34-35: equal spring forces); 1 against a rigid body 2 (infinite k2), 0 against a rigid
/// body 1; None when both rates are zero or both infinite (no split is defined).
pub fn crush_share(k1: Real, k2: Real) -> Option<Real> {
    match (k1.is_infinite(), k2.is_infinite()) {
        (true, true) => None,
        (true, false) => Some(0.0),
        (false, true) => Some(1.0),
        (false, false) => (k1 + k2 > 0.0).then(|| k2 / (k1 + k2)),
    }
}

/// Effective mass (kg) of a body along the unit direction `n` at lever arm `r` (m, world):
/// 1 / (n . (1/m E - `[r]x` I^-1 `[r]x`) n). For planar motion this is gamma m with
/// gamma = k_g^2 / (k_g^2 + h^2) (seed, "Non-central collisions").
pub fn effective_mass(
    mass: Real,
    world_inverse_inertia: &crate::math::Matrix,
    r: &Vector,
    n: &Vector,
) -> Real {
    let rx = r.cross_matrix();
    let k = crate::math::Matrix::identity() / mass - rx * world_inverse_inertia * rx;
    1.0 / n.dot(&(k * n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rigid_face_takes_no_crush_and_leaves_the_other_spring() {
        assert_eq!(series_rate(2e5, 6e5), 1.5e5);
        assert_eq!(series_rate(2e5, Real::INFINITY), 2e5);
        assert_eq!(series_rate(Real::INFINITY, 6e5), 6e5);
        assert_eq!(crush_share(2e5, 6e5), Some(0.75));
        assert_eq!(crush_share(2e5, Real::INFINITY), Some(1.0));
        assert_eq!(crush_share(Real::INFINITY, 6e5), Some(0.0));
        assert_eq!(crush_share(0.0, 0.0), None);
        assert_eq!(crush_share(Real::INFINITY, Real::INFINITY), None);
        assert!(Stiffness::none().is_none());
        let one = Stiffness::none().with(Face::Left, FaceStiffness::new(1e4, 1e5).unwrap());
        assert!(!one.is_none() && !one.is_complete());
    }

    #[test]
    fn the_struck_face_follows_the_direction() {
        assert_eq!(Face::facing(&Vector::new(1.0, 0.2, 0.9)), Face::Front);
        assert_eq!(Face::facing(&Vector::new(-1.0, 0.2, 0.0)), Face::Rear);
        assert_eq!(Face::facing(&Vector::new(0.1, 0.9, 0.0)), Face::Left);
        assert_eq!(Face::facing(&Vector::new(0.1, -0.9, 0.0)), Face::Right);
    }

    #[test]
    fn planar_effective_mass_is_the_seed_gamma() {
        // Yaw inertia I about z, impulse along x at a lever arm h along y.
        let (m, izz, h) = (1500.0, 2500.0, 0.8);
        let inv = crate::math::Matrix::from_diagonal(&Vector::new(1e-3, 1e-3, 1.0 / izz));
        let me = effective_mass(m, &inv, &Vector::new(1.2, h, 0.0), &Vector::x());
        let k2 = izz / m;
        let gamma = k2 / (k2 + h * h);
        assert!((me - gamma * m).abs() < 1e-9 * m, "{me} vs {}", gamma * m);
    }

    #[test]
    fn bad_coefficients_are_refused() {
        assert!(FaceStiffness::new(-1.0, 1.0).is_err());
        assert!(FaceStiffness::new(1.0, 0.0).is_err());
        assert!(FaceStiffness::new(Real::NAN, 1.0).is_err());
        assert!(FaceStiffness::new(0.0, 1.0e6).is_ok());
    }
}
