//! The compliant contact of soft pairs (soft.rs, docs/human.md): a head-on contact against
//! the spring-dashpot's own equation of motion, momentum kept, a body resting on a soft slab
//! sinking m g / k, one sliding on it stopping in v^2 / (2 mu g), a pair too stiff for the step
//! pressing in sub-steps, and steps too long even for those refused.

use std::sync::Arc;

use crashsim_core::ground::Ground;
use crashsim_core::math::{Isometry, Matrix, Point, Real, Rotation, Vector};
use crashsim_core::vehicle::GRAVITY;
use crashsim_core::{
    BodyState, ContactParams, MassProperties, MeshShape, NormalMode, SoftContact, World,
};

const DT: Real = 1e-3;

fn cube(half: Real, mass: Real) -> (Arc<MeshShape>, MassProperties) {
    let shape = MeshShape::cuboid(Vector::zeros(), Vector::repeat(half));
    let i = mass * (2.0 * half).powi(2) / 6.0;
    (
        Arc::new(shape),
        MassProperties::new(mass, Matrix::from_diagonal_element(i)).unwrap(),
    )
}

fn state(x: Real, z: Real, vx: Real) -> BodyState {
    BodyState {
        position: Point::new(x, 0.0, z),
        orientation: Rotation::identity(),
        velocity: Vector::new(vx, 0.0, 0.0),
        angular_velocity: Vector::zeros(),
    }
}

/// The exit speed over the entry speed and the contact's duration of `m x'' = -max(0, k x +
/// c x')` from x = 0 at x' = v0 (RK4 at 1e-7 s): the law the soft pair follows, solved alone.
fn spring_dashpot(m: Real, k: Real, zeta: Real, v0: Real) -> (Real, Real) {
    let c = 2.0 * zeta * (k * m).sqrt();
    let f = |x: Real, v: Real| -(k * x + c * v).max(0.0) / m;
    let (mut x, mut v, mut t, h) = (0.0, v0, 0.0, 1e-7);
    loop {
        let (k1x, k1v) = (v, f(x, v));
        let (k2x, k2v) = (v + 0.5 * h * k1v, f(x + 0.5 * h * k1x, v + 0.5 * h * k1v));
        let (k3x, k3v) = (v + 0.5 * h * k2v, f(x + 0.5 * h * k2x, v + 0.5 * h * k2v));
        let (k4x, k4v) = (v + h * k3v, f(x + h * k3x, v + h * k3v));
        x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        t += h;
        if x <= 0.0 && t > h {
            return (-v / v0, t);
        }
    }
}

/// The head-on pair's masses (kg): cube 1 at x = 0 moving at +2 m/s, cube 2 at 0.6 m at
/// -1 m/s (0.5 m cubes, 0.1 m apart, closing at 3 m/s).
const HEAD_ON_MASSES: (Real, Real) = (4.0, 6.0);

/// Two cubes in space (no ground: nothing else acts) meeting head-on with a soft contact of
/// stiffness `k` (N/m) and damping ratio `zeta`, run 0.2 s at step `dt` (s).
fn head_on(k: Real, zeta: Real, dt: Real) -> crashsim_core::RunOutput {
    let mut w = World::new();
    let (s1, p1) = cube(0.25, HEAD_ON_MASSES.0);
    let (s2, p2) = cube(0.25, HEAD_ON_MASSES.1);
    w.add_body(s1, p1, &state(0.0, 0.0, 2.0)).unwrap();
    w.add_body(s2, p2, &state(0.6, 0.0, -1.0)).unwrap();
    w.set_soft_contact(
        0,
        1,
        SoftContact {
            stiffness: k,
            damping_ratio: zeta,
        },
    )
    .unwrap();
    w.run(0.2, dt).unwrap()
}

#[test]
fn a_head_on_soft_contact_follows_the_spring_dashpot_and_keeps_momentum() {
    // Two cubes in space (no ground: nothing else acts), 4 kg and 6 kg, closing at 3 m/s:
    // the reduced mass 2.4 kg on k = 2e4 N/m, damping ratio 0.3 (sqrt(k/m) dt = 0.091).
    let (m1, m2, k, zeta) = (HEAD_ON_MASSES.0, HEAD_ON_MASSES.1, 2e4, 0.3);
    let out = head_on(k, zeta, DT);
    assert!(out.impacts.is_empty(), "a soft pair exchanges no impulse");
    let last = out.sample(out.len() - 1);
    let (v1, v2) = (last[0].velocity.x, last[1].velocity.x);
    let momentum = m1 * v1 + m2 * v2;
    assert!(
        (momentum - (m1 * 2.0 - m2 * 1.0)).abs() < 1e-12,
        "{momentum}"
    );
    let (e_model, duration) = spring_dashpot(m1 * m2 / (m1 + m2), k, zeta, 3.0);
    let e = (v2 - v1) / 3.0;
    // The kick after each step is first order in the step: 0.4600 against 0.4510 (2.0 %) at
    // 1 ms, 0.4531 (0.47 %) at 0.25 ms.
    assert!(
        (e / e_model - 1.0).abs() < 0.03,
        "restitution {e:.4} against the model's {e_model:.4}"
    );
    let times: Vec<Real> = out.contacts.iter().map(|c| c.time).collect();
    assert_eq!(times.len(), 2, "{:?}", out.contacts);
    let lasted = times[1] - times[0];
    assert!(
        (lasted - duration).abs() < 2.0 * DT,
        "contact {lasted:.4} s against the model's {duration:.4} s"
    );
    assert!(last[0].angular_velocity.norm() < 1e-12);
}

/// A 5 kg cube on a fixed slab 1 m above the road, their pair soft with the volume normal.
fn on_a_slab(vx: Real, friction: Real) -> World {
    let mut w = World::new();
    w.set_ground(Ground::plane(0.0).unwrap()).unwrap();
    let (s, p) = cube(0.1, 5.0);
    w.add_body(s, p, &state(0.0, 1.1 + 1e-4, vx)).unwrap();
    let slab = Arc::new(MeshShape::cuboid(
        Vector::zeros(),
        Vector::new(3.0, 1.0, 0.05),
    ));
    w.add_obstacle(slab, &Isometry::translation(0.0, 0.0, 0.95))
        .unwrap();
    w.set_contact(
        0,
        1,
        ContactParams {
            normal: NormalMode::Volume,
            friction,
            ..ContactParams::default()
        },
    )
    .unwrap();
    w.set_soft_contact(
        0,
        1,
        SoftContact {
            stiffness: 1e4,
            damping_ratio: 0.7,
        },
    )
    .unwrap();
    w
}

#[test]
fn a_body_rests_on_a_soft_slab_sunk_by_its_weight() {
    let mut w = on_a_slab(0.0, 0.5);
    let out = w.run(1.0, DT).unwrap();
    let z = out.sample(out.len() - 1)[0].position.z;
    let sink = 1.1 - z;
    let expected = 5.0 * GRAVITY / 1e4;
    eprintln!("sank {sink:.6} m against {expected:.6} m");
    assert!(
        (sink / expected - 1.0).abs() < 0.01,
        "sank {sink:.5} m against m g / k = {expected:.5} m"
    );
}

#[test]
fn a_body_sliding_on_a_soft_slab_stops_in_v2_over_2_mu_g() {
    let mut w = on_a_slab(2.0, 0.5);
    let out = w.run(1.5, DT).unwrap();
    let x = out.sample(out.len() - 1)[0].position.x;
    let expected = 2.0 * 2.0 / (2.0 * 0.5 * GRAVITY);
    assert!(
        (x / expected - 1.0).abs() < 0.02,
        "slid {x:.4} m against v^2/(2 mu g) = {expected:.4} m"
    );
    eprintln!("slid {x:.4} m against {expected:.4} m");
    // Stopped: it stays within 1 mm over the last half second (it rocks on the slab, +-0.1
    // rad/s decaying slowly: the damper acts on the depth, not on the tilt).
    let xs: Vec<Real> = (1000..out.len())
        .map(|k| out.sample(k)[0].position.x)
        .collect();
    let spread = xs.iter().cloned().fold(Real::MIN, Real::max)
        - xs.iter().cloned().fold(Real::MAX, Real::min);
    assert!(spread < 1e-3, "moved {spread} m after stopping");
}

#[test]
fn a_soft_pair_too_stiff_for_the_step_presses_in_sub_steps() {
    // 2e7 N/m on the 5 kg cube at 1 ms: sqrt(k/m) dt = 2.0 rad (unstable as one step), so
    // 10 sub-steps while it presses. It sinks m g / k as the same run at a tenth of the step
    // does, and only the grid's samples (and the first overlap's) are recorded.
    let stiff = |w: &mut World| {
        w.set_soft_contact(
            0,
            1,
            SoftContact {
                stiffness: 2e7,
                damping_ratio: 0.7,
            },
        )
        .unwrap()
    };
    let mut w = on_a_slab(0.0, 0.5);
    stiff(&mut w);
    let out = w.run(1.0, DT).unwrap();
    let z = out.sample(out.len() - 1)[0].position.z;
    let sink = 1.1 - z;
    let expected = 5.0 * GRAVITY / 2e7;
    assert!(
        (sink / expected - 1.0).abs() < 0.01,
        "sank {sink:.3e} m against m g / k = {expected:.3e} m"
    );
    let mut short = on_a_slab(0.0, 0.5);
    stiff(&mut short);
    let fine = short.run(1.0, DT / 10.0).unwrap();
    let z_fine = fine.sample(fine.len() - 1)[0].position.z;
    assert!((z - z_fine).abs() < 1e-9, "{z} against {z_fine} at DT / 10");
    let soft = on_a_slab(0.0, 0.5).run(1.0, DT).unwrap();
    assert_eq!(out.len(), soft.len(), "the sub-steps are not recorded");
    assert_eq!(out.contacts.len(), soft.contacts.len());
}

#[test]
fn a_stiff_head_on_contact_in_sub_steps_is_the_run_at_the_sub_step() {
    // The head-on pair above at 100 times the stiffness: sqrt(k/m) dt = 0.71 rad on the
    // lighter cube (4 kg) at 1 ms, so 4 sub-steps while it presses. Its restitution and
    // contact time are those of the run at a quarter of the step, and the spring-dashpot's
    // within the first-order step's error (0.23 rad per sub-step on the reduced mass, 2.4
    // kg: 6.3 % here, 2.0 % at 0.09 rad above).
    let (m1, m2, k, zeta) = (HEAD_ON_MASSES.0, HEAD_ON_MASSES.1, 2e6, 0.3);
    let run = |dt: Real| {
        let out = head_on(k, zeta, dt);
        let last = out.sample(out.len() - 1);
        let (v1, v2) = (last[0].velocity.x, last[1].velocity.x);
        let momentum = m1 * v1 + m2 * v2;
        assert!((momentum - (m1 * 2.0 - m2 * 1.0)).abs() < 1e-12);
        assert_eq!(out.contacts.len(), 2, "{:?}", out.contacts);
        let lasted = out.contacts[1].time - out.contacts[0].time;
        ((v2 - v1) / 3.0, lasted)
    };
    let (e, lasted) = run(DT);
    let (e_fine, lasted_fine) = run(DT / 4.0);
    let (e_model, duration) = spring_dashpot(m1 * m2 / (m1 + m2), k, zeta, 3.0);
    assert!(
        (e / e_fine - 1.0).abs() < 0.005,
        "restitution {e:.4} in sub-steps against {e_fine:.4} at DT / 4"
    );
    assert!(
        (lasted - lasted_fine).abs() < 1e-6,
        "{lasted} against {lasted_fine}"
    );
    assert!(
        (e / e_model - 1.0).abs() < 0.07,
        "restitution {e:.4} against the model's {e_model:.4}"
    );
    assert!(
        (lasted - duration).abs() < 2.0 * DT / 4.0,
        "contact {lasted:.5} s against the model's {duration:.5} s"
    );
}

#[test]
fn a_soft_contact_too_stiff_even_for_sub_steps_is_refused() {
    // 1e8 N/m on 5 kg at 10 ms: 44.7 rad per step, past 50 sub-steps of 0.2 rad.
    let stiffest = |w: &mut World| {
        w.set_soft_contact(
            0,
            1,
            SoftContact {
                stiffness: 1e8,
                damping_ratio: 0.7,
            },
        )
        .unwrap()
    };
    let mut w = on_a_slab(0.0, 0.5);
    stiffest(&mut w);
    let err = w.run(0.1, 0.01).unwrap_err().to_string();
    assert!(err.contains("too stiff for the step"), "{err}");
    assert!(err.contains("at most 5.000e6 N/m"), "{err}");
    assert!(err.contains("a step of at most 2.24e-3 s"), "{err}");
    // A run at a step that fits, then resumed with a longer one: refused again.
    let mut w = on_a_slab(0.0, 0.5);
    stiffest(&mut w);
    w.run(0.01, 1e-3).unwrap();
    assert!(w.run(0.01, 0.01).is_err());
}
