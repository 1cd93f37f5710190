//! The suspension over its whole accepted range (issue 24, item 1): no run gains energy, values
//! past the range are refused by name, and the work per simulated second stays bounded.
//!
//! Energy of a body on its wheels, all world frame, SI:
//! `E = m |v|^2 / 2 + w.(I_world w) / 2 + m g z + sum_k V_k`, with each wheel's spring potential
//! `V_k = (F0 + k c)^2 / (2 k)` while it pushes (c the compression R - h), 0 once it hangs free.
//! The spring-damper only pushes (its force is max(0, F0 + k c + d dc/dt)), so dE/dt <= 0 for the
//! exact motion whatever d; the tyres only take energy, but their treads store a little (a few
//! tens of J at the friction limit), which is the tolerance.

use std::sync::Arc;

use crashsim_core::ground::Ground;
use crashsim_core::math::{Matrix, Point, Real, Rotation, Vector};
use crashsim_core::motion::{suspension_rate, MAX_SUBSTEP_SUSPENSION};
use crashsim_core::vehicle::{
    static_loads, DriverInputs, Table, Trigger, Tyre, VehicleSpec, WheelSpec, WheelState,
    WheelSwitch, GRAVITY, MAX_DAMPING_RATIO, MAX_NATURAL_FREQUENCY,
};
use crashsim_core::{BodyState, Error, MassProperties, MeshShape, RunOptions, World};
use proptest::prelude::*;

const MASS: Real = 1500.0;
/// CG 1.1 m behind the front axle and 1.6 m ahead of the rear one, track 1.55 m, CG 0.55 m
/// above the ground, tyre radius 0.3 m (as tests/dynamics.rs).
const A: Real = 1.1;
const B: Real = 1.6;
const TRACK: Real = 1.55;
const CG_HEIGHT: Real = 0.55;
const RADIUS: Real = 0.3;
/// Energy the treads may hold (J): four treads at the friction limit hold about 4 x 26 J at
/// the static loads (the default tyre: 0.8 Fz at 1.7 cm), twice that for load transfer.
const TREAD_ENERGY: Real = 250.0;

fn props() -> MassProperties {
    let wb = A + B;
    MassProperties::new(
        MASS,
        Matrix::from_diagonal(&Vector::new(
            MASS / 12.0 * (1.8f64.powi(2) + 1.4f64.powi(2)),
            MASS / 12.0 * (4.6f64.powi(2) + 1.4f64.powi(2)),
            MASS * (0.5 * wb).powi(2),
        )),
    )
    .unwrap()
}

/// A 4.6 x 1.8 m box whose bottom is 2 m above the CG's static height over the ground: the
/// body itself never reaches the road, so every joule is in the body, the springs or the
/// treads.
fn shape() -> Arc<MeshShape> {
    Arc::new(MeshShape::cuboid(
        Vector::new(0.0, 0.0, 2.0 + 0.7 - CG_HEIGHT),
        Vector::new(2.3, 0.9, 0.7),
    ))
}

fn wheels(frequency: Real, ratio: Real) -> crashsim_core::Result<Vec<WheelSpec>> {
    let xy = [
        [A, TRACK / 2.0],
        [A, -TRACK / 2.0],
        [-B, TRACK / 2.0],
        [-B, -TRACK / 2.0],
    ];
    let loads = static_loads(&xy, MASS * GRAVITY)?;
    xy.iter()
        .zip(&loads)
        .enumerate()
        .map(|(k, (p, f))| {
            let center = Point::new(p[0], p[1], RADIUS - CG_HEIGHT);
            WheelSpec::sprung(center, RADIUS, k < 2, *f, frequency, ratio)
        })
        .collect()
}

/// What the car does on the road: locked from the start, a swerve on free wheels, or braked
/// at half the friction in a turn.
#[derive(Clone, Copy, Debug)]
enum Manoeuvre {
    Locked,
    Swerve,
    BrakeInTurn,
}

fn inputs(m: Manoeuvre) -> DriverInputs {
    let switch = |state: WheelState| {
        (0..4)
            .map(|wheel| WheelSwitch {
                wheel,
                at: Trigger::Time(0.0),
                state: state.clone(),
            })
            .collect()
    };
    let steer =
        |peak: Real| Some(Table::new("steer", &[(0.0, 0.0), (0.3, peak), (1.0, peak)]).unwrap());
    match m {
        Manoeuvre::Locked => DriverInputs {
            switches: switch(WheelState::Locked),
            ..DriverInputs::default()
        },
        Manoeuvre::Swerve => DriverInputs {
            steer: steer(0.12),
            ..DriverInputs::default()
        },
        Manoeuvre::BrakeInTurn => DriverInputs {
            steer: steer(-0.08),
            switches: switch(WheelState::Braked(0.5)),
            ..DriverInputs::default()
        },
    }
}

/// The car dropped from `drop` m above its static ride height at `speed` m/s.
fn world(frequency: Real, ratio: Real, speed: Real, drop: Real, m: Manoeuvre) -> World {
    let mut w = World::new();
    let state = BodyState {
        position: Point::new(0.0, 0.0, CG_HEIGHT + drop),
        orientation: Rotation::identity(),
        velocity: Vector::new(speed, 0.0, 0.0),
        angular_velocity: Vector::zeros(),
    };
    let i = w.add_body(shape(), props(), &state).unwrap();
    let spec = VehicleSpec {
        wheels: wheels(frequency, ratio).unwrap(),
        tyre: Tyre::default(),
        inputs: inputs(m),
    };
    w.set_vehicle(i, spec).unwrap();
    w.set_ground(Ground::default()).unwrap();
    w
}

/// The energy of the state (see the module's comment).
fn energy(s: &BodyState, wheels: &[WheelSpec]) -> Real {
    let p = props();
    let r = s.orientation.to_rotation_matrix();
    let inertia = r.matrix() * p.inertia() * r.matrix().transpose();
    let mut e = 0.5 * MASS * s.velocity.norm_squared()
        + 0.5 * s.angular_velocity.dot(&(inertia * s.angular_velocity))
        + MASS * GRAVITY * s.position.z;
    for wh in wheels {
        let centre = s.position + r * wh.center.coords;
        let push = wh.static_load + wh.spring_rate * (wh.radius - centre.z);
        if push > 0.0 {
            e += push * push / (2.0 * wh.spring_rate);
        }
    }
    e
}

/// Runs 3 s and returns the largest rise of the energy over its start (J), and the start.
fn largest_gain(
    frequency: Real,
    ratio: Real,
    speed: Real,
    drop: Real,
    m: Manoeuvre,
) -> (Real, Real) {
    let mut w = world(frequency, ratio, speed, drop, m);
    let specs = wheels(frequency, ratio).unwrap();
    let out = w.run(3.0, 1e-3).unwrap();
    let e0 = energy(&out.sample(0)[0], &specs);
    let gain = (0..out.len())
        .map(|k| energy(&out.sample(k)[0], &specs) - e0)
        .fold(Real::NEG_INFINITY, Real::max);
    (gain, e0)
}

/// The cases at the ends of the range: the stiffest, the most damped, both, and no
/// damping at all, each locked at 50 km/h and dropped 0.3 m.
#[test]
fn the_ends_of_the_accepted_range_gain_no_energy() {
    for (f, zeta) in [
        (MAX_NATURAL_FREQUENCY, 0.3),
        (1.3, MAX_DAMPING_RATIO),
        (MAX_NATURAL_FREQUENCY, MAX_DAMPING_RATIO),
        (MAX_NATURAL_FREQUENCY, 0.0),
        (0.8, 0.0),
    ] {
        for m in [Manoeuvre::Locked, Manoeuvre::Swerve] {
            let (gain, e0) = largest_gain(f, zeta, 50.0 / 3.6, 0.3, m);
            eprintln!("{f} Hz, zeta {zeta}, {m:?}: largest gain {gain:.3} J of {e0:.0} J");
            assert!(
                gain < TREAD_ENERGY,
                "{f} Hz, zeta {zeta}, {m:?}: gained {gain} J"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 24,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Anywhere in the accepted range, at any speed and drop, locked, swerving or braking in
    /// a turn: the energy never rises by more than the treads can hold.
    #[test]
    fn no_accepted_suspension_gains_energy(
        frequency in 0.8..=MAX_NATURAL_FREQUENCY,
        ratio in 0.0..=MAX_DAMPING_RATIO,
        speed in 0.0..30.0f64,
        drop in 0.0..0.3f64,
        which in 0..3usize,
    ) {
        let m = [Manoeuvre::Locked, Manoeuvre::Swerve, Manoeuvre::BrakeInTurn][which];
        let (gain, e0) = largest_gain(frequency, ratio, speed, drop, m);
        prop_assert!(
            gain < TREAD_ENERGY,
            "{frequency} Hz, zeta {ratio}, {speed} m/s, drop {drop} m, {m:?}: gained {gain} J of {e0} J"
        );
    }
}

/// Past the range, the values are refused by name with the range (the 1e4 and 1e6
/// damping ratios and 1000 Hz threw a locked car into the air or ran for hours); given as rates,
/// the same bounds apply to the frequency and ratio they make.
#[test]
fn suspension_values_past_the_range_are_refused_by_name() {
    for (f, zeta, what) in [
        (1.3, 1e4, "damping_ratio"),
        (1.3, 1e6, "damping_ratio"),
        (1000.0, 0.3, "natural_frequency"),
        (100.0, 0.3, "natural_frequency"),
        (1.3, -0.1, "damping_ratio"),
        (0.0, 0.3, "natural_frequency"),
    ] {
        match wheels(f, zeta) {
            Err(Error::Parameter(m)) => {
                assert!(m.starts_with(what), "{m}");
                assert!(m.contains("must lie in"), "{m}");
            }
            other => panic!("{f} Hz, {zeta}: {other:?}"),
        }
    }
    let mut w = wheels(1.3, 0.3).unwrap().remove(0);
    w.damping *= 100.0; // a ratio of 30
    match w.validate(2) {
        Err(Error::Parameter(m)) => assert!(m.starts_with("wheel 2 damping ratio = 30"), "{m}"),
        other => panic!("{other:?}"),
    }
    let mut w = wheels(1.3, 0.3).unwrap().remove(0);
    w.spring_rate *= 400.0; // 26 Hz
    assert!(matches!(w.validate(0), Err(Error::Parameter(m)) if m.contains("natural frequency")));
    // Exactly at the bounds passes the round trip through the rates.
    assert!(wheels(MAX_NATURAL_FREQUENCY, MAX_DAMPING_RATIO).is_ok());
}

/// At the stiffest accepted values the run to rest takes a bounded number of sub-steps: the
/// same locked stop as the default car (within 1 % of v^2 / (2 mu g)), and the suspension asks
/// for at most 6 sub-steps per ms (2 / |lambda|, its bound, at 20 Hz and 5), the default car
/// for none past the 1 ms the integration takes anyway.
#[test]
fn the_stiffest_suspension_stops_like_the_default_in_bounded_work() {
    let v = 50.0 / 3.6;
    let mut w = world(
        MAX_NATURAL_FREQUENCY,
        MAX_DAMPING_RATIO,
        v,
        0.0,
        Manoeuvre::Locked,
    );
    let options = RunOptions {
        until_rest: true,
        ..RunOptions::default()
    };
    let out = w
        .run_with_options(8.0, 1e-3, &options, &mut |_| true)
        .unwrap();
    let rest = out.rest[0].expect("at rest");
    let k = out.times.iter().position(|&t| t >= rest).unwrap();
    let travel = out.sample(k)[0].position.x;
    let expected = v * v / (2.0 * 0.8 * GRAVITY);
    assert!(
        (travel - expected).abs() < 0.01 * expected,
        "{travel} vs {expected}"
    );
    let per_ms = |f, zeta| {
        let spec = VehicleSpec {
            wheels: wheels(f, zeta).unwrap(),
            tyre: Tyre::default(),
            inputs: DriverInputs::default(),
        };
        1e-3 * suspension_rate(&spec, &props()) / MAX_SUBSTEP_SUSPENSION
    };
    let (stiffest, default) = (
        per_ms(MAX_NATURAL_FREQUENCY, MAX_DAMPING_RATIO),
        per_ms(1.3, 0.3),
    );
    eprintln!("sub-steps per ms: {stiffest:.2} at the bounds, {default:.3} by default");
    assert!(stiffest <= 6.0 && default < 0.1, "{stiffest} {default}");
}
