//! Wheels: where they sit on the body and how they are sprung.
//!
//! Each wheel is a vertical spring-damper between the body and a massless wheel whose tyre
//! touches the ground below its centre. The wheel's centre is a point fixed in the body frame
//! (its position at static ride height); the tyre's normal load is
//!
//! `Fz = max(0, F0 + k (R - h) + c d(R - h)/dt)`,
//!
//! with `h` the centre's height above the ground along the ground normal, `R` the tyre
//! radius, `F0` the static load (the spring's preload at static ride height), `k` the wheel
//! rate and `c` the damping. A wheel whose centre is higher than `R + F0 / k` carries nothing.
//! Load transfer, roll and pitch then follow from the 3-D body.

use crate::error::{require_finite, Error, Place, Result};
use crate::math::{Point, Real};

/// Standard gravity (m/s^2), ISO 80000-3.
pub const GRAVITY: Real = 9.80665;

/// Default natural frequency of a wheel's spring with its share of the sprung mass (Hz):
/// 1.3 Hz, inside the 1.0-1.5 Hz of passenger-car ride frequencies (Gillespie, Fundamentals
/// of Vehicle Dynamics, SAE 1992, ch. 5).
pub const DEFAULT_NATURAL_FREQUENCY: Real = 1.3;
/// Default damping ratio of a wheel's spring-damper: 0.3, inside the 0.2-0.4 of passenger
/// cars (Gillespie, ch. 5).
pub const DEFAULT_DAMPING_RATIO: Real = 0.3;
/// Highest natural frequency a wheel's spring may have with its share of the sprung mass
/// (Hz): 20 Hz. Cars ride at 1.0-1.5 Hz, sports cars and trucks at up to 2.5-3 Hz (Gillespie,
/// ch. 5), and a tyre alone, with no suspension (about 200 kN/m under a quarter of a 1.6 t
/// car), at about 3.5 Hz: 20 Hz is stiffer than any road vehicle. The integration's sub-steps
/// shrink with the stiffest mode ([`crate::motion`]), so this bound is what keeps the work per
/// simulated second bounded.
pub const MAX_NATURAL_FREQUENCY: Real = 20.0;
/// Highest damping ratio a wheel's spring-damper may have: 5. Cars are damped at 0.2-0.4
/// (Gillespie, ch. 5) and 1 is critical (no overshoot); at 5 the damper alone holds the wheel
/// (it takes 10 times the natural period to return halfway). As for the frequency, the bound
/// keeps the sub-steps it asks for (at most 6 per ms at 20 Hz and 5) bounded.
pub const MAX_DAMPING_RATIO: Real = 5.0;

/// One wheel of a vehicle.
#[derive(Clone, Debug, PartialEq)]
pub struct WheelSpec {
    /// Wheel centre at static ride height, body frame (m from the CG; x forward, y left, z up).
    pub center: Point,
    /// Tyre radius (m), > 0.
    pub radius: Real,
    /// Whether the steering input turns it.
    pub steerable: bool,
    /// Normal load at static ride height (N), > 0: the spring's preload there.
    pub static_load: Real,
    /// Wheel rate (N/m), > 0.
    pub spring_rate: Real,
    /// Damping (N s/m), >= 0.
    pub damping: Real,
}

impl WheelSpec {
    /// A wheel whose spring and damper come from its static load: the sprung mass on it,
    /// m = static_load / g, oscillates at `natural_frequency` Hz with `damping_ratio`:
    /// k = m (2 pi f)^2, c = 2 zeta sqrt(k m).
    pub fn sprung(
        center: Point,
        radius: Real,
        steerable: bool,
        static_load: Real,
        natural_frequency: Real,
        damping_ratio: Real,
    ) -> Result<WheelSpec> {
        require_finite("natural_frequency", natural_frequency)?;
        require_finite("damping_ratio", damping_ratio)?;
        check_natural_frequency("natural_frequency", natural_frequency)?;
        check_damping_ratio("damping_ratio", damping_ratio)?;
        let m = static_load / GRAVITY;
        let omega = 2.0 * std::f64::consts::PI * natural_frequency;
        let k = m * omega * omega;
        let spec = WheelSpec {
            center,
            radius,
            steerable,
            static_load,
            spring_rate: k,
            damping: 2.0 * damping_ratio * (k * m).sqrt(),
        };
        spec.validate(0)?;
        Ok(spec)
    }

    /// Checks the numbers; errors are placed at wheel `index`.
    pub fn validate(&self, index: usize) -> Result<()> {
        self.check().map_err(|e| e.at(Place::Wheel(index)))
    }

    fn check(&self) -> Result<()> {
        let name = |what: &str| what.to_string();
        for (what, v) in [
            ("centre x", self.center.x),
            ("centre y", self.center.y),
            ("centre z", self.center.z),
            ("radius", self.radius),
            ("static_load", self.static_load),
            ("spring_rate", self.spring_rate),
            ("damping", self.damping),
        ] {
            require_finite(&name(what), v)?;
        }
        if self.radius <= 0.0 {
            return Err(Error::parameter(
                &name("radius"),
                self.radius,
                "a tyre radius must be > 0 m",
            ));
        }
        if self.static_load <= 0.0 {
            return Err(Error::parameter(
                &name("static_load"),
                self.static_load,
                "a wheel's static load must be > 0 N",
            ));
        }
        if self.spring_rate <= 0.0 {
            return Err(Error::parameter(
                &name("spring_rate"),
                self.spring_rate,
                "a spring rate must be > 0 N/m",
            ));
        }
        if self.damping < 0.0 {
            return Err(Error::parameter(
                &name("damping"),
                self.damping,
                "a damping coefficient must be >= 0 N s/m",
            ));
        }
        // Given as rates (N/m, N s/m) or as a frequency and a ratio, the same bounds.
        check_natural_frequency(&name("natural frequency"), self.natural_frequency())?;
        check_damping_ratio(&name("damping ratio"), self.damping_ratio())
    }

    /// The sprung mass on the wheel (kg): its static load over g.
    #[inline]
    pub fn sprung_mass(&self) -> Real {
        self.static_load / GRAVITY
    }

    /// Natural frequency of the spring with the wheel's sprung mass (Hz).
    pub fn natural_frequency(&self) -> Real {
        (self.spring_rate / self.sprung_mass()).sqrt() / (2.0 * std::f64::consts::PI)
    }

    /// Damping ratio of the spring-damper with the wheel's sprung mass: c / (2 sqrt(k m)).
    pub fn damping_ratio(&self) -> Real {
        self.damping / (2.0 * (self.spring_rate * self.sprung_mass()).sqrt())
    }

    /// The spring-damper's normal load (N, >= 0) at compression `compression` = R - h (m) and
    /// compression rate (m/s), with `extra` (N) from the wheel's anti-roll bar.
    #[inline]
    pub fn normal_load(&self, compression: Real, rate: Real, extra: Real) -> Real {
        (self.static_load + self.spring_rate * compression + self.damping * rate + extra).max(0.0)
    }
}

fn check_natural_frequency(name: &str, f: Real) -> Result<()> {
    // The slack lets a frequency given as exactly the bound pass its round trip through k.
    if f > 0.0 && f <= MAX_NATURAL_FREQUENCY * (1.0 + 1e-12) {
        return Ok(());
    }
    Err(Error::parameter(
        name,
        format!("{f} Hz"),
        &format!(
            "a wheel's natural frequency with its share of the weight must lie in (0, \
             {MAX_NATURAL_FREQUENCY}] Hz (about 1.3 Hz for a car, 2-3 Hz for a truck; a tyre \
             without suspension about 3.5 Hz); stiffer springs are no road vehicle's"
        ),
    ))
}

fn check_damping_ratio(name: &str, zeta: Real) -> Result<()> {
    if (0.0..=MAX_DAMPING_RATIO * (1.0 + 1e-12)).contains(&zeta) {
        return Ok(());
    }
    Err(Error::parameter(
        name,
        zeta,
        &format!(
            "a wheel's damping ratio must lie in [0, {MAX_DAMPING_RATIO}] (about 0.3 for a \
             car; 1 is critical damping)"
        ),
    ))
}

/// An anti-roll bar between two wheels of an axle: a torsion spring that loads the more
/// compressed wheel and unloads the other, `dF = k_bar (c_left - c_right)`, with `k_bar =
/// roll_stiffness / t^2` (t the wheels' lateral distance), so the axle's roll stiffness grows
/// by `roll_stiffness` (the springs give `k t^2 / 2`). A wheel hanging free (its spring
/// unloaded) holds the bar at its full droop, `c = -F0 / k`.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct AntiRollBar {
    /// The wheel on the left (index into the vehicle's wheels).
    pub left: usize,
    /// The wheel on the right.
    pub right: usize,
    /// Roll stiffness the bar adds to its axle (N m/rad), >= 0.
    pub roll_stiffness: Real,
}

impl AntiRollBar {
    /// The bar's rate at the wheels (N/m per m of compression difference) on `wheels`.
    pub fn rate(&self, wheels: &[WheelSpec]) -> Real {
        let t = wheels[self.left].center.y - wheels[self.right].center.y;
        self.roll_stiffness / (t * t)
    }

    /// Checks the bar on `wheels`: two wheels apart across the vehicle, the left one on the
    /// left, a stiffness that keeps each wheel's roll frequency (its spring plus twice the
    /// bar's rate, with its sprung mass) within [`MAX_NATURAL_FREQUENCY`]. `index` names the
    /// bar in errors.
    pub fn validate(&self, index: usize, wheels: &[WheelSpec]) -> Result<()> {
        let n = wheels.len();
        if self.left >= n || self.right >= n || self.left == self.right {
            return Err(Error::invalid(format!(
                "anti-roll bar {index} joins wheels {} and {}: give two different wheels of \
                 the vehicle's {n}",
                self.left, self.right
            )));
        }
        require_finite(
            &format!("anti-roll bar {index} roll stiffness"),
            self.roll_stiffness,
        )?;
        if self.roll_stiffness < 0.0 {
            return Err(Error::parameter(
                &format!("anti-roll bar {index} roll stiffness"),
                format!("{} N m/rad", self.roll_stiffness),
                "it must be >= 0",
            ));
        }
        let (l, r) = (&wheels[self.left], &wheels[self.right]);
        if l.center.y - r.center.y <= 0.05 {
            return Err(Error::invalid(format!(
                "anti-roll bar {index}: wheel {} (left, y = {:.3} m) must lie left of wheel {} \
                 (right, y = {:.3} m) and apart from it (y is left, from the CG)",
                self.left, l.center.y, self.right, r.center.y
            )));
        }
        let rate = self.rate(wheels);
        for w in [l, r] {
            let f = ((w.spring_rate + 2.0 * rate) / w.sprung_mass()).sqrt()
                / (2.0 * std::f64::consts::PI);
            if f > MAX_NATURAL_FREQUENCY * (1.0 + 1e-12) {
                return Err(Error::invalid(format!(
                    "anti-roll bar {index}: {:.0} N m/deg makes its wheels roll at {f:.1} Hz on \
                     their springs, past the {MAX_NATURAL_FREQUENCY} Hz a wheel's spring may \
                     have (measured cars' bars: 225-590 N m/deg)",
                    self.roll_stiffness * std::f64::consts::PI / 180.0
                )));
            }
        }
        Ok(())
    }
}

/// Static loads (N) of supports at body-frame `xy` (m from the CG) carrying `weight` N at the
/// CG and, with `towed`, a load (N) at a point (a trailer on the vehicle's hitch), on level
/// ground: the linear distribution `F_i = a + b x_i + c y_i` with the least sum of squares
/// that balances the forces and both moments (each axle its share; a load behind the rear
/// axle unloads the front). Every support must carry a positive load.
pub fn static_loads_towing(
    xy: &[[Real; 2]],
    weight: Real,
    towed: Option<([Real; 2], Real)>,
) -> Result<Vec<Real>> {
    let loads = distribute(xy, weight, towed)?;
    check_carried(&loads, towed.is_some())?;
    Ok(loads)
}

/// [`static_loads_towing`]'s distribution without the check that every support pushes.
fn distribute(
    xy: &[[Real; 2]],
    weight: Real,
    towed: Option<([Real; 2], Real)>,
) -> Result<Vec<Real>> {
    use nalgebra::{Matrix3, Vector3};
    if xy.len() < 3 {
        return Err(Error::invalid(format!(
            "a vehicle on the ground needs at least 3 wheels (got {})",
            xy.len()
        )));
    }
    // F_i = a + b x_i + c y_i minimises |F| subject to sum F = W + P, sum F x = P px,
    // sum F y = P py.
    let mut m = Matrix3::zeros();
    for p in xy {
        let row = Vector3::new(1.0, p[0], p[1]);
        m += row * row.transpose();
    }
    let rhs = match towed {
        Some((p, load)) => Vector3::new(weight + load, load * p[0], load * p[1]),
        None => Vector3::new(weight, 0.0, 0.0),
    };
    let coef = m.try_inverse().ok_or_else(|| {
        Error::invalid(
            "the wheels are in a line: they cannot carry a vehicle (check their positions)",
        )
    })? * rhs;
    Ok(xy
        .iter()
        .map(|p| coef.x + coef.y * p[0] + coef.z * p[1])
        .collect())
}

/// An error when a wheel's static load is not positive (it would lift off).
fn check_carried(loads: &[Real], towing: bool) -> Result<()> {
    if let Some((k, f)) = loads.iter().enumerate().find(|(_, f)| **f <= 0.0) {
        return Err(Error::invalid(format!(
            "the centre of gravity is not over the wheels: this wheel would carry {f:.1} N \
             (check the wheel positions, which are measured from the CG{})",
            if towing {
                ", and the trailer's load on the hitch"
            } else {
                ""
            }
        ))
        .at(Place::Wheel(k)));
    }
    Ok(())
}

/// [`static_loads_towing`] without a towed load: the weight alone.
pub fn static_loads(xy: &[[Real; 2]], weight: Real) -> Result<Vec<Real>> {
    static_loads_towing(xy, weight, None)
}

/// The static loads (N) of wheels at `xy` and of a coupling at `coupling` (a trailer's hitch
/// coupler or kingpin, body frame, m from the CG) carrying `weight` N together (and, with
/// `towed`, the load of a trailer this one tows in turn): the coupling is one more support of
/// [`static_loads_towing`]'s rule (at least three supports, not in a line), the only one that
/// may pull (a negative load: a tail-heavy trailer). Returns the wheels' loads and the
/// coupling's.
pub fn static_loads_coupled(
    xy: &[[Real; 2]],
    weight: Real,
    coupling: [Real; 2],
    towed: Option<([Real; 2], Real)>,
) -> Result<(Vec<Real>, Real)> {
    if xy.len() < 2 {
        return Err(Error::invalid(format!(
            "a coupled vehicle (a trailer) needs at least 2 wheels besides its coupling (got {})",
            xy.len()
        )));
    }
    let mut all = xy.to_vec();
    all.push(coupling);
    let mut loads = distribute(&all, weight, towed)?;
    // The coupling may pull down (a tail-heavy trailer lifts its tow ball); the wheels push.
    let at_coupling = loads.pop().expect("one load per support");
    check_carried(&loads, towed.is_some())?;
    Ok((loads, at_coupling))
}

/// Checks load groups of `n` wheels: 2 or more wheels each, existing, every wheel in one group
/// at most.
pub fn check_load_groups(groups: &[Vec<usize>], n: usize) -> Result<()> {
    for (g, set) in groups.iter().enumerate() {
        if set.len() < 2 {
            return Err(Error::invalid(format!(
                "load group {g} has {} wheel(s): a group shares the load of 2 or more",
                set.len()
            )));
        }
        for &k in set {
            if k >= n {
                return Err(Error::invalid(format!(
                    "load group {g} names wheel {k}, but the vehicle has {n} wheels"
                )));
            }
            let elsewhere = groups[..g].iter().any(|o| o.contains(&k));
            if elsewhere || set.iter().filter(|&&j| j == k).count() > 1 {
                return Err(Error::invalid(
                    "it is in two load groups: a wheel shares its load in one group",
                )
                .at(Place::Wheel(k)));
            }
        }
    }
    Ok(())
}

/// The static loads (N) of wheels at `xy` (body frame, m from the CG) carrying `weight` N
/// at rest, with everything a vehicle may have: `groups` of wheels sharing their load
/// equally (each one support at its wheels' mean position, its load split equally), a
/// `coupling` (a trailer's, which may pull) and a `towed` load on its hitch. Returns each
/// wheel's load and the coupling's (0 without one). Errors name the wheel of a non-finite
/// position.
pub fn wheel_loads(
    xy: &[[Real; 2]],
    groups: &[Vec<usize>],
    weight: Real,
    coupling: Option<[Real; 2]>,
    towed: Option<([Real; 2], Real)>,
) -> Result<(Vec<Real>, Real)> {
    check_load_groups(groups, xy.len())?;
    for (k, p) in xy.iter().enumerate() {
        require_finite("centre x", p[0])
            .and_then(|_| require_finite("centre y", p[1]))
            .map_err(|e| e.at(Place::Wheel(k)))?;
    }
    let mut supports: Vec<Vec<usize>> = groups.to_vec();
    for k in 0..xy.len() {
        if !groups.iter().any(|g| g.contains(&k)) {
            supports.push(vec![k]);
        }
    }
    let at: Vec<[Real; 2]> = supports
        .iter()
        .map(|s| {
            let n = s.len() as Real;
            let sum = s
                .iter()
                .fold([0.0, 0.0], |a, &k| [a[0] + xy[k][0], a[1] + xy[k][1]]);
            [sum[0] / n, sum[1] / n]
        })
        .collect();
    let (loads, share) = match coupling {
        Some(c) => static_loads_coupled(&at, weight, c, towed)?,
        None => (static_loads_towing(&at, weight, towed)?, 0.0),
    };
    let mut out = vec![0.0; xy.len()];
    for (s, load) in supports.iter().zip(loads) {
        for &k in s {
            out[k] = load / s.len() as Real;
        }
    }
    Ok((out, share))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_load_group_is_one_support_shared_equally() {
        // A tridem trailer on a kingpin: the group's three axles carry equal loads, the
        // kingpin its moment share about the group's middle; without groups the same bits as
        // static_loads_coupled.
        let xy = [
            [-3.0, 1.0],
            [-3.0, -1.0],
            [-4.3, 1.0],
            [-4.3, -1.0],
            [-5.6, 1.0],
            [-5.6, -1.0],
        ];
        let w = 2.4e5;
        let groups = vec![vec![0, 2, 4], vec![1, 3, 5]];
        let (loads, kingpin) = wheel_loads(&xy, &groups, w, Some([4.0, 0.0]), None).unwrap();
        assert!(loads.iter().all(|f| (f - loads[0]).abs() < 1e-9 * w));
        // moments about the group's middle (x = -4.3): kingpin (4.0 + 4.3) = W (0 + 4.3)
        assert!((kingpin - w * 4.3 / 8.3).abs() < 1e-9 * w);
        assert!((loads.iter().sum::<Real>() + kingpin - w).abs() < 1e-9 * w);
        let plain = wheel_loads(&xy, &[], w, Some([4.0, 0.0]), None).unwrap();
        assert_eq!(
            plain,
            static_loads_coupled(&xy, w, [4.0, 0.0], None).unwrap()
        );
        assert!(wheel_loads(&xy, &[vec![0, 2], vec![2, 4]], w, None, None).is_err());
        assert!(wheel_loads(&xy, &[vec![0]], w, None, None).is_err());
    }

    #[test]
    fn static_loads_are_the_axle_shares() {
        // CG 1.1 m behind the front axle, 1.6 m ahead of the rear axle, track 1.5 m.
        let (a, b, t) = (1.1, 1.6, 1.5);
        let xy = [[a, t / 2.0], [a, -t / 2.0], [-b, t / 2.0], [-b, -t / 2.0]];
        let w = 1500.0 * GRAVITY;
        let f = static_loads(&xy, w).unwrap();
        let front = w * b / (a + b) / 2.0;
        let rear = w * a / (a + b) / 2.0;
        for (k, expected) in [front, front, rear, rear].iter().enumerate() {
            assert!(
                (f[k] - expected).abs() < 1e-9 * w,
                "{k}: {} vs {expected}",
                f[k]
            );
        }
        assert!(static_loads(&[[2.0, 0.5], [2.0, -0.5], [1.0, 0.0]], w).is_err());
        assert!(static_loads(&[[1.0, 0.0], [0.0, 0.0], [-1.0, 0.0]], w).is_err());
    }

    #[test]
    fn sprung_wheels_have_the_natural_frequency_and_damping_ratio() {
        let w =
            WheelSpec::sprung(Point::new(1.0, 0.7, -0.25), 0.3, true, 4000.0, 1.3, 0.3).unwrap();
        let m = 4000.0 / GRAVITY;
        let f = (w.spring_rate / m).sqrt() / (2.0 * std::f64::consts::PI);
        assert!((f - 1.3).abs() < 1e-12);
        assert!((w.damping / (2.0 * (w.spring_rate * m).sqrt()) - 0.3).abs() < 1e-12);
        assert!(WheelSpec::sprung(Point::origin(), 0.3, true, 4000.0, -1.0, 0.3).is_err());
        let mut bad = w.clone();
        bad.spring_rate = -5.0;
        assert!(bad
            .validate(2)
            .unwrap_err()
            .to_string()
            .contains("wheel 2: spring_rate"));
    }
}
