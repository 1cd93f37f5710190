//! Triangle-level geometry: triangle-triangle crossing segments, triangle-triangle distance,
//! segment-triangle crossings and solid angles. All inputs are in one common frame (m).
//!
//! parry keeps its triangle-triangle intersection crate-private, so the crossing segment
//! (which the overlap region needs, with its orientation) is computed here; point-triangle
//! projection and segment-segment closest points come from parry.

use crate::math::{box_gap, Aabb, Point, Real, Vector};
use parry3d_f64::query::closest_points::closest_points_segment_segment_with_locations_nD;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{Segment, Triangle};

/// A triangle as three points.
pub type Tri = [Point; 3];

/// The unnormalized normal (b - a) x (c - a) of a triangle; its norm is twice the area.
#[inline]
pub fn scaled_normal(t: &Tri) -> Vector {
    (t[1] - t[0]).cross(&(t[2] - t[0]))
}

/// Where the triangle `t` meets the plane through `origin` with normal `normal`, given the
/// signed distances `d` of its vertices: the end points of the piece of `t` on the plane.
/// Returns None when `t` does not reach the plane.
#[inline]
fn plane_section(t: &Tri, d: &[Real; 3]) -> Option<(Point, Point)> {
    let mut pts = [Point::origin(); 4];
    let mut n = 0;
    for i in 0..3 {
        let j = (i + 1) % 3;
        if d[i] == 0.0 {
            pts[n] = t[i];
            n += 1;
        }
        if (d[i] < 0.0 && d[j] > 0.0) || (d[i] > 0.0 && d[j] < 0.0) {
            let s = d[i] / (d[i] - d[j]);
            pts[n] = t[i] + (t[j] - t[i]) * s;
            n += 1;
        }
    }
    match n {
        0 => None,
        1 => Some((pts[0], pts[0])),
        _ => Some((pts[0], pts[1])),
    }
}

#[inline]
fn same_strict_sign(d: &[Real; 3]) -> bool {
    (d[0] > 0.0 && d[1] > 0.0 && d[2] > 0.0) || (d[0] < 0.0 && d[1] < 0.0 && d[2] < 0.0)
}

/// Relative width of the band about a plane inside which a point counts as lying on it:
/// 2^-40 (about 1e-12) times the magnitude of the coordinates involved, some four thousand
/// times the round-off of rigidly moving them. Faces that are coplanar in the scene (two
/// boxes of one height side by side, a heading of 180 deg) stay coplanar to about that
/// round-off, not exactly; without the band their planes crossed at arbitrary places and a
/// head-on of two equal boxes lost half a front face (its normal came out 1.27 deg off).
pub const PLANE_TOLERANCE: Real = 1.0 / 1_099_511_627_776.0;

/// The largest coordinate magnitude (m) of the given triangles' vertices: the scale of the
/// round-off in their positions, and of [`PLANE_TOLERANCE`].
#[inline]
pub fn coordinate_scale(tris: &[&Tri]) -> Real {
    // Plain loops and `amax` below (the same maxima in the same order as the fold over the
    // flattened points and nalgebra's amax): 9 % of a box batch's instructions, per pair.
    let mut scale: Real = 0.0;
    for t in tris {
        for p in t.iter() {
            scale = scale.max(amax(&p.coords));
        }
    }
    scale
}

/// The largest absolute component of `v`: nalgebra's `amax` without its generic fold (the
/// same comparisons in the same order, `a >= b` keeping `a` as simba's `simd_max`, so the
/// same result, NaN included).
#[inline]
fn amax(v: &Vector) -> Real {
    let pick = |a: Real, b: Real| if a >= b { a } else { b };
    pick(pick(v.x.abs(), v.y.abs()), v.z.abs())
}

/// A triangle's plane with what its snapping band needs.
struct Plane {
    origin: Point,
    /// Unnormalized normal (b - a) x (c - a).
    n: Vector,
    n_norm: Real,
    /// Twice the sum of the largest edge components from the origin: how far the normal's
    /// direction can turn per unit of position round-off, times |n|.
    lever: Real,
}

impl Plane {
    #[inline]
    fn of(t: &Tri) -> Plane {
        let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
        let n = e1.cross(&e2);
        Plane {
            origin: t[0],
            n,
            n_norm: n.norm(),
            lever: 2.0 * (amax(&e1) + amax(&e2)),
        }
    }

    /// The signed distance of `v` (times |n|), exactly 0 within the band: `tol` m of
    /// round-off in every position, through the plane's offset and through its direction
    /// over the lever arm |v - origin| (so a sliver's poorly known plane has a wider band).
    #[inline]
    fn snapped_distance(&self, v: &Point, tol: Real) -> Real {
        let r = v - self.origin;
        let d = self.n.dot(&r);
        if d.abs() <= tol * (self.n_norm + amax(&r) * self.lever) {
            0.0
        } else {
            d
        }
    }
}

/// The signed distances of `t`'s vertices from `plane` (times |n|), snapped to 0 within the
/// band of `tol` m.
#[inline]
fn snapped_plane_distances(t: &Tri, plane: &Plane, tol: Real) -> [Real; 3] {
    t.map(|v| plane.snapped_distance(&v, tol))
}

/// The band (m) within which a vertex of the triangles counts as on a plane of theirs.
#[inline]
fn plane_band(tris: &[&Tri]) -> Real {
    PLANE_TOLERANCE * coordinate_scale(tris)
}

/// The move (per unit length, so a vector of about unit norm) that settles where a point
/// `p` of triangle `t` lying on another surface belongs: towards `t`'s centroid and into its
/// solid (against its normal), p -> p + tau ((c - p) / rho - n / |n|), rho the largest
/// distance from the centroid c to a vertex. Affine in p, so every point of `t` on a plane
/// moves to the same side of it. None for a triangle without area.
#[inline]
pub fn inward_nudge(t: &Tri, p: &Point) -> Option<Vector> {
    let n = scaled_normal(t);
    let full = n.norm();
    let c = centroid(t);
    let rho = t.iter().map(|v| (v - c).norm()).fold(0.0, Real::max);
    (full > 0.0 && rho > 0.0).then(|| (c - p) / rho - n / full)
}

/// The centroid of a triangle.
#[inline]
pub fn centroid(t: &Tri) -> Point {
    Point::from((t[0].coords + t[1].coords + t[2].coords) / 3.0)
}

/// Whether `t`, nudged by [`inward_nudge`], has vertices strictly on both sides of the
/// plane with unnormalized normal `n_other`, given the snapped distances `d` of its vertices
/// from that plane (times |n_other|): a vertex on the plane takes the side the nudge moves
/// it to, which is the same for all of them.
#[inline]
fn nudged_straddles(t: &Tri, nt: &Vector, d: &[Real; 3], n_other: &Vector) -> bool {
    let side = if d.contains(&0.0) {
        let c = centroid(t);
        let rho = t.iter().map(|v| (v - c).norm()).fold(0.0, Real::max);
        let (full, mean) = (nt.norm(), (d[0] + d[1] + d[2]) / 3.0);
        if full == 0.0 || rho == 0.0 {
            0.0
        } else {
            mean / rho - n_other.dot(nt) / full
        }
    } else {
        0.0
    };
    let signed = d.map(|x| if x == 0.0 { side } else { x });
    signed.iter().any(|&x| x < 0.0) && signed.iter().any(|&x| x > 0.0)
}

/// How two triangles (one common frame, m) meet: the limit of their crossing segment and,
/// for each, whether it is crossed when it alone is moved a hair into its own solid and
/// interior ([`inward_nudge`]); see [`triangle_triangle_contact`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleContact {
    /// Start of the segment the triangles share, oriented along n_a x n_b (m).
    pub start: Point,
    /// End of that segment (equal to the start for a touch at a point).
    pub end: Point,
    /// `a`, nudged into its solid and interior, crosses `b` along a segment: the segment
    /// bounds a part of `a` inside `b`'s side (false for a mere touch, which bounds nothing).
    pub a_crossed: bool,
    /// The same for `b` nudged into its own solid and interior.
    pub b_crossed: bool,
    /// Which vertices of `a` lie on `b`'s plane (within the band): where their side is
    /// settled by the nudge, which can differ from one triangle at the vertex to another.
    pub a_on_plane: [bool; 3],
    /// Which vertices of `b` lie on `a`'s plane (within the band).
    pub b_on_plane: [bool; 3],
}

impl TriangleContact {
    /// True when either triangle is crossed (not a mere touch of both).
    #[inline]
    pub fn is_crossing(&self) -> bool {
        self.a_crossed || self.b_crossed
    }
}

/// How triangles `a` and `b` meet; None when they do not, are coplanar or degenerate.
///
/// A vertex within [`PLANE_TOLERANCE`] (relative to the coordinates' magnitude) of the
/// other triangle's plane counts as on it, so triangles coplanar up to round-off are
/// coplanar, and an edge lying on the other's plane up to round-off touches it. Which
/// touches are crossings is settled by a symbolic nudge of one triangle at a time into its
/// own solid and interior (the rule the overlap region classifies points on the other
/// surface by): `a` is crossed when its nudged vertices straddle `b`'s plane and `b` reaches
/// below `a`'s plane (b's vertices on that plane lie above the nudged `a`).
pub fn triangle_triangle_contact(a: &Tri, b: &Tri) -> Option<TriangleContact> {
    let tol = plane_band(&[a, b]);
    let plane_b = Plane::of(b);
    let nb = plane_b.n;
    let da = snapped_plane_distances(a, &plane_b, tol);
    if same_strict_sign(&da) {
        return None;
    }
    let plane_a = Plane::of(a);
    let na = plane_a.n;
    let db = snapped_plane_distances(b, &plane_a, tol);
    if same_strict_sign(&db) {
        return None;
    }
    let dir = na.cross(&nb);
    // The planes' directions are known to about tol * lever / |n| rad each: planes parallel
    // to within that have no crossing line (it would lie anywhere).
    let (la, lb) = (plane_a.n_norm, plane_b.n_norm);
    let parallel = la == 0.0
        || lb == 0.0
        || dir.norm() <= tol * (plane_a.lever / la + plane_b.lever / lb) * la * lb;
    if da == [0.0; 3] || db == [0.0; 3] || parallel {
        // Coplanar, parallel or degenerate: no crossing segment (coplanar faces bound no
        // volume).
        return None;
    }
    let (a0, a1) = plane_section(a, &da)?;
    let (b0, b1) = plane_section(b, &db)?;
    // Both pieces lie on the line of the two planes: intersect their intervals along `dir`.
    let (sa0, sa1) = (dir.dot(&a0.coords), dir.dot(&a1.coords));
    let (sb0, sb1) = (dir.dot(&b0.coords), dir.dot(&b1.coords));
    let (alo, ahi, pa_lo, pa_hi) = if sa0 <= sa1 {
        (sa0, sa1, a0, a1)
    } else {
        (sa1, sa0, a1, a0)
    };
    let (blo, bhi, pb_lo, pb_hi) = if sb0 <= sb1 {
        (sb0, sb1, b0, b1)
    } else {
        (sb1, sb0, b1, b0)
    };
    // Intervals that meet within the band touch (an edge of one triangle through the edge
    // of the other): reported, though not as a crossing, so the overlap region still tests
    // the own triangle's edges against this triangle.
    let slack = 2.0 * tol * dir.norm();
    if alo > bhi + slack || blo > ahi + slack {
        return None;
    }
    let start = if alo >= blo { pa_lo } else { pb_lo };
    let end = if ahi <= bhi { pa_hi } else { pb_hi };
    // A segment no longer than the band is a touch at a point, which the nudges part (a
    // crossing through a vertex or edge of either mesh is also reported, with length, by the
    // triangles beside it).
    let long = (end - start).norm_squared() > tol * tol;
    Some(TriangleContact {
        start,
        end,
        a_crossed: long && nudged_straddles(a, &na, &da, &nb) && db.iter().any(|&x| x < 0.0),
        b_crossed: long && nudged_straddles(b, &nb, &db, &na) && da.iter().any(|&x| x < 0.0),
        a_on_plane: da.map(|x| x == 0.0),
        b_on_plane: db.map(|x| x == 0.0),
    })
}

/// The segment along which triangles `a` and `b` cross, oriented along `n_a x n_b`
/// (n the unnormalized normals). None when they do not meet, are coplanar or degenerate.
/// A touching contact gives a zero-length segment (or the shared piece of an edge lying on
/// the other's plane). Vertices within the band of [`triangle_triangle_contact`] count as
/// on the other's plane.
pub fn triangle_triangle_segment(a: &Tri, b: &Tri) -> Option<(Point, Point)> {
    triangle_triangle_contact(a, b).map(|c| (c.start, c.end))
}

/// True when the vertices of `a` lie strictly on both sides of the plane of `b` (so `a` is
/// cut by that plane, not merely touching it); vertices within the band of
/// [`triangle_triangle_segment`] count as on the plane.
#[inline]
pub fn triangle_cut_by_plane_of(a: &Tri, b: &Tri) -> bool {
    let d = snapped_plane_distances(a, &Plane::of(b), plane_band(&[a, b]));
    d.iter().any(|&x| x < 0.0) && d.iter().any(|&x| x > 0.0)
}

/// True when the triangles touch or cross (coplanar pairs count as not crossing).
#[inline]
pub fn triangles_intersect(a: &Tri, b: &Tri) -> bool {
    triangle_triangle_segment(a, b).is_some()
}

/// The point of triangle `t` nearest to `p`.
#[inline]
fn point_triangle_closest(p: &Point, t: &Tri) -> Point {
    if scaled_normal(t).norm_squared() == 0.0 {
        // A zero-area triangle is its edges: parry's projection onto it is undefined (it
        // returned distance 0 for far points, stalling the first-contact search).
        let mut best = (Real::INFINITY, *p);
        for i in 0..3 {
            let seg = Segment::new(t[i], t[(i + 1) % 3]);
            let q = seg.project_local_point(p, true).point;
            let d = (q - p).norm_squared();
            if d < best.0 {
                best = (d, q);
            }
        }
        return best.1;
    }
    let tri = Triangle::new(t[0], t[1], t[2]);
    tri.project_local_point(p, true).point
}

#[inline]
fn segment_segment_closest(p0: &Point, p1: &Point, q0: &Point, q1: &Point) -> (Point, Point) {
    let (l1, l2) = closest_points_segment_segment_with_locations_nD((p0, p1), (q0, q1));
    (
        Segment::new(*p0, *p1).point_at(&l1),
        Segment::new(*q0, *q1).point_at(&l2),
    )
}

/// The 15 candidate features of two triangles' closest points, in a fixed order: each vertex
/// of `a` against `b`, each vertex of `b` against `a`, each edge of `a` against each edge of
/// `b`. `measure(k)` is called for candidate k in that order and returns the least squared
/// distance (m^2) so far; a candidate whose features' boxes are farther apart than that,
/// by far more than the candidates' round-off, is passed over: its distance could not be the
/// least, nor tie with it.
fn closest_candidates(a: &Tri, b: &Tri, mut measure: impl FnMut(usize) -> Real) {
    let (box_a, box_b) = (
        Aabb::from_points(a.iter().copied()),
        Aabb::from_points(b.iter().copied()),
    );
    let edge = |t: &Tri, i: usize| Aabb::from_points([t[i], t[(i + 1) % 3]]);
    let point = |p: &Point| Aabb::new(*p, *p);
    // A candidate's computed points lie within round-off (a few units in the last place of
    // the coordinates) of its features: widen the bound's distance by far more than that.
    let slack = 1e-12 * coordinate_scale(&[a, b]);
    let mut limit = Real::INFINITY; // squared distance a candidate must be under to matter
    let mut consider = |k: usize, (f1, f2): (Aabb, Aabb)| {
        if box_gap(&f1, &f2).norm_squared() > limit {
            return;
        }
        let reach = measure(k).sqrt() + slack;
        limit = reach * reach;
    };
    for (k, p) in a.iter().enumerate() {
        consider(k, (point(p), box_b));
    }
    for (k, p) in b.iter().enumerate() {
        consider(3 + k, (box_a, point(p)));
    }
    for i in 0..3 {
        for j in 0..3 {
            consider(6 + 3 * i + j, (edge(a, i), edge(b, j)));
        }
    }
}

/// The closest points of candidate `k` of [`closest_candidates`].
#[inline]
fn candidate_points(a: &Tri, b: &Tri, k: usize) -> (Point, Point) {
    match k {
        0..=2 => (a[k], point_triangle_closest(&a[k], b)),
        3..=5 => (point_triangle_closest(&b[k - 3], a), b[k - 3]),
        _ => {
            let (i, j) = ((k - 6) / 3, (k - 6) % 3);
            segment_segment_closest(&a[i], &a[(i + 1) % 3], &b[j], &b[(j + 1) % 3])
        }
    }
}

/// The closest points (on `a`, on `b`) of two triangles that neither touch nor cross, None
/// when they do (as [`triangles_intersect`] decides). Between two convex sets the plane
/// through the closest points' midpoint, normal to the segment joining them, separates the
/// sets: every point pair is at least the distance apart along that direction.
pub fn triangle_triangle_closest(a: &Tri, b: &Tri) -> Option<(Point, Point)> {
    if triangles_intersect(a, b) {
        return None;
    }
    // The first candidate at the least distance (candidates passed over by their bounds
    // could not have been it).
    let mut best = (Real::INFINITY, a[0], b[0]);
    closest_candidates(a, b, |k| {
        let (pa, pb) = candidate_points(a, b, k);
        let d = (pa - pb).norm_squared();
        if d < best.0 {
            best = (d, pa, pb);
        }
        best.0
    });
    Some((best.1, best.2))
}

/// The squared distance between two triangles (0 when they touch or cross).
pub fn triangle_triangle_distance_sq(a: &Tri, b: &Tri) -> Real {
    if triangles_intersect(a, b) {
        return 0.0;
    }
    let mut best = Real::INFINITY;
    closest_candidates(a, b, |k| {
        let (pa, pb) = candidate_points(a, b, k);
        best = best.min((pa - pb).norm_squared());
        best
    });
    best
}

/// The parameter s in (0, 1) at which the segment p0 -> p1 crosses triangle `t`, if it does
/// (end points on the triangle's plane do not count as crossings). End points within the
/// band of [`triangle_triangle_segment`] count as on the plane, and a crossing point within
/// that band of the triangle's boundary as inside it (a crossing through an edge the
/// triangle shares is then reported by both its triangles).
pub fn segment_triangle_crossing(p0: &Point, p1: &Point, t: &Tri) -> Option<Real> {
    let tol = plane_band(&[t, &[*p0, *p1, *p1]]);
    let plane = Plane::of(t);
    let n = plane.n;
    let band_sq = tol * tol * n.norm_squared();
    let d0 = plane.snapped_distance(p0, tol);
    let d1 = plane.snapped_distance(p1, tol);
    if !((d0 < 0.0 && d1 > 0.0) || (d0 > 0.0 && d1 < 0.0)) {
        return None;
    }
    let s = d0 / (d0 - d1);
    let x = p0 + (p1 - p0) * s;
    // Inside test by the signs of the sub-triangle normals against n.
    for i in 0..3 {
        let e = t[(i + 1) % 3] - t[i];
        // Outside edge i by more than the band: v < -tol |e| |n|.
        let v = e.cross(&(x - t[i])).dot(&n);
        if v < 0.0 && v * v > band_sq * e.norm_squared() {
            return None;
        }
    }
    Some(s)
}

/// The signed solid angle (sr) that triangle `t` subtends at `p`; positive when `p` sees the
/// triangle's back (the side opposite its normal), so a closed outward mesh gives 4 pi inside.
#[inline]
pub fn solid_angle(t: &Tri, p: &Point) -> Real {
    let a = t[0] - p;
    let b = t[1] - p;
    let c = t[2] - p;
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let det = a.dot(&b.cross(&c));
    if det == 0.0 {
        // On the triangle's plane: 0 outside it, and the mean of the +2 pi and -2 pi of the
        // two sides on it (atan2 gave either, by the sign of a zero), so a point on a closed
        // surface has winding number one half.
        return 0.0;
    }
    let denom = la * lb * lc + a.dot(&b) * lc + b.dot(&c) * la + c.dot(&a) * lb;
    2.0 * det.atan2(denom)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every one of the 15 candidates measured, in the order of `closest_candidates`: what
    /// the passing-over by the features' boxes must reproduce bit for bit.
    fn closest_by_every_candidate(a: &Tri, b: &Tri) -> (Real, Point, Point) {
        let mut best = (Real::INFINITY, a[0], b[0]);
        for k in 0..15 {
            let (pa, pb) = candidate_points(a, b, k);
            let d = (pa - pb).norm_squared();
            if d < best.0 {
                best = (d, pa, pb);
            }
        }
        best
    }

    #[test]
    fn passing_over_far_candidates_keeps_the_closest_points_bit_for_bit() {
        use rand::rngs::SmallRng;
        use rand::{Rng, SeedableRng};
        let mut rng = SmallRng::seed_from_u64(11);
        let mut compared = 0;
        for case in 0..30_000 {
            let s = [1e-3, 1.0, 40.0][case % 3];
            let pt = |rng: &mut SmallRng, c: Vector| {
                Point::from(
                    c + Vector::new(
                        rng.random_range(-s..s),
                        rng.random_range(-s..s),
                        rng.random_range(-s..s),
                    ),
                )
            };
            let o = Vector::zeros();
            let a: Tri = [pt(&mut rng, o), pt(&mut rng, o), pt(&mut rng, o)];
            let b: Tri = match case % 5 {
                // a copy of a, moved a hair along its normal: every vertex ties
                0 => {
                    let n = scaled_normal(&a).normalize() * (s * 1e-7);
                    [a[0] + n, a[1] + n, a[2] + n]
                }
                // a copy of a, moved along an edge and off its plane: edges tie
                1 => {
                    let m = (a[1] - a[0]) * 0.25 + scaled_normal(&a).normalize() * (s * 1e-3);
                    [a[0] + m, a[1] + m, a[2] + m]
                }
                // a sliver: two vertices a hair apart
                2 => {
                    let c = Vector::new(2.0 * s, 0.0, 0.0);
                    let p = pt(&mut rng, c);
                    [p, p + Vector::new(1e-13, 0.0, 0.0), pt(&mut rng, c)]
                }
                _ => {
                    let c = Vector::new(rng.random_range(0.0..3.0) * s, 0.0, 0.0);
                    [pt(&mut rng, c), pt(&mut rng, c), pt(&mut rng, c)]
                }
            };
            if triangles_intersect(&a, &b) {
                continue;
            }
            let (d, pa, pb) = closest_by_every_candidate(&a, &b);
            assert_eq!(
                triangle_triangle_closest(&a, &b),
                Some((pa, pb)),
                "case {case}"
            );
            assert_eq!(triangle_triangle_distance_sq(&a, &b).to_bits(), d.to_bits());
            compared += 1;
        }
        assert!(compared > 20_000, "{compared}");
    }

    #[test]
    fn closest_points_give_the_distance_and_a_separating_plane() {
        use rand::rngs::SmallRng;
        use rand::{Rng, SeedableRng};
        let mut rng = SmallRng::seed_from_u64(7);
        let pt = |rng: &mut SmallRng, s: Real| {
            Point::new(
                rng.random_range(-s..s),
                rng.random_range(-s..s),
                rng.random_range(-s..s),
            )
        };
        let mut apart = 0;
        for _ in 0..2000 {
            let a = [pt(&mut rng, 1.0), pt(&mut rng, 1.0), pt(&mut rng, 1.0)];
            let o = Vector::new(rng.random_range(-2.0..2.0), 0.5, 0.0);
            let b = [
                pt(&mut rng, 1.0) + o,
                pt(&mut rng, 1.0) + o,
                pt(&mut rng, 1.0) + o,
            ];
            let d = triangle_triangle_distance_sq(&a, &b).sqrt();
            match triangle_triangle_closest(&a, &b) {
                None => assert_eq!(d, 0.0),
                Some((p, q)) => {
                    apart += 1;
                    let g = (q - p).norm();
                    assert!((g - d).abs() <= 1e-12 * (1.0 + d), "{g} vs {d}");
                    // Every point pair (corners and random convex combinations) is at least
                    // the distance apart along the closest points' direction.
                    let n = (q - p) / g;
                    for _ in 0..20 {
                        let w = |rng: &mut SmallRng| {
                            let (u, v): (Real, Real) =
                                (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
                            let (u, v) = if u + v > 1.0 {
                                (1.0 - u, 1.0 - v)
                            } else {
                                (u, v)
                            };
                            (u, v)
                        };
                        let (u, v) = w(&mut rng);
                        let pa = a[0] + (a[1] - a[0]) * u + (a[2] - a[0]) * v;
                        let (u, v) = w(&mut rng);
                        let pb = b[0] + (b[1] - b[0]) * u + (b[2] - b[0]) * v;
                        assert!(
                            n.dot(&(pb - pa)) >= g - 1e-12,
                            "{} < {g}",
                            n.dot(&(pb - pa))
                        );
                    }
                }
            }
        }
        assert!(apart > 500, "{apart} pairs apart");
    }

    fn p(x: Real, y: Real, z: Real) -> Point {
        Point::new(x, y, z)
    }

    #[test]
    fn a_zero_area_triangle_is_as_far_as_its_edges() {
        // Regression: a collinear sliver of the shared sedan mesh and a triangle 4.3 m away
        // were found at distance 0 (parry's projection onto a zero-area triangle), which made
        // the first-contact search crawl at its smallest step for the rest of a run.
        let sliver = [
            p(-0.6290842128924499, 0.8328753611647658, -0.32834738990404),
            p(-0.16585975717822407, 0.8328753611647658, -0.32834738990404),
            p(0.22851519454201366, 0.8328753611647658, -0.32834738990404),
        ];
        let other = [
            p(0.4213799985994494, -3.505786827394423, 0.3201440649659735),
            p(0.2470379073736806, -3.374318089551551, 0.13379077735084133),
            p(0.1661761887149371, -3.4824319702711035, 0.13316833429172692),
        ];
        let d = triangle_triangle_distance_sq(&sliver, &other).sqrt();
        assert!(d > 4.0 && d < 4.4, "{d}");
        let d_rev = triangle_triangle_distance_sq(&other, &sliver).sqrt();
        assert_eq!(d, d_rev);
    }

    #[test]
    fn faces_coplanar_up_to_round_off_do_not_cross() {
        // Regression (issue 10, item 5): a side face of a box and the side face of another
        // turned by 180 deg lie in one plane up to 1e-16 rad; their planes crossed in the
        // middle of the face and tilted the head-on's normal by 1.27 deg.
        let a = [p(-2.25, 0.9, -0.7), p(-2.25, 0.9, 0.7), p(2.25, 0.9, -0.7)];
        let tilt = 1.2246467991473532e-16;
        let b = [
            p(6.73, 0.9 - 6.73 * tilt, -0.7),
            p(2.23, 0.9 - 2.23 * tilt, 0.7),
            p(2.23, 0.9 - 2.23 * tilt, -0.7),
        ];
        assert!(triangle_triangle_contact(&a, &b).is_none());
        // A real tilt (1e-6 rad) is a crossing.
        let tilt = 1e-6;
        let b = [
            p(6.73, 0.9 + (6.73 - 2.24) * tilt, -0.7),
            p(2.23, 0.9 + (2.23 - 2.24) * tilt, 0.7),
            p(2.23, 0.9 + (2.23 - 2.24) * tilt, -0.7),
        ];
        let c = triangle_triangle_contact(&a, &b).unwrap();
        assert!(c.a_crossed && c.b_crossed, "{c:?}");
    }

    #[test]
    fn an_edge_lying_on_a_face_is_crossed_only_for_the_face() {
        // A front face (plane x = 2.25, normal +x) whose edge lies on a side face of the
        // other box (plane y = 0.9, normal +y, the other box at y < 0.9): nudged into its
        // triangle the edge leaves the side's plane, so the front face is only touched; the
        // side face, nudged into its solid, is cut by the front face along the edge.
        let front = [p(2.25, 0.9, -0.7), p(2.25, 0.9, 0.7), p(2.25, -0.9, 0.7)];
        let side = [p(6.73, 0.9, -0.7), p(2.23, 0.9, -0.7), p(2.23, 0.9, 0.7)];
        assert!(scaled_normal(&side).y > 0.0);
        let c = triangle_triangle_contact(&front, &side).unwrap();
        assert!(!c.a_crossed && c.b_crossed, "{c:?}");
        assert!((c.end - c.start).norm() > 1.0);
        let r = triangle_triangle_contact(&side, &front).unwrap();
        assert!(r.a_crossed && !r.b_crossed, "{r:?}");
        // The same front face against a side face of a box at y > 0.9 (touching from
        // outside): nothing is crossed.
        let outside = [p(6.73, 0.9, -0.7), p(2.23, 0.9, 0.7), p(2.23, 0.9, -0.7)];
        let c = triangle_triangle_contact(&front, &outside).unwrap();
        assert!(!c.is_crossing(), "{c:?}");
    }

    #[test]
    fn a_touch_at_a_point_is_not_a_crossing() {
        // Two boxes side by side touching along a side: the bottom of one meets the front
        // face of the other only at a corner (a segment 1e-16 m long).
        let front = [p(2.25, -0.9, -0.7), p(2.25, 0.9, -0.7), p(2.25, -0.9, 0.7)];
        let bottom = [
            p(-1.25, 2.7, -0.7),
            p(3.25, 0.8999999999999998, -0.7),
            p(-1.25, 0.9000000000000002, -0.7),
        ];
        let c = triangle_triangle_contact(&front, &bottom).unwrap();
        assert!(!c.is_crossing(), "{c:?}");
        assert!((c.end - c.start).norm() < 1e-12);
    }

    #[test]
    fn crossing_segment_of_perpendicular_triangles_is_oriented_along_na_cross_nb() {
        // a in the plane z = 0 (normal +z), b in the plane x = 0.2 (normal +x).
        let a = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
        let b = [p(0.2, -1.0, -1.0), p(0.2, 2.0, -1.0), p(0.2, -1.0, 2.0)];
        let (s, e) = triangle_triangle_segment(&a, &b).unwrap();
        let na = scaled_normal(&a);
        let nb = scaled_normal(&b);
        assert!((e - s).dot(&na.cross(&nb)) > 0.0);
        // The crossing is x = 0.2, z = 0, y from 0 to 0.8.
        for q in [s, e] {
            assert!((q.x - 0.2).abs() < 1e-15 && q.z.abs() < 1e-15);
        }
        let (ylo, yhi) = (s.y.min(e.y), s.y.max(e.y));
        assert!(ylo.abs() < 1e-15 && (yhi - 0.8).abs() < 1e-15);
    }

    #[test]
    fn separated_and_coplanar_triangles_do_not_cross() {
        let a = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
        let far = [p(0.0, 0.0, 1.0), p(1.0, 0.0, 1.0), p(0.0, 1.0, 1.0)];
        assert!(triangle_triangle_segment(&a, &far).is_none());
        let coplanar = [p(0.1, 0.1, 0.0), p(2.0, 0.1, 0.0), p(0.1, 2.0, 0.0)];
        assert!(triangle_triangle_segment(&a, &coplanar).is_none());
        assert!((triangle_triangle_distance_sq(&a, &far) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn edge_edge_distance_between_skew_triangles() {
        let a = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
        // b's edge runs parallel to y at x = 0.5, z = 0.3 over a's hypotenuse region... place
        // it beyond the hypotenuse so the closest features are a's hypotenuse and b's edge.
        let b = [p(2.0, 2.0, 0.5), p(2.0, 3.0, 0.5), p(3.0, 2.0, 0.5)];
        let d = triangle_triangle_distance_sq(&a, &b).sqrt();
        // Closest: a's corner region on the hypotenuse x + y = 1 to b's vertex (2, 2, 0.5).
        let expected = ((2.0f64 - 0.5).powi(2) * 2.0 + 0.25).sqrt();
        assert!((d - expected).abs() < 1e-12, "{d} vs {expected}");
    }

    #[test]
    fn solid_angle_of_a_closed_tetrahedron_is_4pi_inside_and_0_outside() {
        let v = [
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(0.0, 0.0, 1.0),
        ];
        // Outward-oriented faces.
        let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let total = |q: &Point| -> Real {
            faces
                .iter()
                .map(|f| solid_angle(&[v[f[0]], v[f[1]], v[f[2]]], q))
                .sum()
        };
        let four_pi = 4.0 * std::f64::consts::PI;
        assert!((total(&p(0.1, 0.1, 0.1)) - four_pi).abs() < 1e-12);
        assert!(total(&p(2.0, 0.1, 0.1)).abs() < 1e-12);
    }

    #[test]
    fn segment_crosses_triangle_at_the_right_parameter() {
        let t = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
        let s = segment_triangle_crossing(&p(0.2, 0.2, -1.0), &p(0.2, 0.2, 3.0), &t).unwrap();
        assert!((s - 0.25).abs() < 1e-15);
        assert!(segment_triangle_crossing(&p(0.8, 0.8, -1.0), &p(0.8, 0.8, 1.0), &t).is_none());
    }
}
