//! Triangle-level geometry: triangle-triangle crossing segments, triangle-triangle distance,
//! segment-triangle crossings and solid angles. All inputs are in one common frame (m).
//!
//! parry keeps its triangle-triangle intersection crate-private, so the crossing segment
//! (which the overlap region needs, with its orientation) is computed here; point-triangle
//! projection and segment-segment closest points come from parry.

use crate::math::{Point, Real, Vector};
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

/// The segment along which triangles `a` and `b` cross, oriented along `n_a x n_b`
/// (n the unnormalized normals). None when they do not meet, are coplanar or degenerate.
/// A touching contact gives a zero-length segment.
pub fn triangle_triangle_segment(a: &Tri, b: &Tri) -> Option<(Point, Point)> {
    let nb = scaled_normal(b);
    let da = [
        nb.dot(&(a[0] - b[0])),
        nb.dot(&(a[1] - b[0])),
        nb.dot(&(a[2] - b[0])),
    ];
    if same_strict_sign(&da) {
        return None;
    }
    let na = scaled_normal(a);
    let db = [
        na.dot(&(b[0] - a[0])),
        na.dot(&(b[1] - a[0])),
        na.dot(&(b[2] - a[0])),
    ];
    if same_strict_sign(&db) {
        return None;
    }
    let dir = na.cross(&nb);
    if dir.norm_squared() == 0.0 {
        // Coplanar or degenerate: no crossing segment (coplanar faces bound no volume).
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
    if alo > bhi || blo > ahi {
        return None;
    }
    let lo = if alo >= blo { pa_lo } else { pb_lo };
    let hi = if ahi <= bhi { pa_hi } else { pb_hi };
    Some((lo, hi))
}

/// True when the vertices of `a` lie strictly on both sides of the plane of `b` (so `a` is
/// cut by that plane, not merely touching it).
#[inline]
pub fn triangle_cut_by_plane_of(a: &Tri, b: &Tri) -> bool {
    let nb = scaled_normal(b);
    let (mut below, mut above) = (false, false);
    for v in a {
        let d = nb.dot(&(v - b[0]));
        below |= d < 0.0;
        above |= d > 0.0;
    }
    below && above
}

/// True when the triangles touch or cross (coplanar pairs count as not crossing).
#[inline]
pub fn triangles_intersect(a: &Tri, b: &Tri) -> bool {
    triangle_triangle_segment(a, b).is_some()
}

#[inline]
fn point_triangle_distance_sq(p: &Point, t: &Tri) -> Real {
    if scaled_normal(t).norm_squared() == 0.0 {
        // A zero-area triangle is its edges: parry's projection onto it is undefined (it
        // returned distance 0 for far points, stalling the first-contact search).
        let mut best = Real::INFINITY;
        for i in 0..3 {
            let seg = Segment::new(t[i], t[(i + 1) % 3]);
            best = best.min((seg.project_local_point(p, true).point - p).norm_squared());
        }
        return best;
    }
    let tri = Triangle::new(t[0], t[1], t[2]);
    let proj = tri.project_local_point(p, true);
    (proj.point - p).norm_squared()
}

#[inline]
fn segment_segment_distance_sq(p0: &Point, p1: &Point, q0: &Point, q1: &Point) -> Real {
    let (l1, l2) = closest_points_segment_segment_with_locations_nD((p0, p1), (q0, q1));
    let a = Segment::new(*p0, *p1).point_at(&l1);
    let b = Segment::new(*q0, *q1).point_at(&l2);
    (a - b).norm_squared()
}

/// The squared distance between two triangles (0 when they touch or cross).
pub fn triangle_triangle_distance_sq(a: &Tri, b: &Tri) -> Real {
    if triangles_intersect(a, b) {
        return 0.0;
    }
    let mut best = Real::INFINITY;
    for p in a {
        best = best.min(point_triangle_distance_sq(p, b));
    }
    for p in b {
        best = best.min(point_triangle_distance_sq(p, a));
    }
    for i in 0..3 {
        let (p0, p1) = (&a[i], &a[(i + 1) % 3]);
        for j in 0..3 {
            best = best.min(segment_segment_distance_sq(p0, p1, &b[j], &b[(j + 1) % 3]));
        }
    }
    best
}

/// The parameter s in (0, 1) at which the segment p0 -> p1 crosses triangle `t`, if it does
/// (end points on the triangle's plane do not count as crossings).
pub fn segment_triangle_crossing(p0: &Point, p1: &Point, t: &Tri) -> Option<Real> {
    let n = scaled_normal(t);
    let d0 = n.dot(&(p0 - t[0]));
    let d1 = n.dot(&(p1 - t[0]));
    if !((d0 < 0.0 && d1 > 0.0) || (d0 > 0.0 && d1 < 0.0)) {
        return None;
    }
    let s = d0 / (d0 - d1);
    let x = p0 + (p1 - p0) * s;
    // Inside test by the signs of the sub-triangle normals against n.
    for i in 0..3 {
        let e = t[(i + 1) % 3] - t[i];
        if e.cross(&(x - t[i])).dot(&n) < 0.0 {
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
    let denom = la * lb * lc + a.dot(&b) * lc + b.dot(&c) * la + c.dot(&a) * lb;
    2.0 * det.atan2(denom)
}

#[cfg(test)]
mod tests {
    use super::*;

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
