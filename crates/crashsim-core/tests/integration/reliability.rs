//! Regression tests of issue 10 (reliability): runs that never ended, unbounded memory.
//! Each test is named after the bug it pins.

use std::sync::Arc;

use crashsim_core::math::{Matrix, Point, Real, Rotation, Vector};
use crashsim_core::{error_kind, ErrorKind, Place};
use crashsim_core::{
    BodyState, ContactParams, DepthOfPenetration, MassProperties, MeshShape, RunOptions, World,
};

fn box_body(
    w: &mut World,
    size: [Real; 3],
    mass: Real,
    at: [Real; 3],
    yaw: Real,
    v: Vector,
    yaw_rate: Real,
) -> usize {
    let [l, b, h] = size;
    let shape = Arc::new(MeshShape::cuboid(
        Vector::zeros(),
        Vector::new(l, b, h) * 0.5,
    ));
    let i = Matrix::from_diagonal(&Vector::new(
        mass / 12.0 * (b * b + h * h),
        mass / 12.0 * (l * l + h * h),
        mass / 12.0 * (l * l + b * b),
    ));
    let state = BodyState {
        position: Point::new(at[0], at[1], at[2]),
        orientation: Rotation::from_axis_angle(&Vector::z_axis(), yaw),
        velocity: v,
        angular_velocity: Vector::new(0.0, 0.0, yaw_rate),
    };
    w.add_body(shape, MassProperties::new(mass, i).unwrap(), &state)
        .unwrap()
}

/// A plate `thick` m thick, 0.5 m long and 1 m high, at 100 m/s edge-on into a wall 1 mm
/// thick (10,000 kg) with dt_p = 0.
fn plate_into_wall(thick: Real) -> World {
    let mut w = World::new();
    let plate = box_body(
        &mut w,
        [0.5, thick, 1.0],
        100.0,
        [-5.0, 0.0, 1.0],
        std::f64::consts::FRAC_PI_2,
        Vector::new(100.0, 0.0, 0.0),
        0.0,
    );
    let wall = box_body(
        &mut w,
        [0.001, 10.0, 2.0],
        10000.0,
        [0.0, 0.0, 1.0],
        0.0,
        Vector::zeros(),
        0.0,
    );
    let params = ContactParams {
        depth_of_penetration: DepthOfPenetration::Fixed(0.0),
        ..ContactParams::default()
    };
    w.set_contact(plate, wall, params).unwrap();
    w
}

/// The 1 mm plate edge-on into a 1 mm wall at 100 m/s with dt_p = 0 ran forever at 100 % CPU,
/// growing memory by about 18 MB/s: the first-contact search landed exactly on the touching
/// instant (faces meeting), counted the touch as a first overlap, the exchange found no
/// overlap region and the pair started again at the same instant, forever. A first overlap is
/// now an instant with a non-empty overlap region, at the very poses the run then has.
#[test]
fn plate_edge_on_into_a_wall_with_zero_depth_of_penetration_ends_with_one_exchange() {
    for (thick, dt) in [(0.001, 1e-3), (0.002, 1e-3), (0.001, 5e-4), (0.001, 1e-2)] {
        let mut w = plate_into_wall(thick);
        let out = w.run(0.1, dt).unwrap();
        assert_eq!(
            out.impacts.len(),
            1,
            "plate {thick} m, dt {dt} s: {:?}",
            out.contacts
        );
        let imp = &out.impacts[0];
        // The plate touches the wall after 4.95 m at 100 m/s (its face at x = -5 + thick/2).
        let t_touch = (5.0 - thick / 2.0 - 0.0005) / 100.0;
        assert!(
            (imp.first_contact_time - t_touch).abs() < 2e-9,
            "{}",
            imp.first_contact_time
        );
        assert_eq!(imp.time, imp.first_contact_time);
        // A central collinear impact: delta-V = (1 + e) m2 / (m1 + m2) * closing speed.
        let dv = (imp.velocity_after[0] - imp.velocity_before[0]).norm();
        let expected = 1.1 * 10000.0 / 10100.0 * 100.0;
        assert!(
            (dv - expected).abs() < 1e-9 * expected,
            "{dv} vs {expected}"
        );
    }
}

/// Two boxes 4.5 x 1.8 x 1.4 m passing 0.7 m apart side by side, the first at 10 m/s and
/// yawing at 0.01 rad/s (so its swept box reaches the other's and the search runs): they never
/// meet.
fn passing_boxes() -> World {
    let mut w = World::new();
    let v = Vector::new(10.0, 0.0, 0.0);
    box_body(
        &mut w,
        [4.5, 1.8, 1.4],
        1450.0,
        [-10.0, 0.0, 0.7],
        0.0,
        v,
        0.01,
    );
    box_body(
        &mut w,
        [4.5, 1.8, 1.4],
        1450.0,
        [0.0, 2.5, 0.7],
        0.0,
        Vector::zeros(),
        0.0,
    );
    w
}

/// `crashsim run --duration "1e4 s"` under a 2.5 GB memory limit aborted with "memory
/// allocation of 208 bytes failed" (exit 134): every step was kept (about 460 B per step).
/// Now a long run keeps about 100,000 samples by default, a history above the limit is
/// refused before the run starts, and recording never aborts on a failed allocation.
#[test]
fn a_long_run_keeps_about_a_hundred_thousand_samples_by_default() {
    let mut w = passing_boxes();
    let out = w.run(2000.0, 1e-3).unwrap(); // 2e6 steps
    assert_eq!(out.record_interval, 20.0 * 1e-3);
    assert_eq!(out.len(), 100_001, "the start and every 20th step");
    assert_eq!(*out.times.last().unwrap(), 2000.0);
    assert_eq!(out.states.len(), 2 * out.len());
    // A short run keeps every step.
    let out = passing_boxes().run(1.0, 1e-3).unwrap();
    assert_eq!((out.len(), out.record_interval), (1001, 1e-3));
}

#[test]
fn a_history_above_the_limit_is_refused_before_the_run_with_the_interval_that_fits() {
    let mut w = passing_boxes();
    let every_step = RunOptions {
        record_interval: Some(1e-3),
        max_history_bytes: 1 << 20,
        until_rest: false,
        history: true,
    };
    let err = w
        .run_with_options(100.0, 1e-3, &every_step, &mut |_| true)
        .unwrap_err();
    assert_eq!(err.kind, ErrorKind::Parameter, "{err:?}");
    let msg = err.to_string();
    assert!(
        msg.contains("100002 samples of 2 bodies") && msg.contains("record_interval = "),
        "{msg}"
    );
    assert_eq!(w.time(), 0.0, "refused before it started");
    // The interval it names fits.
    let fits: f64 = msg
        .split("record_interval = ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let ok = RunOptions {
        record_interval: Some(fits),
        max_history_bytes: 1 << 20,
        until_rest: false,
        history: true,
    };
    let out = w.run_with_options(100.0, 1e-3, &ok, &mut |_| true).unwrap();
    assert!((out.len() * (8 + 2 * 104)) as u64 <= 1 << 20);
    // A recording interval must be a positive time.
    for bad in [0.0, -1e-3, f64::NAN] {
        let r = RunOptions {
            record_interval: Some(bad),
            ..RunOptions::default()
        };
        assert_eq!(
            error_kind(&passing_boxes().run_with_options(1.0, 1e-3, &r, &mut |_| true)),
            Some(ErrorKind::Parameter)
        );
    }
}

/// The run ignored Ctrl-C while a step was searching for a first contact (the hook was asked
/// only after each step). The hook is now asked inside the search too.
#[test]
fn the_interrupt_hook_is_asked_inside_the_first_contact_search() {
    let mut w = passing_boxes();
    let mut calls = 0;
    // One step of 2 s: without polling inside the search the hook would be asked once.
    let err = w
        .run_with_progress(2.0, 2.0, &mut |_| {
            calls += 1;
            calls < 3
        })
        .unwrap_err();
    assert!(
        err.kind == ErrorKind::Simulation && err.message.contains("interrupted"),
        "{err:?}"
    );
    assert_eq!(calls, 3);
    assert_eq!(w.time(), 0.0, "stopped inside the first step");
}

/// The time a run stopped at is a place of its error (data, as `.loc` in Python), written
/// before the message.
#[test]
fn an_interrupted_run_is_placed_at_its_time() {
    let mut w = passing_boxes();
    let mut last = Real::NAN;
    let err = w
        .run_with_progress(0.1, 1e-3, &mut |t| {
            last = t;
            t < 0.0025
        })
        .unwrap_err();
    assert_eq!(
        (err.kind, err.loc.clone()),
        (ErrorKind::Simulation, vec![Place::Time(last)])
    );
    assert_eq!(err.message, "the run was interrupted");
    assert_eq!(
        err.to_string(),
        format!("t = {last:.6} s: the run was interrupted")
    );
    assert!(last >= 0.0025 && last < 0.01, "{last}");
}

/// A variant of the box seed scene (red at 13.157894938354506 m/s, 0.124 m right of blue's
/// centre line) never ended: its first overlap, resolved on the 2^-30 s grid, rounded up
/// 1.6e-10 s past the step's end, the run advanced past the grid instant and waited for a
/// step count that never came (found by benches/batch_throughput.py's 100,000 variants).
/// Now a grid point past the step is met at the next step's start, and the step count
/// advances at or past its grid point.
#[test]
fn a_first_overlap_rounded_past_the_step_end_does_not_stall_the_run() {
    let mut w = World::new();
    box_body(
        &mut w,
        [4.5, 1.8, 1.4],
        1450.0,
        [-3.65, -0.12403064090975291, 0.7],
        0.0,
        Vector::new(13.157894938354506, 0.0, 0.0),
        0.0,
    );
    box_body(
        &mut w,
        [4.6, 1.8, 1.45],
        1500.0,
        [0.0, 0.0, 0.725],
        std::f64::consts::FRAC_PI_2,
        Vector::zeros(),
        0.0,
    );
    let out = w.run(0.1, 1e-3).unwrap();
    assert_eq!(out.impacts.len(), 1, "{:?}", out.contacts);
    let imp = &out.impacts[0];
    // Red's front (x = -3.65 + 2.25) meets blue's side (x = -0.9) after 0.5 m.
    let t_touch = 0.5 / 13.157894938354506;
    assert!(
        (imp.first_contact_time - t_touch).abs() < 2e-9,
        "{}",
        imp.first_contact_time
    );
    assert_eq!(imp.depth_of_penetration, 0.030);
    assert!((*out.times.last().unwrap() - 0.1).abs() < 1e-12);
}
