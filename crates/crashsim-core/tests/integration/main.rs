//! The core's integration tests in one test binary, a module per topic (README.md lists
//! them): the build compiles and links the engine's generic code once for all of them, not
//! once per topic (4-5 s less of a from-scratch `cargo test` on 2 cores, benches/README.md,
//! "The test run"). One topic alone: its module's name as the filter,
//! `cargo test -p crashsim-core --release --test integration fuzz::`.

mod common;

mod batch;
mod coplanar;
mod dynamics;
mod engine;
mod fuzz;
mod fuzz_regressions;
mod glancing;
mod joints;
mod reliability;
mod soft;
mod suspension;
mod thin_parts;
