//! The joints' equations in the bodies' coordinates (world frame, SI).
//!
//! Every held quantity is a row: a scalar C of the two bodies' poses that the joint keeps at
//! 0, whose rate is linear in the bodies' velocities, `dC/dt = J nu` (nu = v_a, w_a, v_b, w_b),
//! and whose second derivative is `J dnu/dt + (J' nu)`, the last term from the velocities
//! alone. Two shapes of row cover every kind:
//!
//! - an anchor coordinate, `C = e.(p_b - p_a)` with p the anchors and e a world axis: J is
//!   (-e, -(r_a x e)) on body a and (e, r_b x e) on body b (r from the CG to the anchor), and
//!   `J' nu = e.(w_b x (w_b x r_b) - w_a x (w_a x r_a))`;
//! - an alignment, `C = u.n` with u an axis fixed in body a and n one fixed in body b (held
//!   perpendicular): J is (0, u x n) on a and (0, -(u x n)) on b, and
//!   `J' nu = (w_a x (w_a x u)).n + 2 (w_a x u).(w_b x n) + u.(w_b x (w_b x n))`.
//!
//! The reactions lambda (one per row, the force or torque body a puts on body b) make every
//! row's acceleration vanish: `(J W J^T) lambda = -(J a_free + J' nu)`, W the bodies' inverse
//! masses and world inverse inertias, a_free their accelerations without the joints. The
//! matrix is symmetric positive definite when no row repeats another (a tree of joints);
//! redundant rows (a loop, a body held twice) are solved by least squares.

use nalgebra::DVector;

use super::angles::{angles, frames, limit_angles, limit_axis_rates, velocity};
use super::row::{JointBody, Row};
use super::solve::{mobility, solve, solve_each};
use super::{passive, JointKind, JointSpec, FRICTION_SMOOTHING};
use crate::math::{Real, Vector};

/// Per body (or per joint): a (force, torque) or (linear, angular) pair, world frame.
pub(crate) type Pairs = Vec<(Vector, Vector)>;

/// The pairs (axis of F1, axis of F2) a kind holds perpendicular (column indices).
fn alignments(kind: JointKind) -> &'static [(usize, usize)] {
    match kind {
        JointKind::Spherical => &[],
        JointKind::Revolute => &[(0, 2), (1, 2)],
        JointKind::Fixed => &[(0, 1), (1, 2), (2, 0)],
        JointKind::FifthWheel => &[(1, 2)],
    }
}

/// Every row of `joint` at the bodies' state.
pub(crate) fn rows(joint: &JointSpec, bodies: &[JointBody], out: &mut Vec<Row>) {
    let ((p1, a1), (p2, a2)) = frames(joint, bodies);
    let (a, b) = (joint.body1, joint.body2);
    let r1 = p1 - bodies[a].x;
    let r2 = b.map_or(Vector::zeros(), |b| p2 - bodies[b].x);
    let (_, wa) = velocity(bodies, Some(a));
    let (_, wb) = velocity(bodies, b);
    let centripetal = wb.cross(&wb.cross(&r2)) - wa.cross(&wa.cross(&r1));
    for k in 0..3 {
        let e = Vector::ith(k, 1.0);
        out.push(Row {
            a,
            b,
            ja: [-e, -r1.cross(&e)],
            jb: [e, r2.cross(&e)],
            c: (p2 - p1)[k],
            bias: e.dot(&centripetal),
        });
    }
    for &(i, j) in alignments(joint.kind) {
        let (u, n) = (a1.column(i).into_owned(), a2.column(j).into_owned());
        let g = u.cross(&n);
        let (du, dn) = (wa.cross(&u), wb.cross(&n));
        out.push(Row {
            a,
            b,
            ja: [Vector::zeros(), g],
            jb: [Vector::zeros(), -g],
            c: u.dot(&n),
            bias: wa.cross(&du).dot(&n) + 2.0 * du.dot(&dn) + u.dot(&wb.cross(&dn)),
        });
    }
}

/// The torque (N m, world) the joint's stiffness, damping, friction and passive moments put
/// on body b (body a gets its negative): the first three about the free angles, towards the
/// angles at the start; each passive moment about its angle's axis (see [`passive::passive_torque`]).
/// `joints` are the mechanism's (the coupled angles' joints among them).
pub(crate) fn applied_torques(
    joint: &JointSpec,
    bodies: &[JointBody],
    joints: &[JointSpec],
) -> Vector {
    let linear = (joint.stiffness, joint.damping, joint.friction) != (0.0, 0.0, 0.0);
    match (linear, joint.passive.is_empty()) {
        (false, true) => Vector::zeros(),
        (true, true) => linear_torques(joint, bodies),
        (false, false) => passive::passive_torque(joint, bodies, joints),
        (true, false) => {
            linear_torques(joint, bodies) + passive::passive_torque(joint, bodies, joints)
        }
    }
}

/// The stiffness, damping and friction torque of [`applied_torques`] (N m, world, on body b).
fn linear_torques(joint: &JointSpec, bodies: &[JointBody]) -> Vector {
    let (_, wa) = velocity(bodies, Some(joint.body1));
    let (_, wb) = velocity(bodies, joint.body2);
    let relative = wb - wa;
    let resist = |angle: Real, rate: Real| {
        -(joint.stiffness * angle
            + joint.damping * rate
            + joint.friction * rate / (rate.abs() + FRICTION_SMOOTHING))
    };
    let (theta, axes) = angles(joint, bodies);
    match joint.kind {
        // About the hinge; the fifth wheel's about the kingpin (the plate's friction).
        JointKind::Revolute | JointKind::FifthWheel => {
            axes[0] * resist(theta[0], relative.dot(&axes[0]))
        }
        JointKind::Spherical => {
            let angle_world = axes[0] * theta.x + axes[1] * theta.y + axes[2] * theta.z;
            let speed = relative.norm();
            -(angle_world * joint.stiffness
                + relative * joint.damping
                + relative * (joint.friction / (speed + FRICTION_SMOOTHING)))
        }
        JointKind::Fixed => Vector::zeros(),
    }
}

/// The rows of the limits `joint` is past now, or within `margin` (rad) of (each with C the
/// angle past its bound, negative inside it) and, per row, the limit's index and whether the
/// joint moves further out. The position projection takes the limits past (margin 0); the
/// velocity projection those within [`RESTING_ANGLE`], as the position projection leaves a
/// joint it put back on its bound a rounding's worth inside it as often as outside.
pub(crate) fn limit_rows(
    joint: &JointSpec,
    bodies: &[JointBody],
    margin: Real,
    out: &mut Vec<Row>,
) -> Vec<(usize, bool)> {
    if joint.limits.is_empty() {
        return Vec::new();
    }
    let (theta, axes) = limit_angles(joint, bodies);
    let (_, wa) = velocity(bodies, Some(joint.body1));
    let (_, wb) = velocity(bodies, joint.body2);
    let mut which = Vec::new();
    for (k, limit) in joint.limits.iter().enumerate() {
        let (angle, axis) = (theta[limit.angle], axes[limit.angle]);
        if axis == Vector::zeros() {
            continue; // an angle with no rate now (a swing of 0, a twist past its swing)
        }
        let rate = (wb - wa).dot(&axis);
        let (past, outward) = if angle > limit.upper - margin {
            (angle - limit.upper, rate > 0.0)
        } else if angle < limit.lower + margin {
            (angle - limit.lower, rate < 0.0)
        } else {
            continue;
        };
        out.push(Row {
            a: joint.body1,
            b: joint.body2,
            ja: [Vector::zeros(), -axis],
            jb: [Vector::zeros(), axis],
            c: past,
            bias: 0.0,
        });
        which.push((k, outward));
    }
    which
}

/// How close (rad) to a limit's bound a joint resting on it may be for the limit to hold it
/// (the projection leaves it on the bound to about 1e-13 rad).
pub(crate) const RESTING_ANGLE: Real = 1e-6;
/// How fast (rad/s) a joint resting on a limit may move away from it for the limit to hold
/// it still (a Runge-Kutta stage's rounding).
pub(crate) const RESTING_RATE: Real = 1e-6;

/// The rows of the `engaged` limits `joint` rests on now (at the bound within
/// [`RESTING_ANGLE`], not leaving it faster than [`RESTING_RATE`]), each held still
/// (C'' = 0), and per row the sign its reaction must have: +1 at a lower bound, -1 at an
/// upper one.
fn resting_limit_rows(
    joint: &JointSpec,
    bodies: &[JointBody],
    engaged: &[bool],
    out: &mut Vec<Row>,
    signs: &mut Vec<Real>,
) {
    let (theta, axes) = limit_angles(joint, bodies);
    let turning = limit_axis_rates(joint, bodies);
    let (_, wa) = velocity(bodies, Some(joint.body1));
    let (_, wb) = velocity(bodies, joint.body2);
    for (limit, _) in joint.limits.iter().zip(engaged).filter(|(_, &e)| e) {
        let (angle, axis) = (theta[limit.angle], axes[limit.angle]);
        if axis == Vector::zeros() {
            continue; // as in limit_rows
        }
        let rate = (wb - wa).dot(&axis);
        let sign = if angle >= limit.upper - RESTING_ANGLE && rate >= -RESTING_RATE {
            -1.0
        } else if angle <= limit.lower + RESTING_ANGLE && rate <= RESTING_RATE {
            1.0
        } else {
            continue;
        };
        out.push(Row {
            a: joint.body1,
            b: joint.body2,
            ja: [Vector::zeros(), -axis],
            jb: [Vector::zeros(), axis],
            c: 0.0,
            bias: (wb - wa).dot(&turning[limit.angle]),
        });
        signs.push(sign);
    }
}

/// The largest rate (m/s at the anchor, rad/s between axes) at which the joint's held
/// quantities change now: 0 when the bodies' velocities agree with the joint.
pub(crate) fn drift_rate(joint: &JointSpec, bodies: &[JointBody]) -> Real {
    let mut rows = Vec::new();
    self::rows(joint, bodies, &mut rows);
    let nu: Vec<_> = bodies.iter().map(|b| (b.v, b.w)).collect();
    rows.iter()
        .fold(0.0, |m: Real, r| m.max(apply(r, &nu).abs()))
}

/// `J x` of one row for per-body (linear, angular) values `x`.
fn apply(row: &Row, x: &[(Vector, Vector)]) -> Real {
    let mut s = row.ja[0].dot(&x[row.a].0) + row.ja[1].dot(&x[row.a].1);
    if let Some(b) = row.b {
        s += row.jb[0].dot(&x[b].0) + row.jb[1].dot(&x[b].1);
    }
    s
}

/// Per body, the sum of `J^T lambda` weighted by `W` (a velocity change per impulse) or not
/// (a force and torque), for the rows' `lambda`.
fn spread(
    rows: &[Row],
    bodies: &[JointBody],
    lambda: &DVector<Real>,
    weighted: bool,
) -> Vec<(Vector, Vector)> {
    let mut out = vec![(Vector::zeros(), Vector::zeros()); bodies.len()];
    for (row, l) in rows.iter().zip(lambda.iter()) {
        let (da, db) = if weighted {
            mobility(row, bodies)
        } else {
            (row.ja, row.jb)
        };
        out[row.a].0 += da[0] * *l;
        out[row.a].1 += da[1] * *l;
        if let Some(b) = row.b {
            out[b].0 += db[0] * *l;
            out[b].1 += db[1] * *l;
        }
    }
    out
}

/// The joints' reactions: per body the force and torque (N, N m, world) that keep every
/// joint's rows from accelerating, given each body's acceleration without them (linear,
/// angular; m/s^2, rad/s^2). Also each joint's reaction on its body 2 (force, torque about
/// the anchor's ... as the rows give it: the anchor force, and the alignment torques).
///
/// `engaged` (per joint and limit, may be empty: none) marks the limits a joint rests
/// against: each one the joint is at (within [`RESTING_ANGLE`]) and not leaving (faster than
/// [`RESTING_RATE`]) is held too, as long as its reaction pushes the joint inward (a
/// unilateral row: one pulling is dropped and the rest solved again).
pub(crate) fn reactions(
    joints: &[JointSpec],
    bodies: &[JointBody],
    free: &[(Vector, Vector)],
    engaged: &[Vec<bool>],
) -> (Pairs, Pairs) {
    let mut rows = Vec::new();
    let mut owner = Vec::new();
    for (k, joint) in joints.iter().enumerate() {
        let before = rows.len();
        self::rows(joint, bodies, &mut rows);
        owner.extend(std::iter::repeat_n(k, rows.len() - before));
    }
    let held = rows.len();
    // Per resting limit row: the sign its reaction must have (+1 at a lower bound).
    let mut signs = Vec::new();
    for (k, joint) in joints.iter().enumerate() {
        if engaged.get(k).is_some_and(|e| e.iter().any(|&f| f)) {
            let before = rows.len();
            resting_limit_rows(joint, bodies, &engaged[k], &mut rows, &mut signs);
            owner.extend(std::iter::repeat_n(k, rows.len() - before));
        }
    }
    let rhs = |rows: &[Row]| {
        DVector::from_iterator(rows.len(), rows.iter().map(|r| -(apply(r, free) + r.bias)))
    };
    let mut lambda = solve(&rows, bodies, rhs(&rows));
    // Drop the limit rows that pull (the joint leaves the limit) until none does.
    while let Some(i) = (held..rows.len()).find(|&i| lambda[i] * signs[i - held] < 0.0) {
        rows.remove(i);
        owner.remove(i);
        signs.remove(i - held);
        lambda = solve(&rows, bodies, rhs(&rows));
    }
    let per_body = spread(&rows, bodies, &lambda, false);
    let mut per_joint = vec![(Vector::zeros(), Vector::zeros()); joints.len()];
    for ((row, l), k) in rows.iter().zip(lambda.iter()).zip(&owner) {
        per_joint[*k].0 += row.jb[0] * *l;
        // The torque on body b about its anchor: the alignment rows' (the anchor rows' force
        // acts at the anchor).
        if row.jb[0] == Vector::zeros() {
            per_joint[*k].1 += row.jb[1] * *l;
        }
    }
    (per_body, per_joint)
}

/// The velocity change per body (linear, angular) that brings every row's rate to zero with
/// the least kinetic energy change: `-W J^T (J W J^T)^-1 J nu` over the joints' rows and the
/// extra rows given (the limits being stopped), nu the bodies' own velocities.
pub(crate) fn project_velocities(
    joints: &[JointSpec],
    bodies: &[JointBody],
    extra: &[Row],
) -> Vec<(Vector, Vector)> {
    let nu: Vec<_> = bodies.iter().map(|b| (b.v, b.w)).collect();
    let mut change = project_velocities_each(joints, bodies, extra, &[nu]);
    change.pop().expect("one change per set of velocities")
}

/// [`project_velocities`] of several sets of velocities of the same bodies at the same poses
/// (`bodies`' own velocities are not used: the rows' Jacobians depend on the poses only): the
/// rows' matrix built and factored once; each change the bits it would get alone.
pub(crate) fn project_velocities_each(
    joints: &[JointSpec],
    bodies: &[JointBody],
    extra: &[Row],
    velocities: &[Vec<(Vector, Vector)>],
) -> Vec<Vec<(Vector, Vector)>> {
    let mut rows = Vec::new();
    for joint in joints {
        self::rows(joint, bodies, &mut rows);
    }
    rows.extend_from_slice(extra);
    if rows.is_empty() {
        return vec![vec![(Vector::zeros(), Vector::zeros()); bodies.len()]; velocities.len()];
    }
    let rhs = velocities
        .iter()
        .map(|nu| DVector::from_iterator(rows.len(), rows.iter().map(|r| -apply(r, nu))))
        .collect();
    solve_each(&rows, bodies, rhs)
        .iter()
        .map(|lambda| spread(&rows, bodies, lambda, true))
        .collect()
}

/// The largest |C| over the rows (m or rad) and the position change per body (CG shift m,
/// rotation vector rad) that brings every row's value to zero, to first order with the least
/// mass-weighted motion (one Newton step of `-W J^T (J W J^T)^-1 C`), over the joints' rows
/// and the extra rows given; no change (zeros, nothing solved) when the largest |C| is below
/// `settled` (m or rad; 0: always solved).
pub(crate) fn project_positions(
    joints: &[JointSpec],
    bodies: &[JointBody],
    extra: &[Row],
    settled: Real,
) -> (Vec<(Vector, Vector)>, Real) {
    let mut rows = Vec::new();
    for joint in joints {
        self::rows(joint, bodies, &mut rows);
    }
    rows.extend_from_slice(extra);
    let worst = rows.iter().fold(0.0, |m: Real, r| m.max(r.c.abs()));
    if rows.is_empty() || worst == 0.0 || worst < settled {
        return (
            vec![(Vector::zeros(), Vector::zeros()); bodies.len()],
            worst,
        );
    }
    let rhs = DVector::from_iterator(rows.len(), rows.iter().map(|r| -r.c));
    let lambda = solve(&rows, bodies, rhs);
    (spread(&rows, bodies, &lambda, true), worst)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Matrix, Point, Rotation};

    /// Past TWIST_HELD_SWING a ball joint's twist has no rate vector and no limit row, even
    /// far past its bounds; below it, its rate vector is 1 / cos(s/2) long and a twist past
    /// its limit gets its row (the stall of docs/studies.md: a shoulder at 179.99 deg).
    #[test]
    fn a_twist_is_not_held_past_its_largest_swing() {
        let mut joint = JointSpec::new(
            JointKind::Spherical,
            0,
            Some(1),
            (Point::origin(), Rotation::identity()),
            (Point::origin(), Rotation::identity()),
        );
        joint.limits = vec![crate::joint::AngleLimit {
            angle: 1,
            lower: -0.5,
            upper: 0.5,
        }];
        let w = Vector::new(0.3, -2.0, 5.0);
        for (swing, held) in [
            (140.0_f64, true),
            (149.9, true),
            (150.1, false),
            (179.99, false),
        ] {
            // a swing about x, then a twist of 1.2 rad about the swung z (past the 0.5 bound)
            let s = swing.to_radians();
            let rb = (Rotation::from_scaled_axis(Vector::x() * s)
                * Rotation::from_scaled_axis(Vector::z() * 1.2))
            .to_rotation_matrix()
            .into_inner();
            let bodies = [
                JointBody::turning(Matrix::identity(), Vector::zeros()),
                JointBody::turning(rb, w),
            ];
            let (theta, axes) = limit_angles(&joint, &bodies);
            assert!((theta.x - s).abs() < 1e-9 && (theta.y - 1.2).abs() < 1e-9);
            let mut rows = Vec::new();
            limit_rows(&joint, &bodies, 0.0, &mut rows);
            let turning = limit_axis_rates(&joint, &bodies);
            if held {
                assert!((axes[1].norm() - 1.0 / (s / 2.0).cos()).abs() < 1e-9);
                assert_eq!(rows.len(), 1, "at {swing} deg");
                assert!((rows[0].c - 0.7).abs() < 1e-9);
            } else {
                assert_eq!(axes[1], Vector::zeros(), "at {swing} deg");
                assert_eq!(turning[1], Vector::zeros());
                assert!(rows.is_empty(), "at {swing} deg");
            }
        }
    }
}
