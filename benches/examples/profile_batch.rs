//! A batch from a spec document and an overrides file, run on a pool of `threads` threads
//! (1 by default): the wall, the time per variant and a digest of the columns' bits, for `perf record` or
//! `valgrind --tool=callgrind` (instruction counts, repeatable on a shared machine).
//! benches/batch_throughput.py --dump DIR writes both files for its scenes.
//! `cargo run --release -p crashsim-benches --example profile_batch -- spec.json overrides.txt
//! [threads] [repeats]`
//!
//! The overrides file: per key, a line `name dim0 dim1 ...` (dim0 = n, the variants) and a
//! line of the row-major values (SI units, as the batch contract gives them).

use std::time::Instant;

use crashsim_core::batch::{run_batch, BatchOptions, Control, Overrides, Values};
use crashsim_core::spec;

fn main() {
    let mut args = std::env::args().skip(1);
    let usage = "usage: profile_batch spec.json overrides.txt [threads] [repeats]";
    let spec_path = args.next().expect(usage);
    let over_path = args.next().expect(usage);
    let threads: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let repeats: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let text = std::fs::read_to_string(&spec_path).expect("the spec file reads");
    let base = spec::from_json(&text).expect("the spec parses");
    let over = std::fs::read_to_string(&over_path).expect("the overrides file reads");
    let mut lines = over.lines().filter(|l| !l.trim().is_empty());
    let mut given = Vec::new();
    let mut n = 0;
    while let Some(head) = lines.next() {
        let mut words = head.split_whitespace();
        let name = words.next().expect("a key").to_string();
        let shape: Vec<usize> = words.map(|w| w.parse().expect("a dimension")).collect();
        let values: Vec<f64> = lines
            .next()
            .expect("a line of values after each key")
            .split_whitespace()
            .map(|w| w.parse().expect("a number"))
            .collect();
        n = shape[0];
        given.push((name, shape, values));
    }
    let overrides = Overrides::new(&base, n, given).expect("the overrides fit the spec");
    let options = BatchOptions {
        threads,
        max_impacts: 2,
    };
    for _ in 0..repeats {
        let control = Control::default();
        let start = Instant::now();
        let out = run_batch(&base, &overrides, &options, &control).expect("the batch runs");
        let wall = start.elapsed().as_secs_f64();
        let impacts = match &out.columns.columns[0].1 {
            Values::Int(v) => v.iter().filter(|&&k| k > 0).count(),
            Values::Float(_) => 0,
        };
        // FNV-1a over every column's bits: equal digests, equal results bit for bit
        let mut digest: u64 = 0xcbf2_9ce4_8422_2325;
        let mut eat = |bits: u64| {
            for byte in bits.to_le_bytes() {
                digest = (digest ^ byte as u64).wrapping_mul(0x0100_0000_01b3);
            }
        };
        for (_, values) in &out.columns.columns {
            match values {
                Values::Int(v) => v.iter().for_each(|&k| eat(k as u64)),
                Values::Float(v) => v.iter().for_each(|x| eat(x.to_bits())),
            }
        }
        println!(
            "{n} variants ({impacts} with an impact, {} failed) on {threads} threads: {:.3} s, \
             {:.4} ms per variant; columns' digest {digest:016x}",
            out.errors.len(),
            wall,
            wall / n as f64 * 1e3
        );
    }
}
