//! Driver inputs and wheel states as functions of time: steering, braking, drive force, and
//! the switches of a wheel's state (free, locked, braked) at a time or at an exchange.

use crate::error::{require_finite, Error, Place, Result};
use crate::math::Real;

use super::steering::SteerInput;
use super::table::Table;

/// Largest braking deceleration demand accepted (m/s^2): 20, about 2 g. Road tyres give
/// 0.8-1.2 g on dry asphalt; a demand past the friction is capped by it, so a larger one only
/// hides a mistake (100 m/s^2 was accepted and ran as full braking).
pub const MAX_BRAKING_DECELERATION: Real = 20.0;

/// What a wheel's brake does.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum Braking {
    /// A fraction of the friction available at the wheel (0 = none, 1 = at the limit without
    /// locking), as a time table.
    Fraction(Table),
    /// A deceleration demand (m/s^2, >= 0) as a time table: the wheel's longitudinal force is
    /// at most its load times demand / g (so a vehicle braked this way on every wheel
    /// decelerates at the demand while the friction allows it).
    Deceleration(Table),
    /// A fixed share of the whole vehicle's brake force: the wheel brakes with `share` (0-1)
    /// of `m a(t)`, `a` the vehicle's deceleration demand (m/s^2, >= 0) as a time table and
    /// `m` its mass (a front/rear split of 0.7 gives each front wheel 0.35). The wheels' shares
    /// add up to 1. A wheel asked for more than its friction locks unless the vehicle has ABS.
    Distributed {
        /// The vehicle's deceleration demand (m/s^2).
        deceleration: Table,
        /// This wheel's share of the vehicle's brake force (0-1).
        share: Real,
    },
}

impl Braking {
    /// The braking's own rules: a fraction in [0, 1], a deceleration demand in [0, 20] m/s^2,
    /// a wheel's share in [0, 1] (the shares adding up to 1 is the vehicle's rule).
    pub fn check(&self) -> Result<()> {
        match self {
            Braking::Fraction(t) => {
                let (lo, hi) = t.range();
                if lo < 0.0 || hi > 1.0 {
                    return Err(Error::invalid(format!(
                        "a braking fraction must lie in [0, 1] (got {lo} to {hi})"
                    )));
                }
            }
            Braking::Deceleration(t)
            | Braking::Distributed {
                deceleration: t, ..
            } if t.range().0 < 0.0 || t.range().1 > MAX_BRAKING_DECELERATION => {
                let (lo, hi) = t.range();
                return Err(Error::invalid(format!(
                    "a braking deceleration must lie in [0, 20] m/s^2 (got {lo} to {hi}): \
                     no tyre brakes harder than about 1.2 g; to brake at the friction \
                     limit give a braking fraction of 1"
                )));
            }
            Braking::Distributed { share, .. } if !(0.0..=1.0).contains(share) => {
                return Err(Error::parameter(
                    "brake share",
                    share,
                    "a wheel's share of the vehicle's brake force must lie in [0, 1]",
                ));
            }
            Braking::Deceleration(_) | Braking::Distributed { .. } => {}
        }
        Ok(())
    }
}

/// A wheel's state: how it turns.
#[derive(Clone, Debug, PartialEq)]
pub enum WheelState {
    /// Rolls freely (the driver's braking and drive apply).
    Free,
    /// Does not turn: the tyre slides against its patch velocity at the full friction.
    Locked,
    /// Braked at this fraction of the available friction (0-1), whatever the driver does
    /// (e.g. a wheel jammed by the crush).
    Braked(Real),
}

/// When a wheel's state switches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Trigger {
    /// At this time (s).
    Time(Real),
    /// At this vehicle's n-th impulse exchange (1 = its first), whichever pair.
    Exchange(usize),
}

/// One switch of a wheel's state.
#[derive(Clone, Debug, PartialEq)]
pub struct WheelSwitch {
    /// The wheel (index into the vehicle's wheels).
    pub wheel: usize,
    /// When.
    pub at: Trigger,
    /// The state from then on.
    pub state: WheelState,
}

impl WheelSwitch {
    /// The switch's own rules: a finite time or an exchange counted from 1, a braked
    /// fraction in [0, 1] (its wheel is the vehicle's rule).
    pub fn check(&self) -> Result<()> {
        match self.at {
            Trigger::Time(t) => require_finite("wheel-state switch time", t)?,
            Trigger::Exchange(0) => {
                return Err(Error::invalid(
                    "a wheel-state switch at exchange 0: exchanges count from 1",
                ))
            }
            Trigger::Exchange(_) => {}
        }
        if let WheelState::Braked(f) = self.state {
            if !(0.0..=1.0).contains(&f) {
                return Err(Error::parameter(
                    "braked wheel fraction",
                    f,
                    "it must lie in [0, 1]",
                ));
            }
        }
        Ok(())
    }
}

/// A vehicle's driver inputs and wheel-state switches.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DriverInputs {
    /// The steering input (through the vehicle's linkage, or per wheel), or None.
    pub steer: Option<SteerInput>,
    /// Braking per wheel (None: no braking on that wheel); empty: none anywhere.
    pub brake: Vec<Option<Braking>>,
    /// Drive force per wheel (N, + forward along the wheel), None: none; empty: none.
    pub drive: Vec<Option<Table>>,
    /// Wheel-state switches (initially every wheel is free).
    pub switches: Vec<WheelSwitch>,
}

impl DriverInputs {
    /// Checks the inputs against a vehicle with `wheels` wheels.
    pub fn validate(&self, wheels: usize) -> Result<()> {
        if !self.brake.is_empty() && self.brake.len() != wheels {
            return Err(Error::invalid(format!(
                "braking is given for {} wheels but the vehicle has {wheels}",
                self.brake.len()
            )));
        }
        if !self.drive.is_empty() && self.drive.len() != wheels {
            return Err(Error::invalid(format!(
                "drive force is given for {} wheels but the vehicle has {wheels}",
                self.drive.len()
            )));
        }
        for (k, b) in self.brake.iter().enumerate() {
            if let Some(b) = b {
                b.check().map_err(|e| e.at(Place::Wheel(k)))?;
            }
        }
        let shares: Vec<Real> = self
            .brake
            .iter()
            .filter_map(|b| match b {
                Some(Braking::Distributed { share, .. }) => Some(*share),
                _ => None,
            })
            .collect();
        let total: Real = shares.iter().sum();
        if !shares.is_empty() && (total - 1.0).abs() > 1e-9 {
            return Err(Error::invalid(format!(
                "the wheels' shares of the vehicle's brake force add up to {total}: they must \
                 add up to 1 (a front/rear split of 0.7 gives each front wheel 0.35, each rear \
                 wheel 0.15)"
            )));
        }
        for s in &self.switches {
            if s.wheel >= wheels {
                return Err(Error::invalid(format!(
                    "a wheel-state switch names wheel {} but the vehicle has {wheels} wheels",
                    s.wheel
                )));
            }
            s.check()?;
        }
        Ok(())
    }

    /// Drive force of wheel `k` at `t` (N).
    pub fn drive_at(&self, k: usize, t: Real) -> Real {
        self.drive
            .get(k)
            .and_then(|d| d.as_ref())
            .map_or(0.0, |d| d.at(t))
    }

    /// The state of wheel `k` at time `t` after the vehicle's `exchanges` exchanges: the last
    /// switch that has fired (in the order given), else free.
    pub fn wheel_state(&self, k: usize, t: Real, exchanges: usize) -> &WheelState {
        let mut state = &WheelState::Free;
        for s in &self.switches {
            let fired = match s.at {
                Trigger::Time(ts) => t >= ts,
                Trigger::Exchange(n) => exchanges >= n,
            };
            if s.wheel == k && fired {
                state = &s.state;
            }
        }
        state
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_interpolate_hold_and_refuse_bad_rows() {
        let t = Table::new("steer", &[(0.0, 0.0), (1.0, 2.0), (3.0, 2.0)]).unwrap();
        assert_eq!(t.at(-1.0), 0.0);
        assert_eq!(t.at(0.5), 1.0);
        assert_eq!(t.at(2.0), 2.0);
        assert_eq!(t.at(10.0), 2.0);
        assert!(Table::new("x", &[]).is_err());
        assert!(Table::new("x", &[(0.0, 1.0), (0.0, 2.0)]).is_err());
        assert!(Table::new("x", &[(1.0, 1.0), (0.5, 2.0)]).is_err());
        assert!(Table::new("x", &[(0.0, Real::NAN)]).is_err());
    }

    #[test]
    fn wheel_states_switch_at_times_and_exchanges() {
        let inputs = DriverInputs {
            switches: vec![
                WheelSwitch {
                    wheel: 0,
                    at: Trigger::Exchange(1),
                    state: WheelState::Locked,
                },
                WheelSwitch {
                    wheel: 1,
                    at: Trigger::Time(2.0),
                    state: WheelState::Braked(0.5),
                },
            ],
            ..DriverInputs::default()
        };
        inputs.validate(4).unwrap();
        assert_eq!(inputs.wheel_state(0, 5.0, 0), &WheelState::Free);
        assert_eq!(inputs.wheel_state(0, 0.0, 1), &WheelState::Locked);
        assert_eq!(inputs.wheel_state(1, 1.9, 3), &WheelState::Free);
        assert_eq!(inputs.wheel_state(1, 2.0, 0), &WheelState::Braked(0.5));
        assert!(inputs.validate(1).is_err());
    }
}
