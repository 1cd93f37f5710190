//! Passive moments (docs/joints.md, "Passive moments"): the law's value and slope against its
//! closed form, a rod held up on a hinge by one (its energy with the law's potential, its
//! rest where the moment carries its weight), and bad laws refused by name.

use std::f64::consts::PI;

use crashsim_core::ground::Ground;
use crashsim_core::joint::{JointKind, JointSpec, PassiveMoment, PassiveTerm};
use crashsim_core::math::{Point, Real, Rotation, Vector};
use crashsim_core::vehicle::GRAVITY;
use crashsim_core::{RunOutput, World};

use super::{at, energy, horizontal_rod, props_of, rod, DT, HEIGHT};

/// `2 exp(-4 (phi - 0.3)) - 2` N m with phi = 0.3 + the hinge's angle: 0 where the rod starts
/// (horizontal), growing as the rod falls (the angle negative, below).
fn law() -> PassiveMoment {
    PassiveMoment {
        angle: 0,
        offset: 0.3,
        terms: vec![PassiveTerm::new(2.0, -4.0, 0.3)],
        constant: -2.0,
    }
}

/// The law's potential (J) at the hinge's angle `a` (rad), zero at 0: -(integral of M from 0
/// to a), with M(a) = 2 exp(-4 a) - 2 in the angle.
fn potential(a: Real) -> Real {
    0.5 * ((-4.0 * a).exp() - 1.0) + 2.0 * a
}

/// The hinge's angle (rad) at sample `k`: the world's frame against the rod's about the
/// hinge's axis (world y), the rod's pitch p (rotation about y) negated: 0 horizontal, -pi/2
/// hanging straight down.
fn angle(out: &RunOutput, k: usize) -> Real {
    let x = out.sample(k)[0].orientation * Vector::x();
    -(-x.z).atan2(x.x)
}

/// A 1 m, 5 kg rod horizontal on a hinge at its end (the joints' one-link chain) with the
/// law, and `damping` N m s/rad.
fn held_rod(damping: Real) -> World {
    held_rod_on(JointKind::Revolute, 0, damping)
}

/// The rod of [`held_rod`] on a joint of `kind`, the law about its angle `angle` (a ball
/// joint's component 2 is about F1's z, the hinge's axis: world y).
fn held_rod_on(kind: JointKind, angle: usize, damping: Real) -> World {
    horizontal_rod(kind, |joint| {
        joint.passive = vec![PassiveMoment { angle, ..law() }];
        joint.damping = damping;
    })
}

#[test]
fn the_law_and_its_slope_are_the_closed_form() {
    let m = law();
    for a in [-1.2, -0.5, 0.0, 0.4] {
        let phi: Real = 0.3 + a;
        let expected = 2.0 * (-4.0 * (phi - 0.3)).exp() - 2.0;
        assert!((m.moment(a) - expected).abs() <= 1e-12 * expected.abs().max(1.0));
        let slope = -8.0 * (-4.0 * (phi - 0.3)).exp();
        assert!((m.slope(a) - slope).abs() <= 1e-12 * slope.abs());
    }
}

#[test]
fn a_rod_on_a_passive_moment_keeps_the_energy_of_its_potential() {
    // Released horizontal, the rod falls until the moment (24.5 N m of weight at 0.5 m)
    // throws it back: a conservative swing about -0.6 rad. Its kinetic and gravity energy plus
    // the law's potential stay constant; with the moment's sign reversed they would not.
    let mut w = held_rod(0.0);
    let out = w.run(5.0, DT).unwrap();
    let props = props_of(1, 1.0);
    let total = |k: usize| energy(&w, &out, &props, k) + potential(angle(&out, k));
    let e0 = total(0);
    let scale = 5.0 * GRAVITY * 0.5; // J: the rod's CG falling half a metre
    let worst = (0..out.len())
        .map(|k| (total(k) - e0).abs())
        .fold(0.0, Real::max);
    assert!(worst < 1e-4 * scale, "energy off by {worst:.3e} J");
    let lowest = (0..out.len())
        .map(|k| angle(&out, k))
        .fold(Real::INFINITY, Real::min);
    assert!((-1.3..-0.9).contains(&lowest), "lowest {lowest:.3} rad");
    assert!(angle(&out, out.len() - 1) < 0.01);
}

#[test]
fn a_damped_rod_rests_where_the_moment_carries_its_weight() {
    // Static balance: M(a) = m g (l / 2) cos(a), by bisection; the run settles there.
    let weight = 5.0 * GRAVITY * 0.5;
    let balance = |a: Real| law().moment(a) - weight * a.cos();
    let (mut lo, mut hi) = (-PI / 2.0, 0.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if balance(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let expected = 0.5 * (lo + hi);
    // On a hinge, and on a ball joint with the law about its rotation vector's z component
    // (the motion stays in the plane: that component is the hinge's angle).
    for (kind, which) in [(JointKind::Revolute, 0), (JointKind::Spherical, 2)] {
        let mut w = held_rod_on(kind, which, 10.0);
        let out = w.run(10.0, DT).unwrap();
        let end = angle(&out, out.len() - 1);
        assert!(
            (end - expected).abs() < 1e-5,
            "{kind:?}: rests at {end:.6} rad, the balance at {expected:.6} rad"
        );
    }
}

#[test]
fn bad_passive_moments_are_refused_by_name() {
    let frame = (Point::origin(), Rotation::identity());
    let mut w = World::new();
    w.set_ground(Ground::plane(0.0).unwrap()).unwrap();
    let (shape, props) = rod(1.0, 0.2, 5.0);
    w.add_body(shape, props, &at(0.0, HEIGHT, 0.0)).unwrap();
    let err = |kind: JointKind, passive: Vec<PassiveMoment>, w: &mut World| {
        let mut j = JointSpec::new(kind, 0, None, frame, frame);
        j.name = "knee".into();
        j.passive = passive;
        w.add_joint(j).unwrap_err().to_string()
    };
    let with = |change: &dyn Fn(&mut PassiveMoment)| {
        let mut m = law();
        change(&mut m);
        vec![m]
    };
    let e = err(JointKind::Revolute, with(&|m| m.angle = 1), &mut w);
    assert!(e.contains("the angles angle for a passive moment"), "{e}");
    let e = err(JointKind::Fixed, vec![law()], &mut w);
    assert!(e.contains("no free angle for a passive moment"), "{e}");
    let e = err(JointKind::Spherical, vec![law(), law()], &mut w);
    assert!(e.contains("two passive moments about its x"), "{e}");
    let e = err(
        JointKind::Revolute,
        with(&|m| m.terms[0].rate = 1e3),
        &mut w,
    );
    assert!(e.contains("rate = 1000 1/rad is invalid"), "{e}");
    let e = err(
        JointKind::Revolute,
        with(&|m| m.terms[0].scale = Real::NAN),
        &mut w,
    );
    assert!(e.contains("scale") && e.contains("finite"), "{e}");
    let e = err(JointKind::Revolute, with(&|m| m.offset = 7.0), &mut w);
    assert!(e.contains("offset"), "{e}");
    // A ball joint's three components and a fifth wheel's pitch are angles too.
    let mut ball = JointSpec::new(JointKind::Spherical, 0, None, frame, frame);
    ball.passive = [0, 1, 2]
        .map(|angle| PassiveMoment { angle, ..law() })
        .to_vec();
    w.add_joint(ball).unwrap();
}

#[test]
fn a_law_too_steep_for_the_run_is_refused_naming_the_passive_moments() {
    // 1e6 N m at the start, growing 200-fold per rad: its slope (2e8 N m/rad) on a 1.7 kg m^2
    // rod needs more sub-steps than the engine takes.
    let mut w = held_rod(0.0);
    let mut steep = horizontal_rod(JointKind::Revolute, |joint| {
        joint.passive = vec![PassiveMoment {
            angle: 0,
            offset: 0.0,
            terms: vec![PassiveTerm::new(1e6, 200.0, 0.0)],
            constant: -1e6,
        }];
    });
    let e = steep.run(0.1, DT).unwrap_err().to_string();
    assert!(
        e.contains("passive moments need") && e.contains("passive moments less steep"),
        "{e}"
    );
    // the law of the other tests is within reach
    assert!(w.run(0.1, DT).is_ok());
}
