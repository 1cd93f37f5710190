//! Batches: many variants of one base [`SceneSpec`] over a rayon thread pool.
//!
//! A variant is the base spec with per-variant overrides ([`Overrides`]: initial states,
//! masses, contact parameters, ground frictions). Each variant is built and run alone on one
//! thread (nothing in a run is parallel or shared), so its results are the same bits whatever
//! the pool's size, and the same as running that spec alone. A run keeps no history
//! ([`RunOptions::history`] false): only what the summary's columns need (the impacts, the
//! last state, the rest times), so memory does not grow with the batch.
//!
//! The summary ([`Columns`]) has one row per variant (the column list of
//! docs/batch-contract.md, units m, m/s, s, J, deg): the number of exchanges; per
//! exchange k up to `max_impacts` its time and dissipated energy and per vehicle its
//! delta-V (magnitude, world x and y, EDR longitudinal and lateral) and PDOF; per vehicle the
//! sum of its delta-V magnitudes, its final position, heading and speed, and its rest time,
//! position and heading. A failed or unfinished variant has NaN (floats) and -1 (ints).
//!
//! [`RunOptions::history`]: crate::world::RunOptions::history

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::body::MassProperties;
use crate::contact::{DepthOfPenetration, NormalMode};
use crate::error::{Error, Place, Result};
use crate::math::{Real, Rotation, Vector};
use crate::spec::{BodyMotion, SceneSpec};
use crate::world::{degrees, heading, magnitude, RunOutput};

/// What an override changes; the per-variant shape in brackets (V vehicles = moving bodies in
/// the spec's order, P pairs = the spec's contacts in order).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// `position` [V, 3]: world CG position (m).
    Position,
    /// `orientation` [V, 4]: quaternion (w, x, y, z), body -> world (normalised).
    Orientation,
    /// `velocity` [V, 3]: world CG velocity (m/s).
    Velocity,
    /// `angular_velocity` [V, 3]: world (rad/s).
    AngularVelocity,
    /// `mass` \[V\]: kg; the inertia scales by the same ratio (radii of gyration kept) and a
    /// vehicle's wheels keep their natural frequencies (static loads, spring rates and
    /// damping scale with it).
    Mass,
    /// `contact.restitution` \[P\]: 1, in [0, 1].
    Restitution,
    /// `contact.friction` \[P\]: 1, >= 0.
    Friction,
    /// `contact.depth_of_penetration` \[P\]: s in [0, 0.060]; NaN = automatic.
    DepthOfPenetration,
    /// `contact.pitch` \[P\]: rad in [-pi/2, pi/2], for pairs with the horizontal normal.
    Pitch,
    /// `ground.tyre_friction` []: tyre-road friction outside friction zones, in (0, 2].
    TyreFriction,
    /// `ground.body_friction` []: body-ground friction, in (0, 2].
    BodyFriction,
}

impl Key {
    /// Every key with its name.
    pub const ALL: [(Key, &'static str); 11] = [
        (Key::Position, "position"),
        (Key::Orientation, "orientation"),
        (Key::Velocity, "velocity"),
        (Key::AngularVelocity, "angular_velocity"),
        (Key::Mass, "mass"),
        (Key::Restitution, "contact.restitution"),
        (Key::Friction, "contact.friction"),
        (Key::DepthOfPenetration, "contact.depth_of_penetration"),
        (Key::Pitch, "contact.pitch"),
        (Key::TyreFriction, "ground.tyre_friction"),
        (Key::BodyFriction, "ground.body_friction"),
    ];

    /// The key of a name; a ParameterError naming it (and the known ones) otherwise.
    pub fn parse(name: &str) -> Result<Key> {
        Key::ALL
            .iter()
            .find(|(_, n)| *n == name)
            .map(|(k, _)| *k)
            .ok_or_else(|| {
                let known: Vec<&str> = Key::ALL.iter().map(|(_, n)| *n).collect();
                Error::invalid(format!(
                    "unknown override {name:?}: the overrides are {}",
                    known.join(", ")
                ))
            })
    }

    /// The key's name.
    pub fn name(self) -> &'static str {
        Key::ALL
            .iter()
            .find(|(k, _)| *k == self)
            .map(|(_, n)| *n)
            .expect("every key is named")
    }

    /// The shape of one variant's values for `v` vehicles and `p` pairs.
    fn variant_shape(self, v: usize, p: usize) -> Vec<usize> {
        match self {
            Key::Position | Key::Velocity | Key::AngularVelocity => vec![v, 3],
            Key::Orientation => vec![v, 4],
            Key::Mass => vec![v],
            Key::Restitution | Key::Friction | Key::DepthOfPenetration | Key::Pitch => vec![p],
            Key::TyreFriction | Key::BodyFriction => vec![],
        }
    }
}

/// Per-variant values of a base spec's inputs, checked against it: every key known, every
/// array of shape (n, ...) as [`Key`] says. Values are checked per variant (a bad one fails
/// that variant only).
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    n: usize,
    /// (key, values of all variants, row-major: variant after variant).
    entries: Vec<(Key, Vec<Real>)>,
}

fn shape_text(s: &[usize]) -> String {
    let inner: Vec<String> = s.iter().map(|x| x.to_string()).collect();
    if s.len() == 1 {
        format!("({},)", inner[0])
    } else {
        format!("({})", inner.join(", "))
    }
}

impl Overrides {
    /// Overrides of `n` variants of `base`: each (name, shape, row-major values). An unknown
    /// name, a wrong shape, a key the base scene cannot take (a ground key without a ground,
    /// a pitch on a pair whose normal is not horizontal) or a repeated key is a
    /// ParameterError naming the key.
    pub fn new(
        base: &SceneSpec,
        n: usize,
        given: Vec<(String, Vec<usize>, Vec<Real>)>,
    ) -> Result<Overrides> {
        let v = base.moving().len();
        let p = base.contacts.len();
        let mut entries: Vec<(Key, Vec<Real>)> = Vec::with_capacity(given.len());
        for (name, shape, values) in given {
            let key = Key::parse(&name)?;
            let mut want = vec![n];
            want.extend(key.variant_shape(v, p));
            if shape != want {
                return Err(Error::invalid(format!(
                    "override {name:?} has shape {} but needs {} (n = {n} variants{})",
                    shape_text(&shape),
                    shape_text(&want),
                    match key {
                        Key::TyreFriction | Key::BodyFriction => String::new(),
                        Key::Restitution | Key::Friction | Key::DepthOfPenetration | Key::Pitch => {
                            format!(", {p} pairs")
                        }
                        _ => format!(", {v} vehicles"),
                    }
                )));
            }
            if values.len() != want.iter().product::<usize>() {
                return Err(Error::invalid(format!(
                    "override {name:?} has {} values for shape {}",
                    values.len(),
                    shape_text(&want)
                )));
            }
            if entries.iter().any(|(k, _)| *k == key) {
                return Err(Error::invalid(format!("override {name:?} is given twice")));
            }
            if matches!(key, Key::TyreFriction | Key::BodyFriction) && base.ground.is_none() {
                return Err(Error::invalid(format!(
                    "override {name:?} needs a ground: the scene has none"
                )));
            }
            if key == Key::Pitch {
                if let Some(c) = base
                    .contacts
                    .iter()
                    .find(|c| !matches!(c.params.normal, NormalMode::Horizontal { .. }))
                {
                    return Err(Error::invalid(format!(
                        "override {name:?}: the pair ({}, {}) has no horizontal normal, so no \
                         pitch (the pitch tilts the horizontal normal only)",
                        base.bodies[c.body1].name, base.bodies[c.body2].name
                    )));
                }
            }
            entries.push((key, values));
        }
        Ok(Overrides { n, entries })
    }

    /// Number of variants.
    pub fn len(&self) -> usize {
        self.n
    }

    /// True for no variants.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// `base` with variant `i`'s values (checked: a value out of range is the engine's error).
    pub fn apply(&self, base: &SceneSpec, i: usize) -> Result<SceneSpec> {
        let mut spec = base.clone();
        let moving = spec.moving();
        for (key, all) in &self.entries {
            let width = all.len() / self.n.max(1);
            let row = &all[i * width..(i + 1) * width];
            match key {
                Key::Position
                | Key::Velocity
                | Key::AngularVelocity
                | Key::Orientation
                | Key::Mass => {
                    for (slot, &b) in moving.iter().enumerate() {
                        let body = &mut spec.bodies[b];
                        let BodyMotion::Moving {
                            props,
                            state,
                            vehicle,
                        } = &mut body.motion
                        else {
                            unreachable!("moving() lists moving bodies")
                        };
                        let v3 = |k: usize| Vector::new(row[3 * k], row[3 * k + 1], row[3 * k + 2]);
                        match key {
                            Key::Position => state.position = v3(slot).into(),
                            Key::Velocity => state.velocity = v3(slot),
                            Key::AngularVelocity => state.angular_velocity = v3(slot),
                            Key::Orientation => {
                                let q = &row[4 * slot..4 * slot + 4];
                                state.orientation =
                                    rotation(q).map_err(|e| at_body(e, b, &body.name))?;
                            }
                            Key::Mass => {
                                let m = row[slot];
                                let ratio = m / props.mass();
                                *props = MassProperties::new(m, props.inertia() * ratio)
                                    .map_err(|e| at_body(e, b, &body.name))?;
                                if let Some(v) = vehicle {
                                    for w in &mut v.wheels {
                                        w.static_load *= ratio;
                                        w.spring_rate *= ratio;
                                        w.damping *= ratio;
                                    }
                                }
                            }
                            _ => unreachable!("a per-vehicle key"),
                        }
                        state.validate().map_err(|e| at_body(e, b, &body.name))?;
                    }
                }
                Key::Restitution | Key::Friction | Key::DepthOfPenetration | Key::Pitch => {
                    for (c, &x) in spec.contacts.iter_mut().zip(row) {
                        let p = &mut c.params;
                        match key {
                            Key::Restitution => p.restitution = x,
                            Key::Friction => p.friction = x,
                            Key::DepthOfPenetration => {
                                p.depth_of_penetration = if x.is_nan() {
                                    DepthOfPenetration::Auto
                                } else {
                                    DepthOfPenetration::Fixed(x)
                                }
                            }
                            Key::Pitch => p.normal = NormalMode::Horizontal { pitch: x },
                            _ => unreachable!("a per-pair key"),
                        }
                    }
                }
                Key::TyreFriction | Key::BodyFriction => {
                    let g = spec.ground.take().expect("checked: the scene has a ground");
                    let (tyre, body) = match key {
                        Key::TyreFriction => (row[0], g.body_friction()),
                        _ => (g.tyre_friction(), row[0]),
                    };
                    spec.ground = Some(g.with_friction(tyre, body)?);
                }
            }
        }
        // Ranges of the pairs' parameters (and every other value) are the build's checks.
        for c in &spec.contacts {
            c.params.validate().map_err(|e| {
                e.at(Place::bodies(c.body1, c.body2))
                    .with_body_names(&spec.body_names())
            })?;
        }
        Ok(spec)
    }
}

fn rotation(q: &[Real]) -> Result<Rotation> {
    let q = nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]);
    let norm = q.norm();
    if !norm.is_finite() || norm == 0.0 {
        return Err(Error::invalid(
            "orientation must be a finite, non-zero quaternion (w, x, y, z)",
        ));
    }
    // As the bindings read a quaternion (convert.rs), so a variant equals the same scene run
    // alone.
    Ok(Rotation::new_normalize(q))
}

/// The error at body `b`, named.
fn at_body(e: Error, b: usize, name: &str) -> Error {
    e.at(Place::Body(b, Some(name.to_string())))
}

/// One column of a batch's summary, one value per variant.
#[derive(Clone, Debug, PartialEq)]
pub enum Values {
    /// Floats; NaN for a failed or unfinished variant (or a figure that does not apply).
    Float(Vec<Real>),
    /// Integers; -1 for a failed or unfinished variant.
    Int(Vec<i64>),
}

/// The summary columns of a batch, in the contract's order.
#[derive(Clone, Debug, PartialEq)]
pub struct Columns {
    /// (name, values) per column.
    pub columns: Vec<(String, Values)>,
}

/// A variant that failed: its index, the error (its message prefixed "variant i: ").
#[derive(Clone, Debug, PartialEq)]
pub struct VariantError {
    /// The variant's index.
    pub index: usize,
    /// The engine's error.
    pub error: Error,
}

/// What a batch returns.
#[derive(Clone, Debug, PartialEq)]
pub struct BatchOutput {
    /// The summary, one row per variant.
    pub columns: Columns,
    /// The variants that failed, by index.
    pub errors: Vec<VariantError>,
    /// Per variant: true when it ran (to the end or to its error); false when the batch was
    /// interrupted before it finished.
    pub finished: Vec<bool>,
    /// True when the interrupt flag stopped the batch.
    pub interrupted: bool,
}

/// How a batch runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BatchOptions {
    /// Threads of the pool (0: rayon's default, one per core). Each variant runs on one.
    pub threads: usize,
    /// Exchanges reported per variant as columns (the first ones, in time order); default 2.
    pub max_impacts: usize,
}

impl Default for BatchOptions {
    fn default() -> Self {
        BatchOptions {
            threads: 0,
            max_impacts: 2,
        }
    }
}

/// A batch's controls, shared with the caller's thread: set `interrupt` to stop (variants
/// under way stop at their next step and count as unfinished; finished ones are kept);
/// `done` counts the variants finished (run or failed).
#[derive(Debug, Default)]
pub struct Control {
    /// Stop as soon as possible.
    pub interrupt: AtomicBool,
    /// Variants finished so far.
    pub done: AtomicUsize,
}

/// The columns' names for vehicles `names` and `max_impacts` exchanges, and which are ints.
fn column_names(names: &[String], max_impacts: usize) -> Vec<(String, bool)> {
    let mut out = vec![("n_impacts".to_string(), true)];
    for k in 1..=max_impacts {
        out.push((format!("impact{k}.time"), false));
        out.push((format!("impact{k}.energy"), false));
        for n in names {
            for f in [
                "delta_v",
                "delta_v_x",
                "delta_v_y",
                "delta_v_long",
                "delta_v_lat",
                "pdof_deg",
            ] {
                out.push((format!("impact{k}.{n}.{f}"), false));
            }
        }
    }
    for n in names {
        for f in [
            "total_delta_v",
            "final_x",
            "final_y",
            "final_heading_deg",
            "final_speed",
            "rest_time",
            "rest_x",
            "rest_y",
            "rest_heading_deg",
        ] {
            out.push((format!("{n}.{f}"), false));
        }
    }
    out
}

/// One variant's row (n_impacts, then the float columns in order) from its run.
fn summary(spec: &SceneSpec, out: &RunOutput, max_impacts: usize) -> (i64, Vec<Real>) {
    let moving = spec.moving();
    let mut row = Vec::new();
    for k in 0..max_impacts {
        let imp = out.impacts.get(k);
        row.push(imp.map_or(Real::NAN, |i| i.time));
        row.push(imp.map_or(Real::NAN, |i| i.energy_dissipated));
        for &b in &moving {
            let side = imp.and_then(|i| {
                if i.body1 == b {
                    Some(0)
                } else if i.body2 == b {
                    Some(1)
                } else {
                    None
                }
            });
            match (imp, side) {
                (Some(i), Some(s)) => {
                    let dv = i.delta_v(s);
                    let body = i.delta_v_body[s];
                    row.extend([
                        magnitude(&dv),
                        dv.x,
                        dv.y,
                        body.x,
                        -body.y,
                        i.pdof_deg[s].unwrap_or(Real::NAN),
                    ]);
                }
                _ => row.extend([Real::NAN; 6]),
            }
        }
    }
    let last = out.sample(out.len() - 1);
    for &b in &moving {
        let mut total = 0.0;
        for i in &out.impacts {
            if i.body1 == b {
                total += magnitude(&i.delta_v(0));
            } else if i.body2 == b {
                total += magnitude(&i.delta_v(1));
            }
        }
        let s = &last[b];
        let h = degrees(heading(&s.orientation));
        row.extend([total, s.position.x, s.position.y, h, magnitude(&s.velocity)]);
        match out.rest[b] {
            Some(t) => row.extend([t, s.position.x, s.position.y, h]),
            None => row.extend([Real::NAN; 4]),
        }
    }
    (out.impacts.len() as i64, row)
}

/// The engine's error class name of an error (as the Python exception tree names it).
pub fn kind_name(e: &Error) -> &'static str {
    e.kind.class_name()
}

enum Outcome {
    Done(i64, Vec<Real>),
    Failed(Error),
    NotRun,
}

/// Runs variant `i`: overrides applied, built, run without history, summarised. A panic is
/// caught and becomes a SimulationError of this variant.
fn run_variant(
    base: &SceneSpec,
    overrides: &Overrides,
    i: usize,
    max_impacts: usize,
    control: &Control,
) -> Outcome {
    if control.interrupt.load(Ordering::Relaxed) {
        return Outcome::NotRun;
    }
    let attempt = catch_unwind(AssertUnwindSafe(|| -> Result<(i64, Vec<Real>)> {
        let mut spec = overrides.apply(base, i)?;
        spec.run.options.history = false;
        let out = spec.run_with_progress(&mut |_| !control.interrupt.load(Ordering::Relaxed))?;
        Ok(summary(&spec, &out, max_impacts))
    }));
    let outcome = match attempt {
        Ok(Ok((n, row))) => Outcome::Done(n, row),
        Ok(Err(_)) if control.interrupt.load(Ordering::Relaxed) => Outcome::NotRun,
        Ok(Err(e)) => Outcome::Failed(e),
        Err(payload) => {
            let what = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "unknown".into());
            Outcome::Failed(Error::simulation(format!(
                "internal engine error ({what}); please report it with the scene that caused it"
            )))
        }
    };
    if !matches!(outcome, Outcome::NotRun) {
        control.done.fetch_add(1, Ordering::Relaxed);
    }
    outcome
}

/// Runs every variant of `base` given by `overrides` on a pool of `options.threads` threads.
/// Fails as a whole only when the pool cannot be made; a variant's error is listed in
/// [`BatchOutput::errors`] and the others run.
pub fn run_batch(
    base: &SceneSpec,
    overrides: &Overrides,
    options: &BatchOptions,
    control: &Control,
) -> Result<BatchOutput> {
    let n = overrides.len();
    let names: Vec<String> = base
        .moving()
        .iter()
        .map(|&b| base.bodies[b].name.clone())
        .collect();
    let layout = column_names(&names, options.max_impacts);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
        .map_err(|e| Error::simulation(format!("the batch's thread pool failed to start: {e}")))?;
    let outcomes: Vec<Outcome> = pool.install(|| {
        (0..n)
            .into_par_iter()
            .map(|i| run_variant(base, overrides, i, options.max_impacts, control))
            .collect()
    });
    let mut columns: Vec<(String, Values)> = layout
        .iter()
        .map(|(name, int)| {
            let v = if *int {
                Values::Int(vec![-1; n])
            } else {
                Values::Float(vec![Real::NAN; n])
            };
            (name.clone(), v)
        })
        .collect();
    let mut errors = Vec::new();
    let mut finished = vec![false; n];
    for (i, o) in outcomes.into_iter().enumerate() {
        match o {
            Outcome::Done(count, row) => {
                finished[i] = true;
                let (first, rest) = columns.split_first_mut().expect("n_impacts is a column");
                if let Values::Int(v) = &mut first.1 {
                    v[i] = count;
                }
                for ((_, col), x) in rest.iter_mut().zip(row) {
                    if let Values::Float(v) = col {
                        v[i] = x;
                    }
                }
            }
            Outcome::Failed(e) => {
                finished[i] = true;
                let e = e.with_body_names(&base.body_names()).at(Place::Variant(i));
                errors.push(VariantError { index: i, error: e });
            }
            Outcome::NotRun => {}
        }
    }
    let interrupted = control.interrupt.load(Ordering::Relaxed) && finished.iter().any(|f| !f);
    Ok(BatchOutput {
        columns: Columns { columns },
        errors,
        finished,
        interrupted,
    })
}
