//! The overlap region at the scene's shallow pose (where the first exchange's normal is read,
//! part of the first-overlap step), repeated, for profiling (`perf record`) and a quick
//! median: `SIZE=20k cargo run --release -p crashsim-benches --example profile_region [n]`.

use std::time::Instant;

use crashsim_benches::{Scene, Size};
use crashsim_core::overlap::overlap_region;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(200);
    let wanted = std::env::var("SIZE").ok();
    for size in Size::ALL {
        if wanted.as_deref().is_some_and(|z| z != size.label()) {
            continue;
        }
        let s = Scene::load(size).expect("the scene's meshes load");
        let [a, b] = s.vehicles();
        for (label, [p1, p2]) in [
            ("shallow", s.timeline.shallow_poses),
            ("exchange", s.timeline.exchange_poses),
        ] {
            let mut walls = Vec::with_capacity(n);
            let mut region = overlap_region(&a.shape, &p1, &b.shape, &p2);
            for _ in 0..n {
                let start = Instant::now();
                region = overlap_region(&a.shape, &p1, &b.shape, &p2);
                walls.push(start.elapsed().as_secs_f64());
            }
            walls.sort_by(f64::total_cmp);
            println!(
                "{} {label}: median {:.3} ms over {n}; {} segments, {} inside vertices, \
                 volume normal {:?}",
                size.label(),
                walls[n / 2] * 1e3,
                region.segment_count,
                region.inside_vertex_count,
                region.volume_normal().map(|v| [v.x, v.y, v.z]),
            );
        }
    }
}
