//! Tyres: the force of the road on a contact patch, in the road plane, from the patch's slip.
//!
//! Both models share one state per wheel: the deflection `u` (m, wheel axes: x forward, y
//! left) of the tread relative to the rim, a "bristle" that the road drags along while the
//! patch slips and that the rolling renews over the relaxation length sigma:
//!
//! `du/dt = -s - (|vx| / sigma) u`,   `F = k u + c du/dt`   (before saturation),
//!
//! with `s` the patch's slip velocity (its lateral velocity vy, and its longitudinal velocity
//! vx when the wheel is braked or locked) and `k = C / sigma` the tread stiffness from the
//! cornering stiffness C. The wheel's share m of the mass on this tread is damped critically:
//! the rolling's renewal already damps it (the pair's characteristic equation is
//! `s^2 + (|vx| / sigma + c / m) s + k / m`), so the damper adds only what it lacks,
//! `c = max(0, 2 sqrt(k m) - m |vx| / sigma)`, and vanishes above `2 sqrt(sigma C / m)`
//! (4.2 m/s for the default tyre). At speed the force then lags the slip over the relaxation
//! length, as a tyre's does (a damper kept at every speed made it lead the slip angle by
//! 2 sqrt(sigma alpha_sat / (mu g)) = 94 ms: a steer ramp's lateral acceleration 62 % above
//! the linear single-track model's); the steady state is the familiar `Fy = -C tan(alpha)`.
//! At rest the tread is a critically damped spring, so a braked vehicle on a slope stands
//! still and a sliding one stops without chatter or drift (no division by the speed
//! anywhere). Saturation is elasto-plastic: at the friction limit the tread slides, its
//! deflection stops growing and turns with the slip, and the force lies against the patch's
//! slip velocity.
//!
//! - [`TyreModel::Linear`], the reconstruction tyre: C = mu Fz / alpha_sat, so the lateral
//!   force is linear in the slip angle up to the saturation angle alpha_sat and mu Fz beyond;
//!   the resultant is limited to the friction circle mu Fz (Kamm's circle); a locked wheel
//!   slides at mu Fz against its patch velocity.
//! - [`TyreModel::MagicFormula`]: Pacejka's `D sin(C atan(B a - E (B a - atan(B a))))` with
//!   D = mu Fz, applied to the resultant slip (combined slip by the similarity method: the
//!   force's magnitude from the combined slip angle, its direction from the tread's
//!   deflection); C_alpha = B C D.
//!
//! A free-rolling wheel's longitudinal force is its rolling resistance `-f_r Fz` (against the
//! motion, smoothed below 0.1 m/s) plus the drive force; a braked wheel's is at most its brake
//! capacity; everything is then limited to the friction circle.

use crate::error::{require_finite, Error, Result};
use crate::math::Real;

use super::wheel::GRAVITY;

/// Deflection relaxation time (s) of a wheel in the air (no load): the tread springs back.
const AIRBORNE_RELAXATION: Real = 0.02;
/// Time (s) over which a tread deflected past the friction limit (e.g. when the load drops)
/// returns to it.
const YIELD_RELAXATION: Real = 0.005;
/// Rolling resistance acts against the motion; below this speed (m/s) it fades linearly so a
/// vehicle comes to rest without chatter.
const ROLLING_RESISTANCE_SPEED: Real = 0.1;
/// Largest combined slip angle (rad) a Magic Formula tread deflection represents, 20 deg: past
/// the peak of every usual tyre, into its sliding range (B 10, C 1.9, E 0.97 gives 0.97 D
/// there), with the tread deflected sigma times this (3.5 cm at sigma 0.1 m).
const MAGIC_FORMULA_MAX_SLIP: Real = 0.35;

/// Largest rolling resistance coefficient accepted: 0.3, a passenger tyre in sand (Wong,
/// Theory of Ground Vehicles, 4th ed., table 1.1: 0.015 on concrete, 0.08 on medium-hard
/// soil, 0.30 on sand). Past it the wheel is ploughing, not rolling.
pub const MAX_ROLLING_RESISTANCE: Real = 0.3;

/// A typical dry passenger tyre's Magic Formula factors (B 1/rad, C, E) (Pacejka, Tire and
/// Vehicle Dynamics, 3rd ed., ch. 4): the defaults of [`TyreModel::MagicFormula`] where a
/// caller gives none.
pub const MAGIC_FORMULA_DEFAULTS: [Real; 3] = [10.0, 1.9, 0.97];

/// The force law of a tyre.
#[derive(Clone, Debug, PartialEq)]
pub enum TyreModel {
    /// The reconstruction tyre: linear in the slip angle up to `saturation_angle` (rad,
    /// default 10 deg, in (0, 45 deg]), then mu Fz.
    Linear {
        /// Slip angle at which the lateral force reaches mu Fz (rad).
        saturation_angle: Real,
    },
    /// Pacejka's Magic Formula with D = mu Fz: stiffness factor `b` (1/rad, > 0), shape
    /// factor `c` (in (0, 2)), curvature factor `e` (< 1). Typical dry passenger tyre:
    /// b 10, c 1.9, e 0.97 (Pacejka, Tire and Vehicle Dynamics, 3rd ed., ch. 4).
    MagicFormula {
        /// Stiffness factor B (1/rad).
        b: Real,
        /// Shape factor C.
        c: Real,
        /// Curvature factor E.
        e: Real,
    },
}

/// A tyre: its force law, relaxation length and rolling resistance.
#[derive(Clone, Debug, PartialEq)]
pub struct Tyre {
    /// The force law; default the reconstruction tyre with a 10 deg saturation angle.
    pub model: TyreModel,
    /// Relaxation length sigma (m), > 0; default 0.1 m. It sets how far the wheel rolls
    /// before a new slip's force builds up, the tread stiffness C / sigma and the tread's
    /// deflection at the friction limit, alpha_sat sigma for the reconstruction tyre (1.7 cm
    /// at 10 deg: a real carcass deflects 1-2 cm there, about 150-200 kN/m at 4 kN). Real
    /// tyres' 0.3-0.6 m (Pacejka, Tire and Vehicle Dynamics, ch. 7) go with their cornering
    /// stiffness of about 15-20 Fz per rad, four times the reconstruction tyre's mu Fz /
    /// alpha_sat = 4.6 Fz per rad; 0.5 m here made a locked skid spring back 8.7 cm at the
    /// stop (1.6 % of a 6.4 m skid).
    pub relaxation_length: Real,
    /// Rolling resistance coefficient f_r (force / load), >= 0; default 0.012 (passenger
    /// tyres on asphalt, 0.010-0.015: Gillespie, Fundamentals of Vehicle Dynamics, ch. 4).
    pub rolling_resistance: Real,
}

impl Default for Tyre {
    fn default() -> Self {
        Tyre {
            model: TyreModel::Linear {
                saturation_angle: 10f64.to_radians(),
            },
            relaxation_length: 0.1,
            rolling_resistance: 0.012,
        }
    }
}

/// How a wheel turns at an instant (from the driver's inputs and its state).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WheelAction {
    /// Does not turn: the patch slips at its full velocity and may use all the friction.
    pub locked: bool,
    /// Largest longitudinal force the brake can make (N, >= 0; 0 = not braked). The patch
    /// slips longitudinally while braked.
    pub brake_capacity: Real,
    /// Drive force (N, + forward).
    pub drive: Real,
}

/// The tyre's force and the rate of its deflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TyreForce {
    /// Force on the vehicle in the road plane, wheel axes (N): x forward, y left.
    pub force: [Real; 2],
    /// d u / dt (m/s), wheel axes.
    pub deflection_rate: [Real; 2],
    /// True when the patch slides (the tread is at the friction limit).
    pub sliding: bool,
}

impl Tyre {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<()> {
        require_finite("relaxation_length", self.relaxation_length)?;
        require_finite("rolling_resistance", self.rolling_resistance)?;
        if self.relaxation_length <= 0.0 {
            return Err(Error::parameter(
                "relaxation_length",
                self.relaxation_length,
                "a tyre's relaxation length must be > 0 m (about 0.1 m)",
            ));
        }
        if !(0.0..=MAX_ROLLING_RESISTANCE).contains(&self.rolling_resistance) {
            return Err(Error::parameter(
                "rolling_resistance",
                self.rolling_resistance,
                "a rolling resistance coefficient must lie in [0, 0.3] (about 0.012 on \
                 asphalt, 0.08 on firm soil, 0.3 in sand)",
            ));
        }
        match self.model {
            TyreModel::Linear { saturation_angle } => {
                require_finite("saturation_angle", saturation_angle)?;
                if !(saturation_angle > 0.0 && saturation_angle <= 45f64.to_radians()) {
                    return Err(Error::parameter(
                        "saturation_angle",
                        saturation_angle,
                        "the saturation angle must lie in (0, 45] deg (about 10 deg)",
                    ));
                }
            }
            TyreModel::MagicFormula { b, c, e } => {
                for (name, v) in [("B", b), ("C", c), ("E", e)] {
                    require_finite(&format!("Magic Formula {name}"), v)?;
                }
                if b <= 0.0 || !(c > 0.0 && c < 2.0) || e >= 1.0 {
                    return Err(Error::Parameter(format!(
                        "Magic Formula B = {b}, C = {c}, E = {e} is invalid: B must be > 0, C in \
                         (0, 2), E < 1 (a dry passenger tyre: B 10, C 1.9, E 0.97)"
                    )));
                }
            }
        }
        Ok(())
    }

    /// Cornering stiffness (N/rad) at normal load `fz` (N) and friction `mu`.
    fn cornering_stiffness(&self, fz: Real, mu: Real) -> Real {
        match self.model {
            TyreModel::Linear { saturation_angle } => mu * fz / saturation_angle,
            TyreModel::MagicFormula { b, c, .. } => b * c * mu * fz,
        }
    }

    /// The saturated magnitude of a force whose linear value is `f_lin` (N), and whether it
    /// is at the friction limit; `c_alpha` is the cornering stiffness.
    fn saturate(&self, f_lin: Real, c_alpha: Real, friction: Real) -> (Real, bool) {
        match self.model {
            TyreModel::Linear { .. } => {
                if f_lin > friction {
                    (friction, true)
                } else {
                    (f_lin, false)
                }
            }
            TyreModel::MagicFormula { b, c, e } => {
                let a = (f_lin / c_alpha).min(MAGIC_FORMULA_MAX_SLIP);
                let x = b * a - e * (b * a - (b * a).atan());
                let f = friction * (c * x.atan()).sin();
                (f, c * x.atan() >= std::f64::consts::FRAC_PI_2)
            }
        }
    }

    /// The largest deflection force (N) the tread holds before it slides.
    fn yield_force(&self, c_alpha: Real, friction: Real) -> Real {
        match self.model {
            TyreModel::Linear { .. } => friction,
            TyreModel::MagicFormula { .. } => c_alpha * MAGIC_FORMULA_MAX_SLIP,
        }
    }

    /// The force at a contact patch and the rate of the tread's deflection.
    ///
    /// `fz` normal load (N), `mu` tyre-road friction, `vx`, `vy` the patch's velocity in
    /// wheel axes (m/s), `u` the deflection (m, wheel axes), `action` how the wheel turns.
    pub fn force(
        &self,
        fz: Real,
        mu: Real,
        vx: Real,
        vy: Real,
        u: [Real; 2],
        action: &WheelAction,
    ) -> TyreForce {
        if fz <= 0.0 || mu <= 0.0 {
            return TyreForce {
                force: [0.0, 0.0],
                deflection_rate: [-u[0] / AIRBORNE_RELAXATION, -u[1] / AIRBORNE_RELAXATION],
                sliding: false,
            };
        }
        let sigma = self.relaxation_length;
        let c_alpha = self.cornering_stiffness(fz, mu);
        let k = c_alpha / sigma;
        let slips_long = action.locked || action.brake_capacity > 0.0;
        let relax = vx.abs() / sigma;
        // Critical damping of the wheel's share of the mass on the tread, less what the
        // rolling's renewal gives (N s/m).
        let share = fz / GRAVITY;
        let damping = (2.0 * (k * share).sqrt() - share * relax).max(0.0);
        // The tread's elastic rate: dragged by the slip, renewed by the rolling.
        let elastic = [
            if slips_long {
                -vx - relax * u[0]
            } else {
                -u[0] / AIRBORNE_RELAXATION // a rolling wheel's tread carries no x deflection
            },
            -vy - relax * u[1],
        ];
        let friction = mu * fz;
        let long_limit = if action.locked {
            Real::INFINITY
        } else {
            action.brake_capacity
        };
        // The force from the elastic state, limited by the brake along x, then saturated.
        let mut f = [
            if slips_long {
                k * u[0] + damping * elastic[0]
            } else {
                0.0
            },
            k * u[1] + damping * elastic[1],
        ];
        if slips_long && f[0].abs() > long_limit {
            f[0] = f[0].signum() * long_limit;
        }
        let f_lin = (f[0] * f[0] + f[1] * f[1]).sqrt();
        let (f_mag, mut sliding) = self.saturate(f_lin, c_alpha, friction);
        if f_lin > 0.0 {
            f = [f[0] * f_mag / f_lin, f[1] * f_mag / f_lin];
        }
        // Elasto-plastic deflection: at a limit the tread slides, so its deflection stops
        // growing (it still turns with the slip) and returns to the limit if past it.
        let mut du = elastic;
        if slips_long && k * u[0].abs() >= long_limit && u[0] * du[0] >= 0.0 {
            du[0] = -(u[0] - u[0].signum() * long_limit / k) / YIELD_RELAXATION;
        }
        let yield_force = self.yield_force(c_alpha, friction);
        let un = (u[0] * u[0] + u[1] * u[1]).sqrt();
        if k * un >= yield_force && un > 0.0 {
            let dir = [u[0] / un, u[1] / un];
            let radial = du[0] * dir[0] + du[1] * dir[1];
            let back = (un - yield_force / k) / YIELD_RELAXATION;
            let keep = radial.min(0.0) - back;
            du = [
                du[0] - (radial - keep) * dir[0],
                du[1] - (radial - keep) * dir[1],
            ];
        }
        if !action.locked {
            let v = vx / vx.abs().max(ROLLING_RESISTANCE_SPEED);
            f[0] += action.drive - self.rolling_resistance * fz * v;
        }
        let total = (f[0] * f[0] + f[1] * f[1]).sqrt();
        if total > friction {
            f = [f[0] * friction / total, f[1] * friction / total];
            sliding = true;
        }
        TyreForce {
            force: f,
            deflection_rate: du,
            sliding,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FREE: WheelAction = WheelAction {
        locked: false,
        brake_capacity: 0.0,
        drive: 0.0,
    };

    /// The steady deflection of a free-rolling tyre at speed vx and lateral velocity vy.
    fn steady(t: &Tyre, vx: Real, vy: Real) -> [Real; 2] {
        [0.0, -vy * t.relaxation_length / vx.abs()]
    }

    #[test]
    fn linear_tyre_follows_the_cornering_stiffness_then_saturates() {
        let t = Tyre {
            rolling_resistance: 0.0,
            ..Tyre::default()
        };
        let (fz, mu, vx) = (4000.0, 0.8, 20.0);
        let c = mu * fz / 10f64.to_radians();
        for alpha_deg in [0.5, 2.0, 5.0, 9.9] {
            let vy = vx * (alpha_deg as Real).to_radians().tan();
            let out = t.force(fz, mu, vx, vy, steady(&t, vx, vy), &FREE);
            let expected = -c * (alpha_deg as Real).to_radians().tan();
            assert!(
                (out.force[1] - expected).abs() < 1e-9 * c,
                "{alpha_deg}: {out:?}"
            );
            assert!(out.deflection_rate[1].abs() < 1e-12 && !out.sliding);
        }
        let vy = vx * 0.5;
        let out = t.force(fz, mu, vx, vy, steady(&t, vx, vy), &FREE);
        assert!((out.force[1] + mu * fz).abs() < 1e-9 && out.sliding);
    }

    #[test]
    fn a_locked_wheel_slides_at_full_friction_against_its_patch_velocity() {
        let t = Tyre::default();
        let (fz, mu) = (4000.0, 0.8);
        let locked = WheelAction {
            locked: true,
            ..FREE
        };
        // The tread at its limit, deflected against the slip.
        let k = mu * fz / 10f64.to_radians() / t.relaxation_length;
        let v = (15.0f64.powi(2) + 25.0).sqrt();
        let u = [-15.0 / v * mu * fz / k, -5.0 / v * mu * fz / k];
        let out = t.force(fz, mu, 15.0, 5.0, u, &locked);
        let f = (out.force[0].powi(2) + out.force[1].powi(2)).sqrt();
        assert!((f - mu * fz).abs() < 1e-9 && out.sliding);
        let v = (15.0f64.powi(2) + 25.0).sqrt();
        let along = -(out.force[0] * 15.0 + out.force[1] * 5.0) / (f * v);
        assert!(along > 0.99, "{along}");
    }

    #[test]
    fn the_brake_capacity_limits_the_longitudinal_force() {
        let t = Tyre {
            rolling_resistance: 0.0,
            ..Tyre::default()
        };
        let braked = WheelAction {
            locked: false,
            brake_capacity: 1000.0,
            drive: 0.0,
        };
        let k = 0.8 * 4000.0 / 10f64.to_radians() / t.relaxation_length;
        let out = t.force(4000.0, 0.8, 20.0, 0.0, [-2000.0 / k, 0.0], &braked);
        assert!((out.force[0] + 1000.0).abs() < 1e-9, "{out:?}");
        // Once the tread reaches the capacity it stops deflecting further.
        let out = t.force(4000.0, 0.8, 20.0, 0.0, [-1000.0 / k, 0.0], &braked);
        assert!(out.deflection_rate[0].abs() < 1e-9, "{out:?}");
    }

    #[test]
    fn magic_formula_has_the_cornering_stiffness_bcd_and_peaks_at_d() {
        let t = Tyre {
            model: TyreModel::MagicFormula {
                b: 10.0,
                c: 1.9,
                e: 0.97,
            },
            rolling_resistance: 0.0,
            ..Tyre::default()
        };
        t.validate().unwrap();
        let (fz, mu, vx) = (4000.0, 0.9, 20.0);
        let vy = vx * 0.001;
        let out = t.force(fz, mu, vx, vy, steady(&t, vx, vy), &FREE);
        let c_alpha = 10.0 * 1.9 * mu * fz;
        assert!(
            (out.force[1] / (-c_alpha * 0.001) - 1.0).abs() < 1e-3,
            "{out:?}"
        );
        let mut peak: Real = 0.0;
        for k in 1..400 {
            let vy = vx * (k as Real * 0.1).to_radians().tan();
            peak = peak.max(-t.force(fz, mu, vx, vy, steady(&t, vx, vy), &FREE).force[1]);
        }
        assert!((peak / (mu * fz) - 1.0).abs() < 1e-3, "{peak}");
        assert!(Tyre {
            model: TyreModel::MagicFormula {
                b: 10.0,
                c: 2.5,
                e: 0.0
            },
            ..Tyre::default()
        }
        .validate()
        .is_err());
    }

    /// After a step of the slip angle at speed the force lags: it starts where it was and
    /// approaches its new steady value over the relaxation length (time sigma / vx), without
    /// the lead a damper would add; at rest the tread is damped critically.
    #[test]
    fn at_speed_the_force_lags_the_slip_over_the_relaxation_length() {
        let t = Tyre {
            rolling_resistance: 0.0,
            ..Tyre::default()
        };
        let (fz, mu, vx) = (4000.0, 0.8, 20.0);
        let c = mu * fz / 10f64.to_radians();
        let vy = vx * 2f64.to_radians().tan();
        // Integrate the deflection after the step (from a straight-running tread) exactly
        // enough: explicit Euler at 1 us over 3 time constants.
        let tau = t.relaxation_length / vx;
        let (mut u, h) = ([0.0, 0.0], 1e-6);
        let first = t.force(fz, mu, vx, vy, u, &FREE);
        assert!(
            first.force[1].abs() < 1e-9,
            "no jump at the step: {first:?}"
        );
        let steps = (tau / h).round() as usize;
        for _ in 0..steps {
            let out = t.force(fz, mu, vx, vy, u, &FREE);
            u[1] += h * out.deflection_rate[1];
        }
        let after_tau = t.force(fz, mu, vx, vy, u, &FREE).force[1];
        let steady = -c * 2f64.to_radians().tan();
        let expected = steady * (1.0 - (-1.0f64).exp());
        assert!(
            (after_tau / expected - 1.0).abs() < 1e-3,
            "{after_tau} vs {expected}"
        );
        // At rest: a lateral velocity acts through the critical damping 2 sqrt(k m).
        let k = c / t.relaxation_length;
        let out = t.force(fz, mu, 0.0, 0.01, [0.0, 0.0], &FREE);
        let critical = 2.0 * (k * fz / GRAVITY).sqrt();
        assert!(
            (out.force[1] + critical * 0.01).abs() < 1e-9 * critical,
            "{out:?}"
        );
    }

    #[test]
    fn without_load_there_is_no_force() {
        let out = Tyre::default().force(0.0, 0.8, 10.0, 3.0, [0.01, 0.02], &FREE);
        assert_eq!(out.force, [0.0, 0.0]);
        assert!(out.deflection_rate[0] < 0.0 && out.deflection_rate[1] < 0.0);
    }
}
