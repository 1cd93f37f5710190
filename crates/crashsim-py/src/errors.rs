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

use crashsim_core::Error;
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
        new_class(
            py,
            "CrashsimError",
            "Root of every error crashsim raises.",
            vec![py.get_type::<PyException>()],
        )
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

/// Maps a core error onto its Python class.
pub fn to_py(e: Error) -> PyErr {
    match e {
        Error::Mesh(m) => raise(&MESH_ERROR, m),
        Error::Parameter(m) => raise(&PARAMETER_ERROR, m),
        Error::InitialOverlap(m) => raise(&INITIAL_OVERLAP_ERROR, m),
        Error::Simulation(m) => raise(&SIMULATION_ERROR, m),
    }
}

/// An input-shape error (wrong array shape or type) as a ParameterError or MeshError.
pub fn parameter(message: String) -> PyErr {
    raise(&PARAMETER_ERROR, message)
}

/// A mesh-array error as a MeshError.
pub fn mesh(message: String) -> PyErr {
    raise(&MESH_ERROR, message)
}
