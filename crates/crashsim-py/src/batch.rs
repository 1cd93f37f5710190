//! `run_batch`: the core's batch with the GIL released, numpy columns out. The batch runs on
//! its own thread pool while the caller's thread polls every 50 ms: Ctrl-C (or an exception
//! from `progress`) sets the core's interrupt flag, `progress(done, n)` is called from here.
//! The batch's end wakes the caller at once (it does not wait out the poll).

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use crashsim_core as core;
use numpy::{AllowTypeChange, IntoPyArray, PyArrayLikeDyn};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::errors;
use crate::spec::SceneSpec;

/// How often the caller's thread looks at the batch (progress, Ctrl-C).
const POLL: Duration = Duration::from_millis(50);

/// Runs n variants of `spec` (see the stub and python/crashsim/batch.py).
#[pyfunction]
#[pyo3(signature = (spec, overrides, n, *, threads = None, progress = None, max_impacts = 2))]
pub fn run_batch<'py>(
    py: Python<'py>,
    spec: &SceneSpec,
    overrides: Option<&Bound<'py, PyDict>>,
    n: usize,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    max_impacts: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let given = override_arrays(overrides)?;
    if threads == Some(0) {
        return Err(errors::parameter(
            "threads = 0 is invalid: give at least 1 (None: one per core)".into(),
        ));
    }
    let base = &spec.inner;
    let o = core::batch::Overrides::new(base, n, given).map_err(errors::to_py)?;
    let options = core::batch::BatchOptions {
        threads: threads.unwrap_or(0),
        max_impacts,
    };
    let control = core::batch::Control::default();
    let mut failure: Option<PyErr> = None;
    let out = run_polling(
        py,
        || core::batch::run_batch(base, &o, &options, &control),
        &control,
        &progress,
        n,
        &mut failure,
    );
    if let Some(e) = failure {
        return Err(e);
    }
    let out = match out {
        Ok(r) => r.map_err(errors::to_py)?,
        Err(_) => {
            return Err(errors::to_py(core::Error::simulation(
                "internal engine error (the batch's thread panicked); please report it",
            )))
        }
    };
    batch_dict(py, out, &control)
}

/// An override as the core takes it: its name, its array's shape and its values (C order).
type OverrideArray = (String, Vec<usize>, Vec<f64>);

/// The overrides, in the dict's order.
fn override_arrays(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<OverrideArray>> {
    let mut given = Vec::new();
    if let Some(d) = overrides {
        for (key, value) in d.iter() {
            let name: String = key
                .extract()
                .map_err(|_| errors::parameter(format!("override keys are strings, got {key}")))?;
            let a: PyArrayLikeDyn<'_, f64, AllowTypeChange> = value.extract().map_err(|_| {
                errors::parameter(format!("override {name:?} must be an array of numbers"))
            })?;
            let a = a.as_array();
            given.push((name, a.shape().to_vec(), a.iter().copied().collect()));
        }
    }
    Ok(given)
}

/// Runs `batch` on its own thread with the GIL released while the caller's thread polls it
/// every POLL ([`poll`]) until it ends; what the batch's thread returned (Err: it panicked).
/// A Python exception that stopped it is left in `failure`.
fn run_polling<T: Send>(
    py: Python<'_>,
    batch: impl FnOnce() -> T + Send,
    control: &core::batch::Control,
    progress: &Option<Py<PyAny>>,
    n: usize,
    failure: &mut Option<PyErr>,
) -> std::thread::Result<T> {
    // The batch's end unparks the caller: sleeping out the poll added 25 ms on average (up
    // to 50) to every batch, 1.2 % of a 2,000-variant box batch (2 s) and of a study's chunks.
    let ended = AtomicBool::new(false);
    py.detach(|| {
        let caller = std::thread::current();
        std::thread::scope(|s| {
            let worker = s.spawn(|| {
                let out = batch();
                ended.store(true, Ordering::Release);
                caller.unpark();
                out
            });
            let mut reported = usize::MAX;
            loop {
                // a spurious wake-up only polls early
                std::thread::park_timeout(POLL);
                let finished = ended.load(Ordering::Acquire);
                let done = control.done.load(Ordering::Relaxed);
                Python::attach(|py| poll(py, control, progress, done, n, &mut reported, failure));
                if finished {
                    break;
                }
            }
            worker.join()
        })
    })
}

/// One look at the batch from the caller's thread, `done` of its `n` variants finished: a
/// signal (Ctrl-C) sets the interrupt flag, and `progress(done, n)` is called when `done`
/// has changed since `reported`; an exception from either, other than KeyboardInterrupt,
/// is kept in `failure` (after which neither is looked at again).
fn poll(
    py: Python<'_>,
    control: &core::batch::Control,
    progress: &Option<Py<PyAny>>,
    done: usize,
    n: usize,
    reported: &mut usize,
    failure: &mut Option<PyErr>,
) {
    if failure.is_none() {
        if let Err(e) = py.check_signals() {
            // Ctrl-C: keep what finished
            control.interrupt.store(true, Ordering::Relaxed);
            if !e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                *failure = Some(e);
            }
        }
    }
    if let (Some(f), true) = (progress, done != *reported && failure.is_none()) {
        *reported = done;
        if let Err(e) = f.call1(py, (done, n)) {
            control.interrupt.store(true, Ordering::Relaxed);
            // Ctrl-C while the callback ran: keep what finished, as above
            if !e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                *failure = Some(e);
            }
        }
    }
}

/// The batch's output as the dict python/crashsim/batch.py reads: numpy columns, the
/// variants' errors, which finished and whether it was interrupted (by the core's flag in
/// `control` too).
fn batch_dict<'py>(
    py: Python<'py>,
    out: core::batch::BatchOutput,
    control: &core::batch::Control,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let columns = PyList::empty(py);
    for (name, values) in out.columns.columns {
        let array = match values {
            core::batch::Values::Float(v) => v.into_pyarray(py).into_any(),
            core::batch::Values::Int(v) => v.into_pyarray(py).into_any(),
        };
        columns.append((name, array))?;
    }
    d.set_item("columns", columns)?;
    let errs = PyList::empty(py);
    for e in out.errors {
        errs.append((
            e.index,
            core::batch::kind_name(&e.error),
            e.error.to_string(),
            errors::loc_tuple(py, &e.error.loc)?,
            e.error.message.as_str(),
        ))?;
    }
    d.set_item("errors", errs)?;
    d.set_item("finished", out.finished.into_pyarray(py))?;
    // Ctrl-C counts even when it came as the last variants finished: the caller (a study
    // running chunks) must stop too.
    let ctrl_c = control.interrupt.load(Ordering::Relaxed);
    d.set_item("interrupted", out.interrupted || ctrl_c)?;
    Ok(d)
}
