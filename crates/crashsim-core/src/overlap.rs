//! Queries between two posed meshes: do they overlap, how far apart are they, and the
//! overlap region S with its volume normal (docs/model.md, "The overlap region").
//!
//! A pose maps body-frame points into the world. The two-tree traversals work in mesh 1's
//! body frame: mesh 2's node boxes are carried over by the relative pose and re-boxed
//! (a conservative box), so pruning never drops a real contact.

use crate::bvh::{BvhNode, LEAF_SIZE};
use crate::math::{Aabb, Isometry, Point, Real, RigidMap, Vector};
use crate::shape::MeshShape;
use crate::triangle::{
    centroid, inward_nudge, scaled_normal, segment_triangle_crossing, triangle_triangle_contact,
    triangle_triangle_distance_sq, Tri, TriangleContact, PLANE_TOLERANCE,
};
use parry3d_f64::bounding_volume::BoundingVolume;

/// Reusable traversal storage, so per-step queries do not allocate once warmed up.
#[derive(Default, Debug)]
pub struct QueryWorkspace {
    pairs: Vec<(u32, u32)>,
    bounded_pairs: Vec<(Real, u32, u32)>,
}

#[inline]
fn map_tri(t: &Tri, m: &RigidMap) -> Tri {
    [m.point(&t[0]), m.point(&t[1]), m.point(&t[2])]
}

/// The triangles of leaf `node` of `mesh` (at most [`crate::bvh::LEAF_SIZE`]) mapped by `m`,
/// with their indices, in the leaf's order.
#[inline]
fn mapped_leaf(mesh: &MeshShape, node: &BvhNode, m: &RigidMap) -> [Option<(u32, Tri)>; LEAF_SIZE] {
    let mut out = [None; LEAF_SIZE];
    for (slot, &t) in out.iter_mut().zip(mesh.bvh().leaf_primitives(node)) {
        *slot = Some((t, map_tri(&mesh.triangle(t), m)));
    }
    out
}

/// Simultaneous descent of two trees (2 in 1's frame by `pose12`): calls `leaf` on every leaf
/// pair whose boxes meet; `leaf` returns true to stop early. Returns true if stopped early.
fn traverse_pairs(
    s1: &MeshShape,
    s2: &MeshShape,
    pose12: &Isometry,
    stack: &mut Vec<(u32, u32)>,
    mut leaf: impl FnMut(&BvhNode, &BvhNode) -> bool,
) -> bool {
    let (n1, n2) = (s1.bvh().nodes(), s2.bvh().nodes());
    let map = RigidMap::new(pose12);
    stack.clear();
    stack.push((0, 0));
    while let Some((i, j)) = stack.pop() {
        let (a, b) = (&n1[i as usize], &n2[j as usize]);
        if !a.aabb.intersects(&map.aabb(&b.aabb)) {
            continue;
        }
        match (a.is_leaf(), b.is_leaf()) {
            (true, true) => {
                if leaf(a, b) {
                    return true;
                }
            }
            (false, true) => {
                let (l, r) = s1.bvh().children(i);
                stack.push((r, j));
                stack.push((l, j));
            }
            (true, false) => {
                let (l, r) = s2.bvh().children(j);
                stack.push((i, r));
                stack.push((i, l));
            }
            (false, false) => {
                // Descend the larger box first keeps the pairs balanced.
                if a.aabb.volume() >= b.aabb.volume() {
                    let (l, r) = s1.bvh().children(i);
                    stack.push((r, j));
                    stack.push((l, j));
                } else {
                    let (l, r) = s2.bvh().children(j);
                    stack.push((i, r));
                    stack.push((i, l));
                }
            }
        }
    }
    false
}

/// True when the two posed surfaces cross: a triangle of one, nudged a hair into its own
/// solid and interior, is crossed by a triangle of the other (see
/// [`crate::triangle::triangle_triangle_contact`]). Surfaces that merely touch (faces
/// resting on each other, coplanar faces, an edge on a face from outside) do not intersect;
/// [`surface_distance`] is 0 for them. This is the test [`overlap_region`] takes its crossing
/// segments by, so the region is not empty whenever it holds.
pub fn surfaces_intersect(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    ws: &mut QueryWorkspace,
) -> bool {
    first_crossing(s1, pose1, s2, pose2, ws).is_some()
}

/// The first pair of triangles (of s1, of s2) whose surfaces cross that the traversal of
/// [`surfaces_intersect`] meets, or None.
fn first_crossing(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    ws: &mut QueryWorkspace,
) -> Option<(u32, u32)> {
    let pose12 = pose1.inv_mul(pose2);
    let map = RigidMap::new(&pose12);
    let mut found = None;
    traverse_pairs(s1, s2, &pose12, &mut ws.pairs, |a, b| {
        // b's triangles in 1's frame, mapped once per leaf pair (not once per triangle of a)
        let leaf2 = mapped_leaf(s2, b, &map);
        for &t1 in s1.bvh().leaf_primitives(a) {
            let tri1 = s1.triangle(t1);
            for &(t2, tri2) in leaf2.iter().flatten() {
                if triangle_triangle_contact(&tri1, &tri2).is_some_and(|c| c.is_crossing()) {
                    found = Some((t1, t2));
                    return true;
                }
            }
        }
        false
    });
    found
}

/// [`shapes_overlap`] that first tries the pair of triangles `hint` (of s1, of s2): when they
/// still cross, the surfaces intersect and no traversal is needed. `hint` is left at a
/// crossing pair found (None when the surfaces do not cross). The answer is
/// [`shapes_overlap`]'s: a crossing pair is one whichever way it is found. An engaged pair
/// (meshes pushed into each other) keeps crossing at the same triangles from step to step:
/// two boxes' seed impact, 1 s at 1 ms, tested about 100 triangle pairs a step without it.
pub fn shapes_overlap_hinted(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    ws: &mut QueryWorkspace,
    hint: &mut Option<(u32, u32)>,
) -> bool {
    if !s1
        .aabb()
        .transform_by(pose1)
        .intersects(&s2.aabb().transform_by(pose2))
    {
        return false;
    }
    if let Some((t1, t2)) = *hint {
        let map = RigidMap::new(&pose1.inv_mul(pose2));
        let tri2 = map_tri(&s2.triangle(t2), &map);
        if triangle_triangle_contact(&s1.triangle(t1), &tri2).is_some_and(|c| c.is_crossing()) {
            return true;
        }
    }
    *hint = first_crossing(s1, pose1, s2, pose2, ws);
    if hint.is_some() {
        return true;
    }
    let pose12 = pose1.inv_mul(pose2);
    let nudge = nudge_length(s1, s2, &pose12);
    shell_inside(s1, s2, &pose12, nudge) || shell_inside(s2, s1, &pose12.inverse(), nudge)
}

/// True when a shell of `inner` lies inside `outer` (its representative vertex, nudged by
/// `nudge` m into a triangle of it and its solid, has a winding number above one half);
/// `pose_io` maps inner's frame into outer's.
fn shell_inside(outer: &MeshShape, inner: &MeshShape, pose_io: &Isometry, nudge: Real) -> bool {
    let bounds = outer.aabb();
    inner.shells().iter().any(|s| {
        let p = nudged_vertex(inner, s.vertex, nudge);
        let p = pose_io * p;
        bounds.contains_local_point(&p) && outer.contains_point(&p)
    })
}

/// Vertex `vi` of `mesh` (own frame) nudged `nudge` m into a triangle at it and into the
/// solid ([`inward_nudge`]); the vertex itself when that triangle has no area.
fn nudged_vertex(mesh: &MeshShape, vi: u32, nudge: Real) -> Point {
    let v = mesh.vertices()[vi as usize];
    let ti = mesh.vertex_triangle(vi);
    if ti == u32::MAX {
        return v;
    }
    inward_nudge(&mesh.triangle(ti), &v).map_or(v, |w| v + w * nudge)
}

/// How far (m) points lying on the other surface are nudged to settle their side: 2^8 times
/// the band within which the crossing tests count a vertex as on a plane
/// ([`PLANE_TOLERANCE`] of the largest coordinate either mesh has in either body frame), so
/// a nudged point is clear of the band, yet close enough to be on the side the crossing
/// tests put it (a few 1e-10 m for vehicles; the winding number is exact that near a face).
fn nudge_length(s1: &MeshShape, s2: &MeshShape, pose12: &Isometry) -> Real {
    let magnitude = |b: &Aabb| b.mins.coords.amax().max(b.maxs.coords.amax());
    let to1 = RigidMap::new(pose12);
    let to2 = RigidMap::new(&pose12.inverse());
    let scale = magnitude(s1.aabb())
        .max(magnitude(&to1.aabb(s2.aabb())))
        .max(magnitude(s2.aabb()))
        .max(magnitude(&to2.aabb(s1.aabb())));
    NUDGE_BANDS * PLANE_TOLERANCE * scale
}

/// The nudge length in plane bands (see [`nudge_length`]).
const NUDGE_BANDS: Real = 256.0;

/// True when the two posed meshes overlap: their surfaces cross ([`surfaces_intersect`]), or
/// a shell of one lies inside the other.
pub fn shapes_overlap(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    ws: &mut QueryWorkspace,
) -> bool {
    if !s1
        .aabb()
        .transform_by(pose1)
        .intersects(&s2.aabb().transform_by(pose2))
    {
        return false;
    }
    if surfaces_intersect(s1, pose1, s2, pose2, ws) {
        return true;
    }
    let pose12 = pose1.inv_mul(pose2);
    let nudge = nudge_length(s1, s2, &pose12);
    shell_inside(s1, s2, &pose12, nudge) || shell_inside(s2, s1, &pose12.inverse(), nudge)
}

/// Distance between two boxes (0 when they meet).
#[inline]
fn aabb_distance(a: &Aabb, b: &Aabb) -> Real {
    let gap = (a.mins - b.maxs)
        .sup(&(b.mins - a.maxs))
        .sup(&Vector::zeros());
    gap.norm()
}

/// The smallest distance between the two posed surfaces (m), or `cap` if that is smaller.
/// 0 when they touch or cross. Branch and bound over the two trees, nearest pairs first.
pub fn surface_distance(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    cap: Real,
    ws: &mut QueryWorkspace,
) -> Real {
    surface_distance_from(s1, pose1, s2, pose2, cap, None, ws).0
}

/// [`surface_distance`] warm-started from a pair of triangles (of mesh 1, mesh 2) likely to
/// be near the closest, e.g. the closest at a previous query: their distance bounds the
/// search from the start, so far fewer node pairs are opened when the surfaces are close.
/// The distance is the same; also returns the closest pair found (None when nothing is
/// nearer than `cap`).
pub fn surface_distance_from(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    cap: Real,
    hint: Option<(u32, u32)>,
    ws: &mut QueryWorkspace,
) -> (Real, Option<(u32, u32)>) {
    let pose12 = pose1.inv_mul(pose2);
    let map = RigidMap::new(&pose12);
    let (n1, n2) = (s1.bvh().nodes(), s2.bvh().nodes());
    let stack = &mut ws.bounded_pairs;
    stack.clear();
    let mut best = cap;
    let mut closest = None;
    if let Some((t1, t2)) = hint {
        if (t1 as usize) < s1.triangles().len() && (t2 as usize) < s2.triangles().len() {
            let d =
                triangle_triangle_distance_sq(&s1.triangle(t1), &map_tri(&s2.triangle(t2), &map))
                    .sqrt();
            if d < best {
                best = d;
                closest = Some((t1, t2));
                if best == 0.0 {
                    return (0.0, closest);
                }
            }
        }
    }
    let bound = |i: u32, j: u32| -> Real {
        aabb_distance(&n1[i as usize].aabb, &map.aabb(&n2[j as usize].aabb))
    };
    stack.push((bound(0, 0), 0, 0));
    while let Some((lb, i, j)) = stack.pop() {
        if lb >= best {
            continue;
        }
        let (a, b) = (&n1[i as usize], &n2[j as usize]);
        if a.is_leaf() && b.is_leaf() {
            // b's triangles in 1's frame and their boxes, once per leaf pair
            let leaf2 = mapped_leaf(s2, b, &map)
                .map(|e| e.map(|(t2, tri2)| (t2, tri2, Aabb::from_points(tri2.iter().copied()))));
            for &t1 in s1.bvh().leaf_primitives(a) {
                let tri1 = s1.triangle(t1);
                let box1 = Aabb::from_points(tri1.iter().copied());
                for (t2, tri2, box2) in leaf2.iter().flatten() {
                    let (t2, tri2) = (*t2, *tri2);
                    // The boxes' distance bounds the triangles' from below: a cheap reject.
                    if aabb_distance(&box1, box2) >= best {
                        continue;
                    }
                    let d = triangle_triangle_distance_sq(&tri1, &tri2).sqrt();
                    if d < best {
                        best = d;
                        closest = Some((t1, t2));
                        if best == 0.0 {
                            return (0.0, closest);
                        }
                    }
                }
            }
            continue;
        }
        let split_first = !a.is_leaf() && (b.is_leaf() || a.aabb.volume() >= b.aabb.volume());
        let ((i1, j1), (i2, j2)) = if split_first {
            let (l, r) = s1.bvh().children(i);
            ((l, j), (r, j))
        } else {
            let (l, r) = s2.bvh().children(j);
            ((i, l), (i, r))
        };
        let (d1, d2) = (bound(i1, j1), bound(i2, j2));
        // Push the farther first so the nearer is explored first.
        if d1 <= d2 {
            if d2 < best {
                stack.push((d2, i2, j2));
            }
            if d1 < best {
                stack.push((d1, i1, j1));
            }
        } else {
            if d1 < best {
                stack.push((d1, i1, j1));
            }
            if d2 < best {
                stack.push((d2, i2, j2));
            }
        }
    }
    (best, closest)
}

/// The overlap region of two posed meshes (world frame).
#[derive(Clone, Debug, Default)]
pub struct OverlapRegion {
    /// The set S: end points of all triangle-triangle crossing segments and the vertices of
    /// each mesh inside the other (m, world). Where the surfaces merely touch (see
    /// [`surfaces_intersect`]) nothing is added: a point on both surfaces must not widen the
    /// region beyond the overlap.
    pub points: Vec<Point>,
    /// Vector area (m^2, world) of mesh 1's surface inside mesh 2, outward normals.
    pub area_normal_1_in_2: Vector,
    /// Vector area (m^2, world) of mesh 2's surface inside mesh 1, outward normals.
    pub area_normal_2_in_1: Vector,
    /// Number of crossing segments (touches not counted).
    pub segment_count: usize,
    /// Number of vertices of either mesh inside the other.
    pub inside_vertex_count: usize,
    /// Of those, mesh 1's (inside mesh 2). `points` holds the crossings' end points (2 per
    /// segment), then mesh 1's vertices inside mesh 2, then mesh 2's inside mesh 1.
    pub inside_1_count: usize,
}

impl OverlapRegion {
    /// True when the meshes do not overlap at all.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The centre of the region's box (m, world); None when it is empty.
    pub fn center(&self) -> Option<Point> {
        let first = *self.points.first()?;
        let (lo, hi) = self
            .points
            .iter()
            .fold((first, first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
        Some(nalgebra::center(&lo, &hi))
    }

    /// The volume normal from mesh 1 into mesh 2, unit; None when it vanishes.
    pub fn volume_normal(&self) -> Option<Vector> {
        let n = self.area_normal_1_in_2 - self.area_normal_2_in_1;
        let len = n.norm();
        (len > 0.0 && len.is_finite()).then(|| n / len)
    }
}

/// One triangle's meeting with a triangle of the other mesh: own triangle, other triangle,
/// the segment (own frame) oriented so the other mesh's inside lies to its left (about the own
/// triangle's normal), whether the own triangle, nudged into its solid and interior, is
/// crossed (false for a mere touch, which bounds no inside region of the own triangle), and
/// which own vertices lie on the other triangle's plane.
type Crossing = (u32, u32, Point, Point, bool, [bool; 3]);

/// Vector area (own frame) of the part of triangle `t` inside `other`.
///
/// Points on the other surface are classified as the point `nudge` m into the own triangle
/// and into the own solid ([`inward_nudge`]): so two coplanar faces of the same orientation
/// both count as inside (and cancel in the volume normal), two facing ones neither, and an
/// edge lying on the other's face takes the side of its triangle. The crossing segments'
/// flags follow the same rule ([`triangle_triangle_contact`]), so the boundary pieces agree.
///
/// `edges[k]` says what is known of edge k (vertex k to k + 1): wholly inside or outside, or
/// the status of its two ends (nudged into `t`), from which the pieces follow by flipping at
/// each crossing when the count of crossings agrees (else, and when unknown, a winding
/// number per piece).
fn inside_vector_area(
    t: &Tri,
    crossings: &[(Tri, Point, Point, bool)],
    other: &MeshShape,
    to_other: &Isometry,
    edges: [EdgeStatus; 3],
    nudge: Real,
) -> Vector {
    let n = scaled_normal(t);
    let full = n.norm();
    if full == 0.0 {
        return Vector::zeros();
    }
    let nhat = n / full;
    let c = centroid(t);
    let inside = |p: &Point| -> bool {
        let q = inward_nudge(t, p).map_or(*p, |w| p + w * nudge);
        other.contains_point(&(to_other * q))
    };
    if !crossings.iter().any(|x| x.3) {
        return if inside(&c) { n * 0.5 } else { Vector::zeros() };
    }
    // Green's theorem in the triangle's plane: the region's boundary is the segments along
    // which the other surface cuts the triangle plus the pieces of the triangle's edges that
    // lie inside the other mesh.
    let mut twice_area = 0.0;
    for (_, p, q, cut) in crossings {
        if *cut {
            twice_area += (p - c).cross(&(q - c)).dot(&nhat);
        }
    }
    let mut params: Vec<Real> = Vec::with_capacity(2 + crossings.len());
    for k in 0..3 {
        let (e0, e1) = (t[k], t[(k + 1) % 3]);
        if let EdgeStatus::Whole(is_inside) = edges[k] {
            if is_inside {
                twice_area += (e0 - c).cross(&(e1 - c)).dot(&nhat);
            }
            continue;
        }
        params.clear();
        params.push(0.0);
        params.push(1.0);
        for (u, _, _, _) in crossings {
            if let Some(s) = segment_triangle_crossing(&e0, &e1, u) {
                params.push(s);
            }
        }
        params.sort_by(|a, b| a.total_cmp(b));
        // A crossing through a shared edge of the other mesh is reported by both its
        // triangles: count it once.
        params.dedup_by(|b, a| *b - *a <= 1e-12);
        let crossings_along = params.len() - 2;
        let parity = match edges[k] {
            EdgeStatus::Ends(start, end) if start ^ end == (crossings_along % 2 == 1) => {
                Some(start)
            }
            _ => None,
        };
        for (i, w) in params.windows(2).enumerate() {
            if w[1] <= w[0] {
                continue;
            }
            let p0 = e0 + (e1 - e0) * w[0];
            let p1 = e0 + (e1 - e0) * w[1];
            let piece_inside = match parity {
                Some(start) => start ^ (i % 2 == 1),
                None => inside(&(p0 + (p1 - p0) * 0.5)),
            };
            if piece_inside {
                twice_area += (p0 - c).cross(&(p1 - c)).dot(&nhat);
            }
        }
    }
    nhat * (0.5 * twice_area).clamp(0.0, 0.5 * full)
}

/// Vector area (own frame) of `own`'s surface inside `other`, and the own vertices inside it
/// (own frame). `crossings` are sorted by own triangle.
///
/// When `other` is closed, inside and outside change only across its surface: the own
/// triangles no crossing touches form patches (joined across shared edges) that are wholly
/// inside or outside, decided by one winding number per patch (none for a patch reaching out
/// of the other's box), and a vertex takes the status of a patch it belongs to. Otherwise
/// (an open mesh, whose winding number also changes near its holes) every triangle and vertex
/// is decided alone.
fn surface_inside(
    own: &MeshShape,
    other: &MeshShape,
    own_to_other: &Isometry,
    crossings: &[Crossing],
    other_tri_in_own: impl Fn(u32) -> Tri,
    use_patches: bool,
    nudge: Real,
) -> (Vector, Vec<Point>) {
    let mut inside = Vec::new();
    let other_box_in_own = other.aabb().transform_by(&own_to_other.inverse());
    let n = own.triangles().len();
    let mut crossed = vec![false; n];
    // Own vertices on a plane of an other triangle they meet: on (or within the band of) the
    // other surface, where the side depends on the triangle they are seen from.
    let mut on_other = vec![false; own.vertices().len()];
    for x in crossings {
        crossed[x.0 as usize] = true;
        let tri = own.triangles()[x.0 as usize];
        for k in 0..3 {
            on_other[tri[k] as usize] |= x.5[k];
        }
    }
    let in_box =
        |ti: u32| Aabb::from_points(own.triangle(ti).iter().copied()).intersects(&other_box_in_own);
    let patches = (use_patches && other.is_closed()).then(|| Patches::new(own, &crossed, &in_box));
    let mut cls = Classifier {
        own,
        other,
        own_to_other,
        crossed: &crossed,
        patches: patches.as_ref(),
        patch_status: vec![None; if patches.is_some() { n } else { 0 }],
        vertex_patch: vec![
            None;
            if patches.is_some() {
                own.vertices().len()
            } else {
                0
            }
        ],
        vertex_status: vec![None; own.vertices().len()],
        on_other: &on_other,
        nudge,
    };
    let mut total = Vector::zeros();
    let mut k = 0;
    let mut local: Vec<(Tri, Point, Point, bool)> = Vec::new();
    for ti in 0..n as u32 {
        local.clear();
        while k < crossings.len() && crossings[k].0 == ti {
            let (_, o, p, q, cut, _) = crossings[k];
            local.push((other_tri_in_own(o), p, q, cut));
            k += 1;
        }
        let t = own.triangle(ti);
        if local.is_empty() {
            if !in_box(ti) {
                continue;
            }
            if let Some(is_inside) = cls.patch(ti) {
                if is_inside {
                    total += scaled_normal(&t) * 0.5;
                }
                continue;
            }
        }
        let mut edges = [EdgeStatus::Unknown; 3];
        if patches.is_some() && !local.is_empty() {
            let tri = own.triangles()[ti as usize];
            for (k, &nb) in own.neighbors(ti).iter().enumerate() {
                edges[k] = match (nb != u32::MAX && !crossed[nb as usize])
                    .then(|| cls.patch(nb))
                    .flatten()
                {
                    Some(is_inside) => EdgeStatus::Whole(is_inside),
                    None => EdgeStatus::Ends(
                        cls.vertex_seen_from(tri[k], &t),
                        cls.vertex_seen_from(tri[(k + 1) % 3], &t),
                    ),
                };
            }
        }
        total += inside_vector_area(&t, &local, other, own_to_other, edges, nudge);
    }
    for (vi, v) in own.vertices().iter().enumerate() {
        if other_box_in_own.contains_local_point(v) && cls.vertex(vi as u32) {
            inside.push(*v);
        }
    }
    (total, inside)
}

/// What is known of an edge of a cut triangle before its pieces are classified.
#[derive(Clone, Copy, Debug)]
enum EdgeStatus {
    /// Nothing: classify each piece by a winding number.
    Unknown,
    /// The other surface does not meet the edge (the triangle beyond it is uncut): wholly
    /// inside or outside.
    Whole(bool),
    /// Whether its start and end vertices are inside (the other mesh is closed, so the status
    /// flips at each crossing of its surface along the edge).
    Ends(bool, bool),
}

/// Inside/outside decisions for one mesh's triangles and vertices against a closed other
/// mesh, cached per patch and per vertex (see `surface_inside`).
struct Classifier<'a> {
    own: &'a MeshShape,
    other: &'a MeshShape,
    own_to_other: &'a Isometry,
    crossed: &'a [bool],
    patches: Option<&'a Patches>,
    patch_status: Vec<Option<bool>>,
    /// Per vertex (with patches): the status of an uncut triangle's patch at it, if any.
    vertex_patch: Vec<Option<Option<bool>>>,
    /// Per vertex: its status for the region's point set.
    vertex_status: Vec<Option<bool>>,
    /// Per vertex: whether it lies on a plane of an other triangle it meets.
    on_other: &'a [bool],
    nudge: Real,
}

impl Classifier<'_> {
    /// The status of uncut triangle ti's patch; None without patches, or when it is unknown
    /// and ti has no area to decide it by.
    fn patch(&mut self, ti: u32) -> Option<bool> {
        let p = self.patches?;
        let root = p.root(ti) as usize;
        if self.patch_status[root].is_none() {
            self.patch_status[root] = if p.leaves_box[root] {
                Some(false)
            } else {
                tri_inside(
                    &self.own.triangle(ti),
                    self.other,
                    self.own_to_other,
                    self.nudge,
                )
            };
        }
        self.patch_status[root]
    }

    /// The status of vertex vi from an uncut triangle at it (its own one, or the one across
    /// an edge at it): such a vertex is off the other surface, so it is the same seen from
    /// every triangle. None without patches or such a triangle. Cached.
    fn vertex_patch(&mut self, vi: u32) -> Option<bool> {
        if let Some(known) = self.vertex_patch.get(vi as usize).copied().flatten() {
            return known;
        }
        let ti = self.own.vertex_triangle(vi);
        let from_patch = if ti == u32::MAX || self.patches.is_none() {
            None
        } else if !self.crossed[ti as usize] {
            self.patch(ti)
        } else {
            let tri = self.own.triangles()[ti as usize];
            let k = (0..3).find(|&k| tri[k] == vi).unwrap_or(0);
            let nbs = self.own.neighbors(ti);
            [nbs[k], nbs[(k + 2) % 3]]
                .into_iter()
                .filter(|&nb| nb != u32::MAX && !self.crossed[nb as usize])
                .find_map(|nb| self.patch(nb))
        };
        if let Some(slot) = self.vertex_patch.get_mut(vi as usize) {
            *slot = Some(from_patch);
        }
        from_patch
    }

    /// Whether vertex vi is inside, for the region's point set: from an uncut triangle at
    /// it, else its winding number; for a vertex on the other surface, nudged into a triangle
    /// at it and the solid (it counts as inside when its own solid goes into the other's).
    /// Cached.
    fn vertex(&mut self, vi: u32) -> bool {
        if let Some(known) = self.vertex_status[vi as usize] {
            return known;
        }
        let is_inside = self.vertex_patch(vi).unwrap_or_else(|| {
            let q = if self.on_other[vi as usize] {
                nudged_vertex(self.own, vi, self.nudge)
            } else {
                self.own.vertices()[vi as usize]
            };
            self.other.contains_point(&(self.own_to_other * q))
        });
        self.vertex_status[vi as usize] = Some(is_inside);
        is_inside
    }

    /// Whether vertex vi, as an end of an edge of the cut triangle `t`, is inside: as for
    /// the point set, except that a vertex on the other surface is nudged into `t` (it can be
    /// inside seen from one triangle and outside from another).
    fn vertex_seen_from(&mut self, vi: u32, t: &Tri) -> bool {
        if !self.on_other[vi as usize] {
            return self.vertex(vi);
        }
        self.vertex_patch(vi).unwrap_or_else(|| {
            let v = self.own.vertices()[vi as usize];
            let q = inward_nudge(t, &v).map_or(v, |w| v + w * self.nudge);
            self.other.contains_point(&(self.own_to_other * q))
        })
    }
}

/// The own triangles no crossing touches, joined across shared edges (union-find), and for
/// each patch root whether the patch reaches out of the other mesh's box.
struct Patches {
    parent: Vec<u32>,
    leaves_box: Vec<bool>,
}

impl Patches {
    fn new(own: &MeshShape, crossed: &[bool], in_box: &impl Fn(u32) -> bool) -> Patches {
        let n = crossed.len();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        fn find(parent: &mut [u32], mut x: u32) -> u32 {
            while parent[x as usize] != x {
                parent[x as usize] = parent[parent[x as usize] as usize];
                x = parent[x as usize];
            }
            x
        }
        for &(a, b) in own.edge_pairs() {
            if crossed[a as usize] || crossed[b as usize] {
                continue;
            }
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            if ra != rb {
                let (lo, hi) = (ra.min(rb), ra.max(rb));
                parent[hi as usize] = lo;
            }
        }
        for i in 0..n as u32 {
            let r = find(&mut parent, i);
            parent[i as usize] = r;
        }
        let mut leaves_box = vec![false; n];
        for i in 0..n as u32 {
            if !crossed[i as usize] && !in_box(i) {
                leaves_box[parent[i as usize] as usize] = true;
            }
        }
        Patches { parent, leaves_box }
    }

    #[inline]
    fn root(&self, t: u32) -> u32 {
        self.parent[t as usize]
    }
}

/// Whether an uncrossed triangle lies inside `other`: its centroid nudged `nudge` m into the
/// triangle's own solid (see `inside_vector_area`). None for a triangle without area.
fn tri_inside(t: &Tri, other: &MeshShape, to_other: &Isometry, nudge: Real) -> Option<bool> {
    let c = centroid(t);
    let w = inward_nudge(t, &c)?;
    Some(other.contains_point(&(to_other * (c + w * nudge))))
}

/// The overlap region S of two posed meshes and their inside vector areas.
pub fn overlap_region(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
) -> OverlapRegion {
    overlap_region_with(s1, pose1, s2, pose2, true)
}

/// [`overlap_region`], deciding inside and outside per patch (`use_patches`, for closed
/// meshes) or per triangle and vertex (the reference the patches are tested against).
fn overlap_region_with(
    s1: &MeshShape,
    pose1: &Isometry,
    s2: &MeshShape,
    pose2: &Isometry,
    use_patches: bool,
) -> OverlapRegion {
    let pose12 = pose1.inv_mul(pose2);
    let pose21 = pose12.inverse();
    // The same map as `surfaces_intersect`, so both see bit-identical triangles.
    let (map12, map21) = (RigidMap::new(&pose12), RigidMap::new(&pose21));
    let nudge = nudge_length(s1, s2, &pose12);
    let mut stack = Vec::new();
    // Where the triangles meet, in frame 1: the segment oriented along n1 x n2, and whether
    // triangle 1 and triangle 2 are crossed (not merely touched) by the other.
    let mut segs: Vec<(u32, u32, TriangleContact)> = Vec::new();
    traverse_pairs(s1, s2, &pose12, &mut stack, |a, b| {
        for &t1 in s1.bvh().leaf_primitives(a) {
            let tri1 = s1.triangle(t1);
            for &t2 in s2.bvh().leaf_primitives(b) {
                let tri2 = map_tri(&s2.triangle(t2), &map12);
                if let Some(c) = triangle_triangle_contact(&tri1, &tri2) {
                    segs.push((t1, t2, c));
                }
            }
        }
        false
    });
    let mut region = OverlapRegion::default();
    // Only crossings are in S: where the surfaces merely touch (faces resting on each other)
    // nothing overlaps. Touching triangles still count as met for the patches below.
    for (_, _, c) in &segs {
        if c.is_crossing() {
            region.segment_count += 1;
            region.points.push(pose1 * c.start);
            region.points.push(pose1 * c.end);
        }
    }
    // Mesh 1's side, in frame 1.
    let mut by_1: Vec<Crossing> = segs
        .iter()
        .map(|&(t1, t2, c)| (t1, t2, c.start, c.end, c.a_crossed, c.a_on_plane))
        .collect();
    by_1.sort_by_key(|c| (c.0, c.1));
    let (va1, inside1) = surface_inside(
        s1,
        s2,
        &pose21,
        &by_1,
        |o| map_tri(&s2.triangle(o), &map12),
        use_patches,
        nudge,
    );
    // Mesh 2's side, in frame 2: its triangles' segments run the other way (n2 x n1).
    let mut by_2: Vec<Crossing> = segs
        .iter()
        .map(|&(t1, t2, c)| {
            let (p, q) = (map21.point(&c.end), map21.point(&c.start));
            (t2, t1, p, q, c.b_crossed, c.b_on_plane)
        })
        .collect();
    by_2.sort_by_key(|c| (c.0, c.1));
    let (va2, inside2) = surface_inside(
        s2,
        s1,
        &pose12,
        &by_2,
        |o| map_tri(&s1.triangle(o), &map21),
        use_patches,
        nudge,
    );
    region.inside_vertex_count = inside1.len() + inside2.len();
    region.inside_1_count = inside1.len();
    region.points.extend(inside1.iter().map(|p| pose1 * p));
    region.points.extend(inside2.iter().map(|p| pose2 * p));
    region.area_normal_1_in_2 = pose1.rotation * va1;
    region.area_normal_2_in_1 = pose2.rotation * va2;
    region
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rotation;
    use crate::shape::tests::box_mesh;

    fn at(x: Real, y: Real, z: Real, yaw: Real) -> Isometry {
        Isometry::from_parts(
            nalgebra::Translation3::new(x, y, z),
            Rotation::from_axis_angle(&Vector::z_axis(), yaw),
        )
    }

    #[test]
    fn boxes_overlap_touch_and_separate() {
        let a = box_mesh(Vector::zeros(), Vector::new(1.0, 1.0, 1.0));
        let b = box_mesh(Vector::zeros(), Vector::new(0.5, 0.5, 0.5));
        let mut ws = QueryWorkspace::default();
        let id = at(0.0, 0.0, 0.0, 0.0);
        assert!(shapes_overlap(
            &a,
            &id,
            &b,
            &at(1.2, 0.1, 0.0, 0.3),
            &mut ws
        ));
        assert!(!shapes_overlap(
            &a,
            &id,
            &b,
            &at(3.0, 0.0, 0.0, 0.0),
            &mut ws
        ));
        // b wholly inside a: no surface crossing, still an overlap, both ways round.
        assert!(!surfaces_intersect(
            &a,
            &id,
            &b,
            &at(0.1, 0.0, 0.0, 0.2),
            &mut ws
        ));
        assert!(shapes_overlap(
            &a,
            &id,
            &b,
            &at(0.1, 0.0, 0.0, 0.2),
            &mut ws
        ));
        assert!(shapes_overlap(
            &b,
            &at(0.1, 0.0, 0.0, 0.2),
            &a,
            &id,
            &mut ws
        ));
        let d = surface_distance(&a, &id, &b, &at(3.0, 0.0, 0.0, 0.0), 1e9, &mut ws);
        assert!((d - 1.5).abs() < 1e-12, "{d}");
    }

    #[test]
    fn box_into_box_side_gives_the_side_normal_and_the_overlap_box() {
        // Body 1 (4.5 x 1.8 x 1.2, 0.1 m above ground) driven along +x 0.4 m into body 2's
        // side (a 4.6 long box turned 90 deg, 1.8 wide, 1.45 high, on the ground).
        let car1 = box_mesh(Vector::zeros(), Vector::new(2.25, 0.9, 0.6));
        let car2 = box_mesh(Vector::zeros(), Vector::new(2.3, 0.9, 0.725));
        let pose1 = at(0.0, 0.3, 0.7, 0.0);
        let pose2 = at(2.25 + 0.9 - 0.4, 0.0, 0.725, std::f64::consts::FRAC_PI_2);
        let r = overlap_region(&car1, &pose1, &car2, &pose2);
        let n = r.volume_normal().unwrap();
        assert!((n - Vector::x()).norm() < 1e-12, "{n}");
        let (mut lo, mut hi) = (r.points[0], r.points[0]);
        for p in &r.points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let c = nalgebra::center(&lo, &hi);
        assert!((c.x - (2.25 - 0.2)).abs() < 1e-12, "{c}");
        assert!(
            (c.y - 0.3).abs() < 1e-12 && (c.z - 0.7).abs() < 1e-12,
            "{c}"
        );
        // Vector areas: 1's front face (1.8 x 1.2) and 2's struck side under it.
        assert!((r.area_normal_1_in_2.x - 1.8 * 1.2).abs() < 1e-12);
        assert!((r.area_normal_2_in_1.x + 1.8 * 1.2).abs() < 1e-12);
    }

    #[test]
    fn coplanar_bottoms_and_tops_do_not_tilt_the_normal() {
        // Regression: two boxes standing on the same ground (coplanar bottoms, and in the
        // second case coplanar tops too), one driven 0.3 m into the other's rear. Points on
        // the shared planes used to be classified at random, tilting the normal by 1.3 deg.
        let car1 = box_mesh(Vector::zeros(), Vector::new(2.25, 0.9, 0.7));
        for h2 in [0.6, 0.7] {
            let car2 = box_mesh(Vector::zeros(), Vector::new(2.1, 0.85, h2));
            let pose1 = at(-4.05, 0.0, 0.7, 0.0);
            let pose2 = at(0.0, 0.0, h2, 0.0);
            let r = overlap_region(&car1, &pose1, &car2, &pose2);
            let n = r.volume_normal().unwrap();
            let horizontal = Vector::new(n.x, n.y, 0.0).normalize();
            assert!((horizontal - Vector::x()).norm() < 1e-12, "{n}");
            // Front face of 1 inside 2 and rear face of 2 inside 1: 1.7 m x (2 h2) each.
            assert!((r.area_normal_1_in_2.x - 1.7 * 2.0 * h2).abs() < 1e-12);
            assert!((r.area_normal_2_in_1.x + 1.7 * 2.0 * h2).abs() < 1e-12);
            let (mut lo, mut hi) = (r.points[0], r.points[0]);
            for p in &r.points {
                lo = lo.inf(p);
                hi = hi.sup(p);
            }
            assert!((lo.y + 0.85).abs() < 1e-12 && (hi.y - 0.85).abs() < 1e-12);
            assert!((lo.x + 2.1).abs() < 1e-12 && (hi.x + 1.8).abs() < 1e-12);
        }
    }

    #[test]
    fn patch_classification_equals_the_per_triangle_one() {
        // Closed meshes (a subdivided box and a tilted, subdivided box) at random poses: the
        // region decided per patch must equal the one decided per triangle and vertex.
        use rand::rngs::SmallRng;
        use rand::{Rng, SeedableRng};
        let refine = |m: &MeshShape, times: usize| -> MeshShape {
            let (mut v, mut t) = (m.vertices().to_vec(), m.triangles().to_vec());
            for _ in 0..times {
                let mut mid = std::collections::HashMap::new();
                let mut nt = Vec::new();
                let mut midpoint = |a: u32, b: u32, v: &mut Vec<Point>| -> u32 {
                    *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                        v.push(nalgebra::center(&v[a as usize], &v[b as usize]));
                        (v.len() - 1) as u32
                    })
                };
                for tri in &t {
                    let [a, b, c] = *tri;
                    let (ab, bc, ca) = (
                        midpoint(a, b, &mut v),
                        midpoint(b, c, &mut v),
                        midpoint(c, a, &mut v),
                    );
                    nt.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
                }
                t = nt;
            }
            MeshShape::new(v, t).unwrap()
        };
        let car = refine(&box_mesh(Vector::zeros(), Vector::new(2.25, 0.9, 0.7)), 3);
        let other = refine(&box_mesh(Vector::zeros(), Vector::new(2.0, 0.85, 0.6)), 2);
        assert!(car.is_closed() && other.is_closed());
        let mut rng = SmallRng::seed_from_u64(3);
        let mut overlapping = 0;
        for _ in 0..60 {
            let pose2 = Isometry::from_parts(
                nalgebra::Translation3::new(
                    rng.random_range(-4.0..4.0),
                    rng.random_range(-1.5..1.5),
                    rng.random_range(-0.5..0.5),
                ),
                Rotation::from_euler_angles(
                    rng.random_range(-0.3..0.3),
                    rng.random_range(-0.3..0.3),
                    rng.random_range(-3.1..3.1),
                ),
            );
            let id = Isometry::identity();
            let a = overlap_region_with(&car, &id, &other, &pose2, true);
            let b = overlap_region_with(&car, &id, &other, &pose2, false);
            assert_eq!(a.points.len(), b.points.len());
            for (p, q) in a.points.iter().zip(&b.points) {
                assert_eq!(p, q);
            }
            assert!((a.area_normal_1_in_2 - b.area_normal_1_in_2).norm() < 1e-12);
            assert!((a.area_normal_2_in_1 - b.area_normal_2_in_1).norm() < 1e-12);
            overlapping += usize::from(!a.points.is_empty());
        }
        assert!(overlapping > 20, "{overlapping}");
    }
}
