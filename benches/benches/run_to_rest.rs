//! The whole scene on the ground, run until both vehicles are at rest (criterion's elem/s =
//! scenes per second): the approach, the first overlap, the timer, the exchange, the
//! engaged phase, the separation and the run-out with locked wheels (at most 20 s).

use std::time::Duration;

use crashsim_benches::{load_scenes, sampling_for, time_each, wall_of, DT};
use crashsim_core::{RunOptions, World};
use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};

fn to_rest(c: &mut Criterion) {
    let scenes = load_scenes();
    let mut g = c.benchmark_group("run_to_rest");
    g.warm_up_time(Duration::from_secs(1));
    g.throughput(Throughput::Elements(1));
    let options = RunOptions {
        until_rest: true,
        ..RunOptions::default()
    };
    for s in &scenes {
        let setup = || s.ground_world();
        let run = |w: &mut World| {
            let out = w
                .run_with_options(20.0, DT, &options, &mut |_| true)
                .unwrap();
            assert!(out.rest.iter().all(|r| r.is_some()), "both at rest");
            out
        };
        let (n, time) = sampling_for(wall_of(setup, run));
        g.sample_size(n)
            .measurement_time(time)
            .sampling_mode(SamplingMode::Flat);
        g.bench_function(BenchmarkId::from_parameter(s.size.label()), |b| {
            b.iter_custom(|iters| time_each(iters, setup, run))
        });
    }
    g.finish();
}

criterion_group!(benches, to_rest);
criterion_main!(benches);
