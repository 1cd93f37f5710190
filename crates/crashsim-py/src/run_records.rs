//! What a run returns, as Python values: each impulse exchange and each entry of the contact
//! log is the core's record (`Impact`, `ContactEvent`) serialized field by field
//! (crates/crashsim-core/src/world/events.rs says how) into a dict of floats, ints, bools,
//! str, None and nested sequences by pythonize. The binding names no field:
//! python/crashsim/records.py reads the dicts in one place.

use crashsim_core as core;
use pyo3::prelude::*;

/// One impulse exchange as a dict keyed by the core record's field names (world frame, SI).
pub fn impact<'py>(py: Python<'py>, imp: &core::Impact) -> PyResult<Bound<'py, PyAny>> {
    Ok(pythonize::pythonize(py, imp)?)
}

/// One entry of the contact log as a dict: `body1`, `body2`, `time`, `kind` and, for a
/// skipped exchange, its `reason`.
pub fn contact<'py>(py: Python<'py>, event: &core::ContactEvent) -> PyResult<Bound<'py, PyAny>> {
    Ok(pythonize::pythonize(py, event)?)
}
