//! One scene from a spec document (`Scene.to_spec().to_json()` in Python), run to its end in
//! windows: the wall time and distance queries of each window and of each event's step, for
//! finding where a run's time goes (and for `perf record`).
//! `cargo run --release -p crashsim-benches --example profile_spec -- scene.json [window_s
//! [repeats]]` (window 0.1 s, one repeat by default). The whole run's record digest says
//! whether a change kept the results' bits.

use std::time::Instant;

use crashsim_core::{spec, RunOptions};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .expect("usage: profile_spec scene.json [window_s]");
    let window: f64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(0.1);
    let repeats: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let text = std::fs::read_to_string(&path).expect("the spec file reads");
    let spec = spec::from_json(&text).expect("the spec parses");
    let (duration, dt) = (spec.run.duration, spec.run.dt);
    let until_rest = spec.run.options.until_rest;

    // A whole run first: its events and the total.
    let start = Instant::now();
    let mut world = spec.build().expect("builds");
    let full = world
        .run_with_options(duration, dt, &spec.run.options, &mut |_| true)
        .expect("runs");
    let total = start.elapsed().as_secs_f64();
    let end = *full.times.last().expect("a sample");
    println!(
        "whole run: {:.2} ms to t = {end:.4} s, {} distance queries, {} impacts",
        total * 1e3,
        world.distance_queries(),
        full.impacts.len()
    );
    for c in &full.contacts {
        println!("  {:?} {}-{} at {:.6} s", c.kind, c.body1, c.body2, c.time);
    }
    for i in &full.impacts {
        println!("  exchange at {:.6} s", i.time);
    }
    println!("  rest {:?}", full.rest);
    // FNV-1a over the record's every number (Debug prints each float's shortest exact
    // form): equal digests, equal runs bit for bit.
    let record = format!(
        "{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}",
        full.times,
        full.states,
        full.wheels,
        full.rest,
        full.impacts,
        full.contacts,
        full.joint_events,
        full.joints
    );
    let digest = record.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    });
    println!("  record digest {digest:016x}");

    // The same run in windows on the step grid (the same bits: runs resume where they
    // stop), `repeats` times: the least wall time of each window (a shared machine's noise
    // only adds), the counts of the last.
    let options = RunOptions {
        until_rest: false,
        ..spec.run.options
    };
    let steps_per_window = ((window / dt).round() as usize).max(1);
    let mut windows: Vec<(f64, f64, f64, u64, u64, u64, usize)> = Vec::new();
    for rep in 0..repeats {
        let mut w = spec.build().expect("builds");
        let mut t = 0.0;
        let mut k = 0;
        while t < end - 1e-12 {
            let span = (steps_per_window as f64 * dt).min(end - t);
            let (q0, e0, c0) = (
                w.distance_queries(),
                w.clearance_evaluations(),
                w.clearance_checks(),
            );
            let s = Instant::now();
            let out = w
                .run_with_options(span, dt, &options, &mut |_| true)
                .expect("runs");
            let wall = s.elapsed().as_secs_f64();
            let row = (
                t,
                t + span,
                wall,
                w.distance_queries() - q0,
                w.clearance_evaluations() - e0,
                w.clearance_checks() - c0,
                out.contacts.len() + out.impacts.len(),
            );
            if rep == 0 {
                windows.push(row);
            } else {
                windows[k].2 = windows[k].2.min(wall);
            }
            k += 1;
            t += span;
        }
    }
    let mut sum = 0.0;
    for (t0, t1, wall, q, e, c, events) in &windows {
        sum += wall;
        println!(
            "  {t0:7.3}-{t1:7.3} s {:9.3} ms {q:6} queries {e:8} evaluations {c:8} checks {}",
            wall * 1e3,
            if *events > 0 {
                format!("({events} events)")
            } else {
                String::new()
            }
        );
    }
    println!(
        "sum of windows {:.2} ms (least of {repeats}; until_rest {until_rest})",
        sum * 1e3
    );
}
