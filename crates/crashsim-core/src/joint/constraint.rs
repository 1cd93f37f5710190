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

use super::row::{JointBody, Row};
use super::solve::{mobility, solve, solve_each};
use super::{passive, JointKind, JointSpec, FRICTION_SMOOTHING};
use crate::math::{Matrix, Point, Real, Rotation, Vector};

/// Per body (or per joint): a (force, torque) or (linear, angular) pair, world frame.
pub(crate) type Pairs = Vec<(Vector, Vector)>;

/// A joint's frames in the world now: (anchor, axes as columns) on body a and on body b.
fn frames(joint: &JointSpec, bodies: &[JointBody]) -> ((Point, Matrix), (Point, Matrix)) {
    let a = &bodies[joint.body1];
    let (p1, q1) = &joint.frame1;
    let f1 = (
        a.x + a.r * p1.coords,
        a.r * q1.to_rotation_matrix().into_inner(),
    );
    let (p2, q2) = &joint.frame2;
    let f2 = match joint.body2 {
        Some(b) => {
            let b = &bodies[b];
            (
                b.x + b.r * p2.coords,
                b.r * q2.to_rotation_matrix().into_inner(),
            )
        }
        None => (*p2, q2.to_rotation_matrix().into_inner()),
    };
    (f1, f2)
}

/// The pairs (axis of F1, axis of F2) a kind holds perpendicular (column indices).
fn alignments(kind: JointKind) -> &'static [(usize, usize)] {
    match kind {
        JointKind::Spherical => &[],
        JointKind::Revolute => &[(0, 2), (1, 2)],
        JointKind::Fixed => &[(0, 1), (1, 2), (2, 0)],
        JointKind::FifthWheel => &[(1, 2)],
    }
}

fn velocity(bodies: &[JointBody], b: Option<usize>) -> (Vector, Vector) {
    b.map_or((Vector::zeros(), Vector::zeros()), |b| {
        (bodies[b].v, bodies[b].w)
    })
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

/// The kind's angles (rad; see [`super::JointSample::angles`]) and the world axis each
/// turns about.
pub(super) fn angles(joint: &JointSpec, bodies: &[JointBody]) -> (Vector, [Vector; 3]) {
    let ((_, a1), (_, a2)) = frames(joint, bodies);
    let col = |m: &Matrix, k: usize| m.column(k).into_owned();
    let (x1, y1, z1) = (col(&a1, 0), col(&a1, 1), col(&a1, 2));
    let (x2, z2) = (col(&a2, 0), col(&a2, 2));
    match joint.kind {
        JointKind::Revolute => (
            Vector::new(y1.dot(&x2).atan2(x1.dot(&x2)), 0.0, 0.0),
            [z1, Vector::zeros(), Vector::zeros()],
        ),
        JointKind::FifthWheel => {
            let across = y1.cross(&z2);
            (
                Vector::new(
                    x2.dot(&y1).atan2(x2.dot(&across)),
                    x1.dot(&z2).atan2(z1.dot(&z2)),
                    0.0,
                ),
                [z2, y1, Vector::zeros()],
            )
        }
        JointKind::Spherical => {
            // The product of two rotations is a rotation: taken as it is (nalgebra's
            // from_matrix iterates to the nearest rotation, 38 % of a towed run's time).
            let relative = Rotation::from_rotation_matrix(
                &nalgebra::Rotation3::from_matrix_unchecked(a1.transpose() * a2),
            );
            (
                relative.scaled_axis(),
                [a1 * Vector::x(), a1 * Vector::y(), a1 * Vector::z()],
            )
        }
        JointKind::Fixed => (Vector::zeros(), [Vector::zeros(); 3]),
    }
}

/// The angles a limit bounds (rad; see [`super::JointKind::limit_names`]) and, per angle, the
/// world vector g whose dot product with the relative angular velocity (body b's less body
/// a's) is the angle's rate. The kinds with angles about fixed axes give [`angles`]; a ball
/// joint gives its swing and twist:
///
/// - swing `s = acos(z1.z2)`: `ds/dt = (w_b - w_a).(z1 x z2)/|z1 x z2|` (a unit axis);
/// - twist `t = 2 atan2(q_z, q_w)`, q = (q_w, q_x, q_y, q_z) the relative rotation F1 -> F2 in
///   F1's axes (q_w >= 0): with `dq/dt = (0, w)/2 * q` for w the relative angular velocity in
///   F1's axes, `dt/dt = g.w` with `g = (q_w q_y + q_x q_z, q_y q_z - q_w q_x, q_w^2 + q_z^2) /
///   (q_w^2 + q_z^2)` (not a unit vector: the twist's rate also takes a share of a swing's).
///   Its size is 1 / cos(s/2): past a swing of [`TWIST_HELD_SWING`] g is taken as none and
///   no limit holds the twist (a rate vector of zero: see [`limit_rows`]).
pub(crate) fn limit_angles(joint: &JointSpec, bodies: &[JointBody]) -> (Vector, [Vector; 3]) {
    if joint.kind != JointKind::Spherical {
        return angles(joint, bodies);
    }
    let ((_, a1), (_, a2)) = frames(joint, bodies);
    let (z1, z2) = (a1.column(2).into_owned(), a2.column(2).into_owned());
    let across = z1.cross(&z2);
    let swing = across.norm().atan2(z1.dot(&z2));
    // At no swing the cone's axis is undefined, and no cone limit is reached there.
    let swing_axis = across.try_normalize(1e-12).unwrap_or_else(Vector::zeros);
    let relative = Rotation::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(
        a1.transpose() * a2,
    ));
    let q = relative.quaternion();
    let sign = if q.w < 0.0 { -1.0 } else { 1.0 };
    let (w, x, y, z) = (sign * q.w, sign * q.i, sign * q.j, sign * q.k);
    let twist = 2.0 * z.atan2(w);
    let norm = w * w + z * z;
    // Past TWIST_HELD_SWING the twist is not held: its rate vector (size 1/cos(s/2)) is none.
    let twist_axis = if swing <= TWIST_HELD_SWING {
        a1 * Vector::new(w * y + x * z, y * z - w * x, norm) / norm
    } else {
        Vector::zeros()
    };
    (
        Vector::new(swing, twist, 0.0),
        [swing_axis, twist_axis, Vector::zeros()],
    )
}

/// The time derivative of each rate vector g of [`limit_angles`] (1/s, world) as the bodies
/// turn at their angular velocities: the angle's second derivative is
/// `g.(dw_b/dt - dw_a/dt) + (w_b - w_a).dg/dt`, whose last term is a limit row's J' nu (the
/// curvature of a cone: a thigh sliding round its hip's cone at rate w has a swing
/// acceleration of about w^2 / tan s with no torque at all).
///
/// - An axis fixed in a body turns with it: `dg/dt = w x g` (a hinge's z1, a fifth wheel's).
/// - The swing's unit axis `n = c / |c|`, `c = z1 x z2`: `dn/dt = (dc/dt - n (n.dc/dt)) / |c|`
///   with `dc/dt = (w_a x z1) x z2 + z1 x (w_b x z2)`.
/// - The twist's `g = A1 u / N`, `u = (q_w q_y + q_x q_z, q_y q_z - q_w q_x, N)`, `N = q_w^2 +
///   q_z^2`: `dg/dt = w_a x g + A1 (du/dt - (u / N) dN/dt) / N`, with `dq/dt = (0, W) q / 2`
///   and W the relative angular velocity in F1's axes.
pub(crate) fn limit_axis_rates(joint: &JointSpec, bodies: &[JointBody]) -> [Vector; 3] {
    let (_, wa) = velocity(bodies, Some(joint.body1));
    let (_, wb) = velocity(bodies, joint.body2);
    let ((_, a1), (_, a2)) = frames(joint, bodies);
    let col = |m: &Matrix, k: usize| m.column(k).into_owned();
    match joint.kind {
        JointKind::Revolute => [wa.cross(&col(&a1, 2)), Vector::zeros(), Vector::zeros()],
        JointKind::FifthWheel => [
            wb.cross(&col(&a2, 2)),
            wa.cross(&col(&a1, 1)),
            Vector::zeros(),
        ],
        JointKind::Fixed => [Vector::zeros(); 3],
        JointKind::Spherical => {
            let (z1, z2) = (col(&a1, 2), col(&a2, 2));
            let c = z1.cross(&z2);
            let size = c.norm();
            let swing = if size > 1e-12 {
                let n = c / size;
                let dc = wa.cross(&z1).cross(&z2) + z1.cross(&wb.cross(&z2));
                (dc - n * n.dot(&dc)) / size
            } else {
                Vector::zeros()
            };
            let relative = Rotation::from_rotation_matrix(
                &nalgebra::Rotation3::from_matrix_unchecked(a1.transpose() * a2),
            );
            let q = relative.quaternion();
            let sign = if q.w < 0.0 { -1.0 } else { 1.0 };
            let q = nalgebra::Quaternion::new(sign * q.w, sign * q.i, sign * q.j, sign * q.k);
            let turn = a1.transpose() * (wb - wa);
            let dq = nalgebra::Quaternion::from_parts(0.0, turn) * q * 0.5;
            let (w, x, y, z) = (q.w, q.i, q.j, q.k);
            let (dw, dx, dy, dz) = (dq.w, dq.i, dq.j, dq.k);
            let norm = w * w + z * z;
            let twist = if size.atan2(z1.dot(&z2)) <= TWIST_HELD_SWING {
                let u = Vector::new(w * y + x * z, y * z - w * x, norm);
                let du = Vector::new(
                    dw * y + w * dy + dx * z + x * dz,
                    dy * z + y * dz - dw * x - w * dx,
                    2.0 * (w * dw + z * dz),
                );
                let g = a1 * u / norm;
                wa.cross(&g) + a1 * (du - u * (du.z / norm)) / norm
            } else {
                Vector::zeros()
            };
            [swing, twist, Vector::zeros()]
        }
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

/// The largest swing (rad, 150 deg) at which a ball joint's twist limit holds. The twist's
/// rate vector grows as 1 / cos(s/2) towards a swing of 180 deg, where the twist is not
/// defined: a shoulder (no swing limit: its published range reaches 180 deg) whose arm was
/// flung past 179.99 deg made the limit's row 1e5 times the size of the others and its J' nu
/// 2e12, and one Runge-Kutta step threw every segment of the person to 1e8 m/s (the stalled
/// study variant of docs/studies.md). At 150 deg the vector is 3.9 times a unit one.
pub(crate) const TWIST_HELD_SWING: Real = 150.0 * std::f64::consts::PI / 180.0;

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

    fn body(r: Matrix, w: Vector) -> JointBody {
        JointBody {
            x: Point::origin(),
            r,
            v: Vector::zeros(),
            w,
            inv_mass: 1.0,
            inv_inertia: Matrix::identity(),
        }
    }

    /// The swing's and the twist's rate vectors against central differences of the angles
    /// along the motion, over orientations of every swing up to 170 deg and twists of both
    /// signs (relative error below 1e-6).
    /// Sample `i` of the test motions: two bodies' orientations (world from body) and
    /// angular velocities (rad/s, world), spread over many relative orientations.
    fn sample_motion(i: usize) -> (Matrix, Matrix, Vector, Vector) {
        let f = i as Real;
        let ra = Rotation::from_scaled_axis(Vector::new(0.1 * f, -0.05 * f, 0.02 * f))
            .to_rotation_matrix()
            .into_inner();
        let rb = Rotation::from_scaled_axis(Vector::new(
            (0.37 * f).sin() * 2.5,
            (0.23 * f).cos() * 1.5,
            0.3 * f - 6.0,
        ))
        .to_rotation_matrix()
        .into_inner();
        let wa = Vector::new(0.4, -0.7, 0.2);
        let wb = Vector::new((0.5 * f).cos(), 0.8, -(0.3 * f).sin());
        (ra, rb, wa, wb)
    }

    #[test]
    fn a_ball_joints_limit_rates_are_the_angles_derivatives() {
        let joint = JointSpec::new(
            JointKind::Spherical,
            0,
            Some(1),
            (Point::origin(), Rotation::from_euler_angles(0.3, -0.2, 0.9)),
            (Point::origin(), Rotation::from_euler_angles(-0.1, 0.4, 0.2)),
        );
        let h = 1e-6;
        let mut checked = 0;
        for i in 0..40 {
            let (ra, rb, wa, wb) = sample_motion(i);
            let at = |s: Real| {
                let turn = |w: Vector| Rotation::from_scaled_axis(w * s).to_rotation_matrix();
                let bodies = [
                    body(turn(wa).into_inner() * ra, wa),
                    body(turn(wb).into_inner() * rb, wb),
                ];
                limit_angles(&joint, &bodies)
            };
            let (theta, axes) = at(0.0);
            if theta.x > TWIST_HELD_SWING - 0.01 || theta.x < 0.05 {
                continue; // no rate past TWIST_HELD_SWING (below)
            }
            let (plus, minus) = (at(h).0, at(-h).0);
            for k in 0..2 {
                let numeric = (plus[k] - minus[k]) / (2.0 * h);
                let rate = (wb - wa).dot(&axes[k]);
                assert!(
                    (numeric - rate).abs() < 1e-6 * (1.0 + rate.abs()),
                    "angle {k} at {theta:?}: {numeric} against {rate}"
                );
            }
            checked += 1;
        }
        assert!(checked > 30, "only {checked} orientations checked");
    }
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
            let bodies = [body(Matrix::identity(), Vector::zeros()), body(rb, w)];
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

    /// The rate vectors' time derivatives (a limit row's J' nu) against central differences
    /// of the rate vectors along the motion, for a ball joint (swing and twist), a hinge and
    /// a fifth wheel, over many orientations (relative error below 1e-6).
    #[test]
    fn limit_axis_rates_are_the_rate_vectors_derivatives() {
        let frames = (
            (Point::origin(), Rotation::from_euler_angles(0.3, -0.2, 0.9)),
            (Point::origin(), Rotation::from_euler_angles(-0.1, 0.4, 0.2)),
        );
        let h = 1e-6;
        for kind in [
            JointKind::Spherical,
            JointKind::Revolute,
            JointKind::FifthWheel,
        ] {
            let joint = JointSpec::new(kind, 0, Some(1), frames.0, frames.1);
            let mut checked = 0;
            for i in 0..40 {
                let (ra, rb, wa, wb) = sample_motion(i);
                let bodies_at = |s: Real| {
                    let turn = |w: Vector| Rotation::from_scaled_axis(w * s).to_rotation_matrix();
                    [
                        body(turn(wa).into_inner() * ra, wa),
                        body(turn(wb).into_inner() * rb, wb),
                    ]
                };
                let (theta, _) = limit_angles(&joint, &bodies_at(0.0));
                if kind == JointKind::Spherical
                    && (theta.x > TWIST_HELD_SWING - 0.01 || theta.x < 0.05)
                {
                    continue;
                }
                let rates = limit_axis_rates(&joint, &bodies_at(0.0));
                let (plus, minus) = (
                    limit_angles(&joint, &bodies_at(h)).1,
                    limit_angles(&joint, &bodies_at(-h)).1,
                );
                for k in 0..3 {
                    let numeric = (plus[k] - minus[k]) / (2.0 * h);
                    assert!(
                        (numeric - rates[k]).norm() < 1e-6 * (1.0 + rates[k].norm()),
                        "{kind:?} angle {k} at {theta:?}: {numeric:?} against {:?}",
                        rates[k]
                    );
                }
                checked += 1;
            }
            assert!(
                checked > 30,
                "{kind:?}: only {checked} orientations checked"
            );
        }
    }
}
