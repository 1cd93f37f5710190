//! Coplanar contact: faces that are coplanar in the scene (equal heights and widths, a common
//! ground plane, a heading of 180 deg) are classified consistently and symmetrically. Mirror
//! images give mirrored results to round-off; touching surfaces do not overlap.
//! Frames and units: world frame, m; boxes are given by half extents.

use std::f64::consts::PI;
use std::sync::Arc;

use crashsim_core::math::{Isometry, Matrix, Point, Real, Rotation, Vector};
use crashsim_core::overlap::{
    overlap_region, shapes_overlap, surface_distance, surfaces_intersect, OverlapRegion,
    QueryWorkspace,
};
use crashsim_core::{
    BodyState, ContactParams, DepthOfPenetration, Face, FaceStiffness, MassProperties, MeshShape,
    Stiffness, World,
};

/// A closed box mesh centred on its body origin with half extents (hx, hy, hz).
fn cuboid(hx: Real, hy: Real, hz: Real) -> MeshShape {
    MeshShape::cuboid(Vector::zeros(), Vector::new(hx, hy, hz))
}

/// The pose at (x, y, z) turned by `yaw` about z.
fn at(x: Real, y: Real, z: Real, yaw: Real) -> Isometry {
    Isometry::from_parts(
        nalgebra::Translation3::new(x, y, z),
        Rotation::from_axis_angle(&Vector::z_axis(), yaw),
    )
}

/// The reflection through the plane x = 0 (axis 0) or y = 0 (axis 1).
fn reflection(axis: usize) -> Matrix {
    let mut m = Matrix::identity();
    m[(axis, axis)] = -1.0;
    m
}

/// The mirror image of a mesh by the reflection `m` (its triangles rewound, so it stays
/// outward).
fn mirror_mesh(mesh: &MeshShape, m: &Matrix) -> MeshShape {
    let v = mesh
        .vertices()
        .iter()
        .map(|p| Point::from(m * p.coords))
        .collect();
    let t = mesh
        .triangles()
        .iter()
        .map(|t| [t[0], t[2], t[1]])
        .collect();
    MeshShape::new(v, t).unwrap()
}

/// The pose of the mirrored body: rotation m R m, position m t.
fn mirror_pose(pose: &Isometry, m: &Matrix) -> Isometry {
    let r = m * pose.rotation.to_rotation_matrix().into_inner() * m;
    Isometry::from_parts(
        nalgebra::Translation3::from(m * pose.translation.vector),
        Rotation::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(r)),
    )
}

/// Lower and upper corners of the region's point set (world).
fn bounds(r: &OverlapRegion) -> (Vector, Vector) {
    let (mut lo, mut hi) = (r.points[0].coords, r.points[0].coords);
    for p in &r.points {
        lo = lo.inf(&p.coords);
        hi = hi.sup(&p.coords);
    }
    (lo, hi)
}

/// The reflected bounds of a point set.
fn mirror_bounds((lo, hi): (Vector, Vector), m: &Matrix) -> (Vector, Vector) {
    let (a, b) = (m * lo, m * hi);
    (a.inf(&b), a.sup(&b))
}

/// Angle (rad) between two directions.
fn angle(a: &Vector, b: &Vector) -> Real {
    a.cross(b).norm().atan2(a.dot(b))
}

/// Two equal 4.5 x 1.8 x 1.4 m boxes head-on on the ground, the second turned 180 deg,
/// `depth` m into each other: their sides, tops and bottoms are coplanar.
fn head_on(depth: Real) -> (MeshShape, Isometry, MeshShape, Isometry) {
    let m = cuboid(2.25, 0.9, 0.7);
    let h = 0.5 * depth;
    (
        m.clone(),
        at(-2.25 + h, 0.0, 0.7, 0.0),
        m,
        at(2.25 - h, 0.0, 0.7, PI),
    )
}

#[test]
fn a_symmetric_head_on_gives_the_axis_normal_and_the_true_width() {
    // Regression (issue 10, item 5): two identical boxes head-on. The 180 deg turn is exact
    // only to round-off, so the coplanar sides, tops and bottoms crossed at arbitrary places
    // (1e-16 rad apart): half of a front face was lost, the normal came out 1.27 deg off the
    // axis and the overlap width 1.8095 m instead of 1.8.
    for depth in [1e-6, 0.02, 0.45, 0.9] {
        let (a, pa, b, pb) = head_on(depth);
        let r = overlap_region(&a, &pa, &b, &pb);
        let n = r.volume_normal().unwrap();
        assert!(angle(&n, &Vector::x()) < 1e-9, "depth {depth}: normal {n}");
        // Each front face (1.8 x 1.4) is inside the other box, nothing else is left over.
        assert!((r.area_normal_1_in_2 - Vector::x() * 2.52).norm() < 1e-9);
        assert!((r.area_normal_2_in_1 + Vector::x() * 2.52).norm() < 1e-9);
        let (lo, hi) = bounds(&r);
        assert!((hi.y - lo.y - 1.8).abs() < 1e-9, "width {}", hi.y - lo.y);
        assert!((hi.z - lo.z - 1.4).abs() < 1e-9 && lo.z.abs() < 1e-9);
        assert!((hi.x - lo.x - depth).abs() < 1e-9, "depth {}", hi.x - lo.x);
        assert!((hi.x + lo.x).abs() < 1e-9);
    }
}

/// A 1450 kg box 4.5 x 1.8 x 1.4 m with the given state.
fn add_box(w: &mut World, x: Real, yaw: Real, vx: Real) {
    let (m, l, wd, h) = (1450.0, 4.5, 1.8, 1.4);
    let inertia = Matrix::from_diagonal(&Vector::new(
        m / 12.0 * (wd * wd + h * h),
        m / 12.0 * (l * l + h * h),
        m / 12.0 * (l * l + wd * wd),
    ));
    w.add_body(
        Arc::new(cuboid(2.25, 0.9, 0.7)),
        MassProperties::new(m, inertia).unwrap(),
        &BodyState {
            position: Point::new(x, 0.0, 0.7),
            orientation: Rotation::from_axis_angle(&Vector::z_axis(), yaw),
            velocity: Vector::new(vx, 0.0, 0.0),
            angular_velocity: Vector::zeros(),
        },
    )
    .unwrap();
}

#[test]
fn a_symmetric_head_on_run_gives_the_axis_normal_width_and_automatic_depth() {
    // The same head-on through the engine (15 m/s each, automatic depth of penetration): the
    // normal is the axis, W = 1.8 m, and dt_p = sqrt(m' / k') with m' = 725 kg and
    // k' = B W / 2 (equal faces in series); before the fix W was 0.6 % too wide.
    let (a_coef, b_coef) = (64_000.0, 769_000.0);
    let face = FaceStiffness::new(a_coef, b_coef).unwrap();
    let stiff = Stiffness::none()
        .with(Face::Front, face)
        .with(Face::Rear, face)
        .with(Face::Left, face)
        .with(Face::Right, face);
    let mut w = World::new();
    add_box(&mut w, -3.0, 0.0, 15.0);
    add_box(&mut w, 3.0, PI, -15.0);
    w.set_stiffness(0, stiff.clone()).unwrap();
    w.set_stiffness(1, stiff).unwrap();
    w.set_contact(
        0,
        1,
        ContactParams {
            depth_of_penetration: DepthOfPenetration::Auto,
            ..ContactParams::default()
        },
    )
    .unwrap();
    let out = w.run(0.2, 1e-3).unwrap();
    let imp = &out.impacts[0];
    assert!(angle(&imp.normal, &Vector::x()) < 1e-9, "{}", imp.normal);
    assert!(
        (imp.overlap_width - 1.8).abs() < 1e-9,
        "{}",
        imp.overlap_width
    );
    assert!((imp.region_max.y + imp.region_min.y).abs() < 1e-9);
    let expected = (725.0 / (b_coef * 1.8 / 2.0)).sqrt();
    // Bisection to 1e-9 s.
    assert!(
        (imp.depth_of_penetration - expected).abs() < 2e-9,
        "dt_p {} vs {expected}",
        imp.depth_of_penetration
    );
}

/// Checks that the region of the boxes (b1 at p1, b2 at p2), reflected through x = 0 or
/// y = 0, is the region of the reflected configuration, also with the bodies swapped (the
/// normal then reverses). The reflected bodies are the reflected meshes, and the unreflected
/// ones (a box centred on its origin is its own mirror image as a solid, though not as a
/// triangulation): so the result must not depend on the triangulation either.
fn assert_mirror_image(b1: &MeshShape, p1: &Isometry, b2: &MeshShape, p2: &Isometry) {
    let r = overlap_region(b1, p1, b2, p2);
    assert!(!r.is_empty());
    let n = r.volume_normal().unwrap();
    let bb = bounds(&r);
    for (axis, swap, remesh) in [
        (1, false, true),
        (0, false, true),
        (0, true, true),
        (1, true, true),
        (1, false, false),
        (0, true, false),
    ] {
        let m = reflection(axis);
        let (m1, m2) = if remesh {
            (mirror_mesh(b1, &m), mirror_mesh(b2, &m))
        } else {
            (b1.clone(), b2.clone())
        };
        let (q1, q2) = (mirror_pose(p1, &m), mirror_pose(p2, &m));
        let (rm, sign) = if swap {
            (overlap_region(&m2, &q2, &m1, &q1), -1.0)
        } else {
            (overlap_region(&m1, &q1, &m2, &q2), 1.0)
        };
        let what = format!("reflected through axis {axis}, swapped {swap}, remeshed {remesh}");
        let nm = rm.volume_normal().unwrap();
        assert!((nm - m * n * sign).norm() < 1e-12, "{what}: {nm} vs {n}");
        let (a12, a21) = if swap {
            (rm.area_normal_2_in_1, rm.area_normal_1_in_2)
        } else {
            (rm.area_normal_1_in_2, rm.area_normal_2_in_1)
        };
        assert!((a12 - m * r.area_normal_1_in_2).norm() < 1e-12, "{what}");
        assert!((a21 - m * r.area_normal_2_in_1).norm() < 1e-12, "{what}");
        let (lo, hi) = bounds(&rm);
        let (elo, ehi) = mirror_bounds(bb, &m);
        assert!(
            (lo - elo).norm() < 1e-12 && (hi - ehi).norm() < 1e-12,
            "{what}: [{lo}, {hi}] vs [{elo}, {ehi}]"
        );
    }
}

#[test]
fn mirror_images_give_mirrored_normals_and_regions() {
    // The head-on (coplanar sides, tops and bottoms), at the normal's depth and deep.
    for depth in [0.02, 0.45] {
        let (a, pa, b, pb) = head_on(depth);
        assert_mirror_image(&a, &pa, &b, &pb);
    }
    // Boxes on a common ground, one 0.3 m into the other's rear with a lateral offset.
    let car = cuboid(2.25, 0.9, 0.7);
    let low = cuboid(2.1, 0.85, 0.6);
    assert_mirror_image(
        &car,
        &at(-4.05, 0.4, 0.7, 0.0),
        &low,
        &at(0.0, 0.0, 0.6, 0.0),
    );
    // A 50 % offset frontal with the 180 deg turn (coplanar tops, bottoms and one side pair).
    let (a, _, b, pb) = head_on(0.02);
    assert_mirror_image(&a, &at(-2.24, 0.9, 0.7, 0.0), &b, &pb);
    // Oblique, tilted, nothing coplanar.
    let tilted = Isometry::from_parts(
        nalgebra::Translation3::new(3.1, 0.8, 0.9),
        Rotation::from_euler_angles(0.05, -0.08, 2.4),
    );
    assert_mirror_image(&car, &at(0.0, 0.0, 0.7, 0.1), &low, &tilted);
}

#[test]
fn coplanar_sides_with_small_offsets() {
    // Head-on 2 cm deep; the second box's sides set in by `off` (narrower by 2 off) or the
    // second box moved sideways by `off`. Offsets within the plane band (about 1e-12 of the
    // coordinates' size) count as coplanar; larger ones are taken as they are.
    let a = cuboid(2.25, 0.9, 0.7);
    let (pa, pb) = (at(-2.24, 0.0, 0.7, 0.0), at(2.24, 0.0, 0.7, PI));
    for off in [0.0, 1e-12, 1e-9, 1e-6, 1e-3] {
        // Set in: symmetric whatever the offset.
        let b = cuboid(2.25, 0.9 - off, 0.7);
        let r = overlap_region(&a, &pa, &b, &pb);
        let n = r.volume_normal().unwrap();
        assert!(angle(&n, &Vector::x()) < 1e-9, "set in {off}: {n}");
        let (lo, hi) = bounds(&r);
        assert!(
            (hi.y - lo.y - (1.8 - 2.0 * off)).abs() < 1e-9,
            "set in {off}"
        );
        assert!((hi.y + lo.y).abs() < 1e-9 && (hi.z - lo.z - 1.4).abs() < 1e-9);
        // Moved sideways: one side strip of each box is inside the other, so the normal
        // turns by atan(depth / (1.8 - off)) (the definition: the area-weighted normal of
        // the surface inside), except within the band, where the sides are coplanar.
        let r = overlap_region(&a, &pa, &a, &at(2.24, off, 0.7, PI));
        let n = r.volume_normal().unwrap();
        let expected = if off < 1e-11 {
            0.0
        } else {
            (0.02 / (1.8 - off)).atan()
        };
        let turn = n.y.atan2(n.x);
        assert!((turn - expected).abs() < 1e-9, "moved {off}: {turn}");
        assert!(n.z.abs() < 1e-12, "moved {off}: {n}");
        let (lo, hi) = bounds(&r);
        assert!((hi.y - lo.y - (1.8 - off)).abs() < 1e-9, "moved {off}");
        assert!((lo.y - (-0.9 + off)).abs() < 1e-9 && (hi.y - 0.9).abs() < 1e-9);
    }
}

#[test]
fn boxes_on_a_common_ground_keep_a_horizontal_normal() {
    // Bottoms coplanar on z = 0; the second box lower (its top is not coplanar) and turned by
    // 180 deg (coplanar to round-off), or the same height (tops coplanar too).
    let car = cuboid(2.25, 0.9, 0.7);
    for (hz, yaw) in [(0.6, PI), (0.7, PI), (0.6, 0.0), (0.7, 0.0)] {
        let other = cuboid(2.1, 0.85, hz);
        let r = overlap_region(
            &car,
            &at(-4.05, 0.0, 0.7, 0.0),
            &other,
            &at(0.0, 0.0, hz, yaw),
        );
        let n = r.volume_normal().unwrap();
        let horizontal = Vector::new(n.x, n.y, 0.0).normalize();
        assert!(angle(&horizontal, &Vector::x()) < 1e-9, "{hz} {yaw}: {n}");
        // Front face of 1 inside 2 and rear face of 2 inside 1: 1.7 m x (2 hz) each.
        assert!((r.area_normal_1_in_2.x - 1.7 * 2.0 * hz).abs() < 1e-9);
        assert!((r.area_normal_2_in_1.x + 1.7 * 2.0 * hz).abs() < 1e-9);
        let (lo, hi) = bounds(&r);
        assert!((lo.y + 0.85).abs() < 1e-9 && (hi.y - 0.85).abs() < 1e-9);
        assert!((lo.x + 2.1).abs() < 1e-9 && (hi.x + 1.8).abs() < 1e-9);
        assert!(lo.z.abs() < 1e-9 && (hi.z - 2.0 * hz).abs() < 1e-9);
    }
}

#[test]
fn touching_surfaces_do_not_overlap() {
    // Face to face (front on front, the second turned 180 deg), a box resting on another, and
    // two boxes side by side on the ground touching along a side: distance 0, no crossing,
    // no region, no overlap.
    let a = cuboid(2.25, 0.9, 0.7);
    let mut ws = QueryWorkspace::default();
    let cases = [
        (at(-2.25, 0.0, 0.7, 0.0), at(2.25, 0.0, 0.7, PI)),
        (at(0.0, 0.0, 0.7, 0.0), at(0.3, 0.2, 2.1, 0.0)),
        (at(0.0, 0.0, 0.7, 0.0), at(1.0, 1.8, 0.7, PI)),
    ];
    for (i, (p1, p2)) in cases.iter().enumerate() {
        assert_eq!(surface_distance(&a, p1, &a, p2, 1.0, &mut ws), 0.0, "{i}");
        assert!(!surfaces_intersect(&a, p1, &a, p2, &mut ws), "{i}");
        assert!(!shapes_overlap(&a, p1, &a, p2, &mut ws), "{i}");
        assert!(overlap_region(&a, p1, &a, p2).is_empty(), "{i}");
    }
    // A small box standing inside a big one on its floor (coplanar bottoms, same
    // orientation): that is an overlap, the small box's vertices are all in the region. The
    // surfaces cross: the big box's floor, nudged into its solid, is cut by the small box.
    let small = cuboid(0.5, 0.4, 0.3);
    let (p1, p2) = (at(0.0, 0.0, 0.7, 0.0), at(0.2, 0.1, 0.3, PI));
    assert!(surfaces_intersect(&a, &p1, &small, &p2, &mut ws));
    assert!(shapes_overlap(&a, &p1, &small, &p2, &mut ws));
    assert!(shapes_overlap(&small, &p2, &a, &p1, &mut ws));
    let r = overlap_region(&a, &p1, &small, &p2);
    let (lo, hi) = bounds(&r);
    assert!((lo - Vector::new(-0.3, -0.3, 0.0)).norm() < 1e-12, "{lo}");
    assert!((hi - Vector::new(0.7, 0.5, 0.6)).norm() < 1e-12, "{hi}");
}
