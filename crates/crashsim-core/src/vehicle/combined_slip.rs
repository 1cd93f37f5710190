//! The combined-slip law of Nicolas and Comstock as Brach and Brach modified it
//! ([`CombinedSlip::NicolasComstock`](crate::vehicle::CombinedSlip::NicolasComstock)): the pure-slip forces Fx(s) and Fy(alpha) of a wheel
//! combined into the force at both slips, from crashsim's equivalent slips (docs/vehicle-model.md
//! states them). Forces in N, wheel axes (x forward, y left).

use crate::math::Real;

/// Largest longitudinal slip stiffness per unit load accepted (1 per unit slip): 100, five
/// times a stiff passenger tyre's (about 20 Fz per unit slip); there the equivalent slip of
/// any braking force is at most mu / 100 (0.02 at mu 2).
pub const MAX_LONGITUDINAL_STIFFNESS: Real = 100.0;

/// The [`CombinedSlip::NicolasComstock`](crate::vehicle::CombinedSlip::NicolasComstock) law's forces (N, wheel axes) from crashsim's inputs:
/// the longitudinal demand `fx` (N, signed; capped at the friction, the pure-slip curve's
/// peak, it is Fx(s)), the law's lateral force `fy` with all the `friction` (N, signed:
/// Fy(alpha)), the tread's linear lateral force `fy_lin` (N; over C_alpha it is tan(alpha))
/// and `slip_stiffness` [Cs N per unit slip, C_alpha N/rad].
pub(crate) fn combine_pure_slip_forces(
    fx: Real,
    fy: Real,
    fy_lin: Real,
    slip_stiffness: [Real; 2],
    friction: Real,
) -> (Real, Real) {
    let fx0 = fx.clamp(-friction, friction);
    let [cs, c_alpha] = slip_stiffness;
    nicolas_comstock(fx0, fy, fy_lin.abs() / c_alpha, cs, c_alpha)
}

/// The modified Nicolas-Comstock combination (Brach and Brach, SAE 2000-01-0357, 2009-01-0102,
/// 2011-01-0094) of the pure-slip forces: `fx0` = Fx(s) (N, signed, |fx0| <= mu Fz), `fy0` =
/// Fy(alpha) (N, signed), `tan_alpha` = tan(alpha) >= 0, the slip stiffnesses `cs` (N per unit
/// slip) and `c_alpha` (N/rad) > 0; returns the combined (Fx, Fy) (N, the signs of fx0 and
/// fy0). With s = |fx0| / cs (the equivalent slip, at most 1) and F = |Fx(s)| |Fy(a)| /
/// hypot(s |Fy(a)|, |Fx(s)| tan a):
///
/// `Fx = F hypot(s C_alpha, (1 - s) cos(a) |Fx(s)|) / C_alpha`,
/// `Fy = F hypot((1 - s) cos(a) |Fy(a)|, sin(a) Cs) / (Cs cos(a))`,
///
/// Nicolas and Comstock's `F s` and `F tan a` (the force along the slip vector (s, tan a))
/// times Brach and Brach's factors, which give Fx(s) as alpha -> 0 and Fy(alpha) as s -> 0.
/// crashsim's wheels have no spin: the slip s is the one at which the linear pure-slip curve
/// `Cs s` gives the braking demand (the brake force the tread delivers, at most its capacity,
/// plus drive, less rolling resistance), and tan a is the tread's lateral force over its
/// cornering stiffness (in steady rolling exactly |vy / vx|).
pub fn nicolas_comstock(
    fx0: Real,
    fy0: Real,
    tan_alpha: Real,
    cs: Real,
    c_alpha: Real,
) -> (Real, Real) {
    // The pure-slip limits the modification was made for (the formula's 0 / 0 there).
    if tan_alpha == 0.0 {
        return (fx0, 0.0);
    }
    if fx0 == 0.0 {
        return (0.0, fy0);
    }
    let (x0, y0) = (fx0.abs(), fy0.abs());
    let s = (x0 / cs).min(1.0);
    let cos = 1.0 / tan_alpha.hypot(1.0);
    let sin = tan_alpha * cos;
    let f = x0 * y0 / (s * y0).hypot(x0 * tan_alpha);
    let fx = f * (s * c_alpha).hypot((1.0 - s) * cos * x0) / c_alpha;
    let fy = f * ((1.0 - s) * cos * y0).hypot(sin * cs) / (cs * cos);
    (fx.copysign(fx0), fy.copysign(fy0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vehicle::tyre::{
        CombinedSlip, Tyre, TyreModel, WheelAction, DEFAULT_CORNERING_COEFFICIENT,
    };

    use crate::vehicle::tyre::tests::{steady, FREE};

    /// The Nicolas-Comstock tyre with the given law and longitudinal stiffness.
    fn nicolas_comstock_tyre(model: TyreModel, longitudinal_stiffness: Option<Real>) -> Tyre {
        let t = Tyre {
            model,
            combined: CombinedSlip::NicolasComstock,
            longitudinal_stiffness,
            ..Tyre::default()
        };
        t.validate().unwrap();
        t
    }

    const MF: TyreModel = TyreModel::MagicFormula {
        b: 10.0,
        c: 1.9,
        e: 0.97,
    };

    /// Brach and Brach's modification gives the pure-slip forces back: at alpha = 0 the brake
    /// force (its demand, Fx(s)), at s = 0 (a free wheel) the law's lateral force Fy(alpha),
    /// both to rounding. Fy is continuous there (a braking force of 1e-9 Fz changes it by
    /// less than 1e-8 of it); Fx is not: as alpha -> 0 with Fy(alpha) = C_alpha tan(alpha) it
    /// tends to `Fx(s) hypot(s C_alpha, (1 - s) Fx(s)) / hypot(s C_alpha, Fx(s))` (to 1e-8 at
    /// 1e-9 rad), 0.933 Fx(s) at the default tyre's largest equivalent slip (s = 0.14, mu 0.8).
    #[test]
    fn nicolas_comstock_gives_the_pure_slip_forces_back() {
        let (fz, mu, vx) = (4000.0, 0.8, 20.0);
        let friction = mu * fz;
        for model in [Tyre::default().model, MF] {
            for cs in [None, Some(20.0)] {
                let t = nicolas_comstock_tyre(model.clone(), cs);
                let reference = Tyre {
                    model: model.clone(),
                    ..Tyre::default()
                };
                let k = t.cornering_stiffness(fz, mu, fz) / t.relaxation_length;
                for fraction in [0.1, 0.5, 1.0] {
                    let braked = WheelAction {
                        locked: false,
                        brake_capacity: fraction * friction,
                        drive: 0.0,
                    };
                    let u = [-2.0 * friction / k, 0.0];
                    let out = t.force(fz, fz, mu, vx, 0.0, u, &braked);
                    assert!(
                        (out.force[0] + fraction * friction).abs() < 1e-12 * friction
                            && out.force[1] == 0.0,
                        "{model:?} {cs:?} {fraction}: {out:?}"
                    );
                }
                for alpha_deg in [0.5, 3.0, 7.0, 15.0, 30.0] {
                    let vy = vx * (alpha_deg as Real).to_radians().tan();
                    let u = steady(&t, vx, vy);
                    let out = t.force(fz, fz, mu, vx, vy, u, &FREE);
                    let pure = reference.force(fz, fz, mu, vx, vy, u, &FREE);
                    assert!(
                        out.force[0] == 0.0
                            && (out.force[1] - pure.force[1]).abs() < 1e-12 * friction
                            && out.sliding == pure.sliding,
                        "{model:?} {cs:?} {alpha_deg}: {out:?} vs {pure:?}"
                    );
                }
            }
        }
        let (cs, c_alpha) = (5.0 * fz, 5.7 * fz);
        let x0 = 0.5 * friction;
        let (fx, fy) = nicolas_comstock(-x0, 1e-9 * c_alpha, 1e-9, cs, c_alpha);
        let slip = x0 / cs;
        let limit = x0 * (slip * c_alpha).hypot((1.0 - slip) * x0) / (slip * c_alpha).hypot(x0);
        assert!((fx / -limit - 1.0).abs() < 1e-8 && fy.abs() < 1e-8 * friction);
        let c = DEFAULT_CORNERING_COEFFICIENT * fz;
        let slip = friction / c;
        let gap = (slip * c).hypot((1.0 - slip) * friction) / (slip * c).hypot(friction);
        assert!((gap - 0.933).abs() < 1e-3, "{gap}");
        let fy0 = 0.7 * friction;
        let (fx, fy) = nicolas_comstock(-1e-9 * fz, fy0, 0.1, cs, c_alpha);
        assert!((fy / fy0 - 1.0).abs() < 1e-8 && fx.abs() < 1e-8 * friction);
    }

    /// The resultant never exceeds mu Fz (to 1e-12): over slip angles 0.5-40 deg and braking
    /// demands 0.1-1 mu Fz, both laws, both stiffnesses. The formula alone does: at the
    /// linear tyre's saturation (tan a = s = mu / c, Cs = C_alpha) under full braking it gives
    /// `mu Fz sqrt(((1 + (1 - s)^2 cos^2 a) + (1 + (1 - s)^2)) / 2)`, 1.3165 mu Fz at mu 0.8.
    #[test]
    fn nicolas_comstock_never_exceeds_the_friction() {
        let (fz, mu, vx) = (4000.0, 0.8, 20.0);
        let friction = mu * fz;
        for model in [Tyre::default().model, MF] {
            for cs in [None, Some(20.0)] {
                let t = nicolas_comstock_tyre(model.clone(), cs);
                let k = t.cornering_stiffness(fz, mu, fz) / t.relaxation_length;
                for fraction in [0.1, 0.3, 0.6, 0.9, 1.0] {
                    let braked = WheelAction {
                        locked: false,
                        brake_capacity: fraction * friction,
                        drive: 0.0,
                    };
                    for alpha_deg in [0.5, 2.0, 5.0, 8.0, 12.0, 20.0, 40.0] {
                        let vy = vx * (alpha_deg as Real).to_radians().tan();
                        let u = [-2.0 * friction / k, steady(&t, vx, vy)[1]];
                        let out = t.force(fz, fz, mu, vx, vy, u, &braked);
                        let total = out.force[0].hypot(out.force[1]);
                        assert!(
                            total <= friction * (1.0 + 1e-12) && out.force[0] < 0.0,
                            "{model:?} {cs:?} {fraction} {alpha_deg}: {out:?}"
                        );
                    }
                }
            }
        }
        let c = DEFAULT_CORNERING_COEFFICIENT * fz;
        let slip = friction / c;
        let (fx, fy) = nicolas_comstock(-friction, -friction, slip, c, c);
        let cos2 = 1.0 / (1.0 + slip * slip);
        let one_less = (1.0 - slip).powi(2);
        let expected = (((1.0 + one_less * cos2) + (1.0 + one_less)) / 2.0).sqrt();
        let raw = fx.hypot(fy) / friction;
        assert!(
            (raw - expected).abs() < 1e-12 && (raw - 1.3165).abs() < 1e-4,
            "{raw}"
        );
    }

    /// Nicolas and Comstock's force lies along the slip vector (s, tan a); Brach and Brach's
    /// factors turn it by `sqrt((1 + (1 - s)^2 cos^2 a) / (1 + (1 - s)^2))` in Fx / Fy. With
    /// Cs = C_alpha and linear pure-slip forces (below saturation) Fx / Fy is exactly
    /// (s / tan a) times that (to 1e-12), within 0.2 deg of the slip vector over s <= 0.15,
    /// a <= 10 deg; at s = 1 (Fx(s) = Cs) it is along the slip vector for any curves.
    #[test]
    fn nicolas_comstock_force_follows_the_slip_vector() {
        let c = 4000.0 * DEFAULT_CORNERING_COEFFICIENT;
        let mut worst: Real = 0.0;
        for slip in [0.01, 0.05, 0.1, 0.15] {
            for alpha_deg in [0.5, 2.0, 5.0, 10.0] {
                let tan = (alpha_deg as Real).to_radians().tan();
                let (fx, fy) = nicolas_comstock(-c * slip, -c * tan, tan, c, c);
                let cos2 = 1.0 / (1.0 + tan * tan);
                let one_less = (1.0 - slip).powi(2);
                let turn = ((1.0 + one_less * cos2) / (1.0 + one_less)).sqrt();
                let ratio = fx / fy / (slip / tan * turn);
                assert!((ratio - 1.0).abs() < 1e-12, "{slip} {alpha_deg}: {ratio}");
                let off = (fy.atan2(fx) - (-tan).atan2(-slip)).abs().to_degrees();
                worst = worst.max(off);
            }
        }
        assert!(worst < 0.2, "{worst} deg");
        for (fx0, fy0, tan) in [(-3000.0, -2500.0, 0.3), (-1000.0, 2000.0, 1.2)] {
            let (fx, fy) = nicolas_comstock(fx0, fy0, tan, fx0.abs(), 20000.0);
            assert!(
                (fy / fx - fy0.signum() * fx0.signum() * tan).abs() < 1e-12,
                "{fx} {fy}"
            );
        }
    }

    /// In a turn the Nicolas-Comstock wheel brakes less than its demand (braking priority
    /// keeps it): sliding sideways (the tread at its yield, tan a = mu / c) with a demand of
    /// 0.6 mu Fz the linear tyre gives (-0.5729, 0.9590) mu Fz, 1.117 mu Fz, capped to
    /// (-0.5128, 0.8585) mu Fz (closed form, to 1e-4).
    #[test]
    fn a_nicolas_comstock_wheel_in_a_turn_brakes_less_than_its_demand() {
        let (fz, mu, vx) = (4000.0, 0.8, 20.0);
        let friction = mu * fz;
        let t = nicolas_comstock_tyre(Tyre::default().model, None);
        let k = t.cornering_stiffness(fz, mu, fz) / t.relaxation_length;
        let braked = WheelAction {
            locked: false,
            brake_capacity: 0.6 * friction,
            drive: 0.0,
        };
        let vy = vx * 12f64.to_radians().tan();
        let u = [-friction / k, -friction / k];
        let out = t.force(fz, fz, mu, vx, vy, u, &braked);
        let [fx, fy] = [out.force[0] / friction, out.force[1] / friction];
        assert!(
            (fx + 0.5128).abs() < 1e-4 && (fy + 0.8585).abs() < 1e-4 && out.sliding,
            "{fx} {fy}"
        );
        assert!(Tyre {
            longitudinal_stiffness: Some(20.0),
            ..Tyre::default()
        }
        .validate()
        .is_err());
        for bad in [0.0, -1.0, 101.0, Real::NAN] {
            assert!(Tyre {
                combined: CombinedSlip::NicolasComstock,
                longitudinal_stiffness: Some(bad),
                ..Tyre::default()
            }
            .validate()
            .is_err());
        }
    }
}
