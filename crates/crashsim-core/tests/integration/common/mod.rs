//! The reference car of the integration tests on the ground (dynamics.rs, suspension.rs): 1500 kg,
//! CG 1.1 m behind the front axle and 1.6 m ahead of the rear one, track 1.55 m, CG 0.55 m
//! above the ground, tyre radius 0.3 m; roll and pitch inertia of a 4.6 x 1.8 x 1.4 m box, yaw
//! radius of gyration half the wheelbase. SI throughout.

// Each test file uses its own part of this module.
#![allow(dead_code)]

use std::sync::Arc;

use crashsim_core::math::{Matrix, Point, Real, Rotation, Vector};
use crashsim_core::vehicle::{static_loads, Trigger, WheelSpec, WheelState, WheelSwitch, GRAVITY};
use crashsim_core::{BodyState, ContactEventKind, MassProperties, MeshShape, RunOutput, World};

pub const MASS: Real = 1500.0;
pub const A: Real = 1.1;
pub const B: Real = 1.6;
pub const TRACK: Real = 1.55;
pub const CG_HEIGHT: Real = 0.55;
pub const RADIUS: Real = 0.3;

/// The car's mass properties.
pub fn props() -> MassProperties {
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

/// The four wheels (front left, front right, rear left, rear right; the fronts steer) on
/// springs of natural frequency `frequency` (Hz) and damping ratio `ratio`, each carrying its
/// axle's share of the weight at static ride height.
pub fn wheels(frequency: Real, ratio: Real) -> crashsim_core::Result<Vec<WheelSpec>> {
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

/// Every wheel switched to `state` from t = 0.
pub fn all_wheels_from_start(state: WheelState) -> Vec<WheelSwitch> {
    (0..4)
        .map(|wheel| WheelSwitch {
            wheel,
            at: Trigger::Time(0.0),
            state: state.clone(),
        })
        .collect()
}

// -- box bodies (engine.rs, thin_parts.rs, batch.rs) -------------------------------------

/// A box: length, width, height (m), body frame at its centre.
pub fn box_shape(l: Real, w: Real, h: Real) -> Arc<MeshShape> {
    Arc::new(MeshShape::cuboid(
        Vector::zeros(),
        Vector::new(l, w, h) * 0.5,
    ))
}

/// A uniform solid box of `m` kg and those sizes (m): its mass properties about the CG.
pub fn box_props(m: Real, l: Real, w: Real, h: Real) -> MassProperties {
    let i = Matrix::from_diagonal(&Vector::new(
        m / 12.0 * (w * w + h * h),
        m / 12.0 * (l * l + h * h),
        m / 12.0 * (l * l + w * w),
    ));
    MassProperties::new(m, i).unwrap()
}

/// A body at (x, y, z) m, turned `yaw` rad about z, moving at `v` m/s, not turning.
pub fn state(x: Real, y: Real, z: Real, yaw: Real, v: Vector) -> BodyState {
    BodyState {
        position: Point::new(x, y, z),
        orientation: Rotation::from_axis_angle(&Vector::z_axis(), yaw),
        velocity: v,
        angular_velocity: Vector::zeros(),
    }
}

/// Adds a uniform box of `m` kg and sizes `(l, w, h)` m at `state`; its index.
pub fn add_box(
    world: &mut World,
    m: Real,
    (l, w, h): (Real, Real, Real),
    state: &BodyState,
) -> usize {
    world
        .add_body(box_shape(l, w, h), box_props(m, l, w, h), state)
        .unwrap()
}

/// Every first overlap or closing-again starts a timer; each must end in an exchange or a
/// no-exchange event with a reason.
pub fn every_timer_is_accounted_for(out: &RunOutput) {
    let timers = out
        .contacts
        .iter()
        .filter(|c| {
            matches!(
                c.kind,
                ContactEventKind::FirstOverlap | ContactEventKind::ClosingAgain
            )
        })
        .count();
    let skipped = out
        .contacts
        .iter()
        .filter(|c| matches!(&c.kind, ContactEventKind::NoExchange(r) if !r.is_empty()))
        .count();
    assert_eq!(timers, out.impacts.len() + skipped, "{:?}", out.contacts);
}
