//! Vehicles on the ground: wheels with suspension, tyres and the driver's inputs.
//!
//! A [`VehicleSpec`] is what a body needs to run on the ground; the forces it makes are
//! evaluated per wheel and per integration stage by [`crate::motion`].

pub mod combined_slip;
pub mod inputs;
pub mod steering;
pub mod table;
pub mod tyre;
pub mod wheel;

pub use inputs::{Braking, DriverInputs, Trigger, WheelState, WheelSwitch};
pub use steering::{
    DriverPath, LinkageGeometry, ReferenceAngle, SteerInput, SteerInterpolation, SteerReference,
    Steering, DEFAULT_ACKERMANN, DEFAULT_PATH_MIN_DISTANCE, DEFAULT_PATH_PREVIEW,
};
pub use table::Table;
pub use tyre::{
    CombinedSlip, Tyre, TyreForce, TyreModel, WheelAction, DEFAULT_CORNERING_COEFFICIENT,
    MAGIC_FORMULA_DEFAULTS,
};
pub use wheel::{
    check_load_groups, static_loads, static_loads_coupled, static_loads_towing, wheel_loads,
    AntiRollBar, WheelSpec, DEFAULT_DAMPING_RATIO, DEFAULT_NATURAL_FREQUENCY, GRAVITY,
    MAX_DAMPING_RATIO, MAX_NATURAL_FREQUENCY,
};

use crate::error::{Error, Place, Result};
use crate::math::{Aabb, Matrix, Point, Real, Vector};

/// Wheels may stick out of the body's box by this much (m) before they count as outside it.
const WHEEL_OUTSIDE_MARGIN: Real = 0.1;

/// Everything a body needs to run on the ground on its wheels.
#[derive(Clone, Debug, PartialEq)]
pub struct VehicleSpec {
    /// The wheels (at least 3), body frame.
    pub wheels: Vec<WheelSpec>,
    /// The tyre on every wheel.
    pub tyre: Tyre,
    /// The steering linkage (ratio, Ackermann).
    pub steering: Steering,
    /// Anti-roll bars (one per axle at most, each between a left and a right wheel).
    pub anti_roll: Vec<AntiRollBar>,
    /// Anti-lock brakes: true, a braked wheel asked for more than its friction brakes at the
    /// friction and keeps rolling (and steering, as the combined-slip law allows); false, it
    /// locks and slides at mu Fz against its patch velocity while the demand exceeds the
    /// friction. A braking fraction (at most the friction) never locks a wheel.
    pub abs: bool,
    /// Steering, braking, drive and wheel-state switches over time.
    pub inputs: DriverInputs,
    /// Where the vehicle rests on another (a trailer's hitch coupler or kingpin, body frame,
    /// m): that point carries its share of the weight at rest ([`static_loads_coupled`]) and
    /// the wheels the rest; None for a vehicle on its own wheels.
    pub coupling: Option<Point>,
    /// What its own trailer puts on its hitch at rest: the hitch (body frame, m; x and y
    /// used) and the static vertical load there (N, down; negative when a tail-heavy trailer
    /// lifts it): the wheels carry the vehicle's weight and this. The world sets it (and the
    /// wheels' static loads) from its joints when a run starts (world/joints.rs); a spec may
    /// leave it None.
    pub hitch_load: Option<(Point, Real)>,
    /// Wheels that share their load equally (a tandem's or tridem's load-equalising
    /// suspension, a walking beam or a linked leaf set: each side's wheels of the group one
    /// set, wheel indices): their springs act on the set's mean travel and each wheel on the
    /// ground carries an equal share, so braking or pitch moves no load between the axles of
    /// the group. Empty: every wheel on its own spring.
    pub load_groups: Vec<Vec<usize>>,
}

impl VehicleSpec {
    /// Checks the wheels, tyre and inputs of a vehicle of `mass` kg: at least 3 wheels (2
    /// coupled), each wheel's numbers, its load groups, the static loads carrying the weight
    /// (within 1 %), the tyre, linkage, anti-roll bars and driver inputs; with `body_box`
    /// (the body's box, body frame, m) also every wheel inside its outline (within 0.1 m).
    /// A scene's or a world's set_vehicle gives the box; None checks the rest, the wheels
    /// before they are put on a body (the Python binding's `check_vehicle`).
    pub fn validate(&self, body_box: Option<&Aabb>, mass: Real) -> Result<()> {
        self.check_wheels(body_box)?;
        self.checked_groups()?;
        self.check_weight(mass)?;
        self.tyre.validate()?;
        self.steering.validate()?;
        self.check_bars()?;
        self.inputs.validate(self.wheels.len())?;
        if let Some(steer) = &self.inputs.steer {
            self.steering.validate_input(steer, &self.wheels)?;
        }
        Ok(())
    }

    /// Enough wheels, each one's numbers and, with `body_box`, its centre inside the box's
    /// outline (x and y, within [`WHEEL_OUTSIDE_MARGIN`]).
    fn check_wheels(&self, body_box: Option<&Aabb>) -> Result<()> {
        let least = if self.coupling.is_some() { 2 } else { 3 };
        if self.wheels.len() < least {
            return Err(Error::invalid(format!(
                "a vehicle on the ground needs at least 3 wheels, a coupled one (a trailer) 2 \
                 (got {})",
                self.wheels.len()
            )));
        }
        for (k, w) in self.wheels.iter().enumerate() {
            w.validate(k)?;
            let Some(body_box) = body_box else { continue };
            let c = w.center;
            let (lo, hi) = (body_box.mins, body_box.maxs);
            let m = WHEEL_OUTSIDE_MARGIN;
            if c.x < lo.x - m || c.x > hi.x + m || c.y < lo.y - m || c.y > hi.y + m {
                return Err(Error::invalid(format!(
                    "its centre at ({:.3}, {:.3}) m (body frame, from the CG) lies outside the \
                     body, whose outline spans x {:.3} to {:.3} m and y {:.3} to {:.3} m: \
                     wheel positions are measured from the CG, x forward, y left",
                    c.x, c.y, lo.x, hi.x, lo.y, hi.y
                ))
                .at(Place::Wheel(k)));
            }
        }
        Ok(())
    }

    /// A finite, positive `mass` (kg) whose weight the wheels' static loads (N) carry
    /// (within 1 %): with a hitch load, that too; with a coupling, less its share.
    fn check_weight(&self, mass: Real) -> Result<()> {
        crate::body::check_mass(mass)?;
        let mut weight = mass * GRAVITY;
        let towed = match &self.hitch_load {
            Some((p, load)) => {
                crate::error::require_finite_vector("the hitch point", &p.coords)?;
                crate::error::require_finite("the hitch load", *load)?;
                weight += load;
                Some(([p.x, p.y], *load))
            }
            None => None,
        };
        if let Some(c) = &self.coupling {
            crate::error::require_finite_vector("the coupling point", &c.coords)?;
            let xy: Vec<[Real; 2]> = self
                .wheels
                .iter()
                .map(|w| [w.center.x, w.center.y])
                .collect();
            let groups = self.checked_groups()?;
            weight -= wheel_loads(&xy, groups, mass * GRAVITY, Some([c.x, c.y]), towed)?.1;
        }
        let carried: Real = self.wheels.iter().map(|w| w.static_load).sum();
        if (carried - weight).abs() > 0.01 * weight {
            return Err(Error::invalid(format!(
                "the wheels' static loads add up to {carried:.1} N but the vehicle weighs \
                 {weight:.1} N: they must carry its weight (leave them to the engine)"
            )));
        }
        Ok(())
    }

    /// Each anti-roll bar's wheels and stiffness, and one bar per wheel.
    fn check_bars(&self) -> Result<()> {
        for (k, bar) in self.anti_roll.iter().enumerate() {
            bar.validate(k, &self.wheels)?;
            let shared = self.anti_roll[..k].iter().any(|b| {
                [b.left, b.right]
                    .iter()
                    .any(|w| *w == bar.left || *w == bar.right)
            });
            if shared {
                return Err(Error::invalid(format!(
                    "anti-roll bar {k} shares a wheel with another bar: one bar per wheel"
                )));
            }
        }
        Ok(())
    }

    /// The load groups, checked ([`check_load_groups`]).
    fn checked_groups(&self) -> Result<&[Vec<usize>]> {
        check_load_groups(&self.load_groups, self.wheels.len())?;
        Ok(&self.load_groups)
    }

    /// The linkage's geometry and the reference's road-wheel angle at time `t` (rad) for the
    /// body at `position` (CG, world, m) turned by `rotation` (body to world) moving at
    /// `velocity` (world, m/s): what [`VehicleSpec::wheel_steer`] needs; None without a
    /// reference angle (no steering, or per-wheel tables), the geometry then not worked out
    /// (it was 1.5 % of a run-out to rest, called in every evaluation). A driver's path is
    /// steered from the pose.
    pub fn steering_at(
        &self,
        t: Real,
        position: &Point,
        rotation: &Matrix,
        velocity: &Vector,
    ) -> Option<(LinkageGeometry, ReferenceAngle)> {
        match &self.inputs.steer {
            Some(SteerInput::Path(path)) => {
                let geometry = LinkageGeometry::of(&self.wheels);
                let x0 = geometry.fixed_axle_x().unwrap_or(0.0);
                let axle = position + rotation * Vector::new(x0, geometry.centre_y(), 0.0);
                let ahead = rotation * Vector::x();
                let flat = ahead.x.hypot(ahead.y).max(1e-12);
                let heading = [ahead.x / flat, ahead.y / flat];
                let speed = velocity.x * heading[0] + velocity.y * heading[1];
                let delta = path.steer([axle.x, axle.y], heading, speed, geometry.wheelbase());
                Some((geometry, ReferenceAngle::At(delta)))
            }
            Some(input) => self
                .steering
                .reference_angle(input, t)
                .map(|delta| (LinkageGeometry::of(&self.wheels), delta)),
            None => None,
        }
    }

    /// Road-wheel angle (rad, about the body z axis, + left) of wheel `k` at time `t`, with
    /// [`VehicleSpec::steering_at`]'s geometry and reference angle: through the linkage, or
    /// from its own table; 0 for a wheel that does not steer.
    pub fn wheel_steer(
        &self,
        k: usize,
        t: Real,
        at: &Option<(LinkageGeometry, ReferenceAngle)>,
    ) -> Real {
        let w = &self.wheels[k];
        match (&self.inputs.steer, at) {
            (Some(SteerInput::PerWheel(tables)), _) => {
                tables[k].as_ref().map_or(0.0, |table| table.at(t))
            }
            (Some(SteerInput::Path(_)), Some((geometry, ReferenceAngle::At(delta)))) => {
                self.steering.wheel_angle_from(
                    SteerReference::Centre,
                    geometry,
                    *delta,
                    w.steerable,
                    w.center.x,
                    w.center.y,
                )
            }
            (_, Some((geometry, angle))) => {
                self.steering
                    .wheel_angle_at(geometry, *angle, w.steerable, w.center.x, w.center.y)
            }
            _ => 0.0,
        }
    }
}

#[cfg(test)]
#[path = "validate_tests.rs"]
mod tests;
