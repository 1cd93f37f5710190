//! Tests of [`VehicleSpec::validate`]: without a body (the rules the Python binding's
//! `check_vehicle` applies) and on one (a scene's set_vehicle), one rule in one place.

use std::sync::Arc;

use super::*;
use crate::body::{BodyState, MassProperties};
use crate::error::{error_kind, ErrorKind};
use crate::shape::MeshShape;
use crate::spec::SceneSpec;

/// The car's mass (kg).
const MASS: Real = 1500.0;

/// Four wheels, wheelbase 2.75 m, track 1.55 m, the CG 1.2 m behind the front axle, radius
/// 0.3 m; static loads the axle shares of MASS, springs at 1.3 Hz and 0.3.
fn car() -> VehicleSpec {
    let xy = [[1.2, 0.775], [1.2, -0.775], [-1.55, 0.775], [-1.55, -0.775]];
    let (loads, _) = wheel_loads(&xy, &[], MASS * GRAVITY, None, None).unwrap();
    let wheels = xy
        .iter()
        .zip(loads)
        .enumerate()
        .map(|(k, (p, load))| {
            let c = Point::new(p[0], p[1], -0.25);
            WheelSpec::sprung(c, 0.3, k < 2, load, 1.3, 0.3).unwrap()
        })
        .collect();
    VehicleSpec {
        wheels,
        tyre: Tyre::default(),
        steering: Steering::default(),
        anti_roll: Vec::new(),
        abs: true,
        inputs: DriverInputs::default(),
        coupling: None,
        hitch_load: None,
        load_groups: Vec::new(),
    }
}

/// A scene with one moving box body of MASS kg, half extents `half` (m) about its CG.
fn scene_with_body(half: Vector) -> SceneSpec {
    let mut s = SceneSpec::new();
    let shape = Arc::new(MeshShape::cuboid(Vector::zeros(), half));
    let props = MassProperties::new(MASS, Matrix::identity() * MASS).unwrap();
    let state = BodyState {
        position: Point::origin(),
        orientation: crate::math::Rotation::identity(),
        velocity: Vector::zeros(),
        angular_velocity: Vector::zeros(),
    };
    s.add_body(None, shape, props, state).unwrap();
    s
}

/// Body half extents (m) that hold the car's wheels.
fn holding() -> Vector {
    Vector::new(2.3, 0.9, 0.7)
}

/// The place of the parameter `name`.
fn parameter(name: &str) -> Place {
    Place::Parameter(name.to_string())
}

/// One bad value of each kind the rules without a body catch: a part of the message it
/// gives and the place it is reported at (empty: the whole vehicle).
fn bad_cases() -> Vec<(&'static str, VehicleSpec, Vec<Place>)> {
    let edit = |f: &dyn Fn(&mut VehicleSpec)| {
        let mut v = car();
        f(&mut v);
        v
    };
    let fraction = |x: Real| Some(Braking::Fraction(Table::constant(x)));
    vec![
        (
            "needs at least 3 wheels",
            edit(&|v| v.wheels.truncate(2)),
            vec![],
        ),
        (
            "radius = -0.3 is invalid",
            edit(&|v| v.wheels[2].radius = -0.3),
            vec![Place::Wheel(2), parameter("radius")],
        ),
        (
            "centre y = NaN is invalid",
            edit(&|v| v.wheels[1].center.y = Real::NAN),
            vec![Place::Wheel(1), parameter("centre y")],
        ),
        // 1e9 N/m on 3.6 kN: about 260 Hz, past 20 Hz
        (
            "natural frequency = ",
            edit(&|v| v.wheels[3].spring_rate = 1e9),
            vec![Place::Wheel(3), parameter("natural frequency")],
        ),
        (
            "it is in two load groups",
            edit(&|v| v.load_groups = vec![vec![0, 1], vec![1, 2]]),
            vec![Place::Wheel(1)],
        ),
        (
            "static loads add up to",
            edit(&|v| v.wheels[0].static_load *= 1.5),
            vec![],
        ),
        (
            "relaxation_length = 0 is invalid",
            edit(&|v| v.tyre.relaxation_length = 0.0),
            vec![parameter("relaxation_length")],
        ),
        (
            "ackermann = 3 is invalid",
            edit(&|v| v.steering.ackermann = 3.0),
            vec![parameter("ackermann")],
        ),
        (
            "anti-roll bar 0 joins wheels 0 and 0",
            edit(&|v| {
                v.anti_roll = vec![AntiRollBar {
                    left: 0,
                    right: 0,
                    roll_stiffness: 1e4,
                }]
            }),
            vec![],
        ),
        (
            "braking is given for 3 wheels",
            edit(&|v| v.inputs.brake = vec![fraction(0.5); 3]),
            vec![],
        ),
        (
            "a braking fraction must lie in [0, 1]",
            edit(&|v| v.inputs.brake = vec![None, fraction(1.5), None, None]),
            vec![Place::Wheel(1)],
        ),
        // 1.2 rad = 69 deg, past the 60 deg a road wheel turns
        (
            "road wheels turn at most 60 deg",
            edit(&|v| v.inputs.steer = Some(SteerInput::RoadWheel(Table::constant(1.2)))),
            vec![],
        ),
    ]
}

#[test]
fn a_sound_vehicle_passes_with_and_without_its_body() {
    let car = car();
    assert!(car.validate(None, MASS).is_ok());
    let body = Aabb::new(Point::from(-holding()), Point::from(holding()));
    assert!(car.validate(Some(&body), MASS).is_ok());
    assert!(scene_with_body(holding()).set_vehicle(0, car).is_ok());
}

#[test]
fn each_bad_value_is_a_parameter_error_at_its_place() {
    for (what, spec, place) in bad_cases() {
        let result = spec.validate(None, MASS);
        assert_eq!(error_kind(&result), Some(ErrorKind::Parameter), "{what}");
        let e = result.unwrap_err();
        assert!(e.message.contains(what), "{what}: {e}");
        assert_eq!(e.loc, place, "{what}");
    }
}

#[test]
fn a_scene_refuses_the_same_values_with_the_same_errors() {
    // set_vehicle on a body that holds the wheels applies the same rules: the same error
    for (what, spec, _) in bad_cases() {
        let alone = spec.validate(None, MASS).unwrap_err();
        let on_body = scene_with_body(holding()).set_vehicle(0, spec).unwrap_err();
        assert_eq!(on_body, alone, "{what}");
    }
}

#[test]
fn a_bad_mass_is_refused_as_a_body_s_mass_is() {
    let car = car();
    for mass in [-1.0, 0.0, Real::NAN, Real::INFINITY] {
        let result = car.validate(None, mass);
        assert_eq!(error_kind(&result), Some(ErrorKind::Parameter));
        let (e, by_body) = (
            result.unwrap_err(),
            crate::body::check_mass(mass).unwrap_err(),
        );
        assert_eq!(e, by_body);
        assert_eq!(e.loc, [parameter("mass")]);
        assert!(e.message.starts_with("mass = "), "{e}");
    }
    // loads for 1500 kg do not carry 2000 kg
    let e = car.validate(None, 2000.0).unwrap_err();
    assert!(
        e.message.contains("static loads add up to 14710.0 N"),
        "{e}"
    );
}

#[test]
fn only_a_wheel_outside_its_body_needs_the_body() {
    let mut spec = car();
    spec.wheels[0].center.x = 2.5; // 0.2 m past the body's front at 2.3 m (margin 0.1 m)
    assert!(spec.validate(None, MASS).is_ok());
    let body = Aabb::new(Point::from(-holding()), Point::from(holding()));
    let e = spec.validate(Some(&body), MASS).unwrap_err();
    assert_eq!(
        (e.kind, e.loc.clone()),
        (ErrorKind::Parameter, vec![Place::Wheel(0)])
    );
    assert!(e.message.contains("lies outside the body"), "{e}");
    let by_scene = scene_with_body(holding()).set_vehicle(0, spec).unwrap_err();
    assert_eq!(by_scene, e);
}

#[test]
fn wheel_loads_name_a_wheel_with_a_non_finite_position() {
    let xy = [
        [1.2, 0.775],
        [1.2, Real::NAN],
        [-1.55, 0.775],
        [-1.55, -0.775],
    ];
    let e = wheel_loads(&xy, &[], MASS * GRAVITY, None, None).unwrap_err();
    assert_eq!(
        (e.kind, e.loc),
        (
            ErrorKind::Parameter,
            vec![Place::Wheel(1), parameter("centre y")]
        )
    );
    assert_eq!(
        e.message,
        "centre y = NaN is invalid: it must be a finite number"
    );
}

#[test]
fn a_braking_is_refused_alone_with_the_rules_a_vehicle_applies() {
    let bad = Braking::Fraction(Table::constant(1.5));
    let alone = bad.check().unwrap_err();
    let mut spec = car();
    spec.inputs.brake = vec![None, Some(bad), None, None];
    assert_eq!(
        spec.validate(None, MASS).unwrap_err(),
        alone.at(Place::Wheel(1))
    );
    let too_hard = Braking::Distributed {
        deceleration: Table::constant(25.0),
        share: 0.35,
    };
    assert!(too_hard
        .check()
        .is_err_and(|e| e.message.contains("[0, 20] m/s^2")));
    let share = Braking::Distributed {
        deceleration: Table::constant(5.0),
        share: 1.5,
    };
    assert_eq!(share.check().unwrap_err().loc, [parameter("brake share")]);
    assert!(Braking::Deceleration(Table::constant(5.0)).check().is_ok());
}

#[test]
fn a_wheel_switch_is_refused_alone_with_the_rules_a_vehicle_applies() {
    let braked = |f: Real| WheelSwitch {
        wheel: 2,
        at: Trigger::Time(0.5),
        state: WheelState::Braked(f),
    };
    let alone = braked(1.5).check().unwrap_err();
    assert_eq!(alone.loc, [parameter("braked wheel fraction")]);
    let mut spec = car();
    spec.inputs.switches = vec![braked(0.3), braked(1.5)];
    assert_eq!(spec.validate(None, MASS).unwrap_err(), alone);
    let never = WheelSwitch {
        wheel: 0,
        at: Trigger::Exchange(0),
        state: WheelState::Locked,
    };
    assert!(never
        .check()
        .is_err_and(|e| e.message.contains("count from 1")));
    assert!(braked(0.3).check().is_ok());
}
