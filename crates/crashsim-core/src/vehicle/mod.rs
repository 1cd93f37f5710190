//! Vehicles on the ground: wheels with suspension, tyres and the driver's inputs.
//!
//! A [`VehicleSpec`] is what a body needs to run on the ground; the forces it makes are
//! evaluated per wheel and per integration stage by [`crate::motion`].

pub mod inputs;
pub mod tyre;
pub mod wheel;

pub use inputs::{Braking, DriverInputs, Table, Trigger, WheelState, WheelSwitch};
pub use tyre::{Tyre, TyreForce, TyreModel, WheelAction, MAGIC_FORMULA_DEFAULTS};
pub use wheel::{
    static_loads, WheelSpec, DEFAULT_DAMPING_RATIO, DEFAULT_NATURAL_FREQUENCY, GRAVITY,
    MAX_DAMPING_RATIO, MAX_NATURAL_FREQUENCY,
};

use crate::error::{Error, Result};
use crate::math::{Aabb, Real};

/// Wheels may stick out of the body's box by this much (m) before they count as outside it.
const WHEEL_OUTSIDE_MARGIN: Real = 0.1;

/// Everything a body needs to run on the ground on its wheels.
#[derive(Clone, Debug, PartialEq)]
pub struct VehicleSpec {
    /// The wheels (at least 3), body frame.
    pub wheels: Vec<WheelSpec>,
    /// The tyre on every wheel.
    pub tyre: Tyre,
    /// Steering, braking, drive and wheel-state switches over time.
    pub inputs: DriverInputs,
}

impl VehicleSpec {
    /// Checks the wheels, tyre and inputs against the body's box `body_box` (body frame) and
    /// mass (kg): every wheel inside the box's outline (within 0.1 m), the static loads
    /// carrying the weight (within 1 %).
    pub fn validate(&self, body_box: &Aabb, mass: Real) -> Result<()> {
        if self.wheels.len() < 3 {
            return Err(Error::Parameter(format!(
                "a vehicle on the ground needs at least 3 wheels (got {})",
                self.wheels.len()
            )));
        }
        for (k, w) in self.wheels.iter().enumerate() {
            w.validate(k)?;
            let c = w.center;
            let (lo, hi) = (body_box.mins, body_box.maxs);
            let m = WHEEL_OUTSIDE_MARGIN;
            if c.x < lo.x - m || c.x > hi.x + m || c.y < lo.y - m || c.y > hi.y + m {
                return Err(Error::Parameter(format!(
                    "wheel {k} at ({:.3}, {:.3}) m (body frame, from the CG) lies outside the \
                     body, whose outline spans x {:.3} to {:.3} m and y {:.3} to {:.3} m: \
                     wheel positions are measured from the CG, x forward, y left",
                    c.x, c.y, lo.x, hi.x, lo.y, hi.y
                )));
            }
        }
        let weight = mass * GRAVITY;
        let carried: Real = self.wheels.iter().map(|w| w.static_load).sum();
        if (carried - weight).abs() > 0.01 * weight {
            return Err(Error::Parameter(format!(
                "the wheels' static loads add up to {carried:.1} N but the vehicle weighs \
                 {weight:.1} N: they must carry its weight (leave them to the engine)"
            )));
        }
        self.tyre.validate()?;
        self.inputs.validate(self.wheels.len())
    }
}
