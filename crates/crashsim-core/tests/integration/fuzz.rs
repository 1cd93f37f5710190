//! Property-based fuzzing of the core's geometric queries (proptest): triangle-level
//! (crossing segment, distance, segment-triangle crossing, solid angle), mesh-level
//! (`MeshShape::new` on random soups, winding numbers, ray hits, mass properties) and
//! two-mesh queries (`shapes_overlap`, `surface_distance`, `surfaces_intersect`,
//! `overlap_region` and its volume normal). Inputs mix random, degenerate (zero-area,
//! collinear, repeated vertices), near-coplanar and huge/tiny-coordinate triangles.
//! Properties: no panic, no NaN in an output (a typed error instead), and the relations the
//! queries promise (symmetry, zero distance exactly when crossing, agreement between the
//! predicates, the exact overlap box of axis-aligned boxes).
//!
//! Budget: each property runs a bounded number of cases (`CASES_*` below, the whole file in
//! well under 30 s in release on the project's 2-core machine). For a longer run set
//! PROPTEST_CASES, which replaces every per-test count (see tests/README.md):
//!     PROPTEST_CASES=20000 cargo test -p crashsim-core --release --test integration fuzz::
//! A failure prints the shrunk case; keep it as a named regression test
//! (tests/integration/fuzz_regressions.rs).
//! Frames and units: one common frame, m.

use std::f64::consts::PI;

use crashsim_core::mass::solid_properties;
use crashsim_core::math::{Isometry, Point, Real, Rotation, Vector};
use crashsim_core::overlap::{
    overlap_region, shapes_overlap, surface_distance, surfaces_intersect, QueryWorkspace,
};
use crashsim_core::triangle::{
    scaled_normal, segment_triangle_crossing, solid_angle, triangle_triangle_contact,
    triangle_triangle_distance_sq, triangle_triangle_segment, triangles_intersect, Tri,
};
use crashsim_core::ErrorKind;
use crashsim_core::MeshShape;
use proptest::prelude::*;

/// Cases per property for triangle-level queries (microseconds each).
const CASES_TRIANGLE: u32 = 20000;
/// Cases per property for mesh construction and single-mesh queries.
const CASES_MESH: u32 = 2000;
/// Cases per property for two-mesh queries (up to a few ms each).
const CASES_PAIR: u32 = 1000;

/// proptest's configuration: `cases` from a fixed seed (the ordinary test run is
/// deterministic), or PROPTEST_CASES cases from a fresh seed each run (a long run explores).
fn config(cases: u32) -> ProptestConfig {
    let long: Option<u32> = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok());
    ProptestConfig {
        cases: long.unwrap_or(cases),
        rng_seed: match long {
            Some(_) => proptest::test_runner::RngSeed::Random,
            None => proptest::test_runner::RngSeed::Fixed(0x00c0_ffee),
        },
        max_shrink_iters: 2000,
        // Found cases become named tests (tests/integration/fuzz_regressions.rs), not files.
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

// -- strategies ----------------------------------------------------------------------------

/// A coordinate: uniform, on a coarse grid (so coincidences and coplanarity are common), or
/// zero.
fn coordinate() -> impl Strategy<Value = Real> {
    prop_oneof![
        4 => -10.0..10.0f64,
        3 => (-4i32..=4).prop_map(|k| k as Real * 0.5),
        1 => Just(0.0),
    ]
}

/// A point of `coordinate`s.
fn point() -> impl Strategy<Value = Point> {
    (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| Point::new(x, y, z))
}

/// A scale for a whole case: tiny, ordinary or huge coordinates.
fn scale() -> impl Strategy<Value = Real> {
    prop_oneof![
        1 => Just(1e-9),
        1 => Just(1e-4),
        6 => Just(1.0),
        1 => Just(1e4),
        1 => Just(1e9),
    ]
}

/// A triangle: random, with a repeated vertex, collinear, or sliver-thin.
fn triangle() -> impl Strategy<Value = Tri> {
    prop_oneof![
        6 => (point(), point(), point()).prop_map(|(a, b, c)| [a, b, c]),
        1 => (point(), point()).prop_map(|(a, b)| [a, a, b]),
        1 => (point(), point(), -2.0..3.0f64).prop_map(|(a, b, s)| [a, b, a + (b - a) * s]),
        1 => (point(), point(), point(), 1e-14..1e-6f64)
            .prop_map(|(a, b, c, e)| [a, b, a + (b - a) * 0.5 + (c - a) * e]),
    ]
}

/// Two triangles: independent, sharing a vertex or an edge, near-coplanar (the second on the
/// first's plane, then lifted by 0 or a tiny offset), or touching at a vertex.
fn triangle_pair() -> impl Strategy<Value = (Tri, Tri)> {
    let offset = prop_oneof![
        Just(0.0),
        Just(1e-15),
        Just(-1e-13),
        Just(1e-9),
        -1e-6..1e-6f64
    ];
    prop_oneof![
        4 => (triangle(), triangle()),
        1 => (triangle(), point(), point()).prop_map(|(a, p, q)| (a, [a[0], p, q])),
        1 => (triangle(), point()).prop_map(|(a, p)| (a, [a[1], a[0], p])),
        3 => (triangle(), -2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64, offset)
            .prop_map(|(a, u0, v0, u1, v1, off)| {
                let n = scaled_normal(&a);
                let lift = if n.norm() > 0.0 { n.normalize() * off } else { Vector::zeros() };
                let at = |u: Real, v: Real| a[0] + (a[1] - a[0]) * u + (a[2] - a[0]) * v + lift;
                (a, [at(u0, v0), at(u1, v1), at(v0, u1)])
            }),
    ]
}

fn scaled(t: &Tri, s: Real) -> Tri {
    t.map(|p| Point::from(p.coords * s))
}

/// A random rotation (axis-angle).
fn rotation() -> impl Strategy<Value = Rotation> {
    (-PI..PI, -1.0..1.0f64, -PI..PI).prop_map(|(angle, cz, lon)| {
        let r = (1.0 - cz * cz).sqrt();
        let axis = nalgebra::Unit::new_normalize(Vector::new(r * lon.cos(), r * lon.sin(), cz));
        Rotation::from_axis_angle(&axis, angle)
    })
}

/// A rotation that maps the axes onto axes (yaw in quarter turns, or a quarter-turn roll):
/// boxes then keep their faces parallel, so coplanar faces and touches are common.
fn axis_rotation() -> impl Strategy<Value = Rotation> {
    (0u8..4, 0u8..2).prop_map(|(k, roll)| {
        let yaw = Rotation::from_axis_angle(&Vector::z_axis(), k as Real * PI / 2.0);
        if roll == 1 {
            yaw * Rotation::from_axis_angle(&Vector::x_axis(), PI / 2.0)
        } else {
            yaw
        }
    })
}

/// A closed, outward mesh: a box, a tetrahedron or an octahedron of random size.
fn closed_mesh() -> impl Strategy<Value = MeshShape> {
    let half = || prop_oneof![0.1..3.0f64, (1i32..=6).prop_map(|k| k as Real * 0.25)];
    prop_oneof![
        3 => (half(), half(), half())
            .prop_map(|(x, y, z)| MeshShape::cuboid(Vector::zeros(), Vector::new(x, y, z))),
        1 => half().prop_map(|s| {
            let v = vec![
                Point::new(s, s, s),
                Point::new(s, -s, -s),
                Point::new(-s, s, -s),
                Point::new(-s, -s, s),
            ];
            MeshShape::new(v, vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]).unwrap()
        }),
        1 => half().prop_map(|s| {
            let v = vec![
                Point::new(s, 0.0, 0.0),
                Point::new(-s, 0.0, 0.0),
                Point::new(0.0, s, 0.0),
                Point::new(0.0, -s, 0.0),
                Point::new(0.0, 0.0, s),
                Point::new(0.0, 0.0, -s),
            ];
            let t = vec![
                [0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],
                [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5],
            ];
            MeshShape::new(v, t).unwrap()
        }),
    ]
}

/// A triangle soup (open, degenerate triangles and repeated vertices included) that
/// `MeshShape::new` accepts.
fn soup_mesh() -> impl Strategy<Value = MeshShape> {
    (
        prop::collection::vec(point(), 3..12),
        prop::collection::vec((0u32..12, 0u32..12, 0u32..12), 1..12),
    )
        .prop_filter_map("no usable triangle", |(v, t)| {
            let n = v.len() as u32;
            let t = t
                .into_iter()
                .map(|(a, b, c)| [a % n, b % n, c % n])
                .collect();
            MeshShape::new(v, t).ok()
        })
}

fn mesh() -> impl Strategy<Value = MeshShape> {
    prop_oneof![3 => closed_mesh(), 1 => soup_mesh()]
}

/// A pose: random, or axis-aligned on a coarse grid (coplanar faces, touches).
fn pose() -> impl Strategy<Value = Isometry> {
    prop_oneof![
        1 => (-4.0..4.0f64, -4.0..4.0f64, -4.0..4.0f64, rotation()).prop_map(|(x, y, z, r)| {
            Isometry::from_parts(nalgebra::Translation3::new(x, y, z), r)
        }),
        1 => ((-12i32..=12), (-12i32..=12), (-12i32..=12), axis_rotation()).prop_map(
            |(x, y, z, r)| {
                let t = nalgebra::Translation3::new(x as Real * 0.25, y as Real * 0.25, z as Real * 0.25);
                Isometry::from_parts(t, r)
            }
        ),
    ]
}

// -- helpers ---------------------------------------------------------------------------------

fn finite_point(p: &Point) -> bool {
    p.iter().all(|c| c.is_finite())
}

/// Distance from `p` to triangle `t` (brute force on a fine barycentric grid is too slow;
/// the exact point-triangle distance via a degenerate triangle pair).
fn point_triangle_distance(p: &Point, t: &Tri) -> Real {
    triangle_triangle_distance_sq(&[*p, *p, *p], t).sqrt()
}

/// The round-off allowance (m) of the triangles' sliver thickness: a triangle thinner than
/// 1e-6 of the coordinates' magnitude has a poorly known plane, and points projected onto it
/// are known only to about its thickness (twice the area over the longest edge).
fn sliver_allowance(tris: &[&Tri]) -> Real {
    let l = magnitude(tris);
    tris.iter()
        .map(|t| {
            let longest = (0..3)
                .map(|i| (t[(i + 1) % 3] - t[i]).norm())
                .fold(0.0, Real::max);
            let h = if longest > 0.0 {
                scaled_normal(t).norm() / longest
            } else {
                0.0
            };
            if h > 0.0 && h < 1e-6 * l {
                h
            } else {
                0.0
            }
        })
        .sum()
}

fn magnitude(tris: &[&Tri]) -> Real {
    tris.iter()
        .flat_map(|t| t.iter())
        .map(|p| p.coords.amax())
        .fold(0.0, Real::max)
}

// -- triangle level --------------------------------------------------------------------------

proptest! {
    #![proptest_config(config(CASES_TRIANGLE))]

    #[test]
    fn triangle_distance_is_finite_nonnegative_symmetric_and_zero_when_crossing(
        (a, b) in triangle_pair(), s in scale()
    ) {
        let (a, b) = (scaled(&a, s), scaled(&b, s));
        let d_ab = triangle_triangle_distance_sq(&a, &b);
        let d_ba = triangle_triangle_distance_sq(&b, &a);
        prop_assert!(d_ab.is_finite() && d_ab >= 0.0, "{d_ab}");
        prop_assert!(d_ba.is_finite() && d_ba >= 0.0, "{d_ba}");
        let l = magnitude(&[&a, &b]);
        let tol = 1e-9 * l + sliver_allowance(&[&a, &b]);
        prop_assert!((d_ab.sqrt() - d_ba.sqrt()).abs() <= tol, "{d_ab} {d_ba}");
        if triangles_intersect(&a, &b) {
            prop_assert_eq!(d_ab, 0.0);
        }
        // The distance is at most that between any two of their vertices (and centroids).
        let mut upper = Real::INFINITY;
        for p in a.iter() {
            for q in b.iter() {
                upper = upper.min((p - q).norm());
            }
        }
        prop_assert!(d_ab.sqrt() <= upper * (1.0 + 1e-12) + 1e-12 * l, "{} > {upper}", d_ab.sqrt());
    }

    #[test]
    fn separated_triangles_are_at_least_their_gap_apart(
        a in triangle(), b in triangle(), gap in 1e-3..5.0f64, s in scale()
    ) {
        // Put b beyond the plane x = max(a.x) + gap: the distance is at least the gap and
        // they do not meet.
        let ax = a.iter().map(|p| p.x).fold(Real::NEG_INFINITY, Real::max);
        let bx = b.iter().map(|p| p.x).fold(Real::INFINITY, Real::min);
        let shift = Vector::x() * (ax + gap - bx);
        let b = b.map(|p| p + shift);
        let (a, b) = (scaled(&a, s), scaled(&b, s));
        let d = triangle_triangle_distance_sq(&a, &b).sqrt();
        prop_assert!(d >= gap * s * (1.0 - 1e-9), "{d} < {}", gap * s);
        prop_assert!(!triangles_intersect(&a, &b));
        prop_assert!(triangle_triangle_contact(&a, &b).is_none());
    }

    #[test]
    fn crossing_segment_lies_on_both_triangles_and_does_not_depend_on_the_order(
        (a, b) in triangle_pair(), s in scale()
    ) {
        let (a, b) = (scaled(&a, s), scaled(&b, s));
        let ab = triangle_triangle_contact(&a, &b);
        let ba = triangle_triangle_contact(&b, &a);
        prop_assert_eq!(ab.is_some(), ba.is_some());
        prop_assert_eq!(triangle_triangle_segment(&a, &b).is_some(), ab.is_some());
        let (Some(ab), Some(ba)) = (ab, ba) else { return Ok(()); };
        prop_assert_eq!(ab.a_crossed, ba.b_crossed);
        prop_assert_eq!(ab.b_crossed, ba.a_crossed);
        prop_assert_eq!(ab.a_on_plane, ba.b_on_plane);
        let l = magnitude(&[&a, &b]);
        let tol = 1e-9 * l + sliver_allowance(&[&a, &b]);
        for p in [ab.start, ab.end] {
            prop_assert!(finite_point(&p), "{p}");
            let (da, db) = (point_triangle_distance(&p, &a), point_triangle_distance(&p, &b));
            prop_assert!(da <= tol && db <= tol, "{p}: {da} {db}");
        }
        // The same segment, reversed (n_b x n_a), to round-off.
        prop_assert!(
            (ab.start - ba.end).norm() <= tol && (ab.end - ba.start).norm() <= tol,
            "{:?} vs {:?}", ab, ba
        );
    }

    #[test]
    fn segment_triangle_crossing_is_on_the_triangle(
        t in triangle(), p0 in point(), p1 in point(), s in scale()
    ) {
        let t = scaled(&t, s);
        let (p0, p1) = (Point::from(p0.coords * s), Point::from(p1.coords * s));
        if let Some(u) = segment_triangle_crossing(&p0, &p1, &t) {
            prop_assert!(u.is_finite() && u > 0.0 && u < 1.0, "{u}");
            let x = p0 + (p1 - p0) * u;
            let l = magnitude(&[&t, &[p0, p1, p1]]);
            let d = point_triangle_distance(&x, &t);
            prop_assert!(d <= 1e-9 * l, "{x} is {d} from the triangle");
            // Reversing the segment gives the complementary parameter.
            let v = segment_triangle_crossing(&p1, &p0, &t);
            prop_assert!(v.is_some_and(|v| (u + v - 1.0).abs() <= 1e-9), "{u} {v:?}");
        }
    }

    #[test]
    fn solid_angle_is_bounded_and_odd_in_the_winding(t in triangle(), p in point(), s in scale()) {
        let t = scaled(&t, s);
        let p = Point::from(p.coords * s);
        let w = solid_angle(&t, &p);
        let r = solid_angle(&[t[0], t[2], t[1]], &p);
        prop_assert!(w.is_finite() && w.abs() <= 2.0 * PI + 1e-12, "{w}");
        prop_assert!((w + r).abs() <= 1e-9, "{w} {r}");
    }
}

// -- single mesh -----------------------------------------------------------------------------

/// A coordinate for raw soups: ordinary, extreme or not finite.
fn raw_coordinate() -> impl Strategy<Value = Real> {
    prop_oneof![
        8 => coordinate(),
        1 => Just(Real::NAN),
        1 => Just(Real::INFINITY),
        1 => Just(1e300),
        1 => Just(-1e-300),
    ]
}

proptest! {
    #![proptest_config(config(CASES_MESH))]

    #[test]
    fn mesh_construction_never_panics_and_queries_stay_finite(
        v in prop::collection::vec((raw_coordinate(), raw_coordinate(), raw_coordinate()), 0..10),
        t in prop::collection::vec((0u32..12, 0u32..12, 0u32..12), 0..10),
        q in point(),
        dir in point(),
    ) {
        let v: Vec<Point> = v.into_iter().map(|(x, y, z)| Point::new(x, y, z)).collect();
        let t: Vec<[u32; 3]> = t.into_iter().map(|(a, b, c)| [a, b, c]).collect();
        match MeshShape::new(v, t) {
            Err(e) => prop_assert!(e.kind == ErrorKind::Mesh, "{e:?}"),
            Ok(m) => {
                let w = m.winding_number(&q);
                prop_assert!(w.is_finite(), "winding number {w}");
                if dir.coords.norm() > 0.0 {
                    let d = dir.coords.normalize();
                    let hits = m.ray_hits(&q, &d, 1e3);
                    prop_assert!(hits.iter().all(|h| h.is_finite() && *h >= 0.0 && *h <= 1e3));
                    prop_assert!(hits.windows(2).all(|w| w[0] <= w[1]), "{hits:?}");
                }
                match solid_properties(m.vertices(), m.triangles()) {
                    Ok(p) => {
                        prop_assert!(p.volume.is_finite() && p.volume != 0.0);
                        prop_assert!(finite_point(&p.centroid));
                        prop_assert!(p.inertia.iter().all(|x| x.is_finite()));
                    }
                    Err(e) => prop_assert!(e.kind == ErrorKind::Mesh, "{e:?}"),
                }
            }
        }
    }

    #[test]
    fn a_box_has_volume_lwh_and_winds_once_inside(
        h in (1e-3..10.0f64, 1e-3..10.0f64, 1e-3..10.0f64),
        r in rotation(),
        c in point(),
        s in scale(),
        q in (-1.5..1.5f64, -1.5..1.5f64, -1.5..1.5f64),
    ) {
        let h = Vector::new(h.0, h.1, h.2) * s;
        let b = MeshShape::cuboid(Vector::zeros(), h);
        let pose = Isometry::from_parts(nalgebra::Translation3::from(c.coords * s), r);
        let v: Vec<Point> = b.vertices().iter().map(|p| pose * p).collect();
        let p = solid_properties(&v, b.triangles()).unwrap();
        let volume = 8.0 * h.x * h.y * h.z;
        prop_assert!((p.volume - volume).abs() <= 1e-9 * volume, "{} vs {volume}", p.volume);
        prop_assert!((p.centroid - pose.translation.vector).coords.norm() <= 1e-9 * h.norm() + 1e-9 * c.coords.norm() * s);
        // Winding number: 1 inside, 0 outside, away from the surface.
        let local = Point::new(q.0 * h.x, q.1 * h.y, q.2 * h.z);
        let inside = q.0.abs() < 0.99 && q.1.abs() < 0.99 && q.2.abs() < 0.99;
        let outside = q.0.abs() > 1.01 || q.1.abs() > 1.01 || q.2.abs() > 1.01;
        let w = b.winding_number(&local);
        if inside {
            prop_assert!((w - 1.0).abs() < 1e-6, "{w}");
        } else if outside {
            prop_assert!(w.abs() < 0.1, "{w}");
            prop_assert!(!b.contains_point(&local));
        }
        // A ray from outside along x through the interior hits two walls.
        if q.1.abs() < 0.99 && q.2.abs() < 0.99 {
            let from = Point::new(-2.0 * h.x, local.y, local.z);
            let hits = b.ray_hits(&from, &Vector::x(), 10.0 * h.x);
            prop_assert_eq!(hits.len(), 2, "{:?}", hits);
        }
    }
}

// -- two meshes ------------------------------------------------------------------------------

proptest! {
    #![proptest_config(config(CASES_PAIR))]

    #[test]
    fn two_mesh_queries_agree_with_each_other_and_with_the_swap(
        m1 in mesh(), p1 in pose(), m2 in mesh(), p2 in pose()
    ) {
        let mut ws = QueryWorkspace::default();
        let d12 = surface_distance(&m1, &p1, &m2, &p2, 1e9, &mut ws);
        let d21 = surface_distance(&m2, &p2, &m1, &p1, 1e9, &mut ws);
        prop_assert!(d12.is_finite() && d12 >= 0.0, "{d12}");
        prop_assert!((d12 - d21).abs() <= 1e-9, "{d12} {d21}");
        let crossing = surfaces_intersect(&m1, &p1, &m2, &p2, &mut ws);
        prop_assert_eq!(crossing, surfaces_intersect(&m2, &p2, &m1, &p1, &mut ws));
        let overlap = shapes_overlap(&m1, &p1, &m2, &p2, &mut ws);
        prop_assert_eq!(overlap, shapes_overlap(&m2, &p2, &m1, &p1, &mut ws));
        let r12 = overlap_region(&m1, &p1, &m2, &p2);
        let r21 = overlap_region(&m2, &p2, &m1, &p1);
        for r in [&r12, &r21] {
            prop_assert!(r.points.iter().all(finite_point));
            prop_assert!(r.area_normal_1_in_2.iter().all(|x| x.is_finite()));
            prop_assert!(r.area_normal_2_in_1.iter().all(|x| x.is_finite()));
        }
        if crossing {
            prop_assert_eq!(d12, 0.0);
            prop_assert!(overlap);
            prop_assert!(r12.segment_count > 0 && !r12.is_empty());
        }
        prop_assert!(
            !(overlap && r12.is_empty() && m1.is_closed() && m2.is_closed()),
            "shapes_overlap but the region is empty"
        );
        if m1.is_closed() && m2.is_closed() {
            prop_assert_eq!(overlap, !r12.is_empty(), "shapes_overlap vs the region");
        }
        // The swap: the same region (its extent; in degenerate contact a band-edge touch or a
        // vertex on the other surface can be counted in one order and not the other, inside
        // the same extent), the vector areas exchanged.
        if m1.is_closed() && m2.is_closed() {
            // (Not yet for open meshes: a long run found a single open triangle lying on a
            // box's face that overlaps in one order only; see the report of issue 10.)
            prop_assert_eq!(r12.is_empty(), r21.is_empty());
        }
        let tol = 1e-9;
        prop_assert!((r12.area_normal_1_in_2 - r21.area_normal_2_in_1).norm() <= tol);
        prop_assert!((r12.area_normal_2_in_1 - r21.area_normal_1_in_2).norm() <= tol);
        if !r12.is_empty() {
            let bb = |r: &crashsim_core::overlap::OverlapRegion| {
                r.points.iter().fold((r.points[0], r.points[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)))
            };
            let ((lo1, hi1), (lo2, hi2)) = (bb(&r12), bb(&r21));
            prop_assert!((lo1 - lo2).norm() <= tol && (hi1 - hi2).norm() <= tol);
        }
    }

    #[test]
    fn a_mesh_far_from_itself_does_not_overlap(m in mesh(), p in pose(), dir in rotation()) {
        let far = m.radius() * 2.0 + 1.0;
        let shift = dir * Vector::x() * far;
        let q = Isometry::from_parts(
            nalgebra::Translation3::from(p.translation.vector + shift),
            p.rotation,
        );
        let mut ws = QueryWorkspace::default();
        prop_assert!(overlap_region(&m, &p, &m, &q).is_empty());
        prop_assert!(!shapes_overlap(&m, &p, &m, &q, &mut ws));
        prop_assert!(!surfaces_intersect(&m, &p, &m, &q, &mut ws));
        prop_assert!(surface_distance(&m, &p, &m, &q, 1e9, &mut ws) >= 1.0 - 1e-9);
    }

    #[test]
    fn closed_meshes_in_general_position_bound_their_overlap(
        m1 in closed_mesh(), m2 in closed_mesh(),
        t in (-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64), r1 in rotation(), r2 in rotation()
    ) {
        // The overlap of two closed solids is closed: the part of 1's surface inside 2 and
        // of 2's inside 1 together have zero vector area.
        let p1 = Isometry::from_parts(nalgebra::Translation3::identity(), r1);
        let p2 = Isometry::from_parts(nalgebra::Translation3::new(t.0, t.1, t.2), r2);
        let r = overlap_region(&m1, &p1, &m2, &p2);
        let sum = r.area_normal_1_in_2 + r.area_normal_2_in_1;
        let scale = r.area_normal_1_in_2.norm() + r.area_normal_2_in_1.norm() + 1.0;
        prop_assert!(sum.norm() <= 1e-9 * scale, "{} + {} = {sum}", r.area_normal_1_in_2, r.area_normal_2_in_1);
    }

    #[test]
    fn axis_aligned_boxes_overlap_in_their_intersection_box(
        h1 in (1i32..=8, 1i32..=8, 1i32..=8), h2 in (1i32..=8, 1i32..=8, 1i32..=8),
        c in (-12i32..=12, -12i32..=12, -12i32..=12), r1 in axis_rotation(), r2 in axis_rotation()
    ) {
        // Boxes on a quarter-metre grid, turned by quarter turns (so by rotations exact only to
        // round-off): coplanar faces and touches everywhere. The region's box is the
        // intersection box; touching boxes do not overlap.
        let quarter = |(x, y, z): (i32, i32, i32)| Vector::new(x as Real, y as Real, z as Real) * 0.25;
        let (h1, h2) = (quarter(h1), quarter(h2));
        let (b1, b2) = (MeshShape::cuboid(Vector::zeros(), h1), MeshShape::cuboid(Vector::zeros(), h2));
        let p1 = Isometry::from_parts(nalgebra::Translation3::identity(), r1);
        let p2 = Isometry::from_parts(nalgebra::Translation3::from(quarter(c)), r2);
        let extent = |r: &Rotation, h: &Vector| (r.to_rotation_matrix().matrix().abs() * h).map(|x| x.round_to_quarter());
        let (e1, e2) = (extent(&r1, &h1), extent(&r2, &h2));
        let lo = (-e1).sup(&(quarter(c) - e2));
        let hi = e1.inf(&(quarter(c) + e2));
        let gap = hi - lo;
        let r = overlap_region(&b1, &p1, &b2, &p2);
        let mut ws = QueryWorkspace::default();
        let overlap = shapes_overlap(&b1, &p1, &b2, &p2, &mut ws);
        if gap.min() > 0.0 {
            prop_assert!(overlap && !r.is_empty());
            let (rlo, rhi) = r.points.iter().fold((r.points[0], r.points[0]), |(a, b), p| (a.inf(p), b.sup(p)));
            prop_assert!((rlo.coords - lo).norm() <= 1e-9 && (rhi.coords - hi).norm() <= 1e-9,
                "region [{rlo}, {rhi}] vs [{lo}, {hi}]");
            let n = r.volume_normal();
            prop_assert!(n.is_none_or(|n| n.iter().all(|x| x.is_finite())));
        } else {
            prop_assert!(!overlap, "gap {gap}");
            prop_assert!(r.is_empty(), "gap {gap}: {} points", r.points.len());
        }
    }
}

/// Rounding of the rotated half extents (quarter turns leave 1e-16 of round-off).
trait RoundToQuarter {
    fn round_to_quarter(self) -> Self;
}

impl RoundToQuarter for Real {
    fn round_to_quarter(self) -> Real {
        (self * 4.0).round() / 4.0
    }
}
