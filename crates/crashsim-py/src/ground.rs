//! Python values <-> the core's ground, wheels, tyres and driver inputs. Translation only.

use core::ground::{FrictionZone, Ground};
use core::math::{Point, Real};
use core::vehicle::{
    AntiRollBar, Braking, CombinedSlip, DriverInputs, SteerInput, Steering, Table, Trigger,
    TyreModel, VehicleSpec, WheelSpec, WheelState, WheelSwitch,
};
use core::{Error, Place};
use crashsim_core as core;
use numpy::{AllowTypeChange, PyArrayLike1, PyArrayLike2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors;

/// An (n, k) float array-like with `k` columns.
fn rows(obj: &Bound<'_, PyAny>, k: usize, name: &str) -> core::Result<Vec<Vec<Real>>> {
    let a: PyArrayLike2<'_, f64, AllowTypeChange> = obj.extract().map_err(|_| {
        core::Error::invalid(format!("{name} must be an (n, {k}) array of numbers"))
    })?;
    let a = a.as_array();
    if a.ncols() != k {
        return Err(core::Error::invalid(format!(
            "{name} must have shape (n, {k}), got {:?}",
            a.shape()
        )));
    }
    Ok(a.rows().into_iter().map(|r| r.to_vec()).collect())
}

/// An (n,) float array-like.
fn values(obj: &Bound<'_, PyAny>, n: usize, name: &str) -> PyResult<Vec<Real>> {
    let a: PyArrayLike1<'_, f64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| errors::parameter(format!("{name} must be a sequence of {n} numbers")))?;
    let a = a.as_array();
    if a.len() != n {
        return Err(errors::parameter(format!(
            "{name} must have {n} values (one per wheel), got {}",
            a.len()
        )));
    }
    Ok(a.to_vec())
}

/// A (k, 2) table of (time s, value).
pub fn table(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Table> {
    table_at(obj, name, None)
}

/// [`table`] of one wheel: an error is placed at wheel `k`.
fn wheel_table(obj: &Bound<'_, PyAny>, name: &str, k: usize) -> PyResult<Table> {
    table_at(obj, name, Some(Place::Wheel(k)))
}

fn table_at(obj: &Bound<'_, PyAny>, name: &str, place: Option<Place>) -> PyResult<Table> {
    rows(obj, 2, name)
        .and_then(|r| {
            let points: Vec<(Real, Real)> = r.iter().map(|p| (p[0], p[1])).collect();
            Table::new(name, &points)
        })
        .map_err(|e| errors::to_py(place.into_iter().fold(e, Error::at)))
}

/// The ground from the keywords of `World.set_ground`.
pub fn ground(
    height: Real,
    terrain: Option<std::sync::Arc<core::MeshShape>>,
    tyre_friction: Real,
    body_friction: Real,
    zones: &[(Bound<'_, PyAny>, Real)],
) -> PyResult<Ground> {
    let base = match terrain {
        Some(mesh) => Ground::terrain(mesh),
        None => Ground::plane(height),
    }
    .map_err(errors::to_py)?;
    let mut z = Vec::with_capacity(zones.len());
    for (k, (poly, friction)) in zones.iter().enumerate() {
        z.push(zone(poly, *friction).map_err(|e| errors::to_py(e.at(Place::Zone(k))))?);
    }
    base.with_friction(tyre_friction, body_friction)
        .and_then(|g| g.with_zones(z))
        .map_err(errors::to_py)
}

/// A friction zone of (k, 2) corners (m, world) and a friction.
fn zone(polygon: &Bound<'_, PyAny>, friction: Real) -> core::Result<FrictionZone> {
    Ok(FrictionZone {
        polygon: rows(polygon, 2, "its corners")?
            .iter()
            .map(|c| [c[0], c[1]])
            .collect(),
        friction,
    })
}

/// The core's rules of one friction zone ((k, 2) corners in m, the friction): a
/// ParameterError naming what is wrong (crashsim.FrictionZone checks itself with them; a
/// ground checks its zones with the same rules and that they do not overlap).
#[pyfunction]
pub fn check_friction_zone(polygon: &Bound<'_, PyAny>, friction: Real) -> PyResult<()> {
    zone(polygon, friction)
        .and_then(|z| z.check())
        .map_err(errors::to_py)
}

/// The core's rule of a body's own friction with the ground (in (0, 2]): a ParameterError
/// naming it `name` (crashsim.Pedestrian checks its road friction with it when made; the
/// scene's spec checks it again with the same rule).
#[pyfunction]
pub fn check_ground_friction(friction: Real, name: &str) -> PyResult<()> {
    core::ground::check_body_friction(name, friction).map_err(errors::to_py)
}

/// The ground, checked by the core once, when it is made (crashsim.Ground builds one and
/// SceneSpec.set_ground takes it as it is).
#[pyclass(frozen, module = "crashsim._core", name = "Ground")]
pub struct GroundValue {
    pub inner: Ground,
}

#[pymethods]
impl GroundValue {
    /// The plane z = height (m), or a terrain mesh (world coordinates), with tyre-road and
    /// body-ground friction (None: the engine's defaults) and friction zones ((k, 2) polygon
    /// m, friction), checked by the core.
    #[new]
    #[pyo3(signature = (*, height = 0.0, terrain = None, tyre_friction = None, body_friction = None, zones = Vec::new()))]
    fn new(
        height: Real,
        terrain: Option<&crate::Shape>,
        tyre_friction: Option<Real>,
        body_friction: Option<Real>,
        zones: Vec<(Bound<'_, PyAny>, Real)>,
    ) -> PyResult<GroundValue> {
        let inner = ground(
            height,
            terrain.map(|t| t.inner.clone()),
            tyre_friction.unwrap_or(core::ground::DEFAULT_TYRE_FRICTION),
            body_friction.unwrap_or(core::ground::DEFAULT_BODY_FRICTION),
            &zones,
        )?;
        Ok(GroundValue { inner })
    }

    /// Tyre-road friction outside every zone.
    #[getter]
    fn tyre_friction(&self) -> Real {
        self.inner.tyre_friction()
    }

    /// Body-ground friction.
    #[getter]
    fn body_friction(&self) -> Real {
        self.inner.body_friction()
    }

    /// Tyre-road friction at (x, y) (m, world): the first zone holding the point, else the
    /// ground's (the engine's own lookup).
    fn friction_at(&self, x: Real, y: Real) -> Real {
        self.inner.tyre_friction_at(x, y)
    }

    /// The same ground with other frictions (a study's variant), checked by the core.
    fn with_friction(&self, tyre_friction: Real, body_friction: Real) -> PyResult<GroundValue> {
        let inner = self
            .inner
            .clone()
            .with_friction(tyre_friction, body_friction)
            .map_err(errors::to_py)?;
        Ok(GroundValue { inner })
    }
}

/// A tyre, checked by the core when it is made (crashsim.Tyre builds one).
#[pyclass(frozen, eq, module = "crashsim._core")]
#[derive(Clone, PartialEq)]
pub struct Tyre {
    pub inner: core::vehicle::Tyre,
}

#[pymethods]
impl Tyre {
    /// model "linear" (cornering: the cornering coefficient, 1/rad, or saturation_angle:
    /// its equivalent at mu = 1, rad), "linear_friction_scaled" (saturation_angle, rad) or
    /// "magic_formula" (b 1/rad, c, e); relaxation_length (m), rolling_resistance (-),
    /// combined ("braking_priority", "circle" or "nicolas_comstock"), load_sensitivity (-),
    /// longitudinal_stiffness (nicolas_comstock's Cs per unit load, 1 per unit slip; None:
    /// equal to the cornering stiffness). None: the engine's default.
    #[new]
    #[pyo3(signature = (model = "linear", *, cornering = None, saturation_angle = None, b = None, c = None, e = None, relaxation_length = None, rolling_resistance = None, combined = None, load_sensitivity = None, longitudinal_stiffness = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        model: &str,
        cornering: Option<Real>,
        saturation_angle: Option<Real>,
        b: Option<Real>,
        c: Option<Real>,
        e: Option<Real>,
        relaxation_length: Option<Real>,
        rolling_resistance: Option<Real>,
        combined: Option<&str>,
        load_sensitivity: Option<Real>,
        longitudinal_stiffness: Option<Real>,
    ) -> PyResult<Tyre> {
        let mut t = core::vehicle::Tyre {
            model: tyre_model(model, cornering, saturation_angle, b, c, e)?,
            ..Default::default()
        };
        if let Some(v) = relaxation_length {
            t.relaxation_length = v;
        }
        if let Some(v) = rolling_resistance {
            t.rolling_resistance = v;
        }
        if let Some(v) = load_sensitivity {
            t.load_sensitivity = v;
        }
        if let Some(v) = combined {
            t.combined = combined_slip(v)?;
        }
        t.longitudinal_stiffness = longitudinal_stiffness;
        t.validate().map_err(errors::to_py)?;
        Ok(Tyre { inner: t })
    }

    /// Every parameter as the engine runs it: model, its own parameters (cornering 1/rad;
    /// saturation_angle rad; b, c, e), relaxation_length, rolling_resistance, combined,
    /// load_sensitivity and, with combined "nicolas_comstock", longitudinal_stiffness.
    fn resolved<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let t = &self.inner;
        match t.model {
            TyreModel::Linear { cornering } => {
                d.set_item("model", "linear")?;
                d.set_item("cornering", cornering)?;
            }
            TyreModel::LinearFrictionScaled { saturation_angle } => {
                d.set_item("model", "linear_friction_scaled")?;
                d.set_item("saturation_angle", saturation_angle)?;
            }
            TyreModel::MagicFormula { b, c, e } => {
                d.set_item("model", "magic_formula")?;
                d.set_item("b", b)?;
                d.set_item("c", c)?;
                d.set_item("e", e)?;
            }
        }
        d.set_item("relaxation_length", t.relaxation_length)?;
        d.set_item("rolling_resistance", t.rolling_resistance)?;
        d.set_item(
            "combined",
            match t.combined {
                CombinedSlip::BrakingPriority => "braking_priority",
                CombinedSlip::Circle => "circle",
                CombinedSlip::NicolasComstock => "nicolas_comstock",
            },
        )?;
        d.set_item("load_sensitivity", t.load_sensitivity)?;
        // Listed with the law that uses it only (None: the cornering stiffness).
        if t.combined == CombinedSlip::NicolasComstock {
            d.set_item("longitudinal_stiffness", t.longitudinal_stiffness)?;
        }
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!("Tyre({:?})", self.inner)
    }
}

/// The tyre model named `model` with its own parameters (cornering 1/rad or
/// saturation_angle rad; b 1/rad, c, e; None: the engine's default); an error for another
/// model's parameter, both cornering and saturation_angle, or an unknown model.
fn tyre_model(
    model: &str,
    cornering: Option<Real>,
    saturation_angle: Option<Real>,
    b: Option<Real>,
    c: Option<Real>,
    e: Option<Real>,
) -> PyResult<TyreModel> {
    let mf = [("b", b.is_some()), ("c", c.is_some()), ("e", e.is_some())];
    Ok(match model {
        "linear" => {
            foreign(&mf, model)?;
            let cornering = linear_cornering(cornering, saturation_angle)?;
            core::vehicle::TyreModel::Linear { cornering }
        }
        "linear_friction_scaled" => {
            foreign(&mf, model)?;
            foreign(&[("cornering", cornering.is_some())], model)?;
            core::vehicle::TyreModel::LinearFrictionScaled {
                saturation_angle: saturation_angle.unwrap_or(10f64.to_radians()),
            }
        }
        "magic_formula" => {
            foreign(
                &[
                    ("cornering", cornering.is_some()),
                    ("saturation_angle", saturation_angle.is_some()),
                ],
                model,
            )?;
            let [b0, c0, e0] = core::vehicle::MAGIC_FORMULA_DEFAULTS;
            core::vehicle::TyreModel::MagicFormula {
                b: b.unwrap_or(b0),
                c: c.unwrap_or(c0),
                e: e.unwrap_or(e0),
            }
        }
        other => {
            return Err(errors::parameter(format!(
                "tyre model {other:?} is unknown: use \"linear\" (the reconstruction \
                 programs' tyre), \"linear_friction_scaled\" or \"magic_formula\""
            )))
        }
    })
}

/// An error naming the parameters in `names` that are given (true) when they do not belong
/// to tyre model `model`.
fn foreign(names: &[(&str, bool)], model: &str) -> PyResult<()> {
    let given: Vec<&str> = names.iter().filter(|(_, g)| *g).map(|(n, _)| *n).collect();
    if given.is_empty() {
        Ok(())
    } else {
        Err(errors::parameter(format!(
            "tyre {} do(es) not belong to model {model:?} (linear: cornering or \
             saturation_angle; linear_friction_scaled: saturation_angle; \
             magic_formula: b, c, e)",
            given.join(", ")
        )))
    }
}

/// The linear tyre's cornering coefficient (1/rad): as given, or 1 / saturation_angle (rad,
/// > 0), or the default; an error for both.
fn linear_cornering(cornering: Option<Real>, saturation_angle: Option<Real>) -> PyResult<Real> {
    Ok(match (cornering, saturation_angle) {
        (Some(_), Some(_)) => {
            return Err(errors::parameter(
                "tyre: give the cornering coefficient or the saturation angle, not \
                 both (the saturation angle at mu = 1 is 1 / cornering)"
                    .into(),
            ))
        }
        (Some(c), None) => c,
        (None, Some(a)) => {
            if !(a.is_finite() && a > 0.0) {
                return Err(errors::parameter(format!(
                    "tyre saturation_angle = {a} is invalid: it must be > 0 rad"
                )));
            }
            1.0 / a
        }
        (None, None) => core::vehicle::DEFAULT_CORNERING_COEFFICIENT,
    })
}

/// The combined-slip law named `v`.
fn combined_slip(v: &str) -> PyResult<CombinedSlip> {
    Ok(match v {
        "braking_priority" => CombinedSlip::BrakingPriority,
        "circle" => CombinedSlip::Circle,
        "nicolas_comstock" => CombinedSlip::NicolasComstock,
        other => {
            return Err(errors::parameter(format!(
                "tyre combined = {other:?} is unknown: use \"braking_priority\" (the \
                 brake force kept, the lateral force from what the friction leaves), \
                 \"circle\" (both scaled onto the friction circle) or \
                 \"nicolas_comstock\" (Brach and Brach's modified Nicolas-Comstock \
                 combination of the pure-slip forces)"
            )))
        }
    })
}

/// One wheel-state switch: (wheel, "time" | "exchange", when, "free" | "locked" |
/// "braked", braked fraction).
fn switch(obj: &Bound<'_, PyAny>) -> PyResult<WheelSwitch> {
    let (wheel, trigger, when, state, fraction): (usize, String, Real, String, Real) =
        obj.extract().map_err(|_| {
            errors::parameter(
                "a wheel-state switch is (wheel, 'time' | 'exchange', when, 'free' | 'locked' | \
                 'braked', fraction)"
                    .into(),
            )
        })?;
    wheel_switch(wheel, &trigger, when, &state, fraction)
}

/// The core's rules of one wheel-state switch ('time' | 'exchange', when: s or the
/// vehicle's n-th exchange, 'free' | 'locked' | 'braked', the braked fraction):
/// ParameterError otherwise (crashsim.DriverInputs checks its switches with them when made;
/// a vehicle checks them with the same rules and that their wheels exist).
#[pyfunction]
pub fn check_wheel_switch(trigger: &str, when: Real, state: &str, fraction: Real) -> PyResult<()> {
    let s = wheel_switch(0, trigger, when, state, fraction)?;
    s.check().map_err(errors::to_py)
}

/// The core's rule of a steering ratio (steering-wheel angle per road-wheel angle): finite,
/// in [1, 100]; ParameterError otherwise (DriverInputs' own ratio; a vehicle's is checked
/// with its steering).
#[pyfunction]
pub fn check_steering_ratio(ratio: Real) -> PyResult<()> {
    core::vehicle::steering::check_steering_ratio(ratio).map_err(errors::to_py)
}

fn wheel_switch(
    wheel: usize,
    trigger: &str,
    when: Real,
    state: &str,
    fraction: Real,
) -> PyResult<WheelSwitch> {
    let at = match trigger {
        "time" => Trigger::Time(when),
        "exchange" => {
            if !(when >= 0.0) || when.fract() != 0.0 {
                return Err(errors::parameter(format!(
                    "a wheel-state switch at exchange {when}: give a whole number (exchanges \
                     count from 1)"
                )));
            }
            Trigger::Exchange(when as usize)
        }
        other => {
            return Err(errors::parameter(format!(
                "a wheel-state switch happens at a 'time' or an 'exchange', not {other:?}"
            )))
        }
    };
    let state = match state {
        "free" => WheelState::Free,
        "locked" => WheelState::Locked,
        "braked" => WheelState::Braked(fraction),
        other => {
            return Err(errors::parameter(format!(
                "a wheel state is 'free', 'locked' or 'braked', not {other:?}"
            )))
        }
    };
    Ok(WheelSwitch { wheel, at, state })
}

/// One wheel's braking as `World.set_vehicle` takes it: (kind, table, share), the share given
/// for "distributed" only.
pub type BrakeRow<'py> = (String, Bound<'py, PyAny>, Option<Real>);

/// A vehicle from the arrays and lists of `World.set_vehicle`.
#[allow(clippy::too_many_arguments)]
pub fn vehicle(
    centers: &Bound<'_, PyAny>,
    radii: &Bound<'_, PyAny>,
    steerable: &Bound<'_, PyAny>,
    static_loads: &Bound<'_, PyAny>,
    spring_rates: &Bound<'_, PyAny>,
    damping: &Bound<'_, PyAny>,
    tyre: Option<&Tyre>,
    linkage: Steering,
    anti_roll: Vec<(usize, usize, Real)>,
    abs: bool,
    steer: Option<(String, Bound<'_, PyAny>)>,
    brake: Vec<Option<BrakeRow<'_>>>,
    drive: Vec<Option<Bound<'_, PyAny>>>,
    switches: Vec<Bound<'_, PyAny>>,
) -> PyResult<VehicleSpec> {
    let wheels = wheel_specs(
        centers,
        radii,
        steerable,
        static_loads,
        spring_rates,
        damping,
    )?;
    // (in this order: the first bad input is the one reported)
    let brake = brakings(brake)?;
    let steer = steer_input(steer)?;
    let inputs = DriverInputs {
        steer,
        brake,
        drive: drive
            .iter()
            .enumerate()
            .map(|(k, d)| {
                d.as_ref()
                    .map(|t| wheel_table(t, "drive force", k))
                    .transpose()
            })
            .collect::<PyResult<_>>()?,
        switches: switches.iter().map(switch).collect::<PyResult<_>>()?,
    };
    Ok(VehicleSpec {
        wheels,
        tyre: tyre.map_or_else(core::vehicle::Tyre::default, |t| t.inner.clone()),
        steering: linkage,
        anti_roll: anti_roll
            .into_iter()
            .map(|(left, right, roll_stiffness)| AntiRollBar {
                left,
                right,
                roll_stiffness,
            })
            .collect(),
        abs,
        inputs,
        coupling: None,
        hitch_load: None,
        load_groups: Vec::new(),
    })
}

/// The wheels from the per-wheel arrays (n centres, m; radii m; steerable; static loads N;
/// spring rates N/m; damping N s/m), each array's length checked against the centres'.
fn wheel_specs(
    centers: &Bound<'_, PyAny>,
    radii: &Bound<'_, PyAny>,
    steerable: &Bound<'_, PyAny>,
    static_loads: &Bound<'_, PyAny>,
    spring_rates: &Bound<'_, PyAny>,
    damping: &Bound<'_, PyAny>,
) -> PyResult<Vec<WheelSpec>> {
    let c = rows(centers, 3, "wheel centres").map_err(errors::to_py)?;
    let n = c.len();
    let radii = values(radii, n, "wheel radii")?;
    let loads = values(static_loads, n, "wheel static loads")?;
    let rates = values(spring_rates, n, "wheel spring rates")?;
    let damp = values(damping, n, "wheel damping")?;
    let steerable: Vec<bool> = steerable
        .extract()
        .map_err(|_| errors::parameter("steerable must be a sequence of booleans".into()))?;
    if steerable.len() != n {
        return Err(errors::parameter(format!(
            "steerable must have {n} values (one per wheel), got {}",
            steerable.len()
        )));
    }
    Ok((0..n)
        .map(|k| WheelSpec {
            center: Point::new(c[k][0], c[k][1], c[k][2]),
            radius: radii[k],
            steerable: steerable[k],
            static_load: loads[k],
            spring_rate: rates[k],
            damping: damp[k],
        })
        .collect())
}

/// Each wheel's braking: None, or (kind, table, share) as [`BrakeRow`] gives it.
fn brakings(brake: Vec<Option<BrakeRow<'_>>>) -> PyResult<Vec<Option<Braking>>> {
    let mut brakes = Vec::with_capacity(brake.len());
    for (k, b) in brake.into_iter().enumerate() {
        brakes.push(match b {
            None => None,
            Some((kind, t, share)) => Some(braking(&kind, wheel_table(&t, "braking", k)?, share)?),
        });
    }
    Ok(brakes)
}

/// The core's braking of a kind ("fraction", "deceleration" or "distributed" with a share),
/// its (time s, value) table and the share.
fn braking(kind: &str, t: Table, share: Option<Real>) -> PyResult<Braking> {
    Ok(match (kind, share) {
        ("fraction", None) => Braking::Fraction(t),
        ("deceleration", None) => Braking::Deceleration(t),
        ("distributed", Some(share)) => Braking::Distributed {
            deceleration: t,
            share,
        },
        (other, _) => {
            return Err(errors::parameter(format!(
                "braking is ('fraction' | 'deceleration', table) or ('distributed', table, \
                 share), not {other:?}"
            )))
        }
    })
}

/// The core's rules of one braking demand (kind "fraction" or "deceleration", its (time s,
/// value) table): a fraction in [0, 1], a deceleration in [0, 20] m/s^2; ParameterError
/// otherwise (crashsim.Brake checks itself with them when made, a split brake's demand as a
/// deceleration; a vehicle checks each wheel's braking with the same rules).
#[pyfunction]
pub fn check_brake(kind: &str, table: &Bound<'_, PyAny>) -> PyResult<()> {
    let b = braking(kind, self::table(table, "braking")?, None)?;
    b.check().map_err(errors::to_py)
}

/// The steering input: None, or (kind, value) with kind "road_wheel" or "steering_wheel"
/// (a table), "per_wheel" (a table or None per wheel) or "path" (points, preview,
/// min_distance).
fn steer_input(steer: Option<(String, Bound<'_, PyAny>)>) -> PyResult<Option<SteerInput>> {
    Ok(match steer {
        None => None,
        Some((kind, value)) => {
            Some(match kind.as_str() {
                "road_wheel" => SteerInput::RoadWheel(table(&value, "steering")?),
                "steering_wheel" => SteerInput::SteeringWheel(table(&value, "steering wheel")?),
                "per_wheel" => {
                    let tables: Vec<Option<Bound<'_, PyAny>>> = value.extract().map_err(|_| {
                        errors::parameter(
                            "per-wheel steering is a list with one table or None per wheel".into(),
                        )
                    })?;
                    let mut out = Vec::with_capacity(tables.len());
                    for (k, t) in tables.iter().enumerate() {
                        out.push(match t {
                            None => None,
                            Some(t) => Some(wheel_table(t, "steering", k)?),
                        });
                    }
                    SteerInput::PerWheel(out)
                }
                "path" => {
                    let (points, preview, min_distance): (Bound<'_, PyAny>, Option<Real>, Option<Real>) =
                    value.extract().map_err(|_| {
                        errors::parameter(
                            "a driver's path is ((n, 2) points m, preview s or None, min_distance m \
                             or None)"
                                .into(),
                        )
                    })?;
                    let points = rows(&points, 2, "the driver's path")
                        .map_err(errors::to_py)?
                        .into_iter()
                        .map(|p| [p[0], p[1]])
                        .collect();
                    SteerInput::Path(core::vehicle::DriverPath {
                        points,
                        preview: preview.unwrap_or(core::vehicle::DEFAULT_PATH_PREVIEW),
                        min_distance: min_distance
                            .unwrap_or(core::vehicle::DEFAULT_PATH_MIN_DISTANCE),
                    })
                }
                other => {
                    return Err(errors::parameter(format!(
                        "steering is 'road_wheel', 'steering_wheel', 'per_wheel' or 'path', not \
                     {other:?}"
                    )))
                }
            })
        }
    })
}
