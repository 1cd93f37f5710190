//! The steering linkage: from the driver's steering input to each steered wheel's road-wheel
//! angle (rad, about the body's z axis, + to the left).
//!
//! The driver's input is the steering-wheel angle (divided by the steering ratio) or the
//! road-wheel angle `delta` of the linkage's reference wheel, on the steered axle farthest
//! from the turn centre's line (x_s): by default the wheel on the outside of the turn, as the
//! reconstruction programs steer (PC-Crash's 15 mph run of a 2004 sedan loops on the radius
//! of its outer front wheel at 360 deg / 15.9; see docs/vehicle-model.md), or a virtual wheel
//! at the axle's centre (the single-track model's angle). The turn centre lies on the line
//! `x = x_ref` of the wheels that do not steer (their mean x; the rear axle of a car); each
//! steered wheel at `(x_i, y_i)` turns to
//!
//! `tan(delta_i) = (x_i - x_ref) tan(delta) / ((x_s - x_ref) + a (y_r - y_i) tan(delta))`,
//!
//! `y_r` the reference's y (the outer wheel's, or the wheels' centre line) and `a` the
//! Ackermann fraction: 1 points every wheel at the turn centre (full Ackermann: the inner
//! wheel turns more, `cot(delta_o) - cot(delta_i) = track / wheelbase`), 0 turns the reference
//! axle's wheels alike (parallel steer). Between, the inner-outer difference at small angles
//! is `a` times Ackermann's. A second steered
//! axle nearer the turn centre's line turns less, as a truck's linkage makes it. Without a
//! wheel that does not steer (every wheel steers) there is no turn centre's line: every
//! steered wheel turns by `delta` (crab steering), whatever `a`.
//!
//! Between the points of a steering table the input itself is linear by default, and each
//! wheel follows it through the linkage at every instant, as a real linkage does. A
//! reconstruction program's steering ramp moves each wheel linearly from its angle at one
//! point to its angle at the next instead (PC-Crash's 15 mph run: docs/vehicle-model.md), so
//! during a ramp the inner wheel keeps the ratio it has at the ramp's end;
//! [`SteerInterpolation::Wheels`] does that.
//!
//! Per-wheel tables (the angles a program or a test measured at each wheel) replace the
//! linkage.

use crate::error::{require_finite, Error, Place, Result};
use crate::math::Real;

use super::table::Table;
use super::wheel::WheelSpec;

/// Default Ackermann fraction: 1, the linkage of reconstruction programs' vehicle models
/// (every wheel pointed at the turn centre).
pub const DEFAULT_ACKERMANN: Real = 1.0;
/// Largest road-wheel angle (rad) of a wheel or the linkage's reference: 60 deg.
pub const MAX_ROAD_WHEEL_ANGLE: Real = 60.0 * std::f64::consts::PI / 180.0;

/// A vehicle's steering linkage.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct Steering {
    /// Steering ratio (-, > 0): steering-wheel angle per road-wheel angle of the reference
    /// (about 16 for a car); None when the driver's input is never a steering-wheel angle.
    pub ratio: Option<Real>,
    /// Ackermann fraction `a` (-, in [0, 1.5]): 1 full Ackermann (default), 0 parallel steer;
    /// more than 1 is "pro-Ackermann" beyond the geometric one.
    pub ackermann: Real,
    /// Which wheel the input's road-wheel angle is: the outer one (default) or the axle's
    /// centre.
    pub reference: SteerReference,
    /// What is linear between a steering table's points: the input (default) or each wheel.
    #[cfg_attr(feature = "serde", serde(default))]
    pub interpolation: SteerInterpolation,
}

/// What is linear in time between the points of a road-wheel or steering-wheel table.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum SteerInterpolation {
    /// The input: each wheel follows it through the linkage at every instant (a real
    /// linkage's wheels; the default).
    #[default]
    Input,
    /// Each wheel: its angle moves linearly from the linkage's angle at one point to the
    /// linkage's angle at the next (a reconstruction program's steering ramp: during a ramp
    /// from straight ahead, the inner wheel keeps the ratio to the outer it has at the end).
    Wheels,
}

/// The linkage's reference angle (rad, + left) at an instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReferenceAngle {
    /// The reference is at this angle.
    At(Real),
    /// Between two points of the input's table ([`SteerInterpolation::Wheels`]): the
    /// reference's angles at the points before and after, and how far between them the
    /// instant lies (0 at `from`, 1 at `to`).
    Between {
        /// The reference's angle at the point before (rad).
        from: Real,
        /// The reference's angle at the point after (rad).
        to: Real,
        /// The instant's place between the two points, in [0, 1).
        fraction: Real,
    },
}

/// Which wheel the steering input's road-wheel angle belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum SteerReference {
    /// The reference axle's wheel on the outside of the turn (the reconstruction programs').
    Outer,
    /// A virtual wheel at the reference axle's centre (the single-track model's angle).
    Centre,
}

impl Default for Steering {
    fn default() -> Self {
        Steering {
            ratio: None,
            ackermann: DEFAULT_ACKERMANN,
            reference: SteerReference::Outer,
            interpolation: SteerInterpolation::Input,
        }
    }
}

/// The driver's steering input.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum SteerInput {
    /// Road-wheel angle of the linkage's reference (rad, + left).
    RoadWheel(Table),
    /// Steering-wheel angle (rad, + left): the reference turns by it over the ratio.
    SteeringWheel(Table),
    /// Each wheel's own road-wheel angle (rad, + left), None for a wheel that does not turn.
    PerWheel(Vec<Option<Table>>),
    /// A driver following a path: the linkage's road-wheel angle steers the axle's centre
    /// onto a circle through a point of the path ahead (pure pursuit).
    Path(DriverPath),
}

/// Default look-ahead of a driver following a path, in time at the current speed (s): 1 s,
/// the preview of a driver's steering at road speeds (MacAdam, "Application of an optimal
/// preview control for simulation of closed-loop automobile driving", IEEE SMC-11, 1981, used
/// preview times of about 1 s).
pub const DEFAULT_PATH_PREVIEW: Real = 1.0;
/// Default shortest look-ahead of a driver following a path (m): 3 m, about a car's wheelbase.
pub const DEFAULT_PATH_MIN_DISTANCE: Real = 3.0;

/// A driver who follows a path on the ground by pure pursuit (Coulter, "Implementation of the
/// Pure Pursuit Path Tracking Algorithm", CMU-RI-TR-92-01, 1992): from the point of the path
/// nearest the centre of the axle that does not steer, the goal lies `l_d = max(min_distance,
/// preview v)` further along the path; the steer angle (the steered axle's centre, the
/// single-track model's) is `atan(2 L sin(alpha) / l_d)`, alpha the angle from the vehicle's
/// heading to the goal seen from that axle and L the wheelbase, within +-60 deg. Forward
/// driving only. Past the path's end the goal runs on along its last segment.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct DriverPath {
    /// The path's points on the ground (world x, y, m), at least 2, consecutive ones apart.
    pub points: Vec<[Real; 2]>,
    /// How far ahead the driver looks, in time at the current speed (s), in (0, 10].
    pub preview: Real,
    /// The shortest look-ahead distance (m), > 0 (at low speed).
    pub min_distance: Real,
}

impl DriverPath {
    /// Checks the numbers.
    pub fn validate(&self) -> Result<()> {
        if self.points.len() < 2 {
            return Err(Error::invalid(format!(
                "a driver's path needs at least 2 points (got {})",
                self.points.len()
            )));
        }
        for (k, p) in self.points.iter().enumerate() {
            for v in p {
                crate::error::require_coordinate(&format!("path point {k}"), *v)?;
            }
            if k > 0 {
                let q = self.points[k - 1];
                if (p[0] - q[0]).hypot(p[1] - q[1]) < 1e-6 {
                    return Err(Error::invalid(format!(
                        "path points {} and {k} are the same point: drop one",
                        k - 1
                    )));
                }
            }
        }
        require_finite("path preview", self.preview)?;
        require_finite("path min_distance", self.min_distance)?;
        if !(self.preview > 0.0 && self.preview <= 10.0) {
            return Err(Error::parameter(
                "path preview",
                format!("{} s", self.preview),
                "a driver looks ahead (0, 10] s (about 0.5-1.5 s)",
            ));
        }
        if self.min_distance <= 0.0 {
            return Err(Error::parameter(
                "path min_distance",
                format!("{} m", self.min_distance),
                "the shortest look-ahead must be > 0 m (about the wheelbase)",
            ));
        }
        Ok(())
    }

    /// The point `distance` (m) along the path from the point of it nearest `p` (world x,
    /// y), extrapolated along the last segment past the end.
    fn goal(&self, p: [Real; 2], distance: Real) -> [Real; 2] {
        let (mut best, mut best_s, mut s) = (Real::INFINITY, 0.0, 0.0);
        for w in self.points.windows(2) {
            let (a, b) = (w[0], w[1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let len = d[0].hypot(d[1]);
            let u = (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (len * len)).clamp(0.0, 1.0);
            let q = [a[0] + u * d[0], a[1] + u * d[1]];
            let gap = (p[0] - q[0]).hypot(p[1] - q[1]);
            if gap < best {
                (best, best_s) = (gap, s + u * len);
            }
            s += len;
        }
        let mut target = best_s + distance;
        for w in self.points.windows(2) {
            let (a, b) = (w[0], w[1]);
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            if target <= len {
                let u = target / len;
                return [a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])];
            }
            target -= len;
        }
        // Past the end: along the last segment.
        let n = self.points.len();
        let (a, b) = (self.points[n - 2], self.points[n - 1]);
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        [
            b[0] + (b[0] - a[0]) / len * target,
            b[1] + (b[1] - a[1]) / len * target,
        ]
    }

    /// The steer angle (rad, + left) of the steered axle's centre for a vehicle whose
    /// non-steered axle's centre is at `axle` (world x, y, m), heading along the unit `heading`
    /// (world x, y) at `speed` (m/s) with wheelbase `wheelbase` (m).
    pub fn steer(&self, axle: [Real; 2], heading: [Real; 2], speed: Real, wheelbase: Real) -> Real {
        let l_d = self.min_distance.max(self.preview * speed.max(0.0));
        let g = self.goal(axle, l_d);
        let to = [g[0] - axle[0], g[1] - axle[1]];
        let alpha = (heading[0] * to[1] - heading[1] * to[0])
            .atan2(heading[0] * to[0] + heading[1] * to[1]);
        (2.0 * wheelbase * alpha.sin() / l_d)
            .atan()
            .clamp(-MAX_ROAD_WHEEL_ANGLE, MAX_ROAD_WHEEL_ANGLE)
    }
}

/// Where the linkage's geometry lies, body frame (m): precomputed from the wheels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkageGeometry {
    /// x of the turn centre's line (the wheels that do not steer), None when all steer.
    x_ref: Option<Real>,
    /// x of the reference's axle (the steered wheel farthest from the line).
    x_s: Real,
    /// y of the wheels' centre line.
    y_c: Real,
    /// y of the reference axle's leftmost and rightmost steered wheels.
    y_left: Real,
    y_right: Real,
}

impl LinkageGeometry {
    /// The body-frame x of the axle that does not steer (m), None when every wheel steers.
    pub fn fixed_axle_x(&self) -> Option<Real> {
        self.x_ref
    }

    /// The wheelbase the linkage steers about (m): from the axle that does not steer to the
    /// steered axle farthest from it.
    pub fn wheelbase(&self) -> Real {
        self.x_ref.map_or(0.0, |x0| (self.x_s - x0).abs())
    }

    /// The body-frame y of the wheels' centre line (m).
    pub fn centre_y(&self) -> Real {
        self.y_c
    }

    /// The geometry of `wheels`.
    pub fn of(wheels: &[WheelSpec]) -> LinkageGeometry {
        // Called per evaluation: no allocation.
        let (sum, count) = wheels
            .iter()
            .filter(|w| !w.steerable)
            .fold((0.0, 0usize), |(s, n), w| (s + w.center.x, n + 1));
        let x_ref = (count > 0).then(|| sum / count as Real);
        let y_c = wheels.iter().map(|w| w.center.y).sum::<Real>() / wheels.len().max(1) as Real;
        let x_s = match x_ref {
            Some(x0) => wheels
                .iter()
                .filter(|w| w.steerable)
                .map(|w| w.center.x)
                .fold(x0, |best, x| {
                    if (x - x0).abs() > (best - x0).abs() {
                        x
                    } else {
                        best
                    }
                }),
            None => 0.0,
        };
        // The reference axle's wheels: the steered ones within 1 cm of x_s.
        let axle = || {
            wheels
                .iter()
                .filter(|w| w.steerable && (w.center.x - x_s).abs() <= 0.01)
                .map(|w| w.center.y)
        };
        let y_left = axle().fold(y_c, Real::max);
        let y_right = axle().fold(y_c, Real::min);
        LinkageGeometry {
            x_ref,
            x_s,
            y_c,
            y_left,
            y_right,
        }
    }
}

/// Checks a steering ratio (steering-wheel angle per road-wheel angle): finite, in [1, 100].
pub fn check_steering_ratio(r: Real) -> Result<()> {
    require_finite("steering_ratio", r)?;
    if !(1.0..=100.0).contains(&r) {
        return Err(Error::parameter(
            "steering_ratio",
            r,
            "a steering ratio must lie in [1, 100] (about 16 for a car, 20-30 for a truck)",
        ));
    }
    Ok(())
}

impl Steering {
    /// Checks the numbers.
    pub fn validate(&self) -> Result<()> {
        require_finite("ackermann", self.ackermann)?;
        if !(0.0..=1.5).contains(&self.ackermann) {
            return Err(Error::parameter(
                "ackermann",
                self.ackermann,
                "the Ackermann fraction must lie in [0, 1.5] (1 full Ackermann, 0 parallel \
                 steer)",
            ));
        }
        if let Some(r) = self.ratio {
            check_steering_ratio(r)?;
        }
        Ok(())
    }

    /// The reference's road-wheel angle (rad) for the input `input` at time `t`; None for
    /// per-wheel tables and a driver's path.
    pub fn reference_angle(&self, input: &SteerInput, t: Real) -> Option<ReferenceAngle> {
        let (table, per) = match input {
            SteerInput::RoadWheel(table) => (table, 1.0),
            SteerInput::SteeringWheel(table) => (table, self.ratio.unwrap_or(1.0)),
            SteerInput::PerWheel(_) | SteerInput::Path(_) => return None,
        };
        Some(match self.interpolation {
            SteerInterpolation::Input => ReferenceAngle::At(table.at(t) / per),
            SteerInterpolation::Wheels => {
                let (from, to, fraction) = table.segment(t);
                ReferenceAngle::Between {
                    from: from / per,
                    to: to / per,
                    fraction,
                }
            }
        })
    }

    /// Road-wheel angle (rad) of wheel `wheel` (at body-frame `x`, `y`) at the reference
    /// angle `angle`: [`Steering::wheel_angle`], or between two points of the input's table
    /// the wheel's angles at both, linear between them.
    pub fn wheel_angle_at(
        &self,
        geometry: &LinkageGeometry,
        angle: ReferenceAngle,
        steerable: bool,
        x: Real,
        y: Real,
    ) -> Real {
        match angle {
            ReferenceAngle::At(delta) => self.wheel_angle(geometry, delta, steerable, x, y),
            ReferenceAngle::Between { from, to, fraction } => {
                let a = self.wheel_angle(geometry, from, steerable, x, y);
                let b = self.wheel_angle(geometry, to, steerable, x, y);
                a + (b - a) * fraction
            }
        }
    }

    /// Road-wheel angle (rad) of wheel `wheel` (at body-frame `x`, `y`, steerable or not)
    /// when the reference is at `delta` (rad).
    pub fn wheel_angle(
        &self,
        geometry: &LinkageGeometry,
        delta: Real,
        steerable: bool,
        x: Real,
        y: Real,
    ) -> Real {
        self.wheel_angle_from(self.reference, geometry, delta, steerable, x, y)
    }

    /// [`Steering::wheel_angle`] with the input's angle the `reference` wheel's.
    pub fn wheel_angle_from(
        &self,
        reference: SteerReference,
        geometry: &LinkageGeometry,
        delta: Real,
        steerable: bool,
        x: Real,
        y: Real,
    ) -> Real {
        if !steerable || delta == 0.0 {
            return 0.0;
        }
        let Some(x_ref) = geometry.x_ref else {
            return delta; // every wheel steers: no turn centre's line
        };
        let tan = delta.tan();
        // The reference's y: the outer wheel's (on the right in a turn to the left, + delta,
        // when the axle lies ahead of the turn centre's line) or the centre line.
        let ahead = geometry.x_s > x_ref;
        let y_r = match reference {
            SteerReference::Centre => geometry.y_c,
            SteerReference::Outer if (delta > 0.0) == ahead => geometry.y_right,
            SteerReference::Outer => geometry.y_left,
        };
        let num = (x - x_ref) * tan;
        let den = (geometry.x_s - x_ref) + self.ackermann * (y_r - y) * tan;
        // The reference's side of the line (num and den of one sign) keeps den's sign; a
        // wheel turned past 90 deg cannot be, so den > 0 for the reference's axle is checked
        // with the inputs.
        (num / den).atan()
    }

    /// Checks the steering input against `wheels`: a steering-wheel input needs a ratio,
    /// per-wheel tables name steerable wheels only, and no wheel turns past
    /// [`MAX_ROAD_WHEEL_ANGLE`] or through 90 deg (an Ackermann inner wheel of a short
    /// vehicle at a large angle).
    pub fn validate_input(&self, input: &SteerInput, wheels: &[WheelSpec]) -> Result<()> {
        let check = |what: &str, lo: Real, hi: Real| -> Result<()> {
            if lo < -MAX_ROAD_WHEEL_ANGLE || hi > MAX_ROAD_WHEEL_ANGLE {
                let advice = if matches!(input, SteerInput::SteeringWheel(_)) {
                    "check the steering-wheel table and the steering ratio"
                } else {
                    "a steering-wheel angle goes with the steering ratio"
                };
                return Err(Error::invalid(format!(
                    "{what} reaches {:.1} deg: road wheels turn at most 60 deg ({advice})",
                    if hi > MAX_ROAD_WHEEL_ANGLE { hi } else { lo }.to_degrees()
                )));
            }
            Ok(())
        };
        match input {
            SteerInput::RoadWheel(table) => {
                let (lo, hi) = table.range();
                check("the road-wheel steering angle", lo, hi)?;
            }
            SteerInput::SteeringWheel(table) => {
                let Some(ratio) = self.ratio else {
                    return Err(Error::invalid(
                        "a steering-wheel angle needs the vehicle's steering ratio (about 16 for \
                         a car)",
                    ));
                };
                let (lo, hi) = table.range();
                check(
                    "the road-wheel steering angle (steering wheel / ratio)",
                    lo / ratio,
                    hi / ratio,
                )?;
            }
            SteerInput::Path(path) => {
                path.validate()?;
                let g = LinkageGeometry::of(wheels);
                if g.x_ref.is_none_or(|x0| g.x_s <= x0) {
                    return Err(Error::invalid(
                        "a driver's path needs steered wheels ahead of wheels that do not steer \
                         (the pure pursuit steers the front axle about the rear one)",
                    ));
                }
                return Ok(());
            }
            SteerInput::PerWheel(tables) => {
                if tables.len() != wheels.len() {
                    return Err(Error::invalid(format!(
                        "per-wheel steering is given for {} wheels but the vehicle has {}",
                        tables.len(),
                        wheels.len()
                    )));
                }
                for (k, (t, w)) in tables.iter().zip(wheels).enumerate() {
                    let Some(t) = t else { continue };
                    if !w.steerable {
                        return Err(Error::invalid(
                            "it has a steering table but does not steer (make it steerable)",
                        )
                        .at(Place::Wheel(k)));
                    }
                    let (lo, hi) = t.range();
                    check("steering angle", lo, hi).map_err(|e| e.at(Place::Wheel(k)))?;
                }
                return Ok(());
            }
        }
        // Through the linkage: the reference's extreme angles must keep every wheel short of
        // 90 deg.
        let geometry = LinkageGeometry::of(wheels);
        let Some(x_ref) = geometry.x_ref else {
            return Ok(());
        };
        let delta_max = match input {
            SteerInput::RoadWheel(t) => t.range().0.abs().max(t.range().1.abs()),
            SteerInput::SteeringWheel(t) => {
                t.range().0.abs().max(t.range().1.abs()) / self.ratio.unwrap_or(1.0)
            }
            SteerInput::PerWheel(_) | SteerInput::Path(_) => 0.0,
        };
        let tan = delta_max.tan();
        for (k, w) in wheels.iter().enumerate().filter(|(_, w)| w.steerable) {
            let lever = (geometry.x_s - x_ref).abs();
            let span = (w.center.y - geometry.y_right)
                .abs()
                .max((w.center.y - geometry.y_left).abs());
            let inward = self.ackermann * span * tan;
            if lever - inward <= 0.0 {
                return Err(Error::invalid(format!(
                    "it would turn past 90 deg at the largest steering angle ({:.1} deg at the \
                     reference): the steering input is too large for the vehicle's wheelbase \
                     and track",
                    delta_max.to_degrees()
                ))
                .at(Place::Wheel(k)));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Point;

    /// Four wheels: wheelbase 2.75 m, track 1.55 m, front steered, CG 1.2 m behind the front
    /// axle.
    fn car() -> Vec<WheelSpec> {
        [(1.2, 0.775), (1.2, -0.775), (-1.55, 0.775), (-1.55, -0.775)]
            .iter()
            .enumerate()
            .map(|(k, &(x, y))| WheelSpec {
                center: Point::new(x, y, -0.25),
                radius: 0.3,
                steerable: k < 2,
                static_load: 3600.0,
                spring_rate: 25e3,
                damping: 1.8e3,
            })
            .collect()
    }

    fn angles(s: &Steering, wheels: &[WheelSpec], delta: Real) -> Vec<Real> {
        let g = LinkageGeometry::of(wheels);
        wheels
            .iter()
            .map(|w| s.wheel_angle(&g, delta, w.steerable, w.center.x, w.center.y))
            .collect()
    }

    #[test]
    fn full_ackermann_points_every_wheel_at_the_turn_centre() {
        let wheels = car();
        for reference in [SteerReference::Outer, SteerReference::Centre] {
            let s = Steering {
                reference,
                ..Steering::default()
            };
            for delta in [0.05_f64, 0.3, -0.5] {
                let a = angles(&s, &wheels, delta);
                // cot(outer) - cot(inner) = track / wheelbase: both wheels' normals meet on
                // the rear axle's line.
                let (inner, outer) = if delta > 0.0 {
                    (a[0], a[1])
                } else {
                    (a[1], a[0])
                };
                let expected = 1.55 / 2.75;
                let got = (1.0 / outer.tan() - 1.0 / inner.tan()) * delta.signum();
                assert!(
                    (got - expected).abs() < 1e-12,
                    "{delta}: {got} vs {expected}"
                );
                match reference {
                    // The input is the outer wheel's angle (PC-Crash's 360 deg / 15.9 =
                    // 22.64 deg gives an inner 28.64 deg on a 2.692 x 1.524 m car).
                    SteerReference::Outer => assert!((outer - delta).abs() < 1e-15),
                    // The input is the axle centre's: R = L / tan(delta) there.
                    SteerReference::Centre => {
                        let r = 2.75 / delta.tan();
                        let left = a[0];
                        assert!((2.75 / left.tan() - (r - 0.775)).abs() < 1e-12);
                    }
                }
                assert!((a[2], a[3]) == (0.0, 0.0));
                assert!(inner.abs() > outer.abs());
            }
        }
    }

    #[test]
    fn parallel_steer_turns_both_alike_and_a_fraction_scales_the_difference() {
        let wheels = car();
        let parallel = Steering {
            ackermann: 0.0,
            ..Steering::default()
        };
        let a = angles(&parallel, &wheels, 0.3);
        assert_eq!((a[0], a[1]), (0.3, 0.3));
        // At a small angle the inner-outer difference is the fraction times Ackermann's.
        let half = Steering {
            ackermann: 0.5,
            ..Steering::default()
        };
        let (h, f) = (
            angles(&half, &wheels, 0.001),
            angles(&Steering::default(), &wheels, 0.001),
        );
        let ratio = (h[0] - h[1]) / (f[0] - f[1]);
        assert!((ratio - 0.5).abs() < 1e-3, "{ratio}");
    }

    #[test]
    fn wheels_interpolated_between_points_keep_the_ratio_of_the_ramps_end() {
        // A ramp of the outer (right) wheel from 0 to 0.4 rad over 1 s, turning left.
        let wheels = car();
        let g = LinkageGeometry::of(&wheels);
        let ramp = SteerInput::RoadWheel(Table::new("steer", &[(0.0, 0.0), (1.0, 0.4)]).unwrap());
        let by_wheel = Steering {
            interpolation: SteerInterpolation::Wheels,
            ..Steering::default()
        };
        let linkage = Steering::default();
        let end = angles(&linkage, &wheels, 0.4);
        let ratio = end[0] / end[1];
        assert!(ratio > 1.2, "{ratio}"); // the inner (left) wheel turns more at the end
        for t in [0.1, 0.25, 0.5, 0.9] {
            let at = by_wheel.reference_angle(&ramp, t).unwrap();
            let a: Vec<Real> = wheels
                .iter()
                .map(|w| by_wheel.wheel_angle_at(&g, at, w.steerable, w.center.x, w.center.y))
                .collect();
            // Each wheel linear in time: the outer at the input, the inner at the end's ratio.
            assert!((a[1] - 0.4 * t).abs() < 1e-14, "{t}: {}", a[1]);
            assert!((a[0] / a[1] - ratio).abs() < 1e-12, "{t}: {}", a[0] / a[1]);
            // The linkage at every instant gives the geometric ratio, near 1 early on.
            let geometric = angles(&linkage, &wheels, 0.4 * t);
            assert!(geometric[0] / geometric[1] < ratio);
            assert!((geometric[1] - a[1]).abs() < 1e-14);
        }
        // At and beyond the points both give the linkage's angles.
        for t in [-1.0, 0.0, 1.0, 2.0] {
            let at = by_wheel.reference_angle(&ramp, t).unwrap();
            let delta = linkage.reference_angle(&ramp, t).unwrap();
            for w in &wheels {
                let (x, y, s) = (w.center.x, w.center.y, w.steerable);
                assert_eq!(
                    by_wheel.wheel_angle_at(&g, at, s, x, y),
                    linkage.wheel_angle_at(&g, delta, s, x, y)
                );
            }
        }
    }

    #[test]
    fn inputs_are_checked_against_the_wheels() {
        let wheels = car();
        let table = |v: Real| Table::new("steer", &[(0.0, 0.0), (1.0, v)]).unwrap();
        let s = Steering::default();
        assert!(s
            .validate_input(&SteerInput::RoadWheel(table(0.5)), &wheels)
            .is_ok());
        assert!(s
            .validate_input(&SteerInput::RoadWheel(table(1.1)), &wheels)
            .is_err());
        // A steering-wheel angle needs the ratio.
        let sw = SteerInput::SteeringWheel(table(6.0));
        assert!(s.validate_input(&sw, &wheels).is_err());
        let with_ratio = Steering {
            ratio: Some(16.0),
            ..Steering::default()
        };
        assert!(with_ratio.validate_input(&sw, &wheels).is_ok());
        assert_eq!(
            with_ratio.reference_angle(&sw, 0.5),
            Some(ReferenceAngle::At(3.0 / 16.0))
        );
        // Per-wheel tables: one per wheel, only on steerable wheels.
        let per = |k: usize| {
            let mut v: Vec<Option<Table>> = vec![None; 4];
            v[k] = Some(table(0.2));
            SteerInput::PerWheel(v)
        };
        assert!(s.validate_input(&per(1), &wheels).is_ok());
        assert!(s.validate_input(&per(2), &wheels).is_err());
        assert!(Steering {
            ackermann: 2.0,
            ..Steering::default()
        }
        .validate()
        .is_err());
        assert!(Steering {
            ratio: Some(0.5),
            ..Steering::default()
        }
        .validate()
        .is_err());
    }
}
