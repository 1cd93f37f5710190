//! The two per-exchange computations on their own: the overlap region (per mesh size) at the
//! scene's exchange pose and at the shallow pose where the engine takes the first exchange's
//! normal (part of the first-overlap step), and the impulse solve.

use std::hint::black_box;
use std::time::Duration;

use crashsim_benches::{load_scenes, sampling_for, wall_of, Size, SLIDING_FRICTION};
use crashsim_core::overlap::overlap_region;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};

fn queries(c: &mut Criterion) {
    let scenes = load_scenes();

    let mut g = c.benchmark_group("overlap_region");
    g.warm_up_time(Duration::from_secs(1));
    g.throughput(Throughput::Elements(1));
    for s in &scenes {
        let [a, b] = s.vehicles();
        for (pose, [p1, p2]) in [
            ("exchange", s.timeline.exchange_poses),
            ("shallow", s.timeline.shallow_poses),
        ] {
            let region = || overlap_region(black_box(&a.shape), &p1, &b.shape, &p2);
            let (n, time) = sampling_for(wall_of(|| (), |_| region()));
            g.sample_size(n).measurement_time(time);
            g.bench_function(BenchmarkId::new(pose, s.size.label()), |bench| {
                bench.iter(region)
            });
        }
    }
    g.finish();

    // The solve does not depend on the mesh: the exchange of the smallest scene present,
    // which sticks (friction 0.6), and the same with friction 0.1, which slides.
    let mut g = c.benchmark_group("impulse_solve");
    g.warm_up_time(Duration::from_secs(1));
    g.measurement_time(Duration::from_secs(3));
    g.throughput(Throughput::Elements(1));
    if let Some(s) = scenes
        .iter()
        .find(|s| s.size == Size::Small)
        .or(scenes.first())
    {
        let sticking = s.impulse_problem();
        let mut sliding = sticking.clone();
        sliding.friction = SLIDING_FRICTION;
        g.bench_function("sticking", |b| b.iter(|| black_box(&sticking).solve()));
        g.bench_function("sliding", |b| b.iter(|| black_box(&sliding).solve()));
    }
    g.finish();
}

criterion_group!(benches, queries);
criterion_main!(benches);
