//! The data the joints' rows and their solve share: a body of a mechanism as the joints see
//! it, and one row of J (constraint.rs makes the rows, solve.rs solves for their reactions).

use crate::math::{Matrix, Point, Real, Vector};

/// One body of a mechanism as the joints see it at an instant (world frame).
#[derive(Clone, Debug)]
pub(crate) struct JointBody {
    /// CG (m).
    pub x: Point,
    /// Orientation, body -> world.
    pub r: Matrix,
    /// CG velocity (m/s).
    pub v: Vector,
    /// Angular velocity (rad/s).
    pub w: Vector,
    /// 1 / mass (1/kg).
    pub inv_mass: Real,
    /// World inverse inertia (1/(kg m^2)).
    pub inv_inertia: Matrix,
}

/// One held quantity (see constraint.rs's notes). Body b is None for the world.
#[derive(Clone, Debug)]
pub(crate) struct Row {
    pub(super) a: usize,
    pub(super) b: Option<usize>,
    /// (linear, angular) parts of J on body a and body b.
    pub(super) ja: [Vector; 2],
    pub(super) jb: [Vector; 2],
    /// The value C (m or 1).
    pub(super) c: Real,
    /// J' nu, the part of C's second derivative from the velocities alone.
    pub(super) bias: Real,
}

#[cfg(test)]
impl JointBody {
    /// The tests' body: unit mass and inertia at the origin, turned by `r` (body -> world),
    /// turning at `w` (rad/s, world), its CG still.
    pub(super) fn turning(r: Matrix, w: Vector) -> JointBody {
        JointBody {
            x: Point::origin(),
            r,
            v: Vector::zeros(),
            w,
            inv_mass: 1.0,
            inv_inertia: Matrix::identity(),
        }
    }
}
