//! One run of each mesh size's two-car scene on the ground until rest, for profiling (`perf
//! record`): wall time, steps recorded, distance queries and the rest times.
//! `SIZE=20k cargo run --release -p crashsim-benches --example profile_rest [repeats]` (SIZE
//! 1k, 20k or 200k; all without it).

use std::time::Instant;

use crashsim_benches::{Scene, Size, DT};
use crashsim_core::{ContactEventKind, RunOptions};

fn main() {
    let repeats: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1);
    let options = RunOptions {
        until_rest: true,
        ..RunOptions::default()
    };
    let wanted = std::env::var("SIZE").ok();
    for size in Size::ALL {
        if wanted.as_deref().is_some_and(|z| z != size.label()) {
            continue;
        }
        let s = Scene::load(size).expect("the scene's meshes load");
        // One run to find the phases' limits (step boundaries), then timed runs in pieces.
        let mut probe = s.ground_world();
        let full = probe
            .run_with_options(20.0, DT, &options, &mut |_| true)
            .expect("runs");
        let floor = |t: f64| (t / DT).floor() * DT;
        let imp = &full.impacts[0];
        let sep = full
            .contacts
            .iter()
            .find(|c| matches!(c.kind, ContactEventKind::Separation))
            .map(|c| c.time);
        let mut marks = vec![
            ("approach", floor(imp.first_contact_time)),
            (
                "step with the first overlap",
                floor(imp.first_contact_time) + DT,
            ),
            ("timer", floor(imp.time)),
            ("step with the exchange", floor(imp.time) + DT),
        ];
        if let Some(t) = sep {
            marks.push(("engaged", floor(t)));
            marks.push(("step with the separation", floor(t) + DT));
        }
        println!(
            "{}: {} samples to t = {:.3} s, {} impacts, rest {:?}",
            s.size.label(),
            full.len(),
            full.times.last().unwrap(),
            full.impacts.len(),
            full.rest
        );
        let mut walls = vec![Vec::new(); marks.len() + 1];
        let mut queries = vec![0u64; marks.len() + 1];
        for _ in 0..repeats {
            let mut w = s.ground_world();
            let mut t = 0.0;
            // PHASES=n times only the first n phases (to profile one).
            let phases: usize = std::env::var("PHASES")
                .ok()
                .and_then(|p| p.parse().ok())
                .unwrap_or(usize::MAX);
            for (k, (_, end)) in marks.iter().enumerate().take(phases) {
                let q0 = w.distance_queries();
                let start = Instant::now();
                w.run(((end - t) / DT).round() * DT, DT).expect("runs");
                walls[k].push(start.elapsed().as_secs_f64());
                queries[k] = w.distance_queries() - q0;
                t = *end;
            }
            if phases < marks.len() {
                continue;
            }
            let q0 = w.distance_queries();
            let start = Instant::now();
            w.run_with_options(20.0, DT, &options, &mut |_| true)
                .expect("runs");
            walls[marks.len()].push(start.elapsed().as_secs_f64());
            queries[marks.len()] = w.distance_queries() - q0;
        }
        let median = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v.get(v.len() / 2).copied().unwrap_or(0.0)
        };
        let mut total = 0.0;
        let mut t = 0.0;
        for (k, wall) in walls.iter_mut().enumerate() {
            let (name, end) = marks
                .get(k)
                .copied()
                .unwrap_or(("run-out to rest", f64::NAN));
            let m = median(wall);
            let least = wall.first().copied().unwrap_or(0.0);
            total += m;
            println!(
                "  {t:6.3}-{end:6.3} s  {name:28} {:9.2} ms (least {:8.2})  {:5} distance queries",
                m * 1e3,
                least * 1e3,
                queries[k]
            );
            t = end;
        }
        println!("  total (sum of medians)            {:9.2} ms", total * 1e3);
    }
}
