//! A joint's kind, limits, resistance and passive moments as a Python value (translation
//! only: every check is the core's); Scene.join builds one.

use crashsim_core as core;
use pyo3::prelude::*;

use crate::errors;

/// A joint's kind, limits and resistance, checked by the core when made (crashsim's
/// Scene.join builds one; the bodies and frames are given when it is added to a spec).
#[pyclass(frozen, eq, module = "crashsim._core")]
#[derive(Clone, PartialEq)]
pub struct Joint {
    pub inner: core::joint::JointSpec,
}

/// A passive moment as Python gives it: (angle name, offset rad, [(scale N m, rate 1/rad,
/// centre rad), ...], constant N m).
type PassiveParts = (String, f64, Vec<(f64, f64, f64)>, f64);
/// A coupled angle as Python gives it: (the law's angle name, the term's index, the other
/// joint's name, its angle's name, that angle's offset rad, rate 1/rad).
type CoupledParts = (String, usize, String, String, f64, f64);
/// The same as Python reads them back (the kind's static angle names).
type PassiveOut = (&'static str, f64, Vec<(f64, f64, f64)>, f64);
type CoupledOut = (&'static str, usize, String, String, f64, f64);

/// The index of angle `name` among a joint of `kind`'s `names`; else a ParameterError that
/// lists them ("a revolute joint has no angle "pitch" to limit: its angles are angle").
fn angle_index(
    kind: core::joint::JointKind,
    names: &[&str],
    name: &str,
    purpose: &str,
) -> PyResult<usize> {
    names.iter().position(|n| *n == name).ok_or_else(|| {
        errors::parameter(format!(
            "a {} joint has no angle {name:?} {purpose}{}",
            kind.name(),
            if names.is_empty() {
                String::new()
            } else {
                format!(": its angles are {}", names.join(", "))
            }
        ))
    })
}

#[pymethods]
impl Joint {
    /// kind "spherical", "revolute", "fixed" or "fifth_wheel"; limits (angle name, lower
    /// rad, upper rad); stiffness N m/rad, damping N m s/rad, friction N m; collide: the two
    /// bodies' meshes still collide; passive: (angle name, offset rad, [(scale N m, rate
    /// 1/rad, centre rad), ...], constant N m) per passive moment (core `PassiveMoment`);
    /// coupled: (the law's angle, term index, other joint's name, its angle, offset rad, rate
    /// 1/rad) per angle of another joint a term reads (core `CoupledAngle`).
    #[new]
    #[pyo3(signature = (kind, *, limits = Vec::new(), stiffness = 0.0, damping = 0.0, friction = 0.0, collide = false, passive = Vec::new(), coupled = Vec::new()))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        kind: &str,
        limits: Vec<(String, f64, f64)>,
        stiffness: f64,
        damping: f64,
        friction: f64,
        collide: bool,
        passive: Vec<PassiveParts>,
        coupled: Vec<CoupledParts>,
    ) -> PyResult<Joint> {
        let kind = core::joint::JointKind::from_name(kind).map_err(errors::to_py)?;
        let names = kind.limit_names();
        let frame = (
            core::math::Point::origin(),
            core::math::Rotation::identity(),
        );
        // Bodies 0 and 1 stand in until the joint is added to a scene.
        let mut joint = core::joint::JointSpec::new(kind, 0, Some(1), frame, frame);
        for (name, lower, upper) in limits {
            let angle = angle_index(kind, names, &name, "to limit")?;
            joint.limits.push(core::joint::AngleLimit {
                angle,
                lower,
                upper,
            });
        }
        joint.stiffness = stiffness;
        joint.damping = damping;
        joint.friction = friction;
        joint.collide = collide;
        let passive_names = kind.passive_names();
        for (name, offset, terms, constant) in passive {
            let angle = angle_index(kind, passive_names, &name, "for a passive moment")?;
            joint.passive.push(core::joint::PassiveMoment {
                angle,
                offset,
                terms: terms
                    .into_iter()
                    .map(|(scale, rate, centre)| core::joint::PassiveTerm::new(scale, rate, centre))
                    .collect(),
                constant,
            });
        }
        for (law_angle, k, other, angle, offset, rate) in coupled {
            let term = passive_names
                .iter()
                .position(|n| *n == law_angle)
                .and_then(|a| joint.passive.iter_mut().find(|m| m.angle == a))
                .and_then(|m| m.terms.get_mut(k))
                .ok_or_else(|| {
                    errors::parameter(format!(
                        "a coupled angle names term {k} of a passive moment about {law_angle:?}, \
                         which the joint does not have"
                    ))
                })?;
            term.coupled
                .push(core::joint::CoupledAngle::new(&other, &angle, offset, rate));
        }
        joint.validate("the joint").map_err(errors::to_py)?;
        Ok(Joint { inner: joint })
    }

    /// Per coupled angle: (the law's angle name, the term's index, the other joint's name,
    /// its angle's name, offset rad, rate 1/rad), as given.
    #[getter]
    fn coupled(&self) -> Vec<CoupledOut> {
        let names = self.inner.kind.passive_names();
        let mut out = Vec::new();
        for m in &self.inner.passive {
            for (k, t) in m.terms.iter().enumerate() {
                for c in &t.coupled {
                    out.push((
                        names[m.angle],
                        k,
                        c.joint.clone(),
                        c.angle.clone(),
                        c.offset,
                        c.rate,
                    ));
                }
            }
        }
        out
    }

    /// Per passive moment: (angle name, offset rad, [(scale N m, rate 1/rad, centre rad),
    /// ...], constant N m), as given.
    #[getter]
    fn passive(&self) -> Vec<PassiveOut> {
        let names = self.inner.kind.passive_names();
        self.inner
            .passive
            .iter()
            .map(|m| {
                (
                    names[m.angle],
                    m.offset,
                    m.terms
                        .iter()
                        .map(|t| (t.scale, t.rate, t.centre))
                        .collect(),
                    m.constant,
                )
            })
            .collect()
    }

    /// The names of the angles a passive moment may act about.
    #[getter]
    fn passive_names(&self) -> Vec<&'static str> {
        self.inner.kind.passive_names().to_vec()
    }

    /// The kind's name.
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.kind.name()
    }

    /// True when the two bodies' meshes still collide.
    #[getter]
    fn collide(&self) -> bool {
        self.inner.collide
    }

    /// (stiffness N m/rad, damping N m s/rad, friction N m).
    #[getter]
    fn resistance(&self) -> (f64, f64, f64) {
        (
            self.inner.stiffness,
            self.inner.damping,
            self.inner.friction,
        )
    }

    /// The names of the kind's angles, in the order of the records' angle columns.
    #[getter]
    fn angle_names(&self) -> Vec<&'static str> {
        self.inner.kind.limit_names().to_vec()
    }

    /// (angle name, lower rad, upper rad) per limit.
    #[getter]
    fn limits(&self) -> Vec<(&'static str, f64, f64)> {
        let names = self.inner.kind.limit_names();
        self.inner
            .limits
            .iter()
            .map(|l| (names[l.angle], l.lower, l.upper))
            .collect()
    }

    /// Pickled as its constructor's arguments (every number exact): a scene with joints
    /// (a trailer, a pedestrian) pickles, for studies on other processes.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        (
            &'static str,
            Vec<(&'static str, f64, f64)>,
            f64,
            f64,
            f64,
            bool,
            Vec<PassiveOut>,
            Vec<CoupledOut>,
        ),
    )> {
        let j = slf.get();
        let from = slf.get_type().getattr("_from_parts")?;
        Ok((
            from,
            (
                j.inner.kind.name(),
                j.limits(),
                j.inner.stiffness,
                j.inner.damping,
                j.inner.friction,
                j.inner.collide,
                j.passive(),
                j.coupled(),
            ),
        ))
    }

    #[staticmethod]
    #[pyo3(signature = (kind, limits, stiffness, damping, friction, collide, passive = Vec::new(), coupled = Vec::new()))]
    #[allow(clippy::too_many_arguments)]
    fn _from_parts(
        kind: &str,
        limits: Vec<(String, f64, f64)>,
        stiffness: f64,
        damping: f64,
        friction: f64,
        collide: bool,
        passive: Vec<PassiveParts>,
        coupled: Vec<CoupledParts>,
    ) -> PyResult<Joint> {
        Joint::new(
            kind, limits, stiffness, damping, friction, collide, passive, coupled,
        )
    }

    fn __repr__(&self) -> String {
        let j = &self.inner;
        let passive = if j.passive.is_empty() {
            String::new()
        } else {
            format!(", passive={:?}", self.passive())
        };
        let coupled = self.coupled();
        let passive = if coupled.is_empty() {
            passive
        } else {
            format!("{passive}, coupled={coupled:?}")
        };
        format!(
            "Joint({:?}, limits={:?}, stiffness={}, damping={}, friction={}, collide={}{passive})",
            j.kind.name(),
            self.limits(),
            j.stiffness,
            j.damping,
            j.friction,
            j.collide
        )
    }
}
