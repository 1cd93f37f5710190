//! A whole scene per mesh size (criterion's elem/s = scenes per second): 1 s simulated at
//! 1 ms steps, two vehicles, from 50 ms before their boxes touch through the approach, the
//! first overlap, the 30 ms timer, the exchange, the engaged phase, the separation and what
//! follows (in this scene B, spun by the first exchange, strikes A a second time).

use std::time::Duration;

use crashsim_benches::{load_scenes, sampling_for, time_each, wall_of, DT, WHOLE_DURATION};
use crashsim_core::World;
use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};

fn whole(c: &mut Criterion) {
    let scenes = load_scenes();
    let mut g = c.benchmark_group("whole_scene");
    g.warm_up_time(Duration::from_secs(1));
    g.throughput(Throughput::Elements(1));
    for s in &scenes {
        let setup = || s.whole_world();
        let run = |w: &mut World| w.run(WHOLE_DURATION, DT).unwrap();
        // Ten samples at every size here (a scene takes 0.4 s at 1k to 5 s at 200k).
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

criterion_group!(benches, whole);
criterion_main!(benches);
