//! Jointed bodies in the world: joints are added before the first run, the bodies they join
//! form mechanisms (the members of a connected set of joints, moved together by
//! [`advance_mechanism`]), and an exchange with a member sees the whole mechanism through the
//! joints (docs/joints.md).

use std::sync::Arc;

use super::{Motion, Prediction, PredictionKey, World};
use crate::error::{Error, Place, Result};
use crate::joint::{
    drift_rate, find_coupled_angles, project_positions, project_velocities,
    project_velocities_each, JointBody, JointSpec,
};
use crate::math::{Matrix, Point, Real, Vector};
use crate::motion::{advance_mechanism, BodyContact, LimitHit, OnGround};
use crate::vehicle::{wheel_loads, GRAVITY};

/// How far (m) a joint's anchor may lie outside the box of the nearer of its bodies: a tow
/// ball stands 0.1-0.3 m behind a bumper, a kingpin sits under a trailer's floor.
pub const ANCHOR_REACH: Real = 1.0;
/// How far apart (m, and rad between axes) a joint's two frames may be when a run starts,
/// and how fast (m/s, rad/s) they may move apart then.
const START_TOLERANCE: Real = 1e-3;

/// Bodies joined by joints, moved together.
#[derive(Clone, Debug)]
pub(super) struct Mechanism {
    /// The members' world indices, ascending.
    pub members: Vec<usize>,
    /// The joints with the members' positions as body indices.
    pub joints: Vec<JointSpec>,
    /// Each joint's world index.
    pub ids: Vec<usize>,
    /// Per joint and limit: the joint rests against the limit.
    pub engaged: Vec<Vec<bool>>,
}

/// A limit a joint ran into during a run.
#[derive(Clone, Debug, PartialEq)]
pub struct JointEvent {
    /// The joint's index (in the order the joints were added).
    pub joint: usize,
    /// Which limit of the joint (its index).
    pub limit: usize,
    /// When (s).
    pub time: Real,
    /// The relative angular rate the stop took out (rad/s, about the limited angle's axis).
    pub rate: Real,
}

/// What a mechanism's predicted span leaves besides its members' states.
#[derive(Clone, Debug)]
pub(super) struct MechanismOutcome {
    pub engaged: Vec<Vec<bool>>,
    pub hits: Vec<LimitHit>,
}

impl World {
    /// Adds a joint (checked: its bodies exist and are not fixed obstacles, its numbers and
    /// limits, its anchor near one of its bodies). Unless the joint says `collide`, the two
    /// bodies no longer form a contact pair. Returns its index.
    pub fn add_joint(&mut self, joint: JointSpec) -> Result<usize> {
        if self.started {
            return Err(Error::invalid("joints must be added before the first run"));
        }
        let index = self.joints.len();
        let name = joint.label(index);
        joint.validate(&name)?;
        let n = self.bodies.len();
        for b in std::iter::once(joint.body1).chain(joint.body2) {
            if b >= n {
                return Err(Error::invalid(format!(
                    "{name} names body {b}, which does not exist (the world has {n} bodies)"
                )));
            }
            if self.is_obstacle(b) {
                return Err(Error::invalid(format!(
                    "{name} names body {b}, a fixed obstacle: join the body to the world \
                     instead (a joint with no second body)"
                )));
            }
        }
        // The anchor (world, as the joint is made) near at least one of the bodies.
        let anchor = self.bodies[joint.body1].body().pose() * joint.frame1.0;
        let outside = |b: usize| {
            let pose = self.bodies[b].body().pose();
            let local = pose.inverse_transform_point(&anchor);
            let aabb = self.bodies[b].shape.aabb();
            let d = (aabb.mins - local)
                .sup(&(local - aabb.maxs))
                .sup(&Vector::zeros());
            d.norm()
        };
        let nearest = std::iter::once(joint.body1)
            .chain(joint.body2)
            .map(outside)
            .fold(Real::INFINITY, Real::min);
        if nearest > ANCHOR_REACH {
            return Err(Error::invalid(format!(
                "{name}'s anchor at ({:.2}, {:.2}, {:.2}) m lies {nearest:.2} m outside the \
                 box of every body it joins (at most {ANCHOR_REACH} m): put the hitch or \
                 kingpin where the bodies meet",
                anchor.x, anchor.y, anchor.z
            )));
        }
        if let (Some(b), false) = (joint.body2, joint.collide) {
            let (lo, hi) = (joint.body1.min(b), joint.body1.max(b));
            self.pairs
                .retain(|p| (p.body1.min(p.body2), p.body1.max(p.body2)) != (lo, hi));
        }
        self.joints.push(joint);
        Ok(index)
    }

    /// Number of joints.
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// Sets the static loads of every vehicle in a towing chain for the combination (before
    /// the bodies are put on the ground): a trailer (a vehicle with a coupling) joined as body
    /// 2 to a vehicle rests its coupling's share of its weight on the joint's anchor in that
    /// vehicle, whose wheels then carry its own weight and that share ([`wheel_loads`]: load
    /// groups, its own coupling, the towed load), from the chain's end forwards, so a dolly
    /// carries its drawbar trailer's body and passes the rest on. The springs' preloads are
    /// these loads, so a parked combination stands level whatever
    /// the trailer's load (a study's mass override included); each spring keeps its natural
    /// frequency and damping ratio. Vehicles in no towing chain keep what they were given.
    pub(super) fn carry_coupling_loads(&mut self) -> Result<()> {
        // (tower, trailer, the anchor in the tower's frame)
        let mut tows = Vec::new();
        for joint in &self.joints {
            let Some(t) = joint.body2 else { continue };
            let coupled = self.bodies[t]
                .vehicle
                .as_ref()
                .is_some_and(|v| v.coupling.is_some());
            if coupled && self.bodies[joint.body1].vehicle.is_some() {
                tows.push((joint.body1, t, joint.frame1.0));
            }
        }
        if tows.is_empty() {
            return Ok(());
        }
        for (k, &(w, _, _)) in tows.iter().enumerate() {
            if tows[..k].iter().any(|&(o, _, _)| o == w) {
                return Err(Error::invalid(
                    "it tows two trailers: a vehicle has one hitch (give the second \
                     trailer to the first)"
                        .to_string(),
                )
                .at(Place::body(w)));
            }
        }
        // From the chain's end: a vehicle's load is known once its own trailer's is.
        let mut share: Vec<Option<Real>> = vec![None; self.bodies.len()];
        let mut done = vec![false; self.bodies.len()];
        for _ in 0..=tows.len() {
            for &(w, t, anchor) in &tows {
                if done[t] || tows.iter().any(|&(o, tt, _)| o == t && !done[tt]) {
                    continue;
                }
                // The trailer's loads with what its own trailer puts on it.
                let towed_t = tows
                    .iter()
                    .find(|&&(o, _, _)| o == t)
                    .map(|&(_, tt, a)| ([a.x, a.y], share[tt].expect("its trailer first")));
                share[t] = Some(self.set_static_loads(t, towed_t)?);
                done[t] = true;
                if !tows.iter().any(|&(_, tt, _)| tt == w) {
                    // the chain's head: its wheels carry the first trailer's share
                    let head = Some(([anchor.x, anchor.y], share[t].expect("just set")));
                    self.set_static_loads(w, head)?;
                    done[w] = true;
                }
            }
        }
        Ok(())
    }

    /// Sets body `i`'s wheels' static loads for its weight, its coupling and `towed` (the
    /// point in its frame and the load of its own trailer), and its hitch load; returns the
    /// load on its coupling (0 without one).
    fn set_static_loads(&mut self, i: usize, towed: Option<([Real; 2], Real)>) -> Result<Real> {
        let wb = &mut self.bodies[i];
        let mass = wb.body().props().mass();
        let spec = wb.vehicle.as_mut().expect("a vehicle in a towing chain");
        let spec = Arc::make_mut(spec);
        let xy: Vec<[Real; 2]> = spec
            .wheels
            .iter()
            .map(|w| [w.center.x, w.center.y])
            .collect();
        let coupling = spec.coupling.map(|c| [c.x, c.y]);
        let (loads, share) = wheel_loads(&xy, &spec.load_groups, mass * GRAVITY, coupling, towed)
            .map_err(|e| e.at(Place::Part("towing".into())).at(Place::body(i)))?;
        // Each spring keeps its natural frequency and damping ratio with its new load (rate
        // and damping in proportion, as a batch's mass override scales them): a tractor's
        // rear springs are a laden tractor's, not its own weight's.
        for (w, f) in spec.wheels.iter_mut().zip(loads) {
            let ratio = f / w.static_load;
            w.spring_rate *= ratio;
            w.damping *= ratio;
            w.static_load = f;
        }
        spec.hitch_load = towed.map(|(p, f)| (Point::new(p[0], p[1], 0.0), f));
        Ok(share)
    }

    /// Groups the jointed bodies into mechanisms (at the first run, after the bodies were
    /// put on the ground).
    pub(super) fn build_mechanisms(&mut self) -> Result<()> {
        self.mechanism_of = vec![None; self.bodies.len()];
        self.mechanisms.clear();
        if self.joints.is_empty() {
            return Ok(());
        }
        if self.ground.is_none() {
            return Err(Error::invalid(
                "joints need a ground (its gravity and the bodies' motion on it): set one",
            ));
        }
        // Connected sets of bodies, by union of each joint's two bodies.
        let mut root: Vec<usize> = (0..self.bodies.len()).collect();
        fn find(root: &mut [usize], mut i: usize) -> usize {
            while root[i] != i {
                root[i] = root[root[i]];
                i = root[i];
            }
            i
        }
        for j in &self.joints {
            let a = find(&mut root, j.body1);
            if let Some(b) = j.body2 {
                let b = find(&mut root, b);
                root[a.max(b)] = a.min(b);
            }
        }
        // Every body's set, once (each a root: its set's smallest index).
        let set: Vec<usize> = (0..self.bodies.len()).map(|i| find(&mut root, i)).collect();
        let mut by_root: Vec<Option<usize>> = vec![None; self.bodies.len()];
        for (id, joint) in self.joints.iter().enumerate() {
            let r = set[joint.body1];
            let g = match by_root[r] {
                Some(g) => g,
                None => {
                    let members: Vec<usize> =
                        (0..self.bodies.len()).filter(|&i| set[i] == r).collect();
                    self.mechanisms.push(Mechanism {
                        members,
                        joints: Vec::new(),
                        ids: Vec::new(),
                        engaged: Vec::new(),
                    });
                    by_root[r] = Some(self.mechanisms.len() - 1);
                    self.mechanisms.len() - 1
                }
            };
            let m = &mut self.mechanisms[g];
            let local = |i: usize| m.members.iter().position(|&x| x == i).expect("a member");
            let mut j = joint.clone();
            j.body1 = local(joint.body1);
            j.body2 = joint.body2.map(local);
            m.engaged.push(vec![false; j.limits.len()]);
            m.joints.push(j);
            m.ids.push(id);
        }
        for (g, m) in self.mechanisms.iter_mut().enumerate() {
            for &i in &m.members {
                self.mechanism_of[i] = Some(g);
            }
            find_coupled_angles(&mut m.joints, &m.ids)?;
        }
        self.size_ground_contacts_to_mechanisms()?;
        // Each joint's frames meet at the start and do not move apart (within START_TOLERANCE);
        // the velocities are then projected onto the joints (removing the rounding).
        for g in 0..self.mechanisms.len() {
            let jb = self.joint_bodies(g);
            let m = &self.mechanisms[g];
            for (joint, id) in m.joints.iter().zip(&m.ids) {
                let label = joint.label(*id);
                // (only how far apart: nothing solved)
                let (_, apart) =
                    project_positions(std::slice::from_ref(joint), &jb, &[], Real::INFINITY);
                if apart > START_TOLERANCE {
                    return Err(Error::invalid(format!(
                        "{label}'s frames do not meet at the start ({apart:.4} m or rad \
                         apart): give each body's frame of the joint at the same world point \
                         and axes"
                    )));
                }
                let rate = drift_rate(joint, &jb);
                if rate > START_TOLERANCE {
                    return Err(Error::invalid(format!(
                        "{label}'s bodies move apart at the start ({rate:.4} m/s at the \
                         anchor, or rad/s between its axes): give the joined bodies velocities \
                         that agree (a trailer moving with its tractor)"
                    )));
                }
            }
            let first = m.members[0];
            self.share_impulse(first);
        }
        Ok(())
    }

    /// Sizes the ground contact of every wheel-less member of a mechanism to the mechanism's
    /// whole mass: a pedestrian's foot carries the body (sized to its own 1 kg, it sank 4.4 cm
    /// under 75 kg), a bicycle's wheel the frame; and gives it static friction
    /// ([`BodyContact::with_static_friction`]: a lying person comes to rest). Members with
    /// wheels are carried by them and keep their own (a trailer's body).
    fn size_ground_contacts_to_mechanisms(&mut self) -> Result<()> {
        for m in &self.mechanisms {
            let total: Real = m
                .members
                .iter()
                .map(|&i| self.bodies[i].body().props().mass())
                .sum();
            for &i in &m.members {
                let wb = &mut self.bodies[i];
                if wb.vehicle.is_some() {
                    continue;
                }
                let own = wb.body().props().mass();
                if let Motion::OnGround(g) = &mut wb.motion {
                    let contact = BodyContact::new(&wb.shape, own, total, None)?
                        .with_friction(wb.ground_friction);
                    g.contact = Arc::new(contact.with_static_friction());
                }
            }
        }
        Ok(())
    }

    /// The prediction of member `i` of mechanism `g` `dt` s from now (or back into the
    /// current step for dt < 0): the whole mechanism is advanced and every member's
    /// prediction kept. None (the error kept for the stepper) when the motion fails.
    pub(super) fn predicted_mechanism(
        &self,
        g: usize,
        i: usize,
        dt: Real,
        key: PredictionKey,
    ) -> Option<Prediction> {
        let ground = self.ground.as_ref().expect("a mechanism has a ground");
        let m = &self.mechanisms[g];
        let (mut bodies, mut motions, mut engaged, from, span) = if dt >= 0.0 {
            let (b, o): (Vec<_>, Vec<_>) = m
                .members
                .iter()
                .map(|&k| {
                    (
                        self.bodies[k].body().clone(),
                        on_ground(&self.bodies[k].motion),
                    )
                })
                .unzip();
            (b, o, m.engaged.clone(), self.time, dt)
        } else {
            let (t0, states) = self
                .step_start
                .as_ref()
                .expect("a step is under way when predicting backwards");
            let (b, o): (Vec<_>, Vec<_>) = m
                .members
                .iter()
                .map(|&k| (states[k].0.clone(), on_ground(&states[k].1)))
                .unzip();
            let engaged = self.engaged_at_step_start[g].clone();
            (b, o, engaged, *t0, (self.time + dt - t0).max(0.0))
        };
        let outcome = advance_mechanism(
            &mut bodies,
            &mut motions,
            &m.joints,
            &mut engaged,
            ground,
            from,
            span,
        );
        let outcome = match outcome {
            Ok(o) => o,
            Err(e) => {
                let e = e.at(Place::Bodies(
                    m.members.clone(),
                    vec![None; m.members.len()],
                ));
                self.deferred.lock().expect("not poisoned").get_or_insert(e);
                return None;
            }
        };
        let shared = Arc::new(MechanismOutcome {
            engaged,
            hits: outcome.hits,
        });
        let mut mine = None;
        for (k, ((state, motion), bound)) in bodies
            .into_iter()
            .zip(motions)
            .zip(outcome.bounds)
            .enumerate()
        {
            let p = Prediction {
                key: key.for_body(m.members[k]),
                state,
                motion,
                bound: (dt >= 0.0).then_some(bound),
                mechanism: Some(shared.clone()),
            };
            if m.members[k] == i {
                mine = Some(p.clone());
            }
            self.predictions.keep(p, self.predictions_kept());
        }
        mine
    }

    /// Takes a mechanism's outcome into the world after its members moved: the limits it
    /// rests against and the limits newly hit (as events).
    pub(super) fn settle_mechanism(&mut self, g: usize, outcome: &MechanismOutcome) {
        let m = &mut self.mechanisms[g];
        m.engaged = outcome.engaged.clone();
        for hit in &outcome.hits {
            self.joint_events.push(JointEvent {
                joint: m.ids[hit.joint],
                limit: hit.limit,
                time: hit.time,
                rate: hit.rate,
            });
        }
    }

    /// The velocity change of body `i`'s material point at `p` per unit impulse there (the
    /// point's mobility, 1/kg): through the joints when the body is a mechanism's member (the
    /// joints' reactions share the impulse with the other members), else the free body's
    /// `I/m - [r]x I^-1 [r]x`.
    pub(super) fn point_mobility(&self, i: usize, p: &Point) -> Matrix {
        let body = self.bodies[i].body();
        let r = p - body.position();
        let rx = r.cross_matrix();
        let free =
            Matrix::identity() / body.props().mass() - rx * body.world_inverse_inertia() * rx;
        let Some(g) = self.mechanism_of.get(i).copied().flatten() else {
            return free;
        };
        let m = &self.mechanisms[g];
        let me = m.members.iter().position(|&k| k == i).expect("a member");
        let jb = self.joint_bodies(g);
        // per axis e: the free members' velocities after a unit impulse e at p (all at rest
        // but this one), then projected onto the joints (one factor for the three)
        let kicks: Vec<Vec<(Vector, Vector)>> = (0..3)
            .map(|axis| {
                let e = Vector::ith(axis, 1.0);
                let mut nu = vec![(Vector::zeros(), Vector::zeros()); jb.len()];
                nu[me] = (e * jb[me].inv_mass, jb[me].inv_inertia * r.cross(&e));
                nu
            })
            .collect();
        let changes = project_velocities_each(&m.joints, &jb, &[], &kicks);
        let mut k = Matrix::zeros();
        for (axis, (nu, change)) in kicks.iter().zip(&changes).enumerate() {
            let (dv, dw) = (nu[me].0 + change[me].0, nu[me].1 + change[me].1);
            k.set_column(axis, &(dv + dw.cross(&r)));
        }
        k
    }

    /// The collision matrix K (1/kg) of an exchange at `p` between `i1` and `i2` when either is
    /// jointed: an impulse J on `i2` and -J on `i1` at `p` changes their relative point
    /// velocity by -K J, the joints' reactions included (two members of one mechanism feel
    /// each other through it).
    pub(super) fn pair_mobility(&self, i1: usize, i2: usize, p: &Point) -> Matrix {
        let (g1, g2) = (self.mechanism_of[i1], self.mechanism_of[i2]);
        if g1.is_none() || g2.is_none() || g1 != g2 {
            return self.point_mobility(i1, p) + self.point_mobility(i2, p);
        }
        let g = g1.expect("checked");
        let m = &self.mechanisms[g];
        let at = |i: usize| m.members.iter().position(|&k| k == i).expect("a member");
        let (a, b) = (at(i1), at(i2));
        let (ra, rb) = (
            p - self.bodies[i1].body().position(),
            p - self.bodies[i2].body().position(),
        );
        let jb = self.joint_bodies(g);
        // per axis e: -e on a and e on b at p, then projected onto the joints (one factor)
        let kicks: Vec<Vec<(Vector, Vector)>> = (0..3)
            .map(|axis| {
                let e = Vector::ith(axis, 1.0);
                let mut nu = vec![(Vector::zeros(), Vector::zeros()); jb.len()];
                nu[a] = (-e * jb[a].inv_mass, jb[a].inv_inertia * ra.cross(&(-e)));
                nu[b] = (e * jb[b].inv_mass, jb[b].inv_inertia * rb.cross(&e));
                nu
            })
            .collect();
        let changes = project_velocities_each(&m.joints, &jb, &[], &kicks);
        let mut k = Matrix::zeros();
        for (axis, (nu, change)) in kicks.iter().zip(&changes).enumerate() {
            let point =
                |i: usize, r: &Vector| (nu[i].0 + change[i].0) + (nu[i].1 + change[i].1).cross(r);
            k.set_column(axis, &(point(b, &rb) - point(a, &ra)));
        }
        k
    }

    /// After an impulse on body `i`: its mechanism's velocities projected back onto the
    /// joints (the joints' reaction impulses).
    pub(super) fn share_impulse(&mut self, i: usize) {
        let Some(g) = self.mechanism_of.get(i).copied().flatten() else {
            return;
        };
        let jb = self.joint_bodies(g);
        let change = project_velocities(&self.mechanisms[g].joints, &jb, &[]);
        let members = self.mechanisms[g].members.clone();
        for (k, (dv, dw)) in members.into_iter().zip(change) {
            self.bodies[k].change_velocity(&dv, &dw);
        }
    }

    /// The bodies an exchange between `i1` and `i2` moves: the two (in that order, so a
    /// pair without joints sums its energies as it always has) and their mechanisms' other
    /// members.
    pub(super) fn moved_by(&self, i1: usize, i2: usize) -> Vec<usize> {
        let mut out = vec![i1, i2];
        for i in [i1, i2] {
            if let Some(g) = self.mechanism_of.get(i).copied().flatten() {
                for &k in &self.mechanisms[g].members {
                    if !out.contains(&k) {
                        out.push(k);
                    }
                }
            }
        }
        out
    }

    /// The members of mechanism `g` as the joints see them now.
    fn joint_bodies(&self, g: usize) -> Vec<JointBody> {
        self.mechanisms[g]
            .members
            .iter()
            .map(|&k| {
                let b = self.bodies[k].body();
                let r = *b.orientation().to_rotation_matrix().matrix();
                JointBody {
                    x: b.position(),
                    r,
                    v: b.velocity(),
                    w: b.angular_velocity(),
                    inv_mass: 1.0 / b.props().mass(),
                    inv_inertia: b.world_inverse_inertia(),
                }
            })
            .collect()
    }

    /// How many predictions are kept: enough for every member of the largest mechanism
    /// twice over.
    pub(super) fn predictions_kept(&self) -> usize {
        super::PREDICTIONS_KEPT.max(2 * self.bodies.len())
    }
}

fn on_ground(motion: &Motion) -> OnGround {
    match motion {
        Motion::OnGround(g) => g.as_ref().clone(),
        _ => unreachable!("a mechanism's members move on the ground"),
    }
}
