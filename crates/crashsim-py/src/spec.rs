//! The scene spec and the contact parameters as Python values (translation only: every
//! check is the core's).

use crashsim_core as core;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::convert::{self, matrix3, rotation, vector3};
use crate::joint::Joint;
use crate::{errors, ground, Shape, World};

/// One vehicle pair's contact parameters, checked by the engine when made (contact.rs
/// documents each: default, unit, range). Immutable.
#[pyclass(frozen, eq, module = "crashsim._core")]
#[derive(Clone, PartialEq)]
pub struct ContactParams {
    pub inner: core::ContactParams,
}

#[pymethods]
impl ContactParams {
    /// None takes the engine's default for that parameter.
    #[new]
    #[pyo3(signature = (
        *, depth_of_penetration = None, restitution = None, friction = None,
        restitution_mode = "total", centroid = "auto", centroid_point = None,
        centroid_body = None, normal = "horizontal", normal_vector = None, pitch = None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        depth_of_penetration: Option<&Bound<'_, PyAny>>,
        restitution: Option<f64>,
        friction: Option<f64>,
        restitution_mode: &str,
        centroid: &str,
        centroid_point: Option<&Bound<'_, PyAny>>,
        centroid_body: Option<usize>,
        normal: &str,
        normal_vector: Option<&Bound<'_, PyAny>>,
        pitch: Option<f64>,
    ) -> PyResult<Self> {
        let d = core::ContactParams::default();
        let default_pitch = match d.normal {
            core::NormalMode::Horizontal { pitch } => pitch,
            _ => 0.0,
        };
        let inner = convert::contact_params(
            depth_of_penetration,
            restitution.unwrap_or(d.restitution),
            friction.unwrap_or(d.friction),
            restitution_mode,
            centroid,
            centroid_point,
            centroid_body,
            normal,
            normal_vector,
            pitch.unwrap_or(default_pitch),
        )?;
        inner.validate().map_err(errors::to_py)?;
        Ok(ContactParams { inner })
    }

    /// Time from first overlap to the exchange (s), or "auto".
    #[getter]
    fn depth_of_penetration<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(match self.inner.depth_of_penetration {
            core::DepthOfPenetration::Fixed(t) => t.into_pyobject(py)?.into_any(),
            core::DepthOfPenetration::Auto => "auto".into_pyobject(py)?.into_any(),
        })
    }

    #[getter]
    fn restitution(&self) -> f64 {
        self.inner.restitution
    }

    #[getter]
    fn friction(&self) -> f64 {
        self.inner.friction
    }

    /// "total" or "normal".
    #[getter]
    fn restitution_mode(&self) -> &'static str {
        match self.inner.restitution_mode {
            core::RestitutionMode::Total => "total",
            core::RestitutionMode::Normal => "normal",
        }
    }

    /// "auto", "stiffness", "world" or "body".
    #[getter]
    fn centroid(&self) -> &'static str {
        match self.inner.centroid {
            core::CentroidMode::Auto => "auto",
            core::CentroidMode::Stiffness => "stiffness",
            core::CentroidMode::World(_) => "world",
            core::CentroidMode::Body { .. } => "body",
        }
    }

    /// The fixed centroid (m; world, or the body's frame), or None.
    #[getter]
    fn centroid_point<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        match &self.inner.centroid {
            core::CentroidMode::World(p) | core::CentroidMode::Body { point: p, .. } => {
                Some(convert::vector_to_array(&p.coords).into_pyarray(py))
            }
            _ => None,
        }
    }

    #[getter]
    fn centroid_body(&self) -> Option<usize> {
        match self.inner.centroid {
            core::CentroidMode::Body { body, .. } => Some(body),
            _ => None,
        }
    }

    /// "horizontal", "volume" or "vector".
    #[getter]
    fn normal(&self) -> &'static str {
        match self.inner.normal {
            core::NormalMode::Horizontal { .. } => "horizontal",
            core::NormalMode::Volume => "volume",
            core::NormalMode::Fixed(_) => "vector",
        }
    }

    #[getter]
    fn normal_vector<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        match &self.inner.normal {
            core::NormalMode::Fixed(v) => Some(convert::vector_to_array(v).into_pyarray(py)),
            _ => None,
        }
    }

    /// Tilt of the horizontal normal (rad); 0 for the other normals.
    #[getter]
    fn pitch(&self) -> f64 {
        match self.inner.normal {
            core::NormalMode::Horizontal { pitch } => pitch,
            _ => 0.0,
        }
    }

    /// True when the parameters need face stiffness on both vehicles.
    #[getter]
    fn needs_stiffness(&self) -> bool {
        self.inner.needs_stiffness()
    }

    fn __repr__(&self) -> String {
        format!("ContactParams({:?})", self.inner)
    }
}

/// A whole scene as a value (crashsim-core's SceneSpec): bodies, obstacles, the ground,
/// wheels, contacts, stiffness and the run's options; each value checked by the engine at the
/// call that sets it. Serialisable (to_json / from_json, pickle).
#[pyclass(module = "crashsim._core")]
#[derive(Clone)]
pub struct SceneSpec {
    pub inner: core::SceneSpec,
}

#[pymethods]
impl SceneSpec {
    #[new]
    fn new() -> Self {
        SceneSpec {
            inner: core::SceneSpec::new(),
        }
    }

    #[getter]
    fn n_bodies(&self) -> usize {
        self.inner.bodies.len()
    }

    /// The bodies' names, in order.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.inner.bodies.iter().map(|b| b.name.clone()).collect()
    }

    /// Adds a moving body; returns its index.
    #[pyo3(signature = (shape, mass, inertia, position, orientation, velocity, angular_velocity, name = None))]
    #[allow(clippy::too_many_arguments)]
    fn add_body(
        &mut self,
        shape: &Shape,
        mass: f64,
        inertia: &Bound<'_, PyAny>,
        position: &Bound<'_, PyAny>,
        orientation: &Bound<'_, PyAny>,
        velocity: &Bound<'_, PyAny>,
        angular_velocity: &Bound<'_, PyAny>,
        name: Option<String>,
    ) -> PyResult<usize> {
        let (props, state) = body_input(
            mass,
            inertia,
            position,
            orientation,
            velocity,
            angular_velocity,
        )?;
        self.inner
            .add_body(name, shape.inner.clone(), props, state)
            .map_err(errors::to_py)
    }

    /// Adds a fixed obstacle with its mesh at a pose; returns its index.
    #[pyo3(signature = (shape, position, orientation, name = None))]
    fn add_obstacle(
        &mut self,
        shape: &Shape,
        position: &Bound<'_, PyAny>,
        orientation: &Bound<'_, PyAny>,
        name: Option<String>,
    ) -> PyResult<usize> {
        let pose = convert::pose(position, orientation)?;
        self.inner
            .add_obstacle(name, shape.inner.clone(), pose)
            .map_err(errors::to_py)
    }

    /// Gives a moving body its own friction with the ground (in (0, 2]), in place of the
    /// ground's body friction: a person's clothing on the road.
    fn set_ground_friction(&mut self, body: usize, friction: f64) -> PyResult<()> {
        self.inner
            .set_ground_friction(body, friction)
            .map_err(errors::to_py)
    }

    /// Puts the scene on the ground (a Ground, checked when it was made).
    fn set_ground(&mut self, ground: &ground::GroundValue) {
        self.inner.set_ground(ground.inner.clone());
    }

    /// Gives a body wheels, a tyre, the steering linkage, anti-roll bars and driver inputs:
    /// [`VehicleArgs`]' keywords (see the stub).
    #[pyo3(signature = (body, **keywords))]
    fn set_vehicle(&mut self, body: usize, keywords: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        let spec = VehicleArgs::from_keywords("set_vehicle", keywords)?.spec()?;
        self.inner.set_vehicle(body, spec).map_err(errors::to_py)
    }

    /// Adds `joint` between body1 and body2 (None: the world): `frame1` (anchor m, axes
    /// quaternion w, x, y, z) in body1's frame and `frame2` in body2's (or the world's), the
    /// same frame when the run starts; `name` for the engine's messages. Returns its index.
    #[pyo3(signature = (joint, body1, body2, frame1, frame2, name = None))]
    fn add_joint(
        &mut self,
        joint: &Joint,
        body1: usize,
        body2: Option<usize>,
        frame1: (Bound<'_, PyAny>, Bound<'_, PyAny>),
        frame2: (Bound<'_, PyAny>, Bound<'_, PyAny>),
        name: Option<String>,
    ) -> PyResult<usize> {
        let frame = |(p, q): &(Bound<'_, PyAny>, Bound<'_, PyAny>)| -> PyResult<_> {
            Ok((
                core::math::Point::from(vector3(p, "the joint's anchor")?),
                rotation(q)?,
            ))
        };
        let mut spec = joint.inner.clone();
        spec.name = name.unwrap_or_default();
        spec.body1 = body1;
        spec.body2 = body2;
        spec.frame1 = frame(&frame1)?;
        spec.frame2 = frame(&frame2)?;
        self.inner.add_joint(spec).map_err(errors::to_py)
    }

    /// Number of joints.
    #[getter]
    fn n_joints(&self) -> usize {
        self.inner.joints.len()
    }

    /// Sets the pair's parameters; the normal points from body1 into body2.
    fn set_contact(&mut self, body1: usize, body2: usize, params: &ContactParams) -> PyResult<()> {
        self.inner
            .set_contact(body1, body2, params.inner.clone())
            .map_err(errors::to_py)
    }

    /// Makes two bodies never collide (their meshes pass through each other).
    fn set_no_contact(&mut self, body1: usize, body2: usize) -> PyResult<()> {
        self.inner
            .set_no_contact(body1, body2)
            .map_err(errors::to_py)
    }

    /// The pairs that never collide, (lower index, higher).
    #[getter]
    fn no_contact(&self) -> Vec<(usize, usize)> {
        self.inner.no_contact.clone()
    }

    /// Gives two bodies a compliant contact (stiffness N/m, damping ratio) in place of the
    /// timer and the exchange.
    fn set_soft_contact(
        &mut self,
        body1: usize,
        body2: usize,
        stiffness: f64,
        damping_ratio: f64,
    ) -> PyResult<()> {
        self.inner
            .set_soft_contact(
                body1,
                body2,
                core::SoftContact {
                    stiffness,
                    damping_ratio,
                },
            )
            .map_err(errors::to_py)
    }

    /// The soft pairs, (lower index, higher, stiffness N/m, damping ratio).
    #[getter]
    fn soft_contacts(&self) -> Vec<(usize, usize, f64, f64)> {
        self.inner
            .soft_contacts
            .iter()
            .map(|&(a, b, s)| (a, b, s.stiffness, s.damping_ratio))
            .collect()
    }

    /// Sets a body's face stiffness: each face (A, B) in (N/m, N/m^2) or None.
    #[pyo3(signature = (body, *, front = None, rear = None, left = None, right = None))]
    fn set_stiffness(
        &mut self,
        body: usize,
        front: Option<&Bound<'_, PyAny>>,
        rear: Option<&Bound<'_, PyAny>>,
        left: Option<&Bound<'_, PyAny>>,
        right: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let mut s = core::Stiffness::none();
        for (face, value) in [
            (core::Face::Front, front),
            (core::Face::Rear, rear),
            (core::Face::Left, left),
            (core::Face::Right, right),
        ] {
            if let Some(f) = convert::face_stiffness(value, face.name())? {
                s = s.with(face, f);
            }
        }
        self.inner.set_stiffness(body, s).map_err(errors::to_py)
    }

    /// The run: duration (s; with until_rest the longest), largest step dt (s), the kept
    /// samples' spacing record_interval (s; None: the engine's), the history limit (bytes;
    /// None: 2**30), until_rest (needs a ground). The duration, step and interval are checked
    /// here (RunSpec::check); the ground and the history's size when the scene runs.
    #[pyo3(signature = (duration, dt, *, record_interval = None, max_history_bytes = None, until_rest = false))]
    fn set_run(
        &mut self,
        duration: f64,
        dt: f64,
        record_interval: Option<f64>,
        max_history_bytes: Option<u64>,
        until_rest: bool,
    ) -> PyResult<()> {
        let run = core::RunSpec {
            duration,
            dt,
            options: core::RunOptions {
                record_interval,
                max_history_bytes: max_history_bytes.unwrap_or(core::DEFAULT_MAX_HISTORY_BYTES),
                until_rest,
                history: true,
            },
        };
        run.check().map_err(errors::to_py)?;
        self.inner.run = run;
        Ok(())
    }

    /// (duration s, dt s, until_rest) of the run.
    #[getter]
    fn run_options(&self) -> (f64, f64, bool) {
        let r = &self.inner.run;
        (r.duration, r.dt, r.options.until_rest)
    }

    /// A fresh engine world holding the scene at t = 0 (every value checked).
    fn build(&self) -> PyResult<World> {
        let inner = self.inner.build().map_err(errors::to_py)?;
        Ok(World { inner })
    }

    /// Builds the scene and runs it with its run options (set_run); `progress(t)` as
    /// World.run calls it. Returns World.run's dict.
    #[pyo3(signature = (progress = None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut world = self.inner.build().map_err(errors::to_py)?;
        let r = self.inner.run;
        crate::run_world(py, &mut world, r.duration, r.dt, &r.options, progress)
    }

    /// The scene as JSON text (meshes as vertices and triangles, each shared mesh once).
    fn to_json(&self, py: Python<'_>) -> String {
        let spec = &self.inner;
        py.detach(|| core::spec::to_json(spec))
    }

    /// A scene from the JSON text of to_json (checked as the setup calls check).
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str) -> PyResult<SceneSpec> {
        let inner = py
            .detach(|| core::spec::from_json(text))
            .map_err(errors::to_py)?;
        Ok(SceneSpec { inner })
    }

    /// Pickled as its JSON (UTF-8 bytes): the same scene, bit for bit.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        let py = slf.py();
        let text = slf.borrow().to_json(py);
        let from = slf.get_type().getattr("_from_json_bytes")?;
        Ok((from, (PyBytes::new(py, text.as_bytes()),)))
    }

    #[staticmethod]
    fn _from_json_bytes(py: Python<'_>, data: &[u8]) -> PyResult<SceneSpec> {
        let text = std::str::from_utf8(data)
            .map_err(|e| errors::parameter(format!("a pickled scene spec is not UTF-8: {e}")))?;
        SceneSpec::from_json(py, text)
    }

    fn __repr__(&self) -> String {
        format!(
            "SceneSpec(bodies={:?}, contacts={}, ground={})",
            self.names(),
            self.inner.contacts.len(),
            self.inner.ground.is_some()
        )
    }
}

/// Checked mass properties and state of a body from Python values (SI, world frame).
pub fn body_input(
    mass: f64,
    inertia: &Bound<'_, PyAny>,
    position: &Bound<'_, PyAny>,
    orientation: &Bound<'_, PyAny>,
    velocity: &Bound<'_, PyAny>,
    angular_velocity: &Bound<'_, PyAny>,
) -> PyResult<(core::MassProperties, core::BodyState)> {
    let props =
        core::MassProperties::new(mass, matrix3(inertia, "inertia")?).map_err(errors::to_py)?;
    let state = core::BodyState {
        position: vector3(position, "position")?.into(),
        orientation: rotation(orientation)?,
        velocity: vector3(velocity, "velocity")?,
        angular_velocity: vector3(angular_velocity, "angular_velocity")?,
    };
    Ok((props, state))
}

/// set_vehicle's (and check_vehicle's) keywords as one value: wheels (body frame, m, N,
/// N/m, N s/m), tyre, linkage, bars (N m/rad), ABS, inputs, coupling, hitch load (m, N) and
/// load groups; the stub gives each one's shape. Only translation: the rules are the core's.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
struct VehicleArgs<'py> {
    centers: Bound<'py, PyAny>,
    radii: Bound<'py, PyAny>,
    steerable: Bound<'py, PyAny>,
    static_loads: Bound<'py, PyAny>,
    spring_rates: Bound<'py, PyAny>,
    damping: Bound<'py, PyAny>,
    #[pyo3(default)]
    tyre: Option<PyRef<'py, ground::Tyre>>,
    #[pyo3(default)]
    steering_ratio: Option<f64>,
    #[pyo3(default)]
    ackermann: Option<f64>,
    #[pyo3(default)]
    steering_reference: Option<String>,
    #[pyo3(default)]
    steering_interpolation: Option<String>,
    #[pyo3(default)]
    anti_roll: Vec<(usize, usize, f64)>,
    #[pyo3(default = true)]
    abs: bool,
    #[pyo3(default)]
    steer: Option<(String, Bound<'py, PyAny>)>,
    #[pyo3(default)]
    brake: Vec<Option<ground::BrakeRow<'py>>>,
    #[pyo3(default)]
    drive: Vec<Option<Bound<'py, PyAny>>>,
    #[pyo3(default)]
    switches: Vec<Bound<'py, PyAny>>,
    #[pyo3(default)]
    coupling: Option<Bound<'py, PyAny>>,
    #[pyo3(default)]
    hitch_load: Option<(Bound<'py, PyAny>, f64)>,
    #[pyo3(default)]
    load_groups: Vec<Vec<usize>>,
}

impl<'py> VehicleArgs<'py> {
    /// The keywords every call needs, and those it may give.
    const REQUIRED: [&'static str; 6] = [
        "centers",
        "radii",
        "steerable",
        "static_loads",
        "spring_rates",
        "damping",
    ];
    const OPTIONAL: [&'static str; 14] = [
        "tyre",
        "steering_ratio",
        "ackermann",
        "steering_reference",
        "steering_interpolation",
        "anti_roll",
        "abs",
        "steer",
        "brake",
        "drive",
        "switches",
        "coupling",
        "hitch_load",
        "load_groups",
    ];

    /// From `function`'s keywords, refusing an unknown or missing one with Python's own
    /// TypeError, as a signature would.
    fn from_keywords(function: &str, keywords: Option<&Bound<'py, PyDict>>) -> PyResult<Self> {
        let type_error = |m: String| PyErr::new::<pyo3::exceptions::PyTypeError, _>(m);
        let Some(keywords) = keywords else {
            return Err(type_error(format!(
                "{function}() missing required keyword argument: 'centers'"
            )));
        };
        for key in keywords.keys() {
            let key: String = key.extract()?;
            if !Self::REQUIRED.contains(&key.as_str()) && !Self::OPTIONAL.contains(&key.as_str()) {
                return Err(type_error(format!(
                    "{function}() got an unexpected keyword argument '{key}'"
                )));
            }
        }
        for key in Self::REQUIRED {
            if !keywords.contains(key)? {
                return Err(type_error(format!(
                    "{function}() missing required keyword argument: '{key}'"
                )));
            }
        }
        keywords.as_any().extract()
    }

    /// The core's VehicleSpec.
    fn spec(self) -> PyResult<core::vehicle::VehicleSpec> {
        let hitch_load = match self.hitch_load {
            Some((p, f)) => Some((core::math::Point::from(vector3(&p, "the hitch")?), f)),
            None => None,
        };
        let coupling = match self.coupling {
            Some(c) => Some(core::math::Point::from(vector3(&c, "coupling")?)),
            None => None,
        };
        let reference = match self.steering_reference.as_deref() {
            None | Some("outer") => core::vehicle::SteerReference::Outer,
            Some("centre") | Some("center") => core::vehicle::SteerReference::Centre,
            Some(other) => {
                return Err(errors::parameter(format!(
                    "steering_reference = {other:?} is unknown: the input's road-wheel angle is \
                     the 'outer' wheel's (the reconstruction programs') or the axle 'centre''s"
                )))
            }
        };
        let interpolation = match self.steering_interpolation.as_deref() {
            None | Some("input") => core::vehicle::SteerInterpolation::Input,
            Some("wheels") => core::vehicle::SteerInterpolation::Wheels,
            Some(other) => {
                return Err(errors::parameter(format!(
                    "steering_interpolation = {other:?} is unknown: between a steering table's \
                     points either the 'input' is linear and each wheel follows it through the \
                     linkage (a real linkage), or each of the 'wheels' moves linearly between \
                     its angles at the points (a reconstruction program's steering ramp)"
                )))
            }
        };
        let linkage = core::vehicle::Steering {
            ratio: self.steering_ratio,
            ackermann: self.ackermann.unwrap_or(core::vehicle::DEFAULT_ACKERMANN),
            reference,
            interpolation,
        };
        let mut spec = ground::vehicle(
            &self.centers,
            &self.radii,
            &self.steerable,
            &self.static_loads,
            &self.spring_rates,
            &self.damping,
            self.tyre.as_deref(),
            linkage,
            self.anti_roll,
            self.abs,
            self.steer,
            self.brake,
            self.drive,
            self.switches,
        )?;
        spec.coupling = coupling;
        spec.hitch_load = hitch_load;
        spec.load_groups = self.load_groups;
        Ok(spec)
    }
}

/// The core's checks of a vehicle of `mass` kg (VehicleSpec::validate), set_vehicle's
/// keywords without a body: every rule but the wheels' place in the body's outline, which
/// is checked too when the body's `shape` (body frame, m) is given. No scene is made.
#[pyfunction]
#[pyo3(signature = (mass, *, shape = None, **keywords))]
pub fn check_vehicle(
    mass: f64,
    shape: Option<&Shape>,
    keywords: Option<&Bound<'_, PyDict>>,
) -> PyResult<()> {
    let spec = VehicleArgs::from_keywords("check_vehicle", keywords)?.spec()?;
    spec.validate(shape.map(|s| s.inner.aabb()), mass)
        .map_err(errors::to_py)
}
