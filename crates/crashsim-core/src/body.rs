//! Rigid bodies: mass properties, state, and torque-free motion between impulses.
//!
//! State is kept as CG position x (m, world), orientation q (body -> world), linear velocity
//! v (m/s, world) and world angular momentum L (kg m^2/s) about the CG. Between impulses
//! v and L are constant, x moves linearly and q follows w = R I^-1 R^T L, integrated with
//! classical Runge-Kutta on the quaternion in sub-steps of at most `MAX_SUBSTEP_ANGLE` rad
//! of rotation, so an asymmetric body's w evolves correctly while L stays exact.

use crate::error::{require_coordinate, require_finite, require_finite_vector, Error, Result};
use crate::math::{Isometry, Matrix, Point, Real, Rotation, Vector};

/// Largest rotation (rad) per Runge-Kutta sub-step; the local error is about angle^5 / 120.
const MAX_SUBSTEP_ANGLE: Real = 0.01;

/// Checks a body's mass (kg): finite and positive.
pub fn check_mass(mass: Real) -> Result<()> {
    require_finite("mass", mass)?;
    if mass <= 0.0 {
        return Err(Error::parameter(
            "mass",
            mass,
            "a mass must be positive (kg)",
        ));
    }
    Ok(())
}

/// Mass properties: mass (kg) and inertia tensor about the CG in the body frame (kg m^2).
#[derive(Clone, Debug, PartialEq)]
pub struct MassProperties {
    mass: Real,
    inertia: Matrix,
    inverse_inertia: Matrix,
    /// Principal moments, ascending (kg m^2).
    principal: [Real; 3],
    /// The largest eigenvalue of `inverse_inertia` (1/(kg m^2)): what the integration's
    /// sub-step bounds read every step (motion/), worked out once here.
    largest_inverse_moment: Real,
}

/// The largest eigenvalue of an inverse inertia (1/(kg m^2), 0 for none).
fn largest_eigenvalue(inverse_inertia: &Matrix) -> Real {
    inverse_inertia
        .symmetric_eigenvalues()
        .iter()
        .fold(0.0, |a: Real, b| a.max(*b))
}

impl MassProperties {
    /// Checks and builds mass properties. Errors: mass not finite or <= 0, inertia not
    /// finite, not symmetric (relative 1e-9), not positive definite, or impossible (its
    /// largest principal moment above the sum of the other two, relative 1e-6).
    pub fn new(mass: Real, inertia: Matrix) -> Result<MassProperties> {
        check_mass(mass)?;
        if !inertia.iter().all(|x| x.is_finite()) {
            return Err(Error::invalid(
                "the inertia tensor has a non-finite entry: give finite kg m^2 values",
            ));
        }
        let scale = inertia.abs().max();
        if (inertia - inertia.transpose()).abs().max() > 1e-9 * scale {
            return Err(Error::invalid(
                "the inertia tensor is not symmetric: I[i][j] must equal I[j][i]",
            ));
        }
        let sym = (inertia + inertia.transpose()) * 0.5;
        let eig = sym.symmetric_eigenvalues();
        let mut principal = [eig[0], eig[1], eig[2]];
        principal.sort_by(|a, b| a.total_cmp(b));
        let min_moment = principal[0];
        if min_moment <= 0.0 {
            return Err(Error::invalid(format!(
                "the inertia tensor is not positive definite (principal moments {:.6e}, {:.6e}, \
                 {:.6e} kg m^2): every principal moment must be positive",
                eig[0], eig[1], eig[2]
            )));
        }
        // Each principal moment of a body is at most the sum of the other two (I_z = sum of
        // m (x^2 + y^2) <= I_x + I_y = sum of m (x^2 + y^2 + 2 z^2)); equality for a flat body.
        let [a, b, c] = principal;
        if c - (a + b) > 1e-6 * c {
            return Err(Error::invalid(format!(
                "the inertia tensor is impossible: its largest principal moment {c:.6e} kg m^2 \
                 exceeds the sum of the other two ({a:.6e} + {b:.6e}); a body's principal \
                 moments each lie within the sum of the other two (check the axes and units)"
            )));
        }
        let inverse_inertia = sym
            .try_inverse()
            .ok_or_else(|| Error::invalid("the inertia tensor is singular"))?;
        Ok(MassProperties {
            mass,
            inertia: sym,
            largest_inverse_moment: largest_eigenvalue(&inverse_inertia),
            inverse_inertia,
            principal,
        })
    }

    /// The mass properties of an immovable body (a fixed obstacle): infinite mass and
    /// inertia, so 1/m = 0 and I^-1 = 0 in the collision matrix.
    pub fn immovable() -> MassProperties {
        MassProperties {
            mass: Real::INFINITY,
            inertia: Matrix::from_diagonal_element(Real::INFINITY),
            inverse_inertia: Matrix::zeros(),
            principal: [Real::INFINITY; 3],
            largest_inverse_moment: largest_eigenvalue(&Matrix::zeros()),
        }
    }

    /// True for an immovable body (infinite mass).
    #[inline]
    pub fn is_immovable(&self) -> bool {
        self.mass == Real::INFINITY
    }

    /// Mass (kg).
    #[inline]
    pub fn mass(&self) -> Real {
        self.mass
    }

    /// Inertia about the CG, body frame (kg m^2).
    #[inline]
    pub fn inertia(&self) -> &Matrix {
        &self.inertia
    }

    /// Inverse inertia, body frame (1 / (kg m^2)).
    #[inline]
    pub fn inverse_inertia(&self) -> &Matrix {
        &self.inverse_inertia
    }

    /// The largest eigenvalue of [`MassProperties::inverse_inertia`] (1/(kg m^2); 0 for an
    /// immovable body): one over the least principal moment.
    #[inline]
    pub fn largest_inverse_moment(&self) -> Real {
        self.largest_inverse_moment
    }
}

/// A body's kinematic state, world frame.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyState {
    /// CG position (m).
    pub position: Point,
    /// Orientation, body -> world.
    pub orientation: Rotation,
    /// CG velocity (m/s).
    pub velocity: Vector,
    /// Angular velocity (rad/s).
    pub angular_velocity: Vector,
}

impl BodyState {
    /// Checks that every number is finite and the position within the world
    /// ([`crate::error::MAX_COORDINATE`]).
    pub fn validate(&self) -> Result<()> {
        require_finite_vector("position", &self.position.coords)?;
        for (axis, x) in ["x", "y", "z"].iter().zip(self.position.iter()) {
            require_coordinate(&format!("position {axis}"), *x)?;
        }
        require_finite_vector("velocity", &self.velocity)?;
        require_finite_vector("angular_velocity", &self.angular_velocity)?;
        let q = self.orientation.coords;
        if !q.iter().all(|x| x.is_finite()) {
            return Err(Error::invalid("the orientation quaternion is not finite"));
        }
        Ok(())
    }
}

/// A rigid body in motion: mass properties and its state at the time it was last set.
#[derive(Clone, Debug)]
pub struct RigidBody {
    props: MassProperties,
    position: Point,
    orientation: Rotation,
    velocity: Vector,
    /// World angular momentum about the CG (kg m^2/s).
    angular_momentum: Vector,
}

impl RigidBody {
    /// A body with the given properties and state.
    pub fn new(props: MassProperties, state: &BodyState) -> Result<RigidBody> {
        state.validate()?;
        let mut body = RigidBody {
            props,
            position: state.position,
            orientation: state.orientation,
            velocity: state.velocity,
            angular_momentum: Vector::zeros(),
        };
        body.angular_momentum = body.world_inertia() * state.angular_velocity;
        Ok(body)
    }

    /// A body from its state with the angular momentum given directly (world, about the CG,
    /// kg m^2/s), as an integrator holds it.
    pub(crate) fn from_momentum(
        props: MassProperties,
        position: Point,
        orientation: Rotation,
        velocity: Vector,
        angular_momentum: Vector,
    ) -> RigidBody {
        RigidBody {
            props,
            position,
            orientation,
            velocity,
            angular_momentum,
        }
    }

    /// An immovable body (a fixed obstacle) at `pose`: at rest for ever, unmoved by impulses.
    pub fn immovable(position: Point, orientation: Rotation) -> RigidBody {
        RigidBody {
            props: MassProperties::immovable(),
            position,
            orientation,
            velocity: Vector::zeros(),
            angular_momentum: Vector::zeros(),
        }
    }

    /// Mass properties.
    #[inline]
    pub fn props(&self) -> &MassProperties {
        &self.props
    }

    /// CG position (m, world).
    #[inline]
    pub fn position(&self) -> Point {
        self.position
    }

    /// Orientation body -> world.
    #[inline]
    pub fn orientation(&self) -> Rotation {
        self.orientation
    }

    /// Pose body -> world.
    #[inline]
    pub fn pose(&self) -> Isometry {
        Isometry::from_parts(self.position.coords.into(), self.orientation)
    }

    /// CG velocity (m/s, world).
    #[inline]
    pub fn velocity(&self) -> Vector {
        self.velocity
    }

    /// World angular momentum about the CG (kg m^2/s).
    #[inline]
    pub fn angular_momentum(&self) -> Vector {
        self.angular_momentum
    }

    /// Angular velocity (rad/s, world).
    #[inline]
    pub fn angular_velocity(&self) -> Vector {
        self.world_inverse_inertia() * self.angular_momentum
    }

    /// Inertia in world axes about the CG (kg m^2).
    #[inline]
    pub fn world_inertia(&self) -> Matrix {
        let r = self.orientation.to_rotation_matrix();
        r.matrix() * self.props.inertia * r.matrix().transpose()
    }

    /// Inverse inertia in world axes (1 / (kg m^2)).
    #[inline]
    pub fn world_inverse_inertia(&self) -> Matrix {
        let r = self.orientation.to_rotation_matrix();
        r.matrix() * self.props.inverse_inertia * r.matrix().transpose()
    }

    /// The state (world frame).
    pub fn state(&self) -> BodyState {
        BodyState {
            position: self.position,
            orientation: self.orientation,
            velocity: self.velocity,
            angular_velocity: self.angular_velocity(),
        }
    }

    /// Upper bound of |w| over the torque-free motion from here (rad/s).
    ///
    /// In principal axes, x_i = w_i^2 satisfies sum I_i^2 x_i = |L|^2 and sum I_i x_i = 2 T
    /// (both constant), so |w|^2 is at most the largest sum x_i of that linear program, found
    /// at a vertex with at most two non-zero x_i. For a car yawing about its vertical axis this
    /// is the yaw rate itself, where |L| / I_min (the plain bound) overstates it about five-fold.
    pub fn angular_speed_bound(&self) -> Real {
        let l2 = self.angular_momentum.norm_squared();
        if l2 == 0.0 || self.props.is_immovable() {
            return 0.0;
        }
        let p = self.props.principal;
        let two_t = self.angular_velocity().dot(&self.angular_momentum).max(0.0);
        let plain = (l2.sqrt() / p[0]).min((two_t / p[0]).sqrt());
        let mut best: Real = -1.0;
        for &moment in &p {
            let x = l2 / (moment * moment);
            if (moment * x - two_t).abs() <= 1e-9 * two_t {
                best = best.max(x);
            }
        }
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let det = p[i] * p[i] * p[j] - p[j] * p[j] * p[i];
            if det.abs() <= 1e-12 * p[i] * p[i] * p[j] {
                continue; // equal moments: the single-axis vertices above cover them
            }
            let xi = (l2 * p[j] - p[j] * p[j] * two_t) / det;
            let xj = (p[i] * p[i] * two_t - p[i] * l2) / det;
            let tol = 1e-9 * (xi.abs() + xj.abs());
            if xi >= -tol && xj >= -tol {
                best = best.max(xi.max(0.0) + xj.max(0.0));
            }
        }
        if best < 0.0 {
            return plain;
        }
        // A margin for round-off and the integrator's drift in T; never above the plain bound.
        (best.sqrt() * (1.0 + 1e-6)).min(plain)
    }

    /// Kinetic energy, translational plus rotational (J).
    pub fn kinetic_energy(&self) -> Real {
        if self.props.is_immovable() {
            return 0.0;
        }
        let w = self.angular_velocity();
        0.5 * self.props.mass * self.velocity.norm_squared() + 0.5 * w.dot(&self.angular_momentum)
    }

    /// Velocity (m/s, world) of the body's material point now at world point `p`.
    #[inline]
    pub fn point_velocity(&self, p: &Point) -> Vector {
        self.velocity + self.angular_velocity().cross(&(p - self.position))
    }

    /// Applies the world impulse `j` (N s) at world point `p` (nothing for an immovable body).
    pub fn apply_impulse(&mut self, j: &Vector, p: &Point) {
        if self.props.is_immovable() {
            return;
        }
        self.velocity += j / self.props.mass;
        self.angular_momentum += (p - self.position).cross(j);
    }

    /// The body advanced by `dt` s of torque-free motion (negative `dt` runs it backwards).
    pub fn advanced(&self, dt: Real) -> RigidBody {
        let mut b = self.clone();
        b.advance(dt);
        b
    }

    /// Advances the body by `dt` s of torque-free motion (negative `dt` runs it backwards).
    pub fn advance(&mut self, dt: Real) {
        if dt == 0.0 {
            return;
        }
        self.position += self.velocity * dt;
        // Sub-steps from the plain bound |L| / I_min (finer than the exact one when the body
        // spins near a principal axis: the integrator's accuracy stays as it was).
        let wmax = self.angular_momentum.norm() / self.props.principal[0];
        if wmax == 0.0 {
            return;
        }
        let n = ((wmax * dt.abs()) / MAX_SUBSTEP_ANGLE).ceil().max(1.0) as usize;
        let h = dt / n as Real;
        for _ in 0..n {
            self.orientation = rk4_rotation_step(
                &self.orientation,
                &self.angular_momentum,
                &self.props.inverse_inertia,
                h,
            );
        }
    }
}

/// dq/dt = 1/2 q (0, w_b), w_b = I^-1 R^T L the body-frame angular velocity, as a raw
/// 4-vector (w, x, y, z) derivative; equal to 1/2 (0, w) q with w = R w_b the world one.
/// Runge-Kutta's intermediate q are not unit: for q = (s, u) of any norm,
/// conj(q) (0, L) q = (s^2 - |u|^2) L + 2 (u.L) u - 2 s (u x L) = |q|^2 R^T L, so the body
/// frame's L comes from one quadratic form and one division, without normalizing q (a
/// square root and a division) or rotating w back to the world.
#[inline]
fn quaternion_rate(
    q: &nalgebra::Quaternion<Real>,
    l: &Vector,
    inv_i: &Matrix,
) -> nalgebra::Quaternion<Real> {
    let (s, u) = (q.w, q.imag());
    let uu = u.norm_squared();
    // |q|^2 times the body-frame angular momentum (kg m^2/s)
    let l_body = l * (s * s - uu) + u * (2.0 * u.dot(l)) - u.cross(l) * (2.0 * s);
    // half the body-frame angular velocity (rad/s)
    let half_w = (inv_i * l_body) * (0.5 / (s * s + uu));
    // q (0, w_b / 2) = (-u.w_b, s w_b + u x w_b) / 2
    nalgebra::Quaternion::from_parts(-u.dot(&half_w), half_w * s + u.cross(&half_w))
}

fn rk4_rotation_step(q: &Rotation, l: &Vector, inv_i: &Matrix, h: Real) -> Rotation {
    let q0 = *q.quaternion();
    let k1 = quaternion_rate(&q0, l, inv_i);
    let k2 = quaternion_rate(&(q0 + k1 * (0.5 * h)), l, inv_i);
    let k3 = quaternion_rate(&(q0 + k2 * (0.5 * h)), l, inv_i);
    let k4 = quaternion_rate(&(q0 + k3 * h), l, inv_i);
    Rotation::new_normalize(q0 + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(w: Vector) -> BodyState {
        BodyState {
            position: Point::new(1.0, 2.0, 0.5),
            orientation: Rotation::identity(),
            velocity: Vector::new(3.0, -1.0, 0.0),
            angular_velocity: w,
        }
    }

    #[test]
    fn bad_mass_properties_are_refused() {
        let i = Matrix::identity();
        assert!(MassProperties::new(0.0, i).is_err());
        assert!(MassProperties::new(-1.0, i).is_err());
        assert!(MassProperties::new(Real::NAN, i).is_err());
        assert!(
            MassProperties::new(1.0, Matrix::from_diagonal(&Vector::new(1.0, 1.0, -1.0))).is_err()
        );
        let mut skew = i;
        skew[(0, 1)] = 0.5;
        assert!(MassProperties::new(1.0, skew).is_err());
        // Izz > Ixx + Iyy: no body has it; a flat one reaches the sum.
        let impossible = Matrix::from_diagonal(&Vector::new(500.0, 2000.0, 3000.0));
        assert!(MassProperties::new(1450.0, impossible).is_err());
        assert!(
            MassProperties::new(1.0, Matrix::from_diagonal(&Vector::new(1.0, 2.0, 3.0))).is_ok()
        );
    }

    #[test]
    fn symmetric_top_precesses_as_euler_says_and_conserves_momentum_and_energy() {
        // Axisymmetric body (I1 = I2 = 1, I3 = 2); body-frame w rotates about z at rate
        // (I3 - I1) / I1 * w3, |w| stays constant.
        let (i1, i3) = (1.0, 2.0);
        let props =
            MassProperties::new(10.0, Matrix::from_diagonal(&Vector::new(i1, i1, i3))).unwrap();
        let w0 = Vector::new(0.3, 0.0, 2.0);
        let body = RigidBody::new(props, &state(w0)).unwrap();
        let (l0, e0) = (body.angular_momentum(), body.kinetic_energy());
        let t = 1.7;
        let b = body.advanced(t);
        let w_body = b
            .orientation()
            .inverse_transform_vector(&b.angular_velocity());
        let omega = (i3 - i1) / i1 * w0.z;
        let expected = Vector::new(0.3 * (omega * t).cos(), 0.3 * (omega * t).sin(), 2.0);
        assert!((w_body - expected).norm() < 1e-10, "{w_body} vs {expected}");
        assert_eq!(b.angular_momentum(), l0);
        assert!((b.kinetic_energy() - e0).abs() < 1e-10 * e0);
        assert!((b.position() - Point::new(1.0 + 3.0 * t, 2.0 - t, 0.5)).norm() < 1e-12);
    }

    #[test]
    fn asymmetric_body_keeps_energy_and_result_does_not_depend_on_step_split() {
        let props = MassProperties::new(
            1500.0,
            Matrix::from_diagonal(&Vector::new(500.0, 2200.0, 2500.0)),
        )
        .unwrap();
        let body = RigidBody::new(props, &state(Vector::new(1.0, 0.5, 2.0))).unwrap();
        let e0 = body.kinetic_energy();
        let once = body.advanced(0.5);
        let mut split = body.clone();
        for _ in 0..7 {
            split.advance(0.5 / 7.0);
        }
        assert!((once.kinetic_energy() - e0).abs() < 1e-9 * e0);
        let dq = once.orientation().angle_to(&split.orientation());
        assert!(dq < 1e-10, "{dq}");
    }

    #[test]
    fn the_angular_speed_bound_holds_along_the_motion_and_is_tight_for_a_principal_spin() {
        use rand::rngs::SmallRng;
        use rand::{Rng, SeedableRng};
        let mut rng = SmallRng::seed_from_u64(11);
        let mut case = 0;
        while case < 200 {
            // A random physical tensor (random principal moments and axes; each moment at
            // most the sum of the other two).
            let moments = Vector::new(
                rng.random_range(300.0..3000.0),
                rng.random_range(300.0..3000.0),
                rng.random_range(300.0..3000.0),
            );
            if 2.0 * moments.max() > moments.sum() {
                continue;
            }
            case += 1;
            let axes = Rotation::from_euler_angles(
                rng.random_range(-3.0..3.0),
                rng.random_range(-1.5..1.5),
                rng.random_range(-3.0..3.0),
            );
            let r = axes.to_rotation_matrix().into_inner();
            let inertia = r * Matrix::from_diagonal(&moments) * r.transpose();
            let props = MassProperties::new(1500.0, inertia).unwrap();
            let w0 = Vector::new(
                rng.random_range(-3.0..3.0),
                rng.random_range(-3.0..3.0),
                rng.random_range(-3.0..3.0),
            );
            let mut body = RigidBody::new(props, &state(w0)).unwrap();
            let bound = body.angular_speed_bound();
            let plain = body.angular_momentum().norm() / moments.min();
            assert!(bound <= plain * (1.0 + 1e-12), "case {case}");
            for _ in 0..400 {
                body.advance(0.01);
                let w = body.angular_velocity().norm();
                assert!(w <= bound, "case {case}: |w| {w} above the bound {bound}");
            }
        }
        // A car yawing about its vertical principal axis: the bound is the yaw rate.
        let car = MassProperties::new(
            1500.0,
            Matrix::from_diagonal(&Vector::new(500.0, 2500.0, 2800.0)),
        )
        .unwrap();
        let yaw = RigidBody::new(car, &state(Vector::new(0.0, 0.0, 2.0))).unwrap();
        assert!((yaw.angular_speed_bound() - 2.0).abs() <= 2.0 * 1.1e-6);
    }
}
