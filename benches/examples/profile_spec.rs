//! One scene from a spec document (`Scene.to_spec().to_json()` in Python), run to its end in
//! windows: the wall time and distance queries of each window and of each event's step, for
//! finding where a run's time goes (and for `perf record`).
//! `cargo run --release -p crashsim-benches --example profile_spec -- scene.json [window_s]`
//! (window 0.1 s by default).

use std::time::Instant;

use crashsim_core::{spec, RunOptions};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .expect("usage: profile_spec scene.json [window_s]");
    let window: f64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(0.1);
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

    // The same run in windows on the step grid (the same bits: runs resume where they stop).
    let mut w = spec.build().expect("builds");
    let options = RunOptions {
        until_rest: false,
        ..spec.run.options
    };
    let steps_per_window = ((window / dt).round() as usize).max(1);
    let mut t = 0.0;
    let mut sum = 0.0;
    while t < end - 1e-12 {
        let span = (steps_per_window as f64 * dt).min(end - t);
        let q0 = w.distance_queries();
        let s = Instant::now();
        let out = w
            .run_with_options(span, dt, &options, &mut |_| true)
            .expect("runs");
        let wall = s.elapsed().as_secs_f64();
        sum += wall;
        let events = out.contacts.len() + out.impacts.len();
        println!(
            "  {t:7.3}-{:7.3} s {:9.3} ms {:6} queries {}",
            t + span,
            wall * 1e3,
            w.distance_queries() - q0,
            if events > 0 {
                format!("({events} events)")
            } else {
                String::new()
            }
        );
        t += span;
    }
    println!(
        "sum of windows {:.2} ms (until_rest {until_rest})",
        sum * 1e3
    );
}
