//! Errors of the engine. Every fallible public function returns [`Result`].
//!
//! An error is a kind, a place and a message. The kinds map one to one onto the Python
//! exception tree in crashsim-py (`MeshError`, `ParameterError`, `InitialOverlapError`,
//! `SimulationError`); the place travels as data (`.loc` in Python), so no layer reads an
//! index back out of the text.

use crate::math::Real;
use std::fmt;

/// Which kind of mistake an error is; one Python exception class per kind (the binding's
/// errors.rs maps them, in one place).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// A mesh is empty, has non-finite vertices or out-of-range indices.
    Mesh,
    /// A number is non-finite or outside its accepted range.
    Parameter,
    /// Two bodies of a contact pair already overlap when a run starts.
    InitialOverlap,
    /// The engine could not complete a run.
    Simulation,
}

impl ErrorKind {
    /// The Python exception class's name of this kind.
    pub fn class_name(self) -> &'static str {
        match self {
            ErrorKind::Mesh => "MeshError",
            ErrorKind::Parameter => "ParameterError",
            ErrorKind::InitialOverlap => "InitialOverlapError",
            ErrorKind::Simulation => "SimulationError",
        }
    }
}

/// One step of the path to where an error happened, outermost first in [`Error::loc`].
/// Indices are the scene spec's: bodies in the order added, wheels in a vehicle's order,
/// friction zones in the ground's order. A body's name is filled in by the scene spec's run
/// and the batch ([`Error::with_body_names`]); the layers above (Python) give wheels and
/// zones their names from the same indices, never by reading the message.
#[derive(Debug, Clone, PartialEq)]
pub enum Place {
    /// A batch's variant.
    Variant(usize),
    /// A body, with its name when known.
    Body(usize, Option<String>),
    /// A pair of bodies (a contact pair, a soft contact, a joined mechanism's members).
    Bodies(Vec<usize>, Vec<Option<String>>),
    /// A wheel of the vehicle named before it (or of the only vehicle).
    Wheel(usize),
    /// A friction zone of the ground.
    Zone(usize),
    /// Two friction zones (that overlap).
    Zones(usize, usize),
    /// A named part or parameter group: "ground", "towing", "inputs"; from Python also a
    /// vehicle that is not yet in a scene ("vehicle 'red'") and its driver inputs.
    Part(String),
    /// The parameter at fault, by the name its message gives it ("friction", "stiffness A",
    /// "position x"); innermost. Not written before the message: the message names it with
    /// its value ("friction = -1 is invalid: ...").
    Parameter(String),
    /// The simulated time (s) at which a run failed.
    Time(Real),
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let body = |f: &mut fmt::Formatter<'_>, i: usize, name: &Option<String>| match name {
            Some(n) => write!(f, "{i} ({n:?})"),
            None => write!(f, "{i}"),
        };
        match self {
            Place::Variant(i) => write!(f, "variant {i}"),
            Place::Body(i, name) => {
                f.write_str("body ")?;
                body(f, *i, name)
            }
            Place::Bodies(ids, names) => {
                f.write_str("bodies ")?;
                for (k, (i, n)) in ids.iter().zip(names).enumerate() {
                    if k > 0 {
                        f.write_str(if k + 1 == ids.len() { " and " } else { ", " })?;
                    }
                    body(f, *i, n)?;
                }
                Ok(())
            }
            Place::Wheel(k) => write!(f, "wheel {k}"),
            Place::Zone(k) => write!(f, "friction zone {k}"),
            Place::Zones(a, b) => write!(f, "friction zones {a} and {b}"),
            Place::Part(name) | Place::Parameter(name) => f.write_str(name),
            Place::Time(t) => write!(f, "t = {t:.6} s"),
        }
    }
}

/// What went wrong ([`ErrorKind`]), where ([`Place`]s, outermost first) and a message that
/// says how to fix it. Displayed as "place: place: message", each place as
/// [`Place::written`] says.
#[derive(Debug, Clone, PartialEq)]
pub struct Error {
    /// The kind of mistake.
    pub kind: ErrorKind,
    /// Where it happened, outermost first (empty: the whole input).
    pub loc: Vec<Place>,
    /// What is wrong and how to fix it, without the places written before it (a parameter
    /// is named in it, with its value).
    pub message: String,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for p in self.loc.iter().filter(|p| p.written()) {
            write!(f, "{p}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for Error {}

/// The engine's result type.
pub type Result<T> = std::result::Result<T, Error>;

/// The kind of a result's error; None when it is Ok.
pub fn error_kind<T>(r: &Result<T>) -> Option<ErrorKind> {
    r.as_ref().err().map(|e| e.kind)
}

impl Error {
    /// An error of `kind` with no place yet.
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Error {
            kind,
            loc: Vec::new(),
            message: message.into(),
        }
    }

    /// A mesh error.
    pub fn mesh(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::Mesh, message)
    }

    /// A parameter error with a free message.
    pub fn invalid(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::Parameter, message)
    }

    /// An initial-overlap error.
    pub fn initial_overlap(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::InitialOverlap, message)
    }

    /// A simulation error.
    pub fn simulation(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::Simulation, message)
    }

    /// A parameter error naming the parameter, its value and the accepted range; placed in
    /// [`Place::Parameter`] `name`.
    pub fn parameter(name: &str, value: impl fmt::Display, expected: &str) -> Self {
        Error::invalid(format!("{name} = {value} is invalid: {expected}"))
            .at(Place::Parameter(name.to_string()))
    }

    /// The same error, happened inside `place` (put before the places it has).
    pub fn at(mut self, place: Place) -> Self {
        self.loc.insert(0, place);
        self
    }

    /// The same error with every body place given its name from `names` (by index).
    pub fn with_body_names(mut self, names: &[&str]) -> Self {
        let name = |i: usize| names.get(i).map(|n| n.to_string());
        for p in &mut self.loc {
            match p {
                Place::Body(i, n) => *n = name(*i),
                Place::Bodies(ids, ns) => *ns = ids.iter().map(|&i| name(i)).collect(),
                _ => {}
            }
        }
        self
    }
}

impl Place {
    /// Body `i` (unnamed).
    pub fn body(i: usize) -> Place {
        Place::Body(i, None)
    }

    /// Bodies `i` and `j` (unnamed).
    pub fn bodies(i: usize, j: usize) -> Place {
        Place::Bodies(vec![i, j], vec![None, None])
    }

    /// Whether an error's text writes the place before its message: every place but a
    /// parameter, which the message names with its value.
    pub fn written(&self) -> bool {
        !matches!(self, Place::Parameter(_))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_read_outermost_first_and_take_the_bodies_names() {
        let e = Error::initial_overlap("they already overlap")
            .at(Place::bodies(0, 1))
            .at(Place::Variant(3));
        assert_eq!(
            e.to_string(),
            "variant 3: bodies 0 and 1: they already overlap"
        );
        let named = e.with_body_names(&["a", "b"]);
        assert_eq!(
            named.to_string(),
            "variant 3: bodies 0 (\"a\") and 1 (\"b\"): they already overlap"
        );
        assert_eq!(named.message, "they already overlap");
        assert_eq!(named.kind, ErrorKind::InitialOverlap);
        let wheel = Error::parameter("damping ratio", 30, "it must lie in [0, 2]")
            .at(Place::Wheel(2))
            .at(Place::body(1))
            .with_body_names(&["a"]);
        // a body the names do not cover stays unnamed
        assert_eq!(
            wheel.to_string(),
            "body 1: wheel 2: damping ratio = 30 is invalid: it must lie in [0, 2]"
        );
    }
}
