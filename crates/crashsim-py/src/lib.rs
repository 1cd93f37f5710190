//! crashsim._core: thin pyo3 bindings of crashsim-core.
//!
//! This crate only translates: numpy arrays in and out, the GIL released while the engine
//! runs, and core errors mapped in one place ([`errors::to_py`]) onto the Python exception
//! tree rooted at `CrashsimError`. No physics lives here.

mod batch;
mod convert;
mod errors;
mod ground;
mod joint;
mod run_records;
mod spec;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Arc;

use crashsim_core as core;
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use convert::{pose, triangles as to_triangles, vector3, vertices as to_points};
use spec::body_input;

/// Runs engine code, turning a panic into a SimulationError instead of letting it cross.
fn guarded<T>(f: impl FnOnce() -> core::Result<T>) -> core::Result<T> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "unknown".into());
        Err(core::Error::simulation(format!(
            "internal engine error ({what}); please report it with the scene that caused it"
        )))
    })
}

/// An immutable triangle mesh in a body frame (m) with its bounding-volume hierarchy.
#[pyclass(frozen, module = "crashsim._core")]
pub struct Shape {
    pub(crate) inner: Arc<core::MeshShape>,
}

#[pymethods]
impl Shape {
    #[new]
    fn new(vertices: &Bound<'_, PyAny>, triangles: &Bound<'_, PyAny>) -> PyResult<Self> {
        let v = to_points(vertices)?;
        let t = to_triangles(triangles)?;
        let inner = core::MeshShape::new(v, t).map_err(errors::to_py)?;
        Ok(Shape {
            inner: Arc::new(inner),
        })
    }

    #[getter]
    fn n_vertices(&self) -> usize {
        self.inner.vertices().len()
    }

    #[getter]
    fn n_triangles(&self) -> usize {
        self.inner.triangles().len()
    }

    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        convert::points_to_array(self.inner.vertices()).into_pyarray(py)
    }

    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<u32>> {
        let t = self.inner.triangles();
        Array2::from_shape_fn((t.len(), 3), |(i, k)| t[i][k]).into_pyarray(py)
    }

    /// (mins, maxs) of the vertices, body frame (m).
    fn aabb<'py>(&self, py: Python<'py>) -> (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>) {
        let b = self.inner.aabb();
        (
            Array1::from_iter(b.mins.iter().copied()).into_pyarray(py),
            Array1::from_iter(b.maxs.iter().copied()).into_pyarray(py),
        )
    }

    /// Volume (m^3), centroid (m) and inertia about the centroid (kg m^2 for unit density) of
    /// the mesh as a uniform solid, body frame; meaningful for a closed, outward-wound mesh
    /// (MeshError when it encloses no volume).
    fn solid_properties<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let p = self.inner.solid_properties().map_err(errors::to_py)?;
        solid_properties_to_dict(py, &p)
    }

    /// Distances (m, ascending) at which the ray from `origin` along `direction` (body frame;
    /// normalized here) crosses the mesh, up to `max_distance`.
    #[pyo3(signature = (origin, direction, max_distance = f64::INFINITY))]
    fn ray_hits<'py>(
        &self,
        py: Python<'py>,
        origin: &Bound<'py, PyAny>,
        direction: &Bound<'py, PyAny>,
        max_distance: f64,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let o = vector3(origin, "origin")?;
        let d = vector3(direction, "direction")?;
        let len = d.norm();
        if len == 0.0 || !len.is_finite() {
            return Err(errors::parameter(
                "the ray direction must be a non-zero finite vector".into(),
            ));
        }
        if max_distance.is_nan() || max_distance < 0.0 {
            return Err(errors::parameter(format!(
                "max_distance = {max_distance} is invalid: it must be >= 0 m"
            )));
        }
        let shape = self.inner.clone();
        let hits =
            py.detach(move || shape.ray_hits(&o.into(), &(d / len), max_distance.min(f64::MAX)));
        Ok(hits.into_pyarray(py))
    }

    /// Generalized winding number of each body-frame point, (k,).
    fn winding_numbers<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let pts = to_points(points)?;
        let shape = self.inner.clone();
        let w: Vec<f64> = py.detach(move || shape.winding_numbers(&pts));
        Ok(w.into_pyarray(py))
    }

    /// Pickling (studies send scenes to other processes): rebuilt from its vertices and
    /// triangles, which gives the same hierarchy and so the same results bit for bit.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<u32>>),
    )> {
        let py = slf.py();
        let me = slf.get();
        Ok((
            slf.get_type().into_any(),
            (me.vertices(py), me.triangles(py)),
        ))
    }

    fn __repr__(&self) -> String {
        format!(
            "Shape(n_vertices={}, n_triangles={})",
            self.inner.vertices().len(),
            self.inner.triangles().len()
        )
    }
}

/// True when the two posed meshes' surfaces intersect or one lies inside the other.
/// Checks a soft contact's stiffness (N/m) and damping ratio by the engine's rule
/// (ParameterError naming the bad one).
#[pyfunction]
fn check_soft_contact(stiffness: f64, damping_ratio: f64) -> PyResult<()> {
    core::SoftContact {
        stiffness,
        damping_ratio,
    }
    .validate()
    .map_err(errors::to_py)
}

#[pyfunction]
fn shapes_overlap(
    py: Python<'_>,
    shape1: &Shape,
    position1: &Bound<'_, PyAny>,
    orientation1: &Bound<'_, PyAny>,
    shape2: &Shape,
    position2: &Bound<'_, PyAny>,
    orientation2: &Bound<'_, PyAny>,
) -> PyResult<bool> {
    let p1 = pose(position1, orientation1)?;
    let p2 = pose(position2, orientation2)?;
    let (s1, s2) = (shape1.inner.clone(), shape2.inner.clone());
    py.detach(move || {
        guarded(|| {
            let mut ws = core::overlap::QueryWorkspace::default();
            Ok(core::overlap::shapes_overlap(&s1, &p1, &s2, &p2, &mut ws))
        })
    })
    .map_err(errors::to_py)
}

/// The overlap region S of two posed meshes (world frame).
#[pyfunction]
fn overlap_region<'py>(
    py: Python<'py>,
    shape1: &Shape,
    position1: &Bound<'py, PyAny>,
    orientation1: &Bound<'py, PyAny>,
    shape2: &Shape,
    position2: &Bound<'py, PyAny>,
    orientation2: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let p1 = pose(position1, orientation1)?;
    let p2 = pose(position2, orientation2)?;
    let (s1, s2) = (shape1.inner.clone(), shape2.inner.clone());
    let region = py
        .detach(move || guarded(|| Ok(core::overlap::overlap_region(&s1, &p1, &s2, &p2))))
        .map_err(errors::to_py)?;
    let d = PyDict::new(py);
    d.set_item(
        "points",
        convert::points_to_array(&region.points).into_pyarray(py),
    )?;
    let n = region
        .volume_normal()
        .unwrap_or_else(core::math::Vector::zeros);
    d.set_item(
        "volume_normal",
        convert::vector_to_array(&n).into_pyarray(py),
    )?;
    d.set_item("segment_count", region.segment_count)?;
    d.set_item("inside_vertices", region.inside_vertex_count)?;
    Ok(d)
}

/// A running world: made by SceneSpec.build() (the one path from a scene to the engine).
#[pyclass(module = "crashsim._core")]
pub struct World {
    pub(crate) inner: core::World,
}

#[pymethods]
impl World {
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }

    #[getter]
    fn n_bodies(&self) -> usize {
        self.inner.body_count()
    }

    /// Advances the world by `duration` s with steps of at most `dt` s. `progress`, if given,
    /// is called with the current time (s) at most every 0.1 s of wall time (and Ctrl-C is
    /// honoured then); an exception it raises stops the run and propagates.
    /// `record_interval` (s; None: the core's default) spaces the kept samples;
    /// `max_history_bytes` (None: the core's default, 1 GiB) refuses runs whose history would
    /// be larger.
    #[pyo3(signature = (duration, dt, progress = None, record_interval = None, max_history_bytes = None, until_rest = false))]
    #[allow(clippy::too_many_arguments)]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        duration: f64,
        dt: f64,
        progress: Option<Py<PyAny>>,
        record_interval: Option<f64>,
        max_history_bytes: Option<u64>,
        until_rest: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let options = core::RunOptions {
            record_interval,
            max_history_bytes: max_history_bytes.unwrap_or(core::DEFAULT_MAX_HISTORY_BYTES),
            until_rest,
            history: true,
        };
        run_world(py, &mut self.inner, duration, dt, &options, progress)
    }
}

/// Runs a world with the GIL released: `progress(t)` and Ctrl-C looked at every 0.1 s of wall
/// time; the run's output as a dict (the stub of World.run describes it).
pub(crate) fn run_world<'py>(
    py: Python<'py>,
    world: &mut core::World,
    duration: f64,
    dt: f64,
    options: &core::RunOptions,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut failure: Option<PyErr> = None;
    let out = py.detach(|| {
        let mut last = std::time::Instant::now();
        let mut hook = |t: f64| -> bool {
            if last.elapsed().as_secs_f64() < 0.1 {
                return true;
            }
            last = std::time::Instant::now();
            Python::attach(|py| {
                let called = py.check_signals().and_then(|()| match &progress {
                    Some(f) => f.call1(py, (t,)).map(|_| ()),
                    None => Ok(()),
                });
                match called {
                    Ok(()) => true,
                    Err(e) => {
                        failure = Some(e);
                        false
                    }
                }
            })
        };
        guarded(|| world.run_with_options(duration, dt, options, &mut hook))
    });
    if let Some(e) = failure {
        return Err(e);
    }
    let out = out.map_err(errors::to_py)?;
    run_output_to_dict(py, &out, world.body_count())
}

fn run_output_to_dict<'py>(
    py: Python<'py>,
    out: &core::RunOutput,
    n_bodies: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let k = out.times.len();
    let d = PyDict::new(py);
    d.set_item("t", out.times.clone().into_pyarray(py))?;
    d.set_item("record_interval", out.record_interval)?;
    // Allocated fallibly: a history too large for memory is a MemoryError, never an abort.
    let field = |f: &dyn Fn(&core::BodyState) -> [f64; 4], width: usize| -> PyResult<Array3<f64>> {
        let mut data = Vec::new();
        data.try_reserve_exact(n_bodies * k * width).map_err(|_| {
            pyo3::exceptions::PyMemoryError::new_err(format!(
                "no memory for the run's history ({n_bodies} bodies x {k} samples): record less \
                 often (record_interval)"
            ))
        })?;
        for i in 0..n_bodies {
            for s in 0..k {
                data.extend_from_slice(&f(&out.sample(s)[i])[..width]);
            }
        }
        Ok(Array3::from_shape_vec((n_bodies, k, width), data).expect("the shape fits the data"))
    };
    let v3 = |v: &core::math::Vector| [v.x, v.y, v.z, 0.0];
    d.set_item(
        "position",
        field(&|s| v3(&s.position.coords), 3)?.into_pyarray(py),
    )?;
    d.set_item(
        "orientation",
        field(
            &|s| {
                let q = s.orientation.quaternion();
                [q.w, q.i, q.j, q.k]
            },
            4,
        )?
        .into_pyarray(py),
    )?;
    d.set_item("velocity", field(&|s| v3(&s.velocity), 3)?.into_pyarray(py))?;
    wheels_to_dict(py, &d, out)?;
    d.set_item(
        "angular_velocity",
        field(&|s| v3(&s.angular_velocity), 3)?.into_pyarray(py),
    )?;
    let impacts = PyList::empty(py);
    for imp in &out.impacts {
        impacts.append(run_records::impact(py, imp)?)?;
    }
    d.set_item("impacts", impacts)?;
    let contacts = PyList::empty(py);
    for c in &out.contacts {
        contacts.append(run_records::contact(py, c)?)?;
    }
    d.set_item("contacts", contacts)?;
    joints_to_dict(py, &d, out)?;
    Ok(d)
}

/// The joints' records: `joint_angles`, `joint_force`, `joint_torque` (J, k, 3) (rad, N, N m;
/// the force and torque of body 1 on body 2, world) and `joint_events` (the limits hit).
fn joints_to_dict(py: Python<'_>, d: &Bound<'_, PyDict>, out: &core::RunOutput) -> PyResult<()> {
    let (n, k) = (out.joint_count, out.times.len());
    let field =
        |f: &dyn Fn(&core::joint::JointSample) -> core::math::Vector| -> PyResult<Array3<f64>> {
            let mut data = Vec::new();
            data.try_reserve_exact(n * k * 3).map_err(|_| {
                pyo3::exceptions::PyMemoryError::new_err(format!(
                    "no memory for the run's joints ({n} joints x {k} samples): record less often \
                 (record_interval)"
                ))
            })?;
            for j in 0..n {
                for s in 0..k {
                    let v = f(&out.joints_at(s)[j]);
                    data.extend_from_slice(&[v.x, v.y, v.z]);
                }
            }
            Ok(Array3::from_shape_vec((n, k, 3), data).expect("the shape fits the data"))
        };
    d.set_item("joint_angles", field(&|s| s.angles)?.into_pyarray(py))?;
    d.set_item("joint_force", field(&|s| s.force)?.into_pyarray(py))?;
    d.set_item("joint_torque", field(&|s| s.torque)?.into_pyarray(py))?;
    let events = PyList::empty(py);
    for e in &out.joint_events {
        let item = PyDict::new(py);
        item.set_item("joint", e.joint)?;
        item.set_item("limit", e.limit)?;
        item.set_item("time", e.time)?;
        item.set_item("rate", e.rate)?;
        events.append(item)?;
    }
    d.set_item("joint_events", events)?;
    Ok(())
}

/// Volume (m^3), centroid (m) and inertia about the centroid (kg m^2 for unit density) of
/// the solid bounded by a closed, outward-wound triangle mesh (no BVH is built); MeshError
/// when it encloses no volume.
#[pyfunction]
fn solid_properties<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    triangles: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let v = to_points(vertices)?;
    let t = to_triangles(triangles)?;
    if t.is_empty() {
        return Err(errors::mesh("the mesh has no triangles".into()));
    }
    if let Some(bad) = t.iter().flatten().find(|&&k| k as usize >= v.len()) {
        return Err(errors::mesh(format!(
            "a triangle refers to vertex {bad} but the mesh has only {} vertices",
            v.len()
        )));
    }
    let p = py
        .detach(move || core::mass::solid_properties(&v, &t))
        .map_err(errors::to_py)?;
    solid_properties_to_dict(py, &p)
}

fn solid_properties_to_dict<'py>(
    py: Python<'py>,
    p: &core::SolidProperties,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("volume", p.volume)?;
    d.set_item(
        "centroid",
        convert::vector_to_array(&p.centroid.coords).into_pyarray(py),
    )?;
    let i = p.inertia;
    d.set_item(
        "inertia",
        Array2::from_shape_fn((3, 3), |(r, c)| i[(r, c)]).into_pyarray(py),
    )?;
    Ok(d)
}

/// The state of a body after `dt` s of torque-free motion (negative `dt` runs it back):
/// (position, orientation (w, x, y, z), velocity, angular_velocity), world frame, SI.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[allow(clippy::type_complexity)]
fn free_motion<'py>(
    py: Python<'py>,
    mass: f64,
    inertia: &Bound<'py, PyAny>,
    position: &Bound<'py, PyAny>,
    orientation: &Bound<'py, PyAny>,
    velocity: &Bound<'py, PyAny>,
    angular_velocity: &Bound<'py, PyAny>,
    dt: f64,
) -> PyResult<(
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
)> {
    let (props, state) = body_input(
        mass,
        inertia,
        position,
        orientation,
        velocity,
        angular_velocity,
    )?;
    core::error::require_finite("dt", dt).map_err(errors::to_py)?;
    let body = core::RigidBody::new(props, &state).map_err(errors::to_py)?;
    let s = py.detach(move || body.advanced(dt).state());
    let q = s.orientation.quaternion();
    Ok((
        convert::vector_to_array(&s.position.coords).into_pyarray(py),
        Array1::from_vec(vec![q.w, q.i, q.j, q.k]).into_pyarray(py),
        convert::vector_to_array(&s.velocity).into_pyarray(py),
        convert::vector_to_array(&s.angular_velocity).into_pyarray(py),
    ))
}

/// The wheels' records: `wheel_counts` (per body), `wheel_contact` (W, k, 3) m,
/// `wheel_load` (W, k) N, `wheel_force` (W, k, 3) N, `wheel_sliding` (W, k) bool,
/// `wheel_steer` (W, k) rad (each wheel's road-wheel angle about the body z axis); and
/// `rest` (per body: the time it came to rest, s, or None).
fn wheels_to_dict(py: Python<'_>, d: &Bound<'_, PyDict>, out: &core::RunOutput) -> PyResult<()> {
    let n: usize = out.wheel_counts.iter().sum();
    let k = out.len();
    let memory = |what: &str| {
        pyo3::exceptions::PyMemoryError::new_err(format!(
            "no memory for the run's {what} ({n} wheels x {k} samples): record less often \
             (record_interval)"
        ))
    };
    let mut contact = Vec::new();
    let mut force = Vec::new();
    let mut load = Vec::new();
    let mut sliding = Vec::new();
    let mut steer = Vec::new();
    contact
        .try_reserve_exact(n * k * 3)
        .map_err(|_| memory("wheel contacts"))?;
    force
        .try_reserve_exact(n * k * 3)
        .map_err(|_| memory("wheel forces"))?;
    load.try_reserve_exact(n * k)
        .map_err(|_| memory("wheel loads"))?;
    sliding
        .try_reserve_exact(n * k)
        .map_err(|_| memory("wheel marks"))?;
    steer
        .try_reserve_exact(n * k)
        .map_err(|_| memory("wheel steering"))?;
    for w in 0..n {
        for s in 0..k {
            let sample = &out.wheels_at(s)[w];
            contact.extend_from_slice(sample.contact.coords.as_slice());
            force.extend_from_slice(sample.force.as_slice());
            load.push(sample.load);
            sliding.push(sample.sliding);
            steer.push(sample.steer);
        }
    }
    let shape3 = |v: Vec<f64>| Array3::from_shape_vec((n, k, 3), v).expect("the shape fits");
    d.set_item("wheel_counts", out.wheel_counts.clone())?;
    d.set_item("wheel_contact", shape3(contact).into_pyarray(py))?;
    d.set_item("wheel_force", shape3(force).into_pyarray(py))?;
    d.set_item(
        "wheel_load",
        Array2::from_shape_vec((n, k), load)
            .expect("the shape fits")
            .into_pyarray(py),
    )?;
    d.set_item(
        "wheel_sliding",
        Array2::from_shape_vec((n, k), sliding)
            .expect("the shape fits")
            .into_pyarray(py),
    )?;
    d.set_item(
        "wheel_steer",
        Array2::from_shape_vec((n, k), steer)
            .expect("the shape fits")
            .into_pyarray(py),
    )?;
    d.set_item("rest", out.rest.clone())?;
    Ok(())
}

/// Static loads (N) of wheels at body-frame (x, y) positions (m from the CG) carrying
/// `weight` (N) on level ground (each axle its share), and with `towed` ((x, y), N) the load a
/// trailer puts on the hitch there.
#[pyfunction]
#[pyo3(signature = (xy, weight, towed = None))]
fn static_loads<'py>(
    py: Python<'py>,
    xy: &Bound<'py, PyAny>,
    weight: f64,
    towed: Option<([f64; 2], f64)>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let a: numpy::PyArrayLike2<'_, f64, numpy::AllowTypeChange> = xy
        .extract()
        .map_err(|_| errors::parameter("wheel positions must be an (n, 2) array".into()))?;
    let a = a.as_array();
    if a.ncols() != 2 {
        return Err(errors::parameter(format!(
            "wheel positions must have shape (n, 2), got {:?}",
            a.shape()
        )));
    }
    let pts: Vec<[f64; 2]> = a.rows().into_iter().map(|r| [r[0], r[1]]).collect();
    let loads = core::vehicle::static_loads_towing(&pts, weight, towed).map_err(errors::to_py)?;
    Ok(Array1::from_vec(loads).into_pyarray(py))
}

/// The engine's checks of a body's mass (kg, finite and positive) and inertia (kg m^2, a
/// finite, symmetric, positive definite 3x3 tensor), as a scene spec's add_body makes them.
#[pyfunction]
fn check_mass(mass: f64, inertia: &Bound<'_, PyAny>) -> PyResult<()> {
    let zero = [0.0; 3].into_pyobject(inertia.py())?.into_any();
    let identity = [1.0, 0.0, 0.0, 0.0].into_pyobject(inertia.py())?.into_any();
    body_input(mass, inertia, &zero, &identity, &zero, &zero).map(|_| ())
}

/// The engine's checks of a moving body's initial state (position m, orientation quaternion
/// (w, x, y, z) or 3x3 rotation, velocity m/s, angular velocity rad/s; world frame), as a
/// scene spec's add_body makes them.
#[pyfunction]
fn check_state(
    position: &Bound<'_, PyAny>,
    orientation: &Bound<'_, PyAny>,
    velocity: &Bound<'_, PyAny>,
    angular_velocity: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let eye = Array2::<f64>::eye(3).into_pyarray(position.py());
    let (_, state) = body_input(
        1.0,
        eye.as_any(),
        position,
        orientation,
        velocity,
        angular_velocity,
    )?;
    state.validate().map_err(errors::to_py)
}

/// The engine's checks of a fixed body's pose (position m, orientation), as a scene spec's
/// add_obstacle makes them.
#[pyfunction]
fn check_pose(position: &Bound<'_, PyAny>, orientation: &Bound<'_, PyAny>) -> PyResult<()> {
    core::spec::check_pose(&pose(position, orientation)?).map_err(errors::to_py)
}

/// The engine's check that a pair's parameters have the face stiffness they need (auto
/// depth of penetration, the stiffness centroid): each side is its faces' (A N/m, B N/m^2)
/// or None in the order front, rear, left, right and whether it is a fixed obstacle; the
/// error is placed at body 0 or 1, the side that lacks it.
#[pyfunction]
fn check_contact_stiffness(
    params: &spec::ContactParams,
    faces1: Vec<Option<Bound<'_, PyAny>>>,
    obstacle1: bool,
    faces2: Vec<Option<Bound<'_, PyAny>>>,
    obstacle2: bool,
) -> PyResult<()> {
    let stiffness = |faces: &[Option<Bound<'_, PyAny>>]| -> PyResult<core::Stiffness> {
        let mut s = core::Stiffness::none();
        for (face, value) in core::Face::ALL.iter().zip(faces) {
            if let Some(f) = convert::face_stiffness(value.as_ref(), face.name())? {
                s = s.with(*face, f);
            }
        }
        Ok(s)
    };
    let (s1, s2) = (stiffness(&faces1)?, stiffness(&faces2)?);
    params
        .inner
        .check_stiffness([(0, &s1, obstacle1), (1, &s2, obstacle2)])
        .map_err(errors::to_py)
}

/// True when (x, y) (m) lies inside the polygon ((k, 2) corners, m) or on its edge: the
/// engine's friction-zone test.
#[pyfunction]
fn point_in_polygon(x: f64, y: f64, polygon: Vec<[f64; 2]>) -> bool {
    core::ground::point_in_polygon(x, y, &polygon)
}

/// Checks a (k, 2) table of (time s, value) by the core's rules (increasing times, finite
/// numbers, at least one row): a ParameterError naming it `name` otherwise.
#[pyfunction]
fn check_table(table: &Bound<'_, PyAny>, name: &str) -> PyResult<()> {
    ground::table(table, name).map(|_| ())
}

/// Static loads (N) of wheels at body-frame (x, y) positions carrying `weight` N at rest
/// with `groups` of wheels sharing their load (index lists), a trailer's `coupling` (x, y)
/// and a `towed` load ((x, y), N) on its hitch: each wheel's load and the coupling's.
#[pyfunction]
#[pyo3(signature = (xy, weight, groups = Vec::new(), coupling = None, towed = None))]
fn wheel_loads(
    xy: Vec<[f64; 2]>,
    weight: f64,
    groups: Vec<Vec<usize>>,
    coupling: Option<[f64; 2]>,
    towed: Option<([f64; 2], f64)>,
) -> PyResult<(Vec<f64>, f64)> {
    core::vehicle::wheel_loads(&xy, &groups, weight, coupling, towed).map_err(errors::to_py)
}

/// (spring rate N/m, damping N s/m) of a wheel with `static_load` N sprung at
/// `natural_frequency` Hz (None: the engine's 1.3) with `damping_ratio` (None: 0.3).
#[pyfunction]
#[pyo3(signature = (static_load, natural_frequency = None, damping_ratio = None))]
fn suspension(
    static_load: f64,
    natural_frequency: Option<f64>,
    damping_ratio: Option<f64>,
) -> PyResult<(f64, f64)> {
    let w = core::vehicle::WheelSpec::sprung(
        core::math::Point::origin(),
        1.0,
        false,
        static_load,
        natural_frequency.unwrap_or(core::vehicle::DEFAULT_NATURAL_FREQUENCY),
        damping_ratio.unwrap_or(core::vehicle::DEFAULT_DAMPING_RATIO),
    )
    .map_err(errors::to_py)?;
    Ok((w.spring_rate, w.damping))
}

/// The engine's defaults for the ground, wheels and tyres, and its rest thresholds.
#[pyfunction]
fn dynamics_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    let t = core::vehicle::Tyre::default();
    let core::vehicle::TyreModel::Linear { cornering } = t.model else {
        unreachable!("the default tyre is the reconstruction programs' linear tyre")
    };
    d.set_item("gravity", core::vehicle::GRAVITY)?;
    d.set_item(
        "natural_frequency",
        core::vehicle::DEFAULT_NATURAL_FREQUENCY,
    )?;
    d.set_item("damping_ratio", core::vehicle::DEFAULT_DAMPING_RATIO)?;
    d.set_item("cornering", cornering)?;
    d.set_item("load_sensitivity", t.load_sensitivity)?;
    d.set_item("ackermann", core::vehicle::DEFAULT_ACKERMANN)?;
    d.set_item("relaxation_length", t.relaxation_length)?;
    d.set_item("rolling_resistance", t.rolling_resistance)?;
    d.set_item("tyre_friction", core::ground::DEFAULT_TYRE_FRICTION)?;
    d.set_item("body_friction", core::ground::DEFAULT_BODY_FRICTION)?;
    let [b, c, e] = core::vehicle::MAGIC_FORMULA_DEFAULTS;
    d.set_item("magic_formula_b", b)?;
    d.set_item("magic_formula_c", c)?;
    d.set_item("magic_formula_e", e)?;
    d.set_item("rest_speed", core::world::REST_SPEED)?;
    d.set_item("rest_yaw_rate", core::world::REST_YAW_RATE)?;
    d.set_item("rest_turn_speed", core::world::REST_TURN_SPEED)?;
    d.set_item("rest_time", core::world::REST_TIME)?;
    Ok(d)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    m.add_class::<Shape>()?;
    m.add_class::<World>()?;
    m.add_class::<spec::SceneSpec>()?;
    m.add_class::<spec::ContactParams>()?;
    m.add_class::<joint::Joint>()?;
    m.add_class::<ground::Tyre>()?;
    m.add_class::<ground::GroundValue>()?;
    m.add_function(wrap_pyfunction!(batch::run_batch, m)?)?;
    m.add_function(wrap_pyfunction!(shapes_overlap, m)?)?;
    m.add_function(wrap_pyfunction!(check_soft_contact, m)?)?;
    m.add_function(wrap_pyfunction!(overlap_region, m)?)?;
    m.add_function(wrap_pyfunction!(free_motion, m)?)?;
    m.add_function(wrap_pyfunction!(solid_properties, m)?)?;
    m.add_function(wrap_pyfunction!(static_loads, m)?)?;
    m.add_function(wrap_pyfunction!(wheel_loads, m)?)?;
    m.add_function(wrap_pyfunction!(check_table, m)?)?;
    m.add_function(wrap_pyfunction!(ground::check_friction_zone, m)?)?;
    m.add_function(wrap_pyfunction!(ground::check_ground_friction, m)?)?;
    m.add_function(wrap_pyfunction!(ground::check_brake, m)?)?;
    m.add_function(wrap_pyfunction!(ground::check_wheel_switch, m)?)?;
    m.add_function(wrap_pyfunction!(ground::check_steering_ratio, m)?)?;
    m.add_function(wrap_pyfunction!(convert::check_face_stiffness, m)?)?;
    m.add_function(wrap_pyfunction!(errors::describe_place, m)?)?;
    m.add_function(wrap_pyfunction!(point_in_polygon, m)?)?;
    m.add_function(wrap_pyfunction!(check_mass, m)?)?;
    m.add_function(wrap_pyfunction!(check_state, m)?)?;
    m.add_function(wrap_pyfunction!(check_pose, m)?)?;
    m.add_function(wrap_pyfunction!(check_contact_stiffness, m)?)?;
    m.add_function(wrap_pyfunction!(spec::check_vehicle, m)?)?;
    m.add_function(wrap_pyfunction!(suspension, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics_defaults, m)?)?;
    Ok(())
}
