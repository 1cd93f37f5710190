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
//! The laws (per unit of the wheel's load Fz, with the road's friction mu):
//!
//! - [`TyreModel::Linear`], the reconstruction programs' linear tyre (PC-Crash's, as Steffan and
//!   Moser describe it, SAE 960886; Virtual CRASH's "linear"): the cornering stiffness is a
//!   property of the tyre and its load, `C = c Fz` with the cornering coefficient `c` (1/rad;
//!   default 1 per 10 deg), and the lateral force `c Fz alpha` is capped at what the friction
//!   leaves: a slippery road saturates earlier but does not soften the tyre.
//! - [`TyreModel::LinearFrictionScaled`], crashsim's law before 2026-11: `C = mu Fz /
//!   alpha_sat`, the force reaching mu Fz at the saturation angle on every road (24 % softer
//!   than the linear law at mu 0.76 and alpha_sat 10 deg).
//! - [`TyreModel::MagicFormula`]: Pacejka's `D sin(C atan(B a - E (B a - atan(B a))))` with
//!   B, C, E given at mu = 1 and Pacejka's similarity on other roads: `D = mu Fz` and the slip
//!   scaled by 1/mu, so `C = B C Fz` whatever the road.
//!
//! The longitudinal force of a braked or driven wheel is its brake's (at most its capacity)
//! plus its drive force, less the rolling resistance `f_r Fz` (against the motion, smoothed
//! below 0.1 m/s). The lateral force is then limited by the friction the longitudinal one
//! leaves ([`CombinedSlip`]): by default `sqrt((mu Fz)^2 - Fx^2)` (the braking force kept and
//! the friction ellipse giving the steering force, as Brach and Brach describe the
//! reconstruction programs' combined laws, SAE 2009-01-0102), or both scaled onto the friction
//! circle (Kamm's circle), or combined by Nicolas and Comstock's formula as Brach and Brach
//! modified it ([`super::combined_slip::nicolas_comstock`]: the brake demand is the pure-slip force Fx(s), its slip
//! the one the linear curve Cs s gives it at, and the tread's force over its cornering
//! stiffness tan(alpha)), capped at mu Fz. The Magic Formula's curve applies to the lateral
//! slip only, scaled to the lateral force available (the similarity method again), so a braked
//! wheel delivers its brake force under the first two laws. A locked wheel slides at mu Fz
//! against its patch velocity under every law.

use crate::error::{require_finite, Error, Result};
use crate::math::Real;

use super::combined_slip::{combine_pure_slip_forces, MAX_LONGITUDINAL_STIFFNESS};
use super::wheel::GRAVITY;

/// Deflection relaxation time (s) of a wheel in the air (no load): the tread springs back.
const AIRBORNE_RELAXATION: Real = 0.02;
/// Time (s) over which a tread deflected past the friction limit (e.g. when the load drops)
/// returns to it.
const YIELD_RELAXATION: Real = 0.005;
/// Rolling resistance acts against the motion; below this speed (m/s) it fades linearly so a
/// vehicle comes to rest without chatter.
const ROLLING_RESISTANCE_SPEED: Real = 0.1;
/// Largest slip angle (rad, at mu = 1: on other roads it scales with the friction left) a
/// Magic Formula tread deflection represents, 20 deg: past the peak of every usual tyre, into
/// its sliding range (B 10, C 1.9, E 0.97 gives 0.97 D there), with the tread deflected sigma
/// times this (3.5 cm at sigma 0.1 m).
const MAGIC_FORMULA_MAX_SLIP: Real = 0.35;

/// Largest rolling resistance coefficient accepted: 0.3, a passenger tyre in sand (Wong,
/// Theory of Ground Vehicles, 4th ed., table 1.1: 0.015 on concrete, 0.08 on medium-hard
/// soil, 0.30 on sand). Past it the wheel is ploughing, not rolling.
pub const MAX_ROLLING_RESISTANCE: Real = 0.3;

/// A typical dry passenger tyre's Magic Formula factors (B 1/rad, C, E) (Pacejka, Tire and
/// Vehicle Dynamics, 3rd ed., ch. 4): the defaults of [`TyreModel::MagicFormula`] where a
/// caller gives none.
pub const MAGIC_FORMULA_DEFAULTS: [Real; 3] = [10.0, 1.9, 0.97];

/// Default cornering coefficient of the linear tyre (1/rad): 1 per 10 deg (5.73 /rad), the
/// reconstruction programs' linear tyre (pycrash's reading of PC-Crash, Steffan and Moser, SAE
/// 960886: the force reaches mu Fz at mu x 10 deg). Real radial tyres measure about 15 % of
/// the load per degree (8.6 /rad; Gillespie, Fundamentals of Vehicle Dynamics, 1992, as
/// McHenry's SMAC manual quotes it) and modern datasets 15-22 /rad: give a tyre's own
/// coefficient when matching a test rather than a reconstruction program.
pub const DEFAULT_CORNERING_COEFFICIENT: Real = 1.0 / (10.0 * std::f64::consts::PI / 180.0);

/// The force law of a tyre.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum TyreModel {
    /// The reconstruction programs' linear tyre: `Fy = c Fz alpha`, capped at the friction
    /// left by the longitudinal force. `cornering` is c (1/rad, in (0, 60]; default
    /// [`DEFAULT_CORNERING_COEFFICIENT`]); the saturation angle at mu = 1 is 1 / c.
    Linear {
        /// Cornering coefficient c: cornering stiffness per unit load (1/rad).
        cornering: Real,
    },
    /// crashsim's law before 2026-11: the lateral force reaches mu Fz at `saturation_angle`
    /// (rad, in (0, 45 deg]) whatever the road: cornering stiffness mu Fz / alpha_sat.
    LinearFrictionScaled {
        /// Slip angle at which the lateral force reaches mu Fz (rad).
        saturation_angle: Real,
    },
    /// Pacejka's Magic Formula at mu = 1 (stiffness factor `b` 1/rad > 0, shape factor `c` in
    /// (0, 2), curvature factor `e` < 1), on other roads by similarity (D = mu Fz, the slip
    /// scaled by 1 / mu): cornering stiffness B C Fz. A dry passenger tyre: b 10, c 1.9,
    /// e 0.97 (Pacejka, Tire and Vehicle Dynamics, 3rd ed., ch. 4): 19 Fz per rad.
    MagicFormula {
        /// Stiffness factor B (1/rad).
        b: Real,
        /// Shape factor C.
        c: Real,
        /// Curvature factor E.
        e: Real,
    },
}

/// How a wheel's longitudinal force (brake, drive, rolling resistance) and its lateral force
/// share the friction mu Fz.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum CombinedSlip {
    /// The longitudinal force is kept (at most mu Fz) and the lateral force limited to
    /// `sqrt((mu Fz)^2 - Fx^2)`: the friction ellipse gives the steering force that a given
    /// braking force leaves, as Brach and Brach (SAE 2009-01-0102, EVU 2008) describe several
    /// reconstruction programs' tyre models. The default.
    BrakingPriority,
    /// Each component from its own law, then both scaled together onto the friction circle
    /// mu Fz (Kamm's circle): braking in a turn at the limit keeps part of the lateral force
    /// and gives up part of the braking. crashsim's law before 2026-11.
    Circle,
    /// Nicolas and Comstock's combination of the pure-slip forces Fx(s) and Fy(alpha) as
    /// Brach and Brach modified it to give the pure-slip forces back at alpha = 0 and s = 0
    /// (SAE 2000-01-0357; SAE 2009-01-0102; SAE 2011-01-0094), with crashsim's equivalent
    /// slips (see [`super::combined_slip::nicolas_comstock`]): both components change with both slips, so a braked
    /// wheel in a turn brakes less than its demand. The resultant is capped at mu Fz (the
    /// formula alone reaches 1.32 mu Fz with the linear tyre's sharp saturation).
    NicolasComstock,
}

/// A tyre: its force law, relaxation length, rolling resistance and combined-slip law.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct Tyre {
    /// The force law; default the reconstruction programs' linear tyre, 1 per 10 deg.
    pub model: TyreModel,
    /// Relaxation length sigma (m), > 0; default 0.1 m. It sets how far the wheel rolls
    /// before a new slip's force builds up, the tread stiffness C / sigma and the tread's
    /// deflection at the friction limit, sigma mu / c for the linear tyre (1.4 cm at mu 0.8:
    /// a real carcass deflects 1-2 cm there, about 150-200 kN/m at 4 kN). Real tyres' 0.3-0.6
    /// m (Pacejka, Tire and Vehicle Dynamics, ch. 7) go with their cornering stiffness of
    /// about 15-20 Fz per rad, three times the linear tyre's 5.7; 0.5 m here made a locked
    /// skid spring back 8.7 cm at the stop (1.6 % of a 6.4 m skid).
    pub relaxation_length: Real,
    /// Rolling resistance coefficient f_r (force / load), in [0, 0.3]; default 0, as the
    /// reconstruction programs: their runs keep their speed without a driver's input (a
    /// PC-Crash run at 30 mph kept 44.0001 ft/s), and a rolling resistance is the user's
    /// (PC-Crash and Virtual CRASH as a braking percentage). Passenger tyres on asphalt:
    /// 0.010-0.015 (Gillespie, ch. 4).
    pub rolling_resistance: Real,
    /// How the longitudinal and lateral forces share the friction; default
    /// [`CombinedSlip::BrakingPriority`].
    pub combined: CombinedSlip,
    /// Load sensitivity `e` of the cornering stiffness (-, in [0, 1)): `C(Fz) = C(F0)
    /// (Fz / F0)^(1 - e)`, F0 the wheel's static load, so an axle whose load moves from its
    /// inner to its outer wheel loses cornering stiffness (about `e (1 - e) (dF / F0)^2` of it)
    /// and the axle taking more of the lateral load transfer (the stiffer in roll) saturates
    /// first: the understeer of real tyres (Gillespie, ch. 6; Milliken, ch. 2). Default 0,
    /// the reconstruction programs' linear tyre, whose stiffness is proportional to the load.
    pub load_sensitivity: Real,
    /// Longitudinal slip stiffness per unit load `Cs / Fz` (1 per unit slip, in (0, 100]) of
    /// the [`CombinedSlip::NicolasComstock`] law, the only one that uses it. None (default):
    /// Cs equal to the cornering stiffness C_alpha (per rad), the isotropic tread crashsim's
    /// bristle already is (one stiffness C / sigma both ways), with which the combined force
    /// follows the slip vector. Measured passenger tyres: Cs about 1-1.5 C_alpha, 15-30 Fz
    /// per unit slip (Pacejka, Tire and Vehicle Dynamics, ch. 4). Proportional to the load
    /// (the load sensitivity applies to C_alpha only).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub longitudinal_stiffness: Option<Real>,
}

impl Default for Tyre {
    fn default() -> Self {
        Tyre {
            model: TyreModel::Linear {
                cornering: DEFAULT_CORNERING_COEFFICIENT,
            },
            relaxation_length: 0.1,
            rolling_resistance: 0.0,
            combined: CombinedSlip::BrakingPriority,
            load_sensitivity: 0.0,
            longitudinal_stiffness: None,
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
        require_finite("load_sensitivity", self.load_sensitivity)?;
        if !(0.0..1.0).contains(&self.load_sensitivity) {
            return Err(Error::parameter(
                "load_sensitivity",
                self.load_sensitivity,
                "a tyre's load sensitivity must lie in [0, 1) (0: stiffness proportional to \
                 the load)",
            ));
        }
        if let Some(cs) = self.longitudinal_stiffness {
            require_finite("longitudinal_stiffness", cs)?;
            if !(cs > 0.0 && cs <= MAX_LONGITUDINAL_STIFFNESS) {
                return Err(Error::parameter(
                    "longitudinal_stiffness",
                    cs,
                    "a longitudinal slip stiffness per unit load must lie in (0, 100] per unit \
                     slip (passenger tyres 15-30; leave it unset for the cornering stiffness)",
                ));
            }
            if self.combined != CombinedSlip::NicolasComstock {
                return Err(Error::invalid(format!(
                    "longitudinal_stiffness = {cs} is used by the nicolas_comstock combined-slip \
                     law only: set combined = nicolas_comstock or leave it unset"
                )));
            }
        }
        match self.model {
            TyreModel::Linear { cornering } => {
                require_finite("cornering_coefficient", cornering)?;
                if !(cornering > 0.0 && cornering <= 60.0) {
                    return Err(Error::parameter(
                        "cornering_coefficient",
                        cornering,
                        "a cornering coefficient must lie in (0, 60] per rad (the \
                         reconstruction programs' 5.73, 1 per 10 deg; real tyres 8-22)",
                    ));
                }
            }
            TyreModel::LinearFrictionScaled { saturation_angle } => {
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
                    return Err(Error::invalid(format!(
                        "Magic Formula B = {b}, C = {c}, E = {e} is invalid: B must be > 0, C in \
                         (0, 2), E < 1 (a dry passenger tyre: B 10, C 1.9, E 0.97)"
                    )));
                }
            }
        }
        Ok(())
    }

    /// Cornering stiffness (N/rad) at normal load `fz` (N) and friction `mu` of a wheel whose
    /// static load is `nominal` (N; what the load sensitivity is relative to).
    pub fn cornering_stiffness(&self, fz: Real, mu: Real, nominal: Real) -> Real {
        let proportional = match self.model {
            TyreModel::Linear { cornering } => cornering * fz,
            TyreModel::LinearFrictionScaled { saturation_angle } => mu * fz / saturation_angle,
            TyreModel::MagicFormula { b, c, .. } => b * c * fz,
        };
        if self.load_sensitivity == 0.0 {
            proportional
        } else {
            proportional * (fz / nominal).powf(-self.load_sensitivity)
        }
    }

    /// The lateral force (N, >= 0) whose linear value is `f_lin` (N, >= 0) when `available`
    /// (N) of the friction is left for it, and whether it is at the limit (sliding).
    fn lateral(&self, f_lin: Real, available: Real) -> (Real, bool) {
        match self.model {
            TyreModel::Linear { .. } | TyreModel::LinearFrictionScaled { .. } => {
                if f_lin >= available {
                    (available, true)
                } else {
                    (f_lin, false)
                }
            }
            TyreModel::MagicFormula { b, c, e } => {
                if available <= 0.0 {
                    return (0.0, true);
                }
                // Similarity: the curve scaled to `available` with the cornering stiffness
                // C_alpha kept, Fy = A g(alpha C_alpha / (B C A)) with g'(0) = B C, at
                // alpha = f_lin / C_alpha: x = f_lin / (B C A).
                let x = (f_lin / (b * c * available)).min(MAGIC_FORMULA_MAX_SLIP);
                let bx = b * x;
                let phase = c * (bx - e * (bx - bx.atan())).atan();
                (
                    available * phase.sin(),
                    phase >= std::f64::consts::FRAC_PI_2,
                )
            }
        }
    }

    /// The largest elastic lateral force (N) the tread holds before it slides, with
    /// `available` (N) of the friction left for it.
    fn lateral_yield(&self, available: Real) -> Real {
        // The tread holds x up to MAGIC_FORMULA_MAX_SLIP: f_lin = B C x available.
        match self.model {
            TyreModel::Linear { .. } | TyreModel::LinearFrictionScaled { .. } => available,
            TyreModel::MagicFormula { b, c, .. } => b * c * MAGIC_FORMULA_MAX_SLIP * available,
        }
    }

    /// The force at a contact patch and the rate of the tread's deflection.
    ///
    /// `fz` normal load (N) of a wheel whose static load is `nominal` (N), `mu` tyre-road
    /// friction, `vx`, `vy` the patch's velocity in wheel axes (m/s), `u` the deflection (m,
    /// wheel axes), `action` how the wheel turns.
    #[allow(clippy::too_many_arguments)]
    pub fn force(
        &self,
        fz: Real,
        nominal: Real,
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
        let c_alpha = self.cornering_stiffness(fz, mu, nominal);
        let k = c_alpha / sigma;
        let relax = vx.abs() / sigma;
        // Critical damping of the wheel's share of the mass on the tread, less what the
        // rolling's renewal gives (N s/m).
        let share = fz / GRAVITY;
        let damping = (2.0 * (k * share).sqrt() - share * relax).max(0.0);
        let friction = mu * fz;
        if action.locked {
            return self.locked(k, damping, relax, friction, vx, vy, u);
        }
        let braked = action.brake_capacity > 0.0;
        // The tread's elastic rate: dragged by the slip, renewed by the rolling; a rolling,
        // unbraked wheel's tread carries no x deflection.
        let mut du = [
            if braked {
                -vx - relax * u[0]
            } else {
                -u[0] / AIRBORNE_RELAXATION
            },
            -vy - relax * u[1],
        ];
        // Longitudinal: the brake's force from the tread (the tread holds a braked vehicle at
        // rest), at most its capacity; then drive and rolling resistance.
        let mut fx = 0.0;
        if braked {
            let limit = action.brake_capacity;
            fx = (k * u[0] + damping * du[0]).clamp(-limit, limit);
            if k * u[0].abs() >= limit && u[0] * du[0] >= 0.0 {
                du[0] = -(u[0] - u[0].signum() * limit / k) / YIELD_RELAXATION;
            }
        }
        fx += action.drive
            - self.rolling_resistance * fz * vx / vx.abs().max(ROLLING_RESISTANCE_SPEED);
        // Lateral: what the combined-slip law leaves of the friction.
        let mut sliding = false;
        let available = match self.combined {
            CombinedSlip::BrakingPriority => {
                if fx.abs() >= friction {
                    fx = fx.signum() * friction;
                    sliding = true;
                }
                (friction * friction - fx * fx).max(0.0).sqrt()
            }
            CombinedSlip::Circle | CombinedSlip::NicolasComstock => friction,
        };
        let fy_lin = k * u[1] + damping * du[1];
        let (fy_mag, at_limit) = self.lateral(fy_lin.abs(), available);
        let mut fy = fy_lin.signum() * fy_mag;
        sliding |= at_limit;
        // Elasto-plastic lateral deflection: at its limit the tread slides, its deflection
        // stops growing and returns to the limit if past it.
        let yield_force = self.lateral_yield(available);
        if k * u[1].abs() >= yield_force && u[1] * du[1] >= 0.0 {
            du[1] = -(u[1] - u[1].signum() * yield_force / k) / YIELD_RELAXATION;
        }
        if self.combined == CombinedSlip::NicolasComstock {
            let slip_stiffness = [
                self.longitudinal_stiffness.map_or(c_alpha, |c| c * fz),
                c_alpha,
            ];
            let pure_saturated = fx.abs() >= friction;
            (fx, fy) = combine_pure_slip_forces(fx, fy, fy_lin, slip_stiffness, friction);
            sliding |= pure_saturated;
        }
        if self.combined != CombinedSlip::BrakingPriority {
            let total = fx.hypot(fy);
            if total > friction {
                fx *= friction / total;
                fy *= friction / total;
                sliding = true;
            }
        }
        TyreForce {
            force: [fx, fy],
            deflection_rate: du,
            sliding,
        }
    }

    /// A locked wheel: the tread dragged both ways by the patch's slip, the resultant at
    /// most mu Fz (then sliding against the slip), whatever the law.
    #[allow(clippy::too_many_arguments)]
    fn locked(
        &self,
        k: Real,
        damping: Real,
        relax: Real,
        friction: Real,
        vx: Real,
        vy: Real,
        u: [Real; 2],
    ) -> TyreForce {
        let mut du = [-vx - relax * u[0], -vy - relax * u[1]];
        let mut f = [k * u[0] + damping * du[0], k * u[1] + damping * du[1]];
        let f_lin = f[0].hypot(f[1]);
        let sliding = f_lin >= friction;
        if sliding {
            f = [f[0] * friction / f_lin, f[1] * friction / f_lin];
        }
        let un = u[0].hypot(u[1]);
        if k * un >= friction && un > 0.0 {
            let dir = [u[0] / un, u[1] / un];
            let radial = du[0] * dir[0] + du[1] * dir[1];
            let back = (un - friction / k) / YIELD_RELAXATION;
            let keep = radial.min(0.0) - back;
            du = [
                du[0] - (radial - keep) * dir[0],
                du[1] - (radial - keep) * dir[1],
            ];
        }
        TyreForce {
            force: f,
            deflection_rate: du,
            sliding,
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A wheel neither braked nor driven (shared with combined_slip.rs's tests).
    pub(crate) const FREE: WheelAction = WheelAction {
        locked: false,
        brake_capacity: 0.0,
        drive: 0.0,
    };

    /// The steady deflection of a free-rolling tyre at speed vx and lateral velocity vy.
    pub(crate) fn steady(t: &Tyre, vx: Real, vy: Real) -> [Real; 2] {
        [0.0, -vy * t.relaxation_length / vx.abs()]
    }

    /// The linear tyre's slope is c Fz on every road (1 per 10 deg: Fz at 10 deg), and the
    /// road's friction only caps it: on mu 0.4 it saturates at 4 deg, on 0.8 at 8 deg (issue
    /// 19: the slope scaled with mu, 24 % soft at 0.76).
    #[test]
    fn linear_tyre_has_a_slope_of_c_fz_whatever_the_road_and_saturates_at_mu_fz() {
        let t = Tyre::default();
        let (fz, vx) = (4000.0, 20.0);
        let c = fz / 10f64.to_radians();
        for mu in [0.4, 0.8, 1.0] {
            for alpha_deg in [0.5, 2.0, 0.99 * 10.0 * mu] {
                let vy = vx * (alpha_deg as Real).to_radians().tan();
                let out = t.force(fz, fz, mu, vx, vy, steady(&t, vx, vy), &FREE);
                let expected = -c * (alpha_deg as Real).to_radians().tan();
                assert!(
                    (out.force[1] - expected).abs() < 1e-9 * c,
                    "mu {mu}, {alpha_deg} deg: {out:?}"
                );
                assert!(out.deflection_rate[1].abs() < 1e-12 && !out.sliding);
            }
            let vy = vx * 0.5;
            let out = t.force(fz, fz, mu, vx, vy, steady(&t, vx, vy), &FREE);
            assert!((out.force[1] + mu * fz).abs() < 1e-9 && out.sliding);
        }
        // The law before 2026-11, kept by name: mu Fz at the saturation angle on every road.
        let old = Tyre {
            model: TyreModel::LinearFrictionScaled {
                saturation_angle: 10f64.to_radians(),
            },
            ..Tyre::default()
        };
        let vy = vx * 2f64.to_radians().tan();
        let out = old.force(fz, fz, 0.5, vx, vy, steady(&old, vx, vy), &FREE);
        let expected = -0.5 * fz / 10f64.to_radians() * 2f64.to_radians().tan();
        assert!((out.force[1] - expected).abs() < 1e-9 * fz, "{out:?}");
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
        let k = t.cornering_stiffness(fz, mu, fz) / t.relaxation_length;
        let v = (15.0f64.powi(2) + 25.0).sqrt();
        let u = [-15.0 / v * mu * fz / k, -5.0 / v * mu * fz / k];
        let out = t.force(fz, fz, mu, 15.0, 5.0, u, &locked);
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
        let k = t.cornering_stiffness(4000.0, 0.8, 4000.0) / t.relaxation_length;
        let out = t.force(4000.0, 4000.0, 0.8, 20.0, 0.0, [-2000.0 / k, 0.0], &braked);
        assert!((out.force[0] + 1000.0).abs() < 1e-9, "{out:?}");
        // Once the tread reaches the capacity it stops deflecting further.
        let out = t.force(4000.0, 4000.0, 0.8, 20.0, 0.0, [-1000.0 / k, 0.0], &braked);
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
        let (fz, vx) = (4000.0, 20.0);
        // B C Fz on every road (Pacejka's similarity), the peak mu Fz.
        for mu in [0.5, 0.9] {
            let vy = vx * 0.001;
            let out = t.force(fz, fz, mu, vx, vy, steady(&t, vx, vy), &FREE);
            let c_alpha = 10.0 * 1.9 * fz;
            assert!(
                (out.force[1] / (-c_alpha * 0.001) - 1.0).abs() < 1e-3,
                "{out:?}"
            );
            let mut peak: Real = 0.0;
            for k in 1..400 {
                let vy = vx * (k as Real * 0.1).to_radians().tan();
                peak = peak.max(-t.force(fz, fz, mu, vx, vy, steady(&t, vx, vy), &FREE).force[1]);
            }
            assert!((peak / (mu * fz) - 1.0).abs() < 1e-3, "{peak}");
        }
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

    /// A braked wheel delivers its brake's force under every law (issue 19: the Magic Formula
    /// passed the brake's force through its lateral curve and braked at 2.857 m/s^2 for a
    /// demand of 3); in a turn, the lateral force is what the friction ellipse leaves
    /// (braking priority) or both share the circle.
    #[test]
    fn a_braked_wheel_delivers_its_brake_force_and_the_lateral_takes_what_is_left() {
        let (fz, mu, vx) = (4000.0, 0.8, 20.0);
        let friction = mu * fz;
        let braked = |capacity: Real| WheelAction {
            locked: false,
            brake_capacity: capacity,
            drive: 0.0,
        };
        let mf = TyreModel::MagicFormula {
            b: 10.0,
            c: 1.9,
            e: 0.97,
        };
        for model in [Tyre::default().model, mf] {
            for combined in [CombinedSlip::BrakingPriority, CombinedSlip::Circle] {
                let t = Tyre {
                    model: model.clone(),
                    combined,
                    ..Tyre::default()
                };
                let k = t.cornering_stiffness(fz, mu, fz) / t.relaxation_length;
                // Straight: the tread past the capacity gives the capacity.
                for capacity in [0.3 * friction, 0.5 * friction, friction] {
                    let out = t.force(
                        fz,
                        fz,
                        mu,
                        vx,
                        0.0,
                        [-2.0 * friction / k, 0.0],
                        &braked(capacity),
                    );
                    assert!(
                        (out.force[0] + capacity).abs() < 1e-9 * friction,
                        "{model:?} {combined:?} {capacity}: {out:?}"
                    );
                }
                // In a turn at 12 deg (past the linear tyre's saturation), braked at 0.6 mu Fz.
                let vy = vx * 12f64.to_radians().tan();
                let out = t.force(
                    fz,
                    fz,
                    mu,
                    vx,
                    vy,
                    [-friction / k, steady(&t, vx, vy)[1]],
                    &braked(0.6 * friction),
                );
                let (fx, fy) = (out.force[0], out.force[1]);
                match combined {
                    CombinedSlip::BrakingPriority => {
                        assert!((fx + 0.6 * friction).abs() < 1e-9 * friction, "{out:?}");
                        assert!(fy.abs() <= 0.8 * friction * (1.0 + 1e-12), "{out:?}");
                    }
                    CombinedSlip::Circle | CombinedSlip::NicolasComstock => {
                        assert!(fx.hypot(fy) <= friction * (1.0 + 1e-12), "{out:?}");
                    }
                }
            }
        }
        // The linear tyre saturates laterally exactly at the ellipse's 0.8 mu Fz.
        let t = Tyre::default();
        let k = t.cornering_stiffness(fz, mu, fz) / t.relaxation_length;
        let vy = vx * 12f64.to_radians().tan();
        let out = t.force(
            fz,
            fz,
            mu,
            vx,
            vy,
            [-friction / k, steady(&t, vx, vy)[1]],
            &braked(0.6 * friction),
        );
        assert!(
            (out.force[1] + 0.8 * friction).abs() < 1e-9 * friction && out.sliding,
            "{out:?}"
        );
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
        let c = t.cornering_stiffness(fz, mu, fz);
        let vy = vx * 2f64.to_radians().tan();
        // Integrate the deflection after the step (from a straight-running tread) exactly
        // enough: explicit Euler at 1 us over 3 time constants.
        let tau = t.relaxation_length / vx;
        let (mut u, h) = ([0.0, 0.0], 1e-6);
        let first = t.force(fz, fz, mu, vx, vy, u, &FREE);
        assert!(
            first.force[1].abs() < 1e-9,
            "no jump at the step: {first:?}"
        );
        let steps = (tau / h).round() as usize;
        for _ in 0..steps {
            let out = t.force(fz, fz, mu, vx, vy, u, &FREE);
            u[1] += h * out.deflection_rate[1];
        }
        let after_tau = t.force(fz, fz, mu, vx, vy, u, &FREE).force[1];
        let steady = -c * 2f64.to_radians().tan();
        let expected = steady * (1.0 - (-1.0f64).exp());
        assert!(
            (after_tau / expected - 1.0).abs() < 1e-3,
            "{after_tau} vs {expected}"
        );
        // At rest: a lateral velocity acts through the critical damping 2 sqrt(k m).
        let k = c / t.relaxation_length;
        let out = t.force(fz, fz, mu, 0.0, 0.01, [0.0, 0.0], &FREE);
        let critical = 2.0 * (k * fz / GRAVITY).sqrt();
        assert!(
            (out.force[1] + critical * 0.01).abs() < 1e-9 * critical,
            "{out:?}"
        );
    }

    #[test]
    fn without_load_there_is_no_force() {
        let out = Tyre::default().force(0.0, 4000.0, 0.8, 10.0, 3.0, [0.01, 0.02], &FREE);
        assert_eq!(out.force, [0.0, 0.0]);
        assert!(out.deflection_rate[0] < 0.0 && out.deflection_rate[1] < 0.0);
    }
}
