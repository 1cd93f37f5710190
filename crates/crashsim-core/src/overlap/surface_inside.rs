//! The part of one mesh's surface inside the other (for the overlap region): the vector
//! area of each cut triangle's inside part (Green's theorem), patches of uncut triangles
//! decided once each against a closed mesh, the vertices inside.

use super::inside::nudged_vertex;
use crate::math::{Aabb, Isometry, Point, Real, Vector};
use crate::shape::MeshShape;
use crate::triangle::{centroid, inward_nudge, scaled_normal, segment_triangle_crossing, Tri};
use parry3d_f64::bounding_volume::BoundingVolume;

/// One triangle's meeting with a triangle of the other mesh: own triangle, other triangle,
/// the segment (own frame) oriented so the other mesh's inside lies to its left (about the own
/// triangle's normal), whether the own triangle, nudged into its solid and interior, is
/// crossed (false for a mere touch, which bounds no inside region of the own triangle), and
/// which own vertices lie on the other triangle's plane.
pub(super) type Crossing = (u32, u32, Point, Point, bool, [bool; 3]);

/// Vector area (own frame) of the part of triangle `t` inside `other`.
///
/// Points on the other surface are classified as the point `nudge` m into the own triangle
/// and into the own solid ([`inward_nudge`]): so two coplanar faces of the same orientation
/// both count as inside (and cancel in the volume normal), two facing ones neither, and an
/// edge lying on the other's face takes the side of its triangle. The crossing segments'
/// flags follow the same rule ([`triangle_triangle_contact`](crate::triangle::triangle_triangle_contact)), so the boundary pieces agree.
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
/// is decided alone. Without `areas` the vector area is not summed (zero); without
/// `vertices` no vertex is listed (the areas do not depend on it).
#[allow(clippy::too_many_arguments)]
pub(super) fn surface_inside(
    own: &MeshShape,
    other: &MeshShape,
    own_to_other: &Isometry,
    crossings: &[Crossing],
    other_tri_in_own: impl Fn(u32) -> Tri,
    use_patches: bool,
    areas: bool,
    vertices: bool,
    nudge: Real,
) -> (Vector, Vec<Point>) {
    let other_box_in_own = other.aabb().transform_by(&own_to_other.inverse());
    let n = own.triangles().len();
    let (crossed, on_other) = crossed_and_on_other(own, crossings);
    // Only the own triangles whose box meets the other's can be inside it (found through the
    // own tree: a shallow overlap's few hundred, not the mesh's every triangle).
    let in_box = triangles_in_box(own, &other_box_in_own);
    let candidates: Vec<u32> = (0..n as u32).filter(|&t| in_box[t as usize]).collect();
    let patches = (use_patches && other.is_closed())
        .then(|| Patches::new(own, &crossed, &in_box, &candidates));
    let mut cls = Classifier {
        own,
        other,
        own_to_other,
        crossed: &crossed,
        in_box: &in_box,
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
    // The triangles to look at, ascending: those in the box and the crossed ones (every
    // other triangle is uncut and out of the box: outside); none without `areas`.
    let order = (0..n as u32).filter(|&t| areas && (in_box[t as usize] || crossed[t as usize]));
    let mut total = Vector::zeros();
    let mut k = 0;
    let mut local: Vec<(Tri, Point, Point, bool)> = Vec::new();
    for ti in order {
        local.clear();
        while k < crossings.len() && crossings[k].0 == ti {
            let (_, o, p, q, cut, _) = crossings[k];
            local.push((other_tri_in_own(o), p, q, cut));
            k += 1;
        }
        let t = own.triangle(ti);
        if local.is_empty() {
            if !in_box[ti as usize] {
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
            edges = cls.cut_edges(ti, &t);
        }
        total += inside_vector_area(&t, &local, other, own_to_other, edges, nudge);
    }
    if !vertices {
        return (total, Vec::new());
    }
    let inside = cls.inside_vertices(&candidates, &other_box_in_own);
    (total, inside)
}

/// Per own triangle, whether a crossing touches it; per own vertex, whether it lies on a
/// plane of an other triangle it meets: on (or within the band of) the other surface, where
/// the side depends on the triangle it is seen from.
fn crossed_and_on_other(own: &MeshShape, crossings: &[Crossing]) -> (Vec<bool>, Vec<bool>) {
    let mut crossed = vec![false; own.triangles().len()];
    let mut on_other = vec![false; own.vertices().len()];
    for x in crossings {
        crossed[x.0 as usize] = true;
        let tri = own.triangles()[x.0 as usize];
        for k in 0..3 {
            on_other[tri[k] as usize] |= x.5[k];
        }
    }
    (crossed, on_other)
}

/// Per triangle of `own`, whether its box meets `bx` (own frame), found through its tree.
fn triangles_in_box(own: &MeshShape, bx: &Aabb) -> Vec<bool> {
    let bvh = own.bvh();
    let mut out = vec![false; own.triangles().len()];
    let mut stack = vec![0u32];
    while let Some(i) = stack.pop() {
        let node = &bvh.nodes()[i as usize];
        if !node.aabb.intersects(bx) {
            continue;
        }
        if bx.contains(&node.aabb) {
            // every triangle's box lies in the node's, so in `bx`
            for &ti in bvh.subtree_primitives(i) {
                out[ti as usize] = true;
            }
            continue;
        }
        if node.is_leaf() {
            for &ti in bvh.leaf_primitives(node) {
                out[ti as usize] =
                    Aabb::from_points(own.triangle(ti).iter().copied()).intersects(bx);
            }
        } else {
            let (left, right) = bvh.children(i);
            stack.push(right);
            stack.push(left);
        }
    }
    out
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
    /// Per own triangle: its box meets the other's.
    in_box: &'a [bool],
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
        // Out of the other's box: outside (its patch reaches out of the box).
        if !self.in_box[ti as usize] {
            return Some(false);
        }
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

    /// What is known of the edges of cut triangle ti (`t`, with patches): wholly inside or
    /// outside where the triangle across is uncut (its patch's status), else whether the
    /// edge's ends are inside seen from `t`.
    fn cut_edges(&mut self, ti: u32, t: &Tri) -> [EdgeStatus; 3] {
        let own = self.own;
        let mut edges = [EdgeStatus::Unknown; 3];
        let tri = own.triangles()[ti as usize];
        for (k, &nb) in own.neighbors(ti).iter().enumerate() {
            edges[k] = match (nb != u32::MAX && !self.crossed[nb as usize])
                .then(|| self.patch(nb))
                .flatten()
            {
                Some(is_inside) => EdgeStatus::Whole(is_inside),
                None => EdgeStatus::Ends(
                    self.vertex_seen_from(tri[k], t),
                    self.vertex_seen_from(tri[(k + 1) % 3], t),
                ),
            };
        }
        edges
    }

    /// The own vertices inside the other mesh (own frame, ascending), from those in its box
    /// `other_box` (own frame) that are corners of the `candidates` triangles or unused.
    fn inside_vertices(&mut self, candidates: &[u32], other_box: &Aabb) -> Vec<Point> {
        let own = self.own;
        let mut inside = Vec::new();
        // A vertex in the box is a corner of a triangle in it, or of none (an unused vertex).
        let mut corner = vec![false; own.vertices().len()];
        for &ti in candidates {
            for v in own.triangles()[ti as usize] {
                corner[v as usize] = true;
            }
        }
        let corners = (0..own.vertices().len() as u32)
            .filter(|&v| corner[v as usize] || own.vertex_triangle(v) == u32::MAX);
        for vi in corners {
            let v = own.vertices()[vi as usize];
            if other_box.contains_local_point(&v) && self.vertex(vi) {
                inside.push(v);
            }
        }
        inside
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

/// The own triangles in the other's box that no crossing touches, joined across shared edges
/// (union-find: a patch's root is its smallest triangle), and for each patch root whether the
/// patch reaches out of the other mesh's box (an uncut triangle beyond it shares an edge with
/// it). A patch of the whole mesh's uncut triangles that leaves the box may be cut here into
/// several, each of which leaves it: outside all the same; one inside the box is whole.
struct Patches {
    parent: Vec<u32>,
    leaves_box: Vec<bool>,
}

impl Patches {
    fn new(own: &MeshShape, crossed: &[bool], in_box: &[bool], candidates: &[u32]) -> Patches {
        let n = crossed.len();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        fn find(parent: &mut [u32], mut x: u32) -> u32 {
            while parent[x as usize] != x {
                parent[x as usize] = parent[parent[x as usize] as usize];
                x = parent[x as usize];
            }
            x
        }
        let uncut = |t: u32| !crossed[t as usize];
        // Each uncut candidate joined to its uncut partners in the box (each pair once: the
        // partner is a candidate too; a root is its set's smallest triangle whatever the
        // order), and noted when a partner is out of the box.
        let mut out_partner = Vec::new();
        for &a in candidates.iter().filter(|&&a| uncut(a)) {
            for &b in own.edge_partners(a) {
                if !uncut(b) {
                    continue;
                }
                if !in_box[b as usize] {
                    out_partner.push(a);
                    continue;
                }
                if b < a {
                    continue;
                }
                let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
                if ra != rb {
                    let (lo, hi) = (ra.min(rb), ra.max(rb));
                    parent[hi as usize] = lo;
                }
            }
        }
        for &a in candidates {
            let r = find(&mut parent, a);
            parent[a as usize] = r;
        }
        let mut leaves_box = vec![false; n];
        for a in out_partner {
            leaves_box[parent[a as usize] as usize] = true;
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
