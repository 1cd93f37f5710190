//! Tests of the scene document: JSON round trips and refusals.

use super::*;
use crate::error::{error_kind, ErrorKind};
use crate::joint::{CoupledAngle, JointKind, JointSpec, PassiveMoment, PassiveTerm};

#[test]
fn json_round_trip_runs_the_same_bits() {
    let mut s = crate::spec::tests::head_on();
    s.bodies[1].stiffness =
        Stiffness::none().with(Face::Front, FaceStiffness::new(1.0, 2.0).unwrap());
    let text = to_json(&s);
    let back = from_json(&text).unwrap();
    assert_eq!(to_json(&back), text);
    assert_eq!(back.run().unwrap(), s.run().unwrap());
    // one mesh shared by both bodies is written once
    assert_eq!(document(&s).meshes.len(), 1);
    assert!(Arc::ptr_eq(&back.bodies[0].shape, &back.bodies[1].shape));
}

#[test]
fn every_float_reads_back_bit_for_bit() {
    // Numbers whose shortest decimal the default JSON parser rounded 1 ulp off (a
    // generated sedan's vertices: 0.46650655999999996, -1.9575393560865266, ...).
    let mut s = crate::spec::tests::head_on();
    let awkward = [
        0.46650655999999996,
        -1.9575393560865266,
        0.22477449709999986,
        1.6795116774677465,
        30414.342848110522,
    ];
    if let BodyMotion::Moving { state, .. } = &mut s.bodies[0].motion {
        state.position = Point::new(awkward[0] - 3.0, awkward[1], awkward[2]);
        state.velocity = Vector::new(awkward[3] * 6.0, awkward[4] * 1e-5, 0.0);
    }
    let back = from_json(&to_json(&s)).unwrap();
    let BodyMotion::Moving { state: a, .. } = &s.bodies[0].motion else {
        unreachable!()
    };
    let BodyMotion::Moving { state: b, .. } = &back.bodies[0].motion else {
        unreachable!()
    };
    assert_eq!(a, b);
    assert_eq!(to_json(&back), to_json(&s));
}

#[test]
fn a_bad_document_is_a_typed_error() {
    assert_eq!(error_kind(&from_json("{")), Some(ErrorKind::Parameter));
    let s = crate::spec::tests::head_on();
    let text = to_json(&s).replace("\"restitution\":0.1", "\"restitution\":3.0");
    assert!(from_json(&text)
        .is_err_and(|e| e.kind == ErrorKind::Parameter && e.message.contains("restitution")));
}

#[test]
fn a_joints_passive_moments_round_trip_and_none_are_not_written() {
    let frame = (Point::new(0.1, -0.2, 0.3), Rotation::identity());
    let mut j = JointSpec::new(JointKind::Spherical, 0, Some(1), frame, frame);
    let plain = serde_json::to_string(&joint_doc(&j)).unwrap();
    assert!(!plain.contains("passive"), "{plain}");
    j.passive = vec![
        PassiveMoment {
            angle: 2,
            offset: -0.7418,
            terms: vec![
                PassiveTerm::new(-2.03, 38.11, 0.52),
                PassiveTerm::new(0.18, -12.12, -0.74),
            ],
            constant: 0.1 + 0.2,
        },
        PassiveMoment {
            angle: 0,
            offset: 0.0,
            terms: Vec::new(),
            constant: 1.5,
        },
    ];
    let text = serde_json::to_string(&joint_doc(&j)).unwrap();
    assert!(!text.contains("coupled"), "{text}");
    let back = joint(serde_json::from_str(&text).unwrap()).unwrap();
    assert_eq!(back, j);
    // a term reading another joint's angle (a two-joint muscle's)
    j.passive[0].terms[1]
        .coupled
        .push(CoupledAngle::new("knee_left", "angle", 0.1, -0.5));
    let text = serde_json::to_string(&joint_doc(&j)).unwrap();
    let back = joint(serde_json::from_str(&text).unwrap()).unwrap();
    assert_eq!(back, j);
}

#[test]
fn a_bodys_ground_friction_round_trips_is_checked_and_absent_is_not_written() {
    let mut s = crate::spec::tests::head_on();
    let plain = to_json(&s);
    assert!(!plain.contains("ground_friction"), "{plain}");
    s.set_ground_friction(1, 0.66).unwrap();
    let text = to_json(&s);
    assert!(text.contains("\"ground_friction\":0.66"), "{text}");
    let back = from_json(&text).unwrap();
    assert_eq!(back.bodies[1].ground_friction, Some(0.66));
    assert_eq!(back.bodies[0].ground_friction, None);
    assert_eq!(to_json(&back), text);
    // out of (0, 2], non-finite, an unknown body: typed errors naming what is wrong
    for bad in [0.0, -0.1, 2.5, Real::NAN, Real::INFINITY] {
        let e = s.set_ground_friction(0, bad).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Parameter, "{bad}: {e}");
        assert!(e.message.contains("ground friction"), "{e}");
    }
    assert!(s.set_ground_friction(7, 0.5).is_err());
    let shape = s.bodies[0].shape.clone();
    let k = s.add_obstacle(None, shape, Isometry::identity()).unwrap();
    assert!(s
        .set_ground_friction(k, 0.5)
        .is_err_and(|e| e.message.contains("fixed obstacle")));
    let bad = text.replace("\"ground_friction\":0.66", "\"ground_friction\":3.0");
    assert!(from_json(&bad).is_err_and(|e| e.kind == ErrorKind::Parameter));
}
