//! Face stiffness (issue 4): the automatic depth of penetration, the stiffness centroid
//! and the rule that both need every face of both bodies (a fixed obstacle without any
//! is rigid). A module of the engine tests; the helpers are theirs.

use super::*;

// -- face stiffness: automatic depth of penetration and the stiffness centroid ----------------

/// Every face of a vehicle with the same A and the given B (N/m^2) front, rear, sides.
pub(super) fn stiffness(front: Real, rear: Real, side: Real) -> Stiffness {
    let f = |b| FaceStiffness::new(35_000.0, b).unwrap();
    Stiffness::none()
        .with(Face::Front, f(front))
        .with(Face::Rear, f(rear))
        .with(Face::Left, f(side))
        .with(Face::Right, f(side))
}

/// A 1500 kg, 4.5 x 1.8 x 1.4 m box at `v` m/s (+x) into the rear of a 1200 kg,
/// 4.2 x 1.7 x 1.2 m box at rest, both CGs at 0.7 m height on the x axis: an in-line,
/// central impact with the overlap 1.7 m wide (the narrower box). (No faces are coplanar.)
fn rear_end_scene(v: Real, b_front1: Real, b_rear2: Real, params: ContactParams) -> World {
    let mut w = World::new();
    add_box(
        &mut w,
        1500.0,
        (4.5, 1.8, 1.4),
        &state(-4.5, 0.0, 0.7, 0.0, Vector::new(v, 0.0, 0.0)),
    );
    add_box(
        &mut w,
        1200.0,
        (4.2, 1.7, 1.2),
        &state(0.0, 0.0, 0.7, 0.0, Vector::zeros()),
    );
    w.set_stiffness(0, stiffness(b_front1, 0.8e6, 0.5e6))
        .unwrap();
    w.set_stiffness(1, stiffness(1.1e6, b_rear2, 0.5e6))
        .unwrap();
    w.set_contact(0, 1, params).unwrap();
    w
}

#[test]
fn automatic_depth_of_penetration_is_sqrt_of_reduced_mass_over_series_stiffness() {
    let (v, b1, b2, width) = (15.0, 1.0e6, 0.6e6, 1.7);
    let params = ContactParams {
        depth_of_penetration: DepthOfPenetration::Auto,
        ..ContactParams::default()
    };
    for dt in [1e-3, 7e-3] {
        let mut w = rear_end_scene(v, b1, b2, params.clone());
        let out = w.run(0.5, dt).unwrap();
        let imp = &out.impacts[0];
        let (k1, k2) = (b1 * width, b2 * width);
        let m_reduced = 1500.0 * 1200.0 / 2700.0;
        let expected = (m_reduced / (k1 * k2 / (k1 + k2))).sqrt();
        // Bisection to 1e-9 s.
        assert!(
            (imp.depth_of_penetration - expected).abs() < 2e-9,
            "dt_p {} vs {expected}",
            imp.depth_of_penetration
        );
        assert_eq!(imp.depth_of_penetration_mode, DepthOfPenetration::Auto);
        assert_eq!(imp.struck_faces, [Face::Front, Face::Rear]);
        assert!((imp.overlap_width - width).abs() < 1e-12);
        let [r1, r2] = imp.spring_rates.unwrap();
        assert!((r1 - k1).abs() < 1e-6 && (r2 - k2).abs() < 1e-6);
        // Central impact: the effective masses are the masses.
        assert!((imp.effective_mass[0] - 1500.0).abs() < 1e-9 * 1500.0);
        assert!((imp.effective_mass[1] - 1200.0).abs() < 1e-9 * 1200.0);
        // The bullet travels v dt_p past the first overlap (1 um).
        let x_at = |t: Real| {
            let k = out.times.iter().rposition(|&s| s == t).unwrap();
            out.sample(k)[0].position.x
        };
        let travel = x_at(imp.time) - x_at(imp.first_contact_time);
        assert!((travel - v * expected).abs() < 1e-6, "travel {travel}");
        assert!(imp.notes.is_empty(), "{:?}", imp.notes);
    }
}

#[test]
fn automatic_depth_of_penetration_is_clamped_to_60_ms_with_a_note() {
    // Very soft faces: sqrt(m'/k') is about 0.26 s.
    let params = ContactParams {
        depth_of_penetration: DepthOfPenetration::Auto,
        ..ContactParams::default()
    };
    let mut w = rear_end_scene(15.0, 1.0e4, 1.0e4, params);
    let out = w.run(0.5, 1e-3).unwrap();
    let imp = &out.impacts[0];
    assert!((imp.depth_of_penetration - 0.060).abs() < 1e-12);
    assert_eq!(imp.notes.len(), 1);
    assert!(imp.notes[0].contains("clamped"), "{:?}", imp.notes);
}

#[test]
fn stiffness_centroid_splits_the_crush_as_k2_to_k1() {
    let (v, dtp, width) = (15.0, 0.030, 1.7);
    for (b1, b2) in [(1.0e6, 0.6e6), (0.7e6, 0.7e6), (0.3e6, 1.2e6)] {
        let params = ContactParams {
            depth_of_penetration: DepthOfPenetration::Fixed(dtp),
            centroid: CentroidMode::Stiffness,
            ..ContactParams::default()
        };
        let mut w = rear_end_scene(v, b1, b2, params);
        let out = w.run(0.5, 1e-3).unwrap();
        let imp = &out.impacts[0];
        let (k1, k2) = (b1 * width, b2 * width);
        // Bullet front at the exchange: its CG x + 2.25; struck rear face at -2.1.
        let k = out.times.iter().rposition(|&s| s == imp.time).unwrap();
        let front1 = out.sample(k)[0].position.x + 2.25;
        let rear2 = -2.1;
        let total = front1 - rear2;
        assert!((total - v * dtp).abs() < 1e-6, "total crush {total}");
        let c1 = front1 - imp.centroid.x;
        let c2 = imp.centroid.x - rear2;
        assert!((c1 - k2 / (k1 + k2) * total).abs() < 1e-9, "C1 {c1}");
        assert!((c2 - k1 / (k1 + k2) * total).abs() < 1e-9, "C2 {c2}");
        // Across the contact: the centre of the overlap in y and z.
        assert!(imp.centroid.y.abs() < 1e-12 && (imp.centroid.z - 0.7).abs() < 1e-12);
    }
}

#[test]
fn stiffness_modes_need_stiffness_on_both_vehicles() {
    for params in [
        ContactParams {
            depth_of_penetration: DepthOfPenetration::Auto,
            ..ContactParams::default()
        },
        ContactParams {
            centroid: CentroidMode::Stiffness,
            ..ContactParams::default()
        },
    ] {
        let mut w = World::new();
        for x in [-5.0, 0.0] {
            add_box(
                &mut w,
                1500.0,
                (4.5, 1.8, 1.4),
                &state(x, 0.0, 0.7, 0.0, Vector::zeros()),
            );
        }
        w.set_stiffness(0, stiffness(1e6, 1e6, 1e6)).unwrap();
        match w.set_contact(0, 1, params.clone()) {
            Err(e) if e.kind == ErrorKind::Parameter => {
                assert!(e.to_string().contains("body 1: it has no stiffness"), "{e}")
            }
            other => panic!("expected a parameter error, got {other:?}"),
        }
    }
}

/// An obstacle with stiffness on some faces only is not rigid: the stiffness modes still
/// need every face (its message says how to fix it).
#[test]
fn an_obstacle_with_partial_stiffness_is_refused_by_the_stiffness_modes() {
    let mut w = World::new();
    let car = w
        .add_body(
            box_shape(4.6, 1.8, 1.4),
            box_props(1500.0, 4.6, 1.8, 1.4),
            &state(-3.0, 0.0, 0.7, 0.0, Vector::zeros()),
        )
        .unwrap();
    w.set_stiffness(car, stiffness(1e6, 1e6, 1e6)).unwrap();
    let pose = crashsim_core::math::Isometry::translation(0.5, 0.0, 1.0);
    let wall = w.add_obstacle(box_shape(1.0, 6.0, 2.0), &pose).unwrap();
    let rear = FaceStiffness::new(1e5, 5e6).unwrap();
    w.set_stiffness(wall, Stiffness::none().with(Face::Rear, rear))
        .unwrap();
    let params = ContactParams {
        depth_of_penetration: DepthOfPenetration::Auto,
        ..ContactParams::default()
    };
    match w.set_contact(car, wall, params) {
        Err(e) if e.kind == ErrorKind::Parameter => assert!(
            e.to_string()
                .contains("body 1: it has no stiffness on its front face")
                && e.to_string().contains("none at all for a rigid obstacle"),
            "{e}"
        ),
        other => panic!("expected a parameter error, got {other:?}"),
    }
}
