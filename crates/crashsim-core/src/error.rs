//! Errors of the engine. Every fallible public function returns [`Result`].
//!
//! The variants map one to one onto the Python exception tree in crashsim-py
//! (`MeshError`, `ParameterError`, `InitialOverlapError`, `SimulationError`).

use crate::math::Real;

/// What went wrong, with a message that says how to fix it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A mesh is empty, has non-finite vertices or out-of-range indices.
    #[error("{0}")]
    Mesh(String),
    /// A number is non-finite or outside its accepted range.
    #[error("{0}")]
    Parameter(String),
    /// Two bodies of a contact pair already overlap when a run starts.
    #[error("{0}")]
    InitialOverlap(String),
    /// The engine could not complete a run.
    #[error("{0}")]
    Simulation(String),
}

/// The engine's result type.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// A parameter error naming the parameter, its value and the accepted range.
    pub fn parameter(name: &str, value: impl std::fmt::Display, expected: &str) -> Self {
        Error::Parameter(format!("{name} = {value} is invalid: {expected}"))
    }
}

/// Checks that `value` is finite.
pub fn require_finite(name: &str, value: Real) -> Result<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(Error::parameter(name, value, "it must be a finite number"))
    }
}

/// Largest world coordinate (m) a position, a ground height or a terrain may have: 1000 km.
/// Beyond it a double's rounding grows past the engine's tolerances (at 1e30 m a wheel's
/// 0.05 m of spring travel is below one unit in the last place, so a car on a plane at
/// z = 1e30 skidded with no load on its tyres); a scene in a national grid belongs in
/// coordinates from a local origin.
pub const MAX_COORDINATE: Real = 1e6;

/// Checks that `value` (m) is a finite world coordinate within [`MAX_COORDINATE`].
pub fn require_coordinate(name: &str, value: Real) -> Result<()> {
    require_finite(name, value)?;
    if value.abs() <= MAX_COORDINATE {
        Ok(())
    } else {
        Err(Error::parameter(
            name,
            format!("{value} m"),
            "world coordinates must lie within +-1e6 m (1000 km): place the scene near the \
             origin (subtract a local reference point from every coordinate)",
        ))
    }
}

/// Checks that every component of `v` is finite.
pub fn require_finite_vector(name: &str, v: &crate::math::Vector) -> Result<()> {
    if crate::math::is_finite_vector(v) {
        Ok(())
    } else {
        Err(Error::parameter(
            name,
            format!("[{}, {}, {}]", v.x, v.y, v.z),
            "every component must be a finite number",
        ))
    }
}
