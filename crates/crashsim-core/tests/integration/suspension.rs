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
use crashsim_core::math::{Point, Real, Rotation, Vector};
use crashsim_core::motion::{suspension_rate, MAX_SUBSTEP_SUSPENSION};
use crashsim_core::vehicle::{
    AntiRollBar, DriverInputs, SteerInput, Table, Tyre, VehicleSpec, WheelSpec, WheelState,
    GRAVITY, MAX_DAMPING_RATIO, MAX_NATURAL_FREQUENCY,
};
use crashsim_core::ErrorKind;
use crashsim_core::{BodyState, MeshShape, RunOptions, World};
use proptest::prelude::*;

use crate::common::{all_wheels_from_start, props, wheels, CG_HEIGHT, MASS, TRACK};

/// Energy the treads may hold (J): four treads at the friction limit hold about 4 x 26 J at
/// the static loads (the default tyre: 0.8 Fz at 1.7 cm), twice that for load transfer.
const TREAD_ENERGY: Real = 250.0;

/// A 4.6 x 1.8 m box whose bottom is 2 m above the CG's static height over the ground: the
/// body itself never reaches the road, so every joule is in the body, the springs or the
/// treads.
fn shape() -> Arc<MeshShape> {
    Arc::new(MeshShape::cuboid(
        Vector::new(0.0, 0.0, 2.0 + 0.7 - CG_HEIGHT),
        Vector::new(2.3, 0.9, 0.7),
    ))
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
    let steer = |peak: Real| {
        Some(SteerInput::RoadWheel(
            Table::new("steer", &[(0.0, 0.0), (0.3, peak), (1.0, peak)]).unwrap(),
        ))
    };
    match m {
        Manoeuvre::Locked => DriverInputs {
            switches: all_wheels_from_start(WheelState::Locked),
            ..DriverInputs::default()
        },
        Manoeuvre::Swerve => DriverInputs {
            steer: steer(0.12),
            ..DriverInputs::default()
        },
        Manoeuvre::BrakeInTurn => DriverInputs {
            steer: steer(-0.08),
            switches: all_wheels_from_start(WheelState::Braked(0.5)),
            ..DriverInputs::default()
        },
    }
}

/// An anti-roll bar on each axle at `fraction` (0-1) of the stiffest the wheels accept (their
/// spring plus twice the bar's rate at the 20 Hz bound).
fn bars(wheels: &[WheelSpec], fraction: Real) -> Vec<AntiRollBar> {
    let omega = 2.0 * std::f64::consts::PI * MAX_NATURAL_FREQUENCY;
    [(0, 1), (2, 3)]
        .iter()
        .map(|&(left, right)| {
            let rate = [left, right]
                .iter()
                .map(|&k| (omega * omega * wheels[k].sprung_mass() - wheels[k].spring_rate) / 2.0)
                .fold(Real::INFINITY, Real::min);
            AntiRollBar {
                left,
                right,
                roll_stiffness: fraction * rate * TRACK * TRACK,
            }
        })
        .collect()
}

/// The car dropped from `drop` m above its static ride height at `speed` m/s, with anti-roll
/// bars at `bar` of the stiffest accepted.
fn world(frequency: Real, ratio: Real, bar: Real, speed: Real, drop: Real, m: Manoeuvre) -> World {
    let mut w = World::new();
    let state = BodyState {
        position: Point::new(0.0, 0.0, CG_HEIGHT + drop),
        orientation: Rotation::identity(),
        velocity: Vector::new(speed, 0.0, 0.0),
        angular_velocity: Vector::zeros(),
    };
    let i = w.add_body(shape(), props(), &state).unwrap();
    let wheels = wheels(frequency, ratio).unwrap();
    let spec = VehicleSpec {
        anti_roll: bars(&wheels, bar),
        wheels,
        tyre: Tyre::default(),
        steering: Default::default(),
        abs: true,
        inputs: inputs(m),
        coupling: None,
        hitch_load: None,
        load_groups: Vec::new(),
    };
    w.set_vehicle(i, spec).unwrap();
    w.set_ground(Ground::default()).unwrap();
    w
}

/// The energy of the state (see the module's comment), with each bar's `k_bar (c_l - c_r)^2 / 2`
/// (a hanging wheel's travel held at its droop).
fn energy(s: &BodyState, wheels: &[WheelSpec], bars: &[AntiRollBar]) -> Real {
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
    let travel = |wh: &WheelSpec| {
        let centre = s.position + r * wh.center.coords;
        (wh.radius - centre.z).max(-wh.static_load / wh.spring_rate)
    };
    for bar in bars {
        let d = travel(&wheels[bar.left]) - travel(&wheels[bar.right]);
        e += 0.5 * bar.rate(wheels) * d * d;
    }
    e
}

/// Runs 3 s and returns the largest rise of the energy over its start (J), and the start.
fn largest_gain(
    frequency: Real,
    ratio: Real,
    bar: Real,
    speed: Real,
    drop: Real,
    m: Manoeuvre,
) -> (Real, Real) {
    let mut w = world(frequency, ratio, bar, speed, drop, m);
    let specs = wheels(frequency, ratio).unwrap();
    let bars = bars(&specs, bar);
    let out = w.run(3.0, 1e-3).unwrap();
    let e0 = energy(&out.sample(0)[0], &specs, &bars);
    let gain = (0..out.len())
        .map(|k| energy(&out.sample(k)[0], &specs, &bars) - e0)
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
        for (m, bar) in [
            (Manoeuvre::Locked, 0.0),
            (Manoeuvre::Swerve, 0.0),
            (Manoeuvre::Swerve, 1.0),
        ] {
            let (gain, e0) = largest_gain(f, zeta, bar, 50.0 / 3.6, 0.3, m);
            eprintln!(
                "{f} Hz, zeta {zeta}, bars {bar}, {m:?}: largest gain {gain:.3} J of {e0:.0} J"
            );
            assert!(
                gain < TREAD_ENERGY,
                "{f} Hz, zeta {zeta}, bars {bar}, {m:?}: gained {gain} J"
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
        bar in 0.0..=1.0f64,
    ) {
        let m = [Manoeuvre::Locked, Manoeuvre::Swerve, Manoeuvre::BrakeInTurn][which];
        let (gain, e0) = largest_gain(frequency, ratio, bar, speed, drop, m);
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
            Err(e) if e.kind == ErrorKind::Parameter => {
                let m = e.to_string();
                assert!(m.starts_with(what), "{m}");
                assert!(m.contains("must lie in"), "{m}");
            }
            other => panic!("{f} Hz, {zeta}: {other:?}"),
        }
    }
    let mut w = wheels(1.3, 0.3).unwrap().remove(0);
    w.damping *= 100.0; // a ratio of 30
    match w.validate(2) {
        Err(e) if e.kind == ErrorKind::Parameter => {
            assert!(
                e.to_string().starts_with("wheel 2: damping ratio = 30"),
                "{e}"
            )
        }
        other => panic!("{other:?}"),
    }
    let mut w = wheels(1.3, 0.3).unwrap().remove(0);
    w.spring_rate *= 400.0; // 26 Hz
    assert!(w
        .validate(0)
        .is_err_and(|e| e.kind == ErrorKind::Parameter && e.message.contains("natural frequency")));
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
        0.0,
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
            steering: Default::default(),
            abs: true,
            anti_roll: Vec::new(),
            inputs: DriverInputs::default(),
            coupling: None,
            hitch_load: None,
            load_groups: Vec::new(),
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
