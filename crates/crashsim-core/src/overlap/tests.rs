//! Tests of the overlap queries.

use super::region::{overlap_region_with, RegionParts};
use super::*;
use crate::math::{Isometry, Point, Real, Rotation, Vector};
use crate::shape::tests::{box_mesh, without_top};
use crate::shape::MeshShape;

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
fn patch_classification_equals_the_per_triangle_one_and_the_points_alone_are_the_regions() {
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
    let open = without_top(&other, 0.59);
    assert!(!open.is_closed());
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
        let a = overlap_region_with(&car, &id, &other, &pose2, true, RegionParts::All);
        let b = overlap_region_with(&car, &id, &other, &pose2, false, RegionParts::All);
        assert_eq!(a.points.len(), b.points.len());
        for (p, q) in a.points.iter().zip(&b.points) {
            assert_eq!(p, q);
        }
        assert!((a.area_normal_1_in_2 - b.area_normal_1_in_2).norm() < 1e-12);
        assert!((a.area_normal_2_in_1 - b.area_normal_2_in_1).norm() < 1e-12);
        // The point set alone is the region's, bit for bit, against the closed mesh and
        // against it opened (its top face gone: each triangle and vertex decided alone).
        for mesh in [&other, &open] {
            let full = overlap_region(&car, &id, mesh, &pose2);
            let points = overlap_points(&car, &id, mesh, &pose2);
            assert_eq!(full.points, points.points);
            assert_eq!(
                (
                    full.segment_count,
                    full.inside_vertex_count,
                    full.inside_1_count
                ),
                (
                    points.segment_count,
                    points.inside_vertex_count,
                    points.inside_1_count
                )
            );
            assert_eq!(points.area_normal_1_in_2, Vector::zeros());
            // The vector areas alone are the region's, bit for bit, with no points.
            let areas = overlap_areas(&car, &id, mesh, &pose2);
            assert_eq!(
                (areas.area_normal_1_in_2, areas.area_normal_2_in_1),
                (full.area_normal_1_in_2, full.area_normal_2_in_1)
            );
            assert!(areas.points.is_empty() && areas.inside_vertex_count == 0);
        }
        overlapping += usize::from(!a.points.is_empty());
    }
    assert!(overlapping > 20, "{overlapping}");
}
