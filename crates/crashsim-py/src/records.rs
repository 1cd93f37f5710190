//! What a run returns, as Python values: each impulse exchange is the core's `Impact`
//! serialized field by field (crates/crashsim-core/src/world/events.rs says how) into a dict
//! of floats, ints, bools, str, None and nested lists by pythonize. The binding names no
//! field: python/crashsim/records.py reads the dict in one place.

use crashsim_core as core;
use pyo3::prelude::*;

/// One impulse exchange as a dict keyed by the core record's field names (world frame, SI).
pub fn impact<'py>(py: Python<'py>, imp: &core::Impact) -> PyResult<Bound<'py, PyAny>> {
    Ok(pythonize::pythonize(py, imp)?)
}
