//! The body's own contact with the ground: the points of its mesh that can touch it, the
//! spring-damper forces and friction on those in the ground, the landing impulses, whether the
//! ground carries the body, and the plane bounding the ground under it that spares the
//! points above it a look.

use crate::body::{MassProperties, RigidBody};
use crate::error::{Error, Result};
use crate::ground::{Ground, GroundBound, GroundPoint};
use crate::math::{Aabb, Point, Real, Rotation, Vector};
use crate::shape::MeshShape;
use crate::vehicle::VehicleSpec;

use super::{OnGround, Stage};

/// Margin (m) over the ground's bounding plane within which a body's point is still tested
/// against the ground below it: the plane's products round by about 1e-16 of the coordinates
/// (at most 1e6 m), far below it, so a point skipped is above the ground.
const BOUND_MARGIN: Real = 1e-6;
/// How far (m) the region of the kept ground bound reaches past the body's box: wider is
/// taken less often and bounds the ground less tightly; 0.5 m renews it about every 30 ms at
/// 15 m/s. It hardly matters: `benches/terrain_speed.py` on its 96,000-triangle bumpy slope
/// took 27.0 / 26.7 / 26.9 ms (locked) and 25.8 / 25.4 / 25.7 ms (rolling) per 2 s run at
/// 0.25 / 0.5 / 1 m (237.6 ms locked with 1 m and the normal of the triangle under the CG
/// instead of the mean slope: its bumps tilt it).
const GROUND_NEAR_MARGIN: Real = 0.5;
/// Natural frequency (Hz) of a body resting on its whole footprint on the ground: 20 Hz, so
/// it sinks g / (2 pi 20)^2 = 0.6 mm under its weight; a box car landing on its side corner
/// after a roll went 5.1 cm into the road at 10 Hz, 2.7 cm at 20 Hz
/// (tests/integration/dynamics.rs).
const BODY_CONTACT_FREQUENCY: Real = 20.0;
/// Damping ratio of the body-ground contact.
const BODY_CONTACT_DAMPING: Real = 0.5;
/// A contact point of the body approaching the ground faster than this (m/s) lands: an
/// inelastic impulse slows it, stopping it from twice this speed (see `OnGround::land`).
/// Resting, rocking and sliding bodies touch slower and stay with the spring-damper.
const LANDING_SPEED: Real = 0.5;
/// Depth (m) over which a landing point's impulse grows to its whole: a point just under the
/// road gets almost none, so where a landing begins moves continuously with the scene's
/// inputs (a whole stop at the first sub-step in the road made blue's rest heading in a
/// synthetic fit jump by 0.75 tolerances between speeds 0.05 % apart, against 0.05 with no
/// landing; benches/fit_synthetic.py scan --seed 1).
const LANDING_DEPTH: Real = 0.005;
/// Passes of the landing impulses over the points that land together.
const LANDING_PASSES: usize = 8;
/// Below this sliding speed (m/s) body-ground friction fades linearly (no chatter at rest),
/// for a body without static friction ([`BodyContact::with_static_friction`]), and for a
/// point of one in the sub-step it first touches.
pub const BODY_SLIP_SPEED: Real = 0.05;
/// Points of the hull within this distance (m) of a wheel's tyre (radially) count as the
/// wheel's, and this far to either side of its mid-plane.
const WHEEL_CLEARANCE: Real = 0.05;
const WHEEL_HALF_WIDTH: Real = 0.15;

/// The points by which a body's mesh can touch the ground, body frame.
#[derive(Clone, Debug)]
pub struct BodyContact {
    /// Convex-hull vertices not inside a wheel (m, body frame), by ascending z.
    points: Vec<Point>,
    /// Stiffness of each point (N/m).
    stiffness: Vec<Real>,
    /// Damping of each point (N s/m).
    damping: Vec<Real>,
    /// Box of the points, body frame (m): its lowest corner in the world bounds them all.
    bounds: Aabb,
    /// Largest |x| and |y| of a point (m): with the rotation's bottom row they bound how far
    /// a point's world height can differ from its body z (scaled), so only the points low
    /// enough in the body frame need a look.
    reach_xy: [Real; 2],
    /// Static friction: each touching point holds to an anchor on the ground by a tangential
    /// spring-damper capped at mu times its normal force (see [`OnGround::hold_anchors`]).
    sticks: bool,
    /// The body's own friction with the ground, in place of the ground's body friction
    /// ([`BodyContact::with_friction`]; None: the ground's).
    friction: Option<Real>,
}

impl BodyContact {
    /// The contact points of a mesh (body frame, origin at the CG) of mass `mass` (kg) whose
    /// wheels (if any) carry it. The stiffness per unit hull area makes a body resting on its
    /// footprint (the box's x-y area) sink 0.6 mm under the weight of `carried` kg (its own
    /// mass, or more for a body that carries others through joints: a pedestrian's foot); the
    /// damping is the damping ratio's for its own mass on that spring (with `carried` = `mass`,
    /// 2 zeta m omega).
    pub fn new(
        shape: &MeshShape,
        mass: Real,
        carried: Real,
        wheels: Option<&VehicleSpec>,
    ) -> Result<BodyContact> {
        let (vertices, triangles) = shape.convex_hull().map_err(|e| {
            Error::mesh(format!(
                "the body's convex hull (its contact with the ground) failed: {e}; the mesh \
                 may be flat or degenerate"
            ))
        })?;
        let mut area = vec![0.0; vertices.len()];
        for t in triangles {
            let [a, b, c] = t.map(|i| vertices[i as usize]);
            let third = (b - a).cross(&(c - a)).norm() / 6.0;
            for &i in t {
                area[i as usize] += third;
            }
        }
        let b = shape.aabb();
        let footprint = ((b.maxs.x - b.mins.x) * (b.maxs.y - b.mins.y)).max(1e-6);
        let omega = 2.0 * std::f64::consts::PI * BODY_CONTACT_FREQUENCY;
        let per_area = carried * omega * omega / footprint;
        // sqrt(k m) per unit area; exactly m omega for a body carrying its own weight.
        let effective = if carried == mass {
            mass
        } else {
            (carried * mass).sqrt()
        };
        let damping_per_area = 2.0 * BODY_CONTACT_DAMPING * effective * omega / footprint;
        let in_wheel = |p: &Point| {
            wheels.is_some_and(|spec| {
                spec.wheels.iter().any(|w| {
                    let d = p - w.center;
                    d.y.abs() <= WHEEL_HALF_WIDTH
                        && (d.x * d.x + d.z * d.z).sqrt() <= w.radius + WHEEL_CLEARANCE
                })
            })
        };
        let mut out = BodyContact {
            points: Vec::new(),
            stiffness: Vec::new(),
            damping: Vec::new(),
            bounds: Aabb::new_invalid(),
            reach_xy: [0.0, 0.0],
            sticks: false,
            friction: None,
        };
        let mut kept: Vec<(Point, Real)> = vertices
            .iter()
            .zip(&area)
            .filter(|(p, a)| **a > 0.0 && !in_wheel(p))
            .map(|(p, a)| (*p, *a))
            .collect();
        kept.sort_by(|a, b| a.0.z.total_cmp(&b.0.z).then(a.0.x.total_cmp(&b.0.x)));
        out.reach_xy = [0.0, 0.0];
        for (p, a) in kept {
            out.points.push(p);
            out.stiffness.push(per_area * a);
            out.damping.push(damping_per_area * a);
            out.bounds.take_point(p);
            out.reach_xy = [
                out.reach_xy[0].max(p.x.abs()),
                out.reach_xy[1].max(p.y.abs()),
            ];
        }
        Ok(out)
    }

    /// The same contact with static friction: each point touching the ground holds to an
    /// anchor on it by a tangential spring and damper (the point's normal stiffness and
    /// damping) until that force reaches mu times the point's normal force, past which the
    /// anchor slides behind the point (the tangential spring and Coulomb slider of Cundall &
    /// Strack, "A discrete numerical model for granular assemblies", Geotechnique 29(1),
    /// 1979). Without it the friction is viscous below [`BODY_SLIP_SPEED`], so a body
    /// pushed along the ground by less than its friction (a lying pedestrian whose joints
    /// press his segments apart) creeps at a few mm/s and never rests.
    pub fn with_static_friction(mut self) -> BodyContact {
        self.sticks = true;
        self
    }

    /// The same contact sliding on the ground with its own friction `mu` (None: the
    /// ground's body friction): a person's clothing on the road (a pedestrian's segments),
    /// not a car body's metal. `mu` is checked by the world (in (0, 2]).
    pub fn with_friction(mut self, mu: Option<Real>) -> BodyContact {
        self.friction = mu;
        self
    }

    /// Its friction with `ground`: its own, else the ground's body friction.
    fn friction_on(&self, ground: &Ground) -> Real {
        self.friction.unwrap_or_else(|| ground.body_friction())
    }

    /// The ground's normal force (N, >= 0) on point `k`, `depth` m in it and approaching at
    /// `vn` m/s along the ground's normal (negative: into it).
    fn normal_force(&self, k: usize, depth: Real, vn: Real) -> Real {
        (self.stiffness[k] * depth - self.damping[k] * vn).max(0.0)
    }

    /// Number of contact points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True without contact points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

/// The part of `d` along the ground (normal `n`, unit).
fn tangential(d: Vector, n: &Vector) -> Vector {
    d - n * d.dot(n)
}

/// `v` shortened to length `cap` when longer.
fn capped(v: Vector, cap: Real) -> Vector {
    let size = v.norm();
    if size > cap {
        v * (cap / size)
    } else {
        v
    }
}

/// A [`GroundBound`] over the box `lo`..`hi` (x, y; m, world) seen from above.
#[derive(Clone, Debug)]
pub(super) struct GroundNear {
    lo: [Real; 2],
    hi: [Real; 2],
    bound: GroundBound,
}

impl GroundNear {
    /// True when the box `lo`..`hi` (x, y) lies inside this one's.
    fn covers(&self, lo: [Real; 2], hi: [Real; 2]) -> bool {
        (0..2).all(|i| self.lo[i] <= lo[i] && hi[i] <= self.hi[i])
    }
}

impl OnGround {
    /// Adds the ground's forces on the body's contact points.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn body_contact(
        &self,
        ground: &Ground,
        x: &Point,
        r: &nalgebra::Matrix3<Real>,
        v: &Vector,
        w: &Vector,
        force: &mut Vector,
        torque: &mut Vector,
    ) {
        let c = &self.contact;
        let mu = c.friction_on(ground);
        self.for_each_touching(ground, x, r, |k, p, g, depth| {
            let vp = v + w.cross(&(p - x));
            let vn = vp.dot(&g.normal);
            let fn_ = c.normal_force(k, depth, vn);
            let vt = vp - g.normal * vn;
            let ft = match self.anchors.get(k).copied().flatten() {
                Some(a) => {
                    // the spring-damper to the anchor, capped at the sliding friction
                    let d = tangential(p - a, &g.normal);
                    capped(-d * c.stiffness[k] - vt * c.damping[k], mu * fn_)
                }
                None => -vt * (mu * fn_ / vt.norm().max(BODY_SLIP_SPEED)),
            };
            let f = g.normal * fn_ + ft;
            *force += f;
            *torque += (p - x).cross(&f);
        });
    }

    /// Moves the anchors of static friction to the stage `s` at a sub-step's end: a point
    /// touching the ground keeps its anchor while the tangential spring's force (its
    /// stiffness times the point's tangential distance from it) is at most mu times the
    /// point's normal force, else the anchor slides towards the point until it is; a point
    /// that has just touched takes the anchor whose spring gives the sliding friction it
    /// felt ([`BODY_SLIP_SPEED`]'s law); a point off the ground has none. Nothing for a
    /// contact without static friction.
    pub(super) fn hold_anchors(&mut self, props: &MassProperties, ground: &Ground, s: &Stage) {
        let c = &self.contact;
        if !c.sticks {
            return;
        }
        let r = *Rotation::new_normalize(s.q).to_rotation_matrix().matrix();
        let w = r * props.inverse_inertia() * r.transpose() * s.l;
        let x = Point::from(s.x);
        let mu = c.friction_on(ground);
        let mut held: Vec<Option<Point>> = Vec::new();
        self.for_each_touching(ground, &x, &r, |k, p, g, depth| {
            let vp = s.v + w.cross(&(p - x));
            let vn = vp.dot(&g.normal);
            let fn_ = c.normal_force(k, depth, vn);
            let reach = mu * fn_ / c.stiffness[k]; // the spring's longest stretch (m)
            let d = match self.anchors.get(k).copied().flatten() {
                Some(a) => capped(tangential(p - a, &g.normal), reach),
                None => {
                    let vt = vp - g.normal * vn;
                    vt * (reach / vt.norm().max(BODY_SLIP_SPEED))
                }
            };
            if held.is_empty() {
                held = vec![None; c.len()];
            }
            held[k] = Some(p - d);
        });
        self.anchors = held;
    }

    /// Calls `f(k, p, g, depth)` for every contact point k of the body (CG at `x`, rotation
    /// `r`) that is in the ground: its world position p, the ground below it and how deep.
    pub(super) fn for_each_touching(
        &self,
        ground: &Ground,
        x: &Point,
        r: &nalgebra::Matrix3<Real>,
        mut f: impl FnMut(usize, Point, GroundPoint, Real),
    ) {
        let c = &self.contact;
        if c.is_empty() {
            return;
        }
        let highest_ground = match ground.surface() {
            crate::ground::Surface::Plane { height } => *height,
            crate::ground::Surface::Terrain(mesh) => mesh.aabb().maxs.z,
        };
        // The corners of the points' box, turned into the world (about the CG).
        let (lo, hi) = (c.bounds.mins, c.bounds.maxs);
        let corners = [0, 1, 2, 3, 4, 5, 6, 7].map(|k| {
            r * Vector::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        });
        // Its lowest corner above the highest ground: nothing touches (a car on its wheels on
        // a plane or a level terrain: every evaluation ends here).
        if x.z + corners.iter().map(|c| c.z).fold(Real::INFINITY, Real::min) > highest_ground {
            return;
        }
        // The ground under the box seen from above, bounded by a plane along its mean slope
        // (on a slope the highest ground is far above the car's).
        let (mut xy_lo, mut xy_hi) = ([Real::INFINITY; 2], [Real::NEG_INFINITY; 2]);
        for c in &corners {
            for i in 0..2 {
                xy_lo[i] = xy_lo[i].min(x[i] + c[i]);
                xy_hi[i] = xy_hi[i].max(x[i] + c[i]);
            }
        }
        let bound = match &self.ground_near {
            Some(near) if near.covers(xy_lo, xy_hi) => near.bound,
            _ => ground.bound_under(xy_lo, xy_hi),
        };
        let n = bound.normal;
        // A point can touch only below the plane `n . p = limit_n`: the ground's bound, with a
        // margin over the rounding of the products (the points within it are tested exactly).
        let limit_n = bound.offset + BOUND_MARGIN;
        let base = n.dot(&x.coords);
        if base
            + corners
                .iter()
                .map(|c| n.dot(c))
                .fold(Real::INFINITY, Real::min)
            > limit_n
        {
            return;
        }
        // A point's height along n is base + m . p (m = r^T n, the normal in the body frame),
        // at least base + m_z p_z - slack: only points whose m_z p_z is low enough can touch.
        // The points are sorted by p_z, so that is a prefix (m_z > 0) or a suffix.
        let m = r.transpose() * n;
        let slack = m.x.abs() * c.reach_xy[0] + m.y.abs() * c.reach_xy[1];
        let limit = limit_n - base + slack;
        let count = c.points.len();
        let range = if m.z > 0.0 {
            0..c.points.partition_point(|p| m.z * p.z <= limit)
        } else if m.z < 0.0 {
            c.points.partition_point(|p| m.z * p.z > limit)..count
        } else {
            0..count
        };
        for k in range {
            let p = x + r * c.points[k].coords;
            if p.z > highest_ground || n.dot(&p.coords) > limit_n {
                continue;
            }
            let Some(g) = ground.below(&p) else {
                continue; // off the terrain: nothing to touch
            };
            let depth = (g.point - p).dot(&g.normal);
            if depth > 0.0 {
                f(k, p, g, depth);
            }
        }
    }

    /// True when the ground carries the body: a wheel's spring pushes (its centre lower than
    /// its tyre's radius plus the spring's free travel F0 / k above the ground) or a point
    /// of the body is in the ground. A body in the air, falling or at the top of a bounce,
    /// is not at rest whatever its speed along the ground.
    pub fn supported(&self, body: &RigidBody, ground: &Ground) -> bool {
        let x = body.position();
        let rot = body.orientation().to_rotation_matrix();
        let r = rot.matrix();
        if let Some(spec) = &self.vehicle {
            for wheel in &spec.wheels {
                let c = x + r * wheel.center.coords;
                let Some(g) = ground.below(&c) else {
                    continue;
                };
                let h = (c - g.point).dot(&g.normal);
                if wheel.static_load + wheel.spring_rate * (wheel.radius - h) > 0.0 {
                    return true;
                }
            }
        }
        self.deepest(body, ground).is_some()
    }

    /// The deepest of the body's contact points in the ground (m) and where it is (world),
    /// None when none is.
    pub fn deepest(&self, body: &RigidBody, ground: &Ground) -> Option<(Real, Point)> {
        let r = *body.orientation().to_rotation_matrix().matrix();
        let mut deepest: Option<(Real, Point)> = None;
        self.for_each_touching(ground, &body.position(), &r, |_, p, _, depth| {
            if deepest.is_none_or(|(d, _)| depth > d) {
                deepest = Some((depth, p));
            }
        });
        deepest
    }

    /// A landing: contact points in the ground approaching it faster than [`LANDING_SPEED`]
    /// get inelastic impulses toward a normal velocity v_n (1 - f h), accumulated over
    /// [`LANDING_PASSES`] passes of the points in turn, never pulling, then one pass of
    /// body-ground friction (at most mu times each point's normal impulse, against its
    /// sliding). f = min(1, depth / [`LANDING_DEPTH`]) and h = clamp(-v_n / LANDING_SPEED - 1,
    /// 0, 1): a point 5 mm deep approaching at 1 m/s or more is stopped, and the impulse
    /// fades to zero at the road's surface and at LANDING_SPEED, so the motion changes
    /// continuously with where and how fast a landing begins. Each impulse takes kinetic
    /// energy, none adds it. The spring-damper alone let a roof landing 4.6 cm into the road
    /// (a few hull points carry the whole stop); a body resting or sliding on the ground, or
    /// placed in it, stays with the spring.
    pub(super) fn land(&self, props: &MassProperties, ground: &Ground, s: &mut Stage) {
        let q = Rotation::new_normalize(s.q);
        let r = *q.to_rotation_matrix().matrix();
        let inv_i = r * props.inverse_inertia() * r.transpose();
        let x = Point::from(s.x);
        let w = inv_i * s.l;
        // Lever arm, ground normal, the normal velocity aimed for (m/s).
        let mut points: Vec<(Vector, Vector, Real)> = Vec::new();
        self.for_each_touching(ground, &x, &r, |_, p, g, depth| {
            let arm = p - x;
            let vn = (s.v + w.cross(&arm)).dot(&g.normal);
            if vn < -LANDING_SPEED {
                let f = (depth / LANDING_DEPTH).min(1.0);
                let h = (-vn / LANDING_SPEED - 1.0).min(1.0);
                points.push((arm, g.normal, vn * (1.0 - f * h)));
            }
        });
        if points.is_empty() {
            return;
        }
        let inv_m = 1.0 / props.mass();
        // Inverse effective mass of the body at lever arm `arm` along unit `d`.
        let inverse_mass =
            |arm: &Vector, d: &Vector| inv_m + d.dot(&(inv_i * arm.cross(d)).cross(arm));
        let point_velocity = |s: &Stage, arm: &Vector| s.v + (inv_i * s.l).cross(arm);
        let mut normal = vec![0.0; points.len()];
        for _ in 0..LANDING_PASSES {
            for ((arm, n, aim), acc) in points.iter().zip(normal.iter_mut()) {
                let vn = point_velocity(s, arm).dot(n);
                let next = (*acc - (vn - aim) / inverse_mass(arm, n)).max(0.0);
                let j = *n * (next - *acc);
                *acc = next;
                s.v += j * inv_m;
                s.l += arm.cross(&j);
            }
        }
        let mu = self.contact.friction_on(ground);
        for ((arm, n, _), acc) in points.iter().zip(&normal) {
            let vp = point_velocity(s, arm);
            let vt = vp - *n * vp.dot(n);
            let slip = vt.norm();
            if slip == 0.0 || *acc == 0.0 {
                continue;
            }
            let t = vt / slip;
            let j = -t * (slip / inverse_mass(arm, &t)).min(mu * acc);
            s.v += j * inv_m;
            s.l += arm.cross(&j);
        }
    }

    /// Keeps [`OnGround::ground_near`] over the body's box for the next `dt` s: when the box,
    /// grown by twice the farthest a point of the body can move in `dt` (its speed plus its
    /// angular speed times its reach), leaves the kept region, the region becomes that box
    /// grown by [`GROUND_NEAR_MARGIN`] more and its bound is taken anew. A body on a plane
    /// needs none.
    pub(super) fn keep_ground_near(&mut self, body: &RigidBody, ground: &Ground, dt: Real) {
        if matches!(ground.surface(), crate::ground::Surface::Plane { .. }) {
            return;
        }
        let c = &self.contact;
        if c.is_empty() {
            return;
        }
        let x = body.position();
        let r = *body.orientation().to_rotation_matrix().matrix();
        let reach = c
            .bounds
            .mins
            .coords
            .abs()
            .sup(&c.bounds.maxs.coords.abs())
            .norm();
        let travel = 2.0 * (body.velocity().norm() + body.angular_velocity().norm() * reach) * dt;
        let (mut lo, mut hi) = ([Real::INFINITY; 2], [Real::NEG_INFINITY; 2]);
        for k in 0..8 {
            let corner = r * Vector::new(
                if k & 1 == 0 {
                    c.bounds.mins.x
                } else {
                    c.bounds.maxs.x
                },
                if k & 2 == 0 {
                    c.bounds.mins.y
                } else {
                    c.bounds.maxs.y
                },
                if k & 4 == 0 {
                    c.bounds.mins.z
                } else {
                    c.bounds.maxs.z
                },
            );
            for i in 0..2 {
                lo[i] = lo[i].min(x[i] + corner[i] - travel);
                hi[i] = hi[i].max(x[i] + corner[i] + travel);
            }
        }
        if self
            .ground_near
            .as_ref()
            .is_some_and(|near| near.covers(lo, hi))
        {
            return;
        }
        let lo = lo.map(|a| a - GROUND_NEAR_MARGIN);
        let hi = hi.map(|a| a + GROUND_NEAR_MARGIN);
        self.ground_near = Some(GroundNear {
            lo,
            hi,
            bound: ground.bound_under(lo, hi),
        });
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::body::BodyState;
    use crate::ground::DEFAULT_BODY_FRICTION;
    use crate::vehicle::GRAVITY;
    use proptest::prelude::*;

    /// A closed ellipsoid (lat-long grid) with semi-axes `a` (m), centred at the origin.
    fn ellipsoid(a: Vector) -> MeshShape {
        let (rings, sectors) = (10, 20);
        let mut v = vec![Point::new(0.0, 0.0, -a.z)];
        for i in 1..rings {
            let theta = std::f64::consts::PI * i as Real / rings as Real;
            for j in 0..sectors {
                let phi = 2.0 * std::f64::consts::PI * j as Real / sectors as Real;
                v.push(Point::new(
                    a.x * theta.sin() * phi.cos(),
                    a.y * theta.sin() * phi.sin(),
                    -a.z * theta.cos(),
                ));
            }
        }
        v.push(Point::new(0.0, 0.0, a.z));
        let top = (v.len() - 1) as u32;
        let at = |i: u32, j: u32| 1 + (i - 1) * sectors + j % sectors;
        let mut t = Vec::new();
        for j in 0..sectors {
            t.push([0, at(1, j + 1), at(1, j)]);
            t.push([top, at(rings - 1, j), at(rings - 1, j + 1)]);
        }
        for i in 1..rings - 1 {
            for j in 0..sectors {
                t.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
                t.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
            }
        }
        MeshShape::new(v, t).unwrap()
    }

    /// A 60 m x 60 m terrain rising 12 deg along x with bumps and a 0.3 m kerb (its face
    /// vertical) along x = 10 m.
    fn bumpy_slope() -> Ground {
        let n = 61;
        let height = |x: Real, y: Real| {
            0.21 * x + 0.15 * (0.7 * x).sin() * (0.5 * y).cos() + if x >= 10.0 { 0.3 } else { 0.0 }
        };
        let mut v = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let (x, y) = (-30.0 + i as Real, -30.0 + j as Real);
                // the kerb: the grid line x = 10 carries both heights
                let x_low = if (x - 10.0).abs() < 1e-9 {
                    10.0 - 1e-9
                } else {
                    x
                };
                v.push(Point::new(x_low, y, height(x_low, y)));
            }
        }
        let id = |i: usize, j: usize| (i * n + j) as u32;
        let mut t = Vec::new();
        for i in 0..n - 1 {
            for j in 0..n - 1 {
                t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        Ground::terrain(Arc::new(MeshShape::new(v, t).unwrap())).unwrap()
    }

    /// A plane through the origin rising `deg` along x (200 m square).
    fn tilted(deg: Real) -> Ground {
        let slope = deg.to_radians().tan();
        let v = [
            (-100.0, -100.0),
            (100.0, -100.0),
            (100.0, 100.0),
            (-100.0, 100.0),
        ]
        .map(|(x, y)| Point::new(x, y, slope * x));
        let mesh = MeshShape::new(v.to_vec(), vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        Ground::terrain(Arc::new(mesh)).unwrap()
    }

    /// A 20 kg box 0.4 x 0.4 x 0.2 m resting (just touching) on `tilted(deg)` at the origin,
    /// with or without static friction, with its own ground friction or the ground's,
    /// advanced in 1 ms steps; the CG's distance down the slope (m) at 0.5, 1.0 and 1.5 s.
    fn box_on_slope(deg: Real, sticks: bool) -> [Real; 3] {
        box_on_slope_with(deg, sticks, None)
    }

    fn box_on_slope_with(deg: Real, sticks: bool, friction: Option<Real>) -> [Real; 3] {
        let ground = tilted(deg);
        let shape = MeshShape::cuboid(Vector::zeros(), Vector::new(0.2, 0.2, 0.1));
        let (mass, inertia) = (20.0, Vector::new(0.0833, 0.0833, 0.1333)); // kg, kg m^2
        let props = MassProperties::new(mass, nalgebra::Matrix3::from_diagonal(&inertia));
        let contact = BodyContact::new(&shape, mass, mass, None)
            .unwrap()
            .with_friction(friction);
        let contact = if sticks {
            contact.with_static_friction()
        } else {
            contact
        };
        let mut on = OnGround::new(None, Arc::new(contact));
        let theta = deg.to_radians();
        let normal = Vector::new(-theta.sin(), 0.0, theta.cos());
        let state = BodyState {
            position: Point::from(normal * 0.1),
            orientation: Rotation::from_euler_angles(0.0, -theta, 0.0),
            velocity: Vector::zeros(),
            angular_velocity: Vector::zeros(),
        };
        let mut body = RigidBody::new(props.unwrap(), &state).unwrap();
        let down = Vector::new(-theta.cos(), 0.0, -theta.sin());
        let mut out = [0.0; 3];
        for step in 0..1500 {
            on.advance(&mut body, &ground, step as Real * 1e-3, 1e-3)
                .unwrap();
            if (step + 1) % 500 == 0 {
                out[step / 500] = body.position().coords.dot(&down);
            }
        }
        out
    }

    /// Static friction holds a box on a 10 deg slope (tan 10 deg = 0.18 below the body
    /// friction 0.45): from 0.5 to 1.5 s it moves less than 1 um, where the friction fading
    /// below BODY_SLIP_SPEED lets it creep at about 0.05 tan(10 deg) / 0.45 = 19.6 mm/s.
    #[test]
    fn static_friction_holds_a_body_on_a_slope_the_regularised_law_lets_creep() {
        let held = box_on_slope(10.0, true);
        assert!((held[2] - held[0]).abs() < 1e-6, "{held:?}");
        let crept = box_on_slope(10.0, false);
        let creep = (crept[2] - crept[0]) / 1.0; // m/s
        let expected = 0.05 * 10.0_f64.to_radians().tan() / DEFAULT_BODY_FRICTION;
        // measured 19.11 mm/s, steady from 0.5 s on
        assert!(
            (creep - expected).abs() < 0.05 * expected,
            "{creep} {expected}"
        );
    }

    /// On a 30 deg slope (steeper than atan 0.45 = 24.2 deg) the box slides with the
    /// closed form's acceleration g (sin 30 deg - 0.45 cos 30 deg) = 1.082 m/s^2 within
    /// 0.5 %, static friction or not (from the distances at 0.5, 1 and 1.5 s).
    #[test]
    fn a_body_steeper_than_its_friction_slides_at_the_closed_form_acceleration() {
        let t = 30.0_f64.to_radians();
        let a = GRAVITY * (t.sin() - DEFAULT_BODY_FRICTION * t.cos());
        for sticks in [true, false] {
            let [s05, s10, s15] = box_on_slope(30.0, sticks);
            // second difference over 0.5 s intervals: a h^2
            let measured = (s15 - 2.0 * s10 + s05) / 0.25;
            assert!((measured - a).abs() < 0.005 * a, "{sticks}: {measured} {a}");
        }
    }

    /// A body's own ground friction replaces the ground's: on the 30 deg slope a box with
    /// its own 0.3 slides at g (sin 30 deg - 0.3 cos 30 deg) = 2.356 m/s^2 within 0.5 %
    /// (the ground's 0.45 gives 1.082); on a 25 deg slope (tan 25 deg = 0.466), which the
    /// ground's 0.45 does not hold, one with its own 0.9 is held by its static friction:
    /// under 1 um from 0.5 to 1.5 s. Its own 0.45 is the ground's friction, bit for bit.
    #[test]
    fn a_body_with_its_own_ground_friction_slides_or_holds_by_it() {
        let t = 30.0_f64.to_radians();
        let a = GRAVITY * (t.sin() - 0.3 * t.cos());
        for sticks in [true, false] {
            let [s05, s10, s15] = box_on_slope_with(30.0, sticks, Some(0.3));
            let measured = (s15 - 2.0 * s10 + s05) / 0.25;
            assert!((measured - a).abs() < 0.005 * a, "{sticks}: {measured} {a}");
        }
        let held = box_on_slope_with(25.0, true, Some(0.9));
        assert!((held[2] - held[0]).abs() < 1e-6, "{held:?}");
        let slid = box_on_slope(25.0, true);
        assert!(slid[2] - slid[0] > 0.05, "{slid:?}");
        let ground = box_on_slope_with(30.0, true, Some(DEFAULT_BODY_FRICTION));
        assert_eq!(ground, box_on_slope(30.0, true));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// The points the bound lets through touch exactly as the brute force (every point
        /// against the ground straight below it) finds, in any pose over the sloped, bumpy
        /// terrain with its kerb.
        #[test]
        fn touching_points_are_those_of_the_brute_force(
            x in -20.0..20.0f64, y in -20.0..20.0f64, dz in -1.5..1.5f64,
            yaw in -3.2..3.2f64, pitch in -3.2..3.2f64, roll in -3.2..3.2f64,
        ) {
            let ground = bumpy_slope();
            let shape = ellipsoid(Vector::new(2.3, 0.9, 0.7));
            let contact = Arc::new(BodyContact::new(&shape, 1500.0, 1500.0, None).unwrap());
            let on = OnGround::new(None, contact.clone());
            let h = ground.height_at(x, y).unwrap();
            let cg = Point::new(x, y, h + dz);
            let r = Rotation::from_euler_angles(roll, pitch, yaw).to_rotation_matrix().into_inner();
            let mut found = Vec::new();
            on.for_each_touching(&ground, &cg, &r, |k, _, g, depth| found.push((k, g, depth)));
            let mut brute = Vec::new();
            for (k, q) in contact.points.iter().enumerate() {
                let p = cg + r * q.coords;
                if let Some(g) = ground.below(&p) {
                    let depth = (g.point - p).dot(&g.normal);
                    if depth > 0.0 {
                        brute.push((k, g, depth));
                    }
                }
            }
            found.sort_by_key(|e| e.0);
            prop_assert_eq!(found, brute);
        }
    }
}
