//! The one place that maps core errors onto the Python exception tree:
//!
//! ```text
//! CrashsimError(Exception)
//! ├── InputError(CrashsimError, ValueError)     the input is at fault
//! │   ├── MeshError                             empty or broken mesh
//! │   ├── ParameterError                        non-finite or out-of-range number
//! │   └── InitialOverlapError                   bodies overlap when the run starts
//! └── SimulationError(CrashsimError, RuntimeError)
//! ```

use crashsim_core::{Error, ErrorKind, Place};
use pyo3::exceptions::{PyException, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple, PyType};

static CRASHSIM_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static INPUT_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static MESH_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static PARAMETER_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static INITIAL_OVERLAP_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static SIMULATION_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();

/// A new exception class `name` with the given bases, living in crashsim._core.
fn new_class<'py>(
    py: Python<'py>,
    name: &str,
    doc: &str,
    bases: Vec<Bound<'py, PyType>>,
) -> PyResult<Py<PyType>> {
    let ns = PyDict::new(py);
    ns.set_item("__module__", "crashsim._core")?;
    ns.set_item("__doc__", doc)?;
    let class = py
        .get_type::<PyType>()
        .call1((name, PyTuple::new(py, bases)?, ns))?;
    Ok(class.cast_into::<PyType>()?.unbind())
}

/// Creates the classes and adds them to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    let root = CRASHSIM_ERROR.get_or_try_init(py, || {
        let class = new_class(
            py,
            "CrashsimError",
            "Root of every error crashsim raises. ``loc`` is where it happened, outermost \
             first: a tuple of (kind, index, name) places (kinds: variant, body, bodies, wheel, \
             zone, zones, part, parameter, time), empty when the error is the whole input's; \
             ``message`` is the text without the places written before it (a parameter is \
             named in it with its value; None when the text has no places).",
            vec![py.get_type::<PyException>()],
        )?;
        class.bind(py).setattr("loc", PyTuple::empty(py))?;
        class.bind(py).setattr("message", py.None())?;
        Ok::<_, PyErr>(class)
    })?;
    let input = INPUT_ERROR.get_or_try_init(py, || {
        new_class(
            py,
            "InputError",
            "The input is at fault (a value, a mesh, a parameter).",
            vec![root.bind(py).clone(), py.get_type::<PyValueError>()],
        )
    })?;
    let children: [(&PyOnceLock<Py<PyType>>, &str, &str); 3] = [
        (
            &MESH_ERROR,
            "MeshError",
            "A mesh is empty, has non-finite vertices or out-of-range triangle indices.",
        ),
        (
            &PARAMETER_ERROR,
            "ParameterError",
            "A number is non-finite or outside its accepted range.",
        ),
        (
            &INITIAL_OVERLAP_ERROR,
            "InitialOverlapError",
            "Two bodies of a contact pair overlap when the run starts.",
        ),
    ];
    for (cell, name, doc) in children {
        let class = cell.get_or_try_init(py, || {
            new_class(py, name, doc, vec![input.bind(py).clone()])
        })?;
        m.add(name, class.bind(py))?;
    }
    let sim = SIMULATION_ERROR.get_or_try_init(py, || {
        new_class(
            py,
            "SimulationError",
            "The engine could not complete a run.",
            vec![root.bind(py).clone(), py.get_type::<PyRuntimeError>()],
        )
    })?;
    m.add("CrashsimError", root.bind(py))?;
    m.add("InputError", input.bind(py))?;
    m.add("SimulationError", sim.bind(py))?;
    Ok(())
}

fn raise(cell: &PyOnceLock<Py<PyType>>, message: String) -> PyErr {
    Python::attach(|py| match cell.get(py) {
        Some(class) => PyErr::from_type(class.bind(py).clone(), message),
        None => PyRuntimeError::new_err(message),
    })
}

/// A place as Python sees it: (kind, index, name), with index and name None where they do
/// not apply ("part" and "parameter" have a name and no index; a pair of bodies has two of
/// each; "time" has the time in s as its index).
fn place_tuple<'py>(py: Python<'py>, place: &Place) -> PyResult<Bound<'py, PyTuple>> {
    let none = py.None().into_bound(py);
    let (kind, index, name): (&str, Bound<'py, PyAny>, Bound<'py, PyAny>) = match place {
        Place::Variant(i) => ("variant", i.into_pyobject(py)?.into_any(), none),
        Place::Body(i, n) => (
            "body",
            i.into_pyobject(py)?.into_any(),
            n.clone().into_pyobject(py)?.into_any(),
        ),
        Place::Bodies(ids, names) => (
            "bodies",
            PyTuple::new(py, ids)?.into_any(),
            PyTuple::new(py, names.clone())?.into_any(),
        ),
        Place::Wheel(k) => ("wheel", k.into_pyobject(py)?.into_any(), none),
        Place::Zone(k) => ("zone", k.into_pyobject(py)?.into_any(), none),
        Place::Zones(a, b) => ("zones", PyTuple::new(py, [a, b])?.into_any(), none),
        Place::Part(n) => ("part", none, n.into_pyobject(py)?.into_any()),
        Place::Parameter(n) => ("parameter", none, n.into_pyobject(py)?.into_any()),
        Place::Time(t) => ("time", t.into_pyobject(py)?.into_any(), none),
    };
    PyTuple::new(py, [kind.into_pyobject(py)?.into_any(), index, name])
}

/// A (kind, index, name) tuple of [`place_tuple`] back as the core's [`Place`]; None for a
/// tuple no place gives.
fn place_of(place: &Bound<'_, PyAny>) -> Option<Place> {
    let (kind, index, name): (String, Bound<'_, PyAny>, Bound<'_, PyAny>) = place.extract().ok()?;
    let names = |n: &Bound<'_, PyAny>, count: usize| -> Option<Vec<Option<String>>> {
        if n.is_none() {
            return Some(vec![None; count]);
        }
        n.extract().ok()
    };
    Some(match kind.as_str() {
        "variant" => Place::Variant(index.extract().ok()?),
        "body" => Place::Body(index.extract().ok()?, name.extract().ok()?),
        "bodies" => {
            let ids: Vec<usize> = index.extract().ok()?;
            let n = ids.len();
            Place::Bodies(ids, names(&name, n)?)
        }
        "wheel" => Place::Wheel(index.extract().ok()?),
        "zone" => Place::Zone(index.extract().ok()?),
        "zones" => {
            let (a, b): (usize, usize) = index.extract().ok()?;
            Place::Zones(a, b)
        }
        "part" => Place::Part(name.extract().ok()?),
        "parameter" => Place::Parameter(name.extract().ok()?),
        "time" => Place::Time(index.extract().ok()?),
        _ => return None,
    })
}

/// The text one place of an error's `.loc` puts before its message ("wheel 2",
/// "body 0 (\"red\")", "friction zones 1 and 3", "t = 0.125000 s"), the one rendering the
/// core's messages use; "" for a parameter (the message names it with its value); a
/// ValueError for a tuple that is no place.
#[pyfunction]
pub fn describe_place(place: &Bound<'_, PyAny>) -> PyResult<String> {
    let written = |p: Place| {
        if p.written() {
            p.to_string()
        } else {
            String::new()
        }
    };
    place_of(place).map(written).ok_or_else(|| {
        pyo3::exceptions::PyValueError::new_err(format!(
            "{place} is no place: give (kind, index, name) as an error's .loc holds"
        ))
    })
}

/// The error's place as a tuple of [`place_tuple`]s, outermost first.
pub fn loc_tuple<'py>(py: Python<'py>, loc: &[Place]) -> PyResult<Bound<'py, PyTuple>> {
    let places = loc
        .iter()
        .map(|p| place_tuple(py, p))
        .collect::<PyResult<Vec<_>>>()?;
    PyTuple::new(py, places)
}

/// Maps a core error onto its Python class. The exception's text is the core's rendering
/// ("place: place: message"); it also carries `.loc` (the places, see [`place_tuple`]) and
/// `.message` (the text without the places), so the layers above name a wheel or a zone
/// from its index instead of reading the text.
pub fn to_py(e: Error) -> PyErr {
    let cell = match e.kind {
        ErrorKind::Mesh => &MESH_ERROR,
        ErrorKind::Parameter => &PARAMETER_ERROR,
        ErrorKind::InitialOverlap => &INITIAL_OVERLAP_ERROR,
        ErrorKind::Simulation => &SIMULATION_ERROR,
    };
    let err = raise(cell, e.to_string());
    Python::attach(|py| {
        let value = err.value(py);
        // Setting attributes on a fresh exception instance cannot fail but for memory.
        let _ = loc_tuple(py, &e.loc).and_then(|loc| value.setattr("loc", loc));
        let _ = value.setattr("message", e.message.as_str());
    });
    err
}

/// An input-shape error (wrong array shape or type) as a ParameterError or MeshError.
pub fn parameter(message: String) -> PyErr {
    raise(&PARAMETER_ERROR, message)
}

/// A mesh-array error as a MeshError.
pub fn mesh(message: String) -> PyErr {
    raise(&MESH_ERROR, message)
}
