//! A joint's kinematics (world frame, SI): its frames on the two bodies, the free angles and
//! the axes they turn about, the angles its limits bound (a ball joint's swing and twist) with
//! their rate vectors, and those vectors' time derivatives. constraint.rs builds the rows and
//! torques from them; passive.rs reads the angles its moments act about.

use super::row::JointBody;
use super::{JointKind, JointSpec};
use crate::math::{Matrix, Point, Real, Rotation, Vector};

/// A joint's frames in the world now: (anchor, axes as columns) on body a and on body b.
pub(super) fn frames(
    joint: &JointSpec,
    bodies: &[JointBody],
) -> ((Point, Matrix), (Point, Matrix)) {
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

/// Body `b`'s (velocity, angular velocity) (m/s, rad/s, world); zeros for the world (None).
pub(super) fn velocity(bodies: &[JointBody], b: Option<usize>) -> (Vector, Vector) {
    b.map_or((Vector::zeros(), Vector::zeros()), |b| {
        (bodies[b].v, bodies[b].w)
    })
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
///   no limit holds the twist (a rate vector of zero: see [`super::constraint::limit_rows`]).
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

/// The largest swing (rad, 150 deg) at which a ball joint's twist limit holds. The twist's
/// rate vector grows as 1 / cos(s/2) towards a swing of 180 deg, where the twist is not
/// defined: a shoulder (no swing limit: its published range reaches 180 deg) whose arm was
/// flung past 179.99 deg made the limit's row 1e5 times the size of the others and its J' nu
/// 2e12, and one Runge-Kutta step threw every segment of the person to 1e8 m/s (the stalled
/// study variant of docs/studies.md). At 150 deg the vector is 3.9 times a unit one.
pub(crate) const TWIST_HELD_SWING: Real = 150.0 * std::f64::consts::PI / 180.0;

#[cfg(test)]
mod tests {
    use super::*;

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

    /// The swing's and the twist's rate vectors against central differences of the angles
    /// along the motion, over orientations of every swing up to 170 deg and twists of both
    /// signs (relative error below 1e-6).
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
                    JointBody::turning(turn(wa).into_inner() * ra, wa),
                    JointBody::turning(turn(wb).into_inner() * rb, wb),
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
                        JointBody::turning(turn(wa).into_inner() * ra, wa),
                        JointBody::turning(turn(wb).into_inner() * rb, wb),
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
