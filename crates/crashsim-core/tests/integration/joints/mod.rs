//! Joints (issue 21, docs/joints.md): pendulums against their closed forms and their energy,
//! a chain of 20 links, the joints' drift, limits as inelastic stops, jointed bodies that
//! overlap without a contact, and refusals by name. Bodies hang 50 m above a plane they never
//! reach, so gravity is the only force besides the joints'.

use std::f64::consts::PI;
use std::sync::Arc;

use crashsim_core::ground::Ground;
use crashsim_core::joint::{AngleLimit, JointKind, JointSpec};
use crashsim_core::math::{Matrix, Point, Real, Rotation, Vector};
use crashsim_core::vehicle::GRAVITY;
use crashsim_core::{BodyState, MassProperties, MeshShape, RunOutput, World};

mod limits;
mod passive;

const HEIGHT: Real = 50.0;
const DT: Real = 1e-3;

fn rod(length: Real, thickness: Real, mass: Real) -> (Arc<MeshShape>, MassProperties) {
    let shape = MeshShape::cuboid(
        Vector::zeros(),
        Vector::new(length, thickness, thickness) * 0.5,
    );
    let (l, t) = (length, thickness);
    let i = Matrix::from_diagonal(&Vector::new(
        mass / 12.0 * (2.0 * t * t),
        mass / 12.0 * (l * l + t * t),
        mass / 12.0 * (l * l + t * t),
    ));
    (Arc::new(shape), MassProperties::new(mass, i).unwrap())
}

fn at(x: Real, z: Real, pitch: Real) -> BodyState {
    BodyState {
        position: Point::new(x, 0.0, z),
        orientation: Rotation::from_axis_angle(&Vector::y_axis(), pitch),
        velocity: Vector::zeros(),
        angular_velocity: Vector::zeros(),
    }
}

/// The joint frame whose z axis is the world's (and the bodies' at the start) y axis.
fn hinge_axes() -> Rotation {
    Rotation::from_axis_angle(&Vector::x_axis(), -PI / 2.0)
}

/// A chain of `n` rods of `length` m (5 kg, 5 cm thick) along +x from the pivot at
/// (0, 0, HEIGHT), tilted `pitch` rad about y, each joined to the one before by `kind` at
/// their ends (the first to the world).
fn chain(n: usize, length: Real, kind: JointKind, pitch: Real) -> World {
    let mut w = World::new();
    w.set_ground(Ground::plane(0.0).unwrap()).unwrap();
    let dir = Vector::new(pitch.cos(), 0.0, -pitch.sin());
    for k in 0..n {
        let (shape, props) = rod(length, 0.05, 5.0);
        let c = Point::new(0.0, 0.0, HEIGHT) + dir * (length * (k as Real + 0.5));
        w.add_body(shape, props, &at(c.x, c.z, pitch)).unwrap();
    }
    let half = Point::new(-length / 2.0, 0.0, 0.0);
    let axes = hinge_axes();
    // Body-frame joint axes: the world's at the start, seen from the tilted rod.
    let tilt = Rotation::from_axis_angle(&Vector::y_axis(), pitch);
    let local = tilt.inverse() * axes;
    w.add_joint(JointSpec::new(
        kind,
        0,
        None,
        (half, local),
        (Point::new(0.0, 0.0, HEIGHT), axes),
    ))
    .unwrap();
    for k in 1..n {
        let end = Point::new(length / 2.0, 0.0, 0.0);
        w.add_joint(JointSpec::new(
            kind,
            k - 1,
            Some(k),
            (end, local),
            (half, local),
        ))
        .unwrap();
    }
    w
}

/// Kinetic plus potential energy (J) of every body at sample `k`.
fn energy(world: &World, out: &RunOutput, props: &[MassProperties], k: usize) -> Real {
    let _ = world;
    out.sample(k)
        .iter()
        .zip(props)
        .map(|(s, p)| {
            let r = s.orientation.to_rotation_matrix().into_inner();
            let inertia = r * p.inertia() * r.transpose();
            let w = s.angular_velocity;
            0.5 * p.mass() * s.velocity.norm_squared()
                + 0.5 * w.dot(&(inertia * w))
                + p.mass() * GRAVITY * s.position.z
        })
        .sum()
}

/// The sample at `time` (an exchange's instant) and the bodies' momentum change (N s) from
/// the sample before it, less gravity's impulse between the two: every body of `m` kg.
fn momentum_jump(out: &RunOutput, time: Real, m: Real) -> (usize, Vector) {
    let k = out.times.iter().position(|&t| t == time).unwrap();
    let momentum = |k: usize| -> Vector { out.sample(k).iter().map(|s| s.velocity * m).sum() };
    let weight = out.sample(k).len() as Real * m * GRAVITY;
    let gravity = Vector::new(0.0, 0.0, -weight * (out.times[k] - out.times[k - 1]));
    (k, momentum(k) - momentum(k - 1) - gravity)
}

/// Largest distance (m) between joined rods' ends (and the first rod's from the pivot) over
/// the run, and the largest angle (rad) between hinge axes.
fn drift(out: &RunOutput, n: usize, length: Real, hinges: bool) -> (Real, Real) {
    let (mut gap, mut turn): (Real, Real) = (0.0, 0.0);
    for k in 0..out.len() {
        let s = out.sample(k);
        let end = |i: usize, sign: Real| {
            s[i].position + s[i].orientation * Vector::new(sign * length / 2.0, 0.0, 0.0)
        };
        gap = gap.max((end(0, -1.0) - Point::new(0.0, 0.0, HEIGHT)).norm());
        for i in 1..n {
            gap = gap.max((end(i, -1.0) - end(i - 1, 1.0)).norm());
        }
        if hinges {
            let y = |i: usize| s[i].orientation * Vector::y();
            turn = turn.max(y(0).angle(&Vector::y()));
            for i in 1..n {
                turn = turn.max(y(i).angle(&y(i - 1)));
            }
        }
    }
    (gap, turn)
}

/// A 1 m, 5 kg rod horizontal along +x, 50 m up, on a joint of `kind` at its end to the
/// world (the joint frame's z along world y: a hinge's axis), the joint as `shape` makes it.
fn horizontal_rod(kind: JointKind, shape: impl FnOnce(&mut JointSpec)) -> World {
    let mut w = World::new();
    w.set_ground(Ground::plane(0.0).unwrap()).unwrap();
    let (mesh, props) = rod(1.0, 0.05, 5.0);
    w.add_body(mesh, props, &at(0.5, HEIGHT, 0.0)).unwrap();
    let axes = hinge_axes();
    let mut joint = JointSpec::new(
        kind,
        0,
        None,
        (Point::new(-0.5, 0.0, 0.0), axes),
        (Point::new(0.0, 0.0, HEIGHT), axes),
    );
    shape(&mut joint);
    w.add_joint(joint).unwrap();
    w
}

fn props_of(n: usize, length: Real) -> Vec<MassProperties> {
    (0..n).map(|_| rod(length, 0.05, 5.0).1).collect()
}

#[test]
fn a_pendulum_swings_with_the_period_of_its_closed_form() {
    // A 1 m rod on a hinge at its end, 5 deg from the vertical: T = 2 pi sqrt(I_O / (m g d))
    // (1 + theta0^2 / 16) to the amplitude's second order.
    let (l, theta0) = (1.0, 5.0_f64.to_radians());
    let mut w = chain(1, l, JointKind::Revolute, PI / 2.0 - theta0);
    let out = w.run(6.0, DT).unwrap();
    let (_, props) = rod(l, 0.05, 5.0);
    let i_o = props.inertia()[(1, 1)] + 5.0 * (l / 2.0).powi(2);
    let expected =
        2.0 * PI * (i_o / (5.0 * GRAVITY * l / 2.0)).sqrt() * (1.0 + theta0 * theta0 / 16.0);
    // The rod's angle from the vertical through its upward crossings of zero.
    let angle: Vec<Real> = (0..out.len())
        .map(|k| {
            let x = out.sample(k)[0].position.x;
            x.atan2(HEIGHT - out.sample(k)[0].position.z)
        })
        .collect();
    let mut crossings = Vec::new();
    for k in 1..out.len() {
        if angle[k - 1] < 0.0 && angle[k] >= 0.0 {
            let f = -angle[k - 1] / (angle[k] - angle[k - 1]);
            crossings.push(out.times[k - 1] + f * (out.times[k] - out.times[k - 1]));
        }
    }
    assert!(crossings.len() >= 3, "{crossings:?}");
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as Real;
    assert!(
        (period / expected - 1.0).abs() < 1e-3,
        "period {period:.5} s, closed form {expected:.5} s"
    );
}

#[test]
fn a_passive_double_pendulum_keeps_its_energy_and_its_joints() {
    // Released horizontal: chaotic, fast (about 7 rad/s), 10 s at the default step.
    let (n, l) = (2, 1.0);
    let mut w = chain(n, l, JointKind::Revolute, 0.0);
    let out = w.run(10.0, DT).unwrap();
    let props = props_of(n, l);
    let e0 = energy(&w, &out, &props, 0);
    // The energy scale: what the fall from horizontal gives, m g (l/2 + 3 l/2).
    let scale = 5.0 * GRAVITY * 2.0 * l;
    let worst = (0..out.len())
        .map(|k| (energy(&w, &out, &props, k) - e0).abs())
        .fold(0.0, Real::max);
    assert!(
        worst < 1e-3 * scale,
        "energy off by {worst:.3e} J of {scale:.1} J"
    );
    let (gap, turn) = drift(&out, n, l, true);
    assert!(
        gap < 1e-3 && turn < 0.1_f64.to_radians(),
        "{gap:.3e} m, {turn:.3e} rad"
    );
    // And it did swing: the lower rod's end went below the pivot by more than a rod.
    let lowest = (0..out.len())
        .map(|k| out.sample(k)[1].position.z)
        .fold(Real::INFINITY, Real::min);
    assert!(lowest < HEIGHT - 1.0, "{lowest}");
}

#[test]
fn a_chain_of_twenty_links_is_stable_at_the_default_step() {
    let (n, l) = (20, 0.3);
    let mut w = chain(n, l, JointKind::Spherical, 0.3);
    let out = w.run(5.0, DT).unwrap();
    let props = props_of(n, l);
    let e0 = energy(&w, &out, &props, 0);
    let scale: Real = props
        .iter()
        .enumerate()
        .map(|(k, p)| p.mass() * GRAVITY * l * (k as Real + 0.5))
        .sum();
    let worst = (0..out.len())
        .map(|k| (energy(&w, &out, &props, k) - e0).abs())
        .fold(0.0, Real::max);
    assert!(
        worst < 1e-3 * scale,
        "energy off by {worst:.3e} J of {scale:.1} J"
    );
    let (gap, _) = drift(&out, n, l, false);
    assert!(gap < 1e-3, "{gap:.3e} m");
}

#[test]
fn jointed_bodies_overlap_without_a_contact_unless_asked() {
    // Two rods overlapping 10 cm at a hinge: no initial-overlap error, no contact event.
    let build = |collide: bool| {
        let mut w = World::new();
        w.set_ground(Ground::plane(0.0).unwrap()).unwrap();
        let (shape, props) = rod(1.0, 0.2, 5.0);
        w.add_body(shape.clone(), props.clone(), &at(0.5, HEIGHT, 0.0))
            .unwrap();
        w.add_body(shape, props, &at(1.4, HEIGHT, 0.0)).unwrap();
        let mut j = JointSpec::new(
            JointKind::Spherical,
            0,
            Some(1),
            (Point::new(0.45, 0.0, 0.0), Rotation::identity()),
            (Point::new(-0.45, 0.0, 0.0), Rotation::identity()),
        );
        j.collide = collide;
        w.add_joint(j).unwrap();
        w.run(0.2, DT)
    };
    let out = build(false).unwrap();
    assert!(out.contacts.is_empty() && out.impacts.is_empty());
    assert_eq!(
        crashsim_core::error_kind(&build(true)),
        Some(crashsim_core::ErrorKind::InitialOverlap)
    );
}

#[test]
fn bad_joints_are_refused_by_name() {
    let mut w = World::new();
    w.set_ground(Ground::plane(0.0).unwrap()).unwrap();
    let (shape, props) = rod(1.0, 0.2, 5.0);
    w.add_body(shape.clone(), props, &at(0.0, HEIGHT, 0.0))
        .unwrap();
    let pole = w
        .add_obstacle(shape, &crashsim_core::math::Isometry::identity())
        .unwrap();
    let frame = (Point::origin(), Rotation::identity());
    let err = |j: JointSpec, w: &mut World| w.add_joint(j).unwrap_err().to_string();
    let itself = JointSpec::new(JointKind::Spherical, 0, Some(0), frame, frame);
    assert!(err(itself, &mut w).contains("to itself"));
    let obstacle = JointSpec::new(JointKind::Spherical, 0, Some(pole), frame, frame);
    assert!(err(obstacle, &mut w).contains("fixed obstacle"));
    let far = JointSpec::new(
        JointKind::Spherical,
        0,
        None,
        (Point::new(5.0, 0.0, 0.0), Rotation::identity()),
        frame,
    );
    assert!(err(far, &mut w).contains("outside the box"));
    let mut limited = JointSpec::new(JointKind::Spherical, 0, None, frame, frame);
    limited.limits = vec![AngleLimit {
        angle: 0,
        lower: -1.0,
        upper: 1.0,
    }];
    assert!(err(limited, &mut w).contains("never negative"));
    let mut hinge_twist = JointSpec::new(JointKind::Fixed, 0, None, frame, frame);
    hinge_twist.limits = vec![AngleLimit {
        angle: 0,
        lower: -1.0,
        upper: 1.0,
    }];
    assert!(err(hinge_twist, &mut w).contains("no angle to limit"));
    let mut stiff = JointSpec::new(JointKind::Revolute, 0, None, frame, frame);
    stiff.stiffness = -1.0;
    assert!(err(stiff, &mut w).contains("stiffness"));
    // Without a ground a joint has no gravity to work in.
    let mut space = World::new();
    let (shape, props) = rod(1.0, 0.2, 5.0);
    space.add_body(shape, props, &at(0.0, HEIGHT, 0.0)).unwrap();
    space
        .add_joint(JointSpec::new(JointKind::Spherical, 0, None, frame, frame))
        .unwrap();
    assert!(space
        .run(0.1, DT)
        .unwrap_err()
        .to_string()
        .contains("ground"));
}

use crate::common;

/// A parked car (the common module's reference car) with a 750 kg centre-axle trailer on its tow
/// ball: at rest the ball carries the trailer's weight times the CG's lead over the axle per
/// the drawbar's lever (moments about the axle's contact line), the car's wheels the car's
/// weight plus that; within 1 % in the pose the run settles to.
#[test]
fn a_parked_car_and_trailer_share_the_weight_as_statics_says() {
    use crashsim_core::vehicle::{static_loads_coupled, VehicleSpec, WheelSpec};
    let mut w = crashsim_core::SceneSpec::new();
    w.set_ground(Ground::plane(0.0).unwrap());
    let car_shape = Arc::new(MeshShape::cuboid(
        Vector::new(0.0, 0.0, 0.15 + 0.7 - common::CG_HEIGHT),
        Vector::new(2.3, 0.9, 0.7),
    ));
    let still = |x: Real, z: Real| BodyState {
        position: Point::new(x, 0.0, z),
        orientation: Rotation::identity(),
        velocity: Vector::zeros(),
        angular_velocity: Vector::zeros(),
    };
    let car = w
        .add_body(
            None,
            car_shape,
            common::props(),
            still(0.0, common::CG_HEIGHT),
        )
        .unwrap();
    w.set_vehicle(
        car,
        VehicleSpec {
            wheels: common::wheels(1.3, 0.3).unwrap(),
            tyre: Default::default(),
            steering: Default::default(),
            abs: true,
            anti_roll: Vec::new(),
            inputs: Default::default(),
            coupling: None,
            hitch_load: None,
            load_groups: Vec::new(),
        },
    )
    .unwrap();
    // The trailer: 3.0 x 1.8 x 1.2 m box 0.3 m above the road, CG 0.6 m up, its axle 0.3 m
    // behind the CG, the coupler 2.2 m ahead of the CG at the ball's height.
    let (mt, cg_t, hitch_x, axle_x, radius) = (750.0, 0.6, 2.2, -0.3, 0.3);
    let ball = Point::new(-2.6, 0.0, 0.45);
    let trailer_x = ball.x - hitch_x;
    let (l, wd, h) = (3.0, 1.8, 1.2);
    let inertia = Matrix::from_diagonal(&Vector::new(
        mt / 12.0 * (wd * wd + h * h),
        mt / 12.0 * (l * l + h * h),
        mt / 12.0 * (l * l + wd * wd),
    ));
    let trailer = w
        .add_body(
            Some("trailer".into()),
            Arc::new(MeshShape::cuboid(
                Vector::new(0.0, 0.0, 0.3 + h / 2.0 - cg_t),
                Vector::new(l, wd, h) * 0.5,
            )),
            MassProperties::new(mt, inertia).unwrap(),
            still(trailer_x, cg_t),
        )
        .unwrap();
    let xy = [[axle_x, 0.8], [axle_x, -0.8]];
    let (loads, _) = static_loads_coupled(&xy, mt * GRAVITY, [hitch_x, 0.0], None).unwrap();
    let wheels = xy
        .iter()
        .zip(&loads)
        .map(|(p, f)| {
            let c = Point::new(p[0], p[1], radius - cg_t);
            WheelSpec::sprung(c, radius, false, *f, 1.3, 0.3).unwrap()
        })
        .collect();
    let coupler = Point::new(hitch_x, 0.0, ball.z - cg_t);
    w.set_vehicle(
        trailer,
        VehicleSpec {
            wheels,
            tyre: Default::default(),
            steering: Default::default(),
            abs: true,
            anti_roll: Vec::new(),
            inputs: Default::default(),
            coupling: Some(coupler),
            hitch_load: None,
            load_groups: Vec::new(),
        },
    )
    .unwrap();
    let car_ball = Point::new(ball.x, 0.0, ball.z - common::CG_HEIGHT);
    w.add_joint(JointSpec::new(
        JointKind::Spherical,
        car,
        Some(trailer),
        (car_ball, Rotation::identity()),
        (coupler, Rotation::identity()),
    ))
    .unwrap();
    w.run.duration = 5.0;
    let out = w.run().unwrap();
    // The scene as a JSON document runs the same bits.
    let again = crashsim_core::spec::from_json(&crashsim_core::spec::to_json(&w)).unwrap();
    assert_eq!(again.run().unwrap(), out);
    let last = out.len() - 1;
    let s = out.sample(last);
    let joint = out.joints_at(last)[0];
    let wheels = out.wheels_at(last);
    let car_load: Real = wheels[..4].iter().map(|w| w.force.z).sum();
    let trailer_load: Real = wheels[4..].iter().map(|w| w.force.z).sum();
    // Moments about the trailer's contact line, horizontal lever arms in the settled pose.
    let contact_x = 0.5 * (wheels[4].contact.x + wheels[5].contact.x);
    let ball_now = s[trailer].position + s[trailer].orientation * coupler.coords;
    let expected = mt * GRAVITY * (s[trailer].position.x - contact_x) / (ball_now.x - contact_x);
    eprintln!(
        "ball load {:.2} N (statics {expected:.2} N); car wheels {car_load:.1} N, trailer \
         wheels {trailer_load:.1} N; horizontal {:.3} N",
        joint.force.z,
        joint.force.xy().norm()
    );
    assert!((joint.force.z / expected - 1.0).abs() < 0.01);
    let car_weight = common::MASS * GRAVITY;
    assert!(((car_load - car_weight) / joint.force.z - 1.0).abs() < 0.01);
    assert!(((trailer_load + joint.force.z) / (mt * GRAVITY) - 1.0).abs() < 0.01);
    // Both at rest: nothing rolled.
    assert!(s[car].velocity.norm() < 1e-3 && s[trailer].velocity.norm() < 1e-3);
}

/// A box struck on one of two hinged boxes: the exchange sees the pair through the joint.
/// Three 1 m cubes fall together 50 m above the ground (gravity moves them alike); A and B
/// are joined by a ball joint at their shared face's edge, C hits B's side. Newton's
/// restitution at the centroid holds with the joint's reaction (it would not with B's mass
/// alone), the momentum of all three is kept, the joint too.
#[test]
fn an_exchange_with_a_jointed_body_sees_the_mechanism() {
    use crashsim_core::{ContactParams, RestitutionMode};
    let cube = || {
        let props =
            MassProperties::new(1000.0, Matrix::from_diagonal(&Vector::repeat(1000.0 / 6.0)))
                .unwrap();
        (
            Arc::new(MeshShape::cuboid(Vector::zeros(), Vector::repeat(0.5))),
            props,
        )
    };
    let mut w = World::new();
    w.set_ground(Ground::plane(0.0).unwrap()).unwrap();
    let place = |x: Real, y: Real, vy: Real| BodyState {
        position: Point::new(x, y, HEIGHT),
        orientation: Rotation::identity(),
        velocity: Vector::new(0.0, vy, 0.0),
        angular_velocity: Vector::zeros(),
    };
    let (s, p) = cube();
    let a = w
        .add_body(s.clone(), p.clone(), &place(0.0, 0.0, 0.0))
        .unwrap();
    let b = w
        .add_body(s.clone(), p.clone(), &place(1.05, 0.0, 0.0))
        .unwrap();
    let c = w.add_body(s, p, &place(1.3, 1.6, -5.0)).unwrap();
    w.add_joint(JointSpec::new(
        JointKind::Spherical,
        a,
        Some(b),
        (Point::new(0.525, 0.0, 0.0), Rotation::identity()),
        (Point::new(-0.525, 0.0, 0.0), Rotation::identity()),
    ))
    .unwrap();
    let params = ContactParams {
        restitution: 0.3,
        restitution_mode: RestitutionMode::Normal,
        friction: 0.0,
        depth_of_penetration: crashsim_core::DepthOfPenetration::Fixed(0.0),
        ..ContactParams::default()
    };
    w.set_contact(b, c, params).unwrap();
    let out = w.run(0.2, DT).unwrap();
    assert_eq!(out.impacts.len(), 1, "{:?}", out.contacts);
    let imp = &out.impacts[0];
    let n = imp.normal;
    let (before, after) = (
        imp.relative_velocity_before.dot(&n),
        imp.relative_velocity_after.dot(&n),
    );
    assert!(
        (after + 0.3 * before).abs() < 1e-9 * before.abs(),
        "{before} -> {after}"
    );
    // Momentum of all three across the exchange instant (the samples either side, less
    // gravity's impulse between them).
    let (k, change) = momentum_jump(&out, imp.time, 1000.0);
    assert!(change.norm() < 1e-6, "{change:?}");
    // B was pushed, and A came along through the joint.
    let (va, vb) = (out.sample(k)[a].velocity, out.sample(k)[b].velocity);
    assert!(va.y < -0.1 && vb.y < va.y, "A {va:?}, B {vb:?}");
    // The kinetic energy the exchange took counts A too (it is at most what the pair lost).
    assert!(imp.energy_dissipated > 0.0);
    // B's mass as felt at the centroid along n: more through the joint than its own.
    let sb = &out.sample(k - 1)[b];
    let own = crashsim_core::stiffness::effective_mass(
        1000.0,
        &Matrix::from_diagonal(&Vector::repeat(6.0 / 1000.0)),
        &(imp.centroid - sb.position),
        &n,
    );
    assert!(
        imp.effective_mass[0] > 1.05 * own,
        "{:?} vs {own}",
        imp.effective_mass
    );
}

/// Two members of one mechanism striking each other (a jackknife: the trailer's front against
/// the cab): the exchange's collision matrix has each feel the other through the joint, so
/// Newton's restitution at the centroid holds and the momentum of the pair is kept.
#[test]
fn jointed_bodies_that_collide_exchange_through_their_joint() {
    use crashsim_core::{ContactParams, RestitutionMode};
    let (l, w) = (2.0, 0.4);
    let props = || {
        let m = 500.0;
        MassProperties::new(
            m,
            Matrix::from_diagonal(&Vector::new(
                m / 12.0 * (2.0 * w * w),
                m / 12.0 * (l * l + w * w),
                m / 12.0 * (l * l + w * w),
            )),
        )
        .unwrap()
    };
    let bar = || {
        Arc::new(MeshShape::cuboid(
            Vector::zeros(),
            Vector::new(l, w, w) * 0.5,
        ))
    };
    let mut world = World::new();
    world.set_ground(Ground::plane(0.0).unwrap()).unwrap();
    let a = world
        .add_body(bar(), props(), &at(0.0, HEIGHT, 0.0))
        .unwrap();
    // B along +y from the hinge, turning about it at 2 rad/s towards A.
    let omega = 2.0;
    let b_state = BodyState {
        position: Point::new(1.2, 1.2, HEIGHT),
        orientation: Rotation::from_axis_angle(&Vector::z_axis(), PI / 2.0),
        velocity: Vector::new(-1.2 * omega, 0.0, 0.0),
        angular_velocity: Vector::new(0.0, 0.0, omega),
    };
    let b = world.add_body(bar(), props(), &b_state).unwrap();
    let mut joint = JointSpec::new(
        JointKind::Revolute,
        a,
        Some(b),
        (Point::new(1.2, 0.0, 0.0), Rotation::identity()),
        (
            Point::new(-1.2, 0.0, 0.0),
            Rotation::from_axis_angle(&Vector::z_axis(), -PI / 2.0),
        ),
    );
    joint.collide = true;
    world.add_joint(joint).unwrap();
    let params = ContactParams {
        restitution: 0.3,
        restitution_mode: RestitutionMode::Normal,
        friction: 0.0,
        depth_of_penetration: crashsim_core::DepthOfPenetration::Fixed(0.0),
        ..ContactParams::default()
    };
    world.set_contact(a, b, params).unwrap();
    let out = world.run(1.5, DT).unwrap();
    assert!(!out.impacts.is_empty(), "{:?}", out.contacts);
    let imp = &out.impacts[0];
    let n = imp.normal;
    let (before, after) = (
        imp.relative_velocity_before.dot(&n),
        imp.relative_velocity_after.dot(&n),
    );
    assert!(before > 0.5, "{before}");
    assert!(
        (after + 0.3 * before).abs() < 1e-9 * before,
        "{before} -> {after}"
    );
    let (k, change) = momentum_jump(&out, imp.time, 500.0);
    assert!(change.norm() < 1e-6, "{change:?}");
    // The joint held through it.
    let s = out.sample(k);
    let gap = (s[a].position + s[a].orientation * Vector::new(1.2, 0.0, 0.0))
        - (s[b].position + s[b].orientation * Vector::new(-1.2, 0.0, 0.0));
    assert!(gap.norm() < 1e-6, "{gap:?}");
}

/// A no-contact pair (a pedestrian's segments among themselves): two rods overlapping at the
/// start pass through each other with no contact (without it the scene is refused), a third
/// body still strikes them, the JSON document keeps the pair and runs the same bits, and a
/// pair that never collides takes no contact parameters.
#[test]
fn a_no_contact_pair_passes_through_and_round_trips() {
    use crashsim_core::spec::{self, SceneSpec};
    use crashsim_core::ContactParams;
    let build = |ignore: bool| {
        let mut s = SceneSpec::new();
        for (name, x, v) in [("a", 0.0, 0.0), ("b", 0.6, 0.0), ("c", 3.0, -5.0)] {
            let (shape, props) = rod(1.0, 0.2, 5.0);
            let mut state = at(x, HEIGHT, 0.0);
            state.velocity = Vector::new(v, 0.0, 0.0);
            s.add_body(Some(name.into()), shape, props, state).unwrap();
        }
        if ignore {
            s.set_no_contact(1, 0).unwrap();
        }
        s.run.duration = 0.5;
        s
    };
    assert_eq!(
        crashsim_core::error_kind(&build(false).run()),
        Some(crashsim_core::ErrorKind::InitialOverlap)
    );
    let s = build(true);
    assert_eq!(s.no_contact, vec![(0, 1)]);
    let out = s.run().unwrap();
    // c, thrown at the pair, strikes b: the only exchange.
    assert_eq!(out.impacts.len(), 1);
    let hit = &out.impacts[0];
    assert_eq!((hit.body1.min(hit.body2), hit.body1.max(hit.body2)), (1, 2));
    let again = spec::from_json(&spec::to_json(&s)).unwrap();
    assert_eq!(again.no_contact, s.no_contact);
    assert_eq!(again.run().unwrap(), out);
    let mut s = build(true);
    let err = s
        .set_contact(0, 1, ContactParams::default())
        .unwrap_err()
        .to_string();
    assert!(err.contains("never collide"), "{err}");
    let mut s = build(false);
    s.set_contact(0, 1, ContactParams::default()).unwrap();
    let err = s.set_no_contact(0, 1).unwrap_err().to_string();
    assert!(err.contains("contact parameters of their own"), "{err}");
}
