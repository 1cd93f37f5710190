//! A pair's clearance front: parts of the two meshes (pairs of BVH nodes, or of triangles)
//! known to be apart, so that a step whose motion cannot close any of those gaps needs no
//! mesh query (the no-contact-stepped-over guarantee of docs/model.md, "First overlap", kept by
//! certificates, not by a distance query every step).
//!
//! The front is a tree grown from the two root nodes. Its leaves hold two convex parts
//! (boxes of the two trees, or two triangles) whose contents were, at the leaf's evaluation,
//! separated by `gap` (m) along the world direction `n`: every point b of part 2 and a of
//! part 1 had n.(b - a) >= gap (a separating plane: the gap vector of two boxes, the closest
//! points of two triangles). Later, with each body's CG moved and turned,
//!
//! n.(b - a) >= gap + [f(now) - f(then)] - chord1 r1 - chord2 r2,
//!
//! f = n.(x2 + R2 u2 - x1 - R1 u1) the parts' centres u (body frames) carried exactly, chord
//! the chord 2 sin(theta / 2) of each body's rotation since the evaluation and r the parts'
//! radii about their centres: the bound follows the net motion (a car rocking on its springs
//! back and forth does not wear it down) and its rotation term is a part's size, not the
//! body's. Within a step the bound's rate is bounded from the velocities now and the motion's
//! bounds over the step ([`MotionBound`]), so a pair parting (the rate positive) stays
//! certified however small its gap.
//!
//! A leaf that fails is evaluated afresh at the current poses; a node pair that still fails
//! becomes a group of its children (the larger box split, or the triangle pairs of two
//! leaves). A group keeps the least bound of its subtree at a reference instant and is
//! certified while the net motion of its own region since then, |change of x2 + R2 u2 - x1 -
//! R1 u1| + chord1 r1 + chord2 r2 (u, r its boxes' centres and radii), plus how far that
//! region can drift within the step, stays below it: a step descends only into the groups its motion could wear out, so the
//! far parts of two cars cost nothing while the cars rock next to each other. A triangle
//! pair that still fails is critical: the step is then searched on the critical pairs alone.

use crate::math::{box_gap, Aabb, Isometry, Matrix, Real, RigidMap, Rotation, Vector};
use crate::motion::MotionBound;
use crate::shape::{MeshShape, Obb};
use crate::triangle::{centroid, triangle_triangle_closest, triangle_triangle_contact, Tri};

/// Margin (m) a certificate must keep above zero: round-off in the poses and gaps.
const CLEARANCE_MARGIN: Real = 1e-9;
/// Most parts a front may hold; past it the front is dropped and the pair searched exactly
/// (two meshes pressed together over a large area at high speed).
pub(super) const MAX_PARTS: usize = 50_000;

/// Which parts of the two meshes a front node keeps apart.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Parts {
    /// BVH nodes (of mesh 1, of mesh 2).
    Nodes(u32, u32),
    /// Triangles (of mesh 1, of mesh 2).
    Triangles(u32, u32),
}

/// A leaf's separating plane, or a group's children.
#[derive(Clone, Copy, Debug)]
enum Kind {
    Leaf {
        /// Separation along `n` at the evaluation (m, >= 0).
        gap: Real,
        /// World direction from part 1 to part 2 (unit; zero when the parts meet).
        n: Vector,
        /// f at the evaluation (m): n.(x2 + R2 u2 - x1 - R1 u1).
        f: Real,
    },
    Group {
        /// The children's slots: `count` consecutive ones from `first`.
        first: u32,
        count: u32,
        /// The least lower bound of the subtree's separations at the reference (m).
        margin: Real,
        /// x2 + R2 u2 - x1 - R1 u1 at the reference (m, world).
        offset: Vector,
    },
}

#[derive(Clone, Debug)]
struct Node {
    parts: Parts,
    /// Centres of the parts, each in its body's frame (m).
    u: [Vector; 2],
    /// Radii of the parts about their centres (m).
    r: [Real; 2],
    /// The bodies' orientations at the leaf's evaluation, or the group's reference.
    q: [Rotation; 2],
    kind: Kind,
}

/// The two bodies over the coming step, as the front reads them.
#[derive(Clone, Debug)]
pub(super) struct PairMotion {
    /// Poses now (body -> world).
    pub pose: [Isometry; 2],
    /// Rotation matrices now.
    pub rot: [Matrix; 2],
    /// CG velocities now (m/s) and angular velocities now (rad/s), world.
    pub v: [Vector; 2],
    pub w: [Vector; 2],
    /// Each body's motion bound over the step.
    pub bound: [MotionBound; 2],
    /// Length of the step (s).
    pub span: Real,
    /// A bound on the relative speed of any point of one mesh against any of the other over
    /// the step (m/s).
    pub speed: Real,
}

impl PairMotion {
    /// The offset x2 + R2 u2 - x1 - R1 u1 of two parts' centres now (m, world).
    #[inline]
    fn offset(&self, u: &[Vector; 2]) -> Vector {
        self.pose[1].translation.vector + self.rot[1] * u[1]
            - self.pose[0].translation.vector
            - self.rot[0] * u[0]
    }

    /// A lower bound (m) of the separation now of a group's subtree: its margin less the net
    /// motion of its region since the reference.
    #[inline]
    fn group_bound(&self, node: &Node, margin: Real, offset: &Vector) -> Real {
        margin
            - (self.offset(&node.u) - offset).norm()
            - chord_bound(&self.pose[0].rotation, &node.q[0]) * node.r[0]
            - chord_bound(&self.pose[1].rotation, &node.q[1]) * node.r[1]
    }

    /// How far (m) the parts of a front node can move relative to each other over the step:
    /// the rate of their centres' offset now, how far it can stray (the CG velocities' and
    /// angular velocities' change, the lever arms' turning) and the parts' own turning.
    #[inline]
    fn drift(&self, node: &Node) -> Real {
        let a1 = self.rot[0] * node.u[0];
        let a2 = self.rot[1] * node.u[1];
        let rate = self.v[1] + self.w[1].cross(&a2) - self.v[0] - self.w[0].cross(&a1);
        self.span * (rate.norm() + self.stray(node, 0) + self.stray(node, 1))
    }

    /// How far the velocity (m/s) of body `k`'s part of `node` can stray from its value
    /// now over the step, plus the part's own turning about its centre.
    #[inline]
    fn stray(&self, node: &Node, k: usize) -> Real {
        let b = &self.bound[k];
        b.velocity_change
            + (b.angular_velocity_change + self.w[k].norm() * b.angular_speed * self.span)
                * node.u[k].norm()
            + b.angular_speed * node.r[k]
    }

    /// Lower bound of a leaf's separation now (m), and of its rate over the step (m/s): it
    /// is at least `now + s min(0, slope)` for s in [0, span].
    #[inline]
    fn bound(&self, e: &Node) -> (Real, Real) {
        let Kind::Leaf { gap, n, f: f_then } = e.kind else {
            unreachable!("bounds are of leaves")
        };
        let a1 = self.rot[0] * e.u[0];
        let a2 = self.rot[1] * e.u[1];
        let x1 = self.pose[0].translation.vector;
        let x2 = self.pose[1].translation.vector;
        let f = n.dot(&(x2 + a2 - x1 - a1));
        let chord = |k: usize| chord_bound(&self.pose[k].rotation, &e.q[k]);
        let now = gap + (f - f_then) - chord(0) * e.r[0] - chord(1) * e.r[1];
        // d/dt of f now, and how far it can stray over the step: the CG velocities' change,
        // the angular velocities' change and the turning of the centres' lever arms.
        let rate = n.dot(&(self.v[1] + self.w[1].cross(&a2) - self.v[0] - self.w[0].cross(&a1)));
        (now, rate - self.stray(e, 0) - self.stray(e, 1))
    }

    /// Lower bound of an entry's separation now, and its lowest over the step (m).
    #[inline]
    fn lowest(&self, e: &Node) -> (Real, Real) {
        let (now, slope) = self.bound(e);
        (now, now + self.span * slope.min(0.0))
    }

    /// The same bodies `offset` s into the step, at the poses and velocities given: the rest
    /// of the step, with the bounds on the change from the step's start doubled (they bound
    /// the change from any instant of it).
    pub fn later(
        &self,
        offset: Real,
        pose: [Isometry; 2],
        v: [Vector; 2],
        w: [Vector; 2],
    ) -> PairMotion {
        let twice = |b: &MotionBound| MotionBound {
            velocity_change: 2.0 * b.velocity_change,
            angular_speed: b.angular_speed,
            angular_velocity_change: 2.0 * b.angular_velocity_change,
        };
        PairMotion {
            rot: [
                pose[0].rotation.to_rotation_matrix().into_inner(),
                pose[1].rotation.to_rotation_matrix().into_inner(),
            ],
            pose,
            v,
            w,
            bound: [twice(&self.bound[0]), twice(&self.bound[1])],
            span: (self.span - offset).max(0.0),
            speed: self.speed,
        }
    }

    /// Two triangles (of mesh 1, of mesh 2) at these poses: None when they touch or cross,
    /// else a lower bound of their distance now (m) and of its rate over the rest of the
    /// step (m/s), from their closest points.
    pub fn triangles_apart(
        &self,
        (t1, t2): (u32, u32),
        s1: &MeshShape,
        s2: &MeshShape,
    ) -> Option<(Real, Real)> {
        let e = closest_leaf(t1, t2, s1, s2, self);
        match e.kind {
            Kind::Leaf { gap, .. } if gap > 0.0 => Some(self.bound(&e)),
            _ => None,
        }
    }

    /// True when the two triangles' surfaces cross at these poses (as the mesh-level
    /// crossing test decides: [`crate::overlap::surfaces_intersect`]).
    pub fn triangles_cross(&self, (t1, t2): (u32, u32), s1: &MeshShape, s2: &MeshShape) -> bool {
        let map = RigidMap::new(&self.pose[0].inv_mul(&self.pose[1]));
        let tri2 = s2.triangle(t2);
        let tri2_in_1 = [
            map.point(&tri2[0]),
            map.point(&tri2[1]),
            map.point(&tri2[2]),
        ];
        triangle_triangle_contact(&s1.triangle(t1), &tri2_in_1).is_some_and(|c| c.is_crossing())
    }
}

/// An upper bound of the chord 2 sin(theta / 2) of the rotation between two orientations
/// (theta its angle): 2 |q - q0| with the sign that makes them closest, exact to first order
/// and free of the cancellation of 1 - (q.q0)^2 for small angles.
#[inline]
fn chord_bound(q: &Rotation, q0: &Rotation) -> Real {
    let (a, b) = (q.as_ref().coords, q0.as_ref().coords);
    let d = if a.dot(&b) >= 0.0 { a - b } else { a + b };
    2.0 * d.norm()
}

/// What [`Front::certify`] found for a step.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Certificate {
    /// No part of one mesh can reach the other within the step; the meshes are at least
    /// this far apart now (m).
    Clear(Real),
    /// These triangle pairs (of mesh 1, of mesh 2) may meet within the step; every other
    /// part is apart over the whole step.
    Critical(Vec<(u32, u32)>),
    /// The front grew past [`MAX_PARTS`]: drop it and search exactly.
    TooLarge,
}

/// The clearance front of an apart pair (see the module's documentation): a tree whose root
/// is slot 0.
#[derive(Clone, Debug, Default)]
pub(super) struct Front {
    nodes: Vec<Node>,
    /// Parts evaluated afresh so far.
    evaluations: u64,
    /// Front nodes looked at so far.
    checks: u64,
    /// Scratch: children of a split node pair.
    split: Vec<Parts>,
}

/// What a step's walk of the front collects.
struct Walk<'a> {
    s1: &'a MeshShape,
    s2: &'a MeshShape,
    m: &'a PairMotion,
    critical: Vec<(u32, u32)>,
}

impl Front {
    /// A front of one leaf, the two root nodes, evaluated at `m`'s poses.
    pub fn new(s1: &MeshShape, s2: &MeshShape, m: &PairMotion) -> Front {
        Front {
            nodes: vec![evaluate(Parts::Nodes(0, 0), s1, s2, m)],
            evaluations: 1,
            ..Front::default()
        }
    }

    /// Nodes of the front (leaves and groups).
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Parts (node or triangle pairs) evaluated afresh so far.
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// Front nodes looked at so far.
    pub fn checks(&self) -> u64 {
        self.checks
    }

    /// Whether the step `m` describes is clear: walks into the groups its motion could wear
    /// out, evaluating leaves afresh and splitting as needed.
    pub fn certify(&mut self, s1: &MeshShape, s2: &MeshShape, m: &PairMotion) -> Certificate {
        let mut walk = Walk {
            s1,
            s2,
            m,
            critical: Vec::new(),
        };
        let margin = self.visit(0, false, &mut walk);
        if self.nodes.len() > MAX_PARTS {
            Certificate::TooLarge
        } else if walk.critical.is_empty() {
            Certificate::Clear(margin)
        } else {
            Certificate::Critical(walk.critical)
        }
    }

    /// Looks at node `idx` (`fresh`: a leaf just evaluated at the current poses) for the
    /// step; returns a lower bound of its parts' separation now (m).
    fn visit(&mut self, idx: u32, fresh: bool, w: &mut Walk) -> Real {
        self.checks += 1;
        let m = w.m;
        let node = &self.nodes[idx as usize];
        if let Kind::Group {
            first,
            count,
            margin,
            offset,
        } = node.kind
        {
            let now = m.group_bound(node, margin, &offset);
            if now - m.drift(node) > CLEARANCE_MARGIN {
                return now; // no part of the subtree can be reached within the step
            }
            return self.visit_group(idx, first, count, false, w);
        }
        let (now, low) = m.lowest(node);
        let parts = node.parts;
        if low > CLEARANCE_MARGIN {
            return now;
        }
        if !fresh {
            // Worn by the motion since its evaluation: look again from here.
            self.evaluations += 1;
            self.nodes[idx as usize] = evaluate(parts, w.s1, w.s2, m);
            return self.visit(idx, true, w);
        }
        match parts {
            Parts::Triangles(t1, t2) => {
                w.critical.push((t1, t2));
                now
            }
            Parts::Nodes(a, b) => {
                if self.nodes.len() > MAX_PARTS {
                    return Real::NEG_INFINITY; // given up: the caller drops the front
                }
                // The leaf becomes a group of its children, evaluated and looked at now.
                let mut split = std::mem::take(&mut self.split);
                split.clear();
                children(a, b, w.s1, w.s2, &mut split);
                let first = self.nodes.len() as u32;
                for &child in &split {
                    self.evaluations += 1;
                    self.nodes.push(evaluate(child, w.s1, w.s2, m));
                }
                let count = split.len() as u32;
                self.split = split;
                self.visit_group(idx, first, count, true, w)
            }
        }
    }

    /// Visits the `count` children from `first` of node `idx` (`fresh`: just evaluated) and
    /// makes `idx` their group: their least bound, with the poses and net offset it holds
    /// from. Returns that bound (m).
    fn visit_group(&mut self, idx: u32, first: u32, count: u32, fresh: bool, w: &mut Walk) -> Real {
        let mut least = Real::INFINITY;
        for c in first..first + count {
            least = least.min(self.visit(c, fresh, w));
        }
        let m = w.m;
        let node = &mut self.nodes[idx as usize];
        node.q = [m.pose[0].rotation, m.pose[1].rotation];
        node.kind = Kind::Group {
            first,
            count,
            margin: least,
            offset: m.offset(&node.u),
        };
        least
    }
}

/// The child pairs of a node pair: the larger box split (as the distance query descends),
/// or, at two leaves, every pair of their triangles.
fn children(a: u32, b: u32, s1: &MeshShape, s2: &MeshShape, out: &mut Vec<Parts>) {
    let (n1, n2) = (s1.bvh().nodes(), s2.bvh().nodes());
    let (na, nb) = (&n1[a as usize], &n2[b as usize]);
    let split_first = !na.is_leaf() && (nb.is_leaf() || na.aabb.volume() >= nb.aabb.volume());
    if na.is_leaf() && nb.is_leaf() {
        let (p1, p2) = (s1.bvh().leaf_primitives(na), s2.bvh().leaf_primitives(nb));
        for &t1 in p1 {
            out.extend(p2.iter().map(|&t2| Parts::Triangles(t1, t2)));
        }
    } else if split_first {
        let (l, r) = s1.bvh().children(a);
        out.extend([Parts::Nodes(l, b), Parts::Nodes(r, b)]);
    } else {
        let (l, r) = s2.bvh().children(b);
        out.extend([Parts::Nodes(a, l), Parts::Nodes(a, r)]);
    }
}

/// The centre (centroid) and radius (farthest vertex) of a triangle (m).
#[inline]
fn ball_of_triangle(t: &Tri) -> (Vector, Real) {
    let c = centroid(t);
    let r = t.iter().map(|p| (p - c).norm()).fold(0.0, Real::max);
    (c.coords, r)
}

/// A leaf for `parts` evaluated at `m`'s poses: its gap (0 when the parts meet) and
/// direction, in mesh 1's frame first (where the trees are compared), then in the world.
fn evaluate(parts: Parts, s1: &MeshShape, s2: &MeshShape, m: &PairMotion) -> Node {
    let pose12 = m.pose[0].inv_mul(&m.pose[1]);
    let map = RigidMap::new(&pose12);
    match parts {
        Parts::Nodes(a, b) => {
            let (o1, o2) = (s1.node_obb(a), s2.node_obb(b));
            let (gap, n) = nodes_apart(a, b, s1, s2, &map, m);
            let u = [o1.center.coords, o2.center.coords];
            leaf(parts, gap, n, u, [o1.half.norm(), o2.half.norm()], m)
        }
        Parts::Triangles(t1, t2) => {
            let tri1 = s1.triangle(t1);
            let tri2 = s2.triangle(t2);
            let tri2_in_1 = [
                map.point(&tri2[0]),
                map.point(&tri2[1]),
                map.point(&tri2[2]),
            ];
            let (c1, r1) = ball_of_triangle(&tri1);
            let (c2, r2) = ball_of_triangle(&tri2);
            // The triangles' boxes first (cheap); their closest points when the boxes'
            // gap does not certify the step.
            let boxed = box_gap(
                &Aabb::from_points(tri1.iter().copied()),
                &Aabb::from_points(tri2_in_1.iter().copied()),
            );
            let e = finish(parts, boxed, [c1, c2], [r1, r2], m);
            if m.lowest(&e).1 > CLEARANCE_MARGIN {
                return e;
            }
            closest_leaf(t1, t2, s1, s2, m)
        }
    }
}

/// The leaf of two triangles from their closest points at `m`'s poses (gap 0 when they
/// touch or cross).
fn closest_leaf(t1: u32, t2: u32, s1: &MeshShape, s2: &MeshShape, m: &PairMotion) -> Node {
    let map = RigidMap::new(&m.pose[0].inv_mul(&m.pose[1]));
    let tri1 = s1.triangle(t1);
    let tri2 = s2.triangle(t2);
    let tri2_in_1 = [
        map.point(&tri2[0]),
        map.point(&tri2[1]),
        map.point(&tri2[2]),
    ];
    let g = match triangle_triangle_closest(&tri1, &tri2_in_1) {
        Some((p, q)) => q - p,
        None => Vector::zeros(),
    };
    let (c1, r1) = ball_of_triangle(&tri1);
    let (c2, r2) = ball_of_triangle(&tri2);
    finish(Parts::Triangles(t1, t2), g, [c1, c2], [r1, r2], m)
}

/// A part's bounding volumes in the world: an axis-aligned box of its body frame and an
/// oriented box (both hold it; a direction's support is the lesser of theirs).
struct Volumes {
    /// Axis-aligned box: world centre and half extents along the body axes.
    aabb_center: Vector,
    aabb_half: Vector,
    /// Oriented box: world centre, world axes (columns), half extents.
    obb_center: Vector,
    obb_axes: Matrix,
    obb_half: Vector,
    /// The body's rotation (body -> world).
    rot: Matrix,
}

impl Volumes {
    fn new(aabb: &Aabb, obb: &Obb, pose: &Isometry, rot: &Matrix) -> Volumes {
        let x = pose.translation.vector;
        Volumes {
            aabb_center: x + rot * aabb.center().coords,
            aabb_half: aabb.half_extents(),
            obb_center: x + rot * obb.center.coords,
            obb_axes: rot * obb.axes,
            obb_half: obb.half,
            rot: *rot,
        }
    }

    /// Upper bound of n.p over the part (n a world direction).
    #[inline]
    fn max_along(&self, n: &Vector) -> Real {
        let by_aabb = n.dot(&self.aabb_center) + self.rot.tr_mul(n).abs().dot(&self.aabb_half);
        let by_obb = n.dot(&self.obb_center) + self.obb_axes.tr_mul(n).abs().dot(&self.obb_half);
        by_aabb.min(by_obb)
    }
}

/// How far apart two BVH nodes (of mesh 1, of mesh 2) are at `m`'s poses, and along which
/// world direction: the best of the separating-axis candidates, the face normals of the
/// nodes' axis-aligned and oriented boxes and the gap vector of node 2's box re-boxed in
/// mesh 1's frame. Along a unit n every pair of points is at least min n.b - max n.a apart.
/// The oriented boxes keep the gap of two near-parallel surface patches (a car's front
/// against another's side) near their true distance whatever their slant.
fn nodes_apart(
    a: u32,
    b: u32,
    s1: &MeshShape,
    s2: &MeshShape,
    map: &RigidMap,
    m: &PairMotion,
) -> (Real, Vector) {
    let (box1, box2) = (
        &s1.bvh().nodes()[a as usize].aabb,
        &s2.bvh().nodes()[b as usize].aabb,
    );
    let v1 = Volumes::new(box1, s1.node_obb(a), &m.pose[0], &m.rot[0]);
    let v2 = Volumes::new(box2, s2.node_obb(b), &m.pose[1], &m.rot[1]);
    let d = v2.obb_center - v1.obb_center;
    let mut best = (0.0, Vector::zeros());
    let mut consider = |n: Vector| {
        let n = if n.dot(&d) < 0.0 { -n } else { n };
        let gap = -v2.max_along(&-n) - v1.max_along(&n);
        if gap > best.0 {
            best = (gap, n);
        }
    };
    for k in 0..3 {
        consider(v1.obb_axes.column(k).into_owned());
        consider(v2.obb_axes.column(k).into_owned());
        consider(m.rot[0].column(k).into_owned());
        consider(m.rot[1].column(k).into_owned());
    }
    let g = box_gap(box1, &map.aabb(box2));
    let norm = g.norm();
    if norm > 0.0 {
        consider(m.rot[0] * (g / norm));
    }
    best
}

/// A leaf from its gap vector in mesh 1's frame, its parts' centres and radii, at `m`'s
/// poses.
fn finish(parts: Parts, gap_in_1: Vector, u: [Vector; 2], r: [Real; 2], m: &PairMotion) -> Node {
    let gap = gap_in_1.norm();
    let n = if gap > 0.0 {
        m.rot[0] * (gap_in_1 / gap)
    } else {
        Vector::zeros() // no direction: the bound is 0 - ..., never a certificate
    };
    leaf(parts, gap, n, u, r, m)
}

/// A leaf separated by `gap` (m) along the world direction `n` at `m`'s poses.
fn leaf(parts: Parts, gap: Real, n: Vector, u: [Vector; 2], r: [Real; 2], m: &PairMotion) -> Node {
    let x1 = m.pose[0].translation.vector;
    let x2 = m.pose[1].translation.vector;
    let f = n.dot(&(x2 + m.rot[1] * u[1] - x1 - m.rot[0] * u[0]));
    Node {
        parts,
        u,
        r,
        q: [m.pose[0].rotation, m.pose[1].rotation],
        kind: Kind::Leaf { gap, n, f },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Point;
    use std::sync::Arc;

    fn cube(h: Real) -> Arc<MeshShape> {
        Arc::new(MeshShape::cuboid(Vector::zeros(), Vector::repeat(h)))
    }

    fn motion(x2: Vector, v2: Vector, w2: Vector, span: Real) -> PairMotion {
        let pose = [
            Isometry::identity(),
            Isometry::translation(x2.x, x2.y, x2.z),
        ];
        let bound = MotionBound {
            angular_speed: w2.norm(),
            ..MotionBound::default()
        };
        PairMotion {
            rot: [Matrix::identity(), Matrix::identity()],
            pose,
            v: [Vector::zeros(), v2],
            w: [Vector::zeros(), w2],
            bound: [MotionBound::default(), bound],
            span,
            speed: v2.norm() + w2.norm() * 3f64.sqrt(),
        }
    }

    #[test]
    fn parting_boxes_a_hair_apart_are_clear_and_closing_ones_critical() {
        let (a, b) = (cube(1.0), cube(1.0));
        // 1 um apart along x, parting at 1 m/s: clear for any step.
        let m = motion(
            Vector::new(2.0 + 1e-6, 0.0, 0.0),
            Vector::x(),
            Vector::zeros(),
            1e-3,
        );
        let mut front = Front::new(&a, &b, &m);
        assert!(matches!(front.certify(&a, &b, &m), Certificate::Clear(_)));
        // The same gap closing at 1 m/s: some triangle pair may meet within the step.
        let m = motion(
            Vector::new(2.0 + 1e-6, 0.0, 0.0),
            -Vector::x(),
            Vector::zeros(),
            1e-3,
        );
        let mut front = Front::new(&a, &b, &m);
        assert!(matches!(
            front.certify(&a, &b, &m),
            Certificate::Critical(..)
        ));
        // Closing, but 2 mm apart: 1 mm of travel in the step cannot close it.
        let m = motion(
            Vector::new(2.002, 0.0, 0.0),
            -Vector::x(),
            Vector::zeros(),
            1e-3,
        );
        let mut front = Front::new(&a, &b, &m);
        assert!(matches!(front.certify(&a, &b, &m), Certificate::Clear(_)));
    }

    #[test]
    fn a_certificate_follows_the_net_motion_back_and_forth() {
        let (a, b) = (cube(1.0), cube(1.0));
        // 5 mm apart; body 2 swings 4 mm toward body 1 and back many times: every step is
        // clear, and the front is looked at only while the swing nears the gap.
        let mut front = None;
        for k in 0..400 {
            let phase = k as Real * 0.05;
            let x = 2.005 - 0.004 * phase.sin().abs();
            let v = -0.004 * phase.cos() * phase.sin().signum() / 1e-3 * 0.05;
            let m = motion(
                Vector::new(x, 0.0, 0.0),
                Vector::new(v, 0.0, 0.0),
                Vector::zeros(),
                1e-3,
            );
            let f = front.get_or_insert_with(|| Front::new(&a, &b, &m));
            assert!(
                matches!(f.certify(&a, &b, &m), Certificate::Clear(_)),
                "step {k}"
            );
        }
        assert!(front.unwrap().len() < 200);
    }

    /// An ellipsoid of `n` x 2n latitude-longitude quads (m), centred at the origin.
    fn ellipsoid(n: usize, r: Vector) -> MeshShape {
        let mut v = Vec::new();
        for i in 0..=n {
            let th = std::f64::consts::PI * i as Real / n as Real;
            for j in 0..2 * n {
                let ph = std::f64::consts::PI * j as Real / n as Real;
                v.push(Point::new(
                    r.x * th.sin() * ph.cos(),
                    r.y * th.sin() * ph.sin(),
                    r.z * th.cos(),
                ));
            }
        }
        let id = |i: usize, j: usize| (i * 2 * n + j % (2 * n)) as u32;
        let mut t = Vec::new();
        for i in 0..n {
            for j in 0..2 * n {
                t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        MeshShape::new(v, t).unwrap()
    }

    #[test]
    fn node_and_triangle_gaps_never_exceed_the_true_distance() {
        use crate::triangle::triangle_triangle_distance_sq;
        use rand::rngs::SmallRng;
        use rand::{Rng, SeedableRng};
        let a = ellipsoid(12, Vector::new(2.0, 0.9, 0.7));
        let b = ellipsoid(10, Vector::new(1.5, 1.0, 0.8));
        let mut rng = SmallRng::seed_from_u64(3);
        let mut checked = 0;
        for _ in 0..40 {
            let q = |rng: &mut SmallRng| {
                Rotation::from_euler_angles(
                    rng.random_range(-0.3..0.3),
                    rng.random_range(-0.3..0.3),
                    rng.random_range(-3.1..3.1),
                )
            };
            let pose = [
                Isometry::from_parts(Vector::zeros().into(), q(&mut rng)),
                Isometry::from_parts(
                    Vector::new(rng.random_range(3.0..3.8), rng.random_range(-1.0..1.0), 0.0)
                        .into(),
                    q(&mut rng),
                ),
            ];
            let m = PairMotion {
                rot: [
                    pose[0].rotation.to_rotation_matrix().into_inner(),
                    pose[1].rotation.to_rotation_matrix().into_inner(),
                ],
                pose,
                v: [Vector::zeros(); 2],
                w: [Vector::zeros(); 2],
                bound: [MotionBound::default(); 2],
                span: 1e-3,
                speed: 0.0,
            };
            let map = RigidMap::new(&m.pose[0].inv_mul(&m.pose[1]));
            let (na, nb) = (a.bvh().nodes().len() as u32, b.bvh().nodes().len() as u32);
            for _ in 0..30 {
                let (i, j) = (rng.random_range(0..na), rng.random_range(0..nb));
                let (gap, n) = nodes_apart(i, j, &a, &b, &map, &m);
                let mut exact = Real::INFINITY;
                for &t1 in a.bvh().subtree_primitives(i) {
                    for &t2 in b.bvh().subtree_primitives(j) {
                        let tri1 = a.triangle(t1).map(|p| m.pose[0] * p);
                        let tri2 = b.triangle(t2).map(|p| m.pose[1] * p);
                        exact = exact.min(triangle_triangle_distance_sq(&tri1, &tri2).sqrt());
                        // Along n, every pair of their vertices is at least the gap apart.
                        if gap > 0.0 {
                            for pa in &tri1 {
                                for pb in &tri2 {
                                    assert!(n.dot(&(pb - pa)) >= gap - 1e-12);
                                }
                            }
                        }
                    }
                }
                assert!(gap <= exact + 1e-12, "node gap {gap} > distance {exact}");
                checked += 1;
            }
        }
        assert_eq!(checked, 1200);
    }

    #[test]
    fn the_chord_bound_holds_for_small_and_large_turns() {
        for angle in [1e-12, 1e-8, 1e-4, 0.3, 2.0, 3.1] {
            let q0 = Rotation::from_euler_angles(0.1, -0.2, 0.3);
            let q = Rotation::from_axis_angle(&Vector::y_axis(), angle) * q0;
            let exact = 2.0 * (angle / 2.0).sin();
            let b = chord_bound(&q, &q0);
            assert!(b >= exact * (1.0 - 1e-12), "{angle}: {b} < {exact}");
            assert!(b <= exact * 1.5 + 1e-15, "{angle}: {b} loose");
            // The chord bounds how far a point at unit distance moves.
            let p = Point::new(0.0, 0.0, 1.0);
            let moved = (q * (q0.inverse() * p) - p).norm();
            assert!(moved <= b * (1.0 + 1e-12) + 1e-15);
        }
    }
}
