//! Where the whole scene's time goes (not a criterion benchmark: one timed run per size).
//!
//! Runs each size's whole scene once (1 s at 1 ms steps) with a progress hook that reads the
//! clock after every step, and prints the wall time of each step that holds an event (first
//! overlap, exchange, separation, closing again) and of the steps between events, by phase.
//! One run on a shared machine: read the shares, not the last digit.
//!
//!     cargo bench -p crashsim-benches --bench scene_breakdown

use std::collections::BTreeMap;
use std::time::Instant;

use crashsim_benches::{load_scenes, DT, WHOLE_DURATION};

fn main() {
    // `cargo bench -- FILTER` passes FILTER to every bench: run only when it names this one.
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    if !filters.is_empty()
        && !filters
            .iter()
            .any(|f| "scene_breakdown".contains(f.as_str()))
    {
        return;
    }
    for s in load_scenes() {
        let mut w = s.whole_world();
        // Wall time (ms) per grid step: index k covers ((k - 1) DT, k DT].
        let mut per_step: BTreeMap<i64, f64> = BTreeMap::new();
        let grid = |t: f64| (t / DT - 1e-6).ceil() as i64;
        let start = Instant::now();
        let mut last = start;
        let out = w
            .run_with_progress(WHOLE_DURATION, DT, &mut |t| {
                let now = Instant::now();
                *per_step.entry(grid(t)).or_default() += (now - last).as_secs_f64() * 1e3;
                last = now;
                true
            })
            .expect("the whole scene runs");
        let total = start.elapsed().as_secs_f64() * 1e3;
        let mut events: Vec<(f64, String)> = out
            .contacts
            .iter()
            .map(|c| (c.time, format!("{:?}", c.kind)))
            .chain(out.impacts.iter().map(|i| (i.time, "Exchange".to_string())))
            .collect();
        events.sort_by(|a, b| a.0.total_cmp(&b.0));
        println!(
            "\nwhole scene {} ({} triangles per vehicle): {:.0} ms in all",
            s.size.label(),
            s.triangles,
            total
        );
        println!(
            "  {:<44} {:>6} {:>10} {:>8}",
            "steps", "count", "ms", "share"
        );
        let row = |label: &str, lo: i64, hi: i64| {
            // Grid steps lo..hi (inclusive).
            let (n, ms) = per_step
                .range(lo..=hi)
                .fold((0, 0.0), |(n, ms), (_, v)| (n + 1, ms + v));
            if n > 0 {
                println!(
                    "  {:<44} {:>6} {:>10.1} {:>7.1}%",
                    label,
                    n,
                    ms,
                    100.0 * ms / total
                );
            }
        };
        let mut prev_label = "apart, before the first overlap".to_string();
        let mut prev_step = 0;
        for (t, kind) in &events {
            let k = grid(*t);
            if k > prev_step {
                row(&prev_label, prev_step + 1, k - 1);
                row(&format!("the step holding {kind} at {t:.4} s"), k, k);
                prev_step = k;
            }
            prev_label = match kind.as_str() {
                "FirstOverlap" | "ClosingAgain" => "timer running".into(),
                "Exchange" => "engaged".into(),
                "Separation" => "apart, after a separation".into(),
                other => format!("after {other}"),
            };
        }
        row(&prev_label, prev_step + 1, i64::MAX);
    }
}
