//! A scene as a value: everything a run needs (bodies with their shared meshes, mass
//! properties and initial states, fixed obstacles, the ground, wheels, tyres and driver
//! inputs, per-pair contact parameters, face stiffness, run options), cheap to copy with
//! changes (meshes are shared through `Arc`), and serialisable with the `serde` feature
//! (document.rs: meshes as vertices and triangles, JSON through serde_json).
//!
//! [`SceneSpec::build`] turns it into a fresh [`World`]; [`SceneSpec::run`] builds and runs it.
//! The setup methods check every value at the call (the same checks a [`World`] makes), so a
//! caller learns of a bad value where it gave it; [`SceneSpec::build`] checks the whole again
//! (stiffness a pair needs, wheels against their body), since the fields are public and a
//! batch's overrides change them. Frames and units: world frame, SI (m, kg, s, rad).

#[cfg(feature = "serde")]
mod document;

use std::sync::Arc;

use crate::body::{BodyState, MassProperties};
use crate::contact::{CentroidMode, ContactParams};
use crate::error::{Error, Place, Result};
use crate::ground::Ground;
use crate::joint::JointSpec;
use crate::math::{Isometry, Real};
use crate::shape::MeshShape;
use crate::soft::SoftContact;
use crate::stiffness::Stiffness;
use crate::vehicle::VehicleSpec;
use crate::world::{RunOptions, RunOutput, World};

/// How a body of a scene moves.
#[derive(Clone, Debug, PartialEq)]
pub enum BodyMotion {
    /// A vehicle (or any movable body): mass properties, the state at t = 0 (world frame),
    /// and, for a world with a ground, its wheels, tyre and driver inputs (None: it slides on
    /// its body).
    Moving {
        /// Mass (kg) and inertia about the CG, body frame (kg m^2).
        props: MassProperties,
        /// CG position (m), orientation (body -> world), velocity (m/s), angular velocity
        /// (rad/s), world frame, at t = 0.
        state: BodyState,
        /// Wheels, tyre and inputs (used when the scene has a ground).
        vehicle: Option<VehicleSpec>,
    },
    /// A fixed obstacle at a pose (its frame's origin, m, and orientation, world frame):
    /// infinite mass, never moves.
    Fixed {
        /// Obstacle frame -> world.
        pose: Isometry,
    },
}

/// One body of a scene.
#[derive(Clone, Debug)]
pub struct BodySpec {
    /// Its name (used in a batch's column names and messages); "body i" when not given.
    pub name: String,
    /// The mesh in the body frame (m; origin at the CG for a moving body), shared.
    pub shape: Arc<MeshShape>,
    /// Moving (with its mass properties and initial state) or fixed.
    pub motion: BodyMotion,
    /// CRASH3 face stiffness (none by default).
    pub stiffness: Stiffness,
    /// Its own friction with the ground, in (0, 2], in place of the ground's body friction
    /// (a person's clothing on the road); None by default: the ground's.
    pub ground_friction: Option<Real>,
}

impl BodySpec {
    /// True for a fixed obstacle.
    pub fn is_fixed(&self) -> bool {
        matches!(self.motion, BodyMotion::Fixed { .. })
    }
}

/// The contact parameters of one pair; the normal points from `body1` into `body2`.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactSpec {
    /// Index of body 1 in [`SceneSpec::bodies`].
    pub body1: usize,
    /// Index of body 2.
    pub body2: usize,
    /// The pair's parameters (contact.rs: every field's default, unit and range).
    pub params: ContactParams,
}

/// How long and how finely a scene runs, and what it keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunSpec {
    /// Length of the run (s), >= 0; with `options.until_rest` the longest it may take.
    /// Default 1 s.
    pub duration: Real,
    /// Largest step (s), > 0; default 1 ms.
    pub dt: Real,
    /// Recording, history limit, until rest ([`RunOptions`]: defaults there).
    pub options: RunOptions,
}

impl RunSpec {
    /// The run's own rules, checked before any world is built: the duration and step
    /// ([`crate::world::check_run_length`]) and the recording interval. A run until rest
    /// needs a ground, and the history must fit its limit: the world checks those when it
    /// runs.
    pub fn check(&self) -> Result<()> {
        let steps = crate::world::check_run_length(self.duration, self.dt)?;
        self.options.stride(steps, self.dt).map(|_| ())
    }
}

impl Default for RunSpec {
    fn default() -> Self {
        RunSpec {
            duration: 1.0,
            dt: 1e-3,
            options: RunOptions::default(),
        }
    }
}

/// A whole scene as a value. Bodies are in the engine's order: a pair's indices refer to it.
#[derive(Clone, Debug, Default)]
pub struct SceneSpec {
    /// The bodies, moving ones and obstacles, in the world's order.
    pub bodies: Vec<BodySpec>,
    /// Pairs with parameters of their own (every other pair of bodies, except two obstacles,
    /// collides with [`ContactParams::default`]); at most one entry per unordered pair.
    pub contacts: Vec<ContactSpec>,
    /// The ground (None: every body moves torque-free between exchanges).
    pub ground: Option<Ground>,
    /// Joints between bodies (or a body and the world), in order (docs/joints.md).
    pub joints: Vec<JointSpec>,
    /// Pairs of bodies that never collide (a pedestrian's segments among themselves), each
    /// once, (lower index, higher).
    pub no_contact: Vec<(usize, usize)>,
    /// Pairs with a compliant contact instead of the timer and the exchange (soft.rs), each
    /// once, (lower index, higher, its law).
    pub soft_contacts: Vec<(usize, usize, SoftContact)>,
    /// Duration, step and options of a run.
    pub run: RunSpec,
}

/// Checks a fixed body's pose (an obstacle's): every number finite.
pub fn check_pose(pose: &Isometry) -> Result<()> {
    let t = pose.translation.vector;
    let q = pose.rotation.coords;
    if t.iter().all(|x| x.is_finite()) && q.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::invalid("an obstacle's pose has a non-finite number"))
    }
}

impl SceneSpec {
    /// An empty scene with the default run (1 s at 1 ms).
    pub fn new() -> SceneSpec {
        SceneSpec::default()
    }

    fn name_or_default(&self, name: Option<String>) -> String {
        name.unwrap_or_else(|| format!("body {}", self.bodies.len()))
    }

    fn body_mut(&mut self, i: usize) -> Result<&mut BodySpec> {
        let n = self.bodies.len();
        self.bodies.get_mut(i).ok_or_else(|| {
            Error::invalid(format!("it does not exist (the scene has {n} bodies)"))
                .at(Place::body(i))
        })
    }

    /// Adds a moving body (its state checked: finite numbers); returns its index.
    pub fn add_body(
        &mut self,
        name: Option<String>,
        shape: Arc<MeshShape>,
        props: MassProperties,
        state: BodyState,
    ) -> Result<usize> {
        state.validate()?;
        let name = self.name_or_default(name);
        self.bodies.push(BodySpec {
            name,
            shape,
            motion: BodyMotion::Moving {
                props,
                state,
                vehicle: None,
            },
            stiffness: Stiffness::none(),
            ground_friction: None,
        });
        Ok(self.bodies.len() - 1)
    }

    /// Adds a fixed obstacle at `pose` (world); returns its index.
    pub fn add_obstacle(
        &mut self,
        name: Option<String>,
        shape: Arc<MeshShape>,
        pose: Isometry,
    ) -> Result<usize> {
        check_pose(&pose)?;
        let name = self.name_or_default(name);
        self.bodies.push(BodySpec {
            name,
            shape,
            motion: BodyMotion::Fixed { pose },
            stiffness: Stiffness::none(),
            ground_friction: None,
        });
        Ok(self.bodies.len() - 1)
    }

    /// Sets body `i`'s face stiffness.
    pub fn set_stiffness(&mut self, i: usize, stiffness: Stiffness) -> Result<()> {
        self.body_mut(i)?.stiffness = stiffness;
        Ok(())
    }

    /// Gives moving body `i` its own friction with the ground (checked: in (0, 2]), in place
    /// of the ground's body friction: a person's clothing on the road.
    pub fn set_ground_friction(&mut self, i: usize, mu: Real) -> Result<()> {
        crate::ground::check_body_friction("ground friction", mu)
            .map_err(|e| e.at(Place::body(i)))?;
        let body = self.body_mut(i)?;
        if body.is_fixed() {
            return Err(Error::invalid(
                "it is a fixed obstacle: it does not slide on the ground".to_string(),
            )
            .at(Place::body(i)));
        }
        body.ground_friction = Some(mu);
        Ok(())
    }

    /// Gives body `i` wheels, a tyre and driver inputs (checked against its box and mass).
    pub fn set_vehicle(&mut self, i: usize, spec: VehicleSpec) -> Result<()> {
        let body = self.body_mut(i)?;
        match &mut body.motion {
            BodyMotion::Fixed { .. } => Err(Error::invalid(
                "it is a fixed obstacle: it has no wheels".to_string(),
            )
            .at(Place::body(i))),
            BodyMotion::Moving { props, vehicle, .. } => {
                spec.validate(Some(body.shape.aabb()), props.mass())?;
                *vehicle = Some(spec);
                Ok(())
            }
        }
    }

    /// Puts the scene on the ground.
    pub fn set_ground(&mut self, ground: Ground) {
        self.ground = Some(ground);
    }

    /// Sets the pair's parameters (checked: ranges, two different bodies, a centroid fixed
    /// in a body of the pair); the normal points from `body1` into `body2`. Replaces what the
    /// pair had, whichever its order. Face stiffness the parameters need is checked by
    /// [`SceneSpec::build`] (stiffness may be set after).
    pub fn set_contact(&mut self, body1: usize, body2: usize, params: ContactParams) -> Result<()> {
        let n = self.bodies.len();
        if body1 >= n || body2 >= n || body1 == body2 {
            return Err(Error::invalid(format!(
                "contact ({body1}, {body2}) must name two different bodies among 0..{n}"
            )));
        }
        if self.bodies[body1].is_fixed() && self.bodies[body2].is_fixed() {
            return Err(Error::invalid(
                "they are both fixed obstacles: two obstacles never meet".to_string(),
            )
            .at(Place::bodies(body1, body2)));
        }
        if self
            .no_contact
            .contains(&(body1.min(body2), body1.max(body2)))
        {
            return Err(Error::invalid(
                "they never collide (a no-contact pair): they take no \
                 contact parameters"
                    .to_string(),
            )
            .at(Place::bodies(body1, body2)));
        }
        params.validate()?;
        if let CentroidMode::Body { body, .. } = params.centroid {
            if body != body1 && body != body2 {
                return Err(Error::invalid(format!(
                    "the centroid is fixed in body {body}, which is not in the pair ({body1}, {body2})"
                )));
            }
        }
        let entry = ContactSpec {
            body1,
            body2,
            params,
        };
        match self
            .contacts
            .iter_mut()
            .find(|c| (c.body1, c.body2) == (body1, body2) || (c.body1, c.body2) == (body2, body1))
        {
            Some(c) => *c = entry,
            None => self.contacts.push(entry),
        }
        Ok(())
    }

    /// Makes bodies `body1` and `body2` never collide (their meshes pass through each other,
    /// no contact, no exchange), as a joint without `collide` does; checked: two different
    /// bodies of the scene, not both fixed, no contact parameters of their own.
    pub fn set_no_contact(&mut self, body1: usize, body2: usize) -> Result<()> {
        let n = self.bodies.len();
        if body1 >= n || body2 >= n || body1 == body2 {
            return Err(Error::invalid(format!(
                "no-contact pair ({body1}, {body2}) must name two different bodies among 0..{n}"
            )));
        }
        if self.bodies[body1].is_fixed() && self.bodies[body2].is_fixed() {
            return Err(Error::invalid(
                "they are both fixed obstacles: two obstacles never meet".to_string(),
            )
            .at(Place::bodies(body1, body2)));
        }
        let key = (body1.min(body2), body1.max(body2));
        if self
            .contacts
            .iter()
            .any(|c| (c.body1.min(c.body2), c.body1.max(c.body2)) == key)
        {
            return Err(Error::invalid(
                "they have contact parameters of their own: a pair that \
                 never collides takes none"
                    .to_string(),
            )
            .at(Place::bodies(body1, body2)));
        }
        if self.soft_contacts.iter().any(|&(a, b, _)| (a, b) == key) {
            return Err(Error::invalid(
                "they have a soft contact: a pair that never collides \
                 takes none"
                    .to_string(),
            )
            .at(Place::bodies(body1, body2)));
        }
        if !self.no_contact.contains(&key) {
            self.no_contact.push(key);
        }
        Ok(())
    }

    /// Gives bodies `body1` and `body2` a compliant contact (soft.rs) in place of the timer
    /// and the exchange; checked: its numbers, two different bodies of the scene, not both
    /// fixed, not a pair that never collides. Replaces the pair's earlier one.
    pub fn set_soft_contact(
        &mut self,
        body1: usize,
        body2: usize,
        soft: SoftContact,
    ) -> Result<()> {
        let n = self.bodies.len();
        if body1 >= n || body2 >= n || body1 == body2 {
            return Err(Error::invalid(format!(
                "soft contact ({body1}, {body2}) must name two different bodies among 0..{n}"
            )));
        }
        if self.bodies[body1].is_fixed() && self.bodies[body2].is_fixed() {
            return Err(Error::invalid(
                "they are both fixed obstacles: two obstacles never meet".to_string(),
            )
            .at(Place::bodies(body1, body2)));
        }
        soft.validate()?;
        let (a, b) = (body1.min(body2), body1.max(body2));
        if self.no_contact.contains(&(a, b)) {
            return Err(Error::invalid(
                "they never collide (a no-contact pair): they take no \
                 soft contact"
                    .to_string(),
            )
            .at(Place::bodies(body1, body2)));
        }
        self.soft_contacts.retain(|&(x, y, _)| (x, y) != (a, b));
        self.soft_contacts.push((a, b, soft));
        Ok(())
    }

    /// Adds a joint (checked: its numbers and limits, its bodies moving bodies of the scene;
    /// where its anchor lies, when the world is built); returns its index.
    pub fn add_joint(&mut self, joint: JointSpec) -> Result<usize> {
        let name = joint.label(self.joints.len());
        joint.validate(&name)?;
        let n = self.bodies.len();
        for b in std::iter::once(joint.body1).chain(joint.body2) {
            match self.bodies.get(b) {
                None => {
                    return Err(Error::invalid(format!(
                        "{name} names body {b}, which does not exist (the scene has {n} bodies)"
                    )))
                }
                Some(body) if body.is_fixed() => {
                    return Err(Error::invalid(format!(
                        "{name} names body {b} ({}), a fixed obstacle: join the body to the \
                         world instead (a joint with no second body)",
                        body.name
                    )))
                }
                Some(_) => {}
            }
        }
        self.joints.push(joint);
        Ok(self.joints.len() - 1)
    }

    /// The bodies' names in index order (for errors' places).
    pub fn body_names(&self) -> Vec<&str> {
        self.bodies.iter().map(|b| b.name.as_str()).collect()
    }

    /// Indices of the moving bodies (the vehicles), in order.
    pub fn moving(&self) -> Vec<usize> {
        (0..self.bodies.len())
            .filter(|&i| !self.bodies[i].is_fixed())
            .collect()
    }

    /// A fresh world holding this scene at t = 0, every value checked.
    pub fn build(&self) -> Result<World> {
        let mut world = World::new();
        for b in &self.bodies {
            match &b.motion {
                BodyMotion::Moving { props, state, .. } => {
                    world.add_body(b.shape.clone(), props.clone(), state)?
                }
                BodyMotion::Fixed { pose } => world.add_obstacle(b.shape.clone(), pose)?,
            };
        }
        for (i, b) in self.bodies.iter().enumerate() {
            world.set_stiffness(i, b.stiffness.clone())?;
            if let Some(mu) = b.ground_friction {
                world.set_ground_friction(i, mu)?;
            }
            if let BodyMotion::Moving {
                vehicle: Some(v), ..
            } = &b.motion
            {
                world.set_vehicle(i, v.clone())?;
            }
        }
        for j in &self.joints {
            world.add_joint(j.clone())?;
        }
        for c in &self.contacts {
            world.set_contact(c.body1, c.body2, c.params.clone())?;
        }
        for &(a, b) in &self.no_contact {
            world.set_no_contact(a, b)?;
        }
        for &(a, b, soft) in &self.soft_contacts {
            world.set_soft_contact(a, b, soft)?;
        }
        if let Some(g) = &self.ground {
            world.set_ground(g.clone())?;
        }
        Ok(world)
    }

    /// Builds the world and runs it as [`SceneSpec::run`] says, calling `progress` as
    /// [`World::run_with_options`] does.
    pub fn run_with_progress(&self, progress: &mut dyn FnMut(Real) -> bool) -> Result<RunOutput> {
        let mut world = self.build()?;
        world.run_with_options(self.run.duration, self.run.dt, &self.run.options, progress)
    }

    /// Builds the world and runs it.
    pub fn run(&self) -> Result<RunOutput> {
        self.run_with_progress(&mut |_| true)
    }
}

#[cfg(feature = "serde")]
pub use document::{from_json, to_json};

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::error::{error_kind, ErrorKind};
    use crate::math::{Point, Rotation, Vector};

    fn cube(h: Real) -> Arc<MeshShape> {
        let v: Vec<Point> = (0..8)
            .map(|i| {
                Point::new(
                    if i & 1 == 0 { -h } else { h },
                    if i & 2 == 0 { -h } else { h },
                    if i & 4 == 0 { -h } else { h },
                )
            })
            .collect();
        let t = vec![
            [0, 2, 1],
            [1, 2, 3],
            [4, 5, 6],
            [5, 7, 6],
            [0, 1, 4],
            [1, 5, 4],
            [2, 6, 3],
            [3, 6, 7],
            [0, 4, 2],
            [2, 4, 6],
            [1, 3, 5],
            [3, 7, 5],
        ];
        Arc::new(MeshShape::new(v, t).unwrap())
    }

    fn state(x: Real, vx: Real) -> BodyState {
        BodyState {
            position: Point::new(x, 0.0, 0.0),
            orientation: Rotation::identity(),
            velocity: Vector::new(vx, 0.0, 0.0),
            angular_velocity: Vector::zeros(),
        }
    }

    pub(crate) fn head_on() -> SceneSpec {
        let mut s = SceneSpec::new();
        let props = MassProperties::new(1000.0, nalgebra::Matrix3::identity() * 500.0).unwrap();
        let shape = cube(1.0);
        s.add_body(
            Some("a".into()),
            shape.clone(),
            props.clone(),
            state(-3.0, 10.0),
        )
        .unwrap();
        s.add_body(Some("b".into()), shape, props, state(3.0, -10.0))
            .unwrap();
        s.set_contact(0, 1, ContactParams::default()).unwrap();
        s.run.duration = 0.5;
        s
    }

    #[test]
    fn a_spec_runs_as_the_world_it_builds() {
        let spec = head_on();
        let by_spec = spec.run().unwrap();
        let mut w = spec.build().unwrap();
        let by_world = w.run(0.5, 1e-3).unwrap();
        assert_eq!(by_spec, by_world);
        assert_eq!(by_spec.impacts.len(), 1);
    }

    #[test]
    fn without_history_the_run_is_the_same_bits() {
        let mut spec = head_on();
        let full = spec.run().unwrap();
        spec.run.options.history = false;
        let last = spec.run().unwrap();
        assert_eq!(last.len(), 1);
        assert_eq!(last.times[0], *full.times.last().unwrap());
        assert_eq!(last.sample(0), full.sample(full.len() - 1));
        assert_eq!(last.impacts, full.impacts);
        assert_eq!(last.contacts, full.contacts);
    }

    #[test]
    fn setup_errors_name_the_problem() {
        let mut spec = head_on();
        let bad = ContactParams {
            restitution: 2.0,
            ..ContactParams::default()
        };
        assert_eq!(
            error_kind(&spec.set_contact(0, 1, bad)),
            Some(ErrorKind::Parameter)
        );
        assert_eq!(
            error_kind(&spec.set_contact(0, 0, ContactParams::default())),
            Some(ErrorKind::Parameter)
        );
        assert_eq!(
            error_kind(&spec.set_stiffness(5, Stiffness::none())),
            Some(ErrorKind::Parameter)
        );
        // the pair replaced whichever its order
        spec.set_contact(1, 0, ContactParams::default()).unwrap();
        assert_eq!(spec.contacts.len(), 1);
        assert_eq!((spec.contacts[0].body1, spec.contacts[0].body2), (1, 0));
    }
}
