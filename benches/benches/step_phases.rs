//! Step throughput per contact phase and mesh size (criterion's elem/s = steps per second).
//!
//! Each iteration runs `World::run` over a window of 1 ms steps on a fresh world placed in
//! the phase; placing it and any run-up are not timed (`iter_custom`):
//! - approach: the boxes overlap, the meshes do not; the first-contact search runs its
//!   distance queries every step (from one step after the boxes touch to at least one
//!   step before the step of the first overlap);
//! - first_overlap: the one step in which the first overlap is found, bisected to 1e-9 s,
//!   and the timer started (which takes the early normal's overlap region);
//! - engaged: after the exchange, meshes overlapping; the engaged-pair check every step.
//!
//! The windows are checked by `cargo test -p crashsim-benches`.

use std::time::Duration;

use crashsim_benches::{load_scenes, sampling_for, time_each, wall_of, Scene, DT};
use crashsim_core::World;
use criterion::measurement::WallTime;
use criterion::{
    criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, SamplingMode,
    Throughput,
};

/// Benchmarks `steps` steps of the world `setup` makes, for one scene.
fn bench_window(
    g: &mut BenchmarkGroup<'_, WallTime>,
    s: &Scene,
    steps: usize,
    setup: impl Fn() -> World,
) {
    let run = |w: &mut World| w.run(steps as f64 * DT, DT).unwrap();
    let (n, time) = sampling_for(wall_of(&setup, run));
    // Flat: the same iteration count in every sample (iterations are long; the setup is
    // outside the timing but inside the wall clock criterion plans with).
    g.sample_size(n)
        .measurement_time(time)
        .sampling_mode(SamplingMode::Flat);
    g.throughput(Throughput::Elements(steps as u64));
    g.bench_function(BenchmarkId::from_parameter(s.size.label()), |b| {
        b.iter_custom(|iters| time_each(iters, &setup, run))
    });
}

fn phases(c: &mut Criterion) {
    let scenes = load_scenes();

    let mut g = c.benchmark_group("approach");
    g.warm_up_time(Duration::from_secs(1));
    for s in &scenes {
        bench_window(&mut g, s, s.timeline.approach.steps, || s.approach_world());
    }
    g.finish();

    let mut g = c.benchmark_group("first_overlap");
    g.warm_up_time(Duration::from_secs(1));
    for s in &scenes {
        bench_window(&mut g, s, 1, || s.first_overlap_world());
    }
    g.finish();

    let mut g = c.benchmark_group("engaged");
    g.warm_up_time(Duration::from_secs(1));
    for s in &scenes {
        bench_window(&mut g, s, s.timeline.engaged_steps, || s.engaged_world().0);
    }
    g.finish();
}

criterion_group!(benches, phases);
criterion_main!(benches);
