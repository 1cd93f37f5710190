//! Python values <-> the core's ground, wheels, tyres and driver inputs. Translation only.

use core::ground::{FrictionZone, Ground};
use core::math::{Point, Real};
use core::vehicle::{
    Braking, DriverInputs, Table, Trigger, Tyre, TyreModel, VehicleSpec, WheelSpec, WheelState,
    WheelSwitch,
};
use crashsim_core as core;
use numpy::{AllowTypeChange, PyArrayLike1, PyArrayLike2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors;

/// An (n, k) float array-like with `k` columns.
fn rows(obj: &Bound<'_, PyAny>, k: usize, name: &str) -> PyResult<Vec<Vec<Real>>> {
    let a: PyArrayLike2<'_, f64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| errors::parameter(format!("{name} must be an (n, {k}) array of numbers")))?;
    let a = a.as_array();
    if a.ncols() != k {
        return Err(errors::parameter(format!(
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
    let r = rows(obj, 2, name)?;
    let points: Vec<(Real, Real)> = r.iter().map(|p| (p[0], p[1])).collect();
    Table::new(name, &points).map_err(errors::to_py)
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
        let corners = rows(poly, 2, &format!("friction zone {k}"))?;
        z.push(FrictionZone {
            polygon: corners.iter().map(|c| [c[0], c[1]]).collect(),
            friction: *friction,
        });
    }
    base.with_friction(tyre_friction, body_friction)
        .and_then(|g| g.with_zones(z))
        .map_err(errors::to_py)
}

/// A tyre from a dict (missing keys take the core's defaults).
pub fn tyre(d: Option<&Bound<'_, PyDict>>) -> PyResult<Tyre> {
    let mut t = Tyre::default();
    let Some(d) = d else {
        return Ok(t);
    };
    let get = |key: &str| -> PyResult<Option<Real>> {
        match d.get_item(key)? {
            Some(v) if !v.is_none() => {
                Ok(Some(v.extract().map_err(|_| {
                    errors::parameter(format!("tyre {key} must be a number"))
                })?))
            }
            _ => Ok(None),
        }
    };
    let model: String = match d.get_item("model")? {
        Some(v) if !v.is_none() => v
            .extract()
            .map_err(|_| errors::parameter("tyre model must be a string".into()))?,
        _ => "linear".into(),
    };
    t.model = match model.as_str() {
        "linear" => TyreModel::Linear {
            saturation_angle: get("saturation_angle")?.unwrap_or(10f64.to_radians()),
        },
        "magic_formula" => TyreModel::MagicFormula {
            b: get("b")?.unwrap_or(core::vehicle::MAGIC_FORMULA_DEFAULTS[0]),
            c: get("c")?.unwrap_or(core::vehicle::MAGIC_FORMULA_DEFAULTS[1]),
            e: get("e")?.unwrap_or(core::vehicle::MAGIC_FORMULA_DEFAULTS[2]),
        },
        other => {
            return Err(errors::parameter(format!(
                "tyre model {other:?} is unknown: use \"linear\" (the reconstruction tyre) or \
                 \"magic_formula\""
            )))
        }
    };
    if let Some(v) = get("relaxation_length")? {
        t.relaxation_length = v;
    }
    if let Some(v) = get("rolling_resistance")? {
        t.rolling_resistance = v;
    }
    Ok(t)
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
    let at = match trigger.as_str() {
        "time" => Trigger::Time(when),
        "exchange" => {
            if when < 1.0 || when.fract() != 0.0 {
                return Err(errors::parameter(format!(
                    "a wheel-state switch at exchange {when}: give a whole number from 1"
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
    let state = match state.as_str() {
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

/// A vehicle from the arrays and lists of `World.set_vehicle`.
#[allow(clippy::too_many_arguments)]
pub fn vehicle(
    centers: &Bound<'_, PyAny>,
    radii: &Bound<'_, PyAny>,
    steerable: &Bound<'_, PyAny>,
    static_loads: &Bound<'_, PyAny>,
    spring_rates: &Bound<'_, PyAny>,
    damping: &Bound<'_, PyAny>,
    tyre_params: Option<&Bound<'_, PyDict>>,
    steer: Option<&Bound<'_, PyAny>>,
    brake: Vec<Option<(String, Bound<'_, PyAny>)>>,
    drive: Vec<Option<Bound<'_, PyAny>>>,
    switches: Vec<Bound<'_, PyAny>>,
) -> PyResult<VehicleSpec> {
    let c = rows(centers, 3, "wheel centres")?;
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
    let wheels = (0..n)
        .map(|k| WheelSpec {
            center: Point::new(c[k][0], c[k][1], c[k][2]),
            radius: radii[k],
            steerable: steerable[k],
            static_load: loads[k],
            spring_rate: rates[k],
            damping: damp[k],
        })
        .collect();
    let mut brakes = Vec::with_capacity(brake.len());
    for (k, b) in brake.into_iter().enumerate() {
        brakes.push(match b {
            None => None,
            Some((kind, t)) => {
                let t = table(&t, &format!("wheel {k} braking"))?;
                Some(match kind.as_str() {
                    "fraction" => Braking::Fraction(t),
                    "deceleration" => Braking::Deceleration(t),
                    other => {
                        return Err(errors::parameter(format!(
                            "braking is a 'fraction' of the friction or a 'deceleration', not \
                             {other:?}"
                        )))
                    }
                })
            }
        });
    }
    let mut drives = Vec::with_capacity(drive.len());
    for (k, d) in drive.into_iter().enumerate() {
        drives.push(match d {
            None => None,
            Some(t) => Some(table(&t, &format!("wheel {k} drive force"))?),
        });
    }
    let inputs = DriverInputs {
        steer: steer.map(|s| table(s, "steering")).transpose()?,
        brake: brakes,
        drive: drives,
        switches: switches.iter().map(switch).collect::<PyResult<_>>()?,
    };
    Ok(VehicleSpec {
        wheels,
        tyre: tyre(tyre_params)?,
        inputs,
    })
}
