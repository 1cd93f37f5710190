//! Batches (batch.rs): bit-identical for any thread count, equal to running each variant
//! alone, failed variants listed while the others finish, bad overrides refused up front,
//! the interrupt flag keeping what finished.

use std::f64::consts::FRAC_PI_2;
use std::sync::atomic::Ordering;
use std::sync::Arc;

use crashsim_core::batch::{run_batch, BatchOptions, BatchOutput, Control, Overrides, Values};
use crashsim_core::ground::Ground;
use crashsim_core::math::{Point, Real, Vector};
use crashsim_core::vehicle::{
    static_loads, DriverInputs, Trigger, Tyre, VehicleSpec, WheelSpec, WheelState, WheelSwitch,
    GRAVITY,
};
use crashsim_core::world::{degrees, heading, magnitude, pdof_deg};
use crashsim_core::ErrorKind;
use crashsim_core::{ContactParams, MeshShape, SceneSpec};

use crate::common::{box_props, state};

/// The seed's 90 deg side impact (examples/seed-90deg.toml): red 30 mph into blue's left
/// side, 1 s at 1 ms.
fn seed() -> SceneSpec {
    let mut s = SceneSpec::new();
    let red = Arc::new(MeshShape::cuboid(
        Vector::zeros(),
        Vector::new(2.25, 0.9, 0.7),
    ));
    let blue = Arc::new(MeshShape::cuboid(
        Vector::zeros(),
        Vector::new(2.3, 0.9, 0.725),
    ));
    let v = 30.0 * 0.44704;
    s.add_body(
        Some("red".into()),
        red,
        box_props(1450.0, 4.5, 1.8, 1.4),
        state(-3.65, 0.3, 0.7, 0.0, Vector::new(v, 0.0, 0.0)),
    )
    .unwrap();
    s.add_body(
        Some("blue".into()),
        blue,
        box_props(1500.0, 4.6, 1.8, 1.45),
        state(0.0, 0.0, 0.725, FRAC_PI_2, Vector::zeros()),
    )
    .unwrap();
    s.set_contact(0, 1, ContactParams::default()).unwrap();
    s
}

/// n variants of the seed: red's speed and lateral offset, and the pair's restitution.
fn seed_overrides(spec: &SceneSpec, n: usize) -> Overrides {
    let mut vel = Vec::new();
    let mut pos = Vec::new();
    let mut eps = Vec::new();
    for i in 0..n {
        let f = i as Real / n.max(1) as Real;
        vel.extend([10.0 + 8.0 * f, 0.5 * f, 0.0, 0.0, 0.0, 0.0]);
        pos.extend([-3.65, 0.3 - 1.5 * f, 0.7, 0.0, 0.0, 0.725]);
        eps.push(0.05 + 0.3 * f);
    }
    Overrides::new(
        spec,
        n,
        vec![
            ("velocity".into(), vec![n, 2, 3], vel),
            ("position".into(), vec![n, 2, 3], pos),
            ("contact.restitution".into(), vec![n, 1], eps),
        ],
    )
    .unwrap()
}

fn run(spec: &SceneSpec, o: &Overrides, threads: usize) -> BatchOutput {
    run_batch(
        spec,
        o,
        &BatchOptions {
            threads,
            max_impacts: 2,
        },
        &Control::default(),
    )
    .unwrap()
}

fn column<'a>(out: &'a BatchOutput, name: &str) -> &'a [Real] {
    match &out
        .columns
        .columns
        .iter()
        .find(|(n, _)| n == name)
        .unwrap()
        .1
    {
        Values::Float(v) => v,
        Values::Int(_) => panic!("{name} is an int column"),
    }
}

fn same_bits(a: &BatchOutput, b: &BatchOutput) {
    assert_eq!(a.columns.columns.len(), b.columns.columns.len());
    for ((na, va), (nb, vb)) in a.columns.columns.iter().zip(&b.columns.columns) {
        assert_eq!(na, nb);
        match (va, vb) {
            (Values::Float(x), Values::Float(y)) => {
                let bx: Vec<u64> = x.iter().map(|v| v.to_bits()).collect();
                let by: Vec<u64> = y.iter().map(|v| v.to_bits()).collect();
                assert_eq!(bx, by, "column {na}");
            }
            (Values::Int(x), Values::Int(y)) => assert_eq!(x, y, "column {na}"),
            _ => panic!("column {na} changed type"),
        }
    }
    assert_eq!(a.errors, b.errors);
    assert_eq!(a.finished, b.finished);
}

#[test]
fn a_batch_is_the_same_bits_on_1_2_and_4_threads() {
    let spec = seed();
    let o = seed_overrides(&spec, 24);
    let one = run(&spec, &o, 1);
    assert!(one.errors.is_empty(), "{:?}", one.errors);
    assert!(one.finished.iter().all(|f| *f));
    for threads in [2, 4] {
        same_bits(&one, &run(&spec, &o, threads));
    }
    // the variants differ (the overrides reached the runs) and most of them hit
    let dv = column(&one, "impact1.red.delta_v");
    assert!(dv.iter().filter(|x| x.is_finite()).count() >= 12);
    assert!(dv[0] != dv[5]);
}

#[test]
fn each_variant_equals_its_scene_run_alone() {
    let spec = seed();
    let n = 6;
    let o = seed_overrides(&spec, n);
    let out = run(&spec, &o, 2);
    for i in 0..n {
        let alone = o.apply(&spec, i).unwrap();
        let r = alone.run().unwrap();
        let k = r.len() - 1;
        let last = r.sample(k);
        for (b, name) in [(0usize, "red"), (1, "blue")] {
            let s = &last[b];
            assert_eq!(column(&out, &format!("{name}.final_x"))[i], s.position.x);
            assert_eq!(column(&out, &format!("{name}.final_y"))[i], s.position.y);
            assert_eq!(
                column(&out, &format!("{name}.final_heading_deg"))[i],
                degrees(heading(&s.orientation))
            );
            assert_eq!(
                column(&out, &format!("{name}.final_speed"))[i],
                magnitude(&s.velocity)
            );
            assert!(column(&out, &format!("{name}.rest_time"))[i].is_nan());
        }
        match r.impacts.first() {
            Some(imp) => {
                assert_eq!(column(&out, "impact1.time")[i], imp.time);
                assert_eq!(column(&out, "impact1.energy")[i], imp.energy_dissipated);
                let body = imp.delta_v_body[1];
                assert_eq!(column(&out, "impact1.blue.delta_v_long")[i], body.x);
                assert_eq!(column(&out, "impact1.blue.delta_v_lat")[i], -body.y);
                assert_eq!(
                    column(&out, "impact1.blue.pdof_deg")[i],
                    pdof_deg(&body).unwrap()
                );
            }
            None => assert!(column(&out, "impact1.time")[i].is_nan()),
        }
    }
}

#[test]
fn failed_variants_are_listed_and_the_others_finish() {
    let spec = seed();
    let n = 4;
    // variant 1 starts with red inside blue; variant 2 has restitution 1.5
    let mut pos = Vec::new();
    let mut eps = Vec::new();
    for i in 0..n {
        let x = if i == 1 { -1.0 } else { -3.65 };
        pos.extend([x, 0.3, 0.7, 0.0, 0.0, 0.725]);
        eps.push(if i == 2 { 1.5 } else { 0.1 });
    }
    let o = Overrides::new(
        &spec,
        n,
        vec![
            ("position".into(), vec![n, 2, 3], pos),
            ("contact.restitution".into(), vec![n, 1], eps),
        ],
    )
    .unwrap();
    let out = run(&spec, &o, 2);
    assert!(out.finished.iter().all(|f| *f));
    assert_eq!(out.errors.len(), 2);
    assert_eq!(out.errors[0].index, 1);
    assert!(
        {
            let e = &out.errors[0].error;
            e.kind == ErrorKind::InitialOverlap
                && e.to_string().starts_with("variant 1: ")
                && e.to_string().contains("\"red\"")
                && e.to_string().contains("\"blue\"")
        },
        "{:?}",
        out.errors[0]
    );
    assert_eq!(out.errors[1].index, 2);
    assert!(
        {
            let e = &out.errors[1].error;
            e.kind == ErrorKind::Parameter
                && e.to_string().starts_with("variant 2: ")
                && e.to_string().contains("restitution")
        },
        "{:?}",
        out.errors[1]
    );
    let t = column(&out, "impact1.time");
    assert!(t[0].is_finite() && t[3].is_finite());
    assert!(t[1].is_nan() && t[2].is_nan());
    let Values::Int(count) = &out.columns.columns[0].1 else {
        panic!("n_impacts is an int column")
    };
    assert_eq!((count[1], count[2]), (-1, -1));
    assert!(count[0] >= 1);
}

#[test]
fn bad_overrides_are_refused_naming_the_key() {
    let spec = seed();
    let unknown = Overrides::new(&spec, 2, vec![("speed".into(), vec![2], vec![1.0, 2.0])]);
    assert!(
        unknown.is_err_and(|e| e.kind == ErrorKind::Parameter && e.message.contains("\"speed\""))
    );
    let shape = Overrides::new(
        &spec,
        2,
        vec![("velocity".into(), vec![2, 3], vec![0.0; 6])],
    );
    assert!(shape.is_err_and(|e| e.kind == ErrorKind::Parameter
        && e.message.contains("\"velocity\"")
        && e.message.contains("(2, 2, 3)")));
    let ground = Overrides::new(
        &spec,
        1,
        vec![("ground.tyre_friction".into(), vec![1], vec![0.7])],
    );
    assert!(ground.is_err_and(
        |e| e.kind == ErrorKind::Parameter && e.message.contains("ground.tyre_friction")
    ));
}

#[test]
fn an_interrupt_keeps_the_variants_that_finished() {
    let spec = seed();
    let n = 40;
    let o = seed_overrides(&spec, n);
    let control = Control::default();
    let out = std::thread::scope(|s| {
        let h = s.spawn(|| {
            run_batch(
                &spec,
                &o,
                &BatchOptions {
                    threads: 1,
                    max_impacts: 1,
                },
                &control,
            )
            .unwrap()
        });
        while control.done.load(Ordering::Relaxed) < 5 {
            std::thread::yield_now();
        }
        control.interrupt.store(true, Ordering::Relaxed);
        h.join().unwrap()
    });
    assert!(out.interrupted);
    let done = out.finished.iter().filter(|f| **f).count();
    assert!((5..n).contains(&done), "{done} finished");
    assert!(out.errors.is_empty());
    // the finished ones are the full results, the others NaN
    let whole = run(&spec, &seed_overrides(&spec, n), 1);
    let x = column(&out, "red.final_x");
    let full = column(&whole, "red.final_x");
    for i in 0..n {
        if out.finished[i] {
            assert_eq!(x[i].to_bits(), full[i].to_bits());
        } else {
            assert!(x[i].is_nan());
        }
    }
}

/// A car on its wheels on level ground, locked wheels: it skids to rest.
fn skidding_car() -> SceneSpec {
    let (a, b, track, h, r, m) = (1.1, 1.6, 1.55, 0.55, 0.3, 1500.0);
    let mut s = SceneSpec::new();
    let shape = Arc::new(MeshShape::cuboid(
        Vector::new(0.0, 0.0, 0.15 + 0.7 - h),
        Vector::new(2.3, 0.9, 0.7),
    ));
    let props = box_props(m, 4.6, 1.8, 1.4);
    let i = s
        .add_body(
            Some("car".into()),
            shape,
            props,
            state(0.0, 0.0, h, 0.0, Vector::new(15.0, 0.0, 0.0)),
        )
        .unwrap();
    let xy = [
        [a, track / 2.0],
        [a, -track / 2.0],
        [-b, track / 2.0],
        [-b, -track / 2.0],
    ];
    let loads = static_loads(&xy, m * GRAVITY).unwrap();
    let wheels = xy
        .iter()
        .zip(&loads)
        .enumerate()
        .map(|(k, (p, f))| {
            WheelSpec::sprung(Point::new(p[0], p[1], r - h), r, k < 2, *f, 1.3, 0.3).unwrap()
        })
        .collect();
    let inputs = DriverInputs {
        switches: (0..4)
            .map(|wheel| WheelSwitch {
                wheel,
                at: Trigger::Time(0.0),
                state: WheelState::Locked,
            })
            .collect(),
        ..DriverInputs::default()
    };
    s.set_vehicle(
        i,
        VehicleSpec {
            wheels,
            tyre: Tyre::default(),
            steering: Default::default(),
            abs: true,
            anti_roll: Vec::new(),
            inputs,
            coupling: None,
            hitch_load: None,
            load_groups: Vec::new(),
        },
    )
    .unwrap();
    s.set_ground(Ground::plane(0.0).unwrap());
    s.run.duration = 5.0;
    s.run.options.until_rest = true;
    s
}

#[test]
fn ground_variants_come_to_rest_and_equal_their_runs_alone() {
    let spec = skidding_car();
    let n = 3;
    let o = Overrides::new(
        &spec,
        n,
        vec![
            ("ground.tyre_friction".into(), vec![n], vec![0.5, 0.7, 0.9]),
            ("mass".into(), vec![n, 1], vec![1200.0, 1500.0, 1800.0]),
        ],
    )
    .unwrap();
    let out = run(&spec, &o, 2);
    assert!(out.errors.is_empty(), "{:?}", out.errors);
    same_bits(&out, &run(&spec, &o, 1));
    let rest_x = column(&out, "car.rest_x");
    // v^2 / (2 mu g): 22.9, 16.4, 12.7 m (the locked skid, to a few per cent)
    for (i, mu) in [0.5, 0.7, 0.9].iter().enumerate() {
        let closed = 15.0 * 15.0 / (2.0 * mu * GRAVITY);
        assert!(
            (rest_x[i] - closed).abs() < 0.05 * closed,
            "{} vs {closed}",
            rest_x[i]
        );
        let alone = o.apply(&spec, i).unwrap().run().unwrap();
        assert_eq!(column(&out, "car.rest_time")[i], alone.rest[0].unwrap());
        let s = &alone.sample(alone.len() - 1)[0];
        assert_eq!(rest_x[i], s.position.x);
        assert_eq!(
            column(&out, "car.rest_heading_deg")[i],
            degrees(heading(&s.orientation))
        );
    }
}
